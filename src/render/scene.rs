//! `extract`: the hecs world to an immutable, `Send + Sync` render scene: primitives with
//! both transforms, materials, lights, the camera and the acceleration structure.

use std::sync::Arc;

use glam::{DAffine3, DMat3, DVec3};
use prism_api::{Aabb, Ray, Shape};

use super::accel::Accel;
use super::camera::RenderCamera;
use crate::material::Material;
use crate::scene::Scene;
use crate::scene::components::{
    Environment, Light, LightKind, MaterialComponent, ObjectFlags, RenderSettings, ShapeComponent, WorldTransform,
};

/// One shape instance in world space.
#[derive(Clone, Debug)]
pub struct Primitive {
    /// The geometry in object space.
    pub shape: Arc<dyn Shape>,
    /// Object to world.
    pub world_from_object: DAffine3,
    /// World to object.
    pub object_from_world: DAffine3,
    /// Maps object-space normals to world space (inverse transpose).
    pub normal_to_world: DMat3,
    /// True when the transform is the identity (the ray needs no transforming).
    pub identity: bool,
    /// Bounds in world space (infinite for unbounded shapes).
    pub world_bounds: Aabb,
    /// Index into the scene's materials.
    pub material: u32,
    /// Casts no shadow.
    pub no_shadow: bool,
}

impl Primitive {
    /// `ray` in this primitive's object space (direction not renormalised, so t is shared).
    #[inline]
    pub fn object_ray(&self, ray: &Ray) -> Ray {
        if self.identity {
            *ray
        } else {
            Ray::new(self.object_point(ray.origin), self.object_from_world.transform_vector3(ray.direction))
        }
    }

    /// The world point `p` in this primitive's object space.
    #[inline]
    pub fn object_point(&self, p: DVec3) -> DVec3 {
        if self.identity { p } else { self.object_from_world.transform_point3(p) }
    }
}

/// A light ready for shading.
#[derive(Clone, Debug)]
pub struct RenderLight {
    /// The light as described in the scene.
    pub kind: LightKind,
    /// Centre.
    pub position: DVec3,
    /// Colour times intensity.
    pub color: DVec3,
    /// Fade distance and power (POV-Ray semantics).
    pub fade_distance: f64,
    /// See `fade_distance`.
    pub fade_power: f64,
    /// No shadows, no highlights.
    pub shadowless: bool,
    /// Unit axis for spot and parallel lights (from the light toward point_at).
    pub axis: DVec3,
    /// Spot parameters: cos(radius), cos(falloff), tightness. `None` for non-spot lights.
    pub spot: Option<(f64, f64, f64)>,
    /// Area grid: axis vectors and sample counts, POV-Ray flags.
    pub area: Option<AreaGrid>,
}

/// The grid of an area light.
#[derive(Clone, Debug)]
pub struct AreaGrid {
    /// First edge.
    pub axis1: DVec3,
    /// Second edge.
    pub axis2: DVec3,
    /// Samples along axis1.
    pub size1: u32,
    /// Samples along axis2.
    pub size2: u32,
    /// Levels always subdivided.
    pub adaptive: u32,
    /// Jittered sample positions.
    pub jitter: bool,
    /// Grid mapped to a disc.
    pub circular: bool,
    /// Grid turned toward each shaded point.
    pub orient: bool,
    /// The weight of each grid sample (row-major, `size1` per row) when `adaptive` is deep
    /// enough that POV-Ray's recursive average always subdivides down to neighbouring
    /// samples: the average is then this fixed weighted sum. `None` when the recursion
    /// depends on the samples.
    pub fixed_weights: Option<Vec<f64>>,
}

impl AreaGrid {
    /// The sample weights of POV-Ray's hierarchical average when it never depends on the
    /// samples, or `None`. The recursion mirrors `classic::block`: a block whose corners
    /// are further apart than neighbours splits into four at its midpoints (sharing the
    /// middle row and column when the span is even), and a block that no longer splits
    /// gives each of its four corners a quarter of its weight.
    pub fn fixed_weights(size1: u32, size2: u32, adaptive: u32) -> Option<Vec<f64>> {
        fn split(
            weights: &mut [f64],
            n1: usize,
            (u1, v1, u2, v2): (usize, usize, usize, usize),
            level: u32,
            adaptive: u32,
            weight: f64,
        ) -> bool {
            let large = u2 - u1 > 1 || v2 - v1 > 1;
            if !large {
                for (u, v) in [(u1, v1), (u2, v1), (u1, v2), (u2, v2)] {
                    weights[v * n1 + u] += 0.25 * weight;
                }
                return true;
            }
            if level >= adaptive {
                return false;
            }
            let (lo_u, lo_v) = ((u1 + u2) / 2, (v1 + v2) / 2);
            let (hi_u, hi_v) = ((u1 + u2).div_ceil(2), (v1 + v2).div_ceil(2));
            let quarter = 0.25 * weight;
            [(u1, v1, lo_u, lo_v), (hi_u, v1, u2, lo_v), (u1, hi_v, lo_u, v2), (hi_u, hi_v, u2, v2)]
                .into_iter()
                .all(|block| split(weights, n1, block, level + 1, adaptive, quarter))
        }
        let (n1, n2) = (size1.max(1) as usize, size2.max(1) as usize);
        let mut weights = vec![0.0; n1 * n2];
        split(&mut weights, n1, (0, 0, n1 - 1, n2 - 1), 0, adaptive, 1.0).then_some(weights)
    }
}

