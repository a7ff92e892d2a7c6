//! `write`: the film to files. EXR stays linear and unclipped; 8-bit formats go through
//! exposure, a tone-mapping operator and the exact sRGB curve. Every file is written to a
//! temporary name in the same directory and renamed into place, so a failed or interrupted
//! render never leaves a half-written image.

use std::io::Cursor;
use std::path::{Path, PathBuf};

use image::{ImageFormat, RgbImage};

use crate::film::Film;
use crate::world::components::ToneMap;

/// Errors from writing output files.
#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    /// The extension names no format Prism writes.
    #[error("{path}: unknown image format `.{extension}` (use .png, .exr, .ppm, .jpg, .bmp, .tga, .tif, .qoi or .hdr)")]
    UnknownFormat {
        /// The output path.
        path: PathBuf,
        /// Its extension.
        extension: String,
    },
    /// The directory cannot be written.
    #[error("{path}: cannot write output: {source}")]
    Io {
        /// The output path.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// The output names a directory, device, FIFO or socket.
    #[error("{}: cannot write output: it is {what}, not a regular file", path.display())]
    NotRegular {
        /// The output path.
        path: PathBuf,
        /// `a directory`, `a device`...
        what: &'static str,
    },
    /// Encoding failed.
    #[error("{path}: cannot encode image: {message}")]
    Encode {
        /// The output path.
        path: PathBuf,
        /// What the encoder said.
        message: String,
    },
    /// An EXR file cannot be read back.
    #[error("{path}: {source}")]
    ReadExr {
        /// The EXR file.
        path: PathBuf,
        /// The cause.
        source: exr::error::Error,
    },
}

/// The file formats Prism writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OutputFormat {
    /// Linear float OpenEXR.
    Exr,
    /// Radiance HDR (linear float).
    Hdr,
    /// An 8-bit format of the image crate.
    Ldr(ImageFormat),
}

/// The format for `path`, from its extension.
pub fn format_for(path: &Path) -> Result<OutputFormat, OutputError> {
    let extension = path.extension().and_then(|e| e.to_str()).unwrap_or("").to_ascii_lowercase();
    let unknown = || OutputError::UnknownFormat { path: path.to_path_buf(), extension: extension.clone() };
    match extension.as_str() {
        "exr" => Ok(OutputFormat::Exr),
        "hdr" => Ok(OutputFormat::Hdr),
        "png" | "ppm" | "pnm" | "jpg" | "jpeg" | "bmp" | "tga" | "tif" | "tiff" | "qoi" => {
            ImageFormat::from_extension(&extension).map(OutputFormat::Ldr).ok_or_else(unknown)
        }
        _ => Err(unknown()),
    }
}

/// Fails early (before a render) when `path` has an unknown format, names something other
/// than a regular file (a directory, a device such as `/dev/null`, a FIFO), or its
/// directory cannot be written. Leaves nothing behind.
pub fn check_writable(path: &Path) -> Result<(), OutputError> {
    format_for(path)?;
    check_target(path)?;
    let (temp, file) = create_temp(path)?;
    drop(file);
    remove_temp(&temp);
    Ok(())
}

/// Ok when `path` does not exist or is a regular file (or a symlink, which the rename
/// replaces without touching what it points to).
fn check_target(path: &Path) -> Result<(), OutputError> {
    match std::fs::symlink_metadata(path) {
        Ok(meta) if meta.file_type().is_symlink() => Ok(()),
        Ok(meta) => match crate::files::not_regular(&meta.file_type()) {
            None => Ok(()),
            Some(what) => Err(OutputError::NotRegular { path: path.to_path_buf(), what }),
        },
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(()),
        Err(source) => Err(OutputError::Io { path: path.to_path_buf(), source }),
    }
}

/// Temporary files being written, so that a signal handler can remove them
/// ([`remove_all_temps`]).
static TEMPS: std::sync::Mutex<Vec<PathBuf>> = std::sync::Mutex::new(Vec::new());

/// Removes `temp` and forgets it.
fn remove_temp(temp: &Path) {
    let _ = std::fs::remove_file(temp);
    forget_temp(temp);
}

fn forget_temp(temp: &Path) {
    let mut temps = TEMPS.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
    temps.retain(|p| p != temp);
}

/// Removes every temporary file still being written (after a panic, before the CLI exits).
pub fn remove_all_temps() {
    remove_registered_temps(|_| true);
}

/// Removes and forgets the temporary files being written that `which` picks.
fn remove_registered_temps(which: impl Fn(&Path) -> bool) {
    let mut temps = TEMPS.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
    temps.retain(|temp| {
        let remove = which(temp);
        if remove {
            let _ = std::fs::remove_file(temp);
        }
        !remove
    });
}

/// Removes every temporary file still being written and exits with `code`, holding the
/// registry's lock until the process ends (for SIGINT and SIGTERM: the CLI's signal thread
/// calls this). Holding it matters: another thread writing outputs would otherwise create
/// its next temporary file between the cleanup and the exit, and leave it behind.
pub fn remove_all_temps_and_exit(code: i32) -> ! {
    let mut temps = TEMPS.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
    for temp in temps.drain(..) {
        let _ = std::fs::remove_file(temp);
    }
    std::process::exit(code)
}

