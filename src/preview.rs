//! `preview`: a window that shows a render as its tiles finish (`render --preview`).
//!
//! The window comes from `minifb`, which loads the X11 or Wayland client libraries when a
//! window is opened (dlopen), so the binary links no windowing library and runs where
//! there is none. The render threads hand finished tiles to a [`TileObserver`] that only
//! copies them into a channel; one preview thread owns the window, folds the tiles into an
//! image the size of the window's picture and redraws it a few times a second. The window
//! closes when the render ends. Nothing here writes into the film, so an image rendered
//! with a preview is the same, byte for byte, as one rendered without.

use std::sync::mpsc::{self, Receiver, RecvTimeoutError, Sender, SyncSender};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use crate::film::Region;
use crate::output::ldr_channel;
use crate::render::{TileHook, TileObserver};
use crate::world::components::ToneMap;

/// The longest side a small image is enlarged to (by a whole factor) in the window.
pub const SMALL_IMAGE_SIDE: u32 = 512;

/// Share of the screen's width and height the window may take.
const SCREEN_SHARE: f64 = 0.9;

/// The screen assumed on Wayland without X11 (no portable query for its size).
const WAYLAND_SCREEN: (u32, u32) = (1280, 720);

/// Time between redraws of the window.
const FRAME: Duration = Duration::from_millis(50);

/// Why the preview window cannot be opened.
#[derive(Debug, thiserror::Error)]
pub enum PreviewError {
    /// Neither `DISPLAY` nor `WAYLAND_DISPLAY` is set.
    #[error(
        "--preview needs a display, and neither DISPLAY nor WAYLAND_DISPLAY is set: run it in a desktop session, over `ssh -X`, or under `xvfb-run`; nothing was rendered"
    )]
    NoDisplay,
    /// The X11 client library cannot be loaded.
    #[error(
        "--preview: cannot load the X11 client library ({reason}); install it (Debian/Ubuntu: `apt-get install libx11-6`, Fedora: `dnf install libX11`); nothing was rendered"
    )]
    NoLibrary {
        /// What the loader said.
        reason: String,
    },
    /// The display named by `DISPLAY` cannot be reached.
    #[error(
        "--preview: cannot open the X11 display `{display}` (DISPLAY): no X server answers there, or it refuses this user; nothing was rendered"
    )]
    Unreachable {
        /// The value of `DISPLAY`.
        display: String,
    },
    /// The windowing library refused to make the window.
    #[error("--preview: cannot open a window: {reason}; nothing was rendered")]
    Window {
        /// What the library said.
        reason: String,
    },
}

/// How the preview turns radiance into colours: as the tone-mapped outputs do.
#[derive(Clone, Copy, Debug)]
pub struct PreviewSettings {
    /// Exposure in stops.
    pub exposure: f64,
    /// The tone-mapping operator.
    pub tone_map: ToneMap,
}

/// Where the image goes in the window: the picture (the image, shrunk to fit the screen
/// when it is larger) and the whole factor it is enlarged by on screen.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Layout {
    /// The rendered image's size in pixels.
    pub image: (u32, u32),
    /// The picture's size: each of its pixels is the mean of a block of image pixels.
    pub picture: (u32, u32),
    /// Window pixels per picture pixel along each axis (1 unless the image is small).
    pub zoom: u32,
}

impl Layout {
    /// The layout of a `image` (width, height) on a `screen` (width, height): an image that
    /// does not fit `SCREEN_SHARE` of the screen is shrunk (keeping its aspect ratio),
    /// and a small one is enlarged by the largest whole factor that keeps its longer side
    /// at most [`SMALL_IMAGE_SIDE`] and the window on the screen.
    pub fn fit(image: (u32, u32), screen: (u32, u32)) -> Self {
        let (w, h) = (image.0.max(1), image.1.max(1));
        let room = (f64::from(screen.0.max(1)) * SCREEN_SHARE, f64::from(screen.1.max(1)) * SCREEN_SHARE);
        let fit = (room.0 / f64::from(w)).min(room.1 / f64::from(h));
        if fit < 1.0 {
            let shrink = |side: u32| ((f64::from(side) * fit).floor() as u32).clamp(1, side);
            return Self { image: (w, h), picture: (shrink(w), shrink(h)), zoom: 1 };
        }
        let by_side = SMALL_IMAGE_SIDE / w.max(h);
        let zoom = (fit.floor() as u32).min(by_side).max(1);
        Self { image: (w, h), picture: (w, h), zoom }
    }

