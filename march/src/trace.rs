//! Contour following: sample the field lazily, only along (and, for holes, inside) outlines.

use alloc::vec::Vec;

use glam::Vec2;

use crate::cell::{self, CORNERS};
use crate::options::MAX_GRID_COORDINATE;
use crate::tile::{TILE_NODES, TileField, node_point};
use crate::{MarchError, MarchOptions, Ring, Saddle};

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
    let raw = tracer.rings.into_iter().map(|r| (r.points, Some(r.area)));
    let weld = options.weld * step;
    Ok(crate::ring::finish_with_areas(raw, weld))
}

/// A ring while tracing.
struct Traced {
    /// Points in world units.
    points: Vec<Vec2>,
    /// The vertical grid edges it crosses, as `(column, lower row)`, sorted.
    verticals: Vec<(i32, i32)>,
    /// Where each column's crossings lie in `verticals`.
    columns: Option<Columns>,
    /// Counter-clockwise: an outer ring.
    outer: bool,
    /// `ring::signed_area(points)`.
    area: f64,
    /// Bounding box of `points`.
    lo: Vec2,
    hi: Vec2,
    /// Found by a hole scan (so its inside has been scanned already).
    nested: bool,
}

impl Traced {
    /// Whether the ring encloses grid node `(x, y)`, by the parity of its crossings above the
    /// node on the node's column: exact, no floating point.
    fn encloses(&self, x: i32, y: i32) -> bool {
        match &self.columns {
            // Column `x`'s crossings alone, from the index: those above the node.
            Some(Columns { first, starts }) => {
                let k = i64::from(x) - i64::from(*first);
                let range = usize::try_from(k)
                    .ok()
                    .and_then(|k| Some(*starts.get(k)? as usize..*starts.get(k + 1)? as usize));
                odd_above(range.and_then(|r| self.verticals.get(r)).unwrap_or(&[]), y)
            }
            None => encloses(&self.verticals, x, y),
        }
    }
}

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

    /// The sample at node `(i, j)`, taken on first use: the node alone, or (tiled) the whole
    /// tile holding it, when its tile is first touched.
    #[inline(always)]
    fn node(&mut self, i: i32, j: i32) -> f32 {
        let tile = self.tile(i, j);
        let slot = Nodes::slot(i, j);
        match self.nodes.tiles.get(tile) {
            Some(t) if t.sampled & (1 << slot) != 0 => t.values[slot],
            _ => self.sample_node(tile, slot, i, j),
        }
    }

    /// Samples node `(i, j)`, in `slot` of `tile`: alone (point by point), or, tiled, with
    /// the rest of its tile (one proven inside and left unsampled so far).
    #[inline]
    fn sample_node(&mut self, tile: usize, slot: usize, i: i32, j: i32) -> f32 {
        if self.tiled {
            let first = [i & !TILE_MASK, j & !TILE_MASK];
            let (field, step, iso) = (self.field, self.step, self.iso);
            self.nodes
                .fill(tile, iso, |out| field.sample_tile(first, step, out));
            return self.nodes.sampled(tile, slot);
        }
        let v = self.field.value(node_point([i, j], self.step));
        self.nodes.set(tile, slot, v, cell::is_inside(v, self.iso));
        v
    }

    /// The index of the tile holding node `(i, j)`: from the tile cache, else found or
    /// created (and, tiled, filled) by [`Tracer::tile_miss`].
    #[inline(always)]
    fn tile(&mut self, i: i32, j: i32) -> usize {
        self.lookup_tile(i, j, false)
    }

    /// The tile holding node `(i, j)`, for its inside flags only: as [`Tracer::tile`], but
    /// a new tile the field proves inside is not sampled.
    #[inline(always)]
    fn flag_tile(&mut self, i: i32, j: i32) -> usize {
        self.lookup_tile(i, j, true)
    }

    /// [`Tracer::tile`] (`flags` false) or [`Tracer::flag_tile`] (true).
    #[inline(always)]
    fn lookup_tile(&mut self, i: i32, j: i32, flags: bool) -> usize {
        let key = (i >> TILE_SHIFT, j >> TILE_SHIFT);
        match self.nodes.cached(key) {
            Some(tile) => tile,
            None => self.tile_miss(key, flags),
        }
    }

    /// The tile at tile coordinates `key`, past the cache: found or created. A new tile is
    /// filled when the tracer samples by tiles, unless only its inside flags are needed
    /// (`flags`) and the field proves it inside ([`TileField::tile_inside`]): then it is left
    /// unsampled.
    #[inline(never)]
    fn tile_miss(&mut self, key: (i32, i32), flags: bool) -> usize {
        let (tile, created) = self.nodes.find_or_add(key);
        if created && self.tiled {
            let first = [key.0 << TILE_SHIFT, key.1 << TILE_SHIFT];
            let (field, step, iso) = (self.field, self.step, self.iso);
            if flags && field.tile_inside(first, step, iso) {
                self.nodes.prove_inside(tile);
            } else {
                self.nodes
                    .fill(tile, iso, |out| field.sample_tile(first, step, out));
            }
        }
        tile
    }

    /// Whether node `(i, j)` is inside: from its tile's flags when known (sampled, or proven),
    /// else from its sample.
    #[inline]
    fn inside(&mut self, i: i32, j: i32) -> bool {
        let tile = self.flag_tile(i, j);
        let slot = Nodes::slot(i, j);
        match self.nodes.tiles.get(tile) {
            Some(t) if (t.sampled | t.proven) & (1 << slot) != 0 => t.inside & (1 << slot) != 0,
            _ => cell::is_inside(self.sample_node(tile, slot, i, j), self.iso),
        }
    }

    /// Whether grid node `(x, y)` is already known to be inside a traced component: the
    /// innermost traced ring enclosing it is an outer ring. Exact (crossing parity), no
    /// sampling.
    fn covered(&self, x: i32, y: i32) -> bool {
        let p = Vec2::new(x as f32, y as f32) * self.step;
        let mut best: Option<(bool, f32)> = None;
        for ring in &self.rings {
            if p.cmplt(ring.lo).any() || p.cmpgt(ring.hi).any() {
                continue;
            }
            let size = (ring.hi - ring.lo).element_product();
            if best.is_some_and(|(_, s)| s <= size) {
                continue;
            }
            if ring.encloses(x, y) {
                best = Some((ring.outer, size));
            }
        }
        best.is_some_and(|(outer, _)| outer)
    }

    /// The ring crossing the vertical edge from node `(x, y)` up, if any.
    fn crossing_ring(&mut self, x: i32, y: i32) -> Option<usize> {
        if !self.nodes.crossed(x, y) {
            return None;
        }
        let rings = &self.rings;
        let table = self.ring_of_edge.get_or_insert_with(|| {
            let edges = rings.iter().map(|r| r.verticals.len()).sum::<usize>();
            let mut table = Table::with_slots((2 * edges + 16).next_power_of_two());
            for (id, r) in rings.iter().enumerate() {
                for &edge in &r.verticals {
                    table.insert(edge, id as u32);
                }
            }
            table
        });
        table.get((x, y)).map(|r| r as usize)
    }

    fn outline_hint(&mut self, index: usize, hint: Vec2) -> Result<(), MarchError> {
        // The corners of the cell holding the hint, nearest first.
        let g = hint / self.step;
        // `floor` by truncation (exact: hints lie within `MAX_GRID_COORDINATE` steps, where
        // `f32` holds every integer), not a library call on targets without SSE4.1.
        let floor = |v: f32| {
            let t = v as i32;
            if t as f32 > v { t - 1 } else { t }
        };
        let base = (floor(g.x), floor(g.y));
        let mut corners = CORNERS.map(|(di, dj)| {
            let (i, j) = (base.0 + di, base.1 + dj);
            (Vec2::new(i as f32, j as f32).distance_squared(g), (i, j))
        });
        // Already outlined: the nearest node (the first of the nearest, in corner order) lies
        // in a traced component (what the walk below would find, without sampling).
        let nearest = corners
            .iter()
            .reduce(|a, b| if b.0.total_cmp(&a.0).is_lt() { b } else { a })
            .map_or(base, |c| c.1);
        if self.covered(nearest.0, nearest.1) {
            return Ok(());
        }
        // A stable insertion sort of four: ties keep the corner order.
        for n in 1..corners.len() {
            let mut m = n;
            while m > 0 && corners[m].0.total_cmp(&corners[m - 1].0).is_lt() {
                corners.swap(m, m - 1);
                m -= 1;
            }
        }
        let corners = corners.map(|(_, c)| c);
        if !cell::is_inside(self.field.value(hint), self.iso) {
            return Ok(());
        }
        let mut start = None;
        for (i, j) in corners {
            if self.inside(i, j) {
                start = Some((i, j));
                break;
            }
        }
        let Some((x, y0)) = start else {
            return Ok(());
        };
        // Walk up the column, tracing every crossing not traced yet, until an outer ring
        // enclosing the start node turns up.
        let mut y = y0;
        let mut below = true;
        loop {
            self.tick(index)?;
            let above = self.inside(x, y + 1);
            if above != below {
                let ring = match self.crossing_ring(x, y) {
                    Some(r) => r,
                    None if below => self.trace_ring((x - 1, y), 1, index, false)?,
                    None => self.trace_ring((x, y), 3, index, false)?,
                };
                if self
                    .rings
                    .get(ring)
                    .is_some_and(|r| r.outer && r.encloses(x, y0))
                {
                    return Ok(());
                }
            }
            below = above;
            y += 1;
        }
    }

    /// Scans the nodes enclosed by every outer ring not scanned yet, tracing each crossing
    /// that is not part of a known ring.
    fn scan_pending(&mut self) -> Result<(), MarchError> {
        while self.scanned < self.rings.len() {
            let r = self.scanned;
            self.scanned += 1;
            if !self.rings[r].outer || self.rings[r].nested {
                continue;
            }
            let verticals = core::mem::take(&mut self.rings[r].verticals);
            let scanned = if self.tiled {
                self.scan_bands(&verticals)
            } else {
                column_pairs(&verticals)
                    .try_for_each(|(x, bottom, top)| self.scan_column(x, bottom, top))
            };
            if let Some(ring) = self.rings.get_mut(r) {
                ring.verticals = verticals;
            }
            scanned?;
        }
        Ok(())
    }

    /// [`Tracer::scan_column`] for every column pair `verticals` holds (a ring's sorted
    /// vertical crossings), when sampling by tiles: a band of eight columns (a column of
    /// tiles) at a time, each tile of the band at once. The tiles holding the enclosed nodes
    /// are proven or filled, as `scan_column` would; in each, the inside flags of the tile and
    /// of the row below it give every node whose flag differs from the node below's. Those
    /// whose edge no traced ring crosses (few: the ring's own crossings are traced) and whose
    /// two nodes the ring encloses start a ring, in the order `scan_column` meets them (by
    /// column, then row), so the same rings come out in the same order.
    fn scan_bands(&mut self, verticals: &[(i32, i32)]) -> Result<(), MarchError> {
        let mut visit: Vec<u64> = Vec::new();
        let mut starts: Vec<(i32, i32, bool)> = Vec::new();
        let mut rest = verticals;
        while let Some(&(first, _)) = rest.first() {
            let band = first >> TILE_SHIFT;
            // A band holds few crossings: a linear scan.
            let end = rest
                .iter()
                .position(|v| v.0 >> TILE_SHIFT != band)
                .unwrap_or(rest.len());
            let (pairs, next) = rest.split_at(end);
            rest = next;
            // The tile rows holding enclosed nodes with a node above them to check.
            let (mut low, mut high) = (i32::MAX, i32::MIN);
            let mut nodes = 0;
            for (_, bottom, top) in column_pairs(pairs) {
                nodes += (top - bottom - 1).max(0) as usize;
                if top - bottom >= 2 {
                    low = low.min((bottom + 1) >> TILE_SHIFT);
                    high = high.max(top >> TILE_SHIFT);
                }
            }
            self.count_scanned(nodes)?;
            if low > high {
                continue;
            }
            visit.clear();
            visit.resize(((i64::from(high) - i64::from(low)) as usize >> 6) + 1, 0);
            let enclosed =
                column_pairs(pairs)
                    .filter(|p| p.2 - p.1 >= 2)
                    .map(|(_, bottom, top)| {
                        (
                            ((bottom + 1) >> TILE_SHIFT) - low,
                            (top >> TILE_SHIFT) - low,
                        )
                    });
            if let [word] = visit.as_mut_slice() {
                // Up to 64 tile rows (the usual case): the word kept in a register.
                *word = enclosed.fold(0, |bits, (from, to)| bits | bit_range(from, to));
            } else {
                for (from, to) in enclosed {
                    set_bits(&mut visit, from, to);
                }
            }
            starts.clear();
            let x = band << TILE_SHIFT;
            for (word, &bits) in visit.iter().enumerate() {
                let mut bits = bits;
                while bits != 0 {
                    let ty = low + (word << 6) as i32 + bits.trailing_zeros() as i32;
                    bits &= bits - 1;
                    let y = ty << TILE_SHIFT;
                    // Rows 1 to 7 against the row below in the tile; row 0 against the tile
                    // below's row 7, when that tile exists (else its nodes lie outside the
                    // ring, and row 0's edges down cross it: nothing to check).
                    let (below, crossed_below) = self
                        .nodes
                        .find(x, y - 1)
                        .map_or((!0, !0), |t| self.nodes.flags(t));
                    // A new tile just above one holding an outside node is filled without
                    // asking the field to prove it inside: the field dips below the level
                    // within a tile of it, where a bound over the whole tile seldom holds,
                    // and a failed proof costs about half a fill on top of the fill. Either
                    // way the flags are the same.
                    let tile = if below == !0 {
                        self.flag_tile(x, y)
                    } else {
                        self.tile(x, y)
                    };
                    let (inside, crossed) = self.nodes.flags(tile);
                    let row_7 = 8 * TILE_MASK;
                    let changes = inside ^ (inside << 8 | below >> row_7);
                    let crossed = crossed << 8 | crossed_below >> row_7;
                    let mut changes = changes & !crossed;
                    while changes != 0 {
                        let slot = changes.trailing_zeros() as i32;
                        changes &= changes - 1;
                        let node = (x + (slot & TILE_MASK), y + (slot >> TILE_SHIFT));
                        if encloses(pairs, node.0, node.1) && encloses(pairs, node.0, node.1 - 1) {
                            starts.push((node.0, node.1, inside >> slot & 1 != 0));
                        }
                    }
                }
            }
            // `scan_column`'s order: by column, then row.
            starts.sort_unstable();
            for &(x, up, inside) in &starts {
                self.trace_nested(x, up, inside)?;
            }
        }
        Ok(())
    }

    /// Scans nodes `bottom + 1 ..= top` of column `x` (enclosed by a ring), point by point,
    /// tracing every crossing between two of them that no ring has crossed yet. The nodes
    /// above the first are counted against the budget at once ([`Tracer::count_scanned`]).
    /// Runs a tile's rows at a time: each node is sampled, then the inside flags of the
    /// column's segment come from the tile's mask, and only the rows where the flag changes
    /// are looked at. (Sampling by tiles, [`Tracer::scan_bands`] scans instead.)
    fn scan_column(&mut self, x: i32, bottom: i32, top: i32) -> Result<(), MarchError> {
        self.count_scanned((top - bottom - 1).max(0) as usize)?;
        let mut below = self.inside(x, bottom + 1);
        let mut y = bottom + 1;
        while y < top {
            // Nodes y + 1 ..= last lie in one tile, in rows `first ..= last_row` of it.
            let last = ((y + 1) | TILE_MASK).min(top);
            for up in y + 1..=last {
                self.node(x, up);
            }
            let tile = self.flag_tile(x, y + 1);
            let first = (y + 1) & TILE_MASK;
            let last_row = last & TILE_MASK;
            let rows = (u32::MAX << first) & (u32::MAX >> (31 - last_row));
            // Bit r: the node in row r of the segment is inside.
            let inside = self.nodes.column_inside(tile, x & TILE_MASK) & rows;
            // Bit r: the node below it is inside.
            let previous = (inside << 1) | (u32::from(below) << first);
            let mut changes = (inside ^ previous) & rows;
            let base = (y + 1) & !TILE_MASK;
            while changes != 0 {
                let up = base + changes.trailing_zeros() as i32;
                changes &= changes - 1;
                self.trace_nested(x, up, inside & (1 << (up - base)) != 0)?;
            }
            below = inside & (1 << last_row) != 0;
            y = last;
        }
        Ok(())
    }

    /// Traces the ring crossing the edge from node `(x, up − 1)` to node `(x, up)` (whose
    /// inside flag is `inside`, the other node's the opposite) inside a scanned ring, unless
    /// a traced ring crosses it already. Rings traced during a scan may cross edges the scan
    /// has yet to reach: it asks each time.
    fn trace_nested(&mut self, x: i32, up: i32, inside: bool) -> Result<(), MarchError> {
        if !self.nodes.crossed(x, up - 1) {
            if inside {
                self.trace_ring((x, up - 1), 3, usize::MAX, true)?;
            } else {
                self.trace_ring((x - 1, up - 1), 1, usize::MAX, true)?;
            }
        }
        Ok(())
    }

    fn joined(&mut self, i: i32, j: i32, values: [f32; 4]) -> bool {
        match self.options.saddle {
            Saddle::Centre => {
                let v = match self.centres.get((i, j)) {
                    Some(v) => v,
                    None => {
                        let p = (Vec2::new(i as f32, j as f32) + 0.5) * self.step;
                        let v = self.field.value(p);
                        self.centres.insert((i, j), v);
                        v
                    }
                };
                cell::is_inside(v, self.iso)
            }
            Saddle::Asymptotic => cell::asymptotic_joined(values, self.iso),
        }
    }

    /// Follows the contour entering cell `start` through its in→out edge `k` until it closes.
    /// Returns the new ring's index.
    ///
    /// The cell's corners are kept relative to the entry edge: `a` (corner `k`, inside) and
    /// `b` (corner `k + 1`, outside) are carried over from the previous cell, `c` and `d`
    /// (corners `k + 2`, `k + 3`) are read. Which of `c` and `d` are inside settles the exit
    /// edge (see [`cell::exit_edge`]): `k + 1` when both are, `k + 2` when only `d` is, `k + 3`
    /// when neither is, and the saddle rule when only `c` is.
    fn trace_ring(
        &mut self,
        start: (i32, i32),
        k: usize,
        hint: usize,
        nested: bool,
    ) -> Result<usize, MarchError> {
        let id = self.rings.len();
        let iso = self.iso;
        let mut path = Path::new();
        let start_k = k & 3;
        let mut at = Step {
            ci: start.0,
            cj: start.1,
            k: start_k,
            a: 0.0,
            b: 0.0,
        };
        let (i, j) = at.corner(0);
        at.a = self.node(i, j);
        let (i, j) = at.corner(1);
        at.b = self.node(i, j);
        let closed = |at: &Step| (at.ci, at.cj) == start && at.k == start_k;
        // The budget left for this ring, counted locally and settled when it closes.
        let budget = self.options.max_cells.saturating_sub(self.cells);
        let mut cells = 0;
        loop {
            // Any cell: its far corners through the tile cache; saddles settled.
            cells += 1;
            if cells > budget {
                return Err(self.out_of_budget(hint));
            }
            let (i, j) = at.corner(2);
            let c = self.node(i, j);
            let (i, j) = at.corner(3);
            let d = self.node(i, j);
            let p = self.crossing(at.edge(), at.a, at.b);
            path.push(p, &at);
            if at.k & 1 == 1 {
                // A vertical entry edge, from node (x, cj) up: marked crossed.
                let x = at.corner(0).0;
                let tile = self.tile(x, at.cj);
                self.nodes.mark_crossed(tile, 1 << Nodes::slot(x, at.cj));
            }
            let flags =
                usize::from(cell::is_inside(c, iso)) | usize::from(cell::is_inside(d, iso)) << 1;
            let mut turn = Step::turn(flags);
            if flags == 1 {
                let mut values = [0.0; 4];
                for (n, v) in [at.a, at.b, c, d].into_iter().enumerate() {
                    values[(at.k + n) & 3] = v;
                }
                if !self.joined(at.ci, at.cj, values) {
                    turn = 3;
                }
            }
            at.advance(turn, c, d);
            if closed(&at) {
                break;
            }
            // Cells whose corners all lie in one tile whose nodes are all sampled: the inside
            // flags from the tile's mask, kept in a register, and the samples read only for
            // the crossings, so that the walk does not wait on them.
            if at.ci & TILE_MASK == TILE_MASK || at.cj & TILE_MASK == TILE_MASK {
                continue;
            }
            let tile = self.tile(at.ci, at.cj);
            let Some(inside) = self.nodes.all_inside(tile) else {
                continue;
            };
            // The vertical entry edges crossed in the tile, marked when the walk leaves it.
            let mut crossed = 0u64;
            let closed_here = loop {
                let (slot_c, slot_d) = (at.slot(2), at.slot(3));
                let flags = (inside >> slot_c & 1) | (inside >> slot_d & 1) << 1;
                if flags == 1 {
                    // A saddle: settled above.
                    break false;
                }
                cells += 1;
                if cells > budget {
                    return Err(self.out_of_budget(hint));
                }
                let c = self.nodes.sampled(tile, slot_c);
                let d = self.nodes.sampled(tile, slot_d);
                let p = self.crossing(at.edge(), at.a, at.b);
                path.push(p, &at);
                crossed |= ((at.k & 1) as u64) << Nodes::slot(at.corner(0).0, at.cj);
                at.advance(Step::turn(flags as usize), c, d);
                if closed(&at) {
                    break true;
                }
                if at.ci & TILE_MASK == TILE_MASK || at.cj & TILE_MASK == TILE_MASK {
                    break false;
                }
            };
            self.nodes.mark_crossed(tile, crossed);
            if closed_here {
                break;
            }
        }
        self.cells += cells;
        let Path {
            points,
            mut verticals,
            crossed,
        } = path;
        verticals.truncate(crossed);
        if let Some(table) = &mut self.ring_of_edge {
            for &edge in &verticals {
                table.insert(edge, id as u32);
            }
        }
        let columns = sort_by_column(&mut verticals);
        let area = crate::ring::signed_area(&points);
        let outer = area > 0.0;
        let (lo, hi) = bounds(&points);
        self.rings.push(Traced {
            points,
            verticals,
            columns,
            outer,
            area,
            lo,
            hi,
            nested,
        });
        Ok(id)
    }

    /// The budget error, once the cells of a ring run over it.
    fn out_of_budget(&mut self, hint: usize) -> MarchError {
        self.cells = self.options.max_cells + 1;
        MarchError::BudgetExceeded {
            hint,
            cells: self.options.max_cells,
        }
    }

    /// The crossing between an inside node `a` and an outside node `b` (an edge of the grid),
    /// in world units, refined on the field when asked.
    #[inline(always)]
    fn crossing(&mut self, (a, b): ((i32, i32), (i32, i32)), v_in: f32, v_out: f32) -> Vec2 {
        let pa = Vec2::new(a.0 as f32, a.1 as f32);
        let pb = Vec2::new(b.0 as f32, b.1 as f32);
        let t = cell::crossing(v_in, v_out, self.iso);
        let t = if self.options.refine_steps > 0 {
            self.refine(pa, pb, t, v_in, v_out)
        } else {
            // Off the nodes, as in the grid: two crossings beside an outside node a hair below
            // the iso-level would otherwise both sit on it and pinch the ring.
            t.clamp(cell::NODE_GAP, 1.0 - cell::NODE_GAP)
        };
        (pa + (pb - pa) * t) * self.step
    }

    /// Illinois false-position steps on the field along the edge, bracketing the crossing.
    #[inline(never)]
    fn refine(&mut self, pa: Vec2, pb: Vec2, t0: f32, v_in: f32, v_out: f32) -> f32 {
        let steps = self.options.refine_steps;
        let (mut a, mut fa) = (0.0f32, v_in - self.iso);
        let (mut b, mut fb) = (1.0f32, v_out - self.iso);
        if fa == 0.0 {
            // The inside node sits on the iso-line.
            return 0.0;
        }
        let mut t = t0;
        let mut side = 0i8;
        for _ in 0..steps {
            let v = self.field.value((pa + (pb - pa) * t) * self.step);
            if v == self.iso {
                return t;
            }
            if cell::is_inside(v, self.iso) {
                a = t;
                fa = v - self.iso;
                if side == 1 {
                    fb *= 0.5;
                }
                side = 1;
            } else {
                b = t;
                fb = v - self.iso;
                if side == -1 {
                    fa *= 0.5;
                }
                side = -1;
            }
            let secant = a + (b - a) * fa / (fa - fb);
            t = if secant.is_finite() && secant >= a && secant <= b {
                secant
            } else {
                0.5 * (a + b)
            };
            if !(b - a > f32::EPSILON) {
                break;
            }
        }
        t
    }
}

