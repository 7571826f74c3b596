//! Removal of the points added on the input surface (George and Borouchaki §5.3): a point
//! `P` of the partition leaves the surface. In every input triangle holding it, the subfaces
//! around `P` are replaced by a triangulation of their outline without `P`; the input
//! triangles through `P` cut its star into pieces (two for a point inside a triangle, one per
//! wedge between consecutive triangles for a point on an edge), and each piece gets its own
//! copy of `P` moved off the surface into the piece, far enough for every new tetrahedron to
//! be positive. The copies are ordinary interior points; those outside the surface go with
//! the outside.
//!
//! The paper proves the moved point exists (the piece is star-shaped from `P`, which sees
//! the outline's triangulation from its side); here the move is searched along the sum of
//! the piece's side normals, then toward the centroid of the piece's vertices, then between
//! the two, halving the distance until every new tetrahedron is positive.
//!
//! Where many points crowd on a planar face the move can find no place: the point is then
//! merged on the surface into a neighbour on the same input triangle or edge (the paper's
//! merging, [`collapse_on_surface`]), and a point that can do neither is tried again after
//! the others. Where points are still stuck, the points already moved off, which sit as near
//! the surface as the halving left them and make their neighbours' stars thin, go to better
//! places ([`relocate_interior`]) before the stuck ones are tried again (Chazelle's
//! polyhedron with eight notches a side meshes so: 32 points stuck, 3 after one relocation,
//! none after two). Last, for the points still left, a
//! piece no move fits is filled without the point: its boundary, or that boundary grown by a
//! few layers of tetrahedra, is tetrahedralized by this module's recovery with no point
//! allowed ([`fill_piece`]; Chazelle's polyhedron with two notches a side meshes so). The
//! outline is triangulated without flat triangles (three points of one input edge).
//!
//! The interior points then go where they can ([`merge_interior`]): collapsed onto a
//! neighbour (the paper's merging), or removed by filling their star, or their star and a few
//! layers around it, again without them: the recovery of the region's boundary, with no point
//! allowed, does that when it can. Last, a point left is dissolved by flips where they can
//! take its edges away one by one ([`dissolve`]). Only the points inside the kept regions are
//! removed so; where some are left, all this runs once more with more layers
//! ([`SECOND_REMOVAL`]).

use rustc_hash::FxHashMap as HashMap;

use super::flips::{remove_edge_deep, Any, Memo, Protected};
use super::partition::{Host, Partition};
use super::tetmesh::{key, Key, TetMesh};
use super::until_stable;
use crate::error::{Error, ErrorKind, Result};
use crate::geometry::{add, cross, dist, dot, midpoint, norm, sub};
use crate::io::surface::triangulate_polygon_avoiding;
use crate::predicates::Point;
use crate::triangulation::tets::FACE;

/// Halvings of the move before giving up.
const MOVES: usize = 48;

/// One input triangle through the removed point: its old subfaces there and their
/// replacement.
struct Patch {
    face: usize,
    old: Vec<[u32; 3]>,
    new: Vec<[u32; 3]>,
}

/// Moves every point of the partition off the surface: points inside triangles first, then
/// points on edges. `normals[f]` is the unit normal of partition triangle `f`. The triangles
/// from `first_hull` on are the convex hull's (`keep_convex_hull`): a point on those alone
/// merges into a neighbour there where it can, else stays, a vertex of the mesh's boundary.
pub fn suppress_all(
    mesh: &mut TetMesh,
    part: &mut Partition,
    normals: &[Point],
    first_hull: usize,
) -> Result<()> {
    let mut inside: Vec<u32> = Vec::new();
    let mut on_edges: Vec<u32> = Vec::new();
    let mut on_hull: Vec<u32> = Vec::new();
    for (&v, host) in &part.host {
        if part.faces_of(v).iter().all(|&f| f >= first_hull) {
            on_hull.push(v);
            continue;
        }
        match host {
            Host::Face(_) => inside.push(v),
            Host::Edge(_) => on_edges.push(v),
        }
    }
    inside.sort_unstable();
    on_edges.sort_unstable();
    // A point that cannot leave may after its neighbours have: passes while some leave.
    // Pieces of a star filled without the point come last, for the points left then.
    let mut stuck: Vec<u32> = inside.into_iter().chain(on_edges).collect();
    let mut errors: HashMap<u32, Error> = HashMap::default();
    let first = mesh.first_added();
    for fill in [false, true] {
        let mut passes = |mesh: &mut TetMesh, part: &mut Partition, stuck: Vec<u32>| {
            until_stable(stuck, |&v| match suppress(mesh, part, normals, v, fill) {
                Err(e) if e.kind == ErrorKind::Limit => {
                    errors.entry(v).or_insert(e);
                    Ok(false)
                }
                result => result.map(|()| true),
            })
        };
        stuck = passes(mesh, part, stuck)?;
        // The points moved off so far sit as near the surface as the halving of their moves
        // left them, and the stars of points still on it can be too thin for a move: the
        // interior points go to better places ([`relocate_interior`]) before the next passes.
        while !stuck.is_empty() {
            relocate_interior(mesh, part, first);
            let before = stuck.len();
            stuck = passes(mesh, part, stuck)?;
            if stuck.len() == before {
                break;
            }
        }
    }
    if let Some(e) = stuck.first().and_then(|v| errors.remove(v)) {
        return Err(e);
    }
    // Points on the hull's triangles alone cannot leave (nothing is beyond the hull to take
    // them) but may merge into a neighbour there.
    on_hull.sort_unstable();
    until_stable(on_hull, |&v| collapse_on_surface(mesh, part, v))?;
    Ok(())
}

fn failure(message: String) -> Error {
    Error::new(ErrorKind::Limit, message)
}

