//! Long renders (issue 14): AOV layers on the command line and in the EXR as OpenEXR's own
//! Python bindings read them, adaptive sampling (deterministic for any thread count, the
//! same image as before when off), time budgets (the kept image is the fixed-count render
//! of its sample count) and the bad input of each.

use std::path::{Path, PathBuf};
use std::process::Command;

use prism::film::{Aov, Film};
use prism::render::extract::RenderScene;
use prism::render::{RenderOptions, render_frame, render_within};

fn prism() -> Command {
    Command::new(env!("CARGO_BIN_EXE_prism"))
}

fn scene_path(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(name)
}

/// The path-traced Cornell box at `size` x `size` pixels and `samples` per pixel.
fn cornell(size: u32, samples: u32, noise: Option<f64>) -> RenderScene {
    let path = scene_path("scenes/mitsuba/cornell.toml");
    let mut scene = prism::scene::load::load_file(&path, &prism::plugins::registry()).unwrap();
    scene.render.width = size;
    scene.render.height = size;
    scene.render.samples = samples;
    scene.render.noise = noise;
    prism::prepare(&mut scene).unwrap()
}

fn render_with(scene: &RenderScene, threads: usize, aovs: &[Aov]) -> (Film, prism::render::RenderStats) {
    let options = RenderOptions { threads: Some(threads), aovs: aovs.to_vec(), ..Default::default() };
    render_frame(scene, &options).unwrap()
}

fn layer(film: &Film, aov: Aov) -> &[f32] {
    &film.layer(aov).unwrap().data
}

/// Every file in `dir`, by name.
fn files_in(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> =
        std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    names.sort();
    names
}

#[test]
fn adaptive_sampling_is_deterministic_and_spends_samples_where_the_noise_is() {
    let scene = cornell(24, 128, Some(0.015));
    let aovs = [Aov::Samples, Aov::Variance];
    let (one, stats) = render_with(&scene, 1, &aovs);
    let (two, _) = render_with(&scene, 2, &aovs);
    assert_eq!(one, two, "the same image and layers for one and two threads");
    let counts = layer(&one, Aov::Samples);
    let (min, max) = counts.iter().fold((f32::MAX, 0.0f32), |(lo, hi), &c| (lo.min(c), hi.max(c)));
    // The bright, flat walls stop early; the noisy corners go on to the limit.
    assert_eq!(min, (prism::render::SAMPLE_BATCH * prism::render::MIN_BATCHES) as f32);
    assert_eq!(max, 128.0);
    assert!(stats.samples.mean < 120.0 && stats.samples.mean > 32.0, "{:?}", stats.samples);
    assert_eq!(stats.primary_rays, counts.iter().map(|&c| c as u64).sum::<u64>());
    assert!(stats.noise > 0.0);
}

#[test]
fn without_a_noise_target_the_image_is_unchanged_and_every_pixel_takes_every_sample() {
    let scene = cornell(16, 24, None);
    let (plain, _) = render_with(&scene, 2, &[]);
    let (with_layers, stats) = render_with(&scene, 2, &[Aov::Samples, Aov::Variance]);
    assert_eq!(plain.pixels, with_layers.pixels, "the estimates leave the image bit-identical");
    assert!(layer(&with_layers, Aov::Samples).iter().all(|&c| c == 24.0));
    assert_eq!((stats.samples.min, stats.samples.max), (24, 24));
    // Three batches of 8 give a variance; it is positive where light bounces.
    let variance = layer(&with_layers, Aov::Variance);
    assert!(variance.iter().all(|v| v.is_finite() && *v >= 0.0));
    assert!(variance.iter().filter(|&&v| v > 0.0).count() > variance.len() / 2);
}

#[test]
fn a_time_budget_keeps_the_image_of_a_fixed_count_render() {
    let mut scene = cornell(16, 1, None);
    let options = RenderOptions { threads: Some(2), ..Default::default() };
    let run = render_within(&mut scene, &options, std::time::Duration::from_millis(600), 64).unwrap();
    let reached = scene.settings.samples;
    assert!(run.passes >= 2 && reached > 1 && reached <= 64, "{} passes, {reached} spp", run.passes);
    assert!(!run.stats.cancelled);
    let fixed = cornell(16, reached, None);
    assert_eq!(run.film, render_frame(&fixed, &options).unwrap().0, "{reached} spp");
}

