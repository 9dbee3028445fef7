//! Marching squares over a whole sampled grid.

use alloc::vec::Vec;

use glam::Vec2;

use crate::cell::{self, CORNERS};
use crate::{MarchError, MarchOptions, Ring, Saddle};

const NONE: u32 = u32::MAX;

/// The largest number of samples [`march_grid`] accepts (2³⁰).
pub const MAX_GRID_SAMPLES: usize = 1 << 30;

/// Every contour of a sampled grid at `iso`, with the default [`MarchOptions`].
///
/// `values` holds `width × height` samples row by row: sample `(x, y)` is
/// `values[y * width + x]` and sits at point `(x, y)` (x = column, y = row, y up). Values
/// `>= iso` are inside; NaN samples are outside, as is everything beyond the grid, so regions
/// touching the border are closed along it (through the border samples themselves). Crossings
/// are placed by linear interpolation along cell edges (at the midpoint when a sample is
/// infinite), kept at least 1/1000 of a cell from the samples so that a ring never passes
/// twice through one (a pinch where a sample lies a hair below `iso`). Saddle cells follow [`MarchOptions::saddle`]. One sweep over the cells, row by
/// row, computes each crossing once and links it to the next; beyond its output it keeps two
/// rows of flags and edge ids (memory O(width + crossings)).
///
/// Returns closed rings in grid coordinates: outer rings counter-clockwise, holes clockwise
/// with their parent set. An empty grid (width or height 0) gives no rings.
///
/// # Errors
///
/// [`MarchError::NonFinite`] for a NaN or infinite `iso`, [`MarchError::GridSize`] when
/// `values.len() != width * height`, [`MarchError::GridTooLarge`] above
/// [`MAX_GRID_SAMPLES`] samples (or when a very long, thin grid has more than 2³² cell
/// edges).
///
/// ```
/// use creature_march::march_grid;
///
/// // A 5×5 grid with a ring of inside samples around an outside centre: one outer ring with
/// // one hole.
/// #[rustfmt::skip]
/// let values = [
///     0.0, 0.0, 0.0, 0.0, 0.0,
///     0.0, 1.0, 1.0, 1.0, 0.0,
///     0.0, 1.0, 0.0, 1.0, 0.0,
///     0.0, 1.0, 1.0, 1.0, 0.0,
///     0.0, 0.0, 0.0, 0.0, 0.0,
/// ];
/// let rings = march_grid(&values, 5, 5, 0.5)?;
/// assert_eq!(rings.len(), 2);
/// let hole = rings.iter().find(|r| r.hole).expect("a hole");
/// assert!(hole.signed_area() < 0.0);
/// assert!(!rings[hole.parent.expect("a parent")].hole);
/// # Ok::<(), creature_march::MarchError>(())
/// ```
pub fn march_grid(
    values: &[f32],
    width: usize,
    height: usize,
    iso: f32,
) -> Result<Vec<Ring>, MarchError> {
    march_grid_with(values, width, height, iso, &MarchOptions::DEFAULT)
}

/// [`march_grid`] with explicit options. Uses [`MarchOptions::saddle`] (the centre value is
/// the mean of the four corners) and [`MarchOptions::weld`] (a fraction of one cell); the
/// trace-only options are ignored.
///
/// # Errors
///
/// As [`march_grid`], plus [`MarchError::OutOfRange`] for invalid options.
///
/// ```
/// use creature_march::{march_grid_with, MarchOptions, Saddle};
///
/// // A checkerboard saddle: split by the asymptotic decider (two rings), joined by the mean
/// // of the corners (one ring).
/// let values = [2.0, 0.0, 0.0, 0.55];
/// let split = march_grid_with(&values, 2, 2, 0.5, &MarchOptions::DEFAULT.with_saddle(Saddle::Asymptotic))?;
/// assert_eq!(split.len(), 2);
/// let joined = march_grid_with(&values, 2, 2, 0.5, &MarchOptions::DEFAULT)?;
/// assert_eq!(joined.len(), 1);
/// # Ok::<(), creature_march::MarchError>(())
/// ```
pub fn march_grid_with(
    values: &[f32],
    width: usize,
    height: usize,
    iso: f32,
    options: &MarchOptions,
) -> Result<Vec<Ring>, MarchError> {
    options.validate()?;
    if !iso.is_finite() {
        return Err(MarchError::NonFinite {
            what: "iso",
            index: 0,
        });
    }
    let too_large = MarchError::GridTooLarge { width, height };
    let expected = width
        .checked_mul(height)
        .filter(|&n| n <= MAX_GRID_SAMPLES)
        .ok_or(too_large.clone())?;
    if values.len() != expected {
        return Err(MarchError::GridSize {
            width,
            height,
            len: values.len(),
        });
    }
    if expected == 0 {
        return Ok(Vec::new());
    }
    // Edge numbers of the padded grid must fit in `u32` (below the `NONE` marker).
    let edges = (width + 1)
        .checked_mul(height + 2)
        .zip((width + 2).checked_mul(height + 1))
        .and_then(|(h, v)| h.checked_add(v));
    if edges.is_none_or(|e| e >= NONE as usize) {
        return Err(too_large);
    }
    let grid = Padded {
        values,
        width,
        height,
        iso,
    };
    Ok(grid.march(options))
}

