//! Latitude-longitude environment maps (HDR images of the light arriving from every
//! direction) with their importance-sampling distribution, for the physically based `path`
//! integrator. Nothing in the scene format uses them yet.
//!
//! # Convention (Mitsuba 3's `envmap`, exactly)
//!
//! Directions are in the map's local frame: right-handed, y up, as everywhere in Prism. A
//! direction `d` (unit; the direction a ray travels, so the light arrives from `d` toward the
//! ray's origin) has image coordinates
//!
//! ```text
//! u = atan2(d.x, -d.z) / 2π   wrapped into [0, 1)
//! v = acos(d.y) / π           in [0, 1]
//! ```
//!
//! and back, with `φ = 2π u`, `θ = π v`: `d = (sin φ sin θ, cos θ, -cos φ sin θ)`. So the top
//! row of the image is straight up (+y), the bottom row straight down (-y), and along the
//! horizon row the image runs `-z` (left edge, u = 0) → `+x` (u = 1/4) → `+z` (the centre,
//! u = 1/2) → `-x` (u = 3/4) → `-z` (right edge): seen from inside, looking along +z with y
//! up, the map appears unmirrored with +x on the left.
//!
//! Radiance is interpolated bilinearly between texels as Mitsuba's `eval` does, with its
//! texel placement: in a `W × H` image (row 0 at the top), texel `(x, y)` sits at
//! `u = (x + 0.5) / W` (texel-centred, periodic in u) and `v = y / (H - 1)` ("align
//! corners": the first and last rows lie on the poles, and v is clamped there). The
//! continuous texel position of `(u, v)` is therefore `(u W - 0.5, v (H - 1))`.
//!
//! # Sampling
//!
//! The texel grid splits the sphere into `W × (H - 1)` cells, each between two neighbouring
//! texel columns and two neighbouring rows: cell `(j, i)` spans `u` in
//! `[(j + 0.5) / W, (j + 1.5) / W]` and `θ` in `[i π / (H - 1), (i + 1) π / (H - 1)]`. Its
//! weight is the mean luminance of its four corner texels times its solid angle
//! `2π / W · (cos θ_i - cos θ_{i+1})` (which is the sin θ correction, exactly); a cell is
//! chosen with [`Distribution2D`] and a direction drawn uniformly in solid angle inside it.
//! The density is piecewise constant in solid angle, positive wherever the bilinear radiance
//! is, so estimates are unbiased. Mitsuba samples the bilinear interpolant itself
//! (`Hierarchical2D` over the texel grid, weighted by sin θ at each row); only the radiance
//! definition needs to match it, not the sampling.

use std::f64::consts::{PI, TAU};
use std::fmt;
use std::io::Cursor;
use std::path::{Path, PathBuf};

use glam::{DVec2, DVec3};

use super::distribution::Distribution2D;
use crate::files::{FileAccess, FileError, FileKind, shown_path};
use crate::limits::{MemoryBudget, OverBudget};

/// Images with more texels than this are refused before they are decoded (2^26: an
/// 11585 × 5792 map; 16k × 8k is too large).
pub const MAX_TEXELS: usize = 1 << 26;

/// Bytes an environment map costs per texel while it is decoded and tabulated (the decoded
/// image, the RGB texels and the sampling distribution).
const ENVIRONMENT_BYTES_PER_TEXEL: u64 = 40;

/// Luminance weights of linear Rec. 709 RGB, as Mitsuba's `luminance()`.
const LUMINANCE: DVec3 = DVec3::new(0.212_671, 0.715_160, 0.072_169);

