//! Image textures: decoding through the `image` crate, sRGB or linear storage, mip-mapping,
//! wrap modes and trilinear filtering driven by a footprint, and a store that decodes each
//! image once however many materials use it.
//!
//! Texture coordinates follow glTF: `(0, 0)` is the top-left corner of the image, u grows to
//! the right and v downward. The OBJ importer flips `vt`'s v (OBJ counts from the bottom).
//! Texel `i` covers `[i / w, (i + 1) / w]`, so its centre is at `(i + 0.5) / w`.

pub mod distribution;
pub mod environment;

use std::collections::HashMap;
use std::fmt;
use std::path::{Path, PathBuf};
use std::sync::{Arc, LazyLock};

use glam::{DVec2, Vec4};
use schemars::JsonSchema;
use serde::de::{self, Deserializer, MapAccess, Visitor};
use serde::{Deserialize, Serialize};

use crate::files::{FileAccess, FileError, FileKind, shown_path};
use crate::limits::{MAX_TEXTURE_SIDE, MemoryBudget, OverBudget};

/// How texture coordinates outside [0, 1] are mapped back into the image.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Wrap {
    /// The image tiles the plane.
    #[default]
    Repeat,
    /// Coordinates are clamped: the border texels extend forever.
    Clamp,
    /// The image tiles the plane, every other copy mirrored.
    Mirror,
}

impl Wrap {
    /// The texel index for integer texel coordinate `i` in an axis of `n` texels.
    #[inline]
    fn index(self, i: i64, n: usize) -> usize {
        let n = n as i64;
        let j = match self {
            Wrap::Repeat => i.rem_euclid(n),
            Wrap::Clamp => i.clamp(0, n - 1),
            Wrap::Mirror => {
                let period = i.rem_euclid(2 * n);
                if period < n { period } else { 2 * n - 1 - period }
            }
        };
        j as usize
    }
}

/// Whether a texture holds colours (stored sRGB-encoded, decoded to linear on lookup) or
/// data such as roughness or normals (stored and returned as is).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ColorSpace {
    /// Colour maps: base colour, emissive. Alpha is always linear.
    Srgb,
    /// Data maps: metallic-roughness, normal maps, alpha masks.
    Linear,
}

/// sRGB-encoded byte to linear value.
static SRGB_TO_LINEAR: LazyLock<[f32; 256]> = LazyLock::new(|| {
    let mut table = [0.0; 256];
    for (i, v) in table.iter_mut().enumerate() {
        *v = srgb_to_linear(i as f32 / 255.0);
    }
    table
});

/// The sRGB transfer function, decoding.
pub fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.04045 { c / 12.92 } else { ((c + 0.055) / 1.055).powf(2.4) }
}

/// The sRGB transfer function, encoding.
pub fn linear_to_srgb(c: f32) -> f32 {
    crate::gamma::GammaCurve::Srgb.encode(c)
}

/// One mip level: RGBA bytes, row-major from the top.
#[derive(Clone, Debug)]
struct Level {
    width: usize,
    height: usize,
    texels: Vec<[u8; 4]>,
}

/// A decoded, mip-mapped RGBA image. Eight bits per channel keeps large texture sets (Sponza's
/// dozens of 1024-squared maps) small; colour maps keep their sRGB encoding, so the eight
/// bits are spent where the eye needs them, and are decoded through a table.
#[derive(Clone)]
pub struct Texture {
    levels: Vec<Level>,
    space: ColorSpace,
}

impl fmt::Debug for Texture {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "Texture({}x{}, {} levels, {:?})", self.width(), self.height(), self.levels.len(), self.space)
    }
}

impl Texture {
    /// A texture from RGBA8 texels (`width * height` of them, rows from the top).
    ///
    /// # Panics
    ///
    /// When the sizes do not match or are zero (a programming error: decoders give both).
    pub fn from_rgba8(width: usize, height: usize, texels: Vec<[u8; 4]>, space: ColorSpace) -> Self {
        assert!(width > 0 && height > 0 && texels.len() == width * height, "texture size mismatch");
        let mut levels = vec![Level { width, height, texels }];
        while let Some(last) = levels.last()
            && (last.width > 1 || last.height > 1)
        {
            let next = downsample(last, space);
            levels.push(next);
        }
        Self { levels, space }
    }

