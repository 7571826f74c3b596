//! Insertion order for bulk input: biased randomized insertion order (BRIO, Amenta–Choi–Rote)
//! with every round sorted along a Hilbert curve, so that consecutive points are close (short
//! walks, warm caches) while the rounds keep the expected cavity sizes of a random order.
//!
//! Deterministic: the shuffle uses PCG32 with a fixed seed, and ties between equal curve keys
//! are broken by input index.

use rand_core::{RngCore, SeedableRng};
use rand_pcg::Pcg32;

/// Bits per axis of the Hilbert curve (3 * 21 = 63 bits per key).
const HILBERT_BITS: u32 = 21;
/// The first BRIO round has at most this many points; each later one is 8 times larger.
const FIRST_ROUND: usize = 64;
const ROUND_RATIO: usize = 8;
const SEED: u64 = 0x00de_1e5a_u64;

/// A permutation of `0..points.len()`: BRIO rounds, each in Hilbert order. `lo` and `hi`
/// bound the points.
pub fn brio_order(points: &[[f64; 3]], lo: &[f64; 3], hi: &[f64; 3]) -> Vec<u32> {
    let keys = hilbert_keys(points, lo, hi);
    let mut order: Vec<u32> = (0..points.len() as u32).collect();
    shuffle(&mut order);
    let mut pairs = Vec::new();
    for round in rounds(order.len()) {
        pairs.clear();
        pairs.extend(order[round.clone()].iter().map(|&i| (keys[i as usize], i)));
        pairs.sort_unstable();
        for (slot, &(_, i)) in order[round].iter_mut().zip(&pairs) {
            *slot = i;
        }
    }
    order
}

/// Fisher–Yates with a fixed-seed PCG32.
fn shuffle(order: &mut [u32]) {
    let mut rng = Pcg32::seed_from_u64(SEED);
    for i in (1..order.len()).rev() {
        // Multiply-shift maps a 32-bit draw to 0..=i without division.
        let j = ((u64::from(rng.next_u32()) * (i as u64 + 1)) >> 32) as usize;
        order.swap(i, j);
    }
}

/// The BRIO rounds as index ranges covering `0..n`, smallest first.
fn rounds(n: usize) -> Vec<std::ops::Range<usize>> {
    let mut ranges = Vec::new();
    let mut end = n;
    while end > FIRST_ROUND {
        let start = end / ROUND_RATIO;
        ranges.push(start..end);
        end = start;
    }
    ranges.push(0..end);
    ranges.reverse();
    ranges
}

/// Hilbert-curve index of every point, on a 2^21 grid spanning the box `lo..hi`.
fn hilbert_keys(points: &[[f64; 3]], lo: &[f64; 3], hi: &[f64; 3]) -> Vec<u64> {
    let cells = f64::from((1u32 << HILBERT_BITS) - 1);
    let scale = [0, 1, 2].map(|k| {
        let extent = hi[k] - lo[k];
        if extent > 0.0 {
            cells / extent
        } else {
            0.0
        }
    });
    points
        .iter()
        .map(|p| {
            let cell = [0, 1, 2].map(|k| (((p[k] - lo[k]) * scale[k]) as u32).min(cells as u32));
            hilbert_index(cell)
        })
        .collect()
}

/// Skilling's transform ("Programming the Hilbert curve", 2004): grid coordinates to the
/// transposed Hilbert index, then interleaved into one key (most significant bits first).
fn hilbert_index(mut x: [u32; 3]) -> u64 {
    let top = 1u32 << (HILBERT_BITS - 1);
    let mut q = top;
    while q > 1 {
        let p = q - 1;
        for i in 0..3 {
            // Branch-free: invert the low bits of x[0] if bit q of x[i] is set, else
            // exchange the low bits of x[0] and x[i].
            let set = 0u32.wrapping_sub(u32::from(x[i] & q != 0));
            let t = (x[0] ^ x[i]) & p & !set;
            x[0] ^= (p & set) | t;
            x[i] ^= t;
        }
        q >>= 1;
    }
    x[1] ^= x[0];
    x[2] ^= x[1];
    let mut t = 0;
    q = top;
    while q > 1 {
        if x[2] & q != 0 {
            t ^= q - 1;
        }
        q >>= 1;
    }
    for xi in &mut x {
        *xi ^= t;
    }
    interleave(x)
}

/// Bit `b` of `x[i]` goes to bit `3*b + (2-i)` of the key.
fn interleave(x: [u32; 3]) -> u64 {
    let spread = |v: u32| -> u64 {
        let mut v = u64::from(v) & 0x1f_ffff;
        v = (v | (v << 32)) & 0x001f_0000_0000_ffff;
        v = (v | (v << 16)) & 0x001f_0000_ff00_00ff;
        v = (v | (v << 8)) & 0x100f_00f0_0f00_f00f;
        v = (v | (v << 4)) & 0x10c3_0c30_c30c_30c3;
        v = (v | (v << 2)) & 0x1249_2492_4924_9249;
        v
    };
    (spread(x[0]) << 2) | (spread(x[1]) << 1) | spread(x[2])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn order_is_a_permutation_and_deterministic() {
        let pts: Vec<[f64; 3]> = (0..5000)
            .map(|i| {
                let f = f64::from(i);
                [(f * 0.37).sin(), (f * 0.11).cos(), (f * 0.07).sin()]
            })
            .collect();
        let (lo, hi) = ([-1.0; 3], [1.0; 3]);
        let a = brio_order(&pts, &lo, &hi);
        let mut s = a.clone();
        s.sort_unstable();
        assert!(s.iter().enumerate().all(|(i, &v)| v as usize == i));
        assert_eq!(a, brio_order(&pts, &lo, &hi));
    }

    #[test]
    fn rounds_cover_everything_once() {
        for n in [0, 1, 64, 65, 1000, 123_457] {
            let r = rounds(n);
            assert_eq!(r.first().unwrap().start, 0);
            assert_eq!(r.last().unwrap().end, n);
            assert!(r.windows(2).all(|w| w[0].end == w[1].start));
            assert!(r[0].len() <= FIRST_ROUND);
        }
    }

    #[test]
    fn hilbert_neighbours_are_grid_neighbours() {
        // Consecutive keys on a full 8x8x8 subgrid must be adjacent cells.
        let side = 8u32;
        let shift = HILBERT_BITS - 3;
        let mut cells: Vec<([u32; 3], u64)> = Vec::new();
        for x in 0..side {
            for y in 0..side {
                for z in 0..side {
                    let c = [x << shift, y << shift, z << shift];
                    cells.push(([x, y, z], hilbert_index(c)));
                }
            }
        }
        cells.sort_by_key(|c| c.1);
        for w in cells.windows(2) {
            let d: u32 = (0..3).map(|k| w[0].0[k].abs_diff(w[1].0[k])).sum();
            assert_eq!(d, 1, "{:?} -> {:?}", w[0].0, w[1].0);
        }
    }
}
