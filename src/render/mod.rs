//! `render`: the scheduler. It splits a region of the frame into tiles, renders them in
//! parallel (rayon), makes every camera ray and its random stream, and gathers the pixel
//! samples of any [`Integrator`] into a [`Film`]. Each pixel's samples depend only on
//! (pixel, sample, dimension, seed), so the image is bit-identical for any thread count,
//! tiling or region.

pub mod antialias;
pub mod bsdf;
pub mod camera;
pub mod extract;
pub mod filter;
pub mod focal_blur;
pub mod integrators;
pub mod lights;
pub mod sampling;
pub mod tile_queue;

use std::ops::Range;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex, PoisonError};
use std::time::{Duration, Instant};

use glam::{BVec3, DVec2, DVec3};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use rayon::prelude::*;

use crate::film::{Aov, Film, Region};
use crate::gamma;
use crate::limits::{MAX_THREADS, MemoryBudget, OverBudget};
use crate::partial::PixelSums;
use crate::world::components::{IntegratorKind, ToneMap};
use camera::pov_screen;
use extract::RenderScene;
use integrators::classic::Classic;
use integrators::path::Path;
use integrators::{FirstHit, Integrator, PixelSample};
use sampling::{SampleStream, hash4};
use tile_queue::TileQueue;

/// Side of a square render tile in pixels.
pub const TILE_SIZE: u32 = 16;

/// Samples per batch: adaptive sampling decides after each whole batch whether a pixel
/// stops.
pub const SAMPLE_BATCH: u32 = 8;

/// Batches a pixel takes before adaptive sampling may stop it.
pub const MIN_BATCHES: u32 = 2;

/// The largest standard deviation a displayed value (in [0, 1]) can have: adaptive
/// sampling's stopping rule is scaled so that a pixel this noisy stops exactly at the
/// `noise` target and every other pixel below it.
const LARGEST_DISPLAY_DEVIATION: f64 = 0.5;

/// How to run a render.
#[derive(Clone, Debug, Default)]
pub struct RenderOptions {
    /// Worker threads (`None`: those of the current rayon pool, one per core unless its
    /// builder said otherwise). A render runs on the current pool when it has this many
    /// threads, else on a pool of its own.
    pub threads: Option<usize>,
    /// Draw a progress bar on stderr (only when stderr is a terminal).
    pub progress: bool,
    /// AOV layers to gather besides the beauty image.
    pub aovs: Vec<Aov>,
    /// Set to stop the render: tiles not yet started are skipped (left black) and the
    /// stats say the render was cancelled.
    pub cancel: Option<Arc<AtomicBool>>,
    /// The memory the film and the tiles' results may take (estimated before the render).
    /// The default is [`MemoryBudget::default`]: a fraction of the machine's memory.
    pub budget: MemoryBudget,
    /// Text before the progress bar (for example the pass of a time-budgeted render).
    pub progress_prefix: String,
    /// Tiles not started by then are skipped (left black) and the stats say the render was
    /// cancelled, as with `cancel`.
    pub deadline: Option<Instant>,
    /// Told when the render starts and handed each finished tile's pixels (a preview
    /// window); it only reads them, so the image is the same with or without it.
    pub observer: Option<TileHook>,
}

/// Watches a render as it goes: where it starts, then each finished tile. Called from the
/// render threads, in no particular tile order.
pub trait TileObserver: Send + Sync {
    /// A render (or a pass of a time-budgeted one) of `region` of a `frame` (width, height)
    /// begins; the tiles that follow replace those of earlier renders.
    fn begin(&self, region: Region, frame: (u32, u32));
    /// A tile is done: `pixels` are the linear radiance of `area` (full-frame coordinates),
    /// row by row, before non-finite values are blackened. Under POV-Ray's antialiasing
    /// `area` is a whole block of the frame, which may reach outside the region.
    fn tile(&self, area: Region, pixels: &[[f32; 3]]);
}

/// A shared [`TileObserver`] (a newtype so that [`RenderOptions`] stays `Debug`).
#[derive(Clone)]
pub struct TileHook(pub Arc<dyn TileObserver>);

impl std::fmt::Debug for TileHook {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("TileHook")
    }
}

/// What a render did.
#[derive(Clone, Copy, Debug, Default)]
pub struct RenderStats {
    /// Wall time of the render itself.
    pub elapsed: Duration,
    /// Camera rays.
    pub primary_rays: u64,
    /// All rays: camera, reflected, refracted and shadow rays.
    pub total_rays: u64,
    /// Pixels whose radiance was NaN or infinite, written as black (the scene's loader
    /// rejects the inputs known to cause them; this is the last line of defence).
    pub non_finite_pixels: u64,
    /// Samples whose radiance was NaN or infinite, counted as black (see
    /// [`PixelStats::non_finite_samples`]).
    pub non_finite_samples: u64,
    /// Pixels with a channel at f32's largest magnitude: an overflow the classic integrator
    /// saturated channel by channel (as POV-Ray writes an infinite channel) instead of
    /// counting the sample as black.
    pub saturated_pixels: u64,
    /// True when `RenderOptions::cancel` stopped the render before every tile was done.
    pub cancelled: bool,
    /// Samples per pixel over the rendered pixels: fewest, median, 90th percentile, most
    /// and mean (all equal to `samples` without adaptive sampling; 0 under POV-Ray's
    /// antialiasing methods, which count their own).
    pub samples: SampleSpread,
    /// Root mean square over the pixels of each pixel's estimated display error (see
    /// [`PixelStats::display_error`]); 0 when pixels took one sample each.
    pub noise: f64,
}

/// How many samples the pixels of a render took.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SampleSpread {
    /// Fewest.
    pub min: u32,
    /// Median.
    pub median: u32,
    /// 90th percentile.
    pub p90: u32,
    /// Most.
    pub max: u32,
    /// Mean.
    pub mean: f64,
}

impl SampleSpread {
    /// The spread of `counts` (sorted in place).
    pub fn of(counts: &mut [u32]) -> Self {
        if counts.is_empty() {
            return Self::default();
        }
        counts.sort_unstable();
        let at = |q: f64| counts[((counts.len() - 1) as f64 * q).round() as usize];
        let total: u64 = counts.iter().map(|&c| u64::from(c)).sum();
        Self { min: counts[0], median: at(0.5), p90: at(0.9), max: at(1.0), mean: total as f64 / counts.len() as f64 }
    }
}

impl RenderStats {
    /// Million rays per second over all rays.
    pub fn mrays_per_second(&self) -> f64 {
        self.total_rays as f64 / self.elapsed.as_secs_f64().max(1e-9) / 1e6
    }
}

