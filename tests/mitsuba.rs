//! The `path` integrator against committed Mitsuba 3 references, without Mitsuba installed
//! (CI also renders fresh references and runs the full test: `scripts/mitsuba-check.sh`).
//!
//! For every equivalence scene `scenes/mitsuba/NAME.toml`:
//! - the committed `NAME.xml` (and its PLY meshes) is what `prism export mitsuba` writes now;
//! - `refs/NAME.exr` is Mitsuba's mean over 16 seeds and `refs/NAME_stderr.exr` its standard
//!   error per pixel channel (`scripts/mitsuba-references.py`); a missing reference fails;
//! - Prism renders the scene with [`SEEDS`] seeds at [`SAMPLES`] samples per pixel each, and
//!   every pixel channel's mean is compared with the reference by a z-score over both
//!   standard errors (Prism's measured over its seeds): at least [`MIN_PASS`] of the channels
//!   must lie within [`Z_LIMIT`], and the image means must agree within [`MAX_BIAS`]. This
//!   is the quick check; the live one (`scripts/mitsuba-check.sh`, 16 fresh seeds on each
//!   side, Welch and Sidak) is the strict one.
//!
//! A failure writes the Prism image and a difference image next to the target folder and
//! prints how to regenerate the references.

use std::path::{Path, PathBuf};

use prism::film::Film;
use prism::render::{RenderOptions, render_frame};

/// Prism's seeds.
const SEEDS: u64 = 8;
/// Prism's samples per pixel per seed.
const SAMPLES: u32 = 32;
/// A pixel channel passes within this many standard errors: Student's t at two-sided
/// p = 0.001 for the 7 degrees of freedom of Prism's 8-seed error estimate (heavier-tailed
/// pixels, caustics seen through glass, fail more often than that).
const Z_LIMIT: f64 = 5.41;
/// Fraction of pixel channels that must pass.
const MIN_PASS: f64 = 0.98;
/// Largest relative difference of the image means.
const MAX_BIAS: f64 = 0.01;

