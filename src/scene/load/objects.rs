//! `[[object]]` tables: shapes built through the registry, their transforms, materials,
//! names and parents.

use super::*;

use std::sync::Arc;

use prism_api::ShapeType;

use crate::geometry::csg::{CsgMember, CsgOperation, CsgShape, MAX_LEAVES};
use crate::world::components::CsgMaterials;

/// Keys of a CSG group (`shape = "union"`...) besides the [`OBJECT_KEYS`].
pub const CSG_KEYS: [&str; 1] = ["members"];

/// Keys of a CSG member table besides its shape's parameters (and, for a nested group,
/// [`CSG_KEYS`]).
pub const MEMBER_KEYS: [&str; 4] = ["shape", "material", "transform", "inverse"];

/// The files a shape read: parameter key and canonical path.
type ReadFiles = Vec<(String, PathBuf)>;

/// The files a shape plugin reads, resolved relative to the scene file that names them and
/// read through the scene's [`FileAccess`] (regular files, size cap, sandbox, watch log).
struct ShapeFiles {
    access: FileAccess,
    directory: PathBuf,
    /// What was read.
    read: ReadFiles,
}

impl prism_api::FileReader for ShapeFiles {
    fn read(&mut self, key: &str, written: &str) -> Result<prism_api::ParamFile, prism_api::ParamError> {
        let failed = |e: crate::files::FileError| prism_api::ParamError::new(key, e.to_string());
        let path = self.access.join(&self.directory, written).map_err(failed)?;
        let bytes = self.access.read(&path, FileKind::ShapeData).map_err(failed)?;
        let path = self.access.resolve(&path).unwrap_or(path);
        self.read.push((key.to_string(), path.clone()));
        Ok(prism_api::ParamFile { path, bytes })
    }
}

/// A CSG group as loaded.
struct CsgGroup {
    /// Its geometry.
    shape: Arc<dyn prism_api::Shape>,
    /// The material of each leaf, depth first.
    leaves: Vec<MaterialComponent>,
    /// Its `members` as they are saved.
    members: toml::Value,
}

/// What an object's or member's `shape` names.
#[derive(Clone, Copy)]
enum ObjectKind<'a> {
    /// A CSG group.
    Csg(CsgOperation),
    /// A registered shape type.
    Plugin(&'a ShapeType),
    /// `shape = "mesh"`: an imported file.
    Mesh,
}

impl<'a> Loader<'a> {
    /// Removes the string `table[field]` (`None` when absent); a diagnostic `message` at
    /// `key.field` and `Err` when it is not a string.
    fn optional_string(
        &mut self,
        table: &mut toml::Table,
        file: usize,
        key: &str,
        field: &str,
        message: &str,
    ) -> Result<Option<String>, ()> {
        match table.remove(field) {
            None => Ok(None),
            Some(toml::Value::String(s)) => Ok(Some(s)),
            Some(_) => {
                let at = self.files[file].locate_value(&format!("{key}.{field}"));
                self.diagnostics.push(Diagnostic::new(at, message));
                Err(())
            }
        }
    }

    /// A boolean flag `key.field` whose value is `value` (false when absent); a diagnostic
    /// at `key.field` and `Err` when it is not `true` or `false`.
    pub(super) fn boolean_flag(
        &mut self,
        value: Option<&toml::Value>,
        file: usize,
        key: &str,
        field: &str,
    ) -> Result<bool, ()> {
        match value {
            None => Ok(false),
            Some(toml::Value::Boolean(b)) => Ok(*b),
            Some(_) => {
                let at = self.files[file].locate_value(&format!("{key}.{field}"));
                self.diagnostics.push(Diagnostic::new(at, format!("`{field}` must be true or false")));
                Err(())
            }
        }
    }