/// Errors a render can stop with.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// The worker threads could not be started.
    #[error("cannot start {threads} render threads: {source}")]
    Threads {
        /// Requested thread count.
        threads: usize,
        /// The cause.
        source: rayon::ThreadPoolBuildError,
    },
    /// More threads than [`MAX_THREADS`] were asked for.
    #[error("--threads: {threads} is more than the limit of {MAX_THREADS}")]
    TooManyThreads {
        /// Requested thread count.
        threads: usize,
    },
    /// The film would not fit the memory budget.
    #[error(transparent)]
    OverBudget(#[from] OverBudget),
    /// The sample range is empty or goes beyond the scene's samples.
    #[error("--sample-range {}..{}: not a non-empty part of the scene's {samples} samples (0..{samples})", range.start, range.end)]
    SampleRange {
        /// The range asked for.
        range: Range<u32>,
        /// The scene's samples per pixel.
        samples: u32,
    },
    /// A sample range was asked of POV-Ray's antialiasing.
    #[error(
        "--sample-range: the scene uses POV-Ray's antialiasing (pov1/pov2), which picks each pixel's samples by comparing it with its neighbours, so its samples cannot be split; split the image with --region or --tile instead"
    )]
    SampleRangeWithPovAntialiasing,
    /// A sample range was asked of an adaptively sampled render.
    #[error(
        "--sample-range: the scene samples adaptively (`noise`), so each pixel decides from all its samples when to stop and its samples cannot be split; split the image with --region or --tile instead, or drop `noise`"
    )]
    SampleRangeWithNoise,
    /// A sample range was asked of a render with adaptive focal blur.
    #[error(
        "--sample-range: the scene's focal blur is adaptive (`blur_variance`), so each pixel decides from all its lens samples when to stop and its samples cannot be split; split the image with --region or --tile instead, or drop `blur_variance`"
    )]
    SampleRangeWithAdaptiveBlur,
    /// A sample range was asked of a classic render with an `assumed_gamma` other than 1.
    #[error(
        "--sample-range: the scene's assumed_gamma averages each pixel's samples in its working space before decoding them, so a pixel's samples cannot be split; split the image with --region or --tile instead, or render with assumed_gamma = 1"
    )]
    SampleRangeWithAssumedGamma,
    /// The region is empty or leaves the frame.
    #[error("region {x0},{y0},{x1},{y1} is not a non-empty part of the {width}x{height} image", x0 = region.x0, y0 = region.y0, x1 = region.x1, y1 = region.y1)]
    Region {
        /// The region asked for.
        region: Region,
        /// Frame width.
        width: u32,
        /// Frame height.
        height: u32,
    },
}

/// Renders the whole frame with the integrator the scene's settings name.
pub fn render_frame(scene: &RenderScene, options: &RenderOptions) -> Result<(Film, RenderStats), RenderError> {
    let region = Region::full(scene.settings.width, scene.settings.height);
    match scene.settings.integrator {
        IntegratorKind::Classic => render(scene, &classic(scene, options), region, options),
        IntegratorKind::Path => render(scene, &path(scene, options), region, options),
    }
}

/// The classic integrator for a render with `options`: first hits carry their uv when
/// the `uv` AOV is asked for.
pub fn classic<'a>(scene: &'a RenderScene, options: &RenderOptions) -> Classic<'a> {
    Classic::new(scene).with_first_hit_uv(options.aovs.contains(&Aov::Uv))
}

/// The path integrator for a render with `options`: first hits carry their uv when the
/// `uv` AOV is asked for.
pub fn path<'a>(scene: &'a RenderScene, options: &RenderOptions) -> Path<'a> {
    Path::new(scene).with_first_hit_uv(options.aovs.contains(&Aov::Uv))
}

/// A render that fits a time budget: what it made and how.
#[derive(Debug)]
pub struct BudgetedRender {
    /// The last complete pass's image: the image a render with its sample count gives.
    pub film: Film,
    /// That pass's stats.
    pub stats: RenderStats,
    /// Passes started (the last one may have been cut off by the budget and discarded).
    pub passes: u32,
    /// Wall time of all passes.
    pub elapsed: Duration,
}

/// Share of the remaining budget a pass is planned to fill (the rest absorbs the error of
/// predicting its time from the previous pass's).
const BUDGET_FILL: f64 = 0.9;

/// Renders the whole frame in passes of increasing sample count until `budget` runs out,
/// and returns the last pass that completed: exactly the image a render with that pass's
/// sample count gives. The first pass takes one sample per pixel and always completes;
/// each later pass takes as many samples as the previous pass's time per sample predicts
/// will fill `BUDGET_FILL` of the remaining time, at most `max_samples`. A pass the budget
/// cuts off is discarded. `scene`'s sample count is left at the returned pass's.
pub fn render_within(
    scene: &mut RenderScene,
    options: &RenderOptions,
    budget: Duration,
    max_samples: u32,
) -> Result<BudgetedRender, RenderError> {
    let start = Instant::now();
    let deadline = start + budget;
    let max_samples = max_samples.max(1);
    let pass = |scene: &mut RenderScene, samples: u32, passes: u32, deadline: Option<Instant>| {
        scene.set_samples(samples);
        let pass_options =
            RenderOptions { progress_prefix: format!("pass {passes} ({samples} spp) "), deadline, ..options.clone() };
        render_frame(scene, &pass_options)
    };
    // The first pass has no deadline, so there is an image (only `options.cancel` stops it).
    let (mut film, mut stats) = pass(scene, 1, 1, None)?;
    let (mut samples, mut passes) = (1, 1);
    let mut pass_time = start.elapsed().as_secs_f64();
    while !stats.cancelled && !options.cancel.as_ref().is_some_and(|c| c.load(Ordering::Relaxed)) {
        let remaining = deadline.saturating_duration_since(Instant::now()).as_secs_f64();
        let per_sample = pass_time / f64::from(samples);
        let next = (remaining * BUDGET_FILL / per_sample.max(1e-9)).floor().min(f64::from(max_samples)) as u32;
        if next <= samples {
            break;
        }
        let pass_start = Instant::now();
        passes += 1;
        let (next_film, next_stats) = pass(scene, next, passes, Some(deadline))?;
        if next_stats.cancelled {
            break;
        }
        (film, stats, samples) = (next_film, next_stats, next);
        pass_time = pass_start.elapsed().as_secs_f64();
    }
    scene.set_samples(samples);
    Ok(BudgetedRender { film, stats, passes, elapsed: start.elapsed() })
}

/// One tile's results: where it lies (full-frame pixels) and its pixels row by row.
struct TileResult {
    area: Region,
    /// The beauty, until it is written into the film (then empty).
    pixels: Vec<[f32; 3]>,
    first_hits: Vec<Option<FirstHit>>,
    /// Each pixel's sums, when asked for (stratified sampling only).
    sums: Vec<PixelSums>,
    /// Per pixel (empty under POV-Ray's antialiasing methods).
    estimates: Vec<PixelStats>,
}

