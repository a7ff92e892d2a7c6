//! Checkpoints: the state of an unfinished render, saved so that it can be resumed and end
//! in exactly the image an uninterrupted render makes.
//!
//! A render with checkpoints renders the frame tile by tile, as any render does, and keeps
//! which pixels are finished. A checkpoint file is a [`crate::partial`] part of the whole
//! frame holding every finished pixel's final value (beauty and AOV layers, f32, exactly as
//! the film holds them) and, in its `samples` channel, the scene's samples per pixel for a
//! finished pixel and 0 for one still to render; its header keeps the scene's fingerprint
//! and the scene itself as `prism save` writes it, so a checkpoint of another scene or
//! other settings is refused with the first setting that differs.
//!
//! The unit of work is the tile: each finished pixel is already the full render's pixel
//! (every pixel is a pure function of pixel, sample and seed), so resuming renders only the
//! tiles left and the result is bit-identical for any interruption, thread count or number
//! of resumes. This holds for adaptive sampling (a pixel decides from its own samples) and
//! for POV-Ray's antialiasing (whose 32 x 32 blocks are the tiles).
//!
//! A checkpoint is tied to its sample count: the stratified sample patterns are made for
//! the render's `samples` (sample `s` of a 16-sample pixel is not sample `s` of a 64-sample
//! one), so a render to another count is another render, and resuming refuses it.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use crate::film::{Aov, Film, Region};
use crate::partial::{Fingerprint, PartInfo, Partial, PartialError, Sampling};
use crate::render::extract::RenderScene;
use crate::render::{RenderError, RenderOptions, RenderStats, SampleSpread, render_remaining};
use crate::world::Scene;
use crate::world::components::Antialias;

/// The state of a render: the frame so far and which of its pixels are finished.
#[derive(Clone, Debug, PartialEq)]
pub struct Checkpoint {
    /// What is rendered: scene, settings, frame, samples per pixel (the region is the frame).
    pub info: PartInfo,
    /// The whole frame; finished pixels hold their final values, the others black.
    pub film: Film,
    /// One flag per pixel, row-major: finished.
    pub done: Vec<bool>,
}

/// Why a checkpoint cannot be resumed (or written).
#[derive(Debug, thiserror::Error)]
pub enum CheckpointError {
    /// The file is not a readable part.
    #[error(transparent)]
    Part(#[from] PartialError),
    /// A readable part that is not a checkpoint of a whole frame.
    #[error("{}: not a checkpoint: {what}", crate::files::shown_path(.path))]
    NotACheckpoint {
        /// The file.
        path: PathBuf,
        /// What is wrong.
        what: String,
    },
    /// The render asks for fewer samples per pixel than the checkpoint's pixels already hold.
    #[error(
        "{}: its finished pixels already hold {done} samples each; --samples {asked} is below that (resume with --samples {done}, the count the checkpoint was started with)",
        crate::files::shown_path(.path)
    )]
    SamplesBelowDone {
        /// The file.
        path: PathBuf,
        /// Samples per finished pixel.
        done: u32,
        /// Samples per pixel of this render.
        asked: u32,
    },
    /// The render asks for more samples per pixel than the checkpoint was started with.
    #[error(
        "{}: the checkpoint renders {target} samples per pixel, this render {asked}; its sample patterns are made for {target} samples (a pixel's first {target} samples of a {asked}-sample render are other samples), so it can only continue to {target}: resume with --samples {target}, or start a new render",
        crate::files::shown_path(.path)
    )]
    OtherSampleCount {
        /// The file.
        path: PathBuf,
        /// The checkpoint's samples per pixel.
        target: u32,
        /// Samples per pixel of this render.
        asked: u32,
    },
    /// The scene or a setting differs from the checkpoint's.
    #[error(
        "{}: a checkpoint of another scene or other settings: `{key}` is {checkpoint} in the checkpoint but {current} in this render; resume with the scene and options the checkpoint was started with",
        crate::files::shown_path(.path)
    )]
    OtherSettings {
        /// The file.
        path: PathBuf,
        /// The differing key path (`render.seed`, `object[2].radius`...).
        key: String,
        /// Its value in the checkpoint (or `absent`).
        checkpoint: String,
        /// Its value in this render (or `absent`).
        current: String,
    },
    /// Same scene and settings, another fingerprint: another version of Prism wrote it.
    #[error(
        "{}: written by another version of Prism (the scene and settings are the same, the fingerprint is not); its pixels may differ from this version's, so render anew",
        crate::files::shown_path(.path)
    )]
    OtherVersion {
        /// The file.
        path: PathBuf,
    },
    /// The scene cannot be written as text (for the fingerprint).
    #[error("cannot write the scene for the checkpoint's fingerprint: {0}")]
    Save(#[from] toml::ser::Error),
}

