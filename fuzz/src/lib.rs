//! The fuzz targets' bodies: each feeds bytes to one of Prism's loaders through an in-memory
//! [`FileAccess`] (never the disk), the way `prism render` would, and must not panic, hang or
//! blow up memory. Errors are the expected outcome for most inputs and are ignored.
//!
//! `tests/fuzz_regressions.rs` in the main crate includes this file (`#[path]`) and replays
//! every input in `fuzz/regressions/<target>/` through the same functions, so a crash found
//! once stays a test of the normal suite.

use std::path::{Path, PathBuf};

use prism::files::FileAccess;
use prism::import::{ImportOptions, import};
use prism::limits::MemoryBudget;
use prism::render::{RenderOptions, render_frame};
use prism::scene::load::{FileSystem, load_with};
use prism::texture::environment::EnvironmentMap;
use prism::texture::{ColorSpace, TextureStore};

/// What one decoded image or film may cost inside a fuzz run (libFuzzer's default RSS
/// limit is 2 GiB).
pub const FUZZ_BUDGET: MemoryBudget = MemoryBudget(256 << 20);

/// Where the scene target's input lies in the in-memory file system.
pub const SCENE_PATH: &str = "scenes/fuzz.toml";

/// The repository's small assets, at their repository paths: what the seed scenes (and the
/// mutations of them) name. Paths are relative to the repository root.
pub fn repository_files() -> Vec<(PathBuf, Vec<u8>)> {
    macro_rules! file {
        ($path:literal) => {
            (PathBuf::from($path), include_bytes!(concat!("../../", $path)).to_vec())
        };
    }
    vec![
        file!("scenes/base/room.toml"),
        file!("scenes/room.toml"),
        file!("scenes/snowman.toml"),
        file!("assets/cornell_box/cornell_box.obj"),
        file!("assets/cornell_box/cornell_box.mtl"),
        file!("assets/BoxTextured/BoxTextured.gltf"),
        file!("assets/BoxTextured/BoxTextured0.bin"),
        file!("assets/BoxTextured/CesiumLogoFlat.png"),
        file!("assets/env/studio_256x128.hdr"),
        file!("assets/env/sunset_256x128.exr"),
        file!("scenes/parity/image_map.png"),
        file!("scenes/parity/image_map_alpha.png"),
        file!("scenes/parity/image_map_grey.png"),
        file!("scenes/parity/image_map_rgb16.png"),
        file!("scenes/parity/image_map_palette.png"),
        file!("scenes/parity/image_map_grey4.png"),
        file!("scenes/parity/image_map_gamma.png"),
    ]
}

/// An access holding the repository's assets and `extra`.
fn access_with(extra: impl IntoIterator<Item = (PathBuf, Vec<u8>)>) -> FileAccess {
    FileAccess::in_memory(repository_files().into_iter().chain(extra))
}

/// Scene target: the bytes as `scenes/fuzz.toml` (its includes, meshes, textures and
/// environment maps come from [`repository_files`]), loaded, saved back to TOML, prepared
/// (transforms, validation, BVH) and rendered at most 16 x 16 pixels, 4 samples, depth 6.
pub fn scene(data: &[u8]) {
    let access = access_with([(PathBuf::from(SCENE_PATH), data.to_vec())]);
    let registry = prism::plugins::registry();
    let Ok(mut scene) = load_with(&FileSystem(access), Path::new(SCENE_PATH), &registry, FUZZ_BUDGET) else {
        return;
    };
    let _ = prism::scene::save::save(&scene);
    let settings = &mut scene.render;
    settings.width = settings.width.min(16);
    settings.height = settings.height.min(16);
    settings.samples = settings.samples.min(4);
    settings.max_depth = settings.max_depth.min(6);
    let Ok(render_scene) = prism::prepare(&mut scene) else { return };
    let options = RenderOptions { threads: Some(1), budget: FUZZ_BUDGET, ..RenderOptions::default() };
    if let Ok((film, _)) = render_frame(&render_scene, &options) {
        let image = prism::output::ImageSettings {
            exposure: scene.render.exposure,
            tone_map: scene.render.tone_map,
            exr_half: false,
        };
        let _ = prism::output::encode(&film, Path::new("fuzz.png"), &image);
    }
}

/// Separates the OBJ part of an `obj` input from its MTL part.
pub const MTL_SEPARATOR: &[u8] = b"\n#--- m.mtl ---\n";