/// What can go wrong loading or building an environment map.
#[derive(Debug, thiserror::Error)]
pub enum EnvironmentError {
    /// The file could not be opened or read (or is not a regular file, too large, or
    /// outside the `--root` sandbox).
    #[error("environment map: {0}")]
    File(#[from] FileError),
    /// Decoding would exceed the memory budget.
    #[error(transparent)]
    OverBudget(#[from] OverBudget),
    /// The file is not a readable `.exr` or `.hdr` image.
    #[error("cannot decode environment map {}: {message}", shown_path(.path))]
    Decode {
        /// The file.
        path: PathBuf,
        /// The decoder's complaint.
        message: String,
    },
    /// The image is not exactly twice as wide as it is high, or smaller than 4 × 2.
    #[error(
        "an environment map is {width} x {height} texels; a latitude-longitude map is exactly twice as wide as high, \
         at least 4 x 2"
    )]
    NotLatLong {
        /// Width in texels.
        width: usize,
        /// Height in texels.
        height: usize,
    },
    /// The image has more than [`MAX_TEXELS`] texels.
    #[error("an environment map of {width} x {height} texels is larger than the {MAX_TEXELS} texels allowed")]
    TooLarge {
        /// Width in texels.
        width: usize,
        /// Height in texels.
        height: usize,
    },
    /// The texel data does not fill the image.
    #[error("an environment map of {width} x {height} needs {} texels, got {count}", width * height)]
    TexelCount {
        /// Width in texels.
        width: usize,
        /// Height in texels.
        height: usize,
        /// Texels given.
        count: usize,
    },
    /// A texel is NaN or infinite.
    #[error("texel ({x}, {y}) of the environment map is not finite")]
    NonFinite {
        /// Column, from the left.
        x: usize,
        /// Row, from the top.
        y: usize,
    },
    /// A texel has a negative component.
    #[error("texel ({x}, {y}) of the environment map is negative")]
    Negative {
        /// Column, from the left.
        x: usize,
        /// Row, from the top.
        y: usize,
    },
}

/// A direction sampled from an environment map.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EnvironmentSample {
    /// Unit direction in the map's local frame (toward the light).
    pub direction: DVec3,
    /// [`EnvironmentMap::eval`] of `direction`.
    pub radiance: DVec3,
    /// Density with respect to solid angle: [`EnvironmentMap::pdf`] of `direction`.
    pub pdf: f64,
}

/// The image coordinates of local direction `d` (unit), Mitsuba's `direction_to_uv`:
/// `u = atan2(d.x, -d.z) / 2π` wrapped into `[0, 1)`, `v = acos(d.y) / π`.
pub fn direction_to_uv(d: DVec3) -> DVec2 {
    let u = d.x.atan2(-d.z) / TAU;
    let u = u - u.floor();
    DVec2::new(if u < 1.0 { u } else { 0.0 }, d.y.clamp(-1.0, 1.0).acos() / PI)
}

/// The local direction at image coordinates `uv`, the inverse of [`direction_to_uv`]:
/// `(sin φ sin θ, cos θ, -cos φ sin θ)` with `φ = 2π u`, `θ = π v`.
pub fn uv_to_direction(uv: DVec2) -> DVec3 {
    let (sin_theta, cos_theta) = (PI * uv.y).sin_cos();
    direction_at(TAU * uv.x, cos_theta, sin_theta)
}

fn direction_at(phi: f64, cos_theta: f64, sin_theta: f64) -> DVec3 {
    let (sin_phi, cos_phi) = phi.sin_cos();
    DVec3::new(sin_phi * sin_theta, cos_theta, -cos_phi * sin_theta)
}

/// An HDR environment image in latitude-longitude layout, with its importance-sampling
/// distribution. See the [module documentation](self) for the mapping, the interpolation
/// and the sampling.
#[derive(Clone)]
pub struct EnvironmentMap {
    width: usize,
    height: usize,
    /// Linear RGB, row-major, top row first.
    texels: Vec<[f32; 3]>,
    /// `cos θ` of each texel row, `height` entries from +1 to -1.
    row_cos: Vec<f64>,
    /// Over the `width × (height - 1)` cells between texels.
    cells: Distribution2D,
}

impl fmt::Debug for EnvironmentMap {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("EnvironmentMap")
            .field("width", &self.width)
            .field("height", &self.height)
            .field("power", &self.power())
            .finish_non_exhaustive()
    }
}

