//! `resolve_transforms`: parent chains to world transforms.

use std::collections::{HashMap, HashSet};

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
    // Each entity is resolved once, from its parent's resolved transform (walking up only
    // to the nearest resolved ancestor), so the work is linear in the number of entities
    // however deep the chains. The product is formed root first, as a walk of the whole
    // chain would.
    let mut resolved: HashMap<hecs::Entity, Option<DAffine3>> = HashMap::with_capacity(local.len());
    let mut diagnostics = Vec::new();
    let mut path: Vec<hecs::Entity> = Vec::new();
    let mut on_path: HashSet<hecs::Entity> = HashSet::new();
    for &entity in local.keys() {
        if resolved.contains_key(&entity) {
            continue;
        }
        path.clear();
        on_path.clear();
        let mut cursor = Some(entity);
        // The transform above the path's top, or None when the walk met a cycle.
        let mut above = Some(DAffine3::IDENTITY);
        while let Some(e) = cursor {
            if let Some(known) = resolved.get(&e) {
                above = *known;
                break;
            }
            if !on_path.insert(e) {
                above = None;
                break;
            }
            path.push(e);
            cursor = local.get(&e).and_then(|(_, parent)| *parent);
        }
        for &e in path.iter().rev() {
            above = above.map(|m| m * local.get(&e).map_or(DAffine3::IDENTITY, |(t, _)| *t));
            resolved.insert(e, above);
        }
    }
    for (&entity, m) in &resolved {
        if m.is_none() && local.contains_key(&entity) {
            let location =
                world.get::<&Origin>(entity).map(|o| o.0.clone()).unwrap_or_else(|_| Location::file_only("", "parent"));
            diagnostics.push(Diagnostic::new(location.child("parent"), "parent chain forms a cycle"));
        }
    }
    let resolved: Vec<(hecs::Entity, DAffine3)> =
        resolved.into_iter().filter_map(|(e, m)| Some((e, m?))).filter(|(e, _)| local.contains_key(e)).collect();
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
