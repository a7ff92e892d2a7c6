//! `extract`: the hecs world to an immutable, `Send + Sync` render scene: primitives with
//! both transforms, materials, lights (with the table from primitives to the area emitters),
//! the camera and the acceleration structure.

use super::camera::RenderCamera;
use super::filter::FilterSampler;
use super::lights::{RenderLight, SceneLights};
use super::sampling::PatternTable;
use crate::accel::primitive::Primitive;
use crate::accel::scene_bvh::Accel;
use std::collections::HashMap;
use std::sync::Arc;

use crate::material::Material;
use crate::material::pov_view::PovView;
use crate::world::Scene;
use crate::world::components::{
    Environment, Light, MaterialComponent, ObjectFlags, PhotometricLight, RenderSettings, ShapeComponent,
    WorldTransform,
};

/// Everything a render needs, immutable and shareable across threads.
pub struct RenderScene {
    /// Shape instances.
    pub primitives: Vec<Primitive>,
    /// Materials, indexed by `Primitive::material`: one per shared material (`Arc`), in the
    /// order primitives first use them (load order).
    pub materials: Vec<Material>,
    /// Light sources, area emitters and the environment.
    pub lights: SceneLights,
    /// The camera.
    pub camera: RenderCamera,
    /// Render settings.
    pub settings: RenderSettings,
    /// Background and ambient light.
    pub environment: Environment,
    /// Ray queries.
    pub accel: Accel,
    /// True when any material lets light through (shadow rays must then look at every hit).
    pub has_transparency: bool,
    /// Stratified pixel and lens patterns.
    pub patterns: PatternTable,
    /// Draws sample offsets for a non-box pixel filter.
    pub filter: Option<FilterSampler>,
}

impl RenderScene {
    /// Sets the samples per pixel and remakes the stratified patterns for that count: the
    /// scene then renders exactly as one extracted with that count.
    pub fn set_samples(&mut self, samples: u32) {
        self.settings.samples = samples;
        self.patterns = patterns_for(&self.settings, self.camera.aperture);
    }
}

/// The pixel and lens patterns of `settings.samples` points per pixel (none under adaptive
/// sampling, whose pixels draw progressive patterns of their own).
fn patterns_for(settings: &RenderSettings, aperture: f64) -> PatternTable {
    let samples = settings.samples;
    if (samples > 1 || aperture > 0.0) && settings.noise.is_none() {
        PatternTable::new(samples, settings.seed)
    } else {
        PatternTable::untabulated(samples)
    }
}

/// Builds the render scene. Call after `resolve_transforms` and `validate`.
pub fn extract(scene: &Scene) -> RenderScene {
    let mut entries: Vec<(hecs::Entity, Primitive, Arc<Material>)> = Vec::new();
    let mut query =
        scene
            .world
            .query::<(hecs::Entity, &ShapeComponent, &WorldTransform, &MaterialComponent, Option<&ObjectFlags>)>();
    for (entity, shape, transform, material, flags) in query.iter() {
        let primitive = Primitive::new(shape.geometry.clone(), transform.0, 0, flags.is_some_and(|f| f.no_shadow));
        entries.push((entity, primitive, material.material.clone()));
    }
    // Entity order is load order: the render scene does not depend on hecs's archetypes.
    entries.sort_by_key(|(e, _, _)| e.id());
    let mut primitives = Vec::with_capacity(entries.len());
    let mut materials: Vec<Material> = Vec::new();
    // Keyed by the shared allocation; ids follow first use, so hash order never matters.
    let mut ids: HashMap<*const Material, usize> = HashMap::new();
    for (_, mut primitive, material) in entries {
        let index = *ids.entry(Arc::as_ptr(&material)).or_insert_with(|| {
            materials.push(Material::clone(&material));
            materials.len() - 1
        });
        primitive.material = index as u32;
        primitives.push(primitive);
    }

    let mut lights: Vec<(hecs::Entity, RenderLight)> =
        scene.world.query::<(hecs::Entity, &Light)>().iter().map(|(e, l)| (e, RenderLight::from_scene(l))).collect();
    let mut imported = scene.world.query::<(hecs::Entity, &PhotometricLight)>();
    lights.extend(imported.iter().map(|(e, l)| (e, RenderLight::from_photometric(l))));
    lights.sort_by_key(|(e, _)| e.id());
    let sources = lights.into_iter().map(|(_, l)| l).collect();
    let lights = SceneLights::new(sources, &primitives, &materials, &scene.environment);

    let accel = Accel::build(&primitives);
    let has_transparency = materials.iter().any(|m| PovView::new(m).base.is_transparent());
    let camera = RenderCamera::new(&scene.camera(), scene.render.width, scene.render.height);
    let patterns = patterns_for(&scene.render, camera.aperture);
    RenderScene {
        camera,
        primitives,
        materials,
        lights,
        settings: scene.render.clone(),
        environment: scene.environment.clone(),
        accel,
        has_transparency,
        patterns,
        filter: FilterSampler::new(scene.render.filter),
    }
}

#[cfg(test)]
mod tests {
    use crate::scene::load::{Embedded, load_from};

    #[test]
    fn objects_naming_one_material_share_its_id() {
        const SCENE: Embedded = Embedded(&[(
            "s.toml",
            "[materials.red]\ncolor = [1, 0, 0]\n\
             [[object]]\nshape = \"sphere\"\nmaterial = \"red\"\n\
             [[object]]\nshape = \"sphere\"\nmaterial = { color = [1, 0, 0] }\n\
             [[object]]\nshape = \"sphere\"\nmaterial = \"red\"\n\
             [[object]]\nshape = \"sphere\"\n\
             [[object]]\nshape = \"sphere\"\n",
        )]);
        let mut scene = load_from(&SCENE, std::path::Path::new("s.toml"), &crate::plugins::registry()).unwrap();
        let scene = crate::prepare(&mut scene).unwrap();
        let ids: Vec<u32> = scene.primitives.iter().map(|p| p.material).collect();
        // The named material once, the inline table on its own, one default for the rest.
        assert_eq!(ids, [0, 1, 0, 2, 2]);
        assert_eq!(scene.materials.len(), 3);
        assert_eq!(scene.materials[0], scene.materials[1]);
    }
}
