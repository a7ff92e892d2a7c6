//! The torus shape plugin: POV-Ray's `torus { major, minor }`, a ring in the x–z plane
//! around the y axis, centred on the origin.
//!
//! The ray is moved to the entry of the bounding box and its direction normalised before
//! the quartic is formed, so the coefficients stay of the torus's own scale however far away
//! the ray starts. A ray that stays in the hole or outside the widest circle while it crosses
//! the box is turned away before any quartic (POV-Ray's thick-cylinder test). The quartic is solved by isolating its roots between the roots of its
//! derivatives ([`prism_api::math::polynomial_roots`]), never by Ferrari's formula, and each
//! root is then polished with Newton's method on the torus's distance function.

#![forbid(unsafe_code)]

use std::f64::consts::{PI, TAU};
use std::ops::ControlFlow;
use std::sync::Arc;

use prism_api::math::{polynomial_roots, visit_polynomial_roots};
use prism_api::{
    Aabb, AreaSample, DVec2, DVec3, DirectionSample, Hit, HitPoint, ParamError, Ray, Shape, ShapeParams, Surface, math,
    pov,
};
use schemars::JsonSchema;
use serde::Deserialize;

/// Parameters of `shape = "torus"`.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct TorusParams {
    /// Distance from the centre of the hole to the middle of the tube; must be greater than 0.
    #[serde(default = "default_major_radius")]
    pub major_radius: f64,
    /// Radius of the tube; must be greater than 0 and less than `major_radius` (no spindle tori).
    #[serde(default = "default_minor_radius")]
    pub minor_radius: f64,
}

fn default_major_radius() -> f64 {
    1.0
}

fn default_minor_radius() -> f64 {
    0.25
}

impl ShapeParams for TorusParams {
    fn build(self) -> Result<Arc<dyn Shape>, ParamError> {
        ParamError::require_positive("major_radius", self.major_radius)?;
        ParamError::require_positive("minor_radius", self.minor_radius)?;
        if self.minor_radius >= self.major_radius {
            return Err(ParamError::new(
                "minor_radius",
                format!(
                    "must be less than `major_radius` ({}), got {}: spindle tori are not supported",
                    self.major_radius, self.minor_radius
                ),
            ));
        }
        Ok(Arc::new(Torus::new(self.major_radius, self.minor_radius)))
    }
}

/// A torus around the y axis: the points at distance `minor` from the circle of radius
/// `major` in the x–z plane.
#[derive(Clone, Debug, PartialEq)]
pub struct Torus {
    /// Radius of the circle through the middle of the tube (> `minor`).
    pub major: f64,
    /// Radius of the tube (> 0).
    pub minor: f64,
}

/// The torus's quartic along a ray, set up from the entry of the bounds along the unit
/// direction, and the span of distance along it where its roots are searched.
struct Quartic {
    /// Ray parameter of the bounds' entry.
    t_enter: f64,
    /// The entry point.
    origin: DVec3,
    /// Unit direction.
    dir: DVec3,
    /// Length of the ray's direction.
    length: f64,
    /// Coefficients in distance along `dir` from `origin`, constant first.
    coefficients: [f64; 5],
    /// Where roots are searched: the bounds' span, a little widened.
    range: (f64, f64),
}

impl Quartic {
    /// The ray parameter of a root, polished on the distance function.
    fn t(&self, torus: &Torus, u: f64) -> f64 {
        self.t_enter + torus.polish(self.origin, self.dir, u) / self.length
    }
}

