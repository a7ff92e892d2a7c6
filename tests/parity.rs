//! Parity with POV-Ray 3.7: every scene in `scenes/parity/` renders like its POV-Ray
//! reference, `scenes/parity/NAME.exr` (committed, rendered by POV-Ray from `NAME.pov`, which
//! Prism's exporter wrote), and every scene in `scenes/povray-examples/` like the reference
//! POV-Ray renders from the original sample scene `NAME.pov` beside it. Images are compared in
//! linear light (Prism's image rounded to half floats, the references' precision): RMSE at
//! most 1e-3 and at most 0.5 % of the pixels off by more than 2/255 after sRGB encoding,
//! unless the scene file states a statistical tolerance and its reason
//! (`# parity-tolerance:` / `# parity-reason:`).
//!
//! With `PRISM_PARITY_REFS=DIR` the scenes are also compared with the references in DIR and
//! `DIR/povray-examples` (rendered afresh by `scripts/povray-references.sh DIR` and
//! `scripts/povray-example-references.sh DIR/povray-examples`, as CI does), so the check is
//! live. A failure writes Prism's image, the reference and a false-colour difference image to
//! `target/parity/` and prints the command that regenerates the reference. A missing
//! reference fails.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use exr::prelude::f16;
use prism::film::Film;
use prism::output::{read_exr, srgb_encode};
use prism::render::{RenderOptions, render_frame};
use prism::scene::load::load_file;
use prism::{plugins, prepare};

/// Default limits (REPORT.md section 10).
const RMSE: f64 = 1e-3;
const PERCENT: f64 = 0.5;
/// The per-pixel threshold, in sRGB-encoded units.
const PIXEL_THRESHOLD: f64 = 2.0 / 255.0;
/// Side of the blocks averaged for the statistical comparison.
const BLOCK: usize = 4;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A set of parity scenes: a directory of `NAME.toml` with their references `NAME.exr`.
#[derive(Clone, Copy)]
struct Suite {
    /// The scenes' directory, relative to the repository.
    dir: &'static str,
    /// Where the live references of this suite lie under `PRISM_PARITY_REFS`.
    live_subdir: &'static str,
    /// The script that renders the references: `SCRIPT OUTDIR NAME`.
    script: &'static str,
}

/// Scenes written by hand, their `.pov` files by Prism's exporter.
const PARITY: Suite = Suite { dir: "scenes/parity", live_subdir: "", script: "scripts/povray-references.sh" };
/// POV-Ray's own sample scenes, their `.pov` files the originals (see its README).
const EXAMPLES: Suite = Suite {
    dir: "scenes/povray-examples",
    live_subdir: "povray-examples",
    script: "scripts/povray-example-references.sh",
};

fn scenes(suite: Suite) -> Vec<String> {
    let dir = root().join(suite.dir);
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .filter_map(|e| {
            let path = e.ok()?.path();
            (path.extension()? == "toml").then(|| path.file_stem().unwrap().to_string_lossy().into_owned())
        })
        .collect();
    names.sort();
    names
}

/// Acceptance limits of one scene.
#[derive(Debug, PartialEq)]
struct Tolerance {
    rmse: f64,
    percent: f64,
    /// RMSE of BLOCK x BLOCK pixel means (statistical scenes only).
    blurred_rmse: Option<f64>,
}

/// The limits a scene file states in `# parity-tolerance: key = value, ...` (keys `rmse`,
/// `percent`, `blurred-rmse`), which must come with a `# parity-reason:`.
fn tolerance(text: &str) -> Result<Tolerance, String> {
    let mut t = Tolerance { rmse: RMSE, percent: PERCENT, blurred_rmse: None };
    let Some(line) = text.lines().find_map(|l| l.strip_prefix("# parity-tolerance:")) else {
        return Ok(t);
    };
    if !text.lines().any(|l| l.starts_with("# parity-reason:")) {
        return Err("a parity-tolerance needs a `# parity-reason:` line saying why".into());
    }
    for item in line.split(',') {
        let (key, value) = item.split_once('=').ok_or_else(|| format!("`{item}` is not `key = value`"))?;
        let value: f64 = value.trim().parse().map_err(|e| format!("`{item}`: {e}"))?;
        match key.trim() {
            "rmse" => t.rmse = value,
            "percent" => t.percent = value,
            "blurred-rmse" => t.blurred_rmse = Some(value),
            other => return Err(format!("unknown parity-tolerance key `{other}`")),
        }
    }
    Ok(t)
}

