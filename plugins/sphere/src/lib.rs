//! The sphere shape plugin: a sphere of a given radius around a centre point.

#![forbid(unsafe_code)]

use std::f64::consts::{PI, TAU};
use std::sync::Arc;

use prism_api::{Aabb, AreaSample, DVec2, DVec3, Hit, ParamError, Ray, Shape, ShapeParams, Surface, pov};
use schemars::JsonSchema;
use serde::Deserialize;

/// Parameters of `shape = "sphere"`.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SphereParams {
    /// Centre of the sphere in object space.
    #[serde(default)]
    pub center: [f64; 3],
    /// Radius of the sphere; must be greater than 0.
    #[serde(default = "default_radius")]
    pub radius: f64,
}

fn default_radius() -> f64 {
    1.0
}

impl ShapeParams for SphereParams {
    fn build(self) -> Result<Arc<dyn Shape>, ParamError> {
        ParamError::require_finite("center", &self.center)?;
        ParamError::require_positive("radius", self.radius)?;
        Ok(Arc::new(Sphere { center: DVec3::from_array(self.center), radius: self.radius }))
    }
}

/// A sphere solved in f64 with a cancellation-free quadratic.
#[derive(Clone, Debug, PartialEq)]
pub struct Sphere {
    /// Centre in object space.
    pub center: DVec3,
    /// Radius (> 0).
    pub radius: f64,
}

/// Squared half chords up to this count as tangent and miss (POV-Ray's `EPSILON`).
pub const TANGENT_EPSILON: f64 = 1e-10;

impl Shape for Sphere {
    fn bounds(&self) -> Aabb {
        Aabb::from_corners(self.center - self.radius, self.center + self.radius)
    }

    fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit> {
        // Hearn-Baker form: the discriminant is computed from the distance of the closest
        // approach, which keeps precision for rays that start far away.
        let oc = ray.origin - self.center;
        let a = ray.direction.length_squared();
        let b_half = oc.dot(ray.direction);
        let closest = oc - (b_half / a) * ray.direction;
        let half_chord_squared = self.radius * self.radius - closest.length_squared();
        // POV-Ray misses a ray whose half chord (for a unit direction) is not longer than
        // 1e-5: exactly tangent rays would otherwise hit or miss by rounding.
        if half_chord_squared <= TANGENT_EPSILON {
            return None;
        }
        let disc = a * half_chord_squared;
        let c = oc.length_squared() - self.radius * self.radius;
        let q = -(b_half + b_half.signum() * disc.sqrt());
        let (t0, t1) = if q == 0.0 { (0.0, 0.0) } else { (q / a, c / q) };
        let (near, far) = if t0 <= t1 { (t0, t1) } else { (t1, t0) };
        [near, far].into_iter().find(|&t| t > t_min && t < t_max).map(Hit::at)
    }

    fn surface(&self, ray: &Ray, hit: &Hit) -> Surface {
        let mut surface = self.surface_geometry(ray, hit);
        let normal = surface.normal;
        let u = 0.5 + normal.z.atan2(-normal.x) / TAU;
        let v = 0.5 + normal.y.clamp(-1.0, 1.0).asin() / PI;
        surface.uv = DVec2::new(u.rem_euclid(1.0), v);
        surface
    }

    fn surface_geometry(&self, ray: &Ray, hit: &Hit) -> Surface {
        let normal = (ray.at(hit.t) - self.center).normalize();
        // Project exactly onto the sphere: removes the error of ray.at(t) along the normal.
        Surface::new(self.center + normal * self.radius, normal, DVec2::ZERO)
    }

    fn inside(&self, point: DVec3) -> bool {
        point.distance_squared(self.center) < self.radius * self.radius
    }

    fn area(&self) -> Option<f64> {
        Some(4.0 * PI * self.radius * self.radius)
    }

    fn sample_area(&self, u: DVec2) -> Option<AreaSample> {
        let z = 1.0 - 2.0 * u.x;
        let r = (1.0 - z * z).max(0.0).sqrt();
        let phi = TAU * u.y;
        let normal = DVec3::new(r * phi.cos(), r * phi.sin(), z);
        Some(AreaSample { point: self.center + normal * self.radius, normal, pdf_area: 1.0 / self.area()? })
    }

