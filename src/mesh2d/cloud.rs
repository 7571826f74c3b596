//! The growing point set `S` of the subdivision, with a bucket grid (Pébay §3.3: "un tri par
//! boîtes") answering "which points lie in this disk" without scanning them all.
//!
//! Invariants: `points[i]` is stored in exactly one bucket, the one of its clamped cell (but
//! the points added by [`Cloud::push_unindexed`], stored in none); the
//! grid covers the bounding box of the input points (points added later lie on input segments,
//! hence in that box up to rounding, and clamping keeps them findable: a query box is clamped
//! the same way). Queries return candidates whose cells meet the box; exact predicates decide.

use super::exact::{dot_sign, in_circumcircle};
use crate::predicates::{orient2d, Sign};

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
    pub fn candidates(&self, lo: [f64; 2], hi: [f64; 2], f: impl FnMut(u32)) {
        self.in_cells_of(lo, hi).for_each(f);
    }

    /// The points whose bucket meets the box `[lo, hi]`, row by row of cells.
    fn in_cells_of(&self, lo: [f64; 2], hi: [f64; 2]) -> BoxPoints<'_> {
        let (x0, y0) = self.cell(&lo);
        let (x1, y1) = self.cell(&hi);
        BoxPoints {
            cloud: self,
            cells: [x0, y0, x1, y1],
            at: (x0, y0),
            point: self.head[y0 * self.nx + x0],
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
    /// diameter `[a b]`), decided exactly, as the grid meets them.
    pub fn small_disk(&self, a: u32, b: u32) -> impl Iterator<Item = u32> + '_ {
        let (pa, pb) = (self.points[a as usize], self.points[b as usize]);
        let (lo, hi) = widened_box(&pa, &pb);
        self.in_cells_of(lo, hi).filter(move |&i| {
            i != a && i != b && dot_sign(&pa, &pb, &self.points[i as usize]) != Sign::Positive
        })
    }

    /// Where the points strictly beyond the line `(a b)`, on the side opposite `c`, lie with
    /// respect to the circumcircle of the non-collinear `a, b, c`, decided exactly: the
    /// greatest [`in_circumcircle`] sign among them (`Positive` as soon as one lies strictly
    /// inside; `Negative` when none is inside or on the circle, or there is none). Only the
    /// cells meeting the part of the circle's box beyond the line are visited, in rings around
    /// the midpoint of `a b`, where a point inside is likeliest: the circumdisk of a flat
    /// triangle covers most of the grid, and a scan in row order would often meet its first
    /// inside point last.
    pub fn circumdisk_beyond(&self, a: u32, b: u32, c: u32) -> Sign {
        let [pa, pb, pc] = [a, b, c].map(|i| self.points[i as usize]);
        let near = orient2d(&pa, &pb, &pc);
        let (lo, hi) = match circumdisk_box(&pa, &pb, &pc) {
            Some(disk) => match beyond_line(disk, &pa, &pb, near) {
                Some(part) => part,
                None => return Sign::Negative,
            },
            None => ([f64::NEG_INFINITY; 2], [f64::INFINITY; 2]),
        };
        let (x0, y0) = self.cell(&lo);
        let (x1, y1) = self.cell(&hi);
        let (mx, my) = self.cell(&[(pa[0] + pb[0]) * 0.5, (pa[1] + pb[1]) * 0.5]);
        let (cx, cy) = (mx.clamp(x0, x1), my.clamp(y0, y1));
        let reach = (cx - x0).max(x1 - cx).max(cy - y0).max(y1 - cy);
        let mut greatest = Sign::Negative;
        for r in 0..=reach {
            for (x, y) in ring((cx, cy), r, [x0, y0, x1, y1]) {
                for i in self.bucket(x, y) {
                    let q = &self.points[i as usize];
                    if orient2d(&pa, &pb, q) * near != Sign::Negative {
                        continue;
                    }
                    match in_circumcircle(&pa, &pb, &pc, q) {
                        Sign::Positive => return Sign::Positive,
                        Sign::Zero => greatest = Sign::Zero,
                        Sign::Negative => {}
                    }
                }
            }
        }
        greatest
    }
}

/// The iterator of [`Cloud::in_cells_of`]: the cells `[x0, y0, x1, y1]` in rows, and in each
/// cell its bucket list.
struct BoxPoints<'a> {
    cloud: &'a Cloud,
    cells: [usize; 4],
    /// The current cell.
    at: (usize, usize),
    /// The next point of the current cell's list (NONE at its end).
    point: u32,
}

impl Iterator for BoxPoints<'_> {
    type Item = u32;

    fn next(&mut self) -> Option<u32> {
        let [x0, _, x1, y1] = self.cells;
        while self.point == NONE {
            let (x, y) = &mut self.at;
            if *x < x1 {
                *x += 1;
            } else if *y < y1 {
                (*x, *y) = (x0, *y + 1);
            } else {
                return None;
            }
            self.point = self.cloud.head[*y * self.cloud.nx + *x];
        }
        let i = self.point;
        self.point = self.cloud.next[i as usize];
        Some(i)
    }
}

