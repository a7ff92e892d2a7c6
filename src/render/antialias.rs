//! POV-Ray 3.7's antialiasing, methods 1 and 2 without jitter (`+AM1 -J`, `+AM2 -J`;
//! `shared/povray/REPORT.md` section 5, `TraceTask` in POV-Ray's `tracetask.cpp`), so that a
//! scene rendered with `antialias = { method = "pov1" }` takes exactly the samples POV-Ray
//! takes and the two images can be compared pixel by pixel.
//!
//! Both methods work on 32 x 32 blocks of the image (POV-Ray's default `Render_Block_Size`).
//! Method 1's decisions depend on the order pixels are visited inside a block but never on
//! other blocks, so a block is one task and the image does not depend on the thread count.
//!
//! A trace is a function of its image position alone (its random numbers are keyed by the
//! position's bits), so a position traced twice gives the same colour twice. POV-Ray traces
//! the samples on a block's edge again for each block that reads them; here the blocks of one
//! frame share them through [`BorderSamples`], and a supersampled pixel reuses its centre
//! where the sub-pixel grid passes through it.

use std::sync::OnceLock;

use glam::{DVec2, DVec3};

use super::camera::pov_screen;
use super::extract::RenderScene;
use super::integrators::Integrator;
use super::sampling::{ProgressivePattern, SampleStream, hash4, mix64};
use crate::gamma::{self, GammaCurve, Transcoding};
use crate::world::components::Antialias;

/// Side of the square blocks POV-Ray antialiases independently (`Render_Block_Size`).
pub const BLOCK_SIZE: u32 = 32;

/// POV-Ray's `Antialias_Gamma`: colours are compared after encoding with 1 / 2.5.
const AA_GAMMA: f64 = 2.5;

/// POV-Ray's `EPSILON`, which ends its sub-pixel loops.
const EPSILON: f64 = 1e-10;

/// One of POV-Ray's two antialiasing methods with its threshold and depth.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PovMethod {
    /// Method 1: non-adaptive supersampling of pixels that differ from a neighbour.
    NonAdaptive {
        /// Colour distance at which neighbours count as different.
        threshold: f64,
        /// Samples per axis of a supersampled pixel.
        depth: u32,
    },
    /// Method 2: recursive subdivision of pixels whose corners differ.
    Adaptive {
        /// Colour distance at which corners count as different.
        threshold: f64,
        /// Subdivision depth; the finest spacing is 1 / 2^(depth - 1) pixel.
        depth: u32,
    },
}

impl PovMethod {
    /// The method an [`Antialias`] setting asks for, if it is one of POV-Ray's.
    pub fn from_setting(antialias: Antialias) -> Option<Self> {
        match antialias {
            Antialias::Stratified {} => None,
            Antialias::Pov1 { threshold, depth } => Some(PovMethod::NonAdaptive { threshold, depth }),
            Antialias::Pov2 { threshold, depth } => Some(PovMethod::Adaptive { threshold, depth }),
        }
    }
}

/// The samples on the lines where neighbouring blocks meet, shared by the blocks of one
/// frame: method 1's pixel centres on each block's last row and column (the next blocks
/// compare their first pixels with them), method 2's pixel corners on each block's first row
/// and column (the previous blocks' last ones). Each is traced by whichever block needs it
/// first and read by the other; both would trace the same colour.
pub struct BorderSamples {
    /// Sample-grid coordinate (pixel for method 1, corner for method 2) of the lines modulo
    /// [`BLOCK_SIZE`].
    phase: i64,
    /// The first sample-grid column and row stored, and the number of each.
    x0: i64,
    y0: i64,
    columns_wide: i64,
    rows_high: i64,
    /// The shared rows (one per block row, `columns_wide` samples each) and columns (one per
    /// block column, `rows_high` samples each).
    rows: Vec<OnceLock<DVec3>>,
    columns: Vec<OnceLock<DVec3>>,
}

impl BorderSamples {
    /// The shared samples of the blocks from (`block_x0`, `block_y0`) to (`block_x1`,
    /// `block_y1`) (exclusive, in blocks) rendered with `method`.
    pub fn new(method: PovMethod, (block_x0, block_y0): (u32, u32), (block_x1, block_y1): (u32, u32)) -> Self {
        let size = i64::from(BLOCK_SIZE);
        let phase = match method {
            PovMethod::NonAdaptive { .. } => size - 1,
            PovMethod::Adaptive { .. } => 0,
        };
        // Method 1 reads one pixel before each block, method 2 one corner after it.
        let (x0, y0) = (i64::from(block_x0) * size - 1, i64::from(block_y0) * size - 1);
        let (columns_wide, rows_high, row_lines, column_lines) =
            Self::layout((block_x0, block_y0), (block_x1, block_y1));
        let cells = |count: usize, len: i64| (0..count * len as usize).map(|_| OnceLock::new()).collect();
        Self {
            phase,
            x0,
            y0,
            columns_wide,
            rows_high,
            rows: cells(row_lines, columns_wide),
            columns: cells(column_lines, rows_high),
        }
    }