/// A fresh temporary file beside `path`, created exclusively (`O_EXCL`: never an existing
/// name, never through a symlink) under a name no other process can predict, and
/// registered for [`remove_all_temps`].
fn create_temp(path: &Path) -> Result<(PathBuf, std::fs::File), OutputError> {
    use std::hash::{BuildHasher, Hasher};
    static COUNTER: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    let name: String = name.chars().take(64).collect();
    let mut last = None;
    for _ in 0..16 {
        // RandomState is seeded from the operating system's random source.
        let mut hasher = std::collections::hash_map::RandomState::new().build_hasher();
        hasher.write_u64(COUNTER.fetch_add(1, std::sync::atomic::Ordering::Relaxed));
        hasher.write_u128(
            std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).unwrap_or_default().as_nanos(),
        );
        let temp = path.with_file_name(format!(".{name}.prism-{}-{:016x}.tmp", std::process::id(), hasher.finish()));
        let mut options = std::fs::OpenOptions::new();
        options.write(true).create_new(true);
        #[cfg(unix)]
        {
            use std::os::unix::fs::OpenOptionsExt;
            options.mode(0o644);
        }
        // Created and registered under the lock, so a signal never finds it unregistered.
        let mut temps = TEMPS.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        match options.open(&temp) {
            Ok(file) => {
                temps.push(temp.clone());
                return Ok((temp, file));
            }
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => last = Some(e),
            Err(source) => return Err(OutputError::Io { path: path.to_path_buf(), source }),
        }
    }
    let source = last.unwrap_or_else(|| std::io::Error::other("no free temporary name"));
    Err(OutputError::Io { path: path.to_path_buf(), source })
}

/// A file written under a temporary name, not yet renamed into place.
#[derive(Debug)]
pub struct Staged {
    temp: PathBuf,
    path: PathBuf,
}

impl Staged {
    /// Renames the temporary file over the target (which must still be a regular file or
    /// absent).
    pub fn commit(self) -> Result<(), OutputError> {
        commit_all(vec![self])
    }

    /// Removes the temporary file.
    pub fn discard(self) {
        remove_temp(&self.temp);
    }
}

/// Renames every staged file into place, holding the registry's lock so that a signal
/// arriving meanwhile waits until all are renamed (or, on an error, all remaining
/// temporary files are removed).
fn commit_all(staged: Vec<Staged>) -> Result<(), OutputError> {
    let mut temps = TEMPS.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
    let mut result = Ok(());
    for s in &staged {
        if result.is_ok() {
            result = check_target(&s.path).and_then(|()| {
                std::fs::rename(&s.temp, &s.path).map_err(|source| OutputError::Io { path: s.path.clone(), source })
            });
        }
        if result.is_err() {
            let _ = std::fs::remove_file(&s.temp);
        }
        temps.retain(|p| *p != s.temp);
    }
    result
}

/// Writes `bytes` to a fresh temporary file beside `path` (nothing is renamed yet).
pub fn stage(path: &Path, bytes: &[u8]) -> Result<Staged, OutputError> {
    use std::io::Write;
    check_target(path)?;
    let (temp, mut file) = create_temp(path)?;
    let written = file.write_all(bytes);
    drop(file);
    if let Err(source) = written {
        remove_temp(&temp);
        return Err(OutputError::Io { path: path.to_path_buf(), source });
    }
    Ok(Staged { temp, path: path.to_path_buf() })
}

/// Writes `bytes` to `path` through an exclusive temporary file and a rename.
pub fn write_atomically(path: &Path, bytes: &[u8]) -> Result<(), OutputError> {
    stage(path, bytes)?.commit()
}

/// Writes several files all or none: every one is staged first, and only when all are
/// written are they renamed into place.
pub fn write_all_atomically(files: &[(&Path, Vec<u8>)]) -> Result<(), OutputError> {
    let mut staged = Vec::new();
    for (path, bytes) in files {
        match stage(path, bytes) {
            Ok(s) => staged.push(s),
            Err(e) => {
                staged.into_iter().for_each(Staged::discard);
                return Err(e);
            }
        }
    }
    commit_all(staged)
}

/// The exact sRGB encoding of a linear value in [0, 1].
pub fn srgb_encode(x: f64) -> f64 {
    if x <= 0.003_130_8 { 12.92 * x } else { 1.055 * x.powf(1.0 / 2.4) - 0.055 }
}

/// A tone-mapping operator applied to one linear channel (after exposure). Monotonic on
/// `[0, inf]`: an infinite input gives the operator's limit (the formulas alone would give
/// NaN, a black pixel where the image is brightest); negative and NaN inputs give 0.
pub fn tone_map(x: f64, op: ToneMap) -> f64 {
    let x = x.max(0.0);
    match op {
        ToneMap::Clamp => x,
        ToneMap::Reinhard if x.is_infinite() => 1.0,
        ToneMap::Reinhard => x / (1.0 + x),
        ToneMap::Aces if x.is_infinite() => 2.51 / 2.43,
        ToneMap::Aces => (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14),
    }
}

/// The film as 8-bit sRGB: exposure (stops), tone map, clip, sRGB curve, round; rows in
/// parallel, each value exactly [`ldr_channel`]'s.
pub fn to_ldr(film: &Film, exposure: f64, op: ToneMap) -> RgbImage {
    use rayon::prelude::*;
    let encoder = LdrEncoder::new(exposure.exp2(), op);
    let width = film.width as usize;
    let mut bytes = vec![0u8; film.pixels.len() * 3];
    if width > 0 {
        bytes.par_chunks_mut(width * 3).zip(film.pixels.par_chunks(width)).for_each(|(row, pixels)| {
            for (out, &linear) in row.iter_mut().zip(pixels.iter().flatten()) {
                *out = encoder.encode(linear);
            }
        });
    }
    RgbImage::from_raw(film.width, film.height, bytes).expect("the buffer holds width x height pixels")
}