    /// A texture from any decoded image (16-bit and float images are reduced to 8 bits).
    pub fn from_image(image: image::DynamicImage, space: ColorSpace) -> Self {
        let rgba = image.into_rgba8();
        let (w, h) = (rgba.width() as usize, rgba.height() as usize);
        let texels = rgba.pixels().map(|p| p.0).collect();
        Self::from_rgba8(w.max(1), h.max(1), texels, space)
    }

    /// The full-resolution level as an 8-bit RGB PNG file (alpha dropped): the texels
    /// exactly as sampling reads them, for exporters that need the image as a file.
    pub fn rgb_png(&self) -> image::ImageResult<Vec<u8>> {
        use image::ImageEncoder;
        let level = &self.levels[0];
        let rgb: Vec<u8> = level.texels.iter().flat_map(|t| [t[0], t[1], t[2]]).collect();
        let mut bytes = Vec::new();
        image::codecs::png::PngEncoder::new(&mut bytes).write_image(
            &rgb,
            level.width as u32,
            level.height as u32,
            image::ExtendedColorType::Rgb8,
        )?;
        Ok(bytes)
    }

    /// Width of the full-resolution level.
    pub fn width(&self) -> usize {
        self.levels[0].width
    }

    /// Height of the full-resolution level.
    pub fn height(&self) -> usize {
        self.levels[0].height
    }

    /// Number of mip levels (1 for a 1x1 image).
    pub fn level_count(&self) -> usize {
        self.levels.len()
    }

    /// Bytes of texel storage over all levels.
    pub fn memory_bytes(&self) -> usize {
        self.levels.iter().map(|l| l.texels.len() * 4).sum()
    }

    /// The mip level (fractional) for a footprint `width` in uv units: log2 of the
    /// footprint measured in texels of the full-resolution level.
    pub fn lod_for_footprint(&self, width: f64) -> f64 {
        let texels = width * self.width().max(self.height()) as f64;
        if texels > 1.0 { texels.log2() } else { 0.0 }
    }

    /// The linear RGBA value at `uv`, trilinearly filtered at mip level `lod` (0 = full
    /// resolution; clamped to the levels that exist).
    pub fn sample(&self, uv: DVec2, lod: f64, wrap: [Wrap; 2]) -> Vec4 {
        let max = (self.levels.len() - 1) as f64;
        let lod = if lod.is_finite() { lod.clamp(0.0, max) } else { 0.0 };
        let lo = lod.floor() as usize;
        let f = (lod - lo as f64) as f32;
        let a = self.bilinear(lo, uv, wrap);
        if f <= 0.0 || lo + 1 >= self.levels.len() {
            return a;
        }
        let b = self.bilinear(lo + 1, uv, wrap);
        a + (b - a) * f
    }

    /// Bilinear interpolation of the four texels around `uv` in `level`.
    pub fn bilinear(&self, level: usize, uv: DVec2, wrap: [Wrap; 2]) -> Vec4 {
        let l = &self.levels[level.min(self.levels.len() - 1)];
        let uv = if uv.is_finite() { uv } else { DVec2::ZERO };
        let x = uv.x * l.width as f64 - 0.5;
        let y = uv.y * l.height as f64 - 0.5;
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = ((x - x0) as f32, (y - y0) as f32);
        // Texel coordinates far outside the image still wrap correctly in i64.
        let (x0, y0) = (x0.clamp(-1e15, 1e15) as i64, y0.clamp(-1e15, 1e15) as i64);
        let (xa, xb) = (wrap[0].index(x0, l.width), wrap[0].index(x0 + 1, l.width));
        let (ya, yb) = (wrap[1].index(y0, l.height), wrap[1].index(y0 + 1, l.height));
        let t = |x: usize, y: usize| self.decode(l.texels[y * l.width + x]);
        let top = t(xa, ya) * (1.0 - fx) + t(xb, ya) * fx;
        let bottom = t(xa, yb) * (1.0 - fx) + t(xb, yb) * fx;
        top * (1.0 - fy) + bottom * fy
    }

