//! The `prism` command line.

use std::io::{IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{Args, Parser, Subcommand};
use prism::diagnostics::{Diagnostic, SceneError};
use prism::files::{FileAccess, FileError};
use prism::film::Region;
use prism::limits::{MAX_THREADS, MemoryBudget};
use prism::output::OutputError;
use prism::render::{RenderError, RenderOptions, render_frame};
use prism::scene::load::{FileSystem, load_from, load_with};
use prism::world::Scene;
use prism::world::components::{IntegratorKind, ToneMap};
use prism::world::validate::{MAX_IMAGE_SIDE, MAX_PIXELS, MAX_SAMPLES};
use prism::{builtin, output, plugins, prepare};

/// Prism renders scenes written as TOML: analytic shapes, lights and materials, to PNG and
/// OpenEXR. With no arguments it renders the built-in demo room to `prism.png`.
#[derive(Parser)]
#[command(name = "prism", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Subcommand)]
enum Command {
    /// Render a scene file to an image.
    Render(RenderArgs),
    /// Render a scene file, then again whenever it or a file it reads (includes, meshes,
    /// textures) changes, until Ctrl-C. Takes `render`'s options; a broken edit is reported
    /// and the last good image stays.
    Watch(RenderArgs),
    /// List the registered shape types and their parameters.
    Shapes,
    /// Write a JSON Schema of the scene format (for editors such as taplo / Even Better TOML).
    Schema {
        /// Where to write it (standard output when absent).
        #[arg(short, long)]
        output: Option<PathBuf>,
    },
    /// Write a scene in another renderer's scene language.
    #[command(subcommand)]
    Export(ExportCommand),
    /// Merge part files (from `render --region/--tile/--sample-range`) into the whole image:
    /// regions are assembled, sample ranges summed. Refuses parts of other scenes or settings,
    /// overlapping and truncated parts, and lists what is missing.
    Merge(MergeArgs),
    /// Render on a cluster: job scripts for a scheduler (see `docs/farm.md`).
    #[command(subcommand)]
    Farm(FarmCommand),
    /// Load a scene and write it back as one self-contained TOML file (includes flattened).
    Save {
        /// The scene file.
        scene: PathBuf,
        /// Where to write it (standard output when absent). Mesh and texture paths are written
        /// relative to this file when possible, absolute on standard output.
        #[arg(short, long)]
        output: Option<PathBuf>,
        #[command(flatten)]
        limits: LimitArgs,
    },
}

/// The image's size and sample count, overriding the scene's (`render` and `farm slurm`).
#[derive(Args, Default, Clone, Copy)]
struct FrameArgs {
    /// Image width in pixels (overrides the scene).
    #[arg(long, allow_hyphen_values = true, value_parser = parse_side)]
    width: Option<u32>,
    /// Image height in pixels (overrides the scene).
    #[arg(long, allow_hyphen_values = true, value_parser = parse_side)]
    height: Option<u32>,
    /// Samples per pixel (overrides the scene).
    #[arg(long, allow_hyphen_values = true, value_parser = parse_samples)]
    samples: Option<u32>,
}

/// What a scene may read and allocate (see `docs/security.md`).
#[derive(Args, Default, Clone)]
struct LimitArgs {
    /// Read only files inside DIR (the scene, includes, meshes, material libraries, textures,
    /// glTF buffers and images, environment maps), after resolving symlinks; absolute paths
    /// written in scene and mesh files are refused.
    #[arg(long, value_name = "DIR")]
    root: Option<PathBuf>,
    /// Memory budget for the film and decoded images, in bytes or with a K, M, G or T suffix
    /// (default: three quarters of the machine's memory).
    #[arg(long, value_name = "SIZE", value_parser = parse_memory)]
    max_memory: Option<u64>,
}

impl LimitArgs {
    fn budget(&self) -> MemoryBudget {
        self.max_memory.map_or_else(MemoryBudget::default, MemoryBudget)
    }

    fn access(&self) -> Result<FileAccess, CliError> {
        match &self.root {
            Some(root) => FileAccess::sandboxed(root).map_err(CliError::Root),
            None => Ok(FileAccess::unrestricted()),
        }
    }
}

fn parse_memory(text: &str) -> Result<u64, String> {
    prism::limits::parse_size(text)
}

/// A whole number in `min..=max` (the message names the range; clap names the flag).
fn ranged<T: std::str::FromStr + PartialOrd + std::fmt::Display + Copy>(
    text: &str,
    min: T,
    max: T,
) -> Result<T, String> {
    let value: T = text.trim().parse().map_err(|_| format!("must be a whole number from {min} to {max}"))?;
    if value < min {
        return Err(format!("must be at least {min}"));
    }
    if value > max {
        return Err(format!("must be at most {max}"));
    }
    Ok(value)
}

fn parse_side(text: &str) -> Result<u32, String> {
    ranged(text, 1, MAX_IMAGE_SIDE)
}

fn parse_samples(text: &str) -> Result<u32, String> {
    ranged(text, 1, MAX_SAMPLES)
}

fn parse_threads(text: &str) -> Result<usize, String> {
    ranged(text, 1, MAX_THREADS)
}

fn parse_seed(text: &str) -> Result<u64, String> {
    ranged(text, 0, u64::MAX)
}

fn parse_exposure(text: &str) -> Result<f64, String> {
    let value: f64 = text.trim().parse().map_err(|_| "must be a number of stops".to_string())?;
    if !value.is_finite() || value.abs() > 64.0 {
        return Err("must be a finite number of stops between -64 and 64".into());
    }
    Ok(value)
}

#[derive(Subcommand)]
enum ExportCommand {
    /// POV-Ray 3.7 scene language, rendering to the image of the classic integrator. The
    /// POV-Ray options for the same size and antialiasing are in its `// povray-options:` line.
    Pov {
        /// The scene file.
        scene: PathBuf,
        /// Where to write it (standard output when absent).
        #[arg(short, long)]
        output: Option<PathBuf>,
        #[command(flatten)]
        limits: LimitArgs,
    },
    /// Mitsuba 3 XML, rendering with Mitsuba's `path` integrator to the image of Prism's `path`
    /// integrator. Meshes are written as PLY files into `<output stem>_meshes/` beside it.
    Mitsuba {
        /// The scene file.
        scene: PathBuf,
        /// Where to write the XML.
        #[arg(short, long)]
        output: PathBuf,
        #[command(flatten)]
        limits: LimitArgs,
    },
}

/// `prism merge`.
#[derive(Args)]
struct MergeArgs {
    /// Merged images (format from the extension; repeat for several, e.g. -o a.exr -o a.png).
    #[arg(short, long, required = true)]
    output: Vec<PathBuf>,
    /// The part files.
    #[arg(required = true)]
    parts: Vec<PathBuf>,
    /// Write EXR channels as 16-bit half floats.
    #[arg(long)]
    half: bool,
    #[command(flatten)]
    limits: LimitArgs,
}

#[derive(Subcommand)]
enum FarmCommand {
    /// Submit a Slurm job array (one task per tile, requeued on node failure) and a merge job
    /// that runs when every task succeeded. Scene, assets, `prism` and the output folder must
    /// be on a filesystem every node sees at the same path.
    Slurm(SlurmArgs),
}

/// `prism farm slurm`.
#[derive(Args)]
struct SlurmArgs {
    /// The scene file.
    scene: PathBuf,
    /// Tiles: one array task each.
    #[arg(long, allow_hyphen_values = true, value_parser = parse_tiles)]
    tiles: u32,
    /// Slurm partition (`sbatch --partition`).
    #[arg(long)]
    partition: Option<String>,
    /// Time limit per task (`sbatch --time`, e.g. 30 or 01:00:00).
    #[arg(long)]
    time: Option<String>,
    /// Memory per task (`sbatch --mem`, e.g. 4G).
    #[arg(long)]
    mem: Option<String>,
    /// Folder for tiles, logs, job scripts and the merged images (default: `<scene stem>-farm`).
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
    /// Print the job scripts and the sbatch commands instead of writing and submitting them.
    #[arg(long)]
    dry_run: bool,
    #[command(flatten)]
    frame: FrameArgs,
    #[command(flatten)]
    limits: LimitArgs,
}

fn parse_tiles(text: &str) -> Result<u32, String> {
    ranged(text, 1, MAX_IMAGE_SIDE)
}

fn parse_region_arg(text: &str) -> Result<Region, String> {
    prism::partial::parse_region(text)
        .ok_or_else(|| "must be X0,Y0,X1,Y1: four whole numbers (half-open pixel bounds)".into())
}

fn parse_range_arg(text: &str) -> Result<std::ops::Range<u32>, String> {
    prism::partial::parse_range(text).ok_or_else(|| "must be A..B: two whole numbers (samples A to B-1)".into())
}

fn parse_tile_arg(text: &str) -> Result<(u32, u32), String> {
    prism::farm::parse_tile(text).map_err(|e| e.to_string())
}

#[derive(Args, Default)]
struct RenderArgs {
    /// The scene file (TOML).
    scene: PathBuf,
    /// Tone-mapped image (format from the extension: png, ppm, jpg, bmp, tga, tif, qoi, exr, hdr).
    /// Defaults to the scene's name with `.png` when neither -o nor --exr is given.
    #[arg(short, long)]
    output: Option<PathBuf>,
    /// Linear, unclipped OpenEXR image.
    #[arg(long)]
    exr: Option<PathBuf>,
    /// Write EXR channels as 16-bit half floats (as POV-Ray does) instead of 32-bit floats.
    #[arg(long)]
    half: bool,
    #[command(flatten)]
    frame: FrameArgs,
    /// Threads for rendering and for encoding the image (default: one per core; at most 256).
    #[arg(long, allow_hyphen_values = true, value_parser = parse_threads)]
    threads: Option<usize>,
    /// Seed of every random number (overrides the scene).
    #[arg(long, allow_hyphen_values = true, value_parser = parse_seed)]
    seed: Option<u64>,
    /// Exposure in stops for the tone-mapped image (overrides the scene).
    #[arg(long, allow_hyphen_values = true, value_parser = parse_exposure)]
    exposure: Option<f64>,
    /// Tone-mapping operator for the tone-mapped image (overrides the scene).
    #[arg(long, value_enum)]
    tone_map: Option<ToneMapArg>,
    /// The light transport algorithm (overrides the scene's `[render] integrator`).
    #[arg(long, value_enum)]
    integrator: Option<IntegratorArg>,
    /// Render only pixels X0..X1-1 of rows Y0..Y1-1 (half-open, as pbrt's --pixelbounds) into a
    /// part file (an EXR whose data window is the region; see `prism merge`).
    #[arg(long, value_name = "X0,Y0,X1,Y1", value_parser = parse_region_arg, conflicts_with = "tile")]
    region: Option<Region>,
    /// Render tile I of N (0-based, as Slurm's SLURM_ARRAY_TASK_ID and Kubernetes'
    /// JOB_COMPLETION_INDEX; full-width bands of rows) into a part file.
    #[arg(long, value_name = "I/N", value_parser = parse_tile_arg)]
    tile: Option<(u32, u32)>,
    /// Render samples A..B-1 of each pixel (of the scene's samples, with the full render's
    /// sample patterns) into a part file holding per-pixel sums, for `prism merge` to add.
    #[arg(long, value_name = "A..B", value_parser = parse_range_arg)]
    sample_range: Option<std::ops::Range<u32>>,
    // Long renders (issue 14): AOVs, adaptive sampling, time budgets.
    /// AOV layers for the EXR output, comma-separated (overrides `[render] aovs`): albedo,
    /// normal, depth, position, uv, object_id, material_id, variance, samples.
    #[arg(long, value_name = "LIST", value_parser = parse_aovs)]
    aov: Option<AovList>,
    /// Also write an 8-bit PNG preview of each AOV layer, named `<output stem>.<aov>.png`.
    #[arg(long)]
    aov_png: bool,
    /// Adaptive sampling: the largest estimated error a pixel's displayed value may keep
    /// (between 0 and 1, in units of display white; overrides `[render] noise`). Each pixel
    /// takes samples in proportion to their spread, the allocation with the lowest RMSE for
    /// the time, up to `samples`.
    #[arg(long, allow_hyphen_values = true, value_parser = parse_noise)]
    noise: Option<f64>,
    /// Time budget (`90s`, `10m`, `1h30m`; a bare number is seconds): render passes of
    /// increasing sample count (at most --samples when given) and keep the last complete one.
    #[arg(long, value_name = "DURATION", allow_hyphen_values = true, value_parser = parse_duration)]
    time: Option<std::time::Duration>,
    /// Save the render's state every DURATION (`60s`, `10m`...) to the checkpoint file, at
    /// the next tile; Ctrl-C then stops at the next tile and writes the checkpoint and the
    /// image so far (a second Ctrl-C quits at once, writing nothing).
    #[arg(long, value_name = "DURATION", allow_hyphen_values = true, value_parser = parse_duration)]
    checkpoint: Option<std::time::Duration>,
    /// The checkpoint file (an EXR; default: the --resume file, else
    /// `<output stem>.checkpoint.exr`).
    #[arg(long, value_name = "FILE")]
    checkpoint_file: Option<PathBuf>,
    /// Continue the render saved in this checkpoint (same scene and options, same --samples):
    /// only the unfinished tiles are rendered, and the image is the uninterrupted render's.
    #[arg(long, value_name = "FILE")]
    resume: Option<PathBuf>,
    /// Denoise the image with Intel Open Image Denoise (loaded at run time from OIDN_DIR or
    /// the library path), guided by the albedo and normal layers it adds; the EXR keeps the
    /// beauty as rendered as the `raw` layer.
    #[arg(long)]
    denoise: bool,
    /// Show the image in a window while it renders (needs an X11 or Wayland display); the
    /// window closes when the render ends.
    #[arg(long)]
    preview: bool,
    #[command(flatten)]
    limits: LimitArgs,
}

/// `--aov`: the parsed list (a newtype, so that clap takes the whole list as one value).
#[derive(Clone, Debug)]
struct AovList(Vec<prism::film::Aov>);

fn parse_aovs(text: &str) -> Result<AovList, String> {
    prism::film::Aov::parse_list(text.split(',')).map(AovList)
}

fn parse_noise(text: &str) -> Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(v) if v > 0.0 && v < 1.0 => Ok(v),
        _ => Err("must be an error between 0 and 1 (exclusive), such as 0.02".into()),
    }
}

