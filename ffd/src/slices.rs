//! Slice helpers: the operations a procedural body makes on whole layers of control points.
//!
//! A *slice* along an axis is every control point with one fixed index on that axis; for the
//! creature body's 3×3×11 lattice the 11 slices along U are the 3×3 cross-sections.
//!
//! **No-fold guarantee.** Starting from an undeformed lattice, if slices along one axis are only
//! scaled with positive factors ([`Lattice::scale_slice`]), moved across that axis
//! ([`Lattice::translate_slice`] with an offset that has no component along it), and spaced
//! with positive gaps ([`Lattice::distribute_slices`]), then the Jacobian determinant is
//! positive everywhere inside the lattice: the deformation never folds. (In the lattice's own
//! frame the Jacobian is then triangular: each coordinate across the axis is a positive-slope
//! function of its own local coordinate, and the coordinate along the axis is a Bernstein
//! polynomial with increasing control values.) This holds in exact arithmetic; in `f32` it
//! holds as long as the gaps are well above the rounding of the control points' coordinates,
//! which any body-shaped lattice satisfies (a lattice 10,000 times longer across than along,
//! far from the origin, may not). The seed's body
//! generator, "each slice at the previous one plus a random step", is `distribute_slices` with
//! random positive gaps.

use alloc::vec::Vec;

use glam::{Vec3, Vec3A};

use crate::error::FfdError;
use crate::lattice::{Axis, Lattice, check_coordinates};

impl Lattice {
    /// Number of slices along `axis` (its divisions + 1).
    #[must_use]
    pub fn slice_count(&self, axis: Axis) -> usize {
        self.divisions()[axis.index()] + 1
    }

    /// The `[i, j, k]` indices of the control points in one slice, in storage order.
    ///
    /// # Errors
    /// [`FfdError::SliceOutOfRange`] when `slice >= slice_count(axis)`.
    pub fn slice_indices(&self, axis: Axis, slice: usize) -> Result<Vec<[usize; 3]>, FfdError> {
        self.check_slice(axis, slice)?;
        let [l, m, n] = self.divisions();
        let mut out = Vec::new();
        for k in 0..=n {
            for j in 0..=m {
                for i in 0..=l {
                    let index = [i, j, k];
                    if index[axis.index()] == slice {
                        out.push(index);
                    }
                }
            }
        }
        Ok(out)
    }

    /// The centroid of one slice's control points.
    ///
    /// # Errors
    /// [`FfdError::SliceOutOfRange`] when `slice >= slice_count(axis)`.
    ///
    /// ```
    /// use creature_ffd::{glam::Vec3, Axis, Lattice};
    ///
    /// let lattice = Lattice::new(Vec3::ZERO, [Vec3::X, Vec3::Y, Vec3::Z * 10.0], [2, 2, 10])?;
    /// assert_eq!(lattice.slice_center(Axis::U, 3)?, Vec3::new(0.5, 0.5, 3.0));
    /// # Ok::<(), creature_ffd::FfdError>(())
    /// ```
    pub fn slice_center(&self, axis: Axis, slice: usize) -> Result<Vec3, FfdError> {
        let indices = self.slice_indices(axis, slice)?;
        let sum: Vec3 = indices
            .iter()
            .filter_map(|&index| self.control_point(index))
            .sum();
        Ok(sum / indices.len() as f32)
    }

