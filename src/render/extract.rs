//! `extract`: the hecs world to an immutable, `Send + Sync` render scene: primitives with
//! both transforms, materials, lights (with the table from primitives to the area emitters),
//! the camera and the acceleration structure.

use super::camera::RenderCamera;
use super::filter::FilterSampler;
use super::focal_blur::BlurSchedule;
use super::lights::{RenderLight, SceneLights};
use super::sampling::PatternTable;
use crate::accel::primitive::Primitive;
use crate::accel::scene_bvh::{Accel, SeparableParts};
use std::any::Any;
use std::collections::HashMap;
use std::sync::Arc;

use glam::Vec3;

use crate::geometry::csg::CsgShape;
use crate::geometry::mesh::MeshShape;
use crate::material::Material;
use crate::material::pov_view::PovView;
use crate::world::Scene;
use crate::world::components::{
    CsgMaterials, Environment, IntegratorKind, Light, MaterialComponent, ObjectFlags, PhotometricLight, RenderSettings,
    ShapeComponent, WorldTransform,
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
    /// POV-Ray's adaptive focal blur (`[camera] blur_variance`): when each pixel (or, under
    /// POV-Ray's antialiasing, each traced position) stops taking lens samples.
    pub focal_blur: Option<BlurSchedule>,
}

impl RenderScene {
    /// Sets the samples per pixel and remakes the stratified patterns for that count: the
    /// scene then renders exactly as one extracted with that count.
    pub fn set_samples(&mut self, samples: u32) {
        self.settings.samples = samples;
        self.focal_blur = self.focal_blur.as_ref().map(|blur| blur.with_max(samples));
        self.patterns = patterns_for(&self.settings, self.camera.aperture, self.focal_blur.is_some());
    }
}

/// The pixel and lens patterns of `settings.samples` points per pixel (none under adaptive
/// sampling or adaptive focal blur, whose pixels draw progressive patterns of their own).
fn patterns_for(settings: &RenderSettings, aperture: f64, adaptive_blur: bool) -> PatternTable {
    let samples = settings.samples;
    if (samples > 1 || aperture > 0.0) && settings.noise.is_none() && !adaptive_blur {
        PatternTable::new(samples, settings.seed)
    } else {
        PatternTable::untabulated(samples)
    }
}

/// A mesh of at most this many triangles has them put into the scene-level BVH: for the
/// few-dozen-triangle meshes of room-like scenes, a second traversal per mesh, its transform
/// and its `dyn Shape` call cost more than its triangles. Larger meshes keep their own tree.
const FLATTEN_MESH_TRIANGLES: usize = 4096;

/// At most this many triangles are flattened in all, so that thousands of instances of a
/// small mesh are not copied thousands of times (the rest stay instances).
const FLATTEN_TOTAL_TRIANGLES: usize = 1 << 18;

/// Which primitives' triangles go into the scene-level BVH (see
/// [`Accel::build_flattening`]): meshes without alpha masks of at most
/// [`FLATTEN_MESH_TRIANGLES`], in primitive order while the total allows.
pub(crate) fn flattenable(primitives: &[Primitive]) -> Vec<Option<&[[Vec3; 3]]>> {
    let mut total = 0;
    primitives
        .iter()
        .map(|p| {
            let shape: &dyn Any = p.shape.as_ref();
            let triangles = shape.downcast_ref::<MeshShape>()?.flattenable_triangles()?;
            let fits = triangles.len() <= FLATTEN_MESH_TRIANGLES && total + triangles.len() <= FLATTEN_TOTAL_TRIANGLES;
            total += if fits { triangles.len() } else { 0 };
            fits.then_some(triangles)
        })
        .collect()
}

/// Which primitives' parts go into the scene-level BVH one by one (see
/// [`Accel::build_flattening`]): CSG unions that keep their interior surfaces, of at least
/// two members with bounded surfaces.
pub(crate) fn separable(primitives: &[Primitive]) -> Vec<Option<Arc<dyn SeparableParts>>> {
    primitives
        .iter()
        .map(|p| {
            if !CsgShape::of(p.shape.as_ref()).is_some_and(CsgShape::is_separable) {
                return None;
            }
            let any: Arc<dyn Any + Send + Sync> = p.shape.clone();
            any.downcast::<CsgShape>().ok().map(|group| group as Arc<dyn SeparableParts>)
        })
        .collect()
}

