//! The priority queue of a refinement level: worst element first (by class, then by the
//! ratio of its worst measure to the bound, to a factor 2^(1/4)); the order depends only on
//! the sequence of pushes, so refinement is deterministic. Entries are not removed when
//! their element disappears: an element names its tetrahedron slot and the insertion that
//! created that tetrahedron ([`Complex::stamp`](super::Complex::stamp)), and a level skips
//! it on `pop` when the slot has been reused since.

use crate::criteria::Badness;

/// An element of a level: a tetrahedron (`handle = t`) or a facet (`handle = 4*t+i`), with
/// the stamp of its tetrahedron and its priority, in 16 bytes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Element {
    /// Class in the top 3 bits, then the ratio's bits (positive floats order as integers).
    key: u64,
    pub handle: u32,
    pub stamp: u32,
}

impl Element {
    pub fn new(handle: u32, stamp: u32, badness: Badness) -> Self {
        let ratio = badness.ratio.max(0.0).to_bits() >> 3;
        Element {
            key: (u64::from(badness.class) << 61) | ratio,
            handle,
            stamp,
        }
    }

    pub fn class(&self) -> u8 {
        (self.key >> 61) as u8
    }
}

/// Buckets per class: the ratio's binary exponent in quarters, from 1 up to 2^60.
const BUCKETS_PER_CLASS: usize = 240;
const CLASSES: usize = 4;

/// A bucket queue: elements are grouped by class and by the ratio rounded down to a power of
/// 2^(1/4); the worst non-empty bucket is served first, last in first out (the newest
/// elements lie next to the last insertion, in memory as in space). Push and pop are O(1)
/// amortized, with no comparison of ratios within a bucket.
pub struct Queue {
    buckets: Vec<Vec<Element>>,
    /// No bucket above this one is non-empty.
    top: usize,
    len: usize,
}

impl Default for Queue {
    fn default() -> Self {
        Queue {
            buckets: vec![Vec::new(); CLASSES * BUCKETS_PER_CLASS],
            top: 0,
            len: 0,
        }
    }
}

impl Queue {
    fn bucket(e: &Element) -> usize {
        let ratio = f64::from_bits(e.key << 3 & (u64::MAX >> 1));
        let quarter = if ratio > 1.0 {
            ((ratio.log2() * 4.0) as usize).min(BUCKETS_PER_CLASS - 1)
        } else {
            0
        };
        usize::from(e.class()).min(CLASSES - 1) * BUCKETS_PER_CLASS + quarter
    }

    pub fn push(&mut self, element: Element) {
        let b = Self::bucket(&element);
        self.buckets[b].push(element);
        self.top = self.top.max(b);
        self.len += 1;
    }

    pub fn pop(&mut self) -> Option<Element> {
        loop {
            if let Some(e) = self.buckets[self.top].pop() {
                self.len -= 1;
                return Some(e);
            }
            if self.top == 0 {
                return None;
            }
            self.top -= 1;
        }
    }

    /// Entries queued, stale ones included.
    pub fn len(&self) -> usize {
        self.len
    }
}