/// The cells at distance `r` (in the maximum norm) from cell `(cx, cy)` within the cells
/// `[x0, y0, x1, y1]` (those `(x, y)` with `x0 <= x <= x1`, `y0 <= y <= y1`): the ring's
/// bottom and top rows, then the rest of its left and right columns.
fn ring(
    (cx, cy): (usize, usize),
    r: usize,
    cells: [usize; 4],
) -> impl Iterator<Item = (usize, usize)> {
    let [cx, cy, r] = [cx, cy, r].map(|x| x as isize);
    let [x0, y0, x1, y1] = cells.map(|x| x as isize);
    let columns = (cx - r).max(x0)..=(cx + r).min(x1);
    let between = (cy - r + 1).max(y0)..=(cy + r - 1).min(y1);
    let rows = [Some(cy - r), (r > 0).then_some(cy + r)];
    let sides = [(r > 0).then_some(cx - r), (r > 0).then_some(cx + r)];
    let rows = rows
        .into_iter()
        .flatten()
        .filter(move |y| (y0..=y1).contains(y));
    let sides = sides
        .into_iter()
        .flatten()
        .filter(move |x| (x0..=x1).contains(x));
    rows.flat_map(move |y| columns.clone().map(move |x| (x, y)))
        .chain(sides.flat_map(move |x| between.clone().map(move |y| (x, y))))
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

/// The box of the part of the box `[lo, hi]` (finite) strictly on the side of the line
/// `(a b)` opposite `near` (nonzero), widened to cover the rounding of the line's crossings
/// with the box's sides; `None` when the whole box is on `near`'s side. The corners' sides
/// are decided exactly; a side is crossed between two corners on different sides.
fn beyond_line(
    (lo, hi): ([f64; 2], [f64; 2]),
    a: &[f64; 2],
    b: &[f64; 2],
    near: Sign,
) -> Option<([f64; 2], [f64; 2])> {
    let corners = [
        [lo[0], lo[1]],
        [hi[0], lo[1]],
        [hi[0], hi[1]],
        [lo[0], hi[1]],
    ];
    let beyond = corners.map(|p| orient2d(a, b, &p) != near);
    if !beyond.iter().any(|&x| x) {
        return None;
    }
    let (mut min, mut max) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    let mut include = |k: usize, from: f64, to: f64| {
        min[k] = min[k].min(from);
        max[k] = max[k].max(to);
    };
    for (corner, _) in corners.iter().zip(beyond).filter(|&(_, x)| x) {
        include(0, corner[0], corner[0]);
        include(1, corner[1], corner[1]);
    }
    for k in 0..4 {
        let (p, q) = (corners[k], corners[(k + 1) % 4]);
        if beyond[k] == beyond[(k + 1) % 4] {
            continue;
        }
        // Sides 0 and 2 are horizontal: the crossing's abscissa varies; sides 1 and 3 its
        // ordinate. The line is not parallel to a side it crosses.
        let along = usize::from(k % 2 == 1);
        let fixed = 1 - along;
        let t = (p[fixed] - a[fixed]) * (b[along] - a[along]) / (b[fixed] - a[fixed]);
        let x = a[along] + t;
        // Five roundings in `t`, one in the sum, each at most half an epsilon relative.
        let error = 4.0 * f64::EPSILON * (a[along].abs() + t.abs()) + f64::MIN_POSITIVE;
        let (side_lo, side_hi) = (p[along].min(q[along]), p[along].max(q[along]));
        include(along, (x - error).max(side_lo), (x + error).min(side_hi));
        include(fixed, p[fixed], p[fixed]);
    }
    Some((min, max))
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    #[test]
    fn the_part_beyond_a_line_holds_every_point_beyond_it() {
        let mut rng = rand::rngs::StdRng::seed_from_u64(5);
        for _ in 0..2000 {
            let mut corner =
                || -> [f64; 2] { [rng.gen_range(-4.0..4.0), rng.gen_range(-4.0..4.0)] };
            let (p, q) = (corner(), corner());
            let lo = [p[0].min(q[0]), p[1].min(q[1])];
            let hi = [p[0].max(q[0]), p[1].max(q[1])];
            let (a, b) = (corner(), corner());
            let near = if rng.gen_bool(0.5) {
                Sign::Positive
            } else {
                Sign::Negative
            };
            let part = beyond_line((lo, hi), &a, &b, near);
            for _ in 0..200 {
                let x = [rng.gen_range(lo[0]..=hi[0]), rng.gen_range(lo[1]..=hi[1])];
                if orient2d(&a, &b, &x) * near != Sign::Positive {
                    let (l, h) = part.expect("a point beyond the line, so a part");
                    assert!(
                        (0..2).all(|k| l[k] <= x[k] && x[k] <= h[k]),
                        "{x:?} out of {part:?}"
                    );
                }
            }
        }
    }

    #[test]
    fn the_part_beyond_a_line_is_tight() {
        let unit = ([0.0, 0.0], [1.0, 1.0]);
        let close = |x: f64, y: f64| (x - y).abs() < 1e-14;
        // Beyond the horizontal line y = 0.5 from (0.5, 1) (on its left): the lower half.
        let (lo, hi) = beyond_line(unit, &[0.0, 0.5], &[1.0, 0.5], Sign::Positive).unwrap();
        assert!(
            lo == [0.0, 0.0] && hi[0] == 1.0 && close(hi[1], 0.5),
            "{hi:?}"
        );
        // Beyond the diagonal x + y = 1 from the origin: the triangle's box, the whole square.
        let (lo, hi) = beyond_line(unit, &[1.0, 0.0], &[0.0, 1.0], Sign::Positive).unwrap();
        assert_eq!((lo, hi), ([0.0, 0.0], [1.0, 1.0]));
        // Beyond x + y = 1.5 from the origin: the corner triangle above (0.5, 1) and (1, 0.5).
        let (lo, hi) = beyond_line(unit, &[1.5, 0.0], &[0.0, 1.5], Sign::Positive).unwrap();
        assert!(
            (0..2).all(|k| close(lo[k], 0.5) && hi[k] == 1.0),
            "{lo:?} {hi:?}"
        );
        // A line missing the box, the box on the near side.
        assert_eq!(
            beyond_line(unit, &[3.0, 0.0], &[3.0, 1.0], Sign::Positive),
            None
        );
    }
}
