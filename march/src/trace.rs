//! Contour following: sample the field lazily, only along (and, for holes, inside) outlines.
//!
//! [`trace_field`] checks its input and drives a [`Tracer`] through the three steps its docs
//! list, one file each: [`hints`] (step 1), [`walk`] (step 2) and [`holes`] (step 3). Beneath
//! them, [`sample`] takes node samples on first use into the tile store of [`nodes`] (tiles
//! found through the hash table of [`table`]), and [`rings`] keeps the traced rings with
//! their crossings, for the exact enclosure tests.

mod hints;
mod holes;
mod nodes;
mod rings;
mod sample;
mod table;
mod walk;

use alloc::vec::Vec;

use glam::Vec2;

use crate::options::MAX_GRID_COORDINATE;
use crate::tile::TileField;
use crate::{MarchError, MarchOptions, Ring};

use nodes::Nodes;
use rings::Traced;
use table::Table;

/// Every component of `field ≥ iso` that contains a hint, outlined by contour-following
/// marching squares, with the default [`MarchOptions`].
///
/// The field is sampled on the square grid of nodes `step × (i, j)` for integers `i, j`
/// (anchored at the origin), and only where needed, each node once:
///
/// 1. For each hint in order that is not already inside a traced component (judged exactly,
///    without sampling, at the grid node nearest to it: the innermost traced ring enclosing
///    that node is an outer ring) and is inside (`field(hint) >= iso`), take the nearest
///    inside node of the cell containing it and walk up its column to the first crossing, as
///    the seed does from its top-most ball.
/// 2. Follow the contour cell by cell from that crossing until it closes (the inside on the
///    left); a saddle cell is settled by [`MarchOptions::saddle`] (by default by sampling the
///    cell centre). If the ring is a hole of the hint's component, keep walking up until its
///    outer ring is found.
/// 3. With [`MarchOptions::holes`] (the default), scan the nodes each new outer ring encloses
///    and trace every hole (and island in a hole) they reveal.
///
/// Samples are cached in dense 8 × 8 tiles of nodes (a small direct-mapped cache, then a hash
/// table, finds the tiles), so the field is called once per node and once per saddle centre,
/// plus once per hint and [`MarchOptions::refine_steps`] times per ring point. For a field that can fill a whole tile
/// in one cheap call, see [`trace_field`] and [`TileField`](crate::TileField).
///
/// So unlike the seed, which traces only the component above its top-most ball, every
/// component holding a hint is found: pass every ball centre as a hint. Features smaller than a
/// cell (no inside node in the hint's cell) are not resolved, as in [`march_grid`](crate::march_grid).
/// NaN samples are outside. The rings are those [`march_grid`](crate::march_grid) gives on the
/// same samples (in world units): outer rings counter-clockwise, holes clockwise with their
/// parent set, near-duplicate points welded.
///
/// # Errors
///
/// [`MarchError::NonFinite`] for a non-finite `iso`, `step` or hint,
/// [`MarchError::NotPositive`] for `step <= 0`, [`MarchError::TooFar`] for a hint more than
/// [`MAX_GRID_COORDINATE`] steps from the origin, and [`MarchError::BudgetExceeded`] when the
/// walks and traces visit more than [`MarchOptions::max_cells`] cells (for instance when the
/// field stays inside all the way up from a hint): it never loops forever.
///
/// ```
/// use creature_march::{glam::Vec2, trace};
///
/// // Two separate discs of radius 10: the seed would outline only one of them.
/// let centres = [Vec2::new(-30.0, 0.0), Vec2::new(30.0, 5.0)];
/// let field = |p: Vec2| {
///     centres.iter().map(|c| 100.0 / (1.0 + p.distance_squared(*c))).sum::<f32>()
/// };
/// // field = 1 at a distance of about 10 from a lone centre.
/// let rings = trace(field, &centres, 1.0, 1.0)?;
/// assert_eq!(rings.len(), 2);
/// for (ring, centre) in rings.iter().zip(centres) {
///     assert!(!ring.hole && ring.signed_area() > 0.0);
///     assert!(ring.contains(centre));
/// }
/// # Ok::<(), creature_march::MarchError>(())
/// ```
pub fn trace(
    field: impl Fn(Vec2) -> f32,
    hints: &[Vec2],
    step: f32,
    iso: f32,
) -> Result<Vec<Ring>, MarchError> {
    trace_with(field, hints, step, iso, &MarchOptions::DEFAULT)
}