/// Where a contour walk is: cell `(ci, cj)`, entered through its edge `k` from corner `k`
/// (inside, sample `a`) to corner `k + 1` (outside, sample `b`).
struct Step {
    ci: i32,
    cj: i32,
    k: usize,
    a: f32,
    b: f32,
}

impl Step {
    /// The exit edge, counted from the entry edge, by the inside flags of corners `k + 2` and
    /// `k + 3` (`c | d << 1`): `k + 3` when neither is inside, `k + 2` when only `d` is,
    /// `k + 1` when both are; a saddle (only `c`) goes to `k + 1` when joined, else `k + 3`.
    /// As [`cell::exit_edge`], with the entry edge's corners known to be inside, outside.
    const TURN: [usize; 4] = [3, 1, 2, 1];

    /// `TURN[flags & 3]` from a constant's bit pairs rather than a table (see
    /// [`cell::corner`]).
    #[inline(always)]
    const fn turn(flags: usize) -> usize {
        const PACKED: usize =
            Step::TURN[0] | Step::TURN[1] << 2 | Step::TURN[2] << 4 | Step::TURN[3] << 6;
        PACKED >> (2 * (flags & 3)) & 3
    }

    /// Grid node of corner `k + n`.
    #[inline]
    fn corner(&self, n: usize) -> (i32, i32) {
        let (di, dj) = cell::corner(self.k + n);
        (self.ci + di, self.cj + dj)
    }