/// One linear channel as an 8-bit sRGB value, as [`to_ldr`] makes it: times `scale` (the
/// exposure as a factor, `2^stops`), tone map, clip, sRGB curve, round.
pub fn ldr_channel(linear: f64, scale: f64, op: ToneMap) -> u8 {
    let v = tone_map(linear * scale, op).clamp(0.0, 1.0);
    (srgb_encode(v) * 255.0 + 0.5).floor() as u8
}

/// [`ldr_channel`] of f32 values for one scale and operator, by table: the function is a
/// non-decreasing step function of its input, so it is fixed by the 255 inputs where it
/// steps, found once by bisection over the ordered bit patterns of non-negative f32s. A
/// value then costs a short search of 255 floats instead of a `powf`.
pub struct LdrEncoder {
    /// `steps[k]` is the least f32 whose byte exceeds `k`, or infinity where none does.
    steps: [f32; 255],
}

impl LdrEncoder {
    /// The table for `scale` (exposure as a factor) and `op`.
    pub fn new(scale: f64, op: ToneMap) -> Self {
        let byte = |bits: u32| ldr_channel(f64::from(f32::from_bits(bits)), scale, op);
        let top = f32::INFINITY.to_bits();
        let brightest = byte(top);
        let mut steps = [f32::INFINITY; 255];
        for (k, step) in steps.iter_mut().enumerate().take(usize::from(brightest)) {
            // The least bit pattern in [0, +inf] whose byte exceeds k.
            let (mut lo, mut hi) = (0u32, top);
            while lo < hi {
                let mid = lo + (hi - lo) / 2;
                if byte(mid) > k as u8 { hi = mid } else { lo = mid + 1 }
            }
            *step = f32::from_bits(lo);
        }
        Self { steps }
    }

    /// The byte of `linear`: how many steps lie at or below it (0 for NaN and negatives).
    pub fn encode(&self, linear: f32) -> u8 {
        self.steps.partition_point(|&step| step <= linear) as u8
    }
}

/// An 8-bit preview of one AOV layer (for `--aov-png`): albedo through the sRGB curve,
/// normals as `0.5 + 0.5 n`, depth and position scaled to the range of their finite
/// values (near is bright; escaped rays black), uv clipped to [0, 1] as red and green, ids
/// as one hashed colour each (escaped rays black), the raw beauty clipped through the sRGB
/// curve, variance as the standard deviation of luminance
/// (scaled to its 99th percentile) and samples as a count (scaled to the largest). `None` when the film has no
/// such layer.
pub fn layer_preview(film: &Film, aov: crate::film::Aov) -> Option<RgbImage> {
    use crate::film::Aov;
    let layer = film.layer(aov)?;
    let n = layer.channel_count();
    let pixels: Vec<&[f32]> = layer.data.chunks_exact(n).collect();
    // Escaped rays' depth is f32::MAX (no file holds an infinity): not part of the range.
    let seen = |v: f32| v.abs() < f32::MAX;
    let range = |values: &mut dyn Iterator<Item = f32>| {
        values.filter(|&v| seen(v)).fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), v| (lo.min(v), hi.max(v)))
    };
    let scale = |v: f32, (lo, hi): (f32, f32)| if hi > lo { (v - lo) / (hi - lo) } else { 0.0 };
    let byte = |v: f32| (v.clamp(0.0, 1.0) * 255.0 + 0.5).floor() as u8;
    let srgb_byte = |v: f32| byte(srgb_encode(f64::from(v.clamp(0.0, 1.0))) as f32);
    let luminance = |p: &[f32]| 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
    let colours: Vec<[u8; 3]> = match aov {
        Aov::Albedo | Aov::Raw => pixels.iter().map(|p| [srgb_byte(p[0]), srgb_byte(p[1]), srgb_byte(p[2])]).collect(),
        Aov::Normal => pixels.iter().map(|p| [0, 1, 2].map(|c| byte(0.5 + 0.5 * p[c]))).collect(),
        Aov::Depth => {
            let r = range(&mut pixels.iter().map(|p| p[0]));
            pixels.iter().map(|p| [byte(if seen(p[0]) { 1.0 - scale(p[0], r) } else { 0.0 }); 3]).collect()
        }
        Aov::Position => {
            let ranges = [0, 1, 2].map(|c| range(&mut pixels.iter().map(|p| p[c])));
            pixels.iter().map(|p| [0, 1, 2].map(|c| byte(scale(p[c], ranges[c])))).collect()
        }
        Aov::Uv => pixels.iter().map(|p| [byte(p[0]), byte(p[1]), 0]).collect(),
        Aov::ObjectId | Aov::MaterialId => pixels
            .iter()
            .map(|p| {
                if p[0] < 0.0 {
                    return [0; 3];
                }
                // A multiplicative hash spreads neighbouring ids over distinct colours.
                let h = (p[0] as u64 + 1).wrapping_mul(0x9E37_79B9_7F4A_7C15);
                let h = h ^ (h >> 29);
                [(h & 0xff) as u8 | 0x30, ((h >> 8) & 0xff) as u8 | 0x30, ((h >> 16) & 0xff) as u8 | 0x30]
            })
            .collect(),
        Aov::Variance => {
            let deviations: Vec<f32> = pixels.iter().map(|p| luminance(p).max(0.0).sqrt()).collect();
            // Scaled to the 99th percentile: a few edge pixels of a light would leave the
            // rest black.
            let mut sorted: Vec<f32> = deviations.iter().copied().filter(|d| d.is_finite()).collect();
            sorted.sort_unstable_by(f32::total_cmp);
            let top = sorted.get((sorted.len() as f64 * 0.99) as usize).or(sorted.last()).copied().unwrap_or(0.0);
            let r = (0.0, top);
            deviations.iter().map(|&d| [byte(scale(d, r)); 3]).collect()
        }
        Aov::Samples => {
            let r = (0.0, range(&mut pixels.iter().map(|p| p[0])).1);
            pixels.iter().map(|p| [byte(scale(p[0], r)); 3]).collect()
        }
    };
    let mut img = RgbImage::new(film.width, film.height);
    for (dst, src) in img.pixels_mut().zip(colours) {
        dst.0 = src;
    }
    Some(img)
}