/// [`trace`] with explicit options.
///
/// # Errors
///
/// As [`trace`], plus [`MarchError::OutOfRange`] for invalid options.
///
/// ```
/// use creature_march::{glam::Vec2, trace_with, MarchOptions};
///
/// let disc = |p: Vec2| 1.0 - p.length() / 10.0; // inside within radius 10
/// let coarse = trace_with(disc, &[Vec2::ZERO], 2.5, 0.0, &MarchOptions::DEFAULT)?;
/// let refined = trace_with(
///     disc,
///     &[Vec2::ZERO],
///     2.5,
///     0.0,
///     &MarchOptions::DEFAULT.with_refine_steps(4),
/// )?;
/// // Refined crossings sit on the circle itself.
/// let worst = |rings: &[creature_march::Ring]| {
///     rings[0].points.iter().map(|p| (p.length() - 10.0).abs()).fold(0.0, f32::max)
/// };
/// assert!(worst(&refined) < 1e-4);
/// assert!(worst(&refined) <= worst(&coarse));
/// # Ok::<(), creature_march::MarchError>(())
/// ```
pub fn trace_with(
    field: impl Fn(Vec2) -> f32,
    hints: &[Vec2],
    step: f32,
    iso: f32,
    options: &MarchOptions,
) -> Result<Vec<Ring>, MarchError> {
    trace_field(&field, hints, step, iso, options)
}

