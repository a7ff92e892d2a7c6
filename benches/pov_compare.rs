//! Prism and POV-Ray side by side on the same scenes: every parity scene and the seed room,
//! at 1000 x 563 with and without antialiasing, each renderer as a whole process (`prism
//! render` and `povray` on the file `prism export pov` writes), same size, same samples; and
//! POV-Ray's sample scenes of `scenes/povray-examples` (rows `example-NAME`), where POV-Ray
//! renders the original file, at the benchmark's width and the scene's own aspect ratio.
//! Prints wall time, CPU time, their ratios, each renderer's own render-only time, and the
//! difference between the two images.
//!
//! ```text
//! cargo bench --bench pov_compare -- [--runs N] [--threads 1,2] [--size 1000x563] [--aa-only] [NAME...]
//! ```
//!
//! `--aa-only` times only the antialiased variant (the one the 4K comparison is about).
//!
//! Both write the same file: a half-float, ZIP-compressed OpenEXR (POV-Ray's `+FE`, Prism's
//! `--half --exr`).
//!
//! Focal blur is random sampling, where the fair comparison is at equal image error: the
//! benchmark first finds, at the scene's own size, how many lens samples Prism needs for an
//! RMSE against a converged POV-Ray render (25 times the scene's samples) no larger than
//! POV-Ray's at the scene's count, then adds an "equal error" row that times Prism at that
//! count against POV-Ray at the scene's.
//!
//! "aa" is the scene's own POV-Ray antialiasing method, else method 1 with threshold 0.3 and
//! depth 3 (`+A0.3 +AM1 +R3 -J`), which both renderers sample identically. Each figure is the
//! best of `--runs` runs (default 3): the machine is shared, and the best run is the one
//! least disturbed. Needs `povray` (Debian: `apt-get install povray`).

use std::fs::File;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::Instant;

use prism::output::{read_exr, srgb_encode};

struct Options {
    runs: usize,
    threads: Vec<usize>,
    size: (u32, u32),
    names: Vec<String>,
    aa_only: bool,
}

fn options() -> Options {
    let mut o = Options { runs: 3, threads: vec![1, 2], size: (1000, 563), names: Vec::new(), aa_only: false };
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        let mut value = || args.next().unwrap_or_else(|| panic!("{a} needs a value"));
        match a.as_str() {
            "--runs" => o.runs = value().parse().expect("--runs N"),
            "--threads" => o.threads = value().split(',').map(|t| t.parse().expect("--threads 1,2")).collect(),
            "--size" => {
                let v = value();
                let (w, h) = v.split_once('x').expect("--size WxH");
                o.size = (w.parse().expect("width"), h.parse().expect("height"));
            }
            "--aa-only" => o.aa_only = true,
            // `cargo bench` passes --bench; other harness flags do not apply.
            flag if flag.starts_with("--") => {}
            name => o.names.push(name.to_string()),
        }
    }
    o
}

/// One measured process: wall seconds, CPU seconds (user + system), and its stderr.
struct Run {
    wall: f64,
    cpu: f64,
    log: String,
}

fn children_cpu() -> f64 {
    // SAFETY: getrusage only writes the struct it is given.
    let usage = unsafe {
        let mut usage: libc::rusage = std::mem::zeroed();
        libc::getrusage(libc::RUSAGE_CHILDREN, &mut usage);
        usage
    };
    let seconds = |t: libc::timeval| t.tv_sec as f64 + t.tv_usec as f64 * 1e-6;
    seconds(usage.ru_utime) + seconds(usage.ru_stime)
}

fn measure(mut command: Command, log: &Path) -> Run {
    let cpu = children_cpu();
    let start = Instant::now();
    let status = command
        .stdout(Stdio::null())
        .stderr(File::create(log).expect("log file"))
        .status()
        .unwrap_or_else(|e| panic!("cannot start {command:?}: {e}"));
    let wall = start.elapsed().as_secs_f64();
    assert!(status.success(), "{command:?} failed, see {}", log.display());
    let log = std::fs::read_to_string(log).unwrap_or_default();
    Run { wall, cpu: children_cpu() - cpu, log }
}

fn best(runs: Vec<Run>) -> Run {
    runs.into_iter().min_by(|a, b| a.wall.total_cmp(&b.wall)).expect("at least one run")
}

