//! delmesh — tetrahedral and triangular mesh generation with exact predicates,
//! used from C, C++ and Fortran through a stable C ABI (`ffi`, header `include/delmesh.h`).
//!
//! Layers, bottom up (see the design notes in the README):
//! - [`predicates`]: exact orientation, in-sphere and power tests with a deterministic
//!   symbolic perturbation;
//! - [`triangulation`]: 3D Delaunay and regular triangulations in flat index arrays;
//! - [`domain`]: the geometry as an oracle (implicit and labeling functions);
//! - [`criteria`]: facet and cell bounds, constant or sizing fields;
//! - [`refine`]: oracle-driven Delaunay refinement (restricted Delaunay, refinement levels);
//! - [`recovery`]: tetrahedralization of a triangulated surface, every triangle kept;
//! - [`mesh2d`]: planar Delaunay and conforming (Pébay) triangulations;
//! - [`optimize`]: sliver removal after refinement (exudation);
//! - [`prefetch`]: cache hints for the searches whose next steps are known ahead;
//! - [`mesh`]: the result type handed to users, and its [`quality`] report;
//! - `ffi`: the C ABI, a panic boundary around every exported function.

pub mod criteria;
pub mod domain;
pub mod error;
pub mod ffi;
pub mod geometry;
pub mod io;
pub mod mesh;
pub mod mesh2d;
pub mod optimize;
pub mod predicates;
pub mod prefetch;
pub mod quality;
pub mod recovery;
pub mod refine;
pub mod triangulation;
pub mod union_find;

pub use error::{Error, ErrorKind, Result};
pub use mesh::Mesh;

/// Version of the C ABI; bumped on every breaking change of `include/delmesh.h`.
pub const ABI_VERSION: u32 = 1;