/// What a pixel's samples say about its error.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PixelStats {
    /// Samples taken.
    pub samples: u32,
    /// Estimated variance of the mean radiance per channel (0 with one sample).
    pub variance: [f32; 3],
    /// Estimated error of the pixel as displayed: the standard deviation of the mean of its
    /// samples' displayed values (each channel after exposure and tone map, clipped to
    /// [0, 1], so in units of display white; root mean square over the channels), 0 with one
    /// sample. Adaptive sampling never stops a pixel above the
    /// `noise` target, and stops quiet pixels below it (see [`render_pixel_samples`]).
    pub display_error: f32,
    /// Samples whose radiance was NaN or infinite (overflow of extreme but accepted values),
    /// counted as black.
    pub non_finite_samples: u32,
}

/// Renders `region` of the frame with `integrator` into a film of that region.
pub fn render<I: Integrator>(
    scene: &RenderScene,
    integrator: &I,
    region: Region,
    options: &RenderOptions,
) -> Result<(Film, RenderStats), RenderError> {
    render_samples(scene, integrator, region, 0..scene.settings.samples, false, None, options)
        .map(|done| (done.film, done.stats))
}

/// What [`render_remaining`] rendered: a film of the whole frame in which only `tiles` were
/// rendered (the rest is black), and each rendered pixel's sample count (in no order).
#[derive(Debug)]
pub struct RemainingRender {
    /// The frame, black outside `tiles`.
    pub film: Film,
    /// The tiles rendered (full-frame pixels), each complete.
    pub tiles: Vec<Region>,
    /// Samples each rendered pixel took (empty under POV-Ray's antialiasing methods).
    pub sample_counts: Vec<u32>,
    /// What the render did.
    pub stats: RenderStats,
}

/// Renders every tile of the whole frame that has a pixel not yet `done` (one flag per
/// pixel, row-major), with the integrator the scene's settings name; tiles whose pixels are
/// all done are skipped, and `options.cancel` or `options.deadline` stop the render at the
/// next tile. Every rendered pixel is the pixel a full render gives (a pure function of
/// pixel, sample and seed): the scheduler of resumable renders ([`crate::checkpoint`]).
pub fn render_remaining(
    scene: &RenderScene,
    done: &[bool],
    options: &RenderOptions,
) -> Result<RemainingRender, RenderError> {
    let region = Region::full(scene.settings.width, scene.settings.height);
    let range = 0..scene.settings.samples;
    match scene.settings.integrator {
        IntegratorKind::Classic => {
            render_samples(scene, &classic(scene, options), region, range, false, Some(done), options)
        }
        IntegratorKind::Path => render_samples(scene, &path(scene, options), region, range, false, Some(done), options),
    }
    .map(|r| RemainingRender { film: r.film, tiles: r.tiles, sample_counts: r.sample_counts, stats: r.stats })
}

/// Renders samples `range` (of the scene's `0..samples`) of every pixel of `region`: a film
/// of their means, and each pixel's weighted sums (row-major over the region) for summing
/// with other ranges ([`crate::partial`]). Only stratified sampling has sample ranges:
/// POV-Ray's antialiasing decides where to sample by comparing neighbouring pixels.
pub fn render_sums<I: Integrator>(
    scene: &RenderScene,
    integrator: &I,
    region: Region,
    range: Range<u32>,
    options: &RenderOptions,
) -> Result<(Film, Vec<PixelSums>, RenderStats), RenderError> {
    render_samples(scene, integrator, region, range, true, None, options).map(|r| (r.film, r.sums, r.stats))
}

/// What [`render_samples`] made.
struct SampledRegion {
    film: Film,
    sums: Vec<PixelSums>,
    /// The tiles rendered (clipped to the region).
    tiles: Vec<Region>,
    /// Samples each rendered pixel took, in no order.
    sample_counts: Vec<u32>,
    stats: RenderStats,
}