/// A duration such as `90s`, `10m`, `1h30m` or `2.5m` (a bare number is seconds), more
/// than zero and at most a year.
fn parse_duration(text: &str) -> Result<std::time::Duration, String> {
    let wrong =
        || format!("`{}` is not a duration such as 90s, 10m or 1h30m", text.chars().take(40).collect::<String>());
    let text = text.trim();
    let mut seconds = 0.0;
    let mut number = String::new();
    for c in text.chars() {
        if c.is_ascii_digit() || c == '.' {
            number.push(c);
            continue;
        }
        let unit = match c {
            's' => 1.0,
            'm' => 60.0,
            'h' => 3600.0,
            'd' => 86400.0,
            _ => return Err(wrong()),
        };
        let value: f64 = number.parse().map_err(|_| wrong())?;
        seconds += value * unit;
        number.clear();
    }
    if !number.is_empty() {
        seconds += number.parse::<f64>().map_err(|_| wrong())?;
    }
    if text.is_empty() || text.ends_with(|c: char| !c.is_ascii_digit() && !"smhd.".contains(c)) {
        return Err(wrong());
    }
    if seconds <= 0.0 {
        return Err("must be more than zero".into());
    }
    if seconds > 366.0 * 86400.0 {
        return Err("must be at most a year".into());
    }
    Ok(std::time::Duration::from_secs_f64(seconds))
}

