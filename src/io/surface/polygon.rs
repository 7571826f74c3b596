//! Triangulation of planar polygons with their own corners only (no new point), shared by
//! every reader.
//!
//! A polygon is triangulated in the coordinate plane where its normal (Newell's method) has
//! its largest component: dropping a coordinate keeps the coordinates exact, so every
//! decision taken there with [`orient2d`] is exact. The triangles then come from ear
//! clipping ([`super::ears`]); they keep the orientation of the polygon.
//!
//! A `.poly` facet with hole points is a planar region: the faces of its closed polygons
//! (each polygon minus the polygons directly inside it), less the faces that contain a hole
//! point. Each remaining face is triangulated, its inner polygons bridged to its outer one.

use super::ears;
use crate::predicates::{orient2d, Point, Sign};

/// Appends to `triangles` the triangles of the polygon with corners `corners` (indices into
/// `points`): a triangle as is, a larger polygon triangulated in its plane after its
/// repeated consecutive corners are dropped. The error is the reason, for the caller to
/// place.
pub(crate) fn triangulate_polygon(
    points: &[Point],
    corners: &[u32],
    triangles: &mut Vec<u32>,
) -> Result<(), String> {
    triangulate_polygon_avoiding(points, corners, &|_| false, triangles)
}

/// [`triangulate_polygon`] with no triangle whose corners `flat` accepts (corners that lie
/// on one line although rounding put them off it); an error when every triangulation the
/// ear clipping reaches needs one.
pub(crate) fn triangulate_polygon_avoiding(
    points: &[Point],
    corners: &[u32],
    flat: &dyn Fn([u32; 3]) -> bool,
    triangles: &mut Vec<u32>,
) -> Result<(), String> {
    match corners.len() {
        0..=2 => Err(too_few_corners(corners.len())),
        3 if flat([corners[0], corners[1], corners[2]]) => {
            Err("the polygon is a flat triangle".to_string())
        }
        3 => {
            triangles.extend_from_slice(corners);
            Ok(())
        }
        _ => {
            let corners = distinct_corners(points, corners);
            if corners.len() < 3 {
                return Err(too_few_corners(corners.len()));
            }
            let axis = projection_axis(&newell_normal(points, &corners))?;
            ears::triangulate(points, axis, (&corners, &[]), flat, triangles)
        }
    }
}

/// Appends to `triangles` the triangles of a facet made of the closed polygons `polygons`
/// with the hole points `holes` (in the facet's plane). Without hole points each polygon is
/// triangulated on its own ([`triangulate_polygon`]); with some, the facet is the region
/// described in the module documentation. Polygons of fewer than 3 corners (segments and
/// points inside a facet) are not supported.
pub(super) fn triangulate_facet(
    points: &[Point],
    polygons: &[Vec<u32>],
    holes: &[Point],
    triangles: &mut Vec<u32>,
) -> Result<(), String> {
    if holes.is_empty() {
        for (k, polygon) in polygons.iter().enumerate() {
            triangulate_polygon(points, polygon, triangles)
                .map_err(|reason| format!("polygon {}: {reason}", k + 1))?;
        }
        return Ok(());
    }
    let loops: Vec<Vec<u32>> = polygons
        .iter()
        .map(|p| distinct_corners(points, p))
        .collect();
    if let Some(k) = loops.iter().position(|l| l.len() < 3) {
        return Err(format!(
            "polygon {}: {}",
            k + 1,
            too_few_corners(loops[k].len())
        ));
    }
    let Some(widest) = loops
        .iter()
        .map(|l| newell_normal(points, l))
        .reduce(|a, b| if norm2(&b) > norm2(&a) { b } else { a })
    else {
        return Ok(());
    };
    let axis = projection_axis(&widest)?;
    let xy: Vec<Vec<[f64; 2]>> = loops
        .iter()
        .map(|l| {
            l.iter()
                .map(|&v| project(&points[v as usize], axis))
                .collect()
        })
        .collect();
    let (parents, depth) = nesting(&xy);
    let mut removed = vec![false; loops.len()];
    for (k, hole) in holes.iter().enumerate() {
        if let Some(face) = face_of(&xy, &depth, project(hole, axis))
            .map_err(|()| format!("hole {} lies on a polygon's boundary", k + 1))?
        {
            removed[face] = true;
        }
    }
    for (k, outer) in loops.iter().enumerate() {
        if removed[k] {
            continue;
        }
        let inner: Vec<Vec<u32>> = (0..loops.len())
            .filter(|&j| parents[j] == Some(k))
            .map(|j| loops[j].clone())
            .collect();
        ears::triangulate(points, axis, (outer, &inner), &|_| false, triangles)
            .map_err(|reason| format!("polygon {}: {reason}", k + 1))?;
    }
    Ok(())
}

fn too_few_corners(n: usize) -> String {
    format!(
        "{n} distinct corner{}: a face needs at least 3 (segments and points are not supported)",
        if n == 1 { "" } else { "s" }
    )
}

/// `corners` without repeated consecutive corners (same index or same position), the last
/// and the first corners counting as consecutive.
fn distinct_corners(points: &[Point], corners: &[u32]) -> Vec<u32> {
    let same = |a: u32, b: u32| points[a as usize] == points[b as usize];
    let mut out: Vec<u32> = Vec::with_capacity(corners.len());
    for &c in corners {
        if out.last().is_none_or(|&last| !same(last, c)) {
            out.push(c);
        }
    }
    while out.len() > 1 && same(out[0], out[out.len() - 1]) {
        out.pop();
    }
    out
}

