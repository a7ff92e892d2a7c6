//! Ray queries over all primitives: an obvhs BVH over the world bounds of bounded
//! primitives, plus a short list of unbounded ones (infinite planes) tested beside it, as
//! POV-Ray does. Shapes are intersected in f64 in their own object space; the BVH works in
//! f32 with conservatively enlarged boxes, and the closest hit is decided in f64.

use std::time::Duration;

use glam::Vec3A;
use obvhs::BvhBuildParams;
use obvhs::bvh2::Bvh2;
use obvhs::bvh2::builder::build_bvh2;
use prism_api::{Hit, Ray};

use super::scene::Primitive;

/// The acceleration structure.
pub struct Accel {
    bvh: Option<Bvh2>,
    /// Primitive index of each BVH leaf slot (leaf order).
    leaf_primitive: Vec<u32>,
    /// Primitives that are not bounded.
    unbounded: Vec<u32>,
}

/// The closest hit of a ray: which primitive, the shape's hit record, and the object ray.
#[derive(Clone, Copy, Debug)]
pub struct ClosestHit {
    /// Index into the render scene's primitives.
    pub primitive: u32,
    /// The shape's hit (t is shared by world and object space).
    pub hit: Hit,
    /// The ray in the primitive's object space.
    pub object_ray: Ray,
}

fn to_obvhs_aabb(b: &prism_api::Aabb) -> obvhs::aabb::Aabb {
    // Round outward and pad, so f32 rounding of boxes and rays never loses a hit.
    let pad = 1e-5 * b.min.abs().max(b.max.abs()).max_element() + 1e-6;
    let min = (b.min - pad).as_vec3();
    let max = (b.max + pad).as_vec3();
    obvhs::aabb::Aabb { min: Vec3A::from(min), max: Vec3A::from(max) }
}

/// The f32 ray the BVH traverses, reaching up to `t_max` rounded up so that f32 pruning
/// never drops a box holding a hit at exactly `t_max`.
fn bvh_ray(ray: &Ray, t_max: f64) -> obvhs::ray::Ray {
    let tmax = if t_max.is_finite() { (t_max as f32).next_up() } else { f32::INFINITY };
    obvhs::ray::Ray::new(Vec3A::from(ray.origin.as_vec3()), Vec3A::from(ray.direction.as_vec3()), 0.0, tmax)
}

impl Accel {
    /// Builds the BVH over `primitives`' world bounds.
    pub fn build(primitives: &[Primitive]) -> Self {
        let mut boxes = Vec::new();
        let mut bounded = Vec::new();
        let mut unbounded = Vec::new();
        for (i, p) in primitives.iter().enumerate() {
            if p.world_bounds.is_bounded() {
                boxes.push(to_obvhs_aabb(&p.world_bounds));
                bounded.push(i as u32);
            } else {
                unbounded.push(i as u32);
            }
        }
        let bvh = (!boxes.is_empty()).then(|| {
            let mut build_time = Duration::default();
            build_bvh2(&boxes, BvhBuildParams::medium_build(), &mut build_time)
        });
        let leaf_primitive = match &bvh {
            Some(bvh) => bvh.primitive_indices.iter().map(|&i| bounded[i as usize]).collect(),
            None => Vec::new(),
        };
        Self { bvh, leaf_primitive, unbounded }
    }

    /// The closest hit with `t_min < t < t_max` among primitives for which `accept` is true.
    pub fn closest(
        &self,
        primitives: &[Primitive],
        ray: &Ray,
        t_min: f64,
        t_max: f64,
        accept: impl Fn(u32) -> bool,
    ) -> Option<ClosestHit> {
        let mut best: Option<ClosestHit> = None;
        let mut best_t = t_max;
        let test = |index: u32, best_t: &mut f64, best: &mut Option<ClosestHit>| -> f32 {
            if !accept(index) {
                return f32::INFINITY;
            }
            let p = &primitives[index as usize];
            let object_ray = p.object_ray(ray);
            match p.shape.intersect(&object_ray, t_min, *best_t) {
                Some(hit) => {
                    *best_t = hit.t;
                    *best = Some(ClosestHit { primitive: index, hit, object_ray });
                    // Round up so the f32 traversal never prunes a box holding an equal hit.
                    (hit.t as f32).next_up()
                }
                None => f32::INFINITY,
            }
        };
        for &index in &self.unbounded {
            test(index, &mut best_t, &mut best);
        }
        if let Some(bvh) = &self.bvh {
            let mut hit = obvhs::ray::RayHit::none();
            bvh.ray_traverse(bvh_ray(ray, best_t), &mut hit, |_, slot| {
                test(self.leaf_primitive[slot], &mut best_t, &mut best)
            });
        }
        best
    }

    /// True when any primitive for which `accept` is true lies on the ray in (t_min, t_max).
    pub fn occluded(
        &self,
        primitives: &[Primitive],
        ray: &Ray,
        t_min: f64,
        t_max: f64,
        accept: impl Fn(u32) -> bool,
    ) -> bool {
        let test = |index: u32| -> bool {
            if !accept(index) {
                return false;
            }
            let p = &primitives[index as usize];
            p.shape.occluded(&p.object_ray(ray), t_min, t_max)
        };
        if self.unbounded.iter().any(|&i| test(i)) {
            return true;
        }
        let Some(bvh) = &self.bvh else { return false };
        !bvh.ray_traverse_miss(
            bvh_ray(ray, t_max),
            |_, slot| if test(self.leaf_primitive[slot]) { 0.0 } else { f32::INFINITY },
        )
    }
}
