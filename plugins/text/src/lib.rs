//! The text shape plugin: POV-Ray's `text { ttf "font.ttf" "string" thickness, offset }`, a
//! string of TrueType glyphs extruded along z, intersected exactly with the font's quadratic
//! outlines (no tessellation).
//!
//! Layout, scale and inside rule follow POV-Ray 3.7's `truetype.cpp`:
//!
//! * one unit is one em: outline coordinates are divided by the font's units per em;
//! * the first glyph is moved so that its left edge (the glyph's `xMin`) is at x = 0, and the
//!   pen then advances by its advance width less its left side bearing; every later glyph is
//!   placed at the pen plus its left side bearing less its `xMin` plus the horizontal kerning
//!   of the pair (format 0 `kern` subtables read as POV-Ray reads them, see `font.rs`; clamped
//!   below at -1 em), and the pen advances by its advance width plus that kerning;
//! * characters map to glyphs through the cmap table POV-Ray's default `ascii` charset picks
//!   (Macintosh first, see `font.rs`);
//! * after each glyph the pen moves by `offset` (x and y; POV-Ray ignores its z);
//! * each glyph is extruded over the thickness, the front face in the plane z = 0 facing the
//!   default camera (+z; POV-Ray's z = 0 facing -z after the exporter's mirror) and the back
//!   face at z = -thickness;
//! * a point is inside a glyph by the even-odd rule over all its contours; the text is the
//!   union of its glyphs.

#![forbid(unsafe_code)]

mod font;

use std::path::PathBuf;
use std::sync::Arc;

use prism_api::math::solve_quadratic;
use prism_api::{
    Aabb, DAffine3, DMat3, DVec2, DVec3, FileReader, Hit, ParamError, Ray, Shape, ShapeParams, Surface, pov,
};
use schemars::JsonSchema;
use serde::Deserialize;

/// The longest `string`, in characters.
pub const MAX_CHARS: usize = 1024;
/// The most outline pieces (lines and y-monotone quadratic arcs) a text may hold.
pub const MAX_SEGMENTS: usize = 1 << 20;
/// The largest `thickness` and `offset` component, in ems.
pub const MAX_EXTENT: f64 = 1e6;

/// Parameters of `shape = "text"`.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct TextParams {
    /// Path of a TrueType font file (.ttf with glyf outlines), relative to the scene file.
    pub font: String,
    /// The text to write, at most 1024 characters; every character needs a glyph in the font.
    pub string: String,
    /// Depth of the extrusion along -z, in ems; greater than 0 (POV-Ray's default 1).
    #[serde(default = "default_thickness")]
    pub thickness: f64,
    /// Extra pen movement after each character, [x, y] or [x, y, z] in ems (z is ignored, as in POV-Ray).
    #[serde(default = "default_offset")]
    #[schemars(length(min = 2, max = 3))]
    pub offset: Vec<f64>,
}

fn default_thickness() -> f64 {
    1.0
}

fn default_offset() -> Vec<f64> {
    vec![0.0, 0.0]
}

impl ShapeParams for TextParams {
    /// Text needs its font file: Prism builds it with [`ShapeParams::build_with_files`].
    fn build(self) -> Result<Arc<dyn Shape>, ParamError> {
        Err(ParamError::new("font", "cannot be read: build `text` with a file reader"))
    }

