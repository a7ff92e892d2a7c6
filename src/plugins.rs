//! Shape registration: one line per shape plugin crate.

use prism_api::shape_type;

use crate::registry::ShapeRegistry;

/// The registry of every shape type Prism ships.
pub fn registry() -> ShapeRegistry {
    let mut registry = ShapeRegistry::new();
    registry.add(shape_type::<prism_sphere::SphereParams>("sphere", "A sphere around a centre point."));
    registry.add(shape_type::<prism_plane::PlaneParams>("plane", "An infinite plane (a solid half-space)."));
    registry.add(shape_type::<prism_disc::DiscParams>("disc", "A flat disc, optionally with a hole."));
    registry.add(shape_type::<prism_rectangle::RectangleParams>(
        "rectangle",
        "A flat rectangle in the z = 0 plane, facing +z (Mitsuba 3's rectangle).",
    ));
    registry.add(shape_type::<prism_cone::ConeParams>("cone", "A finite cone, capped unless open."));
    registry.add(shape_type::<prism_cylinder::CylinderParams>("cylinder", "A finite cylinder, capped unless open."));
    registry.add(shape_type::<prism_box::BoxParams>("box", "An axis-aligned box."));
    registry.add(shape_type::<prism_triangle::TriangleParams>("triangle", "A single triangle."));
    registry.add(shape_type::<prism_torus::TorusParams>("torus", "A torus around the y axis."));
    registry.add(shape_type::<prism_superellipsoid::SuperellipsoidParams>(
        "superellipsoid",
        "POV-Ray's superquadric ellipsoid in the cube [-1, 1]^3.",
    ));
    registry
        .add(shape_type::<prism_blob::BlobParams>("blob", "Metaballs: spherical field components around a threshold."));
    registry.add(shape_type::<prism_template::CapsuleParams>("capsule", "A capsule (pill) along the y axis."));
    registry.add(shape_type::<prism_text::TextParams>(
        "text",
        "TrueType text extruded along -z (POV-Ray's text { ttf ... }).",
    ));
    registry
}
