//! The playground's WebAssembly module: `creature`'s generator, live animator, terrain and
//! exporters bound for JavaScript with `wasm-bindgen`. It has no generation logic of its own:
//! every creature, pose and file comes from the facade, so the page shows (and downloads)
//! exactly what the library makes.
//!
//! - [`World`]: a procedural terrain and the creatures living on it, each driven every frame by
//!   its [`Animator`] (go to a point, stand, or wander), with the terrain's mesh, each creature's
//!   mesh and its skinning matrices (joint world × inverse bind, column-major) for the renderer.
//! - [`Creature2d`]: a 2D creature, its textured mesh and the seed page's idle wiggle.
//! - [`glb_3d`], [`preview_3d_png`], [`glb_2d`], [`preview_2d_png`]: the bytes the `generate`
//!   example writes for the same seed and parameters.
//!
//! Built for `wasm32-unknown-unknown` by `cargo xtask web`; on other targets it is a plain
//! library (its tests run natively).

use creature::d2;
use creature::d3::{self, ARRIVAL_RADIUS, Animator, Intent, Kind};
use creature::export;
use creature::gait::{Ground, HeightField};
use creature::glam::{Vec2, Vec3};
use creature::terrain::{TerrainParams, terrain, terrain_mesh};
use creature::{Error, Span};
use wasm_bindgen::prelude::*;

#[cfg(target_arch = "wasm32")]
#[wasm_bindgen]
extern "C" {
    /// `console.error`.
    #[wasm_bindgen(js_namespace = console, js_name = error)]
    fn console_error(message: &str);
}

/// Runs when the module loads: a panic (a bug: bad input gets an error) says what happened on
/// the console, not only "unreachable".
#[cfg(target_arch = "wasm32")]
#[wasm_bindgen(start)]
pub fn start() {
    std::panic::set_hook(Box::new(|info| {
        console_error(&format!("creature-web: {info}"))
    }));
}

/// The largest seed JavaScript's numbers carry exactly (2^53 − 1).
const MAX_SEED: f64 = 9_007_199_254_740_991.0;

/// A JavaScript error carrying `e`'s message.
fn js(e: impl core::fmt::Display) -> JsError {
    JsError::new(&e.to_string())
}

/// A seed from JavaScript: a whole number in `[0, 2^53)`.
///
/// # Errors
/// When `seed` is not such a number.
pub fn seed_from(seed: f64) -> Result<u64, String> {
    if (0.0..=MAX_SEED).contains(&seed) && seed.fract() == 0.0 {
        // Exact: a whole number below 2^53.
        Ok(seed as u64)
    } else {
        Err(format!(
            "seed {seed} is not a whole number from 0 to {MAX_SEED}"
        ))
    }
}

/// The kind named `kind`: `walker`, `flier`, `swimmer`, `slitherer` or `random`.
///
/// # Errors
/// For any other name.
pub fn kind_from(kind: &str) -> Result<Kind, String> {
    match kind {
        "walker" => Ok(Kind::Walker),
        "flier" => Ok(Kind::Flier),
        "swimmer" => Ok(Kind::Swimmer),
        "slitherer" => Ok(Kind::Slitherer),
        "random" => Ok(Kind::Random),
        other => Err(format!(
            "kind `{other}` is not one of walker, flier, swimmer, slitherer, random"
        )),
    }
}

/// The 3D parameters the page's controls set, as the `generate` example's flags set them:
/// `kind` (`--kind`), and each of the others, when given, a fixed value instead of the
/// default range (`--body-scale`, `--head-size`, `--snout-length`, `--neck-width`).
///
/// # Errors
/// For an unknown kind or a value out of its range (the message names the field).
pub fn params_3d(
    kind: &str,
    body_scale: Option<f32>,
    head_size: Option<f32>,
    snout_length: Option<f32>,
    neck_width: Option<f32>,
) -> Result<d3::Params, String> {
    let mut params = d3::Params::DEFAULT.with_kind(kind_from(kind)?);
    if let Some(s) = body_scale {
        params = params.with_body_scale(Span::new(s, s));
    }
    if let Some(s) = head_size {
        params = params.with_head_size(Span::new(s, s));
    }
    if let Some(s) = snout_length {
        params = params.with_snout_length(Span::new(s, s));
    }
    if let Some(w) = neck_width {
        params = params.with_neck_width(w);
    }
    params.validate().map_err(|e| e.to_string())?;
    Ok(params)
}

