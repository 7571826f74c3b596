//! An open-addressing table pairing the facets that share an edge: the facets of a cone from
//! a new vertex over a cavity's boundary, glued by their edge opposite the vertex
//! (`triangulation::insert`, `recovery::tetmesh`). Invariant: within one stamp, a key is
//! stored at most once; the second facet with that key takes the first and leaves a tombstone.

/// Open-addressing table from cavity-boundary edges to the facet waiting for its twin,
/// invalidated by a generation stamp. An edge is keyed without direction: the two facets
/// that share it meet in one probe sequence, the first stores, the second takes.
#[derive(Clone, Default)]
pub struct EdgeTable {
    slots: Vec<EdgeSlot>,
    stamp: u32,
    shift: u32,
}

#[derive(Clone, Copy, Default)]
struct EdgeSlot {
    key: u64,
    facet: u32,
    stamp: u32,
}

impl EdgeTable {
    /// Empties the table, sized for `entries` keys at load factor at most 1/2.
    pub fn reset(&mut self, entries: usize) {
        let want = (2 * entries).next_power_of_two().max(64);
        if want > self.slots.len() {
            self.slots = vec![EdgeSlot::default(); want];
            self.stamp = 0;
            self.shift = 64 - want.trailing_zeros();
        }
        self.stamp = self.stamp.wrapping_add(1);
        if self.stamp == 0 {
            self.slots.fill(EdgeSlot::default());
            self.stamp = 1;
        }
    }

    /// The facet already stored under edge `{a, b}`, or `None` after storing `facet` there.
    #[inline]
    pub fn take_or_insert(&mut self, a: u32, b: u32, facet: u32) -> Option<u32> {
        let key = (u64::from(a.min(b)) << 32) | u64::from(a.max(b));
        let mask = self.slots.len() - 1;
        let mut h = (key.wrapping_mul(0x9e37_79b9_7f4a_7c15) >> self.shift) as usize;
        loop {
            let slot = &mut self.slots[h];
            if slot.stamp != self.stamp {
                *slot = EdgeSlot {
                    key,
                    facet,
                    stamp: self.stamp,
                };
                return None;
            }
            if slot.key == key {
                // A tombstone keeps the probe sequences through this slot intact.
                slot.key = TOMBSTONE;
                return Some(slot.facet);
            }
            h = (h + 1) & mask;
        }
    }
}

/// No edge has this key: it would join the infinite vertex to itself.
const TOMBSTONE: u64 = u64::MAX;