    fn build_with_files(self, files: &mut dyn FileReader) -> Result<Arc<dyn Shape>, ParamError> {
        ParamError::require_positive("thickness", self.thickness)?;
        if self.thickness > MAX_EXTENT {
            return Err(ParamError::new("thickness", format!("must be at most {MAX_EXTENT}, got {}", self.thickness)));
        }
        if !(2..=3).contains(&self.offset.len()) {
            return Err(ParamError::new("offset", format!("must be [x, y] or [x, y, z], got {:?}", self.offset)));
        }
        ParamError::require_finite("offset", &self.offset)?;
        if self.offset.iter().any(|v| v.abs() > MAX_EXTENT) {
            return Err(ParamError::new("offset", format!("components must be within ±{MAX_EXTENT}")));
        }
        let chars = self.string.chars().count();
        if chars > MAX_CHARS {
            return Err(ParamError::new("string", format!("must be at most {MAX_CHARS} characters, got {chars}")));
        }
        let file = files.read("font", &self.font)?;
        let offset = DVec3::new(self.offset[0], self.offset[1], self.offset.get(2).copied().unwrap_or(0.0));
        let glyphs = layout(&file.bytes, &self.font, &self.string, offset.truncate())?;
        Ok(Arc::new(Text::new(glyphs, self.thickness, file.path, self.string, offset)))
    }
}

/// A piece of a glyph's outline in ems, monotone in y: a line (`p1` its midpoint) or a
/// quadratic Bézier arc.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Segment {
    p0: DVec2,
    p1: DVec2,
    p2: DVec2,
    line: bool,
    /// +1 when the right-hand normal of the direction of travel, (dy, -dx), points out of
    /// the glyph, -1 when it points in.
    outward: f64,
}

impl Segment {
    fn at(&self, s: f64) -> DVec2 {
        let r = 1.0 - s;
        r * r * self.p0 + 2.0 * s * r * self.p1 + s * s * self.p2
    }

    fn tangent(&self, s: f64) -> DVec2 {
        let d = 2.0 * (1.0 - s) * (self.p1 - self.p0) + 2.0 * s * (self.p2 - self.p1);
        if d.length_squared() > 0.0 { d } else { self.p2 - self.p0 }
    }

    /// The unit outward normal in the glyph's plane at `s`.
    fn normal(&self, s: f64) -> DVec2 {
        let t = self.tangent(s);
        (self.outward * DVec2::new(t.y, -t.x)).normalize_or_zero()
    }

    /// Whether the horizontal ray from `p` toward +x crosses this piece (half-open in y, so
    /// a crossing at a joint between pieces counts once).
    fn crosses_rightward(&self, p: DVec2) -> bool {
        let (y0, y2) = (self.p0.y, self.p2.y);
        if (y0 <= p.y) == (y2 <= p.y) {
            return false;
        }
        let x = if self.line {
            self.p0.x + (p.y - y0) / (y2 - y0) * (self.p2.x - self.p0.x)
        } else {
            let a = y0 - 2.0 * self.p1.y + y2;
            let b = 2.0 * (self.p1.y - y0);
            let c = y0 - p.y;
            // Monotone: exactly one root in [0, 1]; rounding may push it a hair outside.
            let s = match solve_quadratic(a, b, c) {
                Some((r0, r1)) => {
                    if (-1e-9..=1.0 + 1e-9).contains(&r0) {
                        r0
                    } else {
                        r1
                    }
                }
                None => -b / (2.0 * a),
            };
            self.at(s.clamp(0.0, 1.0)).x
        };
        x > p.x
    }
}

/// One glyph placed in the line (in ems): its outline pieces as the font has them (the side
/// walls), the same outline split into pieces monotone in y (the inside test), and bounds.
#[derive(Clone, Debug, PartialEq)]
struct Glyph {
    segments: Vec<Segment>,
    monotone: Vec<Segment>,
    min: DVec2,
    max: DVec2,
}

impl Glyph {
    /// The even-odd rule over all contours, as POV-Ray's `Inside_Glyph`.
    fn contains(&self, p: DVec2) -> bool {
        if p.cmplt(self.min).any() || p.cmpgt(self.max).any() {
            return false;
        }
        self.monotone.iter().filter(|s| s.crosses_rightward(p)).count() % 2 == 1
    }
}

/// POV-Ray's `EPSILON`: a wall whose equation in the arc's parameter has a discriminant
/// below it (a ray grazing the arc, in ems, for a unit world direction), or a line the ray's
/// projection runs parallel to within it, is not hit (`solve_quad` in `truetype.cpp`).
const GRAZING: f64 = 1e-10;