/// The subfaces of `face` around `p`, and the triangulation of their outline without `p`.
fn patch(mesh: &TetMesh, part: &Partition, face: usize, p: u32) -> Result<Patch> {
    let old = part.fan(face, p);
    let mut next: HashMap<u32, u32> = HashMap::default();
    for &s in &old {
        let r = s.iter().position(|&x| x == p).unwrap_or(0);
        next.insert(s[(r + 1) % 3], s[(r + 2) % 3]);
    }
    let targets: Vec<u32> = next.values().copied().collect();
    let start = next
        .keys()
        .copied()
        .filter(|k| !targets.contains(k))
        .min()
        .or_else(|| next.keys().copied().min())
        .ok_or_else(|| Error::internal(format!("point {p} is in no subface of triangle {face}")))?;
    let mut outline = vec![start];
    let mut at = start;
    while let Some(&n) = next.get(&at) {
        if n == start || outline.len() > old.len() {
            break;
        }
        outline.push(n);
        at = n;
    }
    let closed = next.get(&at) == Some(&start);
    let expected = if closed { old.len() } else { old.len() + 1 };
    if outline.len() != expected {
        return Err(Error::internal(format!(
            "the subfaces of triangle {face} around point {p} are not a fan"
        )));
    }
    let mut flat = Vec::new();
    let on_one_edge = |t: [u32; 3]| part.on_one_edge(t);
    triangulate_polygon_avoiding(&mesh.points, &outline, &on_one_edge, &mut flat).map_err(
        |why| {
            failure(format!(
                "the outline of point {p} in triangle {face} cannot be triangulated: {why}"
            ))
        },
    )?;
    let new = flat.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
    Ok(Patch { face, old, new })
}

/// Moves point `p` off the surface; where no move makes every new tetrahedron positive,
/// merges it on the surface into a neighbour ([`collapse_on_surface`]); with `fill`, where
/// that fails too, moves it off again, filling without it the pieces of its star no move
/// fits ([`fill_piece`]).
fn suppress(
    mesh: &mut TetMesh,
    part: &mut Partition,
    normals: &[Point],
    p: u32,
    fill: bool,
) -> Result<()> {
    let added = mesh.points.len();
    let restore = |mesh: &mut TetMesh| {
        while mesh.points.len() > added {
            mesh.pop_point();
        }
    };
    match move_off(mesh, part, normals, p, false) {
        Err(e) if e.kind == ErrorKind::Limit => {
            restore(mesh);
            if collapse_on_surface(mesh, part, p)? {
                return Ok(());
            }
            if !fill {
                return Err(e);
            }
            let result = move_off(mesh, part, normals, p, true);
            if result.is_err() {
                restore(mesh);
            }
            result
        }
        result => result,
    }
}

/// Merges point `p` of the partition into a neighbour `o` on every input triangle through
/// it (George and Borouchaki §5.3, merging): `o` is a vertex of `p`'s subfaces that lies on
/// the same input triangle, or on the same input edge when `p` does. Every subface and
/// tetrahedron through `p` takes `o` in its place, those through both vanish; the nearest `o`
/// for which every new tetrahedron is positive is taken. `false` when there is none.
fn collapse_on_surface(mesh: &mut TetMesh, part: &mut Partition, p: u32) -> Result<bool> {
    let faces = part.faces_of(p);
    let fans: Vec<Vec<[u32; 3]>> = faces.iter().map(|&f| part.fan(f, p)).collect();
    let mut candidates: Vec<u32> = fans.iter().flatten().flatten().copied().collect();
    candidates.sort_unstable();
    candidates.dedup();
    let host = part.host.get(&p).copied();
    candidates.retain(|&o| match host {
        Some(Host::Edge(e)) => o != p && part.on_edge(o, e),
        _ => o != p,
    });
    nearest_first(mesh, p, &mut candidates);
    let ball = mesh.ball(p);
    for o in candidates {
        let flat = fans
            .iter()
            .flatten()
            .any(|&s| !s.contains(&o) && part.on_one_edge(renamed(s, p, o)));
        if flat || !merge_into(mesh, &ball, p, o)? {
            continue;
        }
        for (&f, old) in faces.iter().zip(&fans) {
            let kept: Vec<[u32; 3]> = old
                .iter()
                .filter(|s| !s.contains(&o))
                .map(|&s| renamed(s, p, o))
                .collect();
            part.retriangulate(f, old, &kept);
        }
        part.host.remove(&p);
        return Ok(true);
    }
    Ok(false)
}

/// `q` with vertex `p` renamed `o`.
fn renamed<const N: usize>(q: [u32; N], p: u32, o: u32) -> [u32; N] {
    q.map(|v| if v == p { o } else { v })
}

/// Sorts `vertices` (sorted by number) by their distance to `p`, nearest first; ties keep
/// their order.
fn nearest_first(mesh: &TetMesh, p: u32, vertices: &mut [u32]) {
    let at = *mesh.point(p);
    vertices.sort_by(|&a, &b| dist(&at, mesh.point(a)).total_cmp(&dist(&at, mesh.point(b))));
}

/// Merges `p` into its neighbour `o`: every tetrahedron of `ball`, the star of `p`, takes
/// `o` in place of `p`, and those through both vanish. `false`, changing nothing, when a new
/// tetrahedron would not be positive.
fn merge_into(mesh: &mut TetMesh, ball: &[u32], p: u32, o: u32) -> Result<bool> {
    let new: Vec<[u32; 4]> = ball
        .iter()
        .map(|&t| mesh.tets.vertices(t))
        .filter(|q| !q.contains(&o))
        .map(|q| renamed(q, p, o))
        .collect();
    if !new.iter().all(|&q| mesh.positive(q)) || mesh.try_replace(ball, &new)?.is_none() {
        return Ok(false);
    }
    mesh.forget(p);
    Ok(true)
}

