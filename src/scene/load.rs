//! `load`: scene files (with includes and named materials) into a hecs `World` plus the
//! scene-wide settings. Every problem becomes a [`Diagnostic`] with file, line, column and
//! key path; loading goes on after a problem so one run reports as many as it can.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use serde::de::DeserializeOwned;

use super::Scene;
use super::components::{
    Camera, Environment, Light, LightKind, MaterialComponent, Name, ObjectFlags, Origin, Parent, RenderSettings,
    ShapeComponent, Transform,
};
use super::source::{ParsedFile, deserialize_at};
use super::transforms::world_from_local;
use crate::diagnostics::{Diagnostic, Location, SceneError};
use crate::material::Material;
use crate::mesh::cameras_lights::{self, CameraChoice, ImportedCamera};
use crate::mesh::spawn::{MESH_KEYS, MESH_SHAPE};
use crate::mesh::{CameraProjection, ImportOptions, Imported, MeshSource, MeshStore, Model};
use crate::registry::ShapeRegistry;

/// Top-level keys of a scene file.
pub const TOP_LEVEL_KEYS: [&str; 7] = ["include", "render", "camera", "world", "materials", "object", "light"];

/// Keys of an `[[object]]` table that are not shape parameters.
pub const OBJECT_KEYS: [&str; 6] = ["shape", "name", "material", "transform", "parent", "no_shadow"];

/// Where scene files come from: the file system, or text embedded in the binary.
pub trait SceneSource {
    /// The text of the file at `path`.
    fn read(&self, path: &Path) -> std::io::Result<String>;
    /// A canonical identity for include-cycle detection.
    fn canonical(&self, path: &Path) -> PathBuf;
}

/// Reads scene files from disk.
pub struct FileSystem;

impl SceneSource for FileSystem {
    fn read(&self, path: &Path) -> std::io::Result<String> {
        std::fs::read_to_string(path)
    }

    fn canonical(&self, path: &Path) -> PathBuf {
        std::fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf())
    }
}

