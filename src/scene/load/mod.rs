//! `load`: scene files (with includes and named materials) into a hecs `World` plus the
//! scene-wide settings. Every problem becomes a [`Diagnostic`] with file, line, column and
//! key path; loading goes on after a problem so one run reports as many as it can. Errors
//! end in a [`SceneError`]; warnings (what an imported file skips or approximates) ride
//! along in [`Scene::warnings`].

mod lights;
mod materials;
mod meshes;
use meshes::{CameraImport, LightImport, MeshObject, spawn_imported_camera, spawn_imported_lights};
mod objects;

use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};

use serde::Deserialize;
use serde::de::DeserializeOwned;

use super::source::{ParsedFile, deserialize_at};
use crate::diagnostics::{Diagnostic, Location, SceneError};
use crate::files::{FileAccess, FileError, FileKind, normalize};
use crate::gamma::{AssumedGamma, GammaCurve};
use crate::import::punctual::{self, CameraChoice};
use crate::import::spawn::{MESH_KEYS, MESH_SHAPE};
use crate::import::{CameraProjection, ImportOptions, Imported, MeshSource, MeshStore, Model};
use crate::limits::{MAX_SCENE_FILES, MemoryBudget, PARSED_BYTES_PER_SCENE_BYTE, UNBUDGETED_SCENE_BYTES};
use crate::material::MaterialSpec;
use crate::registry::ShapeRegistry;
use crate::world::Scene;
use crate::world::components::{
    Camera, Environment, ImportedCamera, KeyLocations, Light, LightKind, MaterialComponent, Name, ObjectFlags, Origin,
    Parent, RenderSettings, ShapeComponent, Transform,
};
use crate::world::transforms::world_from_local;

/// Top-level keys of a scene file.
pub const TOP_LEVEL_KEYS: [&str; 7] = ["include", "render", "camera", "world", "materials", "object", "light"];

/// Keys of an `[[object]]` table that are not shape parameters.
pub const OBJECT_KEYS: [&str; 6] = ["shape", "name", "material", "transform", "parent", "no_shadow"];

/// Where scene files come from: the file system, or text embedded in the binary.
pub trait SceneSource {
    /// The text of the file at `path`.
    fn read(&self, path: &Path) -> Result<String, FileError>;
    /// A canonical identity for include-cycle detection and de-duplication.
    fn canonical(&self, path: &Path) -> PathBuf;
    /// How mesh, texture and environment files named by the scene are read.
    fn access(&self) -> FileAccess {
        FileAccess::unrestricted()
    }
}

/// Reads scene files from disk through a [`FileAccess`] (regular files only, at most
/// [`crate::files::MAX_SCENE_BYTES`] each, inside the sandbox if there is one).
#[derive(Default)]
pub struct FileSystem(pub FileAccess);

impl SceneSource for FileSystem {
    fn read(&self, path: &Path) -> Result<String, FileError> {
        self.0.read_text(path, FileKind::Scene)
    }

    fn canonical(&self, path: &Path) -> PathBuf {
        self.0.resolve(path).unwrap_or_else(|_| path.to_path_buf())
    }

    fn access(&self) -> FileAccess {
        self.0.clone()
    }
}

