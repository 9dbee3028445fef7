//! Per-vertex joint influences and their glTF quantisation.

/// The most joints that can influence one vertex: glTF's `JOINTS_0`/`WEIGHTS_0` limit.
pub const MAX_INFLUENCES: usize = 4;

/// Up to [`MAX_INFLUENCES`] joints and their weights for one vertex, ready for glTF's
/// `JOINTS_0` and `WEIGHTS_0` attributes.
///
/// Every constructor in this crate returns influences that are
/// - sorted by weight, largest first (equal weights by joint index, smallest first),
/// - normalised: the weights sum to 1 within `1e-6`,
/// - padded: unused slots have joint 0 and weight 0.
///
/// The one exception is [`Influences::NONE`] (all weights zero): a vertex bound to nothing, which
/// skinning leaves at its rest position and [`report`](crate::report) counts as unbound.
///
/// ```
/// use creature_skin::Influences;
///
/// let inf = Influences { joints: [2, 0, 0, 0], weights: [0.5, 0.3, 0.2, 0.0] };
/// // 127.5, 76.5 and 51 round down to 254; the one unit left goes to the largest remainder
/// // (0.3 is a hair above 0.3 in f32).
/// assert_eq!(inf.quantize_u8(), [127, 77, 51, 0]);
/// assert_eq!(inf.quantize_u8().iter().map(|&w| u32::from(w)).sum::<u32>(), 255);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Influences {
    /// Joint (bone) indices, one per slot.
    pub joints: [u16; MAX_INFLUENCES],
    /// Weights, one per slot, matching `joints`.
    pub weights: [f32; MAX_INFLUENCES],
}

impl Influences {
    /// No influence at all: every weight zero. Skinning leaves such a vertex where it is.
    pub const NONE: Self = Self {
        joints: [0; MAX_INFLUENCES],
        weights: [0.0; MAX_INFLUENCES],
    };

    /// Full weight on one joint.
    #[must_use]
    pub const fn single(joint: u16) -> Self {
        Self {
            joints: [joint, 0, 0, 0],
            weights: [1.0, 0.0, 0.0, 0.0],
        }
    }

    /// How many slots have a weight greater than zero.
    #[must_use]
    pub fn count(&self) -> usize {
        self.weights.iter().filter(|&&w| w > 0.0).count()
    }

    /// The sum of the weights.
    #[must_use]
    pub fn weight_sum(&self) -> f32 {
        self.weights.iter().sum()
    }

    /// The weight this vertex gives `joint` (0 when it is not among its influences).
    #[must_use]
    pub fn weight_of(&self, joint: u16) -> f32 {
        self.iter()
            .filter(|&(j, _)| j == joint)
            .map(|(_, w)| w)
            .sum()
    }

    /// The `(joint, weight)` pairs with a weight greater than zero, in slot order.
    pub fn iter(&self) -> impl Iterator<Item = (u16, f32)> + '_ {
        self.joints
            .iter()
            .zip(self.weights.iter())
            .filter(|&(_, &w)| w > 0.0)
            .map(|(&j, &w)| (j, w))
    }

    /// Weights as glTF normalised unsigned bytes, summing to exactly 255.
    ///
    /// Each weight is scaled by `255 / sum` and rounded down; the units still missing go, one
    /// each, to the slots with the largest remainders (ties to the lower slot). So the sum is
    /// exact and the order is kept: a larger weight never gets a smaller byte.
    ///
    /// Negative, NaN and infinite weights count as 0. If no weight is positive, the result is
    /// all zeros (a vertex bound to nothing).
    #[must_use]
    pub fn quantize_u8(&self) -> [u8; MAX_INFLUENCES] {
        let q = largest_remainder(&self.weights, u8::MAX.into());
        // Each value is at most the total, 255.
        q.map(|v| {
            debug_assert!(v <= u32::from(u8::MAX));
            v as u8
        })
    }

    /// Weights as glTF normalised unsigned shorts, summing to exactly 65535. See
    /// [`quantize_u8`](Self::quantize_u8) for the rounding rule.
    #[must_use]
    pub fn quantize_u16(&self) -> [u16; MAX_INFLUENCES] {
        let q = largest_remainder(&self.weights, u16::MAX.into());
        // Each value is at most the total, 65535.
        q.map(|v| {
            debug_assert!(v <= u32::from(u16::MAX));
            v as u16
        })
    }

    /// Sorts the slots by weight, largest first (ties by joint index, smallest first), and
    /// resets the joint of every zero-weight slot to 0.
    pub(crate) fn canonicalise(&mut self) {
        let mut slots = [(0u16, 0.0f32); MAX_INFLUENCES];
        for (slot, (&j, &w)) in slots
            .iter_mut()
            .zip(self.joints.iter().zip(self.weights.iter()))
        {
            *slot = if w > 0.0 { (j, w) } else { (0, 0.0) };
        }
        slots.sort_by(|a, b| b.1.total_cmp(&a.1).then(a.0.cmp(&b.0)));
        for (i, (j, w)) in slots.into_iter().enumerate() {
            self.joints[i] = j;
            self.weights[i] = w;
        }
    }
}