/// Encodes an 8-bit image as PNG.
pub fn encode_png(img: &RgbImage, path: &Path) -> Result<Vec<u8>, OutputError> {
    use image::ImageEncoder;
    let mut bytes = Vec::new();
    image::codecs::png::PngEncoder::new(&mut bytes)
        .write_image(img.as_raw(), img.width(), img.height(), image::ExtendedColorType::Rgb8)
        .map_err(|e| OutputError::Encode { path: path.to_path_buf(), message: e.to_string() })?;
    Ok(bytes)
}

/// How the film becomes an image file.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ImageSettings {
    /// Exposure in stops for 8-bit formats.
    pub exposure: f64,
    /// Tone-mapping operator for 8-bit formats.
    pub tone_map: ToneMap,
    /// Write EXR channels as 16-bit half floats (as POV-Ray does) instead of 32-bit floats:
    /// half the size and about half the time to write, with 11 significant bits.
    pub exr_half: bool,
}

/// An image encoded for a file, and what the encoding had to change.
#[derive(Debug)]
pub struct Encoded {
    /// The file's bytes.
    pub bytes: Vec<u8>,
    /// How many of the film's values (beauty and layers) lie beyond half's range and were
    /// written as `±HALF_MAX` (a half-float EXR's; 0 for every other format).
    pub values_beyond_half: usize,
}

/// Encodes the film for `path`'s format.
pub fn encode(film: &Film, path: &Path, settings: &ImageSettings) -> Result<Vec<u8>, OutputError> {
    encode_reporting(film, path, settings).map(|encoded| encoded.bytes)
}

/// Encodes the film for `path`'s format, saying what the encoding changed.
pub fn encode_reporting(film: &Film, path: &Path, settings: &ImageSettings) -> Result<Encoded, OutputError> {
    let encode_err =
        |e: &dyn std::fmt::Display| OutputError::Encode { path: path.to_path_buf(), message: e.to_string() };
    let mut bytes = Cursor::new(Vec::new());
    match format_for(path)? {
        OutputFormat::Exr => {
            let (bytes, values_beyond_half) = encode_exr(film, settings.exr_half).map_err(|e| encode_err(&e))?;
            return Ok(Encoded { bytes, values_beyond_half });
        }
        OutputFormat::Hdr => {
            let data: Vec<f32> = film.pixels.iter().flatten().copied().collect();
            let img = image::Rgb32FImage::from_raw(film.width, film.height, data)
                .ok_or_else(|| encode_err(&"film size mismatch"))?;
            image::DynamicImage::ImageRgb32F(img).write_to(&mut bytes, ImageFormat::Hdr).map_err(|e| encode_err(&e))?;
        }
        OutputFormat::Ldr(ImageFormat::Pnm) => {
            use image::ImageEncoder;
            use image::codecs::pnm::{PnmEncoder, PnmSubtype, SampleEncoding};
            let img = to_ldr(film, settings.exposure, settings.tone_map);
            PnmEncoder::new(&mut bytes)
                .with_subtype(PnmSubtype::Pixmap(SampleEncoding::Binary))
                .write_image(img.as_raw(), film.width, film.height, image::ExtendedColorType::Rgb8)
                .map_err(|e| encode_err(&e))?;
        }
        OutputFormat::Ldr(format) => {
            let img = to_ldr(film, settings.exposure, settings.tone_map);
            image::DynamicImage::ImageRgb8(img).write_to(&mut bytes, format).map_err(|e| encode_err(&e))?;
        }
    }
    Ok(Encoded { bytes: bytes.into_inner(), values_beyond_half: 0 })
}

/// One channel of an EXR being written: its name and its values, every `stride`-th of
/// `values` from `offset` (pixel by pixel, row by row over the film).
struct ExrChannel<'a> {
    name: String,
    values: &'a [f32],
    stride: usize,
    offset: usize,
}

impl<'a> ExrChannel<'a> {
    /// The channel's `len` samples from pixel `(x, y)` on, along a row of a film `width`
    /// pixels wide.
    fn line(&self, width: usize, (x, y): (usize, usize), len: usize) -> impl Iterator<Item = &'a f32> + use<'a> {
        let first = (y * width + x) * self.stride + self.offset;
        self.values[first..].iter().step_by(self.stride).take(len)
    }
}