/// Builds the render scene. Call after `resolve_transforms` and `validate`.
pub fn extract(scene: &Scene) -> RenderScene {
    type Entry = (hecs::Entity, Primitive, Arc<Material>, Option<Vec<Arc<Material>>>);
    let mut entries: Vec<Entry> = Vec::new();
    let mut query = scene.world.query::<(
        hecs::Entity,
        &ShapeComponent,
        &WorldTransform,
        &MaterialComponent,
        Option<&ObjectFlags>,
        Option<&CsgMaterials>,
    )>();
    for (entity, shape, transform, material, flags, leaves) in query.iter() {
        let primitive = Primitive::new(shape.geometry.clone(), transform.0, 0, flags.is_some_and(|f| f.no_shadow));
        let leaves = leaves.map(|l| l.leaves.iter().map(|m| m.material.clone()).collect());
        entries.push((entity, primitive, material.material.clone(), leaves));
    }
    // Entity order is load order: the render scene does not depend on hecs's archetypes.
    entries.sort_by_key(|(e, ..)| e.id());
    let mut primitives = Vec::with_capacity(entries.len());
    let mut materials: Vec<Material> = Vec::new();
    // Keyed by the shared allocation; ids follow first use, so hash order never matters.
    let mut ids: HashMap<*const Material, usize> = HashMap::new();
    let mut id_of = |material: &Arc<Material>| {
        *ids.entry(Arc::as_ptr(material)).or_insert_with(|| {
            materials.push(Material::clone(material));
            materials.len() - 1
        }) as u32
    };
    for (_, mut primitive, material, leaves) in entries {
        primitive.material = id_of(&material);
        primitive.leaf_materials = leaves.map(|leaves| leaves.iter().map(&mut id_of).collect());
        primitives.push(primitive);
    }

    let mut lights: Vec<(hecs::Entity, RenderLight)> =
        scene.world.query::<(hecs::Entity, &Light)>().iter().map(|(e, l)| (e, RenderLight::from_scene(l))).collect();
    let mut imported = scene.world.query::<(hecs::Entity, &PhotometricLight)>();
    lights.extend(imported.iter().map(|(e, l)| (e, RenderLight::from_photometric(l))));
    lights.sort_by_key(|(e, _)| e.id());
    let sources = lights.into_iter().map(|(_, l)| l).collect();
    let lights = SceneLights::new(sources, &primitives, &materials, &scene.environment);

    let accel = Accel::build_flattening(&primitives, &flattenable(&primitives), &separable(&primitives));
    let has_transparency = materials.iter().any(|m| PovView::new(m).is_transparent());
    let camera = RenderCamera::new(&scene.camera(), scene.render.width, scene.render.height);
    let focal_blur = scene
        .camera()
        .adaptive_blur()
        .filter(|_| scene.render.integrator == IntegratorKind::Classic)
        .map(|blur| BlurSchedule::new(blur.variance, blur.confidence, blur.min_samples, scene.render.samples));
    let patterns = patterns_for(&scene.render, camera.aperture, focal_blur.is_some());
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
        focal_blur,
    }
}

#[cfg(test)]
mod tests {
    use glam::{DAffine3, DQuat, DVec3};
    use prism_api::contract::TestRng;
    use prism_api::{Ray, Shape};

    use super::*;
    use crate::geometry::mesh::MeshBuilder;
    use crate::scene::load::{Embedded, load_from};