    /// Removes and checks `table.transform` (the identity when absent); `None` after a
    /// diagnostic at `key.transform`.
    fn object_transform(&mut self, table: &mut toml::Table, file: usize, key: &str) -> Option<Transform> {
        let transform: Transform = match table.remove("transform") {
            None => Transform::default(),
            Some(v) => self.deserialize(file, &format!("{key}.transform"), v)?,
        };
        let matrix = transform.parent_from_local();
        if !(matrix.matrix3.is_finite() && matrix.translation.is_finite()) {
            let k = format!("{key}.transform");
            self.diagnostics
                .push(Diagnostic::new(self.files[file].locate(&k), "transform is not finite (NaN or infinity)"));
            return None;
        }
        if matrix.matrix3.determinant().abs() < 1e-18 {
            let k = format!("{key}.transform");
            let d = Diagnostic::new(self.files[file].locate(&k), "transform is singular (it flattens the object)")
                .with_help("a scale of 0 on some axis, or a matrix without an inverse");
            self.diagnostics.push(d);
            return None;
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
            return None;
        }
        Some(transform)
    }

    /// The material `value` written at `key.material`: a `[materials.NAME]` name or an
    /// inline table; `None` after a diagnostic.
    fn object_material(&mut self, file: usize, key: &str, value: toml::Value) -> Option<MaterialComponent> {
        match value {
            toml::Value::String(name) => match self.materials.get(&name) {
                Some((m, _)) => Some(m.clone()),
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
            v @ toml::Value::Table(_) => self.material(file, &format!("{key}.material"), v),
            _ => {
                self.diagnostics.push(Diagnostic::new(
                    self.files[file].locate_value(&format!("{key}.material")),
                    "`material` must be the name of a [materials.NAME] table or an inline table",
                ));
                None
            }
        }
    }

    /// Builds a registered shape from its parameters `table` (the table at `key`, its other
    /// keys removed), with the files it read (parameter key, canonical path); `None` after a
    /// diagnostic naming the key. `other_keys` are the keys besides the shape's own that the
    /// table may hold (for suggestions).
    fn build_shape(
        &mut self,
        file: usize,
        key: &str,
        kind: &str,
        shape_type: &ShapeType,
        table: &toml::Table,
        other_keys: &[&str],
    ) -> Option<(Arc<dyn prism_api::Shape>, ReadFiles)> {
        let mut files = ShapeFiles { access: self.access.clone(), directory: self.directory(file), read: Vec::new() };
        match (shape_type.build)(table.clone(), &mut files) {
            Ok(g) => Some((g, files.read)),
            Err(e) => {
                let d = if let Some((field, expected)) = crate::diagnostics::parse_unknown_field(&e.message) {
                    // The parameter path ends with the unknown key (`components[0].centre`).
                    let inner = if e.key.is_empty() { field.clone() } else { e.key.clone() };
                    let k = format!("{key}.{inner}");
                    Diagnostic::new(self.files[file].locate(&k), format!("unknown key `{field}` for shape `{kind}`"))
                        .suggest(&field, expected.iter().map(String::as_str).chain(other_keys.iter().copied()))
                } else if e.key.is_empty() {
                    Diagnostic::new(self.files[file].locate(key), format!("shape `{kind}`: {}", e.message))
                } else {
                    let k = format!("{key}.{}", e.key);
                    Diagnostic::new(self.files[file].locate_value(&k), e.message.clone())
                };
                self.diagnostics.push(d);
                None
            }
        }
    }

    /// The CSG group `operation` written at `key` (its `table` without the keys every object
    /// or member has), with the material of each leaf; leaves without a material of their
    /// own take `inherited`. `None` after diagnostics (every member is checked).
    fn csg_group(
        &mut self,
        file: usize,
        key: &str,
        operation: CsgOperation,
        table: &toml::Table,
        inherited: &MaterialComponent,
        named: &mut Vec<MaterialComponent>,
    ) -> Option<CsgGroup> {
        let name = operation.name();
        let mut ok = true;
        for field in table.keys().filter(|k| k.as_str() != "members") {
            let d = Diagnostic::new(
                self.files[file].locate(&format!("{key}.{field}")),
                format!("unknown key `{field}` for `{name}`"),
            )
            .suggest(field, CSG_KEYS.into_iter().chain(OBJECT_KEYS));
            let d = if d.help.is_none() {
                d.with_help(format!("a `{name}` group takes `members` (an array of member tables)"))
            } else {
                d
            };
            self.diagnostics.push(d);
            ok = false;
        }
        let members = match table.get("members") {
            Some(toml::Value::Array(members)) => members,
            Some(_) => {
                let d = Diagnostic::new(
                    self.files[file].locate_value(&format!("{key}.members")),
                    "`members` must be an array of tables, one per member shape",
                );
                self.diagnostics.push(d);
                return None;
            }
            None => {
                let d = Diagnostic::new(self.files[file].locate(key), format!("`{name}` needs `members`")).with_help(
                    "an array of member tables, e.g. members = [{ shape = \"sphere\" }, { shape = \"box\" }]",
                );
                self.diagnostics.push(d);
                return None;
            }
        };
        if members.len() < operation.min_members() {
            let message = if members.is_empty() {
                format!("`{name}` has no members")
            } else {
                format!("`{name}` needs at least {} members (it has {})", operation.min_members(), members.len())
            };
            let d = Diagnostic::new(self.files[file].locate_value(&format!("{key}.members")), message);
            let d = if operation == CsgOperation::Difference {
                d.with_help("a difference subtracts every later member from the first")
            } else {
                d
            };
            self.diagnostics.push(d);
            return None;
        }
        let mut built = Vec::with_capacity(members.len());
        let mut leaves = Vec::new();
        let mut written = Vec::with_capacity(members.len());
        for (i, member) in members.iter().enumerate() {
            let member_key = format!("{key}.members[{i}]");
            match self.csg_member(file, &member_key, member, inherited, named) {
                Some((member, member_leaves, as_written)) => {
                    built.push(member);
                    leaves.extend(member_leaves);
                    written.push(as_written);
                }
                None => ok = false,
            }
        }
        if !ok {
            return None;
        }
        if leaves.len() > MAX_LEAVES as usize {
            let d = Diagnostic::new(
                self.files[file].locate(&format!("{key}.members")),
                format!("`{name}` holds {} shapes; a CSG group holds at most {MAX_LEAVES}", leaves.len()),
            );
            self.diagnostics.push(d);
            return None;
        }
        let group = CsgShape::new(operation, built);
        Some(CsgGroup { shape: Arc::new(group), leaves, members: toml::Value::Array(written) })
    }

    /// One member of a CSG group, written at `key`, with the materials of its leaves.
    fn csg_member(
        &mut self,
        file: usize,
        key: &str,
        value: &toml::Value,
        inherited: &MaterialComponent,
        named: &mut Vec<MaterialComponent>,
    ) -> Option<(CsgMember, Vec<MaterialComponent>, toml::Value)> {
        let toml::Value::Table(table) = value else {
            let d = Diagnostic::new(self.files[file].locate_value(key), "a CSG member must be a table")
                .with_help("e.g. { shape = \"sphere\", radius = 1.0 }");
            self.diagnostics.push(d);
            return None;
        };
        let mut as_written = table.clone();
        let mut table = table.clone();
        let kind = match table.remove("shape") {
            Some(toml::Value::String(kind)) => kind,
            Some(_) => {
                let d =
                    Diagnostic::new(self.files[file].locate_value(&format!("{key}.shape")), "`shape` must be a string");
                self.diagnostics.push(d);
                return None;
            }
            None => {
                let d = Diagnostic::new(self.files[file].locate(key), "missing key `shape` in a CSG member");
                self.diagnostics.push(d);
                return None;
            }
        };
        let shape_kind = self.shape_kind(file, key, &kind)?;
        for field in ["name", "parent", "no_shadow"] {
            if table.contains_key(field) {
                let d = Diagnostic::new(
                    self.files[file].locate(&format!("{key}.{field}")),
                    format!("`{field}` cannot be set on a CSG member"),
                )
                .with_help("set it on the whole group's [[object]]");
                self.diagnostics.push(d);
                return None;
            }
        }
        let transform = self.object_transform(&mut table, file, key)?;
        let material = match table.remove("material") {
            None => None,
            Some(value) => Some(self.object_material(file, key, value)?),
        };
        let inverse = self.boolean_flag(table.remove("inverse").as_ref(), file, key, "inverse").ok()?;
        // Saved as loaded: a named material by name (its table goes to [materials]), an
        // inline one with its texture paths resolved.
        match &material {
            Some(m @ MaterialComponent { name: Some(_), .. }) => named.push(m.clone()),
            Some(MaterialComponent { name: None, spec: Some(spec), .. }) => {
                as_written.insert("material".into(), toml::Value::try_from(&**spec).ok()?);
            }
            _ => {}
        }
        let own = material.as_ref().unwrap_or(inherited);
        let (shape, leaves) = match shape_kind {
            ObjectKind::Mesh => {
                let (shape, read) = self.csg_mesh_member(file, key, &table)?;
                // Saved as resolved, like a plugin's files.
                as_written.insert("file".into(), read.display().to_string().into());
                (shape, vec![own.clone()])
            }
            ObjectKind::Csg(operation) => {
                let group = self.csg_group(file, key, operation, &table, own, named)?;
                as_written.insert("members".into(), group.members);
                (group.shape, group.leaves)
            }
            ObjectKind::Plugin(shape_type) => {
                let (shape, read) = self.build_shape(file, key, &kind, shape_type, &table, &MEMBER_KEYS)?;
                // Saved as resolved, like a member's texture paths.
                for (field, path) in read {
                    as_written.insert(field, path.display().to_string().into());
                }
                (shape, vec![own.clone()])
            }
        };
        Some((CsgMember::new(shape, transform.parent_from_local(), inverse), leaves, as_written.into()))
    }

    /// What `shape = "kind"` names: a CSG operation, a registered shape or a mesh (`None`
    /// for an unknown name, which is reported at `key.shape`).
    fn shape_kind(&mut self, file: usize, key: &str, kind: &str) -> Option<ObjectKind<'a>> {
        if let Some(operation) = CsgOperation::from_name(kind) {
            return Some(ObjectKind::Csg(operation));
        }
        let registry: &'a ShapeRegistry = self.registry;
        if let Some(shape_type) = registry.get(kind) {
            return Some(ObjectKind::Plugin(shape_type));
        }
        if kind == MESH_SHAPE {
            return Some(ObjectKind::Mesh);
        }
        let csg = CsgOperation::ALL.map(CsgOperation::name);
        let d =
            Diagnostic::new(self.files[file].locate_value(&format!("{key}.shape")), format!("unknown shape `{kind}`"))
                .suggest(kind, self.registry.names().chain([MESH_SHAPE]).chain(csg));
        let d = if d.help.is_none() {
            d.with_help(format!(
                "known shapes: {}, mesh, {}",
                self.registry.names().collect::<Vec<_>>().join(", "),
                csg.join(", ")
            ))
        } else {
            d
        };
        self.diagnostics.push(d);
        None
    }