    /// Scales one slice's control points about the slice's centroid, by `scale.x` along S,
    /// `scale.y` along T and `scale.z` along U (the lattice's own frame, so this works for
    /// oblique lattices too). For the body lattice, `scale_slice(Axis::U, k, (sx, sy, 1))`
    /// widens or narrows cross-section `k`.
    ///
    /// # Errors
    /// [`FfdError::SliceOutOfRange`], [`FfdError::NonFinite`] for a non-finite scale and
    /// [`FfdError::NotPositive`] for a factor at or below zero (which would crush or mirror the
    /// slice), and [`FfdError::CoordinateTooLarge`] when a scaled control point would lie
    /// beyond ±[`MAX_COORDINATE`](crate::MAX_COORDINATE). The lattice is unchanged on error.
    ///
    /// ```
    /// use creature_ffd::{glam::Vec3, Axis, Lattice};
    ///
    /// let mut lattice = Lattice::new(Vec3::ZERO, [Vec3::X, Vec3::Y, Vec3::Z], [2, 2, 2])?;
    /// lattice.scale_slice(Axis::U, 1, Vec3::new(2.0, 0.5, 1.0))?;
    /// assert_eq!(lattice.control_point([2, 2, 1]), Some(Vec3::new(1.5, 0.75, 0.5)));
    /// # Ok::<(), creature_ffd::FfdError>(())
    /// ```
    pub fn scale_slice(&mut self, axis: Axis, slice: usize, scale: Vec3) -> Result<(), FfdError> {
        self.check_slice(axis, slice)?;
        if !scale.is_finite() {
            return Err(FfdError::NonFinite {
                what: "scale",
                index: None,
            });
        }
        for (index, factor) in scale.to_array().into_iter().enumerate() {
            if !(factor > 0.0) {
                return Err(FfdError::NotPositive {
                    what: "scale",
                    index,
                    value: factor,
                });
            }
        }
        let center = self.slice_center(axis, slice)?;
        let axes = self.axes();
        let dual = *self.dual();
        self.update_slice(axis, slice, |p| {
            let d = Vec3A::from(p - center);
            center
                + axes[0] * (dual[0].dot(d) * scale.x)
                + axes[1] * (dual[1].dot(d) * scale.y)
                + axes[2] * (dual[2].dot(d) * scale.z)
        })
    }

    /// Moves one slice's control points by a world-space `offset`.
    ///
    /// # Errors
    /// [`FfdError::SliceOutOfRange`], [`FfdError::NonFinite`] for a non-finite offset, and
    /// [`FfdError::CoordinateTooLarge`] when a moved control point would lie beyond
    /// ±[`MAX_COORDINATE`](crate::MAX_COORDINATE). The lattice is unchanged on error.
    pub fn translate_slice(
        &mut self,
        axis: Axis,
        slice: usize,
        offset: Vec3,
    ) -> Result<(), FfdError> {
        self.check_slice(axis, slice)?;
        if !offset.is_finite() {
            return Err(FfdError::NonFinite {
                what: "offset",
                index: None,
            });
        }
        self.update_slice(axis, slice, |p| p + offset)
    }

