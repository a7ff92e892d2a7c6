//! `[[object]]` tables: shapes built through the registry, their transforms, materials,
//! names and parents.

use super::*;

impl Loader<'_> {
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

        let Ok(name) = self.optional_string(&mut table, file, &key, "name", "`name` must be a string") else {
            return;
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
            None => Some(self.default_material.clone()),
            Some(toml::Value::String(name)) => match self.materials.get(&name) {
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
            Some(v @ toml::Value::Table(_)) => self.material(file, &format!("{key}.material"), v),
            Some(_) => {
                self.diagnostics.push(Diagnostic::new(
                    self.files[file].locate_value(&format!("{key}.material")),
                    "`material` must be the name of a [materials.NAME] table or an inline table",
                ));
                None
            }
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
        let entity = match shape_type {
            None => match self.mesh_object(
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
}
