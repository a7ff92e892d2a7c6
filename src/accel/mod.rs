//! Acceleration: primitives placed in the world, and both levels of the BVH (the scene
//! level over primitives, the mesh level over triangles), which share one 8-wide node
//! layout and its SIMD box tests.

pub mod mesh_bvh;
pub mod primitive;
pub mod scene_bvh;
pub mod triangle;
pub(crate) mod wide;