/// [`trace_with`] on any [`TileField`]: a field that can fill a tile of `8 × 8` grid nodes
/// in one call ([`TileField::sample_tile`], used when [`TileField::prefers_tiles`] is true)
/// has each tile the trace touches filled that way, instead of node by node.
///
/// Sampling by tiles pays off where most of a tile's nodes are needed — the hole scan reads
/// every node an outer ring encloses — and costs extra samples along the outline, which
/// needs only the nodes near it. For a field whose `sample_tile` is
/// [`TileField`]'s default (64 [`value`](TileField::value) calls), `prefers_tiles` should
/// stay `false`; even so, the rings are the same, bit for bit, either way, since every node's
/// sample is the same. For a field whose `sample_tile` rounds differently from its `value`,
/// the rings are those of its tile samples.
///
/// Closures are `TileField`s (point by point): `trace_with(f, ..)` is
/// `trace_field(&f, ..)`.
///
/// # Errors
///
/// As [`trace_with`].
///
/// ```
/// use creature_march::{glam::Vec2, trace_field, MarchOptions, TileField, TILE_NODES};
///
/// /// A lookup into a pre-sampled image of 64 × 64 nodes (zero outside it), which fills a
/// /// tile by copying rows.
/// struct Image(Vec<f32>);
///
/// impl TileField for Image {
///     fn value(&self, p: Vec2) -> f32 {
///         // Between nodes: the nearest node (enough for hints and saddle centres).
///         let (x, y) = (p.x.round() as i64, p.y.round() as i64);
///         if (0..64).contains(&x) && (0..64).contains(&y) {
///             self.0[(y * 64 + x) as usize]
///         } else {
///             0.0
///         }
///     }
///     fn prefers_tiles(&self) -> bool {
///         true
///     }
///     fn sample_tile(&self, [i, j]: [i32; 2], _step: f32, out: &mut [f32; TILE_NODES]) {
///         for (row, samples) in out.chunks_exact_mut(8).enumerate() {
///             for (col, sample) in samples.iter_mut().enumerate() {
///                 let (x, y) = (i + col as i32, j + row as i32);
///                 *sample = if (0..64).contains(&x) && (0..64).contains(&y) {
///                     self.0[(y * 64 + x) as usize]
///                 } else {
///                     0.0
///                 };
///             }
///         }
///     }
/// }
///
/// // A disc of radius 20 around node (32, 32).
/// let image = Image(
///     (0..64 * 64)
///         .map(|n| 1.0 - Vec2::new((n % 64) as f32, (n / 64) as f32).distance(Vec2::splat(32.0)) / 20.0)
///         .collect(),
/// );
/// let rings = trace_field(&image, &[Vec2::splat(32.0)], 1.0, 0.0, &MarchOptions::DEFAULT)?;
/// assert_eq!(rings.len(), 1);
/// assert!((rings[0].signed_area() - core::f32::consts::PI * 400.0).abs() < 10.0);
/// # Ok::<(), creature_march::MarchError>(())
/// ```
pub fn trace_field<F: TileField + ?Sized>(
    field: &F,
    hints: &[Vec2],
    step: f32,
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
    if !step.is_finite() {
        return Err(MarchError::NonFinite {
            what: "step",
            index: 0,
        });
    }
    if !(step > 0.0) {
        return Err(MarchError::NotPositive {
            what: "step",
            value: step,
        });
    }
    for (index, h) in hints.iter().enumerate() {
        if !h.is_finite() {
            return Err(MarchError::NonFinite {
                what: "hint",
                index,
            });
        }
        let steps = (*h / step).abs().max_element();
        if !(steps <= MAX_GRID_COORDINATE) {
            return Err(MarchError::TooFar {
                index,
                steps,
                max: MAX_GRID_COORDINATE,
            });
        }
    }
    let mut tracer = Tracer {
        field,
        tiled: field.prefers_tiles(),
        step,
        iso,
        options,
        nodes: Nodes::new(),
        ring_of_edge: None,
        centres: Table::with_slots(16),
        cells: 0,
        rings: Vec::new(),
        scanned: 0,
    };
    for (index, &hint) in hints.iter().enumerate() {
        tracer.outline_hint(index, hint)?;
        if options.holes {
            tracer.scan_pending()?;
        }
    }
    walk::unpinch_across(&mut tracer.rings);
    let raw = tracer.rings.into_iter().map(|r| (r.points, Some(r.area)));
    let weld = options.weld * step;
    Ok(crate::ring::finish_with_areas(raw, weld))
}

/// The state of one trace: the field and its parameters, the node samples taken so far, the
/// rings traced so far, and the budget spent.
struct Tracer<'a, F: ?Sized> {
    field: &'a F,
    /// Fill whole tiles with [`TileField::sample_tile`].
    tiled: bool,
    step: f32,
    iso: f32,
    options: &'a MarchOptions,
    /// Node samples, and which vertical edges rings cross, in tiles.
    nodes: Nodes,
    /// The ring crossing each vertical grid edge crossed so far, keyed by the edge's lower
    /// node: built on first use by [`Tracer::crossing_ring`] (most calls never need it).
    ring_of_edge: Option<Table<u32>>,
    /// Saddle cell centre samples, keyed by cell.
    centres: Table<f32>,
    /// Cells (and scanned nodes) counted against [`MarchOptions::max_cells`] so far.
    cells: usize,
    rings: Vec<Traced>,
    /// Rings before this index have had their hole scan (or need none).
    scanned: usize,
}

impl<F: TileField + ?Sized> Tracer<'_, F> {
    /// Counts `nodes` a hole scan passes against the budget: the same total as one by one, so
    /// the same outcome (the count only grows, and every budget error of a scan is the same).
    fn count_scanned(&mut self, nodes: usize) -> Result<(), MarchError> {
        self.cells += nodes;
        if self.cells > self.options.max_cells {
            return Err(MarchError::BudgetExceeded {
                hint: usize::MAX,
                cells: self.options.max_cells,
            });
        }
        Ok(())
    }

    /// Counts one cell of hint `hint`'s walk up its column against the budget.
    fn tick(&mut self, hint: usize) -> Result<(), MarchError> {
        self.cells += 1;
        if self.cells > self.options.max_cells {
            return Err(MarchError::BudgetExceeded {
                hint,
                cells: self.cells - 1,
            });
        }
        Ok(())
    }

    /// The budget error, once the cells of a ring run over it.
    fn out_of_budget(&mut self, hint: usize) -> MarchError {
        self.cells = self.options.max_cells + 1;
        MarchError::BudgetExceeded {
            hint,
            cells: self.options.max_cells,
        }
    }
}

