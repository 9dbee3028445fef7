//! The crate's one entry to std's stable sort: it sorts positions, not the elements.

use alloc::vec::Vec;
use core::cmp::Ordering;

/// `v.sort_by(cmp)`, the same order (a stable sort's is unique), with std's sort instantiated
/// once for the whole crate rather than once per element type and comparator (each copy
/// several KB of WebAssembly). Up to 20 elements are sorted in place by insertion, as std
/// does (no allocation); more, by sorting their positions `0..n` (allocated) by the elements
/// they index, then permuting `v` into that order by following its cycles.
pub(crate) fn sort_by<T>(v: &mut [T], cmp: &mut dyn FnMut(&T, &T) -> Ordering) {
    if v.len() <= 20 {
        for k in 1..v.len() {
            let mut j = k;
            while j > 0 && cmp(&v[j - 1], &v[j]).is_gt() {
                v.swap(j - 1, j);
                j -= 1;
            }
        }
        return;
    }
    let mut order: Vec<usize> = (0..v.len()).collect();
    sort_positions(&mut order, &mut |a, b| cmp(&v[a], &v[b]));
    // `v[i]` takes the element at `order[i]`; a finished position is marked `order[i] == i`.
    for start in 0..v.len() {
        let mut at = start;
        while order[at] != start {
            let from = order[at];
            v.swap(at, from);
            order[at] = at;
            at = from;
        }
        order[at] = at;
    }
}

/// The one instantiation of std's stable sort: positions compared through `cmp`.
fn sort_positions(order: &mut [usize], cmp: &mut dyn FnMut(usize, usize) -> Ordering) {
    order.sort_by(|&a, &b| cmp(a, b));
}

#[cfg(test)]
mod tests {
    use alloc::vec::Vec;

    /// The order of std's stable sort, ties included, by insertion (up to 20) and by positions.
    #[test]
    fn sort_by_is_std_stable_sort() {
        let mut state = 0x9e37_79b9_u32;
        for n in 0..70 {
            let v: Vec<(u8, usize)> = (0..n)
                .map(|i| {
                    state ^= state << 13;
                    state ^= state >> 17;
                    state ^= state << 5;
                    ((state % 7) as u8, i)
                })
                .collect();
            let mut ours = v.clone();
            super::sort_by(&mut ours, &mut |a, b| a.0.cmp(&b.0));
            let mut std = v;
            std.sort_by_key(|a| a.0);
            assert_eq!(ours, std, "{n}");
        }
    }
}