/// Moves point `p` off the surface: one copy into each piece of its star; with `fill`, a
/// piece no copy fits is filled without one where [`fill_piece`] can.
fn move_off(
    mesh: &mut TetMesh,
    part: &mut Partition,
    normals: &[Point],
    p: u32,
    fill: bool,
) -> Result<()> {
    let faces = part.faces_of(p);
    let patches: Vec<Patch> = faces
        .iter()
        .map(|&f| patch(mesh, part, f, p))
        .collect::<Result<_>>()?;
    let mut separators: HashMap<Key, (usize, [u32; 3])> = HashMap::default();
    for (j, patch) in patches.iter().enumerate() {
        for &s in &patch.old {
            separators.insert(key(s), (j, s));
        }
    }
    let ball = mesh.ball(p);
    let pieces = pieces(mesh, &ball, p, &separators);
    let origin = *mesh.point(p);
    let reach = ball
        .iter()
        .flat_map(|&t| mesh.tets.vertices(t))
        .filter(|&v| v != p)
        .map(|v| dist(&origin, mesh.point(v)))
        .fold(f64::INFINITY, f64::min);
    let mut all = Vec::new();
    // Tetrahedra around the star that a filled piece replaces too.
    let mut around: Vec<u32> = Vec::new();
    let mut filled_any = false;
    for piece in pieces {
        let sides = bounding_sides(mesh, &piece, p, &separators);
        let mut normal = [0.0; 3];
        for &(j, front) in &sides {
            let n = normals[patches[j].face];
            let sign = if front { 1.0 } else { -1.0 };
            normal = add(&normal, &[sign * n[0], sign * n[1], sign * n[2]]);
        }
        let q = mesh.add_point(origin);
        let mut tets: Vec<[u32; 4]> = piece
            .iter()
            .map(|&t| mesh.tets.vertices(t).map(|v| if v == p { q } else { v }))
            .collect();
        for &(j, front) in &sides {
            for &[x, y, z] in &patches[j].new {
                tets.push(if front { [x, y, z, q] } else { [y, x, z, q] });
            }
        }
        let toward = sub(&centroid(mesh, &piece, p), &origin);
        let (n, w) = (unit(&normal), unit(&toward));
        let between = n.zip(w).and_then(|(n, w)| unit(&add(&n, &w)));
        let directions = [n, w, between];
        let placed = directions.iter().flatten().any(|d| {
            let mut step = 0.25 * reach;
            (0..MOVES).any(|_| {
                mesh.move_point(q, add(&origin, &[step * d[0], step * d[1], step * d[2]]));
                step *= 0.5;
                tets.iter().all(|&t| mesh.positive(t))
            })
        });
        if placed {
            all.extend(tets);
            continue;
        }
        if !fill {
            return Err(failure(format!(
                "point {p} added on the surface near {origin:?} could not be moved off it"
            )));
        }
        // No place for the copy: the piece, or the piece and a few layers around it, is
        // filled without it where its boundary allows.
        let cone: Vec<[u32; 3]> = tets.iter().map(|t| without(*t, q)).collect();
        mesh.pop_point();
        let taken: Vec<u32> = ball.iter().chain(&around).copied().collect();
        let surface: Vec<Key> = sides
            .iter()
            .flat_map(|&(j, _)| patches[j].new.iter().map(|&f| key(f)))
            .collect();
        let Some((filled, grown)) = fill_piece(mesh, &part.protected, &surface, &taken, &cone)
        else {
            return Err(failure(format!(
                "point {p} added on the surface near {origin:?} could not be moved off it"
            )));
        };
        all.extend(filled);
        around.extend(grown);
        filled_any = true;
    }
    let replaced: Vec<u32> = ball.iter().chain(&around).copied().collect();
    if filled_any {
        // Each filling matches its own region, but a flat part one piece dropped may be
        // what another piece's cone, or the mesh outside, still holds.
        if mesh.try_replace(&replaced, &all)?.is_none() {
            return Err(failure(format!(
                "point {p} added on the surface near {origin:?} could not be moved off it: \
                 the fillings of its star's pieces do not fit together"
            )));
        }
    } else {
        mesh.replace(&replaced, &all)?;
    }
    mesh.forget(p);
    for patch in &patches {
        part.retriangulate(patch.face, &patch.old, &patch.new);
    }
    part.host.remove(&p);
    Ok(())
}

/// The tetrahedra filling a piece of a star without its point: `cone` is the piece's
/// boundary (the bases of the cone from the point's copy). It is grown by up to
/// [`REFILL_LAYERS`] layers of tetrahedra across facets neither protected nor in `surface`
/// (the piece's new subfaces), none of `taken` (the star and what other pieces took), until
/// [`fill_boundary`] fills it and every vertex inside is on its boundary. Returns the
/// filling and the tetrahedra the growth took.
fn fill_piece(
    mesh: &mut TetMesh,
    protected: &Protected,
    surface: &[Key],
    taken: &[u32],
    cone: &[[u32; 3]],
) -> Option<(Vec<[u32; 4]>, Vec<u32>)> {
    let mut grown: Vec<u32> = Vec::new();
    for layer in 0..=REFILL_LAYERS {
        let boundary = boundary_of(mesh, cone, &grown);
        let mut on_boundary: Vec<u32> = boundary.iter().flatten().copied().collect();
        on_boundary.sort_unstable();
        let all_on = grown
            .iter()
            .flat_map(|&t| mesh.tets.vertices(t))
            .all(|v| on_boundary.binary_search(&v).is_ok());
        if all_on {
            if let Some(filled) = fill_boundary(mesh, &boundary, &[]) {
                return Some((filled, grown));
            }
        }
        if layer == REFILL_LAYERS {
            break;
        }
        let before = grown.len();
        for &f in &boundary {
            if protected.facet(f) || surface.contains(&key(f)) {
                continue;
            }
            let Some((t, i)) = mesh.find_face(f) else {
                continue;
            };
            for u in [t, mesh.tets.neighbor(t, i)] {
                if !taken.contains(&u) && !grown.contains(&u) {
                    grown.push(u);
                }
            }
        }
        if grown.len() == before {
            break;
        }
    }
    None
}