/// One 3D creature as the page's controls describe it (see [`params_3d`]), with its clips
/// when `clips`.
fn generate_3d(
    kind: &str,
    seed: f64,
    body_scale: Option<f32>,
    head_size: Option<f32>,
    snout_length: Option<f32>,
    neck_width: Option<f32>,
    clips: bool,
) -> Result<d3::Creature, JsError> {
    let params = params_3d(kind, body_scale, head_size, snout_length, neck_width)
        .map_err(js)?
        .with_clips(clips);
    d3::generate(seed_from(seed).map_err(js)?, &params).map_err(js)
}

/// The .glb the `generate` example writes for this seed and these parameters (the creature
/// with its baked clips).
///
/// # Errors
/// A bad seed, kind or parameter, or an export error.
#[wasm_bindgen]
pub fn glb_3d(
    kind: &str,
    seed: f64,
    body_scale: Option<f32>,
    head_size: Option<f32>,
    snout_length: Option<f32>,
    neck_width: Option<f32>,
) -> Result<Vec<u8>, JsError> {
    let c = generate_3d(
        kind,
        seed,
        body_scale,
        head_size,
        snout_length,
        neck_width,
        true,
    )?;
    export::glb_3d(&c, &c.clips).map_err(js)
}

/// The 256-pixel preview PNG the `generate` example writes for this seed and these parameters.
///
/// # Errors
/// A bad seed, kind or parameter, or an export error.
#[wasm_bindgen]
pub fn preview_3d_png(
    kind: &str,
    seed: f64,
    body_scale: Option<f32>,
    head_size: Option<f32>,
    snout_length: Option<f32>,
    neck_width: Option<f32>,
) -> Result<Vec<u8>, JsError> {
    let c = generate_3d(
        kind,
        seed,
        body_scale,
        head_size,
        snout_length,
        neck_width,
        true,
    )?;
    let image = export::preview_3d(&c, 256).map_err(js)?;
    export::image_png(&image).map_err(js)
}

/// Generates one 3D creature of `kind` from `seed` (default parameters; with its baked clips
/// when `clips`, else as [`World::add`] makes it) and returns its vertex count: what the page
/// times.
///
/// # Errors
/// A bad seed or kind.
#[wasm_bindgen]
pub fn generate_3d_vertices(kind: &str, seed: f64, clips: bool) -> Result<u32, JsError> {
    let c = generate_3d(kind, seed, None, None, None, None, clips)?;
    Ok(u32::try_from(c.mesh.positions.len()).unwrap_or(u32::MAX))
}

/// The .glb the `generate` example writes for this 2D seed (`--dim 2d`).
///
/// # Errors
/// A bad seed, or an export error.
#[wasm_bindgen]
pub fn glb_2d(seed: f64) -> Result<Vec<u8>, JsError> {
    let c =
        creature::generate_2d(seed_from(seed).map_err(js)?, &d2::Params::DEFAULT).map_err(js)?;
    export::glb_2d(&c).map_err(js)
}

/// The preview PNG the `generate` example writes for this 2D seed (`--dim 2d`).
///
/// # Errors
/// A bad seed, or an export error.
#[wasm_bindgen]
pub fn preview_2d_png(seed: f64) -> Result<Vec<u8>, JsError> {
    let c =
        creature::generate_2d(seed_from(seed).map_err(js)?, &d2::Params::DEFAULT).map_err(js)?;
    export::preview_2d_png(&c, &export::PreviewOptions::DEFAULT).map_err(js)
}

/// A creature living on a [`World`]'s terrain.
struct Live {
    creature: d3::Creature,
    animator: Animator,
    /// Where it is going, if anywhere.
    target: Option<Vec3>,
    /// Whether it picks a new target on arrival.
    wander: bool,
}

/// A procedural terrain (hills on a slope, cut into steps; [`creature::terrain`]) and the
/// creatures on it, each driven by its own [`Animator`] every [`update`](Self::update).
#[wasm_bindgen]
pub struct World {
    ground: HeightField,
    size: f32,
    creatures: Vec<Live>,
    /// The wanderers' generator (splitmix64).
    state: u64,
}

#[wasm_bindgen]
impl World {
    /// A square of the default terrain ([`TerrainParams::DEFAULT`]: hills 1.5 m high, 10 m
    /// apart, on an 8° slope, steps 0.2 m high) `size` metres wide from `seed`, 193 samples
    /// a side, with no creature yet: the herd's ground.
    ///
    /// # Errors
    /// A bad seed, or a size out of [`TerrainParams::size`]'s range.
    #[wasm_bindgen(constructor)]
    pub fn new(seed: f64, size: f32) -> Result<World, JsError> {
        let params = TerrainParams::DEFAULT.with_extent(size, 193);
        Self::on(seed_from(seed).map_err(js)?, &params).map_err(js)
    }

