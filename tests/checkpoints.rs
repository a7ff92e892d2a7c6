//! Checkpoints and resume (issue 14, item 5): an interrupted render resumed from its
//! checkpoint is byte-identical to an uninterrupted one (`path` and `classic`, stratified
//! and POV-Ray antialiasing, AOV layers and adaptive sampling, one thread against two);
//! Ctrl-C writes a checkpoint and the image so far and says how to resume, a second Ctrl-C
//! quits at once; checkpoints of other scenes, settings or sample counts and broken files
//! are refused without writing anything.

mod common;

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use prism::checkpoint::{Checkpoint, Outcome, render_resumable};
use prism::film::{Aov, Film};
use prism::render::{RenderError, RenderOptions, render_frame};
use prism::world::Scene;

fn prism() -> Command {
    Command::new(env!("CARGO_BIN_EXE_prism"))
}

fn repo_file(name: &str) -> PathBuf {
    common::repo().join(name)
}

fn load(name: &str, width: u32, height: u32, samples: u32) -> Scene {
    let mut scene = prism::scene::load::load_file(&repo_file(name), &prism::plugins::registry()).unwrap();
    (scene.render.width, scene.render.height, scene.render.samples) = (width, height, samples);
    scene
}

fn options(threads: usize, aovs: &[Aov]) -> RenderOptions {
    RenderOptions { threads: Some(threads), aovs: aovs.to_vec(), ..Default::default() }
}

/// Renders `scene` once uninterrupted on `first` threads, and once stopped after its first
/// checkpoint (a round of 1 ms: the tiles started by then), written to a file, read back into
/// a fresh state and finished on `second` threads. Returns both films.
fn uninterrupted_and_resumed(mut scene: Scene, aovs: &[Aov], first: usize, second: usize) -> (Film, Film) {
    let fresh = Checkpoint::new(&scene, aovs).unwrap();
    let render_scene = prism::prepare(&mut scene).unwrap();
    let reference = render_frame(&render_scene, &options(first, aovs)).unwrap().0;

    let stop = Arc::new(AtomicBool::new(false));
    let stopping = RenderOptions { cancel: Some(stop.clone()), ..options(first, aovs) };
    let mut state = fresh.clone();
    let save = |_: &Checkpoint| {
        stop.store(true, Ordering::Relaxed);
        Ok::<(), RenderError>(())
    };
    let run = render_resumable(&render_scene, &mut state, &stopping, Some(Duration::from_millis(1)), save).unwrap();
    assert_eq!(run.outcome, Outcome::Interrupted, "saves {} elapsed {:?}", run.saves, run.stats.elapsed);
    assert!(state.pixels_done() > 0 && !state.is_complete(), "{} pixels done", state.pixels_done());

    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("state.exr");
    std::fs::write(&file, state.encode().unwrap()).unwrap();
    let mut resumed = fresh;
    resumed.resume_from(&prism::files::FileAccess::unrestricted(), &file).unwrap();
    assert_eq!(resumed.done, state.done);
    let never = |_: &Checkpoint| -> Result<(), RenderError> { panic!("no interval, no checkpoint") };
    let run = render_resumable(&render_scene, &mut resumed, &options(second, aovs), None, never).unwrap();
    assert_eq!(run.outcome, Outcome::Complete);
    (reference, resumed.film)
}

/// The films are equal, and so are their EXR and PNG files, byte for byte.
fn assert_identical(reference: &Film, resumed: &Film, what: &str) {
    assert!(reference == resumed, "{what}: the resumed film differs");
    for name in ["x.exr", "x.png"] {
        let settings = prism::output::ImageSettings::default();
        let a = prism::output::encode(reference, Path::new(name), &settings).unwrap();
        let b = prism::output::encode(resumed, Path::new(name), &settings).unwrap();
        assert!(a == b, "{what}: {name} bytes differ");
    }
}