/// The faces that occur an odd number of times among `cone` and the facets of `grown` (a
/// face of the cone twice bounds a flat part, which vanishes).
fn boundary_of(mesh: &TetMesh, cone: &[[u32; 3]], grown: &[u32]) -> Vec<[u32; 3]> {
    let mut count: HashMap<Key, ([u32; 3], usize)> = HashMap::default();
    let faces = cone.iter().copied().chain(
        grown
            .iter()
            .flat_map(|&t| (0..4).map(move |i| mesh.facet(t, i))),
    );
    for f in faces {
        count.entry(key(f)).or_insert((f, 0)).1 += 1;
    }
    let mut once: Vec<[u32; 3]> = count
        .into_values()
        .filter(|&(_, n)| n % 2 == 1)
        .map(|(f, _)| f)
        .collect();
    once.sort_unstable();
    once
}

/// The three vertices of `t` other than its vertex `q`.
fn without(t: [u32; 4], q: u32) -> [u32; 3] {
    let i = t.iter().position(|&v| v == q).unwrap_or(3);
    let mut f = [0; 3];
    let mut k = 0;
    for (j, &v) in t.iter().enumerate() {
        if j != i {
            f[k] = v;
            k += 1;
        }
    }
    f
}

/// `u` scaled to length 1, if it has a length.
fn unit(u: &Point) -> Option<Point> {
    let l = norm(u);
    (l > 0.0 && l.is_finite()).then(|| [u[0] / l, u[1] / l, u[2] / l])
}

/// The mean of the vertices of `piece` other than `p`.
fn centroid(mesh: &TetMesh, piece: &[u32], p: u32) -> Point {
    let mut sum = [0.0; 3];
    let mut count = 0.0;
    for &t in piece {
        for v in mesh.tets.vertices(t) {
            if v != p {
                sum = add(&sum, mesh.point(v));
                count += 1.0;
            }
        }
    }
    [sum[0] / count, sum[1] / count, sum[2] / count]
}

/// The tetrahedra of `ball` (the star of `p`) grouped by the surface through `p`.
fn pieces(
    mesh: &mut TetMesh,
    ball: &[u32],
    p: u32,
    separators: &HashMap<Key, (usize, [u32; 3])>,
) -> Vec<Vec<u32>> {
    for &t in ball {
        mesh.tets.mark[t as usize] = 4;
    }
    let mut pieces = Vec::new();
    for &seed in ball {
        if mesh.tets.mark[seed as usize] != 4 {
            continue;
        }
        mesh.tets.mark[seed as usize] = 5;
        let mut piece = vec![seed];
        let mut k = 0;
        while k < piece.len() {
            let t = piece[k];
            k += 1;
            let v = mesh.tets.vertices(t);
            for (i, &apex) in v.iter().enumerate() {
                let f = mesh.facet(t, i);
                if apex == p || separators.contains_key(&key(f)) {
                    continue;
                }
                let n = mesh.tets.neighbor(t, i);
                if mesh.tets.mark[n as usize] == 4 {
                    mesh.tets.mark[n as usize] = 5;
                    piece.push(n);
                }
            }
        }
        pieces.push(piece);
    }
    for &t in ball {
        mesh.tets.mark[t as usize] = 0;
    }
    pieces
}

/// The patches bounding a piece, each with the side the piece is on (`true`: in front).
fn bounding_sides(
    mesh: &TetMesh,
    piece: &[u32],
    p: u32,
    separators: &HashMap<Key, (usize, [u32; 3])>,
) -> Vec<(usize, bool)> {
    let mut sides = Vec::new();
    for &t in piece {
        let v = mesh.tets.vertices(t);
        for (i, &apex) in v.iter().enumerate() {
            if apex == p {
                continue;
            }
            if let Some(&(j, s)) = separators.get(&key(mesh.facet(t, i))) {
                let side = (j, mesh.in_front(t, i, s));
                if !sides.contains(&side) {
                    sides.push(side);
                }
            }
        }
    }
    sides.sort_unstable();
    sides
}

/// Removes the points moved off the surface where possible (George and Borouchaki §5.3,
/// "some added points may simply vanish by merging"). Point `s` collapses onto the nearest
/// vertex `q` of its star for which every tetrahedron of the star without `q` stays positive
/// with `s` replaced by `q`; the `points` (sorted) are tried in order until none collapses. Then
/// each point left is removed when its star, or its star and up to `removal.layers` layers
/// around it, can be filled again without it ([`refill`]), and two neighbouring points left
/// are merged into one where one point sees their joined stars' boundary ([`merge_pair`]);
/// collapses are tried again, a bounded number of times. The points still left are then
/// dissolved by flips where possible ([`dissolve`]).
pub fn merge_interior(
    mesh: &mut TetMesh,
    protected: &Protected,
    points: &[u32],
    removal: Removal,
) -> Result<()> {
    for _ in 0..REFILL_PASSES {
        loop {
            let mut merged = false;
            for s in left(mesh, points) {
                merged |= collapse(mesh, protected, s)?;
            }
            if !merged {
                break;
            }
        }
        let mut removed = false;
        for s in left(mesh, points) {
            for layers in 0..=removal.layers {
                if refill(mesh, protected, s, layers, removal.kept_inside)? {
                    removed = true;
                    break;
                }
            }
        }
        for s in left(mesh, points) {
            if mesh.in_mesh(s) && merge_pair(mesh, protected, s, points)? {
                removed = true;
            }
        }
        if !removed {
            break;
        }
    }
    for s in left(mesh, points) {
        dissolve(mesh, protected, s)?;
    }
    Ok(())
}

