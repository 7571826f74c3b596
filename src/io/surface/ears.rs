//! Ear clipping of a projected polygon with holes, every decision exact ([`orient2d`]).
//!
//! The outer polygon is made counter-clockwise and its holes clockwise, so that the region
//! is on the left of every edge. Holes are bridged to the outer polygon one by one, the one
//! reaching farthest in `+x` first: the bridge joins the hole's rightmost corner to the
//! nearest corner of the outer polygon that sees it (the open segment meets no edge and no
//! corner, and it leaves both corners on the region's side). Bridging duplicates the two
//! corners and leaves a single weakly simple polygon.
//!
//! An ear is a strictly convex corner whose triangle with its two neighbours holds no other
//! corner, except copies of its own corners. Among the ears, the one with the largest
//! smallest angle (measured in 3D) is clipped, the first one on ties, so that facets get no
//! avoidable slivers. A corner between two collinear edges is never an ear tip, so
//! polygons with collinear corners get no zero-area triangle.

use std::cmp::Ordering;

use super::polygon::{project, within_box};
use crate::predicates::{orient2d, Point, Sign};

/// Appends to `triangles` the triangles of the face bounded by the polygon `outer` and the
/// polygons `inner` inside it (indices into `points`), projected along `axis`. The triangles
/// have the orientation of `outer`; none has corners that `flat` accepts.
pub(super) fn triangulate(
    points: &[Point],
    axis: usize,
    (outer, inner): (&[u32], &[Vec<u32>]),
    flat: &dyn Fn([u32; 3]) -> bool,
    triangles: &mut Vec<u32>,
) -> Result<(), String> {
    let mut ring = Ring::default();
    let flip = match orientation(&ring.projected(points, axis, outer)) {
        Sign::Positive => false,
        Sign::Negative => true,
        Sign::Zero => return Err(NO_AREA.to_string()),
    };
    let start = ring.add_loop(points, axis, outer, flip);
    let mut holes = Vec::with_capacity(inner.len());
    for (k, hole) in inner.iter().enumerate() {
        let reverse = match orientation(&ring.projected(points, axis, hole)) {
            Sign::Positive => true,
            Sign::Negative => false,
            Sign::Zero => return Err(format!("inner polygon {}: {NO_AREA}", k + 1)),
        };
        holes.push(ring.add_loop(points, axis, hole, reverse));
    }
    ring.bridge_holes(start, &holes)?;
    ring.clip_ears(points, flat, |[a, b, c]| {
        triangles.extend(if flip { [a, c, b] } else { [a, b, c] })
    })
}

const NO_AREA: &str = "the polygon has no area in its plane";

/// Lexicographic order of projected points (finite coordinates).
fn lex(a: &[f64; 2], b: &[f64; 2]) -> Ordering {
    let axis = |k: usize| a[k].partial_cmp(&b[k]).unwrap_or(Ordering::Equal);
    axis(0).then_with(|| axis(1))
}

/// The orientation of a polygon without repeated consecutive corners: the turn at its
/// lexicographically smallest corner, an extreme corner.
fn orientation(ring: &[[f64; 2]]) -> Sign {
    let n = ring.len();
    let k = (1..n).fold(0, |m, k| {
        if lex(&ring[k], &ring[m]).is_lt() {
            k
        } else {
            m
        }
    });
    orient2d(&ring[(k + n - 1) % n], &ring[k], &ring[(k + 1) % n])
}

/// The sine of the smallest angle of the triangle `a, b, c`, 0 when it cannot be computed.
fn min_angle_sine(a: &Point, b: &Point, c: &Point) -> f64 {
    let d = |p: &Point, q: &Point| [q[0] - p[0], q[1] - p[1], q[2] - p[2]];
    let (u, v, w) = (d(a, b), d(b, c), d(c, a));
    let cross = [
        u[1] * w[2] - u[2] * w[1],
        u[2] * w[0] - u[0] * w[2],
        u[0] * w[1] - u[1] * w[0],
    ];
    let length2 = |e: &[f64; 3]| e[0] * e[0] + e[1] * e[1] + e[2] * e[2];
    let mut sides = [length2(&u), length2(&v), length2(&w)];
    sides.sort_by(f64::total_cmp);
    // The smallest angle is opposite the shortest side, between the two longer ones.
    let sine = length2(&cross).sqrt() / (sides[1] * sides[2]).sqrt();
    if sine.is_finite() {
        sine
    } else {
        0.0
    }
}

/// Polygon corners (nodes) linked in rings: the outer polygon and its holes, one ring once
/// the holes are bridged. A vertex has two nodes at each end of a bridge.
#[derive(Default)]
struct Ring {
    vertex: Vec<u32>,
    xy: Vec<[f64; 2]>,
    next: Vec<usize>,
    prev: Vec<usize>,
}