/// Renders samples `range` of `region`, skipping tiles whose pixels are all `done` (flags
/// per pixel of the region, row-major).
fn render_samples<I: Integrator>(
    scene: &RenderScene,
    integrator: &I,
    region: Region,
    range: Range<u32>,
    want_sums: bool,
    done: Option<&[bool]>,
    options: &RenderOptions,
) -> Result<SampledRegion, RenderError> {
    let (width, height) = (scene.settings.width, scene.settings.height);
    if region.is_empty() || !region.fits(width, height) {
        return Err(RenderError::Region { region, width, height });
    }
    let samples = scene.settings.samples;
    if range.is_empty() || range.end > samples {
        return Err(RenderError::SampleRange { range, samples });
    }
    let pov_method = antialias::PovMethod::from_setting(scene.settings.antialias);
    if pov_method.is_some() && (want_sums || range != (0..samples)) {
        return Err(RenderError::SampleRangeWithPovAntialiasing);
    }
    if scene.settings.noise.is_some() && range != (0..samples) {
        return Err(RenderError::SampleRangeWithNoise);
    }
    if scene.focal_blur.is_some() && range != (0..samples) {
        return Err(RenderError::SampleRangeWithAdaptiveBlur);
    }
    if !integrator.working_gamma().is_neutral() && (want_sums || range != (0..samples)) {
        return Err(RenderError::SampleRangeWithAssumedGamma);
    }
    let threads = options.threads.unwrap_or(0);
    if threads > MAX_THREADS {
        return Err(RenderError::TooManyThreads { threads });
    }
    let channels: usize = 3 + options.aovs.iter().map(|a| a.channels().len()).sum::<usize>();
    let want_hits = options.aovs.iter().any(|a| a.needs_first_hit());
    // The film, the tiles' error estimates and, with first-hit AOVs, each pixel's first hit
    // (a tile's pixels go into the film as it is finished).
    let per_pixel = 12
        + if want_sums { 2 * std::mem::size_of::<PixelSums>() as u64 } else { 0 }
        + 4 * channels as u64
        + std::mem::size_of::<PixelStats>() as u64
        + 4
        + if want_hits { std::mem::size_of::<Option<FirstHit>>() as u64 } else { 0 };
    // POV-Ray's antialiasing works on whole 32 x 32 blocks of the frame, each one task; a
    // region renders every block it touches whole and keeps its part, so its pixels are
    // those of the full frame.
    let tile_size = if pov_method.is_some() { antialias::BLOCK_SIZE } else { TILE_SIZE };
    let (tx0, ty0) = (region.x0 / tile_size, region.y0 / tile_size);
    let (tx1, ty1) = (region.x1.div_ceil(tile_size), region.y1.div_ceil(tile_size));
    let estimate = u64::from(region.width()) * u64::from(region.height()) * per_pixel
        + if pov_method.is_some() { antialias::BorderSamples::bytes((tx0, ty0), (tx1, ty1)) } else { 0 };
    options.budget.check(|| format!("a {} x {} film", region.width(), region.height()), estimate)?;
    // The caller's rayon pool when it is the size asked for (the CLI sizes the global pool to
    // `--threads` for BVH builds and encoders), so that no second set of threads waits idle.
    let own_pool = if threads == 0 || threads == rayon::current_num_threads() {
        None
    } else {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .map_err(|source| RenderError::Threads { threads, source })?;
        Some(pool)
    };
    let workers = own_pool.as_ref().map_or_else(rayon::current_num_threads, |pool| pool.current_num_threads());
    let tiles_x = tx1 - tx0;
    let tile_count = u64::from(tiles_x) * u64::from(ty1 - ty0);
    let borders = pov_method.map(|method| antialias::BorderSamples::new(method, (tx0, ty0), (tx1, ty1)));

    let progress = if options.progress {
        let bar = ProgressBar::with_draw_target(Some(tile_count), ProgressDrawTarget::stderr());
        bar.set_style(
            ProgressStyle::with_template(
                "{prefix}{spinner} [{elapsed_precise}] {wide_bar} {percent:>3}% ETA {eta} {msg}",
            )
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
        );
        bar.set_prefix(options.progress_prefix.clone());
        bar
    } else {
        ProgressBar::hidden()
    };
    if let Some(hook) = &options.observer {
        hook.0.begin(region, (width, height));
    }
    // Running totals for the bar's message: pixels, samples and squared display errors.
    let running = std::sync::Mutex::new((0u64, 0u64, 0.0f64));

    let mut film = Film::for_region(region, (width, height), &options.aovs);
    let film_w = region.width() as usize;
    // Each band of the film's rows that a row of tiles covers, from its first row, with its
    // number of rows.
    let band_rows = |ty: u32| {
        let y0 = (ty * tile_size).max(region.y0);
        (y0, ((ty + 1) * tile_size).min(region.y1) - y0)
    };
    // The beauty goes into the film as each tile is finished, a band behind each lock: no
    // tile's pixels outlive its task (at 4K, 100 MB fewer pages to fault in) and none are
    // copied afterwards.
    let beauty: Vec<Mutex<BeautyBand>> = {
        let mut rest = film.pixels.as_mut_slice();
        (ty0..ty1)
            .map(|ty| {
                let (y0, rows) = band_rows(ty);
                let (pixels, tail) = std::mem::take(&mut rest).split_at_mut(rows as usize * film_w);
                rest = tail;
                let area = Region { x0: region.x0, y0, x1: region.x1, y1: y0 + rows };
                Mutex::new(BeautyBand { area, pixels, non_finite: 0, saturated: 0 })
            })
            .collect()
    };
    let rays = AtomicU64::new(0);
    let primary_rays = AtomicU64::new(0);
    let cancelled = AtomicBool::new(false);
    let start = Instant::now();
    // Each thread renders its own run of tiles, then helps with the others' (see
    // `tile_queue`).
    let queue = TileQueue::new(tile_count, workers);
    let render_one = |tile: u64| -> Option<TileResult> {
        if options.cancel.as_ref().is_some_and(|c| c.load(Ordering::Relaxed))
            || options.deadline.is_some_and(|d| Instant::now() >= d)
        {
            cancelled.store(true, Ordering::Relaxed);
            return None;
        }
        let tx = (tx0 + (tile % u64::from(tiles_x)) as u32) * tile_size;
        let ty = (ty0 + (tile / u64::from(tiles_x)) as u32) * tile_size;
        let area = Region { x0: tx, y0: ty, x1: (tx + tile_size).min(width), y1: (ty + tile_size).min(height) };
        if let Some(done) = done
            && all_done(done, region, area)
        {
            progress.inc(1);
            return None;
        }
        let (mut result, tile_rays, tile_primary) = match pov_method {
            Some(method) => {
                let block = antialias::render_block(scene, integrator, method, (tx, ty), borders.as_ref());
                let first_hits = if want_hits { centre_hits(scene, integrator, area) } else { Vec::new() };
                let tile =
                    TileResult { area, pixels: block.pixels, first_hits, sums: Vec::new(), estimates: Vec::new() };
                (tile, block.rays, block.primary_rays)
            }
            None => {
                let area = Region {
                    x0: area.x0.max(region.x0),
                    y0: area.y0.max(region.y0),
                    x1: area.x1.min(region.x1),
                    y1: area.y1.min(region.y1),
                };
                let (result, tile_rays) = render_tile(scene, integrator, area, &range, want_hits, want_sums);
                let primary = result.estimates.iter().map(|e| u64::from(e.samples)).sum();
                (result, tile_rays, primary)
            }
        };
        rays.fetch_add(tile_rays, Ordering::Relaxed);
        primary_rays.fetch_add(tile_primary, Ordering::Relaxed);
        if let Some(hook) = &options.observer {
            hook.0.tile(result.area, &result.pixels);
        }
        let band = &beauty[(result.area.y0 / tile_size - ty0) as usize];
        band.lock().unwrap_or_else(PoisonError::into_inner).write(result.area, &result.pixels);
        result.pixels = Vec::new();
        if options.progress && !result.estimates.is_empty() {
            let mut totals = running.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
            totals.0 += result.estimates.len() as u64;
            totals.1 += tile_primary;
            totals.2 += result.estimates.iter().map(|e| f64::from(e.display_error).powi(2)).sum::<f64>();
            let (pixels, samples, squares) = *totals;
            drop(totals);
            let pixels = pixels.max(1) as f64;
            progress.set_message(format!("{:.1} spp, noise {:.4}", samples as f64 / pixels, (squares / pixels).sqrt()));
        }
        progress.inc(1);
        Some(result)
    };
    let work = |worker: rayon::BroadcastContext<'_>| {
        let mut done_here = Vec::new();
        while let Some(tile) = queue.take(worker.index()) {
            if let Some(result) = render_one(tile) {
                done_here.push((tile, result));
            }
        }
        done_here
    };
    let per_worker = match &own_pool {
        Some(pool) => pool.broadcast(work),
        None => rayon::broadcast(work),
    };
    let mut tiles: Vec<(u64, TileResult)> = per_worker.into_iter().flatten().collect();
    // In raster order, as one loop over the tiles would give them.
    tiles.sort_unstable_by_key(|&(tile, _)| tile);
    let tiles: Vec<TileResult> = tiles.into_iter().map(|(_, result)| result).collect();
    progress.finish_and_clear();
    let elapsed = start.elapsed();
    let (mut non_finite, mut saturated) = (0, 0);
    for band in beauty {
        let band = band.into_inner().unwrap_or_else(PoisonError::into_inner);
        non_finite += band.non_finite;
        saturated += band.saturated;
    }

    let rendered_tiles = tiles.iter().map(|t| intersect(t.area, region)).collect();
    let mut sums = if want_sums { vec![PixelSums::default(); region.pixel_count()] } else { Vec::new() };
    // The tiles go into the film a row of tiles (a band of film rows) per task.
    let mut band_tiles: Vec<Vec<TileResult>> = (ty0..ty1).map(|_| Vec::new()).collect();
    for tile in tiles {
        band_tiles[(tile.area.y0 / tile_size - ty0) as usize].push(tile);
    }
    let mut bands = Vec::with_capacity(band_tiles.len());
    let (mut pixels, mut sums_left) = (film.pixels.as_mut_slice(), sums.as_mut_slice());
    let mut layers: Vec<(Aov, &mut [f32])> = film.layers.iter_mut().map(|l| (l.aov, l.data.as_mut_slice())).collect();
    for (ty, tiles) in (ty0..ty1).zip(band_tiles) {
        let (y0, rows) = band_rows(ty);
        let n = rows as usize * film_w;
        let (band_pixels, rest) = std::mem::take(&mut pixels).split_at_mut(n);
        pixels = rest;
        let (band_sums, rest) = std::mem::take(&mut sums_left).split_at_mut(if want_sums { n } else { 0 });
        sums_left = rest;
        let band_layers = layers
            .iter_mut()
            .map(|(aov, data)| {
                let (band, rest) = std::mem::take(data).split_at_mut(n * aov.channels().len());
                *data = rest;
                (*aov, band)
            })
            .collect();
        bands.push(FilmBand {
            area: Region { x0: region.x0, y0, x1: region.x1, y1: y0 + rows },
            pixels: band_pixels,
            sums: band_sums,
            layers: band_layers,
            tiles,
        });
    }
    let gather = || bands.into_par_iter().map(FilmBand::gather).collect();
    let gathered: Vec<Gathered> = match &own_pool {
        Some(pool) => pool.install(gather),
        None => gather(),
    };
    let mut non_finite_samples = 0;
    let mut counts = Vec::new();
    let mut squared_errors = 0.0;
    for band in gathered {
        non_finite_samples += band.non_finite_samples;
        counts.extend(band.counts);
        // Summed in pixel order, as one loop over the film would.
        squared_errors = band.display_errors.iter().fold(squared_errors, |sum, &e| sum + f64::from(e).powi(2));
    }
    let noise = if counts.is_empty() { 0.0 } else { (squared_errors / counts.len() as f64).sqrt() };
    let sample_counts = if done.is_some() { counts.clone() } else { Vec::new() };
    let stats = RenderStats {
        elapsed,
        primary_rays: primary_rays.load(Ordering::Relaxed),
        total_rays: rays.load(Ordering::Relaxed),
        cancelled: cancelled.load(Ordering::Relaxed),
        non_finite_pixels: non_finite,
        non_finite_samples,
        saturated_pixels: saturated,
        samples: SampleSpread::of(&mut counts),
        noise,
    };
    Ok(SampledRegion { film, sums, tiles: rendered_tiles, sample_counts, stats })
}

