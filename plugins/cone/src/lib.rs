//! The cone shape plugin: a finite cone or truncated cone (frustum) between two points, closed
//! with flat end caps unless `open`.

#![forbid(unsafe_code)]

use std::f64::consts::{PI, TAU};
use std::sync::Arc;

use prism_api::{
    Aabb, AreaSample, DVec2, DVec3, Hit, HitPoint, ParamError, Ray, Shape, ShapeParams, Surface, math, pov,
};
use schemars::JsonSchema;
use serde::Deserialize;

/// How far past a pointed end (radius 0), as a fraction of the height, side hits are still
/// accepted. A ray through the tip meets the side there in a double root whose height
/// rounding puts a few ulps on either side of the end; without this slack it would miss the
/// tip about half of the time and go on to whatever lies behind it.
pub const TIP_SLACK: f64 = 1e-9;

/// Parameters of `shape = "cone"`.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ConeParams {
    /// Centre of the base end in object space.
    #[serde(default)]
    pub base: [f64; 3],
    /// Radius at `base`; at least 0 (0: a point).
    #[serde(default = "default_base_radius")]
    pub base_radius: f64,
    /// Centre of the apex end; must differ from `base`.
    #[serde(default = "default_apex")]
    pub apex: [f64; 3],
    /// Radius at `apex`; at least 0 (0: a point), and not 0 when `base_radius` is.
    #[serde(default)]
    pub apex_radius: f64,
    /// Leave out the end caps (a lampshade); an end of radius 0 has no cap either way.
    #[serde(default)]
    pub open: bool,
}

fn default_base_radius() -> f64 {
    1.0
}

fn default_apex() -> [f64; 3] {
    [0.0, 1.0, 0.0]
}

impl ShapeParams for ConeParams {
    fn build(self) -> Result<Arc<dyn Shape>, ParamError> {
        ParamError::require_finite("base", &self.base)?;
        ParamError::require_non_negative("base_radius", self.base_radius)?;
        ParamError::require_finite("apex", &self.apex)?;
        ParamError::require_non_negative("apex_radius", self.apex_radius)?;
        if self.base_radius == 0.0 && self.apex_radius == 0.0 {
            return Err(ParamError::new(
                "apex_radius",
                "and `base_radius` must not both be 0 (the cone would be a line)",
            ));
        }
        let (base, apex) = (DVec3::from_array(self.base), DVec3::from_array(self.apex));
        let height = base.distance(apex);
        if !(height.is_finite() && height > 0.0) {
            return Err(ParamError::new(
                "apex",
                format!("must differ from `base` by a finite distance, got {:?}", self.apex),
            ));
        }
        Ok(Arc::new(Cone::new(base, self.base_radius, apex, self.apex_radius, self.open)))
    }
}

/// Hit part of the slanted side.
pub const SIDE: u32 = 0;
/// Hit part of the cap at `base`.
pub const BASE_CAP: u32 = 1;
/// Hit part of the cap at `apex`.
pub const APEX_CAP: u32 = 2;

/// A finite cone (frustum) around the segment `base`–`apex`, solved in f64. Equal radii make
/// it a cylinder.
///
/// Hit parts: [`SIDE`], [`BASE_CAP`], [`APEX_CAP`]. Normals point out of the solid: away from
/// the axis on the side, away from the cone on the caps.
#[derive(Clone, Debug, PartialEq)]
pub struct Cone {
    /// Centre of the base end.
    pub base: DVec3,
    /// Radius at `base` (>= 0).
    pub base_radius: f64,
    /// Centre of the apex end.
    pub apex: DVec3,
    /// Radius at `apex` (>= 0; not both radii 0).
    pub apex_radius: f64,
    /// True when the end caps are left out.
    pub open: bool,
    /// Unit vector from `base` to `apex`.
    axis: DVec3,
    /// Distance from `base` to `apex`.
    height: f64,
    /// Change of radius per unit of height, `(apex_radius - base_radius) / height`.
    slope: f64,
    /// Unit vector perpendicular to the axis where the texture's `u` is 0.
    tangent: DVec3,
    /// Unit vector a quarter turn from `tangent` around the axis (`u` = 0.25).
    bitangent: DVec3,
}