/// A string of extruded TrueType glyphs (see the crate documentation for the layout).
#[derive(Clone, Debug, PartialEq)]
pub struct Text {
    glyphs: Vec<Glyph>,
    thickness: f64,
    /// POV-Ray's tilt (see [`pov_tilt`]): object space from the laid-out text, and back.
    tilt: DMat3,
    untilt: DMat3,
    /// Bounds of the laid-out text, before the tilt.
    flat_bounds: Aabb,
    bounds: Aabb,
    font: PathBuf,
    string: String,
    offset: DVec3,
}

/// `Hit::part` values.
const SIDE: u32 = 0;
const FRONT: u32 = 1;
const BACK: u32 = 2;

impl Text {
    fn new(glyphs: Vec<Glyph>, thickness: f64, font: PathBuf, string: String, offset: DVec3) -> Self {
        let (min, max) =
            glyphs.iter().fold((DVec2::INFINITY, DVec2::NEG_INFINITY), |(lo, hi), g| (lo.min(g.min), hi.max(g.max)));
        let flat_bounds = if glyphs.is_empty() {
            // Nothing to hit: an empty string or only spaces. A point-sized box keeps the BVH finite.
            Aabb::from_corners(DVec3::ZERO, DVec3::ZERO)
        } else {
            Aabb::from_corners(min.extend(-thickness), max.extend(0.0))
        };
        let tilt = pov_tilt();
        let bounds = flat_bounds.transformed(&DAffine3::from_mat3(tilt));
        Self { glyphs, thickness, tilt, untilt: tilt.inverse(), flat_bounds, bounds, font, string, offset }
    }

    /// `ray` in the frame of the laid-out text (before the tilt); `t` is unchanged.
    fn untilted(&self, ray: &Ray) -> Ray {
        Ray::new(self.untilt * ray.origin, self.untilt * ray.direction)
    }

    /// The nearest hit in the frame of the laid-out text.
    fn flat_intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit> {
        let mut best: Option<Hit> = None;
        for index in 0..self.glyphs.len() {
            let limit = best.map_or(t_max, |h| h.t);
            if let Some(hit) = self.glyph_hit(index, ray, t_min, limit) {
                best = Some(hit);
            }
        }
        best
    }

    /// The surface at a hit in the frame of the laid-out text.
    fn flat_surface(&self, ray: &Ray, hit: &Hit) -> Surface {
        let mut point = ray.at(hit.t);
        point.z = point.z.clamp(-self.thickness, 0.0);
        match hit.part {
            FRONT | BACK => {
                let (z, normal) = if hit.part == FRONT { (0.0, DVec3::Z) } else { (-self.thickness, DVec3::NEG_Z) };
                point.z = z;
                let width = (self.flat_bounds.max.x - self.flat_bounds.min.x).max(1e-300);
                Surface::new(point, normal, DVec2::ZERO).with_dpdu(DVec3::new(width, 0.0, 0.0))
            }
            _ => {
                let glyph = &self.glyphs[hit.scratch.x as usize];
                let seg = &glyph.segments[hit.scratch.y as usize];
                let n = seg.normal(hit.scratch.z);
                let n = if n == DVec2::ZERO { DVec2::X } else { n };
                let on_curve = seg.at(hit.scratch.z);
                Surface::new(on_curve.extend(point.z), n.extend(0.0), DVec2::ZERO)
            }
        }
    }