    /// The nearest texel of the full-resolution level (alpha tests during traversal).
    pub fn nearest(&self, uv: DVec2, wrap: [Wrap; 2]) -> Vec4 {
        let l = &self.levels[0];
        let uv = if uv.is_finite() { uv } else { DVec2::ZERO };
        let x = (uv.x * l.width as f64).floor().clamp(-1e15, 1e15) as i64;
        let y = (uv.y * l.height as f64).floor().clamp(-1e15, 1e15) as i64;
        self.decode(l.texels[wrap[1].index(y, l.height) * l.width + wrap[0].index(x, l.width)])
    }

    #[inline]
    fn decode(&self, t: [u8; 4]) -> Vec4 {
        match self.space {
            ColorSpace::Srgb => {
                let lut = &*SRGB_TO_LINEAR;
                Vec4::new(lut[t[0] as usize], lut[t[1] as usize], lut[t[2] as usize], f32::from(t[3]) / 255.0)
            }
            ColorSpace::Linear => Vec4::new(f32::from(t[0]), f32::from(t[1]), f32::from(t[2]), f32::from(t[3])) / 255.0,
        }
    }
}

/// The next mip level: each texel the mean of (up to) 2x2 texels, averaged in linear light.
fn downsample(l: &Level, space: ColorSpace) -> Level {
    let width = (l.width / 2).max(1);
    let height = (l.height / 2).max(1);
    let lut = &*SRGB_TO_LINEAR;
    let mut texels = Vec::with_capacity(width * height);
    for y in 0..height {
        for x in 0..width {
            let mut sum = [0.0f32; 4];
            let mut n = 0.0;
            for dy in 0..2 {
                for dx in 0..2 {
                    let sx = (2 * x + dx).min(l.width - 1);
                    let sy = (2 * y + dy).min(l.height - 1);
                    let t = l.texels[sy * l.width + sx];
                    for c in 0..4 {
                        sum[c] += if c < 3 && space == ColorSpace::Srgb {
                            lut[t[c] as usize]
                        } else {
                            f32::from(t[c]) / 255.0
                        };
                    }
                    n += 1.0;
                }
            }
            let mut out = [0u8; 4];
            for c in 0..4 {
                let v = sum[c] / n;
                let encoded = if c < 3 && space == ColorSpace::Srgb { linear_to_srgb(v) } else { v };
                out[c] = (encoded * 255.0 + 0.5).clamp(0.0, 255.0) as u8;
            }
            texels.push(out);
        }
    }
    Level { width, height, texels }
}

