//! `shape = "mesh"` objects: importing the file through the model store, spawning its
//! nodes and parts, and the lights and camera it brings when the scene asks.

use super::*;
use crate::geometry::mesh::{MeshData, MeshShape};

/// Spawns the lights of every `import_lights` object, placed by their node's world transform
/// (parents are linked by now; a parent cycle is reported later by `resolve_transforms`).
/// A light's `range`, which Prism does not use, is reported in `warnings`.
pub(super) fn spawn_imported_lights(
    world: &mut hecs::World,
    imports: Vec<LightImport>,
    warnings: &mut Vec<Diagnostic>,
) {
    for import in imports {
        let Some(object) = world_from_local(world, import.root) else { continue };
        let scale = punctual::uniform_scale(&object);
        for light in &import.model.lights {
            let Some(world_from_light) = world_from_local(world, import.nodes[light.node]) else { continue };
            if let Some(range) = light.range {
                warnings.push(Diagnostic::warning(
                    import.location.clone(),
                    format!(
                        "{}: {}: `range` {range} is ignored (imported lights fall off with the inverse square of the distance)",
                        import.file,
                        punctual::describe_light(light)
                    ),
                ));
            }
            let prism_light = punctual::light_from_node(light, world_from_light, scale);
            world.spawn((prism_light, Origin(import.location.clone()), Imported));
        }
    }
}

/// Spawns the scene's camera from an `import_camera` object: the file's camera at its node's
/// world transform, with the lens (`aperture`, `focal_distance`, the `blur_*` keys) of
/// `[camera]`.
pub(super) fn spawn_imported_camera(world: &mut hecs::World, import: CameraImport, lens: &Camera) -> hecs::Entity {
    let camera = match world_from_local(world, import.node) {
        Some(world_from_camera) => punctual::camera_from_node(world_from_camera, import.view, lens),
        None => lens.clone(),
    };
    let marker = ImportedCamera { aspect_ratio: import.aspect_ratio, description: import.description };
    world.spawn((camera, Name("camera".into()), Origin(import.location), marker))
}

/// A mesh object's `import_lights = true`: its file's lights, placed once parents are known.
pub(super) struct LightImport {
    model: std::sync::Arc<Model>,
    /// The object's entity and its node entities (one per `model.nodes`).
    root: hecs::Entity,
    nodes: Vec<hecs::Entity>,
    /// The mesh file as the scene wrote it, for warnings.
    file: String,
    /// The `import_lights` key (where its warnings point).
    location: Location,
}

/// A mesh object's `import_camera`: the chosen camera, placed once parents are known.
pub(super) struct CameraImport {
    /// The entity of the node holding the camera.
    node: hecs::Entity,
    /// The file's projection (field of view or magnification).
    view: punctual::ImportedView,
    /// Width / height of the viewport the file was made for, if it says.
    aspect_ratio: Option<f64>,
    /// `file.gltf: camera 0 ...`, for messages.
    description: String,
    /// The object's key (`object[2]`) and the file it names, for conflict messages.
    object_key: String,
    file: String,
    /// The `import_camera` key.
    location: Location,
}

/// The keys of a mesh in a CSG group besides the member keys.
const CSG_MESH_KEYS: [&str; 2] = ["file", "smooth_angle"];

/// The most triangles a mesh in a CSG group holds: a group numbers its leaves' parts in
/// the low [`PART_BITS`](crate::accel::primitive::PART_BITS) bits of a hit.
const MAX_MEMBER_TRIANGLES: usize = 1 << crate::accel::primitive::PART_BITS;

/// `[camera]` keys that may accompany an imported camera (the lens).
pub(super) const LENS_KEYS: [&str; 5] =
    ["aperture", "focal_distance", "blur_variance", "blur_confidence", "blur_min_samples"];

/// `[camera]` keys an imported camera takes from the file (a second source is an error).
pub(super) const POSE_KEYS: [&str; 7] = ["position", "look_at", "up", "vfov", "aspect", "projection", "view_height"];

