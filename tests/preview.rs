//! `render --preview` (issue 14, item 6): the window shows the image as its tiles finish,
//! with the outputs' tone map, and closes when the render ends (checked on screenshots of a
//! virtual X server, Xvfb); the image is the same byte for byte with and without it; and
//! without a display it is a clear error before anything is rendered or written.
//!
//! The window tests need `Xvfb` and `xwd` (Debian: `xvfb`, `x11-apps`). Under `CI=true`
//! their absence fails; locally it prints `SKIPPED`.

mod common;

use std::io::{BufRead, BufReader, Write};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use prism::film::Region;
use prism::preview::Layout;
use prism::render::{RenderOptions, TileHook, TileObserver, render_frame};

fn prism() -> Command {
    Command::new(env!("CARGO_BIN_EXE_prism"))
}

fn room() -> PathBuf {
    common::repo().join("scenes/room.toml")
}

/// The screen of the virtual X server.
const SCREEN: (u32, u32) = (800, 600);

/// A virtual X server on a free display, stopped when dropped.
struct Xvfb {
    child: Child,
    display: String,
}

impl Xvfb {
    /// Starts one, or says why not: `None` locally when Xvfb or xwd is missing (printed as
    /// SKIPPED); a failure under `CI=true`.
    fn start() -> Option<Self> {
        let missing: Vec<&str> = ["Xvfb", "xwd"].into_iter().filter(|tool| !on_path(tool)).collect();
        if !missing.is_empty() {
            let message = format!("{} not installed (Debian: apt-get install xvfb x11-apps)", missing.join(" and "));
            if std::env::var("CI").is_ok_and(|v| v == "true") {
                panic!("{message} (CI=true: the preview window must be tested)");
            }
            let _ = writeln!(std::io::stderr(), "SKIPPED (preview window): {message}");
            return None;
        }
        // `-displayfd 1`: the server picks a free display and writes its number to stdout.
        let mut child = Command::new("Xvfb")
            .args(["-displayfd", "1", "-screen", "0", &format!("{}x{}x24", SCREEN.0, SCREEN.1)])
            .args(["-nolisten", "tcp", "-br"])
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .expect("start Xvfb");
        let mut line = String::new();
        BufReader::new(child.stdout.take().unwrap()).read_line(&mut line).unwrap();
        let number: u32 = line.trim().parse().unwrap_or_else(|_| panic!("Xvfb printed `{line}`, not a display"));
        Some(Self { child, display: format!(":{number}") })
    }

    /// A screenshot of the whole screen.
    fn screenshot(&self) -> Screenshot {
        let out = Command::new("xwd").args(["-root", "-silent", "-display", &self.display]).output().unwrap();
        assert!(out.status.success(), "xwd: {}", String::from_utf8_lossy(&out.stderr));
        Screenshot::from_xwd(&out.stdout)
    }
}

impl Drop for Xvfb {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

fn on_path(tool: &str) -> bool {
    std::env::var_os("PATH").is_some_and(|path| std::env::split_paths(&path).any(|dir| dir.join(tool).is_file()))
}

/// A screen's pixels as RGB.
struct Screenshot {
    width: u32,
    height: u32,
    rgb: Vec<[u8; 3]>,
}

impl Screenshot {
    /// Reads an XWD file (xwd's format: a big-endian header, a colour map, then the pixels;
    /// a 24-bit TrueColor screen stores 32 bits a pixel).
    fn from_xwd(bytes: &[u8]) -> Self {
        let field = |i: usize| u32::from_be_bytes(bytes[i * 4..i * 4 + 4].try_into().unwrap());
        let (header, width, height, byte_order) = (field(0), field(4), field(5), field(7));
        let (bits_per_pixel, bytes_per_line, colours) = (field(11), field(12), field(19));
        let (red, green, blue) = (field(14), field(15), field(16));
        assert_eq!(bits_per_pixel, 32, "a 24-bit screen");
        assert_eq!((red, green, blue), (0xff0000, 0xff00, 0xff), "8 bits a channel");
        let start = (header + colours * 12) as usize;
        let mut rgb = Vec::with_capacity((width * height) as usize);
        for y in 0..height as usize {
            let row = &bytes[start + y * bytes_per_line as usize..];
            for x in 0..width as usize {
                let word: [u8; 4] = row[x * 4..x * 4 + 4].try_into().unwrap();
                let v = if byte_order == 0 { u32::from_le_bytes(word) } else { u32::from_be_bytes(word) };
                rgb.push([(v >> 16) as u8, (v >> 8) as u8, v as u8]);
            }
        }
        Self { width, height, rgb }
    }

