//! Partial renders: the state of a part of a render (a region of the frame, a range of each
//! pixel's samples, or both) as one OpenEXR file that can be summed with other parts into
//! the image one machine would make. Render farms write one per job; checkpoints can write
//! one per save.
//!
//! A part file is a single-layer EXR whose data window is the part's region and whose display
//! window is the full frame. Its channels:
//!
//! - `R`, `G`, `B` (f32): the mean of the part's samples, the pixel a viewer shows. For a part
//!   holding all of a pixel's samples these are exactly the pixels of the full render.
//! - `samples` (u32): samples rendered into each pixel.
//! - when the part has [`Partial::sums`]: `sum.R.hi`, `sum.R.lo`, ... `weight.hi`, `weight.lo`
//!   (u32): the f64 weighted sum of each channel's samples and the f64 sum of their filter
//!   weights, as the high and low 32 bits of each f64, so they round-trip exactly.
//! - AOV layers, when the part keeps them (checkpoints do): `albedo.R`, `depth.Z`, ... (f32).
//!
//! One header attribute, `prismPart` (text, `key=value` lines), says what the part is: the
//! [`Fingerprint`] of the scene and its settings, the frame size, the sample range, the
//! scene's total samples, the tile (if any), the antialiasing family, and the exposure and
//! tone map for 8-bit images of the merged result, and for checkpoints
//! ([`crate::checkpoint`]) the scene itself as `prism save` writes it, escaped onto one
//! line. (One attribute, because the EXR writer stores several in hash order, which would
//! make part files differ from run to run.)

use std::io::Cursor;
use std::ops::Range;
use std::path::{Path, PathBuf};

use crate::film::{Aov, Film, Layer, Region};
use crate::world::Scene;
use crate::world::components::ToneMap;

/// Version of the part-file layout written in `prismPart` (`format=`).
pub const FORMAT_VERSION: u32 = 1;

/// Name of the header attribute holding a part's description.
pub const ATTRIBUTE: &str = "prismPart";

/// A digest of everything that decides a scene's pixels: the scene as [`crate::scene::save`]
/// writes it (every object, material, light and render setting: resolution, samples, seed,
/// integrator, antialiasing, filter, depth limits, exposure...) and Prism's version. Parts
/// merge only when their fingerprints are equal. Mesh and texture files enter by path, not
/// by content: a farm must not change them during a render.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Fingerprint(pub String);

impl Fingerprint {
    /// The fingerprint of `text` (two 64-bit FNV-1a digests with different offsets, in hex).
    pub fn of_text(text: &str) -> Self {
        let digest =
            |offset: u64| text.bytes().fold(offset, |h, b| (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3));
        Self(format!("{:016x}{:016x}", digest(0xcbf2_9ce4_8422_2325), digest(0x6c62_272e_07bb_0142)))
    }

    /// The fingerprint of a loaded scene with its settings (after command-line overrides,
    /// before [`crate::prepare`]).
    pub fn of_scene(scene: &Scene) -> Result<Self, toml::ser::Error> {
        let text = crate::scene::save::save(scene)?;
        Ok(Self::of_text(&format!("prism {}\n{text}", env!("CARGO_PKG_VERSION"))))
    }
}

/// How the scene's pixels are sampled, which decides how parts may split them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Sampling {
    /// A fixed number of stratified samples per pixel, each a pure function of (pixel, sample,
    /// seed): parts may split regions and sample ranges.
    Stratified,
    /// POV-Ray's antialiasing, which compares neighbouring pixels to decide where to sample:
    /// parts split regions only (each holds all of its pixels' samples).
    Pov,
}

impl Sampling {
    fn name(self) -> &'static str {
        match self {
            Sampling::Stratified => "stratified",
            Sampling::Pov => "pov",
        }
    }
}

/// What a part is: which scene, which pixels, which samples.
#[derive(Clone, Debug, PartialEq)]
pub struct PartInfo {
    /// The scene and settings rendered.
    pub fingerprint: Fingerprint,
    /// The full frame's width and height in pixels.
    pub frame: (u32, u32),
    /// The pixels the part covers (its data window).
    pub region: Region,
    /// The samples of each pixel the part holds, `start..end` of `0..total_samples`.
    pub samples: Range<u32>,
    /// The scene's samples per pixel.
    pub total_samples: u32,
    /// `(I, N)` when the part is tile I (0-based) of an N-tile split.
    pub tile: Option<(u32, u32)>,
    /// How the scene samples pixels.
    pub sampling: Sampling,
    /// Exposure in stops for 8-bit images of the merged result.
    pub exposure: f64,
    /// Tone map for 8-bit images of the merged result.
    pub tone_map: ToneMap,
    /// The scene with its settings as [`crate::scene::save`] writes it, when the part keeps
    /// it (checkpoints do, to name the setting that differs from a later render's).
    pub scene: Option<String>,
}

