//! Determinism (bit-identical images for any thread count) and `save` as the inverse of
//! `load` (a saved world reloads to the identical image), on both seed scenes (and, for
//! save, the CSG parity scene).

use std::path::{Path, PathBuf};

use prism::film::Film;
use prism::render::{RenderOptions, render_frame};
use prism::scene::load::load_file;
use prism::world::Scene;

fn scene_path(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes").join(name)
}

fn render_scene(mut scene: Scene, width: u32, height: u32, samples: u32, threads: usize) -> Film {
    scene.render.width = width;
    scene.render.height = height;
    scene.render.samples = samples;
    let render_scene = prism::prepare(&mut scene).unwrap();
    render_frame(&render_scene, &RenderOptions { threads: Some(threads), ..Default::default() }).unwrap().0
}

fn load(path: &Path) -> Scene {
    load_file(path, &prism::plugins::registry()).unwrap()
}

#[test]
fn thread_count_does_not_change_a_single_bit() {
    for name in ["room.toml", "snowman.toml"] {
        let one = render_scene(load(&scene_path(name)), 120, 68, 4, 1);
        let two = render_scene(load(&scene_path(name)), 120, 68, 4, 2);
        let exr = |f: &Film| prism::output::encode(f, Path::new("x.exr"), &Default::default()).unwrap();
        assert!(one == two, "{name}: films differ between 1 and 2 threads");
        assert_eq!(exr(&one), exr(&two), "{name}: EXR bytes differ between 1 and 2 threads");
        assert!(one.pixels.iter().any(|p| p[0] > 0.1), "{name}: image is black");
    }
}

#[test]
fn a_saved_scene_reloads_to_the_identical_image() {
    // The pattern parity scene (pigments with transforms), the CSG parity scene: groups
    // with member materials (named and inline), transforms, `inverse` and a nested group; the
    // layered-texture one (named materials of several layers, patterns in layers) and the
    // image map one (PNG paths written absolute and read again), and the pigment map one
    // (nested pigments, an image map inside an entry).
    for name in [
        "room.toml",
        "snowman.toml",
        "parity/patterns.toml",
        "parity/csg.toml",
        "parity/layered.toml",
        "parity/image_map.toml",
        "parity/pigment_map.toml",
    ] {
        let original = load(&scene_path(name));
        let text = prism::scene::save::save(&original).unwrap();
        let dir = tempfile::tempdir().unwrap();
        let saved = dir.path().join(Path::new(name).file_name().unwrap());
        std::fs::write(&saved, &text).unwrap();
        let reloaded = load(&saved);
        assert_eq!(original.render, reloaded.render, "{name}: render settings");
        assert_eq!(original.camera(), reloaded.camera(), "{name}: camera");
        let a = render_scene(original, 96, 54, 2, 2);
        let b = render_scene(reloaded, 96, 54, 2, 2);
        assert!(a == b, "{name}: saved scene renders differently; saved text:\n{text}");
        // Saving the reloaded scene again gives the same text: save is stable.
        let again = prism::scene::save::save(&load(&saved)).unwrap();
        assert_eq!(text, again, "{name}: save is not stable");
    }
}

#[test]
fn stratified_samples_converge_to_the_pixel_mean() {
    // More samples change edge pixels but keep flat regions exactly where they were.
    let one = render_scene(load(&scene_path("room.toml")), 80, 45, 1, 2);
    let many = render_scene(load(&scene_path("room.toml")), 80, 45, 16, 2);
    let wall_one = one.get(2, 22);
    let wall_many = many.get(2, 22);
    for c in 0..3 {
        assert!((wall_one[c] - wall_many[c]).abs() < 0.02, "{wall_one:?} vs {wall_many:?}");
    }
    let changed = one.pixels.iter().zip(&many.pixels).filter(|(a, b)| a != b).count();
    assert!(changed > 0, "supersampling changed nothing");
}

#[test]
fn adaptive_focal_blur_is_bit_identical_for_any_thread_count() {
    // POV-Ray's adaptive focal blur stops each pixel (under pov1, each traced position) from
    // its own samples: the image must not depend on the threads or the tiles.
    for antialias in ["", "antialias = { method = \"pov1\", threshold = 0.1, depth = 2 }\n"] {
        let text = std::fs::read_to_string(scene_path("parity/focal_blur_adaptive.toml"))
            .unwrap()
            .replace("samples = 64\n", &format!("samples = 24\n{antialias}"));
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("blur.toml");
        std::fs::write(&path, text).unwrap();
        let one = render_scene(load(&path), 80, 45, 24, 1);
        let two = render_scene(load(&path), 80, 45, 24, 2);
        assert!(one == two, "{antialias}: films differ between 1 and 2 threads");
        assert!(one.pixels.iter().any(|p| p[0] > 0.1), "{antialias}: image is black");
    }
}

/// An image map is loaded wherever a pigment holds it: a one-layer layered material and a
/// one-entry `pigment_map` render the same image as the plain image map pigment.
#[test]
fn image_maps_in_layers_and_pigment_map_entries_are_loaded() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::copy(scene_path("parity/image_map.png"), dir.path().join("map.png")).unwrap();
    let map = "{ file = \"map.png\", map_type = \"spherical\" }";
    let render = |material: String| {
        let text = format!(
            "[camera]\nposition = [0, 0, 3]\nlook_at = [0, 0, 0]\n[[light]]\nposition = [0, 3, 5]\n\
             [[object]]\nshape = \"sphere\"\nmaterial = {material}\n"
        );
        let path = dir.path().join("scene.toml");
        std::fs::write(&path, text).unwrap();
        render_scene(load(&path), 48, 32, 1, 1)
    };
    let plain = render(format!("{{ diffuse = 0.7, pigment = {{ image_map = {map} }} }}"));
    let layered = render(format!("{{ layers = [{{ diffuse = 0.7, pigment = {{ image_map = {map} }} }}] }}"));
    let entry = render(format!(
        "{{ diffuse = 0.7, pigment = {{ pattern = \"onion\", pigment_map = [[0.5, {{ image_map = {map} }}]] }} }}"
    ));
    assert!(plain.pixels.iter().any(|p| (p[0] - p[1]).abs() > 0.01), "the image map is not read");
    assert!(layered == plain, "a layer's image map renders differently");
    assert!(entry == plain, "a pigment_map entry's image map renders differently");
}
