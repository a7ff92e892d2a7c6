//! Hostile and degenerate scenes found by an adversarial sweep of the newer features
//! (patterns, normals, CSG, text, lights, `[render]` keys): each must render correctly or
//! end with a clear error naming the file, line and key, never a panic, a hang or a
//! half-written output.

mod common;

use common::{failed_run_problems, run, stderr};
use std::path::Path;
use std::process::{Command, Output};

fn prism() -> Command {
    Command::new(env!("CARGO_BIN_EXE_prism"))
}

/// Writes `scene` as `scene.toml` in `dir` and renders it at 8 x 6 to `out.png`.
fn render_scene(dir: &Path, scene: &str) -> Output {
    std::fs::write(dir.join("scene.toml"), scene).unwrap();
    let mut c = prism();
    c.current_dir(dir).args(["render", "scene.toml", "-o", "out.png", "--width", "8", "--height", "6"]);
    run(c)
}

fn assert_renders(dir: &Path, scene: &str) {
    let _ = std::fs::remove_file(dir.join("out.png"));
    let out = render_scene(dir, scene);
    assert!(out.status.success(), "{scene}\n--- stderr:\n{}", stderr(&out));
    assert!(dir.join("out.png").is_file(), "{scene}");
}

fn assert_refused(dir: &Path, scene: &str, expect: &[&str]) {
    let _ = std::fs::remove_file(dir.join("out.png"));
    let out = render_scene(dir, scene);
    let problems = failed_run_problems(&out, expect);
    assert!(problems.is_empty(), "{scene}\n{}\n--- stderr:\n{}", problems.join("; "), stderr(&out));
    assert!(!stderr(&out).contains("internal error"), "{}", stderr(&out));
    assert!(!dir.join("out.png").exists(), "{scene}: an output was written");
}

/// Noise and crackle read far from the origin: a plane seen from a million units up through
/// a pattern scaled down 5,000 times (crackle cells past the i32 range), and turbulence,
/// `lambda` and normal `accuracy` so large that the point leaves the i64 range or becomes
/// infinite. Each used to overflow an integer (an internal error); each renders.
#[test]
fn patterns_read_far_from_the_origin_render() {
    let dir = tempfile::tempdir().unwrap();
    let far_plane = "[camera]\nposition = [0, 1000000, 0]\nlook_at = [1, 0, -1]\n\
         [[light]]\nposition = [0, 1000000, 0]\n\
         [[object]]\nshape = \"plane\"\n\
         material = { pigment = { pattern = \"crackle\", scale = 2e-4, color_map = [[0, 0], [1, 1]] } }\n\
         [[object]]\nshape = \"sphere\"\ntransform = { translate = [0, 0, -1e6] }\n\
         material = { normal = { pattern = \"facets\", scale = 2e-4 } }\n";
    assert_renders(dir.path(), far_plane);
    let sphere = |material: &str| {
        format!(
            "[camera]\nposition = [0, 0, 5]\n[[light]]\nposition = [3, 3, 5]\n[[object]]\nshape = \"sphere\"\nmaterial = {material}\n"
        )
    };
    for pattern in ["bozo", "crackle", "agate", "wood", "marble", "granite", "wrinkles"] {
        for turbulence in ["turbulence = 1e300", "turbulence = 1, octaves = 10, lambda = 1e300"] {
            let material =
                format!("{{ pigment = {{ pattern = \"{pattern}\", {turbulence}, color_map = [[0, 0], [1, 1]] }} }}");
            assert_renders(dir.path(), &sphere(&material));
        }
    }
    assert_renders(dir.path(), &sphere("{ normal = { pattern = \"granite\", accuracy = 1e300 } }"));
}

/// Pattern colours keep a material's limits (components within ±1e30, filter and transmit
/// within ±1e9): a `color_map` colour of 1e31, a `color_map` filter or an image map's
/// `transmit_all` of 1e300 and a `pigment_map` entry's filter of 1e300 used to render with
/// overflowing pixels; each is an error naming the file, line and key.
#[test]
fn pattern_colours_beyond_the_limits_are_refused_at_load() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::copy(common::repo().join("scenes/parity/image_map.png"), dir.path().join("img.png")).unwrap();
    let pigment = |p: &str| format!("[[object]]\nshape = \"sphere\"\nmaterial = {{ pigment = {p} }}\n");
    let cases = [
        ("{ pattern = \"bozo\", color_map = [[0, [1e31, 0, 0]], [1, 1]] }", "pigment.color_map`: entry 0: colour"),
        ("{ pattern = \"bozo\", color_map = [[0, 0], [1, { color = 1, filter = 1e300 }]] }", "entry 1: filter"),
        ("{ pattern = \"checker\", colors = [0, { color = 1, transmit = -1e10 }] }", "pigment.colors`: entry 1"),
        ("{ image_map = { file = \"img.png\", transmit_all = 1e300 } }", "pigment.image_map.transmit_all"),
        ("{ pattern = \"bozo\", pigment_map = [[0, { color = 1, filter = 1e300 }]] }", "pigment_map[0].filter"),
    ];
    for (p, key) in cases {
        assert_refused(dir.path(), &pigment(p), &["scene.toml:3:", key, "1e"]);
    }
}

