//! Import: mesh files (OBJ, glTF, PLY) to a [`Model`] of neutral data, the model store that
//! imports each file once, and the spawning of a model's nodes, parts, cameras and lights
//! as entities. This is the only module that both reads mesh files and spawns entities.
//!
//! A scene writes `shape = "mesh"` and `file = "..."`; [`crate::scene::load`] asks the
//! [`MeshStore`] for the file's [`Model`] (shared by every object that names the file:
//! instancing is `Arc` sharing) and [`spawn::spawn_model`] makes one entity per
//! (node, primitive) so each keeps one material. See `docs/meshes.md` for the import rules.

pub mod gltf;
pub mod obj;
pub mod ply;
pub mod punctual;
pub mod spawn;
pub mod triangulate;

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use glam::DAffine3;

use crate::geometry::mesh::MeshShape;
use crate::material::Material;
use crate::texture::TextureStore;
pub use crate::world::components::PunctualKind;

/// A node of an imported file's scene tree (glTF nodes; an OBJ file has one).
#[derive(Clone, Debug)]
pub struct ModelNode {
    /// The node's name in the file, if any.
    pub name: Option<String>,
    /// The parent node (earlier in [`Model::nodes`]); `None` for roots.
    pub parent: Option<usize>,
    /// Local transform (node space to parent space).
    pub local: DAffine3,
}

/// One mesh part: a triangle primitive with one material, hanging from a node.
#[derive(Clone, Debug)]
pub struct ModelPart {
    /// Index into [`Model::nodes`].
    pub node: usize,
    /// The geometry (the same `Arc<MeshData>` when a file instances a mesh on several nodes).
    pub shape: Arc<MeshShape>,
    /// The material the file gives it, as written (shared by every object using the file).
    pub material: Arc<Material>,
    /// The material's name in the file, if any.
    pub material_name: Option<String>,
}

/// A camera on a node of an imported file (glTF `cameras`).
#[derive(Clone, Debug, PartialEq)]
pub struct ModelCamera {
    /// Index into [`Model::nodes`] of the node that holds the camera.
    pub node: usize,
    /// The camera's index in the file's `cameras` array.
    pub index: usize,
    /// The camera's name in the file, if any.
    pub name: Option<String>,
    /// The projection, or what is wrong with the file's description of it.
    pub projection: Result<CameraProjection, String>,
}

/// The projection of a [`ModelCamera`] (glTF units: radians, file units).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CameraProjection {
    /// A pinhole camera.
    Perspective {
        /// Vertical field of view in radians.
        yfov: f64,
        /// Width / height of the viewport the file was made for, if it says.
        aspect_ratio: Option<f64>,
    },
    /// A parallel projection.
    Orthographic {
        /// Half the viewport's width.
        xmag: f64,
        /// Half the viewport's height.
        ymag: f64,
    },
}

/// A `KHR_lights_punctual` light on a node of an imported file.
#[derive(Clone, Debug, PartialEq)]
pub struct ModelLight {
    /// Index into [`Model::nodes`] of the node that holds the light.
    pub node: usize,
    /// The light's index in the file's `KHR_lights_punctual.lights` array.
    pub index: usize,
    /// The light's name in the file, if any.
    pub name: Option<String>,
    /// Point, spot or directional.
    pub kind: PunctualKind,
    /// Linear RGB colour.
    pub color: [f64; 3],
    /// Candela (point, spot) or lux (directional).
    pub intensity: f64,
    /// Distance where the file says the light may be considered zero, if given.
    pub range: Option<f64>,
}

/// An imported mesh file: node tree, parts, cameras and lights, and what was skipped.
#[derive(Clone, Debug, Default)]
pub struct Model {
    /// Nodes, parents before children.
    pub nodes: Vec<ModelNode>,
    /// Mesh parts.
    pub parts: Vec<ModelPart>,
    /// Cameras on nodes of the imported scene, in depth-first node order (imported only when
    /// the scene asks: `import_camera`).
    pub cameras: Vec<ModelCamera>,
    /// Lights on nodes of the imported scene, in depth-first node order (imported only when
    /// the scene asks: `import_lights`).
    pub lights: Vec<ModelLight>,
    /// Things in the file that were skipped or approximated, as sentences (the scene loader
    /// turns them into warnings at the object that names the file).
    pub warnings: Vec<String>,
}