    /// One creature (see [`params_3d`]) at the origin facing +Z, on terrain from
    /// `terrain_seed` sized to it ([`TerrainParams::for_creature`]: what the `generate`
    /// example's `--terrain` walks it over).
    ///
    /// # Errors
    /// A bad seed, kind or parameter.
    #[allow(clippy::too_many_arguments)]
    pub fn for_creature(
        terrain_seed: f64,
        kind: &str,
        seed: f64,
        body_scale: Option<f32>,
        head_size: Option<f32>,
        snout_length: Option<f32>,
        neck_width: Option<f32>,
    ) -> Result<World, JsError> {
        let creature = generate_3d(
            kind,
            seed,
            body_scale,
            head_size,
            snout_length,
            neck_width,
            false,
        )?;
        let params = TerrainParams::for_creature(&creature);
        let mut world = Self::on(seed_from(terrain_seed).map_err(js)?, &params).map_err(js)?;
        world.live(creature, Vec3::ZERO, 0.0)?;
        Ok(world)
    }

    /// The side of the terrain's square, metres.
    #[must_use]
    pub fn size(&self) -> f32 {
        self.size
    }

    /// The terrain mesh's vertex positions, `x, y, z` each.
    #[must_use]
    pub fn terrain_positions(&self) -> Vec<f32> {
        flat(&terrain_mesh(&self.ground).positions)
    }

    /// The terrain mesh's unit normals, `x, y, z` each.
    #[must_use]
    pub fn terrain_normals(&self) -> Vec<f32> {
        flat(&terrain_mesh(&self.ground).normals)
    }

    /// The terrain mesh's triangles, three vertex indices each.
    #[must_use]
    pub fn terrain_indices(&self) -> Vec<u32> {
        terrain_mesh(&self.ground)
            .triangles
            .iter()
            .flatten()
            .copied()
            .collect()
    }

    /// The terrain's height under `(x, z)`, or `undefined` off it.
    #[must_use]
    pub fn height_at(&self, x: f32, z: f32) -> Option<f32> {
        let top = 1e4;
        self.ground
            .cast_ray(Vec3::new(x, top, z), Vec3::NEG_Y, 2.0 * top)
            .map(|hit| hit.point.y)
    }

    /// Generates a creature (see [`params_3d`]; without clips: the animator moves it) at
    /// `(x, z)` facing `heading` (radians about +Y from +Z); returns its index.
    ///
    /// # Errors
    /// A bad seed, kind or parameter, a creature the animator cannot drive, or a place off
    /// the terrain.
    #[allow(clippy::too_many_arguments)]
    pub fn add(
        &mut self,
        kind: &str,
        seed: f64,
        body_scale: Option<f32>,
        head_size: Option<f32>,
        snout_length: Option<f32>,
        neck_width: Option<f32>,
        x: f32,
        z: f32,
        heading: f32,
    ) -> Result<usize, JsError> {
        let creature = generate_3d(
            kind,
            seed,
            body_scale,
            head_size,
            snout_length,
            neck_width,
            false,
        )?;
        if !heading.is_finite() || self.height_at(x, z).is_none() {
            return Err(js(format!(
                "({x}, {z}) heading {heading} is not a place on the terrain (it spans ±{} m)",
                0.5 * self.size
            )));
        }
        self.live(creature, Vec3::new(x, 0.0, z), heading)?;
        Ok(self.creatures.len() - 1)
    }

    /// Removes every creature.
    pub fn clear(&mut self) {
        self.creatures.clear();
    }

    /// How many creatures live here.
    #[must_use]
    pub fn len(&self) -> usize {
        self.creatures.len()
    }