/// Scene files embedded in the binary, by path.
pub struct Embedded(pub &'static [(&'static str, &'static str)]);

impl SceneSource for Embedded {
    fn read(&self, path: &Path) -> Result<String, FileError> {
        let wanted = normalize(path);
        self.0.iter().find(|(p, _)| normalize(Path::new(p)) == wanted).map(|(_, text)| text.to_string()).ok_or_else(
            || FileError::Io {
                path: path.into(),
                source: std::io::Error::new(std::io::ErrorKind::NotFound, "no such built-in file"),
            },
        )
    }

    fn canonical(&self, path: &Path) -> PathBuf {
        normalize(path)
    }
}

/// Loads the scene at `path` from disk, reading any file, with no memory budget.
pub fn load_file(path: &Path, registry: &ShapeRegistry) -> Result<Scene, SceneError> {
    load_from(&FileSystem::default(), path, registry)
}

/// Loads the scene at `path` from `source`, with no memory budget.
pub fn load_from(source: &dyn SceneSource, path: &Path, registry: &ShapeRegistry) -> Result<Scene, SceneError> {
    load_with(source, path, registry, MemoryBudget::UNLIMITED)
}

/// Loads the scene at `path` from `source`; every image decode is checked against `budget`.
pub fn load_with(
    source: &dyn SceneSource,
    path: &Path,
    registry: &ShapeRegistry,
    budget: MemoryBudget,
) -> Result<Scene, SceneError> {
    let access = source.access();
    let mut loader = Loader {
        source,
        registry,
        access: access.clone(),
        budget,
        stack: Vec::new(),
        seen: HashSet::new(),
        files: Vec::new(),
        diagnostics: Vec::new(),
        warnings: Vec::new(),
        render: Section::default(),
        camera: Section::default(),
        environment: Section::default(),
        materials: HashMap::new(),
        default_material: MaterialComponent::authored(None, std::sync::Arc::new(MaterialSpec::default())),
        objects: Vec::new(),
        lights: Vec::new(),
        meshes: MeshStore::with_limits(access, budget),
        image_maps: HashMap::new(),
        light_imports: Vec::new(),
        camera_import: None,
        working_gamma: GammaCurve::Neutral,
        imported_entities: 0,
        scene_bytes: 0,
    };
    loader.load_all(path);
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

/// A scene file whose includes are being loaded (the loader's explicit stack).
struct Frame {
    /// Index into `Loader::files`.
    index: usize,
    /// Its includes: where each is written, and its path.
    includes: Vec<(Location, PathBuf)>,
    /// The next include to load.
    next: usize,
}

struct Loader<'a> {
    source: &'a dyn SceneSource,
    registry: &'a ShapeRegistry,
    /// How files named by the scene are read.
    access: FileAccess,
    /// The memory budget of decoded images, meshes and imported instances.
    budget: MemoryBudget,
    /// Entities spawned for mesh files' nodes and parts so far (checked against `budget`).
    imported_entities: u64,
    /// Bytes of scene TOML read so far: parsing them takes up to
    /// [`PARSED_BYTES_PER_SCENE_BYTE`] each, checked against `budget`.
    scene_bytes: u64,
    /// Canonical paths of the files whose includes are being loaded, outermost first.
    stack: Vec<PathBuf>,
    /// Canonical paths of every file read so far: each is loaded once.
    seen: HashSet<PathBuf>,
    files: Vec<ParsedFile>,
    /// Errors found so far.
    diagnostics: Vec<Diagnostic>,
    /// Warnings found so far.
    warnings: Vec<Diagnostic>,
    render: Section,
    camera: Section,
    environment: Section,
    /// The working space of the scene's colours (`[render] assumed_gamma`), into which image
    /// maps are decoded: known once every file's settings are merged.
    working_gamma: GammaCurve,
    /// Named materials: the component objects naming them share, and the file defining them.
    materials: HashMap<String, (MaterialComponent, usize)>,
    /// The material of objects that name none (one, shared).
    default_material: MaterialComponent,
    objects: Vec<ObjectDef>,
    lights: Vec<(Light, Location, KeyLocations)>,
    /// Imported mesh files and decoded textures, shared by every object that uses them.
    meshes: MeshStore,
    /// Decoded `image_map` and `bump_map` PNGs by canonical path and whether read raw (a bump
    /// map, without gamma), shared by every material that names them.
    image_maps: HashMap<(PathBuf, bool), std::sync::Arc<crate::material::image_map::MapImage>>,
    /// Mesh objects whose file's lights are imported.
    light_imports: Vec<LightImport>,
    /// The mesh object whose file's camera is the scene's camera.
    camera_import: Option<CameraImport>,
}

impl Loader<'_> {
    /// Loads `path` and its includes, depth first with an explicit stack (so an include
    /// chain thousands deep cannot overflow the call stack), each file once: a file's
    /// includes are merged before its own sections, so it overrides them.
    fn load_all(&mut self, path: &Path) {
        // Files in the order their sections apply (each after its includes).
        let mut order = Vec::new();
        let mut frames: Vec<Frame> = Vec::new();
        if let Some(frame) = self.open_file(path, None) {
            frames.push(frame);
        }
        while let Some(frame) = frames.last_mut() {
            if let Some((location, include)) = frame.includes.get(frame.next).cloned() {
                frame.next += 1;
                if let Some(child) = self.open_file(&include, Some(location)) {
                    frames.push(child);
                }
            } else {
                order.push(frame.index);
                frames.pop();
                self.stack.pop();
            }
        }
        // The settings first, merged over every file: reading a material's image maps needs
        // the final `assumed_gamma`, which the including file may set after an include's
        // materials.
        for &index in &order {
            self.settings_sections(index);
        }
        self.working_gamma = match self.render.table.get("assumed_gamma").cloned().map(AssumedGamma::deserialize) {
            // An invalid value is reported when the settings are read.
            Some(Ok(gamma)) if gamma.is_valid() => gamma.curve(),
            _ => GammaCurve::Neutral,
        };
        for index in order {
            self.sections(index);
        }
    }

    /// Reads and parses one file and lists its includes; `None` when it is not loaded (an
    /// error, or already loaded through another include).
    fn open_file(&mut self, path: &Path, included_from: Option<Location>) -> Option<Frame> {
        let display = path.display().to_string();
        let canonical = self.source.canonical(path);
        if let Some(pos) = self.stack.iter().position(|p| *p == canonical) {
            let chain: Vec<String> = self.stack[pos..]
                .iter()
                .chain(std::iter::once(&canonical))
                .map(|p| crate::files::shown_path(p))
                .collect();
            let location = included_from.unwrap_or_else(|| Location::file_only(display.as_str(), "include"));
            self.diagnostics.push(Diagnostic::new(location, format!("include cycle: {}", chain.join(" -> "))));
            return None;
        }
        if self.seen.contains(&canonical) {
            return None;
        }
        if self.seen.len() >= MAX_SCENE_FILES {
            let location = included_from.unwrap_or_else(|| Location::file_only(display.as_str(), "include"));
            self.diagnostics
                .push(Diagnostic::new(location, format!("more than {MAX_SCENE_FILES} scene files are included")));
            return None;
        }
        self.seen.insert(canonical.clone());
        let text = match self.source.read(path) {
            Ok(text) => text,
            Err(e) => {
                let location = included_from.unwrap_or_else(|| Location::file_only(display.as_str(), ""));
                let what = if location.key.is_empty() { "cannot read scene file" } else { "cannot read included file" };
                let shown = crate::files::shown(&display);
                self.diagnostics.push(Diagnostic::new(location, format!("{what} `{shown}`: {}", e.cause())));
                return None;
            }
        };
        self.scene_bytes += text.len() as u64;
        let estimate = if self.scene_bytes > UNBUDGETED_SCENE_BYTES {
            self.scene_bytes.saturating_mul(PARSED_BYTES_PER_SCENE_BYTE)
        } else {
            0
        };
        if let Err(e) =
            self.budget.check(|| format!("parsing {} KiB of scene TOML", self.scene_bytes.div_ceil(1024)), estimate)
        {
            let location = included_from.unwrap_or_else(|| Location::file_only(display.as_str(), ""));
            self.diagnostics.push(Diagnostic::new(location, e.to_string()));
            return None;
        }
        let parsed = match ParsedFile::parse(&display, text) {
            Ok(p) => p,
            Err(d) => {
                self.diagnostics.push(d);
                return None;
            }
        };
        self.stack.push(canonical);
        let index = self.files.len();
        self.files.push(parsed);

        let keys: Vec<String> = self.files[index].table.keys().cloned().collect();
        for key in keys {
            if !TOP_LEVEL_KEYS.contains(&key.as_str()) {
                let d = Diagnostic::new(self.files[index].locate(&key), format!("unknown top-level key `{key}`"))
                    .suggest(&key, TOP_LEVEL_KEYS);
                let d = if d.help.is_none() {
                    d.with_help(format!("valid top-level keys: {}", TOP_LEVEL_KEYS.join(", ")))
                } else {
                    d
                };
                self.diagnostics.push(d);
            }
        }
        let includes = match self.files[index].table.get("include").cloned() {
            Some(value) => self.includes(index, path, &value),
            None => Vec::new(),
        };
        Some(Frame { index, includes, next: 0 })
    }

    /// File `index`'s `[render]`, `[camera]` and `[world]`, merged over its includes'.
    fn settings_sections(&mut self, index: usize) {
        let table = std::mem::take(&mut self.files[index].table);
        for (name, section) in [("render", 0), ("camera", 1), ("world", 2)] {
            if let Some(value) = table.get(name) {
                self.merge_section(index, name, section, value);
            }
        }
        self.files[index].table = table;
    }

    /// File `index`'s own materials, objects and lights (after its includes').
    fn sections(&mut self, index: usize) {
        let table = std::mem::take(&mut self.files[index].table);
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
                let file = &self.files[index];
                let keys = KeyLocations(t.keys().map(|k| (k.clone(), file.locate(&format!("{key}.{k}")))).collect());
                if let Some(light) = self.light(index, &key, t) {
                    let location = self.files[index].locate(&key);
                    self.lights.push((light, location, keys));
                }
            }
        }
        self.files[index].table = table;
    }

    /// The include paths of file `index` (at `path`), relative to its directory.
    fn includes(&mut self, index: usize, path: &Path, value: &toml::Value) -> Vec<(Location, PathBuf)> {
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
                return Vec::new();
            }
        };
        let dir = path.parent().unwrap_or(Path::new(""));
        let mut out = Vec::new();
        for (key, relative) in entries {
            let location = self.files[index].locate_value(&key);
            match self.access.join(dir, &relative) {
                Ok(path) => out.push((location, path)),
                Err(e) => self.diagnostics.push(Diagnostic::new(location, e.to_string())),
            }
        }
        out
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

    /// Where each top-level key of the merged table `section` (`[name]`) was written: in the
    /// last file that set it.
    fn section_keys(&self, section: &Section, name: &str) -> KeyLocations {
        KeyLocations(
            section
                .origin
                .iter()
                .map(|(key, &file)| (key.clone(), self.files[file].locate(&format!("{name}.{key}"))))
                .collect(),
        )
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
        let mut environment: Option<Environment> = self.section(2, "world");
        if let Some(environment) = &environment {
            self.world_colors(environment);
        }
        if let Some(map) = environment.as_mut().and_then(|e| e.environment.as_mut()) {
            self.environment_map(map);
        }

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
        for (i, (light, location, keys)) in lights.into_iter().enumerate() {
            world.spawn((light, Origin(location), keys, Name(format!("light{i}"))));
        }
        self.check_camera_keys();

        if !self.diagnostics.is_empty() {
            let mut diagnostics = std::mem::take(&mut self.diagnostics);
            self.sort_in_file_order(&mut diagnostics);
            return Err(SceneError { diagnostics });
        }
        let render = render.expect("no diagnostics");
        spawn_imported_lights(&mut world, std::mem::take(&mut self.light_imports), &mut self.warnings);
        let camera = camera.expect("no diagnostics");
        let camera = match self.camera_import.take() {
            Some(import) => spawn_imported_camera(&mut world, import, &camera),
            None => {
                let camera_origin = match self.camera.origin.values().next() {
                    Some(&file) => self.files[file].locate("camera"),
                    None => Location::file_only(self.files[0].name.clone(), "camera"),
                };
                let keys = self.section_keys(&self.camera, "camera");
                world.spawn((camera, Name("camera".into()), Origin(camera_origin), keys))
            }
        };
        let render_origin = match self.render.origin.get("width").or_else(|| self.render.origin.values().next()) {
            Some(&file) => self.files[file].locate("render"),
            None => Location::file_only(self.files[0].name.clone(), "render"),
        };
        let render_keys = self.section_keys(&self.render, "render");
        let mut warnings = std::mem::take(&mut self.warnings);
        self.sort_in_file_order(&mut warnings);
        let environment = environment.expect("no diagnostics");
        Ok(Scene { world, render, render_origin, render_keys, environment, camera, warnings })
    }

    /// Checks `[world]`'s colours as a material's: finite, and components within ±1e30,
    /// beyond which their products overflow into infinite pixels.
    fn world_colors(&mut self, environment: &Environment) {
        for (key, color) in [("background", environment.background), ("ambient_light", environment.ambient_light)] {
            if let Err((_, message)) = crate::material::check_finite(&[(key, color)], &[]) {
                let index = self.environment.origin.get(key).copied().unwrap_or(0);
                self.diagnostics.push(Diagnostic::new(self.files[index].locate(&format!("world.{key}")), message));
            }
        }
    }

    /// Checks `[world] environment` and decodes its image (relative to the file that wrote it).
    fn environment_map(&mut self, map: &mut crate::world::components::EnvironmentMapRef) {
        let index = self.environment.origin.get("environment").copied().unwrap_or(0);
        let at = |key: &str| self.files[index].locate(&format!("world.environment.{key}"));
        for (key, value) in [("intensity", map.intensity), ("rotate", map.rotate)] {
            if !value.is_finite() {
                self.diagnostics.push(Diagnostic::new(at(key), format!("must be finite, got {value}")));
                return;
            }
        }
        if map.intensity < 0.0 {
            self.diagnostics.push(Diagnostic::new(
                at("intensity"),
                format!("must not be negative, got {}", crate::diagnostics::shown_number(map.intensity)),
            ));
            return;
        }
        if map.intensity > crate::limits::MAX_COEFFICIENT {
            self.diagnostics.push(Diagnostic::new(
                at("intensity"),
                format!(
                    "must be at most {:e}, as other light coefficients (products would overflow), got {}",
                    crate::limits::MAX_COEFFICIENT,
                    crate::diagnostics::shown_number(map.intensity)
                ),
            ));
            return;
        }
        let path = match self.access.join(&self.directory(index), &map.file) {
            Ok(path) => path,
            Err(e) => {
                self.diagnostics.push(Diagnostic::new(at("file"), e.to_string()));
                return;
            }
        };
        match crate::texture::environment::EnvironmentMap::load_with(&path, &self.access, self.budget) {
            Ok(loaded) => {
                map.file = std::fs::canonicalize(&path).unwrap_or(path).display().to_string();
                map.map = Some(std::sync::Arc::new(loaded));
            }
            Err(e) => self.diagnostics.push(Diagnostic::new(at("file"), e.to_string())),
        }
    }

    /// Sorts by file (in load order), line and column; a stable sort, so problems at one
    /// place keep the order they were found in.
    fn sort_in_file_order(&self, diagnostics: &mut [Diagnostic]) {
        diagnostics.sort_by_key(|d| {
            (self.files.iter().position(|f| f.name == d.location.file), d.location.line, d.location.column)
        });
    }

    /// The directory of scene file `index` (mesh and texture paths are relative to it).
    fn directory(&self, index: usize) -> PathBuf {
        Path::new(&*self.files[index].name).parent().unwrap_or(Path::new("")).to_path_buf()
    }
}
