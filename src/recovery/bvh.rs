//! A bounding-volume hierarchy of axis-aligned boxes, to find the pairs of items whose boxes
//! overlap in about `O(n log n)` for items spread over a surface, and the items whose boxes
//! hold a point.
//!
//! The items are ordered along a Morton curve of their box centers (ties broken by item
//! number, so the tree depends on the boxes only), and the tree is built top down by halving
//! that order (a linear BVH: one sort, no partitioning per node); node boxes are gathered from
//! the leaves up. Correctness does not depend on the order, only the pruning does. Building
//! and traversal use explicit stacks: no recursion.

/// A closed axis-aligned box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    pub lo: [f64; 3],
    pub hi: [f64; 3],
}

impl Aabb {
    /// The smallest box holding `points`; `points` must not be empty.
    pub fn of_points(points: &[[f64; 3]]) -> Aabb {
        let mut bounds = Aabb {
            lo: points[0],
            hi: points[0],
        };
        for p in &points[1..] {
            bounds.include(&Aabb { lo: *p, hi: *p });
        }
        bounds
    }

    /// Grows `self` to hold `other`.
    fn include(&mut self, other: &Aabb) {
        for k in 0..3 {
            self.lo[k] = self.lo[k].min(other.lo[k]);
            self.hi[k] = self.hi[k].max(other.hi[k]);
        }
    }

    /// Whether the closed boxes share a point (touching counts).
    pub fn overlaps(&self, other: &Aabb) -> bool {
        (0..3).all(|k| self.lo[k] <= other.hi[k] && other.lo[k] <= self.hi[k])
    }

    /// Twice the center along `axis`: a sort key (no rounding to halve, no overflow for the
    /// coordinates the engine accepts).
    fn center2(&self, axis: usize) -> f64 {
        self.lo[axis] + self.hi[axis]
    }
}

/// Items in a leaf at most.
const LEAF_SIZE: usize = 8;

/// A node: the box of its items, which are `order[start..end]`, and its two children unless
/// it is a leaf.
#[derive(Clone, Debug)]
struct Node {
    bounds: Aabb,
    start: usize,
    end: usize,
    children: Option<[usize; 2]>,
}

/// The hierarchy over items `0..n` given by their boxes.
#[derive(Clone, Debug)]
pub struct Bvh {
    /// The items' boxes in the order of `order` (the box of item `order[k]` is `boxes[k]`), so
    /// that a node's boxes are contiguous.
    boxes: Vec<Aabb>,
    /// Item numbers, each node's items contiguous.
    order: Vec<usize>,
    /// The root is node 0 (absent when there are no items).
    nodes: Vec<Node>,
}

impl Bvh {
    /// Builds the hierarchy of the items whose boxes are `boxes` (item `i` has `boxes[i]`).
    pub fn new(boxes: Vec<Aabb>) -> Bvh {
        let mut bvh = Bvh {
            order: (0..boxes.len()).collect(),
            boxes,
            nodes: Vec::new(),
        };
        if !bvh.boxes.is_empty() {
            bvh.build();
        }
        bvh
    }

    /// Orders the items along a Morton (Z-order) curve of their box centers (ties: item
    /// number), then splits nodes at the middle of their items, from the root holding every
    /// item, until leaves hold at most [`LEAF_SIZE`]; bounds are gathered from the leaves up.
    fn build(&mut self) {
        let codes = morton_codes(&self.boxes);
        self.order.sort_unstable_by_key(|&i| (codes[i], i));
        self.boxes = self.order.iter().map(|&i| self.boxes[i]).collect();
        self.nodes.push(self.leaf(0, self.order.len()));
        let mut pending = vec![0];
        while let Some(index) = pending.pop() {
            let (start, end) = (self.nodes[index].start, self.nodes[index].end);
            if end - start <= LEAF_SIZE {
                self.nodes[index].bounds = self.items_bounds(start, end);
                continue;
            }
            let middle = start + (end - start) / 2;
            let left = self.nodes.len();
            self.nodes.push(self.leaf(start, middle));
            self.nodes.push(self.leaf(middle, end));
            self.nodes[index].children = Some([left, left + 1]);
            pending.extend([left, left + 1]);
        }
        // Children come after their parent.
        for index in (0..self.nodes.len()).rev() {
            if let Some([l, r]) = self.nodes[index].children {
                let mut bounds = self.nodes[l].bounds;
                bounds.include(&self.nodes[r].bounds);
                self.nodes[index].bounds = bounds;
            }
        }
    }