    fn at(&self, x: u32, y: u32) -> [u8; 3] {
        self.rgb[(y * self.width + x) as usize]
    }

    fn save_png(&self, path: &Path) {
        let bytes: Vec<u8> = self.rgb.iter().flatten().copied().collect();
        image::RgbImage::from_raw(self.width, self.height, bytes).unwrap().save(path).unwrap();
    }
}

/// What a screenshot shows of the window, compared with the rendered image.
#[derive(Debug, Default)]
struct Seen {
    /// Window pixels that show the image's pixel (not black).
    matching: u64,
    /// Window pixels that show a colour other than the image's.
    wrong: u64,
    /// Lit pixels outside the window.
    outside: u64,
}

/// Compares the window (centred on the screen, as minifb places it) with `image` enlarged
/// by `layout.zoom`.
fn compare(shot: &Screenshot, image: &image::RgbImage, layout: &Layout) -> Seen {
    let (ww, wh) = layout.window();
    let (x0, y0) = ((shot.width - ww) / 2, (shot.height - wh) / 2);
    let mut seen = Seen::default();
    for y in 0..shot.height {
        for x in 0..shot.width {
            let pixel = shot.at(x, y);
            if pixel == [0; 3] {
                continue;
            }
            if !(x0..x0 + ww).contains(&x) || !(y0..y0 + wh).contains(&y) {
                seen.outside += 1;
                continue;
            }
            let want = image.get_pixel((x - x0) / layout.zoom, (y - y0) / layout.zoom).0;
            if pixel.iter().zip(want).all(|(&a, b)| a.abs_diff(b) <= 1) {
                seen.matching += 1;
            } else {
                seen.wrong += 1;
            }
        }
    }
    seen
}

#[test]
fn the_window_shows_the_image_refining_and_closes_when_the_render_ends() {
    let Some(x) = Xvfb::start() else { return };
    let dir = tempfile::tempdir().unwrap();
    let (png, exr) = (dir.path().join("room.png"), dir.path().join("room.exr"));
    // 128 x 96 at 512 samples on one thread: a few seconds, long enough to watch.
    let args = ["--width", "128", "--height", "96", "--samples", "512", "--threads", "1"];
    let mut child = prism()
        .arg("render")
        .arg(room())
        .args(args)
        .arg("-o")
        .arg(&png)
        .arg("--exr")
        .arg(&exr)
        .arg("--preview")
        .env("DISPLAY", &x.display)
        .env_remove("WAYLAND_DISPLAY")
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut shots = Vec::new();
    let start = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        assert!(start.elapsed() < Duration::from_secs(300), "the render did not end");
        shots.push(x.screenshot());
        std::thread::sleep(Duration::from_millis(200));
    };
    let mut stderr = String::new();
    std::io::Read::read_to_string(&mut child.stderr.take().unwrap(), &mut stderr).unwrap();
    assert!(status.success(), "{status}: {stderr}");
    let layout = Layout::fit((128, 96), SCREEN);
    let (ww, wh) = layout.window();
    assert!(stderr.contains(&format!("preview: a {ww}x{wh} window, the image enlarged {}x", layout.zoom)), "{stderr}");

    // Every lit window pixel shows the written PNG's colour (the same tone map), and the
    // image filled in while the render ran.
    let image = image::open(&png).unwrap().to_rgb8();
    let area = u64::from(ww * wh);
    let seen: Vec<Seen> = shots.iter().map(|shot| compare(shot, &image, &layout)).collect();
    let best = (0..seen.len()).max_by_key(|&i| seen[i].matching).expect("at least one screenshot");
    shots[best].save_png(&Path::new(env!("CARGO_TARGET_TMPDIR")).join("preview-screenshot.png"));
    for (i, s) in seen.iter().enumerate() {
        assert_eq!((s.wrong, s.outside), (0, 0), "screenshot {i} shows something other than the image: {s:?}");
    }
    assert!(
        seen[best].matching * 4 >= area,
        "the window never showed a quarter of the image ({} of {area} pixels)",
        seen[best].matching
    );
    assert!(
        seen.iter().any(|s| s.matching > 0 && s.matching * 10 < area * 9),
        "no screenshot caught the image partly drawn: {seen:?}"
    );
    // The window is gone.
    let after = compare(&x.screenshot(), &image, &layout);
    assert_eq!((after.matching, after.wrong, after.outside), (0, 0, 0), "the window stayed open");