/// Prism's own render time ("rendered ... in X s"), from its summary line: a warning before
/// it may say " in " too.
fn prism_render_time(log: &str) -> Option<f64> {
    let summary = log.lines().find(|line| line.starts_with("rendered "))?;
    summary.split(" in ").nth(1)?.split(" s").next()?.trim().parse().ok()
}

/// POV-Ray's "Trace Time: ... (X seconds)".
fn povray_trace_time(log: &str) -> Option<f64> {
    let line = log.lines().find(|l| l.contains("Trace Time"))?;
    line.rsplit('(').next()?.split_whitespace().next()?.parse().ok()
}

/// RMSE in linear light and the percentage of pixels off by more than 2/255 after sRGB
/// encoding, as tests/parity.rs measures them.
fn image_error(a: &Path, b: &Path) -> (f64, f64) {
    let (a, b) = (read_exr(a).expect("prism image"), read_exr(b).expect("povray image"));
    assert_eq!((a.width, a.height), (b.width, b.height));
    let enc = |v: f32| srgb_encode(f64::from(v).clamp(0.0, 1.0));
    let (mut sum, mut over) = (0.0, 0usize);
    for (p, q) in a.pixels.iter().zip(&b.pixels) {
        let mut worst: f64 = 0.0;
        for c in 0..3 {
            sum += (f64::from(p[c]) - f64::from(q[c])).powi(2);
            worst = worst.max((enc(p[c]) - enc(q[c])).abs());
        }
        over += usize::from(worst > 2.0 / 255.0);
    }
    let n = a.pixels.len() as f64;
    ((sum / (3.0 * n)).sqrt(), 100.0 * over as f64 / n)
}

/// RMSE in linear light between two EXR files.
fn rmse(a: &Path, b: &Path) -> f64 {
    image_error(a, b).0
}

