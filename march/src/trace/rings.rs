//! Traced rings: their vertical crossings, sorted by column, and exact enclosure tests by
//! crossing parity.

use alloc::vec::Vec;

use glam::Vec2;

/// A ring while tracing.
pub(super) struct Traced {
    /// Points in world units.
    pub(super) points: Vec<Vec2>,
    /// The vertical grid edges it crosses, as `(column, lower row)`, sorted.
    pub(super) verticals: Vec<(i32, i32)>,
    /// Where each column's crossings lie in `verticals`.
    columns: Option<Columns>,
    /// Counter-clockwise: an outer ring.
    pub(super) outer: bool,
    /// `ring::signed_area(points)`.
    pub(super) area: f64,
    /// Bounding box of `points`.
    pub(super) lo: Vec2,
    pub(super) hi: Vec2,
    /// Found by a hole scan (so its inside has been scanned already).
    pub(super) nested: bool,
    /// Refined crossings left exactly on a grid node: the index of the point and the same
    /// crossing kept off the node (see `walk::unpinch_across`). Almost always empty.
    pub(super) on_node: Vec<(usize, Vec2)>,
}

impl Traced {
    /// A traced ring from its points (at least one) and the vertical edges it crosses, in
    /// the order it crossed them; `nested` when a hole scan found it.
    pub(super) fn new(points: Vec<Vec2>, mut verticals: Vec<(i32, i32)>, nested: bool) -> Self {
        let columns = sort_by_column(&mut verticals);
        let area = crate::ring::signed_area(&points);
        let (lo, hi) = bounds(&points);
        Self {
            points,
            verticals,
            columns,
            outer: area > 0.0,
            area,
            lo,
            hi,
            nested,
            on_node: Vec::new(),
        }
    }

    /// Whether the ring encloses grid node `(x, y)`, by the parity of its crossings above the
    /// node on the node's column: exact, no floating point.
    pub(super) fn encloses(&self, x: i32, y: i32) -> bool {
        match &self.columns {
            // Column `x`'s crossings alone, from the index: those above the node.
            Some(Columns { first, starts }) => {
                // Columns outside the index hold no crossings.
                let Ok(k) = usize::try_from(i64::from(x) - i64::from(*first)) else {
                    return false;
                };
                let (Some(&start), Some(&end)) = (starts.get(k), starts.get(k + 1)) else {
                    return false;
                };
                odd_above(&self.verticals[start as usize..end as usize], y)
            }
            None => encloses(&self.verticals, x, y),
        }
    }
}

/// Where each column's crossings lie in a ring's sorted vertical crossings.
struct Columns {
    /// The first column.
    first: i32,
    /// Column `first + k`'s crossings are `starts[k]..starts[k + 1]`.
    starts: Vec<u32>,
}

/// The bounding box of ring points (of which there is at least one), as
/// [`ring::bounds`](crate::ring::bounds) gives it, with four independent minima and maxima
/// (which the order does not change: ring points are never NaN, nor `-0.0`).
fn bounds(points: &[Vec2]) -> (Vec2, Vec2) {
    let first = points[0];
    let mut lo = [first; 4];
    let mut hi = [first; 4];
    let mut chunks = points.chunks_exact(4);
    for chunk in &mut chunks {
        for ((l, h), &p) in lo.iter_mut().zip(&mut hi).zip(chunk) {
            *l = l.min(p);
            *h = h.max(p);
        }
    }
    for &p in chunks.remainder() {
        lo[0] = lo[0].min(p);
        hi[0] = hi[0].max(p);
    }
    (
        lo[0].min(lo[1]).min(lo[2].min(lo[3])),
        hi[0].max(hi[1]).max(hi[2].max(hi[3])),
    )
}

/// Sorts a ring's vertical crossings `(column, row)` into lexicographic order: a counting sort
/// on the column, then an insertion sort within each column (a closed ring crosses each
/// column it spans at least twice, so there are at most about half as many columns as
/// crossings, and few crossings per column). Returns the columns' index: the first column,
/// and where each column's crossings start (and, last, where they end); `None` when there
/// are more columns than crossings (not from a closed ring), sorted by comparisons instead.
fn sort_by_column(crossings: &mut Vec<(i32, i32)>) -> Option<Columns> {
    let first = crossings.first()?.0;
    let (min, max) = crossings
        .iter()
        .fold((first, first), |(lo, hi), c| (lo.min(c.0), hi.max(c.0)));
    let columns = (i64::from(max) - i64::from(min)) as usize + 1;
    if columns > crossings.len() {
        crossings.sort_unstable();
        return None;
    }
    // Each column's end, then (filling backwards) its start.
    let mut starts = alloc::vec![0u32; columns + 1];
    for c in crossings.iter() {
        starts[(c.0 - min) as usize + 1] += 1;
    }
    // A running sum in a register (not each entry read back from the one just stored).
    let mut sum = 0;
    for start in &mut starts {
        sum += *start;
        *start = sum;
    }
    let mut sorted = alloc::vec![(0, 0); crossings.len()];
    for &c in crossings.iter().rev() {
        let end = &mut starts[(c.0 - min) as usize + 1];
        *end -= 1;
        sorted[*end as usize] = c;
    }
    // `starts[k + 1]` is now column k's start: shift the index down.
    starts.copy_within(1.., 0);
    starts[columns] = crossings.len() as u32;
    for k in 0..columns {
        let column = &mut sorted[starts[k] as usize..starts[k + 1] as usize];
        for n in 1..column.len() {
            let mut m = n;
            while m > 0 && column[m].1 < column[m - 1].1 {
                column.swap(m, m - 1);
                m -= 1;
            }
        }
    }
    *crossings = sorted;
    Some(Columns { first: min, starts })
}

