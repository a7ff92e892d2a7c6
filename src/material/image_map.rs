//! POV-Ray 3.7's `image_map` pigment: a PNG image projected onto an object (`pigment = {
//! image_map = { file = "tex.png", map_type = "planar", ... } }`), as POV-Ray's
//! `imageutil.cpp` does it.
//!
//! The image covers the unit square of the pattern's (POV-Ray-frame) point: `planar` projects
//! along z (x to the right, y up: the image's top row at y = 1), `spherical` wraps it around
//! the unit sphere by longitude (from +x towards +z) and latitude, `cylindrical` around the
//! y axis by angle and height (y from 0 to 1). Outside the square the image repeats, or with
//! `once` the pigment is clear (white, transmit 1). PNG files are decoded as POV-Ray 3.7 reads
//! them: an `sRGB` chunk or none means sRGB, a `gAMA` chunk a power law, decoded into the
//! scene's working space (`assumed_gamma`); alpha becomes transmit `1 - alpha` (never
//! premultiplied).

use std::fmt;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use glam::DVec3;
use prism_api::math::fmod;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::pattern::Rgbft;
use crate::files::{FileAccess, FileError, FileKind, shown_path};
use crate::gamma::{GammaCurve, Transcoding};
use crate::limits::{MAX_COEFFICIENT, MAX_TEXTURE_SIDE, MemoryBudget};
use crate::texture::TextureError;

/// POV-Ray's `EPSILON`, added to the image coordinates before they wrap.
const POV_EPSILON: f64 = 1.0e-10;

/// How the image is wrapped around the object (POV-Ray's `map_type`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum MapType {
    /// `map_type 0`: projected along z onto the x-y unit square.
    #[default]
    Planar,
    /// `map_type 1`: around the unit sphere, longitude and latitude.
    Spherical,
    /// `map_type 2`: around the y axis, angle and height from 0 to 1.
    Cylindrical,
    /// `map_type 5`: around a torus of major radius 1 about the y axis, the angle about y
    /// across the width and the angle around the tube across the height.
    Torus,
}

/// How texels are blended between their centres (POV-Ray's `interpolate`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Interpolate {
    /// No interpolation: the texel the point falls in.
    #[default]
    None,
    /// `interpolate 2`: bilinear between the four nearest texel centres.
    Bilinear,
    /// `interpolate 3`: bicubic (Catmull-Rom) over the sixteen nearest texels.
    Bicubic,
    /// `interpolate 4`: the four nearest texels weighted by inverse squared distance.
    NormalizedDistance,
}

/// A keyword enum spelled by name in the scene file, with a suggestion for a misspelling.
macro_rules! named_enum {
    ($ty:ident, $what:literal, $description:literal, [$(($variant:ident, $name:literal, $pov:literal)),+ $(,)?]) => {
        impl $ty {
            /// Every value with its scene-file name and POV-Ray's number for it.
            pub const ALL: &'static [($ty, &'static str, u32)] = &[$(($ty::$variant, $name, $pov)),+];

            /// The scene file's name.
            pub fn name(self) -> &'static str {
                Self::ALL.iter().find(|(v, _, _)| *v == self).map_or("", |(_, n, _)| n)
            }

            /// POV-Ray's number for it.
            pub fn pov_number(self) -> u32 {
                Self::ALL.iter().find(|(v, _, _)| *v == self).map_or(0, |(_, _, p)| *p)
            }
        }

        impl fmt::Display for $ty {
            fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str(self.name())
            }
        }

        impl Serialize for $ty {
            fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
                s.serialize_str(self.name())
            }
        }

        impl<'de> Deserialize<'de> for $ty {
            fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
                let name = String::deserialize(d)?;
                if let Some((v, _, _)) = Self::ALL.iter().find(|(_, n, _)| *n == name) {
                    return Ok(*v);
                }
                let names: Vec<&str> = Self::ALL.iter().map(|(_, n, _)| *n).collect();
                let hint = crate::diagnostics::nearest_name(&name, names.iter().copied())
                    .map_or(String::new(), |n| format!("did you mean `{n}`? "));
                Err(serde::de::Error::custom(format!(
                    "unknown {} `{name}`; {hint}known: {}",
                    $what,
                    names.join(", ")
                )))
            }
        }

        impl JsonSchema for $ty {
            fn schema_name() -> std::borrow::Cow<'static, str> {
                stringify!($ty).into()
            }

            fn json_schema(_: &mut schemars::SchemaGenerator) -> schemars::Schema {
                let names: Vec<&str> = Self::ALL.iter().map(|(_, n, _)| *n).collect();
                schemars::json_schema!({ "description": $description, "enum": names })
            }
        }
    };
}

named_enum!(
    MapType,
    "map_type",
    "How an image_map wraps its image around the object.",
    [(Planar, "planar", 0), (Spherical, "spherical", 1), (Cylindrical, "cylindrical", 2), (Torus, "torus", 5),]
);

named_enum!(
    Interpolate,
    "interpolate",
    "How an image_map blends its texels.",
    [
        (None, "none", 0),
        (Bilinear, "bilinear", 2),
        (Bicubic, "bicubic", 3),
        (NormalizedDistance, "normalized_distance", 4),
    ]
);