/// Removes interior point `p` together with a neighbour `q` among `points` (sorted), one point
/// in their place: the edge `pq` is collapsed and the point left put at its midpoint, or
/// deepest in the kernel of its new star ([`deepest_in_kernel`]); `false`, changing nothing,
/// where no place keeps every tetrahedron positive. Interior points left on Chazelle's
/// polyhedra with three and four notches a side: 16 -> 14, 22 -> 21.
fn merge_pair(mesh: &mut TetMesh, protected: &Protected, p: u32, points: &[u32]) -> Result<bool> {
    let ball = mesh.ball(p);
    if on_surface(mesh, protected, &ball, p) {
        return Ok(false);
    }
    let mut link = link(mesh, &ball, p);
    link.retain(|q| points.binary_search(q).is_ok());
    nearest_first(mesh, p, &mut link);
    for q in link {
        let others = mesh.ball(q);
        if on_surface(mesh, protected, &others, q) {
            continue;
        }
        // The star of `q` once `p` is merged into it ([`merge_into`]).
        let star: Vec<[u32; 4]> = (others.iter().chain(&ball))
            .map(|&t| mesh.tets.vertices(t))
            .filter(|v| !(v.contains(&p) && v.contains(&q)))
            .map(|v| renamed(v, p, q))
            .collect();
        let at = *mesh.point(q);
        let middle = midpoint(&at, mesh.point(p));
        mesh.move_point(q, middle);
        let deepest = deepest_in_kernel(mesh, &star, q);
        for c in [middle, deepest] {
            mesh.move_point(q, c);
            if star.iter().all(|&v| mesh.positive(v)) && merge_into(mesh, &ball, p, q)? {
                return Ok(true);
            }
        }
        mesh.move_point(q, at);
    }
    Ok(false)
}

/// Removes interior point `s` by flips, as TetGen removes a Steiner point it cannot
/// collapse: the edges at `s` are removed one at a time ([`remove_edge_deep`]) until its star
/// is four tetrahedra, which the tetrahedron of their other four vertices replaces (a 4-1
/// flip). On failure the mesh is restored from a copy, so that a point that stays leaves no
/// trace (the copy costs a pass over the mesh per point left, few after [`refill`]).
fn dissolve(mesh: &mut TetMesh, protected: &Protected, s: u32) -> Result<()> {
    let mut ball = mesh.ball(s);
    if on_surface(mesh, protected, &ball, s) {
        return Ok(());
    }
    let before = mesh.clone();
    for _ in 0..DISSOLVE_ROUNDS {
        let link = link(mesh, &ball, s);
        if ball.len() == 4 && link.len() == 4 {
            // The star's tetrahedron with `s` renamed the link vertex it lacks.
            let q = mesh.tets.vertices(ball[0]);
            let lacking = link.iter().copied().find(|w| !q.contains(w));
            let one = lacking.map(|w| renamed(q, s, w));
            if let Some(one) = one.filter(|&one| mesh.positive(one)) {
                if mesh.try_replace(&ball, &[one])?.is_some() {
                    mesh.forget(s);
                    return Ok(());
                }
            }
            break;
        }
        let mut removed = false;
        for w in link {
            let mut budget = DISSOLVE_BUDGET;
            if remove_edge_deep(mesh, protected, [s, w], &Any, DISSOLVE_DEPTH, &mut budget)? {
                removed = true;
                break;
            }
        }
        if !removed {
            break;
        }
        ball = mesh.ball(s);
    }
    *mesh = before;
    Ok(())
}

/// Edge removals [`dissolve`] makes at most (each takes one edge from the point).
const DISSOLVE_ROUNDS: usize = 64;

/// Depth and budget of each of [`dissolve`]'s edge removals.
const DISSOLVE_DEPTH: u32 = 2;
const DISSOLVE_BUDGET: usize = 64;

/// Whether `s`, whose star is `ball`, is a vertex of a protected facet (a point left on the
/// convex hull's triangles).
fn on_surface(mesh: &TetMesh, protected: &Protected, ball: &[u32], s: u32) -> bool {
    ball.iter().any(|&t| {
        let v = mesh.tets.vertices(t);
        (0..4).any(|i| v[i] != s && protected.facet(mesh.facet(t, i)))
    })
}

/// The vertices of the tetrahedra `ball` other than `s` and the infinite vertex, sorted.
fn link(mesh: &TetMesh, ball: &[u32], s: u32) -> Vec<u32> {
    let mut link: Vec<u32> = ball
        .iter()
        .flat_map(|&t| mesh.tets.vertices(t))
        .filter(|&v| v != s && v != crate::triangulation::tets::INFINITE)
        .collect();
    link.sort_unstable();
    link.dedup();
    link
}

/// Layers of tetrahedra around a piece ([`fill_piece`]) added at most, one at a time.
pub const REFILL_LAYERS: usize = 4;

/// How far [`merge_interior`] looks to remove a point: its star grown by up to `layers`
/// layers of tetrahedra, holding at most `kept_inside` other points, which stay
/// ([`refill`]).
#[derive(Clone, Copy, Debug)]
pub struct Removal {
    pub layers: usize,
    pub kept_inside: usize,
}

/// The removal after points are moved off the surface.
pub const FIRST_REMOVAL: Removal = Removal {
    layers: REFILL_LAYERS,
    kept_inside: 0,
};

/// The removal on the mesh a recovery keeps when points are left in its regions: more
/// layers, and one point kept inside them (handle: 7 points left -> 6). With no bound on the
/// points kept, none of the inputs of the C test that need points (Chazelle's polyhedra with
/// two to four notches a side, anchor, joint, handle, pipe, sphere966) kept fewer, and those
/// polyhedra took 1.5 to 2.1 times as long.
pub const SECOND_REMOVAL: Removal = Removal {
    layers: 6,
    kept_inside: 1,
};

/// Passes of [`refill`] over the points left, each after collapses (a removal can make a
/// neighbour removable).
const REFILL_PASSES: usize = 2;

/// The `points` still in the mesh.
fn left(mesh: &TetMesh, points: &[u32]) -> Vec<u32> {
    points
        .iter()
        .copied()
        .filter(|&s| mesh.in_mesh(s))
        .collect()
}

/// Moves every point added off the surface (ids `first..`, none still on the partition: a
/// point on the convex hull's triangles stays there) to where its star's worst
/// radius-edge ratio is smallest (George and Borouchaki's relocation; the halving that took
/// it off the surface leaves it needlessly close): the candidates lie on the segments from the
/// point to the centroid of its link and to the centroid of each link triangle, and, for a
/// nearly flat star ([`FLAT_STAR`]), to the point of its kernel farthest from the link's
/// planes that an ascent finds ([`deepest_in_kernel`]); a move is kept only when every
/// tetrahedron of the star stays positive (exact) and the worst ratio improves. The mesh's
/// topology does not change.
pub fn relocate_interior(mesh: &mut TetMesh, part: &Partition, first: u32) {
    for _ in 0..RELOCATION_PASSES {
        for s in first..mesh.points.len() as u32 {
            if mesh.in_mesh(s) && !part.host.contains_key(&s) {
                relocate(mesh, s);
            }
        }
    }
}