    pub(super) fn object(
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
        let Some(shape_kind) = self.shape_kind(file, &key, &kind) else { return };

        let Ok(name) = self.optional_string(&mut table, file, &key, "name", "`name` must be a string") else {
            return;
        };
        let Some(transform) = self.object_transform(&mut table, file, &key) else { return };
        let material = match table.remove("material") {
            None => Some(self.default_material.clone()),
            Some(value) => self.object_material(file, &key, value),
        };
        let Ok(parent) =
            self.optional_string(&mut table, file, &key, "parent", "`parent` must be the name of another object")
        else {
            return;
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
        let entity = match shape_kind {
            ObjectKind::Mesh => match self.mesh_object(
                world,
                MeshObject {
                    file,
                    key: &key,
                    location: &location,
                    table,
                    transform,
                    material: material.filter(|_| explicit_material),
                    flags,
                },
            ) {
                Some(entity) => entity,
                None => return,
            },
            ObjectKind::Csg(operation) => {
                let Some(material) = material else { return };
                let mut named = Vec::new();
                let Some(group) = self.csg_group(file, &key, operation, &table, &material, &mut named) else { return };
                let mut params = table;
                params.insert("members".into(), group.members);
                let shape = ShapeComponent { kind, params, geometry: group.shape, files: Vec::new() };
                let materials = CsgMaterials { leaves: group.leaves, named };
                world.spawn((shape, transform, material, flags, Origin(location.clone()), materials))
            }
            ObjectKind::Plugin(shape_type) => {
                let Some((geometry, read)) = self.build_shape(file, &key, &kind, shape_type, &table, &OBJECT_KEYS)
                else {
                    return;
                };
                let Some(material) = material else { return };
                let mut params = table;
                let mut files = Vec::with_capacity(read.len());
                for (field, path) in read {
                    params.insert(field.clone(), path.display().to_string().into());
                    files.push(field);
                }
                let shape = ShapeComponent { kind, params, geometry, files };
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
}