/// `--integrator`: the command-line names of [`IntegratorKind`].
#[derive(Clone, Copy, Debug, clap::ValueEnum)]
enum IntegratorArg {
    /// Whitted-style tracing with POV-Ray 3.7's shading model.
    Classic,
    /// Physically based path tracing.
    Path,
}

impl From<IntegratorArg> for IntegratorKind {
    fn from(arg: IntegratorArg) -> Self {
        match arg {
            IntegratorArg::Classic => IntegratorKind::Classic,
            IntegratorArg::Path => IntegratorKind::Path,
        }
    }
}

/// `--tone-map`: the command-line names of [`ToneMap`].
#[derive(Clone, Copy, Debug, clap::ValueEnum)]
enum ToneMapArg {
    /// Clip to [0, 1].
    Clamp,
    /// Reinhard: x / (1 + x).
    Reinhard,
    /// The ACES filmic fit.
    Aces,
}

impl From<ToneMapArg> for ToneMap {
    fn from(arg: ToneMapArg) -> Self {
        match arg {
            ToneMapArg::Clamp => ToneMap::Clamp,
            ToneMapArg::Reinhard => ToneMap::Reinhard,
            ToneMapArg::Aces => ToneMap::Aces,
        }
    }
}

/// Why a command failed: printed to standard error, and the exit code is 1.
#[derive(Debug, thiserror::Error)]
enum CliError {
    /// The scene has errors (each with file, line, column and key).
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// An image or text file cannot be written.
    #[error(transparent)]
    Output(#[from] OutputError),
    /// The render could not run.
    #[error(transparent)]
    Render(#[from] RenderError),
    /// `--width` and `--height` (with the scene's other side) make too many pixels.
    #[error("--width/--height: an image of {pixels} pixels is more than the limit of {MAX_PIXELS}")]
    TooManyPixels {
        /// Width times height.
        pixels: u64,
    },
    /// `--root` is not a directory that can be read.
    #[error("--root: {0}")]
    Root(FileError),
    /// Standard output cannot be written (closed, or a full disk).
    #[error("cannot write to standard output: {0}")]
    Stdout(std::io::Error),
    /// `--exr` names a file of another format.
    #[error("{}: --exr needs a file ending in .exr", path.display())]
    ExrExtension {
        /// The `--exr` path.
        path: PathBuf,
    },
    /// The scene cannot be written back as TOML.
    #[error("{}: cannot write scene: {source}", path.display())]
    Save {
        /// The scene file.
        path: PathBuf,
        /// The cause.
        source: toml::ser::Error,
    },
    /// The JSON schema cannot be written.
    #[error("cannot write the schema: {0}")]
    Schema(#[from] serde_json::Error),
    /// Tiles of a split.
    #[error(transparent)]
    Tile(#[from] prism::farm::TileError),
    /// Parts do not merge.
    #[error(transparent)]
    Merge(#[from] prism::farm::merge::MergeError),
    /// A part file cannot be read.
    #[error(transparent)]
    Part(#[from] prism::partial::PartialError),
    /// A part render was asked to write something other than one EXR.
    #[error(
        "--region/--tile/--sample-range write a part file: give one output ending in .exr (with --exr or -o), then `prism merge` the parts"
    )]
    PartOutput,
    /// A flag that a part render does not take.
    #[error(
        "{flag} cannot be combined with --region/--tile/--sample-range: a part file holds the beauty's sums for `prism merge`, rendered at the scene's fixed sample count"
    )]
    PartWith {
        /// The flag given.
        flag: &'static str,
    },
    /// A region outside the frame.
    #[error("--region {x0},{y0},{x1},{y1}: not a non-empty rectangle inside the {width}x{height} image (X0 < X1 <= {width}, Y0 < Y1 <= {height})", x0 = region.x0, y0 = region.y0, x1 = region.x1, y1 = region.y1)]
    Region {
        /// The region asked for.
        region: Region,
        /// Frame width.
        width: u32,
        /// Frame height.
        height: u32,
    },
    /// `sbatch` is not installed.
    #[error(
        "sbatch not found: `prism farm slurm` submits with Slurm's sbatch. Run it on the cluster's login node, or install Slurm's client (Debian/Ubuntu: `apt-get install slurm-client`; a one-machine cluster: `apt-get install slurm-wlm munge`, see docs/farm.md); --dry-run prints the job scripts without submitting"
    )]
    NoSbatch,
    /// `sbatch` refused a job.
    #[error("sbatch {script} failed: {message}")]
    Sbatch {
        /// The job script.
        script: String,
        /// What sbatch said.
        message: String,
    },
    /// `--denoise` failed: no library, or the library reported an error.
    #[error(transparent)]
    Denoise(#[from] prism::denoise::DenoiseError),
    /// The `--preview` window cannot be opened.
    #[error(transparent)]
    Preview(#[from] prism::preview::PreviewError),
    /// `--aov` without an EXR output or `--aov-png`: the layers would go nowhere.
    #[error("--aov: AOV layers are written into an OpenEXR output: add --exr FILE.exr (or -o FILE.exr) or --aov-png")]
    AovsNeedExr,
    /// A checkpoint cannot be resumed or written.
    #[error(transparent)]
    Checkpoint(#[from] prism::checkpoint::CheckpointError),
    /// `--time` with checkpoints.
    #[error(
        "--time cannot be combined with --checkpoint/--checkpoint-file/--resume: a time budget renders passes of different sample counts, whose sample patterns differ, so there is no one render to save and resume"
    )]
    CheckpointWithTime,
    /// The checkpoint file is also an image output.
    #[error("{}: the checkpoint file is also an image output; give another --checkpoint-file", path.display())]
    CheckpointIsOutput {
        /// The path given twice.
        path: PathBuf,
    },
    /// The checkpoint file is not named as an OpenEXR file.
    #[error(
        "{}: the checkpoint file (--checkpoint-file, by default the --resume file) is an OpenEXR file and its name must end in .exr",
        path.display()
    )]
    CheckpointNotExr {
        /// The checkpoint path.
        path: PathBuf,
    },
    /// Ctrl-C stopped a render with checkpoints: what was written and how to resume.
    #[error("{0}")]
    Interrupted(String),
    /// A folder for the output cannot be made.
    #[error("{}: cannot create the folder: {source}", path.display())]
    Io {
        /// The folder.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
}

