//! `prism export pov`: the POV-Ray exporter through the command line (a scene that exports,
//! and scenes it must refuse, each with a message naming what it cannot express), and a
//! plugin shape without `to_pov` through the library.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::Arc;

use prism::registry::ShapeRegistry;
use prism_api::{Aabb, DVec2, DVec3, Hit, ParamError, Ray, Shape, ShapeParams, Surface, shape_type};
use schemars::JsonSchema;
use serde::Deserialize;

fn prism() -> Command {
    Command::new(env!("CARGO_BIN_EXE_prism"))
}

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn exports_the_seed_room() {
    let run = prism().arg("export").arg("pov").arg(root().join("scenes/room.toml")).output().unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let pov = String::from_utf8(run.stdout).unwrap();
    for needle in [
        "#version 3.7;",
        "assumed_gamma 1.0",
        "max_trace_level 5",
        "adc_bailout 0.00392156862745098",
        "ambient_light rgb <1.0, 1.0, 1.0>",
        "location <0.0, 0.0, -1.0>",
        "direction <0.0, 0.0, 1.0>",
        "up <0.0, 1.9999999999999998, -0.0>",
        "right <1.0, -0.0, -0.0> * 1.9999999999999998 * image_width / image_height",
        // The light at (0, 2.5, -3) in Prism's right-handed frame.
        "light_source { <0.0, 2.5, 3.0>, color rgb <1.0, 1.0, 1.0>",
        // The orange sphere, translated by (-1.2, -0.5, -3.5): z mirrored.
        "matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -1.2, -0.5, 3.5>",
        "pigment { rgbft <0.9, 0.3, 0.1, 0.0, 0.0> }",
        "reflection { rgb <0.8, 0.8, 0.8>, rgb <0.8, 0.8, 0.8> falloff 1.0 exponent 1.0 metallic 0.0 }",
        "cone { <0.0, -0.2, 5.0>, 0.6, <0.0, 1.2, 6.0>, 0.0 open",
        "// povray-options: +W1000 +H563 -A",
    ] {
        assert!(pov.contains(needle), "missing `{needle}` in:\n{pov}");
    }
    assert_eq!(pov.matches("plane {").count(), 6);
    assert_eq!(pov.matches("interior { ior 1.0 }").count(), 10);
}

#[test]
fn writes_normal_patterns_after_the_pigment() {
    let run = prism().args(["export", "pov"]).arg(root().join("scenes/parity/normals.toml")).output().unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let pov = String::from_utf8(run.stdout).unwrap();
    for needle in [
        "    normal {\n      ripples 0.4\n      frequency 3.0\n      phase 0.2\n",
        "      bumps 0.3\n      turbulence <0.5, 0.5, 0.5> octaves 3\n      matrix ",
        "      waves -0.8\n      turbulence <0.2, 0.2, 0.2> omega 0.6 lambda 2.5 octaves 4\n      frequency 4.0\n",
        "      dents 1.5\n",
        "      wrinkles 0.8\n",
    ] {
        assert!(pov.contains(needle), "missing `{needle}` in:\n{pov}");
    }
    assert_eq!(pov.matches("normal {").count(), 10);
}

#[test]
fn writes_one_texture_per_layer_bottom_first() {
    let run = prism().args(["export", "pov"]).arg(root().join("scenes/parity/layered.toml")).output().unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let pov = String::from_utf8(run.stdout).unwrap();
    // The wall's one texture, two on the floor, three on the sphere, two on the glass and the box.
    assert_eq!(pov.matches("  texture {").count(), 10);
    let sphere = &pov[pov.find("\"three_layers\" sphere").unwrap()..pov.find("\"coated_glass\" box").unwrap()];
    let at = |needle: &str| sphere.find(needle).unwrap_or_else(|| panic!("missing `{needle}` in:\n{sphere}"));
    // POV-Ray puts the last texture on top: the base first, the clear coat last.
    assert!(at("rgbft <0.8, 0.15, 0.1, 0.0, 0.0>") < at("gradient <0.0, 1.0, -0.0>"));
    assert!(at("gradient <0.0, 1.0, -0.0>") < at("bumps 0.4"));
    assert!(at("emission rgb <0.15, 0.15, 0.15>") < at("bumps 0.4"));
    // One interior for the object, after every layer.
    assert_eq!(sphere.matches("interior {").count(), 1);
    assert!(at("bumps 0.4") < at("interior { ior 1.0 }"));
}