/// Whether a ring encloses node `(x, y)`, by the parity of its vertical crossings above the
/// node in its column, from `crossings`: sorted, and holding at least column `x`'s.
pub(super) fn encloses(crossings: &[(i32, i32)], x: i32, y: i32) -> bool {
    let start = crossings.partition_point(|e| e.0 < x);
    let end = crossings.partition_point(|e| e.0 <= x);
    odd_above(&crossings[start..end], y)
}

/// Whether an odd number of a column's vertical crossings lie at row `y` or above.
#[inline]
fn odd_above(column: &[(i32, i32)], y: i32) -> bool {
    column.iter().filter(|e| e.1 >= y).count() % 2 == 1
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A deterministic xorshift32 sequence from a nonzero seed.
    fn xorshift(mut s: u32) -> impl FnMut() -> u32 {
        move || {
            s ^= s << 13;
            s ^= s >> 17;
            s ^= s << 5;
            s
        }
    }

    #[test]
    fn bounds_are_the_ring_bounds() {
        let mut random = xorshift(11);
        let mut next = || (random() % 2001) as f32 * 0.37 - 370.0;
        for len in [1usize, 2, 3, 4, 5, 7, 8, 9, 100, 1001] {
            let points: Vec<Vec2> = (0..len).map(|_| Vec2::new(next(), next())).collect();
            assert_eq!(Some(bounds(&points)), crate::ring::bounds(&points), "{len}");
        }
    }

    #[test]
    fn rings_enclose_nodes_between_their_crossings() {
        // A ring crossing columns 0..=3 between rows 1 and 2 and between rows 5 and 6, and
        // column 4 twice more between rows 8 and 9, 10 and 11 (listed out of order).
        let mut verticals = alloc::vec![(3, 5), (0, 1), (4, 10), (2, 5), (1, 1), (4, 8)];
        verticals.extend([(0, 5), (3, 1), (1, 5), (2, 1)]);
        let mut sorted = verticals.clone();
        let columns = sort_by_column(&mut sorted);
        assert!(columns.is_some());
        let mut by_comparisons = verticals;
        by_comparisons.sort_unstable();
        for columns in [columns, None] {
            let ring = Traced {
                points: Vec::new(),
                verticals: by_comparisons.clone(),
                columns,
                outer: true,
                area: 0.0,
                lo: Vec2::ZERO,
                hi: Vec2::ZERO,
                nested: false,
                on_node: Vec::new(),
            };
            for x in -2..7 {
                for y in -2..14 {
                    let expected = ((0..=3).contains(&x) && (2..=5).contains(&y))
                        || (x == 4 && (9..=10).contains(&y));
                    assert_eq!(ring.encloses(x, y), expected, "({x}, {y})");
                }
            }
        }
    }

    #[test]
    fn crossings_sort_by_column_then_row() {
        let mut random = xorshift(7);
        let mut next = |m: u32| (random() % m) as i32 - (m / 2) as i32;
        for len in [0usize, 1, 2, 5, 40, 300] {
            // Few columns (as a ring makes) and, once, many (the fallback).
            for spread in [len as u32 / 2 + 1, 10 * len as u32 + 1] {
                let mut v: Vec<(i32, i32)> = (0..len).map(|_| (next(spread), next(1000))).collect();
                let mut expected = v.clone();
                expected.sort_unstable();
                let columns = sort_by_column(&mut v);
                assert_eq!(v, expected);
                if let Some(Columns { first, starts }) = columns {
                    for (k, w) in starts.windows(2).enumerate() {
                        let column = &v[w[0] as usize..w[1] as usize];
                        assert!(column.iter().all(|c| c.0 == first + k as i32));
                    }
                    assert_eq!(starts.last().copied(), Some(v.len() as u32));
                } else {
                    assert!(spread as usize > len / 2, "{len} {spread}");
                }
            }
        }
    }
}
