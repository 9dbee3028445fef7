//! Field-weighted binding: the top-k bones by summed contribution (the 2D seed's rule).

use smallvec::SmallVec;

use crate::error::SkinError;
use crate::influences::{Influences, MAX_INFLUENCES};

/// Binds one vertex from `(bone, value)` contributions, such as a metaball field's per-ball
/// values at the vertex tagged with each ball's bone (the 2D seed's rule).
///
/// Values of the same bone are summed (in `f64`, in the order given, so the result is
/// deterministic and cannot overflow); the `k` bones with the largest totals (ties: smaller bone
/// id first) keep their totals, divided by their sum. Bones whose total is zero take no slot.
///
/// ```
/// use creature_skin::from_contributions;
///
/// // Three balls on bone 2, one on bone 0, two on bone 5.
/// let field = [(2, 0.5), (0, 0.25), (2, 0.25), (5, 0.125), (5, 0.125), (2, 0.25)];
/// let inf = from_contributions(field, 2)?;
/// assert_eq!(inf.joints, [2, 0, 0, 0]); // bone 5 ties bone 0 at 0.25 and loses on id
/// assert_eq!(inf.weights, [0.8, 0.2, 0.0, 0.0]);
/// # Ok::<(), creature_skin::SkinError>(())
/// ```
///
/// # Errors
/// - [`SkinError::InvalidInfluenceCount`] if `k` is 0 or more than [`MAX_INFLUENCES`];
/// - [`SkinError::NonFinite`] (`what = "contribution"`), [`SkinError::NegativeContribution`] or
///   [`SkinError::BoneIdTooLarge`] for a bad pair, with its position;
/// - [`SkinError::ZeroContribution`] if no bone has a positive total (no pairs, or all zero).
///   [`from_contributions_or`] takes a fallback bone for that case instead.
pub fn from_contributions(
    per_vertex: impl IntoIterator<Item = (u32, f32)>,
    k: usize,
) -> Result<Influences, SkinError> {
    if k == 0 || k > MAX_INFLUENCES {
        return Err(SkinError::InvalidInfluenceCount { k });
    }
    // Per-bone totals; a vertex rarely hears from more than a handful of bones.
    let mut totals: SmallVec<[(u16, f64); 16]> = SmallVec::new();
    for (index, (bone, value)) in per_vertex.into_iter().enumerate() {
        if !value.is_finite() {
            return Err(SkinError::NonFinite {
                what: "contribution",
                index,
            });
        }
        if value < 0.0 {
            return Err(SkinError::NegativeContribution { index, value });
        }
        let Ok(bone) = u16::try_from(bone) else {
            return Err(SkinError::BoneIdTooLarge { index, bone });
        };
        match totals.iter_mut().find(|(b, _)| *b == bone) {
            Some((_, total)) => *total += f64::from(value),
            None => totals.push((bone, f64::from(value))),
        }
    }
    if totals.iter().any(|&(_, t)| !(t > 0.0)) {
        totals.retain(|&mut (_, t)| t > 0.0);
    }
    if totals.is_empty() {
        return Err(SkinError::ZeroContribution);
    }
    let mut order = |a: &(u16, f64), b: &(u16, f64)| b.1.total_cmp(&a.1).then(a.0.cmp(&b.0));
    // Often sorted already (the top shares of a field come largest first).
    if !totals.windows(2).all(|w| order(&w[0], &w[1]).is_le()) {
        crate::sort::sort_by(&mut totals, &mut order);
    }
    totals.truncate(k);
    let sum: f64 = totals.iter().map(|&(_, t)| t).sum();
    let mut inf = Influences::NONE;
    for (i, &(bone, total)) in totals.iter().enumerate() {
        inf.joints[i] = bone;
        // In (0, 1]; a share too small for f32 rounds to 0 and frees its slot below.
        inf.weights[i] = (total / sum) as f32;
    }
    crate::nearest::normalise(&mut inf);
    Ok(inf)
}

/// [`from_contributions`], but a vertex with no positive contribution is bound wholly to
/// `fallback` (for example its nearest bone, from [`nearest_k`](crate::nearest_k) with `k = 1`)
/// instead of being an error.
///
/// ```
/// use creature_skin::{from_contributions_or, Influences};
///
/// let far_from_every_ball = [(0, 0.0), (1, 0.0)];
/// assert_eq!(from_contributions_or(far_from_every_ball, 4, 3)?, Influences::single(3));
/// # Ok::<(), creature_skin::SkinError>(())
/// ```
///
/// # Errors
/// As [`from_contributions`], except [`SkinError::ZeroContribution`].
pub fn from_contributions_or(
    per_vertex: impl IntoIterator<Item = (u32, f32)>,
    k: usize,
    fallback: u16,
) -> Result<Influences, SkinError> {
    match from_contributions(per_vertex, k) {
        Err(SkinError::ZeroContribution) => Ok(Influences::single(fallback)),
        other => other,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sums_per_bone_and_keeps_the_top_k() {
        let pairs = [(7, 1.0), (3, 2.0), (7, 2.5), (1, 0.5), (9, 0.25), (4, 0.1)];
        let inf = from_contributions(pairs, 4).unwrap();
        assert_eq!(inf.joints, [7, 3, 1, 9]);
        let expected = [3.5, 2.0, 0.5, 0.25].map(|v| v / 6.25);
        for (w, e) in inf.weights.iter().zip(expected) {
            assert!((w - e).abs() < 1e-6);
        }
        assert!((inf.weight_sum() - 1.0).abs() < 1e-6);
    }

    #[test]
    fn fewer_bones_than_k_leave_empty_slots() {
        let inf = from_contributions([(4, 0.3)], 4).unwrap();
        assert_eq!(inf, Influences::single(4));
        // Zero-valued bones take no slot (the seed padded with bone 0, value 0).
        let inf = from_contributions([(4, 0.3), (6, 0.0)], 4).unwrap();
        assert_eq!(inf, Influences::single(4));
    }

    #[test]
    fn zero_total_is_an_error_or_the_fallback() {
        assert_eq!(
            from_contributions([(1, 0.0)], 4),
            Err(SkinError::ZeroContribution)
        );
        assert_eq!(
            from_contributions(core::iter::empty(), 4),
            Err(SkinError::ZeroContribution)
        );
        assert_eq!(
            from_contributions_or([(1, 0.0)], 4, 2),
            Ok(Influences::single(2))
        );
        // The fallback does not hide other errors.
        assert_eq!(
            from_contributions_or([(1, -1.0)], 4, 2),
            Err(SkinError::NegativeContribution {
                index: 0,
                value: -1.0
            })
        );
    }

    #[test]
    fn bad_pairs_are_errors() {
        assert_eq!(
            from_contributions([(0, 1.0), (1, f32::NAN)], 4),
            Err(SkinError::NonFinite {
                what: "contribution",
                index: 1
            })
        );
        assert_eq!(
            from_contributions([(70_000, 1.0)], 4),
            Err(SkinError::BoneIdTooLarge {
                index: 0,
                bone: 70_000
            })
        );
        assert_eq!(
            from_contributions([(0, 1.0)], 0),
            Err(SkinError::InvalidInfluenceCount { k: 0 })
        );
    }

    #[test]
    fn huge_values_do_not_overflow() {
        let inf = from_contributions([(0, f32::MAX), (0, f32::MAX), (1, f32::MAX)], 4).unwrap();
        assert_eq!(inf.joints, [0, 1, 0, 0]);
        assert!((inf.weights[0] - 2.0 / 3.0).abs() < 1e-6);
        assert!((inf.weight_sum() - 1.0).abs() < 1e-6);
    }
}
