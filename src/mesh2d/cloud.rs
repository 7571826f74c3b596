//! The growing point set `S` of the subdivision, with a bucket grid (Pébay §3.3: "un tri par
//! boîtes") answering "which points lie in this disk" without scanning them all.
//!
//! Invariants: `points[i]` is stored in exactly one bucket, the one of its clamped cell (but
//! the points added by [`Cloud::push_unindexed`], stored in none); the
//! grid covers the bounding box of the input points (points added later lie on input segments,
//! hence in that box up to rounding, and clamping keeps them findable: a query box is clamped
//! the same way). Queries return candidates whose cells meet the box; exact predicates decide.

use super::exact::{dot_sign, in_circumcircle};
use crate::predicates::Sign;

/// Points and their bucket grid.
pub struct Cloud {
    pub points: Vec<[f64; 2]>,
    lo: [f64; 2],
    hi: [f64; 2],
    /// Points in the buckets.
    indexed: usize,
    /// Cells per unit length.
    scale: f64,
    nx: usize,
    ny: usize,
    /// The buckets as lists threaded through the points: the last point added to each cell,
    /// and for each point the one added to its cell before it (NONE ends a list; unindexed
    /// points are in no list).
    head: Vec<u32>,
    next: Vec<u32>,
}

/// End of a bucket list.
const NONE: u32 = u32::MAX;

/// `next` of a point in no bucket.
const UNINDEXED: u32 = u32::MAX - 1;

impl Cloud {
    /// A grid of about `cells` buckets over the box `[lo, hi]`, holding no point yet. The grid
    /// is refined as points come (see [`Cloud::push`]).
    pub fn new(lo: [f64; 2], hi: [f64; 2], cells: usize) -> Self {
        let mut cloud = Cloud {
            points: Vec::new(),
            lo,
            hi,
            indexed: 0,
            scale: 0.0,
            nx: 1,
            ny: 1,
            head: Vec::new(),
            next: Vec::new(),
        };
        cloud.grid(cells);
        cloud
    }

    /// Lays a grid of about `cells` buckets over the box and files the indexed points in it,
    /// in index order.
    fn grid(&mut self, cells: usize) {
        let (lo, hi) = (self.lo, self.hi);
        let (w, h) = (hi[0] - lo[0], hi[1] - lo[1]);
        let area = (w * h).max(f64::MIN_POSITIVE);
        let side = (area / cells.max(1) as f64).sqrt();
        let side = if side > 0.0 && side.is_finite() {
            side
        } else {
            1.0
        };
        let scale = 1.0 / side;
        let count = |len: f64| ((len * scale).floor() as usize).clamp(1, 1 << 12);
        let (nx, ny) = (count(w) + 1, count(h) + 1);
        self.scale = if w.max(h) > 0.0 { scale } else { 0.0 };
        (self.nx, self.ny) = (nx, ny);
        self.head = vec![NONE; nx * ny];
        for i in 0..self.points.len() {
            if self.next[i] != UNINDEXED {
                let (cx, cy) = self.cell(&self.points[i]);
                let cell = &mut self.head[cy * self.nx + cx];
                self.next[i] = *cell;
                *cell = i as u32;
            }
        }
    }

    /// The box the grid covers.
    pub fn bounds(&self) -> ([f64; 2], [f64; 2]) {
        (self.lo, self.hi)
    }

    /// The points, the grid dropped.
    pub fn into_points(self) -> Vec<[f64; 2]> {
        self.points
    }

    /// Adds a point; returns its index. When the points outnumber the buckets twice, the grid
    /// is laid again with twice as many buckets as points (up to 2^12 per side): the points
    /// the subdivision adds crowd near small features, and a fixed grid would make every query
    /// scan them.
    pub fn push(&mut self, p: [f64; 2]) -> u32 {
        self.indexed += 1;
        if self.indexed > 2 * self.cell_count() && self.nx.max(self.ny) < 1 << 12 {
            self.grid(2 * self.indexed);
        }
        let i = self.points.len() as u32;
        let (cx, cy) = self.cell(&p);
        let cell = &mut self.head[cy * self.nx + cx];
        self.next.push(*cell);
        *cell = i;
        self.points.push(p);
        i
    }

