//! The scheduler renders any region of the frame with any integrator: a region's pixels and
//! AOV layers are exactly the same pixels of the whole frame, for stratified sampling and
//! for POV-Ray's antialiasing methods (whose 32-pixel blocks a region renders whole).

use std::path::Path;

use prism::film::{Aov, Film, Region};
use prism::render::integrators::classic::Classic;
use prism::render::{RenderOptions, render};
use prism::world::components::Antialias;

fn room(antialias: Antialias, samples: u32) -> prism::render::extract::RenderScene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/room.toml");
    let mut scene = prism::scene::load::load_file(&path, &prism::plugins::registry()).unwrap();
    scene.render.width = 100;
    scene.render.height = 57;
    scene.render.samples = samples;
    scene.render.antialias = antialias;
    prism::prepare(&mut scene).unwrap()
}

fn render_region(scene: &prism::render::extract::RenderScene, region: Region, aovs: &[Aov]) -> Film {
    let options = RenderOptions { threads: Some(2), aovs: aovs.to_vec(), ..Default::default() };
    render(scene, &Classic::new(scene), region, &options).unwrap().0
}

/// Every value of `part` equals the full film's value at the same frame position.
fn assert_is_crop(full: &Film, part: &Film, what: &str) {
    let region = part.region();
    for y in 0..part.height {
        for x in 0..part.width {
            let (fx, fy) = (region.x0 + x, region.y0 + y);
            assert_eq!(part.get(x, y), full.get(fx, fy), "{what}: beauty at ({fx}, {fy})");
            for (a, b) in part.layers.iter().zip(&full.layers) {
                let n = a.channel_count();
                let i = (y * part.width + x) as usize * n;
                let j = (fy * full.width + fx) as usize * n;
                let (pa, pb) = (&a.data[i..i + n], &b.data[j..j + n]);
                // NaN never appears; infinite depth compares equal to itself.
                assert_eq!(pa, pb, "{what}: layer {} at ({fx}, {fy})", a.aov.name());
            }
        }
    }
}

#[test]
fn a_region_is_the_same_pixels_of_the_whole_frame() {
    let aovs = [Aov::Albedo, Aov::Normal, Aov::Depth, Aov::ObjectId];
    for (antialias, samples) in [
        (Antialias::Stratified {}, 3),
        (Antialias::Pov1 { threshold: 0.1, depth: 3 }, 1),
        (Antialias::Pov2 { threshold: 0.1, depth: 3 }, 1),
    ] {
        let scene = room(antialias, samples);
        let full = render_region(&scene, Region::full(100, 57), &aovs);
        assert!(full.is_full_frame());
        // Regions that straddle tile and block edges, and one in the last partial block.
        for region in [
            Region { x0: 13, y0: 7, x1: 50, y1: 41 },
            Region { x0: 64, y0: 32, x1: 100, y1: 57 },
            Region { x0: 31, y0: 31, x1: 33, y1: 33 },
        ] {
            let part = render_region(&scene, region, &aovs);
            assert_eq!((part.origin, part.frame), ((region.x0, region.y0), (100, 57)));
            assert_is_crop(&full, &part, &format!("{antialias:?} {region:?}"));
        }
    }
}

#[test]
fn aov_layers_describe_the_first_surface() {
    let scene = room(Antialias::Stratified {}, 1);
    let film = render_region(&scene, Region::full(100, 57), &[Aov::Normal, Aov::Depth, Aov::ObjectId]);
    let (normal, depth, id) = (&film.layers[0].data, &film.layers[1].data, &film.layers[2].data);
    let pixels = film.pixels.len();
    let mut hits = 0;
    for i in 0..pixels {
        if id[i] >= 0.0 {
            hits += 1;
            let n = &normal[3 * i..3 * i + 3];
            let length = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
            assert!((length - 1.0).abs() < 1e-4, "normal at pixel {i} has length {length}");
            assert!(depth[i].is_finite() && depth[i] > 0.0, "depth at pixel {i} is {}", depth[i]);
        } else {
            assert_eq!(depth[i], f32::INFINITY, "escaped ray at pixel {i} has a depth");
        }
    }
    assert_eq!(hits, pixels, "the room is closed: every camera ray meets a surface");
}

#[test]
fn a_region_outside_the_frame_is_an_error() {
    let scene = room(Antialias::Stratified {}, 1);
    for region in [Region { x0: 0, y0: 0, x1: 101, y1: 10 }, Region { x0: 5, y0: 5, x1: 5, y1: 9 }] {
        let options = RenderOptions::default();
        let error = render(&scene, &Classic::new(&scene), region, &options).unwrap_err().to_string();
        assert!(error.contains("100x57"), "{error}");
    }
}