/// Passes of [`relocate_interior`]: a move changes its neighbours' best places.
const RELOCATION_PASSES: usize = 3;

fn relocate(mesh: &mut TetMesh, s: u32) {
    let ball = mesh.ball(s);
    let star: Vec<[u32; 4]> = ball.iter().map(|&t| mesh.tets.vertices(t)).collect();
    if star
        .iter()
        .any(|q| q.contains(&crate::triangulation::tets::INFINITE))
    {
        return;
    }
    let link = link(mesh, &ball, s);
    let middle =
        [0, 1, 2].map(|k| link.iter().map(|&v| mesh.point(v)[k]).sum::<f64>() / link.len() as f64);
    let worst = |mesh: &TetMesh| {
        star.iter()
            .map(|&q| crate::quality::radius_edge(q.map(|v| mesh.point(v))))
            .fold(0.0, f64::max)
    };
    let at = *mesh.point(s);
    // Toward the link's centroid, which a convex star holds, and toward each link triangle's,
    // which a thin or non-convex star may need (the halving that took the point off the
    // surface can leave it a rounding away from a surface triangle).
    let facet_centroids = ball.iter().map(|&t| centroid(mesh, &[t], s));
    let candidates: Vec<(Point, f64)> = [1.0, 0.75, 0.5, 0.25]
        .map(|step| (middle, step))
        .into_iter()
        .chain(facet_centroids.flat_map(|c| [(c, 0.5), (c, 0.25)]))
        .collect();
    let mut best = (worst(mesh), at);
    // A nearly flat star also tries the point deepest in its kernel.
    let deep: Vec<(Point, f64)> = if best.0 > FLAT_STAR {
        let deepest = deepest_in_kernel(mesh, &star, s);
        vec![(deepest, 1.0), (deepest, 0.5)]
    } else {
        Vec::new()
    };
    for (target, step) in candidates.into_iter().chain(deep) {
        let p = [0, 1, 2].map(|k| at[k] + step * (target[k] - at[k]));
        mesh.move_point(s, p);
        if star.iter().all(|&q| mesh.positive(q)) {
            let w = worst(mesh);
            if w < best.0 {
                best = (w, p);
            }
        }
    }
    mesh.move_point(s, best.1);
}

/// A point of the kernel of the star `star` of `s` far from the planes of its link
/// triangles: from where `s` is, steps along the inner normal of the nearest plane, or of the
/// nearly nearest ones together, as long as they take the point farther from the nearest
/// (an ascent on the smallest distance; a point that a halving left a rounding away from a
/// surface triangle gets away from it even where the star's kernel is thin).
fn deepest_in_kernel(mesh: &TetMesh, star: &[[u32; 4]], s: u32) -> Point {
    // Each link triangle as (a point of it, unit normal toward the kernel).
    let planes: Vec<(Point, Point)> = star
        .iter()
        .filter_map(|q| {
            let i = q.iter().position(|&v| v == s)?;
            let [a, b, c] = FACE[i].map(|k| *mesh.point(q[k]));
            // FACE[i] is turned so that the vertex i of a positive tetrahedron is in front.
            unit(&cross(&sub(&b, &a), &sub(&c, &a))).map(|n| (a, n))
        })
        .collect();
    let height = |x: &Point, (a, n): &(Point, Point)| dot(n, &sub(x, a));
    let nearest = |x: &Point| {
        planes
            .iter()
            .map(|p| height(x, p))
            .fold(f64::INFINITY, f64::min)
    };
    let mut x = *mesh.point(s);
    let mut depth = nearest(&x);
    let mut step = planes
        .iter()
        .map(|(a, _)| dist(a, &x))
        .fold(f64::INFINITY, f64::min)
        / 4.0;
    for _ in 0..KERNEL_STEPS {
        // The normals of the nearly nearest planes: their sum, and the first of them.
        let mut sum = [0.0; 3];
        let mut first = None;
        for p in planes
            .iter()
            .filter(|p| height(&x, p) <= depth + 0.25 * step)
        {
            sum = add(&sum, &p.1);
            first = first.or(Some(p.1));
        }
        let moved = [unit(&sum), first].into_iter().flatten().find_map(|d| {
            let y = add(&x, &[step * d[0], step * d[1], step * d[2]]);
            let deeper = nearest(&y);
            (deeper > depth).then_some((y, deeper))
        });
        match moved {
            Some((y, deeper)) => (x, depth) = (y, deeper),
            None => step *= 0.5,
        }
    }
    x
}

/// The worst radius-edge ratio above which a star is taken for nearly flat by [`relocate`]:
/// one of its tetrahedra is a rounding away from flat. Given to every star, the ascent moved
/// joint's points so that refinement with the bound 1.414 added 2 more (516 tetrahedra
/// against 493).
const FLAT_STAR: f64 = 1e6;

/// Steps of [`deepest_in_kernel`]'s ascent.
const KERNEL_STEPS: usize = 64;

