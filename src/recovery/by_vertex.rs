//! Items grouped by a vertex number with a counting sort: the protected edges and facets by
//! their smallest vertex (`tetmesh`), the input triangles by their smallest vertex
//! (`classify`) and by each of their vertices (`partition`), the input's edges and triangles
//! (`validate`). Linear in the items, and a vertex's items are contiguous, in input order.
//! Invariant: `start` is nondecreasing, `start[0] = 0`, `start[n] = items.len()`.

/// One more than the largest vertex number the triangles use: the vertex count to group
/// their items by.
pub fn vertex_count(triangles: &[[u32; 3]]) -> usize {
    triangles
        .iter()
        .flatten()
        .max()
        .map_or(0, |&v| v as usize + 1)
}

/// Items grouped by a vertex: the items of vertex `a` are `items[start[a]..start[a + 1]]`
/// (a counting sort); vertices out of range (the infinite vertex) have none.
pub struct ByVertex<T> {
    start: Vec<u32>,
    pub items: Vec<T>,
}

impl<T: Copy + Default + PartialEq> ByVertex<T> {
    pub fn new(vertices: usize, pairs: impl Iterator<Item = (u32, T)> + Clone) -> Self {
        let mut start = vec![0u32; vertices + 1];
        for (a, _) in pairs.clone() {
            start[a as usize + 1] += 1;
        }
        for k in 1..start.len() {
            start[k] += start[k - 1];
        }
        let mut next = start.clone();
        let mut items = vec![T::default(); start[vertices] as usize];
        for (a, x) in pairs {
            items[next[a as usize] as usize] = x;
            next[a as usize] += 1;
        }
        ByVertex { start, items }
    }

    /// The items of vertex `a` (none out of range).
    pub fn of(&self, a: u32) -> &[T] {
        &self.items[self.range(a)]
    }

    /// The number of vertices.
    pub fn vertices(&self) -> usize {
        self.start.len() - 1
    }

    /// The range in `items` of the items of `a` (empty out of range).
    fn range(&self, a: u32) -> std::ops::Range<usize> {
        let a = a as usize;
        if a + 1 >= self.start.len() {
            return 0..0;
        }
        self.start[a] as usize..self.start[a + 1] as usize
    }

    /// The index in `items` of `x` among the items of `a`.
    pub fn position(&self, a: u32, x: &T) -> Option<usize> {
        let range = self.range(a);
        let from = range.start;
        self.items[range]
            .iter()
            .position(|y| y == x)
            .map(|k| from + k)
    }

    /// The first item of `a` that `is` accepts.
    pub fn find(&self, a: u32, is: impl Fn(&T) -> bool) -> Option<&T> {
        self.of(a).iter().find(|x| is(x))
    }

    /// Every item's vertex and index in `items`, by vertex.
    pub fn entries(&self) -> impl Iterator<Item = (u32, usize)> + '_ {
        (0..self.start.len() - 1).flat_map(move |a| {
            (self.start[a] as usize..self.start[a + 1] as usize).map(move |k| (a as u32, k))
        })
    }

    /// The pairs `(a, item)` whose item is flagged in `flags` (indexed like `items`).
    pub fn pairs<'a>(&'a self, flags: &'a [bool]) -> impl Iterator<Item = (u32, T)> + 'a {
        self.entries()
            .filter(|&(_, k)| flags[k])
            .map(|(a, k)| (a, self.items[k]))
    }
}