impl Cone {
    /// The cone with radius `base_radius` at `base` and `apex_radius` at `apex` (distinct
    /// points, radii >= 0 and not both 0).
    pub fn new(base: DVec3, base_radius: f64, apex: DVec3, apex_radius: f64, open: bool) -> Self {
        let height = base.distance(apex);
        let axis = (apex - base) / height;
        let (tangent, bitangent) = math::orthonormal_basis(axis);
        let slope = (apex_radius - base_radius) / height;
        Self { base, base_radius, apex, apex_radius, open, axis, height, slope, tangent, bitangent }
    }

    /// Slant length of the side.
    fn slant(&self) -> f64 {
        self.height.hypot(self.apex_radius - self.base_radius)
    }

    /// Area of the side.
    fn side_area(&self) -> f64 {
        PI * (self.base_radius + self.apex_radius) * self.slant()
    }

    /// Areas of the base and apex caps (0 when open or pointed).
    fn cap_areas(&self) -> (f64, f64) {
        if self.open {
            (0.0, 0.0)
        } else {
            (PI * self.base_radius * self.base_radius, PI * self.apex_radius * self.apex_radius)
        }
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

    /// The outward side normal at a point whose unit direction from the axis is `radial`
    /// (zero exactly on the axis, at a tip: the normal is then the axis out of the tip).
    fn side_normal(&self, radial: DVec3) -> DVec3 {
        (radial - self.slope * self.axis).normalize()
    }

    /// The surface point and normals at a hit, and the point's offset from the axis.
    fn point_and_radial(&self, ray: &Ray, hit: &Hit) -> (HitPoint, DVec3) {
        let point = ray.at(hit.t);
        let local = point - self.base;
        let s = local.dot(self.axis);
        let radial = local - s * self.axis;
        let point = match hit.part {
            SIDE => HitPoint::new(point, self.side_normal(radial.normalize_or_zero())),
            part => {
                let (s_cap, normal) = if part == BASE_CAP { (0.0, -self.axis) } else { (self.height, self.axis) };
                // Project onto the cap's plane: removes the rounding of ray.at(t) along it.
                HitPoint::new(self.base + s_cap * self.axis + radial, normal)
            }
        };
        (point, radial)
    }
}

impl Shape for Cone {
    fn bounds(&self) -> Aabb {
        // The frustum is the convex hull of its end circles; a circle of radius r
        // perpendicular to the axis reaches r * sqrt(1 - axis_i^2) along axis i.
        let reach = (DVec3::ONE - self.axis * self.axis).max(DVec3::ZERO).sqrt();
        let (e0, e1) = (reach * self.base_radius, reach * self.apex_radius);
        Aabb::from_corners(self.base - e0, self.base + e0).union(Aabb::from_corners(self.apex - e1, self.apex + e1))
    }

    fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit> {
        let oc = ray.origin - self.base;
        // Heights along the axis and the components perpendicular to it.
        let s_origin = oc.dot(self.axis);
        let s_dir = ray.direction.dot(self.axis);
        let u = oc - s_origin * self.axis;
        let w = ray.direction - s_dir * self.axis;
        let in_range = |t: f64| t > t_min && t < t_max;
        let mut best: Option<Hit> = None;
        let mut consider = |t: f64, part: u32| {
            if in_range(t) && best.is_none_or(|b| t < b.t) {
                best = Some(Hit::on_part(t, part));
            }
        };

        // Side: |u + t w| = rho(t) with rho(t) = rho0 + t * k_dir the radius of the infinite
        // double cone at the height reached; squared, a t^2 + 2 b t + c = 0.
        let rho0 = self.base_radius + self.slope * s_origin;
        let k_dir = self.slope * s_dir;
        let a = w.length_squared() - k_dir * k_dir;
        let b = u.dot(w) - k_dir * rho0;
        let len_u = u.length();
        let c = (len_u - rho0) * (len_u + rho0);
        // The quarter discriminant b^2 - a c, rewritten (Lagrange's identity) as
        // |rho0 w - k_dir u|^2 - |u x w|^2: exactly 0 for a ray along the axis, and free of
        // the cancellation that loses rays passing within rounding distance of the tip.
        let disc = (rho0 * w - k_dir * u).length_squared() - u.cross(w).length_squared();
        if disc >= 0.0 && (a != 0.0 || b != 0.0) {
            let q = -(b + b.signum() * disc.sqrt());
            // q / a is the far root (infinite when a = 0: the ray is parallel to the slant).
            let roots = if q == 0.0 { [0.0, 0.0] } else { [q / a, c / q] };
            let low = if self.base_radius == 0.0 { -TIP_SLACK * self.height } else { 0.0 };
            let high = self.height + if self.apex_radius == 0.0 { TIP_SLACK * self.height } else { 0.0 };
            for t in roots {
                let s = s_origin + t * s_dir;
                if s >= low && s <= high {
                    consider(t, SIDE);
                }
            }
        }

        if !self.open && s_dir != 0.0 {
            for (s_cap, radius, part) in [(0.0, self.base_radius, BASE_CAP), (self.height, self.apex_radius, APEX_CAP)]
            {
                if radius == 0.0 {
                    continue;
                }
                let t = (s_cap - s_origin) / s_dir;
                if in_range(t) && (u + t * w).length_squared() <= radius * radius {
                    consider(t, part);
                }
            }
        }
        best
    }

    fn inside(&self, point: DVec3) -> bool {
        // The solid frustum, also when `open`, as in POV-Ray, which tests in the space where
        // the cone's tip is the origin and its wide end the unit disc at z = 1: there the
        // radius at height z is z, so z is the radius here over the wide end's. A skin of
        // `EPSILON` is outside a closed cone and inside an open one; a cone whose radii (nearly)
        // agree is tested as POV-Ray's cylinder.
        let local = point - self.base;
        let s = local.dot(self.axis);
        let radial2 = (local - s * self.axis).length_squared();
        let (narrow, wide) = (self.base_radius.min(self.apex_radius), self.base_radius.max(self.apex_radius));
        let w2 = radial2 / (wide * wide);
        // POV-Ray's two tests for a cylinder: radii within EPSILON, or a taper so slight that
        // (wide - narrow) * length / (tip-to-wide-end length), which is (wide - narrow)^2 /
        // wide, falls below it.
        let taper = wide - narrow;
        if taper < prism_api::pov::EPSILON || taper * taper / wide < prism_api::pov::EPSILON {
            return prism_api::pov::inside_unit_cylinder(w2, s / self.height, self.open);
        }
        let skin = prism_api::pov::unit_skin(self.open);
        // POV-Ray's side test is `w2 <= z^2 + skin`, which leaves the axis within 1e-5 of
        // the tip outside; a skin relative to z^2 keeps the tip's inside and differs from it
        // by less than 1e-10 elsewhere.
        let z = (self.base_radius + self.slope * s) / wide;
        w2 <= z * z * (1.0 + skin) && z >= narrow / wide - skin && z <= 1.0 + skin
    }

    fn surface(&self, ray: &Ray, hit: &Hit) -> Surface {
        let mut surface = self.surface_geometry(ray, hit);
        let local = surface.point - self.base;
        let s = local.dot(self.axis);
        let radial = local - s * self.axis;
        let v = match hit.part {
            SIDE => (s / self.height).clamp(0.0, 1.0),
            BASE_CAP => (radial.length() / self.base_radius).min(1.0),
            _ => (radial.length() / self.apex_radius).min(1.0),
        };
        surface.uv = DVec2::new(self.angle_u(radial), v);
        surface
    }

    fn surface_geometry(&self, ray: &Ray, hit: &Hit) -> Surface {
        let (HitPoint { point, normal, .. }, radial) = self.point_and_radial(ray, hit);
        // On the side and the caps alike, u turns the point about the axis by a full turn
        // (zero at the tip and the caps' centres, where the tangent of Surface::new stays).
        Surface::new(point, normal, DVec2::ZERO).with_dpdu(TAU * self.axis.cross(radial))
    }