impl Torus {
    /// The quartic of `ray` clipped to the bounds within `(t_min, t_max)`, or `None` when the
    /// ray misses the bounds there.
    fn quartic(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<Quartic> {
        let (t_enter, t_exit) = self.bounds().ray_interval(ray, t_min, t_max)?;
        let length = ray.direction.length();
        if !(length > 0.0 && length.is_finite() && t_enter.is_finite() && t_exit.is_finite()) {
            return None;
        }
        // Work from the box entry along the unit direction: u = (t - t_enter) * length.
        let dir = ray.direction / length;
        let o = ray.at(t_enter);
        let span = (t_exit - t_enter) * length;

        // (|p|^2 + R^2 - r^2)^2 - 4 R^2 (x^2 + z^2) = 0 with p = o + u dir, |dir| = 1.
        let r2 = self.major * self.major;
        let m = o.dot(dir);
        let k = o.length_squared() + r2 - self.minor * self.minor;
        let planar_dd = dir.x * dir.x + dir.z * dir.z;
        let planar_od = o.x * dir.x + o.z * dir.z;
        let planar_oo = o.x * o.x + o.z * o.z;
        // Roots on the box's faces (the outer equator, the top and bottom circles) must not be
        // lost to rounding at the ends of the interval: search slightly beyond both ends;
        // anything found there is still a point of the surface, and t is checked by the caller.
        let margin = 1e-9 * (self.major + self.minor);
        let range = (-margin, span + margin);
        if self.misses_thick_cylinder(range, planar_dd, planar_od, planar_oo) {
            return None;
        }
        let coefficients = [
            k * k - 4.0 * r2 * planar_oo,
            4.0 * m * k - 8.0 * r2 * planar_od,
            4.0 * m * m + 2.0 * k - 4.0 * r2 * planar_dd,
            4.0 * m,
            1.0,
        ];
        Some(Quartic { t_enter, origin: o, dir, length, coefficients, range })
    }

    /// True when, over the distances `range` along a unit direction (within the bounding
    /// box, so between the planes y = ±minor), the ray stays inside the hole (nearer the y
    /// axis than `major - minor`) or outside the torus's widest circle (farther than
    /// `major + minor`): no point there lies on the torus, and the quartic need not be
    /// solved (POV-Ray's thick-cylinder test). The squared distance from the axis is
    /// `oo + 2 od u + dd u^2`; a slack far above its rounding keeps grazing rays to the
    /// quartic.
    fn misses_thick_cylinder(&self, (lo, hi): (f64, f64), dd: f64, od: f64, oo: f64) -> bool {
        let squared = |u: f64| oo + u * (2.0 * od + u * dd);
        let (inner, outer) = ((self.major - self.minor).powi(2), (self.major + self.minor).powi(2));
        let slack = 1e-9 * outer;
        // A convex parabola in u: largest at an end, least at its vertex (or the nearer end).
        let (at_lo, at_hi) = (squared(lo), squared(hi));
        let vertex = if dd > 0.0 { (-od / dd).clamp(lo, hi) } else { lo };
        let (farthest, nearest) = (at_lo.max(at_hi), squared(vertex).min(at_lo).min(at_hi));
        farthest < inner - slack || nearest > outer + slack
    }

    /// Every crossing of `ray` at `t > 0` from one solution of the quartic (rather than one
    /// per crossing, as the API's defaults would): `visit` gets each surface, nearest first.
    fn for_each_crossing(&self, ray: &Ray, mut visit: impl FnMut(&Surface)) {
        let Some(quartic) = self.quartic(ray, 0.0, f64::INFINITY) else { return };
        let roots = polynomial_roots(&quartic.coefficients, quartic.range.0, quartic.range.1);
        for t in roots.as_slice().iter().map(|&u| quartic.t(self, u)).filter(|&t| t > 0.0) {
            visit(&self.surface_geometry(ray, &Hit::at(t)));
        }
    }

    /// A torus with `0 < minor < major` (not checked here; [`TorusParams`] validates).
    pub fn new(major: f64, minor: f64) -> Self {
        Self { major, minor }
    }

    /// Signed distance from `p` to the surface (negative inside the tube). Only asked near
    /// the torus (when polishing a root), so the square root of the sum of squares cannot
    /// overflow, and costs a fraction of `hypot`.
    fn distance(&self, p: DVec3) -> f64 {
        let rho = (p.x * p.x + p.z * p.z).sqrt();
        let across = rho - self.major;
        (across * across + p.y * p.y).sqrt() - self.minor
    }

    /// The unit outward normal at (or near) `p`: from the nearest point of the core circle.
    fn normal(&self, p: DVec3) -> DVec3 {
        let rho = (p.x * p.x + p.z * p.z).sqrt();
        let core =
            if rho > 0.0 { DVec3::new(p.x, 0.0, p.z) * (self.major / rho) } else { DVec3::new(self.major, 0.0, 0.0) };
        (p - core).normalize_or(DVec3::Y)
    }

    /// The tube angle theta in [0, 2 pi) at which the CDF of the marginal density
    /// (R + r cos theta) / (2 pi R), that is (R theta + r sin theta) / (2 pi R), equals `x`
    /// in [0, 1]. The CDF is increasing, so Newton's method kept inside a shrinking bracket
    /// (bisection when a step would leave it) converges for every ratio r / R < 1; plain
    /// Newton overshoots where the density is small (thick tori, theta near pi).
    fn tube_angle(&self, x: f64) -> f64 {
        let target = TAU * self.major * x;
        let (mut lo, mut hi) = (0.0, TAU);
        let mut theta = TAU * x;
        for _ in 0..200 {
            let f = self.major * theta + self.minor * theta.sin() - target;
            if f == 0.0 {
                break;
            }
            if f < 0.0 {
                lo = theta;
            } else {
                hi = theta;
            }
            let newton = theta - f / (self.major + self.minor * theta.cos());
            let next = if newton > lo && newton < hi { newton } else { 0.5 * (lo + hi) };
            let step = (next - theta).abs();
            theta = next;
            if step <= 1e-15 * TAU || hi - lo <= 1e-15 * TAU {
                break;
            }
        }
        theta
    }

    /// Newton's method on the distance function along the unit direction `dir` from
    /// `origin`, starting at the quartic's root `u`. The polynomial root is already close;
    /// this removes the error the quartic's coefficients carry when the origin lies near the
    /// surface. Steps are only taken while they shrink the distance and stay tiny, so a
    /// grazing ray (where the derivative vanishes) keeps the polynomial root.
    fn polish(&self, origin: DVec3, dir: DVec3, mut u: f64) -> f64 {
        let limit = 1e-6 * (self.major + self.minor);
        let mut d = self.distance(origin + u * dir);
        for _ in 0..3 {
            if d == 0.0 {
                break;
            }
            let p = origin + u * dir;
            let slope = self.normal(p).dot(dir);
            if slope.abs() < 1e-3 {
                break;
            }
            let step = -d / slope;
            if step.abs() > limit {
                break;
            }
            let next = self.distance(origin + (u + step) * dir);
            if next.abs() >= d.abs() {
                break;
            }
            u += step;
            d = next;
        }
        u
    }
}

impl Shape for Torus {
    fn bounds(&self) -> Aabb {
        let r = self.major + self.minor;
        Aabb::from_corners(DVec3::new(-r, -self.minor, -r), DVec3::new(r, self.minor, r))
    }

    fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit> {
        let quartic = self.quartic(ray, t_min, t_max)?;
        // Roots in ascending order, until one lies in the range: the farther ones are never
        // searched for.
        let mut nearest = None;
        let _ = visit_polynomial_roots(&quartic.coefficients, quartic.range.0, quartic.range.1, &mut |u| {
            let t = quartic.t(self, u);
            if t > t_min && t < t_max {
                nearest = Some(Hit::at(t));
                return ControlFlow::Break(());
            }
            ControlFlow::Continue(())
        });
        nearest
    }

    fn inside(&self, p: DVec3) -> bool {
        let rho = (p.x * p.x + p.z * p.z).sqrt();
        // The surface itself is inside, as in POV-Ray.
        (rho - self.major).powi(2) + p.y * p.y <= self.minor * self.minor
    }

    fn surface(&self, ray: &Ray, hit: &Hit) -> Surface {
        let mut surface = self.surface_geometry(ray, hit);
        let p = surface.point;
        let rho = (p.x * p.x + p.z * p.z).sqrt();
        // u runs around the y axis (as on the sphere), v around the tube from the outer equator.
        let u = 0.5 + p.z.atan2(-p.x) / TAU;
        let v = p.y.atan2(rho - self.major) / TAU;
        surface.uv = DVec2::new(u.rem_euclid(1.0), v.rem_euclid(1.0));
        surface
    }

    fn surface_geometry(&self, ray: &Ray, hit: &Hit) -> Surface {
        let HitPoint { point, normal, .. } = self.hit_point(ray, hit);
        // u turns the point about the y axis by a full turn, keeping its place around the tube.
        Surface::new(point, normal, DVec2::ZERO).with_dpdu(TAU * DVec3::new(point.z, 0.0, -point.x))
    }

