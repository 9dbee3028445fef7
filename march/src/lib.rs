#![doc = include_str!("../README.md")]
#![no_std]
#![cfg_attr(docsrs, feature(doc_cfg))]
#![doc(test(attr(deny(warnings))))]

extern crate alloc;
#[cfg(feature = "std")]
extern crate std;

#[cfg(not(any(feature = "std", feature = "libm")))]
compile_error!(
    "creature-march needs its `std` feature (default) or its `libm` feature for float math"
);

#[cfg(feature = "mesh")]
mod cdt;
mod cell;
mod error;
mod grid;
#[cfg(feature = "mesh")]
mod math;
#[cfg(feature = "mesh")]
mod mesh;
mod options;
mod ring;
mod sort;
#[cfg(feature = "proptest")]
#[cfg_attr(docsrs, doc(cfg(feature = "proptest")))]
pub mod strategies;
mod tile;
mod trace;

pub use error::MarchError;
pub use grid::{MAX_GRID_SAMPLES, march_grid, march_grid_with};
#[cfg(feature = "mesh")]
#[cfg_attr(docsrs, doc(cfg(feature = "mesh")))]
pub use mesh::{
    MAX_INTERIOR_EXTENT, MAX_INTERIOR_POINTS, Mesh2, MeshOptions, MeshQuality, triangulate,
};
pub use options::{MAX_CELLS, MAX_GRID_COORDINATE, MarchOptions, Saddle};
pub use ring::{Ring, contains_each, validate_rings};
pub use tile::{TILE_NODES, TILE_SIZE, TileField, node_point};
pub use trace::{trace, trace_field, trace_with};

/// The `glam` version this crate's signatures use.
pub use glam;