#[test]
fn path_renders_resume_to_the_same_bytes_with_layers_and_adaptive_sampling() {
    let aovs = [Aov::Albedo, Aov::Normal, Aov::Depth, Aov::Variance, Aov::Samples];
    let scene = load("scenes/mitsuba/cornell.toml", 48, 40, 32);
    let (reference, resumed) = uninterrupted_and_resumed(scene, &aovs, 2, 1);
    assert_identical(&reference, &resumed, "path, 2 then 1 threads, AOVs");

    let mut scene = load("scenes/mitsuba/cornell.toml", 48, 40, 64);
    scene.render.noise = Some(0.05);
    let (reference, resumed) = uninterrupted_and_resumed(scene, &[Aov::Samples], 1, 2);
    assert_identical(&reference, &resumed, "path, adaptive, 1 then 2 threads");
    let counts = &reference.layer(Aov::Samples).unwrap().data;
    assert!(counts.iter().any(|&c| c < 64.0), "adaptive sampling stopped no pixel early");
}

#[test]
fn classic_renders_resume_to_the_same_bytes_with_either_antialiasing() {
    let scene = load("scenes/room.toml", 160, 120, 16);
    let (reference, resumed) = uninterrupted_and_resumed(scene, &[], 1, 2);
    assert_identical(&reference, &resumed, "classic, stratified, 1 then 2 threads");

    let scene = load("scenes/parity/room_pov1.toml", 192, 144, 1);
    let (reference, resumed) = uninterrupted_and_resumed(scene, &[Aov::Depth], 2, 1);
    assert_identical(&reference, &resumed, "classic, POV-Ray antialiasing, 2 then 1 threads");
}

/// The files in `dir` whose names end in `.tmp` (the outputs' temporary files).
fn temporaries(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".tmp"))
        .collect()
}

const CORNELL_ARGS: [&str; 7] = ["--width", "96", "--height", "96", "--samples", "64", "--threads"];

/// `prism render` of the Cornell box in `dir`, writing `out.png` and `out.exr`.
fn cornell_render(dir: &Path, threads: &str) -> Command {
    let mut command = prism();
    command.current_dir(dir).arg("render").arg(repo_file("scenes/mitsuba/cornell.toml"));
    command.args(CORNELL_ARGS).arg(threads).args(["-o", "out.png", "--exr", "out.exr"]);
    command
}

fn sigint(child: &std::process::Child) {
    // SAFETY: sending a signal to our own child process.
    assert_eq!(unsafe { libc::kill(child.id() as libc::pid_t, libc::SIGINT) }, 0);
}

/// Starts `command` and sends it SIGINT once `wait_for` exists; its output.
fn interrupt(mut command: Command, wait_for: &Path) -> Output {
    let mut child = command.stdin(Stdio::null()).stdout(Stdio::null()).stderr(Stdio::piped()).spawn().unwrap();
    let start = Instant::now();
    while !wait_for.exists() {
        assert!(child.try_wait().unwrap().is_none(), "the render ended before its first checkpoint");
        assert!(start.elapsed() < Duration::from_secs(60), "no checkpoint after a minute");
        std::thread::sleep(Duration::from_millis(5));
    }
    sigint(&child);
    child.wait_with_output().unwrap()
}

#[cfg(unix)]
#[test]
fn ctrl_c_writes_a_checkpoint_and_the_image_so_far_and_resuming_finishes_the_same_image() {
    let dir = tempfile::tempdir().unwrap();
    let reference_dir = tempfile::tempdir().unwrap();
    let reference = cornell_render(reference_dir.path(), "2").output().unwrap();
    assert!(reference.status.success(), "{}", String::from_utf8_lossy(&reference.stderr));

    let checkpoint = dir.path().join("out.checkpoint.exr");
    let mut command = cornell_render(dir.path(), "2");
    command.args(["--checkpoint", "0.1s"]);
    let out = interrupt(command, &checkpoint);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(130), "{stderr}");
    assert!(stderr.contains("interrupted: finishing the tiles under way"), "{stderr}");
    assert!(stderr.contains("wrote out.checkpoint.exr, out.png, out.exr"), "{stderr}");
    assert!(stderr.contains("to resume: prism render ") && stderr.contains("--resume out.checkpoint.exr"), "{stderr}");
    assert!(temporaries(dir.path()).is_empty(), "{:?}", temporaries(dir.path()));
    let so_far = image::open(dir.path().join("out.png")).unwrap();
    assert_eq!((so_far.width(), so_far.height()), (96, 96));
    assert_ne!(
        std::fs::read(dir.path().join("out.png")).unwrap(),
        std::fs::read(reference_dir.path().join("out.png")).unwrap()
    );

    // Resumed on one thread (the first run had two), without further checkpoints.
    let resumed = cornell_render(dir.path(), "1").args(["--resume", "out.checkpoint.exr"]).output().unwrap();
    let stderr = String::from_utf8_lossy(&resumed.stderr);
    assert!(resumed.status.success(), "{stderr}");
    assert!(stderr.contains("resuming out.checkpoint.exr: ") && stderr.contains("pixels are finished"), "{stderr}");
    for name in ["out.png", "out.exr"] {
        let (a, b) =
            (std::fs::read(dir.path().join(name)).unwrap(), std::fs::read(reference_dir.path().join(name)).unwrap());
        assert!(a == b, "{name}: the resumed render differs from the uninterrupted one");
    }
    // The checkpoint now holds the finished render; `prism merge` makes the same EXR of it.
    let merged =
        prism().current_dir(dir.path()).args(["merge", "-o", "merged.exr", "out.checkpoint.exr"]).output().unwrap();
    assert!(merged.status.success(), "{}", String::from_utf8_lossy(&merged.stderr));
    assert!(
        std::fs::read(dir.path().join("merged.exr")).unwrap() == std::fs::read(dir.path().join("out.exr")).unwrap()
    );
}