/// Why an image file cannot become a texture.
#[derive(Debug, thiserror::Error)]
pub enum TextureError {
    /// The file cannot be opened or read (or is not a regular file, too large, or outside
    /// the `--root` sandbox).
    #[error(transparent)]
    File(#[from] FileError),
    /// The file is read but is not an image the `image` crate decodes.
    #[error("cannot decode image `{}`: {source}", shown_path(.path))]
    Decode {
        /// The image file.
        path: PathBuf,
        /// The cause.
        source: image::ImageError,
    },
    /// A side is longer than [`MAX_TEXTURE_SIDE`].
    #[error("image `{}` is {width} x {height}: a side is longer than the limit of {MAX_TEXTURE_SIDE}", shown_path(.path))]
    TooLarge {
        /// The image file.
        path: PathBuf,
        /// Width in texels.
        width: u32,
        /// Height in texels.
        height: u32,
    },
    /// The image has no texels (a width or height of 0).
    #[error("image `{}` is empty ({width} x {height})", shown_path(.path))]
    Empty {
        /// The image file.
        path: PathBuf,
        /// Width in texels.
        width: u32,
        /// Height in texels.
        height: u32,
    },
    /// Decoding would exceed the memory budget.
    #[error(transparent)]
    OverBudget(#[from] OverBudget),
}

/// Bytes a `width` × `height` image costs while it becomes a texture: the decoded image
/// (`bytes_per_pixel` each), its RGBA8 copy and the mip chain (a third more).
pub fn decode_estimate(width: u32, height: u32, bytes_per_pixel: u64) -> u64 {
    let texels = u64::from(width) * u64::from(height);
    texels.saturating_mul(bytes_per_pixel + 4 + 6)
}

/// Decodes an encoded image (`path` names it in errors and hints its format by extension),
/// checking its dimensions against [`MAX_TEXTURE_SIDE`] and the budget before decoding.
pub fn decode_image(path: &Path, bytes: &[u8], budget: MemoryBudget) -> Result<image::DynamicImage, TextureError> {
    use image::ImageDecoder;
    let decode_error = |source| TextureError::Decode { path: path.to_path_buf(), source };
    let mut reader = image::ImageReader::new(std::io::Cursor::new(bytes));
    if let Ok(format) = image::ImageFormat::from_path(path) {
        reader.set_format(format);
    }
    let reader = reader.with_guessed_format().map_err(|source| FileError::Io { path: path.to_path_buf(), source })?;
    let decoder = reader.into_decoder().map_err(decode_error)?;
    let (width, height) = decoder.dimensions();
    if width > MAX_TEXTURE_SIDE || height > MAX_TEXTURE_SIDE {
        return Err(TextureError::TooLarge { path: path.to_path_buf(), width, height });
    }
    // A PGM of height 0 decodes to no texels (found by fuzzing: Texture::from_rgba8 asserted).
    if width == 0 || height == 0 {
        return Err(TextureError::Empty { path: path.to_path_buf(), width, height });
    }
    let estimate = decode_estimate(width, height, u64::from(decoder.color_type().bytes_per_pixel()));
    budget.check(|| format!("image `{}` ({width} x {height})", shown_path(path)), estimate)?;
    image::DynamicImage::from_decoder(decoder).map_err(decode_error)
}

/// Decoded textures, keyed by (canonical file, image index inside a glTF file, colour
/// space): an image used by many materials, meshes or instances is decoded once.
#[derive(Debug)]
pub struct TextureStore {
    textures: HashMap<(PathBuf, Option<u32>, ColorSpace), Arc<Texture>>,
    /// How image files (and, through the importers, mesh files) are read.
    access: FileAccess,
    /// What all decoded images and built meshes of one load may cost together.
    budget: MemoryBudget,
    /// Bytes reserved so far (estimates) by decoded images and built meshes.
    spent: u64,
}

impl Default for TextureStore {
    fn default() -> Self {
        Self::with_limits(FileAccess::unrestricted(), MemoryBudget::UNLIMITED)
    }
}

impl TextureStore {
    /// An empty store reading any file, with no memory budget.
    pub fn new() -> Self {
        Self::default()
    }

    /// An empty store reading files through `access`; all decodes and mesh builds (see
    /// [`TextureStore::reserve`]) share `budget`.
    pub fn with_limits(access: FileAccess, budget: MemoryBudget) -> Self {
        Self { textures: HashMap::new(), access, budget, spent: 0 }
    }

    /// How files are read (the importers read mesh files through it too).
    pub fn access(&self) -> &FileAccess {
        &self.access
    }

    /// What remains of the memory budget after the images and meshes reserved so far.
    pub fn budget(&self) -> MemoryBudget {
        MemoryBudget(self.budget.0.saturating_sub(self.spent))
    }

    /// Takes `estimate` bytes for `what` (a decoded image, a mesh with its BVH) out of the
    /// budget that every image and mesh of the load shares, so that many files that each fit
    /// cannot together exceed it. Nothing is taken when it does not fit.
    pub fn reserve(&mut self, what: impl FnOnce() -> String, estimate: u64) -> Result<(), OverBudget> {
        let total = self.spent.saturating_add(estimate);
        if total > self.budget.0 {
            return Err(OverBudget { what: what(), estimate, budget: self.budget.0, spent: self.spent });
        }
        self.spent = total;
        Ok(())
    }

    /// An error from a check against [`TextureStore::budget`] (what remains), restated
    /// against the whole budget and what was spent before.
    pub fn restate(&self, mut error: OverBudget) -> OverBudget {
        error.budget = self.budget.0;
        error.spent = self.spent;
        error
    }

    /// The texture decoded from the image file at `path`.
    pub fn load_file(&mut self, path: &Path, space: ColorSpace) -> Result<Arc<Texture>, TextureError> {
        let canonical = self.access.resolve(path)?;
        let key = (canonical, None, space);
        if let Some(t) = self.textures.get(&key) {
            return Ok(t.clone());
        }
        let bytes = self.access.read(path, FileKind::Image)?;
        let image = match decode_image(path, &bytes, self.budget()) {
            Err(TextureError::OverBudget(e)) => return Err(TextureError::OverBudget(self.restate(e))),
            other => other?,
        };
        drop(bytes);
        let estimate = decode_estimate(image.width(), image.height(), u64::from(image.color().bytes_per_pixel()));
        self.reserve(|| format!("image `{}` ({} x {})", shown_path(path), image.width(), image.height()), estimate)?;
        let texture = Arc::new(Texture::from_image(image, space));
        self.textures.insert(key, texture.clone());
        Ok(texture)
    }

    /// The texture for image `index` of the glTF file at `canonical`, decoding it with
    /// `decode` (width, height, RGBA8 texels) the first time; `decode`'s error is returned
    /// as is, and an image over the memory budget left (see [`TextureStore::reserve`]) as `E::from`.
    pub fn load_embedded<E>(
        &mut self,
        canonical: &Path,
        index: u32,
        space: ColorSpace,
        decode: impl FnOnce() -> Result<(usize, usize, Vec<[u8; 4]>), E>,
    ) -> Result<Arc<Texture>, E>
    where
        E: From<OverBudget>,
    {
        let key = (canonical.to_path_buf(), Some(index), space);
        if let Some(t) = self.textures.get(&key) {
            return Ok(t.clone());
        }
        let (width, height, texels) = decode()?;
        let estimate = decode_estimate(width as u32, height as u32, 4);
        self.reserve(|| format!("image {index} of `{}` ({width} x {height})", shown_path(canonical)), estimate)?;
        let texture = Arc::new(Texture::from_rgba8(width, height, texels, space));
        self.textures.insert(key, texture.clone());
        Ok(texture)
    }

    /// Number of distinct decoded textures.
    pub fn len(&self) -> usize {
        self.textures.len()
    }

    /// True when nothing was decoded.
    pub fn is_empty(&self) -> bool {
        self.textures.is_empty()
    }
}

/// A texture used by a material: the image (a file, or an image inside a glTF file), how its
/// coordinates wrap, and a uv transform (KHR_texture_transform: scale, then rotate, then
/// offset). Written in a scene as a path string or a table
/// `{ file, wrap, offset, scale, rotation }`. The decoded image rides along, not saved.
#[derive(Clone, Serialize)]
pub struct TextureRef {
    /// The image file (relative to the scene file when written; absolute once loaded), or
    /// the glTF file holding the image.
    pub file: String,
    /// Index of the image inside the glTF file `file` (absent for image files).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub image: Option<u32>,
    /// Wrap modes along u and v.
    pub wrap: [Wrap; 2],
    /// Added to the coordinates last.
    pub offset: [f64; 2],
    /// Multiplies the coordinates first.
    pub scale: [f64; 2],
    /// Rotation of the coordinates in degrees, applied between scale and offset (glTF's sense:
    /// counter-clockwise in the image as displayed).
    pub rotation: f64,
    /// The decoded image (set by the loader; not part of the scene text).
    #[serde(skip)]
    pub texture: Option<Arc<Texture>>,
}

impl fmt::Debug for TextureRef {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("TextureRef")
            .field("file", &self.file)
            .field("image", &self.image)
            .field("wrap", &self.wrap)
            .field("loaded", &self.texture.is_some())
            .finish_non_exhaustive()
    }
}

impl PartialEq for TextureRef {
    /// Two references are equal when they name the same image the same way (the decoded
    /// image follows from that).
    fn eq(&self, other: &Self) -> bool {
        self.file == other.file
            && self.image == other.image
            && self.wrap == other.wrap
            && self.offset == other.offset
            && self.scale == other.scale
            && self.rotation == other.rotation
    }
}

impl TextureRef {
    /// A reference to `file` with repeat wrapping and no transform.
    pub fn new(file: impl Into<String>) -> Self {
        Self {
            file: file.into(),
            image: None,
            wrap: [Wrap::Repeat; 2],
            offset: [0.0; 2],
            scale: [1.0; 2],
            rotation: 0.0,
            texture: None,
        }
    }

