//! The disc shape plugin: a flat disc (or annulus, with a hole) of zero thickness.

#![forbid(unsafe_code)]

use std::f64::consts::{PI, TAU};
use std::sync::Arc;

use prism_api::{
    Aabb, AreaSample, DVec2, DVec3, DirectionSample, Hit, HitPoint, ParamError, Ray, Shape, ShapeParams, Surface, math,
    pov,
};
use schemars::JsonSchema;
use serde::Deserialize;

/// Rays with `|normal · d| <= PARALLEL_EPSILON * |d|` run along the disc's plane and miss it,
/// as in POV-Ray; otherwise a ray lying in the plane would hit at a `t` chosen by rounding.
pub const PARALLEL_EPSILON: f64 = 1e-12;

/// Parameters of `shape = "disc"`.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct DiscParams {
    /// Centre of the disc in object space.
    #[serde(default)]
    pub center: [f64; 3],
    /// Normal of the disc's plane, any non-zero length (normalised); the front side.
    #[serde(default = "default_normal")]
    pub normal: [f64; 3],
    /// Outer radius; must be greater than 0.
    #[serde(default = "default_radius")]
    pub radius: f64,
    /// Radius of the hole in the middle; at least 0 and less than `radius` (0: no hole).
    #[serde(default)]
    pub hole_radius: f64,
}

fn default_normal() -> [f64; 3] {
    [0.0, 1.0, 0.0]
}

fn default_radius() -> f64 {
    1.0
}

/// `v` normalised, or `None` when it is zero or not finite. Scaling by the largest component
/// first keeps huge and tiny vectors from overflowing or underflowing.
fn unit_vector(v: [f64; 3]) -> Option<DVec3> {
    let v = DVec3::from_array(v);
    let largest = v.abs().max_element();
    if !largest.is_finite() || largest == 0.0 {
        return None;
    }
    (v / largest).try_normalize()
}

impl ShapeParams for DiscParams {
    fn build(self) -> Result<Arc<dyn Shape>, ParamError> {
        ParamError::require_finite("center", &self.center)?;
        ParamError::require_finite("normal", &self.normal)?;
        let normal = unit_vector(self.normal)
            .ok_or_else(|| ParamError::new("normal", format!("must be non-zero, got {:?}", self.normal)))?;
        ParamError::require_positive("radius", self.radius)?;
        ParamError::require_non_negative("hole_radius", self.hole_radius)?;
        if self.hole_radius >= self.radius {
            return Err(ParamError::new(
                "hole_radius",
                format!("must be less than `radius` ({}), got {}", self.radius, self.hole_radius),
            ));
        }
        Ok(Arc::new(Disc::new(DVec3::from_array(self.center), normal, self.radius, self.hole_radius)))
    }
}

/// A disc of zero thickness around `center` in the plane perpendicular to `normal`, with an
/// optional hole: the points at distance `hole_radius..=radius` from the centre.
#[derive(Clone, Debug, PartialEq)]
pub struct Disc {
    /// Centre in object space.
    pub center: DVec3,
    /// Unit normal, the front side.
    pub normal: DVec3,
    /// Outer radius (> 0).
    pub radius: f64,
    /// Hole radius (0 <= hole_radius < radius).
    pub hole_radius: f64,
    /// In-plane unit vector where the texture's `u` is 0.
    tangent: DVec3,
    /// In-plane unit vector a quarter turn from `tangent` (`u` = 0.25).
    bitangent: DVec3,
}

impl Disc {
    /// The disc around `center` with unit `normal`; `0 <= hole_radius < radius`.
    pub fn new(center: DVec3, normal: DVec3, radius: f64, hole_radius: f64) -> Self {
        let (tangent, bitangent) = math::orthonormal_basis(normal);
        Self { center, normal, radius, hole_radius, tangent, bitangent }
    }

    /// A hit's offset from the centre, projected onto the plane: removes the rounding of
    /// `ray.at(t)` along the normal.
    fn in_plane(&self, ray: &Ray, hit: &Hit) -> DVec3 {
        let local = ray.at(hit.t) - self.center;
        local - self.normal * self.normal.dot(local)
    }
}

