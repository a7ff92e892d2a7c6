//! Render farms: parts merge into the one-machine render. Regions and tiles byte-identically
//! (film and EXR bytes), for both integrators and POV-Ray's antialiasing; sample ranges
//! within one f32 rounding per channel. And the CLI: part renders, merge, and their errors.

mod common;

use std::ops::Range;
use std::path::{Path, PathBuf};
use std::process::Command;

use common::{failed_run_problems, repo};
use prism::farm::merge::{NamedPart, merge};
use prism::farm::tile_region;
use prism::film::{Film, Region};
use prism::limits::MemoryBudget;
use prism::partial::{Fingerprint, PartInfo, Partial, Sampling};
use prism::render::extract::RenderScene;
use prism::render::integrators::Integrator;
use prism::render::integrators::classic::Classic;
use prism::render::integrators::path::Path as PathTracer;
use prism::render::{RenderOptions, render, render_frame, render_sums};
use prism::world::components::{Antialias, IntegratorKind};

fn scene(
    file: &str,
    width: u32,
    height: u32,
    samples: u32,
    antialias: Option<Antialias>,
) -> (RenderScene, Fingerprint) {
    let mut scene = prism::scene::load::load_file(&repo().join(file), &prism::plugins::registry()).unwrap();
    scene.render.width = width;
    scene.render.height = height;
    scene.render.samples = samples;
    if let Some(a) = antialias {
        scene.render.antialias = a;
    }
    let fingerprint = Fingerprint::of_scene(&scene).unwrap();
    (prism::prepare(&mut scene).unwrap(), fingerprint)
}

fn options() -> RenderOptions {
    RenderOptions { threads: Some(2), ..Default::default() }
}

fn info(scene: &RenderScene, fingerprint: &Fingerprint, region: Region, samples: Range<u32>) -> PartInfo {
    let s = &scene.settings;
    PartInfo {
        fingerprint: fingerprint.clone(),
        frame: (s.width, s.height),
        region,
        samples,
        total_samples: s.samples,
        tile: None,
        sampling: if matches!(s.antialias, Antialias::Stratified {}) { Sampling::Stratified } else { Sampling::Pov },
        exposure: s.exposure,
        tone_map: s.tone_map,
        scene: None,
    }
}

/// A part rendered, written to EXR bytes and read back (so the file format is in the loop).
fn part<I: Integrator>(
    scene: &RenderScene,
    integrator: &I,
    fingerprint: &Fingerprint,
    region: Region,
    samples: Range<u32>,
) -> NamedPart {
    let info = info(scene, fingerprint, region, samples.clone());
    let part = if info.has_all_samples() {
        let (film, _) = render(scene, integrator, region, &options()).unwrap();
        Partial::from_film(info, &film, None)
    } else {
        let (film, sums, _) = render_sums(scene, integrator, region, samples, &options()).unwrap();
        Partial::from_film(info, &film, Some(sums))
    };
    let name = format!("{region:?}");
    let part = Partial::decode(&part.encode().unwrap(), Path::new(&name)).unwrap();
    NamedPart { name, part }
}

fn exr(film: &Film) -> Vec<u8> {
    prism::output::encode(film, Path::new("x.exr"), &Default::default()).unwrap()
}

fn tiles<I: Integrator>(scene: &RenderScene, integrator: &I, fingerprint: &Fingerprint, n: u32) -> Vec<NamedPart> {
    let (w, h) = (scene.settings.width, scene.settings.height);
    (0..n)
        .map(|i| part(scene, integrator, fingerprint, tile_region(w, h, i, n, 16).unwrap(), 0..scene.settings.samples))
        .collect()
}