/// The first Ctrl-C asks the render to finish its tiles under way (slow ones here: about a
/// second each); a second one, sent as soon as the first is acknowledged, quits at once:
/// exit 130, no temporary file, no image, and the last periodic checkpoint left whole.
#[cfg(unix)]
#[test]
fn a_second_ctrl_c_quits_at_once_leaving_no_partial_file() {
    use std::io::BufRead;
    let dir = tempfile::tempdir().unwrap();
    let checkpoint = dir.path().join("out.checkpoint.exr");
    let mut child = prism()
        .current_dir(dir.path())
        .arg("render")
        .arg(repo_file("scenes/mitsuba/cornell.toml"))
        .args(["--width", "48", "--height", "48", "--samples", "1024", "--threads", "2", "-o", "out.png"])
        .args(["--exr", "out.exr", "--checkpoint", "0.1s"])
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let (lines, received) = std::sync::mpsc::channel();
    let stderr = child.stderr.take().unwrap();
    let reader = std::thread::spawn(move || {
        for line in std::io::BufReader::new(stderr).lines() {
            let _ = lines.send(line.unwrap());
        }
    });
    let start = Instant::now();
    while !checkpoint.exists() {
        assert!(child.try_wait().unwrap().is_none(), "the render ended before its first checkpoint");
        assert!(start.elapsed() < Duration::from_secs(120), "no checkpoint after two minutes");
        std::thread::sleep(Duration::from_millis(5));
    }
    sigint(&child);
    // Signals are not queued: the second must come after the first was taken.
    let mut seen = Vec::new();
    loop {
        let line = received.recv_timeout(Duration::from_secs(60)).expect("the first Ctrl-C was not acknowledged");
        let acknowledged = line.contains("interrupted: finishing the tiles under way");
        seen.push(line);
        if acknowledged {
            break;
        }
    }
    sigint(&child);
    let status = child.wait().unwrap();
    reader.join().unwrap();
    seen.extend(received.try_iter());
    let stderr = seen.join("\n");
    assert_eq!(status.code(), Some(130), "{stderr}");
    assert!(!stderr.contains("to resume:") && !stderr.contains("internal error"), "{stderr}");
    assert!(temporaries(dir.path()).is_empty(), "{:?}", temporaries(dir.path()));
    assert!(!dir.path().join("out.png").exists() && !dir.path().join("out.exr").exists());
    let state = prism::partial::Partial::read(&prism::files::FileAccess::unrestricted(), &checkpoint).unwrap();
    assert!(state.info.scene.is_some() && state.sample_counts.contains(&1024));
}

/// A small scene in `dir` and a checkpoint of it with nothing finished yet (an interrupted
/// render), `state.exr`.
fn scene_with_checkpoint(dir: &Path) {
    let scene = dir.join("scene.toml");
    std::fs::write(&scene, "[render]\nwidth = 64\nheight = 48\nsamples = 4\n[[object]]\nshape = \"sphere\"\n").unwrap();
    let mut loaded = prism::scene::load::load_file(&scene, &prism::plugins::registry()).unwrap();
    let mut state = Checkpoint::new(&loaded, &[]).unwrap();
    let render_scene = prism::prepare(&mut loaded).unwrap();
    let stop = Arc::new(AtomicBool::new(true));
    // Stopped before it starts: a checkpoint with nothing finished is still a checkpoint.
    let options = RenderOptions { cancel: Some(stop), threads: Some(1), ..Default::default() };
    render_resumable(&render_scene, &mut state, &options, None, |_| Ok::<(), RenderError>(())).unwrap();
    std::fs::write(dir.join("state.exr"), state.encode().unwrap()).unwrap();
}