    /// A node over `order[start..end]`, its bounds not yet known.
    fn leaf(&self, start: usize, end: usize) -> Node {
        Node {
            bounds: self.boxes[start],
            start,
            end,
            children: None,
        }
    }

    /// The box holding the items `order[start..end]`.
    fn items_bounds(&self, start: usize, end: usize) -> Aabb {
        let mut bounds = self.boxes[start];
        for item in &self.boxes[start + 1..end] {
            bounds.include(item);
        }
        bounds
    }

    /// Calls `visit(i, j)`, `i < j`, once for every pair of distinct items whose boxes overlap.
    pub fn for_each_overlapping_pair(&self, mut visit: impl FnMut(usize, usize)) {
        if self.nodes.is_empty() {
            return;
        }
        // Pairs of distinct nodes enter only when their boxes overlap.
        let mut pending = vec![(0, 0)];
        let push = |pending: &mut Vec<(usize, usize)>, a: usize, b: usize| {
            if a == b || self.nodes[a].bounds.overlaps(&self.nodes[b].bounds) {
                pending.push((a, b));
            }
        };
        while let Some((a, b)) = pending.pop() {
            let (na, nb) = (&self.nodes[a], &self.nodes[b]);
            match (na.children, nb.children) {
                (Some([l, r]), _) if a == b => {
                    push(&mut pending, l, l);
                    push(&mut pending, r, r);
                    push(&mut pending, l, r);
                }
                (None, None) => self.leaf_pairs(a, b, &mut visit),
                (Some([l, r]), None) => {
                    push(&mut pending, l, b);
                    push(&mut pending, r, b);
                }
                (Some([l, r]), Some(_)) if na.end - na.start >= nb.end - nb.start => {
                    push(&mut pending, l, b);
                    push(&mut pending, r, b);
                }
                (_, Some([l, r])) => {
                    push(&mut pending, a, l);
                    push(&mut pending, a, r);
                }
            }
        }
    }

    /// Calls `visit(i)` for every item whose box holds the point `p`, in no set order.
    pub fn for_each_containing(&self, p: &[f64; 3], visit: impl FnMut(usize)) {
        self.for_each_overlapping(&Aabb { lo: *p, hi: *p }, visit);
    }

    /// Calls `visit(i)` for every item whose box overlaps `query`, in no set order.
    pub fn for_each_overlapping(&self, query: &Aabb, mut visit: impl FnMut(usize)) {
        if self.nodes.is_empty() {
            return;
        }
        // Depth first: the stack holds at most one node per level below the root, and the
        // tree halves its nodes down to leaves (fewer than 64 levels for any item count).
        let mut pending = [0usize; 64];
        let mut len = 1;
        while len > 0 {
            len -= 1;
            let node = &self.nodes[pending[len]];
            if !node.bounds.overlaps(query) {
                continue;
            }
            match node.children {
                Some([l, r]) => {
                    pending[len] = l;
                    pending[len + 1] = r;
                    len += 2;
                }
                None => (node.start..node.end)
                    .filter(|&k| self.boxes[k].overlaps(query))
                    .for_each(|k| visit(self.order[k])),
            }
        }
    }

    /// Visits the overlapping pairs of items of leaves `a` and `b`: each pair once, and only
    /// `i < j` in the leaf when `a` and `b` are the same leaf.
    fn leaf_pairs(&self, a: usize, b: usize, visit: &mut impl FnMut(usize, usize)) {
        let (na, nb) = (&self.nodes[a], &self.nodes[b]);
        for p in na.start..na.end {
            if a != b && !self.boxes[p].overlaps(&nb.bounds) {
                // No item of `b` can overlap it: one test instead of one per item.
                continue;
            }
            let others = if a == b {
                p + 1..na.end
            } else {
                nb.start..nb.end
            };
            for q in others {
                if self.boxes[p].overlaps(&self.boxes[q]) {
                    let (i, j) = (self.order[p], self.order[q]);
                    visit(i.min(j), i.max(j));
                }
            }
        }
    }
}

