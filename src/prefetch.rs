//! Cache prefetch hints for searches whose next steps are known a little ahead (the
//! breadth-first cavity searches): a hint lets the memory loads of the next tetrahedra overlap
//! the work on the current ones. A hint changes no result.

/// Asks the processor to bring `items[i]` into the cache; nothing when `i` is out of bounds
/// or the target has no prefetch instruction.
#[inline]
pub fn prefetch<T>(items: &[T], i: usize) {
    #[cfg(target_arch = "x86_64")]
    if let Some(x) = items.get(i) {
        use std::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
        // SAFETY: a prefetch never faults, and the pointer is to a live element.
        unsafe { _mm_prefetch::<_MM_HINT_T0>((x as *const T).cast()) };
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = (items, i);
}

#[cfg(test)]
mod tests {
    use super::prefetch;

    #[test]
    fn a_hint_out_of_bounds_is_ignored() {
        // Fails by panicking if a hint indexes instead of asking `get`.
        let items = [1u32, 2, 3];
        for i in [0, 2, 3, usize::MAX] {
            prefetch(&items, i);
        }
        prefetch::<u64>(&[], 0);
    }
}