    /// The coordinates after the uv transform.
    #[inline]
    pub fn transform_uv(&self, uv: DVec2) -> DVec2 {
        if self.scale == [1.0, 1.0] && self.rotation == 0.0 && self.offset == [0.0, 0.0] {
            return uv;
        }
        let (s, c) = self.rotation.to_radians().sin_cos();
        let (u, v) = (uv.x * self.scale[0], uv.y * self.scale[1]);
        DVec2::new(c * u + s * v + self.offset[0], -s * u + c * v + self.offset[1])
    }

    /// How much the transform stretches uv lengths (for footprints).
    pub fn uv_scale(&self) -> f64 {
        (self.scale[0].abs() * self.scale[1].abs()).sqrt()
    }

    /// The linear RGBA value at `uv` for a footprint `width` in (untransformed) uv units;
    /// opaque white when the image was never loaded.
    pub fn sample(&self, uv: DVec2, width: f64) -> Vec4 {
        match &self.texture {
            Some(t) => t.sample(self.transform_uv(uv), t.lod_for_footprint(width * self.uv_scale()), self.wrap),
            None => Vec4::ONE,
        }
    }

    /// Checks the numbers; (key, message) on failure.
    pub fn check(&self) -> Result<(), (&'static str, String)> {
        let numbers = [self.offset[0], self.offset[1], self.scale[0], self.scale[1], self.rotation];
        if numbers.iter().all(|v| v.is_finite()) {
            Ok(())
        } else {
            Err(("texture", format!("offset, scale and rotation must be finite in `{}`", self.file)))
        }
    }
}

/// The table form of a texture.
#[derive(Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
struct TextureTable {
    /// The image file, relative to the scene file (or the glTF file holding the image).
    file: String,
    /// Index of the image inside the glTF file `file`.
    #[serde(default)]
    image: Option<u32>,
    /// Wrap mode for both axes, or `[u, v]` (default `repeat`).
    #[serde(default)]
    wrap: Option<WrapSpec>,
    /// Added to the coordinates last (default `[0, 0]`).
    #[serde(default)]
    offset: Option<[f64; 2]>,
    /// Multiplies the coordinates first (default `[1, 1]`).
    #[serde(default)]
    scale: Option<[f64; 2]>,
    /// Rotation in degrees between scale and offset (default 0).
    #[serde(default)]
    rotation: Option<f64>,
}

/// A texture is written as an image path or as a `TextureTable`, as the deserializer
/// reads it.
impl JsonSchema for TextureRef {
    fn schema_name() -> std::borrow::Cow<'static, str> {
        "TextureRef".into()
    }