impl Checkpoint {
    /// A render of `scene` (after command-line overrides, before [`crate::prepare`]) with
    /// nothing finished, gathering `aovs`.
    pub fn new(scene: &Scene, aovs: &[Aov]) -> Result<Self, CheckpointError> {
        let text = crate::scene::save::save(scene)?;
        let settings = &scene.render;
        let (width, height) = (settings.width, settings.height);
        let pov = !matches!(settings.antialias, Antialias::Stratified {});
        let info = PartInfo {
            fingerprint: Fingerprint::of_scene(scene)?,
            frame: (width, height),
            region: Region::full(width, height),
            samples: 0..settings.samples,
            total_samples: settings.samples,
            tile: None,
            sampling: if pov { Sampling::Pov } else { Sampling::Stratified },
            exposure: settings.exposure,
            tone_map: settings.tone_map,
            scene: Some(text),
        };
        let film = Film::for_region(info.region, info.frame, aovs);
        let done = vec![false; info.region.pixel_count()];
        Ok(Self { info, film, done })
    }

    /// True when every pixel is finished.
    pub fn is_complete(&self) -> bool {
        self.done.iter().all(|&d| d)
    }

    /// Finished pixels.
    pub fn pixels_done(&self) -> usize {
        self.done.iter().filter(|&&d| d).count()
    }

    /// The checkpoint as a part: finished pixels hold all samples, the others none.
    pub fn to_partial(&self) -> Partial {
        let total = self.info.total_samples;
        Partial {
            info: self.info.clone(),
            radiance: self.film.pixels.clone(),
            sample_counts: self.done.iter().map(|&d| if d { total } else { 0 }).collect(),
            sums: None,
            layers: self.film.layers.clone(),
        }
    }

    /// The checkpoint file's bytes (deterministic).
    pub fn encode(&self) -> Result<Vec<u8>, exr::error::Error> {
        self.to_partial().encode()
    }

    /// Reads the checkpoint at `path` and takes its finished pixels into `self` (a fresh
    /// state of this render), after checking that it is a checkpoint of the same scene,
    /// settings and sample count. On an error `self` is unchanged.
    pub fn resume_from(&mut self, access: &crate::files::FileAccess, path: &Path) -> Result<(), CheckpointError> {
        let part = Partial::read(access, path)?;
        self.take(part, path)
    }

    fn take(&mut self, part: Partial, path: &Path) -> Result<(), CheckpointError> {
        let not = |what: &str| CheckpointError::NotACheckpoint { path: path.to_path_buf(), what: what.into() };
        let info = &part.info;
        let Some(scene) = &info.scene else {
            return Err(not("it keeps no scene (a part of a farm render? those are merged with `prism merge`)"));
        };
        if info.region != Region::full(info.frame.0, info.frame.1) || !info.has_all_samples() || part.sums.is_some() {
            return Err(not("it is not a whole frame of finished and unstarted pixels"));
        }
        let (target, asked) = (info.total_samples, self.info.total_samples);
        if asked < target {
            return Err(CheckpointError::SamplesBelowDone { path: path.to_path_buf(), done: target, asked });
        }
        if asked > target {
            return Err(CheckpointError::OtherSampleCount { path: path.to_path_buf(), target, asked });
        }
        if info.fingerprint != self.info.fingerprint {
            let current = self.info.scene.as_deref().unwrap_or_default();
            return Err(match first_difference(scene, current) {
                Some((key, checkpoint, current)) => {
                    CheckpointError::OtherSettings { path: path.to_path_buf(), key, checkpoint, current }
                }
                None => CheckpointError::OtherVersion { path: path.to_path_buf() },
            });
        }
        // Equal fingerprints: same frame, sampling and settings.
        if let Some(count) = part.sample_counts.iter().find(|&&c| c != 0 && c != target) {
            return Err(not(&format!(
                "channel `samples` holds {count}, neither 0 (to render) nor {target} (finished)"
            )));
        }
        let mut layers = Vec::with_capacity(self.film.layers.len());
        for wanted in &self.film.layers {
            let layer = part
                .layers
                .iter()
                .find(|l| l.aov == wanted.aov)
                .ok_or_else(|| not(&format!("it lacks the `{}` layer this render gathers", wanted.aov.name())))?;
            layers.push(layer.clone());
        }
        self.done = part.sample_counts.iter().map(|&c| c != 0).collect();
        self.film.pixels = part.radiance;
        self.film.layers = layers;
        Ok(())
    }

