#![doc = include_str!("../README.md")]
#![no_std]
#![cfg_attr(docsrs, feature(doc_cfg))]
#![doc(test(attr(deny(warnings))))]

extern crate alloc;
#[cfg(feature = "std")]
extern crate std;

#[cfg(not(any(feature = "std", feature = "libm")))]
compile_error!("creature needs its `std` feature (default) or its `libm` feature for float math");

pub mod d2;
pub mod d3;
mod error;
pub mod export;
mod image;
mod math;
mod rng;
mod sort;
mod span;
#[cfg(feature = "proptest")]
#[cfg_attr(docsrs, doc(cfg(feature = "proptest")))]
pub mod strategies;
pub mod terrain;

pub use d2::generate as generate_2d;
pub use d3::generate;
pub use error::Error;
pub use image::Image;
pub use span::{IntSpan, Span};

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
/// The `rand_core` version [`d2::skeleton`] takes generators from.
pub use rand_core;
/// The seeded generator `generate_2d` uses (`Pcg64Mcg`).
pub use rand_pcg;
