//! Hostile input through the CLI (issue 18): files that are not regular files or are too
//! large, include graphs that explode or nest deeply, scenes large enough to expose
//! superlinear loading, glTF and MTL files that used to panic the parser crates, outputs that
//! are devices or unwritable streams, command-line overrides, resource limits and the
//! `--root` sandbox. Every case must end quickly with a clear message and a non-zero exit
//! (or a correct render), never a panic, a hang or a half-written output.

mod common;

use common::{failed_run_problems, run, stderr};
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

fn prism() -> Command {
    Command::new(env!("CARGO_BIN_EXE_prism"))
}

/// A render of `scene` in `dir` at 8 x 6 to `out.png`.
fn render(dir: &Path, scene: &str) -> Command {
    let mut c = prism();
    c.current_dir(dir).args(["render", scene, "-o", "out.png", "--width", "8", "--height", "6"]);
    c
}

fn assert_fails(out: &Output, expect: &[&str]) {
    let problems = failed_run_problems(out, expect);
    assert!(problems.is_empty(), "{}\n--- stderr:\n{}", problems.join("; "), stderr(out));
    assert!(!stderr(out).contains("internal error"), "{}", stderr(out));
}

const SPHERE: &str = "[[object]]\nshape = \"sphere\"\n";

#[cfg(unix)]
fn mkfifo(path: &Path) {
    let status = Command::new("mkfifo").arg(path).status().unwrap();
    assert!(status.success());
}

/// A FIFO (with no writer) or a device as the scene, an include, a mesh, a glTF buffer, a
/// texture, an environment map or a font: refused at once instead of blocking or reading forever.
#[cfg(unix)]
#[test]
fn non_regular_files_are_refused_without_blocking() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    mkfifo(&d.join("fifo.toml"));
    mkfifo(&d.join("fifo.obj"));
    mkfifo(&d.join("fifo.bin"));
    mkfifo(&d.join("fifo.png"));
    mkfifo(&d.join("fifo.hdr"));
    mkfifo(&d.join("fifo.ttf"));
    let gltf = r#"{"asset":{"version":"2.0"},"scenes":[{"nodes":[]}],"buffers":[{"byteLength":4,"uri":"fifo.bin"}]}"#;
    std::fs::write(d.join("buf.gltf"), gltf).unwrap();
    std::os::unix::fs::symlink("/dev/zero", d.join("zero.obj")).unwrap();
    let cases = [
        ("scene FIFO", "fifo.toml".to_string(), "a FIFO"),
        ("scene device", "/dev/zero".to_string(), "a device"),
        ("stdin", "/dev/stdin".to_string(), "not a regular file"),
        ("include", "include = \"fifo.toml\"\n".to_string(), "a FIFO"),
        ("mesh", "[[object]]\nshape = \"mesh\"\nfile = \"fifo.obj\"\n".to_string(), "a FIFO"),
        ("buffer", "[[object]]\nshape = \"mesh\"\nfile = \"buf.gltf\"\n".to_string(), "a FIFO"),
        ("device mesh", "[[object]]\nshape = \"mesh\"\nfile = \"zero.obj\"\n".to_string(), "a device"),
        ("texture", format!("{SPHERE}material = {{ texture = \"fifo.png\" }}\n"), "a FIFO"),
        (
            "image_map",
            format!("{SPHERE}material = {{ pigment = {{ image_map = {{ file = \"fifo.png\" }} }} }}\n"),
            "a FIFO",
        ),
        ("environment", "[world]\nenvironment = { file = \"fifo.hdr\" }\n".to_string(), "a FIFO"),
        ("font", "[[object]]\nshape = \"text\"\nfont = \"fifo.ttf\"\nstring = \"a\"\n".to_string(), "a FIFO"),
    ];
    for (name, scene, expect) in cases {
        let file = if scene.contains('\n') {
            std::fs::write(d.join("scene.toml"), &scene).unwrap();
            "scene.toml".to_string()
        } else {
            scene
        };
        let out = common::run_within(render(d, &file), Duration::from_secs(20));
        let problems = failed_run_problems(&out, &[expect]);
        assert!(problems.is_empty(), "{name}: {}\n{}", problems.join("; "), stderr(&out));
    }
    assert!(!d.join("out.png").exists());
}

/// A sparse file over the scene cap is refused from its size, before it is read.
#[test]
fn files_over_their_cap_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let big = std::fs::File::create(dir.path().join("big.toml")).unwrap();
    big.set_len(prism::files::MAX_SCENE_BYTES + 1).unwrap();
    let out = common::run_within(render(dir.path(), "big.toml"), Duration::from_secs(20));
    assert_fails(&out, &["big.toml", "larger than the limit"]);
}