/// Removes `s` by filling anew, without it, its star grown by `layers` layers of tetrahedra
/// across unprotected facets (a star whose boundary cannot be filled, such as Schönhardt's
/// prism, may be fillable with more around it). The region's boundary, a closed surface, is
/// tetrahedralized by this module's recovery with no point allowed but the region's other
/// inner vertices, at most `kept_inside`, which stay where they are
/// ([`super::fill_without_points`]); `false` if that fails, or if the region holds an input
/// triangle or more inner vertices.
fn refill(
    mesh: &mut TetMesh,
    protected: &Protected,
    s: u32,
    layers: usize,
    kept_inside: usize,
) -> Result<bool> {
    let mut region = mesh.ball(s);
    region.sort_unstable();
    for _ in 0..layers {
        let mut more = Vec::new();
        for &t in &region {
            for i in 0..4 {
                let n = mesh.tets.neighbor(t, i);
                if region.binary_search(&n).is_err() && !protected.facet(mesh.facet(t, i)) {
                    more.push(n);
                }
            }
        }
        if more.is_empty() {
            // The same region as with one layer fewer, which [`merge_interior`] tried first.
            return Ok(false);
        }
        region.extend(more);
        region.sort_unstable();
        region.dedup();
    }
    let mut boundary: Vec<[u32; 3]> = Vec::new();
    for &t in &region {
        for i in 0..4 {
            let f = mesh.facet(t, i);
            if region.binary_search(&mesh.tets.neighbor(t, i)).is_ok() {
                if protected.facet(f) {
                    return Ok(false);
                }
                continue;
            }
            boundary.push(f);
        }
    }
    let mut on_boundary: Vec<u32> = boundary.iter().flatten().copied().collect();
    on_boundary.sort_unstable();
    let mut inner: Vec<u32> = region
        .iter()
        .flat_map(|&t| mesh.tets.vertices(t))
        .filter(|&v| v != s && on_boundary.binary_search(&v).is_err())
        .collect();
    inner.sort_unstable();
    inner.dedup();
    if inner.len() > kept_inside || inner.contains(&crate::triangulation::tets::INFINITE) {
        return Ok(false);
    }
    let Some(new) = fill_boundary(mesh, &boundary, &inner) else {
        return Ok(false);
    };
    if mesh.try_replace(&region, &new)?.is_none() {
        return Ok(false);
    }
    mesh.forget(s);
    Ok(true)
}

/// The tetrahedra filling the closed surface `boundary` (facets of `mesh`) with no added
/// point, the vertices `inner` (inside it) among theirs ([`super::fill_without_points`]),
/// every one positive; `None` if there are none.
fn fill_boundary(
    mesh: &mut TetMesh,
    boundary: &[[u32; 3]],
    inner: &[u32],
) -> Option<Vec<[u32; 4]>> {
    let key = fill_key(mesh, boundary, inner);
    if mesh.failed_fills.contains(&key) {
        return None;
    }
    let filled = fill_boundary_anew(mesh, boundary, inner);
    if filled.is_none() {
        mesh.failed_fills.insert(key, ());
    }
    filled
}

/// The surfaces [`fill_boundary`] could not fill: its result depends on nothing but the
/// boundary's triangles, in order, the inner vertices and the positions of all, which the
/// key holds (points move between the removals), so a failure is not searched again.
/// Refilling the stars grown by layers meets the same boundaries again and again: on anchor,
/// 959 of the 1749 fillings were failures made before, 1.58 s of its 5.3 s. At most 4096
/// keys (one takes 12 words per triangle).
pub type FailedFills = Memo<Vec<u64>, (), 4096>;

/// The key of `boundary` with `inner` in [`FailedFills`]: the triangles' vertices in order,
/// then (after [`INFINITE`](crate::triangulation::tets::INFINITE)) the inner ones, each
/// followed by its coordinates' bits.
fn fill_key(mesh: &TetMesh, boundary: &[[u32; 3]], inner: &[u32]) -> Vec<u64> {
    let mut vertices: Vec<u32> = boundary.iter().flatten().copied().collect();
    if !inner.is_empty() {
        vertices.push(crate::triangulation::tets::INFINITE);
        vertices.extend(inner);
    }
    let mut k = Vec::with_capacity(vertices.len() * 4);
    for v in vertices {
        k.push(u64::from(v));
        if v != crate::triangulation::tets::INFINITE {
            k.extend(mesh.point(v).map(f64::to_bits));
        }
    }
    k
}

/// [`fill_boundary`] searched.
fn fill_boundary_anew(
    mesh: &TetMesh,
    boundary: &[[u32; 3]],
    inner: &[u32],
) -> Option<Vec<[u32; 4]>> {
    // The boundary's vertices, numbered from 0 in order of appearance.
    let mut ids: Vec<u32> = Vec::new();
    let mut number: HashMap<u32, u32> = HashMap::default();
    let local: Vec<[u32; 3]> = boundary
        .iter()
        .map(|f| {
            f.map(|v| {
                *number.entry(v).or_insert_with(|| {
                    ids.push(v);
                    ids.len() as u32 - 1
                })
            })
        })
        .collect();
    if number.contains_key(&crate::triangulation::tets::INFINITE) {
        return None;
    }
    let first_inner = ids.len() as u32;
    ids.extend(inner);
    let local_inner: Vec<u32> = (first_inner..ids.len() as u32).collect();
    let points: Vec<Point> = ids.iter().map(|&v| *mesh.point(v)).collect();
    let filled = super::fill_without_points(&points, &local, &local_inner, mesh.edge_order)?;
    let new: Vec<[u32; 4]> = filled.iter().map(|q| q.map(|v| ids[v as usize])).collect();
    // The filling's boundary is `boundary`, and its tetrahedra are positive.
    let mut faces: HashMap<Key, usize> = HashMap::default();
    for q in &new {
        for f in FACE {
            *faces.entry(key(f.map(|k| q[k]))).or_insert(0) += 1;
        }
    }
    let mut outline: Vec<Key> = faces
        .into_iter()
        .filter(|&(_, n)| n == 1)
        .map(|(f, _)| f)
        .collect();
    outline.sort_unstable();
    let mut expected: Vec<Key> = boundary.iter().map(|&f| key(f)).collect();
    expected.sort_unstable();
    (outline == expected && new.iter().all(|&q| mesh.positive(q))).then_some(new)
}

