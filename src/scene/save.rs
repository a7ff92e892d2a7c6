//! `save`: the inverse of `load`. Writes a world back as one self-contained TOML scene
//! (includes are flattened) that loads to the identical image.
//!
//! Mesh, texture and shape files (a text's font) are written as absolute paths ([`save`]), or relative to the
//! directory of the file being written ([`save_for`]) when such a path exists. What a mesh file
//! brings (nodes, parts, imported lights and camera) is not written: the mesh object's keys
//! (`import_lights`, `import_camera`) recreate it on load.

use std::collections::BTreeMap;
use std::path::{Component, Path, PathBuf};
use std::sync::Arc;

use crate::import::spawn::MESH_SHAPE;
use crate::import::{Imported, MeshSource};
use crate::material::MaterialSpec;
use crate::world::Scene;
use crate::world::components::{
    CsgMaterials, ImportedCamera, Light, MaterialComponent, Name, ObjectFlags, Parent, ShapeComponent, Transform,
};

/// The scene as TOML text, with absolute file paths (the text loads wherever it is written).
pub fn save(scene: &Scene) -> Result<String, toml::ser::Error> {
    write_scene(scene, &FilePaths::Absolute)
}

/// The scene as TOML text to be written to `output`: mesh and texture paths are relative to
/// `output`'s directory when a relative path exists (absolute otherwise, e.g. on another
/// drive), so the written file loads to the identical image.
pub fn save_for(scene: &Scene, output: &Path) -> Result<String, toml::ser::Error> {
    let directory = output.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new("."));
    let base = std::fs::canonicalize(directory).or_else(|_| std::path::absolute(directory)).ok();
    match base {
        Some(base) => write_scene(scene, &FilePaths::RelativeTo(base)),
        None => write_scene(scene, &FilePaths::Absolute),
    }
}

/// How file paths (held absolute in the world) are written.
enum FilePaths {
    /// As they are.
    Absolute,
    /// Relative to this absolute directory when possible.
    RelativeTo(PathBuf),
}

impl FilePaths {
    fn write(&self, absolute: &str) -> String {
        match self {
            FilePaths::Absolute => absolute.to_string(),
            FilePaths::RelativeTo(base) => match relative_path(Path::new(absolute), base) {
                Some(relative) => relative.display().to_string(),
                None => absolute.to_string(),
            },
        }
    }

    /// `material` as a TOML value with its texture paths written this way.
    fn material(&self, material: &MaterialSpec) -> Result<toml::Value, toml::ser::Error> {
        let mut material = material.clone();
        for (texture, _) in material.textures_mut() {
            texture.file = self.write(&texture.file);
        }
        for (_, map, _) in material.image_maps_mut() {
            if let Some(path) = &map.path {
                map.file = self.write(&path.display().to_string());
            }
        }
        toml::Value::try_from(&material)
    }
}

/// The path leading from directory `base` to `target` (both absolute), with `..` where it
/// climbs; `None` when there is none (a relative argument, another drive or root).
pub fn relative_path(target: &Path, base: &Path) -> Option<PathBuf> {
    if !target.is_absolute() || !base.is_absolute() {
        return None;
    }
    let target: Vec<Component> = target.components().collect();
    let base: Vec<Component> = base.components().collect();
    // The root (and on Windows the drive) must agree.
    let roots = |c: &&Component| matches!(c, Component::Prefix(_) | Component::RootDir);
    if target.iter().take_while(roots).ne(base.iter().take_while(roots)) {
        return None;
    }
    if base.iter().any(|c| matches!(c, Component::ParentDir)) {
        return None;
    }
    let common = target.iter().zip(&base).take_while(|(a, b)| a == b).count();
    let mut out = PathBuf::new();
    for _ in common..base.len() {
        out.push("..");
    }
    for c in &target[common..] {
        out.push(c.as_os_str());
    }
    if out.as_os_str().is_empty() {
        out.push(".");
    }
    Some(out)
}

