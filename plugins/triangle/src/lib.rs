//! The triangle shape plugin: a single two-sided flat triangle.

#![forbid(unsafe_code)]

use std::sync::Arc;

use prism_api::{
    Aabb, AreaSample, DVec2, DVec3, DirectionSample, Hit, ParamError, Ray, Shape, ShapeParams, Surface, pov,
};
use schemars::JsonSchema;
use serde::Deserialize;

/// Rays with `|n̂ · d| <= PARALLEL_EPSILON * |d|` run along the triangle's plane and miss it;
/// otherwise a ray lying in the plane would hit at a `t` chosen by rounding noise.
pub const PARALLEL_EPSILON: f64 = 1e-12;

/// Triangles whose smallest angle has a sine below this are rejected as degenerate.
pub const DEGENERATE_SINE: f64 = 1e-12;

/// Parameters of `shape = "triangle"`.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct TriangleParams {
    /// The corners `[v0, v1, v2]`, not collinear; the normal is `(v1 - v0) x (v2 - v0)`.
    pub vertices: [[f64; 3]; 3],
}

impl ShapeParams for TriangleParams {
    fn build(self) -> Result<Arc<dyn Shape>, ParamError> {
        ParamError::require_finite("vertices", self.vertices.as_flattened())?;
        let [a, b, c] = self.vertices.map(DVec3::from_array);
        let (e1, e2) = (b - a, c - a);
        let twice_area = e1.cross(e2).length();
        if !(twice_area.is_finite() && twice_area > DEGENERATE_SINE * e1.length() * e2.length()) {
            return Err(ParamError::new(
                "vertices",
                format!("must be three corners that are not in a line, got {:?}", self.vertices),
            ));
        }
        Ok(Arc::new(Triangle::new([a, b, c])))
    }
}

/// A triangle intersected with Möller–Trumbore in f64; both sides are hit.
///
/// The hit's `scratch` holds the barycentric coordinates `(u, v, 0)` of the hit point
/// `(1 - u - v) v0 + u v1 + v v2`.
#[derive(Clone, Debug, PartialEq)]
pub struct Triangle {
    /// The corners `v0, v1, v2`.
    pub vertices: [DVec3; 3],
    /// `v1 - v0`.
    edge1: DVec3,
    /// `v2 - v0`.
    edge2: DVec3,
    /// Unit normal `normalize((v1 - v0) x (v2 - v0))`.
    normal: DVec3,
    /// `|(v1 - v0) x (v2 - v0)|`, twice the area.
    twice_area: f64,
}

impl Triangle {
    /// The triangle with corners `vertices`, which must not be collinear.
    pub fn new(vertices: [DVec3; 3]) -> Self {
        let edge1 = vertices[1] - vertices[0];
        let edge2 = vertices[2] - vertices[0];
        let cross = edge1.cross(edge2);
        Self { vertices, edge1, edge2, normal: cross.normalize(), twice_area: cross.length() }
    }

    /// The unit geometric normal, `normalize((v1 - v0) x (v2 - v0))`.
    pub fn normal(&self) -> DVec3 {
        self.normal
    }
}

impl Shape for Triangle {
    /// Flat: a surface inside nothing, in CSG too (POV-Ray's `Inside` of a flat shape).
    fn has_inside(&self) -> bool {
        false
    }

    fn bounds(&self) -> Aabb {
        Aabb::from_points(self.vertices)
    }

    fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit> {
        let pvec = ray.direction.cross(self.edge2);
        let det = self.edge1.dot(pvec);
        // det = -(e1 x e2) . d
        if det.abs() <= PARALLEL_EPSILON * self.twice_area * ray.direction.length() {
            return None;
        }
        let inv_det = 1.0 / det;
        let tvec = ray.origin - self.vertices[0];
        let u = tvec.dot(pvec) * inv_det;
        if !(0.0..=1.0).contains(&u) {
            return None;
        }
        let qvec = tvec.cross(self.edge1);
        let v = ray.direction.dot(qvec) * inv_det;
        if v < 0.0 || u + v > 1.0 {
            return None;
        }
        let t = self.edge2.dot(qvec) * inv_det;
        (t > t_min && t < t_max).then_some(Hit { t, part: 0, scratch: DVec3::new(u, v, 0.0) })
    }