/// The pixels both rectangles cover.
fn intersect(a: Region, b: Region) -> Region {
    Region { x0: a.x0.max(b.x0), y0: a.y0.max(b.y0), x1: a.x1.min(b.x1), y1: a.y1.min(b.y1) }
}

/// True when every pixel of `area` inside `region` is flagged in `done` (row-major over
/// `region`).
fn all_done(done: &[bool], region: Region, area: Region) -> bool {
    let area = intersect(area, region);
    (area.y0..area.y1).all(|y| {
        let row = (y - region.y0) as usize * region.width() as usize;
        done[row + (area.x0 - region.x0) as usize..row + (area.x1 - region.x0) as usize].iter().all(|&d| d)
    })
}

fn render_tile<I: Integrator>(
    scene: &RenderScene,
    integrator: &I,
    area: Region,
    range: &Range<u32>,
    want_hits: bool,
    want_sums: bool,
) -> (TileResult, u64) {
    let mut pixels = Vec::with_capacity(area.pixel_count());
    let mut first_hits = Vec::with_capacity(if want_hits { area.pixel_count() } else { 0 });
    let mut sums = Vec::with_capacity(if want_sums { area.pixel_count() } else { 0 });
    let mut estimates = Vec::with_capacity(area.pixel_count());
    let mut rays = 0;
    for y in area.y0..area.y1 {
        for x in area.x0..area.x1 {
            let (pixel, pixel_sums, stats) = render_pixel_samples(scene, integrator, x, y, range.clone());
            if want_sums {
                sums.push(pixel_sums);
            }
            rays += pixel.rays;
            let rgb = pixel.radiance;
            pixels.push([rgb.x as f32, rgb.y as f32, rgb.z as f32]);
            if want_hits {
                first_hits.push(pixel.first_hit);
            }
            estimates.push(stats);
        }
    }
    (TileResult { area, pixels, first_hits, sums, estimates }, rays)
}

/// The first surfaces seen through the pixel centres of `area` (the AOVs of POV-Ray's
/// antialiasing modes, whose samples are placed by the image itself).
fn centre_hits<I: Integrator>(scene: &RenderScene, integrator: &I, area: Region) -> Vec<Option<FirstHit>> {
    let (width, height) = (f64::from(scene.settings.width), f64::from(scene.settings.height));
    let mut hits = Vec::with_capacity(area.pixel_count());
    for y in area.y0..area.y1 {
        for x in area.x0..area.x1 {
            let pixel = u64::from(y) * u64::from(scene.settings.width) + u64::from(x);
            let (x0, y0) = pov_screen(f64::from(x), f64::from(y), width, height);
            let ray = scene.camera.ray(x0, y0, DVec2::ZERO);
            hits.push(integrator.sample(&ray, SampleStream::new(pixel, 0, scene.settings.seed)).first_hit);
        }
    }
    hits
}

/// One row of tiles' band of the film's beauty, written as its tiles finish, with what the
/// writes found.
struct BeautyBand<'a> {
    area: Region,
    pixels: &'a mut [[f32; 3]],
    /// Pixels with a NaN or infinite channel, written black.
    non_finite: u64,
    /// Pixels with a channel saturated at `f32::MAX`.
    saturated: u64,
}

impl BeautyBand<'_> {
    /// Writes the pixels of a tile covering `area` (row-major) that lie in the band, a
    /// non-finite one as black.
    fn write(&mut self, area: Region, pixels: &[[f32; 3]]) {
        // A POV-Ray block can reach past the band (the region's edge): its part is kept.
        let inside = intersect(area, self.area);
        if inside.is_empty() {
            return;
        }
        let (tile_w, band_w, row_w) = (area.width() as usize, self.area.width() as usize, inside.width() as usize);
        for y in inside.y0..inside.y1 {
            let from = (y - area.y0) as usize * tile_w + (inside.x0 - area.x0) as usize;
            let to = (y - self.area.y0) as usize * band_w + (inside.x0 - self.area.x0) as usize;
            let row = &mut self.pixels[to..to + row_w];
            row.copy_from_slice(&pixels[from..from + row_w]);
            for pixel in row {
                if pixel.iter().all(|c| c.is_finite()) {
                    self.saturated += u64::from(pixel.iter().any(|c| c.abs() == f32::MAX));
                } else {
                    self.non_finite += 1;
                    *pixel = [0.0; 3];
                }
            }
        }
    }
}

