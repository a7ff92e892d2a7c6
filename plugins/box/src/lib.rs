//! The box shape plugin: an axis-aligned box between two corners.

#![forbid(unsafe_code)]

use std::ops::ControlFlow;
use std::sync::Arc;

use prism_api::{
    Aabb, AreaSample, DVec2, DVec3, Hit, HitPoint, ParamError, Ray, Shape, ShapeParams, Surface, pov,
    visit_solved_crossings,
};
use schemars::JsonSchema;
use serde::Deserialize;

/// Parameters of `shape = "box"`.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct BoxParams {
    /// The corner with the smallest coordinates.
    #[serde(default = "default_min")]
    pub min: [f64; 3],
    /// The corner with the largest coordinates; greater than `min` on every axis.
    #[serde(default = "default_max")]
    pub max: [f64; 3],
}

fn default_min() -> [f64; 3] {
    [-1.0; 3]
}

fn default_max() -> [f64; 3] {
    [1.0; 3]
}

impl ShapeParams for BoxParams {
    fn build(self) -> Result<Arc<dyn Shape>, ParamError> {
        ParamError::require_finite("min", &self.min)?;
        ParamError::require_finite("max", &self.max)?;
        for (axis, name) in ["x", "y", "z"].into_iter().enumerate() {
            if self.max[axis] <= self.min[axis] {
                return Err(ParamError::new(
                    "max",
                    format!(
                        "must be greater than `min` on every axis, got {name} {} <= {}",
                        self.max[axis], self.min[axis]
                    ),
                ));
            }
        }
        Ok(Arc::new(BoxShape { min: DVec3::from_array(self.min), max: DVec3::from_array(self.max) }))
    }
}

/// An axis-aligned box intersected with the slab test in f64.
///
/// Hit parts are the faces: 0 = -x, 1 = +x, 2 = -y, 3 = +y, 4 = -z, 5 = +z
/// (`2 * axis + 1` for the face at `max`).
#[derive(Clone, Debug, PartialEq)]
pub struct BoxShape {
    /// Smallest corner.
    pub min: DVec3,
    /// Largest corner (greater than `min` on every axis).
    pub max: DVec3,
}

/// The texture axes of a face perpendicular to `axis`: (axis of u, axis of v).
fn face_uv_axes(axis: usize) -> (usize, usize) {
    match axis {
        0 => (2, 1),
        1 => (0, 2),
        _ => (0, 1),
    }
}

impl BoxShape {
    /// Where the ray enters and leaves the box (t and face), whatever their sign; `None`
    /// when it misses.
    fn slabs(&self, ray: &Ray) -> Option<((f64, u32), (f64, u32))> {
        let mut enter = (f64::NEG_INFINITY, 0u32);
        let mut exit = (f64::INFINITY, 0u32);
        for axis in 0..3 {
            let o = ray.origin[axis];
            let d = ray.direction[axis];
            if d == 0.0 {
                // Parallel to this slab: inside it for every t, or never.
                if o < self.min[axis] || o > self.max[axis] {
                    return None;
                }
                continue;
            }
            // Divide rather than multiply by 1/d: no 0 * inf = NaN for tiny d.
            let t_lo = (self.min[axis] - o) / d;
            let t_hi = (self.max[axis] - o) / d;
            let face = 2 * axis as u32;
            let (near, far) = if d > 0.0 { ((t_lo, face), (t_hi, face + 1)) } else { ((t_hi, face + 1), (t_lo, face)) };
            if near.0 > enter.0 {
                enter = near;
            }
            if far.0 < exit.0 {
                exit = far;
            }
        }
        (enter.0 <= exit.0).then_some((enter, exit))
    }

    /// Areas of the faces perpendicular to x, y and z (each one of a pair).
    fn face_areas(&self) -> DVec3 {
        let size = self.max - self.min;
        DVec3::new(size.y * size.z, size.z * size.x, size.x * size.y)
    }
}

impl Shape for BoxShape {
    fn bounds(&self) -> Aabb {
        Aabb { min: self.min, max: self.max }
    }

    fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit> {
        let (enter, exit) = self.slabs(ray)?;
        // The entry when it is in range, else the exit (the ray starts inside).
        [enter, exit].into_iter().find(|&(t, _)| t > t_min && t < t_max).map(|(t, face)| Hit::on_part(t, face))
    }

    /// Both crossings from one slab test, listed as the trait's default (which would test
    /// the slabs once per crossing) lists them.
    fn crossings(&self, ray: &Ray, t_min: f64, t_max: f64, visit: &mut dyn FnMut(&Hit) -> ControlFlow<()>) {
        let Some((enter, exit)) = self.slabs(ray) else { return };
        let hits = [enter, exit].map(|(t, face)| Hit::on_part(t, face));
        visit_solved_crossings(&self.bounds(), ray, t_min, t_max, hits, visit);
    }

    fn inside(&self, point: DVec3) -> bool {
        // The faces themselves are inside, as in POV-Ray.
        point.cmpge(self.min).all() && point.cmple(self.max).all()
    }

    fn surface(&self, ray: &Ray, hit: &Hit) -> Surface {
        let HitPoint { point, normal, .. } = self.hit_point(ray, hit);
        let (ua, va) = face_uv_axes((hit.part / 2) as usize);
        let size = self.max - self.min;
        let rel = (point - self.min) / size;
        // u runs along the face's first texture axis, across the box's full size there.
        let mut dpdu = DVec3::ZERO;
        dpdu[ua] = size[ua];
        Surface::new(point, normal, DVec2::new(rel[ua], rel[va])).with_dpdu(dpdu)
    }

    fn hit_point(&self, ray: &Ray, hit: &Hit) -> HitPoint {
        let axis = (hit.part / 2) as usize;
        let at_max = hit.part % 2 == 1;
        // Snap onto the face and clamp into it: removes the rounding of ray.at(t).
        let mut point = ray.at(hit.t).clamp(self.min, self.max);
        point[axis] = if at_max { self.max[axis] } else { self.min[axis] };
        let mut normal = DVec3::ZERO;
        normal[axis] = if at_max { 1.0 } else { -1.0 };
        HitPoint::new(point, normal)
    }

    fn area(&self) -> Option<f64> {
        let a = self.face_areas();
        Some(2.0 * (a.x + a.y + a.z))
    }

    fn sample_area(&self, u: DVec2) -> Option<AreaSample> {
        // Pick one of the six faces in proportion to its area with u.x, then reuse the
        // remainder of u.x and u.y as the position on it.
        let areas = self.face_areas();
        let half = areas.x + areas.y + areas.z;
        let mut x = (u.x * 2.0 * half).min(2.0 * half);
        let mut face = 5;
        for f in 0..6 {
            let a = areas[f / 2];
            if x < a || f == 5 {
                face = f;
                break;
            }
            x -= a;
        }
        let axis = face / 2;
        let at_max = face % 2 == 1;
        let s = (x / areas[axis]).clamp(0.0, 1.0);
        let (ua, va) = face_uv_axes(axis);
        let mut point = DVec3::ZERO;
        point[axis] = if at_max { self.max[axis] } else { self.min[axis] };
        point[ua] = self.min[ua] + s * (self.max[ua] - self.min[ua]);
        point[va] = self.min[va] + u.y * (self.max[va] - self.min[va]);
        let mut normal = DVec3::ZERO;
        normal[axis] = if at_max { 1.0 } else { -1.0 };
        Some(AreaSample { point, normal, pdf_area: 1.0 / self.area()? })
    }

    fn to_pov(&self) -> Option<String> {
        // Mirroring z makes `max` the smaller POV z; POV accepts any two opposite corners.
        Some(format!("box {{ {}, {} }}", pov::vector(self.min), pov::vector(self.max)))
    }