    /// Bytes [`BorderSamples::new`] allocates for the same arguments.
    pub fn bytes(from: (u32, u32), to: (u32, u32)) -> u64 {
        let (columns_wide, rows_high, row_lines, column_lines) = Self::layout(from, to);
        let samples = row_lines as u64 * columns_wide as u64 + column_lines as u64 * rows_high as u64;
        samples * std::mem::size_of::<OnceLock<DVec3>>() as u64
    }

    /// For the blocks from `from` to `to`: the samples along each shared row and each shared
    /// column (the blocks' span and one beyond each end), and how many rows and columns.
    fn layout((block_x0, block_y0): (u32, u32), (block_x1, block_y1): (u32, u32)) -> (i64, i64, usize, usize) {
        let size = i64::from(BLOCK_SIZE);
        let (blocks_wide, blocks_high) = (block_x1 - block_x0, block_y1 - block_y0);
        (
            i64::from(blocks_wide) * size + 2,
            i64::from(blocks_high) * size + 2,
            blocks_high as usize + 1,
            blocks_wide as usize + 1,
        )
    }

    /// The slot of sample-grid point (x, y) when it lies on a shared line.
    fn slot(&self, x: i64, y: i64) -> Option<&OnceLock<DVec3>> {
        let size = i64::from(BLOCK_SIZE);
        let (dx, dy) = (x - self.x0, y - self.y0);
        if !(0..self.columns_wide).contains(&dx) || !(0..self.rows_high).contains(&dy) {
            return None;
        }
        // Lines are counted from the first one at or after the origin.
        let line =
            |v: i64, origin: i64| (v - self.phase).div_euclid(size) - (origin - self.phase + size - 1).div_euclid(size);
        if (y - self.phase).rem_euclid(size) == 0 {
            self.rows.get((line(y, self.y0) * self.columns_wide + dx) as usize)
        } else if (x - self.phase).rem_euclid(size) == 0 {
            self.columns.get((line(x, self.x0) * self.rows_high + dy) as usize)
        } else {
            None
        }
    }
}

/// Traces single positions on the image plane in POV-Ray's pixel coordinates.
struct Sampler<'a, I: Integrator> {
    scene: &'a RenderScene,
    /// Samples shared with the neighbouring blocks, if any.
    borders: Option<&'a BorderSamples>,
    integrator: &'a I,
    width: f64,
    height: f64,
    /// All rays traced so far.
    rays: u64,
    /// Camera rays traced so far.
    primary: u64,
    /// How colours are compared.
    grade: AaGrade,
}

impl<I: Integrator> Sampler<'_, I> {
    /// The colour at image position (x, y), pixel centres at integers (POV-Ray's
    /// `TracePixel::operator()`). With an aperture it averages `samples` lens samples spread
    /// over the pixel, as POV-Ray's focal blur does (fewer once they agree, under adaptive
    /// focal blur).
    fn trace(&mut self, x: f64, y: f64) -> DVec3 {
        let settings = &self.scene.settings;
        // Random numbers keyed by the exact position, so every block and thread agrees.
        let key = mix64(x.to_bits() ^ mix64(y.to_bits()));
        if self.scene.camera.aperture <= 0.0 {
            let (x0, y0) = pov_screen(x, y, self.width, self.height);
            let stream = SampleStream::new(key, 0, settings.seed);
            return self.radiance(x0, y0, DVec2::ZERO, stream);
        }
        let samples = settings.samples;
        let pattern_key = hash4(key, 0, u64::MAX, settings.seed);
        if let Some(blur) = &self.scene.focal_blur {
            // POV-Ray's adaptive focal blur stops each traced position on its own; its lens
            // and sub-pixel positions then come from a pattern stratified at every prefix.
            let mut pattern = ProgressivePattern::new(pattern_key);
            let mut test = blur.test();
            let mut sum = DVec3::ZERO;
            for s in 0..samples {
                pattern.seek(s);
                let offset = pattern.offset() - DVec2::splat(0.5);
                let (x0, y0) = pov_screen(x + offset.x, y + offset.y, self.width, self.height);
                let stream = SampleStream::new(key, u64::from(s), settings.seed);
                let radiance = self.radiance(x0, y0, pattern.lens(), stream);
                sum += radiance;
                if test.add(radiance) {
                    break;
                }
            }
            return sum / f64::from(test.taken());
        }
        let patterns = self.scene.patterns.for_key(pattern_key);
        let mut sum = DVec3::ZERO;
        for s in 0..samples {
            let offset = patterns.offset(s) - DVec2::splat(0.5);
            let lens = patterns.lens(s);
            let (x0, y0) = pov_screen(x + offset.x, y + offset.y, self.width, self.height);
            let stream = SampleStream::new(key, u64::from(s), settings.seed);
            sum += self.radiance(x0, y0, lens, stream);
        }
        sum / f64::from(samples)
    }

    /// The colour of sample-grid point (`x`, `y`) at image position `at`: read from the
    /// neighbouring blocks' shared samples when it lies on a block border and was traced
    /// already, traced (and shared) otherwise.
    fn grid_trace(&mut self, (x, y): (i64, i64), at: (f64, f64)) -> DVec3 {
        let Some(slot) = self.borders.and_then(|b| b.slot(x, y)) else {
            return self.trace(at.0, at.1);
        };
        if let Some(colour) = slot.get() {
            return *colour;
        }
        let colour = self.trace(at.0, at.1);
        // Another block may have traced it meanwhile: the same colour.
        let _ = slot.set(colour);
        colour
    }

    fn radiance(&mut self, x0: f64, y0: f64, lens: DVec2, stream: SampleStream) -> DVec3 {
        let ray = self.scene.camera.ray(x0, y0, lens);
        let sample = self.integrator.sample(&ray, stream);
        self.rays += sample.rays;
        self.primary += 1;
        sample.radiance
    }
}