#[test]
fn foreign_stale_and_broken_checkpoints_are_refused_and_nothing_is_written() {
    let dir = tempfile::tempdir().unwrap();
    scene_with_checkpoint(dir.path());
    let state = dir.path().join("state.exr");
    let original = std::fs::read(&state).unwrap();
    std::fs::write(dir.path().join("cut.exr"), &original[..original.len() / 2]).unwrap();
    std::fs::write(
        dir.path().join("other.toml"),
        "[render]\nwidth = 64\nheight = 48\nsamples = 4\n[[object]]\nshape = \"sphere\"\nradius = 2\n",
    )
    .unwrap();
    let part = prism()
        .current_dir(dir.path())
        .args(["render", "scene.toml", "--tile", "0/2", "-o", "part.exr"])
        .output()
        .unwrap();
    assert!(part.status.success(), "{}", String::from_utf8_lossy(&part.stderr));
    let cases: &[(&str, &[&str], &[&str])] = &[
        (
            "scene.toml",
            &["--resume", "state.exr", "--seed", "9"],
            &["state.exr: a checkpoint of another scene or other settings: `render.seed`", "but 9 in this render"],
        ),
        ("scene.toml", &["--resume", "state.exr", "--integrator", "path"], &["`render.integrator` is"]),
        ("scene.toml", &["--resume", "state.exr", "--width", "65"], &["`render.width` is 64 in the checkpoint but 65"]),
        ("other.toml", &["--resume", "state.exr"], &["`object[0].radius` is"]),
        (
            "scene.toml",
            &["--resume", "state.exr", "--samples", "2"],
            &["already hold 4 samples each; --samples 2 is below"],
        ),
        (
            "scene.toml",
            &["--resume", "state.exr", "--samples", "8"],
            &["renders 4 samples per pixel, this render 8", "resume with --samples 4"],
        ),
        ("scene.toml", &["--resume", "cut.exr"], &["cut.exr: not a readable part (truncated or corrupt EXR)"]),
        ("scene.toml", &["--resume", "part.exr"], &["part.exr: not a checkpoint"]),
        ("scene.toml", &["--resume", "missing.exr"], &["missing.exr"]),
        ("scene.toml", &["--resume", "state.exr", "--time", "5s"], &["--time cannot be combined with --checkpoint"]),
        (
            "scene.toml",
            &["--checkpoint", "1s", "--checkpoint-file", "out.png"],
            &["out.png: the checkpoint file is also an image output"],
        ),
        (
            "scene.toml",
            &["--checkpoint", "1s", "--checkpoint-file", "state.txt"],
            &["state.txt: the checkpoint file (--checkpoint-file, by default the --resume file) is an OpenEXR file"],
        ),
        ("scene.toml", &["--resume", "/dev/zero"], &["/dev/zero: the checkpoint file", "must end in .exr"]),
        ("scene.toml", &["--checkpoint", "0"], &["more than zero"]),
        ("scene.toml", &["--checkpoint", "soon"], &["not a duration"]),
        (
            "scene.toml",
            &["--resume", "state.exr", "--tile", "0/2"],
            &["--resume cannot be combined with --region/--tile/--sample-range"],
        ),
    ];
    for (scene_name, flags, expect) in cases {
        let out = prism()
            .current_dir(dir.path())
            .args(["render", scene_name, "-o", "out.png"])
            .args(*flags)
            .output()
            .unwrap();
        let problems = common::failed_run_problems(&out, expect);
        assert!(problems.is_empty(), "{flags:?}: {}\n{}", problems.join("; "), String::from_utf8_lossy(&out.stderr));
        assert!(!dir.path().join("out.png").exists(), "{flags:?} wrote the image");
        assert_eq!(std::fs::read(&state).unwrap(), original, "{flags:?} touched the checkpoint");
        assert!(temporaries(dir.path()).is_empty());
    }
}
