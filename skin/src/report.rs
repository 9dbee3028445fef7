//! Diagnostics for a set of influences.

use alloc::vec::Vec;

use crate::influences::{Influences, MAX_INFLUENCES};

/// What [`report`] measured over a mesh's influences.
#[derive(Debug, Clone, PartialEq, Default)]
#[non_exhaustive]
pub struct SkinReport {
    /// How many vertices were checked.
    pub vertices: usize,
    /// The largest `|Σ weights − 1|` over the bound vertices (those with some positive weight and
    /// no invalid one); 0 when there are none. Everything this crate builds stays within `1e-6`.
    pub max_weight_sum_error: f32,
    /// Indices of the vertices with no positive weight: skinning leaves them at rest.
    pub unbound: Vec<usize>,
    /// Indices of the vertices with a negative, NaN or infinite weight.
    pub invalid: Vec<usize>,
    /// Indices of the vertices whose weights are not sorted largest first.
    pub unsorted: Vec<usize>,
    /// `histogram[n]` is how many vertices have exactly `n` positive weights (`n` = 0 to 4).
    pub histogram: [usize; MAX_INFLUENCES + 1],
}

impl SkinReport {
    /// True when every vertex is bound, valid and sorted, and every weight sum is within
    /// `tolerance` of 1.
    #[must_use]
    pub fn is_clean(&self, tolerance: f32) -> bool {
        self.unbound.is_empty()
            && self.invalid.is_empty()
            && self.unsorted.is_empty()
            && self.max_weight_sum_error <= tolerance
    }
}

/// Measures a mesh's influences: the weight-sum error, unbound, invalid and unsorted vertices,
/// and how many influences the vertices use.
///
/// ```
/// use creature_skin::{glam::Vec3, nearest_k, report, Influences};
///
/// let bones = [[Vec3::ZERO, Vec3::Z], [Vec3::Z, Vec3::Z * 2.0]];
/// let mut influences = nearest_k(&[Vec3::X, Vec3::new(0.0, 0.0, 1.5)], &bones, 4)?;
/// influences.push(Influences::NONE);
/// let r = report(&influences);
/// assert!(r.max_weight_sum_error <= 1e-6);
/// assert_eq!(r.unbound, [2]);
/// assert_eq!(r.histogram, [1, 1, 1, 0, 0]); // one unbound, one on a bone, one between two
/// assert!(!r.is_clean(1e-6));
/// # Ok::<(), creature_skin::SkinError>(())
/// ```
#[must_use]
pub fn report(influences: &[Influences]) -> SkinReport {
    let mut r = SkinReport {
        vertices: influences.len(),
        ..SkinReport::default()
    };
    for (i, inf) in influences.iter().enumerate() {
        if inf.weights.iter().any(|w| !w.is_finite() || *w < 0.0) {
            r.invalid.push(i);
            continue;
        }
        let count = inf.count();
        if let Some(slot) = r.histogram.get_mut(count) {
            *slot += 1;
        }
        if count == 0 {
            r.unbound.push(i);
            continue;
        }
        if inf.weights.windows(2).any(|p| p[0] < p[1]) {
            r.unsorted.push(i);
        }
        let error = (inf.weights.iter().map(|&w| f64::from(w)).sum::<f64>() - 1.0).abs() as f32;
        r.max_weight_sum_error = r.max_weight_sum_error.max(error);
    }
    r
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_every_kind_of_problem() {
        let influences = [
            Influences::single(0),
            Influences::NONE,
            Influences {
                joints: [0, 1, 0, 0],
                weights: [0.2, 0.7, 0.0, 0.0],
            },
            Influences {
                joints: [0; 4],
                weights: [f32::NAN, 0.0, 0.0, 0.0],
            },
        ];
        let r = report(&influences);
        assert_eq!(r.vertices, 4);
        assert_eq!(r.unbound, [1]);
        assert_eq!(r.invalid, [3]);
        assert_eq!(r.unsorted, [2]);
        assert_eq!(r.histogram, [1, 1, 1, 0, 0]);
        assert!((r.max_weight_sum_error - 0.1).abs() < 1e-6);
        assert!(!r.is_clean(1e-6));
    }

    #[test]
    fn an_empty_mesh_is_clean() {
        let r = report(&[]);
        assert!(r.is_clean(0.0));
        assert_eq!(r.histogram, [0; 5]);
    }
}
