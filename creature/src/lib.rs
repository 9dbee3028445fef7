#![doc = include_str!("../README.md")]
#![no_std]
#![cfg_attr(docsrs, feature(doc_cfg))]
#![doc(test(attr(deny(warnings))))]

extern crate alloc;
#[cfg(feature = "std")]
extern crate std;

#[cfg(not(any(feature = "std", feature = "libm")))]
compile_error!("creature needs its `std` feature (default) or its `libm` feature for float math");

mod body3d;
mod clip3d;
mod error;
#[cfg(feature = "export")]
#[cfg_attr(docsrs, doc(cfg(feature = "export")))]
pub mod export;
#[cfg(feature = "export")]
mod export3d;
mod gait3d;
mod generate3d;
mod limbs3d;
mod math;
mod noise;
mod params;
mod params3d;
mod pipeline;
mod preview3d;
mod skeleton;
#[cfg(feature = "proptest")]
#[cfg_attr(docsrs, doc(cfg(feature = "proptest")))]
pub mod strategies;
pub mod texture;
mod types;
mod types3d;

pub use clip3d::{CLIP_FPS, Clip, Track};
pub use error::Error;
pub use gait3d::GaitSetup;
pub use generate3d::generate;
pub use params::{IntSpan, Params2d, Span};
pub use params3d::{Kind, Params};
pub use pipeline::{MAX_BONES, build_2d, generate_2d};
pub use preview3d::{PREVIEW_BACKGROUND, preview_3d};
pub use skeleton::{skeleton_2d, skeleton_2d_from_seed};
pub use texture::{Image, TextureOptions};
pub use types::{Ball2d, Bone2, BoneKind, Creature2d, Eye, Mesh2d, Quality2d, Skeleton2d};
pub use types3d::{Creature, Joint3d, Mesh3d, Part, Quality3d, Skeleton3d};

/// Auto-rigging of body meshes: the [`creature-autorig`](https://docs.rs/creature-autorig) crate.
pub use creature_autorig as autorig;
/// Free-form deformation lattices: the [`creature-ffd`](https://docs.rs/creature-ffd) crate.
pub use creature_ffd as ffd;
/// Gait control: the [`creature-gait`](https://docs.rs/creature-gait) crate.
pub use creature_gait as gait;
/// Limb socket planning: the [`creature-limbs`](https://docs.rs/creature-limbs) crate.
pub use creature_limbs as limbs;
/// Marching squares and meshing: the [`creature-march`](https://docs.rs/creature-march) crate.
pub use creature_march as march;
/// Metaball fields: the [`creature-metaball`](https://docs.rs/creature-metaball) crate.
pub use creature_metaball as metaball;
/// Skinning weights: the [`creature-skin`](https://docs.rs/creature-skin) crate.
pub use creature_skin as skin;

/// The `glam` version this crate's signatures use.
pub use glam;
/// The `rand_core` version [`skeleton_2d`] takes generators from.
pub use rand_core;
/// The seeded generator `generate_2d` uses (`Pcg64Mcg`).
pub use rand_pcg;
