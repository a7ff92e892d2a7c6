//! `--denoise` (issue 14): Intel Open Image Denoise brings a 16-spp path-traced Cornell box
//! closer to the converged image and keeps the raw beauty as the `raw` layer; without the
//! library, `--denoise` is a clear error that renders and writes nothing.
//!
//! The converged image is Mitsuba 3's reference of the same scene at 64 x 64 pixels,
//! `scenes/mitsuba/refs/cornell.exr` (`scripts/mitsuba-references.py` made it: 256 spp for
//! each of several seeds, a standard error per pixel of 0.001 on average, against the 16-spp
//! render's 0.03), which `tests/mitsuba.rs` already holds Prism's path tracer to.

mod common;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use common::{failed_run_problems, repo};

fn prism() -> Command {
    Command::new(env!("CARGO_BIN_EXE_prism"))
}

/// True when Open Image Denoise can be loaded (from `OIDN_DIR` or the library path). Under
/// `CI=true` a missing library fails the test; locally the skip is printed.
fn have_library() -> bool {
    match prism::denoise::Denoiser::load() {
        Ok(_) => true,
        Err(e) if std::env::var("CI").is_ok_and(|v| v == "true") => {
            panic!("{e} (CI=true: a missing library is a failure; .ci/run installs the pyoidn wheel)")
        }
        Err(e) => {
            use std::io::Write;
            let _ = writeln!(std::io::stderr(), "SKIPPED (no Open Image Denoise): {e}");
            false
        }
    }
}

