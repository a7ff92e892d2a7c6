//! The cylinder shape plugin: a finite right circular cylinder between two points, closed with
//! flat end caps unless `open`.

#![forbid(unsafe_code)]

use std::f64::consts::{PI, TAU};
use std::sync::Arc;

use prism_api::{
    Aabb, AreaSample, DVec2, DVec3, Hit, HitPoint, ParamError, Ray, Shape, ShapeParams, Surface, math, pov,
};
use schemars::JsonSchema;
use serde::Deserialize;

/// Parameters of `shape = "cylinder"`.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CylinderParams {
    /// Centre of the base end in object space.
    #[serde(default)]
    pub base: [f64; 3],
    /// Centre of the top end; must differ from `base`.
    #[serde(default = "default_top")]
    pub top: [f64; 3],
    /// Radius; must be greater than 0.
    #[serde(default = "default_radius")]
    pub radius: f64,
    /// Leave out the end caps (a tube). Closed cylinders are solid.
    #[serde(default)]
    pub open: bool,
}

fn default_top() -> [f64; 3] {
    [0.0, 1.0, 0.0]
}

fn default_radius() -> f64 {
    1.0
}

impl ShapeParams for CylinderParams {
    fn build(self) -> Result<Arc<dyn Shape>, ParamError> {
        ParamError::require_finite("base", &self.base)?;
        ParamError::require_finite("top", &self.top)?;
        ParamError::require_positive("radius", self.radius)?;
        let (base, top) = (DVec3::from_array(self.base), DVec3::from_array(self.top));
        let height = base.distance(top);
        if !(height.is_finite() && height > 0.0) {
            return Err(ParamError::new(
                "top",
                format!("must differ from `base` by a finite distance, got {:?}", self.top),
            ));
        }
        Ok(Arc::new(Cylinder::new(base, top, self.radius, self.open)))
    }
}

/// Hit part of the curved side.
pub const SIDE: u32 = 0;
/// Hit part of the cap at `base`.
pub const BASE_CAP: u32 = 1;
/// Hit part of the cap at `top`.
pub const TOP_CAP: u32 = 2;

/// A finite cylinder around the segment `base`–`top`, solved in f64.
///
/// Hit parts: [`SIDE`], [`BASE_CAP`], [`TOP_CAP`]. Normals point out of the solid.
#[derive(Clone, Debug, PartialEq)]
pub struct Cylinder {
    /// Centre of the base end.
    pub base: DVec3,
    /// Centre of the top end.
    pub top: DVec3,
    /// Radius (> 0).
    pub radius: f64,
    /// True when the end caps are left out.
    pub open: bool,
    /// Unit vector from `base` to `top`.
    axis: DVec3,
    /// Distance from `base` to `top`.
    height: f64,
    /// Unit vector perpendicular to the axis where the texture's `u` is 0.
    tangent: DVec3,
    /// Unit vector a quarter turn from `tangent` around the axis (`u` = 0.25).
    bitangent: DVec3,
}

impl Cylinder {
    /// The cylinder of `radius` around the segment `base`–`top` (distinct points).
    pub fn new(base: DVec3, top: DVec3, radius: f64, open: bool) -> Self {
        let height = base.distance(top);
        let axis = (top - base) / height;
        let (tangent, bitangent) = math::orthonormal_basis(axis);
        Self { base, top, radius, open, axis, height, tangent, bitangent }
    }

    /// The texture `u` of a direction `radial` perpendicular to the axis.
    fn angle_u(&self, radial: DVec3) -> f64 {
        (radial.dot(self.bitangent).atan2(radial.dot(self.tangent)) / TAU).rem_euclid(1.0)
    }

    /// The unit vector perpendicular to the axis at angle `TAU * u`.
    fn radial_at(&self, u: f64) -> DVec3 {
        let (sin, cos) = (TAU * u).sin_cos();
        cos * self.tangent + sin * self.bitangent
    }

    /// The surface point and normals at a hit, and the point's offset from the axis
    /// (before projecting onto the side).
    fn point_and_radial(&self, ray: &Ray, hit: &Hit) -> (HitPoint, DVec3) {
        let local = ray.at(hit.t) - self.base;
        let s = local.dot(self.axis);
        let radial = local - s * self.axis;
        let point = match hit.part {
            SIDE => {
                let normal = radial.normalize_or(self.tangent);
                // Project onto the side: removes the rounding of ray.at(t) along the normal.
                HitPoint::new(self.base + s * self.axis + normal * self.radius, normal)
            }
            part => {
                let (s_cap, normal) = if part == BASE_CAP { (0.0, -self.axis) } else { (self.height, self.axis) };
                HitPoint::new(self.base + s_cap * self.axis + radial, normal)
            }
        };
        (point, radial)
    }
}

