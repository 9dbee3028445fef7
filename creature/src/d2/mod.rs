//! 2D creatures, the 2D seed's way: a random skeleton covered with metaballs, outlined,
//! meshed, skinned and textured.
//!
//! [`generate`] runs the whole pipeline from a seed; [`skeleton`] and [`build`] split it at the
//! skeleton, for callers that draw or edit skeletons themselves. The stages, in order
//! (see `ARCHITECTURE.md` for the crates each uses):
//!
//! 1. [`skeleton`] — spine, limbs, eyes and colours from the generator ([`Params`]);
//! 2. cover — metaballs along every bone ([`Ball`]), `creature-metaball`'s bone covering;
//! 3. outline — the culled field traced into rings (`creature-march`'s `trace_field`);
//! 4. mesh — the rings triangulated with interior points (`creature-march`'s `triangulate`);
//! 5. skin — weights from the balls' field shares (`creature-skin`);
//! 6. texture — the CPU texture and normal map ([`render_texture`]).
//!
//! ```
//! use creature::d2;
//!
//! let creature = d2::generate(7, &d2::Params::DEFAULT.with_texture_size(64))?;
//! assert!(!creature.mesh.indices.is_empty());
//! # Ok::<(), creature::Error>(())
//! ```

mod creature;
mod generate;
mod params;
mod skeleton;
mod texture;

pub use creature::{
    Ball, Bone, BoneKind, Creature, Eye, IDLE_LOOP_SECONDS, Mesh, Quality, Skeleton,
};
pub use generate::{MAX_BONES, build, generate};
pub use params::Params;
pub use skeleton::{skeleton, skeleton_from_seed};
pub use texture::{TextureOptions, render_texture};