/// The grid with a virtual border of outside nodes: padded node `(I, J)` is sample
/// `(I − 1, J − 1)`.
struct Padded<'a> {
    values: &'a [f32],
    width: usize,
    height: usize,
    iso: f32,
}

impl Padded<'_> {
    /// The sample at a padded node, `None` on the virtual border.
    fn value(&self, i: usize, j: usize) -> Option<f32> {
        if i == 0 || j == 0 || i > self.width || j > self.height {
            return None;
        }
        Some(self.values[(j - 1) * self.width + (i - 1)])
    }

    /// Which nodes of padded row `j` are inside, as 0 or 1 (the border is outside).
    fn inside_row(&self, j: usize, row: &mut [u8]) {
        row.fill(0);
        if j == 0 || j > self.height {
            return;
        }
        let start = (j - 1) * self.width;
        let samples = &self.values[start..start + self.width];
        for (flag, &v) in row[1..=self.width].iter_mut().zip(samples) {
            *flag = u8::from(cell::is_inside(v, self.iso));
        }
    }

    /// One sweep over the cell rows, bottom to top. Each crossed edge gets an id when first
    /// met (its point is computed then, once); each cell links the id of the edge a contour
    /// enters by to the id of the edge it leaves by. Only two rows of flags and edge ids are
    /// kept, so memory is O(width + crossings).
    fn march(&self, options: &MarchOptions) -> Vec<Ring> {
        let nx = self.width + 2;
        let mut lo = alloc::vec![0u8; nx];
        let mut hi = alloc::vec![0u8; nx];
        // Ids of the horizontal edges along the cells' bottom and top, per cell column, and of
        // the vertical edges of the current cell row, per node column.
        let mut bottom = alloc::vec![NONE; nx - 1];
        let mut top = alloc::vec![NONE; nx - 1];
        let mut sides = alloc::vec![NONE; nx];
        let mut points: Vec<Vec2> = Vec::new();
        let mut next: Vec<u32> = Vec::new();
        for j in 0..=self.height {
            self.inside_row(j + 1, &mut hi);
            for i in 0..nx - 1 {
                let (a, b, c, d) = (lo[i], lo[i + 1], hi[i + 1], hi[i]);
                let mask = a | b << 1 | c << 2 | d << 3;
                if mask == 0 || mask == 15 {
                    top[i] = NONE;
                    sides[i + 1] = NONE;
                    continue;
                }
                // The cell's top and right edges are new; its bottom and left ones were met
                // by the cells below and to the left.
                top[i] = if c != d {
                    new_crossing(
                        &mut points,
                        &mut next,
                        self.point((i, j + 1), (i + 1, j + 1), d == 1),
                    )
                } else {
                    NONE
                };
                sides[i + 1] = if b != c {
                    new_crossing(
                        &mut points,
                        &mut next,
                        self.point((i + 1, j), (i + 1, j + 1), b == 1),
                    )
                } else {
                    NONE
                };
                let edges = [bottom[i], sides[i + 1], top[i], sides[i]];
                for k in 0..4 {
                    let from = mask & (1 << k) != 0;
                    let to = mask & (1 << ((k + 1) & 3)) != 0;
                    if from && !to {
                        // Edge `k` runs from an inside corner to an outside one: it is crossed,
                        // so it has an id, and so has the exit edge.
                        let exit = cell::exit_edge(mask, k, || self.joined(i, j, options.saddle));
                        debug_assert!(edges[k] != NONE && edges[exit] != NONE, "{mask:04b} {k}");
                        next[edges[k] as usize] = edges[exit];
                    }
                }
            }
            core::mem::swap(&mut lo, &mut hi);
            core::mem::swap(&mut bottom, &mut top);
        }
        // Every crossed edge is entered by exactly one cell and left by one: the links form
        // closed cycles.
        let mut raw: Vec<Vec<Vec2>> = Vec::new();
        for start in 0..next.len() {
            if next[start] == NONE {
                continue;
            }
            let mut ring = Vec::new();
            let mut current = start;
            loop {
                ring.push(points[current]);
                let following = next[current];
                next[current] = NONE;
                if following == NONE {
                    break;
                }
                current = following as usize;
                if current == start {
                    break;
                }
            }
            raw.push(ring);
        }
        crate::ring::finish(raw, options.weld)
    }

    fn joined(&self, i: usize, j: usize, saddle: Saddle) -> bool {
        let mut values = [f32::NAN; 4];
        for (v, (di, dj)) in values.iter_mut().zip(CORNERS) {
            *v = self
                .value(i + di as usize, j + dj as usize)
                .unwrap_or(f32::NEG_INFINITY);
        }
        match saddle {
            Saddle::Centre => cell::mean_joined(values, self.iso),
            Saddle::Asymptotic => cell::asymptotic_joined(values, self.iso),
        }
    }

    /// The crossing on the edge between padded nodes `a` and `b`, in sample coordinates.
    fn point(&self, a: (usize, usize), b: (usize, usize), a_inside: bool) -> Vec2 {
        let (p_in, p_out) = if a_inside { (a, b) } else { (b, a) };
        let at = |(i, j): (usize, usize)| Vec2::new(i as f32 - 1.0, j as f32 - 1.0);
        // The inside node is a sample, never on the virtual border.
        let v_in = self.values[(p_in.1 - 1) * self.width + (p_in.0 - 1)];
        match self.value(p_out.0, p_out.1) {
            // Beyond the border: the ring runs through the border sample itself.
            None => at(p_in),
            Some(v_out) => {
                // Never on a sample node: two crossings beside an outside node would meet there
                // and pinch the ring (a sample a hair below the iso-level, a notch at the
                // border).
                let t = cell::crossing(v_in, v_out, self.iso).clamp(NODE_GAP, 1.0 - NODE_GAP);
                at(p_in) + (at(p_out) - at(p_in)) * t
            }
        }
    }
}