/// How two images differ.
#[derive(Debug)]
struct Difference {
    rmse: f64,
    percent: f64,
    blurred_rmse: f64,
    /// Largest sRGB-encoded channel difference of each pixel.
    per_pixel: Vec<f64>,
}

fn encoded(v: f32) -> f64 {
    srgb_encode(f64::from(v).clamp(0.0, 1.0))
}

/// `v` rounded to a half float, the precision of the references (POV-Ray writes half-float
/// OpenEXR): far outside [0, 1], where the spacing of halves reaches 1/64 at 16, comparing
/// unrounded values would measure the reference's rounding, not the renderers.
fn as_stored(v: f32) -> f32 {
    f16::from_f32(v).to_f32()
}

fn difference(ours: &Film, reference: &Film) -> Difference {
    let mut sum = 0.0;
    let mut per_pixel = Vec::with_capacity(ours.pixels.len());
    for (a, b) in ours.pixels.iter().zip(&reference.pixels) {
        let a = a.map(as_stored);
        let mut worst: f64 = 0.0;
        for c in 0..3 {
            let d = f64::from(a[c]) - f64::from(b[c]);
            sum += d * d;
            worst = worst.max((encoded(a[c]) - encoded(b[c])).abs());
        }
        per_pixel.push(worst);
    }
    let over = per_pixel.iter().filter(|&&d| d > PIXEL_THRESHOLD).count();
    let (w, h) = (ours.width as usize, ours.height as usize);
    let (bw, bh) = (w / BLOCK, h / BLOCK);
    let mut blurred = 0.0;
    for by in 0..bh {
        for bx in 0..bw {
            let mut d = [0.0f64; 3];
            for y in by * BLOCK..(by + 1) * BLOCK {
                for x in bx * BLOCK..(bx + 1) * BLOCK {
                    let (a, b) = (ours.pixels[y * w + x].map(as_stored), reference.pixels[y * w + x]);
                    for c in 0..3 {
                        d[c] += f64::from(a[c]) - f64::from(b[c]);
                    }
                }
            }
            let n = (BLOCK * BLOCK) as f64;
            blurred += d.iter().map(|v| (v / n) * (v / n)).sum::<f64>();
        }
    }
    Difference {
        rmse: (sum / (3 * ours.pixels.len()) as f64).sqrt(),
        percent: 100.0 * over as f64 / ours.pixels.len() as f64,
        blurred_rmse: (blurred / (3 * bw * bh).max(1) as f64).sqrt(),
        per_pixel,
    }
}

/// Black where equal; blue through green and yellow to red at 16/255 and more; pixels within
/// the 2/255 threshold are dimmed so the failing ones stand out.
fn false_colour(d: f64) -> [u8; 3] {
    if d == 0.0 {
        return [0, 0, 0];
    }
    let t = (d * 255.0 / 16.0).clamp(0.0, 1.0);
    let stops = [[0.0, 0.0, 1.0], [0.0, 1.0, 1.0], [0.0, 1.0, 0.0], [1.0, 1.0, 0.0], [1.0, 0.0, 0.0]];
    let x = t * 4.0;
    let i = (x.floor() as usize).min(3);
    let f = x - i as f64;
    let dim = if d > PIXEL_THRESHOLD { 1.0 } else { 0.3 };
    let mut out = [0u8; 3];
    for c in 0..3 {
        out[c] = ((stops[i][c] * (1.0 - f) + stops[i + 1][c] * f) * dim * 255.0).round() as u8;
    }
    out
}

fn write_artifacts(dir: &Path, name: &str, ours: &Film, reference: &Film, d: &Difference) -> std::io::Result<()> {
    std::fs::create_dir_all(dir)?;
    let image = prism::output::ImageSettings::default();
    let io = |e: prism::output::OutputError| std::io::Error::other(e.to_string());
    prism::output::write_image(ours, &dir.join(format!("{name}.prism.png")), &image).map_err(io)?;
    prism::output::write_image(ours, &dir.join(format!("{name}.prism.exr")), &image).map_err(io)?;
    prism::output::write_image(reference, &dir.join(format!("{name}.povray.png")), &image).map_err(io)?;
    let mut diff = image::RgbImage::new(ours.width, ours.height);
    for (p, &v) in diff.pixels_mut().zip(&d.per_pixel) {
        p.0 = false_colour(v);
    }
    diff.save(dir.join(format!("{name}.diff.png"))).map_err(std::io::Error::other)
}