    fn to_mitsuba(&self) -> Option<Vec<prism_api::mitsuba::MitsubaShape>> {
        let place = prism_api::DAffine3::from_translation(0.5 * (self.min + self.max))
            * prism_api::DAffine3::from_scale(0.5 * (self.max - self.min));
        // Mitsuba's cube lays its faces' (u, v) out otherwise than the box does.
        Some(vec![prism_api::mitsuba::MitsubaShape::new(prism_api::mitsuba::MitsubaKind::Cube, place).with_other_uv()])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// POV-Ray's `Box::Inside` counts the faces themselves as inside.
    #[test]
    fn faces_are_inside() {
        let b = BoxShape { min: DVec3::splat(-1.0), max: DVec3::splat(1.0) };
        assert!(b.inside(DVec3::new(1.0, 0.0, 0.0)) && b.inside(DVec3::splat(-1.0)));
        assert!(!b.inside(DVec3::new(1.0 + 1e-15, 0.0, 0.0)));
    }
    use prism_api::contract::{check_dpdu, check_shape, check_t_range};

    fn cube() -> BoxShape {
        BoxShape { min: DVec3::splat(-1.0), max: DVec3::splat(1.0) }
    }

    /// Signed distance to the box surface (negative inside).
    fn sdf(b: &BoxShape, p: DVec3) -> f64 {
        let c = b.bounds().center();
        let half = 0.5 * (b.max - b.min);
        let q = (p - c).abs() - half;
        q.max(DVec3::ZERO).length() + q.max_element().min(0.0)
    }

    #[test]
    fn contract_holds() {
        check_shape(&cube());
        check_shape(&BoxShape { min: DVec3::new(-50.0, -0.01, -30.0), max: DVec3::new(50.0, 0.01, 30.0) });
        check_shape(&BoxShape { min: DVec3::new(0.1, 0.2, 0.3), max: DVec3::new(0.1005, 0.2002, 0.3001) });
        check_dpdu(&BoxShape { min: DVec3::new(-1.0, 0.0, 2.0), max: DVec3::new(3.0, 0.5, 2.25) });
    }

    #[test]
    fn crossings_are_the_defaults_from_one_slab_test() {
        prism_api::contract::check_crossings_match_intersect(&cube());
        prism_api::contract::check_crossings_match_intersect(&BoxShape {
            min: DVec3::new(0.1, 0.2, 0.3),
            max: DVec3::new(0.1005, 0.2002, 0.3001),
        });
    }

    #[test]
    fn hit_from_outside_and_inside() {
        let b = cube();
        let outside = Ray::new(DVec3::new(0.2, 0.3, 5.0), DVec3::new(0.0, 0.0, -2.0));
        let hit = b.intersect(&outside, 1e-9, f64::INFINITY).unwrap();
        assert!((hit.t - 2.0).abs() < 1e-15, "t in the caller's units, |d| = 2");
        assert_eq!(hit.part, 5);
        let s = b.surface(&outside, &hit);
        assert_eq!(s.normal, DVec3::Z);
        assert_eq!(s.point, DVec3::new(0.2, 0.3, 1.0));
        let inside = Ray::new(DVec3::new(0.5, 0.0, 0.0), DVec3::new(-1.0, 0.1, 0.0));
        let hit = b.intersect(&inside, 1e-9, f64::INFINITY).unwrap();
        assert!((hit.t - 1.5).abs() < 1e-15, "the exit");
        let s = b.surface(&inside, &hit);
        assert_eq!(s.normal, -DVec3::X, "outward from inside too");
        assert!(sdf(&b, s.point).abs() < 1e-15);
    }

    #[test]
    fn behind_grazing_and_t_range() {
        let b = cube();
        assert_eq!(check_t_range(&b, DVec3::new(0.0, 0.0, 5.0), -DVec3::Z, 4.0, 6.0).part, 4, "the exit face");
        let above = Ray::new(DVec3::new(0.0, 1.0 + 1e-12, 5.0), -DVec3::Z);
        assert!(b.intersect(&above, 1e-9, f64::INFINITY).is_none());
        let skim = Ray::new(DVec3::new(0.0, 1.0 - 1e-12, 5.0), -DVec3::Z);
        assert!(b.intersect(&skim, 1e-9, f64::INFINITY).is_some());
        // A ray lying in a face plane does not produce NaN.
        let in_face = Ray::new(DVec3::new(-5.0, 1.0, 0.0), DVec3::X);
        if let Some(hit) = b.intersect(&in_face, 1e-9, f64::INFINITY) {
            assert!(hit.t.is_finite());
        }
        // Subnormal direction components: still no NaN. Starting on the top face, a ray
        // that tilts down by 1e-320 runs through the box; one tilting up leaves it at t = 0.
        let tiny_down = Ray::new(DVec3::new(-5.0, 1.0, 0.0), DVec3::new(1.0, -1e-320, 0.0));
        assert!(b.intersect(&tiny_down, 1e-9, f64::INFINITY).is_some_and(|h| h.t == 4.0));
        let tiny_up = Ray::new(DVec3::new(-5.0, 1.0, 0.0), DVec3::new(1.0, 1e-320, 0.0));
        assert!(b.intersect(&tiny_up, 1e-9, f64::INFINITY).is_none());
    }

    #[test]
    fn normals_are_outward_on_every_face() {
        let b = BoxShape { min: DVec3::new(-1.0, -2.0, -3.0), max: DVec3::new(4.0, 5.0, 6.0) };
        let c = b.bounds().center();
        for axis in 0..3 {
            for sign in [-1.0, 1.0] {
                let mut dir = DVec3::ZERO;
                dir[axis] = sign;
                let ray = Ray::new(c + DVec3::new(0.1, 0.2, 0.3), dir * 3.0);
                let hit = b.intersect(&ray, 1e-9, f64::INFINITY).unwrap();
                let s = b.surface(&ray, &hit);
                assert_eq!(s.normal, dir);
                assert_eq!(hit.part as usize, 2 * axis + usize::from(sign > 0.0));
                assert!(sdf(&b, s.point).abs() < 1e-14);
                assert!(s.uv.cmpge(DVec2::ZERO).all() && s.uv.cmple(DVec2::ONE).all());
            }
        }
    }

    #[test]
    fn samples_cover_the_faces_in_proportion() {
        let b = BoxShape { min: DVec3::ZERO, max: DVec3::new(1.0, 2.0, 3.0) };
        assert_eq!(b.area(), Some(22.0));
        let mut per_face = [0usize; 6];
        let n = 2200;
        for i in 0..n {
            let s = b.sample_area(DVec2::new((i as f64 + 0.5) / n as f64, 0.37)).unwrap();
            assert!(sdf(&b, s.point).abs() < 1e-14);
            let axis = (0..3).find(|&a| s.normal[a] != 0.0).unwrap();
            per_face[2 * axis + usize::from(s.normal[axis] > 0.0)] += 1;
        }
        assert_eq!(per_face, [600, 600, 300, 300, 200, 200]);
    }

    #[test]
    fn parameters_are_validated() {
        let p = |min: [f64; 3], max: [f64; 3]| BoxParams { min, max }.build();
        assert_eq!(p([0.0; 3], [1.0, 1.0, 0.0]).unwrap_err().key, "max");
        assert_eq!(p([0.0; 3], [1.0, -1.0, 1.0]).unwrap_err().key, "max");
        assert_eq!(p([f64::NAN, 0.0, 0.0], [1.0; 3]).unwrap_err().key, "min");
        assert_eq!(p([0.0; 3], [f64::INFINITY; 3]).unwrap_err().key, "max");
        assert!(p([-1.0; 3], [1.0; 3]).is_ok());
    }

    #[test]
    fn exports_to_pov_with_z_mirrored() {
        let b = BoxShape { min: DVec3::new(-1.0, -2.0, -3.0), max: DVec3::new(1.0, 2.0, 3.0) };
        assert_eq!(b.to_pov().unwrap(), "box { <-1.0, -2.0, 3.0>, <1.0, 2.0, -3.0> }");
    }
}
