//! The generated JSON Schema accepts every scene in the repository and rejects broken ones.

use std::path::{Path, PathBuf};

fn scene_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            scene_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "toml") {
            out.push(path);
        }
    }
}

fn validator() -> jsonschema::Validator {
    let schema = prism::scene::schema::scene_schema(&prism::plugins::registry());
    jsonschema::validator_for(&schema).expect("the generated schema is a valid JSON Schema")
}

fn as_json(text: &str) -> serde_json::Value {
    let table: toml::Table = toml::from_str(text).unwrap();
    serde_json::to_value(table).unwrap()
}

#[test]
fn every_scene_in_the_repository_validates() {
    let mut files = Vec::new();
    scene_files(&Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes"), &mut files);
    assert!(files.len() >= 3, "found only {files:?}");
    let validator = validator();
    for file in files {
        let value = as_json(&std::fs::read_to_string(&file).unwrap());
        let errors: Vec<String> =
            validator.iter_errors(&value).map(|e| format!("{} at {}", e, e.instance_path)).collect();
        assert!(errors.is_empty(), "{} does not match the schema:\n{}", file.display(), errors.join("\n"));
    }
}

#[test]
fn broken_scenes_are_rejected() {
    let validator = validator();
    for text in [
        "[rendr]\nwidth = 1\n",
        "[render]\nwidht = 1\n",
        "[[object]]\nshape = \"sphear\"\n",
        "[[object]]\nshape = \"sphere\"\nradus = 1\n",
        "[[object]]\nshape = \"sphere\"\nradius = \"big\"\n",
        "[materials.m]\ncolr = 1\n",
        "[[light]]\nkind = \"laser\"\n",
        "[[light]]\nradius = 10\n",
        "[[light]]\nkind = \"parallel\"\nsize1 = 3\n",
        "[[object]]\nshape = \"sphere\"\nmaterial = { normal = { pattern = \"bumsp\" } }\n",
        "[[object]]\nshape = \"sphere\"\nmaterial = { normal = { pattern = \"bumps\", bumpsize = 1 } }\n",
        "[[object]]\nshape = \"sphere\"\nmaterial = { normal = { pattern = \"bozo\", normal_map = [[0, { pattern = \"bumsp\" }]] } }\n",
        "[[object]]\nshape = \"sphere\"\nmaterial = { normal = { pattern = \"bozo\", slope_map = [[0, [0, 1, 2]]] } }\n",
        "[materials.m]\nlayers = { color = 1 }\n",
        "[materials.m]\n[[materials.m.layers]]\ncolr = 1\n",
    ] {
        assert!(!validator.is_valid(&as_json(text)), "schema accepted:\n{text}");
    }
}

#[test]
fn every_shape_is_described() {
    let schema = prism::scene::schema::scene_schema(&prism::plugins::registry());
    let variants = schema["properties"]["object"]["items"]["oneOf"].as_array().unwrap();
    let names: Vec<&str> = variants.iter().map(|v| v["title"].as_str().unwrap()).collect();
    for shape in prism::plugins::registry().names().chain(["mesh"]) {
        assert!(names.contains(&shape), "{shape} missing from the schema");
    }
}