    /// The nearest hit on glyph `index` with `t_min < t < best`.
    fn glyph_hit(&self, index: usize, ray: &Ray, t_min: f64, best: f64) -> Option<Hit> {
        let glyph = &self.glyphs[index];
        let pad = 1e-9 * (1.0 + self.thickness);
        let bounds = Aabb::from_corners(
            glyph.min.extend(-self.thickness) - DVec3::splat(pad),
            glyph.max.extend(0.0) + DVec3::splat(pad),
        );
        let (t0, _) = bounds.ray_interval(ray, t_min, best)?;
        // Solve from the entry point: coefficients at the glyph's own scale.
        let origin = ray.at(t0);
        let d = ray.direction;
        let mut found: Option<Hit> = None;
        let keep = |found: &mut Option<Hit>, hit: Hit| {
            if hit.t > t_min && hit.t < found.map_or(best, |h| h.t) {
                *found = Some(hit);
            }
        };
        if d.z != 0.0 {
            for (plane, part) in [(0.0, FRONT), (-self.thickness, BACK)] {
                let local = (plane - origin.z) / d.z;
                let t = t0 + local;
                if t > t_min && t < found.map_or(best, |h| h.t) {
                    let p = origin.truncate() + local * d.truncate();
                    if glyph.contains(p) {
                        keep(&mut found, Hit { t, part, scratch: DVec3::new(index as f64, 0.0, 0.0) });
                    }
                }
            }
        }
        let dxy = d.truncate();
        let len2 = dxy.length_squared();
        if len2 > 0.0 {
            let o = origin.truncate();
            let cross = |v: DVec2| dxy.x * v.y - dxy.y * v.x;
            for (k, seg) in glyph.segments.iter().enumerate() {
                let c = cross(seg.p0 - o);
                let b = cross(2.0 * (seg.p1 - seg.p0));
                let a = if seg.line { 0.0 } else { cross(seg.p0 - 2.0 * seg.p1 + seg.p2) };
                let grazing = if seg.line { b.abs() < GRAZING } else { b * b - 4.0 * a * c < GRAZING };
                if grazing {
                    continue;
                }
                let Some((r0, r1)) = solve_quadratic(a, b, c) else { continue };
                for s in [r0, r1] {
                    if !(-1e-9..=1.0 + 1e-9).contains(&s) {
                        continue;
                    }
                    let s = s.clamp(0.0, 1.0);
                    let local = (seg.at(s) - o).dot(dxy) / len2;
                    let t = t0 + local;
                    let z = origin.z + local * d.z;
                    if z <= pad && z >= -self.thickness - pad {
                        keep(&mut found, Hit { t, part: SIDE, scratch: DVec3::new(index as f64, k as f64, s) });
                    }
                }
            }
        }
        found
    }
}

impl Shape for Text {
    fn bounds(&self) -> Aabb {
        self.bounds
    }

    fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit> {
        self.flat_intersect(&self.untilted(ray), t_min, t_max)
    }

    fn surface(&self, ray: &Ray, hit: &Hit) -> Surface {
        let surface = self.surface_geometry(ray, hit);
        let flat = self.untilt * surface.point;
        let (min, max) = (self.flat_bounds.min.truncate(), self.flat_bounds.max.truncate());
        let size = (max - min).max(DVec2::splat(1e-300));
        let uv = ((flat.truncate() - min) / size).clamp(DVec2::ZERO, DVec2::ONE);
        Surface { uv, uv_density: 1.0 / size.max_element(), ..surface }
    }

    fn surface_geometry(&self, ray: &Ray, hit: &Hit) -> Surface {
        let flat = self.flat_surface(&self.untilted(ray), hit);
        let normal = (self.tilt * flat.normal).normalize();
        Surface { point: self.tilt * flat.point, normal, shading_normal: normal, dpdu: self.tilt * flat.dpdu, ..flat }
    }

    fn inside(&self, point: DVec3) -> bool {
        let p = self.untilt * point;
        p.z <= 0.0 && p.z >= -self.thickness && self.glyphs.iter().any(|g| g.contains(p.truncate()))
    }

    /// Text cannot emit light: its area is exact but not sampled (POV-Ray's text is no light either).
    fn can_emit(&self) -> bool {
        false
    }

    fn to_pov_with(&self, files: &dyn pov::FilePaths) -> Option<String> {
        let font = files.path(&self.font)?;
        let string = pov::string(&self.string)?;
        Some(format!("text {{ ttf {font} {string} {}, {} }}", pov::number(self.thickness), pov::vector(self.offset)))
    }