    /// Copies `tiles` of `film` (a film of the whole frame with this state's layers) into
    /// the state and marks their pixels finished.
    fn absorb(&mut self, film: &Film, tiles: &[Region]) {
        let width = self.film.width as usize;
        for tile in tiles {
            for y in tile.y0..tile.y1 {
                let row = y as usize * width;
                let (a, b) = (row + tile.x0 as usize, row + tile.x1 as usize);
                self.film.pixels[a..b].copy_from_slice(&film.pixels[a..b]);
                self.done[a..b].fill(true);
                for (mine, theirs) in self.film.layers.iter_mut().zip(&film.layers) {
                    let n = mine.channel_count();
                    mine.data[a * n..b * n].copy_from_slice(&theirs.data[a * n..b * n]);
                }
            }
        }
    }
}

/// How a resumable render ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// Every pixel is finished.
    Complete,
    /// `options.cancel` stopped it; the finished tiles are in the state.
    Interrupted,
}

/// What [`render_resumable`] did in this run.
#[derive(Debug)]
pub struct ResumableRun {
    /// Complete or interrupted.
    pub outcome: Outcome,
    /// The stats of the pixels this run rendered (times, rays and the sample spread summed
    /// over its rounds).
    pub stats: RenderStats,
    /// Checkpoints saved on the way (by `save`, each interval).
    pub saves: u32,
}

/// Renders the tiles of `state` that are not finished, handing the state to `save` every
/// `interval` (at the first tile boundary after it), until every pixel is finished or
/// `options.cancel` is set. Rendered pixels are exactly those of an uninterrupted render.
/// `save` is not called for the end state: the caller writes it with the image.
pub fn render_resumable<E: From<RenderError>>(
    scene: &RenderScene,
    state: &mut Checkpoint,
    options: &RenderOptions,
    interval: Option<Duration>,
    mut save: impl FnMut(&Checkpoint) -> Result<(), E>,
) -> Result<ResumableRun, E> {
    let mut interval = interval;
    let mut stats = RenderStats::default();
    let mut counts = Vec::new();
    let mut squared_errors = 0.0;
    let mut saves = 0;
    let cancelled = || options.cancel.as_ref().is_some_and(|c| c.load(std::sync::atomic::Ordering::Relaxed));
    loop {
        if state.is_complete() {
            break;
        }
        let round = RenderOptions { deadline: interval.map(|i| Instant::now() + i), ..options.clone() };
        let rendered = render_remaining(scene, &state.done, &round)?;
        state.absorb(&rendered.film, &rendered.tiles);
        let r = &rendered.stats;
        stats.elapsed += r.elapsed;
        stats.primary_rays += r.primary_rays;
        stats.total_rays += r.total_rays;
        stats.non_finite_pixels += r.non_finite_pixels;
        stats.non_finite_samples += r.non_finite_samples;
        stats.saturated_pixels += r.saturated_pixels;
        squared_errors += r.noise * r.noise * rendered.sample_counts.len() as f64;
        counts.extend_from_slice(&rendered.sample_counts);
        if state.is_complete() {
            break;
        }
        if cancelled() {
            stats.cancelled = true;
            break;
        }
        if rendered.tiles.is_empty() {
            // An interval too short for any tile to start: lengthen it.
            interval = interval.map(|i| (i * 2).max(Duration::from_millis(1)));
            continue;
        }
        save(state)?;
        saves += 1;
    }
    stats.noise = if counts.is_empty() { 0.0 } else { (squared_errors / counts.len() as f64).sqrt() };
    stats.samples = SampleSpread::of(&mut counts);
    let outcome = if state.is_complete() { Outcome::Complete } else { Outcome::Interrupted };
    Ok(ResumableRun { outcome, stats, saves })
}

/// The first key (in the order of `a`, then keys only `b` has) whose value differs between
/// two scene texts, with both values (`absent` where a key is missing, shortened to 60
/// characters). `None` when the texts are equal as TOML (or either is not TOML).
pub fn first_difference(a: &str, b: &str) -> Option<(String, String, String)> {
    let a: toml::Value = toml::from_str::<toml::Table>(a).ok()?.into();
    let b: toml::Value = toml::from_str::<toml::Table>(b).ok()?.into();
    difference(Some(&a), Some(&b), String::new())
}