impl Shape for Cylinder {
    fn bounds(&self) -> Aabb {
        // An end circle reaches radius * sqrt(1 - axis_i^2) along axis i.
        let extent = self.radius * (DVec3::ONE - self.axis * self.axis).max(DVec3::ZERO).sqrt();
        Aabb::from_corners(self.base - extent, self.base + extent)
            .union(Aabb::from_corners(self.top - extent, self.top + extent))
    }

    fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit> {
        let oc = ray.origin - self.base;
        // Heights along the axis and the components perpendicular to it.
        let s_origin = oc.dot(self.axis);
        let s_dir = ray.direction.dot(self.axis);
        let u = oc - s_origin * self.axis;
        let w = ray.direction - s_dir * self.axis;
        let r2 = self.radius * self.radius;
        let in_range = |t: f64| t > t_min && t < t_max;
        let mut best: Option<Hit> = None;
        let mut consider = |t: f64, part: u32| {
            if in_range(t) && best.is_none_or(|b| t < b.t) {
                best = Some(Hit::on_part(t, part));
            }
        };

        // Side: |u + t w|^2 = r^2, i.e. a t^2 + 2 b t + c = 0. The quarter discriminant
        // b^2 - a c = a r^2 - |u x w|^2 (the distance of closest approach, as for spheres)
        // keeps its precision for distant origins.
        let a = w.length_squared();
        if a > 0.0 {
            let b = u.dot(w);
            let disc = a * r2 - u.cross(w).length_squared();
            if disc >= 0.0 {
                let len_u = u.length();
                let c = (len_u - self.radius) * (len_u + self.radius);
                let q = -(b + b.signum() * disc.sqrt());
                let roots = if q == 0.0 { [0.0, 0.0] } else { [q / a, c / q] };
                for t in roots {
                    let s = s_origin + t * s_dir;
                    if (0.0..=self.height).contains(&s) {
                        consider(t, SIDE);
                    }
                }
            }
        }

        if !self.open && s_dir != 0.0 {
            for (s_cap, part) in [(0.0, BASE_CAP), (self.height, TOP_CAP)] {
                let t = (s_cap - s_origin) / s_dir;
                if in_range(t) && (u + t * w).length_squared() <= r2 {
                    consider(t, part);
                }
            }
        }
        best
    }

    fn inside(&self, point: DVec3) -> bool {
        // The solid, also when `open` (POV-Ray's open cylinders keep their inside). As in
        // POV-Ray, in the unit cylinder's space a skin of `EPSILON` is outside a closed
        // cylinder and inside an open one.
        let local = point - self.base;
        let z = local.dot(self.axis) / self.height;
        let w2 = (local - local.dot(self.axis) * self.axis).length_squared() / (self.radius * self.radius);
        prism_api::pov::inside_unit_cylinder(w2, z, self.open)
    }

    fn surface(&self, ray: &Ray, hit: &Hit) -> Surface {
        let mut surface = self.surface_geometry(ray, hit);
        let local = surface.point - self.base;
        let s = local.dot(self.axis);
        let radial = local - s * self.axis;
        surface.uv = match hit.part {
            SIDE => DVec2::new(self.angle_u(surface.normal), (s / self.height).clamp(0.0, 1.0)),
            _ => DVec2::new(self.angle_u(radial), (radial.length() / self.radius).min(1.0)),
        };
        surface
    }

    fn surface_geometry(&self, ray: &Ray, hit: &Hit) -> Surface {
        let (HitPoint { point, normal, .. }, radial) = self.point_and_radial(ray, hit);
        let dpdu = match hit.part {
            // u turns the normal about the axis by a full turn.
            SIDE => TAU * self.radius * self.axis.cross(normal),
            // On a cap, u turns the point about the axis (no tangent at the centre itself).
            _ => TAU * self.axis.cross(radial),
        };
        Surface::new(point, normal, DVec2::ZERO).with_dpdu(dpdu)
    }

    fn hit_point(&self, ray: &Ray, hit: &Hit) -> HitPoint {
        self.point_and_radial(ray, hit).0
    }

    fn area(&self) -> Option<f64> {
        let caps = if self.open { 0.0 } else { 2.0 * PI * self.radius * self.radius };
        Some(TAU * self.radius * self.height + caps)
    }

