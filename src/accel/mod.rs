//! Acceleration: primitives placed in the world, and both levels of the BVH (the scene
//! level over primitives, the mesh level over triangles), which share one 8-wide node
//! layout; the SIMD kernels of both (box and triangle tests) live in `simd`, once per
//! instruction set.

pub mod mesh_bvh;
pub(crate) mod pages;
pub mod primitive;
pub mod scene_bvh;
pub(crate) mod simd;
pub mod triangle;
pub mod triangle_groups;
pub(crate) mod wide;

pub use simd::instruction_set;