impl Model {
    /// Each node's transform to the file's space (its ancestors' local transforms applied
    /// after its own), indexed like [`Model::nodes`].
    pub fn world_from_nodes(&self) -> Vec<DAffine3> {
        let mut placed: Vec<DAffine3> = Vec::with_capacity(self.nodes.len());
        for node in &self.nodes {
            // Parents come before their children.
            let parent = node.parent.and_then(|p| placed.get(p)).copied().unwrap_or(DAffine3::IDENTITY);
            placed.push(parent * node.local);
        }
        placed
    }

    /// Triangles over all parts as instanced by the node tree.
    pub fn triangle_count(&self) -> usize {
        self.parts.iter().map(|p| p.shape.data().triangle_count()).sum()
    }
}

/// Options of a `shape = "mesh"` object that change what is imported.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ImportOptions {
    /// OBJ without normals: smooth across edges whose faces meet at less than this angle
    /// (degrees); `None` = flat shading.
    pub smooth_angle: Option<f64>,
}

/// Why a mesh file cannot be imported: the file, the line when known (OBJ), and the cause.
#[derive(Debug, thiserror::Error)]
#[error("{}: {kind}", place(.file, .line))]
pub struct ImportError {
    /// The file as given.
    pub file: PathBuf,
    /// 1-based line, when known.
    pub line: Option<usize>,
    /// What is wrong.
    pub kind: ImportErrorKind,
}

/// `file` or `file:line`.
fn place(file: &Path, line: &Option<usize>) -> String {
    let file = crate::files::shown_path(file);
    match *line {
        Some(line) => format!("{file}:{line}"),
        None => file,
    }
}

impl ImportError {
    /// An error about `file` with no line.
    pub fn new(file: &Path, kind: ImportErrorKind) -> Self {
        Self { file: file.to_path_buf(), line: None, kind }
    }

    /// The same error at 1-based line `line`.
    pub fn at_line(self, line: Option<usize>) -> Self {
        Self { line, ..self }
    }
}