/// One row of tiles' band of the film (its beauty already written): its pixels of the
/// frame, with the tiles that cover it.
struct FilmBand<'a> {
    area: Region,
    pixels: &'a mut [[f32; 3]],
    /// Empty unless sums were asked for.
    sums: &'a mut [PixelSums],
    layers: Vec<(Aov, &'a mut [f32])>,
    tiles: Vec<TileResult>,
}

/// What gathering a band found, in pixel order.
struct Gathered {
    non_finite_samples: u64,
    counts: Vec<u32>,
    display_errors: Vec<f32>,
}

impl FilmBand<'_> {
    /// Copies the tiles' sums and AOVs into the band.
    fn gather(mut self) -> Gathered {
        let mut found = Gathered { non_finite_samples: 0, counts: Vec::new(), display_errors: Vec::new() };
        let (band, width) = (self.area, self.area.width() as usize);
        for tile in std::mem::take(&mut self.tiles) {
            if self.sums.is_empty() && self.layers.is_empty() && tile.estimates.is_empty() {
                // Nothing beside the beauty (POV-Ray's antialiasing without AOVs).
                continue;
            }
            // The tile's part of the band, row by row (a POV-Ray block can reach past it).
            let inside = intersect(tile.area, band);
            let tile_w = tile.area.width() as usize;
            for y in inside.y0..inside.y1 {
                let tile_row = (y - tile.area.y0) as usize * tile_w;
                let band_row = (y - band.y0) as usize * width;
                for x in inside.x0..inside.x1 {
                    let i = tile_row + (x - tile.area.x0) as usize;
                    let index = band_row + (x - band.x0) as usize;
                    if !self.sums.is_empty() {
                        self.sums[index] = tile.sums[i];
                    }
                    let pixel = self.pixels[index];
                    let estimate = tile.estimates.get(i).copied().unwrap_or_default();
                    found.non_finite_samples += u64::from(estimate.non_finite_samples);
                    if !tile.estimates.is_empty() {
                        found.counts.push(estimate.samples);
                        found.display_errors.push(estimate.display_error);
                    }
                    write_aovs(
                        &mut self.layers,
                        index,
                        pixel,
                        tile.first_hits.get(i).and_then(Option::as_ref),
                        &estimate,
                    );
                }
            }
        }
        found
    }
}

/// Writes a pixel's beauty, first-hit data and error estimate into the AOV layers (of a
/// band of the film; `index` counts pixels within it).
fn write_aovs(
    layers: &mut [(Aov, &mut [f32])],
    index: usize,
    beauty: [f32; 3],
    hit: Option<&FirstHit>,
    estimate: &PixelStats,
) {
    for (aov, data) in layers {
        let n = aov.channels().len();
        let out = &mut data[index * n..(index + 1) * n];
        let values: [f64; 3] = match (*aov, hit) {
            (Aov::Albedo, Some(h)) => h.albedo.to_array(),
            (Aov::Normal, Some(h)) => h.normal.to_array(),
            (Aov::Position, Some(h)) => h.position.to_array(),
            (Aov::Depth, Some(h)) => [h.depth, 0.0, 0.0],
            (Aov::Depth, None) => [f64::from(f32::MAX), 0.0, 0.0],
            (Aov::Uv, Some(h)) => [h.uv.x, h.uv.y, 0.0],
            (Aov::ObjectId, Some(h)) => [f64::from(h.primitive), 0.0, 0.0],
            (Aov::MaterialId, Some(h)) => [f64::from(h.material), 0.0, 0.0],
            (Aov::ObjectId | Aov::MaterialId, None) => [-1.0, 0.0, 0.0],
            (Aov::Albedo | Aov::Normal | Aov::Position | Aov::Uv, None) => [0.0; 3],
            (Aov::Variance, _) => estimate.variance.map(f64::from),
            (Aov::Samples, _) => [f64::from(estimate.samples), 0.0, 0.0],
            (Aov::Raw, _) => beauty.map(f64::from),
        };
        for (o, v) in out.iter_mut().zip(values) {
            *o = finite_f32(v);
        }
    }
}

/// `value` as the nearest finite f32: beyond f32's range it saturates at `±f32::MAX` (a
/// variance of 1e60 from extreme but accepted radiance, for example); NaN becomes 0. No
/// infinity or NaN ever reaches a layer of a written file.
fn finite_f32(value: f64) -> f32 {
    if value.is_nan() { 0.0 } else { value.clamp(-f64::from(f32::MAX), f64::from(f32::MAX)) as f32 }
}

/// The mean of one pixel's samples: radiance, the first hit of its first sample that met a
/// surface, and the rays it took.
pub fn render_pixel<I: Integrator>(scene: &RenderScene, integrator: &I, x: u32, y: u32) -> PixelSample {
    render_pixel_samples(scene, integrator, x, y, 0..scene.settings.samples).0
}

/// The spread of a pixel's samples (Welford's running mean and sum of squared deviations,
/// per channel, in radiance and as displayed). The variance of the mean is the samples' variance over
/// their count: this ignores the gain of stratification, so it overestimates the error
/// where stratification helps (the pixel then takes more samples than it needs), but with
/// one degree of freedom per sample it is reliable from a few dozen samples on. (The
/// spread of the means of a few batches credits stratification but, with so few degrees
/// of freedom, often underestimates: pixels on a light's edge stopped at 32 samples with
/// an error of 18 %.)
///
/// The error adaptive sampling reads is that of the displayed values: each channel after
/// exposure and tone map, clipped to [0, 1] (the image's RMSE is measured over channels, and
/// a red wall's noise is mostly in its red channel, which luminance would weigh at 0.21); the
/// pixel's displayed variance is the mean of its three channels'. A light's pixels, all of
/// whose samples are brighter than white, are done at once, however large their variance in
/// radiance.
struct PixelSpread {
    count: u32,
    mean: DVec3,
    squares: DVec3,
    mean_shown: DVec3,
    squares_shown: f64,
    /// Exposure as a factor on radiance.
    exposure: f64,
    tone_map: ToneMap,
}

impl PixelSpread {
    fn new(settings: &crate::world::components::RenderSettings) -> Self {
        Self {
            count: 0,
            mean: DVec3::ZERO,
            squares: DVec3::ZERO,
            mean_shown: DVec3::ZERO,
            squares_shown: 0.0,
            exposure: settings.exposure.exp2(),
            tone_map: settings.tone_map,
        }
    }

    fn add(&mut self, radiance: DVec3) {
        self.count += 1;
        let n = f64::from(self.count);
        let delta = radiance - self.mean;
        self.mean += delta / n;
        self.squares += delta * (radiance - self.mean);
        let shown = (radiance * self.exposure).map(|c| crate::output::tone_map(c, self.tone_map).clamp(0.0, 1.0));
        let delta_shown = shown - self.mean_shown;
        self.mean_shown += delta_shown / n;
        self.squares_shown += (delta_shown * (shown - self.mean_shown)).element_sum() / 3.0;
    }