/// A line on standard error; a closed or full standard error is ignored (there is nowhere
/// left to report to), never a panic.
fn report(line: &dyn std::fmt::Display) {
    let _ = writeln!(std::io::stderr().lock(), "{line}");
}

/// Adds the layers Open Image Denoise is guided by (albedo, normal) to `aovs`.
fn add_denoise_guides(aovs: &mut Vec<prism::film::Aov>) {
    for guide in [prism::film::Aov::Albedo, prism::film::Aov::Normal] {
        if !aovs.contains(&guide) {
            aovs.push(guide);
        }
    }
}

/// Encodes `film` for each of `paths` (format from the extension), warning when a half-float
/// EXR (`--half`) saturates values beyond half's range.
fn encode_outputs<'p>(
    film: &prism::film::Film,
    paths: impl IntoIterator<Item = &'p PathBuf>,
    image: &output::ImageSettings,
) -> Result<Vec<(&'p Path, Vec<u8>)>, CliError> {
    let mut files = Vec::new();
    let mut beyond_half = 0;
    for path in paths {
        let encoded = output::encode_reporting(film, path, image)?;
        beyond_half = beyond_half.max(encoded.values_beyond_half);
        files.push((path.as_path(), encoded.bytes));
    }
    if beyond_half > 0 {
        report(&format!(
            "warning: --half: {beyond_half} values exceed the largest half float ({}) and are written as {0}; \
             write a float EXR (without --half) to keep them",
            output::HALF_MAX
        ));
    }
    Ok(files)
}

/// Prints warnings to standard error, one `file:line:col: warning in `key`: ...` each.
fn print_warnings(warnings: &[Diagnostic]) {
    for warning in warnings {
        report(warning);
    }
}

/// Writes `text` to standard output, flushed; a failure (a full disk, a closed pipe) is an
/// error, not a panic.
fn write_stdout(text: &str) -> Result<(), CliError> {
    let mut out = std::io::stdout().lock();
    out.write_all(text.as_bytes()).and_then(|()| out.flush()).map_err(CliError::Stdout)
}

/// Loads the scene file at `path` under `limits` and prints what loading warns about.
fn load_and_warn(path: &Path, limits: &LimitArgs) -> Result<Scene, CliError> {
    let source = FileSystem(limits.access()?);
    let scene = load_with(&source, path, &plugins::registry(), limits.budget())?;
    print_warnings(&scene.warnings);
    Ok(scene)
}

/// Where the last panic happened, recorded by the panic hook (which prints nothing: a
/// panic's text may quote input, and a caught one is no concern of the user's).
static PANIC_AT: std::sync::Mutex<Option<String>> = std::sync::Mutex::new(None);

fn main() -> ExitCode {
    std::panic::set_hook(Box::new(|info| {
        let at = info.location().map(|l| format!("{}:{}", l.file(), l.line()));
        if let Ok(mut slot) = PANIC_AT.lock() {
            *slot = at;
        }
    }));
    #[cfg(unix)]
    remove_temps_on_signals();
    let cli = Cli::parse();
    let result = std::panic::catch_unwind(move || run(cli));
    match result {
        Ok(Ok(())) => ExitCode::SUCCESS,
        Ok(Err(error @ CliError::Interrupted(_))) => {
            report(&error);
            ExitCode::from(130)
        }
        Ok(Err(error)) => {
            report(&error);
            ExitCode::FAILURE
        }
        Err(_) => {
            prism::output::remove_all_temps();
            let at = PANIC_AT.lock().ok().and_then(|s| s.clone()).unwrap_or_else(|| "unknown place".into());
            report(&format!("prism: internal error (at {at}); please report it with the input that caused it"));
            ExitCode::from(101)
        }
    }
}

/// Set by a render with checkpoints: the first SIGINT sets this flag (the render stops at
/// the next tile and saves) instead of exiting; it is taken, so a second SIGINT exits.
static STOP_AT_NEXT_TILE: std::sync::Mutex<Option<std::sync::Arc<std::sync::atomic::AtomicBool>>> =
    std::sync::Mutex::new(None);

/// SIGINT and SIGTERM are blocked in every thread and taken by one thread that removes the
/// temporary files being written and exits (130 for SIGINT, 143 for SIGTERM). Outputs are
/// renamed into place under the same lock, so a signal leaves all of them or none. During a
/// render with checkpoints the first SIGINT only asks the render to stop
/// ([`STOP_AT_NEXT_TILE`]).
#[cfg(unix)]
fn remove_temps_on_signals() {
    // SAFETY: plain libc calls on a zeroed, then initialised, signal set owned here; the
    // mask is set before any other thread exists, so every later thread inherits it.
    let set = unsafe {
        let mut set: libc::sigset_t = std::mem::zeroed();
        libc::sigemptyset(&mut set);
        libc::sigaddset(&mut set, libc::SIGINT);
        libc::sigaddset(&mut set, libc::SIGTERM);
        if libc::pthread_sigmask(libc::SIG_BLOCK, &set, std::ptr::null_mut()) != 0 {
            return;
        }
        set
    };
    let spawned = std::thread::Builder::new().name("signals".into()).spawn(move || {
        let mut signal: libc::c_int = 0;
        // SAFETY: `set` is a valid initialised signal set; `signal` a valid out-pointer.
        while unsafe { libc::sigwait(&set, &mut signal) } == 0 {
            let stop = STOP_AT_NEXT_TILE.lock().unwrap_or_else(std::sync::PoisonError::into_inner).take();
            if let (libc::SIGINT, Some(stop)) = (signal, stop) {
                stop.store(true, std::sync::atomic::Ordering::Relaxed);
                report(&"\ninterrupted: finishing the tiles under way, then writing the checkpoint and the image so far (Ctrl-C again quits at once, writing nothing)");
                continue;
            }
            prism::output::remove_all_temps_and_exit(128 + signal);
        }
    });
    if spawned.is_err() {
        // SAFETY: as above.
        unsafe { libc::pthread_sigmask(libc::SIG_UNBLOCK, &set, std::ptr::null_mut()) };
    }
}

/// Sizes rayon's global pool to `--threads`: the render's tiles run on it, and so does the
/// work outside the render (BVH builds, image encoding), which would otherwise take one
/// thread per core.
fn limit_global_threads(threads: Option<usize>) {
    if let Some(threads) = threads {
        // Fails only when the global pool already exists, which nothing builds before this.
        let _ = rayon::ThreadPoolBuilder::new().num_threads(threads).build_global();
    }
}

fn run(cli: Cli) -> Result<(), CliError> {
    match cli.command {
        None => render_default(),
        Some(Command::Render(args)) => {
            limit_global_threads(args.threads);
            render_command(&args)
        }
        Some(Command::Watch(args)) => {
            limit_global_threads(args.threads);
            watch_command(&args)
        }
        Some(Command::Merge(args)) => merge_command(&args),
        Some(Command::Farm(FarmCommand::Slurm(args))) => slurm_command(&args),
        Some(Command::Shapes) => write_stdout(&prism::registry::describe(&plugins::registry())),
        Some(Command::Save { scene, output, limits }) => save_command(&scene, output.as_deref(), &limits),
        Some(Command::Schema { output }) => schema_command(output.as_deref()),
        Some(Command::Export(ExportCommand::Pov { scene, output, limits })) => {
            export_pov_command(&scene, output.as_deref(), &limits)
        }
        Some(Command::Export(ExportCommand::Mitsuba { scene, output, limits })) => {
            export_mitsuba_command(&scene, &output, &limits)
        }
    }
}

