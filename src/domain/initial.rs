//! Initial surface points (thesis §3.3.1: the refinement starts from a sample that meets
//! every connected component of the surface; the thesis and CGAL shoot rays for it).
//!
//! Rays are shot along the lines of a regular grid over the box, in the three axis
//! directions: every grid edge whose end labels differ is bisected to a surface point. The
//! grid nodes on the box's faces must be outside (label 0): that is the domain's contract,
//! checked here. Crossings are grouped into components (crossing edges of one grid cell are
//! connected) and each component contributes points spaced about `diagonal / 16` apart, at
//! least [`MIN_PER_COMPONENT`] when it has that many, so that a small component still has
//! restricted facets. The user's seed points are added as they are.

use super::{crossing, Domain};
use crate::error::{Error, Result};
use crate::geometry::dist2;
use crate::predicates::Point;
use crate::union_find::UnionFind;

/// Grid cells per axis.
const GRID: usize = 24;

/// Fewest points taken on a component (when it has that many crossings): a tetrahedron's
/// worth plus margin, so that its restricted Delaunay triangulation is not empty.
const MIN_PER_COMPONENT: usize = 6;

/// Points on every component of the surface the grid meets, plus the user's seeds.
/// Errors: the domain is inside somewhere on the box's faces (`InvalidInput`); no surface
/// was found and no seed given (`InvalidInput`); a callback failed.
pub fn initial_points(domain: &dyn Domain) -> Result<Vec<Point>> {
    let grid = Grid::scan(domain)?;
    let crossings = grid.crossings(domain)?;
    let mut points = select(&crossings, domain.bbox().diagonal() / 16.0);
    points.extend_from_slice(domain.seeds());
    if points.len() < 4 {
        return Err(Error::invalid_input(format!(
            "found {} surface points on a {GRID}^3 grid over the bbox and {} seed points: the \
             domain is empty or too small for the grid; add points on its surface with \
             delmesh_domain_add_surface_points",
            points.len() - domain.seeds().len(),
            domain.seeds().len()
        )));
    }
    Ok(points)
}

/// Labels at the `(GRID + 1)^3` nodes of the grid over the box.
struct Grid {
    labels: Vec<i32>,
    lo: Point,
    step: Point,
}

const NODES: usize = GRID + 1;

impl Grid {
    fn scan(domain: &dyn Domain) -> Result<Grid> {
        let b = domain.bbox();
        let step = std::array::from_fn(|k| (b.hi[k] - b.lo[k]) / GRID as f64);
        let mut g = Grid {
            labels: Vec::with_capacity(NODES * NODES * NODES),
            lo: b.lo,
            step,
        };
        for n in 0..NODES * NODES * NODES {
            let ijk = [n % NODES, (n / NODES) % NODES, n / (NODES * NODES)];
            let p = g.node(ijk, b);
            let label = domain.classify(&p)?;
            if label != 0 && ijk.iter().any(|&i| i == 0 || i == GRID) {
                return Err(Error::invalid_input(format!(
                    "the domain is inside (label {label}) at {p:?}, on the boundary of its \
                     bbox {:?}..{:?}: the bbox must strictly contain the domain",
                    b.lo, b.hi
                )));
            }
            g.labels.push(label);
        }
        Ok(g)
    }

    /// The node's coordinates; the last node of an axis is the box's upper bound exactly.
    fn node(&self, ijk: [usize; 3], b: &super::BBox) -> Point {
        std::array::from_fn(|k| {
            if ijk[k] == GRID {
                b.hi[k]
            } else {
                self.lo[k] + ijk[k] as f64 * self.step[k]
            }
        })
    }

    fn index(ijk: [usize; 3]) -> usize {
        ijk[0] + NODES * (ijk[1] + NODES * ijk[2])
    }

    /// Surface points on the grid edges whose ends have different labels, with the
    /// component (of connected crossing edges) each belongs to.
    fn crossings(&self, domain: &dyn Domain) -> Result<Vec<(usize, Point)>> {
        let b = domain.bbox();
        let edge = |axis: usize, ijk: [usize; 3]| axis * NODES * NODES * NODES + Self::index(ijk);
        let mut found = Vec::new();
        let mut slot = vec![u32::MAX; 3 * NODES * NODES * NODES];
        for n in 0..NODES * NODES * NODES {
            let ijk = [n % NODES, (n / NODES) % NODES, n / (NODES * NODES)];
            for axis in 0..3 {
                if ijk[axis] == GRID {
                    continue;
                }
                let mut next = ijk;
                next[axis] += 1;
                let (la, lb) = (self.labels[n], self.labels[Self::index(next)]);
                if la != lb {
                    let (a, c) = (self.node(ijk, b), self.node(next, b));
                    let x = crossing(domain, &a, la, &c, lb)?;
                    slot[edge(axis, ijk)] = found.len() as u32;
                    found.push(x.point);
                }
            }
        }
        let mut sets = UnionFind::new(found.len());
        for n in 0..GRID * GRID * GRID {
            let c = [n % GRID, (n / GRID) % GRID, n / (GRID * GRID)];
            let mut first = None;
            for (axis, d1, d2) in (0..3).flat_map(|a| (0..4).map(move |d| (a, d & 1, d >> 1))) {
                let mut ijk = c;
                ijk[(axis + 1) % 3] += d1;
                ijk[(axis + 2) % 3] += d2;
                let s = slot[edge(axis, ijk)];
                if s != u32::MAX {
                    match first {
                        None => first = Some(s),
                        Some(f) => {
                            sets.union(f, s);
                        }
                    }
                }
            }
        }
        Ok((0..found.len() as u32)
            .map(|i| (sets.find(i) as usize, found[i as usize]))
            .collect())
    }
}

/// Per component, points greedily kept at least `spacing` apart, the spacing halved until
/// the component has [`MIN_PER_COMPONENT`] points or all of its crossings.
fn select(crossings: &[(usize, Point)], spacing: f64) -> Vec<Point> {
    let mut components: Vec<usize> = crossings.iter().map(|&(c, _)| c).collect();
    components.sort_unstable();
    components.dedup();
    let mut out = Vec::new();
    for c in components {
        let candidates: Vec<Point> = crossings
            .iter()
            .filter(|&&(k, _)| k == c)
            .map(|&(_, p)| p)
            .collect();
        // Halving 60 times reaches spacings below any crossing distance that matters.
        let mut kept = Vec::new();
        for halvings in 0..60 {
            kept = spaced(&candidates, spacing * 0.5f64.powi(halvings));
            if kept.len() >= MIN_PER_COMPONENT.min(candidates.len()) {
                break;
            }
        }
        out.extend(kept);
    }
    out
}

fn spaced(candidates: &[Point], h: f64) -> Vec<Point> {
    let mut kept: Vec<Point> = Vec::new();
    for p in candidates {
        if kept.iter().all(|q| dist2(p, q) >= h * h) {
            kept.push(*p);
        }
    }
    kept
}
