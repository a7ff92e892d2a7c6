//! The plane shape plugin: the infinite plane of points `p` with `normal · p = offset`.

#![forbid(unsafe_code)]

use std::sync::Arc;

use prism_api::{Aabb, DVec2, DVec3, Hit, HitPoint, ParamError, Ray, Shape, ShapeParams, Surface, math, pov};
use schemars::JsonSchema;
use serde::Deserialize;

/// Rays whose direction makes `|normal · d| <= PARALLEL_EPSILON * |d|` with the plane are
/// treated as parallel to it and miss. Such a ray would meet the plane more than 10^12 times
/// its distance from it away, and a ray lying in the plane would otherwise report a hit at
/// an arbitrary `t` decided by rounding noise. POV-Ray has the same cut-off (1e-10).
pub const PARALLEL_EPSILON: f64 = 1e-12;

/// Parameters of `shape = "plane"`.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct PlaneParams {
    /// Normal, any non-zero length (normalised); points out of the solid side `normal · p < offset`.
    #[serde(default = "default_normal")]
    pub normal: [f64; 3],
    /// Signed distance from the origin along the normalised normal: the plane `normal · p = offset`.
    #[serde(default)]
    pub offset: f64,
}

fn default_normal() -> [f64; 3] {
    [0.0, 1.0, 0.0]
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

impl ShapeParams for PlaneParams {
    fn build(self) -> Result<Arc<dyn Shape>, ParamError> {
        ParamError::require_finite("normal", &self.normal)?;
        let normal = unit_vector(self.normal)
            .ok_or_else(|| ParamError::new("normal", format!("must be non-zero, got {:?}", self.normal)))?;
        ParamError::require_finite("offset", &[self.offset])?;
        Ok(Arc::new(Plane::new(normal, self.offset)))
    }
}

/// Side of the square that stands in for an infinite plane in Mitsuba 3 (scene units).
pub const MITSUBA_PLANE_SIZE: f64 = 1e5;

/// An infinite plane `normal · p = offset`, one-sided only in the direction of its normal.
#[derive(Clone, Debug, PartialEq)]
pub struct Plane {
    /// Unit normal, pointing out of the solid half-space.
    pub normal: DVec3,
    /// Signed distance from the origin along `normal`.
    pub offset: f64,
    /// First texture axis, a unit vector in the plane.
    tangent: DVec3,
    /// Second texture axis, a unit vector in the plane perpendicular to `tangent`.
    bitangent: DVec3,
}

impl Plane {
    /// The plane `normal · p = offset`; `normal` must be unit length.
    pub fn new(normal: DVec3, offset: f64) -> Self {
        let (tangent, bitangent) = math::orthonormal_basis(normal);
        Self { normal, offset, tangent, bitangent }
    }
}

impl Shape for Plane {
    fn bounds(&self) -> Aabb {
        Aabb::INFINITE
    }

    // Inline: the scene's list of unbounded primitives calls a plane by its own type.
    #[inline]
    fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit> {
        // Every ray meets the infinite planes first, just after it was built.
        let ray = &Ray::new(math::load_components(&ray.origin), math::load_components(&ray.direction));
        let along = self.normal.dot(ray.direction);
        // |along| <= eps |d|, squared: no square root on this hot path.
        if along * along <= PARALLEL_EPSILON * PARALLEL_EPSILON * ray.direction.length_squared() {
            return None;
        }
        let distance = self.offset - self.normal.dot(ray.origin);
        // Most rays meet most infinite planes behind them or beyond a nearer hit: reject those
        // without the division. A quotient has the sign of its operands, and the margin on
        // the far test (with a normal product) leaves every close call to the exact t below.
        let behind = distance == 0.0 || (distance > 0.0) != (along > 0.0);
        let limit = t_max * along.abs();
        let beyond = !behind && limit.is_normal() && distance.abs() >= limit * (1.0 + 4.0 * f64::EPSILON);
        if (behind && t_min >= 0.0) || beyond {
            return None;
        }
        let t = distance / along;
        (t > t_min && t < t_max).then(|| Hit::at(t))
    }

    fn inside(&self, point: DVec3) -> bool {
        // The solid half-space, as in POV-Ray: behind the normal, and its skin in front.
        self.normal.dot(math::load_components(&point)) - self.offset < prism_api::pov::EPSILON
    }

    #[inline]
    fn misses_hull(&self, points: &[DVec3]) -> bool {
        // Every point strictly on one side, by more than rounding in their signed distances.
        let scale = points.iter().fold(self.offset.abs(), |m, p| m.max(p.abs().max_element()));
        let margin = 1e-9 * scale.max(1.0);
        let side = |p: &DVec3| self.normal.dot(*p) - self.offset;
        points.iter().all(|p| side(p) > margin) || points.iter().all(|p| side(p) < -margin)
    }

    fn surface(&self, ray: &Ray, hit: &Hit) -> Surface {
        let HitPoint { point, normal, .. } = self.hit_point(ray, hit);
        let uv = DVec2::new(point.dot(self.tangent), point.dot(self.bitangent));
        Surface::new(point, normal, uv).with_dpdu(self.tangent)
    }

    fn hit_point(&self, ray: &Ray, hit: &Hit) -> HitPoint {
        let p = ray.at(hit.t);
        // Project onto the plane: removes the rounding error of ray.at(t) along the normal.
        HitPoint::new(p - self.normal * (self.normal.dot(p) - self.offset), self.normal)
    }

    /// An infinite plane has no finite area to sample uniformly: it cannot be an area light.
    fn can_emit(&self) -> bool {
        false
    }

    fn to_pov(&self) -> Option<String> {
        Some(format!("plane {{ {}, {} }}", pov::vector(self.normal), pov::number(self.offset)))
    }

    /// Mitsuba has no infinite plane: a square of side [`MITSUBA_PLANE_SIZE`] centred on the
    /// plane's point nearest the origin stands in for it.
    fn to_mitsuba(&self) -> Option<Vec<prism_api::mitsuba::MitsubaShape>> {
        let frame = prism_api::mitsuba::frame_with_z(self.normal);
        let half = 0.5 * MITSUBA_PLANE_SIZE;
        let place = prism_api::DAffine3::from_mat3_translation(
            prism_api::DMat3::from_cols(frame.x_axis * half, frame.y_axis * half, frame.z_axis),
            self.normal * self.offset,
        );
        // Mitsuba's (u, v) spans the square once; the plane's is the position in it.
        Some(vec![
            prism_api::mitsuba::MitsubaShape::new(prism_api::mitsuba::MitsubaKind::Rectangle, place).with_other_uv(),
        ])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// POV-Ray's `Plane::Inside`: a skin of 1e-10 in front of the plane is inside.
    #[test]
    fn the_skin_in_front_is_inside() {
        let p = Plane::new(DVec3::Y, 1.0);
        assert!(p.inside(DVec3::new(0.0, 1.0 + 5e-11, 0.0)) && !p.inside(DVec3::new(0.0, 1.0 + 2e-10, 0.0)));
    }
    use prism_api::contract::{check_dpdu, check_shape};

    fn ground() -> Plane {
        Plane::new(DVec3::Y, 0.0)
    }

    fn build(normal: [f64; 3], offset: f64) -> Result<Arc<dyn Shape>, ParamError> {
        PlaneParams { normal, offset }.build()
    }

    #[test]
    fn misses_a_hull_only_on_one_side() {
        let plane = ground();
        let above = [DVec3::new(0.0, 0.5, 0.0), DVec3::new(3.0, 2.0, -1.0), DVec3::new(-1.0, 1e-3, 4.0)];
        assert!(plane.misses_hull(&above));
        assert!(plane.misses_hull(&above.map(|p| -p)), "wholly below");
        assert!(!plane.misses_hull(&[above[0], above[1], DVec3::new(0.0, -0.1, 0.0)]), "straddles");
        assert!(!plane.misses_hull(&[above[0], DVec3::new(2.0, 0.0, 1.0)]), "touches");
    }

    #[test]
    fn quick_rejections_agree_with_the_exact_test() {
        let plane = Plane::new(DVec3::new(0.3, 1.0, -0.2).normalize(), 0.7);
        let exact = |ray: &Ray, t_min: f64, t_max: f64| {
            let t = (plane.offset - plane.normal.dot(ray.origin)) / plane.normal.dot(ray.direction);
            (t > t_min && t < t_max).then_some(t)
        };
        let mut hits = 0;
        for i in 0..2000 {
            let f = f64::from(i);
            let origin = DVec3::new((f * 0.37).sin() * 3.0, (f * 0.11).cos() * 3.0, (f * 0.53).sin());
            let direction = DVec3::new((f * 1.7).cos(), (f * 0.9).sin(), (f * 2.3).cos());
            let ray = Ray::new(origin, direction);
            let t = exact(&ray, f64::NEG_INFINITY, f64::INFINITY).unwrap_or(1.0);
            // Bounds at, just around and far from the hit, and below zero.
            for (t_min, t_max) in [
                (0.0, f64::INFINITY),
                (0.0, t),
                (0.0, t.next_up()),
                (0.0, t.next_down()),
                (-10.0, 10.0),
                (t.next_down(), 100.0),
                (1e-6, t * (1.0 + 1e-15)),
            ] {
                let got = plane.intersect(&ray, t_min, t_max).map(|h| h.t);
                assert_eq!(got, exact(&ray, t_min, t_max), "ray {i}, ({t_min}, {t_max})");
                hits += usize::from(got.is_some());
            }
        }
        assert!(hits > 2000, "{hits}");
    }

    #[test]
    fn contract_holds() {
        check_shape(&ground());
        check_shape(&Plane::new(DVec3::new(1.0, 2.0, -3.0).normalize(), 0.7));
        check_shape(&Plane::new(-DVec3::Z, -1.5));
        check_dpdu(&Plane::new(DVec3::new(1.0, 2.0, -3.0).normalize(), 0.7));
        assert!(!ground().can_emit());
    }

    #[test]
    fn hit_from_above_and_below() {
        let p = ground();
        let above = Ray::new(DVec3::new(0.5, 3.0, 0.0), DVec3::new(0.0, -2.0, 0.0));
        let hit = p.intersect(&above, 1e-9, f64::INFINITY).unwrap();
        assert!((hit.t - 1.5).abs() < 1e-15, "t in the caller's units, |d| = 2");
        let s = p.surface(&above, &hit);
        assert_eq!(s.normal, DVec3::Y);
        assert!(s.point.y.abs() < 1e-15);
        // From the solid side the normal still points out of it.
        let below = Ray::new(DVec3::new(0.0, -1.0, 0.0), DVec3::new(0.0, 1.0, 1.0));
        let hit = p.intersect(&below, 1e-9, f64::INFINITY).unwrap();
        assert!((hit.t - 1.0).abs() < 1e-15);
        assert_eq!(p.surface(&below, &hit).normal, DVec3::Y);
    }

    #[test]
    fn behind_parallel_and_t_range() {
        let p = ground();
        let away = Ray::new(DVec3::new(0.0, 1.0, 0.0), DVec3::Y);
        assert!(p.intersect(&away, 1e-9, f64::INFINITY).is_none());
        let parallel = Ray::new(DVec3::new(0.0, 1.0, 0.0), DVec3::X);
        assert!(p.intersect(&parallel, 1e-9, f64::INFINITY).is_none());
        let in_plane = Ray::new(DVec3::ZERO, DVec3::new(1.0, 1e-17, 0.0));
        assert!(p.intersect(&in_plane, 1e-9, f64::INFINITY).is_none());
        let down = Ray::new(DVec3::new(0.0, 1.0, 0.0), -DVec3::Y);
        assert!(p.intersect(&down, 1e-9, 1.0).is_none(), "t_max is exclusive");
        assert!(p.intersect(&down, 1.0, 5.0).is_none(), "t_min is exclusive");
        assert!(p.intersect(&down, 0.999, 1.001).is_some());
    }

    #[test]
    fn grazing_ray_lands_on_the_plane() {
        let p = Plane::new(DVec3::new(0.3, 1.0, -0.2).normalize(), 2.0);
        let ray = Ray::new(DVec3::new(-1e4, 1.0, 3.0), DVec3::new(1.0, -1e-3, 0.0));
        let hit = p.intersect(&ray, 1e-9, f64::INFINITY).unwrap();
        let s = p.surface(&ray, &hit);
        assert!((p.normal.dot(s.point) - p.offset).abs() < 1e-12);
        assert!((s.normal.length() - 1.0).abs() < 1e-15);
    }

    #[test]
    fn uv_is_planar_and_unwrapped() {
        let p = ground();
        let ray = Ray::new(DVec3::new(7.0, 1.0, -3.0), -DVec3::Y);
        let hit = p.intersect(&ray, 0.0, f64::INFINITY).unwrap();
        let uv = p.surface(&ray, &hit).uv;
        assert!((uv.length() - 58f64.sqrt()).abs() < 1e-12, "uv is the in-plane position");
    }

    #[test]
    fn parameters_are_validated_and_normalised() {
        assert_eq!(build([0.0; 3], 0.0).unwrap_err().key, "normal");
        assert_eq!(build([f64::NAN, 1.0, 0.0], 0.0).unwrap_err().key, "normal");
        assert_eq!(build([0.0, 1.0, 0.0], f64::INFINITY).unwrap_err().key, "offset");
        // A long normal is normalised; the offset is measured along the unit normal.
        let p = build([0.0, 1e300, 0.0], 2.0).unwrap();
        let ray = Ray::new(DVec3::new(0.0, 5.0, 0.0), -DVec3::Y);
        assert!((p.intersect(&ray, 0.0, f64::INFINITY).unwrap().t - 3.0).abs() < 1e-15);
        assert!(build([0.0, 1e-310, 0.0], 2.0).is_ok(), "subnormal but non-zero");
    }

    #[test]
    fn exports_to_pov_with_z_mirrored() {
        let p = Plane::new(DVec3::new(0.0, 0.6, 0.8), 2.5);
        assert_eq!(p.to_pov().unwrap(), "plane { <0.0, 0.6, -0.8>, 2.5 }");
    }
}