    /// Spaces the slices along `axis`: slice 0 stays, and slice `q + 1` is moved along the axis
    /// so that its centroid lies `gaps[q]` world units past slice `q`'s (measured along the
    /// axis direction). With all gaps positive the slices stay in order and the deformation
    /// does not fold (see the module docs); the lattice's length along the axis becomes the sum
    /// of the gaps.
    ///
    /// # Errors
    /// [`FfdError::WrongLength`] unless `gaps.len()` equals the axis' divisions,
    /// [`FfdError::NonFinite`] / [`FfdError::NotPositive`] naming the first bad gap, and
    /// [`FfdError::CoordinateTooLarge`] when the gaps would move a control point beyond
    /// ±[`MAX_COORDINATE`](crate::MAX_COORDINATE). The lattice is unchanged on error.
    ///
    /// ```
    /// use creature_ffd::{glam::Vec3, Axis, Lattice};
    ///
    /// let mut body = Lattice::new(Vec3::ZERO, [Vec3::X, Vec3::Y, Vec3::Z * 4.0], [2, 2, 4])?;
    /// // The seed's rule: each slice at the previous one plus a random step.
    /// body.distribute_slices(Axis::U, &[0.5, 1.5, 1.0, 2.0])?;
    /// assert_eq!(body.slice_center(Axis::U, 4)?.z, 5.0);
    /// assert!(!body.folds(8));
    /// # Ok::<(), creature_ffd::FfdError>(())
    /// ```
    pub fn distribute_slices(&mut self, axis: Axis, gaps: &[f32]) -> Result<(), FfdError> {
        let expected = self.divisions()[axis.index()];
        if gaps.len() != expected {
            return Err(FfdError::WrongLength {
                what: "gaps",
                expected,
                found: gaps.len(),
            });
        }
        for (index, &gap) in gaps.iter().enumerate() {
            if !gap.is_finite() {
                return Err(FfdError::NonFinite {
                    what: "gap",
                    index: Some(index),
                });
            }
            if !(gap > 0.0) {
                return Err(FfdError::NotPositive {
                    what: "gap",
                    index,
                    value: gap,
                });
            }
        }
        let edge = self.axes()[axis.index()];
        let length = edge.length();
        let direction = edge / length;
        // Local coordinate along `axis`, times the edge length: distance along the axis.
        let along = |lattice: &Lattice, p: Vec3| lattice.local_coords(p)[axis.index()] * length;
        let start = along(self, self.slice_center(axis, 0)?);
        let mut target = start;
        // Every slice's new points first (a slice's centre depends on its own points only), so
        // that a point out of range leaves the whole lattice unchanged.
        let mut updates = Vec::new();
        for (q, &gap) in gaps.iter().enumerate() {
            target += gap;
            let slice = q + 1;
            let current = along(self, self.slice_center(axis, slice)?);
            let shift = direction * (target - current);
            updates.extend(self.slice_updates(axis, slice, |p| p + shift)?);
        }
        for (idx, index, p) in updates {
            self.write(idx, index, p);
        }
        Ok(())
    }

    fn check_slice(&self, axis: Axis, slice: usize) -> Result<(), FfdError> {
        let count = self.slice_count(axis);
        if slice < count {
            Ok(())
        } else {
            Err(FfdError::SliceOutOfRange {
                axis: axis.index(),
                slice,
                count,
            })
        }
    }

    /// Applies `f` to every control point of a slice; fails without writing anything if any
    /// result is non-finite or beyond ±[`MAX_COORDINATE`](crate::MAX_COORDINATE).
    fn update_slice(
        &mut self,
        axis: Axis,
        slice: usize,
        f: impl Fn(Vec3) -> Vec3,
    ) -> Result<(), FfdError> {
        for (idx, index, p) in self.slice_updates(axis, slice, f)? {
            self.write(idx, index, p);
        }
        Ok(())
    }