/// End-to-end tests through the public functions; the unit tests of the parts live beside
/// them in `trace/`.
#[cfg(test)]
mod tests {
    use super::*;
    use crate::cell;
    use crate::tile::{TILE_NODES, node_point};
    use nodes::TILE_SHIFT;

    fn disc(p: Vec2) -> f32 {
        1.0 - p.length() / 10.0
    }

    #[test]
    fn refinement_puts_points_on_the_iso_line() {
        let worst = |steps| {
            let options = MarchOptions::DEFAULT.with_refine_steps(steps);
            let rings = trace_with(disc, &[Vec2::ZERO], 2.5, 0.0, &options).unwrap();
            rings[0]
                .points
                .iter()
                .map(|p| (p.length() - 10.0).abs())
                .fold(0.0, f32::max)
        };
        assert!(worst(0) > 1e-2);
        assert!(worst(4) < 1e-5);
    }

    #[test]
    fn regression_refinement_with_a_node_on_the_iso_line() {
        // Node (10, 0) lies exactly on the circle: refinement must not bisect away from it.
        let options = MarchOptions::DEFAULT.with_refine_steps(1);
        let rings = trace_with(disc, &[Vec2::ZERO], 2.5, 0.0, &options).unwrap();
        assert!(
            rings[0]
                .points
                .iter()
                .all(|p| (p.length() - 10.0).abs() < 0.01)
        );
    }

    #[test]
    fn hints_outside_or_covered_start_nothing() {
        let rings = trace(disc, &[Vec2::new(50.0, 0.0)], 1.0, 0.0).unwrap();
        assert!(rings.is_empty());
        let rings = trace(disc, &[Vec2::ZERO, Vec2::new(3.0, 2.0)], 1.0, 0.0).unwrap();
        assert_eq!(rings.len(), 1);
    }

    #[test]
    fn an_unbounded_field_exhausts_the_budget() {
        let half_plane = |p: Vec2| p.x;
        let options = MarchOptions::DEFAULT.with_max_cells(1000);
        assert_eq!(
            trace_with(half_plane, &[Vec2::new(5.0, 0.0)], 1.0, 0.0, &options),
            Err(MarchError::BudgetExceeded {
                hint: 0,
                cells: 1000
            })
        );
    }

    #[test]
    fn every_node_is_sampled_once() {
        use alloc::collections::BTreeSet;
        use core::cell::RefCell;
        // An annulus (a hole to scan) and a disc, across negative and positive coordinates.
        let seen = RefCell::new((BTreeSet::new(), 0usize));
        let field = |p: Vec2| {
            let mut s = seen.borrow_mut();
            s.0.insert((p.x.to_bits(), p.y.to_bits()));
            s.1 += 1;
            let ring = (p.length() - 10.0).min(25.0 - p.length());
            let disc = 8.0 - p.distance(Vec2::new(60.0, -20.0));
            ring.max(disc)
        };
        let hints = [Vec2::new(-17.3, 0.1), Vec2::new(60.1, -19.9)];
        let rings = trace(field, &hints, 1.3, 0.0).unwrap();
        assert_eq!(rings.len(), 3);
        assert_eq!(rings.iter().filter(|r| r.hole).count(), 1);
        let (distinct, calls) = &*seen.borrow();
        assert_eq!(distinct.len(), *calls, "a point was sampled twice");
    }

    /// A point-by-point field read tile by tile, counting its calls.
    struct Tiled<F> {
        field: F,
        tiles: core::cell::RefCell<Vec<[i32; 2]>>,
        values: core::cell::Cell<usize>,
    }