    // The same render without the window writes the same bytes.
    let (png2, exr2) = (dir.path().join("plain.png"), dir.path().join("plain.exr"));
    let plain =
        prism().arg("render").arg(room()).args(args).arg("-o").arg(&png2).arg("--exr").arg(&exr2).output().unwrap();
    assert!(plain.status.success(), "{}", String::from_utf8_lossy(&plain.stderr));
    assert!(std::fs::read(&png).unwrap() == std::fs::read(&png2).unwrap(), "PNG differs with --preview");
    assert!(std::fs::read(&exr).unwrap() == std::fs::read(&exr2).unwrap(), "EXR differs with --preview");
}

/// Collects what a render shows its observer.
#[derive(Default)]
struct Recorder {
    begun: Mutex<Vec<(Region, (u32, u32))>>,
    tiles: Mutex<Vec<(Region, Vec<[f32; 3]>)>>,
}

impl TileObserver for Recorder {
    fn begin(&self, region: Region, frame: (u32, u32)) {
        self.begun.lock().unwrap().push((region, frame));
    }

    fn tile(&self, area: Region, pixels: &[[f32; 3]]) {
        self.tiles.lock().unwrap().push((area, pixels.to_vec()));
    }
}

#[test]
fn the_observer_sees_every_tile_of_the_image_and_changes_nothing() {
    let mut scene = prism::scene::load::load_file(&room(), &prism::plugins::registry()).unwrap();
    (scene.render.width, scene.render.height, scene.render.samples) = (70, 37, 4);
    let scene = prism::prepare(&mut scene).unwrap();
    let (plain, _) = render_frame(&scene, &RenderOptions { threads: Some(2), ..Default::default() }).unwrap();
    let recorder = Arc::new(Recorder::default());
    let options = RenderOptions { threads: Some(2), observer: Some(TileHook(recorder.clone())), ..Default::default() };
    let (observed, _) = render_frame(&scene, &options).unwrap();
    assert_eq!(plain, observed, "the same film with an observer");
    assert_eq!(*recorder.begun.lock().unwrap(), vec![(Region::full(70, 37), (70, 37))]);
    // The tiles cover the frame once and hold the film's pixels.
    let mut covered = vec![0u32; 70 * 37];
    for (area, pixels) in recorder.tiles.lock().unwrap().iter() {
        assert_eq!(pixels.len(), area.pixel_count());
        for (i, p) in pixels.iter().enumerate() {
            let (x, y) = (area.x0 + i as u32 % area.width(), area.y0 + i as u32 / area.width());
            let index = (y * 70 + x) as usize;
            covered[index] += 1;
            assert_eq!(*p, plain.pixels[index], "pixel {x},{y}");
        }
    }
    assert!(covered.iter().all(|&c| c == 1), "every pixel exactly once");
}

#[test]
fn without_a_display_preview_is_an_error_before_rendering_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("out.png");
    std::fs::write(&png, b"old").unwrap();
    let run = |display: Option<&str>| {
        let mut command = prism();
        command.arg("render").arg(room()).args(["--width", "32", "--height", "24", "-o"]).arg(&png).arg("--preview");
        command.env_remove("DISPLAY").env_remove("WAYLAND_DISPLAY");
        if let Some(d) = display {
            command.env("DISPLAY", d);
        }
        command.output().unwrap()
    };
    let unset = run(None);
    let problems = common::failed_run_problems(
        &unset,
        &["--preview needs a display", "DISPLAY", "WAYLAND_DISPLAY", "nothing was rendered"],
    );
    assert!(problems.is_empty(), "{problems:?}: {}", String::from_utf8_lossy(&unset.stderr));
    assert!(!String::from_utf8_lossy(&unset.stderr).contains("rendered 32x24"));
    // A display nobody serves (no server listens on display 4095 here).
    let unreachable = run(Some(":4095"));
    let stderr = String::from_utf8_lossy(&unreachable.stderr);
    let problems = common::failed_run_problems(&unreachable, &["--preview", "nothing was rendered"]);
    assert!(problems.is_empty(), "{problems:?}: {stderr}");
    assert!(
        stderr.contains("cannot open the X11 display `:4095`") || stderr.contains("cannot load the X11 client library"),
        "{stderr}"
    );
    assert_eq!(std::fs::read(&png).unwrap(), b"old", "the old output is untouched");
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1, "no other file is left");
}