    /// Tile slot of corner `k + n`, for a cell whose corners lie in one tile.
    #[inline]
    fn slot(&self, n: usize) -> usize {
        let (i, j) = self.corner(n);
        Nodes::slot(i, j)
    }

    /// The entry edge: its inside node, then its outside node.
    #[inline]
    fn edge(&self) -> ((i32, i32), (i32, i32)) {
        (self.corner(0), self.corner(1))
    }

    /// Leaves through edge `k + turn` into the next cell, given the samples `c`, `d` of
    /// corners `k + 2`, `k + 3`. The exit edge, seen from the next cell, runs from its inside
    /// end to its outside end: `c`–`b`, `d`–`c` or `a`–`d`.
    #[inline]
    fn advance(&mut self, turn: usize, c: f32, d: f32) {
        let exit = (self.k + turn) & 3;
        // Turn 1: `c`–`b`; 2: `d`–`c`; 3: `a`–`d` (selects, not an array in memory, which
        // took longer). The turn is never 0 (back through the entry edge): `Step::turn` gives
        // 1 to 3, and so does the saddle rule.
        debug_assert!(matches!(turn, 1..=3), "turn {turn}");
        let (a, b) = match turn & 3 {
            1 => (c, self.b),
            2 => (d, c),
            _ => (self.a, d),
        };
        self.a = a;
        self.b = b;
        let (di, dj) = cell::across(exit);
        self.ci += di;
        self.cj += dj;
        self.k = (exit + 2) & 3;
    }
}