    /// A lumpy closed ball of triangles (a latitude-longitude sphere with a random radius at
    /// each vertex), so rays meet it at every angle, on edges and at silhouettes.
    fn lumpy_ball(rng: &mut TestRng) -> Arc<dyn Shape> {
        let (rings, sectors) = (9, 14);
        let mut positions = vec![Vec3::Y, Vec3::NEG_Y];
        for i in 1..rings {
            let theta = std::f32::consts::PI * i as f32 / rings as f32;
            for j in 0..sectors {
                let phi = std::f32::consts::TAU * j as f32 / sectors as f32;
                let r = rng.range(0.8, 1.2) as f32;
                positions.push(Vec3::new(theta.sin() * phi.cos(), theta.cos(), theta.sin() * phi.sin()) * r);
            }
        }
        let at = |i: u32, j: u32| 2 + (i - 1) * sectors + j % sectors;
        let mut triangles = Vec::new();
        for j in 0..sectors {
            triangles.push([0, at(1, j + 1), at(1, j)]);
            triangles.push([1, at(rings - 1, j), at(rings - 1, j + 1)]);
            for i in 1..rings - 1 {
                triangles.push([at(i, j), at(i, j + 1), at(i + 1, j)]);
                triangles.push([at(i + 1, j), at(i, j + 1), at(i + 1, j + 1)]);
            }
        }
        let data = MeshBuilder { positions, triangles, ..MeshBuilder::default() }.build().unwrap();
        Arc::new(MeshShape::new(Arc::new(data)))
    }

    /// Random rays through a mesh placed three ways (unmoved, moved, turned and squashed)
    /// beside a sphere: the scene BVH with the meshes' triangles flattened into it finds the
    /// hits the two-level BVH finds. Unmoved, the very same hit (primitive, t, triangle,
    /// barycentrics); placed, the same up to the rounding of the vertices to world space.
    #[test]
    fn flattened_meshes_hit_as_the_two_level_tree_does() {
        let mut rng = TestRng::new(21);
        let mesh = lumpy_ball(&mut rng);
        let turned = DAffine3::from_scale_rotation_translation(
            DVec3::new(1.5, 0.7, 1.1),
            DQuat::from_euler(glam::EulerRot::XYZ, 0.3, -1.1, 0.6),
            DVec3::new(-2.5, 0.5, 1.0),
        );
        let sphere: Arc<dyn Shape> = Arc::new(prism_sphere::Sphere { center: DVec3::ZERO, radius: 0.6 });
        let primitives = vec![
            Primitive::new(mesh.clone(), DAffine3::IDENTITY, 0, false),
            Primitive::new(mesh.clone(), DAffine3::from_translation(DVec3::new(2.5, 0.3, -0.2)), 1, false),
            Primitive::new(mesh, turned, 2, false),
            Primitive::new(sphere, DAffine3::from_translation(DVec3::new(0.0, 2.2, 0.0)), 3, false),
        ];
        let flatten = flattenable(&primitives);
        assert_eq!(flatten.iter().map(Option::is_some).collect::<Vec<_>>(), [true, true, true, false]);
        let flat = Accel::build_flattening(&primitives, &flatten, &[]);
        assert_eq!(flat.flattened_triangles(), 3 * flatten[0].unwrap().len());
        let two_level = Accel::build(&primitives);
        assert_eq!(two_level.flattened_triangles(), 0);
        let (mut hits, mut near_misses) = (0, 0);
        for case in 0..6000 {
            let origin = DVec3::new(rng.range(-5.0, 5.0), rng.range(-3.0, 3.0), rng.range(-3.0, 3.0));
            // Toward a point near one of the four objects, so that most rays meet one.
            let centres = [DVec3::ZERO, DVec3::new(2.5, 0.3, -0.2), DVec3::new(-2.5, 0.5, 1.0), DVec3::Y * 2.2];
            let target = centres[case % 4] + rng.unit_vector() * rng.range(0.0, 1.3);
            let ray = Ray::new(origin, (target - origin) * rng.range(0.2, 2.0));
            let t_max = if case % 4 == 0 { rng.range(0.5, 4.0) } else { f64::INFINITY };
            let expected = two_level.closest(&primitives, &ray, 1e-6, t_max, |_| true);
            let found = flat.closest(&primitives, &ray, 1e-6, t_max, |_| true);
            let occluded = flat.occluded(&primitives, &ray, 1e-6, t_max, |_| true);
            assert_eq!(occluded, found.is_some(), "case {case}: occlusion agrees with the closest hit");
            let skip_one = |i: u32| i != 0;
            let without = flat.closest(&primitives, &ray, 1e-6, t_max, skip_one).map(|h| h.primitive);
            let without_expected = two_level.closest(&primitives, &ray, 1e-6, t_max, skip_one).map(|h| h.primitive);
            match (expected, found) {
                (None, None) => {}
                (Some(e), Some(f)) if e.primitive == 0 || e.primitive == 3 => {
                    hits += 1;
                    if without_expected.is_none_or(|p| p == 3) {
                        assert_eq!(without, without_expected, "case {case}: rejected primitives are skipped");
                    }
                    assert_eq!(f.primitive, e.primitive, "case {case}");
                    assert_eq!(
                        (f.hit.t, f.hit.part, f.hit.scratch),
                        (e.hit.t, e.hit.part, e.hit.scratch),
                        "case {case}"
                    );
                    let primitive = &primitives[e.primitive as usize];
                    let object_ray = primitive.object_ray(&ray);
                    let (sf, se) =
                        (primitive.shape.surface(&object_ray, &f.hit), primitive.shape.surface(&object_ray, &e.hit));
                    assert_eq!((sf.point, sf.shading_normal, sf.uv), (se.point, se.shading_normal, se.uv));
                }
                (Some(e), Some(f)) if f.primitive == e.primitive && f.hit.part == e.hit.part => {
                    hits += 1;
                    // World distances; the vertices moved by an f32 rounding of about 1e-7.
                    let apart = (f.hit.t - e.hit.t).abs() * ray.direction.length();
                    assert!(apart <= 1e-4, "case {case}: {} vs {}", f.hit.t, e.hit.t);
                    assert!((f.hit.scratch - e.hit.scratch).abs().max_element() < 1e-4, "case {case}");
                }
                // Rounding the placed meshes' vertices may move a hit across an edge or
                // off a silhouette, for very few rays.
                _ => near_misses += 1,
            }
        }
        assert!(hits > 4000, "most rays hit something ({hits})");
        assert!(near_misses < 10, "{near_misses} rays found different triangles");
    }