    /// The window's size in pixels.
    pub fn window(&self) -> (u32, u32) {
        (self.picture.0 * self.zoom, self.picture.1 * self.zoom)
    }

    /// The picture column (or row) of each image column (or row): `x * picture / image`,
    /// which covers every picture column with a run of image columns.
    fn spans(image: u32, picture: u32) -> Vec<u32> {
        (0..image).map(|x| (u64::from(x) * u64::from(picture) / u64::from(image)) as u32).collect()
    }
}

/// The picture the window shows, folded from tiles: each picture pixel is the tone-mapped
/// mean of the linear radiance of its block of image pixels.
#[derive(Debug)]
pub struct Canvas {
    layout: Layout,
    settings: PreviewSettings,
    /// Picture column of each image column, and picture row of each image row.
    columns: Vec<u32>,
    rows: Vec<u32>,
    /// Image pixels in each picture pixel's block.
    block: Vec<u32>,
    /// This render's sums of the block's radiance, and how many of its pixels came.
    sums: Vec<[f64; 3]>,
    arrived: Vec<u32>,
    /// Whether an earlier render (a pass of `--time`) completed the pixel: then it keeps
    /// showing that one until this render completes it, instead of a partial mean.
    complete_before: Vec<bool>,
    /// The picture as 0RGB words, what the window draws.
    pixels: Vec<u32>,
    /// Image pixels of this render that arrived.
    done: u64,
}

impl Canvas {
    /// An all-black canvas for `layout`.
    pub fn new(layout: Layout, settings: PreviewSettings) -> Self {
        let columns = Layout::spans(layout.image.0, layout.picture.0);
        let rows = Layout::spans(layout.image.1, layout.picture.1);
        let count = |spans: &[u32], n: u32| {
            let mut counts = vec![0u32; n as usize];
            spans.iter().for_each(|&s| counts[s as usize] += 1);
            counts
        };
        let (per_column, per_row) = (count(&columns, layout.picture.0), count(&rows, layout.picture.1));
        let block = per_row.iter().flat_map(|&r| per_column.iter().map(move |&c| r * c)).collect();
        let n = layout.picture.0 as usize * layout.picture.1 as usize;
        Self {
            layout,
            settings,
            columns,
            rows,
            block,
            sums: vec![[0.0; 3]; n],
            arrived: vec![0; n],
            complete_before: vec![false; n],
            pixels: vec![0; n],
            done: 0,
        }
    }

    /// The picture as 0RGB words, row by row.
    pub fn pixels(&self) -> &[u32] {
        &self.pixels
    }

    /// The layout it was made for.
    pub fn layout(&self) -> &Layout {
        &self.layout
    }

    /// Share of the image's pixels that this render delivered so far, in [0, 1].
    pub fn progress(&self) -> f64 {
        let total = u64::from(self.layout.image.0) * u64::from(self.layout.image.1);
        self.done as f64 / total.max(1) as f64
    }

    /// A new render begins: its tiles replace the last one's, pixel by pixel as they
    /// complete.
    pub fn begin(&mut self) {
        for (i, before) in self.complete_before.iter_mut().enumerate() {
            *before |= self.arrived[i] == self.block[i];
        }
        self.sums.fill([0.0; 3]);
        self.arrived.fill(0);
        self.done = 0;
    }

    /// Folds a finished tile in (pixels outside the image are ignored; non-finite values
    /// count as black, as in the written image).
    pub fn tile(&mut self, area: Region, pixels: &[[f32; 3]]) {
        let (w, h) = self.layout.image;
        let pw = self.layout.picture.0 as usize;
        let area_w = area.width() as usize;
        for (i, p) in pixels.iter().enumerate() {
            let (x, y) = (area.x0 + (i % area_w.max(1)) as u32, area.y0 + (i / area_w.max(1)) as u32);
            if x >= w || y >= h {
                continue;
            }
            let at = self.rows[y as usize] as usize * pw + self.columns[x as usize] as usize;
            let finite = p.iter().all(|c| c.is_finite());
            for (sum, &c) in self.sums[at].iter_mut().zip(p) {
                *sum += if finite { f64::from(c) } else { 0.0 };
            }
            self.arrived[at] += 1;
            self.done += 1;
            if self.arrived[at] == self.block[at] || !self.complete_before[at] {
                self.pixels[at] = self.colour(at);
            }
        }
    }

