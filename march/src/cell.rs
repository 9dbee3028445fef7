//! The marching-squares cell rule shared by the grid and the trace.
//!
//! Corners are numbered counter-clockwise from the bottom left (y up): `c0` = (i, j),
//! `c1` = (i+1, j), `c2` = (i+1, j+1), `c3` = (i, j+1). Edge `k` runs from `c_k` to
//! `c_(k+1)`: 0 bottom, 1 right, 2 top, 3 left. A contour segment enters a cell through an
//! edge whose counter-clockwise walk goes from an inside corner to an outside one, and leaves
//! through an edge going from outside to inside; so the inside is always on the segment's
//! left, and outer rings come out counter-clockwise.

/// The corner offsets of a cell, in corner order.
pub(crate) const CORNERS: [(i32, i32); 4] = [(0, 0), (1, 0), (1, 1), (0, 1)];

/// The offset to the neighbouring cell across each edge (the definition [`across`] computes).
#[cfg(test)]
pub(crate) const ACROSS: [(i32, i32); 4] = [(0, -1), (1, 0), (0, 1), (-1, 0)];

/// `CORNERS[k & 3]` by arithmetic rather than a table: a contour walk's next step waits on
/// it, and a load takes several times as long as these few operations.
#[inline(always)]
pub(crate) const fn corner(k: usize) -> (i32, i32) {
    (((k + 1) >> 1 & 1) as i32, (k >> 1 & 1) as i32)
}

/// `ACROSS[e & 3]` by arithmetic (see [`corner`]).
#[inline(always)]
pub(crate) const fn across(e: usize) -> (i32, i32) {
    let odd = (e & 1) as i32;
    let e = (e & 3) as i32;
    (odd * (2 - e), (1 - odd) * (e - 1))
}

/// Whether a sample counts as inside: `v >= iso`; NaN is outside.
#[inline]
pub(crate) fn is_inside(v: f32, iso: f32) -> bool {
    v >= iso
}

/// The edge through which the segment that entered through in→out edge `k` leaves, for a cell
/// whose inside corners are the bits of `mask` (bit `k` = corner `k`). `joined` settles a
/// saddle: `true` joins the two inside corners.
#[inline]
pub(crate) fn exit_edge(mask: u8, k: usize, joined: impl FnOnce() -> bool) -> usize {
    if mask == 0b0101 || mask == 0b1010 {
        return if joined() { (k + 1) & 3 } else { (k + 3) & 3 };
    }
    EXITS[usize::from(mask & 15)][k & 3] as usize
}

/// [`exit_edge`] of every mask that is not a saddle, by mask and entry edge: the first edge
/// after `k`, counter-clockwise, that runs from an outside corner to an inside one.
const EXITS: [[u8; 4]; 16] = exits();

const fn exits() -> [[u8; 4]; 16] {
    let mut table = [[0u8; 4]; 16];
    let mut mask = 0;
    while mask < 16 {
        let mut k = 0;
        while k < 4 {
            // Unreachable for a mask with an in→out edge (it also has an out→in edge): the
            // fallback.
            let mut exit = (k + 3) & 3;
            let mut d = 1;
            while d < 4 {
                let e = (k + d) & 3;
                let (from, to) = (mask & (1 << e) != 0, mask & (1 << ((e + 1) & 3)) != 0);
                if !from && to {
                    exit = e;
                    break;
                }
                d += 1;
            }
            table[mask][k] = exit as u8;
            k += 1;
        }
        mask += 1;
    }
    table
}

/// The nearest a traced crossing comes to a sample node, as a fraction of the cell: never on
/// a node, where two crossings beside an outside node a hair below the iso-level would meet
/// and pinch the ring. (The grid keeps the same gap.)
pub(crate) const NODE_GAP: f32 = 1e-3;

/// Where along an edge from an inside sample to an outside one the contour crosses, as a
/// fraction from the inside end: linear interpolation, or the midpoint when either sample is
/// not finite.
///
/// Callers pass an inside sample (`v_in ≥ iso`) and an outside one (`v_out < iso`, or NaN):
/// the only edges a contour crosses. Then the fraction lies in `[0, 1]` with no clamp: the
/// numerator `iso − v_in` is at most 0 and the denominator `v_out − v_in` below 0 and no
/// smaller in magnitude, which rounding (monotonic, and never to 0 for a nonzero difference
/// of two `f32`s in `f64`) keeps, so the quotient rounds into `[0, 1]` (tested on extreme
/// values). No clamp also means a shorter wait for the walk's crossing points, which wait on
/// this division.
#[inline]
pub(crate) fn crossing(v_in: f32, v_out: f32, iso: f32) -> f32 {
    if !(v_in.is_finite() && v_out.is_finite()) {
        return 0.5;
    }
    // In f64, so that differences of large samples cannot overflow.
    let (v_in, v_out, iso) = (f64::from(v_in), f64::from(v_out), f64::from(iso));
    ((iso - v_in) / (v_out - v_in)) as f32
}

/// The asymptotic decider: whether the bilinear interpolant of a saddle cell is inside at its
/// saddle point. `values` are in corner order. Non-finite corners split the saddle.
pub(crate) fn asymptotic_joined(values: [f32; 4], iso: f32) -> bool {
    if !values.iter().all(|v| v.is_finite()) {
        return false;
    }
    let [a, b, c, d] = values.map(|v| f64::from(v) - f64::from(iso));
    let denominator = a + c - b - d;
    if denominator == 0.0 {
        return false;
    }
    (a * c - b * d) / denominator >= 0.0
}

