//! A `shape = "mesh"` object in the hecs world: a root entity that remembers what the scene
//! said ([`MeshSource`]), one entity per node of the file's tree and one per mesh part. Parts
//! share the imported geometry (`Arc`), so a file used N times costs its memory once.

use std::sync::Arc;

use glam::{DAffine3, DMat4};

use super::{Imported, MeshSource, Model};
use crate::diagnostics::Location;
use crate::world::components::{MaterialComponent, ObjectFlags, Origin, Parent, ShapeComponent, Transform};

/// The `shape` name of mesh objects.
pub const MESH_SHAPE: &str = "mesh";

/// Keys of a mesh object besides the common object keys.
pub const MESH_KEYS: [&str; 5] = ["file", "smooth_angle", "material_map", "import_lights", "import_camera"];

/// The entities a mesh object became.
#[derive(Clone, Debug)]
pub struct SpawnedModel {
    /// The object's own entity (the one names, parents and saving refer to).
    pub root: hecs::Entity,
    /// One entity per node of [`Model::nodes`], in the same order.
    pub nodes: Vec<hecs::Entity>,
}

/// A transform component holding `m` as a matrix (or nothing for the identity).
pub fn transform_of(m: &DAffine3) -> Transform {
    if *m == DAffine3::IDENTITY {
        return Transform::default();
    }
    let rows = DMat4::from(*m).transpose().to_cols_array_2d();
    Transform { matrix: Some(rows), ..Transform::default() }
}

/// Spawns the root entity of a mesh object and its imported descendants (nodes and parts).
pub fn spawn_model(
    world: &mut hecs::World,
    source: MeshSource,
    transform: Transform,
    flags: ObjectFlags,
    origin: &Location,
) -> SpawnedModel {
    let model: Arc<Model> = source.model.clone();
    let material_override = source.material.clone();
    let material_map = source.material_map.clone();
    let root = world.spawn((source, transform, flags, Origin(origin.clone())));
    let mut nodes = Vec::with_capacity(model.nodes.len());
    for node in &model.nodes {
        let parent = node.parent.map_or(root, |p| nodes[p]);
        let entity = world.spawn((transform_of(&node.local), Parent(parent), Imported, Origin(origin.clone())));
        nodes.push(entity);
    }
    for part in &model.parts {
        let replaced = material_override
            .clone()
            .or_else(|| part.material_name.as_ref().and_then(|n| material_map.get(n).cloned()));
        // A replacement drops the file material's cut-outs and normal maps too.
        let geometry: Arc<dyn prism_api::Shape> = if replaced.is_some() {
            Arc::new(super::MeshShape::new(part.shape.data().clone()))
        } else {
            part.shape.clone()
        };
        let material =
            replaced.unwrap_or_else(|| MaterialComponent { name: None, spec: None, material: part.material.clone() });
        let shape =
            ShapeComponent { kind: MESH_SHAPE.to_string(), params: toml::Table::new(), geometry, files: Vec::new() };
        world.spawn((
            shape,
            Transform::default(),
            Parent(nodes[part.node]),
            material,
            flags,
            Imported,
            Origin(origin.clone()),
        ));
    }
    SpawnedModel { root, nodes }
}