#[test]
fn writes_crackle_quilted_and_pattern_normals() {
    let run = prism().args(["export", "pov"]).arg(root().join("scenes/parity/crackle.toml")).output().unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let pov = String::from_utf8(run.stdout).unwrap();
    for needle in [
        "    pigment {\n      crackle solid\n      color_map {",
        "      crackle\n      form <0.8, 0.4, 0.0> metric 3.0 offset 0.3\n",
        "      quilted control0 0.2 control1 0.9\n",
        "      granite bump_size 0.4 accuracy 0.05\n",
        "      quilted 0.8 control0 0.3 control1 0.8\n",
        "      gradient <1.0, 1.0, -0.0> bump_size -0.7\n      frequency 3.0\n      triangle_wave\n",
        "      facets 0.5 size 0.15\n",
        "      facets 0.5 coords 0.6 metric 3.0\n",
        "      crackle bump_size 1.2 accuracy 0.01\n      form <0.0, 1.0, -0.5> metric 2.5\n      turbulence <0.2, 0.2, 0.2>\n",
    ] {
        assert!(pov.contains(needle), "missing `{needle}` in:\n{pov}");
    }
}

#[test]
fn writes_slope_and_normal_maps_with_each_entry_in_its_own_frame() {
    let run = prism().args(["export", "pov"]).arg(root().join("scenes/parity/normal_maps.toml")).output().unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let pov = String::from_utf8(run.stdout).unwrap();
    for needle in [
        "      gradient <1.0, 0.0, -0.0> bump_size 0.5\n      slope_map {\n        [0.0 <0.0, 1.0>]\n        [0.5 <1.0, 0.0>]\n",
        // A map's pattern has no bump size; each entry its own, and its own matrix only.
        "      gradient <0.0, 1.0, -0.0>\n      normal_map {\n        [0.3 bumps 0.8\n          \
         matrix <0.2, 0.0, -0.0, 0.0, 0.2, -0.0, -0.0, -0.0, 0.2, 0.0, 0.0, -0.0>]\n        [0.7 ripples 0.6\n          frequency 3.0]\n      }\n",
        // A slope map inside an entry, and a nested map.
        "        [0.5 granite bump_size 0.4\n          slope_map {\n            [0.0 <0.0, 1.0>]\n",
        "        [1.0 onion\n          normal_map {\n            [0.0 quilted 0.6\n",
    ] {
        assert!(pov.contains(needle), "missing `{needle}` in:\n{pov}");
    }
}

#[test]
fn writes_averages_with_their_weights() {
    let run = prism().args(["export", "pov"]).arg(root().join("scenes/parity/average.toml")).output().unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let pov = String::from_utf8(run.stdout).unwrap();
    for needle in [
        "      average\n      turbulence <0.3, 0.3, 0.3>\n      pigment_map {\n        [1.0 gradient <1.0, 0.0, -0.0>\n",
        // A normal average has no bump size of its own.
        "      average\n      normal_map {\n        [1.0 bumps 0.4\n",
        "        [0.5 color rgbft <0.2, 0.9, 0.2, 0.0, 0.0>]\n",
        // Inside a map entry.
        "        [0.0 average\n          normal_map {\n",
    ] {
        assert!(pov.contains(needle), "missing `{needle}` in:\n{pov}");
    }
}