impl EnvironmentMap {
    /// Loads an OpenEXR (`.exr`: the first layer with RGB channels, alpha ignored) or Radiance
    /// (`.hdr`) file, chosen by the extension. The dimensions are checked from the header
    /// before the pixels are decoded.
    pub fn load(path: &Path) -> Result<Self, EnvironmentError> {
        Self::load_with(path, &FileAccess::unrestricted(), MemoryBudget::UNLIMITED)
    }

    /// [`EnvironmentMap::load`] reading through `access`, the decoded size checked against
    /// `budget` before the pixels are decoded.
    pub fn load_with(path: &Path, access: &FileAccess, budget: MemoryBudget) -> Result<Self, EnvironmentError> {
        let decode = |message: String| EnvironmentError::Decode { path: path.to_path_buf(), message };
        let bytes = access.read(path, FileKind::Image)?;
        let mut reader = Cursor::new(&bytes[..]);
        let extension = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
        let check = |width: usize, height: usize| -> Result<(), EnvironmentError> {
            check_size(width, height)?;
            let estimate = (width as u64 * height as u64).saturating_mul(ENVIRONMENT_BYTES_PER_TEXEL);
            budget.check(|| format!("environment map `{}` ({width} x {height})", shown_path(path)), estimate)?;
            Ok(())
        };
        let (width, height, texels) = match extension.as_deref() {
            Some("exr") => {
                let meta =
                    exr::meta::MetaData::read_from_buffered(&mut reader, false).map_err(|e| decode(e.to_string()))?;
                for header in &meta.headers {
                    check(header.layer_size.width(), header.layer_size.height())?;
                }
                read_exr(Cursor::new(&bytes[..])).map_err(|e| decode(e.to_string()))?
            }
            Some("hdr") => {
                use image::ImageDecoder;
                let decoder = image::codecs::hdr::HdrDecoder::new(reader).map_err(|e| decode(e.to_string()))?;
                let (width, height) = decoder.dimensions();
                check(width as usize, height as usize)?;
                let image =
                    image::DynamicImage::from_decoder(decoder).map_err(|e| decode(e.to_string()))?.into_rgb32f();
                (width as usize, height as usize, image.pixels().map(|p| p.0).collect())
            }
            _ => return Err(decode("unknown format: expected a .exr or .hdr file".into())),
        };
        Self::from_texels(width, height, texels)
    }

    /// From linear RGB texels, row-major, top row first. The image must be exactly twice as
    /// wide as high (at least 4 × 2), hold at most [`MAX_TEXELS`] texels, and every texel
    /// must be finite and non-negative.
    pub fn from_texels(width: usize, height: usize, texels: Vec<[f32; 3]>) -> Result<Self, EnvironmentError> {
        check_size(width, height)?;
        if texels.len() != width * height {
            return Err(EnvironmentError::TexelCount { width, height, count: texels.len() });
        }
        for (i, t) in texels.iter().enumerate() {
            let (x, y) = (i % width, i / width);
            if t.iter().any(|c| !c.is_finite()) {
                return Err(EnvironmentError::NonFinite { x, y });
            }
            if t.iter().any(|&c| c < 0.0) {
                return Err(EnvironmentError::Negative { x, y });
            }
        }
        let row_cos: Vec<f64> = (0..height)
            .map(|y| match y {
                0 => 1.0,
                _ if y == height - 1 => -1.0,
                _ => (PI * y as f64 / (height - 1) as f64).cos(),
            })
            .collect();
        let luminance: Vec<f64> = texels.iter().map(|t| LUMINANCE.dot(DVec3::from_array(t.map(f64::from)))).collect();
        let mut weights = Vec::with_capacity(width * (height - 1));
        for i in 0..height - 1 {
            let solid_angle = TAU / width as f64 * (row_cos[i] - row_cos[i + 1]);
            for j in 0..width {
                let k = (j + 1) % width;
                let corners = luminance[i * width + j]
                    + luminance[i * width + k]
                    + luminance[(i + 1) * width + j]
                    + luminance[(i + 1) * width + k];
                weights.push(0.25 * corners * solid_angle);
            }
        }
        let cells = Distribution2D::new(width, height - 1, &weights);
        Ok(Self { width, height, texels, row_cos, cells })
    }