/// 40 files each including the next twice load 2^40 times without de-duplication; each is
/// now loaded once.
#[test]
fn diamond_includes_load_each_file_once() {
    let dir = tempfile::tempdir().unwrap();
    for i in 0..40 {
        let text = format!("include = [\"f{n}.toml\", \"./f{n}.toml\"]\n", n = i + 1);
        std::fs::write(dir.path().join(format!("f{i}.toml")), text).unwrap();
    }
    std::fs::write(dir.path().join("f40.toml"), SPHERE).unwrap();
    let out = common::run_within(render(dir.path(), "f0.toml"), Duration::from_secs(30));
    assert!(out.status.success(), "{}", stderr(&out));
}

/// A 5,000-deep include chain is loaded with an explicit stack, not recursion.
#[test]
fn deep_include_chains_do_not_overflow_the_stack() {
    let dir = tempfile::tempdir().unwrap();
    let depth = 5000;
    for i in 0..depth {
        std::fs::write(dir.path().join(format!("f{i}.toml")), format!("include = \"f{}.toml\"\n", i + 1)).unwrap();
    }
    std::fs::write(dir.path().join(format!("f{depth}.toml")), SPHERE).unwrap();
    let out = common::run_within(render(dir.path(), "f0.toml"), Duration::from_secs(60));
    assert!(out.status.success(), "{}", stderr(&out));
}

/// Loading, transform resolution, `save` and `export pov` are linear: 100,000 objects and
/// a 10,000-deep parent chain (quadratic before: about 2,000 s and 50 s).
#[test]
fn large_scenes_and_deep_parent_chains_load_in_linear_time() {
    let dir = tempfile::tempdir().unwrap();
    let mut many = String::from("[[light]]\nkind = \"point\"\nposition = [0, 5, -5]\n");
    for i in 0..100_000 {
        many.push_str(&format!(
            "[[object]]\nshape = \"sphere\"\nradius = 0.01\ntransform = {{ translate = [{}, {}, 5] }}\n",
            f64::from(i % 300) * 0.02,
            f64::from(i / 300) * 0.02
        ));
    }
    std::fs::write(dir.path().join("many.toml"), many).unwrap();
    let mut chain = String::new();
    for i in 0..10_000 {
        let parent = if i > 0 { format!("parent = \"o{}\"\n", i - 1) } else { String::new() };
        chain.push_str(&format!(
            "[[object]]\nshape = \"sphere\"\nname = \"o{i}\"\nradius = 0.01\n{parent}transform = {{ translate = [0.0001, 0, 0] }}\n"
        ));
    }
    std::fs::write(dir.path().join("chain.toml"), chain).unwrap();
    for scene in ["many.toml", "chain.toml"] {
        let out = run(render(dir.path(), scene));
        assert!(out.status.success(), "{scene}: {}", stderr(&out));
        for args in [vec!["save", scene, "-o", "saved.toml"], vec!["export", "pov", scene, "-o", "out.pov"]] {
            let mut c = prism();
            c.current_dir(dir.path()).args(&args);
            let out = run(c);
            assert!(out.status.success(), "{args:?}: {}", stderr(&out));
        }
    }
}

/// Writing to a full standard output is an error with a non-zero exit, not a panic.
#[cfg(target_os = "linux")]
#[test]
fn a_full_standard_output_is_an_error() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("scene.toml"), SPHERE).unwrap();
    for args in [vec!["save", "scene.toml"], vec!["export", "pov", "scene.toml"], vec!["schema"], vec!["shapes"]] {
        let full = std::fs::OpenOptions::new().write(true).open("/dev/full").unwrap();
        let out = prism().current_dir(dir.path()).args(&args).stdout(full).stderr(Stdio::piped()).output().unwrap();
        assert_eq!(out.status.code(), Some(1), "{args:?}: {}", stderr(&out));
        assert!(stderr(&out).contains("cannot write to standard output"), "{args:?}: {}", stderr(&out));
        assert!(!stderr(&out).contains("panicked"), "{args:?}: {}", stderr(&out));
    }
}

/// Outputs that are not regular files are refused by name before the render; a symlink
/// at the output is replaced, never written through.
#[cfg(unix)]
#[test]
fn outputs_are_regular_files_only() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("scene.toml"), SPHERE).unwrap();
    std::fs::create_dir(d.join("dir.png")).unwrap();
    mkfifo(&d.join("fifo.png"));
    for (target, what) in [("dir.png", "a directory"), ("fifo.png", "a FIFO")] {
        let mut c = prism();
        c.current_dir(d).args(["render", "scene.toml", "-o", target, "--width", "4", "--height", "4"]);
        let out = common::run_within(c, Duration::from_secs(20));
        assert_fails(&out, &[target, what]);
    }
    std::fs::write(d.join("victim.txt"), "keep me").unwrap();
    std::os::unix::fs::symlink(d.join("victim.txt"), d.join("link.png")).unwrap();
    let mut c = prism();
    c.current_dir(d).args(["render", "scene.toml", "-o", "link.png", "--width", "4", "--height", "4"]);
    let out = run(c);
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(std::fs::read_to_string(d.join("victim.txt")).unwrap(), "keep me");
    assert!(std::fs::symlink_metadata(d.join("link.png")).unwrap().is_file());
    let leftovers: Vec<PathBuf> = std::fs::read_dir(d)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.to_string_lossy().ends_with(".tmp"))
        .collect();
    assert!(leftovers.is_empty(), "{leftovers:?}");
}

