//! An entry to std's unstable sort with an out-of-line comparator.

use core::cmp::Ordering;

/// `v.sort_unstable_by(cmp)` with the comparator behind a `dyn` reference: std's sort is
/// instantiated once per element type in this crate instead of once per closure, and calls
/// the comparator rather than inlining it at every comparison of its partitions and sorting
/// networks, which makes each copy smaller (KBs of WebAssembly). Same algorithm, same
/// comparisons, so the same order.
pub(crate) fn sort_unstable_by<T>(v: &mut [T], cmp: &mut dyn FnMut(&T, &T) -> Ordering) {
    v.sort_unstable_by(|a, b| cmp(a, b));
}