impl Ring {
    /// The corners `corners` projected along `axis`.
    fn projected(&self, points: &[Point], axis: usize, corners: &[u32]) -> Vec<[f64; 2]> {
        corners
            .iter()
            .map(|&v| project(&points[v as usize], axis))
            .collect()
    }

    /// Adds a ring of the corners `corners` (reversed if `reverse`); returns its first node.
    fn add_loop(&mut self, points: &[Point], axis: usize, corners: &[u32], reverse: bool) -> usize {
        let first = self.vertex.len();
        let n = corners.len();
        for k in 0..n {
            let v = corners[if reverse { n - 1 - k } else { k }];
            self.vertex.push(v);
            self.xy.push(project(&points[v as usize], axis));
            self.next.push(first + (k + 1) % n);
            self.prev.push(first + (k + n - 1) % n);
        }
        first
    }

    /// The nodes of the ring of `start`, in order.
    fn nodes(&self, start: usize) -> Vec<usize> {
        let mut nodes = vec![start];
        let mut v = self.next[start];
        while v != start {
            nodes.push(v);
            v = self.next[v];
        }
        nodes
    }

    /// Bridges the holes (rings of the nodes `holes`) to the ring of `start`, rightmost first.
    fn bridge_holes(&mut self, start: usize, holes: &[usize]) -> Result<(), String> {
        let mut rightmost: Vec<usize> = holes
            .iter()
            .map(|&h| {
                self.nodes(h)
                    .into_iter()
                    .reduce(|m, v| {
                        if lex(&self.xy[v], &self.xy[m]).is_gt() {
                            v
                        } else {
                            m
                        }
                    })
                    .unwrap_or(h)
            })
            .collect();
        rightmost.sort_by(|&a, &b| lex(&self.xy[b], &self.xy[a]));
        for m in rightmost {
            let v = self.visible_node(start, m).ok_or(
                "an inner polygon cannot be joined to the polygon around it (they touch or cross)",
            )?;
            self.splice(v, m);
        }
        Ok(())
    }