    fn surface(&self, _ray: &Ray, hit: &Hit) -> Surface {
        let (u, v) = (hit.scratch.x, hit.scratch.y);
        // The barycentric point lies on the triangle up to rounding, unlike ray.at(t).
        let point = self.vertices[0] + u * self.edge1 + v * self.edge2;
        // The uv is (u, v) itself: p = v0 + u e1 + v e2.
        Surface::new(point, self.normal, DVec2::new(u, v)).with_dpdu(self.edge1)
    }

    fn area(&self) -> Option<f64> {
        Some(0.5 * self.twice_area)
    }

    fn sample_area(&self, u: DVec2) -> Option<AreaSample> {
        // Uniform barycentrics by the square-root warp.
        let su = u.x.sqrt();
        let (b1, b2) = (su * (1.0 - u.y), su * u.y);
        Some(AreaSample {
            point: self.vertices[0] + b1 * self.edge1 + b2 * self.edge2,
            normal: self.normal,
            pdf_area: 1.0 / self.area()?,
        })
    }

    /// A flat triangle is crossed at most once: its area sample is the nearest crossing.
    fn sample_toward(&self, reference: DVec3, u: DVec2) -> Option<DirectionSample> {
        prism_api::sample_toward_flat(self, reference, u)
    }

    fn to_pov(&self) -> Option<String> {
        let [a, b, c] = self.vertices.map(pov::vector);
        Some(format!("triangle {{ {a}, {b}, {c} }}"))
    }