/// The lens samples POV-Ray takes per pixel in an exported scene (`blur_samples N`).
fn blur_samples(pov: &str) -> Option<u32> {
    let line = pov.lines().find(|l| l.trim_start().starts_with("blur_samples"))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

/// Equal-error calibration of a focal-blur scene at its own size: POV-Ray's sample count,
/// its RMSE against a converged POV-Ray render, the fewest Prism samples with no larger
/// RMSE, and that RMSE. `None` for scenes without focal blur.
fn equal_error_samples(prism: &str, scene: &Path, work: &Path) -> Option<(u32, f64, u32, f64)> {
    let pov = work.join("calibration.pov");
    let status = Command::new(prism).args(["export", "pov"]).arg(scene).arg("-o").arg(&pov).status().unwrap();
    assert!(status.success(), "export of {} failed", scene.display());
    let text = std::fs::read_to_string(&pov).unwrap();
    let samples = blur_samples(&text)?;
    let options: Vec<String> =
        prism::export::pov::options_of(&text).expect("options line").split_whitespace().map(String::from).collect();
    let povray = |pov: &Path, out: &Path| {
        let status = Command::new("povray")
            .arg(pov)
            .args(&options)
            .args(["-D", "+WT2", "+FE"])
            .arg(format!("+L{}", work.display()))
            .arg(format!("+O{}", out.display()))
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .status()
            .unwrap();
        assert!(status.success(), "povray failed on {}", pov.display());
    };
    let converged = work.join("calibration-converged.pov");
    let many = format!("blur_samples {}", 25 * samples);
    std::fs::write(&converged, text.replace(&format!("blur_samples {samples}"), &many)).unwrap();
    let reference = work.join("calibration-reference.exr");
    povray(&converged, &reference);
    let theirs = work.join("calibration-povray.exr");
    povray(&pov, &theirs);
    let target = rmse(&theirs, &reference);
    let ours = work.join("calibration-prism.exr");
    for n in 1..=samples {
        let status = Command::new(prism)
            .arg("render")
            .arg(scene)
            .args(["--samples", &n.to_string(), "--exr"])
            .arg(&ours)
            .stderr(Stdio::null())
            .status()
            .unwrap();
        assert!(status.success(), "prism failed on {}", scene.display());
        let error = rmse(&ours, &reference);
        if error <= target || n == samples {
            return Some((samples, target, n, error));
        }
    }
    None
}

fn main() {
    let o = options();
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    if Command::new("povray").arg("--version").stdout(Stdio::null()).stderr(Stdio::null()).status().is_err() {
        eprintln!("error: povray is not installed; install it with: apt-get install povray");
        std::process::exit(1);
    }
    let prism = env!("CARGO_BIN_EXE_prism");
    let work = Path::new(env!("CARGO_TARGET_TMPDIR")).join("pov_compare");
    std::fs::create_dir_all(&work).unwrap();

    let mut scenes: Vec<(String, PathBuf)> = std::fs::read_dir(root.join("scenes/parity"))
        .unwrap()
        .filter_map(|e| {
            let p = e.ok()?.path();
            (p.extension()? == "toml").then(|| (p.file_stem().unwrap().to_string_lossy().into_owned(), p))
        })
        .collect();
    scenes.sort();
    scenes.push(("seed-room".into(), root.join("scenes/room.toml")));
    // POV-Ray's own sample scenes, which POV-Ray renders from the original file.
    let mut examples: Vec<(String, PathBuf)> = std::fs::read_dir(root.join("scenes/povray-examples"))
        .unwrap()
        .filter_map(|e| {
            let p = e.ok()?.path();
            (p.extension()? == "toml").then(|| (format!("example-{}", p.file_stem().unwrap().to_string_lossy()), p))
        })
        .collect();
    examples.sort();
    scenes.extend(examples);
    if !o.names.is_empty() {
        scenes.retain(|(n, _)| o.names.contains(n));
    }

    let (w, h) = o.size;
    println!(
        "{w}x{h}, best of {} runs; wall and CPU of the whole process (POV-Ray's include ~0.6 s of start-up)",
        o.runs
    );
    println!("render = each renderer's own render time (Prism's \"rendered in\", POV-Ray's \"Trace Time\")\n");
    println!(
        "| scene | AA | threads | Prism wall s | POV wall s | wall ratio | Prism CPU s | POV CPU s | CPU ratio | Prism render s | POV trace s | RMSE | % > 2/255 |"
    );
    println!("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |");
    // The antialiased rows' wall ratios, for the summary under the table.
    let mut antialiased: Vec<(String, f64)> = Vec::new();
    for (name, path) in &scenes {
        let text = std::fs::read_to_string(path).unwrap();
        let own_method = text.lines().find(|l| l.trim_start().starts_with("antialias"));
        // (label, antialias line, Prism's samples when they differ from POV-Ray's)
        let mut variants: Vec<(String, String, Option<u32>)> = Vec::new();
        variants.push(("noaa".into(), "antialias = { method = \"stratified\" }".into(), None));
        let aa_line = match own_method {
            Some(line) => line.trim().to_string(),
            None => "antialias = { method = \"pov1\", threshold = 0.3, depth = 3 }".to_string(),
        };
        variants.push(("aa".into(), aa_line, None));
        if o.aa_only {
            variants.remove(0);
        } else if text.contains("parity-tolerance")
            && let Some((pov_samples, pov_error, prism_samples, prism_error)) = equal_error_samples(prism, path, &work)
        {
            println!(
                "<!-- {name}: at its own size, POV-Ray's {pov_samples} lens samples give RMSE {pov_error:.2e} against 25x as many; Prism's {prism_samples} give {prism_error:.2e} -->"
            );
            variants.push(("equal-error".into(), variants[0].1.clone(), Some(prism_samples)));
        }
        // An original sample scene keeps its aspect ratio at the benchmark's width.
        let original_options = text.lines().find_map(|l| l.strip_prefix("# povray-options:")).map(str::trim);
        let (w, h) = match original_options {
            Some(options) => {
                let size = |flag: &str| -> f64 {
                    options.split_whitespace().find_map(|t| t.strip_prefix(flag)?.parse().ok()).expect("+W and +H")
                };
                (w, (f64::from(w) * size("+H") / size("+W")).round() as u32)
            }
            None => (w, h),
        };
        for (variant, antialias, prism_samples) in &variants {
            // The scene at the benchmark size and sampling, by including it.
            let tag = format!("{name}-{variant}");
            let toml = work.join(format!("{tag}.toml"));
            let include = path.display().to_string().replace('\\', "/");
            std::fs::write(
                &toml,
                format!("include = [\"{include}\"]\n\n[render]\nwidth = {w}\nheight = {h}\n{antialias}\n"),
            )
            .unwrap();
            let (pov, pov_options) = match original_options {
                Some(options) => {
                    // The original file, at the benchmark's size with the antialiasing asked for.
                    let aa = if variant == "noaa" { "-A" } else { "+A0.3 +AM1 +R3" };
                    let kept: Vec<&str> = options
                        .split_whitespace()
                        .filter(|t| {
                            !t.starts_with("+W") && !t.starts_with("+H") && !t.starts_with("+A") && !t.starts_with("+R")
                        })
                        .collect();
                    (path.with_extension("pov"), format!("+W{w} +H{h} {aa} {}", kept.join(" ")))
                }
                None => {
                    let pov = work.join(format!("{tag}.pov"));
                    let status =
                        Command::new(prism).args(["export", "pov"]).arg(&toml).arg("-o").arg(&pov).status().unwrap();
                    assert!(status.success(), "export of {tag} failed");
                    let pov_text = std::fs::read_to_string(&pov).unwrap();
                    (pov, prism::export::pov::options_of(&pov_text).expect("options line").to_string())
                }
            };
            let aa_label: String = pov_options
                .split_whitespace()
                .filter(|t| !t.starts_with("+W") && !t.starts_with("+H"))
                .collect::<Vec<_>>()
                .join(" ");
            for &threads in &o.threads {
                let ours = work.join(format!("{tag}-{threads}.prism.exr"));
                let theirs = work.join(format!("{tag}-{threads}.povray.exr"));
                let prism_run = best(
                    (0..o.runs)
                        .map(|_| {
                            let mut c = Command::new(prism);
                            c.arg("render").arg(&toml);
                            if let Some(n) = prism_samples {
                                c.args(["--samples", &n.to_string()]);
                            }
                            c.arg("--threads").arg(threads.to_string()).arg("--half").arg("--exr").arg(&ours);
                            measure(c, &work.join(format!("{tag}.prism.log")))
                        })
                        .collect(),
                );
                let pov_run = best(
                    (0..o.runs)
                        .map(|_| {
                            let mut c = Command::new("povray");
                            c.arg(&pov).args(pov_options.split_whitespace());
                            c.args(["-D", &format!("+WT{threads}"), "+FE"]).arg(format!("+O{}", theirs.display()));
                            // Files the scene reads are written relative to the .pov's folder.
                            c.arg(format!("+L{}", pov.parent().unwrap_or(Path::new(".")).display()));
                            measure(c, &work.join(format!("{tag}.povray.log")))
                        })
                        .collect(),
                );
                let (rmse, over) = image_error(&ours, &theirs);
                if variant == "aa" {
                    antialiased.push((format!("{name} ({threads} threads)"), pov_run.wall / prism_run.wall));
                }
                let show = |t: Option<f64>| t.map_or("?".into(), |t| format!("{t:.3}"));
                println!(
                    "| {name} | {} | {threads} | {:.3} | {:.3} | {:.2}x | {:.3} | {:.3} | {:.2}x | {} | {} | {rmse:.1e} | {over:.2} |",
                    match (variant.as_str(), prism_samples) {
                        ("aa", _) => aa_label.clone(),
                        (_, Some(n)) => format!("no; equal error: Prism {n} spp"),
                        _ => "no".to_string(),
                    },
                    prism_run.wall,
                    pov_run.wall,
                    pov_run.wall / prism_run.wall,
                    prism_run.cpu,
                    pov_run.cpu,
                    pov_run.cpu / prism_run.cpu,
                    show(prism_render_time(&prism_run.log)),
                    show(povray_trace_time(&pov_run.log)),
                );
            }
        }
    }
    print_summary(&antialiased);
}

/// Issue 17's measure under the table: how many antialiased rows reach 5x POV-Ray's wall
/// time, their mean ratio and the lowest rows.
fn print_summary(rows: &[(String, f64)]) {
    if rows.is_empty() {
        return;
    }
    let at_five = rows.iter().filter(|(_, ratio)| *ratio >= 5.0).count();
    let mean = rows.iter().map(|(_, ratio)| ratio).sum::<f64>() / rows.len() as f64;
    let mut lowest: Vec<&(String, f64)> = rows.iter().collect();
    lowest.sort_by(|a, b| a.1.total_cmp(&b.1));
    let lowest: Vec<String> = lowest.iter().take(5).map(|(name, ratio)| format!("{name} {ratio:.2}x")).collect();
    println!(
        "\nantialiased rows at 5x POV-Ray's wall time or more: {at_five} of {}; mean {mean:.2}x; lowest: {}",
        rows.len(),
        lowest.join(", ")
    );
}
