//! Geometry that Prism owns itself rather than a plugin: triangle meshes (vertex data, the
//! mesh shape with its bottom-level BVH, area sampling) and CSG groups over any shapes.

pub mod csg;
pub mod member_tree;
pub mod mesh;