    fn sample_area(&self, u: DVec2) -> Option<AreaSample> {
        // u.x picks the side or a cap in proportion to area, and its remainder places the
        // point along that part; u.y is the angle around the axis.
        let area = self.area()?;
        let side = TAU * self.radius * self.height;
        let x = u.x * area;
        let radial = self.radial_at(u.y);
        let (point, normal) = if x < side || self.open {
            let s = (x / side).min(1.0) * self.height;
            (self.base + s * self.axis + self.radius * radial, radial)
        } else {
            let cap = PI * self.radius * self.radius;
            let f = ((x - side) / cap).clamp(0.0, 2.0);
            let (f, center, normal) = if f < 1.0 { (f, self.base, -self.axis) } else { (f - 1.0, self.top, self.axis) };
            (center + self.radius * f.min(1.0).sqrt() * radial, normal)
        };
        Some(AreaSample { point, normal, pdf_area: 1.0 / area })
    }

    fn to_pov(&self) -> Option<String> {
        Some(format!(
            "cylinder {{ {}, {}, {}{} }}",
            pov::vector(self.base),
            pov::vector(self.top),
            pov::number(self.radius),
            if self.open { " open" } else { "" }
        ))
    }

    fn to_mitsuba(&self) -> Option<Vec<prism_api::mitsuba::MitsubaShape>> {
        use prism_api::DAffine3;
        let axis = self.top - self.base;
        let frame = prism_api::mitsuba::frame_with_z(axis);
        let tube = DAffine3::from_mat3_translation(frame, self.base);
        let kind = prism_api::mitsuba::MitsubaKind::Cylinder { radius: self.radius, length: axis.length() };
        let mut shapes = vec![prism_api::mitsuba::MitsubaShape::new(kind, tube)];
        if !self.open {
            // Caps facing out: the top along the axis, the base against it.
            let top = DAffine3::from_mat3_translation(frame * self.radius, self.top);
            let flipped = prism_api::DMat3::from_cols(frame.x_axis, -frame.y_axis, -frame.z_axis);
            let base = DAffine3::from_mat3_translation(flipped * self.radius, self.base);
            // The tube's (u, v) is Mitsuba's (the same frame about the axis); a cap's is not
            // (Mitsuba's disk has (r, angle)).
            shapes.push(
                prism_api::mitsuba::MitsubaShape::new(prism_api::mitsuba::MitsubaKind::Disk, top).with_other_uv(),
            );
            shapes.push(
                prism_api::mitsuba::MitsubaShape::new(prism_api::mitsuba::MitsubaKind::Disk, base).with_other_uv(),
            );
        }
        Some(shapes)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// POV-Ray's `Cone::Inside` for cylinders: a skin of 1e-10 (in the unit cylinder's
    /// space) is outside a closed cylinder and inside an open one, on the caps and the side.
    #[test]
    fn the_skin_is_outside_closed_and_inside_open_cylinders() {
        let (closed, open) = (
            Cylinder::new(DVec3::ZERO, DVec3::Y * 2.0, 0.5, false),
            Cylinder::new(DVec3::ZERO, DVec3::Y * 2.0, 0.5, true),
        );
        for p in [
            DVec3::new(0.1, 0.0, 0.0),
            DVec3::new(0.1, 2.0, 0.0),
            DVec3::new(0.0, 1.0, 0.5),
            DVec3::new(0.1, 2e-11, 0.0),
        ] {
            assert!(!closed.inside(p) && open.inside(p), "{p}");
        }
        assert!(closed.inside(DVec3::new(0.1, 1e-9, 0.0)) && !open.inside(DVec3::new(0.1, -1e-9, 0.0)));
    }
    use prism_api::contract::{ContractConfig, check_dpdu, check_sampling_toward, check_shape, check_t_range};

    fn unit() -> Cylinder {
        Cylinder::new(DVec3::ZERO, DVec3::Y, 1.0, false)
    }

    fn params() -> CylinderParams {
        CylinderParams { base: [0.0; 3], top: [0.0, 1.0, 0.0], radius: 1.0, open: false }
    }

    /// Signed distance to the closed cylinder's surface.
    fn sdf(c: &Cylinder, p: DVec3) -> f64 {
        let local = p - c.base;
        let s = local.dot(c.axis);
        let radial = (local - s * c.axis).length() - c.radius;
        let along = (s - 0.5 * c.height).abs() - 0.5 * c.height;
        DVec2::new(radial, along).max(DVec2::ZERO).length() + radial.max(along).min(0.0)
    }

    fn hit_surface(c: &Cylinder, ray: &Ray) -> (Hit, Surface) {
        let hit = c.intersect(ray, 1e-9, f64::INFINITY).expect("a hit");
        (hit, c.surface(ray, &hit))
    }

    #[test]
    fn contract_holds() {
        check_shape(&unit());
        check_shape(&Cylinder::new(DVec3::ZERO, DVec3::Y, 1.0, true));
        check_shape(&Cylinder::new(DVec3::new(-1.0, 2.0, 0.5), DVec3::new(-1.0, 2.02, 0.6), 30.0, false));
        check_shape(&Cylinder::new(
            DVec3::new(0.1, 0.2, 0.3),
            DVec3::new(0.1, 0.2, 0.3) + DVec3::new(1.0, 2.0, -1.0) * 1e-3,
            2e-4,
            false,
        ));
        check_dpdu(&unit());
        check_dpdu(&Cylinder::new(DVec3::new(1.0, -2.0, 0.5), DVec3::new(0.0, 1.0, 2.0), 0.7, true));
    }

    #[test]
    fn sampling_from_the_axis_of_an_open_tube_and_beside_it() {
        // Inside a tube, most directions leave through the open ends; beside it, directions
        // cross the near and far walls, and both could have been sampled.
        let tube = Cylinder::new(DVec3::ZERO, DVec3::Y * 2.0, 0.5, true);
        let references = [DVec3::new(0.0, 1.0, 0.0), DVec3::new(0.0, 3.0, 0.0), DVec3::new(1.0, 0.5, 0.2)];
        check_sampling_toward(&tube, &references, &ContractConfig::default());
    }

    #[test]
    fn hit_side_from_outside_and_inside() {
        let c = unit();
        let outside = Ray::new(DVec3::new(5.0, 0.5, 0.0), DVec3::new(-2.0, 0.0, 0.0));
        let (hit, s) = hit_surface(&c, &outside);
        assert!((hit.t - 2.0).abs() < 1e-15, "t in the caller's units, |d| = 2");
        assert_eq!(hit.part, SIDE);
        assert!(s.normal.distance(DVec3::X) < 1e-15);
        let inside = Ray::new(DVec3::new(0.0, 0.5, 0.0), DVec3::new(0.0, 0.0, 3.0));
        let (hit, s) = hit_surface(&c, &inside);
        assert!((hit.t - 1.0 / 3.0).abs() < 1e-15);
        assert!(s.normal.distance(DVec3::Z) < 1e-15, "outward from inside");
        assert!(sdf(&c, s.point).abs() < 1e-15);
    }

    #[test]
    fn rays_along_the_axis_hit_the_caps() {
        let c = unit();
        let down = Ray::new(DVec3::new(0.0, 3.0, 0.0), -DVec3::Y);
        let (hit, s) = hit_surface(&c, &down);
        assert_eq!((hit.t, hit.part), (2.0, TOP_CAP));
        assert_eq!(s.normal, DVec3::Y);
        let up_inside = Ray::new(DVec3::new(0.3, 0.5, 0.0), DVec3::Y);
        let (hit, s) = hit_surface(&c, &up_inside);
        assert_eq!((hit.t, hit.part), (0.5, TOP_CAP));
        assert_eq!(s.normal, DVec3::Y);
        let up = Ray::new(DVec3::new(0.0, -1.0, 0.0), DVec3::Y);
        let (hit, s) = hit_surface(&c, &up);
        assert_eq!((hit.t, hit.part), (1.0, BASE_CAP));
        assert_eq!(s.normal, -DVec3::Y);
        // Open: straight through the tube.
        let tube = Cylinder::new(DVec3::ZERO, DVec3::Y, 1.0, true);
        assert!(tube.intersect(&down, 1e-9, f64::INFINITY).is_none());
        // Inside an open tube, a slanted ray hits the inside of the wall; normal still outward.
        let slant = Ray::new(DVec3::new(0.0, 0.5, 0.0), DVec3::new(1.0, 0.1, 0.0));
        let (hit, s) = hit_surface(&tube, &slant);
        assert_eq!(hit.part, SIDE);
        assert!(s.normal.distance(DVec3::X) < 1e-12);
    }

    #[test]
    fn behind_grazing_and_t_range() {
        let c = unit();
        check_t_range(&c, DVec3::new(5.0, 0.5, 0.0), -DVec3::X, 4.0, 6.0);
        let graze = Ray::new(DVec3::new(1.0 + 1e-12, 0.5, 5.0), -DVec3::Z);
        assert!(c.intersect(&graze, 1e-9, f64::INFINITY).is_none());
        let skim = Ray::new(DVec3::new(1.0 - 1e-12, 0.5, 5.0), -DVec3::Z);
        let (_, s) = hit_surface(&c, &skim);
        assert!(sdf(&c, s.point).abs() < 1e-12);
        let above = Ray::new(DVec3::new(0.0, 1.0 + 1e-12, 5.0), -DVec3::Z);
        assert!(c.intersect(&above, 1e-9, f64::INFINITY).is_none());
        // A million units away, still on the surface.
        let far = Ray::new(DVec3::new(0.3, 0.2, 1e6), -DVec3::Z);
        let (_, s) = hit_surface(&c, &far);
        assert!(sdf(&c, s.point).abs() < 1e-9);
    }

    #[test]
    fn oblique_cylinder_normals_are_unit_and_outward() {
        let c = Cylinder::new(DVec3::new(1.0, -1.0, 2.0), DVec3::new(3.0, 2.0, 0.0), 0.7, false);
        let center = 0.5 * (c.base + c.top);
        let mut rng = prism_api::contract::TestRng::new(7);
        for _ in 0..1000 {
            let origin = center + rng.unit_vector() * 10.0;
            let target = center + rng.unit_vector() * 0.5;
            let ray = Ray::new(origin, (target - origin) * 0.3);
            let (_, s) = hit_surface(&c, &ray);
            assert!((s.normal.length() - 1.0).abs() < 1e-12);
            assert!(s.normal.dot(ray.direction) < 0.0, "entering hits face the ray");
            assert!(sdf(&c, s.point).abs() < 1e-12);
            assert!(s.uv.cmpge(DVec2::ZERO).all() && s.uv.cmple(DVec2::ONE).all());
            // From the inside the exit is found, with an outward normal.
            let inner = Ray::new(target, ray.direction);
            let (_, s) = hit_surface(&c, &inner);
            assert!(s.normal.dot(ray.direction) > 0.0);
        }
    }

    #[test]
    fn samples_lie_on_the_surface() {
        let c = Cylinder::new(DVec3::new(1.0, 2.0, 3.0), DVec3::new(1.0, 5.0, 3.0), 0.5, false);
        assert!((c.area().unwrap() - (TAU * 0.5 * 3.0 + 2.0 * PI * 0.25)).abs() < 1e-12);
        let mut caps = 0;
        for i in 0..100 {
            let s = c.sample_area(DVec2::new(i as f64 / 100.0, 0.3)).unwrap();
            assert!(sdf(&c, s.point).abs() < 1e-12);
            assert!((s.normal.length() - 1.0).abs() < 1e-12);
            caps += usize::from(s.normal.y.abs() > 0.5);
        }
        assert_eq!(caps, 14, "caps are 1/7 of the area");
        let open = Cylinder::new(DVec3::ZERO, DVec3::Y, 1.0, true);
        assert_eq!(open.area(), Some(TAU));
        let s = open.sample_area(DVec2::new(0.999, 0.0)).unwrap();
        assert!(s.normal.y == 0.0 && (s.point.y - 0.999).abs() < 1e-12);
    }

    #[test]
    fn parameters_are_validated() {
        let err = |p: CylinderParams| p.build().unwrap_err().key;
        assert_eq!(err(CylinderParams { radius: 0.0, ..params() }), "radius");
        assert_eq!(err(CylinderParams { radius: f64::NAN, ..params() }), "radius");
        assert_eq!(err(CylinderParams { top: [0.0; 3], ..params() }), "top");
        assert_eq!(err(CylinderParams { base: [f64::INFINITY, 0.0, 0.0], ..params() }), "base");
        assert_eq!(err(CylinderParams { base: [-1e308, 0.0, 0.0], top: [1e308, 0.0, 0.0], ..params() }), "top");
        assert!(params().build().is_ok());
    }

    #[test]
    fn exports_to_pov_with_z_mirrored() {
        let c = Cylinder::new(DVec3::new(1.0, 2.0, 3.0), DVec3::new(1.0, 4.0, 3.0), 0.5, false);
        assert_eq!(c.to_pov().unwrap(), "cylinder { <1.0, 2.0, -3.0>, <1.0, 4.0, -3.0>, 0.5 }");
        let tube = Cylinder { open: true, ..c };
        assert_eq!(tube.to_pov().unwrap(), "cylinder { <1.0, 2.0, -3.0>, <1.0, 4.0, -3.0>, 0.5 open }");
    }
}