impl Shape for Disc {
    fn bounds(&self) -> Aabb {
        // A circle of radius r perpendicular to n reaches r * sqrt(1 - n_i^2) along axis i.
        let extent = self.radius * (DVec3::ONE - self.normal * self.normal).max(DVec3::ZERO).sqrt();
        Aabb::from_corners(self.center - extent, self.center + extent)
    }

    /// POV-Ray's `Disc::Inside`: the whole half-space behind the disc's plane (away from the
    /// normal), hole and all, which is what a disc bounds in CSG (an intersection of a sphere
    /// and a disc is the part of the sphere behind the disc's plane, capped by the disc).
    fn inside(&self, point: DVec3) -> bool {
        (point - self.center).dot(self.normal) < 0.0
    }

    fn inside_bounds(&self) -> Aabb {
        Aabb::INFINITE
    }

    fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit> {
        let along = self.normal.dot(ray.direction);
        if along.abs() <= PARALLEL_EPSILON * ray.direction.length() {
            return None;
        }
        let oc = self.center - ray.origin;
        let t = self.normal.dot(oc) / along;
        if !(t > t_min && t < t_max) {
            return None;
        }
        let r2 = (t * ray.direction - oc).length_squared();
        (r2 <= self.radius * self.radius && r2 >= self.hole_radius * self.hole_radius).then(|| Hit::at(t))
    }

    fn surface(&self, ray: &Ray, hit: &Hit) -> Surface {
        let mut surface = self.surface_geometry(ray, hit);
        let local = surface.point - self.center;
        let angle = local.dot(self.bitangent).atan2(local.dot(self.tangent));
        surface.uv = DVec2::new((angle / TAU).rem_euclid(1.0), (local.length() / self.radius).min(1.0));
        surface
    }

    fn surface_geometry(&self, ray: &Ray, hit: &Hit) -> Surface {
        let local = self.in_plane(ray, hit);
        // u turns the point about the centre by a full turn (no tangent at the centre itself).
        Surface::new(self.center + local, self.normal, DVec2::ZERO).with_dpdu(TAU * self.normal.cross(local))
    }

    fn hit_point(&self, ray: &Ray, hit: &Hit) -> HitPoint {
        HitPoint::new(self.center + self.in_plane(ray, hit), self.normal)
    }

    fn area(&self) -> Option<f64> {
        Some(PI * (self.radius * self.radius - self.hole_radius * self.hole_radius))
    }

    fn sample_area(&self, u: DVec2) -> Option<AreaSample> {
        // Uniform in area: r^2 is uniform between hole^2 and radius^2.
        let h2 = self.hole_radius * self.hole_radius;
        let r = (h2 + u.x * (self.radius * self.radius - h2)).sqrt();
        let (sin, cos) = (TAU * u.y).sin_cos();
        Some(AreaSample {
            point: self.center + r * (cos * self.tangent + sin * self.bitangent),
            normal: self.normal,
            pdf_area: 1.0 / self.area()?,
        })
    }

    /// A flat disc is crossed at most once: its area sample is the nearest crossing.
    fn sample_toward(&self, reference: DVec3, u: DVec2) -> Option<DirectionSample> {
        prism_api::sample_toward_flat(self, reference, u)
    }

    fn to_pov(&self) -> Option<String> {
        let hole = if self.hole_radius > 0.0 { format!(", {}", pov::number(self.hole_radius)) } else { String::new() };
        Some(format!(
            "disc {{ {}, {}, {}{hole} }}",
            pov::vector(self.center),
            pov::vector(self.normal),
            pov::number(self.radius)
        ))
    }