/// Tiles and free regions (overlapping the renderer's tiles and POV-Ray's blocks at odd
/// places) merge into the full render, film and EXR bytes, for both integrators.
#[test]
fn merged_regions_are_byte_identical() {
    let cases = [
        ("scenes/room.toml", 3, None),
        ("scenes/parity/snowman_pov2.toml", 1, None),
        ("scenes/room.toml", 1, Some(Antialias::Pov1 { threshold: 0.1, depth: 3 })),
        ("scenes/room_path.toml", 4, None),
    ];
    for (file, samples, antialias) in cases {
        let (scene, fingerprint) = scene(file, 70, 41, samples, antialias);
        let (full, _) = render_frame(&scene, &options()).unwrap();
        let parts = match scene.settings.integrator {
            IntegratorKind::Classic => tiles(&scene, &Classic::new(&scene), &fingerprint, 3),
            IntegratorKind::Path => tiles(&scene, &PathTracer::new(&scene), &fingerprint, 3),
        };
        let merged = merge(&parts, MemoryBudget::default()).unwrap();
        assert!(merged == full, "{file} {antialias:?}: merged tiles differ from the full render");
        assert_eq!(exr(&merged), exr(&full), "{file}: EXR bytes");

        // Free regions: a 2 x 2 grid cut at (37, 19).
        let classic = Classic::new(&scene);
        let path = PathTracer::new(&scene);
        let regions = [(0, 0, 37, 19), (37, 0, 70, 19), (0, 19, 37, 41), (37, 19, 70, 41)]
            .map(|(x0, y0, x1, y1)| Region { x0, y0, x1, y1 });
        let parts: Vec<NamedPart> = regions
            .into_iter()
            .map(|r| match scene.settings.integrator {
                IntegratorKind::Classic => part(&scene, &classic, &fingerprint, r, 0..samples),
                IntegratorKind::Path => part(&scene, &path, &fingerprint, r, 0..samples),
            })
            .collect();
        let merged = merge(&parts, MemoryBudget::default()).unwrap();
        assert_eq!(exr(&merged), exr(&full), "{file} {antialias:?}: regions' EXR bytes");
    }
}

/// Adjacent f32 values (or equal): the merge's stated bound for sample ranges.
fn within_one_rounding(a: f32, b: f32) -> bool {
    a == b || (a.is_finite() && b.is_finite() && a.signum() == b.signum() && a.to_bits().abs_diff(b.to_bits()) <= 1)
}

/// Sample ranges (mixed with a region split) merge to the full render within one f32
/// rounding per channel, for both integrators; almost every pixel is exact.
#[test]
fn merged_sample_ranges_are_within_one_rounding() {
    for (file, samples) in [("scenes/room_path.toml", 8), ("scenes/room.toml", 6)] {
        let (scene, fingerprint) = scene(file, 48, 27, samples, None);
        let (full, _) = render_frame(&scene, &options()).unwrap();
        let top = Region { x0: 0, y0: 0, x1: 48, y1: 13 };
        let bottom = Region { x0: 0, y0: 13, x1: 48, y1: 27 };
        let jobs = [(top, 0..3), (top, 3..samples), (bottom, 0..1), (bottom, 1..5), (bottom, 5..samples)];
        let classic = Classic::new(&scene);
        let path = PathTracer::new(&scene);
        let parts: Vec<NamedPart> = jobs
            .iter()
            .map(|(r, s)| match scene.settings.integrator {
                IntegratorKind::Classic => part(&scene, &classic, &fingerprint, *r, s.clone()),
                IntegratorKind::Path => part(&scene, &path, &fingerprint, *r, s.clone()),
            })
            .collect();
        let merged = merge(&parts, MemoryBudget::default()).unwrap();
        let (mut exact, mut channels) = (0, 0);
        for (m, f) in merged.pixels.iter().zip(&full.pixels) {
            for c in 0..3 {
                assert!(within_one_rounding(m[c], f[c]), "{file}: merged {} vs full {}", m[c], f[c]);
                exact += usize::from(m[c] == f[c]);
                channels += 1;
            }
        }
        eprintln!("{file}: {exact} of {channels} channels exact, the rest one f32 rounding apart");
        assert!(exact * 10 >= channels * 9, "{file}: only {exact} of {channels} exact");
    }
}

// ---- the command line ----

fn prism() -> Command {
    Command::new(env!("CARGO_BIN_EXE_prism"))
}

fn dir() -> tempfile::TempDir {
    tempfile::tempdir().unwrap()
}

const SIZE: [&str; 6] = ["--width", "40", "--height", "23", "--samples", "2"];

fn room() -> PathBuf {
    repo().join("scenes/room.toml")
}

fn run_ok(cmd: &mut Command) {
    let out = cmd.output().unwrap();
    assert!(out.status.success(), "{:?} failed: {}", cmd, String::from_utf8_lossy(&out.stderr));
}