    /// Whether no creature lives here.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.creatures.is_empty()
    }

    /// Creature `i`'s mesh: vertex positions (rest pose, model space), `x, y, z` each.
    ///
    /// # Errors
    /// No creature `i`.
    pub fn positions(&self, i: usize) -> Result<Vec<f32>, JsError> {
        Ok(flat(&self.get(i)?.creature.mesh.positions))
    }

    /// Creature `i`'s unit vertex normals, `x, y, z` each.
    ///
    /// # Errors
    /// No creature `i`.
    pub fn normals(&self, i: usize) -> Result<Vec<f32>, JsError> {
        Ok(flat(&self.get(i)?.creature.mesh.normals))
    }

    /// Creature `i`'s linear RGB vertex colours, `r, g, b` each.
    ///
    /// # Errors
    /// No creature `i`.
    pub fn colours(&self, i: usize) -> Result<Vec<f32>, JsError> {
        Ok(flat(&self.get(i)?.creature.mesh.colours))
    }

    /// Creature `i`'s triangles, three vertex indices each.
    ///
    /// # Errors
    /// No creature `i`.
    pub fn indices(&self, i: usize) -> Result<Vec<u32>, JsError> {
        Ok(self
            .get(i)?
            .creature
            .mesh
            .indices
            .iter()
            .flatten()
            .copied()
            .collect())
    }

    /// Creature `i`'s skin: four joint indices per vertex.
    ///
    /// # Errors
    /// No creature `i`.
    pub fn joints(&self, i: usize) -> Result<Vec<u16>, JsError> {
        Ok(self
            .get(i)?
            .creature
            .mesh
            .joints
            .iter()
            .flatten()
            .copied()
            .collect())
    }

    /// Creature `i`'s skin: four weights per vertex.
    ///
    /// # Errors
    /// No creature `i`.
    pub fn weights(&self, i: usize) -> Result<Vec<f32>, JsError> {
        Ok(self
            .get(i)?
            .creature
            .mesh
            .weights
            .iter()
            .flatten()
            .copied()
            .collect())
    }

    /// Creature `i`'s body length, metres.
    ///
    /// # Errors
    /// No creature `i`.
    pub fn length(&self, i: usize) -> Result<f32, JsError> {
        Ok(self.get(i)?.creature.length)
    }

    /// Creature `i`'s kind: `walker`, `flier`, `swimmer` or `slitherer`.
    ///
    /// # Errors
    /// No creature `i`.
    pub fn kind(&self, i: usize) -> Result<String, JsError> {
        Ok(match self.get(i)?.creature.kind {
            creature::limbs::CreatureKind::Walker => "walker",
            creature::limbs::CreatureKind::Flier => "flier",
            creature::limbs::CreatureKind::Swimmer => "swimmer",
            creature::limbs::CreatureKind::Slitherer => "slitherer",
            _ => "creature",
        }
        .to_string())
    }

    /// Creature `i`'s joints: how many skinning matrices [`skinning`](Self::skinning) gives.
    ///
    /// # Errors
    /// No creature `i`.
    pub fn joint_count(&self, i: usize) -> Result<usize, JsError> {
        Ok(self.get(i)?.creature.skeleton.joints.len())
    }

    /// Creature `i`'s skinning matrices after the last update (joint world × inverse bind,
    /// world space), 16 floats each, column-major (three.js's `Matrix4.fromArray`).
    ///
    /// # Errors
    /// No creature `i`.
    pub fn skinning(&self, i: usize) -> Result<Vec<f32>, JsError> {
        Ok(self
            .get(i)?
            .animator
            .skinning_matrices()
            .iter()
            .flat_map(|m| m.to_cols_array())
            .collect())
    }

    /// Writes every creature's skinning matrices (as [`skinning`](Self::skinning) gives
    /// them), one creature after another, into `out`; returns how many floats it wrote
    /// (fewer than needed when `out` is too short: it stops at the last whole creature).
    pub fn all_skinning(&self, out: &mut [f32]) -> usize {
        let mut at = 0;
        for live in &self.creatures {
            let matrices = live.animator.skinning_matrices();
            let end = at + 16 * matrices.len();
            let Some(into) = out.get_mut(at..end) else {
                break;
            };
            for (chunk, m) in into.chunks_exact_mut(16).zip(matrices) {
                chunk.copy_from_slice(&m.to_cols_array());
            }
            at = end;
        }
        at
    }

    /// Creature `i`'s place (the point that goes to its target, `Animator::lead`: its root's
    /// ground point, a slitherer's head's; `x, y, z`) and heading (radians).
    ///
    /// # Errors
    /// No creature `i`.
    pub fn place(&self, i: usize) -> Result<Vec<f32>, JsError> {
        let a = &self.get(i)?.animator;
        let p = a.lead();
        Ok(vec![p.x, p.y, p.z, a.heading()])
    }

    /// Creature `i`'s target (`x, z`), or nothing once it has arrived (or was never sent).
    ///
    /// # Errors
    /// No creature `i`.
    pub fn target(&self, i: usize) -> Result<Option<Vec<f32>>, JsError> {
        Ok(self.get(i)?.target.map(|t| vec![t.x, t.z]))
    }

    /// Sends creature `i` to `(x, z)`: it walks (flies, swims) there and stands (lands) on
    /// arrival, within [`ARRIVAL_RADIUS`] of its body length.
    ///
    /// # Errors
    /// No creature `i`, or a point that is not on the terrain.
    pub fn go_to(&mut self, i: usize, x: f32, z: f32) -> Result<(), JsError> {
        if self.height_at(x, z).is_none() {
            return Err(js(format!("({x}, {z}) is not on the terrain")));
        }
        self.get_mut(i)?.target = Some(Vec3::new(x, 0.0, z));
        Ok(())
    }

    /// Makes creature `i` wander (a new random target on the terrain each time it arrives)
    /// or, with `false`, stand once it arrives.
    ///
    /// # Errors
    /// No creature `i`.
    pub fn set_wander(&mut self, i: usize, wander: bool) -> Result<(), JsError> {
        self.get_mut(i)?.wander = wander;
        Ok(())
    }

    /// Moves time on by `dt` seconds (at most the animator's `MAX_STEP` at a time is taken):
    /// every creature goes toward its target, or stands; one that arrives stands (a wanderer
    /// picks its next target).
    ///
    /// # Errors
    /// A `dt` that is negative or not finite (nothing moves then), or a creature the animator
    /// rejects.
    pub fn update(&mut self, dt: f32) -> Result<(), JsError> {
        if !(dt >= 0.0 && dt.is_finite()) {
            return Err(js(format!(
                "time step {dt} s is not a finite number of seconds from 0 up"
            )));
        }
        let margin = 0.4 * self.size;
        for (i, live) in self.creatures.iter_mut().enumerate() {
            let intent = match live.target {
                Some(t) => {
                    let p = live.animator.lead();
                    let near = ARRIVAL_RADIUS * live.creature.length;
                    if Vec2::new(p.x - t.x, p.z - t.z).length() <= near {
                        live.target = None;
                        Intent::Stand
                    } else {
                        Intent::GoTo(t)
                    }
                }
                None => Intent::Stand,
            };
            if live.target.is_none() && live.wander {
                let x = (unit(&mut self.state) * 2.0 - 1.0) * margin;
                let z = (unit(&mut self.state) * 2.0 - 1.0) * margin;
                live.target = Some(Vec3::new(x, 0.0, z));
            }
            live.animator
                .update(dt, intent, &self.ground)
                .map_err(|e| js(format!("creature {i}: {e}")))?;
        }
        Ok(())
    }
}