impl PartInfo {
    /// True when the part holds every sample of its pixels.
    pub fn has_all_samples(&self) -> bool {
        self.samples == (0..self.total_samples)
    }

    fn to_text(&self) -> String {
        let r = &self.region;
        let mut text = format!(
            "format={FORMAT_VERSION}\nfingerprint={}\nframe={}x{}\nregion={},{},{},{}\nsamples={}..{}\ntotal_samples={}\nsampling={}\nexposure={}\ntone_map={}\n",
            self.fingerprint.0,
            self.frame.0,
            self.frame.1,
            r.x0,
            r.y0,
            r.x1,
            r.y1,
            self.samples.start,
            self.samples.end,
            self.total_samples,
            self.sampling.name(),
            self.exposure,
            tone_map_name(self.tone_map),
        );
        if let Some((i, n)) = self.tile {
            text += &format!("tile={i}/{n}\n");
        }
        if let Some(scene) = &self.scene {
            text += &format!("scene={}\n", escape(scene));
        }
        text
    }

    fn from_text(text: &str) -> Result<Self, String> {
        let mut fields = std::collections::BTreeMap::new();
        for line in text.lines().filter(|l| !l.is_empty()) {
            let (key, value) = line.split_once('=').ok_or_else(|| format!("line `{line}` is not key=value"))?;
            fields.insert(key, value);
        }
        let get = |key: &str| fields.get(key).copied().ok_or_else(|| format!("key `{key}` is missing"));
        let bad = |key: &str, value: &str| format!("key `{key}`: `{value}` is not valid");
        let format: u32 = get("format")?.parse().map_err(|_| bad("format", get("format").unwrap_or("")))?;
        if format != FORMAT_VERSION {
            return Err(format!("key `format`: version {format} is not {FORMAT_VERSION} (written by another Prism)"));
        }
        let fingerprint = Fingerprint(get("fingerprint")?.to_string());
        let frame = parse_pair(get("frame")?, 'x').ok_or_else(|| bad("frame", get("frame").unwrap_or("")))?;
        let region = parse_region(get("region")?).ok_or_else(|| bad("region", get("region").unwrap_or("")))?;
        let samples = parse_range(get("samples")?).ok_or_else(|| bad("samples", get("samples").unwrap_or("")))?;
        let total = get("total_samples")?;
        let total_samples: u32 = total.parse().map_err(|_| bad("total_samples", total))?;
        let sampling = match get("sampling")? {
            "stratified" => Sampling::Stratified,
            "pov" => Sampling::Pov,
            other => return Err(bad("sampling", other)),
        };
        let exposure: f64 = get("exposure")?.parse().map_err(|_| bad("exposure", get("exposure").unwrap_or("")))?;
        let tone_map = match get("tone_map")? {
            "clamp" => ToneMap::Clamp,
            "reinhard" => ToneMap::Reinhard,
            "aces" => ToneMap::Aces,
            other => return Err(bad("tone_map", other)),
        };
        let tile = match fields.get("tile") {
            None => None,
            Some(value) => Some(parse_pair(value, '/').ok_or_else(|| bad("tile", value))?),
        };
        let scene = match fields.get("scene") {
            None => None,
            Some(value) => Some(unescape(value).ok_or_else(|| bad("scene", "(its escapes)"))?),
        };
        let info =
            PartInfo { fingerprint, frame, region, samples, total_samples, tile, sampling, exposure, tone_map, scene };
        info.check()?;
        Ok(info)
    }