/// `render --tile I/N` for every tile and `merge` make the bytes of `render --exr`, and the
/// PNG too; a missing tile is named and nothing is written.
#[test]
fn cli_tiles_merge_into_the_one_process_render() {
    let d = dir();
    run_ok(
        prism()
            .arg("render")
            .arg(room())
            .args(SIZE)
            .arg("--exr")
            .arg(d.path().join("one.exr"))
            .arg("-o")
            .arg(d.path().join("one.png")),
    );
    let mut parts = Vec::new();
    for i in 0..3 {
        let p = d.path().join(format!("tile-{i}.exr"));
        run_ok(prism().arg("render").arg(room()).args(SIZE).args(["--tile", &format!("{i}/3"), "--exr"]).arg(&p));
        parts.push(p);
    }
    let (exr, png) = (d.path().join("merged.exr"), d.path().join("merged.png"));
    run_ok(prism().arg("merge").arg("-o").arg(&exr).arg("-o").arg(&png).args(&parts));
    assert_eq!(std::fs::read(&exr).unwrap(), std::fs::read(d.path().join("one.exr")).unwrap());
    assert_eq!(std::fs::read(&png).unwrap(), std::fs::read(d.path().join("one.png")).unwrap());

    let out = d.path().join("gap.exr");
    let run = prism().arg("merge").arg("-o").arg(&out).arg(&parts[0]).arg(&parts[2]).output().unwrap();
    let problems = failed_run_problems(&run, &["tile 1/3", "re-run with --tile 1/3"]);
    assert!(problems.is_empty() && !out.exists(), "{problems:?}");
}

/// Sample ranges through the CLI: two halves merge within one rounding of the full render.
#[test]
fn cli_sample_ranges_merge() {
    let d = dir();
    let one = d.path().join("one.exr");
    let scene = repo().join("scenes/room_path.toml");
    let size = ["--width", "24", "--height", "14", "--samples", "4"];
    run_ok(prism().arg("render").arg(&scene).args(size).arg("--exr").arg(&one));
    let (a, b) = (d.path().join("a.exr"), d.path().join("b.exr"));
    run_ok(prism().arg("render").arg(&scene).args(size).args(["--sample-range", "0..1", "--exr"]).arg(&a));
    run_ok(prism().arg("render").arg(&scene).args(size).args(["--sample-range", "1..4", "--exr"]).arg(&b));
    let merged = d.path().join("merged.exr");
    run_ok(prism().arg("merge").arg("-o").arg(&merged).arg(&a).arg(&b));
    let (m, f) = (prism::output::read_exr(&merged).unwrap(), prism::output::read_exr(&one).unwrap());
    for (p, q) in m.pixels.iter().zip(&f.pixels) {
        for c in 0..3 {
            assert!(within_one_rounding(p[c], q[c]), "{} vs {}", p[c], q[c]);
        }
    }
    // The same range twice overlaps.
    let run = prism().arg("merge").arg("-o").arg(&merged).arg(&a).arg(&a).output().unwrap();
    assert!(failed_run_problems(&run, &["overlaps", "samples 0..1"]).is_empty());
}

