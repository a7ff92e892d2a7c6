//! Primitives: shapes placed in the world by an affine transform, with the cheapest exact
//! way to move rays, points and normals between the two spaces.

use std::borrow::Cow;
use std::sync::Arc;

use glam::{DAffine3, DMat3, DVec3};
use prism_api::{Aabb, Hit, Ray, Shape};

/// The bits of [`Hit::part`] a CSG leaf's own part may use; the index of the leaf hit (depth
/// first) sits above them. It lives here, not with the CSG shape, because
/// [`Primitive::material_at`] reads it for every hit of a group.
pub const PART_BITS: u32 = 16;

/// The leaf (depth-first index) a hit of a CSG group lies on.
#[inline]
pub fn leaf_of(hit: &Hit) -> u32 {
    hit.part >> PART_BITS
}

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
    /// For a CSG group: the material index of each member leaf (its own, or the group's it
    /// inherits), which [`Primitive::material_at`] picks by the leaf a hit names.
    pub leaf_materials: Option<Arc<[u32]>>,
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
            leaf_materials: None,
            no_shadow,
        }
    }

    /// The material index at `hit` (a hit of this primitive's shape): the hit leaf's for a
    /// CSG group, else the primitive's.
    #[inline]
    pub fn material_at(&self, hit: &Hit) -> u32 {
        match &self.leaf_materials {
            None => self.material,
            Some(leaves) => leaves.get(leaf_of(hit) as usize).copied().unwrap_or(self.material),
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

    /// [`Primitive::object_ray`], borrowing `ray` itself where object space is world space:
    /// a fresh copy, read back by the shape before its stores retire, would stall the read
    /// (store forwarding), as in [`Primitive::intersect`].
    #[inline]
    pub fn object_ray_of<'a>(&self, ray: &'a Ray) -> Cow<'a, Ray> {
        match self.placement {
            Placement::Identity => Cow::Borrowed(ray),
            _ => Cow::Owned(self.object_ray(ray)),
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

    /// The factor by which this primitive's transform scales an area element whose
    /// object-space unit normal is `object_normal` (Nanson's formula, `|det M| |M^-T n|`):
    /// an object-space area density divided by it is the world-space density.
    #[inline]
    pub fn area_scale(&self, object_normal: DVec3) -> f64 {
        match self.placement {
            Placement::Identity | Placement::Translation(_) => 1.0,
            Placement::Affine => {
                self.world_from_object.matrix3.determinant().abs() * (self.normal_to_world * object_normal).length()
            }
        }
    }

    /// The factor by which this primitive's transform scales a solid-angle element around
    /// the object-space direction `object_direction` (see
    /// [`prism_api::math::solid_angle_scale`]): an object-space direction density from
    /// [`Shape::sample_toward`] or [`Shape::pdf_toward`] divided by it is the world-space one.
    #[inline]
    pub fn solid_angle_scale(&self, object_direction: DVec3) -> f64 {
        match self.placement {
            Placement::Identity | Placement::Translation(_) => 1.0,
            Placement::Affine => prism_api::math::solid_angle_scale(self.world_from_object.matrix3, object_direction),
        }
    }

    /// The world-space normal `n` in object space as a covector, not normalised: the
    /// transpose of the object's linear part applied to it (POV-Ray's `MInvTransNormal`
    /// through the object's transform), so its length tells how the transform scaled it.
    #[inline]
    pub fn object_covector(&self, n: DVec3) -> DVec3 {
        match self.placement {
            Placement::Identity | Placement::Translation(_) => n,
            Placement::Affine => self.world_from_object.matrix3.transpose() * n,
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
            assert_eq!(p.area_scale(n), 1.0, "a translation keeps areas");
        }
        // The general case still maps normals with the inverse transpose.
        let squashed = sphere_at(DAffine3::from_scale(DVec3::new(1.0, 0.5, 1.0)));
        let n = squashed.world_normal(DVec2::new(1.0, 1.0).extend(0.0).normalize());
        assert!((n - DVec3::new(1.0, 2.0, 0.0).normalize()).length() < 1e-12);
    }

    /// The area scale agrees with a small parallelogram mapped through the transform.
    #[test]
    fn area_scale_matches_a_mapped_parallelogram() {
        let m = DMat3::from_cols(DVec3::new(2.0, 0.3, 0.0), DVec3::new(-0.5, 1.5, 0.2), DVec3::new(0.1, 0.0, 0.7));
        let p = sphere_at(DAffine3::from_mat3_translation(m, DVec3::new(1.0, 2.0, 3.0)));
        let mut rng = TestRng::new(9);
        for _ in 0..100 {
            let n = rng.unit_vector();
            let (t1, t2) = (n.any_orthonormal_pair().0 * 1e-3, n.any_orthonormal_pair().1 * 1e-3);
            let mapped = (m * t1).cross(m * t2).length() / t1.cross(t2).length();
            assert!((p.area_scale(n) / mapped - 1.0).abs() < 1e-9, "{} vs {mapped}", p.area_scale(n));
        }
    }
}