    /// The description is consistent: a non-empty region inside the frame, a non-empty
    /// sample range inside the scene's, all samples for POV-Ray's antialiasing, a tile index
    /// below the tile count.
    fn check(&self) -> Result<(), String> {
        let (w, h) = self.frame;
        if self.region.is_empty() || !self.region.fits(w, h) {
            return Err(format!("key `region`: not a non-empty part of the {w}x{h} frame"));
        }
        if self.samples.is_empty() || self.samples.end > self.total_samples {
            return Err(format!("key `samples`: not a non-empty part of 0..{}", self.total_samples));
        }
        if self.sampling == Sampling::Pov && !self.has_all_samples() {
            return Err("key `samples`: POV-Ray antialiasing parts hold all samples".into());
        }
        if let Some((i, n)) = self.tile
            && i >= n
        {
            return Err(format!("key `tile`: {i}/{n} is not below the tile count"));
        }
        if !self.exposure.is_finite() {
            return Err("key `exposure`: not finite".into());
        }
        Ok(())
    }
}

/// `text` on one line of printable ASCII (EXR text attributes hold bytes, and the header
/// is `key=value` lines): `\\`, `\n` and `\u{HEX}` stand for a backslash, a line break and
/// any other character outside printable ASCII.
fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            ' '..='~' => out.push(c),
            _ => out.push_str(&format!("\\u{{{:x}}}", u32::from(c))),
        }
    }
    out
}

/// The text [`escape`] made (`None` for a broken escape).
fn unescape(text: &str) -> Option<String> {
    let mut out = String::with_capacity(text.len());
    let mut chars = text.chars();
    while let Some(c) = chars.next() {
        if c != '\\' {
            out.push(c);
            continue;
        }
        match chars.next()? {
            '\\' => out.push('\\'),
            'n' => out.push('\n'),
            'u' => {
                if chars.next()? != '{' {
                    return None;
                }
                let hex: String = chars.by_ref().take_while(|&c| c != '}').collect();
                out.push(char::from_u32(u32::from_str_radix(&hex, 16).ok()?)?);
            }
            _ => return None,
        }
    }
    Some(out)
}

fn tone_map_name(t: ToneMap) -> &'static str {
    match t {
        ToneMap::Clamp => "clamp",
        ToneMap::Reinhard => "reinhard",
        ToneMap::Aces => "aces",
    }
}

fn parse_pair(text: &str, separator: char) -> Option<(u32, u32)> {
    let (a, b) = text.split_once(separator)?;
    Some((a.trim().parse().ok()?, b.trim().parse().ok()?))
}

/// Parses `A..B` (whole numbers): a half-open range of samples.
pub fn parse_range(text: &str) -> Option<Range<u32>> {
    let (a, b) = text.split_once("..")?;
    Some(a.trim().parse().ok()?..b.trim().parse().ok()?)
}

/// Parses `X0,Y0,X1,Y1` (whole numbers): a half-open pixel rectangle (not checked against a
/// frame).
pub fn parse_region(text: &str) -> Option<Region> {
    let v: Vec<u32> = text.split(',').map(|s| s.trim().parse().ok()).collect::<Option<_>>()?;
    match v[..] {
        [x0, y0, x1, y1] => Some(Region { x0, y0, x1, y1 }),
        _ => None,
    }
}

/// One pixel's accumulated samples: the weighted sum of their radiance and the sum of their
/// filter weights (box-filtered samples weigh 1), in f64 as the renderer accumulates them.
/// The pixel's value is `sum / weight` (black when the weights sum to 0).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PixelSums {
    /// Weighted sum of linear RGB radiance.
    pub sum: [f64; 3],
    /// Sum of the samples' filter weights.
    pub weight: f64,
}

impl PixelSums {
    /// Adds `other`'s samples (which must follow this pixel's samples in sample order for
    /// the sums to be those of one render, up to f64 rounding).
    pub fn add(&mut self, other: &PixelSums) {
        for (a, b) in self.sum.iter_mut().zip(other.sum) {
            *a += b;
        }
        self.weight += other.weight;
    }

    /// The pixel value, as the renderer computes it: `sum / weight` rounded to f32, black
    /// when the weights sum to 0 or the value is not finite.
    pub fn mean(&self) -> [f32; 3] {
        if self.weight == 0.0 {
            return [0.0; 3];
        }
        let p = self.sum.map(|s| (s / self.weight) as f32);
        if p.iter().all(|c| c.is_finite()) { p } else { [0.0; 3] }
    }
}