/// How antialiasing grades colours before comparing them: POV-Ray's antialiasing gamma
/// (2.5) transcoded from the integrator's working space (`view.cpp`).
#[derive(Clone, Copy, Debug)]
struct AaGrade {
    /// The curve from a working space other than linear light; `None` for linear light,
    /// graded in double precision by [`two_fifths_power`] (POV-Ray's single-precision curve
    /// differs from it in the last bits).
    from_working: Option<Transcoding>,
}

impl AaGrade {
    fn new(working: GammaCurve) -> Self {
        let from_working =
            (!working.is_neutral()).then(|| Transcoding::new(working, GammaCurve::power_law(AA_GAMMA as f32)));
        Self { from_working }
    }

    /// A colour as antialiasing compares it: in linear light max(v, 0)^(1 / 2.5) per
    /// channel; from another working space through POV-Ray's transcoding curve, in single
    /// precision as POV-Ray's. A NaN channel stays NaN (POV-Ray's `max(x, 0)` returns its
    /// first argument when the comparison fails), so a NaN sample differs from nothing.
    fn of(self, c: DVec3) -> DVec3 {
        let graded = match self.from_working {
            None => DVec3::new(two_fifths_power(c.x), two_fifths_power(c.y), two_fifths_power(c.z)),
            Some(curve) => DVec3::from_array(c.to_array().map(|v| f64::from(curve.encode(v as f32)))),
        };
        DVec3::select(c.is_nan_mask(), c, graded)
    }

    /// POV-Ray's colour distance after antialiasing gamma: sum over the channels of the
    /// differences of the graded values (the transmit channel is 0 without an alpha channel).
    /// The tests' reference for [`Threshold::differ_graded`].
    #[cfg(test)]
    fn distance(self, a: DVec3, b: DVec3) -> f64 {
        graded_distance(self.of(a), self.of(b))
    }
}

/// max(x, 0)^(1 / 2.5) (the antialiasing gamma's curve, [`AA_GAMMA`]) to within 1e-13
/// relative, somewhat faster than libm's `pow` (which took a tenth of a simple scene's
/// single-thread render at 4K; this takes 7-8 %): x = m 2^e with m in [1, 2), m^(2/5) from a
/// polynomial refined by one Newton step on y^5 = m^2, and 2^(2e/5) as a power of four times
/// one of five constants.
fn two_fifths_power(x: f64) -> f64 {
    // Negatives grade as 0, as `max(0)` then `powf` did (NaN too; [`AaGrade::of`] keeps a
    // NaN channel); subnormals and infinity take the slow path.
    if x.is_nan() || x <= 0.0 {
        return 0.0;
    }
    if !(f64::MIN_POSITIVE..=f64::MAX).contains(&x) {
        return x.powf(0.4);
    }
    const TWO_TO_TWO_FIFTHS: [f64; 5] =
        [1.0, 1.3195079107728942, 1.7411011265922482, 2.2973967099940698, 3.0314331330207964];
    // Chebyshev fit of m^0.4 over t = 2m - 3 in [-1, 1], relative error 8e-8.
    const FIT: [f64; 8] = [
        1.176079040184787,
        0.15681051209407101,
        -0.01568168234674013,
        0.002788093990602002,
        -0.0006006161228651753,
        0.00014362134951812524,
        -4.271887378212206e-05,
        1.1717608030731615e-05,
    ];
    let bits = x.to_bits();
    let exponent = ((bits >> 52) & 0x7ff) as i32 - 1023;
    let m = f64::from_bits((bits & 0x000f_ffff_ffff_ffff) | 0x3ff0_0000_0000_0000);
    let t = 2.0 * m - 3.0;
    // Estrin's scheme (a short dependency chain); not `mul_add`, which is a library call
    // without hardware FMA.
    let t2 = t * t;
    let low = (FIT[0] + FIT[1] * t) + t2 * (FIT[2] + FIT[3] * t);
    let high = (FIT[4] + FIT[5] * t) + t2 * (FIT[6] + FIT[7] * t);
    let y = low + (t2 * t2) * high;
    let y2 = y * y;
    let y = (4.0 * y + m * m / (y2 * y2)) * 0.2;
    let (k, r) = (exponent.div_euclid(5), exponent.rem_euclid(5));
    // 4^k, |2k| <= 410: a normal power of two built from its exponent bits.
    let four_to_k = f64::from_bits(((2 * k + 1023) as u64) << 52);
    y * TWO_TO_TWO_FIFTHS[r as usize] * four_to_k
}

