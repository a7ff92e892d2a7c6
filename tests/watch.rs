//! `prism watch` (issue 14, item 6): renders, then renders again when the scene, an
//! included file or a mesh file changes, printing each summary; a broken edit is reported
//! with file and line while the last good image stays; Ctrl-C ends it without leaving a
//! temporary file.

mod common;

use std::io::{BufRead, BufReader};
use std::path::Path;
use std::process::{Command, Stdio};
use std::sync::mpsc::{Receiver, RecvTimeoutError};
use std::time::{Duration, Instant};

const SCENE: &str = r#"include = ["base.toml"]

[render]
width = 24
height = 24
samples = 1

[[object]]
shape = "mesh"
file = "tri.obj"
material = "paint"
"#;

const BASE: &str = r#"[materials.paint]
color = [0.8, 0.2, 0.2]
ambient = 1.0
"#;

const TRIANGLE: &str = "v -1 -1 -2\nv 1 -1 -2\nv 0 1 -2\nf 1 2 3\n";

/// The lines the watcher writes to standard error, as they come.
struct Lines {
    rx: Receiver<String>,
    seen: Vec<String>,
}

impl Lines {
    /// Waits for a line containing `needle` (at most a minute) and returns it.
    fn wait_for(&mut self, needle: &str) -> String {
        let deadline = Instant::now() + Duration::from_secs(60);
        loop {
            let left = deadline.saturating_duration_since(Instant::now());
            match self.rx.recv_timeout(left) {
                Ok(line) => {
                    self.seen.push(line.clone());
                    if line.contains(needle) {
                        return line;
                    }
                }
                Err(RecvTimeoutError::Timeout | RecvTimeoutError::Disconnected) => {
                    panic!("no line with `{needle}`; the watcher said:\n{}", self.seen.join("\n"))
                }
            }
        }
    }
}

/// Rewrites `path` after making sure its modification time will differ from the last
/// write's even on a coarse clock (the length differs too in every edit below).
fn edit(path: &Path, text: &str) {
    std::thread::sleep(Duration::from_millis(20));
    std::fs::write(path, text).unwrap();
}

#[test]
fn watch_renders_again_on_every_change_reports_broken_edits_and_stops_on_ctrl_c() {
    let dir = tempfile::tempdir().unwrap();
    let (scene, base, mesh, png) = (
        dir.path().join("scene.toml"),
        dir.path().join("base.toml"),
        dir.path().join("tri.obj"),
        dir.path().join("out.png"),
    );
    std::fs::write(&scene, SCENE).unwrap();
    std::fs::write(&base, BASE).unwrap();
    std::fs::write(&mesh, TRIANGLE).unwrap();
    let mut child = Command::new(env!("CARGO_BIN_EXE_prism"))
        .arg("watch")
        .arg(&scene)
        .arg("-o")
        .arg(&png)
        .args(["--threads", "1"])
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let stderr = child.stderr.take().unwrap();
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        for line in BufReader::new(stderr).lines().map_while(Result::ok) {
            let _ = tx.send(line);
        }
    });
    let mut lines = Lines { rx, seen: Vec::new() };

    // The first render, then the scene, its include and the mesh are watched.
    lines.wait_for("rendered 24x24 at 1 spp");
    lines.wait_for("watching 3 files for changes");
    let first = std::fs::read(&png).unwrap();

    // An edit of the included file renders again, with a new image.
    edit(&base, &BASE.replace("[0.8, 0.2, 0.2]", "[0.1, 0.3, 0.95]"));
    lines.wait_for("rendered 24x24 at 1 spp");
    lines.wait_for("watching 3 files");
    let second = std::fs::read(&png).unwrap();
    assert_ne!(first, second, "the new colour is in the new image");

    // So does an edit of the mesh file.
    edit(&mesh, &TRIANGLE.replace("v 0 1 -2", "v 0.9 0.9 -2"));
    lines.wait_for("rendered 24x24 at 1 spp");
    lines.wait_for("watching 3 files");
    let third = std::fs::read(&png).unwrap();
    assert_ne!(second, third, "the moved vertex is in the new image");

    // A broken edit is reported with its file and line, the watch goes on, and the last
    // good image stays.
    edit(&scene, &SCENE.replace("samples = 1", "samples = 1\nsamplez = 2"));
    let error = lines.wait_for("unknown key");
    assert!(error.contains("scene.toml:7:1") && error.contains("samplez"), "{error}");
    lines.wait_for("watching 3 files");
    assert_eq!(std::fs::read(&png).unwrap(), third);

    // Fixed (at a new size), it renders again.
    edit(&scene, &SCENE.replace("height = 24", "height = 16"));
    lines.wait_for("rendered 24x16 at 1 spp");
    lines.wait_for("watching 3 files");
    assert_eq!(image::open(&png).unwrap().height(), 16);

    // Ctrl-C ends it: the interrupted status, and no temporary file beside the outputs.
    // SAFETY: a plain kill(2) of the child this test started (and has not yet reaped).
    let sent = unsafe { libc::kill(child.id() as libc::pid_t, libc::SIGINT) };
    assert_eq!(sent, 0);
    let status = child.wait().unwrap();
    assert_eq!(status.code(), Some(130), "{status}");
    let mut names: Vec<String> =
        std::fs::read_dir(dir.path()).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    names.sort();
    assert_eq!(names, ["base.toml", "out.png", "scene.toml", "tri.obj"]);
}

#[test]
fn watch_starts_on_a_missing_scene_and_renders_once_it_appears() {
    let dir = tempfile::tempdir().unwrap();
    let (scene, png) = (dir.path().join("later.toml"), dir.path().join("out.png"));
    let mut child = Command::new(env!("CARGO_BIN_EXE_prism"))
        .arg("watch")
        .arg(&scene)
        .arg("-o")
        .arg(&png)
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let stderr = child.stderr.take().unwrap();
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        for line in BufReader::new(stderr).lines().map_while(Result::ok) {
            let _ = tx.send(line);
        }
    });
    let mut lines = Lines { rx, seen: Vec::new() };
    let error = lines.wait_for("later.toml");
    assert!(error.contains("No such file") || error.contains("not found"), "{error}");
    lines.wait_for("watching 1 file for changes");
    assert!(!png.exists());
    edit(&scene, "[render]\nwidth = 8\nheight = 8\nsamples = 1\n");
    lines.wait_for("rendered 8x8");
    assert!(png.is_file());
    child.kill().unwrap();
    child.wait().unwrap();
}
