//! `render`: tiles in parallel (rayon); each pixel's samples depend only on
//! (pixel, sample, dimension, seed), so the image is bit-identical for any thread count.

pub mod antialias;
pub mod camera;
pub mod extract;
pub mod integrators;
pub mod lights;
pub mod sampling;

use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

use glam::{DVec2, DVec3};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use rayon::prelude::*;

use crate::film::Film;
use camera::pov_screen;
use extract::RenderScene;
use integrators::classic::{Classic, PathState};
use sampling::{SampleStream, hash4};

/// Side of a square render tile in pixels.
pub const TILE_SIZE: u32 = 16;

/// How to run a render.
#[derive(Clone, Debug, Default)]
pub struct RenderOptions {
    /// Worker threads (`None`: one per core).
    pub threads: Option<usize>,
    /// Draw a progress bar on stderr (only when stderr is a terminal).
    pub progress: bool,
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
}

/// Renders the scene into a film.
pub fn render(scene: &RenderScene, options: &RenderOptions) -> Result<(Film, RenderStats), RenderError> {
    let threads = options.threads.unwrap_or(0);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|source| RenderError::Threads { threads, source })?;
    let (width, height) = (scene.settings.width, scene.settings.height);
    // POV-Ray's antialiasing works on whole 32 x 32 blocks, each one task.
    let pov_method = antialias::PovMethod::from_setting(scene.settings.antialias);
    let tile_size = if pov_method.is_some() { antialias::BLOCK_SIZE } else { TILE_SIZE };
    let tiles_x = width.div_ceil(tile_size);
    let tiles_y = height.div_ceil(tile_size);
    let tile_count = u64::from(tiles_x) * u64::from(tiles_y);

    let progress = if options.progress {
        let bar = ProgressBar::with_draw_target(Some(tile_count), ProgressDrawTarget::stderr());
        bar.set_style(
            ProgressStyle::with_template("{spinner} [{elapsed_precise}] {wide_bar} {percent:>3}% ETA {eta}")
                .unwrap_or_else(|_| ProgressStyle::default_bar()),
        );
        bar
    } else {
        ProgressBar::hidden()
    };

    let rays = AtomicU64::new(0);
    let primary_rays = AtomicU64::new(0);
    let start = Instant::now();
    let integrator = Classic::new(scene);
    let tiles: Vec<(u32, u32, Vec<[f32; 3]>)> = pool.install(|| {
        (0..tile_count)
            .into_par_iter()
            .map(|tile| {
                let tx = (tile % u64::from(tiles_x)) as u32 * tile_size;
                let ty = (tile / u64::from(tiles_x)) as u32 * tile_size;
                let (pixels, tile_rays, tile_primary) = match pov_method {
                    Some(method) => {
                        let block = antialias::render_block(scene, &integrator, method, tx, ty);
                        (block.pixels, block.rays, block.primary_rays)
                    }
                    None => {
                        let (pixels, tile_rays) = render_tile(scene, &integrator, tx, ty);
                        let primary = pixels.len() as u64 * u64::from(scene.settings.samples);
                        (pixels, tile_rays, primary)
                    }
                };
                rays.fetch_add(tile_rays, Ordering::Relaxed);
                primary_rays.fetch_add(tile_primary, Ordering::Relaxed);
                progress.inc(1);
                (tx, ty, pixels)
            })
            .collect()
    });
    progress.finish_and_clear();
    let elapsed = start.elapsed();

    let mut film = Film::new(width, height);
    for (tx, ty, pixels) in tiles {
        let tile_w = tile_size.min(width - tx);
        for (i, p) in pixels.into_iter().enumerate() {
            let x = tx + i as u32 % tile_w;
            let y = ty + i as u32 / tile_w;
            film.pixels[y as usize * width as usize + x as usize] = p;
        }
    }
    let stats = RenderStats {
        elapsed,
        primary_rays: primary_rays.load(Ordering::Relaxed),
        total_rays: rays.load(Ordering::Relaxed),
    };
    Ok((film, stats))
}

fn render_tile(scene: &RenderScene, integrator: &Classic, tx: u32, ty: u32) -> (Vec<[f32; 3]>, u64) {
    let (width, height) = (scene.settings.width, scene.settings.height);
    let tile_w = TILE_SIZE.min(width - tx);
    let tile_h = TILE_SIZE.min(height - ty);
    let mut out = Vec::with_capacity((tile_w * tile_h) as usize);
    let mut rays = 0;
    for y in ty..ty + tile_h {
        for x in tx..tx + tile_w {
            let (rgb, pixel_rays) = render_pixel(scene, integrator, x, y);
            rays += pixel_rays;
            out.push([rgb.x as f32, rgb.y as f32, rgb.z as f32]);
        }
    }
    (out, rays)
}

/// The mean radiance of one pixel and the rays it took.
pub fn render_pixel(scene: &RenderScene, integrator: &Classic, x: u32, y: u32) -> (DVec3, u64) {
    let settings = &scene.settings;
    let (width, height) = (f64::from(settings.width), f64::from(settings.height));
    let pixel = u64::from(y) * u64::from(settings.width) + u64::from(x);
    let samples = settings.samples;
    // Per-pixel pattern keys decorrelate the stratified patterns of neighbouring pixels.
    let patterns = (samples > 1).then(|| scene.patterns.for_key(hash4(pixel, 0, u64::MAX, settings.seed)));
    let mut sum = DVec3::ZERO;
    let mut rays = 0;
    for s in 0..samples {
        let stream = SampleStream::new(pixel, u64::from(s), settings.seed);
        let offset = patterns.as_ref().map_or(DVec2::splat(0.5), |p| p.offset(s));
        let lens = if scene.camera.aperture > 0.0 {
            patterns.as_ref().map_or_else(|| sampling::concentric_disc(stream.uniform2(2)), |p| p.lens(s))
        } else {
            DVec2::ZERO
        };
        // POV-Ray's pixel coordinates put pixel centres at integers.
        let (x0, y0) = pov_screen(f64::from(x) + offset.x - 0.5, f64::from(y) + offset.y - 0.5, width, height);
        let ray = scene.camera.ray(x0, y0, lens);
        let mut state = PathState { stream, dimension: 4, rays: 0 };
        sum += integrator.radiance(&ray, &mut state);
        rays += state.rays;
    }
    (sum / f64::from(samples), rays)
}