/// A part of a render: its description, its pixels' means and sample counts, and (for
/// parts that are to be summed with others) its pixels' sums. Pixel arrays are row-major
/// over [`PartInfo::region`].
#[derive(Clone, Debug, PartialEq)]
pub struct Partial {
    /// What the part is.
    pub info: PartInfo,
    /// Mean radiance of the part's samples per pixel (the film's pixels).
    pub radiance: Vec<[f32; 3]>,
    /// Samples rendered into each pixel.
    pub sample_counts: Vec<u32>,
    /// Weighted sums and weights per pixel; `None` when the part is only to be assembled
    /// (it holds all of its pixels' samples), and always `None` for POV-Ray's antialiasing.
    pub sums: Option<Vec<PixelSums>>,
    /// AOV layers over the region (checkpoints keep them; channels `layer.channel`, f32), in
    /// the order of [`Aov::ALL`] when read from a file.
    pub layers: Vec<Layer>,
}

/// Why a part file cannot be read.
#[derive(Debug, thiserror::Error)]
pub enum PartialError {
    /// The file cannot be read.
    #[error(transparent)]
    File(#[from] crate::files::FileError),
    /// The bytes are not a readable EXR (truncated or corrupt).
    #[error("{}: not a readable part (truncated or corrupt EXR): {message}", crate::files::shown_path(.path))]
    Corrupt {
        /// The part file.
        path: PathBuf,
        /// What the EXR reader said.
        message: String,
    },
    /// The EXR is readable but is not a Prism part, or is inconsistent.
    #[error("{}: not a valid Prism part: {message}", crate::files::shown_path(.path))]
    Invalid {
        /// The part file.
        path: PathBuf,
        /// What is wrong (naming the header key or channel).
        message: String,
    },
}

const SUM_CHANNELS: [&str; 3] = ["sum.R", "sum.G", "sum.B"];

impl Partial {
    /// A part holding `film`'s pixels, each with `info.samples.len()` samples.
    pub fn from_film(info: PartInfo, film: &Film, sums: Option<Vec<PixelSums>>) -> Self {
        let count = info.samples.len() as u32;
        Self {
            radiance: film.pixels.clone(),
            sample_counts: vec![count; film.pixels.len()],
            sums,
            layers: film.layers.clone(),
            info,
        }
    }

    /// The part as the bytes of an EXR file (deterministic: equal parts give equal bytes).
    pub fn encode(&self) -> Result<Vec<u8>, exr::error::Error> {
        use exr::prelude::*;
        let mut channels: SmallVec<[AnyChannel<FlatSamples>; 4]> = SmallVec::new();
        for (c, name) in ["R", "G", "B"].into_iter().enumerate() {
            channels.push(AnyChannel::new(name, FlatSamples::F32(self.radiance.iter().map(|p| p[c]).collect())));
        }
        channels.push(AnyChannel::new("samples", FlatSamples::U32(self.sample_counts.clone())));
        if let Some(sums) = &self.sums {
            let mut push_f64 = |name: &str, values: Vec<f64>| {
                let hi = values.iter().map(|v| (v.to_bits() >> 32) as u32).collect();
                let lo = values.iter().map(|v| v.to_bits() as u32).collect();
                channels.push(AnyChannel::new(format!("{name}.hi").as_str(), FlatSamples::U32(hi)));
                channels.push(AnyChannel::new(format!("{name}.lo").as_str(), FlatSamples::U32(lo)));
            };
            for (c, name) in SUM_CHANNELS.into_iter().enumerate() {
                push_f64(name, sums.iter().map(|s| s.sum[c]).collect());
            }
            push_f64("weight", sums.iter().map(|s| s.weight).collect());
        }
        for layer in &self.layers {
            let names = layer.aov.channels();
            for (c, channel) in names.iter().enumerate() {
                let values = layer.data.iter().skip(c).step_by(names.len()).copied().collect();
                let name = format!("{}.{channel}", layer.aov.name());
                channels.push(AnyChannel::new(name.as_str(), FlatSamples::F32(values)));
            }
        }
        let r = self.info.region;
        let mut attributes =
            LayerAttributes { layer_position: Vec2(r.x0 as i32, r.y0 as i32), ..LayerAttributes::named("part") };
        attributes.other.insert(Text::from(ATTRIBUTE), AttributeValue::Text(Text::from(self.info.to_text().as_str())));
        let size = (r.width() as usize, r.height() as usize);
        let layer = Layer::new(size, attributes, Encoding::SMALL_LOSSLESS, AnyChannels::sort(channels));
        let frame = IntegerBounds::new((0, 0), (self.info.frame.0 as usize, self.info.frame.1 as usize));
        let mut bytes = Cursor::new(Vec::new());
        Image::new(ImageAttributes::new(frame), layer).write().to_buffered(&mut bytes)?;
        Ok(bytes.into_inner())
    }