    fn json_schema(generator: &mut schemars::SchemaGenerator) -> schemars::Schema {
        let table = generator.subschema_for::<TextureTable>();
        schemars::json_schema!({
            "description": "A texture: an image path relative to the scene file, or a table { file, wrap, offset, scale, rotation }.",
            "anyOf": [{ "type": "string" }, table]
        })
    }
}

/// One wrap mode for both axes, or one per axis.
#[derive(Deserialize, JsonSchema)]
#[serde(untagged)]
enum WrapSpec {
    Both(Wrap),
    PerAxis([Wrap; 2]),
}

impl<'de> Deserialize<'de> for TextureRef {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(TextureRefVisitor)
    }
}

struct TextureRefVisitor;

impl<'de> Visitor<'de> for TextureRefVisitor {
    type Value = TextureRef;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a texture: an image path, or a table { file, wrap, offset, scale, rotation }")
    }

    fn visit_str<E: de::Error>(self, v: &str) -> Result<TextureRef, E> {
        Ok(TextureRef::new(v))
    }

    fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<TextureRef, A::Error> {
        let t = TextureTable::deserialize(de::value::MapAccessDeserializer::new(map))?;
        let wrap = match t.wrap {
            None => [Wrap::Repeat; 2],
            Some(WrapSpec::Both(w)) => [w, w],
            Some(WrapSpec::PerAxis(w)) => w,
        };
        Ok(TextureRef {
            file: t.file,
            image: t.image,
            wrap,
            offset: t.offset.unwrap_or([0.0; 2]),
            scale: t.scale.unwrap_or([1.0; 2]),
            rotation: t.rotation.unwrap_or(0.0),
            texture: None,
        })
    }
}

