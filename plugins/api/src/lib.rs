//! The plugin API of the Prism ray tracer.
//!
//! A shape plugin is a crate with a parameter struct (`Deserialize + JsonSchema`, unknown
//! fields denied), one [`ShapeParams`] impl that validates the parameters and builds the
//! shape, and one [`Shape`] impl that intersects rays in the shape's own object space.
//! Prism registers it with one line in its `src/plugins.rs`:
//!
//! ```ignore
//! registry.add(prism_api::shape_type::<SphereParams>("sphere", "A sphere centred on the origin."));
//! ```
//!
//! Everything here is `f64`: analytic shapes are solved in double precision, as POV-Ray does.
//! Right-handed, y up. The [`contract`] module is a test kit every plugin runs.

#![forbid(unsafe_code)]

mod aabb;
pub mod contract;
pub mod files;
pub mod math;
pub mod mitsuba;
pub mod pov;
mod ray;
mod registry;
mod shape;

pub use aabb::Aabb;
pub use files::{FileReader, LocalFiles, NoFiles, ParamFile};
pub use glam::{DAffine3, DMat3, DVec2, DVec3};
pub use ray::Ray;
pub use registry::{ParamError, ShapeParams, ShapeType, shape_type};
pub use shape::{
    AreaSample, CROSSING_GAP, DirectionSample, Hit, HitPoint, MAX_CROSSINGS, Shape, Surface, crossings_by_intersect,
    for_each_crossing, pdf_toward_by_area, sample_toward_by_area, sample_toward_flat, visit_solved_crossings,
};

/// Re-exported so that plugins derive their parameter schema with the same version Prism uses.
pub use schemars;
/// Re-exported so that plugins use the same serde as Prism.
pub use serde;