#[test]
fn writes_bump_maps_with_their_image_options() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("bump_map.pov");
    let run = prism()
        .args(["export", "pov"])
        .arg(root().join("scenes/parity/bump_map.toml"))
        .arg("-o")
        .arg(&out)
        .output()
        .unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let pov = std::fs::read_to_string(&out).unwrap();
    for needle in [
        "image_map_grey.png\" map_type 1 interpolate 3 bump_size -4.0 }\n",
        "image_map.png\" map_type 0 interpolate 2 once bump_size -2.0 }\n      turbulence <0.05, 0.05, 0.05>\n",
        // Inside a normal_map entry, with the entry's own matrix.
        "        [0.7 bump_map { png \"",
        "image_map_palette.png\" map_type 0 interpolate 2 use_index bump_size 0.3 }\n",
    ] {
        assert!(pov.contains(needle), "missing `{needle}` in:\n{pov}");
    }
    // No `gamma`: POV-Ray reads a bump map's samples as stored, as Prism does.
    assert!(!pov.lines().any(|l| l.contains("bump_map") && l.contains(" gamma ")), "{pov}");
}

#[test]
fn writes_pigment_maps_with_each_entry_in_its_own_frame() {
    let run = prism().args(["export", "pov"]).arg(root().join("scenes/parity/pigment_map.toml")).output().unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let pov = String::from_utf8(run.stdout).unwrap();
    for needle in [
        // Plain entries are colours; an entry has its own matrix only, the outer pigment the
        // object's as well.
        "      pigment_map {\n        [0.0 checker color rgbft <0.9, 0.88, 0.8, 0.0, 0.0>, color rgbft <0.25, 0.3, 0.4, 0.0, 0.0>\n          \
         matrix <0.5, 0.0, -0.0, 0.0, 0.5, -0.0, -0.0, -0.0, 0.5, 0.0, 0.0, -0.0>]\n        [0.4 color rgbft <0.9, 0.2, 0.1, 0.0, 0.0>]\n",
        "        [1.0 color rgbft <0.2, 0.9, 0.3, 0.5, 0.2>]\n      }\n",
        // A nested map inside an entry.
        "          pigment_map {\n            [0.0 color rgbft <0.8, 0.1, 0.1, 0.0, 0.0>]\n",
        // An image map entry, its file relative to the written file's folder.
        "[0.3 image_map { png \"",
        // POV-Ray's list form of a discrete pattern's pigments.
        "      checker\n        pigment {\n          gradient <1.0, 1.0, -0.0>\n",
        "        },\n        pigment {\n          radial\n",
    ] {
        assert!(pov.contains(needle), "missing `{needle}` in:\n{pov}");
    }
}

#[test]
fn writes_the_file_given_with_o() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("room.pov");
    let run =
        prism().args(["export", "pov"]).arg(root().join("scenes/parity/room_pov1.toml")).arg("-o").arg(&out).output();
    let run = run.unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let pov = std::fs::read_to_string(&out).unwrap();
    assert!(pov.contains("// povray-options: +W320 +H180 +A0.3 +AM1 +R3 -J"), "{pov}");
    assert!(run.stdout.is_empty());
}

/// Writes `scene` to a temporary scene file and exports it; returns (success, stderr).
fn export(scene: &str) -> (bool, String, tempfile::TempDir) {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("scene.toml"), scene).unwrap();
    let out = dir.path().join("scene.pov");
    let run = prism().current_dir(dir.path()).args(["export", "pov", "scene.toml", "-o"]).arg(&out).output().unwrap();
    assert!(!String::from_utf8_lossy(&run.stderr).contains("panicked"));
    (run.status.success(), String::from_utf8_lossy(&run.stderr).into_owned(), dir)
}

#[test]
fn refuses_what_pov_ray_cannot_render_alike() {
    let cases = [
        (
            "stratified supersampling",
            "[render]\nsamples = 4\n[[object]]\nshape = \"sphere\"\n",
            vec!["scene.toml:", "render.samples", "no POV-Ray equivalent", "pov1"],
        ),
        (
            "trace depth beyond POV-Ray's limit",
            "[render]\nmax_depth = 300\n[[object]]\nshape = \"sphere\"\n",
            vec!["scene.toml:", "render.max_depth", "limit of 256"],
        ),
        (
            "antialiasing deeper than POV-Ray's +R9",
            "[render]\nantialias = { method = \"pov1\", depth = 12 }\n",
            vec!["scene.toml:", "render.antialias.depth", "between 1 and 9"],
        ),
        (
            "a negative antialiasing threshold",
            "[render]\nantialias = { method = \"pov2\", threshold = -0.1 }\n",
            vec!["scene.toml:", "render.antialias.threshold", "0 or positive"],
        ),
        (
            "an unknown antialiasing method",
            "[render]\nantialias = { method = \"pov3\" }\n",
            vec!["scene.toml:2:", "render.antialias", "pov3"],
        ),
    ];
    for (what, scene, expect) in cases {
        let (ok, stderr, dir) = export(scene);
        assert!(!ok, "{what}: exported");
        for e in expect {
            assert!(stderr.contains(e), "{what}: message lacks `{e}`: {stderr}");
        }
        assert!(!dir.path().join("scene.pov").exists(), "{what}: wrote a file anyway");
    }
}