/// An `image_map` as a scene file writes it (inside `pigment`).
#[derive(Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ImageMap {
    /// The PNG file, relative to the scene file that writes it.
    pub file: String,
    /// `planar` (default), `spherical` or `cylindrical`.
    #[serde(default, skip_serializing_if = "is_default")]
    pub map_type: MapType,
    /// `none` (default), `bilinear`, `bicubic` or `normalized_distance`.
    #[serde(default, skip_serializing_if = "is_default")]
    pub interpolate: Interpolate,
    /// Show the image once: outside its unit square the pigment is clear.
    #[serde(default, skip_serializing_if = "is_default")]
    pub once: bool,
    /// POV-Ray's `repeat <u, v>`: the mapping spans the image this many times across its
    /// unit square (both above 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub repeat: Option<[f64; 2]>,
    /// POV-Ray's `offset <u, v>`: shifts the image by these fractions of its width and height
    /// (towards the left and the top), before `once` and the wrap.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub offset: Option<[f64; 2]>,
    /// `bump_map` only: a palette image's indices (0 to 255) as heights instead of its
    /// colours' grey levels (POV-Ray's `use_index`; other images are read by their colours).
    #[serde(default, skip_serializing_if = "is_default")]
    pub use_index: bool,
    /// POV-Ray's `filter all`: added to every texel's filter.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub filter_all: Option<f64>,
    /// POV-Ray's `transmit all`: added to every texel's transmit (`1 - alpha`); for a
    /// palette image it replaces it, as POV-Ray sets the palette's transmit.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub transmit_all: Option<f64>,
    /// The file as resolved by the loader (absolute); not part of the scene text.
    #[serde(skip)]
    #[schemars(skip)]
    pub path: Option<PathBuf>,
    /// The decoded image (set by the loader; not part of the scene text).
    #[serde(skip)]
    #[schemars(skip)]
    pub image: Option<Arc<MapImage>>,
}

fn is_default<T: Default + PartialEq>(v: &T) -> bool {
    *v == T::default()
}

impl fmt::Debug for ImageMap {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("ImageMap")
            .field("file", &self.file)
            .field("map_type", &self.map_type)
            .field("interpolate", &self.interpolate)
            .field("once", &self.once)
            .field("loaded", &self.image.is_some())
            .finish_non_exhaustive()
    }
}

impl PartialEq for ImageMap {
    /// Equal when they name the same file the same way (the image follows from the file).
    fn eq(&self, other: &Self) -> bool {
        self.file == other.file
            && self.path == other.path
            && self.map_type == other.map_type
            && self.interpolate == other.interpolate
            && self.once == other.once
            && self.repeat == other.repeat
            && self.offset == other.offset
            && self.use_index == other.use_index
            && self.filter_all == other.filter_all
            && self.transmit_all == other.transmit_all
    }
}

/// A decoded image: linear RGB and alpha per texel, rows from the top.
#[derive(Clone, Debug, PartialEq)]
pub struct MapImage {
    /// Width in texels.
    pub width: usize,
    /// Height in texels.
    pub height: usize,
    /// Linear RGB and (straight) alpha.
    pub texels: Vec<[f32; 4]>,
    /// A palette image (POV-Ray's colour-mapped images: `transmit all` replaces the
    /// palette's transmit instead of adding to it).
    pub indexed: bool,
    /// Some texel is not fully opaque.
    pub has_alpha: bool,
    /// A palette image's indices, per texel (read only for a bump map's `use_index`; empty
    /// otherwise).
    pub indices: Vec<u8>,
}

/// Why an `image_map` file cannot be used.
#[derive(Debug, thiserror::Error)]
pub enum ImageMapError {
    /// Reading, size or budget (as for every image a scene reads).
    #[error(transparent)]
    Texture(#[from] TextureError),
    /// The file is not a PNG.
    #[error("image_map reads PNG files; `{}` is not one", shown_path(.0))]
    NotPng(PathBuf),
}

impl From<FileError> for ImageMapError {
    fn from(e: FileError) -> Self {
        ImageMapError::Texture(TextureError::File(e))
    }
}

impl ImageMap {
    /// The first out-of-range value, as (key under `image_map`, message).
    pub fn check(&self) -> Result<(), (&'static str, String)> {
        for (key, v) in [("filter_all", self.filter_all), ("transmit_all", self.transmit_all)] {
            if let Some(v) = v
                && !v.is_finite()
            {
                return Err((key, format!("must be finite, got {v}")));
            }
            // As a material's filter and transmit: larger values overflow their products.
            if let Some(v) = v
                && v.abs() > MAX_COEFFICIENT
            {
                let v = crate::diagnostics::shown_number(v);
                return Err((key, format!("must lie within ±{MAX_COEFFICIENT:e} (products would overflow), got {v}")));
            }
        }
        if let Some(r) = self.repeat
            && !r.iter().all(|v| v.is_finite() && *v > 0.0)
        {
            return Err(("repeat", format!("must be two numbers above 0 (POV-Ray's repeat vector), got {r:?}")));
        }
        if let Some(o) = self.offset
            && !o.iter().all(|v| v.is_finite())
        {
            return Err(("offset", format!("must be two finite numbers, got {o:?}")));
        }
        if self.file.is_empty() {
            return Err(("file", "must name a PNG file".into()));
        }
        Ok(())
    }

    /// The most transparent colour the map can give (what shading that does not look the
    /// image up, such as the choice to trace shadows through it, must assume).
    pub fn clearest(&self) -> Rgbft {
        let alpha = self.once || self.image.as_ref().is_some_and(|i| i.has_alpha);
        let transmit = match (self.image.as_ref().is_some_and(|i| i.indexed), self.transmit_all) {
            (true, Some(t)) => t.max(if self.once { 1.0 } else { 0.0 }),
            (_, t) => f64::from(u8::from(alpha)) + t.unwrap_or(0.0),
        };
        Rgbft { rgb: DVec3::ONE, filter: self.filter_all.unwrap_or(0.0), transmit }
    }

    /// The colour at pattern-space point `q` (POV-Ray's frame), POV-Ray's `image_map`.
    pub fn at(&self, q: DVec3) -> Rgbft {
        let clear = Rgbft { rgb: DVec3::ONE, filter: 0.0, transmit: 1.0 };
        let Some(image) = self.image.as_deref() else {
            return Rgbft { rgb: DVec3::ONE, filter: 0.0, transmit: 0.0 };
        };
        match self.image_coords(image, q) {
            Some((x, y)) => self.colour_at(image, x, y),
            None => clear,
        }
    }

