//! Helpers for writing POV-Ray 3.7 scene description language.
//!
//! Prism is right-handed, POV-Ray left-handed; the exporter maps every point, direction and
//! normal with `(x, y, z) -> (x, y, -z)`. Shapes write their object-space geometry through
//! [`vector`], and the exporter writes the transform mirrored the same way.

use glam::DVec3;

/// POV-Ray's `EPSILON` (1e-10): the skin of points on a surface that its inside tests put on
/// one side, deterministically, where rounding alone would scatter them. A closed cylinder or
/// cone counts the skin (in its unit space) as outside, an open one as inside; a plane and a
/// superellipsoid count it as inside. Coincident surfaces in CSG (a tube bored with a
/// cylinder of the same length) depend on it.
pub const EPSILON: f64 = 1e-10;

/// The skin a closed (`open` false) or open cylinder or cone counts inside: `-EPSILON` or
/// `EPSILON` in its unit space, as POV-Ray's `Cone::Inside` offsets its tests.
pub fn unit_skin(open: bool) -> f64 {
    if open { EPSILON } else { -EPSILON }
}

/// POV-Ray's inside test of the unit cylinder (radius 1, from z = 0 to 1), for a point whose
/// squared distance from the axis is `w2` and height `z` there.
pub fn inside_unit_cylinder(w2: f64, z: f64, open: bool) -> bool {
    let skin = unit_skin(open);
    w2 <= 1.0 + skin && z >= -skin && z <= 1.0 + skin
}

/// A number as POV-Ray SDL, with enough digits to round-trip an `f64`.
pub fn number(v: f64) -> String {
    format!("{v:?}")
}

/// A point or direction in Prism's frame as a POV-Ray vector `<x, y, -z>`.
pub fn vector(v: DVec3) -> String {
    format!("<{}, {}, {}>", number(v.x), number(v.y), number(-v.z))
}

/// A string as a POV-Ray SDL string literal: quoted, with `"` and `\` escaped and every
/// character outside printable ASCII written as `\uXXXX`; `None` for a character beyond
/// the Basic Multilingual Plane, which POV-Ray's UCS-2 strings cannot hold.
pub fn string(text: &str) -> Option<String> {
    let mut out = String::with_capacity(text.len() + 2);
    out.push('"');
    for c in text.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            ' '..='~' => out.push(c),
            _ => {
                let code = u16::try_from(u32::from(c)).ok()?;
                out.push_str(&format!("\\u{code:04X}"));
            }
        }
    }
    out.push('"');
    Some(out)
}

/// A file path as a POV-Ray SDL string literal, `None` when POV-Ray cannot read it back: it
/// parses file names with escapes off (`Parse_C_String(true)`), so a `"` ends the string, a
/// `\` stays a backslash and `\uXXXX` is not decoded; only printable ASCII without quotes and
/// backslashes survives.
pub fn path_string(path: &str) -> Option<String> {
    if !path.chars().all(|c| matches!(c, ' '..='~') && c != '"' && c != '\\') {
        return None;
    }
    Some(format!("\"{path}\""))
}

/// How the exporter writes the path of a file a shape reads (a font): relative to the
/// exported file's folder when it has one (POV-Ray is then run with that folder as a library
/// path, `+L`), absolute otherwise. Passed to [`crate::Shape::to_pov_with`].
pub trait FilePaths {
    /// `file` (absolute) as a POV-Ray string literal, `None` when it cannot be written as one.
    fn path(&self, file: &std::path::Path) -> Option<String>;
}

/// [`FilePaths`] that writes every path as it is (absolute paths stay absolute).
#[derive(Clone, Copy, Debug, Default)]
pub struct AsGiven;

impl FilePaths for AsGiven {
    fn path(&self, file: &std::path::Path) -> Option<String> {
        path_string(file.to_str()?)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn path_strings_hold_only_what_povray_reads_back() {
        assert_eq!(path_string("fonts/DejaVu Sans.ttf").as_deref(), Some("\"fonts/DejaVu Sans.ttf\""));
        for unreadable in ["q\"uote.png", "back\\slash.png", "tab\t.png", "café.png"] {
            assert_eq!(path_string(unreadable), None, "{unreadable}");
        }
        // A string keeps its escapes: POV-Ray decodes them outside file names.
        assert_eq!(string("q\"é").as_deref(), Some("\"q\\\"\\u00E9\""));
    }
}