/// [`AaGrade::distance`] of two colours already graded.
fn graded_distance(a: DVec3, b: DVec3) -> f64 {
    (a - b).abs().element_sum()
}

/// Whether two colours differ by the antialiasing threshold, grading them only where that is
/// not certain without: in linear light the grade x^(2/5) is concave and 0 at 0, so a
/// channel's graded difference is at most its difference to the 2/5, and colours within
/// `(threshold / 3)^(5/2)` of each other in every channel are closer than the threshold. The
/// decisions are exactly those of grading both colours (a margin covers the rounding).
#[derive(Clone, Copy, Debug)]
struct Threshold {
    grade: AaGrade,
    threshold: f64,
    /// Per-channel differences below this are certainly below the threshold; 0 where no
    /// such bound is used (other working spaces, thresholds too small for the margin).
    close: f64,
}

/// Colours are compared without grading only when every channel is below this magnitude:
/// their grades are then below 4e3, whose rounding (1e-13 relative) stays far inside the
/// margin the bound leaves (a quarter of a threshold of at least 1e-6).
const UNGRADED_LIMIT: f64 = 1e9;

impl Threshold {
    fn new(grade: AaGrade, threshold: f64) -> Self {
        // Half the bound: three channels then reach at most 0.76 of the threshold.
        let close =
            if grade.from_working.is_none() && threshold >= 1e-6 { 0.5 * (threshold / 3.0).powf(2.5) } else { 0.0 };
        Self { grade, threshold, close }
    }

    /// True when `a` and `b` certainly grade closer than the threshold (false for NaN).
    fn certainly_close(&self, a: DVec3, b: DVec3) -> bool {
        let limit = DVec3::splat(UNGRADED_LIMIT);
        (a - b).abs().cmplt(DVec3::splat(self.close)).all() && a.abs().cmplt(limit).all() && b.abs().cmplt(limit).all()
    }

    /// True when two colours differ by the threshold or more; their grades are kept once
    /// computed (a sample is compared with several neighbours).
    fn differ_graded(&self, a: &mut Graded, b: &mut Graded) -> bool {
        if self.certainly_close(a.colour, b.colour) {
            return false;
        }
        graded_distance(a.graded(self.grade), b.graded(self.grade)) >= self.threshold
    }
}

/// A colour and, once something needed it, its grade.
#[derive(Clone, Copy, Debug, Default)]
struct Graded {
    colour: DVec3,
    grade: Option<DVec3>,
}

impl Graded {
    fn new(colour: DVec3) -> Self {
        Self { colour, grade: None }
    }

    fn graded(&mut self, grade: AaGrade) -> DVec3 {
        *self.grade.get_or_insert_with(|| grade.of(self.colour))
    }
}

/// What rendering one block produced.
pub struct Block {
    /// Pixels row by row, `min(BLOCK_SIZE, width - left)` wide.
    pub pixels: Vec<[f32; 3]>,
    /// All rays traced.
    pub rays: u64,
    /// Camera rays traced.
    pub primary_rays: u64,
}

/// Renders the block whose top-left pixel is (`left`, `top`) with `method`, sharing the
/// samples on its borders through `borders` (made for the same method) when given.
pub fn render_block<I: Integrator>(
    scene: &RenderScene,
    integrator: &I,
    method: PovMethod,
    (left, top): (u32, u32),
    borders: Option<&BorderSamples>,
) -> Block {
    let (width, height) = (scene.settings.width, scene.settings.height);
    let w = BLOCK_SIZE.min(width - left) as usize;
    let h = BLOCK_SIZE.min(height - top) as usize;
    let working = integrator.working_gamma();
    let grade = AaGrade::new(working);
    let mut sampler = Sampler {
        scene,
        borders,
        integrator,
        width: f64::from(width),
        height: f64::from(height),
        rays: 0,
        primary: 0,
        grade,
    };
    let block = BlockArea { left: f64::from(left), top: f64::from(top), w, h };
    let colours = match method {
        PovMethod::NonAdaptive { threshold, depth } => non_adaptive(&mut sampler, block, threshold, depth),
        PovMethod::Adaptive { threshold, depth } => adaptive(&mut sampler, block, threshold, depth),
    };
    Block {
        // Averaged in the working space; the film holds linear light. A NaN channel (a
        // `classic` sample's, spread through the mean) is written as 0, as POV-Ray writes it.
        pixels: colours
            .into_iter()
            .map(|c| {
                let c = gamma::decode_rgb(working, c);
                [c.x, c.y, c.z].map(|v| if v.is_nan() { 0.0 } else { v as f32 })
            })
            .collect(),
        rays: sampler.rays,
        primary_rays: sampler.primary,
    }
}