    fn to_mitsuba(&self) -> Option<Vec<prism_api::mitsuba::MitsubaShape>> {
        if self.hole_radius > 0.0 {
            return None;
        }
        let frame = prism_api::mitsuba::frame_with_z(self.normal);
        let place = prism_api::DAffine3::from_mat3_translation(frame * self.radius, self.center);
        // Mitsuba's disk has (u, v) = (r, angle), the disc (angle, r).
        Some(vec![prism_api::mitsuba::MitsubaShape::new(prism_api::mitsuba::MitsubaKind::Disk, place).with_other_uv()])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// POV-Ray's `Disc::Inside`: the whole half-space behind the disc, hole and all.
    #[test]
    fn the_half_space_behind_is_inside() {
        let d = Disc::new(DVec3::Y, DVec3::Y, 1.0, 0.5);
        assert!(d.inside(DVec3::new(10.0, 0.5, -7.0)) && d.inside(DVec3::new(0.0, 0.9, 0.0)));
        assert!(!d.inside(DVec3::new(0.0, 1.1, 0.0)) && !d.inside(DVec3::new(5.0, 1.0, 0.0)));
        assert!(!d.inside_bounds().is_bounded());
    }
    use prism_api::contract::{ContractConfig, check_dpdu, check_sampling_toward, check_shape};

    fn unit() -> Disc {
        Disc::new(DVec3::ZERO, DVec3::Y, 1.0, 0.0)
    }

    fn params() -> DiscParams {
        DiscParams { center: [0.0; 3], normal: [0.0, 1.0, 0.0], radius: 1.0, hole_radius: 0.0 }
    }

    #[test]
    fn contract_holds() {
        check_shape(&unit());
        check_shape(&Disc::new(DVec3::new(1.0, -2.0, 0.5), DVec3::new(1.0, 2.0, 3.0).normalize(), 50.0, 10.0));
        check_shape(&Disc::new(DVec3::new(0.1, 0.2, 0.3), DVec3::Z, 1e-3, 5e-4));
        check_dpdu(&Disc::new(DVec3::new(1.0, -2.0, 0.5), DVec3::new(1.0, 2.0, 3.0).normalize(), 5.0, 1.0));
    }

    #[test]
    fn sampling_from_above_the_hole_and_at_a_grazing_angle() {
        let ring = Disc::new(DVec3::ZERO, DVec3::Y, 1.0, 0.5);
        let references = [DVec3::new(0.0, 0.1, 0.0), DVec3::new(0.2, -0.3, 0.1), DVec3::new(3.0, 0.05, 0.0)];
        check_sampling_toward(&ring, &references, &ContractConfig::default());
    }

    #[test]
    fn hit_from_front_and_back() {
        let d = unit();
        let front = Ray::new(DVec3::new(0.5, 2.0, 0.0), DVec3::new(0.0, -4.0, 0.0));
        let hit = d.intersect(&front, 1e-9, f64::INFINITY).unwrap();
        assert!((hit.t - 0.5).abs() < 1e-15, "t in the caller's units, |d| = 4");
        let s = d.surface(&front, &hit);
        assert_eq!(s.normal, DVec3::Y);
        assert!(s.point.y.abs() < 1e-15 && (s.point.x - 0.5).abs() < 1e-15);
        let back = Ray::new(DVec3::new(0.2, -1.0, 0.2), DVec3::Y);
        let hit = d.intersect(&back, 1e-9, f64::INFINITY).unwrap();
        assert!((hit.t - 1.0).abs() < 1e-15);
        assert_eq!(d.surface(&back, &hit).normal, DVec3::Y, "normal is the disc's own normal");
    }

    #[test]
    fn misses_outside_the_rim_in_the_hole_and_behind() {
        let d = Disc::new(DVec3::ZERO, DVec3::Y, 1.0, 0.5);
        let down = |x: f64| Ray::new(DVec3::new(x, 1.0, 0.0), -DVec3::Y);
        assert!(d.intersect(&down(1.0 + 1e-12), 0.0, f64::INFINITY).is_none());
        assert!(d.intersect(&down(1.0 - 1e-12), 0.0, f64::INFINITY).is_some());
        assert!(d.intersect(&down(0.3), 0.0, f64::INFINITY).is_none(), "in the hole");
        assert!(d.intersect(&down(0.5 + 1e-12), 0.0, f64::INFINITY).is_some());
        let away = Ray::new(DVec3::new(0.7, 1.0, 0.0), DVec3::Y);
        assert!(d.intersect(&away, 0.0, f64::INFINITY).is_none());
        let grazing = Ray::new(DVec3::new(-5.0, 0.0, 0.0), DVec3::X);
        assert!(d.intersect(&grazing, 0.0, f64::INFINITY).is_none());
    }

    #[test]
    fn t_range_is_exclusive() {
        let d = unit();
        let down = Ray::new(DVec3::new(0.0, 1.0, 0.0), -DVec3::Y);
        assert!(d.intersect(&down, 0.0, 1.0).is_none());
        assert!(d.intersect(&down, 1.0, 2.0).is_none());
        assert!(d.intersect(&down, 0.5, 1.5).is_some());
    }

    #[test]
    fn tilted_disc_hit_lies_on_it() {
        let n = DVec3::new(-1.0, 2.0, 0.5).normalize();
        let d = Disc::new(DVec3::new(3.0, 1.0, -2.0), n, 2.0, 0.0);
        let ray = Ray::new(DVec3::new(3.3, 10.0, -2.1), DVec3::new(0.01, -0.3, 0.02));
        let hit = d.intersect(&ray, 1e-9, f64::INFINITY).unwrap();
        let s = d.surface(&ray, &hit);
        assert!(n.dot(s.point - d.center).abs() < 1e-14);
        assert!(s.point.distance(ray.at(hit.t)) < 1e-12);
        assert!((s.normal.length() - 1.0).abs() < 1e-15);
        assert!(s.uv.x >= 0.0 && s.uv.x < 1.0 && s.uv.y >= 0.0 && s.uv.y <= 1.0);
    }

    #[test]
    fn samples_lie_on_the_annulus() {
        let d = Disc::new(DVec3::new(1.0, 2.0, 3.0), DVec3::new(1.0, 1.0, 0.0).normalize(), 2.0, 1.0);
        assert!((d.area().unwrap() - 3.0 * PI).abs() < 1e-12);
        for (a, b) in [(0.0, 0.0), (0.999, 0.3), (0.5, 0.75)] {
            let s = d.sample_area(DVec2::new(a, b)).unwrap();
            let local = s.point - d.center;
            assert!(local.dot(d.normal).abs() < 1e-12);
            assert!(local.length() >= 1.0 - 1e-12 && local.length() <= 2.0 + 1e-12);
        }
    }

    #[test]
    fn parameters_are_validated() {
        let err = |p: DiscParams| p.build().unwrap_err().key;
        assert_eq!(err(DiscParams { radius: 0.0, ..params() }), "radius");
        assert_eq!(err(DiscParams { hole_radius: -0.1, ..params() }), "hole_radius");
        assert_eq!(err(DiscParams { hole_radius: 1.0, ..params() }), "hole_radius");
        assert_eq!(err(DiscParams { normal: [0.0; 3], ..params() }), "normal");
        assert_eq!(err(DiscParams { center: [0.0, f64::NAN, 0.0], ..params() }), "center");
        assert!(DiscParams { normal: [0.0, 0.0, 7.0], ..params() }.build().is_ok());
    }

    #[test]
    fn exports_to_pov_with_z_mirrored() {
        let d = Disc::new(DVec3::new(1.0, 2.0, 3.0), DVec3::Z, 2.0, 0.0);
        assert_eq!(d.to_pov().unwrap(), "disc { <1.0, 2.0, -3.0>, <0.0, 0.0, -1.0>, 2.0 }");
        let ring = Disc::new(DVec3::ZERO, DVec3::Y, 2.0, 0.5);
        assert_eq!(ring.to_pov().unwrap(), "disc { <0.0, 0.0, -0.0>, <0.0, 1.0, -0.0>, 2.0, 0.5 }");
    }
}