/// Collapses `s` onto the nearest vertex of its star that allows it; `false` if none does or
/// `s` is a vertex of an input triangle.
fn collapse(mesh: &mut TetMesh, protected: &Protected, s: u32) -> Result<bool> {
    let ball = mesh.ball(s);
    if on_surface(mesh, protected, &ball, s) {
        return Ok(false);
    }
    let mut link = link(mesh, &ball, s);
    nearest_first(mesh, s, &mut link);
    for q in link {
        if merge_into(mesh, &ball, s, q)? {
            return Ok(true);
        }
    }
    Ok(false)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::tet_volume;

    /// Schönhardt's prism (the top turned by 30 degrees): its boundary has no filling
    /// without a point.
    fn schonhardt() -> (Vec<Point>, Vec<[u32; 3]>) {
        let mut points = Vec::new();
        for (z, turn) in [(0.0, 0.0), (1.0, 30f64.to_radians())] {
            for k in 0..3 {
                let a = turn + f64::from(k) * std::f64::consts::TAU / 3.0;
                points.push([a.cos(), a.sin(), z]);
            }
        }
        let mut boundary = vec![[0, 2, 1], [3, 4, 5]];
        for k in 0..3 {
            let (b0, b1, t0, t1) = (k, (k + 1) % 3, k + 3, (k + 1) % 3 + 3);
            boundary.extend([[b0, b1, t1], [b0, t1, t0]]);
        }
        (points, boundary)
    }

    #[test]
    fn a_failed_filling_is_remembered_with_its_positions() {
        let (points, boundary) = schonhardt();
        let mut mesh = TetMesh::delaunay(points, &(0..6).collect::<Vec<u32>>()).unwrap();
        let key = fill_key(&mesh, &boundary, &[]);
        assert!(fill_boundary(&mut mesh, &boundary, &[]).is_none());
        assert!(mesh.failed_fills.contains(&key));
        assert!(fill_boundary(&mut mesh, &boundary, &[]).is_none());
        // Turned the other way, the prism is convex and fills without a point: moved
        // vertices make another key.
        for k in 0..3 {
            let a = (f64::from(k) * 120.0 - 30.0).to_radians();
            mesh.move_point(3 + k, [a.cos(), a.sin(), 1.0]);
        }
        assert!(!mesh.failed_fills.contains(&fill_key(&mesh, &boundary, &[])));
        assert!(fill_boundary(&mut mesh, &boundary, &[]).is_some());
    }

    #[test]
    fn a_point_kept_inside_lets_a_boundary_without_a_filling_fill() {
        let (mut points, boundary) = schonhardt();
        points.push([0.0, 0.0, 0.5]);
        let mut mesh = TetMesh::delaunay(points, &(0..7).collect::<Vec<u32>>()).unwrap();
        assert!(fill_boundary(&mut mesh, &boundary, &[]).is_none());
        let filled = fill_boundary(&mut mesh, &boundary, &[6]).expect("a filling");
        assert!(filled.iter().any(|q| q.contains(&6)));
        assert!(filled.iter().all(|&q| mesh.positive(q)));
        // The same boundary without the inner point is still remembered as failed.
        assert!(mesh.failed_fills.contains(&fill_key(&mesh, &boundary, &[])));
        assert!(!mesh
            .failed_fills
            .contains(&fill_key(&mesh, &boundary, &[6])));
    }

    #[test]
    fn two_neighbouring_points_inside_merge_into_one() {
        // Two points near the center of the unit cube, a Delaunay edge apart.
        let mut points: Vec<Point> = (0..8)
            .map(|c| [0, 1, 2].map(|k| f64::from(c >> k & 1)))
            .collect();
        points.extend([[0.45, 0.52, 0.48], [0.56, 0.47, 0.51]]);
        let mut mesh = TetMesh::delaunay(points, &(0..10).collect::<Vec<u32>>()).unwrap();
        let protected = Protected::default();
        assert!(mesh
            .ball(8)
            .iter()
            .any(|&t| mesh.tets.vertices(t).contains(&9)));
        let volume = |mesh: &TetMesh| -> f64 {
            let tets = mesh.tets.live().map(|t| mesh.tets.vertices(t));
            tets.filter(|q| !q.contains(&crate::triangulation::tets::INFINITE))
                .map(|q| tet_volume(q.map(|v| mesh.point(v))).abs())
                .sum()
        };
        assert!(merge_pair(&mut mesh, &protected, 8, &[8, 9]).unwrap());
        assert!(!mesh.in_mesh(8) && mesh.in_mesh(9));
        mesh.validate().unwrap();
        assert!(mesh
            .ball(9)
            .iter()
            .all(|&t| mesh.positive(mesh.tets.vertices(t))));
        assert!((volume(&mesh) - 1.0).abs() < 1e-12);
        // Alone, the point left has nothing to merge with.
        assert!(!merge_pair(&mut mesh, &protected, 9, &[8, 9]).unwrap());
    }

    #[test]
    fn a_point_a_rounding_off_a_face_of_its_star_is_moved_deep_into_the_kernel() {
        // The center of the unit cube, coned to its faces, then put a rounding above the
        // bottom face: the bottom's two tetrahedra are nearly flat but positive.
        let mut points: Vec<Point> = (0..8)
            .map(|c| [0, 1, 2].map(|k| f64::from(c >> k & 1)))
            .collect();
        points.push([0.5, 0.5, 0.5]);
        let mut mesh = TetMesh::delaunay(points, &(0..9).collect::<Vec<u32>>()).unwrap();
        let ball = mesh.ball(8);
        let star: Vec<[u32; 4]> = ball.iter().map(|&t| mesh.tets.vertices(t)).collect();
        mesh.move_point(8, [0.4, 0.55, 1e-15]);
        assert!(star.iter().all(|&q| mesh.positive(q)));
        let deepest = deepest_in_kernel(&mesh, &star, 8);
        // The kernel is the cube: the distance to its nearest face is at most 0.5.
        let depth = deepest
            .iter()
            .map(|&x| x.min(1.0 - x))
            .fold(f64::INFINITY, f64::min);
        assert!(depth > 0.25, "{deepest:?}");
        mesh.move_point(8, deepest);
        assert!(star.iter().all(|&q| mesh.positive(q)));
    }
}