    /// The node of the ring of `start` nearest to node `m` that sees it (the first on ties).
    fn visible_node(&self, start: usize, m: usize) -> Option<usize> {
        let distance2 = |v: usize| {
            let (a, b) = (self.xy[v], self.xy[m]);
            (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1])
        };
        let mut candidates: Vec<(f64, usize)> = self
            .nodes(start)
            .into_iter()
            .map(|v| (distance2(v), v))
            .collect();
        candidates.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        candidates
            .into_iter()
            .map(|(_, v)| v)
            .find(|&v| self.sees(v, m))
    }

    /// True when the segment between nodes `v` and `m` can be a bridge: distinct ends, inside
    /// the region near both, and no corner or edge on it (except at nodes at its ends).
    fn sees(&self, v: usize, m: usize) -> bool {
        let (a, b) = (self.xy[v], self.xy[m]);
        if a == b || !self.in_wedge(v, &b) || !self.in_wedge(m, &a) {
            return false;
        }
        let at_end = |p: &[f64; 2]| *p == a || *p == b;
        (0..self.xy.len()).all(|i| {
            let (p, q) = (&self.xy[i], &self.xy[self.next[i]]);
            if at_end(p) {
                // The edge meets the segment at its end only, or has its other end on it
                // (found when that node is checked).
                return true;
            }
            if orient2d(&a, &b, p) == Sign::Zero && within_box(&a, &b, p) {
                return false;
            }
            at_end(q) || !crosses(&a, &b, p, q)
        })
    }

    /// True when `q` is strictly inside the region near node `v` (left of its edges).
    fn in_wedge(&self, v: usize, q: &[f64; 2]) -> bool {
        let (p, o, n) = (&self.xy[self.prev[v]], &self.xy[v], &self.xy[self.next[v]]);
        let left_of_in = orient2d(p, o, q) == Sign::Positive;
        let left_of_out = orient2d(o, n, q) == Sign::Positive;
        if orient2d(p, o, n) == Sign::Positive {
            left_of_in && left_of_out
        } else {
            left_of_in || left_of_out
        }
    }

    /// Joins the hole ring of node `m` to the ring of node `v`: `v, m, ..., m', v'`, where
    /// `m'` and `v'` are new nodes of the same vertices.
    fn splice(&mut self, v: usize, m: usize) {
        let (v_next, m_prev) = (self.next[v], self.prev[m]);
        let (m2, v2) = (self.vertex.len(), self.vertex.len() + 1);
        for node in [m, v] {
            self.vertex.push(self.vertex[node]);
            self.xy.push(self.xy[node]);
        }
        self.next.extend([v2, v_next]);
        self.prev.extend([m_prev, m2]);
        self.next[v] = m;
        self.prev[m] = v;
        self.next[m_prev] = m2;
        self.prev[v_next] = v2;
    }

    /// The sine of the smallest angle of the ear at node `v`, or `None` when `v` is not an
    /// ear among the `alive` nodes.
    fn ear(
        &self,
        v: usize,
        alive: &[bool],
        points: &[Point],
        flat: &dyn Fn([u32; 3]) -> bool,
    ) -> Option<f64> {
        let (p, n) = (self.prev[v], self.next[v]);
        let (a, b, c) = (&self.xy[p], &self.xy[v], &self.xy[n]);
        let corners = [p, v, n].map(|k| self.vertex[k]);
        if orient2d(a, b, c) != Sign::Positive || flat(corners) {
            return None;
        }
        let low = [a[0].min(b[0]).min(c[0]), a[1].min(b[1]).min(c[1])];
        let high = [a[0].max(b[0]).max(c[0]), a[1].max(b[1]).max(c[1])];
        // A corner on the line of the new side, as the caller sees it.
        let on_side = |w: u32| !corners.contains(&w) && flat([corners[0], w, corners[2]]);
        let blocked = (0..self.xy.len()).any(|r| {
            let q = &self.xy[r];
            alive[r]
                && (within_box(&low, &high, q)
                    && q != a
                    && q != b
                    && q != c
                    && orient2d(a, b, q) != Sign::Negative
                    && orient2d(b, c, q) != Sign::Negative
                    && orient2d(c, a, q) != Sign::Negative
                    || on_side(self.vertex[r]))
        });
        let corner = |node: usize| &points[self.vertex[node] as usize];
        (!blocked).then(|| min_angle_sine(corner(p), corner(v), corner(n)))
    }

    /// Clips ears until one triangle is left, giving each triangle (counter-clockwise in
    /// the projection) to `emit`.
    fn clip_ears(
        &mut self,
        points: &[Point],
        flat: &dyn Fn([u32; 3]) -> bool,
        mut emit: impl FnMut([u32; 3]),
    ) -> Result<(), String> {
        let n = self.xy.len();
        let mut alive = vec![true; n];
        let mut quality: Vec<Option<f64>> =
            (0..n).map(|v| self.ear(v, &alive, points, flat)).collect();
        for _ in 3..n {
            // Clipping can make ears elsewhere than at its neighbours: look again before
            // giving up.
            let best = match best_ear(&quality) {
                Some(v) => v,
                None => {
                    for v in (0..n).filter(|&v| alive[v]) {
                        quality[v] = self.ear(v, &alive, points, flat);
                    }
                    best_ear(&quality).ok_or(
                        "no ear to clip: the polygon crosses itself, or is not planar enough",
                    )?
                }
            };
            let (p, q) = (self.prev[best], self.next[best]);
            emit([self.vertex[p], self.vertex[best], self.vertex[q]]);
            alive[best] = false;
            quality[best] = None;
            self.next[p] = q;
            self.prev[q] = p;
            quality[p] = self.ear(p, &alive, points, flat);
            quality[q] = self.ear(q, &alive, points, flat);
        }
        let v = (0..n).find(|&v| alive[v]).ok_or(NO_AREA)?;
        let (p, q) = (self.prev[v], self.next[v]);
        if orient2d(&self.xy[p], &self.xy[v], &self.xy[q]) != Sign::Positive {
            return Err("the polygon's last triangle has no area: it crosses itself".to_string());
        }
        if flat([p, v, q].map(|k| self.vertex[k])) {
            return Err("the polygon's last triangle is flat".to_string());
        }
        emit([self.vertex[p], self.vertex[v], self.vertex[q]]);
        Ok(())
    }
}

/// True when the segments `a b` and `p q` meet, where `p` and `q` are not on `a b` unless
/// they are its ends: they cross, or `a` or `b` is on `p q`.
fn crosses(a: &[f64; 2], b: &[f64; 2], p: &[f64; 2], q: &[f64; 2]) -> bool {
    let (o1, o2) = (orient2d(a, b, p), orient2d(a, b, q));
    let (o3, o4) = (orient2d(p, q, a), orient2d(p, q, b));
    (o1 * o2 == Sign::Negative && o3 * o4 == Sign::Negative)
        || (o3 == Sign::Zero && within_box(p, q, a))
        || (o4 == Sign::Zero && within_box(p, q, b))
}

/// The node with the best ear (the first on ties), if any.
fn best_ear(quality: &[Option<f64>]) -> Option<usize> {
    let mut best: Option<(usize, f64)> = None;
    for (v, q) in quality.iter().enumerate() {
        if let Some(q) = *q {
            if best.is_none_or(|(_, b)| q > b) {
                best = Some((v, q));
            }
        }
    }
    best.map(|(v, _)| v)
}