fn render_default() -> Result<(), CliError> {
    let scene = load_from(&builtin::FILES, Path::new(builtin::DEFAULT_SCENE), &plugins::registry())?;
    print_warnings(&scene.warnings);
    let args = RenderArgs { output: Some(PathBuf::from("prism.png")), ..RenderArgs::default() };
    render_scene(scene, &args)
}

fn render_command(args: &RenderArgs) -> Result<(), CliError> {
    let scene = load_and_warn(&args.scene, &args.limits)?;
    render_scene(scene, args)
}

/// Opens the `--preview` window for the scene's image, showing it as the outputs will.
fn open_preview(scene: &Scene, path: &Path) -> Result<prism::preview::Preview, CliError> {
    use prism::preview::{Preview, PreviewSettings};
    let settings = PreviewSettings { exposure: scene.render.exposure, tone_map: scene.render.tone_map };
    let title = path.file_name().map_or_else(|| "prism".into(), |n| n.to_string_lossy().into_owned());
    let preview = Preview::open((scene.render.width, scene.render.height), &title, settings)?;
    let layout = preview.layout();
    let (w, h) = layout.window();
    let how = match (layout.zoom, layout.picture == layout.image) {
        (1, true) => "pixel for pixel".to_string(),
        (1, false) => format!("shrunk to {}x{} to fit the screen", layout.picture.0, layout.picture.1),
        (zoom, _) => format!("enlarged {zoom}x"),
    };
    report(&format_args!("preview: a {w}x{h} window, the image {how}"));
    Ok(preview)
}

/// `prism watch`: renders, then waits for a change to any file the scene read and renders
/// again; errors are printed and the watch goes on. Ends with Ctrl-C (the signal thread).
fn watch_command(args: &RenderArgs) -> Result<(), CliError> {
    use prism::watch::FileStamps;
    let access = args.limits.access()?;
    loop {
        let (logged, log) = access.clone().logged();
        let loaded = load_with(&FileSystem(logged), &args.scene, &plugins::registry(), args.limits.budget());
        let mut paths = log.paths();
        let scene_path = std::path::absolute(&args.scene).unwrap_or_else(|_| args.scene.clone());
        if !paths.contains(&scene_path) {
            paths.insert(0, scene_path);
        }
        // Stamped before the render, so that an edit made while it runs starts the next one.
        let stamps = FileStamps::of(&paths);
        let result = loaded.map_err(CliError::from).and_then(|scene| {
            print_warnings(&scene.warnings);
            render_scene(scene, args)
        });
        if let Err(error) = result {
            report(&error);
        }
        report(&format_args!(
            "watching {} file{} for changes (Ctrl-C to stop)",
            paths.len(),
            if paths.len() == 1 { "" } else { "s" }
        ));
        stamps.wait_for_change(WATCH_POLL, WATCH_SETTLE);
    }
}

/// How often `prism watch` looks at the files' modification times.
const WATCH_POLL: std::time::Duration = std::time::Duration::from_millis(200);

/// How long the files must stay unchanged after a change before `prism watch` renders
/// (an editor's save may take several writes).
const WATCH_SETTLE: std::time::Duration = std::time::Duration::from_millis(300);