/// A block's top-left pixel (image coordinates) and its size in pixels.
#[derive(Clone, Copy)]
struct BlockArea {
    left: f64,
    top: f64,
    w: usize,
    h: usize,
}

/// Method 1 (`TraceTask::NonAdaptiveSupersamplingM1`): trace each pixel centre, compare it
/// with its left and upper neighbours (as they are at that moment) and supersample every
/// pixel of a differing pair that was not supersampled yet. The row above the block and the
/// pixel left of each row are traced only to compare with and are never supersampled.
fn non_adaptive<I: Integrator>(s: &mut Sampler<I>, block: BlockArea, threshold: f64, depth: u32) -> Vec<DVec3> {
    let BlockArea { left, top, w, h } = block;
    let threshold = Threshold::new(s.grade, threshold);
    // Each colour is graded at most once, when a comparison first needs its grade.
    let (gx, gy) = (left as i64, top as i64);
    let mut above: Vec<Graded> =
        (0..w).map(|x| Graded::new(s.grid_trace((gx + x as i64, gy - 1), (left + x as f64, top - 1.0)))).collect();
    let mut pixels = vec![Graded::default(); w * h];
    let mut done = vec![false; w * h];
    for y in 0..h {
        let py = top + y as f64;
        let mut before_row = Graded::new(s.grid_trace((gx - 1, gy + y as i64), (left - 1.0, py)));
        for (x, above) in above.iter_mut().enumerate() {
            let px = left + x as f64;
            let i = y * w + x;
            let mut current = Graded::new(s.grid_trace((gx + x as i64, gy + y as i64), (px, py)));
            // Flat regions (a background) repeat the left neighbour's colour exactly, and
            // with it any grade it has.
            if x > 0 && current.colour == pixels[i - 1].colour {
                current = pixels[i - 1];
            }
            let (left_differs, left_done) = if x == 0 {
                (threshold.differ_graded(&mut before_row, &mut current), true)
            } else {
                (threshold.differ_graded(&mut pixels[i - 1], &mut current), done[i - 1])
            };
            let (top_differs, top_done) = if y == 0 {
                (threshold.differ_graded(above, &mut current), true)
            } else {
                (threshold.differ_graded(&mut pixels[i - w], &mut current), done[i - w])
            };
            pixels[i] = current;
            let mut refine = |j: usize, px: f64, py: f64| {
                pixels[j] = Graded::new(supersample(s, px, py, pixels[j].colour, depth));
                done[j] = true;
            };
            if left_differs && !left_done {
                refine(i - 1, px - 1.0, py);
            }
            if top_differs && !top_done {
                refine(i - w, px, py - 1.0);
            }
            if left_differs || top_differs {
                refine(i, px, py);
            }
        }
    }
    pixels.into_iter().map(|p| p.colour).collect()
}

/// `depth` x `depth` samples at (k + 0.5) / depth across the pixel, added to the centre
/// sample already traced: the mean of depth^2 + 1 samples (`TraceTask::SupersampleOnePixel`).
fn supersample<I: Integrator>(s: &mut Sampler<I>, x: f64, y: f64, centre: DVec3, depth: u32) -> DVec3 {
    let step = 1.0 / f64::from(depth);
    let range = 0.5 - step * 0.5;
    let mut sum = centre;
    // POV-Ray steps by accumulation; doing the same keeps the positions bit-identical.
    let mut yy = -range;
    while yy <= range + EPSILON {
        let mut xx = -range;
        while xx <= range + EPSILON {
            let (sx, sy) = (x + xx, y + yy);
            // At odd depths the grid's middle sample is the centre itself (POV-Ray traces it
            // again).
            sum += if sx.to_bits() == x.to_bits() && sy.to_bits() == y.to_bits() { centre } else { s.trace(sx, sy) };
            xx += step;
        }
        yy += step;
    }
    sum / f64::from(depth * depth + 1)
}