    /// The picture pixel's colour from what arrived of its block.
    fn colour(&self, at: usize) -> u32 {
        let scale = self.settings.exposure.exp2();
        let n = f64::from(self.arrived[at].max(1));
        let [r, g, b] = self.sums[at].map(|s| u32::from(ldr_channel(s / n, scale, self.settings.tone_map)));
        (r << 16) | (g << 8) | b
    }
}

/// What the render threads send the preview thread.
enum Message {
    Begin,
    Tile(Region, Vec<[f32; 3]>),
    /// The render ended: draw what came and close the window.
    Close,
}

/// The render side of the channel: copies each tile and sends it.
struct Forwarder(Sender<Message>);

impl TileObserver for Forwarder {
    fn begin(&self, _region: Region, _frame: (u32, u32)) {
        // A closed window (the user closed it) is no concern of the render.
        let _ = self.0.send(Message::Begin);
    }

    fn tile(&self, area: Region, pixels: &[[f32; 3]]) {
        let _ = self.0.send(Message::Tile(area, pixels.to_vec()));
    }
}

/// An open preview window and the thread that draws it.
pub struct Preview {
    hook: TileHook,
    closer: Sender<Message>,
    layout: Layout,
    thread: Option<JoinHandle<()>>,
}

impl Preview {
    /// Opens a window for an image of `image` (width, height) titled `title`, before the
    /// render starts: an error when there is no display to open it on.
    pub fn open(image: (u32, u32), title: &str, settings: PreviewSettings) -> Result<Self, PreviewError> {
        let x11 = std::env::var("DISPLAY").ok().filter(|d| !d.is_empty());
        let wayland = std::env::var_os("WAYLAND_DISPLAY").filter(|d| !d.is_empty());
        // The X11 connection that measured the screen stays open until the window is: a
        // server that resets when its last client leaves (Xvfb by default) would otherwise
        // drop the window's connection while resetting, and `XOpenDisplay` would fail.
        let (screen, measuring) = match (&x11, &wayland) {
            (None, None) => return Err(PreviewError::NoDisplay),
            (Some(display), _) => {
                let connection = X11Connection::open(display)?;
                (connection.screen_size(), Some(connection))
            }
            (None, Some(_)) => (WAYLAND_SCREEN, None),
        };
        let layout = Layout::fit(image, screen);
        let (tiles, inbox) = mpsc::channel();
        let (opened, opened_rx) = mpsc::sync_channel(1);
        let title = format!("prism: {title}");
        let canvas = Canvas::new(layout.clone(), settings);
        let thread = std::thread::Builder::new()
            .name("preview".into())
            .spawn(move || show(canvas, title, inbox, opened))
            .map_err(|e| PreviewError::Window { reason: format!("cannot start its thread: {e}") })?;
        match opened_rx.recv() {
            Ok(Ok(())) => {}
            Ok(Err(reason)) => {
                let _ = thread.join();
                return Err(PreviewError::Window { reason });
            }
            Err(_) => {
                let _ = thread.join();
                return Err(PreviewError::Window { reason: "the windowing library failed".into() });
            }
        }
        drop(measuring);
        let closer = tiles.clone();
        Ok(Self { hook: TileHook(std::sync::Arc::new(Forwarder(tiles))), closer, layout, thread: Some(thread) })
    }

    /// The observer to put into the render's options.
    pub fn hook(&self) -> TileHook {
        self.hook.clone()
    }

    /// Where the image goes in the window.
    pub fn layout(&self) -> &Layout {
        &self.layout
    }

    /// Closes the window (after drawing the tiles sent so far) and waits for its thread.
    pub fn close(mut self) {
        self.finish();
    }

    fn finish(&mut self) {
        let _ = self.closer.send(Message::Close);
        if let Some(thread) = self.thread.take() {
            let _ = thread.join();
        }
    }
}

impl Drop for Preview {
    fn drop(&mut self) {
        self.finish();
    }
}

/// An open connection to an X11 display, closed when dropped. (minifb would say only that
/// `XOpenDisplay` failed, and knows no size to fit to.)
struct X11Connection {
    xlib: x11_dl::xlib::Xlib,
    display: *mut x11_dl::xlib::Display,
}

impl X11Connection {
    /// Connects to `display` (the value of `DISPLAY`); the error says why it cannot.
    fn open(display: &str) -> Result<Self, PreviewError> {
        let xlib = x11_dl::xlib::Xlib::open().map_err(|e| PreviewError::NoLibrary { reason: e.to_string() })?;
        // SAFETY: Xlib's function as loaded; a null name means `DISPLAY`, checked above.
        let connection = unsafe { (xlib.XOpenDisplay)(std::ptr::null()) };
        if connection.is_null() {
            return Err(PreviewError::Unreachable { display: crate::files::shown(display) });
        }
        Ok(Self { xlib, display: connection })
    }

