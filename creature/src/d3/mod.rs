//! 3D creatures, the 3D seed's way: walkers, fliers, swimmers and slitherers with a skinned
//! low-poly mesh, a skeleton, limbs and baked gait clips.
//!
//! [`generate`] runs the pipeline from a seed as a short sequence of stages (see
//! `ARCHITECTURE.md` for the crates each uses): body (blended pill profiles, FFD), rig and
//! skin, spine bend, head, limbs, ground, gait set-up, and the [`Clip`]s a [`Creature`] bakes;
//! the colours (a [`Palette`], countershading and a [`Pattern`]) are vertex colours.
//!
//! ```
//! use creature::d3;
//!
//! let walker = d3::generate(7, &d3::Params::DEFAULT.with_kind(d3::Kind::Walker))?;
//! assert!(!walker.clips.is_empty());
//! # Ok::<(), creature::Error>(())
//! ```

mod accessories;
mod body;
mod clip;
pub(crate) mod colour;
mod creature;
mod extremities;
mod gait;
mod generate;
mod head;
mod limbs;
mod params;
mod wings;

pub use accessories::{BackKind, BackWeights};
pub use clip::{ARRIVAL_RADIUS, Animator, CLIP_FPS, Clip, Intent, MAX_STEP, Track};
pub use colour::{Palette, Pattern, PatternWeights};
pub use creature::{Creature, Joint, Mesh, Part, Quality, Skeleton};
pub use gait::{GaitSetup, HOP_CLIP_FROUDE, HOP_FROUDE, RUN_FROUDE};
pub use generate::generate;
pub use params::{Kind, Params};
pub use wings::{WingKind, WingWeights};