fn render_scene(suite: Suite, name: &str) -> Film {
    let path = root().join(format!("{}/{name}.toml", suite.dir));
    let mut scene = load_file(&path, &plugins::registry()).unwrap_or_else(|e| panic!("{e}"));
    let render_scene = prepare(&mut scene).unwrap_or_else(|e| panic!("{e}"));
    render_frame(&render_scene, &RenderOptions::default()).expect("render").0
}

/// One comparison's line in the report, or `Err` with the reason it failed.
fn check(
    suite: Suite,
    name: &str,
    ours: &Film,
    reference: &Path,
    limits: &Tolerance,
    live: bool,
) -> Result<String, String> {
    let regenerate = if live {
        format!("{} {} {name}", suite.script, reference.parent().unwrap_or(Path::new(".")).display())
    } else {
        format!("{} {} {name}", suite.script, suite.dir)
    };
    if !reference.exists() {
        return Err(format!("{name}: reference {} is missing; render it with: {regenerate}", reference.display()));
    }
    let mut reference_film = read_exr(reference).map_err(|e| e.to_string())?;
    // POV-Ray writes a NaN channel (`pow` of a negative colour) into its EXR as NaN, into
    // its PNG as 0; Prism writes 0.
    for pixel in &mut reference_film.pixels {
        for c in pixel.iter_mut().filter(|c| c.is_nan()) {
            *c = 0.0;
        }
    }
    if (reference_film.width, reference_film.height) != (ours.width, ours.height) {
        return Err(format!(
            "{name}: reference is {}x{}, Prism renders {}x{}; regenerate it with: {regenerate}",
            reference_film.width, reference_film.height, ours.width, ours.height
        ));
    }
    let d = difference(ours, &reference_film);
    let mut line = format!(
        "{name:<16} rmse {:.2e} (<= {})  over 2/255 {:.3} % (<= {})",
        d.rmse, limits.rmse, d.percent, limits.percent
    );
    let mut ok = d.rmse <= limits.rmse && d.percent <= limits.percent;
    if let Some(b) = limits.blurred_rmse {
        let _ = write!(line, "  {BLOCK}x{BLOCK} rmse {:.2e} (<= {b})", d.blurred_rmse);
        ok &= d.blurred_rmse <= b;
    }
    if live {
        line.push_str("  [live]");
    }
    if ok {
        return Ok(line);
    }
    // CARGO_TARGET_TMPDIR is `<target>/tmp`.
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).parent().unwrap_or(Path::new("target")).join("parity");
    let written = match write_artifacts(&dir, name, ours, &reference_film, &d) {
        Ok(()) => format!("images in {}/{name}.{{prism,povray,diff}}.png", dir.display()),
        Err(e) => format!("could not write the difference images: {e}"),
    };
    Err(format!("{line}\n  FAILED: {written}\n  regenerate the reference with: {regenerate}"))
}

/// Renders every scene of `suite` and compares it with its committed reference and, with
/// `live`, the fresh one; returns the report lines and the failures.
fn run_suite(suite: Suite, live: Option<&Path>) -> (Vec<String>, Vec<String>) {
    let mut report = Vec::new();
    let mut failures = Vec::new();
    for name in &scenes(suite) {
        let text = std::fs::read_to_string(root().join(format!("{}/{name}.toml", suite.dir))).unwrap();
        let limits = match tolerance(&text) {
            Ok(t) => t,
            Err(e) => {
                failures.push(format!("{name}: {e}"));
                continue;
            }
        };
        let ours = render_scene(suite, name);
        let mut references = vec![(root().join(format!("{}/{name}.exr", suite.dir)), false)];
        if let Some(dir) = live {
            references.push((dir.join(suite.live_subdir).join(format!("{name}.exr")), true));
        }
        for (reference, is_live) in references {
            match check(suite, name, &ours, &reference, &limits, is_live) {
                Ok(line) => report.push(line),
                Err(e) => failures.push(e),
            }
        }
    }
    (report, failures)
}