    fn hit_point(&self, ray: &Ray, hit: &Hit) -> HitPoint {
        let p = ray.at(hit.t);
        let normal = self.normal(p);
        let rho = (p.x * p.x + p.z * p.z).sqrt();
        let core = if rho > 0.0 { DVec3::new(p.x, 0.0, p.z) * (self.major / rho) } else { p };
        // Project exactly onto the tube: removes the error of ray.at(t) along the normal.
        HitPoint::new(core + normal * self.minor, normal)
    }

    fn area(&self) -> Option<f64> {
        Some(4.0 * PI * PI * self.major * self.minor)
    }

    /// Uniform in area, exactly: the area element is r (R + r cos theta) dtheta dphi, so the
    /// angle around the y axis is uniform and the tube angle theta (0 on the outer equator)
    /// has the marginal density (R + r cos theta) / (2 pi R), whose CDF is inverted.
    fn sample_area(&self, u: DVec2) -> Option<AreaSample> {
        let phi = TAU * u.x;
        let theta = self.tube_angle(u.y);
        let normal = DVec3::new(theta.cos() * phi.cos(), theta.sin(), theta.cos() * phi.sin());
        let core = DVec3::new(phi.cos(), 0.0, phi.sin()) * self.major;
        Some(AreaSample { point: core + normal * self.minor, normal, pdf_area: 1.0 / self.area()? })
    }

    /// The default, area sampling with every crossing counted, from one solution of the
    /// quartic per direction instead of one per crossing.
    fn sample_toward(&self, reference: DVec3, u: DVec2) -> Option<DirectionSample> {
        let sample = self.sample_area(u)?;
        let (mut nearest, mut pdf) = (None, 0.0);
        self.for_each_crossing(&Ray::new(reference, sample.point - reference), |surface| {
            nearest.get_or_insert(*surface);
            pdf += math::area_to_solid_angle(sample.pdf_area, reference, surface.point, surface.normal);
        });
        let nearest: Surface = nearest?;
        (pdf > 0.0 && pdf.is_finite()).then_some(DirectionSample {
            point: nearest.point,
            normal: nearest.normal,
            pdf_solid_angle: pdf,
        })
    }

    fn pdf_toward(&self, reference: DVec3, direction: DVec3) -> f64 {
        let mut pdf = 0.0;
        self.for_each_crossing(&Ray::new(reference, direction), |surface| {
            pdf += math::area_to_solid_angle(self.pdf_area(surface.point), reference, surface.point, surface.normal);
        });
        pdf
    }