    fn to_pov(&self) -> Option<String> {
        self.to_pov_with(&pov::AsGiven)
    }
}

/// POV-Ray's tilt of every text object: after laying the glyphs out, its parser turns the
/// text by `rotate <0.001, 0.001, 0.001>` (degrees; "this tiny rotation should fix cracks in
/// text that lies along an axis", `Parse_TrueType`), about x, then y, then z, in its
/// left-handed frame. Here as a rotation of Prism's object space (the mirror S = diag(1, 1,
/// -1) on both sides). It moves a point 1 em from the origin by about 2e-5 em: enough to
/// flip a pixel where a ray grazes an edge, so parity needs it.
fn pov_tilt() -> DMat3 {
    let (s, c) = 0.001_f64.to_radians().sin_cos();
    let x = DMat3::from_cols(DVec3::X, DVec3::new(0.0, c, s), DVec3::new(0.0, -s, c));
    let y = DMat3::from_cols(DVec3::new(c, 0.0, -s), DVec3::Y, DVec3::new(s, 0.0, c));
    let z = DMat3::from_cols(DVec3::new(c, s, 0.0), DVec3::new(-s, c, 0.0), DVec3::Z);
    let mirror = DMat3::from_diagonal(DVec3::new(1.0, 1.0, -1.0));
    mirror * (z * y * x) * mirror
}

/// Collects a glyph's contours from ttf-parser as lists of pieces (font units).
#[derive(Default)]
struct Outline {
    contours: Vec<Vec<(DVec2, DVec2, DVec2, bool)>>,
    start: DVec2,
    pen: DVec2,
    cubic: bool,
}

impl ttf_parser::OutlineBuilder for Outline {
    fn move_to(&mut self, x: f32, y: f32) {
        self.start = DVec2::new(x.into(), y.into());
        self.pen = self.start;
        self.contours.push(Vec::new());
    }

    fn line_to(&mut self, x: f32, y: f32) {
        let p = DVec2::new(x.into(), y.into());
        if let Some(c) = self.contours.last_mut() {
            c.push((self.pen, 0.5 * (self.pen + p), p, true));
        }
        self.pen = p;
    }

    fn quad_to(&mut self, x1: f32, y1: f32, x: f32, y: f32) {
        let p = DVec2::new(x.into(), y.into());
        if let Some(c) = self.contours.last_mut() {
            c.push((self.pen, DVec2::new(x1.into(), y1.into()), p, false));
        }
        self.pen = p;
    }

    fn curve_to(&mut self, _: f32, _: f32, _: f32, _: f32, x: f32, y: f32) {
        self.cubic = true;
        self.pen = DVec2::new(x.into(), y.into());
    }

    fn close(&mut self) {
        if self.pen != self.start
            && let Some(c) = self.contours.last_mut()
        {
            c.push((self.pen, 0.5 * (self.pen + self.start), self.start, true));
        }
        self.pen = self.start;
    }
}

/// Splits a quadratic piece at its extremum in y, so that every piece is monotone in y.
fn monotone_pieces(p0: DVec2, p1: DVec2, p2: DVec2, line: bool, out: &mut Vec<Segment>) {
    let piece = |p0, p1, p2, line| Segment { p0, p1, p2, line, outward: 1.0 };
    let denom = p0.y - 2.0 * p1.y + p2.y;
    let s = if line || denom == 0.0 { -1.0 } else { (p0.y - p1.y) / denom };
    if s > 0.0 && s < 1.0 {
        let a = p0.lerp(p1, s);
        let b = p1.lerp(p2, s);
        let mut m = a.lerp(b, s);
        // The split point is the extremum: both halves have a horizontal tangent there.
        m.y = p0.y + s * (p1.y - p0.y);
        let (a, b) = (DVec2::new(a.x, m.y), DVec2::new(b.x, m.y));
        out.push(piece(p0, a, m, false));
        out.push(piece(m, b, p2, false));
    } else {
        out.push(piece(p0, p1, p2, line));
    }
}