/// A ring's points and the vertical edges it crosses, while it is traced.
struct Path {
    points: Vec<Vec2>,
    /// The vertical edges crossed, as `(column, lower row)`: the first `crossed`. Each cell
    /// writes its entry edge at `crossed` and keeps it (advancing `crossed`) only when the
    /// edge is vertical: no branch on it.
    verticals: Vec<(i32, i32)>,
    crossed: usize,
}

impl Path {
    fn new() -> Self {
        Self {
            points: Vec::with_capacity(64),
            verticals: alloc::vec![(0, 0); 64],
            crossed: 0,
        }
    }

    /// Records the crossing `p` of the entry edge of the cell at `at`.
    #[inline]
    fn push(&mut self, p: Vec2, at: &Step) {
        self.points.push(p);
        if self.crossed == self.verticals.len() {
            self.verticals.resize(2 * self.crossed, (0, 0));
        }
        // The right (1) or left (3) edge is vertical, from row `cj` up.
        if let Some(slot) = self.verticals.get_mut(self.crossed) {
            *slot = (at.corner(0).0, at.cj);
        }
        self.crossed += at.k & 1;
    }
}

/// The bounding box of ring points (of which there is at least one), as
/// [`ring::bounds`](crate::ring::bounds) gives it, with four independent minima and maxima
/// (which the order does not change: ring points are never NaN, nor `-0.0`).
fn bounds(points: &[Vec2]) -> (Vec2, Vec2) {
    let first = points.first().copied().unwrap_or(Vec2::ZERO);
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

/// The enclosed stretches `(column, bottom, top)` of a ring's sorted vertical crossings: the
/// nodes `bottom + 1 ..= top` of the column lie inside the ring. Crossings come in pairs per
/// column for a closed ring; a pair across two columns (never from a closed ring) is skipped.
fn column_pairs(verticals: &[(i32, i32)]) -> impl Iterator<Item = (i32, i32, i32)> + '_ {
    verticals.chunks_exact(2).filter_map(|pair| match *pair {
        [(x, bottom), (x2, top)] if x == x2 => Some((x, bottom, top)),
        _ => None,
    })
}