#[test]
fn refuses_a_broken_scene_with_its_diagnostics() {
    let (ok, stderr, _dir) = export("[[object]]\nshape = \"sphere\"\nradius = -1\n");
    assert!(!ok);
    assert!(stderr.contains("scene.toml:3:") && stderr.contains("object[0].radius"), "{stderr}");
}

#[test]
fn focal_blur_maps_the_lens() {
    let (ok, stderr, dir) = export(
        "[render]\nsamples = 9\n[camera]\naperture = 0.5\nfocal_distance = 3.0\n[[object]]\nshape = \"sphere\"\n",
    );
    assert!(ok, "{stderr}");
    let pov = std::fs::read_to_string(dir.path().join("scene.pov")).unwrap();
    // POV-Ray's lens disc has radius aperture / 4, Prism's aperture / 2.
    for needle in ["aperture 1.0", "blur_samples 9", "focal_point <0.0, 0.0, 2.0>", "variance 0", "+W1000 +H563 -A"] {
        assert!(pov.contains(needle), "missing `{needle}` in:\n{pov}");
    }
}

#[test]
fn adaptive_focal_blur_writes_povrays_keywords() {
    let (ok, stderr, dir) = export(
        "[render]\nsamples = 64\n[camera]\naperture = 0.5\nblur_variance = 0.0001\nblur_confidence = 0.95\n\
         blur_min_samples = 7\n[[object]]\nshape = \"sphere\"\n",
    );
    assert!(ok, "{stderr}");
    let pov = std::fs::read_to_string(dir.path().join("scene.pov")).unwrap();
    for needle in ["aperture 1.0", "blur_samples 7, 64", "variance 0.0001", "confidence 0.95"] {
        assert!(pov.contains(needle), "missing `{needle}` in:\n{pov}");
    }
    assert!(!pov.contains("variance 0\n"), "{pov}");
}

/// A plugin shape without a POV-Ray equivalent.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
struct LumpParams {}

#[derive(Debug)]
struct Lump;

impl ShapeParams for LumpParams {
    fn build(self) -> Result<Arc<dyn Shape>, ParamError> {
        Ok(Arc::new(Lump))
    }
}

impl Shape for Lump {
    fn bounds(&self) -> Aabb {
        Aabb::from_corners(DVec3::splat(-1.0), DVec3::splat(1.0))
    }

    fn intersect(&self, _: &Ray, _: f64, _: f64) -> Option<Hit> {
        None
    }

    fn surface(&self, ray: &Ray, hit: &Hit) -> Surface {
        Surface::new(ray.at(hit.t), DVec3::Y, DVec2::ZERO)
    }
}

#[test]
fn a_shape_without_to_pov_is_named() {
    let mut registry = ShapeRegistry::new();
    registry.add(shape_type::<LumpParams>("lump", "A shape POV-Ray does not know."));
    registry.add(shape_type::<prism_sphere::SphereParams>("sphere", "A sphere."));
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("scene.toml");
    std::fs::write(&path, "[[object]]\nshape = \"sphere\"\n\n[[object]]\nname = \"odd\"\nshape = \"lump\"\n").unwrap();
    let mut scene = prism::scene::load::load_file(Path::new(&path), &registry).unwrap();
    prism::world::transforms::resolve_transforms(&mut scene).unwrap();
    let error = prism::export::pov::export(&scene, "scene.toml", None).unwrap_err().to_string();
    for needle in ["scene.toml:4:", "object[1].shape", "shape `lump` has no POV-Ray equivalent", "Shape::to_pov"] {
        assert!(error.contains(needle), "missing `{needle}` in: {error}");
    }
}