impl World {
    /// Terrain from `seed` and `params`, with no creature.
    fn on(seed: u64, params: &TerrainParams) -> Result<Self, Error> {
        Ok(Self {
            ground: terrain(seed, params)?,
            size: params.size,
            creatures: Vec::new(),
            state: seed ^ 0x9E37_79B9_7F4A_7C15,
        })
    }

    /// Puts `creature` on the terrain at `at` facing `heading`, standing.
    fn live(&mut self, creature: d3::Creature, at: Vec3, heading: f32) -> Result<(), JsError> {
        let animator = Animator::new(&creature).map_err(js)?.with_pose(at, heading);
        self.creatures.push(Live {
            creature,
            animator,
            target: None,
            wander: false,
        });
        Ok(())
    }

    fn get(&self, i: usize) -> Result<&Live, JsError> {
        self.creatures.get(i).ok_or_else(|| {
            js(format!(
                "no creature {i}: there are {}",
                self.creatures.len()
            ))
        })
    }

    fn get_mut(&mut self, i: usize) -> Result<&mut Live, JsError> {
        let n = self.creatures.len();
        self.creatures
            .get_mut(i)
            .ok_or_else(|| js(format!("no creature {i}: there are {n}")))
    }
}

/// A uniform number in `[0, 1)` from a splitmix64 state.
fn unit(state: &mut u64) -> f32 {
    *state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^= z >> 31;
    // The top 24 bits: exact in an f32.
    (z >> 40) as f32 / (1u64 << 24) as f32
}

/// Vectors as one flat list of their components.
fn flat(v: &[Vec3]) -> Vec<f32> {
    v.iter().flat_map(|p| p.to_array()).collect()
}

