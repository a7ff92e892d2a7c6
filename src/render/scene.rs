//! `extract`: the hecs world to an immutable, `Send + Sync` render scene: primitives with
//! both transforms, materials, lights, the camera and the acceleration structure.

use std::sync::Arc;

use glam::{DAffine3, DMat3, DVec3};
use prism_api::{Aabb, Hit, Ray, Shape};

use super::accel::Accel;
use super::camera::RenderCamera;
use super::sampling::PatternTable;
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
    /// The kind of transform, which picks the cheapest exact way to apply it.
    pub placement: Placement,
    /// Bounds in world space (infinite for unbounded shapes).
    pub world_bounds: Aabb,
    /// Index into the scene's materials.
    pub material: u32,
    /// Casts no shadow.
    pub no_shadow: bool,
}

/// What kind of map a primitive's world-from-object transform is. Most scene objects are
/// only moved, and a ray tested against each of them on every query need not pay for two
/// matrix products: the special cases give bit-identical results to the general one.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Placement {
    /// Object space is world space.
    Identity,
    /// World = object + this offset: points move, directions and normals do not.
    Translation(DVec3),
    /// Any other affine map: the matrices apply.
    Affine,
}

impl Placement {
    /// The placement of `world_from_object`.
    pub fn of(world_from_object: &DAffine3) -> Self {
        if world_from_object.matrix3 != DMat3::IDENTITY {
            Placement::Affine
        } else if world_from_object.translation == DVec3::ZERO {
            Placement::Identity
        } else {
            Placement::Translation(world_from_object.translation)
        }
    }
}

impl Primitive {
    /// `shape` placed in the world by `world_from_object` (which must be invertible), with
    /// material index `material`.
    pub fn new(shape: Arc<dyn Shape>, world_from_object: DAffine3, material: u32, no_shadow: bool) -> Self {
        let object_from_world = world_from_object.inverse();
        Self {
            world_bounds: shape.bounds().transformed(&world_from_object),
            shape,
            world_from_object,
            object_from_world,
            normal_to_world: object_from_world.matrix3.transpose(),
            placement: Placement::of(&world_from_object),
            material,
            no_shadow,
        }
    }

    /// `ray` in this primitive's object space (direction not renormalised, so t is shared).
    #[inline]
    pub fn object_ray(&self, ray: &Ray) -> Ray {
        match self.placement {
            Placement::Identity => *ray,
            Placement::Translation(offset) => Ray::new(ray.origin - offset, ray.direction),
            Placement::Affine => Ray::new(
                self.object_from_world.transform_point3(ray.origin),
                self.object_from_world.transform_vector3(ray.direction),
            ),
        }
    }

    /// The shape's nearest hit along the world ray `ray` with `t_min < t < t_max`.
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit> {
        // The world ray itself when it needs no transforming: a fresh copy, read back by the
        // shape before its stores retire, costs a store-forwarding stall on every test.
        match self.placement {
            Placement::Identity => self.shape.intersect(ray, t_min, t_max),
            _ => self.shape.intersect(&self.object_ray(ray), t_min, t_max),
        }
    }

    /// True when the shape lies on the world ray `ray` with `t_min < t < t_max`.
    #[inline]
    pub fn occluded(&self, ray: &Ray, t_min: f64, t_max: f64) -> bool {
        match self.placement {
            Placement::Identity => self.shape.occluded(ray, t_min, t_max),
            _ => self.shape.occluded(&self.object_ray(ray), t_min, t_max),
        }
    }

    /// The world point `p` in this primitive's object space.
    #[inline]
    pub fn object_point(&self, p: DVec3) -> DVec3 {
        match self.placement {
            Placement::Identity => p,
            Placement::Translation(offset) => p - offset,
            Placement::Affine => self.object_from_world.transform_point3(p),
        }
    }

    /// The object-space point `p` in world space.
    #[inline]
    pub fn world_point(&self, p: DVec3) -> DVec3 {
        match self.placement {
            Placement::Identity => p,
            Placement::Translation(offset) => p + offset,
            Placement::Affine => self.world_from_object.transform_point3(p),
        }
    }