/// Bad input: each a clear error, a non-zero exit, no panic and no output file.
#[test]
fn cli_farm_errors() {
    let d = dir();
    let out = d.path().join("part.exr");
    let pov = repo().join("scenes/parity/snowman_pov2.toml");
    let cases: Vec<(Vec<String>, Vec<&str>)> = vec![
        (vec!["--tile".into(), "5/4".into()], vec!["--tile 5/4", "0-based", "3/4"]),
        (vec!["--tile".into(), "1/0".into()], vec!["--tile 1/0"]),
        (vec!["--tile".into(), "0/24".into()], vec!["23-row image has at most 23 tiles"]),
        (vec!["--region".into(), "0,0,41,10".into()], vec!["--region 0,0,41,10", "40x23"]),
        (vec!["--region".into(), "10,5,10,9".into()], vec!["--region 10,5,10,9", "non-empty"]),
        (vec!["--region".into(), "20,5,10,9".into()], vec!["--region 20,5,10,9"]),
        (vec!["--region".into(), "1,2,3".into()], vec!["--region", "X0,Y0,X1,Y1"]),
        (vec!["--sample-range".into(), "0..3".into()], vec!["--sample-range 0..3", "2 samples"]),
        (vec!["--sample-range".into(), "2..2".into()], vec!["--sample-range 2..2"]),
        (vec!["--sample-range".into(), "1-2".into()], vec!["--sample-range", "A..B"]),
        (vec!["--tile".into(), "0/2".into(), "--time".into(), "5s".into()], vec!["--time cannot be combined"]),
        (vec!["--tile".into(), "0/2".into(), "--aov".into(), "albedo".into()], vec!["--aov cannot be combined"]),
        (
            vec!["--sample-range".into(), "0..1".into(), "--noise".into(), "0.1".into()],
            vec!["--sample-range", "adaptively", "--region or --tile"],
        ),
    ];
    for (args, expect) in cases {
        let run = prism().arg("render").arg(room()).args(SIZE).args(&args).arg("--exr").arg(&out).output().unwrap();
        let problems = failed_run_problems(&run, &expect);
        assert!(problems.is_empty() && !out.exists(), "{args:?}: {problems:?}");
    }
    let run = prism().arg("render").arg(&pov).args(["--sample-range", "0..1", "--exr"]).arg(&out).output().unwrap();
    assert!(failed_run_problems(&run, &["POV-Ray's antialiasing", "--region or --tile"]).is_empty());
    // A working space other than linear light decodes a pixel only once its samples are averaged.
    let gamma = d.path().join("gamma.toml");
    let text = "[render]\nassumed_gamma = 2.2\n[[object]]\nshape = \"sphere\"\ncenter = [0, 0, -3]\n[[light]]\nposition = [2, 2, 0]\n";
    std::fs::write(&gamma, text).unwrap();
    let run = prism()
        .arg("render")
        .arg(&gamma)
        .args(SIZE)
        .args(["--sample-range", "0..1", "--exr"])
        .arg(&out)
        .output()
        .unwrap();
    assert!(failed_run_problems(&run, &["assumed_gamma", "--region or --tile"]).is_empty() && !out.exists());
    let run = prism()
        .arg("render")
        .arg(room())
        .args(SIZE)
        .args(["--tile", "0/2", "-o"])
        .arg(d.path().join("p.png"))
        .output()
        .unwrap();
    assert!(failed_run_problems(&run, &["part file", ".exr"]).is_empty());

    // Parts of different scenes; a truncated part.
    let (a, b) = (d.path().join("a.exr"), d.path().join("b.exr"));
    run_ok(prism().arg("render").arg(room()).args(SIZE).args(["--tile", "0/2", "--exr"]).arg(&a));
    run_ok(prism().arg("render").arg(room()).args(SIZE).args(["--seed", "7", "--tile", "1/2", "--exr"]).arg(&b));
    let merged = d.path().join("merged.exr");
    let run = prism().arg("merge").arg("-o").arg(&merged).arg(&a).arg(&b).output().unwrap();
    assert!(failed_run_problems(&run, &["b.exr: a part of another scene", "fingerprint"]).is_empty());
    let bytes = std::fs::read(&b).unwrap();
    std::fs::write(&b, &bytes[..bytes.len() * 2 / 3]).unwrap();
    let run = prism().arg("merge").arg("-o").arg(&merged).arg(&a).arg(&b).output().unwrap();
    assert!(failed_run_problems(&run, &["b.exr", "truncated or corrupt"]).is_empty());
    std::fs::write(&b, b"").unwrap();
    let run = prism().arg("merge").arg("-o").arg(&merged).arg(&a).arg(&b).output().unwrap();
    assert!(failed_run_problems(&run, &["b.exr", "truncated or corrupt"]).is_empty());
    assert!(!merged.exists());
}

/// `farm slurm`: the dry run prints both scripts; without sbatch a clear error, nothing
/// written.
#[test]
fn cli_farm_slurm() {
    let d = dir();
    let farm = d.path().join("farm");
    let run = prism()
        .args(["farm", "slurm"])
        .arg(room())
        .args(["--tiles", "4", "--partition", "short", "--mem", "2G", "--dry-run", "--width", "40", "--out"])
        .arg(&farm)
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&run.stdout);
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    for line in [
        "#SBATCH --array=0-3",
        "#SBATCH --requeue",
        "#SBATCH --partition=short",
        "#SBATCH --mem=2G",
        "/4\" --width 40 --exr",
        "prism merge -o",
        "--dependency=afterok:",
    ] {
        assert!(text.contains(line) || text.contains(&line.replace("prism merge", "merge")), "{line} not in\n{text}");
    }
    assert!(!farm.exists(), "a dry run writes nothing");

    let run = prism()
        .env("PATH", d.path())
        .args(["farm", "slurm"])
        .arg(room())
        .args(["--tiles", "4", "--out"])
        .arg(&farm)
        .output()
        .unwrap();
    assert!(failed_run_problems(&run, &["sbatch not found", "apt-get install slurm"]).is_empty());
    assert!(!farm.exists());
    let run = prism().args(["farm", "slurm"]).arg(room()).args(["--tiles", "0", "--dry-run"]).output().unwrap();
    assert!(!run.status.success());
}