fn render_scene(mut scene: Scene, args: &RenderArgs) -> Result<(), CliError> {
    let settings = &mut scene.render;
    if let Some(w) = args.frame.width {
        settings.width = w;
    }
    if let Some(h) = args.frame.height {
        settings.height = h;
    }
    if let Some(s) = args.frame.samples {
        settings.samples = s;
        // --samples is POV-Ray's `blur_samples` maximum; the scene's minimum follows it down,
        // so a quick low-sample preview of an adaptive focal blur scene still renders.
        if let Ok(mut camera) = scene.world.get::<&mut prism::world::components::Camera>(scene.camera)
            && camera.blur_min_samples.is_some_and(|m| m > s)
        {
            camera.blur_min_samples = Some(s.max(1));
        }
    }
    if let Some(s) = args.seed {
        settings.seed = s;
    }
    if let Some(e) = args.exposure {
        settings.exposure = e;
    }
    if let Some(t) = args.tone_map {
        settings.tone_map = t.into();
    }
    if let Some(i) = args.integrator {
        settings.integrator = i.into();
    }
    if let Some(n) = args.noise {
        settings.noise = Some(n);
    }
    if let Some(aovs) = &args.aov {
        settings.aovs = aovs.0.iter().map(|a| a.name().to_string()).collect();
    }
    if args.frame.width.is_some() || args.frame.height.is_some() {
        let pixels = u64::from(settings.width) * u64::from(settings.height);
        if pixels > MAX_PIXELS {
            return Err(CliError::TooManyPixels { pixels });
        }
    }
    let is_part = args.region.is_some() || args.tile.is_some() || args.sample_range.is_some();
    let mut outputs: Vec<PathBuf> = args.output.iter().chain(args.exr.iter()).cloned().collect();
    if is_part {
        if let Some(flag) = [
            (args.time.is_some(), "--time"),
            (args.aov.is_some(), "--aov"),
            (args.aov_png, "--aov-png"),
            (args.checkpoint.is_some(), "--checkpoint"),
            (args.checkpoint_file.is_some(), "--checkpoint-file"),
            (args.resume.is_some(), "--resume"),
            (args.denoise, "--denoise"),
            (args.preview, "--preview"),
        ]
        .into_iter()
        .find_map(|(given, flag)| given.then_some(flag))
        {
            return Err(CliError::PartWith { flag });
        }
        if outputs.len() != 1 || output::format_for(&outputs[0]).ok() != Some(output::OutputFormat::Exr) || args.half {
            return Err(CliError::PartOutput);
        }
        return render_part(scene, args, &outputs[0]);
    }
    if outputs.is_empty() {
        let stem = args.scene.file_stem().map_or("prism".into(), |s| s.to_string_lossy().into_owned());
        outputs.push(PathBuf::from(format!("{stem}.png")));
    }
    if let Some(exr) = &args.exr
        && output::format_for(exr)? != output::OutputFormat::Exr
    {
        return Err(CliError::ExrExtension { path: exr.clone() });
    }
    let has_exr = outputs.iter().any(|p| output::format_for(p).is_ok_and(|f| f == output::OutputFormat::Exr));
    if args.aov.is_some() && !has_exr && !args.aov_png {
        return Err(CliError::AovsNeedExr);
    }
    let checkpoint_path = if args.checkpoint.is_some() || args.checkpoint_file.is_some() || args.resume.is_some() {
        if args.time.is_some() {
            return Err(CliError::CheckpointWithTime);
        }
        let path = args.checkpoint_file.clone().or_else(|| args.resume.clone()).unwrap_or_else(|| {
            let stem = outputs[0].file_stem().map_or("prism".into(), |s| s.to_string_lossy().into_owned());
            outputs[0].with_file_name(format!("{stem}.checkpoint.exr"))
        });
        if outputs.contains(&path) {
            return Err(CliError::CheckpointIsOutput { path });
        }
        if !path.extension().is_some_and(|e| e.eq_ignore_ascii_case("exr")) {
            return Err(CliError::CheckpointNotExr { path });
        }
        output::check_writable(&path)?;
        Some(path)
    } else {
        None
    };
    // The fingerprint is of the scene as loaded and overridden, before `prepare`.
    let fresh_state = match checkpoint_path {
        Some(_) => {
            let mut aovs =
                prism::film::Aov::parse_list(scene.render.aovs.iter().map(String::as_str)).unwrap_or_default();
            if args.denoise {
                add_denoise_guides(&mut aovs);
            }
            Some(prism::checkpoint::Checkpoint::new(&scene, &aovs)?)
        }
        None => None,
    };
    let mut render_scene = prepare(&mut scene)?;
    // Validated by `prepare`, so the names are known.
    let aovs = prism::film::Aov::parse_list(scene.render.aovs.iter().map(String::as_str)).unwrap_or_default();
    let previews: Vec<(prism::film::Aov, PathBuf)> = if args.aov_png {
        let first = &outputs[0];
        let stem = first.file_stem().map_or("prism".into(), |s| s.to_string_lossy().into_owned());
        aovs.iter().map(|&a| (a, first.with_file_name(format!("{stem}.{}.png", a.name())))).collect()
    } else {
        Vec::new()
    };
    // Fail before rendering, not after: bad paths and formats are found now.
    for path in outputs.iter().chain(previews.iter().map(|(_, p)| p)) {
        output::check_writable(path)?;
    }
    print_warnings(&prism::world::validate::warnings(&scene));
    // The library is loaded before rendering: without it nothing is rendered or written.
    let denoiser = if args.denoise { Some(prism::denoise::Denoiser::load()?) } else { None };
    let mut render_aovs = aovs.clone();
    if denoiser.is_some() {
        add_denoise_guides(&mut render_aovs);
    }
    let preview = if args.preview { Some(open_preview(&scene, &args.scene)?) } else { None };
    let options = RenderOptions {
        threads: args.threads,
        progress: std::io::stderr().is_terminal(),
        budget: args.limits.budget(),
        aovs: render_aovs,
        observer: preview.as_ref().map(prism::preview::Preview::hook),
        ..Default::default()
    };
    let image =
        output::ImageSettings { exposure: scene.render.exposure, tone_map: scene.render.tone_map, exr_half: args.half };
    let mut checkpoint_bytes = None;
    let (mut film, stats) = match (fresh_state, &checkpoint_path) {
        (Some(mut state), Some(path)) => {
            if let Some(resume) = &args.resume {
                state.resume_from(&args.limits.access()?, resume)?;
                report(&format_args!(
                    "resuming {}: {} of {} pixels are finished",
                    resume.display(),
                    state.pixels_done(),
                    state.done.len()
                ));
            }
            let run = render_with_checkpoints(&render_scene, &mut state, &options, args, path, &outputs, &image)?;
            checkpoint_bytes = Some(encode_checkpoint(&state, path)?);
            (state.film, run.stats)
        }
        _ => match args.time {
            Some(budget) => {
                let cap = args.frame.samples.unwrap_or(MAX_SAMPLES);
                let run = prism::render::render_within(&mut render_scene, &options, budget, cap)?;
                scene.render.samples = render_scene.settings.samples;
                report(&format_args!(
                    "time budget {:.1} s: {} passes in {:.3} s, kept the last complete one ({} spp)",
                    budget.as_secs_f64(),
                    run.passes,
                    run.elapsed.as_secs_f64(),
                    scene.render.samples
                ));
                (run.film, run.stats)
            }
            None => render_frame(&render_scene, &options)?,
        },
    };
    if let Some(preview) = preview {
        preview.close();
    }
    if stats.non_finite_samples > 0 {
        report(&format!(
            "warning: {} samples had a NaN or infinite radiance (products of extreme light, colour or \
             emission values overflowed) and count as black",
            stats.non_finite_samples
        ));
    }
    if stats.saturated_pixels > 0 {
        report(&format!(
            "warning: {} pixels overflowed (products of extreme light, colour or finish values) and \
             are saturated channel by channel, as POV-Ray writes an infinite channel",
            stats.saturated_pixels
        ));
    }
    if stats.non_finite_pixels > 0 {
        report(&format!(
            "warning: {} pixels had a NaN or infinite value and are written black",
            stats.non_finite_pixels
        ));
    }
    if let Some(denoiser) = &denoiser {
        let done = denoiser.denoise(&mut film, args.threads, args.limits.budget())?;
        report(&format_args!(
            "denoised with Open Image Denoise {} ({}) in {:.3} s",
            done.version,
            denoiser.library,
            done.elapsed.as_secs_f64()
        ));
        if done.non_finite_pixels > 0 {
            report(&format!(
                "warning: the denoiser gave {} pixels a NaN or infinite value; they are written black",
                done.non_finite_pixels
            ));
        }
    }
    // Every output is encoded, then all are written at once: all of them or none.
    let mut files = encode_outputs(&film, &outputs, &image)?;
    for (aov, path) in &previews {
        if let Some(img) = output::layer_preview(&film, *aov) {
            files.push((path.as_path(), output::encode_png(&img, path)?));
        }
    }
    if let (Some(path), Some(bytes)) = (&checkpoint_path, checkpoint_bytes) {
        files.push((path.as_path(), bytes));
    }
    output::write_all_atomically(&files)?;
    let names: Vec<String> = outputs
        .iter()
        .chain(previews.iter().map(|(_, p)| p))
        .chain(&checkpoint_path)
        .map(|p| p.display().to_string())
        .collect();
    report(&format_args!(
        "rendered {}x{} at {} spp in {:.3} s: {} primary rays, {} rays in all, {:.2} Mrays/s -> {}",
        scene.render.width,
        scene.render.height,
        scene.render.samples,
        stats.elapsed.as_secs_f64(),
        stats.primary_rays,
        stats.total_rays,
        stats.mrays_per_second(),
        names.join(", ")
    ));
    if scene.render.noise.is_some() || !options.aovs.is_empty() {
        let s = stats.samples;
        report(&format_args!(
            "samples per pixel: min {}, median {}, 90% {}, max {}, mean {:.1}; estimated display error (rms) {:.4}",
            s.min, s.median, s.p90, s.max, s.mean, stats.noise
        ));
    }
    Ok(())
}

/// The checkpoint file's bytes.
fn encode_checkpoint(state: &prism::checkpoint::Checkpoint, path: &Path) -> Result<Vec<u8>, CliError> {
    state.encode().map_err(|e| OutputError::Encode { path: path.to_path_buf(), message: e.to_string() }.into())
}