    /// POV-Ray's `map_pos`: the texel coordinates of pattern-space point `q` (POV-Ray's
    /// frame) in `image` (x from the left, y from the top row, wrapped into the image), or
    /// `None` off the image (`once`) or where the mapping gives no point.
    pub fn image_coords(&self, image: &MapImage, q: DVec3) -> Option<(f64, f64)> {
        let (w, h) = (image.width as f64, image.height as f64);
        // The mapping spans `repeat` images; the offset moves by whole images' fractions.
        let [repeat_u, repeat_v] = self.repeat.unwrap_or([1.0, 1.0]);
        let (x, y) = self.project(q, w * repeat_u, h * repeat_v)?;
        let [offset_u, offset_v] = self.offset.map_or([0.0, 0.0], |[u, v]| [u * -w, v * -h]);
        let (x, y) = (x + (offset_u + POV_EPSILON), y + (offset_v + POV_EPSILON));
        if self.once && (x >= w || y >= h || x < 0.0 || y < 0.0) {
            return None;
        }
        // Image rows count from the top: y is flipped.
        Some((wrap(x, w), wrap(-y, h)))
    }

    /// POV-Ray's `image_colour_at`: the colour at texel coordinates (x, y) of `image`, with the
    /// map's interpolation.
    pub fn colour_at(&self, image: &MapImage, x: f64, y: f64) -> Rgbft {
        if self.interpolate == Interpolate::None {
            return self.texel(image, x, y);
        }
        let mut out = Rgbft { rgb: DVec3::ZERO, filter: 0.0, transmit: 0.0 };
        self.for_each_tap(x, y, |tx, ty, w| {
            let c = self.texel(image, tx, ty);
            out.rgb += c.rgb * w;
            out.filter += c.filter * w;
            out.transmit += c.transmit * w;
        });
        out
    }

    /// The palette index `image_colour_at` gives beside the colour: the texels' indices
    /// blended with the interpolation's weights and truncated, as POV-Ray does (`None` for an
    /// image without a palette).
    pub fn index_at(&self, image: &MapImage, x: f64, y: f64) -> Option<f64> {
        if image.indices.is_empty() {
            return None;
        }
        let mut sum = 0.0;
        self.for_each_tap(x, y, |tx, ty, w| sum += f64::from(image.indices[self.texel_position(image, tx, ty)]) * w);
        Some(sum.trunc())
    }

    /// Calls `visit` with each texel an interpolated lookup at (x, y) reads and its weight,
    /// in POV-Ray's order.
    #[inline(always)]
    fn for_each_tap(&self, x: f64, y: f64, mut visit: impl FnMut(f64, f64, f64)) {
        match self.interpolate {
            Interpolate::None => visit(x, y, 1.0),
            Interpolate::Bilinear | Interpolate::NormalizedDistance => {
                let (x, y) = (x + 0.5, y + 0.5);
                let (ix, iy) = (x.trunc(), y.trunc());
                let (p, q) = (x - ix, y - iy);
                let corners = [(ix, iy), (ix - 1.0, iy), (ix, iy - 1.0), (ix - 1.0, iy - 1.0)];
                let factors = if self.interpolate == Interpolate::Bilinear {
                    [p * q, (1.0 - p) * q, p * (1.0 - q), (1.0 - p) * (1.0 - q)]
                } else {
                    normalized_distance(p, q)
                };
                for ((cx, cy), f) in corners.into_iter().zip(factors) {
                    visit(cx, cy, f);
                }
            }
            Interpolate::Bicubic => {
                let (x, y) = (x + 0.5, y + 0.5);
                let (ix, iy) = (x.trunc(), y.trunc());
                let (fx, fy) = (cubic(x - ix), cubic(y - iy));
                for (i, wx) in fx.iter().enumerate() {
                    for (j, wy) in fy.iter().enumerate() {
                        visit(ix + i as f64 - 2.0, iy + j as f64 - 2.0, wx * wy);
                    }
                }
            }
        }
    }

    /// The point's image coordinates in texels (x right, y up from the bottom row), before
    /// they wrap; `None` where the map gives no colour.
    fn project(&self, q: DVec3, w: f64, h: f64) -> Option<(f64, f64)> {
        match self.map_type {
            MapType::Planar => {
                // POV-Ray's default gradient <1, -1, 0>: x to u, y to v.
                if self.once && (!(0.0..=1.0).contains(&q.x) || !(0.0..=1.0).contains(&q.y)) {
                    return None;
                }
                Some((fmod(q.x * w, w), fmod(q.y * h, h)))
            }
            MapType::Spherical => {
                let len = q.length();
                if len == 0.0 {
                    return None;
                }
                let d = q / len;
                let phi = 0.5 + d.y.asin() / std::f64::consts::PI;
                Some((longitude(d.x, d.z).unwrap_or(0.0) * w, phi * h))
            }
            MapType::Cylindrical => {
                if self.once && !(0.0..=1.0).contains(&q.y) {
                    return None;
                }
                let v = fmod(q.y * h, h);
                let len = q.length();
                if len == 0.0 {
                    return None;
                }
                let theta = longitude(q.x / len, q.z / len)?;
                Some((theta * w, v))
            }
            MapType::Torus => {
                // POV-Ray's torus_image_map, major radius 1 (its gradient's x, fixed for maps).
                let ring = (q.x * q.x + q.z * q.z).sqrt();
                let theta = longitude(q.x, q.z)?;
                let x = ring - 1.0;
                let tube = (x * x + q.y * q.y).sqrt();
                if tube == 0.0 {
                    return None;
                }
                let mut phi = (-x / tube).acos();
                if q.y > 0.0 {
                    phi = std::f64::consts::TAU - phi;
                }
                // POV-Ray negates the angle twice on the way: u runs with it.
                Some((theta * w, phi / std::f64::consts::TAU * h))
            }
        }
    }

