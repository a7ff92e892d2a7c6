//! Helpers for writing POV-Ray 3.7 scene description language.
//!
//! Prism is right-handed, POV-Ray left-handed; the exporter maps every point, direction and
//! normal with `(x, y, z) -> (x, y, -z)`. Shapes write their object-space geometry through
//! [`vector`], and the exporter writes the transform mirrored the same way.

use glam::DVec3;

/// A number as POV-Ray SDL, with enough digits to round-trip an `f64`.
pub fn number(v: f64) -> String {
    format!("{v:?}")
}

/// A point or direction in Prism's frame as a POV-Ray vector `<x, y, -z>`.
pub fn vector(v: DVec3) -> String {
    format!("<{}, {}, {}>", number(v.x), number(v.y), number(-v.z))
}