    fn hit_point(&self, ray: &Ray, hit: &Hit) -> HitPoint {
        self.point_and_radial(ray, hit).0
    }

    fn area(&self) -> Option<f64> {
        let (base_cap, apex_cap) = self.cap_areas();
        Some(self.side_area() + base_cap + apex_cap)
    }

    fn sample_area(&self, u: DVec2) -> Option<AreaSample> {
        // u.x picks the side or a cap in proportion to area, and its remainder places the
        // point along that part; u.y is the angle around the axis.
        let area = self.area()?;
        let side = self.side_area();
        let (base_cap, apex_cap) = self.cap_areas();
        let x = u.x * area;
        let radial = self.radial_at(u.y);
        let (r0, r1) = (self.base_radius, self.apex_radius);
        let (point, normal) = if x < side || base_cap + apex_cap == 0.0 {
            // Uniform in area: the radius squared is uniform between the end radii squared,
            // and the height follows as s / h = f (r0 + r1) / (rho + r0), which stays exact
            // for equal radii.
            let f = (x / side).clamp(0.0, 1.0);
            let rho = (r0 * r0 + f * (r1 * r1 - r0 * r0)).max(0.0).sqrt();
            let s = (f * (r0 + r1) / (rho + r0)).min(1.0) * self.height;
            (self.base + s * self.axis + rho * radial, self.side_normal(radial))
        } else if x < side + base_cap {
            let f = ((x - side) / base_cap).clamp(0.0, 1.0);
            (self.base + r0 * f.sqrt() * radial, -self.axis)
        } else {
            let f = ((x - side - base_cap) / apex_cap).clamp(0.0, 1.0);
            (self.apex + r1 * f.sqrt() * radial, self.axis)
        };
        Some(AreaSample { point, normal, pdf_area: 1.0 / area })
    }

