//! The rectangle shape plugin: Mitsuba 3's `rectangle`, a flat rectangle of zero thickness in
//! the z = 0 plane of object space, centred on the origin, facing +z.

#![forbid(unsafe_code)]

use std::sync::Arc;

use prism_api::{
    Aabb, AreaSample, DVec2, DVec3, DirectionSample, Hit, ParamError, Ray, Shape, ShapeParams, Surface, pov,
};
use schemars::JsonSchema;
use serde::Deserialize;

/// Rays with `|d.z| <= PARALLEL_EPSILON * |d|` run along the rectangle's plane and miss it,
/// as for the disc; otherwise a ray lying in the plane would hit at a `t` chosen by rounding.
pub const PARALLEL_EPSILON: f64 = 1e-12;

/// Parameters of `shape = "rectangle"`.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RectangleParams {
    /// Full side lengths `[w, h]` along x and y, each > 0: spans `[-w/2, w/2] x [-h/2, h/2]`.
    #[serde(default = "default_size")]
    pub size: [f64; 2],
}

fn default_size() -> [f64; 2] {
    [2.0, 2.0]
}

impl ShapeParams for RectangleParams {
    fn build(self) -> Result<Arc<dyn Shape>, ParamError> {
        ParamError::require_finite("size", &self.size)?;
        if self.size.iter().any(|&s| s <= 0.0) {
            return Err(ParamError::new("size", format!("both sides must be greater than 0, got {:?}", self.size)));
        }
        Ok(Arc::new(Rectangle::new(self.size[0], self.size[1])))
    }
}

/// The rectangle `[-w/2, w/2] x [-h/2, h/2]` in the z = 0 plane, normal +z. It has no
/// inside and is hit from both sides; the normal is +z from either side.
#[derive(Clone, Debug, PartialEq)]
pub struct Rectangle {
    /// Half the side along x (> 0).
    pub half_width: f64,
    /// Half the side along y (> 0).
    pub half_height: f64,
}

impl Rectangle {
    /// The rectangle of full side lengths `width` (along x) and `height` (along y), both > 0.
    pub fn new(width: f64, height: f64) -> Self {
        Self { half_width: 0.5 * width, half_height: 0.5 * height }
    }

    /// The four corners, counter-clockwise seen from +z, starting at `(-w/2, -h/2)`.
    pub fn corners(&self) -> [DVec3; 4] {
        let (a, b) = (self.half_width, self.half_height);
        [DVec3::new(-a, -b, 0.0), DVec3::new(a, -b, 0.0), DVec3::new(a, b, 0.0), DVec3::new(-a, b, 0.0)]
    }
}

impl Shape for Rectangle {
    /// Flat: a surface inside nothing, in CSG too (POV-Ray's `Inside` of a flat shape).
    fn has_inside(&self) -> bool {
        false
    }

    fn bounds(&self) -> Aabb {
        // Flat in z, like the disc's box in its normal's axis; the BVH pads boxes outward.
        Aabb::from_corners(
            DVec3::new(-self.half_width, -self.half_height, 0.0),
            DVec3::new(self.half_width, self.half_height, 0.0),
        )
    }

    fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit> {
        let dz = ray.direction.z;
        if dz.abs() <= PARALLEL_EPSILON * ray.direction.length() {
            return None;
        }
        let t = -ray.origin.z / dz;
        if !(t > t_min && t < t_max) {
            return None;
        }
        let x = ray.origin.x + t * ray.direction.x;
        let y = ray.origin.y + t * ray.direction.y;
        (x.abs() <= self.half_width && y.abs() <= self.half_height).then(|| Hit::at(t))
    }

    fn surface(&self, ray: &Ray, hit: &Hit) -> Surface {
        let p = ray.at(hit.t);
        // On the plane exactly: removes the rounding error of ray.at(t) along the normal.
        let point = DVec3::new(p.x, p.y, 0.0);
        let (w, h) = (2.0 * self.half_width, 2.0 * self.half_height);
        let uv =
            DVec2::new(((p.x + self.half_width) / w).clamp(0.0, 1.0), ((p.y + self.half_height) / h).clamp(0.0, 1.0));
        let mut surface = Surface::new(point, DVec3::Z, uv).with_dpdu(DVec3::new(w, 0.0, 0.0));
        surface.uv_density = 1.0 / (w * h).sqrt();
        surface
    }