    impl<F: Fn(Vec2) -> f32> TileField for Tiled<F> {
        fn value(&self, p: Vec2) -> f32 {
            self.values.set(self.values.get() + 1);
            (self.field)(p)
        }
        fn prefers_tiles(&self) -> bool {
            true
        }
    }

    fn tiled<F>(field: F) -> Tiled<F> {
        Tiled {
            field,
            tiles: core::cell::RefCell::new(Vec::new()),
            values: core::cell::Cell::new(0),
        }
    }

    impl<F: Fn(Vec2) -> f32> Tiled<F> {
        fn count(&self, first: [i32; 2]) {
            self.tiles.borrow_mut().push(first);
        }
    }

    /// The same, but recording each tile it is asked for.
    struct Recording<F>(Tiled<F>);

    impl<F: Fn(Vec2) -> f32> TileField for Recording<F> {
        fn value(&self, p: Vec2) -> f32 {
            self.0.value(p)
        }
        fn prefers_tiles(&self) -> bool {
            true
        }
        fn sample_tile(&self, first: [i32; 2], step: f32, out: &mut [f32; TILE_NODES]) {
            self.0.count(first);
            // The default, through `value`.
            for (n, v) in out.iter_mut().enumerate() {
                let node = [first[0] + (n % 8) as i32, first[1] + (n / 8) as i32];
                *v = self.0.value(node_point(node, step));
            }
        }
    }

    fn annulus_and_disc(p: Vec2) -> f32 {
        let ring = (p.length() - 10.0).min(25.0 - p.length());
        let disc = 8.0 - p.distance(Vec2::new(60.0, -20.0));
        ring.max(disc)
    }

    #[test]
    fn tiles_are_filled_once_each_aligned_and_give_the_same_rings() {
        let hints = [Vec2::new(-17.3, 0.1), Vec2::new(60.1, -19.9)];
        let expected = trace(annulus_and_disc, &hints, 1.3, 0.0).unwrap();
        let field = Recording(tiled(annulus_and_disc));
        let rings = trace_field(&field, &hints, 1.3, 0.0, &MarchOptions::DEFAULT).unwrap();
        assert_eq!(rings, expected);
        let tiles = field.0.tiles.borrow();
        assert!(tiles.len() > 10);
        let mut sorted = tiles.clone();
        sorted.sort_unstable();
        sorted.dedup();
        assert_eq!(sorted.len(), tiles.len(), "a tile was filled twice");
        assert!(tiles.iter().all(|t| t[0] % 8 == 0 && t[1] % 8 == 0));
        assert!(tiles.iter().any(|t| t[0] < 0) && tiles.iter().any(|t| t[1] < 0));
        // Point samples: 64 per tile plus one per hint (no saddles, no refinement here).
        assert_eq!(field.0.values.get(), 64 * tiles.len() + hints.len());
    }

    /// A wide annulus (inner radius 10, outer 60, a disc beside it) whose tiles prove
    /// themselves inside from the range of `|p|` over the tile, and record what they prove.
    struct Proving {
        recording: Recording<fn(Vec2) -> f32>,
        proven: core::cell::RefCell<Vec<[i32; 2]>>,
    }

    fn wide_annulus(p: Vec2) -> f32 {
        (p.length() - 10.0).min(60.0 - p.length())
    }

    /// Whether [`wide_annulus`] is above `iso` on the whole tile, with a margin for rounding.
    fn wide_annulus_holds(first: [i32; 2], step: f32, iso: f32) -> bool {
        let lo = node_point(first, step);
        let hi = node_point([first[0] + 7, first[1] + 7], step);
        let nearest = Vec2::ZERO.clamp(lo, hi).length();
        let farthest = lo.abs().max(hi.abs()).length();
        (nearest - 10.0).min(60.0 - farthest) > iso + 1e-3
    }