/// Scene files embedded in the binary, by path.
pub struct Embedded(pub &'static [(&'static str, &'static str)]);

impl SceneSource for Embedded {
    fn read(&self, path: &Path) -> std::io::Result<String> {
        let wanted = normalize(path);
        self.0
            .iter()
            .find(|(p, _)| normalize(Path::new(p)) == wanted)
            .map(|(_, text)| text.to_string())
            .ok_or_else(|| std::io::Error::new(std::io::ErrorKind::NotFound, "no such built-in file"))
    }

    fn canonical(&self, path: &Path) -> PathBuf {
        normalize(path)
    }
}

/// Spawns the lights of every `import_lights` object, placed by their node's world transform
/// (parents are linked by now; a parent cycle is reported later by `resolve_transforms`).
fn spawn_imported_lights(world: &mut hecs::World, imports: Vec<LightImport>) {
    for import in imports {
        let Some(object) = world_from_local(world, import.root) else { continue };
        let scale = cameras_lights::uniform_scale(&object);
        for light in &import.model.lights {
            let Some(world_from_light) = world_from_local(world, import.nodes[light.node]) else { continue };
            if let Some(range) = light.range {
                eprintln!(
                    "warning: {}: {}: `range` {range} is ignored (imported lights fall off with the inverse square of the distance)",
                    import.file,
                    cameras_lights::describe_light(light)
                );
            }
            let prism_light = cameras_lights::light_from_node(light, world_from_light, scale);
            world.spawn((prism_light, Origin(import.location.clone()), Imported));
        }
    }
}

/// Spawns the scene's camera from an `import_camera` object: the file's camera at its node's
/// world transform, with the lens (`aperture`, `focal_distance`) of `[camera]`.
fn spawn_imported_camera(world: &mut hecs::World, import: CameraImport, lens: &Camera) -> hecs::Entity {
    let camera = match world_from_local(world, import.node) {
        Some(world_from_camera) => cameras_lights::camera_from_node(world_from_camera, import.yfov, lens),
        None => lens.clone(),
    };
    let marker = ImportedCamera { aspect_ratio: import.aspect_ratio, description: import.description };
    world.spawn((camera, Name("camera".into()), Origin(import.location), marker))
}

/// `a/b/../c` -> `a/c` without touching the file system.
fn normalize(path: &Path) -> PathBuf {
    let mut out = PathBuf::new();
    for c in path.components() {
        match c {
            std::path::Component::ParentDir => {
                if !out.pop() {
                    out.push("..");
                }
            }
            std::path::Component::CurDir => {}
            other => out.push(other),
        }
    }
    out
}

/// Loads the scene at `path` from disk.
pub fn load_file(path: &Path, registry: &ShapeRegistry) -> Result<Scene, SceneError> {
    load_from(&FileSystem, path, registry)
}

/// Loads the scene at `path` from `source`.
pub fn load_from(source: &dyn SceneSource, path: &Path, registry: &ShapeRegistry) -> Result<Scene, SceneError> {
    let mut loader = Loader {
        source,
        registry,
        stack: Vec::new(),
        files: Vec::new(),
        diagnostics: Vec::new(),
        render: Section::default(),
        camera: Section::default(),
        environment: Section::default(),
        materials: HashMap::new(),
        objects: Vec::new(),
        lights: Vec::new(),
        meshes: MeshStore::new(),
        light_imports: Vec::new(),
        camera_import: None,
    };
    loader.load_file(path, None);
    loader.finish()
}

/// A `[render]`-like table merged over all files: later files override single keys.
#[derive(Default)]
struct Section {
    table: toml::Table,
    /// For each top-level key: the file it came from.
    origin: HashMap<String, usize>,
    present: bool,
}

struct ObjectDef {
    file: usize,
    key: String,
    table: toml::Table,
}

/// A mesh object's `import_lights = true`: its file's lights, placed once parents are known.
struct LightImport {
    model: std::sync::Arc<Model>,
    /// The object's entity and its node entities (one per `model.nodes`).
    root: hecs::Entity,
    nodes: Vec<hecs::Entity>,
    /// The mesh file as the scene wrote it, for warnings.
    file: String,
    /// The `import_lights` key.
    location: Location,
}

/// A mesh object's `import_camera`: the chosen camera, placed once parents are known.
struct CameraImport {
    /// The entity of the node holding the camera.
    node: hecs::Entity,
    /// Vertical field of view in radians.
    yfov: f64,
    aspect_ratio: Option<f64>,
    /// `file.gltf: camera 0 ...`, for messages.
    description: String,
    /// The object's key (`object[2]`) and the file it names, for conflict messages.
    object_key: String,
    file: String,
    /// The `import_camera` key.
    location: Location,
}

/// `[camera]` keys that may accompany an imported camera (the lens).
const LENS_KEYS: [&str; 2] = ["aperture", "focal_distance"];

/// `[camera]` keys an imported camera takes from the file (a second source is an error).
const POSE_KEYS: [&str; 5] = ["position", "look_at", "up", "vfov", "aspect"];

struct Loader<'a> {
    source: &'a dyn SceneSource,
    registry: &'a ShapeRegistry,
    stack: Vec<PathBuf>,
    files: Vec<ParsedFile>,
    diagnostics: Vec<Diagnostic>,
    render: Section,
    camera: Section,
    environment: Section,
    materials: HashMap<String, (Material, usize)>,
    objects: Vec<ObjectDef>,
    lights: Vec<(Light, Location)>,
    /// Imported mesh files and decoded textures, shared by every object that uses them.
    meshes: MeshStore,
    /// Mesh objects whose file's lights are imported.
    light_imports: Vec<LightImport>,
    /// The mesh object whose file's camera is the scene's camera.
    camera_import: Option<CameraImport>,
}