    fn area(&self) -> Option<f64> {
        Some(4.0 * self.half_width * self.half_height)
    }

    fn sample_area(&self, u: DVec2) -> Option<AreaSample> {
        Some(AreaSample {
            point: DVec3::new((2.0 * u.x - 1.0) * self.half_width, (2.0 * u.y - 1.0) * self.half_height, 0.0),
            normal: DVec3::Z,
            pdf_area: 1.0 / self.area()?,
        })
    }

    /// A flat rectangle is crossed at most once: its area sample is the nearest crossing.
    fn sample_toward(&self, reference: DVec3, u: DVec2) -> Option<DirectionSample> {
        prism_api::sample_toward_flat(self, reference, u)
    }

    fn to_pov(&self) -> Option<String> {
        // A closed polygon: the first point repeated at the end, as POV-Ray 3.7 wants.
        let c = self.corners();
        let points = [c[0], c[1], c[2], c[3], c[0]].map(pov::vector).join(", ");
        Some(format!("polygon {{ 5, {points} }}"))
    }

    fn to_mitsuba(&self) -> Option<Vec<prism_api::mitsuba::MitsubaShape>> {
        let place = prism_api::DAffine3::from_scale(DVec3::new(self.half_width, self.half_height, 1.0));
        Some(vec![prism_api::mitsuba::MitsubaShape::new(prism_api::mitsuba::MitsubaKind::Rectangle, place)])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use prism_api::contract::{ContractConfig, check_dpdu, check_sampling_toward, check_shape};

    fn params(size: [f64; 2]) -> RectangleParams {
        RectangleParams { size }
    }

    #[test]
    fn contract_holds() {
        check_shape(&Rectangle::new(2.0, 2.0));
        check_shape(&Rectangle::new(50.0, 0.5));
        check_shape(&Rectangle::new(1e-3, 2e-3));
        check_dpdu(&Rectangle::new(3.0, 1.5));
    }

    #[test]
    fn sampling_from_close_above_beside_and_grazing() {
        let r = Rectangle::new(2.0, 1.0);
        let references = [
            DVec3::new(0.0, 0.0, 0.05),
            DVec3::new(0.9, 0.4, -0.1),
            DVec3::new(3.0, 0.0, 0.02),
            DVec3::new(-0.2, 5.0, 1.0),
        ];
        check_sampling_toward(&r, &references, &ContractConfig::default());
    }

    #[test]
    fn hits_and_misses_at_the_edges() {
        let r = Rectangle::new(4.0, 2.0);
        let down = |x: f64, y: f64| Ray::new(DVec3::new(x, y, 1.0), -DVec3::Z);
        let hit = |x, y| r.intersect(&down(x, y), 0.0, f64::INFINITY).is_some();
        assert!(hit(2.0 - 1e-12, 0.0) && !hit(2.0 + 1e-12, 0.0));
        assert!(hit(-2.0 + 1e-12, 0.0) && !hit(-2.0 - 1e-12, 0.0));
        assert!(hit(0.0, 1.0 - 1e-12) && !hit(0.0, 1.0 + 1e-12));
        assert!(hit(0.0, -1.0 + 1e-12) && !hit(0.0, -1.0 - 1e-12));
        assert!(hit(2.0, 1.0), "the corner itself belongs to the rectangle");
        let away = Ray::new(DVec3::new(0.0, 0.0, 1.0), DVec3::Z);
        assert!(r.intersect(&away, 0.0, f64::INFINITY).is_none());
        let grazing = Ray::new(DVec3::new(-5.0, 0.0, 0.0), DVec3::X);
        assert!(r.intersect(&grazing, 0.0, f64::INFINITY).is_none());
        let slow = Ray::new(DVec3::new(0.5, 0.5, 2.0), DVec3::new(0.0, 0.0, -4.0));
        let h = r.intersect(&slow, 0.0, f64::INFINITY).unwrap();
        assert!((h.t - 0.5).abs() < 1e-15, "t in the caller's units, |d| = 4");
        assert!(r.intersect(&slow, 0.0, 0.5).is_none() && r.intersect(&slow, 0.5, 1.0).is_none(), "exclusive range");
    }

    #[test]
    fn uv_at_the_corners_and_tangent() {
        let r = Rectangle::new(4.0, 2.0);
        for (corner, uv) in r.corners().into_iter().zip([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]) {
            let ray = Ray::new(corner + DVec3::Z, -DVec3::Z);
            let s = r.surface(&ray, &r.intersect(&ray, 0.0, f64::INFINITY).unwrap());
            assert_eq!(s.uv, DVec2::from_array(uv), "corner {corner}");
            assert_eq!(s.dpdu, DVec3::new(4.0, 0.0, 0.0));
            assert!((s.uv_density - 1.0 / 8f64.sqrt()).abs() < 1e-15);
        }
        // Mitsuba's default square: uv = ((x + 1) / 2, (y + 1) / 2).
        let square = Rectangle::new(2.0, 2.0);
        let ray = Ray::new(DVec3::new(0.5, -0.5, 1.0), -DVec3::Z);
        let s = square.surface(&ray, &square.intersect(&ray, 0.0, f64::INFINITY).unwrap());
        assert_eq!(s.uv, DVec2::new(0.75, 0.25));
        assert_eq!(s.dpdu, DVec3::new(2.0, 0.0, 0.0));
    }

    #[test]
    fn back_side_hit_keeps_the_normal_plus_z() {
        let r = Rectangle::new(2.0, 2.0);
        let up = Ray::new(DVec3::new(0.3, -0.2, -1.0), DVec3::new(0.1, 0.0, 1.0));
        let hit = r.intersect(&up, 1e-9, f64::INFINITY).unwrap();
        let s = r.surface(&up, &hit);
        assert_eq!(s.normal, DVec3::Z);
        assert_eq!(s.point.z, 0.0);
        assert!((s.point.x - 0.4).abs() < 1e-15);
        assert!(!r.inside(DVec3::ZERO));
    }

    #[test]
    fn samples_are_uniform_on_the_rectangle() {
        let r = Rectangle::new(4.0, 2.0);
        assert_eq!(r.area(), Some(8.0));
        let s = r.sample_area(DVec2::new(0.0, 1.0)).unwrap();
        assert_eq!(s.point, DVec3::new(-2.0, 1.0, 0.0));
        assert_eq!(s.pdf_area, 0.125);
        assert_eq!(r.sample_area(DVec2::splat(0.5)).unwrap().point, DVec3::ZERO);
    }

    #[test]
    fn parameters_are_validated() {
        let err = |p: RectangleParams| p.build().unwrap_err().key;
        assert_eq!(err(params([0.0, 1.0])), "size");
        assert_eq!(err(params([1.0, -1.0])), "size");
        assert_eq!(err(params([f64::INFINITY, 1.0])), "size");
        assert_eq!(err(params([1.0, f64::NAN])), "size");
        assert!(params([1.0, 3.0]).build().is_ok());
        let parsed = RectangleParams::deserialize(
            serde::de::value::MapDeserializer::<_, serde::de::value::Error>::new(std::iter::empty::<(String, f64)>()),
        )
        .unwrap();
        assert_eq!(parsed.size, [2.0, 2.0], "Mitsuba's square by default");
    }

    #[test]
    fn exports_a_closed_polygon_with_z_mirrored() {
        let r = Rectangle::new(4.0, 2.0);
        assert_eq!(
            r.to_pov().unwrap(),
            "polygon { 5, <-2.0, -1.0, -0.0>, <2.0, -1.0, -0.0>, <2.0, 1.0, -0.0>, <-2.0, 1.0, -0.0>, <-2.0, -1.0, -0.0> }"
        );
    }
}