/// The width in uv units of a ray footprint `width` (world units, across the ray) where it
/// meets a surface: a ray cone (Akenine-Moeller et al., "Texture level of detail strategies
/// for real-time ray tracing", 2019) with an isotropic lookup. `uv_density` is the shape's
/// uv units per object-space length, `area_scale` how much the object-to-world transform
/// scales areas there (world length = object length * sqrt(area_scale)), and `cosine` the
/// cosine between the ray and the surface normal. A footprint seen at an angle is an
/// ellipse stretched by 1 / cosine; its isotropic stand-in is the circle of equal area
/// (1 / sqrt(cosine)), which blurs less than the ellipse's long axis and aliases less than
/// its short one.
pub fn uv_footprint(width: f64, uv_density: f64, area_scale: f64, cosine: f64) -> f64 {
    if !(uv_density > 0.0 && area_scale > 0.0 && width > 0.0) {
        return 0.0;
    }
    let stretch = 1.0 / cosine.abs().max(0.01).sqrt();
    width * uv_density / area_scale.sqrt() * stretch
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Images and meshes of one load share one budget: a reservation that fits alone but not
    /// after the others is refused, naming the whole budget and what was spent before.
    #[test]
    fn reservations_share_one_budget() {
        let mut store = TextureStore::with_limits(FileAccess::unrestricted(), MemoryBudget(100 << 20));
        store.reserve(|| "a".into(), 60 << 20).unwrap();
        assert_eq!(store.budget(), MemoryBudget(40 << 20));
        let e = store.reserve(|| "b".into(), 50 << 20).unwrap_err();
        assert_eq!((e.estimate, e.budget, e.spent), (50 << 20, 100 << 20, 60 << 20));
        assert_eq!(
            e.to_string(),
            "b needs about 50 MiB on top of 60 MiB for the meshes and images loaded before it, \
             over the memory budget of 100 MiB (--max-memory)"
        );
        assert_eq!(store.budget(), MemoryBudget(40 << 20), "a refused reservation takes nothing");
        store.reserve(|| "c".into(), 40 << 20).unwrap();
        assert_eq!(store.budget(), MemoryBudget(0));
    }

    fn checker(space: ColorSpace) -> Texture {
        // 4x4: black and white 1-texel checks.
        let texels =
            (0..16).map(|i| if (i % 4 + i / 4) % 2 == 0 { [0, 0, 0, 255] } else { [255, 255, 255, 255] }).collect();
        Texture::from_rgba8(4, 4, texels, space)
    }

    #[test]
    fn mip_chain_averages_in_linear_light() {
        let t = checker(ColorSpace::Srgb);
        assert_eq!(t.level_count(), 3);
        // The mean of black and white is linear 0.5, not sRGB 0.5 (= linear 0.214).
        let top = t.sample(DVec2::splat(0.5), 2.0, [Wrap::Repeat; 2]);
        assert!((top.x - 0.5).abs() < 0.01, "{top}");
        let data = checker(ColorSpace::Linear);
        assert!((data.sample(DVec2::splat(0.5), 2.0, [Wrap::Repeat; 2]).x - 0.5).abs() < 0.01);
    }

    #[test]
    fn texel_centres_are_exact_and_bilinear_blends_between() {
        let t = Texture::from_rgba8(2, 1, vec![[0, 0, 0, 255], [255, 0, 0, 255]], ColorSpace::Linear);
        let w = [Wrap::Clamp; 2];
        assert_eq!(t.bilinear(0, DVec2::new(0.25, 0.5), w).x, 0.0);
        assert_eq!(t.bilinear(0, DVec2::new(0.75, 0.5), w).x, 1.0);
        assert!((t.bilinear(0, DVec2::new(0.5, 0.5), w).x - 0.5).abs() < 1e-6);
        // Clamped beyond the edge.
        assert_eq!(t.bilinear(0, DVec2::new(5.0, 0.5), w).x, 1.0);
        // Repeat blends the last texel with the first across the seam.
        let r = t.bilinear(0, DVec2::new(1.0, 0.5), [Wrap::Repeat; 2]).x;
        assert!((r - 0.5).abs() < 1e-6, "{r}");
    }

    #[test]
    fn wrap_modes() {
        assert_eq!(Wrap::Repeat.index(-1, 4), 3);
        assert_eq!(Wrap::Repeat.index(9, 4), 1);
        assert_eq!(Wrap::Clamp.index(-3, 4), 0);
        assert_eq!(Wrap::Clamp.index(7, 4), 3);
        assert_eq!(Wrap::Mirror.index(4, 4), 3);
        assert_eq!(Wrap::Mirror.index(5, 4), 2);
        assert_eq!(Wrap::Mirror.index(-1, 4), 0);
        assert_eq!(Wrap::Mirror.index(8, 4), 0);
    }

    #[test]
    fn lod_follows_footprint() {
        let t = Texture::from_rgba8(256, 256, vec![[0; 4]; 256 * 256], ColorSpace::Linear);
        assert_eq!(t.level_count(), 9);
        assert_eq!(t.lod_for_footprint(1.0 / 256.0), 0.0);
        assert!((t.lod_for_footprint(4.0 / 256.0) - 2.0).abs() < 1e-12);
        assert!((t.lod_for_footprint(1.0) - 8.0).abs() < 1e-12);
        assert_eq!(t.lod_for_footprint(1e-9), 0.0, "magnification uses level 0");
    }

    #[test]
    fn footprint_scales_with_distance_density_and_transform() {
        let base = uv_footprint(0.01, 2.0, 1.0, 1.0);
        assert!((base - 0.02).abs() < 1e-15);
        assert!((uv_footprint(0.02, 2.0, 1.0, 1.0) - 0.04).abs() < 1e-15, "twice as far");
        // An object scaled up 2x covers twice the world length per uv unit.
        assert!((uv_footprint(0.01, 2.0, 4.0, 1.0) - 0.01).abs() < 1e-15);
        assert!(uv_footprint(0.01, 2.0, 1.0, 0.25) > base, "oblique views blur more");
        assert_eq!(uv_footprint(0.01, 0.0, 1.0, 1.0), 0.0, "no uv density: full resolution");
    }

    #[test]
    fn srgb_decoding() {
        assert!((srgb_to_linear(0.5) - 0.214).abs() < 1e-3);
        assert!((linear_to_srgb(srgb_to_linear(0.7)) - 0.7).abs() < 1e-6);
        let t = Texture::from_rgba8(1, 1, vec![[128, 128, 128, 128]], ColorSpace::Srgb);
        let v = t.sample(DVec2::ZERO, 0.0, [Wrap::Repeat; 2]);
        assert!((v.x - 0.2158).abs() < 1e-3 && (v.w - 128.0 / 255.0).abs() < 1e-6);
    }

    #[test]
    fn texture_transform_matches_khr_texture_transform() {
        let mut r = TextureRef::new("x.png");
        r.offset = [0.5, 0.0];
        r.scale = [2.0, 2.0];
        r.rotation = 90.0;
        // scale -> (2, 0); rotate by 90: (c u + s v, -s u + c v) = (0, -2); offset -> (0.5, -2).
        let uv = r.transform_uv(DVec2::new(1.0, 0.0));
        assert!((uv - DVec2::new(0.5, -2.0)).length() < 1e-12, "{uv}");
    }

    #[test]
    fn texture_ref_forms() {
        #[derive(Deserialize)]
        struct W {
            t: TextureRef,
        }
        let w: W = toml::from_str("t = \"a.png\"").unwrap();
        assert_eq!(w.t.file, "a.png");
        let w: W = toml::from_str("t = { file = \"a.png\", wrap = \"clamp\", scale = [2, 3] }").unwrap();
        assert_eq!((w.t.wrap, w.t.scale), ([Wrap::Clamp; 2], [2.0, 3.0]));
        let w: W = toml::from_str("t = { file = \"a.png\", wrap = [\"mirror\", \"repeat\"] }").unwrap();
        assert_eq!(w.t.wrap, [Wrap::Mirror, Wrap::Repeat]);
        assert!(toml::from_str::<W>("t = { file = \"a.png\", wrp = \"clamp\" }").is_err());
    }
}