/// The mean-of-corners centre rule for a grid's saddle. Non-finite corners split the saddle.
pub(crate) fn mean_joined(values: [f32; 4], iso: f32) -> bool {
    if !values.iter().all(|v| v.is_finite()) {
        return false;
    }
    let mean = values.iter().map(|&v| f64::from(v)).sum::<f64>() * 0.25;
    mean >= f64::from(iso)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn corner_and_across_are_their_tables() {
        for k in 0..8 {
            assert_eq!(corner(k), CORNERS[k & 3], "corner {k}");
            assert_eq!(across(k), ACROSS[k & 3], "across {k}");
        }
    }

    #[test]
    fn single_inside_corner_cuts_it_off() {
        // Only c0 inside: enter through the bottom (in→out), leave through the left.
        assert_eq!(exit_edge(0b0001, 0, || unreachable!()), 3);
        // Only c1 outside: enter bottom (c0 in → c1 out), leave right (c1 out → c2 in).
        assert_eq!(exit_edge(0b1101, 0, || unreachable!()), 1);
        // Bottom half inside: enter right (c1 in → c2 out), leave left (c3 out → c0 in).
        assert_eq!(exit_edge(0b0011, 1, || unreachable!()), 3);
    }

    #[test]
    fn the_exit_table_is_the_first_out_to_in_edge() {
        // The rule spelt out, for every mask that is not a saddle and every entry edge.
        for mask in 0u8..16 {
            if mask == 0b0101 || mask == 0b1010 {
                continue;
            }
            let inside = |c: usize| mask & (1 << (c & 3)) != 0;
            for k in 0..4 {
                let expected = (1..4)
                    .map(|d| (k + d) & 3)
                    .find(|&e| !inside(e) && inside(e + 1))
                    .unwrap_or((k + 3) & 3);
                assert_eq!(
                    exit_edge(mask, k, || unreachable!()),
                    expected,
                    "{mask:04b} {k}"
                );
            }
        }
    }

    #[test]
    fn saddles_follow_the_decision() {
        assert_eq!(exit_edge(0b0101, 0, || true), 1);
        assert_eq!(exit_edge(0b0101, 0, || false), 3);
        assert_eq!(exit_edge(0b1010, 1, || true), 2);
        assert_eq!(exit_edge(0b1010, 1, || false), 0);
    }

    #[test]
    fn crossing_interpolates_and_guards() {
        assert_eq!(crossing(2.0, 0.0, 1.0), 0.5);
        assert_eq!(crossing(1.0, 0.0, 1.0), 0.0);
        assert_eq!(crossing(f32::INFINITY, 0.0, 1.0), 0.5);
        assert_eq!(crossing(2.0, f32::NAN, 1.0), 0.5);
        assert_eq!(crossing(f32::MAX, -f32::MAX, 0.0), 0.5);
    }

    /// Without a clamp, the fraction stays in `[0, 1]` for every inside–outside pair, down to
    /// subnormal gaps and up to `f32::MAX`.
    #[test]
    fn crossing_stays_on_the_edge_without_a_clamp() {
        let mut state = 0x9e37_79b9_u32;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 17;
            state ^= state << 5;
            state
        };
        let special = [
            0.0,
            -0.0,
            f32::MIN_POSITIVE,
            1e-45,
            -1e-45,
            1.0,
            f32::MAX,
            -f32::MAX,
            f32::EPSILON,
            1.0 + f32::EPSILON,
        ];
        for n in 0..200_000 {
            let pick = |r: u32| {
                if r.is_multiple_of(4) {
                    special[(r / 4) as usize % special.len()]
                } else {
                    f32::from_bits(r)
                }
            };
            let mut v = [pick(next()), pick(next()), pick(next())];
            if v.iter().any(|x| !x.is_finite()) {
                continue;
            }
            v.sort_by(f32::total_cmp);
            // Inside ≥ iso > outside: the largest inside, the smallest outside, iso between
            // (sometimes equal to the inside sample).
            let (v_out, iso, v_in) = if n % 3 == 0 {
                (v[0], v[2], v[2])
            } else {
                (v[0], v[1], v[2])
            };
            if !(v_in >= iso && v_out < iso) {
                continue;
            }
            let t = crossing(v_in, v_out, iso);
            assert!((0.0..=1.0).contains(&t), "{v_in} {v_out} {iso}: {t}");
        }
    }

    #[test]
    fn deciders() {
        // Strong inside diagonal: joined by both rules.
        assert!(asymptotic_joined([3.0, 0.0, 3.0, 0.0], 1.0));
        assert!(mean_joined([3.0, 0.0, 3.0, 0.0], 1.0));
        // Weak inside diagonal: split by both.
        assert!(!asymptotic_joined([1.1, 0.0, 1.1, 0.0], 1.0));
        assert!(!mean_joined([1.1, 0.0, 1.1, 0.0], 1.0));
        // They differ: the mean is 1.5025 ≥ 1 but the bilinear saddle is below the iso-level.
        assert!(mean_joined([4.0, 0.5, 1.01, 0.5], 1.0));
        assert!(!asymptotic_joined([4.0, 0.5, 1.01, 0.5], 1.0));
        assert!(!mean_joined([f32::NAN, 0.0, 3.0, 0.0], 1.0));
    }
}