/// The normal of the polygon `corners` by Newell's method: twice its vector area.
fn newell_normal(points: &[Point], corners: &[u32]) -> [f64; 3] {
    let mut n = [0.0; 3];
    for (k, &c) in corners.iter().enumerate() {
        let a = &points[c as usize];
        let b = &points[corners[(k + 1) % corners.len()] as usize];
        n[0] += (a[1] - b[1]) * (a[2] + b[2]);
        n[1] += (a[2] - b[2]) * (a[0] + b[0]);
        n[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    n
}

fn norm2(v: &[f64; 3]) -> f64 {
    v[0] * v[0] + v[1] * v[1] + v[2] * v[2]
}

/// The axis along which `normal` is largest (the first one on ties): the coordinate that
/// projection drops.
fn projection_axis(normal: &[f64; 3]) -> Result<usize, String> {
    let magnitude = normal.map(f64::abs);
    let axis = (0..3).fold(0, |best, k| {
        if magnitude[k] > magnitude[best] {
            k
        } else {
            best
        }
    });
    if magnitude[axis] > 0.0 && magnitude[axis].is_finite() {
        Ok(axis)
    } else {
        Err("the polygon has no area (its corners are collinear)".to_string())
    }
}

/// `p` without its coordinate `axis`, the other two in cyclic order, so that a polygon
/// whose normal points along `+axis` turns counter-clockwise.
pub(crate) fn project(p: &Point, axis: usize) -> [f64; 2] {
    [p[(axis + 1) % 3], p[(axis + 2) % 3]]
}

/// Where a point is with respect to a closed polygon.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Location {
    Inside,
    Outside,
    Boundary,
}

/// Where `q` is with respect to the polygon `ring`, exactly (winding number).
fn locate(q: [f64; 2], ring: &[[f64; 2]]) -> Location {
    let mut winding = 0i64;
    for (k, a) in ring.iter().enumerate() {
        let b = &ring[(k + 1) % ring.len()];
        let side = orient2d(a, b, &q);
        if side == Sign::Zero && within_box(a, b, &q) {
            return Location::Boundary;
        }
        if a[1] <= q[1] {
            if b[1] > q[1] && side == Sign::Positive {
                winding += 1;
            }
        } else if b[1] <= q[1] && side == Sign::Negative {
            winding -= 1;
        }
    }
    if winding == 0 {
        Location::Outside
    } else {
        Location::Inside
    }
}

/// True when `q` is in the closed bounding box of `a` and `b`.
pub(super) fn within_box(a: &[f64; 2], b: &[f64; 2], q: &[f64; 2]) -> bool {
    (0..2).all(|k| a[k].min(b[k]) <= q[k] && q[k] <= a[k].max(b[k]))
}

/// True when polygon `inner` is inside polygon `outer`: its first corner not on the
/// boundary of `outer` is inside (false when every corner is on it).
fn contains(outer: &[[f64; 2]], inner: &[[f64; 2]]) -> bool {
    inner
        .iter()
        .map(|&q| locate(q, outer))
        .find(|&l| l != Location::Boundary)
        == Some(Location::Inside)
}

/// The nesting of polygons: the innermost polygon containing each one (if any), and the
/// number of polygons containing each one (its depth).
fn nesting(loops: &[Vec<[f64; 2]>]) -> (Vec<Option<usize>>, Vec<usize>) {
    let containers: Vec<Vec<usize>> = (0..loops.len())
        .map(|j| {
            (0..loops.len())
                .filter(|&i| i != j && contains(&loops[i], &loops[j]))
                .collect()
        })
        .collect();
    let depth: Vec<usize> = containers.iter().map(Vec::len).collect();
    let parents = containers
        .iter()
        .map(|c| deepest(c.iter().copied(), &depth))
        .collect();
    (parents, depth)
}

/// Among the polygons `candidates`, the deepest (the first on ties).
fn deepest(candidates: impl Iterator<Item = usize>, depth: &[usize]) -> Option<usize> {
    candidates.reduce(|a, b| if depth[b] > depth[a] { b } else { a })
}

/// The face containing `q`, named by its outer polygon: the deepest polygon that contains
/// it (`None` outside every polygon). An error when `q` is on a polygon's boundary.
fn face_of(loops: &[Vec<[f64; 2]>], depth: &[usize], q: [f64; 2]) -> Result<Option<usize>, ()> {
    let mut inside = Vec::new();
    for (k, ring) in loops.iter().enumerate() {
        match locate(q, ring) {
            Location::Boundary => return Err(()),
            Location::Inside => inside.push(k),
            Location::Outside => {}
        }
    }
    Ok(deepest(inside.into_iter(), depth))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sorted(t: &[u32]) -> [u32; 3] {
        let mut t = [t[0], t[1], t[2]];
        t.sort_unstable();
        t
    }

    /// Declaring flat the first triangle the plain triangulation of a square makes (as if
    /// its corners lay on one line) gives the other diagonal: two positive triangles that
    /// cover the square.
    #[test]
    fn declared_flat_triangles_are_avoided() {
        let points = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ];
        let corners = [0, 1, 2, 3];
        let mut plain = Vec::new();
        triangulate_polygon(&points, &corners, &mut plain).unwrap();
        let banned = sorted(&plain[..3]);
        let flat = |t: [u32; 3]| sorted(&t) == banned;
        let mut triangles = Vec::new();
        triangulate_polygon_avoiding(&points, &corners, &flat, &mut triangles).unwrap();
        assert_eq!(triangles.len(), 6, "{triangles:?}");
        let mut area = 0.0;
        for t in triangles.chunks(3) {
            assert_ne!(sorted(t), banned, "{triangles:?}");
            let [a, b, c] = [t[0], t[1], t[2]].map(|v| project(&points[v as usize], 2));
            assert_eq!(orient2d(&a, &b, &c), Sign::Positive);
            area += 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]));
        }
        assert_eq!(area, 1.0);
    }
}