    fn to_pov(&self) -> Option<String> {
        Some(format!("sphere {{ {}, {} }}", pov::vector(self.center), pov::number(self.radius)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use prism_api::contract::check_shape;

    fn unit() -> Sphere {
        Sphere { center: DVec3::ZERO, radius: 1.0 }
    }

    #[test]
    fn contract_holds() {
        check_shape(&unit());
        check_shape(&Sphere { center: DVec3::new(3.0, -2.0, 1.0), radius: 0.25 });
        check_shape(&Sphere { center: DVec3::ZERO, radius: 1e3 });
    }

    #[test]
    fn tangent_rays_miss_as_in_pov_ray() {
        let s = unit();
        let tangent = Ray::new(DVec3::new(-5.0, 1.0, 0.0), DVec3::X);
        assert!(s.intersect(&tangent, 1e-6, f64::INFINITY).is_none());
        let grazing = Ray::new(DVec3::new(-5.0, 1.0 - 1e-4, 0.0), DVec3::X * 3.0);
        assert!(s.intersect(&grazing, 1e-6, f64::INFINITY).is_some(), "a chord of 0.028 hits");
    }

    #[test]
    fn hit_from_outside_and_inside() {
        let s = unit();
        let outside = Ray::new(DVec3::new(0.0, 0.0, 5.0), -DVec3::Z);
        let hit = s.intersect(&outside, 1e-6, f64::INFINITY).unwrap();
        assert!((hit.t - 4.0).abs() < 1e-12);
        let surface = s.surface(&outside, &hit);
        assert!((surface.normal - DVec3::Z).length() < 1e-12, "outward normal");
        let inside = Ray::new(DVec3::ZERO, DVec3::X);
        let hit = s.intersect(&inside, 1e-6, f64::INFINITY).unwrap();
        assert!((hit.t - 1.0).abs() < 1e-12);
        assert!((s.surface(&inside, &hit).normal - DVec3::X).length() < 1e-12, "still outward from inside");
    }

    #[test]
    fn behind_the_origin_and_t_range() {
        let s = unit();
        let away = Ray::new(DVec3::new(0.0, 0.0, 5.0), DVec3::Z);
        assert!(s.intersect(&away, 1e-6, f64::INFINITY).is_none());
        let toward = Ray::new(DVec3::new(0.0, 0.0, 5.0), -DVec3::Z);
        assert!(s.intersect(&toward, 1e-6, 3.9).is_none());
        let far_only = s.intersect(&toward, 4.5, f64::INFINITY).unwrap();
        assert!((far_only.t - 6.0).abs() < 1e-12);
    }

    #[test]
    fn grazing_and_distant_rays() {
        let s = unit();
        let graze = Ray::new(DVec3::new(1.0 + 1e-9, 0.0, 5.0), -DVec3::Z);
        assert!(s.intersect(&graze, 1e-6, f64::INFINITY).is_none());
        let tangent_inside = Ray::new(DVec3::new(1.0 - 1e-9, 0.0, 5.0), -DVec3::Z);
        let hit = s.intersect(&tangent_inside, 1e-6, f64::INFINITY).unwrap();
        let p = s.surface(&tangent_inside, &hit).point;
        assert!((p.length() - 1.0).abs() < 1e-12);
        // A ray from a million units away still lands on the surface.
        let far = Ray::new(DVec3::new(0.3, 0.2, 1e6), -DVec3::Z);
        let hit = s.intersect(&far, 1e-6, f64::INFINITY).unwrap();
        assert!((far.at(hit.t).length() - 1.0).abs() < 1e-9);
    }

    #[test]
    fn parameters_are_validated() {
        let bad = SphereParams { center: [0.0; 3], radius: -1.0 }.build().unwrap_err();
        assert_eq!(bad.key, "radius");
        let nan = SphereParams { center: [f64::NAN, 0.0, 0.0], radius: 1.0 }.build().unwrap_err();
        assert_eq!(nan.key, "center");
    }

    #[test]
    fn exports_to_pov_with_z_mirrored() {
        let s = Sphere { center: DVec3::new(1.0, 2.0, 3.0), radius: 0.5 };
        assert_eq!(s.to_pov().unwrap(), "sphere { <1.0, 2.0, -3.0>, 0.5 }");
    }
}