/// Method 2 (`TraceTask::AdaptiveSupersamplingM2`): trace every pixel corner, then
/// subdivide each pixel while any two of a square's corners differ, down to 1 / 2^(depth-1).
fn adaptive<I: Integrator>(s: &mut Sampler<I>, block: BlockArea, threshold: f64, depth: u32) -> Vec<DVec3> {
    let BlockArea { left, top, w, h } = block;
    let mut corners = Vec::with_capacity((w + 1) * (h + 1));
    for y in 0..=h {
        for x in 0..=w {
            let grid = (left as i64 + x as i64, top as i64 + y as i64);
            corners.push(s.grid_trace(grid, (left + x as f64 - 0.5, top + y as f64 - 0.5)));
        }
    }
    let threshold = Threshold::new(s.grade, threshold);
    let size = 1usize << depth;
    let mut grid = SubdivisionGrid { size: size + 1, samples: vec![None; (size + 1) * (size + 1)] };
    let mut pixels = Vec::with_capacity(w * h);
    for y in 0..h {
        for x in 0..w {
            grid.samples.fill(None);
            grid.set(0, 0, corners[y * (w + 1) + x]);
            grid.set(0, size, corners[(y + 1) * (w + 1) + x]);
            grid.set(size, 0, corners[y * (w + 1) + x + 1]);
            grid.set(size, size, corners[(y + 1) * (w + 1) + x + 1]);
            let (px, py) = (left + x as f64, top + y as f64);
            let square = Square { x: px, y: py, d: 0.5, bx: 0, by: 0, step: size };
            pixels.push(subdivide(s, &mut grid, square, depth as i32 - 1, threshold));
        }
    }
    pixels
}

/// The sub-pixel samples of one pixel in method 2, on a (2^depth + 1)^2 grid.
struct SubdivisionGrid {
    size: usize,
    samples: Vec<Option<DVec3>>,
}

impl SubdivisionGrid {
    fn get(&self, x: usize, y: usize) -> DVec3 {
        self.samples[x + y * self.size].unwrap_or(DVec3::ZERO)
    }

    fn set(&mut self, x: usize, y: usize, c: DVec3) {
        self.samples[x + y * self.size] = Some(c);
    }

    /// The sample at grid (x, y), traced at image position `at` if not yet known.
    fn sample<I: Integrator>(&mut self, s: &mut Sampler<I>, x: usize, y: usize, at: (f64, f64)) {
        if self.samples[x + y * self.size].is_none() {
            let c = s.trace(at.0, at.1);
            self.set(x, y, c);
        }
    }
}

/// A square of method 2: centre (x, y) in image coordinates, half side `d`, and its top-left
/// corner and side on the sample grid.
#[derive(Clone, Copy)]
struct Square {
    x: f64,
    y: f64,
    d: f64,
    bx: usize,
    by: usize,
    step: usize,
}