    /// A slice's control points after `f`, as `(storage index, index, point)`, each checked
    /// finite and within ±[`MAX_COORDINATE`](crate::MAX_COORDINATE); nothing is written.
    fn slice_updates(
        &self,
        axis: Axis,
        slice: usize,
        f: impl Fn(Vec3) -> Vec3,
    ) -> Result<Vec<(usize, [usize; 3], Vec3)>, FfdError> {
        let indices = self.slice_indices(axis, slice)?;
        let mut updates = Vec::with_capacity(indices.len());
        for index in indices {
            let Some(idx) = self.index_of(index) else {
                continue;
            };
            // The inputs are finite, so a non-finite result overflowed: too large as well.
            let p = f(self.control_points()[idx]);
            check_coordinates("control point", idx, p)?;
            updates.push((idx, index, p));
        }
        Ok(updates)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn body() -> Lattice {
        Lattice::new(Vec3::ZERO, [Vec3::X, Vec3::Y, Vec3::Z * 10.0], [2, 2, 10]).unwrap()
    }

    #[test]
    fn slices_have_the_right_points() {
        let lattice = body();
        assert_eq!(lattice.slice_count(Axis::U), 11);
        let indices = lattice.slice_indices(Axis::U, 4).unwrap();
        assert_eq!(indices.len(), 9);
        assert!(indices.iter().all(|index| index[2] == 4));
        assert_eq!(lattice.slice_indices(Axis::S, 0).unwrap().len(), 33);
        assert_eq!(
            lattice.slice_indices(Axis::U, 11),
            Err(FfdError::SliceOutOfRange {
                axis: 2,
                slice: 11,
                count: 11
            })
        );
    }

    #[test]
    fn scale_slice_rejects_bad_factors_and_leaves_the_lattice_alone() {
        let mut lattice = body();
        let before = lattice.clone();
        assert!(matches!(
            lattice.scale_slice(Axis::U, 2, Vec3::new(1.0, 0.0, 1.0)),
            Err(FfdError::NotPositive { index: 1, .. })
        ));
        assert!(lattice.scale_slice(Axis::U, 2, Vec3::NAN).is_err());
        assert_eq!(lattice, before);
    }

    #[test]
    fn scaling_a_slice_keeps_its_centre() {
        let mut lattice = body();
        let before = lattice.slice_center(Axis::U, 5).unwrap();
        lattice
            .scale_slice(Axis::U, 5, Vec3::new(1.7, 0.4, 3.0))
            .unwrap();
        let after = lattice.slice_center(Axis::U, 5).unwrap();
        assert!(before.abs_diff_eq(after, 1e-6));
        assert!(lattice.is_deformed());
    }

    #[test]
    fn translate_slice_moves_every_point() {
        let mut lattice = body();
        lattice.translate_slice(Axis::U, 0, Vec3::Y).unwrap();
        assert_eq!(
            lattice.control_point([1, 1, 0]),
            Some(Vec3::new(0.5, 1.5, 0.0))
        );
        assert!(lattice.translate_slice(Axis::U, 0, Vec3::INFINITY).is_err());
    }

    #[test]
    fn distribute_checks_the_gaps() {
        let mut lattice = body();
        assert_eq!(
            lattice.distribute_slices(Axis::U, &[1.0; 3]),
            Err(FfdError::WrongLength {
                what: "gaps",
                expected: 10,
                found: 3
            })
        );
        let mut gaps = [1.0; 10];
        gaps[4] = -0.5;
        assert!(matches!(
            lattice.distribute_slices(Axis::U, &gaps),
            Err(FfdError::NotPositive { index: 4, .. })
        ));
        gaps[4] = f32::NAN;
        assert!(matches!(
            lattice.distribute_slices(Axis::U, &gaps),
            Err(FfdError::NonFinite { index: Some(4), .. })
        ));
    }

    #[test]
    fn distribute_places_slices_cumulatively() {
        let mut lattice = body();
        let gaps = [0.5, 1.0, 1.5, 2.0, 0.5, 1.0, 1.5, 2.0, 0.5, 1.0];
        lattice.distribute_slices(Axis::U, &gaps).unwrap();
        let mut z = 0.0;
        for (q, gap) in gaps.iter().enumerate() {
            z += gap;
            let c = lattice.slice_center(Axis::U, q + 1).unwrap();
            assert!((c.z - z).abs() < 1e-5, "slice {} at {} not {z}", q + 1, c.z);
        }
        assert!(!lattice.folds(6));
    }

    /// Documents a limit of the no-fold reasoning: moving one interior slice of the 11-slice
    /// body slightly past its neighbour does not fold the deformation, because the degree-10
    /// Bernstein sum weighs many slices at once. Fold checks therefore test the Jacobian,
    /// never the slice order.
    #[test]
    fn interior_swap_can_be_smoothed_away() {
        let mut lattice = body();
        // Slices 5 and 6 trade places (z = 5 and z = 6).
        lattice.translate_slice(Axis::U, 5, Vec3::Z).unwrap();
        lattice.translate_slice(Axis::U, 6, -Vec3::Z).unwrap();
        assert!(!lattice.folds(32));
    }
}