    /// Reads the part file at `path` through `access` (the sandbox and size cap of images).
    pub fn read(access: &crate::files::FileAccess, path: &Path) -> Result<Self, PartialError> {
        let bytes = access.read(path, crate::files::FileKind::Image)?;
        Self::decode(&bytes, path)
    }

    /// Decodes the bytes of a part file (`path` names it in errors). Checks that the header
    /// describes a consistent part and that every channel is present, of its type and size.
    pub fn decode(bytes: &[u8], path: &Path) -> Result<Self, PartialError> {
        use exr::prelude::*;
        let invalid = |message: String| PartialError::Invalid { path: path.to_path_buf(), message };
        let image = read()
            .no_deep_data()
            .largest_resolution_level()
            .all_channels()
            .all_layers()
            .all_attributes()
            .non_parallel()
            .from_buffered(Cursor::new(bytes))
            .map_err(|e| PartialError::Corrupt { path: path.to_path_buf(), message: e.to_string() })?;
        let [layer] = &image.layer_data[..] else {
            return Err(invalid(format!("{} layers, a part has one", image.layer_data.len())));
        };
        let text = match layer.attributes.other.get(&Text::from(ATTRIBUTE)) {
            Some(AttributeValue::Text(text)) => text.to_string(),
            _ => {
                return Err(invalid(format!(
                    "no `{ATTRIBUTE}` header attribute (not written by `prism render --region/--tile/--sample-range`)"
                )));
            }
        };
        let info = PartInfo::from_text(&text).map_err(|m| invalid(format!("header `{ATTRIBUTE}`: {m}")))?;
        let display = image.attributes.display_window;
        if (display.position, display.size) != (Vec2(0, 0), Vec2(info.frame.0 as usize, info.frame.1 as usize)) {
            return Err(invalid("the display window is not the frame of `prismPart`".into()));
        }
        let r = info.region;
        if layer.attributes.layer_position != Vec2(r.x0 as i32, r.y0 as i32)
            || layer.size != Vec2(r.width() as usize, r.height() as usize)
        {
            return Err(invalid("the data window is not the region of `prismPart`".into()));
        }
        let n = r.pixel_count();
        let channel = |name: &str| {
            layer
                .channel_data
                .list
                .iter()
                .find(|c| c.name.to_string() == name)
                .map(|c| &c.sample_data)
                .ok_or_else(|| invalid(format!("channel `{name}` is missing")))
        };
        // Prism writes no infinity or NaN into any file; one in a part would reach the merged
        // or resumed image.
        let finite = |name: &str, values: &mut dyn Iterator<Item = f64>| {
            let mut values = values.enumerate();
            match values.find(|(_, v)| !v.is_finite()) {
                Some((i, _)) => {
                    Err(invalid(format!("channel `{name}` holds a NaN or infinite value (pixel {i} of the part)")))
                }
                None => Ok(()),
            }
        };
        let f32s = |name: &str| match channel(name)? {
            FlatSamples::F32(v) if v.len() == n => finite(name, &mut v.iter().map(|&x| f64::from(x))).map(|()| v),
            _ => Err(invalid(format!("channel `{name}` is not {n} 32-bit floats"))),
        };
        let u32s = |name: &str| match channel(name)? {
            FlatSamples::U32(v) if v.len() == n => Ok(v),
            _ => Err(invalid(format!("channel `{name}` is not {n} 32-bit unsigned integers"))),
        };
        let (red, green, blue) = (f32s("R")?, f32s("G")?, f32s("B")?);
        let radiance = (0..n).map(|i| [red[i], green[i], blue[i]]).collect();
        let sample_counts = u32s("samples")?.clone();
        if let Some(c) = sample_counts.iter().find(|&&c| c > info.samples.len() as u32) {
            return Err(invalid(format!("channel `samples`: {c} is more than the part's range holds")));
        }
        let has_sums = layer.channel_data.list.iter().any(|c| c.name.to_string() == "weight.hi");
        let sums = if has_sums {
            if info.sampling == Sampling::Pov {
                return Err(invalid("sums in a part of POV-Ray antialiasing".into()));
            }
            let f64s = |name: &str| -> std::result::Result<Vec<f64>, PartialError> {
                let (hi, lo) = (u32s(&format!("{name}.hi"))?, u32s(&format!("{name}.lo"))?);
                Ok(hi.iter().zip(lo).map(|(&h, &l)| f64::from_bits(u64::from(h) << 32 | u64::from(l))).collect())
            };
            let rgb = [f64s(SUM_CHANNELS[0])?, f64s(SUM_CHANNELS[1])?, f64s(SUM_CHANNELS[2])?];
            let weight = f64s("weight")?;
            for (name, values) in SUM_CHANNELS.iter().zip(&rgb).chain([(&"weight", &weight)]) {
                finite(name, &mut values.iter().copied())?;
            }
            Some((0..n).map(|i| PixelSums { sum: [rgb[0][i], rgb[1][i], rgb[2][i]], weight: weight[i] }).collect())
        } else {
            None
        };
        let mut layers = Vec::new();
        for aov in Aov::ALL {
            let names = aov.channels();
            let channel_names: Vec<String> = names.iter().map(|c| format!("{}.{c}", aov.name())).collect();
            if !channel_names.iter().any(|name| channel(name).is_ok()) {
                continue;
            }
            let mut data = vec![0.0; n * names.len()];
            for (c, name) in channel_names.iter().enumerate() {
                for (i, &v) in f32s(name)?.iter().enumerate() {
                    data[i * names.len() + c] = v;
                }
            }
            layers.push(crate::film::Layer { aov, data });
        }
        Ok(Self { info, radiance, sample_counts, sums, layers })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn info(region: Region, samples: Range<u32>) -> PartInfo {
        PartInfo {
            fingerprint: Fingerprint::of_text("scene"),
            frame: (8, 6),
            region,
            samples,
            total_samples: 16,
            tile: Some((1, 3)),
            sampling: Sampling::Stratified,
            exposure: 0.5,
            tone_map: ToneMap::Aces,
            scene: None,
        }
    }

    fn part(with_sums: bool) -> Partial {
        let region = Region { x0: 2, y0: 1, x1: 7, y1: 4 };
        let n = region.pixel_count();
        let sums: Vec<PixelSums> = (0..n)
            .map(|i| PixelSums { sum: [0.1 * i as f64, 1.0 / 3.0, -2e-300], weight: 4.0 + f64::EPSILON * i as f64 })
            .collect();
        Partial {
            info: info(region, 4..8),
            radiance: sums.iter().map(PixelSums::mean).collect(),
            sample_counts: (0..n as u32).map(|i| i % 5).collect(),
            sums: with_sums.then_some(sums),
            layers: Vec::new(),
        }
    }

    /// Sums and weights are f64 bit patterns in the file: they read back exactly, and so
    /// does everything else; equal parts encode to equal bytes.
    #[test]
    fn parts_round_trip_exactly() {
        for with_sums in [true, false] {
            let original = part(with_sums);
            let bytes = original.encode().unwrap();
            assert_eq!(bytes, original.encode().unwrap(), "deterministic bytes");
            let back = Partial::decode(&bytes, Path::new("p.exr")).unwrap();
            assert_eq!(back, original);
        }
    }

    /// A checkpoint's extras: the scene text (any characters, escaped onto one header line)
    /// and AOV layers read back exactly.
    #[test]
    fn scene_text_and_layers_round_trip() {
        let mut original = part(false);
        original.info.scene = Some("[render]\nsamples = 4 # café \\ 東京\n\tend\r\n".into());
        let n = original.info.region.pixel_count();
        original.layers = vec![
            Layer { aov: Aov::Normal, data: (0..3 * n).map(|i| i as f32 * 0.25 - 1.0).collect() },
            Layer { aov: Aov::Depth, data: (0..n).map(|i| if i == 2 { f32::MAX } else { i as f32 }).collect() },
        ];
        let back = Partial::decode(&original.encode().unwrap(), Path::new("c.exr")).unwrap();
        // Read back in the order of `Aov::ALL`.
        assert_eq!(back, original);
        assert_eq!(unescape("\\q"), None);
        assert_eq!(unescape("\\u{110000}"), None);
    }

    #[test]
    fn truncated_and_foreign_files_are_refused() {
        let bytes = part(true).encode().unwrap();
        for cut in [bytes.len() - 1, bytes.len() / 2, 10, 0] {
            let error = Partial::decode(&bytes[..cut], Path::new("cut.exr")).unwrap_err();
            assert!(matches!(error, PartialError::Corrupt { .. }), "cut at {cut}: {error}");
            assert!(error.to_string().starts_with("cut.exr: not a readable part"), "{error}");
        }
        let film = Film::new(3, 2);
        let plain = crate::output::encode(&film, Path::new("x.exr"), &Default::default()).unwrap();
        let error = Partial::decode(&plain, Path::new("plain.exr")).unwrap_err().to_string();
        assert!(error.contains("no `prismPart` header attribute"), "{error}");
    }

    /// Prism writes no infinity or NaN into a file, so a part holding one (a forged or
    /// damaged file) is refused, naming the channel, instead of reaching the merged or
    /// resumed image.
    #[test]
    fn non_finite_values_are_refused() {
        let mut nan_radiance = part(true);
        nan_radiance.radiance[3] = [0.0, f32::NAN, 0.0];
        let mut infinite_sum = part(true);
        infinite_sum.sums.as_mut().unwrap()[1].sum[2] = f64::INFINITY;
        let mut nan_weight = part(true);
        nan_weight.sums.as_mut().unwrap()[0].weight = f64::NAN;
        let mut infinite_layer = part(false);
        let n = infinite_layer.info.region.pixel_count();
        infinite_layer.layers = vec![Layer { aov: Aov::Depth, data: vec![f32::INFINITY; n] }];
        for (part, channel) in
            [(nan_radiance, "`G`"), (infinite_sum, "`sum.B`"), (nan_weight, "`weight`"), (infinite_layer, "`depth.Z`")]
        {
            let error = Partial::decode(&part.encode().unwrap(), Path::new("f.exr")).unwrap_err().to_string();
            assert!(error.contains(channel) && error.contains("NaN or infinite"), "{error}");
        }
    }

    #[test]
    fn inconsistent_descriptions_are_refused() {
        let region = Region { x0: 0, y0: 0, x1: 8, y1: 6 };
        let good = info(region, 0..16);
        assert_eq!(PartInfo::from_text(&good.to_text()).unwrap(), good);
        for (from, to, key) in [
            ("samples=0..16", "samples=0..17", "samples"),
            ("samples=0..16", "samples=5..5", "samples"),
            ("region=0,0,8,6", "region=0,0,9,6", "region"),
            ("region=0,0,8,6", "region=4,0,2,6", "region"),
            ("tile=1/3", "tile=3/3", "tile"),
            ("format=1", "format=2", "format"),
            ("tone_map=aces", "tone_map=none", "tone_map"),
        ] {
            let text = good.to_text().replace(from, to);
            let error = PartInfo::from_text(&text).unwrap_err();
            assert!(error.contains(&format!("key `{key}`")), "{to}: {error}");
        }
        let pov = PartInfo { sampling: Sampling::Pov, ..info(region, 0..8) };
        assert!(PartInfo::from_text(&pov.to_text()).unwrap_err().contains("POV-Ray"));
        let missing = good.to_text().replace("fingerprint=", "print=");
        assert!(PartInfo::from_text(&missing).unwrap_err().contains("key `fingerprint` is missing"));
    }

    #[test]
    fn fingerprints_differ_with_any_byte() {
        assert_eq!(Fingerprint::of_text("a = 1"), Fingerprint::of_text("a = 1"));
        assert_ne!(Fingerprint::of_text("a = 1"), Fingerprint::of_text("a = 2"));
        assert_eq!(Fingerprint::of_text("").0.len(), 32);
    }

    #[test]
    fn pixel_sums_add_and_average() {
        let mut a = PixelSums { sum: [1.0, 2.0, 3.0], weight: 2.0 };
        a.add(&PixelSums { sum: [1.0, 0.0, 1.0], weight: 2.0 });
        assert_eq!(a.mean(), [0.5, 0.5, 1.0]);
        assert_eq!(PixelSums::default().mean(), [0.0; 3]);
        assert_eq!(PixelSums { sum: [f64::INFINITY, 0.0, 0.0], weight: 1.0 }.mean(), [0.0; 3]);
    }

    #[test]
    fn ranges_and_regions_parse() {
        assert_eq!(parse_range("4..12"), Some(4..12));
        assert_eq!(parse_range("4-12"), None);
        assert_eq!(parse_region("1, 2,3,4"), Some(Region { x0: 1, y0: 2, x1: 3, y1: 4 }));
        assert_eq!(parse_region("1,2,3"), None);
        assert_eq!(parse_region("1,2,3,-4"), None);
    }
}