/// `TraceTask::SubdivideOnePixel`: the value of one square.
fn subdivide<I: Integrator>(
    s: &mut Sampler<I>,
    grid: &mut SubdivisionGrid,
    q: Square,
    level: i32,
    threshold: Threshold,
) -> DVec3 {
    let c00 = grid.get(q.bx, q.by);
    let c02 = grid.get(q.bx, q.by + q.step);
    let c20 = grid.get(q.bx + q.step, q.by);
    let c22 = grid.get(q.bx + q.step, q.by + q.step);
    // Each corner meets three others: its grade is computed once, when first needed.
    let [mut g00, mut g02, mut g20, mut g22] = [c00, c02, c20, c22].map(Graded::new);
    let differ = |a: &mut Graded, b: &mut Graded| threshold.differ_graded(a, b);
    let split = level > 0
        && (differ(&mut g00, &mut g02)
            || differ(&mut g00, &mut g20)
            || differ(&mut g00, &mut g22)
            || differ(&mut g02, &mut g20)
            || differ(&mut g02, &mut g22)
            || differ(&mut g20, &mut g22));
    if !split {
        return (c00 + c02 + c20 + c22) / 4.0;
    }
    let (half, d2) = (q.step / 2, q.d * 0.5);
    grid.sample(s, q.bx, q.by + half, (q.x - q.d, q.y));
    grid.sample(s, q.bx + half, q.by, (q.x, q.y - q.d));
    grid.sample(s, q.bx + q.step, q.by + half, (q.x + q.d, q.y));
    grid.sample(s, q.bx + half, q.by + q.step, (q.x, q.y + q.d));
    grid.sample(s, q.bx + half, q.by + half, (q.x, q.y));
    let quarter =
        |dx: f64, dy: f64, bx: usize, by: usize| Square { x: q.x + dx, y: q.y + dy, d: d2, bx, by, step: half };
    let r00 = subdivide(s, grid, quarter(-d2, -d2, q.bx, q.by), level - 1, threshold);
    let r01 = subdivide(s, grid, quarter(-d2, d2, q.bx, q.by + half), level - 1, threshold);
    let r10 = subdivide(s, grid, quarter(d2, -d2, q.bx + half, q.by), level - 1, threshold);
    let r11 = subdivide(s, grid, quarter(d2, d2, q.bx + half, q.by + half), level - 1, threshold);
    (r00 + r01 + r10 + r11) / 4.0
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::integrators::classic::Classic;
    use crate::render::{RenderOptions, render_frame};
    use crate::scene::load::{Embedded, load_from};

    #[test]
    fn the_two_fifths_power_matches_powf() {
        assert_eq!(AA_GAMMA, 2.5);
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = || {
            state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut values: Vec<f64> = (0..200_000).map(|_| 4.0 * next()).collect();
        values.extend((0..200_000).map(|_| 10f64.powf(600.0 * next() - 300.0)));
        values.extend([1.0, 2.0, 0.5, 1.0 - f64::EPSILON, f64::MIN_POSITIVE, f64::MAX, 1e-310, f64::INFINITY]);
        for x in values {
            let (got, want) = (two_fifths_power(x), x.powf(0.4));
            assert!(got == want || (got - want).abs() <= 1e-13 * want, "{x}: {got} against {want}");
        }
        for x in [0.0, -0.0, -1.0, f64::NAN, f64::NEG_INFINITY] {
            assert_eq!(two_fifths_power(x), 0.0, "{x}");
        }
    }

    /// Deciding closeness without grading gives every decision grading both colours gives,
    /// at thresholds from 1e-6 to 3, for colours near each other (the worst case sits at 0,
    /// where the grade is steepest), far apart, negative, huge and NaN; and it does decide
    /// most pairs of nearby colours.
    #[test]
    fn ungraded_comparisons_decide_as_graded_ones() {
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let grade = AaGrade::new(GammaCurve::Neutral);
        let (mut pairs, mut ungraded) = (0, 0);
        for threshold in [1e-6, 1e-3, 0.01, 0.1, 0.3, 1.0, 3.0] {
            let test = Threshold::new(grade, threshold);
            let bound = (threshold / 3.0).powf(2.5);
            for i in 0..100_000 {
                let base = match i % 5 {
                    0 => DVec3::ZERO,
                    1 => DVec3::new(next(), next(), next()) * 1e-6,
                    2 => DVec3::new(next(), next(), next()),
                    3 => DVec3::new(next() - 0.5, next(), next()) * 1e8,
                    _ => DVec3::new(next(), f64::NAN, next()),
                };
                let step = DVec3::new(next(), next(), next()) * if i % 3 == 0 { 10.0 * bound } else { bound };
                let other = base + step;
                let graded = grade.distance(base, other) >= threshold;
                let reversed = test.differ_graded(&mut Graded::new(other), &mut Graded::new(base));
                assert_eq!(reversed, graded, "{other} and {base} at {threshold}");
                let (mut a, mut b) = (Graded::new(base), Graded::new(other));
                assert_eq!(test.differ_graded(&mut a, &mut b), graded);
                pairs += 1;
                ungraded += usize::from(a.grade.is_none());
            }
        }
        assert!(ungraded > pairs / 20, "{ungraded} of {pairs} decided without grading");
    }

    const SCENE: &str = "[render]\nwidth = 40\nheight = 24\n\
        [[object]]\nshape = \"sphere\"\nradius = 0.6\nmaterial = { color = [1.0, 0.5, 0.2], phong = 0.8 }\n\
        [[object]]\nshape = \"plane\"\noffset = -0.7\n\
        [[light]]\nposition = [2.0, 3.0, 4.0]\n";

    fn scene(antialias: Antialias) -> RenderScene {
        const FILES: Embedded = Embedded(&[("s.toml", SCENE)]);
        let mut scene = load_from(&FILES, std::path::Path::new("s.toml"), &crate::plugins::registry()).unwrap();
        scene.render.antialias = antialias;
        crate::prepare(&mut scene).unwrap()
    }

    fn sampler<'a>(scene: &'a RenderScene, integrator: &'a Classic<'a>) -> Sampler<'a, Classic<'a>> {
        Sampler {
            scene,
            borders: None,
            integrator,
            width: 40.0,
            height: 24.0,
            rays: 0,
            primary: 0,
            grade: AaGrade::new(GammaCurve::Neutral),
        }
    }

    /// Renders `scene` with `antialias` and checks each of `pixels` against `expected`, the
    /// pixel's value computed from single traces.
    fn check_pixels(
        antialias: Antialias,
        pixels: &[(u32, u32)],
        expected: impl Fn(&mut Sampler<Classic>, f64, f64) -> DVec3,
    ) {
        let scene = scene(antialias);
        let film = render_frame(&scene, &RenderOptions { threads: Some(2), ..Default::default() }).unwrap().0;
        let integrator = Classic::new(&scene);
        let mut s = sampler(&scene, &integrator);
        for &(x, y) in pixels {
            let expected = expected(&mut s, f64::from(x), f64::from(y));
            let got = film.get(x, y);
            for c in 0..3 {
                assert!((f64::from(got[c]) - expected[c]).abs() < 1e-5, "pixel ({x}, {y}): {got:?} vs {expected}");
            }
        }
    }

    #[test]
    fn method_1_with_threshold_0_supersamples_every_pixel() {
        let pixels = [(0, 0), (17, 9), (39, 23), (31, 5)];
        check_pixels(Antialias::Pov1 { threshold: 0.0, depth: 3 }, &pixels, |s, px, py| {
            let mut sum = s.trace(px, py);
            for j in [-1.0, 0.0, 1.0] {
                for i in [-1.0, 0.0, 1.0] {
                    sum += s.trace(px + i / 3.0, py + j / 3.0);
                }
            }
            sum / 10.0
        });
    }

    #[test]
    fn method_2_with_threshold_0_is_the_trapezoid_rule() {
        check_pixels(Antialias::Pov2 { threshold: 0.0, depth: 2 }, &[(0, 0), (17, 9), (39, 23)], |s, px, py| {
            let weights = [1.0, 2.0, 1.0];
            let mut sum = DVec3::ZERO;
            for (j, wj) in weights.iter().enumerate() {
                for (i, wi) in weights.iter().enumerate() {
                    sum += wi * wj * s.trace(px - 0.5 + i as f64 * 0.5, py - 0.5 + j as f64 * 0.5);
                }
            }
            sum / 16.0
        });
    }

    /// Renders a 70 x 40 frame block by block in order on one thread, sharing border samples
    /// or not: the pixels and the camera rays traced.
    fn blocks_in_order(antialias: Antialias, shared: bool) -> (Vec<[f32; 3]>, u64) {
        const FILES: Embedded = Embedded(&[("s.toml", SCENE)]);
        let mut loaded = load_from(&FILES, std::path::Path::new("s.toml"), &crate::plugins::registry()).unwrap();
        loaded.render.antialias = antialias;
        (loaded.render.width, loaded.render.height) = (70, 40);
        let scene = crate::prepare(&mut loaded).unwrap();
        let integrator = Classic::new(&scene);
        let method = PovMethod::from_setting(antialias).unwrap();
        let borders = BorderSamples::new(method, (0, 0), (3, 2));
        let (mut pixels, mut primary) = (Vec::new(), 0);
        for top in [0, 32] {
            for left in [0, 32, 64] {
                let block = render_block(&scene, &integrator, method, (left, top), shared.then_some(&borders));
                pixels.extend(block.pixels);
                primary += block.primary_rays;
            }
        }
        (pixels, primary)
    }

    #[test]
    fn blocks_share_their_border_samples_and_pixels_reuse_their_centre() {
        // Threshold 0 supersamples every pixel once. Method 1 traces per block the row above,
        // the column to the left and nine samples per pixel (the centre and eight sub-pixel
        // samples: the ninth is the centre again, except in row and column 0, where the
        // accumulated offset, 1e-17 or so, is not lost to rounding). Blocks of 32 x 32,
        // 32 x 32, 6 x 32 over 32 x 8, 32 x 8, 6 x 8: 260 border reads, 150 of them of a
        // neighbour's pixels.
        let method_1 = Antialias::Pov1 { threshold: 0.0, depth: 3 };
        let (alone, alone_rays) = blocks_in_order(method_1, false);
        let (shared, shared_rays) = blocks_in_order(method_1, true);
        assert_eq!(alone, shared);
        assert_eq!(alone_rays, 260 + 9 * 70 * 40 + (70 + 40 - 1));
        assert_eq!(shared_rays, alone_rays - 150);
        // Method 2 traces every block's corners; 155 of them are a previous block's (its
        // first row and column, counted once at their shared corner).
        let method_2 = Antialias::Pov2 { threshold: 0.1, depth: 3 };
        let (alone, alone_rays) = blocks_in_order(method_2, false);
        let (shared, shared_rays) = blocks_in_order(method_2, true);
        assert_eq!(alone, shared);
        assert_eq!(shared_rays, alone_rays - 155);
    }

    #[test]
    fn blocks_make_the_image_independent_of_threads() {
        for antialias in [Antialias::Pov1 { threshold: 0.1, depth: 3 }, Antialias::Pov2 { threshold: 0.1, depth: 3 }] {
            let scene = scene(antialias);
            let one = render_frame(&scene, &RenderOptions { threads: Some(1), ..Default::default() }).unwrap().0;
            let two = render_frame(&scene, &RenderOptions { threads: Some(2), ..Default::default() }).unwrap().0;
            assert_eq!(one, two, "{antialias:?}");
        }
    }

    #[test]
    fn distance_is_povs_gamma_encoded_sum() {
        let a = DVec3::new(1.0, 0.0, 0.0);
        let b = DVec3::new(0.0, 0.0, -1.0);
        let linear = AaGrade::new(GammaCurve::Neutral);
        // Linear light is graded by `two_fifths_power`, within 1e-13 of powf.
        assert!((linear.distance(a, b) - 1.0).abs() < 1e-13, "negative values count as 0");
        let d = linear.distance(DVec3::splat(0.5), DVec3::ZERO);
        assert!((d - 3.0 * 0.5f64.powf(0.4)).abs() < 1e-13);
        // In a 2.2 working space POV-Ray compares max(v, 0)^(2.2 / 2.5).
        let working = AaGrade::new(GammaCurve::power_law(2.2));
        let d = working.distance(DVec3::splat(0.5), DVec3::ZERO);
        assert!((d - 3.0 * 0.5f64.powf(0.88)).abs() < 1e-6, "{d}");
    }
}
