//! Shapes as Mitsuba 3 shapes, for `prism export mitsuba`: the exporter writes each as a
//! `<shape>` of Mitsuba's canonical form placed by a `to_world` matrix, so a shape plugin
//! only says which canonical shape it is and how it sits in its own object space.

use glam::{DAffine3, DVec3};

/// One of Mitsuba 3's shape plugins in its canonical form.
#[derive(Clone, Debug, PartialEq)]
pub enum MitsubaKind {
    /// `sphere`: the unit sphere at the origin (Mitsuba needs a similarity placement).
    Sphere,
    /// `rectangle`: the square [-1, 1]^2 in the z = 0 plane, normal +z.
    Rectangle,
    /// `disk`: the unit disc in the z = 0 plane, normal +z.
    Disk,
    /// `cube`: the cube [-1, 1]^3, normals outward.
    Cube,
    /// `cylinder`: the open tube of radius `radius` from z = 0 to z = `length`, normals
    /// outward (Mitsuba needs a similarity placement).
    Cylinder {
        /// The tube's radius.
        radius: f64,
        /// The tube's length along +z.
        length: f64,
    },
    /// A triangle mesh, written as a PLY file beside the scene.
    Triangles(TriangleList),
}

/// Triangles in object space.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TriangleList {
    /// Vertex positions.
    pub positions: Vec<[f32; 3]>,
    /// Unit vertex normals (empty: flat shading, Mitsuba's `face_normals`).
    pub normals: Vec<[f32; 3]>,
    /// Texture coordinates (empty: none), v downward as in Prism.
    pub uvs: Vec<[f32; 2]>,
    /// Vertex indices, counter-clockwise around the front side.
    pub triangles: Vec<[u32; 3]>,
}

/// A shape as one canonical Mitsuba shape placed in the shape's object space.
#[derive(Clone, Debug, PartialEq)]
pub struct MitsubaShape {
    /// Which shape.
    pub kind: MitsubaKind,
    /// Object space from the canonical shape's space.
    pub object_from_shape: DAffine3,
    /// Mitsuba's (u, v) on this part is the shape's own [`crate::Surface::uv`], so that an
    /// image texture lands where it does in Prism; the exporter refuses textures otherwise.
    pub same_uv: bool,
}

impl MitsubaShape {
    /// A canonical shape placed by `object_from_shape`, whose Mitsuba (u, v) is the shape's.
    pub fn new(kind: MitsubaKind, object_from_shape: DAffine3) -> Self {
        Self { kind, object_from_shape, same_uv: true }
    }

    /// The same part, marked as parameterised otherwise in Mitsuba than by the shape (a
    /// sphere's poles on another axis, a disk's (r, angle) for the shape's (angle, r)).
    pub fn with_other_uv(self) -> Self {
        Self { same_uv: false, ..self }
    }
}

/// The rotation taking +z to the unit vector `axis` (any rotation about it), as the columns
/// of an orthonormal frame (x, y, axis).
pub fn frame_with_z(axis: DVec3) -> glam::DMat3 {
    let z = axis.normalize();
    let x = crate::math::tangent(z);
    glam::DMat3::from_cols(x, z.cross(x), z)
}