    fn to_pov(&self) -> Option<String> {
        Some(format!(
            "cone {{ {}, {}, {}, {}{} }}",
            pov::vector(self.base),
            pov::number(self.base_radius),
            pov::vector(self.apex),
            pov::number(self.apex_radius),
            if self.open { " open" } else { "" }
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// POV-Ray's `Cone::Inside`: a skin of 1e-10 (in the unit cone's space, where the wide
    /// end has radius 1) is outside a closed cone and inside an open one; the axis stays
    /// inside up to the tip; equal radii test as a cylinder.
    #[test]
    fn the_skin_is_outside_closed_and_inside_open_cones() {
        let (closed, open) =
            (Cone::new(DVec3::ZERO, 1.0, DVec3::Y, 0.5, false), Cone::new(DVec3::ZERO, 1.0, DVec3::Y, 0.5, true));
        for p in [DVec3::new(0.2, 0.0, 0.0), DVec3::new(0.2, 1.0, 0.0), DVec3::new(0.75, 0.5, 0.0)] {
            assert!(!closed.inside(p) && open.inside(p), "{p}");
        }
        assert!(closed.inside(DVec3::new(0.2, 1e-9, 0.0)));
        let pointed = Cone::new(DVec3::ZERO, 1.0, DVec3::Y, 0.0, false);
        assert!(pointed.inside(DVec3::Y * (1.0 - 1e-7)) && !pointed.inside(DVec3::Y * (1.0 + 1e-7)));
        let straight = Cone::new(DVec3::ZERO, 0.5, DVec3::Y, 0.5, false);
        assert!(!straight.inside(DVec3::new(0.1, 0.0, 0.0)) && straight.inside(DVec3::new(0.1, 1e-9, 0.0)));
    }
    use prism_api::contract::{ContractConfig, TestRng, check_dpdu, check_sampling_toward, check_shape, check_t_range};

    /// The default cone: radius 1 at the origin, a point at y = 1.
    fn unit() -> Cone {
        Cone::new(DVec3::ZERO, 1.0, DVec3::Y, 0.0, false)
    }

    fn params() -> ConeParams {
        ConeParams { base: [0.0; 3], base_radius: 1.0, apex: [0.0, 1.0, 0.0], apex_radius: 0.0, open: false }
    }

    /// Distance-like measure of how far `p` is from the closed cone's surface: the smallest
    /// of the distances to the side's cone (measured radially) and to each capped end plane,
    /// for points within the cone's extent.
    fn off_surface(c: &Cone, p: DVec3) -> f64 {
        let local = p - c.base;
        let s = local.dot(c.axis);
        let rho = (local - s * c.axis).length();
        let side = (rho - (c.base_radius + c.slope * s)).abs();
        let base = if rho <= c.base_radius + 1e-12 { s.abs() } else { f64::INFINITY };
        let apex = if rho <= c.apex_radius + 1e-12 { (s - c.height).abs() } else { f64::INFINITY };
        side.min(base).min(apex)
    }

    fn hit_surface(c: &Cone, ray: &Ray) -> (Hit, Surface) {
        let hit = c.intersect(ray, 1e-9, f64::INFINITY).expect("a hit");
        (hit, c.surface(ray, &hit))
    }

    #[test]
    fn contract_holds() {
        check_shape(&unit());
        check_shape(&Cone::new(DVec3::ZERO, 1.0, DVec3::Y, 0.0, true));
        check_shape(&Cone::new(DVec3::new(1.0, -2.0, 0.5), 0.0, DVec3::new(1.5, -1.0, 0.0), 0.3, false));
        // Wide and flat: a frustum like a lampshade's rim.
        check_shape(&Cone::new(DVec3::ZERO, 40.0, DVec3::new(0.0, 0.05, 0.0), 39.0, false));
        // Tiny, and a cylinder in disguise.
        check_shape(&Cone::new(
            DVec3::new(0.1, 0.2, 0.3),
            2e-4,
            DVec3::new(0.1, 0.2, 0.3) + DVec3::new(1.0, -2.0, 1.0) * 1e-3,
            2e-4,
            false,
        ));
        check_dpdu(&unit());
        check_dpdu(&Cone::new(DVec3::new(1.0, -2.0, 0.5), 0.0, DVec3::new(1.5, -1.0, 0.0), 0.3, false));
    }

    #[test]
    fn sampling_from_the_tip_side_and_inside_an_open_frustum() {
        let shade = Cone::new(DVec3::ZERO, 1.0, DVec3::Y, 0.4, true);
        let pointed = unit();
        let config = ContractConfig::default();
        check_sampling_toward(&shade, &[DVec3::new(0.0, 0.5, 0.0), DVec3::new(0.0, 2.0, 0.0)], &config);
        check_sampling_toward(&pointed, &[DVec3::new(0.0, 1.5, 0.0), DVec3::new(0.1, -0.5, 0.0)], &config);
    }

    #[test]
    fn hit_side_from_outside_and_inside() {
        let c = unit();
        let outside = Ray::new(DVec3::new(5.0, 0.5, 0.0), DVec3::new(-2.0, 0.0, 0.0));
        let (hit, s) = hit_surface(&c, &outside);
        assert!((hit.t - 2.25).abs() < 1e-15, "t in the caller's units, |d| = 2");
        assert_eq!(hit.part, SIDE);
        let expected = DVec3::new(1.0, 1.0, 0.0).normalize();
        assert!(s.normal.distance(expected) < 1e-15);
        let inside = Ray::new(DVec3::new(0.0, 0.25, 0.0), DVec3::new(0.0, 0.0, 4.0));
        let (hit, s) = hit_surface(&c, &inside);
        assert!((hit.t - 0.75 / 4.0).abs() < 1e-15);
        assert!(s.normal.distance(DVec3::new(0.0, 1.0, 1.0).normalize()) < 1e-15, "outward");
        assert!(off_surface(&c, s.point) < 1e-15);
    }

    #[test]
    fn rays_along_the_axis_hit_the_tip_and_the_caps() {
        let c = unit();
        let down = Ray::new(DVec3::new(0.0, 3.0, 0.0), -DVec3::Y);
        let (hit, s) = hit_surface(&c, &down);
        assert_eq!(hit.part, SIDE);
        assert!((hit.t - 2.0).abs() < 1e-12, "the tip, not the base cap behind it");
        assert!(s.normal.distance(DVec3::Y) < 1e-12, "the tip's normal is the axis");
        assert!(c.intersect(&down, 2.0 + 1e-6, f64::INFINITY).is_some_and(|h| h.part == BASE_CAP));
        let up = Ray::new(DVec3::new(0.0, -1.0, 0.0), DVec3::Y);
        let (hit, s) = hit_surface(&c, &up);
        assert_eq!((hit.t, hit.part), (1.0, BASE_CAP));
        assert_eq!(s.normal, -DVec3::Y);
        // From inside, up the axis: the tip from within.
        let inner = Ray::new(DVec3::new(0.0, 0.5, 0.0), DVec3::Y);
        let (hit, _) = hit_surface(&c, &inner);
        assert!((hit.t - 0.5).abs() < 1e-12);
        // Rays a hair off the axis, in every direction, still find the tip at the same t.
        let mut rng = TestRng::new(3);
        for _ in 0..1000 {
            let off = rng.unit_vector() * 1e-13;
            let ray = Ray::new(DVec3::new(0.0, 3.0, 0.0) + off, DVec3::new(1e-15, -1.0, 0.0));
            let (hit, s) = hit_surface(&c, &ray);
            assert!((hit.t - 2.0).abs() < 1e-9, "t = {} for {ray:?}", hit.t);
            assert!((s.normal.length() - 1.0).abs() < 1e-12);
        }
        // An open frustum: straight through along the axis.
        let shade = Cone::new(DVec3::ZERO, 1.0, DVec3::Y, 0.5, true);
        assert!(shade.intersect(&down, 1e-9, f64::INFINITY).is_none());
        let closed = Cone { open: false, ..shade };
        let (hit, s) = hit_surface(&closed, &down);
        assert_eq!((hit.t, hit.part), (2.0, APEX_CAP));
        assert_eq!(s.normal, DVec3::Y);
    }

    #[test]
    fn behind_grazing_and_t_range() {
        let c = unit();
        check_t_range(&c, DVec3::new(5.0, 0.5, 0.0), -DVec3::X, 4.5, 5.5);
        // Tangent to the side where its radius is 0.5, just outside and just inside.
        let graze = Ray::new(DVec3::new(0.5 + 1e-12, 0.5, 5.0), -DVec3::Z);
        assert!(c.intersect(&graze, 1e-9, f64::INFINITY).is_none());
        let skim = Ray::new(DVec3::new(0.5 - 1e-12, 0.5, 5.0), -DVec3::Z);
        let (_, s) = hit_surface(&c, &skim);
        assert!(off_surface(&c, s.point) < 1e-12);
        // Parallel to the slant (a = 0: a single root), meeting the side at (-0.5, 0.5, 0).
        let parallel = Ray::new(DVec3::new(-2.5, 2.5, 0.0), DVec3::new(1.0, -1.0, 0.0));
        let (hit, s) = hit_surface(&c, &parallel);
        assert!((hit.t - 2.0).abs() < 1e-12 && hit.part == SIDE);
        assert!(off_surface(&c, s.point) < 1e-12);
        assert!(s.normal.distance(DVec3::new(-1.0, 1.0, 0.0).normalize()) < 1e-12);
        // A million units away, still on the surface.
        let distant = Ray::new(DVec3::new(0.3, 0.2, 1e6), -DVec3::Z);
        let (_, s) = hit_surface(&c, &distant);
        assert!(off_surface(&c, s.point) < 1e-9);
        // Past the tip along the mirror nappe of the double cone: nothing.
        let mirror = Ray::new(DVec3::new(5.0, 1.5, 0.0), -DVec3::X);
        assert!(c.intersect(&mirror, 1e-9, f64::INFINITY).is_none());
    }

    #[test]
    fn normals_are_unit_outward_and_hits_on_the_surface() {
        let cones = [
            unit(),
            Cone::new(DVec3::new(1.0, -1.0, 2.0), 0.2, DVec3::new(3.0, 2.0, 0.0), 0.9, false),
            Cone::new(DVec3::new(1.0, -1.0, 2.0), 0.0, DVec3::new(-1.0, 0.0, 0.0), 1.5, false),
        ];
        let mut rng = TestRng::new(11);
        for c in &cones {
            let center = c.bounds().center();
            // The centroid-ish point a quarter of the way from the wide end is inside.
            let inside =
                if c.base_radius >= c.apex_radius { c.base.lerp(c.apex, 0.25) } else { c.apex.lerp(c.base, 0.25) };
            for _ in 0..1000 {
                let origin = center + rng.unit_vector() * 10.0;
                let target = inside + rng.unit_vector() * 0.05;
                let ray = Ray::new(origin, (target - origin) * 0.3);
                let (_, s) = hit_surface(c, &ray);
                assert!((s.normal.length() - 1.0).abs() < 1e-12);
                assert!(s.normal.dot(ray.direction) < 0.0, "entering hits face the ray");
                assert!(off_surface(c, s.point) < 1e-12, "{} off the surface", s.point);
                assert!(s.uv.cmpge(DVec2::ZERO).all() && s.uv.cmple(DVec2::ONE).all());
                let from_inside = Ray::new(target, ray.direction);
                let (_, s) = hit_surface(c, &from_inside);
                assert!(s.normal.dot(ray.direction) > 0.0, "the exit, outward");
                assert!(off_surface(c, s.point) < 1e-12);
            }
        }
    }

    #[test]
    fn samples_lie_on_the_surface() {
        let c = Cone::new(DVec3::new(1.0, 2.0, 3.0), 0.5, DVec3::new(1.0, 5.0, 3.0), 1.5, false);
        let side = PI * 2.0 * 10f64.sqrt();
        assert!((c.area().unwrap() - (side + PI * 0.25 + PI * 2.25)).abs() < 1e-12);
        for i in 0..200 {
            let s = c.sample_area(DVec2::new(i as f64 / 200.0, 0.3)).unwrap();
            assert!(off_surface(&c, s.point) < 1e-12);
            assert!((s.normal.length() - 1.0).abs() < 1e-12);
        }
        // The side's samples are uniform in area: the share below mid-height is the area of
        // the lower half of the frustum.
        let pointed = Cone::new(DVec3::ZERO, 1.0, DVec3::Y, 0.0, true);
        let n = 10_000;
        let below = (0..n)
            .filter(|&i| pointed.sample_area(DVec2::new((i as f64 + 0.5) / n as f64, 0.0)).unwrap().point.y < 0.5)
            .count();
        assert!((below as f64 / n as f64 - 0.75).abs() < 1e-3, "{below}");
    }

    #[test]
    fn parameters_are_validated() {
        let err = |p: ConeParams| p.build().unwrap_err().key;
        assert_eq!(err(ConeParams { base_radius: -1.0, ..params() }), "base_radius");
        assert_eq!(err(ConeParams { apex_radius: f64::NAN, ..params() }), "apex_radius");
        assert_eq!(err(ConeParams { base_radius: 0.0, ..params() }), "apex_radius");
        assert_eq!(err(ConeParams { apex: [0.0; 3], ..params() }), "apex");
        assert_eq!(err(ConeParams { base: [0.0, f64::INFINITY, 0.0], ..params() }), "base");
        assert!(ConeParams { base_radius: 0.0, apex_radius: 2.0, ..params() }.build().is_ok());
        assert!(params().build().is_ok());
    }

    #[test]
    fn exports_to_pov_with_z_mirrored() {
        let c = Cone::new(DVec3::new(1.0, 2.0, 3.0), 0.5, DVec3::new(1.0, 4.0, 3.0), 0.0, false);
        assert_eq!(c.to_pov().unwrap(), "cone { <1.0, 2.0, -3.0>, 0.5, <1.0, 4.0, -3.0>, 0.0 }");
        let shade = Cone { open: true, ..c };
        assert_eq!(shade.to_pov().unwrap(), "cone { <1.0, 2.0, -3.0>, 0.5, <1.0, 4.0, -3.0>, 0.0 open }");
    }
}