/// The film as an EXR: beauty as `R`, `G`, `B`, each AOV layer's channels as
/// `layer.channel` (`albedo.R`, `normal.X`, `depth.Z`...), the data window the film's region
/// and the display window the full frame; ZIP compression of 16-line blocks (OpenEXR's
/// usual choice for rendered images), in 32-bit or `half` floats. Each block's bytes are
/// made straight from the film and compressed on all threads. Also returns how many values
/// were beyond half's range and written as `±HALF_MAX` (0 for 32-bit floats).
fn encode_exr(film: &Film, half: bool) -> exr::error::Result<(Vec<u8>, usize)> {
    use exr::block::chunk::{Chunk, CompressedBlock, CompressedScanLineBlock};
    use exr::block::writer::ChunksWriter;
    use exr::block::{self, BlockIndex};
    use exr::meta::BlockDescription;
    use exr::meta::header::Header;
    use exr::prelude::*;
    use half::slice::HalfFloatSliceExt;
    use rayon::prelude::*;

    let beauty = film.pixels.as_flattened();
    let mut channels: Vec<ExrChannel> = ["R", "G", "B"]
        .into_iter()
        .enumerate()
        .map(|(offset, name)| ExrChannel { name: name.into(), values: beauty, stride: 3, offset })
        .collect();
    for layer in &film.layers {
        let stride = layer.channel_count();
        for (offset, channel) in layer.aov.channels().iter().enumerate() {
            let name = format!("{}.{channel}", layer.aov.name());
            channels.push(ExrChannel { name, values: &layer.data, stride, offset });
        }
    }
    // EXR lists channels sorted by name, and a block holds them in that order.
    channels.sort_by(|a, b| a.name.cmp(&b.name));
    let sample_type = if half { SampleType::F16 } else { SampleType::F32 };
    let descriptions = channels.iter().map(|c| ChannelDescription::named(c.name.as_str(), sample_type)).collect();
    let width = film.width as usize;
    let mut header = Header::new("beauty".into(), (width, film.height as usize), descriptions)
        .with_encoding(Compression::ZIP16, BlockDescription::ScanLines, LineOrder::Increasing)
        .with_display_window(IntegerBounds::new((0, 0), (film.frame.0 as usize, film.frame.1 as usize)));
    header.own_attributes.layer_position = Vec2(film.origin.0 as i32, film.origin.1 as i32);

    // A block's samples, for each of its lines each channel's samples of that line, as
    // `f32`s or (`half`) as half floats, clamped to half's range (a value beyond it would be
    // written as an infinity), with how many were clamped. Half floats are converted a line
    // at a time, eight values per instruction where the CPU has F16C.
    let lines = |index: &BlockIndex| index.pixel_position.y()..index.pixel_position.y() + index.pixel_size.height();
    let block_halves = |index: &BlockIndex| {
        let line_width = index.pixel_size.width();
        let mut halves = vec![f16::ZERO; index.pixel_size.height() * channels.len() * line_width];
        let mut clamped = vec![0.0f32; line_width];
        let mut beyond = 0;
        let mut out = halves.chunks_exact_mut(line_width);
        for y in lines(index) {
            for (channel, line) in channels.iter().zip(&mut out) {
                for (c, &v) in clamped.iter_mut().zip(channel.line(width, (index.pixel_position.x(), y), line_width)) {
                    beyond += usize::from(v.abs() > HALF_MAX);
                    *c = v.clamp(-HALF_MAX, HALF_MAX);
                }
                line.convert_from_f32_slice(&clamped);
            }
        }
        (halves, beyond)
    };
    let block_floats = |index: &BlockIndex| {
        let line_width = index.pixel_size.width();
        let mut bytes = Vec::with_capacity(index.pixel_size.height() * channels.len() * line_width * 4);
        for y in lines(index) {
            for channel in &channels {
                let line = channel.line(width, (index.pixel_position.x(), y), line_width);
                bytes.extend(line.flat_map(|v| v.to_le_bytes()));
            }
        }
        bytes
    };
    let y_origin = film.origin.1 as i32;
    let mut out = Cursor::new(Vec::new());
    let mut beyond_half = 0;
    block::write(&mut out, std::iter::once(header).collect(), true, |meta, writer| {
        let blocks: Vec<_> = block::enumerate_ordered_header_block_indices(&meta.headers).collect();
        let chunks: Vec<_> = blocks
            .par_iter()
            .map(|(_, index)| {
                let y_coordinate = y_origin + index.pixel_position.y() as i32;
                let (compressed_pixels_le, beyond) = if half {
                    let (halves, beyond) = block_halves(index);
                    (zip_compress_halves(halves.reinterpret_cast()), beyond)
                } else {
                    (zip_compress(block_floats(index)), 0)
                };
                let chunk = Chunk {
                    layer_index: 0,
                    compressed_block: CompressedBlock::ScanLine(CompressedScanLineBlock {
                        y_coordinate,
                        compressed_pixels_le,
                    }),
                };
                (chunk, beyond)
            })
            .collect();
        for ((index_in_header, _), (chunk, beyond)) in blocks.iter().zip(chunks) {
            beyond_half += beyond;
            writer.write_chunk(*index_in_header, chunk)?;
        }
        Ok(())
    })?;
    Ok((out.into_inner(), beyond_half))
}

/// OpenEXR's ZIP compression of a block's little-endian bytes: the bytes split into those at
/// even and at odd offsets, each byte replaced by its difference to the one before (plus
/// 128), then zlib. A block that would not shrink is stored as it is, as the format requires.
fn zip_compress(bytes: Vec<u8>) -> Vec<u8> {
    zip_deflate(&zip_predicted(&bytes), bytes.len()).unwrap_or(bytes)
}

/// [`zip_compress`] of a block of half floats (their bits), predicted straight from the
/// values: a half's low byte sits at an even offset, its high byte at an odd one.
fn zip_compress_halves(halves: &[u16]) -> Vec<u8> {
    zip_deflate(&zip_predicted_halves(halves), 2 * halves.len())
        .unwrap_or_else(|| halves.iter().flat_map(|h| h.to_le_bytes()).collect())
}