impl Loader<'_> {
    fn load_file(&mut self, path: &Path, included_from: Option<Location>) {
        let display = path.display().to_string();
        let canonical = self.source.canonical(path);
        if let Some(pos) = self.stack.iter().position(|p| *p == canonical) {
            let chain: Vec<String> =
                self.stack[pos..].iter().chain(std::iter::once(&canonical)).map(|p| p.display().to_string()).collect();
            let location = included_from.unwrap_or_else(|| Location::file_only(display.as_str(), "include"));
            self.diagnostics.push(Diagnostic::new(location, format!("include cycle: {}", chain.join(" -> "))));
            return;
        }
        let text = match self.source.read(path) {
            Ok(text) => text,
            Err(e) => {
                let location = included_from.unwrap_or_else(|| Location::file_only(display.as_str(), ""));
                let what = if location.key.is_empty() { "cannot read scene file" } else { "cannot read included file" };
                self.diagnostics.push(Diagnostic::new(location, format!("{what} `{display}`: {e}")));
                return;
            }
        };
        let parsed = match ParsedFile::parse(&display, text) {
            Ok(p) => p,
            Err(d) => {
                self.diagnostics.push(d);
                return;
            }
        };
        self.stack.push(canonical);
        let index = self.files.len();
        let table = parsed.table.clone();
        self.files.push(parsed);

        for key in table.keys() {
            if !TOP_LEVEL_KEYS.contains(&key.as_str()) {
                let d = Diagnostic::new(self.files[index].locate(key), format!("unknown top-level key `{key}`"))
                    .suggest(key, TOP_LEVEL_KEYS);
                let d = if d.help.is_none() {
                    d.with_help(format!("valid top-level keys: {}", TOP_LEVEL_KEYS.join(", ")))
                } else {
                    d
                };
                self.diagnostics.push(d);
            }
        }
        if let Some(value) = table.get("include") {
            self.includes(index, path, value);
        }
        for (name, section) in [("render", 0), ("camera", 1), ("world", 2)] {
            if let Some(value) = table.get(name) {
                self.merge_section(index, name, section, value);
            }
        }
        if let Some(value) = table.get("materials") {
            self.materials(index, value);
        }
        if let Some(value) = table.get("object") {
            for (i, t) in self.array_of_tables(index, "object", value) {
                self.objects.push(ObjectDef { file: index, key: format!("object[{i}]"), table: t });
            }
        }
        if let Some(value) = table.get("light") {
            for (i, t) in self.array_of_tables(index, "light", value) {
                let key = format!("light[{i}]");
                if let Some(light) = self.light(index, &key, t) {
                    let location = self.files[index].locate(&key);
                    self.lights.push((light, location));
                }
            }
        }
        self.stack.pop();
    }

    fn includes(&mut self, index: usize, path: &Path, value: &toml::Value) {
        let entries: Vec<(String, String)> = match value {
            toml::Value::String(s) => vec![("include".into(), s.clone())],
            toml::Value::Array(items) => {
                let mut out = Vec::new();
                for (i, item) in items.iter().enumerate() {
                    let key = format!("include[{i}]");
                    match item {
                        toml::Value::String(s) => out.push((key, s.clone())),
                        _ => self.diagnostics.push(Diagnostic::new(
                            self.files[index].locate_value(&key),
                            "an include must be a path string",
                        )),
                    }
                }
                out
            }
            _ => {
                self.diagnostics.push(Diagnostic::new(
                    self.files[index].locate_value("include"),
                    "`include` must be a path or an array of paths",
                ));
                return;
            }
        };
        let dir = path.parent().unwrap_or(Path::new(""));
        for (key, relative) in entries {
            let location = self.files[index].locate_value(&key);
            self.load_file(&dir.join(relative), Some(location));
        }
    }

    fn merge_section(&mut self, index: usize, name: &str, which: usize, value: &toml::Value) {
        let toml::Value::Table(table) = value else {
            self.diagnostics
                .push(Diagnostic::new(self.files[index].locate_value(name), format!("`{name}` must be a table")));
            return;
        };
        let section = match which {
            0 => &mut self.render,
            1 => &mut self.camera,
            _ => &mut self.environment,
        };
        section.present = true;
        for (k, v) in table {
            section.table.insert(k.clone(), v.clone());
            section.origin.insert(k.clone(), index);
        }
    }

    fn materials(&mut self, index: usize, value: &toml::Value) {
        let toml::Value::Table(table) = value else {
            self.diagnostics.push(Diagnostic::new(
                self.files[index].locate_value("materials"),
                "`materials` must be a table of named materials",
            ));
            return;
        };
        for (name, def) in table {
            let key = format!("materials.{name}");
            if let Some(material) = self.material(index, &key, def.clone()) {
                self.materials.insert(name.clone(), (material, index));
            }
        }
    }

    fn material(&mut self, index: usize, key: &str, value: toml::Value) -> Option<Material> {
        let mut material: Material = self.deserialize(index, key, value)?;
        if let Err((field, message)) = material.check() {
            let k = format!("{key}.{field}");
            self.diagnostics.push(Diagnostic::new(self.files[index].locate(&k), message));
            return None;
        }
        self.material_textures(index, key, &mut material).then_some(material)
    }

    fn deserialize<T: DeserializeOwned>(&mut self, index: usize, key: &str, value: toml::Value) -> Option<T> {
        match deserialize_at(&self.files[index], key, value) {
            Ok(v) => Some(v),
            Err(d) => {
                self.diagnostics.push(d);
                None
            }
        }
    }

    fn array_of_tables(&mut self, index: usize, name: &str, value: &toml::Value) -> Vec<(usize, toml::Table)> {
        let toml::Value::Array(items) = value else {
            self.diagnostics.push(
                Diagnostic::new(self.files[index].locate_value(name), format!("`{name}` must be an array of tables"))
                    .with_help(format!("write each one as a [[{name}]] table")),
            );
            return Vec::new();
        };
        let mut out = Vec::new();
        for (i, item) in items.iter().enumerate() {
            match item {
                toml::Value::Table(t) => out.push((i, t.clone())),
                _ => self.diagnostics.push(Diagnostic::new(
                    self.files[index].locate_value(&format!("{name}[{i}]")),
                    format!("each `{name}` must be a table"),
                )),
            }
        }
        out
    }

    fn light(&mut self, index: usize, key: &str, table: toml::Table) -> Option<Light> {
        let kind = match table.get("kind") {
            None => LightKind::Point,
            Some(v) => self.deserialize::<LightKind>(index, &format!("{key}.kind"), v.clone())?,
        };
        let allowed = kind.allowed_keys();
        let mut ok = true;
        let mut reported = Vec::new();
        for k in table.keys() {
            if k != "kind" && !allowed.contains(&k.as_str()) {
                let known_elsewhere = LightKind::Area.allowed_keys().contains(&k.as_str())
                    || LightKind::Spot.allowed_keys().contains(&k.as_str());
                let message = if known_elsewhere {
                    format!("key `{k}` does not apply to a {kind:?} light", kind = kind).to_lowercase()
                } else {
                    format!("unknown key `{k}`")
                };
                // Suggest among every light's keys (a misspelt `tightness` on a point light is
                // still most likely `tightness`), else list this kind's.
                let every_key = [LightKind::Area, LightKind::Spot].into_iter().flat_map(|kind| kind.allowed_keys());
                let help = match crate::diagnostics::nearest_name(k, every_key.copied().chain(["kind"])) {
                    Some(name) => format!("did you mean `{name}`?"),
                    None => format!("valid keys here: kind, {}", allowed.join(", ")),
                };
                let d = Diagnostic::new(self.files[index].locate(&format!("{key}.{k}")), message).with_help(help);
                self.diagnostics.push(d);
                reported.push(k.clone());
                ok = false;
            }
        }
        // The rest is still checked, without the keys reported above (serde would name the
        // first of them a second time).
        let mut table = table;
        for k in &reported {
            table.remove(k);
        }
        let light: Light = self.deserialize(index, key, toml::Value::Table(table))?;
        ok.then_some(light)
    }

    fn section<T: DeserializeOwned + Default>(&mut self, which: usize, name: &str) -> Option<T> {
        let section = match which {
            0 => &self.render,
            1 => &self.camera,
            _ => &self.environment,
        };
        if !section.present {
            return Some(T::default());
        }
        match serde_path_to_error::deserialize(toml::Value::Table(section.table.clone())) {
            Ok(v) => Some(v),
            Err(e) => {
                let inner_path = super::source::path_string("", e.path());
                let message = e.inner().message().trim().to_string();
                // The file that set the offending key (or the last one that set the section).
                let first = inner_path.split(['.', '[']).next().unwrap_or("");
                let unknown = crate::diagnostics::parse_unknown_field(&message).map(|(f, _)| f);
                let top = unknown.as_deref().filter(|_| first.is_empty()).unwrap_or(first);
                let file = section.origin.get(top).copied().unwrap_or(self.files.len().saturating_sub(1));
                let path = if inner_path.is_empty() { name.to_string() } else { format!("{name}.{inner_path}") };
                self.diagnostics.push(super::source::serde_diagnostic(&self.files[file], &path, &message));
                None
            }
        }
    }

    fn finish(mut self) -> Result<Scene, SceneError> {
        if !self.diagnostics.is_empty() && self.files.is_empty() {
            return Err(SceneError { diagnostics: self.diagnostics });
        }
        let render: Option<RenderSettings> = self.section(0, "render");
        let camera: Option<Camera> = self.section(1, "camera");
        let environment: Option<Environment> = self.section(2, "world");

        let mut world = hecs::World::new();
        let mut by_name: HashMap<String, (hecs::Entity, Location)> = HashMap::new();
        let mut parents: Vec<(hecs::Entity, String, Location)> = Vec::new();
        let objects = std::mem::take(&mut self.objects);
        for object in objects {
            self.object(&mut world, object, &mut by_name, &mut parents);
        }
        for (entity, parent, location) in parents {
            match by_name.get(&parent) {
                Some((p, _)) => {
                    world.insert_one(entity, Parent(*p)).expect("entity was just spawned");
                }
                None => {
                    let d = Diagnostic::new(location, format!("no object is named `{parent}`"))
                        .suggest(&parent, by_name.keys().map(String::as_str));
                    self.diagnostics.push(d);
                }
            }
        }
        let lights = std::mem::take(&mut self.lights);
        for (i, (light, location)) in lights.into_iter().enumerate() {
            world.spawn((light, Origin(location), Name(format!("light{i}"))));
        }
        self.check_camera_keys();

        if !self.diagnostics.is_empty() {
            let files = &self.files;
            self.diagnostics.sort_by_key(|d| {
                (files.iter().position(|f| f.name == d.location.file), d.location.line, d.location.column)
            });
            return Err(SceneError { diagnostics: self.diagnostics });
        }
        let render = render.expect("no diagnostics");
        spawn_imported_lights(&mut world, std::mem::take(&mut self.light_imports));
        let camera = camera.expect("no diagnostics");
        let camera = match self.camera_import.take() {
            Some(import) => spawn_imported_camera(&mut world, import, &camera),
            None => {
                let camera_origin = match self.camera.origin.values().next() {
                    Some(&file) => self.files[file].locate("camera"),
                    None => Location::file_only(self.files[0].name.clone(), "camera"),
                };
                world.spawn((camera, Name("camera".into()), Origin(camera_origin)))
            }
        };
        let render_origin = match self.render.origin.get("width").or_else(|| self.render.origin.values().next()) {
            Some(&file) => self.files[file].locate("render"),
            None => Location::file_only(self.files[0].name.clone(), "render"),
        };
        Ok(Scene { world, render, render_origin, environment: environment.expect("no diagnostics"), camera })
    }

    fn object(
        &mut self,
        world: &mut hecs::World,
        object: ObjectDef,
        by_name: &mut HashMap<String, (hecs::Entity, Location)>,
        parents: &mut Vec<(hecs::Entity, String, Location)>,
    ) {
        let ObjectDef { file, key, mut table } = object;
        let location = self.files[file].locate(&key);
        // Meshes keep their files' materials unless the object names one.
        let explicit_material = table.contains_key("material");
        let Some(kind_value) = table.remove("shape") else {
            let d = Diagnostic::new(location, "missing key `shape`")
                .with_help(format!("known shapes: {}", self.registry.names().collect::<Vec<_>>().join(", ")));
            self.diagnostics.push(d);
            return;
        };
        let toml::Value::String(kind) = kind_value else {
            let d = Diagnostic::new(self.files[file].locate_value(&format!("{key}.shape")), "`shape` must be a string");
            self.diagnostics.push(d);
            return;
        };
        let shape_type = self.registry.get(&kind);
        if shape_type.is_none() && kind != MESH_SHAPE {
            let d = Diagnostic::new(
                self.files[file].locate_value(&format!("{key}.shape")),
                format!("unknown shape `{kind}`"),
            )
            .suggest(&kind, self.registry.names().chain([MESH_SHAPE]));
            let d = if d.help.is_none() {
                d.with_help(format!("known shapes: {}, mesh", self.registry.names().collect::<Vec<_>>().join(", ")))
            } else {
                d
            };
            self.diagnostics.push(d);
            return;
        }

        let name = match table.remove("name") {
            None => None,
            Some(toml::Value::String(s)) => Some(s),
            Some(_) => {
                self.diagnostics.push(Diagnostic::new(
                    self.files[file].locate_value(&format!("{key}.name")),
                    "`name` must be a string",
                ));
                return;
            }
        };
        let transform: Transform = match table.remove("transform") {
            None => Transform::default(),
            Some(v) => match self.deserialize(file, &format!("{key}.transform"), v) {
                Some(t) => t,
                None => return,
            },
        };
        let matrix = transform.parent_from_local();
        if !(matrix.matrix3.is_finite() && matrix.translation.is_finite()) {
            let k = format!("{key}.transform");
            self.diagnostics
                .push(Diagnostic::new(self.files[file].locate(&k), "transform is not finite (NaN or infinity)"));
            return;
        }
        if matrix.matrix3.determinant().abs() < 1e-18 {
            let k = format!("{key}.transform");
            let d = Diagnostic::new(self.files[file].locate(&k), "transform is singular (it flattens the object)")
                .with_help("a scale of 0 on some axis, or a matrix without an inverse");
            self.diagnostics.push(d);
            return;
        }
        if transform.matrix.is_some()
            && (transform.translate.is_some() || transform.rotate.is_some() || transform.scale.is_some())
        {
            let d = Diagnostic::new(
                self.files[file].locate(&format!("{key}.transform.matrix")),
                "`matrix` cannot be combined with translate, rotate or scale",
            )
            .with_help("fold the other parts into the matrix, or drop the matrix");
            self.diagnostics.push(d);
            return;
        }
        let material = match table.remove("material") {
            None => Some(MaterialComponent { name: None, material: Material::default() }),
            Some(toml::Value::String(name)) => match self.materials.get(&name) {
                Some((m, _)) => Some(MaterialComponent { name: Some(name), material: m.clone() }),
                None => {
                    let d = Diagnostic::new(
                        self.files[file].locate_value(&format!("{key}.material")),
                        format!("no material is named `{name}`"),
                    )
                    .suggest(&name, self.materials.keys().map(String::as_str));
                    self.diagnostics.push(d);
                    None
                }
            },
            Some(v @ toml::Value::Table(_)) => self
                .material(file, &format!("{key}.material"), v)
                .map(|m| MaterialComponent { name: None, material: m }),
            Some(_) => {
                self.diagnostics.push(Diagnostic::new(
                    self.files[file].locate_value(&format!("{key}.material")),
                    "`material` must be the name of a [materials.NAME] table or an inline table",
                ));
                None
            }
        };
        let parent = match table.remove("parent") {
            None => None,
            Some(toml::Value::String(s)) => Some(s),
            Some(_) => {
                self.diagnostics.push(Diagnostic::new(
                    self.files[file].locate_value(&format!("{key}.parent")),
                    "`parent` must be the name of another object",
                ));
                return;
            }
        };
        let flags = match table.remove("no_shadow") {
            None => ObjectFlags::default(),
            Some(toml::Value::Boolean(b)) => ObjectFlags { no_shadow: b },
            Some(_) => {
                self.diagnostics.push(Diagnostic::new(
                    self.files[file].locate_value(&format!("{key}.no_shadow")),
                    "`no_shadow` must be true or false",
                ));
                return;
            }
        };
        let entity = match shape_type {
            None => match self.mesh_object(
                world,
                file,
                &key,
                table,
                transform,
                material.filter(|_| explicit_material),
                flags,
                &location,
            ) {
                Some(entity) => entity,
                None => return,
            },
            Some(shape_type) => {
                let geometry = match (shape_type.build)(table.clone()) {
                    Ok(g) => g,
                    Err(e) => {
                        let d = if let Some((field, expected)) = crate::diagnostics::parse_unknown_field(&e.message) {
                            // The parameter path ends with the unknown key (`components[0].centre`).
                            let inner = if e.key.is_empty() { field.clone() } else { e.key.clone() };
                            let k = format!("{key}.{inner}");
                            Diagnostic::new(
                                self.files[file].locate(&k),
                                format!("unknown key `{field}` for shape `{kind}`"),
                            )
                            .suggest(&field, expected.iter().map(String::as_str).chain(OBJECT_KEYS))
                        } else if e.key.is_empty() {
                            Diagnostic::new(location.clone(), format!("shape `{kind}`: {}", e.message))
                        } else {
                            let k = format!("{key}.{}", e.key);
                            Diagnostic::new(self.files[file].locate_value(&k), e.message.clone())
                        };
                        self.diagnostics.push(d);
                        return;
                    }
                };
                let Some(material) = material else { return };
                let shape = ShapeComponent { kind, params: table, geometry };
                world.spawn((shape, transform, material, flags, Origin(location.clone())))
            }
        };
        if let Some(name) = name {
            if let Some((_, first)) = by_name.get(&name) {
                let d = Diagnostic::new(
                    self.files[file].locate_value(&format!("{key}.name")),
                    format!("duplicate object name `{name}`"),
                )
                .with_help(format!("first used at {first}"));
                self.diagnostics.push(d);
            } else {
                by_name.insert(name.clone(), (entity, location));
            }
            world.insert_one(entity, Name(name)).expect("entity was just spawned");
        }
        if let Some(parent) = parent {
            parents.push((entity, parent, self.files[file].locate_value(&format!("{key}.parent"))));
        }
    }

    /// The directory of scene file `index` (mesh and texture paths are relative to it).
    fn directory(&self, index: usize) -> PathBuf {
        Path::new(&*self.files[index].name).parent().unwrap_or(Path::new("")).to_path_buf()
    }

    /// A `shape = "mesh"` object: imports the file (once per file) and spawns the root
    /// entity and its parts; `None` after reporting a problem.
    #[allow(clippy::too_many_arguments)]
    fn mesh_object(
        &mut self,
        world: &mut hecs::World,
        file: usize,
        key: &str,
        mut table: toml::Table,
        transform: Transform,
        material: Option<MaterialComponent>,
        flags: ObjectFlags,
        location: &Location,
    ) -> Option<hecs::Entity> {
        let material_failed = material.is_none()
            && self.diagnostics.iter().any(|d| d.location.key.starts_with(&format!("{key}.material")));
        let mut ok = true;
        for k in table.keys() {
            if !MESH_KEYS.contains(&k.as_str()) {
                let d = Diagnostic::new(
                    self.files[file].locate(&format!("{key}.{k}")),
                    format!("unknown key `{k}` for shape `mesh`"),
                )
                .suggest(k, MESH_KEYS.into_iter().chain(OBJECT_KEYS));
                self.diagnostics.push(d);
                ok = false;
            }
        }
        let smooth_angle = match table.get("smooth_angle") {
            None => None,
            Some(v) => match v.as_float().or_else(|| v.as_integer().map(|i| i as f64)) {
                Some(a) if a.is_finite() && a > 0.0 && a <= 180.0 => Some(a),
                _ => {
                    let d = Diagnostic::new(
                        self.files[file].locate_value(&format!("{key}.smooth_angle")),
                        "`smooth_angle` must be an angle in degrees, greater than 0 and at most 180",
                    );
                    self.diagnostics.push(d);
                    return None;
                }
            },
        };
        let import_lights = match table.get("import_lights") {
            None | Some(toml::Value::Boolean(false)) => false,
            Some(toml::Value::Boolean(true)) => true,
            Some(_) => {
                let d = Diagnostic::new(
                    self.files[file].locate_value(&format!("{key}.import_lights")),
                    "`import_lights` must be true or false",
                );
                self.diagnostics.push(d);
                return None;
            }
        };
        let camera_choice = match table.get("import_camera").map(CameraChoice::parse) {
            None => None,
            Some(Ok(choice)) => choice,
            Some(Err(message)) => {
                let d = Diagnostic::new(self.files[file].locate_value(&format!("{key}.import_camera")), message)
                    .with_help("true takes the file's first camera; a number or a name picks one");
                self.diagnostics.push(d);
                return None;
            }
        };
        let relative = match table.remove("file") {
            Some(toml::Value::String(s)) => s,
            Some(_) => {
                let d = Diagnostic::new(self.files[file].locate_value(&format!("{key}.file")), "`file` must be a path");
                self.diagnostics.push(d);
                return None;
            }
            None => {
                let d =
                    Diagnostic::new(location.clone(), "a mesh needs `file`: the path of an .obj, .gltf or .glb file")
                        .with_help("the path is relative to this scene file");
                self.diagnostics.push(d);
                return None;
            }
        };
        let path = self.directory(file).join(&relative);
        let is_gltf = path
            .extension()
            .and_then(|e| e.to_str())
            .is_some_and(|e| e.eq_ignore_ascii_case("gltf") || e.eq_ignore_ascii_case("glb"));
        for (wanted, what, k) in
            [(import_lights, "lights", "import_lights"), (camera_choice.is_some(), "cameras", "import_camera")]
        {
            if wanted && !is_gltf {
                let d = Diagnostic::new(
                    self.files[file].locate_value(&format!("{key}.{k}")),
                    format!("`{k}` needs a glTF file (.gltf or .glb): `{relative}` has no {what}"),
                );
                self.diagnostics.push(d);
                return None;
            }
        }
        let model = match self.meshes.get(&path, &ImportOptions { smooth_angle }) {
            Ok(model) => model,
            Err(e) => {
                let d = Diagnostic::new(
                    self.files[file].locate_value(&format!("{key}.file")),
                    format!("cannot import mesh: {e}"),
                );
                self.diagnostics.push(d);
                return None;
            }
        };
        let mut material_map = std::collections::BTreeMap::new();
        if let Some(value) = table.remove("material_map") {
            let map_key = format!("{key}.material_map");
            let toml::Value::Table(entries) = value else {
                let d = Diagnostic::new(
                    self.files[file].locate_value(&map_key),
                    "`material_map` must be a table from the file's material names to materials",
                );
                self.diagnostics.push(d);
                return None;
            };
            let known: Vec<&str> = model.parts.iter().filter_map(|p| p.material_name.as_deref()).collect();
            for (name, value) in entries {
                let entry_key = format!("{map_key}.{name}");
                if !known.contains(&name.as_str()) {
                    let d = Diagnostic::new(
                        self.files[file].locate(&entry_key),
                        format!("`{relative}` has no material named `{name}`"),
                    )
                    .suggest(&name, known.iter().copied());
                    let d =
                        if d.help.is_none() { d.with_help(format!("its materials: {}", known.join(", "))) } else { d };
                    self.diagnostics.push(d);
                    ok = false;
                    continue;
                }
                let component = match value {
                    toml::Value::String(scene_name) => match self.materials.get(&scene_name) {
                        Some((m, _)) => MaterialComponent { name: Some(scene_name), material: m.clone() },
                        None => {
                            let d = Diagnostic::new(
                                self.files[file].locate_value(&entry_key),
                                format!("no material is named `{scene_name}`"),
                            )
                            .suggest(&scene_name, self.materials.keys().map(String::as_str));
                            self.diagnostics.push(d);
                            ok = false;
                            continue;
                        }
                    },
                    v @ toml::Value::Table(_) => match self.material(file, &entry_key, v) {
                        Some(m) => MaterialComponent { name: None, material: m },
                        None => {
                            ok = false;
                            continue;
                        }
                    },
                    _ => {
                        let d = Diagnostic::new(
                            self.files[file].locate_value(&entry_key),
                            "each entry must name a [materials.NAME] table or be an inline material table",
                        );
                        self.diagnostics.push(d);
                        ok = false;
                        continue;
                    }
                };
                material_map.insert(name, component);
            }
        }
        let lights_location = self.files[file].locate_value(&format!("{key}.import_lights"));
        if import_lights && !self.check_lights(&model, &relative, &lights_location) {
            ok = false;
        }
        let camera_location = self.files[file].locate_value(&format!("{key}.import_camera"));
        let camera = match &camera_choice {
            Some(choice) => match self.choose_camera(&model, choice, &relative, &camera_location) {
                Some(chosen) => Some(chosen),
                None => return None,
            },
            None => None,
        };
        if !ok || material_failed {
            return None;
        }
        // Absolute, so the path does not depend on where the scene is loaded from; `save`
        // writes it relative to the saved file when it can.
        let absolute = std::fs::canonicalize(&path).unwrap_or(path).display().to_string();
        let source = MeshSource { file: absolute, material, material_map, params: table, model: model.clone() };
        let spawned = crate::mesh::spawn::spawn_model(world, source, transform, flags, location);
        if import_lights {
            self.light_imports.push(LightImport {
                model: model.clone(),
                root: spawned.root,
                nodes: spawned.nodes.clone(),
                file: relative.clone(),
                location: lights_location,
            });
        }
        if let Some((camera_index, yfov)) = camera {
            let camera = &model.cameras[camera_index];
            let aspect_ratio = match camera.projection {
                Ok(CameraProjection::Perspective { aspect_ratio, .. }) => aspect_ratio,
                _ => None,
            };
            self.camera_import = Some(CameraImport {
                node: spawned.nodes[camera.node],
                yfov,
                aspect_ratio,
                description: format!("{relative}: {}", cameras_lights::describe_camera(&model, camera)),
                object_key: key.to_string(),
                file: relative,
                location: camera_location,
            });
        }
        Some(spawned.root)
    }

    /// `import_lights = true`: the file must have lights, and each must be usable; problems
    /// are reported at `location`. True when all is well.
    fn check_lights(&mut self, model: &Model, relative: &str, location: &Location) -> bool {
        if model.lights.is_empty() {
            let d = Diagnostic::new(
                location.clone(),
                format!("`{relative}` has no KHR_lights_punctual light on a node of its default scene"),
            )
            .with_help("remove `import_lights`, or add lights to the file");
            self.diagnostics.push(d);
            return false;
        }
        let mut ok = true;
        for light in &model.lights {
            if let Err(message) = cameras_lights::check_light(light) {
                self.diagnostics.push(Diagnostic::new(location.clone(), format!("`{relative}`: {message}")));
                ok = false;
            }
        }
        ok
    }

    /// `import_camera`: the chosen camera (its index in `model.cameras` and its vertical
    /// field of view in radians), or `None` after reporting why there is none, or that
    /// another object already imports the camera.
    fn choose_camera(
        &mut self,
        model: &Model,
        choice: &CameraChoice,
        relative: &str,
        location: &Location,
    ) -> Option<(usize, f64)> {
        if let Some(first) = &self.camera_import {
            let d = Diagnostic::new(
                location.clone(),
                format!(
                    "two objects import the camera: `{}.import_camera` already takes it from `{}`",
                    first.object_key, first.file
                ),
            )
            .with_help(format!("first imported at {}; a scene has one camera", first.location));
            self.diagnostics.push(d);
            return None;
        }
        match cameras_lights::select_camera(model, choice) {
            Ok(chosen) => Some(chosen),
            Err(message) => {
                let mut d = Diagnostic::new(location.clone(), format!("`{relative}`: {message}"));
                if let CameraChoice::Name(name) = choice {
                    d = d.suggest(name, cameras_lights::camera_names(model));
                }
                self.diagnostics.push(d);
                None
            }
        }
    }

    /// With an imported camera, `[camera]` may set only the lens: a key the file's camera
    /// sets (in any included file) is a second source for the camera and an error. (Unknown
    /// keys are reported by the section's own check.)
    fn check_camera_keys(&mut self) {
        let Some(import) = &self.camera_import else { return };
        let mut keys: Vec<(&String, &usize)> = self.camera.origin.iter().collect();
        keys.sort();
        let mut found = Vec::new();
        for (k, &file) in keys {
            if !POSE_KEYS.contains(&k.as_str()) {
                continue;
            }
            let d = Diagnostic::new(
                self.files[file].locate(&format!("camera.{k}")),
                format!(
                    "`camera.{k}` cannot be set: `{}.import_camera` takes the camera from `{}`",
                    import.object_key, import.file
                ),
            )
            .with_help(format!(
                "with an imported camera, [camera] may set only {}; remove `import_camera` to place the camera here",
                LENS_KEYS.join(" and ")
            ));
            found.push(d);
        }
        self.diagnostics.extend(found);
    }

    /// Resolves the texture paths of a scene material (relative to scene file `index`) to
    /// absolute paths and decodes the images; reports unreadable images at `key`.
    fn material_textures(&mut self, index: usize, key: &str, material: &mut Material) -> bool {
        let dir = self.directory(index);
        let mut ok = true;
        for (texture, space) in material.textures_mut() {
            let path = dir.join(&texture.file);
            match self.meshes.textures.load_file(&path, space) {
                Ok(t) => {
                    texture.file = std::fs::canonicalize(&path).unwrap_or(path).display().to_string();
                    texture.texture = Some(t);
                }
                Err(e) => {
                    self.diagnostics.push(Diagnostic::new(self.files[index].locate(key), e));
                    ok = false;
                }
            }
        }
        ok
    }
}