#[test]
fn scenes_match_pov_ray() {
    let names = scenes(PARITY);
    assert!(names.len() >= 16, "the parity suite has only {} scenes", names.len());
    let live = std::env::var_os("PRISM_PARITY_REFS").map(PathBuf::from);
    let (report, failures) = run_suite(PARITY, live.as_deref());
    println!("{}", report.join("\n"));
    assert!(failures.is_empty(), "{} parity failure(s):\n{}", failures.len(), failures.join("\n"));
}

#[test]
fn povray_examples_match_pov_ray() {
    let names = scenes(EXAMPLES);
    assert!(names.len() >= 4, "scenes/povray-examples has only {} scenes", names.len());
    for name in &names {
        let original = root().join(format!("{}/{name}.pov", EXAMPLES.dir));
        assert!(original.exists(), "{name}: the original {} is missing", original.display());
        let text = std::fs::read_to_string(root().join(format!("{}/{name}.toml", EXAMPLES.dir))).unwrap();
        let options = text.lines().find_map(|l| l.strip_prefix("# povray-options:"));
        assert!(
            options.is_some_and(|o| o.split_whitespace().any(|w| w == "-J")),
            "{name}.toml needs a `# povray-options:` line (without jitter, -J) for {}",
            EXAMPLES.script
        );
    }
    let live = std::env::var_os("PRISM_PARITY_REFS").map(PathBuf::from);
    let (report, failures) = run_suite(EXAMPLES, live.as_deref());
    println!("{}", report.join("\n"));
    assert!(failures.is_empty(), "{} parity failure(s):\n{}", failures.len(), failures.join("\n"));
}

#[test]
fn committed_pov_files_are_current() {
    let mut stale = Vec::new();
    // Only the exported scenes: the examples' .pov files are POV-Ray's originals.
    for name in scenes(PARITY) {
        let path = root().join(format!("scenes/parity/{name}.toml"));
        let mut scene = load_file(&path, &plugins::registry()).unwrap_or_else(|e| panic!("{e}"));
        prism::world::transforms::resolve_transforms(&mut scene).unwrap();
        prism::world::validate::validate(&scene).unwrap();
        let folder = root().join(PARITY.dir);
        let exported = prism::export::pov::export(&scene, &format!("{name}.toml"), Some(&folder))
            .unwrap_or_else(|e| panic!("{e}"));
        let committed = std::fs::read_to_string(root().join(format!("scenes/parity/{name}.pov"))).unwrap_or_default();
        if exported != committed {
            stale.push(format!("{name}: scenes/parity/{name}.pov differs from what the exporter writes now"));
        }
    }
    assert!(
        stale.is_empty(),
        "{}\nregenerate the files and their references with: scripts/povray-references.sh",
        stale.join("\n")
    );
}

#[test]
fn tolerances_parse_and_need_a_reason() {
    assert_eq!(tolerance("[render]\n").unwrap(), Tolerance { rmse: RMSE, percent: PERCENT, blurred_rmse: None });
    let t = tolerance("# parity-tolerance: rmse = 0.02, percent = 30, blurred-rmse = 0.004\n# parity-reason: noise\n")
        .unwrap();
    assert_eq!(t, Tolerance { rmse: 0.02, percent: 30.0, blurred_rmse: Some(0.004) });
    assert!(tolerance("# parity-tolerance: rmse = 0.02\n").is_err(), "no reason");
    assert!(tolerance("# parity-tolerance: rsme = 0.02\n# parity-reason: x\n").is_err(), "unknown key");
}

#[test]
fn difference_counts_pixels_over_the_threshold() {
    let mut a = Film::new(8, 4);
    let b = Film::new(8, 4);
    a.pixels[0] = [0.5, 0.0, 0.0];
    let d = difference(&a, &b);
    assert!((d.percent - 100.0 / 32.0).abs() < 1e-12);
    assert!((d.rmse - (0.25f64 / 96.0).sqrt()).abs() < 1e-9);
    assert!((d.blurred_rmse - ((0.5f64 / 16.0).powi(2) / 6.0).sqrt()).abs() < 1e-9);
    assert_eq!(false_colour(0.0), [0, 0, 0]);
    assert_eq!(false_colour(1.0), [255, 0, 0]);
}