/// Renders the unfinished tiles of `state`, saving it to `path` every `--checkpoint`
/// interval. The first Ctrl-C stops the render at the next tile; the checkpoint and the
/// image so far are then written (all or none) and the error says what was written and how
/// to resume (exit 130).
fn render_with_checkpoints(
    scene: &prism::render::extract::RenderScene,
    state: &mut prism::checkpoint::Checkpoint,
    options: &RenderOptions,
    args: &RenderArgs,
    path: &Path,
    outputs: &[PathBuf],
    image: &output::ImageSettings,
) -> Result<prism::checkpoint::ResumableRun, CliError> {
    use prism::checkpoint::{Outcome, render_resumable};
    let stop = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
    *STOP_AT_NEXT_TILE.lock().unwrap_or_else(std::sync::PoisonError::into_inner) = Some(stop.clone());
    let options = RenderOptions { cancel: Some(stop), ..options.clone() };
    let save = |state: &prism::checkpoint::Checkpoint| -> Result<(), CliError> {
        output::write_atomically(path, &encode_checkpoint(state, path)?)?;
        report(&format_args!(
            "checkpoint: {} of {} pixels finished -> {}",
            state.pixels_done(),
            state.done.len(),
            path.display()
        ));
        Ok(())
    };
    let run = render_resumable(scene, state, &options, args.checkpoint, save);
    // From here on a SIGINT exits at once (removing temporary files).
    STOP_AT_NEXT_TILE.lock().unwrap_or_else(std::sync::PoisonError::into_inner).take();
    let run = run?;
    if run.outcome == Outcome::Complete {
        return Ok(run);
    }
    let mut files = vec![(path, encode_checkpoint(state, path)?)];
    files.extend(encode_outputs(&state.film, outputs, image)?);
    output::write_all_atomically(&files)?;
    let written: Vec<String> = files.iter().map(|(p, _)| p.display().to_string()).collect();
    Err(CliError::Interrupted(format!(
        "interrupted: {} of {} pixels finished; wrote {} (the unfinished tiles are black)\nto resume: {}",
        state.pixels_done(),
        state.done.len(),
        written.join(", "),
        resume_command(path)
    )))
}

/// This process's command line with `--resume PATH` in place of any `--resume`, quoted for a
/// POSIX shell.
fn resume_command(path: &Path) -> String {
    let quote = |arg: &str| {
        if !arg.is_empty() && arg.chars().all(|c| c.is_ascii_alphanumeric() || "_./:=,+-@%".contains(c)) {
            arg.to_string()
        } else {
            format!("'{}'", arg.replace('\'', "'\\''"))
        }
    };
    let mut words = vec!["prism".to_string()];
    let mut args = std::env::args_os().skip(1).map(|a| a.to_string_lossy().into_owned());
    while let Some(arg) = args.next() {
        if arg == "--resume" {
            args.next();
        } else if !arg.starts_with("--resume=") {
            words.push(quote(&arg));
        }
    }
    words.extend(["--resume".to_string(), quote(&path.to_string_lossy())]);
    words.join(" ")
}

/// `render --region/--tile/--sample-range`: one part file.
fn render_part(mut scene: Scene, args: &RenderArgs, path: &Path) -> Result<(), CliError> {
    use prism::partial::{Fingerprint, PartInfo, Partial, Sampling};
    let (width, height) = (scene.render.width, scene.render.height);
    let pov = !matches!(scene.render.antialias, prism::world::components::Antialias::Stratified {});
    let region = match (args.region, args.tile) {
        (Some(region), _) => {
            if region.is_empty() || !region.fits(width, height) {
                return Err(CliError::Region { region, width, height });
            }
            region
        }
        (None, Some((i, n))) => {
            let align = if pov { prism::render::antialias::BLOCK_SIZE } else { prism::render::TILE_SIZE };
            prism::farm::tile_region(width, height, i, n, align)?
        }
        (None, None) => Region::full(width, height),
    };
    let total = scene.render.samples;
    let samples = args.sample_range.clone().unwrap_or(0..total);
    if samples.is_empty() || samples.end > total {
        return Err(RenderError::SampleRange { range: samples, samples: total }.into());
    }
    if pov && args.sample_range.is_some() {
        return Err(RenderError::SampleRangeWithPovAntialiasing.into());
    }
    output::check_writable(path)?;
    let fingerprint =
        Fingerprint::of_scene(&scene).map_err(|source| CliError::Save { path: args.scene.clone(), source })?;
    let render_scene = prepare(&mut scene)?;
    print_warnings(&prism::world::validate::warnings(&scene));
    let options = RenderOptions {
        threads: args.threads,
        progress: std::io::stderr().is_terminal(),
        budget: args.limits.budget(),
        ..Default::default()
    };
    let whole = samples == (0..total);
    let (film, sums, stats) = match scene.render.integrator {
        IntegratorKind::Classic => {
            let integrator = prism::render::classic(&render_scene, &options);
            part_render(&render_scene, &integrator, region, samples.clone(), whole, &options)?
        }
        IntegratorKind::Path => {
            let integrator = prism::render::path(&render_scene, &options);
            part_render(&render_scene, &integrator, region, samples.clone(), whole, &options)?
        }
    };
    let info = PartInfo {
        fingerprint,
        frame: (width, height),
        region,
        samples: samples.clone(),
        total_samples: total,
        tile: if args.region.is_none() { args.tile } else { None },
        sampling: if pov { Sampling::Pov } else { Sampling::Stratified },
        exposure: scene.render.exposure,
        tone_map: scene.render.tone_map,
        scene: None,
    };
    let part = Partial::from_film(info, &film, sums);
    let bytes = part.encode().map_err(|e| OutputError::Encode { path: path.to_path_buf(), message: e.to_string() })?;
    output::write_atomically(path, &bytes)?;
    report(&format_args!(
        "rendered pixels {},{},{},{} of {width}x{height}, samples {}..{} of {total}, in {:.3} s -> {}",
        region.x0,
        region.y0,
        region.x1,
        region.y1,
        samples.start,
        samples.end,
        stats.elapsed.as_secs_f64(),
        path.display()
    ));
    Ok(())
}

/// A part's film, and its sums unless it holds all its pixels' samples.
fn part_render<I: prism::render::integrators::Integrator>(
    scene: &prism::render::extract::RenderScene,
    integrator: &I,
    region: Region,
    samples: std::ops::Range<u32>,
    whole: bool,
    options: &RenderOptions,
) -> Result<(prism::film::Film, Option<Vec<prism::partial::PixelSums>>, prism::render::RenderStats), CliError> {
    if whole {
        let (film, stats) = prism::render::render(scene, integrator, region, options)?;
        Ok((film, None, stats))
    } else {
        let (film, sums, stats) = prism::render::render_sums(scene, integrator, region, samples, options)?;
        Ok((film, Some(sums), stats))
    }
}

fn merge_command(args: &MergeArgs) -> Result<(), CliError> {
    use prism::farm::merge::{NamedPart, merge, shared_info};
    for path in &args.output {
        output::check_writable(path)?;
    }
    let access = args.limits.access()?;
    let mut parts = Vec::new();
    for path in &args.parts {
        let part = prism::partial::Partial::read(&access, path)?;
        parts.push(NamedPart { name: path.display().to_string(), part });
    }
    let film = merge(&parts, args.limits.budget())?;
    let info = shared_info(&parts).ok_or(prism::farm::merge::MergeError::NoParts)?;
    let image = output::ImageSettings { exposure: info.exposure, tone_map: info.tone_map, exr_half: args.half };
    let files = encode_outputs(&film, &args.output, &image)?;
    output::write_all_atomically(&files)?;
    let names: Vec<String> = args.output.iter().map(|p| p.display().to_string()).collect();
    report(&format_args!("merged {} parts into {}x{} -> {}", parts.len(), film.width, film.height, names.join(", ")));
    Ok(())
}