/// Everything a render needs, immutable and shareable across threads.
pub struct RenderScene {
    /// Shape instances.
    pub primitives: Vec<Primitive>,
    /// Materials, indexed by `Primitive::material`.
    pub materials: Vec<Material>,
    /// Lights.
    pub lights: Vec<RenderLight>,
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
}

/// Builds the render scene. Call after `resolve_transforms` and `validate`.
pub fn extract(scene: &Scene) -> RenderScene {
    let mut entries: Vec<(hecs::Entity, Primitive, Material)> = Vec::new();
    let mut query =
        scene
            .world
            .query::<(hecs::Entity, &ShapeComponent, &WorldTransform, &MaterialComponent, Option<&ObjectFlags>)>();
    for (entity, shape, transform, material, flags) in query.iter() {
        let world_from_object = transform.0;
        let object_from_world = world_from_object.inverse();
        let identity = world_from_object == DAffine3::IDENTITY;
        let primitive = Primitive {
            shape: shape.geometry.clone(),
            world_from_object,
            object_from_world,
            normal_to_world: object_from_world.matrix3.transpose(),
            identity,
            world_bounds: shape.geometry.bounds().transformed(&world_from_object),
            material: 0,
            no_shadow: flags.is_some_and(|f| f.no_shadow),
        };
        entries.push((entity, primitive, material.material.clone()));
    }
    // Entity order is load order: the render scene does not depend on hecs's archetypes.
    entries.sort_by_key(|(e, _, _)| e.id());
    let mut primitives = Vec::with_capacity(entries.len());
    let mut materials: Vec<Material> = Vec::new();
    for (_, mut primitive, material) in entries {
        let index = match materials.iter().position(|m| *m == material) {
            Some(i) => i,
            None => {
                materials.push(material);
                materials.len() - 1
            }
        };
        primitive.material = index as u32;
        primitives.push(primitive);
    }

    let mut lights: Vec<(hecs::Entity, RenderLight)> =
        scene.world.query::<(hecs::Entity, &Light)>().iter().map(|(e, l)| (e, render_light(l))).collect();
    lights.sort_by_key(|(e, _)| e.id());

    let accel = Accel::build(&primitives);
    let has_transparency = materials.iter().any(Material::is_transparent);
    RenderScene {
        camera: RenderCamera::new(&scene.camera(), scene.render.width, scene.render.height),
        primitives,
        materials,
        lights: lights.into_iter().map(|(_, l)| l).collect(),
        settings: scene.render.clone(),
        environment: scene.environment.clone(),
        accel,
        has_transparency,
    }
}

fn render_light(light: &Light) -> RenderLight {
    let position = DVec3::from_array(light.position);
    let point_at = DVec3::from_array(light.point_at);
    let axis = (point_at - position).normalize_or(DVec3::NEG_Y);
    let is_spot = light.kind == LightKind::Spot || (light.kind == LightKind::Area && light.spot);
    RenderLight {
        kind: light.kind,
        position,
        color: light.color.0 * light.intensity,
        fade_distance: light.fade_distance,
        fade_power: light.fade_power,
        shadowless: light.shadowless,
        axis,
        spot: is_spot.then(|| (light.radius.to_radians().cos(), light.falloff.to_radians().cos(), light.tightness)),
        area: (light.kind == LightKind::Area).then(|| AreaGrid {
            axis1: DVec3::from_array(light.axis1),
            axis2: DVec3::from_array(light.axis2),
            size1: light.size1,
            size2: light.size2,
            adaptive: light.adaptive,
            jitter: light.jitter,
            // POV-Ray makes an oriented area light circular.
            circular: light.circular || light.orient,
            orient: light.orient,
            fixed_weights: AreaGrid::fixed_weights(light.size1, light.size2, light.adaptive),
        }),
    }
}