/// The nearest a crossing comes to a sample node, as a fraction of the cell.
const NODE_GAP: f32 = 1e-3;

/// Records a crossing point and returns its id.
fn new_crossing(points: &mut Vec<Vec2>, next: &mut Vec<u32>, p: Vec2) -> u32 {
    let id = points.len() as u32;
    points.push(p);
    next.push(NONE);
    id
}

#[cfg(test)]
mod tests {
    use alloc::vec;

    use super::*;

    #[test]
    fn single_inside_sample_gives_a_diamond() {
        let values = [0.0, 0.0, 0.0, 0.0, 2.0, 0.0, 0.0, 0.0, 0.0];
        let rings = march_grid(&values, 3, 3, 1.0).unwrap();
        assert_eq!(rings.len(), 1);
        let r = &rings[0];
        assert_eq!(r.points.len(), 4);
        assert!(!r.hole);
        assert!((r.signed_area() - 0.5).abs() < 1e-6);
        for p in &r.points {
            assert!((p.distance(Vec2::ONE) - 0.5).abs() < 1e-6);
        }
    }

    #[test]
    fn border_regions_close_along_the_border() {
        let rings = march_grid(&[1.0; 6], 3, 2, 0.5).unwrap();
        assert_eq!(rings.len(), 1);
        assert!((rings[0].signed_area() - 2.0).abs() < 1e-6);
        let one = march_grid(&[1.0], 1, 1, 0.5).unwrap();
        assert!(one.is_empty(), "a single inside sample has no area");
    }

    #[test]
    fn nan_is_outside() {
        let values = [2.0, 2.0, 2.0, 2.0, f32::NAN, 2.0, 2.0, 2.0, 2.0];
        let rings = march_grid(&values, 3, 3, 1.0).unwrap();
        assert_eq!(rings.len(), 2);
        assert_eq!(rings.iter().filter(|r| r.hole).count(), 1);
    }

    #[test]
    fn bad_input_is_an_error() {
        assert!(matches!(
            march_grid(&[0.0; 5], 2, 3, 0.5),
            Err(MarchError::GridSize { len: 5, .. })
        ));
        assert!(matches!(
            march_grid(&[0.0; 4], 2, 2, f32::NAN),
            Err(MarchError::NonFinite { what: "iso", .. })
        ));
        assert!(matches!(
            march_grid(&[], usize::MAX, 2, 0.5),
            Err(MarchError::GridTooLarge { .. })
        ));
        assert_eq!(march_grid(&[], 0, 7, 0.5), Ok(vec![]));
    }
}