/// Errors in command-line overrides name the flag, not the scene file.
#[test]
fn override_errors_name_the_flag() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("scene.toml"), SPHERE).unwrap();
    for (args, expect) in [
        (vec!["--width", "0"], vec!["--width", "at least 1"]),
        (vec!["--height", "-3"], vec!["--height"]),
        (vec!["--seed", "-1"], vec!["--seed"]),
        (vec!["--samples", "0"], vec!["--samples", "at least 1"]),
        (vec!["--threads", "100000"], vec!["--threads", "at most 256"]),
        (vec!["--threads", "0"], vec!["--threads", "at least 1"]),
        (vec!["--exposure", "inf"], vec!["--exposure"]),
        (vec!["--width", "65536", "--height", "65536"], vec!["--width/--height", "pixels"]),
        (vec!["--max-memory", "lots"], vec!["--max-memory"]),
    ] {
        let mut c = prism();
        c.current_dir(dir.path()).args(["render", "scene.toml", "-o", "out.png"]).args(&args);
        let out = run(c);
        assert_fails(&out, &expect);
        assert!(!stderr(&out).contains("scene.toml:"), "{args:?}: {}", stderr(&out));
    }
    assert!(!dir.path().join("out.png").exists());
}

/// The film is estimated against `--max-memory` before it is allocated.
#[test]
fn the_film_is_checked_against_the_memory_budget() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("scene.toml"), SPHERE).unwrap();
    let mut c = prism();
    c.current_dir(dir.path()).args([
        "render",
        "scene.toml",
        "-o",
        "out.png",
        "--width",
        "16384",
        "--height",
        "16383",
        "--max-memory",
        "256M",
    ]);
    let out = run(c);
    assert_fails(&out, &["16384 x 16383 film", "MiB", "--max-memory"]);
}

/// Parsing scene TOML is checked against `--max-memory` before it starts: deeply nested
/// inline tables take up to 200 bytes of memory per byte of text while parsed (a 55 MB file
/// of nested normal maps peaked at 9.8 GB before this check), so the budget bounds them.
#[test]
fn scene_text_is_checked_against_the_memory_budget() {
    let dir = tempfile::tempdir().unwrap();
    // 2 MiB of scene text (a long comment): about 400 MiB while parsed, at the bound.
    let scene = format!("{SPHERE}# {}\n", "x".repeat(2 << 20));
    std::fs::write(dir.path().join("scene.toml"), scene).unwrap();
    let mut c = prism();
    c.current_dir(dir.path()).args(["render", "scene.toml", "-o", "out.png", "--max-memory", "256M"]);
    let out = run(c);
    assert_fails(&out, &["scene.toml", "scene TOML", "MiB", "--max-memory"]);
    assert!(!dir.path().join("out.png").exists());
    // Within the budget it renders.
    let mut c = prism();
    c.current_dir(dir.path()).args([
        "render",
        "scene.toml",
        "-o",
        "out.png",
        "--max-memory",
        "1G",
        "--width",
        "8",
        "--height",
        "8",
    ]);
    let out = run(c);
    assert!(out.status.success(), "{}", stderr(&out));
}

/// A scene whose text is echoed by a parser error (a long string of the wrong type in an
/// include, a long shape name) gives a short message.
#[test]
fn messages_do_not_repeat_file_contents() {
    let dir = tempfile::tempdir().unwrap();
    let secret = "secret".repeat(20_000);
    std::fs::write(dir.path().join("inc.toml"), format!("[render]\nwidth = \"{secret}\"\n")).unwrap();
    std::fs::write(dir.path().join("scene.toml"), format!("include = \"inc.toml\"\n{SPHERE}")).unwrap();
    let out = run(render(dir.path(), "scene.toml"));
    assert_fails(&out, &["inc.toml:2:", "render.width"]);
    assert!(out.stderr.len() < 1000, "{} bytes: {}", out.stderr.len(), stderr(&out));
    std::fs::write(dir.path().join("scene.toml"), format!("[[object]]\nshape = \"{secret}\"\n")).unwrap();
    let out = run(render(dir.path(), "scene.toml"));
    assert_fails(&out, &["unknown shape"]);
    assert!(out.stderr.len() < 2000, "{} bytes", out.stderr.len());
}