/// The Morton codes of the box centers: each coordinate scaled to 21 bits over the extent of
/// the centers, the bits interleaved.
fn morton_codes(boxes: &[Aabb]) -> Vec<u64> {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for b in boxes {
        for k in 0..3 {
            lo[k] = lo[k].min(b.center2(k));
            hi[k] = hi[k].max(b.center2(k));
        }
    }
    let scale = [0, 1, 2].map(|k| {
        let extent = hi[k] - lo[k];
        if extent > 0.0 && extent.is_finite() {
            ((1u64 << 21) - 1) as f64 / extent
        } else {
            0.0
        }
    });
    boxes
        .iter()
        .map(|b| {
            (0..3).fold(0u64, |code, k| {
                let q = ((b.center2(k) - lo[k]) * scale[k]) as u64;
                code | spread(q.min((1 << 21) - 1)) << k
            })
        })
        .collect()
}

/// The 21 low bits of `x` moved to every third bit.
fn spread(x: u64) -> u64 {
    let mut x = x & 0x1f_ffff;
    x = (x | x << 32) & 0x1f_0000_0000_ffff;
    x = (x | x << 16) & 0x1f_0000_ff00_00ff;
    x = (x | x << 8) & 0x100f_00f0_0f00_f00f;
    x = (x | x << 4) & 0x10c3_0c30_c30c_30c3;
    (x | x << 2) & 0x1249_2492_4924_9249
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    /// Random boxes, small and large, some degenerate (points) and some repeated.
    fn boxes(n: usize, seed: u64) -> Vec<Aabb> {
        let mut rng = rand::rngs::StdRng::seed_from_u64(seed);
        let mut out: Vec<Aabb> = (0..n)
            .map(|_| {
                let size = if rng.gen_bool(0.1) { 0.3 } else { 0.02 };
                let corner = [0, 1, 2].map(|_| rng.gen_range(0.0..1.0));
                let far = corner.map(|x| {
                    x + if rng.gen_bool(0.05) {
                        0.0
                    } else {
                        size * rng.gen::<f64>()
                    }
                });
                Aabb::of_points(&[corner, far])
            })
            .collect();
        out.extend_from_within(..n / 10);
        out
    }

    #[test]
    fn overlapping_pairs_are_those_of_brute_force() {
        for (n, seed) in [(0, 1), (1, 2), (7, 3), (500, 4)] {
            let boxes = boxes(n, seed);
            let mut found = Vec::new();
            Bvh::new(boxes.clone()).for_each_overlapping_pair(|i, j| found.push((i, j)));
            found.sort_unstable();
            let mut expected = Vec::new();
            for i in 0..boxes.len() {
                for j in i + 1..boxes.len() {
                    if boxes[i].overlaps(&boxes[j]) {
                        expected.push((i, j));
                    }
                }
            }
            assert_eq!(found, expected, "{n} boxes");
        }
    }

    #[test]
    fn boxes_containing_a_point_are_those_of_brute_force() {
        let boxes = boxes(500, 5);
        let bvh = Bvh::new(boxes.clone());
        let mut rng = rand::rngs::StdRng::seed_from_u64(6);
        for _ in 0..200 {
            let p = [0, 1, 2].map(|_| rng.gen_range(0.0..1.2));
            let mut found = Vec::new();
            bvh.for_each_containing(&p, |i| found.push(i));
            found.sort_unstable();
            let point = Aabb { lo: p, hi: p };
            let expected: Vec<usize> = (0..boxes.len())
                .filter(|&i| boxes[i].overlaps(&point))
                .collect();
            assert_eq!(found, expected);
        }
    }
}
