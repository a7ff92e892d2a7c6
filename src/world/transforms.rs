//! `resolve_transforms`: parent chains to world transforms.

use std::collections::HashMap;

use glam::DAffine3;

use super::Scene;
use super::components::{Origin, Parent, Transform, WorldTransform};
use crate::diagnostics::{Diagnostic, Location, SceneError};

/// The world transform of `entity` computed directly from its `Transform` and `Parent` chain
/// (for use before [`resolve_transforms`], e.g. while loading); `None` when the chain has a
/// cycle, which `resolve_transforms` reports. Entities without a `Transform` count as the
/// identity.
pub fn world_from_local(world: &hecs::World, entity: hecs::Entity) -> Option<DAffine3> {
    let mut chain = vec![entity];
    let mut cursor = world.get::<&Parent>(entity).ok().map(|p| p.0);
    while let Some(parent) = cursor {
        if chain.contains(&parent) {
            return None;
        }
        chain.push(parent);
        cursor = world.get::<&Parent>(parent).ok().map(|p| p.0);
    }
    let mut world_from_object = DAffine3::IDENTITY;
    for e in chain.iter().rev() {
        if let Ok(t) = world.get::<&Transform>(*e) {
            world_from_object *= t.parent_from_local();
        }
    }
    Some(world_from_object)
}

/// Gives every entity with a `Transform` a `WorldTransform` (its own transform after all of
/// its ancestors'). A parent cycle is an error naming the objects in it.
pub fn resolve_transforms(scene: &mut Scene) -> Result<(), SceneError> {
    let world = &mut scene.world;
    let mut local: HashMap<hecs::Entity, (DAffine3, Option<hecs::Entity>)> = HashMap::new();
    for (entity, transform, parent) in world.query::<(hecs::Entity, &Transform, Option<&Parent>)>().iter() {
        local.insert(entity, (transform.parent_from_local(), parent.map(|p| p.0)));
    }
    let mut resolved: HashMap<hecs::Entity, DAffine3> = HashMap::new();
    let mut diagnostics = Vec::new();
    for &entity in local.keys() {
        let mut chain = vec![entity];
        let mut cursor = local[&entity].1;
        let mut cycle = false;
        while let Some(p) = cursor {
            if chain.contains(&p) {
                cycle = true;
                break;
            }
            chain.push(p);
            cursor = local.get(&p).and_then(|(_, parent)| *parent);
        }
        if cycle {
            let location =
                world.get::<&Origin>(entity).map(|o| o.0.clone()).unwrap_or_else(|_| Location::file_only("", "parent"));
            diagnostics.push(Diagnostic::new(location.child("parent"), "parent chain forms a cycle"));
            continue;
        }
        let mut world_from_object = DAffine3::IDENTITY;
        for e in chain.iter().rev() {
            world_from_object *= local.get(e).map_or(DAffine3::IDENTITY, |(m, _)| *m);
        }
        resolved.insert(entity, world_from_object);
    }
    if !diagnostics.is_empty() {
        diagnostics.sort_by_key(|d| (d.location.line, d.location.column));
        diagnostics.dedup();
        return Err(SceneError { diagnostics });
    }
    for (entity, m) in resolved {
        world.insert_one(entity, WorldTransform(m)).expect("entity exists");
    }
    Ok(())
}