/// glTF files that panicked the gltf crate, or loaded against the specification, are errors
/// naming the file.
#[test]
fn malformed_gltf_is_an_error_not_a_panic() {
    let quad = "AAABAAIAAAACAAMAAAAAwAAAAAAAAADAAAAAwAAAAAAAAABAAAAAQAAAAAAAAABAAAAAQAAAAAAAAADA";
    let base = |accessors: &str, primitive: &str, extra: &str| {
        format!(
            r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],"nodes":[{{"mesh":0}}],
            "meshes":[{{"primitives":[{primitive}]}}],
            "buffers":[{{"byteLength":60,"uri":"data:application/octet-stream;base64,{quad}"}}],
            "bufferViews":[{{"buffer":0,"byteOffset":0,"byteLength":12}},{{"buffer":0,"byteOffset":12,"byteLength":48}}],
            "accessors":[{accessors}]{extra}}}"#
        )
    };
    let good_accessors = r#"{"bufferView":0,"componentType":5123,"count":6,"type":"SCALAR"},
        {"bufferView":1,"componentType":5126,"count":4,"type":"VEC3","min":[-2,0,-2],"max":[2,0,2]}"#;
    let cases = [
        (
            "missing POSITION accessor",
            base(good_accessors, r#"{"attributes":{"POSITION":7},"indices":0}"#, ""),
            "accessor 7",
        ),
        (
            "signed SHORT indices",
            base(&good_accessors.replace("5123", "5122"), r#"{"attributes":{"POSITION":1},"indices":0}"#, ""),
            "indices must be",
        ),
        (
            "integer POSITION",
            base(&good_accessors.replace("5126", "5125"), r#"{"attributes":{"POSITION":1},"indices":0}"#, ""),
            "POSITION must be a FLOAT VEC3",
        ),
        (
            "image without a source",
            base(
                good_accessors,
                r#"{"attributes":{"POSITION":1},"indices":0,"material":0}"#,
                r#","materials":[{"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}}],"textures":[{"source":0}],"images":[{}]"#,
            ),
            "image 0",
        ),
        (
            "sparse index out of range",
            base(
                r#"{"bufferView":0,"componentType":5123,"count":6,"type":"SCALAR"},
                {"bufferView":1,"componentType":5126,"count":4,"type":"VEC3","min":[-2,0,-2],"max":[2,0,2],
                 "sparse":{"count":1,"indices":{"bufferView":0,"byteOffset":8,"componentType":5125},"values":{"bufferView":1}}}"#,
                r#"{"attributes":{"POSITION":1},"indices":0}"#,
                "",
            ),
            "sparse index",
        ),
        (
            "sparse count that wraps",
            base(
                r#"{"bufferView":0,"componentType":5123,"count":6,"type":"SCALAR"},
                {"bufferView":1,"componentType":5126,"count":4,"type":"VEC3","min":[-2,0,-2],"max":[2,0,2],
                 "sparse":{"count":4611686018427387904,"indices":{"bufferView":0,"componentType":5123},"values":{"bufferView":1}}}"#,
                r#"{"attributes":{"POSITION":1},"indices":0}"#,
                "",
            ),
            "sparse",
        ),
    ];
    let dir = tempfile::tempdir().unwrap();
    for (name, gltf, expect) in cases {
        std::fs::write(dir.path().join("m.gltf"), gltf).unwrap();
        std::fs::write(dir.path().join("scene.toml"), "[[object]]\nshape = \"mesh\"\nfile = \"m.gltf\"\n").unwrap();
        let out = run(render(dir.path(), "scene.toml"));
        let problems = failed_run_problems(&out, &["m.gltf", expect]);
        assert!(problems.is_empty(), "{name}: {}\n{}", problems.join("; "), stderr(&out));
    }
}

/// A node graph whose 40 levels each name the next node twice expands to 2^40 instances:
/// refused at the documented cap instead of exhausting memory.
#[test]
fn exponential_gltf_node_graphs_hit_the_instance_cap() {
    let mut nodes = Vec::new();
    for i in 0..40 {
        nodes.push(format!(r#"{{"children":[{n},{n}]}}"#, n = i + 1));
    }
    nodes.push("{}".into());
    let gltf = format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],"nodes":[{}]}}"#,
        nodes.join(",")
    );
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("m.gltf"), gltf).unwrap();
    std::fs::write(dir.path().join("scene.toml"), "[[object]]\nshape = \"mesh\"\nfile = \"m.gltf\"\n").unwrap();
    let out = run(render(dir.path(), "scene.toml"));
    assert_fails(&out, &["m.gltf", &prism::limits::MAX_GLTF_INSTANCES.to_string()]);
}