/// A small scene for the command line: the Cornell box at 24 x 24 pixels and 4 spp.
fn small_scene(dir: &Path, extra_render_keys: &str) -> PathBuf {
    let text = std::fs::read_to_string(scene_path("scenes/mitsuba/cornell.toml")).unwrap();
    let assets = scene_path("assets").display().to_string();
    let text = text
        .replace("width = 64", "width = 24")
        .replace("height = 64", "height = 24")
        .replace("samples = 64", &format!("samples = 4\n{extra_render_keys}"))
        .replace("../../assets", &assets);
    let path = dir.join("cornell.toml");
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn every_aov_layer_reads_back_with_openexr_python_bindings() {
    let dir = tempfile::tempdir().unwrap();
    let scene = small_scene(dir.path(), "");
    let exr = dir.path().join("out.exr");
    let all = "albedo,normal,depth,position,uv,object_id,material_id,variance,samples";
    let out = prism().arg("render").arg(&scene).args(["--aov", all, "--aov-png", "--exr"]).arg(&exr).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("samples per pixel: min 4, median 4"), "{stderr}");
    for aov in Aov::ALL {
        let png = dir.path().join(format!("out.{}.png", aov.name()));
        let img = image::open(&png).unwrap_or_else(|e| panic!("{}: {e}", png.display())).to_rgb8();
        assert_eq!(img.dimensions(), (24, 24));
    }
    let script = r#"
import sys, OpenEXR
f = OpenEXR.File(sys.argv[1], separate_channels=True)
part = f.parts[0]
for name in sorted(part.channels):
    pixels = part.channels[name].pixels
    print(name, pixels.shape[1], pixels.shape[0], float(pixels.min()), float(pixels.max()))
"#;
    let run = Command::new("python3").args(["-c", script]).arg(&exr).output();
    let listing = match run {
        Ok(run) if run.status.success() => String::from_utf8_lossy(&run.stdout).into_owned(),
        other => {
            let why = match other {
                Ok(run) => String::from_utf8_lossy(&run.stderr).into_owned(),
                Err(e) => e.to_string(),
            };
            assert!(
                std::env::var("CI").as_deref() != Ok("true"),
                "OpenEXR's Python bindings are needed under CI=true (pip install OpenEXR): {why}"
            );
            eprintln!("skipping the OpenEXR Python check (pip install OpenEXR): {why}");
            return;
        }
    };
    let channels: Vec<&str> = listing.lines().filter_map(|l| l.split(' ').next()).collect();
    let mut expected = vec!["R", "G", "B"];
    for aov in Aov::ALL {
        for channel in aov.channels() {
            expected.push(Box::leak(format!("{}.{channel}", aov.name()).into_boxed_str()));
        }
    }
    for name in &expected {
        assert!(channels.contains(name), "{name} missing from the EXR as OpenEXR reads it:\n{listing}");
    }
    for line in listing.lines() {
        let fields: Vec<&str> = line.split(' ').collect();
        assert_eq!(&fields[1..3], ["24", "24"], "{line}");
        match fields[0] {
            "samples.count" => assert_eq!(&fields[3..], ["4.0", "4.0"], "{line}"),
            "normal.X" | "normal.Y" | "normal.Z" => {
                let (lo, hi): (f64, f64) = (fields[3].parse().unwrap(), fields[4].parse().unwrap());
                assert!((-1.0..=1.0).contains(&lo) && (-1.0..=1.0).contains(&hi) && hi > lo, "{line}");
            }
            _ => {}
        }
    }
}

#[test]
fn toml_settings_drive_aovs_and_adaptive_sampling() {
    let dir = tempfile::tempdir().unwrap();
    let scene = small_scene(dir.path(), "aovs = [\"depth\", \"samples\"]\nnoise = 0.5");
    let exr = dir.path().join("out.exr");
    let out = prism().arg("render").arg(&scene).args(["--samples", "64", "--exr"]).arg(&exr).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let stderr = String::from_utf8_lossy(&out.stderr);
    // A loose target stops most pixels at the first check, after MIN_BATCHES batches.
    let first_check = prism::render::SAMPLE_BATCH * prism::render::MIN_BATCHES;
    assert!(stderr.contains(&format!("samples per pixel: min {first_check}, median {first_check}")), "{stderr}");
    let bytes = std::fs::read(&exr).unwrap();
    for name in [&b"depth.Z"[..], b"samples.count"] {
        assert!(bytes.windows(name.len()).any(|w| w == name), "{}", String::from_utf8_lossy(name));
    }
}

#[test]
fn time_budget_on_the_command_line_reports_its_passes() {
    let dir = tempfile::tempdir().unwrap();
    let scene = small_scene(dir.path(), "");
    let png = dir.path().join("out.png");
    let out = prism().arg("render").arg(&scene).args(["--time", "0.5s", "--samples", "32", "-o"]).arg(&png).output();
    let out = out.unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(stderr.contains("time budget 0.5 s:") && stderr.contains("kept the last complete one"), "{stderr}");
    assert!(png.exists());
}

#[test]
fn bad_long_render_input_is_refused_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let scene = small_scene(dir.path(), "");
    let exr = dir.path().join("out.exr");
    let cases: [(&[&str], &str); 8] = [
        (&["--aov", "albedo,normals"], "did you mean `normal`?"),
        (&["--aov", "albedo,"], "unknown AOV ``"),
        (&["--noise", "0"], "between 0 and 1"),
        (&["--noise", "1.5"], "between 0 and 1"),
        (&["--noise", "nan"], "between 0 and 1"),
        (&["--time", "0"], "more than zero"),
        (&["--time", "10x"], "not a duration"),
        (&["--time", "m"], "not a duration"),
    ];
    for (args, message) in cases {
        let out = prism().arg("render").arg(&scene).args(args).arg("--exr").arg(&exr).output().unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{args:?} succeeded");
        assert!(stderr.contains(message), "{args:?}: {stderr}");
        assert_eq!(files_in(dir.path()), ["cornell.toml"], "{args:?} wrote something");
    }
    // AOVs asked for with nowhere to put them.
    let out = prism().arg("render").arg(&scene).args(["--aov", "depth", "-o"]).arg(dir.path().join("a.png")).output();
    let out = out.unwrap();
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("add --exr"));
    assert_eq!(files_in(dir.path()), ["cornell.toml"]);
    // The same mistakes in the scene file name the file, line and key.
    for (keys, message) in [
        ("aovs = [\"dept\"]", "did you mean `depth`?"),
        ("noise = 2.0", "noise must be between 0 and 1"),
        ("noise = 0.1\nantialias = { method = \"pov1\", threshold = 0.1, depth = 2 }", "stratified sampling only"),
    ] {
        let bad = small_scene(dir.path(), keys);
        let out = prism().arg("render").arg(&bad).arg("--exr").arg(&exr).output().unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{keys}");
        assert!(stderr.contains(message) && stderr.contains("cornell.toml:"), "{keys}: {stderr}");
        assert_eq!(files_in(dir.path()), ["cornell.toml"], "{keys}");
    }
}