/// OBJ target: the bytes up to [`MTL_SEPARATOR`] as `m.obj`, the rest (if any) as `m.mtl`
/// (which the OBJ names with `mtllib m.mtl`); `tex.png` is a real image for `map_Kd` and the
/// like. Imported with smoothing (the normal-less path) through [`import`].
pub fn obj(data: &[u8]) {
    let (obj, mtl) = match data.windows(MTL_SEPARATOR.len()).position(|w| w == MTL_SEPARATOR) {
        Some(at) => (&data[..at], &data[at + MTL_SEPARATOR.len()..]),
        None => (data, &[][..]),
    };
    let png = include_bytes!("../../assets/BoxTextured/CesiumLogoFlat.png").to_vec();
    let access = FileAccess::in_memory([
        (PathBuf::from("m.obj"), obj.to_vec()),
        (PathBuf::from("m.mtl"), mtl.to_vec()),
        (PathBuf::from("tex.png"), png),
    ]);
    let mut textures = TextureStore::with_limits(access, FUZZ_BUDGET);
    let _ = import(Path::new("m.obj"), &ImportOptions { smooth_angle: Some(60.0) }, &mut textures);
}

/// glTF target: the bytes as `m.glb` when they start with the GLB magic, else as `m.gltf`;
/// external buffers and images named `BoxTextured0.bin` and `CesiumLogoFlat.png` resolve to
/// the repository's BoxTextured files.
pub fn gltf(data: &[u8]) {
    let name = if data.starts_with(b"glTF") { "m.glb" } else { "m.gltf" };
    let access = FileAccess::in_memory([
        (PathBuf::from(name), data.to_vec()),
        (PathBuf::from("BoxTextured0.bin"), include_bytes!("../../assets/BoxTextured/BoxTextured0.bin").to_vec()),
        (PathBuf::from("CesiumLogoFlat.png"), include_bytes!("../../assets/BoxTextured/CesiumLogoFlat.png").to_vec()),
    ]);
    let mut textures = TextureStore::with_limits(access, FUZZ_BUDGET);
    let _ = import(Path::new(name), &ImportOptions::default(), &mut textures);
}

/// PLY target: the bytes as `m.ply` (gzip-compressed when they start with gzip's magic
/// bytes, as the importer decides), imported with smoothing through [`import`].
pub fn ply(data: &[u8]) {
    let access = FileAccess::in_memory([(PathBuf::from("m.ply"), data.to_vec())]);
    let mut textures = TextureStore::with_limits(access, FUZZ_BUDGET);
    let _ = import(Path::new("m.ply"), &ImportOptions { smooth_angle: Some(60.0) }, &mut textures);
}

/// The file extensions the image target chooses from (its first byte, modulo the count).
pub const IMAGE_EXTENSIONS: [&str; 9] = ["png", "jpg", "hdr", "exr", "bmp", "tga", "tif", "pnm", "qoi"];

/// Image target: the first byte picks an extension from [`IMAGE_EXTENSIONS`], the rest is
/// the file. Decoded as a texture (both colour spaces), for `.png` as an image map, and for
/// `.hdr` and `.exr` as an environment map: the paths `prism` uses for material textures,
/// `pigment.image_map` and `[world] environment`.
pub fn image(data: &[u8]) {
    let Some((&selector, bytes)) = data.split_first() else { return };
    let extension = IMAGE_EXTENSIONS[usize::from(selector) % IMAGE_EXTENSIONS.len()];
    let path = PathBuf::from(format!("t.{extension}"));
    let access = FileAccess::in_memory([(path.clone(), bytes.to_vec())]);
    let mut textures = TextureStore::with_limits(access.clone(), FUZZ_BUDGET);
    if textures.load_file(&path, ColorSpace::Srgb).is_ok() {
        let _ = textures.load_file(&path, ColorSpace::Linear);
    }
    if extension == "png" {
        let linear = prism::gamma::GammaCurve::Neutral;
        if prism::material::image_map::decode_png(&path, bytes, FUZZ_BUDGET, false, linear).is_ok() {
            let working = prism::gamma::GammaCurve::power_law(2.2);
            let _ = prism::material::image_map::decode_png(&path, bytes, FUZZ_BUDGET, false, working);
        }
    }
    if matches!(extension, "hdr" | "exr") {
        let _ = EnvironmentMap::load_with(&path, &access, FUZZ_BUDGET);
    }
}