/// The zlib stream (level 4, zlib-rs: twice miniz's speed at this level, within 3 % of its
/// size) of a block's `predicted` bytes, when it is shorter than the block's `raw_len` bytes.
fn zip_deflate(predicted: &[u8], raw_len: usize) -> Option<Vec<u8>> {
    use std::io::Write;
    let mut encoder = flate2::write::ZlibEncoder::new(Vec::with_capacity(raw_len / 2), flate2::Compression::new(4));
    let compressed = encoder.write_all(predicted).and_then(|()| encoder.finish()).ok()?;
    (compressed.len() < raw_len).then_some(compressed)
}

/// [`zip_predicted`] of the little-endian bytes of `halves`: their low bytes, then their high
/// bytes, each differenced with the byte before it in that order (plus 128).
fn zip_predicted_halves(halves: &[u16]) -> Vec<u8> {
    let n = halves.len();
    let mut predicted = vec![0u8; 2 * n];
    let (Some(&first), Some(&last)) = (halves.first(), halves.last()) else { return predicted };
    let delta = |current: u8, previous: u8| current.wrapping_sub(previous).wrapping_add(128);
    let (lows, highs) = predicted.split_at_mut(n);
    for ((low, high), (&h, &previous)) in lows[1..].iter_mut().zip(&mut highs[1..]).zip(halves[1..].iter().zip(halves))
    {
        *low = delta(h as u8, previous as u8);
        *high = delta((h >> 8) as u8, (previous >> 8) as u8);
    }
    lows[0] = first as u8;
    highs[0] = delta((first >> 8) as u8, last as u8);
    predicted
}

/// The bytes ZIP compression deflates: those at even offsets, then those at odd offsets,
/// each replaced by its difference to the byte before it in that order, plus 128 (the first
/// kept as it is). One pass, without storing the split.
fn zip_predicted(bytes: &[u8]) -> Vec<u8> {
    let n = bytes.len();
    let half = n.div_ceil(2);
    let mut predicted = vec![0u8; n];
    if n == 0 {
        return predicted;
    }
    let delta = |current: u8, previous: u8| current.wrapping_sub(previous).wrapping_add(128);
    let (evens, odds) = predicted.split_at_mut(half);
    // Pair i holds the i-th even and the i-th odd byte; each follows pair i - 1's.
    let pairs = bytes.chunks_exact(2);
    for ((even, odd), (pair, previous)) in
        evens[1..].iter_mut().zip(odds.iter_mut().skip(1)).zip(pairs.clone().skip(1).zip(pairs))
    {
        *even = delta(pair[0], previous[0]);
        *odd = delta(pair[1], previous[1]);
    }
    evens[0] = bytes[0];
    let last_even = bytes[2 * (half - 1)];
    if n % 2 == 1 && n >= 3 {
        evens[half - 1] = delta(last_even, bytes[n - 3]);
    }
    // The odd bytes follow the last even one.
    if let Some(first_odd) = odds.first_mut() {
        *first_odd = delta(bytes[1], last_even);
    }
    predicted
}

/// The largest finite half float.
pub const HALF_MAX: f32 = 65504.0;

/// Writes the film to `path` (format from the extension), atomically.
pub fn write_image(film: &Film, path: &Path, settings: &ImageSettings) -> Result<(), OutputError> {
    let bytes = encode(film, path, settings)?;
    write_atomically(path, &bytes)
}