/// Per-glyph data read from the font.
struct FontGlyph {
    id: ttf_parser::GlyphId,
    /// Contours in ems: the font's pieces and the same split into y-monotone pieces.
    contours: Vec<(Vec<Segment>, Vec<Segment>)>,
    /// POV-Ray's `xMin` in font units (see [`pov_x_min`]).
    x_min: f64,
    advance: f64,
    lsb: f64,
}

/// POV-Ray's left edge of a glyph, in font units: the header's `xMin` lowered to the smallest
/// outline x of a simple glyph; for a composite glyph, POV-Ray compares its points in ems
/// with the header's font units and truncates to an integer, which leaves 0 whenever the
/// header's `xMin` is positive. Empty glyphs (a space) have 0.
fn pov_x_min(face: &ttf_parser::Face, id: ttf_parser::GlyphId, points_min_x_em: Option<f64>, units: f64) -> f64 {
    let Some(points_min) = points_min_x_em else { return 0.0 };
    let header = face.tables().glyf.and_then(|g| g.bbox(id)).map_or(0.0, |r| f64::from(r.x_min));
    if is_composite(face, id) {
        if points_min < header { points_min.trunc() } else { header }
    } else {
        header.min(points_min * units)
    }
}

/// Whether glyph `id` is a composite glyph (a negative contour count in `glyf`).
fn is_composite(face: &ttf_parser::Face, id: ttf_parser::GlyphId) -> bool {
    let raw = face.raw_face();
    let (Some(glyf), Some(loca)) =
        (raw.table(ttf_parser::Tag::from_bytes(b"glyf")), raw.table(ttf_parser::Tag::from_bytes(b"loca")))
    else {
        return false;
    };
    let i = usize::from(id.0);
    let start = match face.tables().head.index_to_location_format {
        ttf_parser::head::IndexToLocationFormat::Short => {
            loca.get(2 * i..2 * i + 2).map(|b| 2 * usize::from(u16::from_be_bytes([b[0], b[1]])))
        }
        ttf_parser::head::IndexToLocationFormat::Long => {
            loca.get(4 * i..4 * i + 4).and_then(|b| usize::try_from(u32::from_be_bytes([b[0], b[1], b[2], b[3]])).ok())
        }
    };
    start.and_then(|s| glyf.get(s)).is_some_and(|b| b & 0x80 != 0)
}