/// A 2D creature (the 2D seed's metaball creature): its textured mesh and the seed page's
/// idle wiggle, skinned by the facade.
#[wasm_bindgen]
pub struct Creature2d {
    creature: d2::Creature,
}

#[wasm_bindgen]
impl Creature2d {
    /// The 2D creature of `seed` with a `texture_size`-pixel texture (the default params
    /// otherwise).
    ///
    /// # Errors
    /// A bad seed or texture size.
    #[wasm_bindgen(constructor)]
    pub fn new(seed: f64, texture_size: u32) -> Result<Creature2d, JsError> {
        let params = d2::Params::DEFAULT.with_texture_size(texture_size);
        let creature = creature::generate_2d(seed_from(seed).map_err(js)?, &params).map_err(js)?;
        Ok(Self { creature })
    }

    /// The mesh's texture coordinates, `u, v` each (`v` down from the texture's top row).
    #[must_use]
    pub fn uvs(&self) -> Vec<f32> {
        self.creature
            .mesh
            .uvs
            .iter()
            .flat_map(|uv| uv.to_array())
            .collect()
    }

    /// The mesh's triangles, three vertex indices each.
    #[must_use]
    pub fn indices(&self) -> Vec<u32> {
        self.creature
            .mesh
            .indices
            .iter()
            .flatten()
            .copied()
            .collect()
    }

    /// The outline's bounding box: `min x, min y, max x, max y`.
    #[must_use]
    pub fn bounds(&self) -> Vec<f32> {
        let (a, b) = self.creature.bounds;
        vec![a.x, a.y, b.x, b.y]
    }

    /// The texture's side in pixels (0 without one).
    #[must_use]
    pub fn texture_width(&self) -> u32 {
        self.creature.texture.as_ref().map_or(0, |t| t.width)
    }

    /// The texture's height in pixels (0 without one).
    #[must_use]
    pub fn texture_height(&self) -> u32 {
        self.creature.texture.as_ref().map_or(0, |t| t.height)
    }

    /// The texture, RGBA8, row 0 at the top (empty without one).
    #[must_use]
    pub fn texture(&self) -> Vec<u8> {
        self.creature
            .texture
            .as_ref()
            .map_or_else(Vec::new, |t| t.rgba.clone())
    }

    /// The mesh skinned to the idle wiggle at `t` seconds (`d2::Creature::posed_positions`):
    /// `x, y, z` per vertex (`z`, from 0 to 1, draws higher parts on top).
    #[must_use]
    pub fn pose(&self, t: f32) -> Vec<f32> {
        let c = &self.creature;
        c.posed_positions(&c.idle_rotations(t))
            .iter()
            .zip(&c.mesh.positions)
            .flat_map(|(at, rest)| [at.x, at.y, rest.z])
            .collect()
    }

    /// The eyes at `t` seconds of the idle wiggle: `x, y, radius` each.
    #[must_use]
    pub fn eyes(&self, t: f32) -> Vec<f32> {
        let c = &self.creature;
        c.posed_eyes(&c.idle_rotations(t))
            .iter()
            .zip(&c.eyes)
            .flat_map(|(at, eye)| [at.x, at.y, eye.radius])
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn seeds_are_whole_numbers_javascript_carries_exactly() {
        assert_eq!(seed_from(7.0), Ok(7));
        assert_eq!(seed_from(MAX_SEED), Ok(9_007_199_254_740_991));
        for bad in [-1.0, 0.5, f64::NAN, f64::INFINITY, MAX_SEED + 2.0] {
            assert!(seed_from(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn the_page_params_are_the_defaults_with_fixed_values() -> Result<(), String> {
        assert_eq!(
            params_3d("walker", None, None, None, None)?,
            d3::Params::DEFAULT.with_kind(Kind::Walker)
        );
        let p = params_3d("flier", Some(1.5), None, None, Some(0.8))?;
        assert_eq!(p.body_scale, Span::new(1.5, 1.5));
        assert_eq!(p.neck_width, 0.8);
        let e = params_3d("walker", Some(-1.0), None, None, None).err();
        assert!(e.is_some_and(|e| e.contains("body_scale")));
        assert!(params_3d("dragon", None, None, None, None).is_err());
        Ok(())
    }

    #[test]
    fn the_wanderers_draws_stay_in_zero_to_one() {
        let mut state = 3;
        for _ in 0..10_000 {
            let u = unit(&mut state);
            assert!((0.0..1.0).contains(&u));
        }
    }
}