fn difference(a: Option<&toml::Value>, b: Option<&toml::Value>, path: String) -> Option<(String, String, String)> {
    use toml::Value;
    let shown = |v: Option<&Value>| match v {
        None => "absent".to_string(),
        Some(v) => {
            let text = v.to_string();
            if text.chars().count() > 60 { format!("{}...", text.chars().take(57).collect::<String>()) } else { text }
        }
    };
    let join = |key: &str| if path.is_empty() { key.to_string() } else { format!("{path}.{key}") };
    match (a, b) {
        (Some(Value::Table(ta)), Some(Value::Table(tb))) => {
            let keys = ta.keys().chain(tb.keys().filter(|k| !ta.contains_key(*k)));
            keys.into_iter().find_map(|k| difference(ta.get(k), tb.get(k), join(k)))
        }
        (Some(Value::Array(xa)), Some(Value::Array(xb))) => {
            (0..xa.len().max(xb.len())).find_map(|i| difference(xa.get(i), xb.get(i), format!("{path}[{i}]")))
        }
        (a, b) if a == b => None,
        (a, b) => Some((path, shown(a), shown(b))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::load::{Embedded, load_from};

    fn scene(text: &'static str) -> Scene {
        let files: &'static [(&'static str, &'static str)] = Box::leak(Box::new([("s.toml", text)]));
        load_from(&Embedded(files), Path::new("s.toml"), &crate::plugins::registry()).unwrap()
    }

    const SCENE: &str = "[render]\nwidth = 8\nheight = 6\nsamples = 4\n[[object]]\nshape = \"sphere\"\nradius = 0.5\n";

    #[test]
    fn the_first_differing_key_is_named() {
        let a = "[render]\nseed = 1\n[[object]]\nshape = \"sphere\"\n[[object]]\nradius = 2\n";
        let b = "[render]\nseed = 1\n[[object]]\nshape = \"sphere\"\n[[object]]\nradius = 3\n";
        assert_eq!(first_difference(a, b), Some(("object[1].radius".into(), "2".into(), "3".into())));
        assert_eq!(first_difference(a, a), None);
        let c = "[render]\nseed = 1\nnoise = 0.1\n";
        let d = "[render]\nseed = 1\n";
        assert_eq!(first_difference(c, d), Some(("render.noise".into(), "0.1".into(), "absent".into())));
        assert_eq!(first_difference(d, c), Some(("render.noise".into(), "absent".into(), "0.1".into())));
    }

    /// A checkpoint round-trips through its file, and resuming it names what differs.
    #[test]
    fn resuming_checks_scene_samples_and_layers() {
        let base = scene(SCENE);
        let mut state = Checkpoint::new(&base, &[Aov::Depth]).unwrap();
        let tile = Region { x0: 0, y0: 0, x1: 8, y1: 3 };
        let mut film = state.film.clone();
        film.pixels.iter_mut().for_each(|p| *p = [0.5, 0.25, 1.0]);
        film.layers[0].data.iter_mut().for_each(|d| *d = 2.0);
        state.absorb(&film, &[tile]);
        assert_eq!(state.pixels_done(), 24);
        let bytes = state.encode().unwrap();
        let part = Partial::decode(&bytes, Path::new("c.exr")).unwrap();

        let mut fresh = Checkpoint::new(&base, &[Aov::Depth]).unwrap();
        fresh.take(part.clone(), Path::new("c.exr")).unwrap();
        assert_eq!(fresh, state);

        let mut seeded = scene(SCENE);
        seeded.render.seed = 7;
        let error = Checkpoint::new(&seeded, &[Aov::Depth]).unwrap().take(part.clone(), Path::new("c.exr"));
        let error = error.unwrap_err().to_string();
        assert!(error.contains("`render.seed` is 0 in the checkpoint but 7 in this render"), "{error}");

        for (samples, expect) in [(2, "already hold 4 samples each; --samples 2"), (8, "renders 4 samples per pixel")] {
            let mut other = scene(SCENE);
            other.render.samples = samples;
            let error = Checkpoint::new(&other, &[Aov::Depth]).unwrap().take(part.clone(), Path::new("c.exr"));
            assert!(error.unwrap_err().to_string().contains(expect), "{samples}");
        }

        let mut farm = part.clone();
        farm.info.scene = None;
        let error = Checkpoint::new(&base, &[Aov::Depth]).unwrap().take(farm, Path::new("c.exr"));
        assert!(error.unwrap_err().to_string().contains("not a checkpoint"));
        let mut odd = part;
        odd.sample_counts[30] = 3;
        let error = Checkpoint::new(&base, &[Aov::Depth]).unwrap().take(odd, Path::new("c.exr"));
        assert!(error.unwrap_err().to_string().contains("channel `samples` holds 3"));
    }
}
