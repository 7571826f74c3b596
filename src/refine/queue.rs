//! The priority queue of a refinement level: worst element first (by class, then by the
//! ratio of its worst measure to the bound), ties in insertion order, so the refinement
//! order is deterministic. Entries are not removed when their element disappears; a level
//! checks on `pop` that the element still exists (its tetrahedron slot still holds the same
//! vertices) and skips it otherwise.

use std::cmp::Ordering;
use std::collections::BinaryHeap;

use crate::criteria::Badness;

/// An element of a level: a tetrahedron (`handle = t`) or a facet (`handle = 4*t+i`), with
/// the vertices its tetrahedron had when queued.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Element {
    pub handle: u32,
    pub vertices: [u32; 4],
    /// Its priority when queued.
    pub badness: Badness,
    /// Refine even if it meets the criteria (a facet encroached by a lower level's point).
    pub forced: bool,
}

struct Entry {
    sequence: u64,
    element: Element,
}

impl PartialEq for Entry {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}

impl Eq for Entry {}

impl PartialOrd for Entry {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Entry {
    /// Greater is popped first: higher class, then larger ratio, then earlier insertion.
    fn cmp(&self, other: &Self) -> Ordering {
        let (a, b) = (&self.element.badness, &other.element.badness);
        a.class
            .cmp(&b.class)
            .then(a.ratio.total_cmp(&b.ratio))
            .then(other.sequence.cmp(&self.sequence))
    }
}

#[derive(Default)]
pub struct Queue {
    heap: BinaryHeap<Entry>,
    sequence: u64,
}

impl Queue {
    pub fn push(&mut self, element: Element) {
        self.sequence += 1;
        self.heap.push(Entry {
            sequence: self.sequence,
            element,
        });
    }

    pub fn pop(&mut self) -> Option<Element> {
        self.heap.pop().map(|e| e.element)
    }

    /// Entries queued, stale ones included.
    pub fn len(&self) -> usize {
        self.heap.len()
    }
}