/// Lays out `string` in the font `bytes` (named `name` in messages) as POV-Ray does.
fn layout(bytes: &[u8], name: &str, string: &str, offset: DVec2) -> Result<Vec<Glyph>, ParamError> {
    let font_error = |why: &str| ParamError::new("font", format!("`{name}` {why}"));
    let face =
        ttf_parser::Face::parse(bytes, 0).map_err(|e| font_error(&format!("is not a readable TrueType font ({e})")))?;
    if face.tables().glyf.is_none() {
        return Err(font_error("has no TrueType (glyf) outlines; POV-Ray's text reads only those, not CFF"));
    }
    let units = f64::from(face.units_per_em());
    let mut segments_total = 0usize;
    let mut font_glyph = |c: char| -> Result<FontGlyph, ParamError> {
        let id = font::glyph_index(&face, c).ok_or_else(|| {
            ParamError::new("string", format!("has {c:?} (U+{:04X}), for which `{name}` has no glyph", u32::from(c)))
        })?;
        let mut outline = Outline::default();
        // A space has no outline in POV-Ray, whatever the font holds.
        if c != ' ' {
            face.outline_glyph(id, &mut outline);
        }
        if outline.cubic {
            return Err(font_error(&format!("has cubic outlines for {c:?}; TrueType outlines are quadratic")));
        }
        let mut contours = Vec::with_capacity(outline.contours.len());
        let mut min_x: Option<f64> = None;
        for contour in &outline.contours {
            let mut pieces = Vec::with_capacity(contour.len());
            let mut monotone = Vec::with_capacity(contour.len());
            for &(p0, p1, p2, line) in contour {
                let (p0, p1, p2) = (p0 / units, p1 / units, p2 / units);
                let lowest = if line { p0.x.min(p2.x) } else { p0.x.min(p1.x).min(p2.x) };
                min_x = Some(min_x.map_or(lowest, |m| m.min(lowest)));
                pieces.push(Segment { p0, p1, p2, line, outward: 1.0 });
                monotone_pieces(p0, p1, p2, line, &mut monotone);
            }
            segments_total += pieces.len() + monotone.len();
            if segments_total > MAX_SEGMENTS {
                return Err(ParamError::new("string", format!("needs more than {MAX_SEGMENTS} outline pieces")));
            }
            contours.push((pieces, monotone));
        }
        Ok(FontGlyph {
            id,
            contours,
            x_min: pov_x_min(&face, id, min_x, units),
            advance: f64::from(face.glyph_hor_advance(id).unwrap_or(0)),
            lsb: f64::from(face.glyph_hor_side_bearing(id).unwrap_or(0)),
        })
    };
    let kerning = font::Kerning::read(&face).map_err(|e| font_error(&e.message))?;

    let mut glyphs = Vec::new();
    let mut pen = DVec2::ZERO;
    let mut last: Option<ttf_parser::GlyphId> = None;
    for c in string.chars() {
        let g = font_glyph(c)?;
        let shift = match last {
            None => {
                pen.x = (g.advance - g.lsb) / units;
                DVec2::new(-g.x_min / units, 0.0)
            }
            Some(left) => {
                let (kx, ky) = kerning.between(left, g.id);
                let (kx, ky) = (f64::from(kx), f64::from(ky));
                let shift = DVec2::new(pen.x + (g.lsb - g.x_min + kx) / units, pen.y + ky / units);
                pen.x += (g.advance + kx) / units;
                shift
            }
        };
        pen += offset;
        last = Some(g.id);
        if let Some(glyph) = place(&g.contours, shift) {
            glyphs.push(glyph);
        }
    }
    Ok(glyphs)
}

/// The glyph's contours moved by `shift`, with each contour's outward side found; `None`
/// for a glyph without outline.
fn place(contours: &[(Vec<Segment>, Vec<Segment>)], shift: DVec2) -> Option<Glyph> {
    let moved = |s: &Segment| Segment { p0: s.p0 + shift, p1: s.p1 + shift, p2: s.p2 + shift, ..*s };
    let mut segments: Vec<Segment> = Vec::new();
    let mut monotone: Vec<Segment> = Vec::new();
    let mut ranges = Vec::with_capacity(contours.len());
    for (pieces, split) in contours {
        let (start, split_start) = (segments.len(), monotone.len());
        segments.extend(pieces.iter().map(moved));
        monotone.extend(split.iter().map(moved));
        ranges.push((start..segments.len(), split_start..monotone.len()));
    }
    if segments.is_empty() {
        return None;
    }
    let (min, max) = segments.iter().fold((DVec2::INFINITY, DVec2::NEG_INFINITY), |(lo, hi), s| {
        (lo.min(s.p0).min(s.p1).min(s.p2), hi.max(s.p0).max(s.p1).max(s.p2))
    });
    let mut glyph = Glyph { segments, monotone, min, max };
    // Which side of each contour is the inside: probe beside the middle of its longest piece.
    let probe = 1e-6 * (max - min).max_element().max(1e-3);
    for (range, split) in ranges {
        let Some(longest) = glyph.segments[range.clone()]
            .iter()
            .max_by(|a, b| (a.p2 - a.p0).length_squared().total_cmp(&(b.p2 - b.p0).length_squared()))
        else {
            continue;
        };
        let right = longest.normal(0.5);
        let inside = glyph.contains(longest.at(0.5) + probe * right);
        let outward = if inside { -1.0 } else { 1.0 };
        for s in glyph.segments[range].iter_mut().chain(&mut glyph.monotone[split]) {
            s.outward = outward;
        }
    }
    Some(glyph)
}

#[cfg(test)]
mod tests;