/// An MTL colour line with too few numbers (`Kd 0.5`) panicked inside tobj; it is now
/// refused before tobj sees it, with a warning naming the library and line.
#[test]
fn short_mtl_colour_lines_do_not_panic() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("m.mtl"), "newmtl red\nKd 0.5\n").unwrap();
    std::fs::write(d.join("m.obj"), "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n").unwrap();
    std::fs::write(d.join("scene.toml"), "[[object]]\nshape = \"mesh\"\nfile = \"m.obj\"\n").unwrap();
    let out = run(render(d, "scene.toml"));
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(stderr(&out).contains("m.mtl`:2"), "{}", stderr(&out));
    assert!(!stderr(&out).contains("panicked") && !stderr(&out).contains("internal error"));
}

/// `--root DIR` confines every read: includes, meshes, mtllib, textures, glTF buffers and
/// environment maps that are absolute, escape with `..` or through a symlink, or use a
/// `file:` URI are errors naming the key or file.
#[cfg(unix)]
#[test]
fn the_root_sandbox_confines_every_read() {
    let outer = tempfile::tempdir().unwrap();
    let root = outer.path().join("root");
    std::fs::create_dir(&root).unwrap();
    let secret = outer.path().join("secret");
    std::fs::create_dir(&secret).unwrap();
    std::fs::write(secret.join("inc.toml"), SPHERE).unwrap();
    std::fs::write(secret.join("tri.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    std::fs::write(secret.join("m.mtl"), "newmtl red\nKd 1 0 0\n").unwrap();
    std::fs::write(secret.join("b.bin"), [0u8; 64]).unwrap();
    std::os::unix::fs::symlink(secret.join("tri.obj"), root.join("link.obj")).unwrap();
    std::fs::write(root.join("mtl.obj"), "mtllib ../secret/m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    let abs = secret.join("tri.obj").display().to_string();
    let gltf = |uri: &str| {
        format!(
            r#"{{"asset":{{"version":"2.0"}},"scenes":[{{"nodes":[]}}],"buffers":[{{"byteLength":64,"uri":"{uri}"}}]}}"#
        )
    };
    std::fs::write(root.join("up.gltf"), gltf("../secret/b.bin")).unwrap();
    std::fs::write(root.join("file.gltf"), gltf(&format!("file://{}", secret.join("b.bin").display()))).unwrap();
    let mesh = |file: &str| format!("[[object]]\nshape = \"mesh\"\nfile = \"{file}\"\n");
    let cases = [
        ("include ..", "include = \"../secret/inc.toml\"\n".to_string(), vec!["`include`", "outside the --root"]),
        ("absolute mesh", mesh(&abs), vec!["object[0].file", "absolute"]),
        ("symlinked mesh", mesh("link.obj"), vec!["object[0].file", "outside the --root"]),
        ("mtllib ..", mesh("mtl.obj"), vec!["mtl.obj", "outside the --root"]),
        ("buffer ..", mesh("up.gltf"), vec!["up.gltf", "outside the --root"]),
        ("file: URI", mesh("file.gltf"), vec!["file.gltf", "unsupported URI"]),
        (
            "texture ..",
            format!("{SPHERE}material = {{ texture = \"../secret/t.png\" }}\n"),
            vec!["object[0]", "outside the --root"],
        ),
        (
            "image_map ..",
            format!("{SPHERE}material = {{ pigment = {{ image_map = {{ file = \"../secret/t.png\" }} }} }}\n"),
            vec!["object[0].material.pigment.image_map.file", "outside the --root"],
        ),
        (
            "environment absolute",
            "[world]\nenvironment = { file = \"/etc/passwd.hdr\" }\n".to_string(),
            vec!["world.environment.file", "absolute"],
        ),
    ];
    std::fs::write(secret.join("t.png"), [0u8; 8]).unwrap();
    for (name, scene, expect) in cases {
        std::fs::write(root.join("scene.toml"), &scene).unwrap();
        let mut c = render(&root, "scene.toml");
        c.arg("--root").arg(&root);
        let out = run(c);
        let problems = failed_run_problems(&out, &expect);
        assert!(problems.is_empty(), "{name}: {}\n{}", problems.join("; "), stderr(&out));
    }
    // The scene itself must be inside the root, and a scene inside renders.
    let mut c = render(&root, "../secret/inc.toml");
    c.arg("--root").arg(&root);
    assert_fails(&run(c), &["outside the --root"]);
    std::fs::write(root.join("scene.toml"), SPHERE).unwrap();
    let mut c = render(&root, "scene.toml");
    c.arg("--root").arg(&root);
    let out = run(c);
    assert!(out.status.success(), "{}", stderr(&out));
}

/// Extreme but finite values whose products overflow to Inf or NaN pixels (a colour of
/// -1e308, an ior of 1e17 that broke the renderer, a huge intensity) are load errors naming
/// the file, line and key.
#[test]
fn values_that_overflow_are_refused_at_load() {
    let dir = tempfile::tempdir().unwrap();
    let light = "[[light]]\nkind = \"point\"\nposition = [0, 5, -5]\n";
    let cases = [
        (
            format!("{SPHERE}material = {{ color = [-1e308, 0, 0] }}\n"),
            vec!["scene.toml:3:", "object[0].material.color"],
        ),
        (
            format!("{SPHERE}material = {{ transmit = 0.9, ior = 1e17 }}\n"),
            vec!["scene.toml:3:", "object[0].material.ior"],
        ),
        (format!("{SPHERE}{light}color = [-1e308, 1, 1]\n"), vec!["scene.toml:", "light[0].color"]),
        (format!("{SPHERE}{light}intensity = 1e300\n"), vec!["scene.toml:", "light[0].intensity"]),
        (
            format!("{SPHERE}material = {{ fade_distance = 1e-300, fade_power = 1e300 }}\n"),
            vec!["object[0].material.fade_power"],
        ),
    ];
    for (scene, expect) in cases {
        std::fs::write(dir.path().join("scene.toml"), &scene).unwrap();
        let mut c = render(dir.path(), "scene.toml");
        c.args(["--exr", "out.exr"]);
        let out = run(c);
        let problems = failed_run_problems(&out, &expect);
        assert!(problems.is_empty(), "{scene}: {}\n{}", problems.join("; "), stderr(&out));
        assert!(!dir.path().join("out.exr").exists());
    }
}

/// Every value of every channel of an EXR (beauty and all layers, float or half).
fn exr_values(path: &Path) -> Vec<(String, f32)> {
    use exr::prelude::{FlatSamples, read_all_flat_layers_from_file};
    let image = read_all_flat_layers_from_file(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut values = Vec::new();
    for layer in &image.layer_data {
        for channel in &layer.channel_data.list {
            let name = channel.name.to_string();
            let samples: Vec<f32> = match &channel.sample_data {
                FlatSamples::F16(v) => v.iter().map(|h| h.to_f32()).collect(),
                FlatSamples::F32(v) => v.clone(),
                FlatSamples::U32(v) => v.iter().map(|&u| u as f32).collect(),
            };
            values.extend(samples.into_iter().map(|v| (name.clone(), v)));
        }
    }
    values
}

/// Extreme but accepted values (colours at 1e30, intensities at 1e9, several lights, an
/// emitter at 1e30) give radiance beyond f32's range: no value of any channel of the EXR,
/// float or half, beauty or layer, is infinite or NaN, under both integrators, and a warning
/// names what happened to the pixels that overflowed.
#[test]
fn extreme_accepted_values_never_write_inf_or_nan() {
    let dir = tempfile::tempdir().unwrap();
    let mut scene = String::from(
        "[camera]\nposition = [0, 0, -6]\n[render]\nsamples = 4\n\
         [[object]]\nshape = \"sphere\"\nmaterial = { color = [1e30, 1e30, 1e30] }\n\
         [[object]]\nshape = \"sphere\"\ncenter = [2, 0, 0]\nradius = 0.5\n\
         material = { color = [1, 1, 1], emission = [1e30, 1e30, 1e30] }\n",
    );
    for i in 0..6 {
        scene.push_str(&format!(
            "[[light]]\nkind = \"point\"\nposition = [{}, 0.3, -1.5]\ncolor = [1e30, 1e30, 1e30]\nintensity = 1e9\n",
            f64::from(i - 3) * 0.3
        ));
    }
    std::fs::write(dir.path().join("scene.toml"), &scene).unwrap();
    let all = "albedo,normal,depth,position,uv,object_id,material_id,variance,samples";
    for integrator in ["classic", "path"] {
        for half in [false, true] {
            let exr = dir.path().join(format!("{integrator}-{half}.exr"));
            let mut c = prism();
            c.current_dir(dir.path()).args([
                "render",
                "scene.toml",
                "-o",
                "out.png",
                "--width",
                "48",
                "--height",
                "36",
            ]);
            c.args(["--integrator", integrator, "--aov", all, "--exr"]).arg(&exr);
            if half {
                c.arg("--half");
            }
            let out = run(c);
            assert!(out.status.success(), "{integrator} half={half}: {}", stderr(&out));
            let values = exr_values(&exr);
            assert!(values.len() > 48 * 36 * 3, "{integrator}: {} values", values.len());
            let bad: Vec<_> = values.iter().filter(|(_, v)| !v.is_finite()).take(5).collect();
            assert!(bad.is_empty(), "{integrator} half={half}: non-finite values {bad:?}");
            let err = stderr(&out);
            assert!(err.contains("warning"), "{integrator} half={half}: no warning for overflowing pixels:\n{err}");
        }
    }
}

/// SIGINT delivered to `prism render` while it writes its outputs (a temporary file is
/// already there): the temporaries are removed, and `-o` and `--exr` are both written or
/// neither. Tried until one signal lands mid-write (the window is a few milliseconds).
#[cfg(unix)]
#[test]
fn sigint_mid_write_leaves_no_temporary_and_all_outputs_or_none() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("scene.toml"), SPHERE).unwrap();
    let temps = |dir: &Path| -> Vec<String> {
        std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|n| n.ends_with(".tmp"))
            .collect()
    };
    let mut interrupted_mid_write = 0;
    for attempt in 0..40 {
        let (png, exr) = (dir.path().join("out.png"), dir.path().join("out.exr"));
        let _ = std::fs::remove_file(&png);
        let _ = std::fs::remove_file(&exr);
        let mut child = prism()
            .current_dir(dir.path())
            // Large enough that writing takes tens of milliseconds: on a loaded machine the
            // poll below missed a smaller image's write window 40 times running.
            .args(["render", "scene.toml", "-o", "out.png", "--exr", "out.exr", "--width", "3200", "--height"])
            .arg("2400")
            .stdin(Stdio::null())
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        let start = Instant::now();
        let mut signalled_mid_write = false;
        while child.try_wait().unwrap().is_none() {
            if !temps(dir.path()).is_empty() {
                // SAFETY: sending a signal to our own child process.
                assert_eq!(unsafe { libc::kill(child.id() as libc::pid_t, libc::SIGINT) }, 0);
                signalled_mid_write = true;
                break;
            }
            assert!(start.elapsed() < Duration::from_secs(60), "render did not finish");
            std::thread::yield_now();
        }
        let out = child.wait_with_output().unwrap();
        assert!(temps(dir.path()).is_empty(), "attempt {attempt}: temporaries left: {:?}", temps(dir.path()));
        assert_eq!(png.exists(), exr.exists(), "attempt {attempt}: one output without the other");
        assert!(!stderr(&out).contains("internal error"), "{}", stderr(&out));
        match out.status.code() {
            // The signal arrived before or during the writes (nothing is left), or after both
            // renames but before the process ended (both are there, complete).
            Some(130) => {
                if png.exists() {
                    assert!(
                        std::fs::metadata(&png).unwrap().len() > 0 && std::fs::metadata(&exr).unwrap().len() > 0,
                        "attempt {attempt}: exit 130 with empty outputs"
                    );
                } else {
                    interrupted_mid_write += usize::from(signalled_mid_write);
                }
            }
            // The renames were under way (the signal waits for them): both are complete.
            Some(0) => {
                assert!(std::fs::metadata(&png).unwrap().len() > 0 && std::fs::metadata(&exr).unwrap().len() > 0)
            }
            other => panic!("attempt {attempt}: exit {other:?}: {}", stderr(&out)),
        }
        if interrupted_mid_write >= 1 {
            return;
        }
    }
    panic!("no SIGINT landed while a temporary file existed in 40 attempts");
}

/// A mesh whose triangles and BVH would not fit `--max-memory` is refused before they are
/// built, naming the setting and the estimate; so are more imported instances than fit.
#[test]
fn meshes_and_instances_are_checked_against_the_memory_budget() {
    let dir = tempfile::tempdir().unwrap();
    // A 300 x 300 grid of quads: 180,000 triangles, about 86 MiB with their BVH.
    let n = 300;
    let mut obj = String::new();
    for y in 0..=n {
        for x in 0..=n {
            obj.push_str(&format!("v {x} {y} 0\n"));
        }
    }
    for y in 0..n {
        for x in 0..n {
            let i = y * (n + 1) + x + 1;
            obj.push_str(&format!("f {i} {} {} {}\n", i + 1, i + n + 2, i + n + 1));
        }
    }
    std::fs::write(dir.path().join("grid.obj"), obj).unwrap();
    std::fs::write(dir.path().join("grid.toml"), "[[object]]\nshape = \"mesh\"\nfile = \"grid.obj\"\n").unwrap();
    let mut c = render(dir.path(), "grid.toml");
    c.args(["--max-memory", "32M"]);
    assert_fails(&run(c), &["grid.obj", "180000 triangles with their BVH", "MiB", "--max-memory"]);
    let mut c = render(dir.path(), "grid.toml");
    c.args(["--max-memory", "256M"]);
    let out = run(c);
    assert!(out.status.success(), "{}", stderr(&out));

    // The same grid as PLY is checked the same way.
    let mut ply = format!(
        "ply\nformat ascii 1.0\nelement vertex {}\nproperty float x\nproperty float y\nproperty float z\n\
         element face {}\nproperty list uchar int vertex_indices\nend_header\n",
        (n + 1) * (n + 1),
        n * n
    );
    for y in 0..=n {
        for x in 0..=n {
            ply.push_str(&format!("{x} {y} 0\n"));
        }
    }
    for y in 0..n {
        for x in 0..n {
            let i = y * (n + 1) + x;
            ply.push_str(&format!("4 {i} {} {} {}\n", i + 1, i + n + 2, i + n + 1));
        }
    }
    std::fs::write(dir.path().join("grid.ply"), ply).unwrap();
    std::fs::write(dir.path().join("ply.toml"), "[[object]]\nshape = \"mesh\"\nfile = \"grid.ply\"\n").unwrap();
    let mut c = render(dir.path(), "ply.toml");
    c.args(["--max-memory", "32M"]);
    assert_fails(&run(c), &["grid.ply", "180000 triangles with their BVH", "MiB", "--max-memory"]);

    // Three files of that grid: each fits 200 MiB, all three together do not. The third is
    // refused, with what the first two took.
    let mut three = String::new();
    for name in ["a", "b", "c"] {
        std::fs::copy(dir.path().join("grid.obj"), dir.path().join(format!("grid_{name}.obj"))).unwrap();
        three.push_str(&format!("[[object]]\nshape = \"mesh\"\nfile = \"grid_{name}.obj\"\n"));
    }
    std::fs::write(dir.path().join("three.toml"), three).unwrap();
    let mut c = render(dir.path(), "three.toml");
    c.args(["--max-memory", "200M"]);
    let out = run(c);
    assert_fails(&out, &["grid_c.obj", "180000 triangles", "on top of", "loaded before it", "--max-memory"]);
    assert!(!stderr(&out).contains("grid_a.obj") && !stderr(&out).contains("grid_b.obj"), "{}", stderr(&out));
    let mut c = render(dir.path(), "three.toml");
    c.args(["--max-memory", "300M"]);
    let out = run(c);
    assert!(out.status.success(), "{}", stderr(&out));

    // 2,000 objects naming one small mesh: 6,000 imported entities, about 6 MiB.
    std::fs::write(dir.path().join("tri.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    let scene: String = (0..2000)
        .map(|i| {
            format!("[[object]]\nshape = \"mesh\"\nfile = \"tri.obj\"\ntransform = {{ translate = [{i}, 0, 0] }}\n")
        })
        .collect();
    std::fs::write(dir.path().join("many.toml"), scene).unwrap();
    let mut c = render(dir.path(), "many.toml");
    c.args(["--max-memory", "4M"]);
    let out = run(c);
    assert_fails(&out, &["many.toml:", "imported nodes and mesh instances", "MiB", "--max-memory"]);
    assert_eq!(stderr(&out).matches("imported nodes").count(), 1, "reported once: {}", stderr(&out));
    let mut c = render(dir.path(), "many.toml");
    c.args(["--max-memory", "64M"]);
    let out = run(c);
    assert!(out.status.success(), "{}", stderr(&out));
}

/// An OBJ face with a million vertices ends within 20 s (rendered, or refused naming the
/// polygon cap); a concave face larger than the cap is an error naming the file and the cap.
#[test]
fn huge_obj_faces_are_triangulated_quickly_or_refused() {
    let dir = tempfile::tempdir().unwrap();
    let face = |n: usize, spiky: bool| {
        let mut obj = String::with_capacity(n * 40);
        for i in 0..n {
            let a = i as f64 * std::f64::consts::TAU / n as f64;
            let r = if spiky && i % 2 == 1 { 0.5 } else { 1.0 };
            obj.push_str(&format!("v {} {} 0\n", r * a.cos(), r * a.sin()));
        }
        obj.push('f');
        for i in 1..=n {
            obj.push_str(&format!(" {i}"));
        }
        obj.push('\n');
        obj
    };
    std::fs::write(dir.path().join("round.obj"), face(1_000_000, false)).unwrap();
    std::fs::write(dir.path().join("spiky.obj"), face(100_000, true)).unwrap();
    let camera = "[camera]\nposition = [0, 0, -3]\nlook_at = [0, 0, 0]\n";
    for name in ["round", "spiky"] {
        let scene = format!("{camera}[[object]]\nshape = \"mesh\"\nfile = \"{name}.obj\"\nsmooth_angle = 30\n");
        std::fs::write(dir.path().join(format!("{name}.toml")), scene).unwrap();
    }
    // In f32 a million points on a circle are not strictly convex (rounding makes some
    // corners reflex): the face is refused at once, naming the cap, instead of clipped for hours.
    let out = common::run_within(render(dir.path(), "round.toml"), Duration::from_secs(20));
    if !out.status.success() {
        assert_fails(&out, &["round.obj", "1000000 vertices", "16384"]);
    }
    let out = common::run_within(render(dir.path(), "spiky.toml"), Duration::from_secs(20));
    assert_fails(&out, &["spiky.obj", "100000 vertices", "16384"]);
}