    /// The size of the display's default screen in pixels.
    fn screen_size(&self) -> (u32, u32) {
        // SAFETY: a display pointer from `XOpenDisplay`, not null, not yet closed.
        let size = unsafe {
            let screen = (self.xlib.XDefaultScreen)(self.display);
            ((self.xlib.XDisplayWidth)(self.display, screen), (self.xlib.XDisplayHeight)(self.display, screen))
        };
        (size.0.max(1) as u32, size.1.max(1) as u32)
    }
}

impl Drop for X11Connection {
    fn drop(&mut self) {
        // SAFETY: closed once, here, on the pointer `XOpenDisplay` returned.
        unsafe { (self.xlib.XCloseDisplay)(self.display) };
    }
}

/// The preview thread: opens the window (reporting the outcome on `opened`), then folds in
/// tiles and redraws every [`FRAME`] until the channel closes. A window the user closes
/// stops the preview, not the render.
fn show(mut canvas: Canvas, title: String, inbox: Receiver<Message>, opened: SyncSender<Result<(), String>>) {
    let (ww, wh) = canvas.layout().window();
    let options = minifb::WindowOptions {
        resize: true,
        scale_mode: minifb::ScaleMode::AspectRatioStretch,
        use_gpu: minifb::UseGPU::Disabled,
        ..minifb::WindowOptions::default()
    };
    let mut window = match minifb::Window::new(&title, ww as usize, wh as usize, options) {
        Ok(window) => window,
        Err(e) => {
            let _ = opened.send(Err(e.to_string()));
            return;
        }
    };
    // Redraws are paced here, not by minifb's sleeping rate limit.
    window.set_target_fps(0);
    let _ = opened.send(Ok(()));
    let (pw, ph) = (canvas.layout().picture.0 as usize, canvas.layout().picture.1 as usize);
    let mut dirty = true;
    let mut last_draw = Instant::now() - FRAME;
    let mut shown_title = String::new();
    loop {
        let wait = FRAME.saturating_sub(last_draw.elapsed());
        match inbox.recv_timeout(wait) {
            Ok(Message::Begin) => canvas.begin(),
            Ok(Message::Tile(area, pixels)) => {
                canvas.tile(area, &pixels);
                dirty = true;
            }
            Err(RecvTimeoutError::Timeout) => {}
            Ok(Message::Close) | Err(RecvTimeoutError::Disconnected) => break,
        }
        if last_draw.elapsed() < FRAME {
            continue;
        }
        if !window.is_open() {
            return;
        }
        let progress_title = format!("{title} ({:.0}%)", canvas.progress() * 100.0);
        if progress_title != shown_title {
            window.set_title(&progress_title);
            shown_title = progress_title;
        }
        if !dirty {
            window.update();
        } else if window.update_with_buffer(canvas.pixels(), pw, ph).is_err() {
            return;
        }
        dirty = false;
        last_draw = Instant::now();
    }
    if window.is_open() && dirty {
        let _ = window.update_with_buffer(canvas.pixels(), pw, ph);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const PLAIN: PreviewSettings = PreviewSettings { exposure: 0.0, tone_map: ToneMap::Clamp };

    #[test]
    fn small_images_are_enlarged_by_a_whole_factor_and_large_ones_shrunk_to_the_screen() {
        let small = Layout::fit((160, 120), (1280, 1024));
        assert_eq!((small.picture, small.zoom, small.window()), ((160, 120), 3, (480, 360)));
        // A medium image is shown pixel for pixel.
        assert_eq!(Layout::fit((800, 600), (1920, 1080)).window(), (800, 600));
        // A large one fits 90 % of the screen with its aspect ratio.
        let large = Layout::fit((4000, 2000), (1920, 1080));
        assert_eq!((large.picture, large.zoom), ((1728, 864), 1));
        let tall = Layout::fit((100, 5000), (1920, 1080));
        assert_eq!(tall.picture.0, 19);
        assert!((971..=972).contains(&tall.picture.1), "{:?}", tall.picture);
        // Not even a one-pixel screen breaks it.
        assert_eq!(Layout::fit((3, 3), (1, 1)).picture, (1, 1));
    }

    #[test]
    fn every_picture_pixel_is_covered_by_a_block_of_image_pixels() {
        for (image, picture) in [(4000, 1728), (17, 5), (10, 10), (7, 1)] {
            let spans = Layout::spans(image, picture);
            assert_eq!(spans[0], 0);
            assert_eq!(*spans.last().unwrap(), picture - 1);
            assert!(spans.windows(2).all(|p| p[1] == p[0] || p[1] == p[0] + 1), "{image} -> {picture}");
        }
    }

    #[test]
    fn a_one_to_one_picture_holds_the_png_colours() {
        let layout = Layout { image: (2, 1), picture: (2, 1), zoom: 1 };
        let settings = PreviewSettings { exposure: 1.0, tone_map: ToneMap::Reinhard };
        let mut canvas = Canvas::new(layout, settings);
        canvas.begin();
        canvas.tile(Region { x0: 0, y0: 0, x1: 2, y1: 1 }, &[[0.1, 0.5, 2.0], [f32::NAN, 1.0, 0.0]]);
        let film = crate::film::Film {
            pixels: vec![[0.1, 0.5, 2.0], [0.0, 0.0, 0.0]],
            ..crate::film::Film::for_region(Region { x0: 0, y0: 0, x1: 2, y1: 1 }, (2, 1), &[])
        };
        let png = crate::output::to_ldr(&film, 1.0, ToneMap::Reinhard);
        let word = |p: &image::Rgb<u8>| (u32::from(p.0[0]) << 16) | (u32::from(p.0[1]) << 8) | u32::from(p.0[2]);
        assert_eq!(canvas.pixels()[0], word(png.get_pixel(0, 0)));
        // A pixel with a NaN channel is black in the file, so black in the window.
        assert_eq!(canvas.pixels()[1], 0);
        assert_eq!(canvas.progress(), 1.0);
    }

    #[test]
    fn a_shrunk_picture_shows_block_means_and_a_new_pass_replaces_only_completed_pixels() {
        // 4 x 2 image shown as 2 x 1: each picture pixel is a 2 x 2 block.
        let layout = Layout { image: (4, 2), picture: (2, 1), zoom: 1 };
        let mut canvas = Canvas::new(layout, PLAIN);
        canvas.begin();
        let left = Region { x0: 0, y0: 0, x1: 2, y1: 2 };
        canvas.tile(left, &[[1.0; 3], [0.0; 3], [0.0; 3], [0.0; 3]]);
        let quarter = u32::from(ldr_channel(0.25, 1.0, ToneMap::Clamp));
        assert_eq!(canvas.pixels()[0], quarter * 0x010101);
        assert_eq!(canvas.pixels()[1], 0, "the right block has not arrived");
        // Half of the right block: during the first pass a partial mean is shown.
        canvas.tile(Region { x0: 2, y0: 0, x1: 4, y1: 1 }, &[[1.0; 3], [1.0; 3]]);
        assert_eq!(canvas.pixels()[1], 0xffffff);
        canvas.tile(Region { x0: 2, y0: 1, x1: 4, y1: 2 }, &[[1.0; 3], [1.0; 3]]);
        assert_eq!(canvas.progress(), 1.0);
        // A second pass: the completed pixels stay until the new pass completes them.
        canvas.begin();
        assert_eq!(canvas.progress(), 0.0);
        canvas.tile(Region { x0: 0, y0: 0, x1: 2, y1: 1 }, &[[0.0; 3], [0.0; 3]]);
        assert_eq!(canvas.pixels()[0], quarter * 0x010101, "half a block does not replace a whole one");
        canvas.tile(Region { x0: 0, y0: 1, x1: 2, y1: 2 }, &[[0.0; 3], [0.0; 3]]);
        assert_eq!(canvas.pixels()[0], 0);
    }

    #[test]
    fn an_enlarged_picture_keeps_one_pixel_per_image_pixel() {
        let layout = Layout::fit((8, 4), (1000, 1000));
        assert_eq!((layout.picture, layout.zoom), ((8, 4), 64));
        let mut canvas = Canvas::new(layout, PLAIN);
        canvas.tile(Region { x0: 8, y0: 0, x1: 9, y1: 1 }, &[[1.0; 3]]);
        assert!(canvas.pixels().iter().all(|&p| p == 0), "pixels outside the image are ignored");
        canvas.tile(Region { x0: 7, y0: 3, x1: 8, y1: 4 }, &[[1.0; 3]]);
        assert_eq!(canvas.pixels()[3 * 8 + 7], 0xffffff);
    }
}