    /// POV-Ray's `no_interpolation`: the texel at wrapped texel coordinates (clamped to the
    /// edge with `once`), with `filter all` and `transmit all`.
    fn texel(&self, image: &MapImage, x: f64, y: f64) -> Rgbft {
        let [r, g, b, a] = image.texels[self.texel_position(image, x, y)];
        let alpha_transmit = 1.0 - f64::from(a);
        let transmit = match (image.indexed, self.transmit_all) {
            (true, Some(t)) => t,
            (_, t) => alpha_transmit + t.unwrap_or(0.0),
        };
        Rgbft {
            rgb: DVec3::new(f64::from(r), f64::from(g), f64::from(b)),
            filter: self.filter_all.unwrap_or(0.0),
            transmit,
        }
    }
}

impl ImageMap {
    /// The index into `image`'s texels of texel coordinates (x, y): wrapped, or with `once`
    /// clamped to the edge (POV-Ray's `no_interpolation`).
    fn texel_position(&self, image: &MapImage, x: f64, y: f64) -> usize {
        let (w, h) = (image.width as f64, image.height as f64);
        let (ix, iy) = if self.once {
            (x.clamp(0.0, w - 1.0) as usize, y.clamp(0.0, h - 1.0) as usize)
        } else {
            (wrap(x, w) as usize, wrap(y, h) as usize)
        };
        iy.min(image.height - 1) * image.width + ix.min(image.width - 1)
    }
}

/// The angle about y from +x towards +z as a fraction of a turn, for a direction with
/// `x^2 + z^2` not zero (POV-Ray's `acos` form, which the parity depends on to the last bit).
fn longitude(x: f64, z: f64) -> Option<f64> {
    let len = (x * x + z * z).sqrt();
    if len == 0.0 {
        return None;
    }
    let theta = if z == 0.0 {
        if x > 0.0 { 0.0 } else { std::f64::consts::PI }
    } else {
        let t = (x / len).acos();
        if z < 0.0 { std::f64::consts::TAU - t } else { t }
    };
    Some(theta / std::f64::consts::TAU)
}

/// POV-Ray's `wrap`: `val` into `[0, upper)` (fmod, negatives lifted, `upper` itself to 0).
fn wrap(val: f64, upper: f64) -> f64 {
    // Interpolation reads whole texel positions, where the remainder is an integer one
    // (exact either way; `fmod` is a slow library call).
    const WHOLE: f64 = 4_503_599_627_370_496.0;
    if val.trunc() == val && val.abs() < WHOLE && upper.trunc() == upper && (1.0..WHOLE).contains(&upper) {
        return (val as i64).rem_euclid(upper as i64) as f64;
    }
    let mut v = fmod(val, upper);
    if v < 0.0 {
        v += upper;
    }
    if v >= upper { 0.0 } else { v }
}

/// POV-Ray's `norm_dist` weights of the corners (x, y), (x-1, y), (x, y-1), (x-1, y-1).
fn normalized_distance(p: f64, q: f64) -> [f64; 4] {
    let squares =
        [(1.0 - p).powi(2) + (1.0 - q).powi(2), p * p + (1.0 - q).powi(2), (1.0 - p).powi(2) + q * q, p * p + q * q];
    // On a texel centre POV-Ray divides by zero; the texel itself is the limit.
    if let Some(i) = squares.iter().position(|&d| d == 0.0) {
        let mut w = [0.0; 4];
        w[i] = 1.0;
        return w;
    }
    let weights = squares.map(|d| 1.0 / d);
    let sum: f64 = weights.iter().sum();
    weights.map(|w| w / sum)
}

/// POV-Ray's `cubic`: the four Catmull-Rom weights for fraction `x`.
fn cubic(x: f64) -> [f64; 4] {
    let p = x - x.trunc();
    let q = 1.0 - p;
    [-0.5 * p * q * q, 0.5 * q * (q * (3.0 * p + 1.0) + 1.0), 0.5 * p * (p * (3.0 * q + 1.0) + 1.0), -0.5 * q * p * p]
}

/// Reads and decodes the PNG at `path` through `access`, within `budget`, into the working
/// space `working` (the scene's `assumed_gamma`; neutral: linear values). `raw` (a
/// `bump_map`'s image, which POV-Ray reads without gamma) keeps the samples as stored,
/// scaled to [0, 1].
pub fn load(
    path: &Path,
    access: &FileAccess,
    budget: MemoryBudget,
    raw: bool,
    working: GammaCurve,
) -> Result<MapImage, ImageMapError> {
    let bytes = access.read(path, FileKind::Image)?;
    decode_png(path, &bytes, budget, raw, working)
}

/// Bytes a decoded `width` x `height` image map takes.
pub fn memory_estimate(width: u32, height: u32) -> u64 {
    u64::from(width) * u64::from(height) * 16
}

/// Decodes PNG `bytes` (`path` names it in errors): 1 to 16 bits, grey, grey with alpha,
/// RGB, RGBA or palette, to RGB in the working space `working` and alpha (`raw`: the
/// samples as stored, scaled to [0, 1], whatever the file's gamma). As POV-Ray 3.7 reads a
/// PNG: an `sRGB` chunk or no gamma information means the sRGB curve, a `gAMA` chunk a power
/// law, and the samples go from that curve to the working space through POV-Ray's
/// transcoding (no curve at all where the two match).
pub fn decode_png(
    path: &Path,
    bytes: &[u8],
    budget: MemoryBudget,
    raw: bool,
    working: GammaCurve,
) -> Result<MapImage, ImageMapError> {
    const SIGNATURE: [u8; 8] = [0x89, b'P', b'N', b'G', 0x0d, 0x0a, 0x1a, 0x0a];
    if !bytes.starts_with(&SIGNATURE) {
        return Err(ImageMapError::NotPng(path.to_path_buf()));
    }
    let corrupt = |e: png::DecodingError| {
        let source = image::ImageError::Decoding(image::error::DecodingError::new(
            image::error::ImageFormatHint::Exact(image::ImageFormat::Png),
            e,
        ));
        ImageMapError::Texture(TextureError::Decode { path: path.to_path_buf(), source })
    };
    let mut decoder = png::Decoder::new(std::io::Cursor::new(bytes));
    decoder.set_transformations(png::Transformations::EXPAND);
    let mut reader = decoder.read_info().map_err(corrupt)?;
    let info = reader.info();
    let (width, height) = (info.width, info.height);
    if width > MAX_TEXTURE_SIDE || height > MAX_TEXTURE_SIDE {
        return Err(TextureError::TooLarge { path: path.to_path_buf(), width, height }.into());
    }
    if width == 0 || height == 0 {
        return Err(TextureError::Empty { path: path.to_path_buf(), width, height }.into());
    }
    let decoding = match (info.srgb, info.gama_chunk) {
        _ if raw => Transcoding::Single(GammaCurve::Neutral),
        (None, Some(g)) if g.into_value() > 0.0 => Transcoding::new(working, GammaCurve::by_encoding(g.into_value())),
        _ => Transcoding::new(working, GammaCurve::Srgb),
    };
    let indexed = info.color_type == png::ColorType::Indexed;
    // POV-Ray keeps a grey image of at most 8 bits as 8-bit grey after decoding it, truncated.
    let grey8 = info.color_type == png::ColorType::Grayscale && info.bit_depth as u8 <= 8;
    let (color_type, depth) = reader.output_color_type();
    let buffer_size = reader.output_buffer_size().unwrap_or(usize::MAX);
    let estimate = memory_estimate(width, height).saturating_add(buffer_size as u64);
    budget
        .check(|| format!("image `{}` ({width} x {height})", shown_path(path)), estimate)
        .map_err(TextureError::from)?;
    let mut buffer = vec![0; buffer_size];
    let frame = reader.next_frame(&mut buffer).map_err(corrupt)?;
    let buffer = &buffer[..frame.buffer_size()];
    let channels = color_type.samples();
    let sixteen = depth == png::BitDepth::Sixteen;
    let (w, h) = (width as usize, height as usize);
    // EXPAND leaves whole samples of 8 or 16 bits; anything else is not an image this reads.
    let bytes_per_sample = if sixteen { 2 } else { 1 };
    if !(matches!(depth, png::BitDepth::Eight | png::BitDepth::Sixteen)
        && buffer.len() >= w * h * channels * bytes_per_sample)
    {
        return Err(corrupt(png::DecodingError::LimitsExceeded));
    }
    let max = if sixteen { 65535.0 } else { 255.0 };
    let sample = |i: usize| -> f32 {
        let v = if sixteen { u16::from_be_bytes([buffer[2 * i], buffer[2 * i + 1]]) } else { u16::from(buffer[i]) };
        f32::from(v) / max
    };
    let decode = |v: f32| {
        let linear = decoding.decode(v);
        if grey8 && raw {
            // Undecoded, POV-Ray's palette entry goes through its single-precision RGB2Gray
            // (whose weights add up to 1 only nearly) before the truncation.
            let grey = linear * 0.297 + linear * 0.589 + linear * 0.114;
            (grey * 255.0).trunc() / 255.0
        } else if grey8 {
            (linear * 255.0).trunc() / 255.0
        } else {
            linear
        }
    };
    let mut texels = Vec::with_capacity(w * h);
    for t in 0..w * h {
        let s = |c: usize| sample(t * channels + c);
        let texel = match channels {
            1 => {
                let g = decode(s(0));
                [g, g, g, 1.0]
            }
            2 => {
                let g = decode(s(0));
                [g, g, g, s(1)]
            }
            3 => [decode(s(0)), decode(s(1)), decode(s(2)), 1.0],
            _ => [decode(s(0)), decode(s(1)), decode(s(2)), s(3)],
        };
        texels.push(texel);
    }
    let has_alpha = texels.iter().any(|t| t[3] < 1.0);
    let indices = if raw && indexed { palette_indices(bytes, w, h).map_err(corrupt)? } else { Vec::new() };
    Ok(MapImage { width: w, height: h, texels, indexed, has_alpha, indices })
}

/// A palette PNG's `w` x `h` indices (1, 2, 4 or 8 bits each), decoded again without
/// expanding the palette.
fn palette_indices(bytes: &[u8], w: usize, h: usize) -> Result<Vec<u8>, png::DecodingError> {
    let mut decoder = png::Decoder::new(std::io::Cursor::new(bytes));
    decoder.set_transformations(png::Transformations::IDENTITY);
    let mut reader = decoder.read_info()?;
    let depth = reader.info().bit_depth as usize;
    let mut buffer = vec![0; reader.output_buffer_size().unwrap_or(0)];
    let frame = reader.next_frame(&mut buffer)?;
    let line = frame.line_size;
    if !matches!(depth, 1 | 2 | 4 | 8) || buffer.len() < h * line || line * 8 < w * depth {
        return Err(png::DecodingError::LimitsExceeded);
    }
    let mask = ((1u16 << depth) - 1) as u8;
    let mut indices = Vec::with_capacity(w * h);
    for row in 0..h {
        for col in 0..w {
            let bit = col * depth;
            indices.push((buffer[row * line + bit / 8] >> (8 - depth - bit % 8)) & mask);
        }
    }
    Ok(indices)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 4 x 2 RGB image: texel (column, row) has red = column / 4, green = row / 2.
    fn image() -> Arc<MapImage> {
        let mut texels = Vec::new();
        for row in 0..2 {
            for col in 0..4 {
                texels.push([col as f32 / 4.0, row as f32 / 2.0, 0.0, 1.0]);
            }
        }
        Arc::new(MapImage { width: 4, height: 2, texels, indexed: false, has_alpha: false, indices: Vec::new() })
    }

    fn map(text: &str) -> ImageMap {
        let mut m: ImageMap = toml::from_str(&format!("file = \"t.png\"\n{text}")).unwrap();
        m.check().unwrap();
        m.image = Some(image());
        m
    }

    /// The (column, row) of the texel an un-interpolated lookup gives.
    fn texel_of(c: Rgbft) -> (i32, i32) {
        ((c.rgb.x * 4.0).round() as i32, (c.rgb.y * 2.0).round() as i32)
    }

    #[test]
    fn palette_indices_blend_like_colours_and_truncate() {
        let mut image = (*image()).clone();
        image.indices = vec![0, 1, 2, 3, 4, 5, 6, 7];
        let image = Arc::new(image);
        let mut m = map("interpolate = \"bilinear\"");
        // Halfway between texel centres (1, 0) and (2, 0): indices 1 and 2 blend to 1.5,
        // truncated to 1, as POV-Ray's `(int)` does.
        assert_eq!(m.index_at(&image, 2.0, 0.5), Some(1.0));
        m.interpolate = Interpolate::None;
        assert_eq!(m.index_at(&image, 2.2, 1.7), Some(6.0));
        // An image without a palette has no index.
        assert_eq!(m.index_at(&self::image(), 2.2, 1.7), None);
    }

    #[test]
    fn planar_covers_the_unit_square_with_the_top_row_at_y_one() {
        let m = map("");
        // Near the top-left corner (x 0, y 1): column 0, row 0.
        assert_eq!(texel_of(m.at(DVec3::new(0.1, 0.9, 0.0))), (0, 0));
        // Bottom right: column 3, row 1.
        assert_eq!(texel_of(m.at(DVec3::new(0.9, 0.1, 5.0))), (3, 1));
        assert_eq!(texel_of(m.at(DVec3::new(0.3, 0.4, 0.0))), (1, 1));
        // Repeats: x 1.1 is x 0.1; negative x -0.1 is x 0.9.
        assert_eq!(texel_of(m.at(DVec3::new(1.1, 0.9, 0.0))), (0, 0));
        assert_eq!(texel_of(m.at(DVec3::new(-0.1, 0.9, 0.0))), (3, 0));
        assert_eq!(m.at(DVec3::new(0.1, 0.9, 0.0)).transmit, 0.0);
    }

    #[test]
    fn once_leaves_the_outside_clear() {
        let m = map("once = true");
        assert_eq!(texel_of(m.at(DVec3::new(0.9, 0.1, 0.0))), (3, 1));
        for p in [DVec3::new(1.1, 0.5, 0.0), DVec3::new(-0.1, 0.5, 0.0), DVec3::new(0.5, 1.2, 0.0)] {
            let c = m.at(p);
            assert_eq!((c.rgb, c.filter, c.transmit), (DVec3::ONE, 0.0, 1.0), "{p}");
        }
        assert_eq!(m.clearest().transmit, 1.0);
    }

    #[test]
    fn repeat_spans_copies_and_offset_shifts_by_fractions_of_the_image() {
        // repeat 2 across: x 0.1 is 0.2 of the image (column 0), x 0.3 is 0.6 (column 2),
        // x 0.6 is 1.2 (column 0 of the second copy).
        let m = map("repeat = [2, 1]");
        assert_eq!(texel_of(m.at(DVec3::new(0.1, 0.9, 0.0))), (0, 0));
        assert_eq!(texel_of(m.at(DVec3::new(0.3, 0.9, 0.0))), (2, 0));
        assert_eq!(texel_of(m.at(DVec3::new(0.6, 0.9, 0.0))), (0, 0));
        // offset 0.25 moves the image a quarter of its width to the left: x 0.1 shows
        // column 3 (0.1 - 0.25 wraps to 0.85); offset 0.5 down: y 0.9 shows row 1.
        let m = map("offset = [0.25, 0.5]");
        assert_eq!(texel_of(m.at(DVec3::new(0.1, 0.9, 0.0))), (3, 1));
        // With once, what the offset moves off the square is clear.
        let m = map("once = true\noffset = [0.25, 0]");
        assert_eq!(m.at(DVec3::new(0.1, 0.9, 0.0)).transmit, 1.0);
        assert_eq!(texel_of(m.at(DVec3::new(0.6, 0.9, 0.0))), (1, 0));
        for bad in ["repeat = [0, 1]", "repeat = [1, -2]", "offset = [1, nan]"] {
            let m: ImageMap = toml::from_str(&format!("file = \"t.png\"\n{bad}")).unwrap();
            assert!(m.check().is_err(), "{bad}");
        }
    }

    #[test]
    fn torus_maps_the_angle_about_y_and_around_the_tube() {
        let m = map("map_type = \"torus\"");
        // On the ring of radius 1: the inner equator (x 0.8 at theta 0) is v 0, the bottom of
        // the tube a quarter turn, the outer equator half, the top three quarters (flipped:
        // rows count from the top).
        let at = |x: f64, y: f64, z: f64| texel_of(m.at(DVec3::new(x, y, z)));
        assert_eq!(at(0.8, 0.0, 0.0), (0, 1));
        assert_eq!(at(1.0, -0.2, 0.0).0, 0);
        assert_eq!(at(1.2, -0.01, 0.0), (0, 1));
        assert_eq!(at(1.2, 0.01, 0.0), (0, 0));
        // A quarter turn about y towards +z: column 1; half: column 2.
        assert_eq!(at(0.0, 0.05, 1.2).0, 1);
        assert_eq!(at(-1.2, 0.05, 0.0).0, 2);
        // On the axis there is no angle: clear.
        assert_eq!(m.at(DVec3::new(0.0, 0.3, 0.0)).transmit, 1.0);
    }

    #[test]
    fn spherical_maps_longitude_from_x_towards_z_and_latitude() {
        let m = map("map_type = \"spherical\"");
        // +x: theta 0 (column 0); the equator: phi 0.5, v = 1 texel from the bottom, so the
        // flipped row is wrap(-1 - eps, 2) = 1 - eps: row 0.
        assert_eq!(texel_of(m.at(DVec3::new(1.0, 0.0, 0.0))), (0, 0));
        // +z is a quarter turn: column 1; a bit below the equator: row 1.
        assert_eq!(texel_of(m.at(DVec3::new(0.0, -0.1, 1.0))), (1, 1));
        // -x: half a turn, column 2; -z: three quarters, column 3 (radius does not matter).
        assert_eq!(texel_of(m.at(DVec3::new(-3.0, 0.5, 0.0))), (2, 0));
        assert_eq!(texel_of(m.at(DVec3::new(0.0, 0.5, -2.0))), (3, 0));
        // The centre has no direction: clear.
        assert_eq!(m.at(DVec3::ZERO).transmit, 1.0);
    }

    #[test]
    fn cylindrical_maps_angle_and_height() {
        let m = map("map_type = \"cylindrical\"");
        assert_eq!(texel_of(m.at(DVec3::new(1.0, 0.75, 0.01))), (0, 0));
        // Just past a quarter turn: column 1.
        assert_eq!(texel_of(m.at(DVec3::new(-0.01, 0.25, 1.0))), (1, 1));
        // Height repeats every unit.
        assert_eq!(texel_of(m.at(DVec3::new(-0.01, 1.25, 1.0))), (1, 1));
        // On the axis: no angle, clear.
        assert_eq!(m.at(DVec3::new(0.0, 0.5, 0.0)).transmit, 1.0);
        let once = map("map_type = \"cylindrical\"\nonce = true");
        assert_eq!(once.at(DVec3::new(-0.01, 1.25, 1.0)).transmit, 1.0);
        assert_eq!(texel_of(once.at(DVec3::new(-0.01, 0.25, 1.0))), (1, 1));
    }

    #[test]
    fn bilinear_and_normalized_distance_blend_texel_centres() {
        let m = map("interpolate = \"bilinear\"");
        // x = 0.25 is texel coordinate 1.0 + eps: halfway between the centres of columns
        // 0 (0.5) and 1 (1.5); red is the mean of 0 and 0.25.
        let c = m.at(DVec3::new(0.25, 0.75, 0.0));
        assert!((c.rgb.x - 0.125).abs() < 1e-9, "{c:?}");
        // y = 0.75: flipped coordinate 0.5 - eps, row 0's centre: green 0.
        assert!(c.rgb.y.abs() < 1e-9, "{c:?}");
        // On column 1's centre (x 1.5 / 4): column 1 alone.
        let c = m.at(DVec3::new(1.5 / 4.0, 0.75, 0.0));
        assert!((c.rgb.x - 0.25).abs() < 1e-9, "{c:?}");
        // Across the wrap: x = 0 is between column 3 (0.75) and column 0 (0).
        let c = m.at(DVec3::new(0.0, 0.75, 0.0));
        assert!((c.rgb.x - 0.375).abs() < 1e-9, "{c:?}");
        // Normalized distance at a quarter of the way: weights 1 / d^2 of the four corners.
        let n = map("interpolate = \"normalized_distance\"");
        let c = n.at(DVec3::new(0.75 / 4.0, 0.75, 0.0));
        // p = 0.25 past column 0's centre, q = 0 (on row 0's centre up to eps): corners
        // column 1 at distance 0.75 and column 0 at 0.25, each in rows 0 and -1 (row 1).
        let (a, b) = (1.0 / (0.75f64.powi(2) + 1.0), 1.0 / (0.25f64.powi(2) + 1.0));
        let (c0, c1) = (1.0 / 0.75f64.powi(2), 1.0 / 0.25f64.powi(2));
        let red = (0.25 * (c0 + a)) / (a + b + c0 + c1);
        assert!((c.rgb.x - red).abs() < 1e-6, "{} vs {red}", c.rgb.x);
        assert_eq!(normalized_distance(0.0, 0.0), [0.0, 0.0, 0.0, 1.0]);
        // Bicubic reproduces a linear ramp between interior centres.
        let b = map("interpolate = \"bicubic\"");
        let c = b.at(DVec3::new(2.0 / 4.0, 0.75, 0.0));
        assert!((c.rgb.x - 0.375).abs() < 1e-9, "{c:?}");
    }

    #[test]
    fn alpha_filter_all_and_transmit_all() {
        let mut m = map("filter_all = 0.25\ntransmit_all = 0.5");
        let mut img = (*image()).clone();
        img.texels[0][3] = 0.5;
        img.has_alpha = true;
        m.image = Some(Arc::new(img.clone()));
        // Texel (0, 0): transmit (1 - 0.5) + 0.5; texel (3, 1) only the 0.5.
        let c = m.at(DVec3::new(0.1, 0.9, 0.0));
        assert_eq!((c.filter, c.transmit), (0.25, 1.0));
        assert_eq!(m.at(DVec3::new(0.9, 0.1, 0.0)).transmit, 0.5);
        // A palette image's transmit is replaced.
        img.indexed = true;
        m.image = Some(Arc::new(img));
        assert_eq!(m.at(DVec3::new(0.1, 0.9, 0.0)).transmit, 0.5);
    }

    #[test]
    fn decodes_pngs_as_pov_ray_does() {
        let encode = |w: u32, h: u32, color: png::ColorType, depth: png::BitDepth, data: &[u8], srgb: bool| {
            let mut out = Vec::new();
            let mut e = png::Encoder::new(&mut out, w, h);
            e.set_color(color);
            e.set_depth(depth);
            if !srgb {
                e.set_source_gamma(png::ScaledFloat::new(1.0));
            }
            e.write_header().unwrap().write_image_data(data).unwrap();
            out
        };
        let budget = MemoryBudget::UNLIMITED;
        let p = Path::new("t.png");
        let srgb = |v: f32| GammaCurve::Srgb.decode(v);
        let rgb = decode_png(
            p,
            &encode(1, 1, png::ColorType::Rgb, png::BitDepth::Eight, &[64, 128, 255], true),
            budget,
            false,
            GammaCurve::Neutral,
        )
        .unwrap();
        assert_eq!(rgb.texels[0], [srgb(64.0 / 255.0), srgb(128.0 / 255.0), 1.0, 1.0]);
        // 8-bit grey is truncated to 8 bits after decoding: 64 -> 13.07 -> 13.
        let grey = decode_png(
            p,
            &encode(1, 1, png::ColorType::Grayscale, png::BitDepth::Eight, &[64], true),
            budget,
            false,
            GammaCurve::Neutral,
        )
        .unwrap();
        assert_eq!(grey.texels[0][0], 13.0 / 255.0);
        // 16-bit grey keeps its precision.
        let grey16 = decode_png(
            p,
            &encode(1, 1, png::ColorType::Grayscale, png::BitDepth::Sixteen, &[64, 64], true),
            budget,
            false,
            GammaCurve::Neutral,
        )
        .unwrap();
        assert_eq!(grey16.texels[0][0], srgb(f32::from(0x4040u16) / 65535.0));
        // RGBA: straight alpha; a gAMA of 1 decodes linearly.
        let rgba = decode_png(
            p,
            &encode(1, 1, png::ColorType::Rgba, png::BitDepth::Eight, &[64, 0, 0, 128], false),
            budget,
            false,
            GammaCurve::Neutral,
        )
        .unwrap();
        assert_eq!(rgba.texels[0], [64.0 / 255.0, 0.0, 0.0, 128.0 / 255.0]);
        // In a 2.2 working space (assumed_gamma 2.2): an sRGB file goes through linear light
        // into the working space; a file whose gAMA is 1/2.2 matches it and arrives unchanged;
        // 8-bit grey is truncated after the transcoding, as POV-Ray keeps it.
        let working = GammaCurve::power_law(2.2);
        let png = encode(1, 1, png::ColorType::Rgb, png::BitDepth::Eight, &[64, 128, 255], true);
        let rgb = decode_png(p, &png, budget, false, working).unwrap();
        let to_working = |v: f32| srgb(v).powf(1.0 / 2.2f32);
        assert_eq!(rgb.texels[0], [to_working(64.0 / 255.0), to_working(128.0 / 255.0), 1.0, 1.0]);
        let mut gama = Vec::new();
        {
            let mut e = png::Encoder::new(&mut gama, 1, 1);
            e.set_color(png::ColorType::Rgb);
            e.set_depth(png::BitDepth::Eight);
            e.set_source_gamma(png::ScaledFloat::new(1.0 / 2.2));
            e.write_header().unwrap().write_image_data(&[64, 128, 255]).unwrap();
        }
        let matched = decode_png(p, &gama, budget, false, working).unwrap();
        assert_eq!(matched.texels[0], [64.0 / 255.0, 128.0 / 255.0, 1.0, 1.0]);
        let grey = encode(1, 1, png::ColorType::Grayscale, png::BitDepth::Eight, &[64], true);
        let grey = decode_png(p, &grey, budget, false, working).unwrap();
        assert_eq!(grey.texels[0][0], (to_working(64.0 / 255.0) * 255.0).trunc() / 255.0);
        // Bump maps stay raw whatever the working space.
        let raw = decode_png(p, &png, budget, true, working).unwrap();
        assert_eq!(raw.texels[0], [64.0 / 255.0, 128.0 / 255.0, 1.0, 1.0]);
        assert!(rgba.has_alpha);
        assert!(matches!(decode_png(p, b"GIF89a", budget, false, GammaCurve::Neutral), Err(ImageMapError::NotPng(_))));
        let mut broken = encode(1, 1, png::ColorType::Rgb, png::BitDepth::Eight, &[1, 2, 3], true);
        broken.truncate(40);
        assert!(matches!(
            decode_png(p, &broken, budget, false, GammaCurve::Neutral),
            Err(ImageMapError::Texture(TextureError::Decode { .. }))
        ));
        let huge = encode(1, 1, png::ColorType::Rgb, png::BitDepth::Eight, &[1, 2, 3], true);
        assert!(matches!(
            decode_png(p, &huge, MemoryBudget(10), false, GammaCurve::Neutral),
            Err(ImageMapError::Texture(TextureError::OverBudget(_)))
        ));
    }

    #[test]
    fn a_pigment_holds_the_map_in_place_of_a_pattern() {
        use crate::material::pattern::{Pigment, PigmentField};
        let mut p: Pigment =
            toml::from_str("image_map = { file = \"t.png\", map_type = \"spherical\" }\nscale = 2").unwrap();
        p.check().unwrap();
        p.image_map.as_mut().unwrap().image = Some(image());
        let f = PigmentField::new(&p);
        // Prism's -z is POV-Ray's +z, a quarter turn: column 1 (any distance).
        assert_eq!(texel_of(f.at(DVec3::new(0.0, -0.1, -1.0))), (1, 1));
        // The pigment's colours include the map's clearest, for shading that does not look up.
        assert_eq!(p.colors().len(), 1);
        let err = |text: &str| toml::from_str::<Pigment>(text).unwrap().check().unwrap_err().0;
        assert_eq!(err("image_map = { file = \"t.png\" }\ncolor_map = [[0, [1, 1, 1]]]"), "color_map");
        assert_eq!(err("image_map = { file = \"t.png\" }\nwave = \"sine\""), "wave");
        assert_eq!(err("image_map = { file = \"t.png\" }\npattern = \"onion\""), "image_map");
        assert_eq!(err("scale = 2"), "pattern");
        assert_eq!(err("image_map = { file = \"t.png\", filter_all = nan }"), "image_map.filter_all");
        assert_eq!(err("image_map = { file = \"t.png\", transmit_all = 1e300 }"), "image_map.transmit_all");
        assert_eq!(err("image_map = { file = \"t.png\" }\nscale = 0"), "scale");
    }

    #[test]
    fn unknown_names_get_a_suggestion() {
        let e = toml::from_str::<ImageMap>("file = \"a.png\"\nmap_type = \"sphrical\"").unwrap_err().to_string();
        assert!(e.contains("did you mean `spherical`?"), "{e}");
        let e = toml::from_str::<ImageMap>("file = \"a.png\"\ninterpolate = \"bilinar\"").unwrap_err().to_string();
        assert!(e.contains("did you mean `bilinear`?"), "{e}");
    }
}