/// Reads a linear RGB EXR back into a film (used by tests and the parity checks).
pub fn read_exr(path: &Path) -> Result<Film, OutputError> {
    use exr::prelude::*;
    let image = read_first_rgba_layer_from_file(
        path,
        |resolution, _| Film::new(resolution.width() as u32, resolution.height() as u32),
        |film: &mut Film, p: Vec2<usize>, (r, g, b, _a): (f32, f32, f32, f32)| {
            let w = film.width as usize;
            film.pixels[p.y() * w + p.x()] = [r, g, b];
        },
    )
    .map_err(|source| OutputError::ReadExr { path: path.to_path_buf(), source })?;
    Ok(image.layer_data.channel_data.pixels)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::film::{Aov, Region};

    /// The predictor's one pass gives what splitting the bytes and then differencing them
    /// gives, at every length (odd ones too) and for every byte value.
    #[test]
    fn zip_prediction_is_split_then_differenced() {
        let reference = |bytes: &[u8]| -> Vec<u8> {
            let split: Vec<u8> = bytes.iter().step_by(2).chain(bytes.iter().skip(1).step_by(2)).copied().collect();
            let mut predicted: Vec<u8> = split.first().copied().into_iter().collect();
            predicted.extend(split.windows(2).map(|pair| pair[1].wrapping_sub(pair[0]).wrapping_add(128)));
            predicted
        };
        let mut rng = prism_api::contract::TestRng::new(0x2545_f491_4f6c_dd1d);
        for n in (0..40).chain([255, 256, 1001, 4096]) {
            let bytes: Vec<u8> = (0..n).map(|_| (rng.next_u64() >> 24) as u8).collect();
            assert_eq!(zip_predicted(&bytes), reference(&bytes), "{n} bytes");
        }
    }

    /// Predicting half floats straight from their bits gives what predicting their
    /// little-endian bytes gives, at every length; and a block of halves that does not
    /// deflate is stored as those bytes.
    #[test]
    fn zip_prediction_of_halves_is_that_of_their_bytes() {
        let mut rng = prism_api::contract::TestRng::new(0x9e37_79b9_7f4a_7c15);
        for n in (0..40).chain([255, 256, 1001, 4096]) {
            let halves: Vec<u16> = (0..n).map(|_| (rng.next_u64() >> 24) as u16).collect();
            let bytes: Vec<u8> = halves.iter().flat_map(|h| h.to_le_bytes()).collect();
            assert_eq!(zip_predicted_halves(&halves), zip_predicted(&bytes), "{n} halves");
            assert_eq!(zip_compress_halves(&halves), zip_compress(bytes), "{n} halves");
        }
    }

    /// The depth preview spans the depths of surfaces seen (near bright, far dark); escaped
    /// rays (depth f32::MAX) are black and do not stretch the range.
    #[test]
    fn depth_preview_ignores_escaped_rays() {
        let mut film = Film::for_region(Region::full(3, 1), (3, 1), &[Aov::Depth]);
        film.layers[0].data.copy_from_slice(&[1.0, 2.0, f32::MAX]);
        let preview = layer_preview(&film, Aov::Depth).unwrap();
        let shades: Vec<u8> = preview.pixels().map(|p| p.0[0]).collect();
        assert_eq!(shades, [255, 0, 0]);
    }

    /// A film of a region with AOV layers reads back with every channel named as
    /// compositors expect and its data window inside the full frame.
    #[test]
    fn layered_exr_has_named_channels_and_windows() {
        use exr::prelude::*;
        let mut film = Film::for_region(Region { x0: 2, y0: 1, x1: 5, y1: 3 }, (8, 4), &[Aov::Normal, Aov::Depth]);
        for (i, p) in film.pixels.iter_mut().enumerate() {
            *p = [i as f32, 0.5, -1.0];
        }
        film.layers[1].data[4] = 7.25;
        let bytes = Cursor::new(encode_exr(&film, false).unwrap().0);
        let image = read()
            .no_deep_data()
            .largest_resolution_level()
            .all_channels()
            .all_layers()
            .all_attributes()
            .from_buffered(Cursor::new(bytes.into_inner()))
            .unwrap();
        assert_eq!(image.attributes.display_window.size, Vec2(8, 4));
        let layer = &image.layer_data[0];
        assert_eq!(layer.attributes.layer_position, Vec2(2, 1));
        assert_eq!(layer.size, Vec2(3, 2));
        let names: Vec<String> = layer.channel_data.list.iter().map(|c| c.name.to_string()).collect();
        for name in ["B", "G", "R", "depth.Z", "normal.X", "normal.Y", "normal.Z"] {
            assert!(names.contains(&name.to_string()), "{name} missing from {names:?}");
        }
        let depth = layer.channel_data.list.iter().find(|c| c.name.to_string() == "depth.Z").unwrap();
        assert_eq!(depth.sample_data.value_by_flat_index(4).to_f32(), 7.25);
        let red = layer.channel_data.list.iter().find(|c| c.name.to_string() == "R").unwrap();
        assert_eq!(red.sample_data.value_by_flat_index(5).to_f32(), 5.0);
    }

    /// A symlink planted at the name the temporary file used to have (`.name.prism-PID.tmp`,
    /// predictable) is neither followed nor replaced: the temporary file's name is fresh and
    /// it is created exclusively.
    #[cfg(unix)]
    #[test]
    fn temporary_files_never_follow_planted_symlinks() {
        let dir = tempfile::tempdir().unwrap();
        let victim = dir.path().join("victim.txt");
        std::fs::write(&victim, "keep me").unwrap();
        let out = dir.path().join("out.png");
        let planted = dir.path().join(format!(".out.png.prism-{}.tmp", std::process::id()));
        std::os::unix::fs::symlink(&victim, &planted).unwrap();
        write_atomically(&out, b"image").unwrap();
        assert_eq!(std::fs::read_to_string(&victim).unwrap(), "keep me");
        assert_eq!(std::fs::read(&out).unwrap(), b"image");
        assert!(std::fs::symlink_metadata(&planted).unwrap().file_type().is_symlink());
        let names: Vec<String> = std::fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        assert_eq!(names.len(), 3, "no temporary file is left: {names:?}");
        assert!(matches!(write_atomically(Path::new("/dev/null"), b"x"), Err(OutputError::NotRegular { .. })));
    }

    /// Staged files are all renamed or none; the signal handler's cleanup removes the ones
    /// still in flight.
    #[test]
    fn staged_outputs_are_all_or_none_and_cleaned_up() {
        let dir = tempfile::tempdir().unwrap();
        let (a, b) = (dir.path().join("a.png"), dir.path().join("b.exr"));
        std::fs::create_dir(&b).unwrap();
        let files = [(a.as_path(), b"a".to_vec()), (b.as_path(), b"b".to_vec())];
        assert!(write_all_atomically(&files).is_err());
        assert!(!a.exists(), "the first output is not written when the second cannot be");
        let staged = stage(&a, b"a").unwrap();
        let temp = staged.temp.clone();
        assert!(temp.exists());
        // The registry's cleanup, limited to this test's folder: the tests run in parallel in
        // one process, and removing every registered file would pull the temporary files of
        // the others from under them.
        remove_registered_temps(|p| p.starts_with(dir.path()));
        assert!(!temp.exists());
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    }

    #[test]
    fn srgb_curve_known_values() {
        // Linear 0.5 is 188 in 8-bit sRGB; the two pieces meet at 0.0031308.
        assert_eq!((srgb_encode(0.5) * 255.0 + 0.5).floor() as u8, 188);
        assert_eq!(srgb_encode(0.0), 0.0);
        assert!((srgb_encode(1.0) - 1.0).abs() < 1e-12);
        let below = srgb_encode(0.003_130_8 - 1e-12);
        let above = srgb_encode(0.003_130_8 + 1e-12);
        assert!((below - above).abs() < 1e-6);
    }

    #[test]
    fn tone_maps_are_monotonic_and_bounded() {
        for op in [ToneMap::Clamp, ToneMap::Reinhard, ToneMap::Aces] {
            let mut last = -1.0;
            for i in 0..100 {
                let v = tone_map(f64::from(i) * 0.1, op);
                assert!(v >= last);
                last = v;
            }
        }
        assert!(tone_map(1e6, ToneMap::Reinhard) < 1.0);
    }

    #[test]
    fn ldr_table_gives_the_formula_byte_for_every_value() {
        let mut values = vec![0.0, -0.0, -1.0, f32::NAN, f32::INFINITY, f32::NEG_INFINITY, f32::MAX, f32::MIN_POSITIVE];
        values.push(f32::from_bits(1));
        let mut state = 0x2545_f491_4f6c_dd1du64;
        for _ in 0..20_000 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            // Any non-negative f32 bit pattern, and uniform values in [0, 2].
            values.push(f32::from_bits((state >> 33) as u32 & 0x7fff_ffff));
            values.push((state >> 40) as f32 / (1u64 << 23) as f32);
        }
        for op in [ToneMap::Clamp, ToneMap::Reinhard, ToneMap::Aces] {
            for exposure in [0.0, -3.3, 5.0, 200.0] {
                let scale = f64::exp2(exposure);
                let encoder = LdrEncoder::new(scale, op);
                // Each step and its neighbours, where a wrong table would show first.
                let mut probes = values.clone();
                for step in encoder.steps.iter().filter(|s| s.is_finite()) {
                    probes.extend([f32::from_bits(step.to_bits() - 1), *step, f32::from_bits(step.to_bits() + 1)]);
                }
                for v in probes {
                    assert_eq!(
                        encoder.encode(v),
                        ldr_channel(f64::from(v), scale, op),
                        "{v:e} under {op:?}, {exposure} stops"
                    );
                }
            }
        }
    }

    #[test]
    fn infinitely_bright_values_tone_map_to_white() {
        for op in [ToneMap::Clamp, ToneMap::Reinhard, ToneMap::Aces] {
            assert_eq!(ldr_channel(f64::INFINITY, 1.0, op), 255, "{op:?}");
            assert_eq!(ldr_channel(f64::from(f32::MAX), 1e10, op), 255, "{op:?}");
            assert_eq!(ldr_channel(f64::NAN, 1.0, op), 0, "{op:?}");
        }
    }

    #[test]
    fn formats_by_extension() {
        assert_eq!(format_for(Path::new("a.EXR")).unwrap(), OutputFormat::Exr);
        assert_eq!(format_for(Path::new("a.png")).unwrap(), OutputFormat::Ldr(ImageFormat::Png));
        assert_eq!(format_for(Path::new("a.ppm")).unwrap(), OutputFormat::Ldr(ImageFormat::Pnm));
        assert!(format_for(Path::new("a.xyz")).is_err());
        assert!(format_for(Path::new("noext")).is_err());
    }

    #[test]
    fn exr_round_trips_in_float_and_in_half() {
        let mut film = Film::new(5, 3);
        for (i, p) in film.pixels.iter_mut().enumerate() {
            let v = 0.1 + i as f32 * 0.377;
            *p = [v, v * 1e-3, v * 1e3];
        }
        let dir = std::env::temp_dir().join(format!("prism-exr-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("film.exr");
        let mut sizes = Vec::new();
        for exr_half in [false, true] {
            let settings = ImageSettings { exr_half, ..ImageSettings::default() };
            let bytes = encode(&film, &path, &settings).unwrap();
            sizes.push(bytes.len());
            std::fs::write(&path, bytes).unwrap();
            let back = read_exr(&path).unwrap();
            for (a, b) in film.pixels.iter().zip(&back.pixels) {
                for c in 0..3 {
                    let expected = if exr_half { exr::prelude::f16::from_f32(a[c]).to_f32() } else { a[c] };
                    assert_eq!(b[c], expected, "half = {exr_half}");
                }
            }
        }
        std::fs::remove_dir_all(&dir).unwrap();
        assert!(sizes[1] < sizes[0], "half-float file is smaller: {sizes:?}");
    }

    /// Blocks that deflate and blocks that do not (stored as they are) both read back
    /// exactly, through the exr crate's reader.
    #[test]
    fn exr_blocks_compressed_or_stored_read_back_exactly() {
        let (w, h) = (300, 40);
        let mut smooth = Film::new(w, h);
        let mut noise = Film::new(w, h);
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        for (i, (s, n)) in smooth.pixels.iter_mut().zip(&mut noise.pixels).enumerate() {
            let (x, y) = ((i % w as usize) as f32, (i / w as usize) as f32);
            *s = [x / w as f32, y / h as f32, 0.25];
            *n = [0; 3].map(|_| {
                state ^= state << 13;
                state ^= state >> 7;
                state ^= state << 17;
                f32::from_bits((state >> 32) as u32 & 0x3fff_ffff)
            });
        }
        let raw = (w * h * 3 * 4) as usize;
        for (film, compresses) in [(&smooth, true), (&noise, false)] {
            let (bytes, _) = encode_exr(film, false).unwrap();
            assert_eq!(bytes.len() < raw / 2, compresses, "{} bytes of {raw}", bytes.len());
            let path = std::env::temp_dir().join(format!("prism-exr-blocks-{}-{compresses}.exr", std::process::id()));
            std::fs::write(&path, &bytes).unwrap();
            let back = read_exr(&path).unwrap();
            std::fs::remove_file(&path).unwrap();
            assert!(back.pixels == film.pixels, "compresses = {compresses}");
        }
        let incompressible: Vec<u8> = noise.pixels.as_flattened().iter().flat_map(|v| v.to_le_bytes()).collect();
        assert_eq!(zip_compress(incompressible.clone()), incompressible);
    }
}