/// Quantises `weights` to non-negative integers summing to exactly `total` (largest remainder
/// method), or to all zeros when no weight is positive.
fn largest_remainder(weights: &[f32; MAX_INFLUENCES], total: u32) -> [u32; MAX_INFLUENCES] {
    let clean = weights.map(|w| {
        if w.is_finite() && w > 0.0 {
            f64::from(w)
        } else {
            0.0
        }
    });
    let sum: f64 = clean.iter().sum();
    let mut out = [0u32; MAX_INFLUENCES];
    if !(sum > 0.0) {
        return out;
    }
    let mut remainders = [0.0f64; MAX_INFLUENCES];
    let mut assigned = 0u32;
    for i in 0..MAX_INFLUENCES {
        let scaled = (clean[i] / sum * f64::from(total)).min(f64::from(total));
        // Non-negative, so truncation is floor.
        let floor = scaled as u32;
        out[i] = floor;
        remainders[i] = scaled - f64::from(floor);
        assigned += floor;
    }
    // The floors sum to at most `total` (each floor is at most its share, and the shares sum to
    // `total` up to rounding, which cannot lift an integer sum above it). Hand out the rest.
    let mut order = [0usize, 1, 2, 3];
    order.sort_by(|&a, &b| remainders[b].total_cmp(&remainders[a]).then(a.cmp(&b)));
    let mut missing = total.saturating_sub(assigned);
    // Only slots with a positive weight receive units; cycle in case rounding left more units
    // than such slots (never observed, but the sum must be exact).
    while missing > 0 {
        for &i in &order {
            if missing == 0 {
                break;
            }
            if clean[i] > 0.0 {
                out[i] += 1;
                missing -= 1;
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sum_u8(q: [u8; 4]) -> u32 {
        q.iter().map(|&v| u32::from(v)).sum()
    }

    #[test]
    fn thirds_quantise_exactly() {
        let inf = Influences {
            joints: [0, 1, 2, 0],
            weights: [1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0, 0.0],
        };
        assert_eq!(inf.quantize_u8(), [85, 85, 85, 0]);
        assert_eq!(inf.quantize_u16(), [21845, 21845, 21845, 0]);
    }

    #[test]
    fn remainders_go_to_the_largest_fractions_in_order() {
        let inf = Influences {
            joints: [0, 1, 2, 3],
            weights: [0.4, 0.3, 0.2, 0.1],
        };
        let q = inf.quantize_u8();
        assert_eq!(sum_u8(q), 255);
        assert!(q[0] >= q[1] && q[1] >= q[2] && q[2] >= q[3], "{q:?}");
        assert_eq!(q, [102, 77, 51, 25]);
    }

    #[test]
    fn equal_weights_that_do_not_divide_evenly_stay_ordered() {
        let inf = Influences {
            joints: [0, 1, 2, 3],
            weights: [0.25; 4],
        };
        let q = inf.quantize_u8();
        assert_eq!(q, [64, 64, 64, 63]);
    }

    #[test]
    fn no_weight_quantises_to_zero() {
        assert_eq!(Influences::NONE.quantize_u8(), [0; 4]);
        let bad = Influences {
            joints: [0; 4],
            weights: [f32::NAN, -1.0, 0.0, 0.0],
        };
        assert_eq!(bad.quantize_u16(), [0; 4]);
    }

    #[test]
    fn unnormalised_weights_are_normalised_first() {
        let inf = Influences {
            joints: [0, 1, 0, 0],
            weights: [3.0, 1.0, 0.0, 0.0],
        };
        assert_eq!(inf.quantize_u8(), [191, 64, 0, 0]);
    }

    #[test]
    fn single_is_full_weight() {
        let inf = Influences::single(7);
        assert_eq!(inf.quantize_u8(), [255, 0, 0, 0]);
        assert_eq!(inf.quantize_u16(), [65535, 0, 0, 0]);
        assert_eq!(inf.count(), 1);
        assert_eq!(inf.weight_of(7), 1.0);
        assert_eq!(inf.weight_of(0), 0.0);
    }

    #[test]
    fn canonicalise_sorts_and_clears_empty_slots() {
        let mut inf = Influences {
            joints: [5, 9, 2, 4],
            weights: [0.2, 0.0, 0.5, 0.3],
        };
        inf.canonicalise();
        assert_eq!(inf.joints, [2, 4, 5, 0]);
        assert_eq!(inf.weights, [0.5, 0.3, 0.2, 0.0]);
    }
}
