//! A shared entry to std's stable sort.

use core::cmp::Ordering;

/// `v.sort_by(cmp)` with the comparator behind a `dyn` reference: std's sort is instantiated
/// once per element type in this crate instead of once per closure (and per generator type
/// of the generic callers), each copy being several KB of WebAssembly. Same algorithm, same
/// comparisons, so the same order.
pub(crate) fn sort_by<T>(v: &mut [T], cmp: &mut dyn FnMut(&T, &T) -> Ordering) {
    v.sort_by(|a, b| cmp(a, b));
}