    /// Unions with their members in the scene's tree one by one find exactly the hits the
    /// unions find whole (primitive, t and part, so the same leaf and material), occlusion
    /// included: members moved and turned, a nested group and an inverted member among
    /// them, twin members on top of each other (the lower member must win the tie, as in the
    /// group), and a union that is not separable (an intersection) beside them.
    #[test]
    fn separated_unions_hit_as_whole_unions_do() {
        use crate::geometry::csg::{CsgMember, CsgOperation};
        let mut rng = TestRng::new(5);
        let sphere = |c: DVec3, r: f64| -> Arc<dyn Shape> { Arc::new(prism_sphere::Sphere { center: c, radius: r }) };
        let boxed = |h: f64| -> Arc<dyn Shape> {
            Arc::new(prism_box::BoxShape { min: DVec3::splat(-h), max: DVec3::splat(h) })
        };
        let member = |shape: Arc<dyn Shape>, at: DAffine3, inverse: bool| CsgMember::new(shape, at, inverse);
        let mut unions = Vec::new();
        for _ in 0..6 {
            let mut members = Vec::new();
            for k in 0..12 {
                let at = DAffine3::from_scale_rotation_translation(
                    DVec3::new(rng.range(0.5, 1.5), rng.range(0.5, 1.5), rng.range(0.5, 1.5)),
                    DQuat::from_euler(glam::EulerRot::XYZ, rng.range(0.0, 3.0), rng.range(0.0, 3.0), 0.0),
                    DVec3::new(rng.range(-3.0, 3.0), rng.range(-3.0, 3.0), rng.range(-3.0, 3.0)),
                );
                let shape = match k % 4 {
                    0 => sphere(DVec3::ZERO, rng.range(0.2, 0.7)),
                    1 => boxed(rng.range(0.2, 0.6)),
                    2 => Arc::new(CsgShape::new(
                        CsgOperation::Difference,
                        vec![
                            member(boxed(0.5), DAffine3::IDENTITY, false),
                            member(sphere(DVec3::Y * 0.4, 0.4), DAffine3::IDENTITY, false),
                        ],
                    )),
                    _ => Arc::new(CsgShape::new(
                        CsgOperation::Intersection,
                        vec![
                            member(boxed(0.5), DAffine3::IDENTITY, false),
                            member(boxed(0.4), DAffine3::IDENTITY, true),
                        ],
                    )),
                };
                members.push(member(shape.clone(), at, false));
                if k % 5 == 0 {
                    // A twin on top of this member: every hit on one is a tie with the other.
                    members.push(member(shape, at, false));
                }
            }
            unions.push(Arc::new(CsgShape::new(CsgOperation::Union, members)) as Arc<dyn Shape>);
        }
        let inside_out = CsgShape::new(
            CsgOperation::Intersection,
            vec![
                member(sphere(DVec3::ZERO, 1.0), DAffine3::IDENTITY, false),
                member(boxed(0.8), DAffine3::IDENTITY, false),
            ],
        );
        let mut primitives: Vec<Primitive> = unions
            .into_iter()
            .enumerate()
            .map(|(i, u)| Primitive::new(u, DAffine3::from_translation(DVec3::new(i as f64 - 2.5, 0.0, 0.0)), 0, false))
            .collect();
        primitives.push(Primitive::new(Arc::new(inside_out), DAffine3::from_translation(DVec3::Z * 2.0), 0, false));
        let separable = separable(&primitives);
        assert_eq!(separable.iter().filter(|s| s.is_some()).count(), 6, "the unions, not the intersection");
        let split = Accel::build_flattening(&primitives, &[], &separable);
        assert!(split.separated_parts() >= 6 * 14);
        let whole = Accel::build(&primitives);
        let (mut hits, mut twins) = (0, 0);
        for case in 0..20_000 {
            let origin = DVec3::new(rng.range(-9.0, 9.0), rng.range(-9.0, 9.0), rng.range(-9.0, 9.0));
            let target = DVec3::new(rng.range(-5.0, 5.0), rng.range(-3.0, 3.0), rng.range(-3.0, 3.0));
            let ray = Ray::new(origin, (target - origin) * rng.range(0.2, 2.0));
            let t_max = if case % 3 == 0 { rng.range(0.2, 1.5) } else { f64::INFINITY };
            let skip_odd = |i: u32| i.is_multiple_of(2);
            for accept in [&(|_| true) as &dyn Fn(u32) -> bool, &skip_odd] {
                let expected = whole.closest(&primitives, &ray, 1e-6, t_max, accept);
                let found = split.closest(&primitives, &ray, 1e-6, t_max, accept);
                let pair =
                    |h: Option<crate::accel::scene_bvh::ClosestHit>| h.map(|h| (h.primitive, h.hit.t, h.hit.part));
                assert_eq!(pair(found), pair(expected), "case {case}");
                assert_eq!(split.occluded(&primitives, &ray, 1e-6, t_max, accept), expected.is_some(), "case {case}");
                if let Some(hit) = expected {
                    hits += 1;
                    twins += usize::from(on_first_twin(&primitives[hit.primitive as usize], &hit.hit));
                }
            }
        }
        assert!(hits > 10_000, "most rays hit ({hits})");
        assert!(twins > 500, "ties between twins are decided ({twins})");
    }

    /// True when `hit` lies on a union member followed by its twin (the same shape placed
    /// the same way).
    fn on_first_twin(primitive: &Primitive, hit: &prism_api::Hit) -> bool {
        let Some(group) = CsgShape::of(primitive.shape.as_ref()) else { return false };
        let leaf = crate::accel::primitive::leaf_of(hit);
        let members = group.members();
        let mut base = 0;
        for (i, m) in members.iter().enumerate() {
            let leaves = CsgShape::of(m.shape.as_ref()).map_or(1, CsgShape::leaves);
            if leaf < base + leaves {
                return members.get(i + 1).is_some_and(|next| {
                    Arc::ptr_eq(&next.shape, &m.shape) && next.group_from_member == m.group_from_member
                });
            }
            base += leaves;
        }
        false
    }

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