    /// The object-space unit normal `n` as a world-space unit normal.
    #[inline]
    pub fn world_normal(&self, n: DVec3) -> DVec3 {
        match self.placement {
            Placement::Identity | Placement::Translation(_) => n,
            Placement::Affine => (self.normal_to_world * n).normalize(),
        }
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
    /// Stratified pixel and lens patterns.
    pub patterns: PatternTable,
}

/// Builds the render scene. Call after `resolve_transforms` and `validate`.
pub fn extract(scene: &Scene) -> RenderScene {
    let mut entries: Vec<(hecs::Entity, Primitive, Material)> = Vec::new();
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
    let camera = RenderCamera::new(&scene.camera(), scene.render.width, scene.render.height);
    let (samples, seed) = (scene.render.samples, scene.render.seed);
    let patterns = if samples > 1 || camera.aperture > 0.0 {
        PatternTable::new(samples, seed)
    } else {
        PatternTable::untabulated(samples)
    };
    RenderScene {
        camera,
        primitives,
        materials,
        lights: lights.into_iter().map(|(_, l)| l).collect(),
        settings: scene.render.clone(),
        environment: scene.environment.clone(),
        accel,
        has_transparency,
        patterns,
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

#[cfg(test)]
mod tests {
    use glam::{DQuat, DVec2};
    use prism_api::contract::TestRng;
    use prism_sphere::Sphere;

    use super::*;

    fn sphere_at(world_from_object: DAffine3) -> Primitive {
        Primitive::new(Arc::new(Sphere { center: DVec3::ZERO, radius: 1.0 }), world_from_object, 0, false)
    }

    #[test]
    fn placement_is_recognised() {
        assert_eq!(sphere_at(DAffine3::IDENTITY).placement, Placement::Identity);
        let moved = DVec3::new(1.0, -2.0, 0.5);
        assert_eq!(sphere_at(DAffine3::from_translation(moved)).placement, Placement::Translation(moved));
        let turned = DAffine3::from_rotation_translation(DQuat::from_rotation_y(0.3), moved);
        assert_eq!(sphere_at(turned).placement, Placement::Affine);
        assert_eq!(sphere_at(DAffine3::from_scale(DVec3::splat(2.0))).placement, Placement::Affine);
    }

    /// The shortcuts for identity and translation give exactly what the matrices give.
    #[test]
    fn placement_shortcuts_equal_the_matrices() {
        let mut rng = TestRng::new(5);
        for _ in 0..1000 {
            let offset = DVec3::new(rng.range(-1e3, 1e3), rng.range(-1.0, 1.0), rng.range(-1e-3, 1e-3));
            let p = sphere_at(DAffine3::from_translation(offset));
            let ray = Ray::new(rng.unit_vector() * rng.range(0.0, 1e4), rng.unit_vector() * rng.range(0.1, 10.0));
            let by_matrix = Ray::new(
                p.object_from_world.transform_point3(ray.origin),
                p.object_from_world.transform_vector3(ray.direction),
            );
            let shortcut = p.object_ray(&ray);
            assert_eq!((shortcut.origin, shortcut.direction), (by_matrix.origin, by_matrix.direction));
            assert_eq!(p.world_point(ray.origin), p.world_from_object.transform_point3(ray.origin));
            assert_eq!(p.object_point(ray.origin), by_matrix.origin);
            let n = rng.unit_vector();
            assert_eq!(p.world_normal(n), n, "a translation leaves normals alone");
        }
        // The general case still maps normals with the inverse transpose.
        let squashed = sphere_at(DAffine3::from_scale(DVec3::new(1.0, 0.5, 1.0)));
        let n = squashed.world_normal(DVec2::new(1.0, 1.0).extend(0.0).normalize());
        assert!((n - DVec3::new(1.0, 2.0, 0.0).normalize()).length() < 1e-12);
    }
}