    /// Width in texels.
    pub fn width(&self) -> usize {
        self.width
    }

    /// Height in texels.
    pub fn height(&self) -> usize {
        self.height
    }

    /// The texel at column `x`, row `y` (from the top).
    pub fn texel(&self, x: usize, y: usize) -> [f32; 3] {
        self.texels[y * self.width + x]
    }

    /// Radiance (linear RGB, W/(m² sr) before the scene's intensity scale) arriving from
    /// local direction `d` (unit): the bilinear interpolation of the texels at
    /// [`direction_to_uv`]`(d)`, periodic in u and clamped at the poles, as Mitsuba's `eval`.
    pub fn eval(&self, d: DVec3) -> DVec3 {
        let uv = direction_to_uv(d);
        let x = uv.x * self.width as f64 - 0.5;
        let y = uv.y * (self.height - 1) as f64;
        let (x0, y0) = (x.floor(), y.floor().min((self.height - 2) as f64));
        let (fx, fy) = (x - x0, y - y0);
        let column = |c: f64| (c as i64).rem_euclid(self.width as i64) as usize;
        let (c0, c1) = (column(x0), column(x0 + 1.0));
        let r0 = y0 as usize;
        let at = |c: usize, r: usize| DVec3::from_array(self.texels[r * self.width + c].map(f64::from));
        let top = at(c0, r0) * (1.0 - fx) + at(c1, r0) * fx;
        let bottom = at(c0, r0 + 1) * (1.0 - fx) + at(c1, r0 + 1) * fx;
        top * (1.0 - fy) + bottom * fy
    }

    /// Samples a direction with density proportional to the luminance of the cell around it
    /// times the cell's solid angle (the sin θ correction); see the module documentation.
    /// A map that is black everywhere is sampled uniformly over the sphere.
    pub fn sample(&self, u: DVec2) -> EnvironmentSample {
        if self.cells.total() <= 0.0 {
            let z = 1.0 - 2.0 * u.y;
            let direction = direction_at(TAU * u.x, z, (1.0 - z * z).max(0.0).sqrt());
            return EnvironmentSample { direction, radiance: self.eval(direction), pdf: 1.0 / (4.0 * PI) };
        }
        let ((j, i), probability, r) = self.cells.sample(u);
        let phi = TAU * (j as f64 + 0.5 + r.x) / self.width as f64;
        let (top, bottom) = (self.row_cos[i], self.row_cos[i + 1]);
        let z = top + r.y * (bottom - top);
        let direction = direction_at(phi, z, (1.0 - z * z).max(0.0).sqrt());
        EnvironmentSample { direction, radiance: self.eval(direction), pdf: probability / self.cell_solid_angle(i) }
    }

    /// The solid-angle density with which [`EnvironmentMap::sample`] gives direction `d`
    /// (unit).
    pub fn pdf(&self, d: DVec3) -> f64 {
        if self.cells.total() <= 0.0 {
            return 1.0 / (4.0 * PI);
        }
        let uv = direction_to_uv(d);
        let j = ((uv.x * self.width as f64 - 0.5).floor() as i64).rem_euclid(self.width as i64) as usize;
        // The row of cells whose cos θ range holds d.y (rows run from +1 down to -1).
        let z = d.y.clamp(-1.0, 1.0);
        let i = (self.row_cos.partition_point(|&c| c > z).max(1) - 1).min(self.height - 2);
        self.cells.probability(j, i) / self.cell_solid_angle(i)
    }

    /// Total power proxy for choosing between lights: `∫ luminance dω` (sr · W/(m² sr)) of
    /// the map as the sampler sees it, each cell's mean corner luminance over its solid angle.
    /// Exact for a constant map (`4π L`); within the interpolation error otherwise.
    pub fn power(&self) -> f64 {
        self.cells.total()
    }

    fn cell_solid_angle(&self, row: usize) -> f64 {
        TAU / self.width as f64 * (self.row_cos[row] - self.row_cos[row + 1])
    }
}