/// Writes `scene` as `s.toml` in `dir` and runs `prism export mitsuba s.toml -o s.xml` there.
/// With `error` set, asserts the export failed naming `s.toml` and that key (`what` names the
/// case) and wrote nothing, and returns `None`; otherwise asserts it succeeded and returns
/// the XML.
fn export_case(dir: &Path, scene: &str, what: &str, error: Option<&str>) -> Option<String> {
    std::fs::write(dir.join("s.toml"), scene).unwrap();
    let xml = dir.join("s.xml");
    let _ = std::fs::remove_file(&xml);
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_prism"))
        .current_dir(dir)
        .args(["export", "mitsuba", "s.toml", "-o", "s.xml"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    match error {
        None => {
            assert!(out.status.success(), "{what}: {stderr}");
            Some(std::fs::read_to_string(&xml).unwrap())
        }
        Some(key) => {
            assert!(!out.status.success(), "{what}: exported");
            assert!(stderr.contains("s.toml:") && stderr.contains(key), "{what}: {stderr}");
            assert!(!xml.exists(), "{what}: wrote {}", xml.display());
            None
        }
    }
}

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn scenes() -> Vec<PathBuf> {
    let mut scenes: Vec<PathBuf> = std::fs::read_dir(root().join("scenes/mitsuba"))
        .expect("scenes/mitsuba exists")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    scenes.sort();
    scenes
}

fn load(scene: &Path) -> prism::world::Scene {
    prism::scene::load::load_file(scene, &prism::plugins::registry())
        .unwrap_or_else(|e| panic!("{}: {e}", scene.display()))
}

#[test]
fn there_are_at_least_twelve_equivalence_scenes() {
    let count = scenes().len();
    assert!(count >= 12, "only {count} equivalence scenes in scenes/mitsuba");
}

#[test]
fn the_committed_mitsuba_scenes_are_what_the_exporter_writes() {
    for scene in scenes() {
        let mut loaded = load(&scene);
        prism::world::transforms::resolve_transforms(&mut loaded).unwrap();
        prism::world::validate::validate(&loaded).unwrap();
        let name = scene.file_stem().unwrap().to_string_lossy().into_owned();
        let folder = scene.parent().unwrap();
        let source = scene.file_name().unwrap().to_string_lossy().into_owned();
        let exported = prism::export::mitsuba::export(&loaded, &source, &format!("{name}_meshes/"), folder)
            .unwrap_or_else(|e| panic!("{}: {e}", scene.display()));
        let regenerate = format!(
            "regenerate with: cargo run --release -- export mitsuba {0} -o {1}",
            scene.display(),
            folder.join(format!("{name}.xml")).display()
        );
        let committed = std::fs::read_to_string(folder.join(format!("{name}.xml")))
            .unwrap_or_else(|e| panic!("{name}.xml: {e}; {regenerate}"));
        assert!(committed == exported.xml, "scenes/mitsuba/{name}.xml is stale; {regenerate}");
        for (file, bytes) in &exported.meshes {
            let on_disk = std::fs::read(folder.join(file)).unwrap_or_else(|e| panic!("{file}: {e}; {regenerate}"));
            assert!(&on_disk == bytes, "scenes/mitsuba/{file} is stale; {regenerate}");
        }
    }
}

/// The per-pixel mean of `films`.
fn mean_film(films: &[Film]) -> Film {
    let mut mean = films[0].clone();
    for (i, p) in mean.pixels.iter_mut().enumerate() {
        for (c, value) in p.iter_mut().enumerate() {
            *value = (films.iter().map(|f| f64::from(f.pixels[i][c])).sum::<f64>() / films.len() as f64) as f32;
        }
    }
    mean
}

/// The per-pixel standard error of the mean of `films` (whose mean is `mean`).
fn stderr_film(films: &[Film], mean: &Film) -> Film {
    let n = films.len() as f64;
    let mut out = mean.clone();
    for (i, p) in out.pixels.iter_mut().enumerate() {
        for (c, value) in p.iter_mut().enumerate() {
            let m = f64::from(mean.pixels[i][c]);
            let variance = films.iter().map(|f| (f64::from(f.pixels[i][c]) - m).powi(2)).sum::<f64>() / (n - 1.0);
            *value = (variance / n).sqrt() as f32;
        }
    }
    out
}

fn read(path: &Path) -> Film {
    prism::output::read_exr(path).unwrap_or_else(|e| {
        panic!(
            "{}: {e}\nrender the references with: python3 scripts/mitsuba-references.py (needs pip install mitsuba==3.9.1)",
            path.display()
        )
    })
}

#[test]
fn the_path_integrator_matches_mitsuba_on_every_equivalence_scene() {
    let mut failures = Vec::new();
    for scene in scenes() {
        let name = scene.file_stem().unwrap().to_string_lossy().into_owned();
        let refs = root().join("scenes/mitsuba/refs");
        let reference = read(&refs.join(format!("{name}.exr")));
        let stderr = read(&refs.join(format!("{name}_stderr.exr")));
        let mut loaded = load(&scene);
        loaded.render.samples = SAMPLES;
        let films: Vec<Film> = (0..SEEDS)
            .map(|seed| {
                loaded.render.seed = 4242 + seed;
                let mut copy = load(&scene);
                copy.render = loaded.render.clone();
                let prepared = prism::prepare(&mut copy).unwrap();
                render_frame(&prepared, &RenderOptions { threads: Some(2), ..Default::default() }).unwrap().0
            })
            .collect();
        let film = mean_film(&films);
        let film_stderr = stderr_film(&films, &film);
        assert_eq!((film.width, film.height), (reference.width, reference.height), "{name}: size");

        let (mut passed, mut total) = (0usize, 0usize);
        let (mut sum_p, mut sum_m) = (0.0, 0.0);
        let mut worst = (0.0f64, 0u32, 0u32);
        for y in 0..film.height {
            for x in 0..film.width {
                let (p, m, s, q) = (film.get(x, y), reference.get(x, y), stderr.get(x, y), film_stderr.get(x, y));
                for c in 0..3 {
                    let (p, m, s, q) = (f64::from(p[c]), f64::from(m[c]), f64::from(s[c]), f64::from(q[c]));
                    sum_p += p;
                    sum_m += m;
                    let sigma = (s * s + q * q).sqrt();
                    let difference = (p - m).abs();
                    // Channels both renderers see as one constant agree to float rounding.
                    let z = if difference <= 2e-5 * p.abs().max(m.abs()) { 0.0 } else { difference / sigma.max(1e-30) };
                    total += 1;
                    passed += usize::from(z <= Z_LIMIT);
                    if z > worst.0 {
                        worst = (z, x, y);
                    }
                }
            }
        }
        let fraction = passed as f64 / total as f64;
        let bias = (sum_p - sum_m) / sum_m.max(1e-30);
        if fraction < MIN_PASS || bias.abs() > MAX_BIAS {
            let out = root().join("target/mitsuba-failures");
            let _ = std::fs::create_dir_all(&out);
            let _ = prism::output::write_image(&film, &out.join(format!("{name}_prism.exr")), &Default::default());
            let mut difference = film.clone();
            for (d, r) in difference.pixels.iter_mut().zip(&reference.pixels) {
                for c in 0..3 {
                    d[c] = (d[c] - r[c]).abs();
                }
            }
            let _ = prism::output::write_image(
                &difference,
                &out.join(format!("{name}_difference.exr")),
                &Default::default(),
            );
            failures.push(format!(
                "{name}: {:.3} % of pixel channels within {Z_LIMIT} sigma (need {:.1} %) \
                 (worst z {:.1} at {}, {}), image mean {:+.3} % (limit {:.1} %); images in {}",
                100.0 * fraction,
                100.0 * MIN_PASS,
                worst.0,
                worst.1,
                worst.2,
                100.0 * bias,
                100.0 * MAX_BIAS,
                out.display()
            ));
        }
    }
    assert!(
        failures.is_empty(),
        "{}\nif the scenes changed on purpose, regenerate the references: python3 scripts/mitsuba-references.py",
        failures.join("\n")
    );
}

/// A textured material is exported only as a diffuse `bsdf` whose colour is the image
/// itself; every other textured case is an error naming the key, and nothing is written.
#[test]
fn textured_materials_mitsuba_cannot_express_are_errors_naming_the_key() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::copy(root().join("assets/textures/tiles16.png"), dir.path().join("t.png")).unwrap();
    let cases = [
        ("color = 1.0, texture = \"t.png\", bsdf = { type = \"diffuse\" }", None),
        ("color = 0.5, texture = \"t.png\", bsdf = { type = \"diffuse\" }", Some("material.color")),
        ("color = 1.0, texture = \"t.png\", bsdf = { type = \"conductor\", metal = \"Au\" }", Some("material.texture")),
        (
            "color = 1.0, texture = { file = \"t.png\", scale = [2, 2] }, bsdf = { type = \"diffuse\" }",
            Some("material.texture"),
        ),
        (
            "color = 1.0, texture = { file = \"t.png\", wrap = [\"repeat\", \"clamp\"] }, bsdf = { type = \"diffuse\" }",
            Some("material.texture.wrap"),
        ),
    ];
    for (material, error) in cases {
        let scene = format!(
            "[render]\nintegrator = \"path\"\n[[object]]\nshape = \"rectangle\"\nmaterial = {{ {material} }}\n"
        );
        if let Some(text) = export_case(dir.path(), &scene, material, error) {
            assert!(text.contains("<texture type=\"bitmap\" name=\"reflectance\">"), "{text}");
            assert!(text.contains("value=\"t.png\""), "{text}");
        }
    }
}

/// A pigment pattern has no Mitsuba equivalent: the export is an error naming the key, and
/// nothing is written.
#[test]
fn pigment_patterns_are_refused_naming_the_key() {
    let dir = tempfile::tempdir().unwrap();
    let scene = "[render]\nintegrator = \"path\"\n[[object]]\nshape = \"sphere\"\nmaterial = { pigment = { pattern = \"checker\", colors = [[1, 1, 1], [0, 0, 0]] } }\n";
    export_case(dir.path(), scene, "checker", Some("material.pigment"));
}

/// A normal pattern has no Mitsuba equivalent either: refused the same way.
#[test]
fn normal_patterns_are_refused_naming_the_key() {
    let dir = tempfile::tempdir().unwrap();
    let scene = "[render]\nintegrator = \"path\"\n[[object]]\nshape = \"sphere\"\nmaterial = { normal = { pattern = \"bumps\", scale = 0.2 } }\n";
    export_case(dir.path(), scene, "bumps", Some("material.normal"));
}

/// A `normal_map`, a `slope_map`, an `average` or a `bump_map` is a pattern too: refused the
/// same way.
#[test]
fn normal_maps_are_refused_naming_the_key() {
    let dir = tempfile::tempdir().unwrap();
    let scene = "[render]\nintegrator = \"path\"\n[[object]]\nshape = \"sphere\"\nmaterial = { normal = { pattern = \"bozo\", normal_map = [[0, { pattern = \"bumps\" }], [1, { pattern = \"granite\", slope_map = [[0, [0, 1]]] }]] } }\n";
    export_case(dir.path(), scene, "normal_map", Some("material.normal"));
    let scene = "[render]\nintegrator = \"path\"\n[[object]]\nshape = \"sphere\"\nmaterial = { pigment = { pattern = \"average\", pigment_map = [[1, { color = [1, 0, 0] }]] } }\n";
    export_case(dir.path(), scene, "average", Some("material.pigment"));
    std::fs::write(dir.path().join("h.png"), include_bytes!("../scenes/parity/image_map_grey.png")).unwrap();
    let scene = "[render]\nintegrator = \"path\"\n[[object]]\nshape = \"sphere\"\nmaterial = { normal = { bump_map = { file = \"h.png\" } } }\n";
    export_case(dir.path(), scene, "bump_map", Some("material.normal"));
}

/// A layered texture has no Mitsuba equivalent: refused the same way.
#[test]
fn layered_textures_are_refused_naming_the_key() {
    let dir = tempfile::tempdir().unwrap();
    let scene = "[render]\nintegrator = \"path\"\n[[object]]\nshape = \"sphere\"\nmaterial = { layers = [{ color = [1, 0, 0] }, { transmit = 0.5 }] }\n";
    export_case(dir.path(), scene, "layers", Some("material.layers"));
}

/// POV-Ray's adaptive focal blur has no Mitsuba equivalent (Mitsuba takes the same samples
/// in every pixel): the export is an error naming the key, and nothing is written.
#[test]
fn adaptive_focal_blur_is_refused_naming_the_key() {
    let dir = tempfile::tempdir().unwrap();
    let scene = "[camera]\naperture = 0.2\nblur_variance = 0.0001\n[[object]]\nshape = \"sphere\"\n";
    export_case(dir.path(), scene, "blur_variance", Some("camera.blur_variance"));
}

/// POV-Ray's negative lights (which `classic` renders) have no Mitsuba emitter: the export
/// is an error at the key that makes the light negative, and nothing is written.
#[test]
fn negative_lights_are_refused_naming_the_key() {
    let dir = tempfile::tempdir().unwrap();
    let sphere = "[[object]]\nshape = \"sphere\"\n";
    let scene = format!("{sphere}[[light]]\nposition = [0, 5, 0]\n\n[[light]]\nposition = [0, 5, 0]\nintensity = -1\n");
    export_case(dir.path(), &scene, "negative intensity", Some("s.toml:8:1: error in `light[1].intensity`"));
    let scene = format!("{sphere}[[light]]\nposition = [0, 5, 0]\ncolor = [1, -0.5, 1]\n");
    export_case(dir.path(), &scene, "negative colour", Some("s.toml:5:1: error in `light[0].color`"));
}

/// A glTF metallic-roughness material (here a scene's `pbr` table, as glTF files give it) is
/// exported as the `gltf_metallic_roughness` plugin of scripts/mitsuba_gltf_bsdf.py with its
/// factors and bitmaps (the base colour decoded from sRGB, the metallic-roughness texture
/// raw); what the plugin does not hold is an error naming the key, and nothing is written.
#[test]
fn gltf_materials_become_the_plugin_and_what_it_cannot_hold_is_an_error_naming_the_key() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::copy(root().join("assets/textures/tiles16.png"), dir.path().join("t.png")).unwrap();
    let clearcoat = root().join("assets/gltf/khronos-samples/ClearCoatTest/ClearCoatTest.gltf");
    let clearcoat = clearcoat.display().to_string().replace('\\', "/");
    let cases = [
        (
            "material = { color = [0.5, 0.6, 0.7], texture = \"t.png\", pbr = { metallic = 0.25, roughness = 0.5, metallic_roughness_texture = \"t.png\" } }".to_string(),
            None,
        ),
        (
            "material = { pbr = { emissive = [1, 1, 1], emissive_texture = \"t.png\" } }".to_string(),
            Some("material.pbr.emissive_texture"),
        ),
        (
            "material = { pbr = { metallic_roughness_texture = { file = \"t.png\", rotation = 30 } } }".to_string(),
            Some("material.pbr.metallic_roughness_texture"),
        ),
        (
            "material = { texture = { file = \"t.png\", wrap = [\"repeat\", \"mirror\"] }, pbr = { metallic = 0 } }"
                .to_string(),
            Some("material.texture"),
        ),
        (
            "material = { pbr = { transmission = 0.5, transmission_texture = \"t.png\" } }".to_string(),
            Some("material.pbr.transmission_texture"),
        ),
        (
            "material = { pbr = { clearcoat = 1, clearcoat_roughness_texture = \"t.png\" } }".to_string(),
            Some("material.pbr.clearcoat_roughness_texture"),
        ),
        (
            "material = { pbr = { specular_color_texture = \"t.png\" } }".to_string(),
            Some("material.pbr.specular_color_texture"),
        ),
    ];
    let mesh_case = (format!("[[object]]\nshape = \"mesh\"\nfile = \"{clearcoat}\"\n"), Some("normal map"));
    let scenes = cases
        .into_iter()
        .map(|(material, error)| (format!("[[object]]\nshape = \"rectangle\"\n{material}\n"), error))
        .chain([mesh_case]);
    for (object, error) in scenes {
        let scene = format!("[render]\nintegrator = \"path\"\n{object}");
        if let Some(text) = export_case(dir.path(), &scene, &object, error) {
            for needle in [
                "<bsdf type=\"gltf_metallic_roughness\">",
                "<rgb name=\"base_color_factor\" value=\"0.5, 0.6, 0.7\"/>",
                "<float name=\"metallic\" value=\"0.25\"/>",
                "<float name=\"roughness\" value=\"0.5\"/>",
                "<texture type=\"bitmap\" name=\"base_color_texture\"><string name=\"filename\" value=\"t.png\"/><string name=\"filter_type\" value=\"bilinear\"/><string name=\"wrap_mode\" value=\"repeat\"/><boolean name=\"raw\" value=\"false\"/>",
                "<texture type=\"bitmap\" name=\"metallic_roughness_texture\"><string name=\"filename\" value=\"t.png\"/><string name=\"filter_type\" value=\"bilinear\"/><string name=\"wrap_mode\" value=\"repeat\"/><boolean name=\"raw\" value=\"true\"/>",
            ] {
                assert!(text.contains(needle), "missing {needle} in {text}");
            }
        }
    }
}
