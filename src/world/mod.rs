//! The world: a hecs `World` of entities plus scene-wide settings, and the systems that run
//! over it before rendering (`resolve_transforms`, `validate`). It knows neither the scene
//! file format nor rendering.

pub mod components;
pub mod transforms;
pub mod validate;

use crate::diagnostics::{Diagnostic, Location};
use components::{Environment, RenderSettings};

/// A loaded scene.
pub struct Scene {
    /// Entities: objects (Shape, Transform, Material, flags, optional Name and Parent),
    /// lights (Light; PhotometricLight for lights imported from glTF files) and the camera
    /// (Camera).
    pub world: hecs::World,
    /// `[render]` settings.
    pub render: RenderSettings,
    /// Where `[render]` was written (for diagnostics about it).
    pub render_origin: Location,
    /// Where each top-level `[render]` key was written (the last file that set it).
    pub render_keys: components::KeyLocations,
    /// `[world]` settings.
    pub environment: Environment,
    /// The camera entity.
    pub camera: hecs::Entity,
    /// What loading skipped or approximated without failing (parts of imported files that
    /// are not rendered, glTF light ranges that are ignored), as warnings in file order.
    pub warnings: Vec<Diagnostic>,
}

impl Scene {
    /// Where `[render]` key `key` (a path such as `antialias.threshold`) was written: at its
    /// own line where the scene sets it, else at `[render]`.
    pub fn render_key(&self, key: &str) -> Location {
        self.render_keys.locate(&self.render_origin, key)
    }

    /// Where `entity` and each of its keys were written (its table, else `fallback()`), for
    /// diagnostics about it.
    pub fn entity_keys(&self, entity: hecs::Entity, fallback: impl FnOnce() -> Location) -> EntityKeys<'_> {
        let origin = self.world.get::<&components::Origin>(entity).map(|o| o.0.clone()).unwrap_or_else(|_| fallback());
        EntityKeys { origin, keys: self.world.get::<&components::KeyLocations>(entity).ok() }
    }

    /// The camera.
    pub fn camera(&self) -> components::Camera {
        self.world.get::<&components::Camera>(self.camera).map(|c| (*c).clone()).unwrap_or_default()
    }
}

/// Where an entity and each of its keys were written ([`Scene::entity_keys`]).
pub struct EntityKeys<'a> {
    origin: Location,
    keys: Option<hecs::Ref<'a, components::KeyLocations>>,
}

impl EntityKeys<'_> {
    /// Where `key` was written: at its own line, or at the entity's table when it was not.
    pub fn child(&self, key: &str) -> Location {
        match &self.keys {
            Some(keys) => keys.locate(&self.origin, key),
            None => self.origin.child(key),
        }
    }
}
