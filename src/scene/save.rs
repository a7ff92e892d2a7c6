//! `save`: the inverse of `load`. Writes a world back as one self-contained TOML scene
//! (includes are flattened) that loads to the identical image.

use std::collections::BTreeMap;

use super::Scene;
use super::components::{Light, MaterialComponent, Name, ObjectFlags, Parent, ShapeComponent, Transform};
use crate::material::Material;
use crate::mesh::spawn::MESH_SHAPE;
use crate::mesh::{Imported, MeshSource};

/// The scene as TOML text.
pub fn save(scene: &Scene) -> Result<String, toml::ser::Error> {
    let mut doc = toml::Table::new();
    doc.insert("render".into(), toml::Value::try_from(&scene.render)?);
    doc.insert("camera".into(), toml::Value::try_from(scene.camera())?);
    doc.insert("world".into(), toml::Value::try_from(&scene.environment)?);

    let mut objects: Vec<(hecs::Entity, toml::Table)> = Vec::new();
    let mut materials: BTreeMap<String, Material> = BTreeMap::new();
    let query = scene.world.query::<(
        hecs::Entity,
        &ShapeComponent,
        &Transform,
        &MaterialComponent,
        &ObjectFlags,
        Option<&Name>,
        Option<&Parent>,
    )>();
    // Parts and nodes imported from mesh files are recreated by loading the file again.
    for (entity, shape, transform, material, flags, name, parent) in query.without::<&Imported>().iter() {
        let mut t = toml::Table::new();
        t.insert("shape".into(), shape.kind.clone().into());
        let common = CommonKeys { name, material: Some(material), transform, parent, flags };
        common.write(scene, &mut t, &mut materials)?;
        for (k, v) in &shape.params {
            t.insert(k.clone(), v.clone());
        }
        objects.push((entity, t));
    }
    let mut meshes =
        scene.world.query::<(hecs::Entity, &MeshSource, &Transform, &ObjectFlags, Option<&Name>, Option<&Parent>)>();
    for (entity, source, transform, flags, name, parent) in meshes.iter() {
        let mut t = toml::Table::new();
        t.insert("shape".into(), MESH_SHAPE.into());
        t.insert("file".into(), source.file.clone().into());
        let common = CommonKeys { name, material: source.material.as_ref(), transform, parent, flags };
        common.write(scene, &mut t, &mut materials)?;
        if !source.material_map.is_empty() {
            let mut map = toml::Table::new();
            for (file_name, component) in &source.material_map {
                let value = match &component.name {
                    Some(n) => {
                        materials.insert(n.clone(), component.material.clone());
                        n.clone().into()
                    }
                    None => toml::Value::try_from(&component.material)?,
                };
                map.insert(file_name.clone(), value);
            }
            t.insert("material_map".into(), map.into());
        }
        for (k, v) in &source.params {
            t.insert(k.clone(), v.clone());
        }
        objects.push((entity, t));
    }
    objects.sort_by_key(|(e, _)| e.id());

    let mut lights: Vec<(hecs::Entity, toml::Table)> = Vec::new();
    for (entity, light) in scene.world.query::<(hecs::Entity, &Light)>().iter() {
        let toml::Value::Table(all) = toml::Value::try_from(light)? else {
            unreachable!("a struct serialises to a table")
        };
        let allowed = light.kind.allowed_keys();
        let t = all.into_iter().filter(|(k, _)| k == "kind" || allowed.contains(&k.as_str())).collect();
        lights.push((entity, t));
    }
    lights.sort_by_key(|(e, _)| e.id());

    if !materials.is_empty() {
        let mut table = toml::Table::new();
        for (name, m) in materials {
            table.insert(name, toml::Value::try_from(&m)?);
        }
        doc.insert("materials".into(), table.into());
    }
    let objects: Vec<toml::Value> = objects.into_iter().map(|(_, t)| t.into()).collect();
    if !objects.is_empty() {
        doc.insert("object".into(), objects.into());
    }
    let lights: Vec<toml::Value> = lights.into_iter().map(|(_, t)| t.into()).collect();
    if !lights.is_empty() {
        doc.insert("light".into(), lights.into());
    }
    let body = toml::to_string_pretty(&doc)?;
    Ok(format!("# Written by `prism save`: a self-contained copy of the scene (includes flattened).\n\n{body}"))
}

/// The keys every `[[object]]` shares: name, material, transform, parent, no_shadow.
struct CommonKeys<'a> {
    name: Option<&'a Name>,
    material: Option<&'a MaterialComponent>,
    transform: &'a Transform,
    parent: Option<&'a Parent>,
    flags: &'a ObjectFlags,
}

impl CommonKeys<'_> {
    /// Writes the keys into `table`; named materials are collected into `materials`.
    fn write(
        &self,
        scene: &Scene,
        table: &mut toml::Table,
        materials: &mut BTreeMap<String, Material>,
    ) -> Result<(), toml::ser::Error> {
        if let Some(name) = self.name {
            table.insert("name".into(), name.0.clone().into());
        }
        match self.material {
            Some(MaterialComponent { name: Some(n), material }) => {
                materials.insert(n.clone(), material.clone());
                table.insert("material".into(), n.clone().into());
            }
            Some(MaterialComponent { name: None, material }) => {
                table.insert("material".into(), toml::Value::try_from(material)?);
            }
            None => {}
        }
        if !self.transform.is_identity() {
            table.insert("transform".into(), toml::Value::try_from(self.transform)?);
        }
        if let Some(parent) = self.parent
            && let Ok(parent_name) = scene.world.get::<&Name>(parent.0)
        {
            table.insert("parent".into(), parent_name.0.clone().into());
        }
        if self.flags.no_shadow {
            table.insert("no_shadow".into(), true.into());
        }
        Ok(())
    }
}