/// An image map is written with POV-Ray's keywords and numbers and the file as the scene wrote
/// it; a file name POV-Ray's strings cannot hold is refused.
#[test]
fn writes_image_maps_with_the_file_as_written() {
    let png = std::fs::read(root().join("scenes/parity/image_map.png")).unwrap();
    let map = |file: &str| {
        format!(
            "[[object]]\nshape = \"sphere\"\nmaterial = {{ pigment = {{ image_map = {{ file = {file:?}, map_type = \
             \"spherical\", interpolate = \"bilinear\", once = true, filter_all = 0.2, transmit_all = 0.1 }} }} }}\n"
        )
    };
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("tex")).unwrap();
    std::fs::write(dir.path().join("tex/img.png"), &png).unwrap();
    std::fs::write(dir.path().join("scene.toml"), map("tex/img.png")).unwrap();
    // Relative to the exported file's folder (here the scene's), absolute on standard output.
    let run =
        prism().current_dir(dir.path()).args(["export", "pov", "scene.toml", "-o", "scene.pov"]).output().unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let pov = std::fs::read_to_string(dir.path().join("scene.pov")).unwrap();
    assert!(
        pov.contains("image_map { png \"tex/img.png\" map_type 1 interpolate 2 once filter all 0.2 transmit all 0.1 }"),
        "{pov}"
    );
    let run = prism().current_dir(dir.path()).args(["export", "pov", "scene.toml"]).output().unwrap();
    let absolute = std::fs::canonicalize(dir.path().join("tex/img.png")).unwrap();
    assert!(String::from_utf8_lossy(&run.stdout).contains(&format!("png \"{}\" map_type", absolute.display())));
    std::fs::write(dir.path().join("q\"uote.png"), &png).unwrap();
    std::fs::write(dir.path().join("scene.toml"), map("q\"uote.png")).unwrap();
    let run = prism().current_dir(dir.path()).args(["export", "pov", "scene.toml"]).output().unwrap();
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(!run.status.success() && stderr.contains("pigment.image_map.file"), "{stderr}");
    assert!(stderr.contains("cannot be written as a POV-Ray string"), "{stderr}");
}

/// A text's font is written relative to the exported file's folder (absolute without one),
/// and a saved scene names it relative to the saved file, so both still find it.
#[test]
fn font_paths_follow_the_written_file() {
    let scene_path = root().join("scenes/parity/text.toml");
    let mut scene = prism::scene::load::load_file(&scene_path, &prism::plugins::registry()).unwrap();
    prism::world::transforms::resolve_transforms(&mut scene).unwrap();
    prism::world::validate::validate(&scene).unwrap();
    let font = std::fs::canonicalize(root().join("assets/fonts/DejaVuSans.ttf")).unwrap();
    let beside = prism::export::pov::export(&scene, "text.toml", Some(&root().join("scenes/parity"))).unwrap();
    assert!(beside.contains("text { ttf \"../../assets/fonts/DejaVuSans.ttf\" \"Prism\" 0.3,"), "{beside}");
    let absolute = prism::export::pov::export(&scene, "text.toml", None).unwrap();
    assert!(absolute.contains(&format!("ttf \"{}\"", font.display())), "{absolute}");

    let dir = tempfile::tempdir().unwrap();
    let copy = dir.path().join("deeper/copy.toml");
    std::fs::create_dir_all(copy.parent().unwrap()).unwrap();
    let saved = prism::scene::save::save_for(&scene, &copy).unwrap();
    std::fs::write(&copy, &saved).unwrap();
    assert!(!saved.contains("\"../../assets/fonts"), "the scene's own relative path is not reused: {saved}");
    let again =
        prism::scene::load::load_file(&copy, &prism::plugins::registry()).unwrap_or_else(|e| panic!("{e}\n{saved}"));
    assert_eq!(prism::scene::save::save_for(&again, &copy).unwrap(), saved);
}