/// The cause of an [`ImportError`].
#[derive(Debug, thiserror::Error)]
pub enum ImportErrorKind {
    /// The file cannot be read.
    #[error("cannot read: {0}")]
    Read(#[source] std::io::Error),
    /// The file (or one it names) is not read: not a regular file, too large, or outside
    /// the `--root` sandbox.
    #[error("{0}")]
    File(#[source] crate::files::FileError),
    /// The extension is not `.obj`, `.gltf`, `.glb`, `.ply` or `.ply.gz`.
    #[error("unknown mesh format `.{extension}` (expected .obj, .gltf, .glb, .ply or .ply.gz)")]
    UnknownFormat {
        /// The extension, lower case.
        extension: String,
    },
    /// A parser crate panicked on the file.
    #[error("the importer failed on malformed data")]
    ImporterPanicked,
    /// An OBJ file holds NUL bytes (UTF-16 or binary data).
    #[error("not a text file (UTF-16 or binary data)")]
    NotText,
    /// tobj cannot parse an OBJ statement.
    #[error("{}", obj::describe(.0))]
    Obj(#[source] tobj::LoadError),
    /// The gltf crate rejects the file.
    #[error("{}", invalid_gltf(.0))]
    Gltf(#[source] ::gltf::Error),
    /// A glTF buffer cannot be loaded.
    #[error("cannot load buffers: {0}")]
    GltfBuffers(#[source] ::gltf::Error),
    /// A glTF image cannot be loaded.
    #[error("image {index}: {source}")]
    GltfImage {
        /// The image's index in the file.
        index: u32,
        /// The cause.
        source: ::gltf::Error,
    },
    /// A glTF image decodes to a pixel format Prism does not read.
    #[error("image {index}: unsupported pixel format {format:?}")]
    PixelFormat {
        /// The image's index in the file.
        index: u32,
        /// What the gltf crate decoded.
        format: ::gltf::image::Format,
    },
    /// The glTF file has no scene.
    #[error("the file has no scene")]
    NoScene,
    /// A part's vertex data does not make a mesh.
    #[error("{part}: {source}")]
    Mesh {
        /// The part: `mesh 0 primitive 1` (glTF), `material `red`` (OBJ).
        part: String,
        /// The cause.
        source: crate::geometry::mesh::MeshError,
    },
    /// A material's values are out of range.
    #[error("material {material}: `{key}` {message}")]
    Material {
        /// The material's index, or `default`.
        material: String,
        /// The offending key.
        key: &'static str,
        /// What is wrong with it.
        message: String,
    },
    /// The file's structure is broken (indices or accessors out of range, cycles, non-finite
    /// values, faces that do not fit their data): the sentence names what and where.
    #[error("{0}")]
    Invalid(String),
    /// A mesh or image would exceed the memory budget the load's meshes and images share.
    #[error("{0}")]
    OverBudget(#[from] crate::limits::OverBudget),
}

/// The gltf crate's message for a file it rejects, said once as invalid glTF (its own
/// validation messages already begin so).
fn invalid_gltf(error: &::gltf::Error) -> String {
    let message = error.to_string();
    if message.starts_with("invalid glTF") { message } else { format!("invalid glTF: {message}") }
}

/// Imports `path` by its extension (`.obj`, `.gltf`, `.glb`, `.ply`, `.ply.gz`).
pub fn import(path: &Path, options: &ImportOptions, textures: &mut TextureStore) -> Result<Model, ImportError> {
    let mut ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).unwrap_or_default();
    if ext == "gz"
        && path.file_stem().and_then(|s| s.to_str()).is_some_and(|s| s.to_ascii_lowercase().ends_with(".ply"))
    {
        ext = "ply".into();
    }
    // A panic inside a parser crate on hostile input must still end as an error.
    let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| match ext.as_str() {
        "obj" => obj::import(path, options, textures),
        "gltf" | "glb" => gltf::import(path, textures),
        "ply" => ply::import(path, options, textures),
        _ => Err(ImportError::new(path, ImportErrorKind::UnknownFormat { extension: ext.clone() })),
    }));
    result.unwrap_or_else(|_| Err(ImportError::new(path, ImportErrorKind::ImporterPanicked)))
}

/// Imported files, keyed by canonical path and options: a file used by many objects is
/// read, triangulated and given its BVH once.
#[derive(Default)]
pub struct MeshStore {
    models: HashMap<(PathBuf, Option<u64>), Arc<Model>>,
    /// Decoded textures shared by all files and scene materials.
    pub textures: TextureStore,
}

impl MeshStore {
    /// An empty store reading any file, with no memory budget.
    pub fn new() -> Self {
        Self::default()
    }

    /// An empty store reading mesh and image files through `access`, each image decode
    /// checked against `budget`.
    pub fn with_limits(access: crate::files::FileAccess, budget: crate::limits::MemoryBudget) -> Self {
        Self { models: HashMap::new(), textures: TextureStore::with_limits(access, budget) }
    }

    /// The model for `path`, imported on first use.
    pub fn get(&mut self, path: &Path, options: &ImportOptions) -> Result<Arc<Model>, ImportError> {
        self.fetch(path, options).map(|fetched| fetched.model)
    }

    /// The model for `path`, and whether this call imported it (so its
    /// [`Model::warnings`] are reported once, not once per object using the file).
    pub fn fetch(&mut self, path: &Path, options: &ImportOptions) -> Result<Fetched, ImportError> {
        let canonical =
            self.textures.access().resolve(path).map_err(|e| ImportError::new(path, ImportErrorKind::File(e)))?;
        let key = (canonical, options.smooth_angle.map(f64::to_bits));
        if let Some(m) = self.models.get(&key) {
            return Ok(Fetched { model: m.clone(), first_use: false });
        }
        let model = Arc::new(import(path, options, &mut self.textures)?);
        self.models.insert(key, model.clone());
        Ok(Fetched { model, first_use: true })
    }

    /// Number of distinct imported files.
    pub fn len(&self) -> usize {
        self.models.len()
    }

    /// True when nothing was imported.
    pub fn is_empty(&self) -> bool {
        self.models.is_empty()
    }
}

/// A model from [`MeshStore::fetch`].
#[derive(Clone, Debug)]
pub struct Fetched {
    /// The imported file.
    pub model: Arc<Model>,
    /// True when this call imported it; false when an earlier call did.
    pub first_use: bool,
}

/// Component of the entity a `shape = "mesh"` object becomes: what to write back on save.
/// The entity carries the object's `Transform`, `ObjectFlags`, `Origin` and optional `Name`
/// and `Parent`; the imported parts are its descendants, marked [`Imported`].
#[derive(Clone, Debug)]
pub struct MeshSource {
    /// The mesh file, as an absolute path (`save` writes it relative to the saved file when it
    /// can).
    pub file: String,
    /// The material override, if the object gave one.
    pub material: Option<crate::world::components::MaterialComponent>,
    /// Materials replacing the file's materials by name (`material_map`).
    pub material_map: std::collections::BTreeMap<String, crate::world::components::MaterialComponent>,
    /// The other mesh parameters as written (`smooth_angle`, `import_lights`,
    /// `import_camera`; not `file` or `material_map`).
    pub params: toml::Table,
    /// The imported model (shared between objects naming the same file).
    pub model: Arc<Model>,
}

/// Marks entities created from a mesh file (nodes, parts and imported lights): `save` skips
/// them, since loading the file recreates them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Imported;