/// A `shape = "mesh"` object as [`Loader::object`] has read it: the keys common to every
/// object are taken out and checked, the mesh keys are left in `table`.
pub(super) struct MeshObject<'a> {
    /// Index of the scene file it is written in.
    pub(super) file: usize,
    /// Its key path, such as `object[2]`.
    pub(super) key: &'a str,
    /// Its location (the `[[object]]` table).
    pub(super) location: &'a Location,
    /// The remaining keys: `file`, `material_map`, `smooth_angle`, `import_lights`,
    /// `import_camera` (and any unknown ones).
    pub(super) table: toml::Table,
    /// Its `transform`.
    pub(super) transform: Transform,
    /// The material it names, if it names one (`None` keeps the file's materials).
    pub(super) material: Option<MaterialComponent>,
    /// Its `no_shadow` flag.
    pub(super) flags: ObjectFlags,
}

impl Loader<'_> {
    /// A `shape = "mesh"` object: imports the file (once per file) and spawns the root
    /// entity and its parts; `None` after reporting a problem. The file's import warnings
    /// are reported once, at the first object that names it.
    pub(super) fn mesh_object(&mut self, world: &mut hecs::World, object: MeshObject) -> Option<hecs::Entity> {
        let MeshObject { file, key, location, mut table, transform, material, flags } = object;
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
        let smooth_angle = self.smooth_angle(file, key, &table)?;
        let import_lights = self.boolean_flag(table.get("import_lights"), file, key, "import_lights").ok()?;
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
        let (path, relative) = self.mesh_path(file, key, location, table.remove("file"))?;
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
        let model = self.import_model(file, key, &path, &relative, smooth_angle)?;
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
                        Some((m, _)) => m.clone(),
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
                        Some(m) => m,
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
        let entities = (1 + model.nodes.len() + model.parts.len()) as u64;
        self.imported_entities = self.imported_entities.saturating_add(entities);
        let total = self.imported_entities;
        let estimate = total.saturating_mul(crate::limits::BYTES_PER_INSTANCE);
        if let Err(e) = self.budget.check(|| format!("{total} imported nodes and mesh instances"), estimate) {
            // Reported at the object that crossed the budget, not at every one after it.
            let before = (total - entities).saturating_mul(crate::limits::BYTES_PER_INSTANCE);
            if self.budget.check(String::new, before).is_ok() {
                self.diagnostics.push(Diagnostic::new(location.clone(), e.to_string()));
            }
            return None;
        }
        let absolute = std::fs::canonicalize(&path).unwrap_or(path).display().to_string();
        let source = MeshSource { file: absolute, material, material_map, params: table, model: model.clone() };
        let spawned = crate::import::spawn::spawn_model(world, source, transform, flags, location);
        if import_lights {
            self.light_imports.push(LightImport {
                model: model.clone(),
                root: spawned.root,
                nodes: spawned.nodes.clone(),
                file: relative.clone(),
                location: lights_location,
            });
        }
        if let Some((camera_index, view)) = camera {
            let camera = &model.cameras[camera_index];
            let aspect_ratio = match camera.projection {
                Ok(CameraProjection::Perspective { aspect_ratio, .. }) => aspect_ratio,
                Ok(CameraProjection::Orthographic { xmag, ymag }) => Some(xmag / ymag),
                Err(_) => None,
            };
            self.camera_import = Some(CameraImport {
                node: spawned.nodes[camera.node],
                view,
                aspect_ratio,
                description: format!("{relative}: {}", punctual::describe_camera(&model, camera)),
                object_key: key.to_string(),
                file: relative,
                location: camera_location,
            });
        }
        Some(spawned.root)
    }

    /// A mesh's `smooth_angle` (`Some(None)` when it has none); `None` after reporting a
    /// value that is not an angle.
    fn smooth_angle(&mut self, file: usize, key: &str, table: &toml::Table) -> Option<Option<f64>> {
        let Some(v) = table.get("smooth_angle") else { return Some(None) };
        match v.as_float().or_else(|| v.as_integer().map(|i| i as f64)) {
            Some(a) if a.is_finite() && a > 0.0 && a <= 180.0 => Some(Some(a)),
            _ => {
                let d = Diagnostic::new(
                    self.files[file].locate_value(&format!("{key}.smooth_angle")),
                    "`smooth_angle` must be an angle in degrees, greater than 0 and at most 180",
                );
                self.diagnostics.push(d);
                None
            }
        }
    }

    /// The file a mesh's `file` value names (relative to the scene file), and the value as
    /// messages show it; `None` after reporting a missing, mistyped or forbidden path.
    fn mesh_path(
        &mut self,
        file: usize,
        key: &str,
        location: &Location,
        value: Option<toml::Value>,
    ) -> Option<(std::path::PathBuf, String)> {
        let relative = match value {
            Some(toml::Value::String(s)) => s,
            Some(_) => {
                let d = Diagnostic::new(self.files[file].locate_value(&format!("{key}.file")), "`file` must be a path");
                self.diagnostics.push(d);
                return None;
            }
            None => {
                let d = Diagnostic::new(
                    location.clone(),
                    "a mesh needs `file`: the path of an .obj, .gltf, .glb, .ply or .ply.gz file",
                )
                .with_help("the path is relative to this scene file");
                self.diagnostics.push(d);
                return None;
            }
        };
        match self.access.join(&self.directory(file), &relative) {
            Ok(path) => Some((path, crate::files::shown(&relative))),
            Err(e) => {
                let d = Diagnostic::new(self.files[file].locate_value(&format!("{key}.file")), e.to_string());
                self.diagnostics.push(d);
                None
            }
        }
    }

    /// The mesh file at `path` imported (once per file and options, through the model
    /// store); its import warnings are reported at the first object that names it.
    fn import_model(
        &mut self,
        file: usize,
        key: &str,
        path: &std::path::Path,
        relative: &str,
        smooth_angle: Option<f64>,
    ) -> Option<std::sync::Arc<Model>> {
        let file_location = self.files[file].locate_value(&format!("{key}.file"));
        match self.meshes.fetch(path, &ImportOptions { smooth_angle }) {
            Ok(fetched) => {
                if fetched.first_use {
                    for warning in &fetched.model.warnings {
                        self.warnings
                            .push(Diagnostic::warning(file_location.clone(), format!("{relative}: {warning}")));
                    }
                }
                Some(fetched.model)
            }
            Err(e) => {
                let d = Diagnostic::new(file_location, format!("cannot import mesh: {e}"));
                let d = if is_missing_fetched_asset(path, &e) {
                    d.with_help("this large asset is not committed: run `scripts/fetch-assets.sh` in the repository")
                } else {
                    d
                };
                self.diagnostics.push(d);
                None
            }
        }
    }

    /// `shape = "mesh"` as a CSG member, written at `key` (its `table` without the member
    /// keys): every triangle of the file, each part placed by its node, as one surface (a
    /// solid when closed; an open one is a warning), and the file read. `None` after
    /// reporting why it cannot be one (a member holds at most 65,536 triangles).
    pub(super) fn csg_mesh_member(
        &mut self,
        file: usize,
        key: &str,
        table: &toml::Table,
    ) -> Option<(std::sync::Arc<dyn prism_api::Shape>, std::path::PathBuf)> {
        let mut ok = true;
        for k in table.keys().filter(|k| !CSG_MESH_KEYS.contains(&k.as_str())) {
            let location = self.files[file].locate(&format!("{key}.{k}"));
            let d = if MESH_KEYS.contains(&k.as_str()) || OBJECT_KEYS.contains(&k.as_str()) {
                Diagnostic::new(location, format!("`{k}` cannot be set on a mesh in a CSG group")).with_help(
                    "a mesh member takes `file` and `smooth_angle`, and the member keys (material, transform, inverse)",
                )
            } else {
                Diagnostic::new(location, format!("unknown key `{k}` for shape `mesh`"))
                    .suggest(k, CSG_MESH_KEYS.into_iter().chain(super::objects::MEMBER_KEYS))
            };
            self.diagnostics.push(d);
            ok = false;
        }
        let smooth_angle = self.smooth_angle(file, key, table)?;
        let location = self.files[file].locate(key);
        let (path, relative) = self.mesh_path(file, key, &location, table.get("file").cloned())?;
        let model = self.import_model(file, key, &path, &relative, smooth_angle)?;
        if !ok {
            return None;
        }
        let file_location = self.files[file].locate_value(&format!("{key}.file"));
        let triangles = model.triangle_count();
        if triangles > MAX_MEMBER_TRIANGLES {
            let d = Diagnostic::new(
                file_location,
                format!(
                    "`{relative}` has {triangles} triangles; a mesh in a CSG group holds at most {MAX_MEMBER_TRIANGLES}"
                ),
            )
            .with_help("use it as an object of its own, or a decimated copy in the group");
            self.diagnostics.push(d);
            return None;
        }
        let placed = model.world_from_nodes();
        let parts: Vec<_> = model.parts.iter().map(|p| (p.shape.data().clone(), placed[p.node])).collect();
        let data = match MeshData::merged(&parts, self.budget) {
            Ok(data) => data,
            Err(e) => {
                self.diagnostics.push(Diagnostic::new(file_location, format!("`{relative}`: {e}")));
                return None;
            }
        };
        let open = data.open_edges();
        if open > 0 {
            // POV-Ray's mesh without `inside_vector`: a surface that is inside nothing.
            self.warnings.push(Diagnostic::warning(
                file_location,
                format!(
                    "`{relative}` is not a closed surface ({open} edges border a single triangle), so it has no inside: in this group it is inside nothing, as a POV-Ray mesh without `inside_vector`"
                ),
            ));
        }
        let canonical = std::fs::canonicalize(&path).unwrap_or(path);
        Some((std::sync::Arc::new(MeshShape::new(data)), canonical))
    }

    /// `import_lights = true`: the file must have lights, and each must be usable; problems
    /// are reported at `location`. True when all is well.
    pub(super) fn check_lights(&mut self, model: &Model, relative: &str, location: &Location) -> bool {
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
            if let Err(message) = punctual::check_light(light) {
                self.diagnostics.push(Diagnostic::new(location.clone(), format!("`{relative}`: {message}")));
                ok = false;
            }
        }
        ok
    }

    /// `import_camera`: the chosen camera (its index in `model.cameras` and its vertical
    /// field of view in radians), or `None` after reporting why there is none, or that
    /// another object already imports the camera.
    pub(super) fn choose_camera(
        &mut self,
        model: &Model,
        choice: &CameraChoice,
        relative: &str,
        location: &Location,
    ) -> Option<(usize, punctual::ImportedView)> {
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
        match punctual::select_camera(model, choice) {
            Ok(chosen) => Some(chosen),
            Err(message) => {
                let mut d = Diagnostic::new(location.clone(), format!("`{relative}`: {message}"));
                if let CameraChoice::Name(name) = choice {
                    d = d.suggest(name, punctual::camera_names(model));
                }
                self.diagnostics.push(d);
                None
            }
        }
    }

    /// With an imported camera, `[camera]` may set only the lens: a key the file's camera
    /// sets (in any included file) is a second source for the camera and an error. (Unknown
    /// keys are reported by the section's own check.)
    pub(super) fn check_camera_keys(&mut self) {
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
                LENS_KEYS.join(", ")
            ));
            found.push(d);
        }
        self.diagnostics.extend(found);
    }
}

/// True when `path` is missing and lies in an `assets/fetched/` folder: the repository's large
/// assets, which `scripts/fetch-assets.sh` downloads.
fn is_missing_fetched_asset(path: &std::path::Path, error: &crate::import::ImportError) -> bool {
    let missing = matches!(
        &error.kind,
        crate::import::ImportErrorKind::File(crate::files::FileError::Io { source, .. })
            if source.kind() == std::io::ErrorKind::NotFound
    );
    let names: Vec<&std::ffi::OsStr> = path
        .components()
        .filter_map(|c| match c {
            std::path::Component::Normal(n) => Some(n),
            _ => None,
        })
        .collect();
    missing && names.windows(2).any(|w| w[0] == "assets" && w[1] == "fetched")
}