    impl TileField for Proving {
        fn value(&self, p: Vec2) -> f32 {
            self.recording.value(p)
        }
        fn prefers_tiles(&self) -> bool {
            true
        }
        fn sample_tile(&self, first: [i32; 2], step: f32, out: &mut [f32; TILE_NODES]) {
            self.recording.sample_tile(first, step, out);
        }
        fn tile_inside(&self, first: [i32; 2], step: f32, iso: f32) -> bool {
            let inside = wide_annulus_holds(first, step, iso);
            if inside {
                self.proven.borrow_mut().push(first);
            }
            inside
        }
    }

    #[test]
    fn tiles_proven_inside_are_not_sampled_and_change_nothing() {
        let hints = [Vec2::new(-35.3, 0.1), Vec2::new(0.2, 40.1)];
        let expected = trace(wide_annulus, &hints, 1.3, 0.0).unwrap();
        let field = Proving {
            recording: Recording(tiled(wide_annulus as fn(Vec2) -> f32)),
            proven: core::cell::RefCell::new(Vec::new()),
        };
        let rings = trace_field(&field, &hints, 1.3, 0.0, &MarchOptions::DEFAULT).unwrap();
        assert_eq!(rings, expected, "the same rings, bit for bit");
        assert_eq!(rings.len(), 2);
        assert_eq!(rings.iter().filter(|r| r.hole).count(), 1);
        let filled = field.recording.0.tiles.borrow();
        let proven = field.proven.borrow();
        // The hole scan crosses the band: many of its tiles need no samples.
        assert!(proven.len() > 10, "{}", proven.len());
        let mut all: Vec<[i32; 2]> = filled.iter().chain(proven.iter()).copied().collect();
        all.sort_unstable();
        all.dedup();
        // A tile proven inside is filled later only when a sample of it is needed (for a
        // crossing), never twice.
        assert!(all.len() > filled.len());
        let mut sorted = filled.clone();
        sorted.sort_unstable();
        sorted.dedup();
        assert_eq!(sorted.len(), filled.len(), "a tile was filled twice");
        // Without proofs, every one of them is filled.
        let plain = Recording(tiled(wide_annulus as fn(Vec2) -> f32));
        let again = trace_field(&plain, &hints, 1.3, 0.0, &MarchOptions::DEFAULT).unwrap();
        assert_eq!(again, expected);
        assert_eq!(plain.0.tiles.borrow().len(), all.len());
    }

    /// The hole scan fills a new tile lying just above a tile holding an outside node
    /// without asking for a proof first (the field dips below the level right there), and
    /// asks about the others: the rings are the same either way.
    #[test]
    fn scan_fills_tiles_above_outside_nodes_without_asking() {
        /// Tiles filled (`None`) and asked about (`Some(answer)`), in order.
        struct Logging(core::cell::RefCell<Vec<([i32; 2], Option<bool>)>>);
        impl TileField for Logging {
            fn value(&self, p: Vec2) -> f32 {
                wide_annulus(p)
            }
            fn prefers_tiles(&self) -> bool {
                true
            }
            fn sample_tile(&self, first: [i32; 2], step: f32, out: &mut [f32; TILE_NODES]) {
                self.0.borrow_mut().push((first, None));
                for (n, v) in out.iter_mut().enumerate() {
                    let node = [first[0] + (n % 8) as i32, first[1] + (n / 8) as i32];
                    *v = wide_annulus(node_point(node, step));
                }
            }
            fn tile_inside(&self, first: [i32; 2], step: f32, iso: f32) -> bool {
                let inside = wide_annulus_holds(first, step, iso);
                self.0.borrow_mut().push((first, Some(inside)));
                inside
            }
        }
        let (step, iso) = (1.3, 0.0);
        let hints = [Vec2::new(-35.3, 0.1), Vec2::new(0.2, 40.1)];
        let expected = trace(wide_annulus, &hints, step, iso).unwrap();
        let field = Logging(core::cell::RefCell::new(Vec::new()));
        let rings = trace_field(&field, &hints, step, iso, &MarchOptions::DEFAULT).unwrap();
        assert_eq!(rings, expected, "the same rings, bit for bit");
        let log = field.0.borrow();
        let holds_outside = |first: [i32; 2]| {
            (0..TILE_NODES).any(|n| {
                let node = [first[0] + (n % 8) as i32, first[1] + (n / 8) as i32];
                !cell::is_inside(wide_annulus(node_point(node, step)), iso)
            })
        };
        // Replayed: which tiles were filled before each event.
        let mut filled: Vec<[i32; 2]> = Vec::new();
        let (mut asked, mut filled_unasked) = (0, 0);
        for (n, &(first, answer)) in log.iter().enumerate() {
            let below = [first[0], first[1] - (1 << TILE_SHIFT)];
            let over_outside = filled.contains(&below) && holds_outside(below);
            match answer {
                Some(_) => {
                    asked += 1;
                    // The hint walks ask on their way up from a hint; the scan, after every
                    // ring of a hint is traced, never over such a tile.
                    let scanning = log[..n].iter().any(|e| e.1.is_none());
                    assert!(!(scanning && over_outside), "asked about {first:?}");
                }
                None => {
                    let was_asked = log[..n].iter().any(|e| e.0 == first);
                    filled_unasked += usize::from(over_outside && !was_asked);
                    filled.push(first);
                }
            }
        }
        assert!(asked > 10, "{asked}");
        assert!(filled_unasked > 0, "no tile was filled without asking");
    }