    /// Variance of the mean, per channel and of the displayed value (the mean over channels;
    /// 0 with fewer than two samples).
    fn variance_of_mean(&self) -> (DVec3, f64) {
        if self.count < 2 {
            return (DVec3::ZERO, 0.0);
        }
        let n = f64::from(self.count);
        (self.squares / (n * (n - 1.0)), self.squares_shown / (n * (n - 1.0)))
    }

    /// Standard deviation of the mean displayed value (root mean square over channels).
    fn display_error(&self) -> f64 {
        self.variance_of_mean().1.max(0.0).sqrt()
    }

    /// Whether the pixel has had its share of samples under adaptive sampling with target
    /// `noise`. For a given total, the image's mean squared error `sum(sigma_i^2 / n_i)` is
    /// smallest with `n_i` proportional to `sigma_i`, the standard deviation of pixel i's
    /// samples (Neyman's allocation; a Lagrange multiplier gives `sigma_i^2 / n_i^2` equal
    /// everywhere): so a pixel stops once `sigma / n` falls below a constant. Stopping every
    /// pixel at the same error instead costs exactly what uniform sampling costs at equal
    /// RMSE. The constant, `noise^2 / LARGEST_DISPLAY_DEVIATION`, makes the noisiest
    /// possible pixel stop at error `noise` and every other one below: the error at
    /// stopping is `sqrt(sigma * noise^2 / LARGEST_DISPLAY_DEVIATION)`.
    fn has_enough(&self, noise: f64) -> bool {
        if self.count < 2 {
            return false;
        }
        let n = f64::from(self.count);
        let deviation = (self.squares_shown / (n - 1.0)).max(0.0).sqrt();
        deviation / n <= noise * noise / LARGEST_DISPLAY_DEVIATION
    }
}