    /// Removes the last point added by [`Cloud::push`] (the last entry of its bucket).
    pub fn pop(&mut self) {
        if let (Some(p), Some(before)) = (self.points.pop(), self.next.pop()) {
            self.indexed -= 1;
            let (cx, cy) = self.cell(&p);
            let cell = &mut self.head[cy * self.nx + cx];
            if *cell == self.points.len() as u32 {
                *cell = before;
            }
        }
    }

    /// Adds a point that queries never return (an input copy of an earlier point).
    pub fn push_unindexed(&mut self, p: [f64; 2]) -> u32 {
        self.next.push(UNINDEXED);
        self.points.push(p);
        (self.points.len() - 1) as u32
    }

    /// The grid cells that meet the box `[lo, hi]`: `[x0, y0, x1, y1]`, the cells `(x, y)` with
    /// `x0 <= x <= x1` and `y0 <= y <= y1`, numbered `y * columns + x` (see [`Cloud::columns`]).
    pub fn cells_of_box(&self, lo: [f64; 2], hi: [f64; 2]) -> [usize; 4] {
        let (x0, y0) = self.cell(&lo);
        let (x1, y1) = self.cell(&hi);
        [x0, y0, x1, y1]
    }

    /// Columns of the grid; `columns * rows` cells.
    pub fn columns(&self) -> usize {
        self.nx
    }

    /// Cells of the grid.
    pub fn cell_count(&self) -> usize {
        self.nx * self.ny
    }

    fn cell(&self, p: &[f64; 2]) -> (usize, usize) {
        (
            clamped_cell(p[0], self.lo[0], self.scale, self.nx),
            clamped_cell(p[1], self.lo[1], self.scale, self.ny),
        )
    }

    /// Calls `f` with every point whose bucket meets the box `[lo, hi]` (a superset of the
    /// points in the box), in no particular order.
    pub fn candidates(&self, lo: [f64; 2], hi: [f64; 2], mut f: impl FnMut(u32)) {
        let (x0, y0) = self.cell(&lo);
        let (x1, y1) = self.cell(&hi);
        for cy in y0..=y1 {
            for cx in x0..=x1 {
                self.bucket(cx, cy).for_each(&mut f);
            }
        }
    }

    /// The points in the bucket of cell `(x, y)`, last added first.
    fn bucket(&self, x: usize, y: usize) -> impl Iterator<Item = u32> + '_ {
        let first = self.head[y * self.nx + x];
        std::iter::successors((first != NONE).then_some(first), |&i| {
            let n = self.next[i as usize];
            (n != NONE).then_some(n)
        })
    }

    /// The points other than `a` and `b` in the closed small disk of `[a b]` (the disk with
    /// diameter `[a b]`), decided exactly, in increasing index order.
    pub fn in_small_disk(&self, a: u32, b: u32) -> Vec<u32> {
        let (pa, pb) = (self.points[a as usize], self.points[b as usize]);
        let (lo, hi) = widened_box(&pa, &pb);
        let mut found = Vec::new();
        self.candidates(lo, hi, |i| {
            if i != a && i != b && dot_sign(&pa, &pb, &self.points[i as usize]) != Sign::Positive {
                found.push(i);
            }
        });
        found.sort_unstable();
        found
    }

    /// Where the points other than `a`, `b`, `c` lie with respect to the circumcircle of the
    /// non-collinear `a, b, c`, decided exactly: [`Circumdisk::Inside`] as soon as one lies
    /// strictly inside, else the points on the circle in increasing index order. The cells
    /// are visited in rings around the midpoint of `a b`, where a point inside is likeliest:
    /// the circumdisk of a flat triangle covers most of the grid, and a scan in row order
    /// would often meet its first inside point last.
    pub fn circumdisk(&self, a: u32, b: u32, c: u32) -> Circumdisk {
        let [pa, pb, pc] = [a, b, c].map(|i| self.points[i as usize]);
        let (lo, hi) =
            circumdisk_box(&pa, &pb, &pc).unwrap_or(([f64::NEG_INFINITY; 2], [f64::INFINITY; 2]));
        let (x0, y0) = self.cell(&lo);
        let (x1, y1) = self.cell(&hi);
        let (mx, my) = self.cell(&[(pa[0] + pb[0]) * 0.5, (pa[1] + pb[1]) * 0.5]);
        let (cx, cy) = (mx.clamp(x0, x1), my.clamp(y0, y1));
        let reach = (cx - x0).max(x1 - cx).max(cy - y0).max(y1 - cy);
        let mut on_circle = Vec::new();
        for r in 0..=reach {
            for (x, y) in ring(cx, cy, r) {
                if x < x0 || x > x1 || y < y0 || y > y1 {
                    continue;
                }
                for i in self.bucket(x, y).filter(|&i| i != a && i != b && i != c) {
                    match in_circumcircle(&pa, &pb, &pc, &self.points[i as usize]) {
                        Sign::Positive => return Circumdisk::Inside,
                        Sign::Zero => on_circle.push(i),
                        Sign::Negative => {}
                    }
                }
            }
        }
        on_circle.sort_unstable();
        Circumdisk::OnCircle(on_circle)
    }
}