    fn to_pov(&self) -> Option<String> {
        // Symmetric under z -> -z, so the left-handed mapping changes nothing.
        Some(format!("torus {{ {}, {} }}", pov::number(self.major), pov::number(self.minor)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// POV-Ray's `Torus::Inside` counts the surface itself as inside.
    #[test]
    fn the_surface_is_inside() {
        let t = Torus::new(1.0, 0.25);
        assert!(t.inside(DVec3::new(1.25, 0.0, 0.0)) && !t.inside(DVec3::new(1.25 + 1e-12, 0.0, 0.0)));
    }
    use prism_api::contract::{ContractConfig, TestRng, check_dpdu, check_sampling_toward, check_shape};

    fn standard() -> Torus {
        Torus::new(1.0, 0.25)
    }

    fn first_hit(torus: &Torus, origin: DVec3, dir: DVec3) -> Option<f64> {
        torus.intersect(&Ray::new(origin, dir), 1e-9, f64::INFINITY).map(|h| h.t)
    }

    fn on_surface(torus: &Torus, p: DVec3, tol: f64) -> bool {
        torus.distance(p).abs() <= tol
    }

    #[test]
    fn contract_holds() {
        check_shape(&standard());
        check_shape(&Torus::new(3.0, 1.0));
        check_shape(&Torus::new(1.0, 0.02));
        check_shape(&Torus::new(200.0, 199.0));
        check_dpdu(&Torus::new(3.0, 1.0));
    }

    #[test]
    fn sampling_from_the_hole_the_axis_and_the_tube() {
        // From the centre of the hole every direction in the torus's plane crosses the inner
        // and the outer wall twice (four crossings), all of which could have been sampled.
        let config = ContractConfig::default();
        for torus in [standard(), Torus::new(2.0, 1.5)] {
            let references = [DVec3::ZERO, DVec3::new(0.0, 1.0, 0.0), DVec3::new(torus.major, 0.0, 0.0)];
            check_sampling_toward(&torus, &references, &config);
        }
    }

    #[test]
    fn tube_angles_invert_the_marginal_cdf() {
        for torus in [standard(), Torus::new(1.0, 0.999), Torus::new(200.0, 199.0)] {
            let (big, small) = (torus.major, torus.minor);
            for i in 0..=1000 {
                let x = i as f64 / 1000.0;
                let theta = torus.tube_angle(x);
                assert!((0.0..=TAU).contains(&theta), "{theta}");
                let cdf = (big * theta + small * theta.sin()) / (TAU * big);
                assert!((cdf - x).abs() < 1e-13, "{torus:?}: x = {x}, theta = {theta}, cdf = {cdf}");
            }
        }
    }

    #[test]
    fn rays_in_the_torus_plane_find_all_four_walls() {
        let t = standard();
        let ray = Ray::new(DVec3::new(-10.0, 0.0, 0.0), DVec3::X);
        let mut walls = vec![];
        let mut t_min = 1e-9;
        while let Some(hit) = t.intersect(&ray, t_min, f64::INFINITY) {
            walls.push(hit.t);
            t_min = hit.t + 1e-9;
        }
        let expected = [8.75, 9.25, 10.75, 11.25];
        assert_eq!(walls.len(), 4, "{walls:?}");
        for (w, e) in walls.iter().zip(expected) {
            assert!((w - e).abs() < 1e-12, "{w} vs {e}");
        }
        // Normals point out of the tube at each wall.
        let n = t.surface(&ray, &Hit::at(walls[1])).normal;
        assert!((n - DVec3::X).length() < 1e-12, "inner wall of the left tube faces the hole: {n}");
    }

    #[test]
    fn from_inside_the_tube_and_from_the_centre() {
        let t = standard();
        for dir in [DVec3::X, -DVec3::X, DVec3::Y, -DVec3::Y, DVec3::Z] {
            let hit = first_hit(&t, DVec3::new(1.0, 0.0, 0.0), dir).unwrap();
            // Along z the ray follows the core circle's tangent: it leaves the tube where
            // sqrt(1 + z^2) = 1.25.
            let expected = if dir == DVec3::Z { 0.75 } else { 0.25 };
            assert!((hit - expected).abs() < 1e-12, "{dir}: {hit}");
            let ray = Ray::new(DVec3::X, dir);
            let n = t.surface(&ray, &Hit::at(hit)).normal;
            assert!(n.dot(dir) > 0.99 || dir == DVec3::Z, "outward from inside: {n} for {dir}");
        }
        assert!((first_hit(&t, DVec3::ZERO, DVec3::X).unwrap() - 0.75).abs() < 1e-12);
        assert!((first_hit(&t, DVec3::ZERO, DVec3::new(0.0, 0.0, -3.0)).unwrap() - 0.25).abs() < 1e-12);
        assert!(first_hit(&t, DVec3::ZERO, DVec3::Y).is_none(), "up the axis from the centre");
    }

    /// The thick-cylinder test skips only rays that meet no point of the torus: rays aimed
    /// at the hole's rim and the widest circle (grazing both walls of the test) are skipped
    /// only where points sampled densely along them all lie outside the tube, and the rays
    /// that hit are never skipped. It must skip some rays, or it saves nothing.
    #[test]
    fn the_thick_cylinder_test_skips_only_rays_that_miss() {
        let mut rng = TestRng::new(17);
        for torus in [standard(), Torus::new(3.0, 1.0), Torus::new(1.0, 0.02)] {
            let (big, small) = (torus.major, torus.minor);
            let mut skipped = 0;
            for i in 0..1000 {
                // Aim at a point near the inner or the outer circle of the equator (grazing
                // the test's cylinders), or anywhere in the box (through its corners and the
                // hole too).
                let angle = rng.range(0.0, TAU);
                let target = if i % 2 == 0 {
                    let b = torus.bounds();
                    DVec3::new(rng.range(b.min.x, b.max.x), rng.range(b.min.y, b.max.y), rng.range(b.min.z, b.max.z))
                } else {
                    let radius = if i % 4 == 1 { big - small } else { big + small } * (1.0 + rng.range(-1e-3, 1e-3));
                    DVec3::new(radius * angle.cos(), rng.range(-small, small), radius * angle.sin())
                };
                let origin = target - 5.0 * (big + small) * rng.unit_vector();
                let ray = Ray::new(origin, target - origin);
                let skip = torus.bounds().ray_interval(&ray, 0.0, f64::INFINITY).is_some()
                    && torus.quartic(&ray, 0.0, f64::INFINITY).is_none();
                if !skip {
                    continue;
                }
                skipped += 1;
                assert!(torus.intersect(&ray, 0.0, f64::INFINITY).is_none());
                for k in 0..=4000 {
                    let p = ray.at(2.0 * k as f64 / 4000.0);
                    assert!(!torus.inside(p), "{torus:?}: skipped a ray through {p}");
                }
            }
            assert!(skipped > 40, "{torus:?}: only {skipped} of 1000 rays skipped");
        }
    }

    #[test]
    fn through_the_hole_along_the_axis() {
        let t = standard();
        assert!(first_hit(&t, DVec3::new(0.0, 10.0, 0.0), -DVec3::Y).is_none());
        assert!(first_hit(&t, DVec3::new(0.0, -1e7, 0.0), DVec3::Y).is_none());
        // Just inside the hole's rim misses, just on the tube hits near the equator.
        assert!(first_hit(&t, DVec3::new(0.75 - 1e-9, 10.0, 0.0), -DVec3::Y).is_none());
        let hit = first_hit(&t, DVec3::new(0.75 + 1e-6, 10.0, 0.0), -DVec3::Y).unwrap();
        let p = DVec3::new(0.75 + 1e-6, 10.0 - hit, 0.0);
        assert!(on_surface(&t, p, 1e-12) && p.y > 0.0 && p.y < 1e-2, "{p}");
    }

    #[test]
    fn tangent_to_the_top_of_the_tube_and_grazing() {
        let t = standard();
        // The line y = r touches the tube's top circle at x = -R and x = R: a double root.
        // Either outcome is allowed, but a reported hit must lie on the surface.
        if let Some(hit) = first_hit(&t, DVec3::new(-5.0, 0.25, 0.0), DVec3::X) {
            assert!(on_surface(&t, DVec3::new(-5.0 + hit, 0.25, 0.0), 1e-7));
        }
        // Slightly below: two close roots around x = -R, found, with no acne.
        for depth in [1e-4, 1e-6, 1e-8] {
            let y = 0.25 - depth;
            let hit = first_hit(&t, DVec3::new(-5.0, y, 0.0), DVec3::X).unwrap();
            let p = DVec3::new(-5.0 + hit, y, 0.0);
            assert!(on_surface(&t, p, 1e-12), "depth {depth}: {p} off by {}", t.distance(p));
            let half_chord = (0.25f64.powi(2) - y * y).sqrt();
            assert!((p.x + 1.0 + half_chord).abs() < 1e-9, "depth {depth}: {p}");
        }
        // Slightly above: a miss.
        assert!(first_hit(&t, DVec3::new(-5.0, 0.25 + 1e-9, 0.0), DVec3::X).is_none());
        // Grazing the outer equator along z.
        assert!(first_hit(&t, DVec3::new(1.25 + 1e-9, 0.0, -5.0), DVec3::Z).is_none());
        let hit = first_hit(&t, DVec3::new(1.25 - 1e-9, 0.0, -5.0), DVec3::Z).unwrap();
        assert!(on_surface(&t, DVec3::new(1.25 - 1e-9, 0.0, -5.0 + hit), 1e-12));
    }

    #[test]
    fn distant_origins_and_unnormalised_directions() {
        let t = standard();
        for distance in [1e3, 1e6, 1e8] {
            let origin = DVec3::new(0.9, 0.1, distance);
            let hit = first_hit(&t, origin, -DVec3::Z).unwrap();
            let p = origin - DVec3::Z * hit;
            assert!(on_surface(&t, p, 1e-15 * distance + 1e-12), "{distance}: {p}");
            assert!(p.z > 0.0);
            // The same ray with a scaled direction has a proportionally smaller t.
            let scaled = first_hit(&t, origin, -DVec3::Z * 8.0).unwrap();
            assert!((scaled * 8.0 - hit).abs() <= 1e-15 * distance + 1e-12);
        }
    }

    #[test]
    fn random_hits_lie_on_the_surface() {
        let mut rng = TestRng::new(7);
        for torus in [standard(), Torus::new(5.0, 0.1), Torus::new(1e-3, 4e-4)] {
            let scale = torus.major + torus.minor;
            let mut hits = 0;
            for _ in 0..20_000 {
                let origin = rng.unit_vector() * scale * rng.range(0.0, 4.0);
                let target = rng.point_in(&torus.bounds());
                let ray = Ray::new(origin, (target - origin) * rng.range(0.1, 10.0));
                if let Some(hit) = torus.intersect(&ray, 1e-12, f64::INFINITY) {
                    hits += 1;
                    let d = torus.distance(ray.at(hit.t));
                    assert!(d.abs() < 1e-13 * scale, "{ray:?} at {}: off by {d}", hit.t);
                }
            }
            assert!(hits > 1000);
        }
    }

    #[test]
    fn area_samples_lie_on_the_surface() {
        let t = Torus::new(2.0, 0.5);
        let mut rng = TestRng::new(3);
        let mut upper = 0;
        for _ in 0..10_000 {
            let s = t.sample_area(DVec2::new(rng.uniform(), rng.uniform())).unwrap();
            assert!(on_surface(&t, s.point, 1e-12));
            assert!((s.normal - t.normal(s.point)).length() < 1e-9);
            if (s.point.x * s.point.x + s.point.z * s.point.z).sqrt() > 2.0 {
                upper += 1;
            }
        }
        // The outer half holds (pi R + 2 r) / (2 pi R) of the area: 0.5796.
        let expected = (PI * 2.0 + 1.0) / (TAU * 2.0);
        assert!((upper as f64 / 10_000.0 - expected).abs() < 0.02, "{upper}");
    }

    #[test]
    fn uvs_are_finite_and_in_range() {
        let t = standard();
        let ray = Ray::new(DVec3::new(0.3, 5.0, 0.9), DVec3::new(0.3, -5.0, -0.1));
        let hit = t.intersect(&ray, 1e-9, f64::INFINITY).unwrap();
        let uv = t.surface(&ray, &hit).uv;
        assert!(uv.is_finite() && uv.x >= 0.0 && uv.x < 1.0 && uv.y >= 0.0 && uv.y < 1.0);
    }

    #[test]
    fn parameters_are_validated() {
        let ok = TorusParams { major_radius: 2.0, minor_radius: 0.5 }.build();
        assert!(ok.is_ok());
        let bad = TorusParams { major_radius: -1.0, minor_radius: 0.25 }.build().unwrap_err();
        assert_eq!(bad.key, "major_radius");
        let bad = TorusParams { major_radius: 1.0, minor_radius: 0.0 }.build().unwrap_err();
        assert_eq!(bad.key, "minor_radius");
        let spindle = TorusParams { major_radius: 1.0, minor_radius: 1.0 }.build().unwrap_err();
        assert_eq!(spindle.key, "minor_radius");
        assert!(spindle.message.contains("spindle"), "{}", spindle.message);
        let nan = TorusParams { major_radius: f64::NAN, minor_radius: 0.25 }.build().unwrap_err();
        assert_eq!(nan.key, "major_radius");
    }

    #[test]
    fn parameters_deserialise_with_defaults_and_deny_unknown_keys() {
        use serde::de::IntoDeserializer;
        use serde::de::value::{Error, MapDeserializer};
        let parse = |entries: Vec<(&'static str, f64)>| {
            let map: MapDeserializer<'_, _, Error> = MapDeserializer::new(entries.into_iter());
            TorusParams::deserialize(map.into_deserializer())
        };
        let defaults = parse(vec![]).unwrap();
        assert_eq!((defaults.major_radius, defaults.minor_radius), (1.0, 0.25));
        let set = parse(vec![("minor_radius", 0.5), ("major_radius", 3.0)]).unwrap();
        assert_eq!((set.major_radius, set.minor_radius), (3.0, 0.5));
        let unknown = parse(vec![("radius", 1.0)]).unwrap_err().to_string();
        assert!(unknown.contains("radius") && unknown.contains("unknown"), "{unknown}");
    }

    #[test]
    fn exports_to_pov() {
        assert_eq!(standard().to_pov().unwrap(), "torus { 1.0, 0.25 }");
        assert_eq!(Torus::new(2.5, 0.125).to_pov().unwrap(), "torus { 2.5, 0.125 }");
    }
}
