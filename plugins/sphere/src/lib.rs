//! The sphere shape plugin: a sphere of a given radius around a centre point.

#![forbid(unsafe_code)]

use std::f64::consts::{PI, TAU};
use std::ops::ControlFlow;
use std::sync::Arc;

use prism_api::{
    Aabb, AreaSample, DVec2, DVec3, DirectionSample, Hit, HitPoint, ParamError, Ray, Shape, ShapeParams, Surface, math,
    pdf_toward_by_area, pov, sample_toward_by_area, visit_solved_crossings,
};
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

/// The cone of directions a sphere subtends from a point outside it.
struct Cone {
    /// Unit vector from the point to the centre.
    axis: DVec3,
    /// sin^2 of the half angle: (radius / distance)^2.
    sin2_max: f64,
    /// 1 - cos of the half angle.
    one_minus_cos_max: f64,
}

impl Sphere {
    /// The cone subtended from `reference`, or `None` when it is not outside the sphere.
    fn cone_from(&self, reference: DVec3) -> Option<Cone> {
        let to_center = self.center - reference;
        let distance_squared = to_center.length_squared();
        let sin2_max = self.radius * self.radius / distance_squared;
        (sin2_max < 1.0).then(|| Cone {
            axis: to_center / distance_squared.sqrt(),
            sin2_max,
            one_minus_cos_max: sin2_max / (1.0 + (1.0 - sin2_max).sqrt()),
        })
    }

    /// The ray's two parameters on the sphere, nearer first; `None` when it misses or only
    /// grazes it.
    #[inline]
    fn roots(&self, ray: &Ray) -> Option<(f64, f64)> {
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
        Some(if t0 <= t1 { (t0, t1) } else { (t1, t0) })
    }
}

/// Squared half chords up to this count as tangent and miss (POV-Ray's `EPSILON`).
pub const TANGENT_EPSILON: f64 = 1e-10;

impl Shape for Sphere {
    fn bounds(&self) -> Aabb {
        Aabb::from_corners(self.center - self.radius, self.center + self.radius)
    }

    fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit> {
        let (near, far) = self.roots(ray)?;
        [near, far].into_iter().find(|&t| t > t_min && t < t_max).map(Hit::at)
    }

    /// Both roots from one solve: what [`prism_api::crossings_by_intersect`] lists, which
    /// solves the same quadratic once per crossing (CSG walks crossings of every member).
    fn crossings(&self, ray: &Ray, t_min: f64, t_max: f64, visit: &mut dyn FnMut(&Hit) -> ControlFlow<()>) {
        let Some((near, far)) = self.roots(ray) else { return };
        visit_solved_crossings(&self.bounds(), ray, t_min, t_max, [near, far].map(Hit::at), visit);
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
        let HitPoint { point, normal, .. } = self.hit_point(ray, hit);
        Surface::new(point, normal, DVec2::ZERO).with_dpdu(math::longitude_dpdu(normal * self.radius, normal))
    }

