//! The `prism` command line.

use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{Args, Parser, Subcommand};
use prism::diagnostics::{Diagnostic, SceneError};
use prism::output::OutputError;
use prism::render::{RenderError, RenderOptions, render_frame};
use prism::scene::load::{load_file, load_from};
use prism::world::Scene;
use prism::world::components::{IntegratorKind, ToneMap};
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
    /// Load a scene and write it back as one self-contained TOML file (includes flattened).
    Save {
        /// The scene file.
        scene: PathBuf,
        /// Where to write it (standard output when absent). Mesh and texture paths are written
        /// relative to this file when possible, absolute on standard output.
        #[arg(short, long)]
        output: Option<PathBuf>,
    },
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
    },
    /// Mitsuba 3 XML, rendering with Mitsuba's `path` integrator to the image of Prism's `path`
    /// integrator. Meshes are written as PLY files into `<output stem>_meshes/` beside it.
    Mitsuba {
        /// The scene file.
        scene: PathBuf,
        /// Where to write the XML.
        #[arg(short, long)]
        output: PathBuf,
    },
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
    /// Image width in pixels (overrides the scene).
    #[arg(long)]
    width: Option<u32>,
    /// Image height in pixels (overrides the scene).
    #[arg(long)]
    height: Option<u32>,
    /// Samples per pixel (overrides the scene).
    #[arg(long)]
    samples: Option<u32>,
    /// Render threads (default: one per core).
    #[arg(long)]
    threads: Option<usize>,
    /// Seed of every random number (overrides the scene).
    #[arg(long)]
    seed: Option<u64>,
    /// Exposure in stops for the tone-mapped image (overrides the scene).
    #[arg(long, allow_hyphen_values = true)]
    exposure: Option<f64>,
    /// Tone-mapping operator for the tone-mapped image (overrides the scene).
    #[arg(long, value_enum)]
    tone_map: Option<ToneMapArg>,
    /// The light transport algorithm (overrides the scene's `[render] integrator`).
    #[arg(long, value_enum)]
    integrator: Option<IntegratorArg>,
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
    /// `--threads 0`.
    #[error("--threads must be at least 1")]
    NoThreads,
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
    /// A folder for the output cannot be made.
    #[error("{}: cannot create the folder: {source}", path.display())]
    Io {
        /// The folder.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
}

/// Prints warnings to standard error, one `file:line:col: warning in `key`: ...` each.
fn print_warnings(warnings: &[Diagnostic]) {
    for warning in warnings {
        eprintln!("{warning}");
    }
}

/// Loads the scene file at `path` and prints what loading warns about.
fn load_and_warn(path: &Path) -> Result<Scene, CliError> {
    let scene = load_file(path, &plugins::registry())?;
    print_warnings(&scene.warnings);
    Ok(scene)
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        None => render_default(),
        Some(Command::Render(args)) => render_command(&args),
        Some(Command::Shapes) => {
            print!("{}", prism::registry::describe(&plugins::registry()));
            Ok(())
        }
        Some(Command::Save { scene, output }) => save_command(&scene, output.as_deref()),
        Some(Command::Schema { output }) => schema_command(output.as_deref()),
        Some(Command::Export(ExportCommand::Pov { scene, output })) => export_pov_command(&scene, output.as_deref()),
        Some(Command::Export(ExportCommand::Mitsuba { scene, output })) => export_mitsuba_command(&scene, &output),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("{error}");
            ExitCode::FAILURE
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
    let scene = load_and_warn(&args.scene)?;
    render_scene(scene, args)
}

fn render_scene(mut scene: Scene, args: &RenderArgs) -> Result<(), CliError> {
    let settings = &mut scene.render;
    if let Some(w) = args.width {
        settings.width = w;
    }
    if let Some(h) = args.height {
        settings.height = h;
    }
    if let Some(s) = args.samples {
        settings.samples = s;
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
    if args.threads == Some(0) {
        return Err(CliError::NoThreads);
    }
    let mut outputs: Vec<PathBuf> = args.output.iter().chain(args.exr.iter()).cloned().collect();
    if outputs.is_empty() {
        let stem = args.scene.file_stem().map_or("prism".into(), |s| s.to_string_lossy().into_owned());
        outputs.push(PathBuf::from(format!("{stem}.png")));
    }
    if let Some(exr) = &args.exr
        && output::format_for(exr)? != output::OutputFormat::Exr
    {
        return Err(CliError::ExrExtension { path: exr.clone() });
    }
    // Fail before rendering, not after: bad paths and formats are found now.
    for path in &outputs {
        output::check_writable(path)?;
    }
    let render_scene = prepare(&mut scene)?;
    print_warnings(&prism::world::validate::warnings(&scene));
    let options =
        RenderOptions { threads: args.threads, progress: std::io::stderr().is_terminal(), ..Default::default() };
    let (film, stats) = render_frame(&render_scene, &options)?;
    let image =
        output::ImageSettings { exposure: scene.render.exposure, tone_map: scene.render.tone_map, exr_half: args.half };
    for path in &outputs {
        output::write_image(&film, path, &image)?;
    }
    let names: Vec<String> = outputs.iter().map(|p| p.display().to_string()).collect();
    eprintln!(
        "rendered {}x{} at {} spp in {:.3} s: {} primary rays, {} rays in all, {:.2} Mrays/s -> {}",
        scene.render.width,
        scene.render.height,
        scene.render.samples,
        stats.elapsed.as_secs_f64(),
        stats.primary_rays,
        stats.total_rays,
        stats.mrays_per_second(),
        names.join(", ")
    );
    Ok(())
}

fn save_command(path: &Path, output: Option<&Path>) -> Result<(), CliError> {
    let scene = load_and_warn(path)?;
    // Written to a file, mesh and texture paths are relative to it; on standard output,
    // whose destination is unknown, they stay absolute.
    let text = match output {
        Some(out) => prism::scene::save::save_for(&scene, out),
        None => prism::scene::save::save(&scene),
    };
    let text = text.map_err(|source| CliError::Save { path: path.to_path_buf(), source })?;
    match output {
        Some(out) => Ok(output::write_atomically(out, text.as_bytes())?),
        None => {
            print!("{text}");
            Ok(())
        }
    }
}

fn schema_command(output: Option<&Path>) -> Result<(), CliError> {
    let schema = prism::scene::schema::scene_schema(&plugins::registry());
    let text = serde_json::to_string_pretty(&schema)? + "\n";
    match output {
        Some(out) => Ok(output::write_atomically(out, text.as_bytes())?),
        None => {
            print!("{text}");
            Ok(())
        }
    }
}

fn export_mitsuba_command(path: &Path, output: &Path) -> Result<(), CliError> {
    let mut scene = load_and_warn(path)?;
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

fn export_pov_command(path: &Path, output: Option<&Path>) -> Result<(), CliError> {
    let mut scene = load_and_warn(path)?;
    prism::world::transforms::resolve_transforms(&mut scene)?;
    prism::world::validate::validate(&scene)?;
    let source = path.file_name().map_or_else(|| path.display().to_string(), |n| n.to_string_lossy().into_owned());
    let text = prism::export::pov::export(&scene, &source)?;
    match output {
        Some(out) => Ok(output::write_atomically(out, text.as_bytes())?),
        None => {
            print!("{text}");
            Ok(())
        }
    }
}