/// Whether a ring encloses node `(x, y)`, by the parity of its vertical crossings above the
/// node in its column, from `crossings`: sorted, and holding at least column `x`'s.
fn encloses(crossings: &[(i32, i32)], x: i32, y: i32) -> bool {
    let start = crossings.partition_point(|e| e.0 < x);
    let end = crossings.partition_point(|e| e.0 <= x);
    odd_above(crossings.get(start..end).unwrap_or(&[]), y)
}

/// Whether an odd number of a column's vertical crossings lie at row `y` or above.
#[inline]
fn odd_above(column: &[(i32, i32)], y: i32) -> bool {
    column.iter().filter(|e| e.1 >= y).count() % 2 == 1
}

/// Bits `from & 63 ..= to & 63` of a word (`from & 63 ≤ to & 63`).
#[inline]
fn bit_range(from: i32, to: i32) -> u64 {
    (u64::MAX << (from & 63)) & (u64::MAX >> (63 - (to & 63)))
}

/// Sets bits `from ..= to` (both at least 0) of the bit set `words`.
#[inline]
fn set_bits(words: &mut [u64], from: i32, to: i32) {
    let (from, to) = (from as usize, to as usize);
    if from >> 6 == to >> 6 {
        if let Some(word) = words.get_mut(from >> 6) {
            *word |= bit_range(from as i32, to as i32);
        }
        return;
    }
    if let Some(words) = words.get_mut(from >> 6..=to >> 6) {
        let top = words.len() - 1;
        for (k, word) in words.iter_mut().enumerate() {
            let low = if k == 0 { from & 63 } else { 0 };
            let high = if k == top { to & 63 } else { 63 };
            *word |= (u64::MAX << low) & (u64::MAX >> (63 - high));
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

/// Side of a node tile: tiles hold `TILE × TILE` nodes.
const TILE_SHIFT: i32 = 3;
const TILE_MASK: i32 = (1 << TILE_SHIFT) - 1;
const _: () = assert!(TILE_NODES == 1 << (2 * TILE_SHIFT));

/// Bit `s`: `values[s]` is inside `iso` (a NaN is not), four lanes at a time: one compare and
/// its sign mask per four samples. Out of line (once per tile filled): inlined, it slowed the
/// point-by-point walk, which never calls it, by 9% through the code around it.
#[inline(never)]
fn inside_bits(values: &[f32; TILE_NODES], iso: f32) -> u64 {
    let iso = glam::Vec4::splat(iso);
    values
        .chunks_exact(4)
        .enumerate()
        .fold(0, |bits, (k, four)| {
            let inside = glam::Vec4::from_slice(four).cmpge(iso).bitmask();
            bits | u64::from(inside) << (4 * k)
        })
}

/// Bit 0 of each byte of `spread`, gathered into bit `k` for byte `k`: a multiplication
/// whose partial products never overlap, so never carry.
#[inline]
fn gather_bytes(spread: u64) -> u64 {
    (spread & 0x0101_0101_0101_0101).wrapping_mul(0x0102_0408_1020_4080) >> 56
}

/// Column `column` of a tile's bit mask (bit `8 × row + column`), as bit `row` of a byte.
#[inline]
fn column_bits(mask: u64, column: i32) -> u32 {
    gather_bytes(mask >> (column & TILE_MASK)) as u32
}

/// Node samples for an 8 × 8 block of grid nodes.
#[derive(Clone)]
struct Tile {
    values: [f32; TILE_NODES],
    /// Bit `s`: `values[s]` has been sampled.
    sampled: u64,
    /// Bit `s`: the node in slot `s` is inside (known where sampled, or proven).
    inside: u64,
    /// Every bit set when the field proved every node inside without sampling
    /// ([`TileField::tile_inside`]): the inside flags are known, the values not.
    proven: u64,
    /// Bit `s`: a traced ring crosses the edge from the node in slot `s` up to the node above.
    crossed: u64,
}

/// Slots of the tile cache: a tile goes to the slot of the low 2 bits of its column and the
/// low 5 bits of its row, so any block of 4 × 32 neighbouring tiles fits at once: a contour's
/// neighbourhood, and the tiles a hole scan runs up through, column after column.
const CACHE_SLOTS: usize = 128;

/// A sparse grid of node samples in dense tiles: the compact cache behind "each node is
/// sampled once". Contours are local, so lookups mostly hit one of a few neighbouring tiles,
/// which a small direct-mapped cache remembers; other tiles are found through a hash table.
struct Nodes {
    tiles: Vec<Tile>,
    index: Table<u32>,
    /// Tile coordinates and index of a recently used tile, by [`Nodes::cache_slot`].
    cache: [(i32, i32, u32); CACHE_SLOTS],
}

impl Nodes {
    fn new() -> Self {
        Self {
            // A creature's outline and hole scan touch a couple of hundred tiles: room for
            // 256 before either grows (the table keeps half its slots empty).
            tiles: Vec::with_capacity(256),
            index: Table::with_slots(512),
            // No tile has coordinate `i32::MIN`: node coordinates stay within ±2^30.
            cache: [(i32::MIN, i32::MIN, 0); CACHE_SLOTS],
        }
    }

    #[inline]
    fn slot(i: i32, j: i32) -> usize {
        ((j & TILE_MASK) << TILE_SHIFT | (i & TILE_MASK)) as usize
    }

    #[inline]
    fn cache_slot((x, y): (i32, i32)) -> usize {
        ((x & 3) | (y & 31) << 2) as usize
    }

    /// The index of the tile at tile coordinates `key`, if the cache holds it.
    #[inline]
    fn cached(&self, key: (i32, i32)) -> Option<usize> {
        let (x, y, tile) = self.cache[Self::cache_slot(key)];
        ((x, y) == key).then_some(tile as usize)
    }

    /// The index of the tile at tile coordinates `key`, created (unsampled) when missing, and
    /// whether it was created. Caches it.
    fn find_or_add(&mut self, key: (i32, i32)) -> (usize, bool) {
        let next = self.tiles.len() as u32;
        let (tile, created) = self.index.get_or_insert(key, next);
        if created {
            self.tiles.push(Tile {
                values: [0.0; TILE_NODES],
                sampled: 0,
                inside: 0,
                proven: 0,
                crossed: 0,
            });
        }
        let tile = tile as usize;
        self.cache[Self::cache_slot(key)] = (key.0, key.1, tile as u32);
        (tile, created)
    }

    /// The index of the tile holding node `(i, j)`, if any node of it was touched.
    #[inline]
    fn find(&self, i: i32, j: i32) -> Option<usize> {
        let key = (i >> TILE_SHIFT, j >> TILE_SHIFT);
        self.cached(key)
            .or_else(|| self.index.get(key).map(|t| t as usize))
    }

    /// Stores the sample `v` of `slot` of `tile`, inside or not.
    fn set(&mut self, tile: usize, slot: usize, v: f32, inside: bool) {
        if let Some(t) = self.tiles.get_mut(tile)
            && let Some(value) = t.values.get_mut(slot)
        {
            *value = v;
            t.sampled |= 1 << slot;
            t.inside |= u64::from(inside) << slot;
        }
    }

    /// Fills every sample of `tile` with `fill`, and marks which are inside `iso`.
    fn fill(&mut self, tile: usize, iso: f32, fill: impl FnOnce(&mut [f32; TILE_NODES])) {
        if let Some(t) = self.tiles.get_mut(tile) {
            fill(&mut t.values);
            t.sampled = u64::MAX;
            t.inside = inside_bits(&t.values, iso);
        }
    }

    /// Marks every node of `tile` (unsampled) as proven inside.
    fn prove_inside(&mut self, tile: usize) {
        if let Some(t) = self.tiles.get_mut(tile) {
            t.inside = u64::MAX;
            t.proven = u64::MAX;
        }
    }

    /// The inside flags of `tile` (sampled or proven nodes only), and which of its nodes'
    /// edges up traced rings cross.
    #[inline]
    fn flags(&self, tile: usize) -> (u64, u64) {
        self.tiles
            .get(tile)
            .map_or((0, 0), |t| (t.inside, t.crossed))
    }

    /// The inside flags of column `column` of `tile`: bit `r` for row `r` (sampled or proven
    /// nodes only).
    #[inline]
    fn column_inside(&self, tile: usize, column: i32) -> u32 {
        self.tiles
            .get(tile)
            .map_or(0, |t| column_bits(t.inside, column))
    }

    /// The sample in `slot` of `tile`, which has been taken (NaN, outside, otherwise).
    #[inline]
    fn sampled(&self, tile: usize, slot: usize) -> f32 {
        self.tiles
            .get(tile)
            .and_then(|t| t.values.get(slot))
            .copied()
            .unwrap_or(f32::NAN)
    }

    /// The inside flags of `tile`, if all its nodes are sampled.
    #[inline]
    fn all_inside(&self, tile: usize) -> Option<u64> {
        self.tiles
            .get(tile)
            .and_then(|t| (t.sampled == u64::MAX).then_some(t.inside))
    }

    /// Records that a ring crosses the edges from the nodes of `tile` whose bits are set in
    /// `slots` up.
    #[inline]
    fn mark_crossed(&mut self, tile: usize, slots: u64) {
        if let Some(t) = self.tiles.get_mut(tile) {
            t.crossed |= slots;
        }
    }

    /// Whether a traced ring crosses the edge from node `(i, j)` up.
    #[inline]
    fn crossed(&self, i: i32, j: i32) -> bool {
        self.find(i, j)
            .and_then(|tile| self.tiles.get(tile))
            .is_some_and(|t| t.crossed >> Self::slot(i, j) & 1 != 0)
    }
}

/// Open-addressing hash table from grid coordinates to small values. Lookups only:
/// nothing depends on its iteration order, so results stay deterministic.
struct Table<V> {
    keys: Vec<u64>,
    values: Vec<V>,
    len: usize,
}

const EMPTY: u64 = 0;

impl<V: Copy + Default> Table<V> {
    /// An empty table with room for `slots` (a power of two) before it first grows.
    fn with_slots(slots: usize) -> Self {
        Self {
            keys: alloc::vec![EMPTY; slots],
            values: alloc::vec![V::default(); slots],
            len: 0,
        }
    }

    fn key((x, y): (i32, i32)) -> u64 {
        // Doubled coordinates stay within ±2^30, so the offset keeps both halves positive and
        // the key nonzero.
        let x = (x as i64 + (1 << 31)) as u64;
        let y = (y as i64 + (1 << 31)) as u64;
        (x << 32) | y
    }

    fn slot(&self, key: u64) -> usize {
        let mask = self.keys.len() - 1;
        let bits = self.keys.len().trailing_zeros();
        (key.wrapping_mul(0x9e37_79b9_7f4a_7c15) >> (64 - bits)) as usize & mask
    }

    /// The slot holding `key`, and `true`; else the empty slot where it would go, and
    /// `false`. `None` only if the table were full, which it never is (it grows first).
    fn probe(&self, key: u64) -> Option<(usize, bool)> {
        let mask = self.keys.len() - 1;
        let mut s = self.slot(key);
        loop {
            match *self.keys.get(s)? {
                k if k == key => return Some((s, true)),
                EMPTY => return Some((s, false)),
                _ => s = (s + 1) & mask,
            }
        }
    }

    fn get(&self, at: (i32, i32)) -> Option<V> {
        match self.probe(Self::key(at))? {
            (s, true) => self.values.get(s).copied(),
            (_, false) => None,
        }
    }

    /// The value at `at`, and `false`; else `value`, inserted, and `true`. One probe.
    fn get_or_insert(&mut self, at: (i32, i32), value: V) -> (V, bool) {
        self.room_for_one();
        let key = Self::key(at);
        match self.probe(key) {
            Some((s, true)) => (self.values.get(s).copied().unwrap_or(value), false),
            Some((s, false)) => {
                self.store(s, key, value);
                (value, true)
            }
            None => (value, false),
        }
    }

    fn insert(&mut self, at: (i32, i32), value: V) {
        self.room_for_one();
        let key = Self::key(at);
        if let Some((s, _)) = self.probe(key) {
            self.store(s, key, value);
        }
    }

    /// Writes `key` and `value` into slot `s`, counting the key if the slot was empty.
    fn store(&mut self, s: usize, key: u64, value: V) {
        if let (Some(k), Some(v)) = (self.keys.get_mut(s), self.values.get_mut(s)) {
            if *k == EMPTY {
                self.len += 1;
            }
            *k = key;
            *v = value;
        }
    }

    /// Grows the table if one more key would fill more than half its slots.
    fn room_for_one(&mut self) {
        if (self.len + 1) * 2 > self.keys.len() {
            self.grow();
        }
    }

    fn grow(&mut self) {
        let size = self.keys.len() * 2;
        let keys = core::mem::replace(&mut self.keys, alloc::vec![EMPTY; size]);
        let values = core::mem::replace(&mut self.values, alloc::vec![V::default(); size]);
        self.len = 0;
        for (key, value) in keys.into_iter().zip(values) {
            if key == EMPTY {
                continue;
            }
            if let Some((s, _)) = self.probe(key) {
                self.store(s, key, value);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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

    #[test]
    fn node_tiles_keep_samples_apart() {
        let mut nodes = Nodes::new();
        let coords = [
            (0, 0),
            (-1, 0),
            (7, 7),
            (8, 7),
            (-8, -9),
            (-9, -8),
            (1000, -1000),
        ];
        for (n, &(i, j)) in coords.iter().enumerate() {
            let (tile, _) = nodes.find_or_add((i >> TILE_SHIFT, j >> TILE_SHIFT));
            // Even samples inside, odd ones outside.
            nodes.set(tile, Nodes::slot(i, j), n as f32, n % 2 == 0);
        }
        for (n, &(i, j)) in coords.iter().enumerate() {
            let tile = nodes.find(i, j).unwrap();
            let slot = Nodes::slot(i, j);
            assert_eq!(nodes.tiles[tile].values[slot], n as f32);
            assert_ne!(nodes.tiles[tile].sampled & 1 << slot, 0);
            let column = nodes.column_inside(tile, i & TILE_MASK);
            assert_eq!(column >> (j & TILE_MASK) & 1, u32::from(n % 2 == 0));
        }
        assert_eq!(nodes.find(1, 8), None);
        assert_eq!(nodes.find(-100, 5), None);
    }

    #[test]
    fn tile_masks_give_rows_and_columns() {
        let mut values = [0.0f32; TILE_NODES];
        // Inside (≥ 0.5): the diagonal, all of row 5, and NaN nowhere.
        for (slot, v) in values.iter_mut().enumerate() {
            let (column, row) = (slot % 8, slot / 8);
            if column == row || row == 5 {
                *v = 1.0;
            }
        }
        values[9] = f32::NAN; // (1, 1): NaN is outside
        values[18] = 0.5; // (2, 2): exactly the iso-level is inside
        let bits = inside_bits(&values, 0.5);
        for (slot, &v) in values.iter().enumerate() {
            assert_eq!(bits >> slot & 1 == 1, cell::is_inside(v, 0.5), "{slot}");
        }
        for column in 0..8 {
            let expected = (0..8)
                .filter(|&row| cell::is_inside(values[row * 8 + column as usize], 0.5))
                .fold(0u32, |b, row| b | 1 << row);
            assert_eq!(column_bits(bits, column), expected, "column {column}");
        }
        assert_eq!(column_bits(u64::MAX, 7), 0xff);
        assert_eq!(column_bits(0x8000_0000_0000_0000, 7), 0x80);
        assert_eq!(column_bits(0x8000_0000_0000_0000, 6), 0);
    }

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

    #[test]
    fn table_grows_and_finds() {
        let mut t: Table<u32> = Table::with_slots(16);
        for i in -2000..2000 {
            t.insert((i, -i), i as u32);
        }
        for i in -2000..2000 {
            assert_eq!(t.get((i, -i)), Some(i as u32));
        }
        assert_eq!(t.get((1, 1)), None);
        t.insert((5, -5), 7);
        assert_eq!(t.get((5, -5)), Some(7));
    }

    #[test]
    fn set_bits_sets_exactly_the_range() {
        for from in 0..200 {
            for to in from..200 {
                let mut words = [0u64; 4];
                set_bits(&mut words, from, to);
                for bit in 0..256 {
                    let set = words[bit / 64] >> (bit % 64) & 1 == 1;
                    assert_eq!(
                        set,
                        (from..=to).contains(&(bit as i32)),
                        "{from}..={to}: {bit}"
                    );
                }
            }
        }
    }

    #[test]
    fn table_get_or_insert_inserts_once() {
        let mut t: Table<u32> = Table::with_slots(16);
        for i in 0..1000 {
            assert_eq!(t.get_or_insert((i, 2 * i), i as u32), (i as u32, true));
        }
        for i in 0..1000 {
            assert_eq!(t.get_or_insert((i, 2 * i), 5000), (i as u32, false));
            assert_eq!(t.get((i, 2 * i)), Some(i as u32));
        }
        assert_eq!(t.len, 1000);
        assert_eq!(t.get((1, 1)), None);
    }
}