    fn hit_point(&self, ray: &Ray, hit: &Hit) -> HitPoint {
        let normal = (ray.at(hit.t) - self.center).normalize();
        // Project exactly onto the sphere: removes the error of ray.at(t) along the normal.
        HitPoint::new(self.center + normal * self.radius, normal)
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

    /// From outside, uniform over the cone of directions the sphere subtends (pbrt-v4's
    /// `Sphere::Sample(ctx, u)`): every sample is a visible point. From inside (or on the
    /// surface), where every direction meets the sphere once, uniform over the area.
    fn sample_toward(&self, reference: DVec3, u: DVec2) -> Option<DirectionSample> {
        let Some(cone) = self.cone_from(reference) else { return sample_toward_by_area(self, reference, u) };
        // cos(theta) = 1 - u.x (1 - cos(theta_max)) from the axis toward the centre, kept as
        // 1 - cos(theta) so that tiny cones lose nothing to cancellation.
        let one_minus_cos = u.x * cone.one_minus_cos_max;
        let cos_theta = 1.0 - one_minus_cos;
        let sin2_theta = one_minus_cos * (2.0 - one_minus_cos);
        // The angle alpha at the centre between the axis back to the reference and the point
        // where the sampled direction first meets the sphere.
        let sin_max = cone.sin2_max.sqrt();
        let cos_alpha = sin2_theta / sin_max + cos_theta * (1.0 - sin2_theta / cone.sin2_max).max(0.0).sqrt();
        let sin_alpha = (1.0 - cos_alpha * cos_alpha).max(0.0).sqrt();
        let (sin_phi, cos_phi) = (TAU * u.y).sin_cos();
        let (x, y) = math::orthonormal_basis(cone.axis);
        let normal = (x * (sin_alpha * cos_phi) + y * (sin_alpha * sin_phi) - cone.axis * cos_alpha).normalize();
        Some(DirectionSample {
            point: self.center + normal * self.radius,
            normal,
            pdf_solid_angle: 1.0 / (TAU * cone.one_minus_cos_max),
        })
    }

    fn pdf_toward(&self, reference: DVec3, direction: DVec3) -> f64 {
        let Some(cone) = self.cone_from(reference) else { return pdf_toward_by_area(self, reference, direction) };
        // 1 - cos of the angle to the axis, from the chord between the unit vectors.
        let one_minus_cos = 0.5 * (direction.normalize() - cone.axis).length_squared();
        if one_minus_cos <= cone.one_minus_cos_max { 1.0 / (TAU * cone.one_minus_cos_max) } else { 0.0 }
    }

    fn to_pov(&self) -> Option<String> {
        Some(format!("sphere {{ {}, {} }}", pov::vector(self.center), pov::number(self.radius)))
    }

    fn to_mitsuba(&self) -> Option<Vec<prism_api::mitsuba::MitsubaShape>> {
        let place = prism_api::DAffine3::from_translation(self.center)
            * prism_api::DAffine3::from_scale(DVec3::splat(self.radius));
        // Mitsuba's poles are on z, Prism's (POV-Ray's spherical map) on y.
        Some(vec![
            prism_api::mitsuba::MitsubaShape::new(prism_api::mitsuba::MitsubaKind::Sphere, place).with_other_uv(),
        ])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use prism_api::contract::{ContractConfig, check_dpdu, check_sampling_toward, check_shape, check_t_range};

    fn unit() -> Sphere {
        Sphere { center: DVec3::ZERO, radius: 1.0 }
    }

    #[test]
    fn contract_holds() {
        check_shape(&unit());
        check_shape(&Sphere { center: DVec3::new(3.0, -2.0, 1.0), radius: 0.25 });
        check_shape(&Sphere { center: DVec3::ZERO, radius: 1e3 });
        check_dpdu(&unit());
    }

    #[test]
    fn crossings_are_the_defaults_from_one_solve() {
        prism_api::contract::check_crossings_match_intersect(&unit());
        prism_api::contract::check_crossings_match_intersect(&Sphere {
            center: DVec3::new(3.0, -2.0, 1.0),
            radius: 1e-3,
        });
        prism_api::contract::check_crossings_match_intersect(&Sphere {
            center: DVec3::new(0.0, 1e3, 0.0),
            radius: 1e3,
        });
    }

    #[test]
    fn cone_sampling_from_far_near_and_just_outside() {
        let s = Sphere { center: DVec3::new(1.0, 2.0, -1.0), radius: 0.5 };
        let config = ContractConfig::default();
        // A tiny cone (1e-4 radians), a wide one, and one just off the surface.
        let references = [
            s.center + DVec3::new(3.0, 4.0, 0.0) * 1e3,
            s.center + DVec3::new(0.0, 0.0, 0.6),
            s.center + DVec3::new(0.3, -0.4, 0.0) * 1.001,
            s.center + DVec3::new(0.1, 0.2, 0.1),
        ];
        check_sampling_toward(&s, &references, &config);
    }

    #[test]
    fn cone_samples_are_visible_and_uniform_in_the_cone() {
        let s = unit();
        let reference = DVec3::new(0.0, 0.0, 2.0);
        // Half angle 30 degrees: 1 - cos = 1 - sqrt(3) / 2.
        let pdf = 1.0 / (TAU * (1.0 - 0.75f64.sqrt()));
        for u in [DVec2::ZERO, DVec2::new(0.5, 0.25), DVec2::new(0.999_999, 0.7)] {
            let sample = s.sample_toward(reference, u).unwrap();
            assert!((sample.point.length() - 1.0).abs() < 1e-14);
            assert!(sample.normal.dot(reference - sample.point) >= -1e-12, "faces the reference");
            assert!((sample.pdf_solid_angle - pdf).abs() < 1e-12 * pdf);
            assert_eq!(s.pdf_toward(reference, sample.point - reference), sample.pdf_solid_angle);
        }
        let axis = s.sample_toward(reference, DVec2::ZERO).unwrap().point;
        assert!(axis.distance(DVec3::Z) < 1e-15, "u.x = 0: the axis, got {axis}");
        assert_eq!(s.pdf_toward(reference, DVec3::new(0.0, 1.0, -1.0)), 0.0, "outside the cone");
        assert!((s.pdf_toward(reference, -DVec3::Z * 3.0) - pdf).abs() < 1e-12 * pdf, "any length");
        // From inside, area sampling: the density of the single crossing.
        let inside = s.sample_toward(DVec3::ZERO, DVec2::new(0.3, 0.3)).unwrap();
        assert!((inside.pdf_solid_angle - 1.0 / (4.0 * PI)).abs() < 1e-12, "{}", inside.pdf_solid_angle);
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
        check_t_range(&s, DVec3::new(0.0, 0.0, 5.0), -DVec3::Z, 4.0, 6.0);
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