fn write_scene(scene: &Scene, paths: &FilePaths) -> Result<String, toml::ser::Error> {
    let mut doc = toml::Table::new();
    doc.insert("render".into(), toml::Value::try_from(&scene.render)?);
    doc.insert("camera".into(), camera_table(scene)?);
    doc.insert("world".into(), toml::Value::try_from(&scene.environment)?);

    let mut objects: Vec<(hecs::Entity, toml::Table)> = Vec::new();
    let mut materials: BTreeMap<String, Arc<MaterialSpec>> = BTreeMap::new();
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
        common.write(scene, paths, &mut t, &mut materials)?;
        for (k, v) in &shape.params {
            let v = match v.as_str() {
                Some(path) if shape.files.contains(k) => paths.write(path).into(),
                _ => v.clone(),
            };
            t.insert(k.clone(), v);
        }
        // CSG members name their materials in `members`; the tables go to [materials].
        if let Ok(csg) = scene.world.get::<&CsgMaterials>(entity) {
            for m in &csg.named {
                if let (Some(name), Some(spec)) = (&m.name, &m.spec) {
                    materials.insert(name.clone(), spec.clone());
                }
            }
        }
        objects.push((entity, t));
    }
    let mut meshes =
        scene.world.query::<(hecs::Entity, &MeshSource, &Transform, &ObjectFlags, Option<&Name>, Option<&Parent>)>();
    for (entity, source, transform, flags, name, parent) in meshes.iter() {
        let mut t = toml::Table::new();
        t.insert("shape".into(), MESH_SHAPE.into());
        t.insert("file".into(), paths.write(&source.file).into());
        let common = CommonKeys { name, material: source.material.as_ref(), transform, parent, flags };
        common.write(scene, paths, &mut t, &mut materials)?;
        if !source.material_map.is_empty() {
            let mut map = toml::Table::new();
            for (file_name, component) in &source.material_map {
                let Some(spec) = &component.spec else { continue };
                let value = match &component.name {
                    Some(n) => {
                        materials.insert(n.clone(), spec.clone());
                        n.clone().into()
                    }
                    None => paths.material(spec)?,
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
    // Lights imported from mesh files come back with their object's `import_lights`.
    for (entity, light) in scene.world.query::<(hecs::Entity, &Light)>().without::<&Imported>().iter() {
        let toml::Value::Table(all) = toml::Value::try_from(light)? else {
            unreachable!("a struct serialises to a table")
        };
        let t = all.into_iter().filter(|(k, _)| k == "kind" || light.kind.accepts(k)).collect();
        lights.push((entity, t));
    }
    lights.sort_by_key(|(e, _)| e.id());

    if !materials.is_empty() {
        let mut table = toml::Table::new();
        for (name, m) in materials {
            table.insert(name, paths.material(&m)?);
        }
        doc.insert("materials".into(), table.into());
    }
    // Serialised one top-level key, and one `[[object]]` or `[[light]]`, at a time (in the
    // order toml writes them): toml's serialiser is quadratic in the length of an array of
    // tables.
    if !objects.is_empty() {
        doc.insert("object".into(), toml::Value::Array(Vec::new()));
    }
    if !lights.is_empty() {
        doc.insert("light".into(), toml::Value::Array(Vec::new()));
    }
    let mut arrays = [("object", objects), ("light", lights)];
    let mut pieces = Vec::new();
    for (key, value) in doc {
        match arrays.iter_mut().find(|(k, _)| *k == key) {
            Some((_, tables)) => {
                for (_, table) in std::mem::take(tables) {
                    let mut one = toml::Table::new();
                    one.insert(key.clone(), toml::Value::Array(vec![table.into()]));
                    pieces.push(toml::to_string_pretty(&one)?);
                }
            }
            None => {
                let mut one = toml::Table::new();
                one.insert(key, value);
                pieces.push(toml::to_string_pretty(&one)?);
            }
        }
    }
    let body = pieces.join("\n");
    Ok(format!("# Written by `prism save`: a self-contained copy of the scene (includes flattened).\n\n{body}"))
}

/// `[camera]`: every setting, or for a camera imported from a mesh file (which its object's
/// `import_camera` recreates) only the lens.
fn camera_table(scene: &Scene) -> Result<toml::Value, toml::ser::Error> {
    let camera = scene.camera();
    if scene.world.get::<&ImportedCamera>(scene.camera).is_err() {
        return toml::Value::try_from(camera);
    }
    let mut lens = toml::Table::new();
    lens.insert("aperture".into(), camera.aperture.into());
    if let Some(f) = camera.focal_distance {
        lens.insert("focal_distance".into(), f.into());
    }
    if let Some(v) = camera.blur_variance {
        lens.insert("blur_variance".into(), v.into());
    }
    if let Some(c) = camera.blur_confidence {
        lens.insert("blur_confidence".into(), c.into());
    }
    if let Some(m) = camera.blur_min_samples {
        lens.insert("blur_min_samples".into(), i64::from(m).into());
    }
    Ok(lens.into())
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
        paths: &FilePaths,
        table: &mut toml::Table,
        materials: &mut BTreeMap<String, Arc<MaterialSpec>>,
    ) -> Result<(), toml::ser::Error> {
        if let Some(name) = self.name {
            table.insert("name".into(), name.0.clone().into());
        }
        // A material without an authored form (a mesh file's own) is recreated by loading.
        match self.material {
            Some(MaterialComponent { name: Some(n), spec: Some(spec), .. }) => {
                materials.insert(n.clone(), spec.clone());
                table.insert("material".into(), n.clone().into());
            }
            Some(MaterialComponent { name: None, spec: Some(spec), .. }) => {
                table.insert("material".into(), paths.material(spec)?);
            }
            Some(MaterialComponent { spec: None, .. }) | None => {}
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn relative_paths_climb_and_descend() {
        let rel = |t: &str, b: &str| relative_path(Path::new(t), Path::new(b)).map(|p| p.display().to_string());
        assert_eq!(rel("/a/b/mesh.glb", "/a/b").as_deref(), Some("mesh.glb"));
        assert_eq!(rel("/a/b/c/mesh.glb", "/a/b").as_deref(), Some("c/mesh.glb"));
        assert_eq!(rel("/a/x/mesh.glb", "/a/b/c").as_deref(), Some("../../x/mesh.glb"));
        assert_eq!(rel("/mesh.glb", "/a").as_deref(), Some("../mesh.glb"));
        assert_eq!(rel("mesh.glb", "/a"), None);
        assert_eq!(rel("/a/mesh.glb", "a"), None);
    }
}