/// Samples `range` (of the scene's `0..samples`, so with the full render's patterns) of one
/// pixel: their weighted mean as [`render_pixel`] computes it, their weighted sum and
/// weights, accumulated in sample order from zero, and what they say about the pixel's
/// error. With `[render] noise` set and the whole range asked for, the pixel stops after the
/// first whole batch, from [`MIN_BATCHES`] on, after which it has had its share
/// (`PixelSpread::has_enough`: samples in proportion to the spread of its displayed values,
/// never stopping above the `noise` target); its offsets and lens positions are then a
/// progressive pattern ([`sampling::ProgressivePattern`]), stratified at whatever count it
/// stops. The decision depends on the pixel's own samples only, so the image is the same
/// for any thread count or tiling. Adaptive focal blur (`[camera] blur_variance`) stops a
/// pixel the same way at the batch ends of POV-Ray's rule ([`focal_blur::BlurTest`]), on the
/// same progressive pattern. (Sample ranges with either are refused before this.)
pub fn render_pixel_samples<I: Integrator>(
    scene: &RenderScene,
    integrator: &I,
    x: u32,
    y: u32,
    range: Range<u32>,
) -> (PixelSample, PixelSums, PixelStats) {
    let settings = &scene.settings;
    let (width, height) = (f64::from(settings.width), f64::from(settings.height));
    let pixel = u64::from(y) * u64::from(settings.width) + u64::from(x);
    let samples = settings.samples;
    // Per-pixel pattern keys decorrelate the stratified patterns of neighbouring pixels.
    let key = hash4(pixel, 0, u64::MAX, settings.seed);
    let adaptive_blur = scene.focal_blur.as_ref().filter(|_| range == (0..samples));
    let mut progressive = (samples > 1 && (settings.noise.is_some() || scene.focal_blur.is_some()))
        .then(|| sampling::ProgressivePattern::new(key));
    let mut blur_test = adaptive_blur.map(focal_blur::BlurSchedule::test);
    let patterns = (samples > 1 && progressive.is_none()).then(|| scene.patterns.for_key(key));
    let mut sum = DVec3::ZERO;
    let mut weights = 0.0;
    let mut rays = 0;
    let mut first_hit = None;
    let mut spread = PixelSpread::new(settings);
    let mut non_finite_samples = 0;
    let adaptive = settings.noise.filter(|_| range == (0..samples));
    let mut taken = range.len() as u32;
    let spread_wanted = taken > 1;
    let working = integrator.working_gamma();
    let keeps_nan_channels = integrator.keeps_nan_channels();
    for s in range {
        let stream = SampleStream::new(pixel, u64::from(s), settings.seed);
        if let Some(progressive) = &mut progressive {
            progressive.seek(s);
        }
        let mut offset = match (&progressive, &patterns) {
            (Some(progressive), _) => progressive.offset(),
            (None, Some(patterns)) => patterns.offset(s),
            (None, None) => DVec2::splat(0.5),
        };
        let mut weight = 1.0;
        if let Some(filter) = &scene.filter {
            let (from_centre, w) = filter.sample(offset);
            (offset, weight) = (from_centre + 0.5, w);
        }
        let lens = if scene.camera.aperture > 0.0 {
            match (&progressive, &patterns) {
                (Some(progressive), _) => progressive.lens(),
                (None, Some(patterns)) => patterns.lens(s),
                (None, None) => sampling::concentric_disc(stream.uniform2(2)),
            }
        } else {
            DVec2::ZERO
        };
        // POV-Ray's pixel coordinates put pixel centres at integers.
        let (x0, y0) = pov_screen(f64::from(x) + offset.x - 0.5, f64::from(y) + offset.y - 0.5, width, height);
        let ray = scene.camera.ray(x0, y0, lens);
        let sample = integrator.sample(&ray, stream);
        rays += sample.rays;
        first_hit = first_hit.or(sample.first_hit);
        // A kept NaN channel is 0 in this sample alone, as POV-Ray writes a single sample, so
        // that the sums stay finite (a part file holds them, and parts add up).
        let nan_kept = if keeps_nan_channels { sample.radiance.is_nan_mask() } else { BVec3::FALSE };
        let radiance = if (sample.radiance.is_finite_mask() | nan_kept).all() {
            DVec3::select(nan_kept, DVec3::ZERO, sample.radiance)
        } else {
            non_finite_samples += 1;
            DVec3::ZERO
        };
        // Box-filtered samples weigh 1, so their weighted mean is the plain mean, bit for bit.
        sum += weight * radiance;
        weights += weight;
        // The mean is taken in the integrator's working space (POV-Ray's), the error
        // estimates in linear light; a single sample has no spread to estimate (its variance
        // and display error are 0), and skips the tone map per sample.
        if spread_wanted {
            spread.add(gamma::decode_rgb(working, radiance));
        }
        if let Some(noise) = adaptive
            && (s + 1) % SAMPLE_BATCH == 0
            && s + 1 >= SAMPLE_BATCH * MIN_BATCHES
            && s + 1 < samples
            && spread.has_enough(noise)
        {
            taken = s + 1;
            break;
        }
        if let Some(test) = &mut blur_test
            && test.add(radiance)
        {
            taken = s + 1;
            break;
        }
    }
    // Weights summing to 0 (a filter's negative lobes cancelling) give black.
    let radiance = gamma::decode_rgb(working, if weights != 0.0 { sum / weights } else { DVec3::ZERO });
    let variance = spread.variance_of_mean().0;
    let stats = PixelStats {
        samples: taken,
        variance: [variance.x as f32, variance.y as f32, variance.z as f32],
        display_error: spread.display_error() as f32,
        non_finite_samples,
    };
    (PixelSample { radiance, first_hit, rays }, PixelSums { sum: sum.to_array(), weight: weights }, stats)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The `uv` AOV holds the first surface's uv whether or not its material is textured,
    /// under both integrators (shading reads the uv of textured materials only).
    #[test]
    fn the_uv_aov_holds_the_uv_of_untextured_surfaces() {
        use crate::scene::load::{Embedded, load_from};
        for integrator in ["classic", "path"] {
            let text = format!(
                "[render]\nwidth = 9\nheight = 9\nsamples = 4\nintegrator = \"{integrator}\"\n\
                 [camera]\nposition = [0.0, 0.0, 3.0]\nlook_at = [0.0, 0.0, 0.0]\nvfov = 30.0\n\
                 [[object]]\nshape = \"sphere\"\nradius = 1.0\nmaterial = {{ color = [0.5, 0.5, 0.5] }}\n\
                 [[light]]\nposition = [0.0, 0.0, 5.0]\n"
            );
            let text: &'static str = Box::leak(text.into_boxed_str());
            let files = Embedded(Box::leak(Box::new([("s.toml", text)])));
            let mut scene = load_from(&files, std::path::Path::new("s.toml"), &crate::plugins::registry()).unwrap();
            let scene = crate::prepare(&mut scene).unwrap();
            let options = RenderOptions { aovs: vec![Aov::Uv], ..Default::default() };
            let (film, _) = render_frame(&scene, &options).unwrap();
            let uv = &film.layer(Aov::Uv).unwrap().data;
            // The sphere's uv where the centre pixel's ray meets it, as its shape gives it;
            // path's first sample lies somewhere in the pixel (a pixel spans about 0.03 in u).
            let ray = prism_api::Ray::new(DVec3::new(0.0, 0.0, 3.0), DVec3::NEG_Z);
            let primitive = &scene.primitives[0];
            let hit = primitive.shape.intersect(&ray, 0.0, f64::MAX).unwrap();
            let expected = primitive.shape.surface(&ray, &hit).uv;
            let centre = 4 * 9 + 4;
            let got = DVec2::new(f64::from(uv[2 * centre]), f64::from(uv[2 * centre + 1]));
            assert!(expected.x > 0.1 && expected.y > 0.1, "{expected}");
            assert!((got - expected).abs().max_element() < 0.05, "{integrator}: {got} against {expected}");
        }
    }

    /// Feeds `value(i)` (a grey radiance) to a fresh spread until `has_enough(noise)`, checked
    /// after every batch from the first check on as `render_pixel_samples` does; returns the
    /// count and the spread.
    fn samples_until_enough(noise: f64, limit: u32, value: impl Fn(u32) -> f64) -> (u32, PixelSpread) {
        let mut spread = PixelSpread::new(&crate::world::components::RenderSettings::default());
        for i in 0..limit {
            spread.add(DVec3::splat(value(i)));
            let n = i + 1;
            if n % SAMPLE_BATCH == 0 && n >= SAMPLE_BATCH * MIN_BATCHES && spread.has_enough(noise) {
                return (n, spread);
            }
        }
        (limit, spread)
    }

    /// Two-valued samples: `low` and `high` alternating, so the spread is known exactly.
    fn alternating(low: f64, high: f64) -> impl Fn(u32) -> f64 {
        move |i| if i % 2 == 0 { low } else { high }
    }

    #[test]
    fn a_pixel_without_spread_stops_at_the_first_check() {
        let (n, _) = samples_until_enough(0.01, 1 << 16, |_| 0.4);
        assert_eq!(n, SAMPLE_BATCH * MIN_BATCHES);
        // Brighter than white: every displayed value is 1.
        let (n, _) = samples_until_enough(0.01, 1 << 16, alternating(3.0, 50.0));
        assert_eq!(n, SAMPLE_BATCH * MIN_BATCHES);
    }

    /// Neyman's allocation: samples in proportion to the spread, so a pixel twice as noisy
    /// takes twice the samples (not four times, as an equal-error rule would give it).
    #[test]
    fn samples_grow_in_proportion_to_the_spread() {
        let noise = 0.01;
        let (quiet, _) = samples_until_enough(noise, 1 << 20, alternating(0.4, 0.5));
        let (noisy, _) = samples_until_enough(noise, 1 << 20, alternating(0.3, 0.5));
        let ratio = f64::from(noisy) / f64::from(quiet);
        assert!((ratio - 2.0).abs() < 0.1, "{noisy} against {quiet} samples: ratio {ratio}");
    }

    /// The displayed error is the root mean square over channels: a pixel whose red channel
    /// alone alternates between 0 and 1 has a per-sample spread of sqrt(1/4 / 3), not the
    /// 0.21 / 2 of its luminance, so it takes 2.7 times the samples a luminance rule gives it.
    #[test]
    fn the_spread_is_measured_per_channel() {
        let mut spread = PixelSpread::new(&crate::world::components::RenderSettings::default());
        let n = 64;
        for i in 0..n {
            spread.add(if i % 2 == 0 { DVec3::ZERO } else { DVec3::X });
        }
        let per_sample = spread.display_error() * f64::from(n).sqrt();
        let expected = (0.25 * f64::from(n) / f64::from(n - 1) / 3.0).sqrt();
        assert!((per_sample - expected).abs() < 1e-12, "{per_sample} against {expected}");
    }

    /// The noisiest pixel possible (displayed values 0 and 1, standard deviation 1/2) stops
    /// at the target error, and a quieter one below it.
    #[test]
    fn no_pixel_stops_above_the_target() {
        let noise = 0.02;
        for (low, high) in [(0.0, 1.0), (0.0, 0.6), (0.45, 0.55), (0.2, 0.3)] {
            let (n, spread) = samples_until_enough(noise, 1 << 20, alternating(low, high));
            let error = spread.display_error();
            assert!(error <= noise * 1.0001, "values {low} and {high}: error {error} after {n} samples");
            if high - low == 1.0 {
                assert!(error > 0.95 * noise, "the noisiest pixel stops at the target: {error}");
            }
        }
    }
}