fn slurm_command(args: &SlurmArgs) -> Result<(), CliError> {
    use prism::farm::slurm::{FarmJob, parse_job_id};
    let scene = load_and_warn(&args.scene, &args.limits)?;
    let mut render_args = Vec::new();
    for (flag, value) in
        [("--width", args.frame.width), ("--height", args.frame.height), ("--samples", args.frame.samples)]
    {
        if let Some(v) = value {
            render_args.extend([flag.to_string(), v.to_string()]);
        }
    }
    let width = args.frame.width.unwrap_or(scene.render.width);
    let height = args.frame.height.unwrap_or(scene.render.height);
    if u64::from(width) * u64::from(height) > MAX_PIXELS {
        return Err(CliError::TooManyPixels { pixels: u64::from(width) * u64::from(height) });
    }
    // Every tile must exist: the split refuses more tiles than rows.
    prism::farm::tile_region(width, height, 0, args.tiles, 1)?;
    let absolute = |path: &Path| -> Result<PathBuf, CliError> {
        std::path::absolute(path).map_err(|source| CliError::Io { path: path.to_path_buf(), source })
    };
    let stem = args.scene.file_stem().map_or("prism".into(), |s| s.to_string_lossy().into_owned());
    let out_dir = absolute(args.out.as_deref().unwrap_or(Path::new(&format!("{stem}-farm"))))?;
    let prism = std::env::current_exe().map_err(|source| CliError::Io { path: PathBuf::from("prism"), source })?;
    let scene_path =
        std::fs::canonicalize(&args.scene).map_err(|source| CliError::Io { path: args.scene.clone(), source })?;
    if let Some(root) = &args.limits.root {
        render_args.extend(["--root".to_string(), absolute(root)?.display().to_string()]);
    }
    let job = FarmJob {
        prism,
        scene: scene_path,
        tiles: args.tiles,
        out_dir: out_dir.clone(),
        name: stem,
        partition: args.partition.clone(),
        time: args.time.clone(),
        mem: args.mem.clone(),
        render_args,
    };
    let (array, merge) = (out_dir.join("render.sbatch"), out_dir.join("merge.sbatch"));
    if args.dry_run {
        return write_stdout(&format!(
            "# {array}
{}
# {merge}
{}
# submit:
sbatch --parsable {array}
sbatch --parsable --dependency=afterok:ARRAY_JOB_ID {merge}
",
            job.array_script(),
            job.merge_script(),
            array = array.display(),
            merge = merge.display(),
        ));
    }
    let sbatch = |extra: &[String], script: &Path| -> Result<u64, CliError> {
        let result = std::process::Command::new("sbatch").arg("--parsable").args(extra).arg(script).output();
        let shown = script.display().to_string();
        match result {
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => Err(CliError::NoSbatch),
            Err(e) => Err(CliError::Sbatch { script: shown, message: e.to_string() }),
            Ok(out) if !out.status.success() => Err(CliError::Sbatch {
                script: shown,
                message: String::from_utf8_lossy(&out.stderr).trim().to_string(),
            }),
            Ok(out) => parse_job_id(&String::from_utf8_lossy(&out.stdout)).ok_or_else(|| CliError::Sbatch {
                script: shown,
                message: format!("no job id in its output `{}`", String::from_utf8_lossy(&out.stdout).trim()),
            }),
        }
    };
    // Fail before writing anything when sbatch is missing.
    if which_sbatch().is_none() {
        return Err(CliError::NoSbatch);
    }
    std::fs::create_dir_all(&out_dir).map_err(|source| CliError::Io { path: out_dir.clone(), source })?;
    output::write_atomically(&array, job.array_script().as_bytes())?;
    output::write_atomically(&merge, job.merge_script().as_bytes())?;
    let array_id = sbatch(&[], &array)?;
    let merge_id = sbatch(&[format!("--dependency=afterok:{array_id}")], &merge)?;
    write_stdout(&format!(
        "submitted job array {array_id} ({} tiles) and merge job {merge_id} -> {}
",
        args.tiles,
        out_dir.join(format!("{}.exr", job.name)).display()
    ))
}

/// `sbatch` on the PATH, if any.
fn which_sbatch() -> Option<PathBuf> {
    let path = std::env::var_os("PATH")?;
    std::env::split_paths(&path).map(|dir| dir.join("sbatch")).find(|p| p.is_file())
}

fn save_command(path: &Path, output: Option<&Path>, limits: &LimitArgs) -> Result<(), CliError> {
    let mut scene = load_and_warn(path, limits)?;
    // Checked as a render and the exports check it: a scene that cannot render is an error
    // here, at its own file and line, not a saved copy that fails later at the copy's.
    prism::world::transforms::resolve_transforms(&mut scene)?;
    prism::world::validate::validate(&scene)?;
    // Written to a file, mesh and texture paths are relative to it; on standard output,
    // whose destination is unknown, they stay absolute.
    let text = match output {
        Some(out) => prism::scene::save::save_for(&scene, out),
        None => prism::scene::save::save(&scene),
    };
    let text = text.map_err(|source| CliError::Save { path: path.to_path_buf(), source })?;
    match output {
        Some(out) => Ok(output::write_atomically(out, text.as_bytes())?),
        None => write_stdout(&text),
    }
}

fn schema_command(output: Option<&Path>) -> Result<(), CliError> {
    let schema = prism::scene::schema::scene_schema(&plugins::registry());
    let text = serde_json::to_string_pretty(&schema)? + "\n";
    match output {
        Some(out) => Ok(output::write_atomically(out, text.as_bytes())?),
        None => write_stdout(&text),
    }
}

fn export_mitsuba_command(path: &Path, output: &Path, limits: &LimitArgs) -> Result<(), CliError> {
    let mut scene = load_and_warn(path, limits)?;
    prism::world::transforms::resolve_transforms(&mut scene)?;
    prism::world::validate::validate(&scene)?;
    let source = path.file_name().map_or_else(|| path.display().to_string(), |n| n.to_string_lossy().into_owned());
    let stem = output.file_stem().map_or_else(|| "scene".to_string(), |s| s.to_string_lossy().into_owned());
    let folder = format!("{stem}_meshes");
    let beside = output.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    let exported = prism::export::mitsuba::export(&scene, &source, &format!("{folder}/"), beside)?;
    if !exported.meshes.is_empty() {
        let dir = beside.join(&folder);
        std::fs::create_dir_all(&dir).map_err(|source| CliError::Io { path: dir.clone(), source })?;
    }
    for (name, bytes) in &exported.meshes {
        output::write_atomically(&beside.join(name), bytes)?;
    }
    Ok(output::write_atomically(output, exported.xml.as_bytes())?)
}

fn export_pov_command(path: &Path, output: Option<&Path>, limits: &LimitArgs) -> Result<(), CliError> {
    let mut scene = load_and_warn(path, limits)?;
    prism::world::transforms::resolve_transforms(&mut scene)?;
    prism::world::validate::validate(&scene)?;
    let source = path.file_name().map_or_else(|| path.display().to_string(), |n| n.to_string_lossy().into_owned());
    let directory = output.map(|o| o.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new(".")));
    let text = prism::export::pov::export(&scene, &source, directory)?;
    match output {
        Some(out) => Ok(output::write_atomically(out, text.as_bytes())?),
        None => write_stdout(&text),
    }
}