/// What [`Cloud::circumdisk`] finds.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Circumdisk {
    /// Some point lies strictly inside the circle.
    Inside,
    /// No point lies inside; these lie on the circle.
    OnCircle(Vec<u32>),
}

/// The cells at distance `r` (in the maximum norm) from cell `(cx, cy)`, those with negative
/// coordinates left out.
fn ring(cx: usize, cy: usize, r: usize) -> impl Iterator<Item = (usize, usize)> {
    let (cx, cy, r) = (cx as isize, cy as isize, r as isize);
    let rows = (-r..=r).flat_map(move |dx| {
        let top = (cx + dx, cy - r);
        let bottom = (cx + dx, cy + r);
        std::iter::once(top).chain((r > 0).then_some(bottom))
    });
    let sides = (1 - r..r).flat_map(move |dy| [(cx - r, cy + dy), (cx + r, cy + dy)]);
    rows.chain(sides)
        .filter(|&(x, y)| x >= 0 && y >= 0)
        .map(|(x, y)| (x as usize, y as usize))
}

/// The cell, among `n` of `1 / scale` from `lo`, of coordinate `x`; coordinates beyond the
/// grid go to its first or last cell.
pub fn clamped_cell(x: f64, lo: f64, scale: f64, n: usize) -> usize {
    let c = (x - lo) * scale;
    // Truncation is the floor on nonnegative numbers; NaN and negatives go to 0.
    if c >= 0.0 {
        (c as usize).min(n - 1)
    } else {
        0
    }
}

/// A box holding the small disk of `[a b]` (the disk with diameter `[a b]`), widened by a
/// relative margin that covers the rounding of the box itself.
pub fn widened_box(a: &[f64; 2], b: &[f64; 2]) -> ([f64; 2], [f64; 2]) {
    let c = [(a[0] + b[0]) * 0.5, (a[1] + b[1]) * 0.5];
    let r = ((a[0] - b[0]).hypot(a[1] - b[1]) * 0.5) * (1.0 + 1e-9) + 1e-300;
    let pad = |x: f64| x.abs() * 4.0 * f64::EPSILON;
    (
        [c[0] - r - pad(c[0]), c[1] - r - pad(c[1])],
        [c[0] + r + pad(c[0]), c[1] + r + pad(c[1])],
    )
}

/// A box holding the circumdisk of `a, b, c`, or `None` when the disk is too large or too
/// ill-conditioned to bound reliably in floating point (then every point is a candidate).
fn circumdisk_box(a: &[f64; 2], b: &[f64; 2], c: &[f64; 2]) -> Option<([f64; 2], [f64; 2])> {
    let (bx, by) = (b[0] - a[0], b[1] - a[1]);
    let (cx, cy) = (c[0] - a[0], c[1] - a[1]);
    let d = 2.0 * (bx * cy - by * cx);
    let (b2, c2) = (bx * bx + by * by, cx * cx + cy * cy);
    let ux = (cy * b2 - by * c2) / d;
    let uy = (bx * c2 - cx * b2) / d;
    let r = ux.hypot(uy);
    let longest = b2
        .max(c2)
        .max((c[0] - b[0]).powi(2) + (c[1] - b[1]).powi(2))
        .sqrt();
    // The computed centre is off by about eps * r^2 / longest; past r = 1e3 * longest, give up.
    if !r.is_finite() || r > 1e3 * longest {
        return None;
    }
    let centre = [a[0] + ux, a[1] + uy];
    let margin = r * 1e-6 + (centre[0].abs() + centre[1].abs()) * 8.0 * f64::EPSILON;
    let r = r + margin;
    Some((
        [centre[0] - r, centre[1] - r],
        [centre[0] + r, centre[1] + r],
    ))
}