    #[test]
    fn the_budget_runs_out_alike_point_by_point_and_by_tiles() {
        // Every budget from far too small to enough, including ones that run out in the
        // middle of the hole scan (which counts a tile's nodes at once when tiled).
        let hints = [Vec2::new(-17.3, 0.1), Vec2::new(60.1, -19.9)];
        let field = tiled(annulus_and_disc);
        let mut outcomes = (0, 0);
        for max_cells in (1..3000).step_by(7) {
            let options = MarchOptions::DEFAULT.with_max_cells(max_cells);
            let by_nodes = trace_with(annulus_and_disc, &hints, 1.3, 0.0, &options);
            let by_tiles = trace_field(&field, &hints, 1.3, 0.0, &options);
            assert_eq!(by_nodes, by_tiles, "max_cells {max_cells}");
            if by_nodes.is_ok() {
                outcomes.0 += 1;
            } else {
                outcomes.1 += 1;
            }
        }
        assert!(outcomes.0 > 0 && outcomes.1 > 0, "{outcomes:?}");
    }

    #[test]
    fn point_by_point_fields_never_fill_tiles() {
        let field = tiled(annulus_and_disc);
        // `Tiled` prefers tiles; a closure does not.
        assert!(field.prefers_tiles());
        assert!(!TileField::prefers_tiles(&annulus_and_disc));
        let hints = [Vec2::new(-17.3, 0.1)];
        let by_tiles = trace_field(&field, &hints, 1.3, 0.0, &MarchOptions::DEFAULT).unwrap();
        let by_nodes =
            trace_field(&annulus_and_disc, &hints, 1.3, 0.0, &MarchOptions::DEFAULT).unwrap();
        assert_eq!(by_tiles, by_nodes);
    }

    #[test]
    fn nan_tile_samples_are_outside() {
        // A disc whose tiles report NaN everywhere outside radius 10 (and on a stripe inside).
        let field = Recording(tiled(|p: Vec2| {
            if p.length() > 10.0 || (p.x > 2.0 && p.x < 3.0) {
                f32::NAN
            } else {
                1.0
            }
        }));
        let rings = trace_field(
            &field,
            &[Vec2::new(-5.0, 0.0)],
            0.5,
            0.5,
            &MarchOptions::DEFAULT,
        )
        .unwrap();
        assert!(!rings.is_empty());
        assert!(rings.iter().all(|r| r.points.iter().all(|p| p.is_finite())));
        // The stripe cuts the disc: the hint's component stays left of it.
        assert!(rings[0].points.iter().all(|p| p.x <= 3.0));
    }
}