/// Every channel of an EXR's first layer, by name, with the layer's width and height.
fn read_channels(path: &Path) -> (usize, usize, Vec<(String, Vec<f32>)>) {
    use exr::prelude::*;
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .first_valid_layer()
        .all_attributes()
        .from_file(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let layer = image.layer_data;
    let channels =
        layer.channel_data.list.iter().map(|c| (c.name.to_string(), c.sample_data.values_as_f32().collect())).collect();
    (layer.size.width(), layer.size.height(), channels)
}

/// The RGB channels `prefix`R, `prefix`G, `prefix`B as pixels.
fn rgb(channels: &[(String, Vec<f32>)], prefix: &str) -> Vec<[f32; 3]> {
    let get = |c: &str| {
        let name = format!("{prefix}{c}");
        &channels.iter().find(|(n, _)| *n == name).unwrap_or_else(|| panic!("no channel {name}")).1
    };
    let (r, g, b) = (get("R"), get("G"), get("B"));
    (0..r.len()).map(|i| [r[i], g[i], b[i]]).collect()
}

/// Root mean square difference of the displayed images (linear values clipped to [0, 1], as
/// the PNG shows them before its sRGB curve): the ceiling light, 17 times brighter than a
/// wall, would otherwise outweigh the whole box.
fn display_rmse(a: &[[f32; 3]], b: &[[f32; 3]]) -> f64 {
    assert_eq!(a.len(), b.len());
    let sum: f64 = a
        .iter()
        .zip(b)
        .flat_map(|(p, q)| (0..3).map(move |c| f64::from(p[c].clamp(0.0, 1.0) - q[c].clamp(0.0, 1.0)).powi(2)))
        .sum();
    (sum / (3 * a.len()) as f64).sqrt()
}

fn run(command: &mut Command) -> Output {
    command.output().unwrap()
}

#[test]
fn denoising_a_16_spp_cornell_box_brings_it_closer_to_the_converged_image() {
    if !have_library() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let (exr, png) = (dir.path().join("cornell.exr"), dir.path().join("cornell.png"));
    let out = run(prism()
        .arg("render")
        .arg(repo().join("scenes/mitsuba/cornell.toml"))
        .args(["--samples", "16", "--denoise", "--exr"])
        .arg(&exr)
        .arg("-o")
        .arg(&png));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(stderr.contains("denoised with Open Image Denoise 2."), "{stderr}");
    let (w, h, channels) = read_channels(&exr);
    assert_eq!((w, h), (64, 64));
    for name in ["albedo.R", "normal.X", "raw.R", "raw.G", "raw.B"] {
        assert!(channels.iter().any(|(n, _)| n == name), "{name} missing");
    }
    let (denoised, raw) = (rgb(&channels, ""), rgb(&channels, "raw."));
    let (rw, rh, reference) = read_channels(&repo().join("scenes/mitsuba/refs/cornell.exr"));
    assert_eq!((rw, rh), (64, 64));
    let reference = rgb(&reference, "");
    let (raw_error, denoised_error) = (display_rmse(&raw, &reference), display_rmse(&denoised, &reference));
    let factor = raw_error / denoised_error;
    eprintln!("16 spp: RMSE raw {raw_error:.5}, denoised {denoised_error:.5}, {factor:.2} times closer");
    // Measured: 1.94 times closer (raw 0.0145, denoised 0.0075; seeds 1 to 3: 1.88 to 2.06;
    // OIDN 2.5.1 on x86-64). In linear RGB, unclipped, the denoised image is further off (0.10
    // against 0.03), all of it (95 %) in the twenty pixels of the ceiling light, whose radiance
    // of about 15 it moves by up to 3 either way: far above white, so the display clips it.
    assert!(factor > 1.5, "denoised only {factor:.2} times closer: raw {raw_error:.5}, denoised {denoised_error:.5}");
    // The PNG shows the denoised beauty.
    let shown = image::open(&png).unwrap().to_rgb8();
    let srgb = |v: f32| (prism::output::srgb_encode(f64::from(v.clamp(0.0, 1.0))) * 255.0 + 0.5).floor() as u8;
    let centre = 32 * 64 + 32;
    assert_eq!(shown.get_pixel(32, 32).0, denoised[centre].map(srgb));
}

#[cfg(target_os = "linux")]
/// A folder for OIDN_DIR, holding `file` under the library's name when given.
fn oidn_dir_with(dir: &Path, file: Option<&Path>) -> PathBuf {
    let lib = dir.join("oidn");
    std::fs::create_dir(&lib).unwrap();
    if let Some(file) = file {
        std::os::unix::fs::symlink(file, lib.join("libOpenImageDenoise.so.2")).unwrap();
    }
    lib
}

#[cfg(target_os = "linux")]
/// Runs `--denoise` with OIDN_DIR set to `oidn_dir` beside an existing output that must
/// survive, and returns what went wrong besides `expect` missing from the message.
fn denoise_without_the_library(oidn_dir: &Path, out_dir: &Path, expect: &[&str]) -> Vec<String> {
    let png = out_dir.join("kept.png");
    std::fs::write(&png, b"an earlier image").unwrap();
    let before: Vec<_> = std::fs::read_dir(out_dir).unwrap().map(|e| e.unwrap().file_name()).collect();
    let out = run(prism()
        .arg("render")
        .arg(repo().join("scenes/cornell.toml"))
        .args(["--width", "16", "--height", "16", "--samples", "1", "--denoise", "-o"])
        .arg(&png)
        .arg("--exr")
        .arg(out_dir.join("new.exr"))
        .env("OIDN_DIR", oidn_dir));
    let mut problems = failed_run_problems(&out, expect);
    if std::fs::read(&png).unwrap() != b"an earlier image" {
        problems.push("the existing output was overwritten".into());
    }
    let after: Vec<_> = std::fs::read_dir(out_dir).unwrap().map(|e| e.unwrap().file_name()).collect();
    if after.len() != before.len() {
        problems.push(format!("files were written: {after:?}"));
    }
    if String::from_utf8_lossy(&out.stderr).contains("rendered ") {
        problems.push("it rendered before failing".into());
    }
    problems
}

#[cfg(target_os = "linux")]
#[test]
fn denoise_without_the_library_is_a_clear_error_that_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let out_dir = dir.path().join("out");
    std::fs::create_dir(&out_dir).unwrap();
    let mut failures = Vec::new();

    // An empty folder: the message lists where it looked and how to get the library.
    let empty = oidn_dir_with(dir.path(), None);
    let expect = ["Open Image Denoise was not found", "OIDN_DIR=", "pip install pyoidn", "libOpenImageDenoise.so.2"];
    failures.extend(denoise_without_the_library(&empty, &out_dir, &expect).into_iter().map(|p| format!("empty: {p}")));

    // A file under the library's name that is not a shared object.
    let bogus_dir = dir.path().join("bogus");
    std::fs::create_dir(&bogus_dir).unwrap();
    let text = bogus_dir.join("notes.txt");
    std::fs::write(&text, "not a library").unwrap();
    let bogus = oidn_dir_with(&bogus_dir, Some(&text));
    let expect = ["Open Image Denoise was not found", "libOpenImageDenoise.so.2:"];
    failures.extend(denoise_without_the_library(&bogus, &out_dir, &expect).into_iter().map(|p| format!("bogus: {p}")));

    // A real shared library that is not Open Image Denoise (the C maths library).
    let libm = ["/lib/x86_64-linux-gnu/libm.so.6", "/usr/lib/x86_64-linux-gnu/libm.so.6", "/lib64/libm.so.6"]
        .into_iter()
        .chain(["/usr/lib64/libm.so.6", "/lib/aarch64-linux-gnu/libm.so.6", "/usr/lib/libm.so.6"])
        .map(Path::new)
        .find(|p| p.is_file())
        .expect("the C maths library libm.so.6 is in a usual place");
    let other_dir = dir.path().join("other");
    std::fs::create_dir(&other_dir).unwrap();
    let other = oidn_dir_with(&other_dir, Some(libm));
    let expect = ["has no function `oidnNewDevice`", "not Intel Open Image Denoise 2.x"];
    failures.extend(denoise_without_the_library(&other, &out_dir, &expect).into_iter().map(|p| format!("libm: {p}")));

    assert!(failures.is_empty(), "{failures:#?}");
}

#[test]
fn denoise_is_refused_for_part_renders() {
    let dir = tempfile::tempdir().unwrap();
    let part = dir.path().join("part.exr");
    let out = run(prism()
        .arg("render")
        .arg(repo().join("scenes/cornell.toml"))
        .args(["--width", "16", "--height", "16", "--tile", "0/2", "--denoise", "--exr"])
        .arg(&part));
    let problems = failed_run_problems(&out, &["--denoise cannot be combined with --region/--tile/--sample-range"]);
    assert!(problems.is_empty(), "{problems:?}");
    assert!(!part.exists());
}