fn check_size(width: usize, height: usize) -> Result<(), EnvironmentError> {
    if width.checked_mul(height).is_none_or(|n| n > MAX_TEXELS) {
        return Err(EnvironmentError::TooLarge { width, height });
    }
    if width != 2 * height || height < 2 {
        return Err(EnvironmentError::NotLatLong { width, height });
    }
    Ok(())
}

/// The first RGB(A) layer of an EXR file: width, height and RGB texels, top row first.
fn read_exr(reader: Cursor<&[u8]>) -> exr::error::Result<(usize, usize, Vec<[f32; 3]>)> {
    use exr::prelude::*;
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .rgba_channels(
            |size, _| (size.width(), size.height(), vec![[0.0f32; 3]; size.area()]),
            |(width, _, texels): &mut (usize, usize, Vec<[f32; 3]>),
             at: Vec2<usize>,
             (r, g, b, _): (f32, f32, f32, f32)| {
                texels[at.y() * *width + at.x()] = [r, g, b];
            },
        )
        .first_valid_layer()
        .all_attributes()
        .from_buffered(reader)?;
    Ok(image.layer_data.channel_data.pixels)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_support::chi2::sphere_test;
    use prism_api::contract::TestRng;

    fn uniform(rng: &mut TestRng) -> DVec2 {
        DVec2::new(rng.uniform(), rng.uniform())
    }

    /// 64 × 32: a gradient from a dim bottom to a bright top, bluer toward +x, with a 3 × 2
    /// texel "sun" 200 times brighter above the horizon.
    fn sunny() -> EnvironmentMap {
        let (w, h) = (64, 32);
        let mut texels = Vec::with_capacity(w * h);
        for y in 0..h {
            for x in 0..w {
                let g = 0.05 + 1.0 - y as f32 / (h - 1) as f32;
                let b = g * (1.0 + 0.5 * (std::f32::consts::TAU * x as f32 / w as f32).sin());
                texels.push([0.8 * g, g, b]);
            }
        }
        for (x, y) in [(40, 9), (41, 9), (42, 9), (40, 10), (41, 10), (42, 10)] {
            texels[y * w + x] = [300.0, 250.0, 180.0];
        }
        EnvironmentMap::from_texels(w, h, texels).unwrap()
    }

    #[test]
    fn orientation_follows_mitsuba() {
        // 18 × 9: row 4 is the horizon (θ = 4π/8); column x is centred at u = (x + 0.5) / 18.
        let (w, h) = (18, 9);
        let mut texels = vec![[0.0f32; 3]; w * h];
        texels[..w].fill([7.0; 3]); // top row: straight up
        texels[(h - 1) * w..].fill([3.0; 3]); // bottom row: straight down
        let horizon = 4 * w;
        texels[horizon + 4] = [1.0, 0.0, 0.0]; // u = 0.25
        texels[horizon + 13] = [0.0, 1.0, 0.0]; // u = 0.75
        texels[horizon + 8] = [0.0, 0.0, 1.0]; // columns 8 and 9 straddle u = 0.5
        texels[horizon + 9] = [0.0, 0.0, 1.0];
        let map = EnvironmentMap::from_texels(w, h, texels).unwrap();
        let close = |a: DVec3, b: DVec3| (a - b).abs().max_element() < 1e-12;
        assert!(close(map.eval(DVec3::X), DVec3::X), "+x is u = 1/4: {}", map.eval(DVec3::X));
        assert!(close(map.eval(-DVec3::X), DVec3::Y), "-x is u = 3/4");
        assert!(close(map.eval(DVec3::Z), DVec3::Z), "+z is the image centre, u = 1/2");
        assert!(close(map.eval(-DVec3::Z), DVec3::ZERO), "-z is the seam, u = 0");
        assert!(close(map.eval(DVec3::Y), DVec3::splat(7.0)), "+y is the top row");
        assert!(close(map.eval(-DVec3::Y), DVec3::splat(3.0)), "-y is the bottom row");
        assert_eq!(direction_to_uv(DVec3::Z), DVec2::new(0.5, 0.5));
        assert_eq!(direction_to_uv(-DVec3::Z), DVec2::new(0.0, 0.5));
        assert!((direction_to_uv(DVec3::X) - DVec2::new(0.25, 0.5)).length() < 1e-15);
        assert!((uv_to_direction(DVec2::new(0.75, 0.5)) + DVec3::X).length() < 1e-15);
    }

    #[test]
    fn texel_centres_are_exact_and_the_seam_wraps() {
        let map = sunny();
        let (w, h) = (map.width(), map.height());
        // Not the poles: the whole first and last rows sit on one direction each there.
        for (x, y) in [(0, 5), (17, 9), (41, 10), (63, 20), (5, 1), (30, h - 2)] {
            let d = uv_to_direction(DVec2::new((x as f64 + 0.5) / w as f64, y as f64 / (h - 1) as f64));
            let expected = DVec3::from_array(map.texel(x, y).map(f64::from));
            assert!((map.eval(d) - expected).abs().max_element() <= 1e-9 * expected.max_element(), "texel ({x}, {y})");
            assert!(
                (direction_to_uv(d) - DVec2::new((x as f64 + 0.5) / w as f64, y as f64 / (h - 1) as f64)).length()
                    < 1e-12
            );
        }
        // Between the last column and the first: the mean of the two.
        let seam = uv_to_direction(DVec2::new(0.0, 10.0 / 31.0));
        let mean = 0.5 * DVec3::from_array(map.texel(63, 10).map(f64::from))
            + 0.5 * DVec3::from_array(map.texel(0, 10).map(f64::from));
        assert!((map.eval(seam) - mean).abs().max_element() < 1e-9);
    }

    #[test]
    fn samples_fit_the_density_and_agree_with_eval_and_pdf() {
        let map = sunny();
        let mut rng = TestRng::new(0xE17);
        let n = 200_000;
        let mut directions = Vec::with_capacity(n);
        for _ in 0..n {
            let s = map.sample(uniform(&mut rng));
            assert!((s.direction.length() - 1.0).abs() < 1e-12);
            let pdf = map.pdf(s.direction);
            assert!((pdf - s.pdf).abs() <= 1e-9 * s.pdf, "pdf {pdf} of {} vs the sample's {}", s.direction, s.pdf);
            assert_eq!(map.eval(s.direction), s.radiance);
            directions.push(s.direction);
        }
        sphere_test("environment map sample() against pdf()", &directions, &|d| map.pdf(d), 24, 48, 0.01);
    }

    #[test]
    fn importance_estimate_agrees_with_uniform_sampling() {
        let map = sunny();
        let lum = |d: DVec3| LUMINANCE.dot(map.eval(d));
        let mut rng = TestRng::new(3);
        let n = 100_000;
        let stats = |values: Vec<f64>| {
            let mean = values.iter().sum::<f64>() / n as f64;
            let var = values.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / (n - 1) as f64;
            (mean, var / n as f64)
        };
        let important =
            stats((0..n).map(|_| map.sample(uniform(&mut rng))).map(|s| LUMINANCE.dot(s.radiance) / s.pdf).collect());
        let uniform = stats((0..n).map(|_| rng.unit_vector()).map(|d| lum(d) * 4.0 * PI).collect());
        let sigma = (important.1 + uniform.1).sqrt();
        assert!(
            (important.0 - uniform.0).abs() < 3.0 * sigma,
            "importance {} vs uniform {} (σ {sigma})",
            important.0,
            uniform.0
        );
        assert!(important.1 < 0.1 * uniform.1, "importance sampling should cut the variance");
        assert!((map.power() - important.0).abs() < 0.02 * important.0, "power {} vs {}", map.power(), important.0);
    }

    #[test]
    fn constant_map_integrates_to_four_pi() {
        let c = [0.5f32, 2.0, 1.0];
        let map = EnvironmentMap::from_texels(32, 16, vec![c; 512]).unwrap();
        let value = DVec3::from_array(c.map(f64::from));
        let mut rng = TestRng::new(5);
        let n = 20_000;
        let estimates: Vec<DVec3> = (0..n).map(|_| map.sample(uniform(&mut rng))).map(|s| s.radiance / s.pdf).collect();
        let mean = estimates.iter().sum::<DVec3>() / n as f64;
        let var = estimates.iter().map(|e| (*e - mean) * (*e - mean)).sum::<DVec3>() / (n - 1) as f64;
        let sigma = (var / n as f64).max(DVec3::splat(1e-12)).powf(0.5);
        let exact = 4.0 * PI * value;
        assert!(((mean - exact).abs() - 3.0 * sigma - 1e-9 * exact).max_element() <= 0.0, "{mean} vs {exact}");
        assert!((map.power() - 4.0 * PI * LUMINANCE.dot(value)).abs() < 1e-12);
        assert!((map.pdf(DVec3::new(0.3, -0.4, 0.5).normalize()) - 1.0 / (4.0 * PI)).abs() < 1e-12);
    }

    #[test]
    fn black_map_samples_the_sphere_uniformly() {
        let map = EnvironmentMap::from_texels(8, 4, vec![[0.0; 3]; 32]).unwrap();
        let s = map.sample(DVec2::new(0.3, 0.7));
        assert_eq!(s.pdf, 1.0 / (4.0 * PI));
        assert_eq!(s.radiance, DVec3::ZERO);
        assert_eq!(map.pdf(DVec3::Y), s.pdf);
        assert_eq!(map.power(), 0.0);
    }

    #[test]
    fn bad_images_are_refused() {
        let err = |w: usize, h: usize, texels: Vec<[f32; 3]>| EnvironmentMap::from_texels(w, h, texels).unwrap_err();
        assert!(matches!(err(12, 4, vec![[1.0; 3]; 48]), EnvironmentError::NotLatLong { width: 12, height: 4 }));
        assert!(matches!(err(2, 1, vec![[1.0; 3]; 2]), EnvironmentError::NotLatLong { .. }));
        let mut texels = vec![[1.0f32; 3]; 32];
        texels[2 * 8 + 5][1] = f32::NAN;
        assert!(matches!(err(8, 4, texels.clone()), EnvironmentError::NonFinite { x: 5, y: 2 }));
        texels[2 * 8 + 5] = [1.0, 1.0, f32::INFINITY];
        assert!(matches!(err(8, 4, texels.clone()), EnvironmentError::NonFinite { x: 5, y: 2 }));
        texels[2 * 8 + 5] = [1.0; 3];
        texels[3 * 8 + 1] = [0.0, -1e-3, 0.0];
        let negative = err(8, 4, texels);
        assert!(matches!(negative, EnvironmentError::Negative { x: 1, y: 3 }));
        assert_eq!(negative.to_string(), "texel (1, 3) of the environment map is negative");
        assert!(
            matches!(err(1 << 14, 1 << 13, Vec::new()), EnvironmentError::TooLarge { .. }),
            "checked before the texels"
        );
        assert!(matches!(err(8, 4, vec![[1.0; 3]; 31]), EnvironmentError::TexelCount { count: 31, .. }));
        let missing = Path::new("/nonexistent/prism/sky.exr");
        match EnvironmentMap::load(missing).unwrap_err() {
            e @ EnvironmentError::File(_) => assert!(e.to_string().contains("/nonexistent/prism/sky.exr"), "{e}"),
            e => panic!("expected Io, got {e:?}"),
        }
    }

    #[test]
    fn committed_maps_load() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/env");
        for file in ["sunset_256x128.exr", "studio_256x128.hdr"] {
            let map = EnvironmentMap::load(&root.join(file)).unwrap_or_else(|e| panic!("{file}: {e}"));
            assert_eq!((map.width(), map.height()), (256, 128), "{file}");
            assert!(map.power() > 0.0 && map.power().is_finite(), "{file}");
        }
        let not_an_image = EnvironmentMap::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("Cargo.toml")).unwrap_err();
        assert!(matches!(not_an_image, EnvironmentError::Decode { .. }));
    }
}