/// `[world]` keeps the limits on values: a NaN `background` named `render.background`
/// without a line, and a `background` or `ambient_light` beyond ±1e30 or an environment
/// `intensity` of 1e300 loaded and rendered overflowing (or black) pixels. Each is an error
/// at its key's line.
#[test]
fn world_colours_and_environment_intensity_are_checked_at_their_keys() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::copy(common::repo().join("assets/env/sunset_256x128.exr"), dir.path().join("sky.exr")).unwrap();
    let sphere = "[[object]]\nshape = \"sphere\"\n";
    let cases = [
        ("[world]\nbackground = [nan, 0, 0]\n", "scene.toml:2:1: error in `world.background`: must be finite"),
        ("[world]\nbackground = 1e31\n", "scene.toml:2:1: error in `world.background`: components must lie within"),
        ("[world]\nambient_light = [0, 1e300, 0]\n", "scene.toml:2:1: error in `world.ambient_light`"),
        (
            "[render]\nintegrator = \"path\"\n[world]\nenvironment = { file = \"sky.exr\", intensity = 1e300 }\n",
            "scene.toml:4:35: error in `world.environment.intensity`: must be at most 1e9",
        ),
    ];
    for (world, expect) in cases {
        assert_refused(dir.path(), &format!("{world}{sphere}"), &[expect]);
    }
    // At the limits the scene loads.
    let world = "[world]\nbackground = [1e30, 0, 0]\nambient_light = -1e30\n";
    assert_renders(dir.path(), &format!("{world}{sphere}"));
}

/// Keys beside the tag of `antialias = { method = "stratified" }` and `filter = { type =
/// "box" }` (a stray `depth`, a `stddev`) were ignored silently, serde not refusing unknown
/// keys of a unit variant; they are errors at the key like any unknown key.
#[test]
fn keys_beside_stratified_and_box_are_unknown_keys() {
    let dir = tempfile::tempdir().unwrap();
    let sphere = "[[object]]\nshape = \"sphere\"\n";
    let cases = [
        ("antialias = { method = \"stratified\", depth = 3 }", "scene.toml:2:38: error in `render.antialias.depth`"),
        ("filter = { type = \"box\", stddev = 2 }", "scene.toml:2:26: error in `render.filter.stddev`"),
    ];
    for (render, expect) in cases {
        assert_refused(dir.path(), &format!("[render]\n{render}\n{sphere}"), &[expect, "unknown key"]);
    }
    let plain = "[render]\nantialias = { method = \"stratified\" }\nfilter = { type = \"box\" }\n";
    assert_renders(dir.path(), &format!("{plain}{sphere}"));
}

/// `prism save` checks the scene as `render` and the exports do: a camera with `vfov = 0`
/// or a parent cycle used to be saved with exit 0, the copy then failing to load at its own
/// lines. Now it is an error at the original's line, and no copy is written.
#[test]
fn save_refuses_a_scene_that_cannot_render() {
    let dir = tempfile::tempdir().unwrap();
    let sphere = "[[object]]\nshape = \"sphere\"\n";
    let cases = [
        (format!("[camera]\nvfov = 0\n{sphere}"), "scene.toml:2:1: error in `camera.vfov`"),
        (
            "[[object]]\nshape = \"sphere\"\nname = \"a\"\nparent = \"a\"\n".to_string(),
            "scene.toml:1:1: error in `object[0].parent`: parent chain forms a cycle",
        ),
    ];
    for (scene, expect) in cases {
        std::fs::write(dir.path().join("scene.toml"), &scene).unwrap();
        let mut c = prism();
        c.current_dir(dir.path()).args(["save", "scene.toml", "-o", "copy.toml"]);
        let out = run(c);
        let problems = failed_run_problems(&out, &[expect]);
        assert!(problems.is_empty(), "{scene}\n{}\n--- stderr:\n{}", problems.join("; "), stderr(&out));
        assert!(!dir.path().join("copy.toml").exists(), "{scene}: a copy was written");
    }
    std::fs::write(dir.path().join("scene.toml"), sphere).unwrap();
    let mut c = prism();
    c.current_dir(dir.path()).args(["save", "scene.toml", "-o", "copy.toml"]);
    let out = run(c);
    assert!(out.status.success() && dir.path().join("copy.toml").is_file(), "{}", stderr(&out));
}

/// Messages show extreme numbers short: an `assumed_gamma` or a superellipsoid `e` of 1e300
/// was echoed as 301 digits.
#[test]
fn messages_show_extreme_numbers_short() {
    let dir = tempfile::tempdir().unwrap();
    let sphere = "[[object]]\nshape = \"sphere\"\n";
    assert_refused(dir.path(), &format!("[render]\nassumed_gamma = 1e300\n{sphere}"), &["got 1e300"]);
    let superellipsoid = "[[object]]\nshape = \"superellipsoid\"\ne = 1e300\n";
    assert_refused(dir.path(), superellipsoid, &["scene.toml:3:", "got 1e300"]);
    let out = render_scene(dir.path(), superellipsoid);
    assert!(!stderr(&out).contains("0000000000"), "{}", stderr(&out));
}

/// A mesh translated beyond f32's range (1e39, 1e300) had infinite world-space vertices
/// when flattened into the scene's triangle tree, whose build then failed (an internal
/// error); it renders, as far-away analytic shapes do.
#[test]
fn a_mesh_moved_beyond_f32_renders() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = common::assets().join("BoxTextured/BoxTextured.gltf");
    for far in ["1e39", "-1e300"] {
        let scene = format!(
            "[camera]\nposition = [0, 0, 5]\n[[light]]\nposition = [3, 3, 5]\n\
             [[object]]\nshape = \"sphere\"\n\
             [[object]]\nshape = \"mesh\"\nfile = {:?}\ntransform = {{ translate = [0.3, 0.25, {far}] }}\n",
            mesh.display().to_string()
        );
        assert_renders(dir.path(), &scene);
    }
}