    fn to_mitsuba(&self) -> Option<Vec<prism_api::mitsuba::MitsubaShape>> {
        let triangles = prism_api::mitsuba::TriangleList {
            positions: self.vertices.map(|v| v.as_vec3().to_array()).to_vec(),
            triangles: vec![[0, 1, 2]],
            ..Default::default()
        };
        Some(vec![prism_api::mitsuba::MitsubaShape::new(
            prism_api::mitsuba::MitsubaKind::Triangles(triangles),
            prism_api::DAffine3::IDENTITY,
        )])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use prism_api::contract::{check_dpdu, check_shape};

    fn xy() -> Triangle {
        Triangle::new([DVec3::ZERO, DVec3::X, DVec3::Y])
    }

    fn plane_distance(tri: &Triangle, p: DVec3) -> f64 {
        tri.normal().dot(p - tri.vertices[0])
    }

    #[test]
    fn contract_holds() {
        check_dpdu(&Triangle::new([
            DVec3::new(1.0, -2.0, 0.5),
            DVec3::new(3.0, 1.0, -1.0),
            DVec3::new(-2.0, 2.0, 2.0),
        ]));
        check_shape(&xy());
        check_shape(&Triangle::new([
            DVec3::new(-40.0, 0.0, -40.0),
            DVec3::new(40.0, 0.5, -30.0),
            DVec3::new(0.0, -0.3, 60.0),
        ]));
        check_shape(&Triangle::new([
            DVec3::new(1.0, 2.0, 3.0),
            DVec3::new(1.001, 2.0, 3.0),
            DVec3::new(1.0, 2.0005, 3.0007),
        ]));
    }

    #[test]
    fn hit_from_both_sides() {
        let tri = xy();
        let front = Ray::new(DVec3::new(0.25, 0.25, 2.0), DVec3::new(0.0, 0.0, -4.0));
        let hit = tri.intersect(&front, 1e-9, f64::INFINITY).unwrap();
        assert!((hit.t - 0.5).abs() < 1e-15, "t in the caller's units, |d| = 4");
        let s = tri.surface(&front, &hit);
        assert_eq!(s.normal, DVec3::Z);
        assert!(s.point.distance(DVec3::new(0.25, 0.25, 0.0)) < 1e-15);
        assert!(s.uv.distance(DVec2::new(0.25, 0.25)) < 1e-15, "uv = barycentric (u, v)");
        let back = Ray::new(DVec3::new(0.1, 0.6, -1.0), DVec3::Z);
        let hit = tri.intersect(&back, 1e-9, f64::INFINITY).unwrap();
        assert!((hit.t - 1.0).abs() < 1e-15);
        assert_eq!(tri.surface(&back, &hit).normal, DVec3::Z, "the geometric normal, not flipped");
    }

    #[test]
    fn edges_behind_and_t_range() {
        let tri = xy();
        let down = |x: f64, y: f64| Ray::new(DVec3::new(x, y, 1.0), -DVec3::Z);
        assert!(tri.intersect(&down(0.5 + 1e-12, 0.5), 0.0, f64::INFINITY).is_none());
        assert!(tri.intersect(&down(0.5 - 1e-12, 0.5), 0.0, f64::INFINITY).is_some());
        assert!(tri.intersect(&down(-1e-12, 0.5), 0.0, f64::INFINITY).is_none());
        assert!(tri.intersect(&down(0.0, 0.0), 0.0, f64::INFINITY).is_some(), "a corner");
        let away = Ray::new(DVec3::new(0.2, 0.2, 1.0), DVec3::Z);
        assert!(tri.intersect(&away, 0.0, f64::INFINITY).is_none());
        let r = down(0.2, 0.2);
        assert!(tri.intersect(&r, 0.0, 1.0).is_none(), "t_max is exclusive");
        assert!(tri.intersect(&r, 1.0, 2.0).is_none(), "t_min is exclusive");
        assert!(tri.intersect(&r, 0.9, 1.1).is_some());
        let in_plane = Ray::new(DVec3::new(-1.0, 0.2, 0.0), DVec3::X);
        assert!(tri.intersect(&in_plane, 0.0, f64::INFINITY).is_none());
    }

    #[test]
    fn oblique_hit_lies_on_the_triangle() {
        let tri = Triangle::new([DVec3::new(1.0, -2.0, 0.5), DVec3::new(3.0, 1.0, -1.0), DVec3::new(-2.0, 2.0, 2.0)]);
        let ray = Ray::new(DVec3::new(0.3, 0.2, 1e5), DVec3::new(1e-6, 2e-6, -0.7));
        let hit = tri.intersect(&ray, 1e-9, f64::INFINITY).unwrap();
        let s = tri.surface(&ray, &hit);
        assert!(plane_distance(&tri, s.point).abs() < 1e-12);
        assert!(s.point.distance(ray.at(hit.t)) < 1e-9);
        assert!((s.normal.length() - 1.0).abs() < 1e-15);
        let expected = (tri.vertices[1] - tri.vertices[0]).cross(tri.vertices[2] - tri.vertices[0]);
        assert!(s.normal.distance(expected.normalize()) < 1e-15);
    }

    #[test]
    fn samples_lie_on_the_triangle() {
        let tri = Triangle::new([DVec3::ZERO, DVec3::new(2.0, 0.0, 0.0), DVec3::new(0.0, 0.0, -3.0)]);
        assert_eq!(tri.area(), Some(3.0));
        for (a, b) in [(0.0, 0.0), (0.999, 0.999), (0.5, 0.25), (1.0, 1.0)] {
            let s = tri.sample_area(DVec2::new(a, b)).unwrap();
            assert!(plane_distance(&tri, s.point).abs() < 1e-15);
            let (x, z) = (s.point.x / 2.0, -s.point.z / 3.0);
            assert!(x >= -1e-15 && z >= -1e-15 && x + z <= 1.0 + 1e-15);
        }
    }

    #[test]
    fn parameters_are_validated() {
        let p = |vertices| TriangleParams { vertices }.build();
        assert_eq!(p([[0.0; 3], [1.0, 1.0, 1.0], [2.0, 2.0, 2.0]]).unwrap_err().key, "vertices");
        assert_eq!(p([[0.0; 3], [0.0; 3], [0.0, 1.0, 0.0]]).unwrap_err().key, "vertices");
        assert_eq!(p([[0.0; 3], [1.0, 0.0, f64::NAN], [0.0, 1.0, 0.0]]).unwrap_err().key, "vertices");
        assert!(p([[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]).is_ok());
    }

    #[test]
    fn exports_to_pov_with_z_mirrored() {
        let tri = Triangle::new([DVec3::new(0.0, 0.0, 1.0), DVec3::X, DVec3::new(0.0, 2.0, -3.0)]);
        assert_eq!(tri.to_pov().unwrap(), "triangle { <0.0, 0.0, -1.0>, <1.0, 0.0, -0.0>, <0.0, 2.0, 3.0> }");
    }
}
