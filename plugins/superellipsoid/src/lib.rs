//! The superellipsoid shape plugin: POV-Ray's `superellipsoid { <e, n> }`, the surface
//!
//! ```text
//! (|x|^(2/e) + |y|^(2/e))^(e/n) + |z|^(2/n) = 1
//! ```
//!
//! inside the cube [-1, 1]^3, with `e` the east–west exponent (the shape of the cross
//! sections perpendicular to z) and `n` the north–south exponent (the profile along z, the
//! polar axis, as in POV-Ray). The equation is even in z, so the shape is the same in
//! Prism's right-handed frame and in POV-Ray's left-handed one.
//!
//! Rays are solved on the *gauge* of the shape rather than on the equation above:
//! `G(p) = N_b(N_a(|x|, |y|), |z|)` with `N_k(u, v) = (u^k + v^k)^(1/k)`, `a = 2/e`,
//! `b = 2/n`. `G = 1` is the same surface (`G < 1` inside), but `G` is homogeneous of degree
//! one (`G(s p) = s G(p)`), so it behaves like a distance whatever the exponents: no huge
//! powers, no overflow, and `p / G(p)` projects a point exactly onto the surface.
//!
//! * `e <= 2` and `n <= 2`: the shape is convex and `G` is a norm, convex along every ray.
//!   Newton's method started outside the shape then approaches the first root monotonically
//!   and cannot step over it, so there are no holes, even at grazing angles.
//! * Otherwise (star-shaped, concave sides): the ray is split where it crosses the planes
//!   x = 0, y = 0, z = 0, x = ±y, x = ±z, y = ±z (where POV-Ray splits it too), sampled
//!   every 0.05 units, and every sign change is refined by bisection and false position;
//!   sampled local minima of |G - 1| that come close to the surface are refined with a
//!   golden-section search so that grazing hits between samples are not lost.

use std::f64::consts::{PI, TAU};
use std::sync::Arc;

use prism_api::{Aabb, DVec2, DVec3, Hit, ParamError, Ray, Shape, ShapeParams, Surface, pov};
use schemars::JsonSchema;
use serde::Deserialize;

/// The largest exponent accepted: beyond it the shape degenerates into needles along the axes.
pub const MAX_EXPONENT: f64 = 10.0;

/// Parameters of `shape = "superellipsoid"`.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SuperellipsoidParams {
    /// East–west exponent, in (0, 10]: sections across z (1 round, to 0 square, 2 diamond, >2 concave).
    #[serde(default = "default_exponent")]
    pub e: f64,
    /// North–south exponent, in (0, 10]: profile along z, the polar axis (1 round, to 0 flat, 2 pointed).
    #[serde(default = "default_exponent")]
    pub n: f64,
}

fn default_exponent() -> f64 {
    1.0
}

fn require_exponent(key: &str, value: f64) -> Result<(), ParamError> {
    ParamError::require_positive(key, value)?;
    if value > MAX_EXPONENT {
        return Err(ParamError::new(key, format!("must be at most {MAX_EXPONENT}, got {value}")));
    }
    Ok(())
}

impl ShapeParams for SuperellipsoidParams {
    fn build(self) -> Result<Arc<dyn Shape>, ParamError> {
        require_exponent("e", self.e)?;
        require_exponent("n", self.n)?;
        Ok(Arc::new(Superellipsoid::new(self.e, self.n)))
    }
}

/// POV-Ray's superellipsoid in the cube [-1, 1]^3.
#[derive(Clone, Debug, PartialEq)]
pub struct Superellipsoid {
    /// East–west exponent (> 0).
    pub e: f64,
    /// North–south exponent (> 0).
    pub n: f64,
    /// 2 / e: the power inside the x–y norm.
    a: f64,
    /// 2 / n: the power of the outer norm.
    b: f64,
}

/// `(u^k + v^k)^(1/k)` for `u, v >= 0`, scaled so that nothing overflows.
fn pnorm(u: f64, v: f64, k: f64) -> f64 {
    let m = u.max(v);
    if m == 0.0 {
        return 0.0;
    }
    let s = u.min(v) / m;
    if k == 2.0 {
        m * (1.0 + s * s).sqrt()
    } else if k == 1.0 {
        m * (1.0 + s)
    } else {
        m * (1.0 + s.powf(k)).powf(1.0 / k)
    }
}

/// `ratio^(k - 1)`: the partial derivative of `N_k` along a component, given the component
/// divided by the norm (in [0, 1]).
fn partial(ratio: f64, k: f64) -> f64 {
    if k == 2.0 {
        ratio
    } else if k == 1.0 {
        1.0
    } else {
        ratio.powf(k - 1.0)
    }
}

/// Spacing of the samples along the ray in the non-convex case, in object-space units.
const SAMPLE_SPACING: f64 = 0.05;

impl Superellipsoid {
    /// The superellipsoid `<e, n>` (exponents not checked here; [`SuperellipsoidParams`]
    /// validates).
    pub fn new(e: f64, n: f64) -> Self {
        Self { e, n, a: 2.0 / e, b: 2.0 / n }
    }

    /// True when the shape is convex (both exponents at most 2).
    pub fn is_convex(&self) -> bool {
        self.e <= 2.0 && self.n <= 2.0
    }

    /// The gauge G(p): 1 on the surface, less inside, homogeneous of degree one.
    pub fn gauge(&self, p: DVec3) -> f64 {
        pnorm(pnorm(p.x.abs(), p.y.abs(), self.a), p.z.abs(), self.b)
    }

    /// The gradient of the gauge; components may be infinite at the tips of a concave shape
    /// and undefined on creases (a subgradient is returned there).
    fn gradient(&self, p: DVec3) -> DVec3 {
        let (ax, ay, az) = (p.x.abs(), p.y.abs(), p.z.abs());
        let u = pnorm(ax, ay, self.a);
        let g = pnorm(u, az, self.b);
        if g == 0.0 {
            return DVec3::ZERO;
        }
        let du = partial(u / g, self.b);
        let (dx, dy) = if u > 0.0 { (du * partial(ax / u, self.a), du * partial(ay / u, self.a)) } else { (0.0, 0.0) };
        let dz = partial(az / g, self.b);
        DVec3::new(1f64.copysign(p.x) * dx, 1f64.copysign(p.y) * dy, 1f64.copysign(p.z) * dz)
    }

    /// The unit outward normal at `p`: the normalised gradient, or, at the tip of a spike
    /// (where the gradient is infinite: every direction across the spike is a limit of the
    /// normal) and where it vanishes, the radial direction, which points along the spike.
    fn normal(&self, p: DVec3) -> DVec3 {
        let grad = self.gradient(p);
        let grad = if grad.is_finite() { grad } else { DVec3::ZERO };
        grad.try_normalize().or_else(|| p.try_normalize()).unwrap_or(DVec3::Y)
    }

    /// G - 1 along the ray `o + u dir`.
    fn level(&self, o: DVec3, dir: DVec3, u: f64) -> f64 {
        self.gauge(o + u * dir) - 1.0
    }

    /// Newton's method on the convex function G(o + u dir) - 1 from `u`, where it is
    /// positive, moving in direction `sense` (+1 forward, -1 backward). Convexity makes the
    /// iterates approach the nearest root from outside without passing it. `None` when the
    /// function stops decreasing (no root that way) or the iterate leaves `[lo, hi]`.
    fn newton_convex(&self, o: DVec3, dir: DVec3, mut u: f64, sense: f64, lo: f64, hi: f64) -> Option<f64> {
        for _ in 0..200 {
            let p = o + u * dir;
            let value = self.gauge(p) - 1.0;
            if value <= 0.0 {
                return Some(u);
            }
            let slope = self.gradient(p).dot(dir) * sense;
            // Not decreasing (or NaN): no root in this direction.
            if slope.is_nan() || slope >= 0.0 {
                return None;
            }
            let step = -value / slope * sense;
            u += step;
            if u < lo || u > hi {
                return None;
            }
            if step.abs() <= 1e-15 * (1.0 + u.abs()) {
                return Some(u);
            }
        }
        // Creeping towards a tangent point: a grazing miss.
        None
    }

    /// The root of `level` in `[u0, u1]`, where its values `g0` and `g1` differ in sign:
    /// false position (Illinois variant) safeguarded by bisection.
    fn refine(&self, o: DVec3, dir: DVec3, mut u0: f64, mut u1: f64, mut g0: f64, mut g1: f64) -> f64 {
        let mut side = 0;
        for i in 0..100 {
            let width = u1 - u0;
            if width <= 1e-15 * (1.0 + u0.abs().max(u1.abs())) {
                break;
            }
            let secant = u0 - g0 * width / (g1 - g0);
            let u = if i % 4 == 3 || !(secant > u0 && secant < u1) { 0.5 * (u0 + u1) } else { secant };
            let g = self.level(o, dir, u);
            if g == 0.0 {
                return u;
            }
            if (g < 0.0) == (g0 < 0.0) {
                u0 = u;
                g0 = g;
                if side == -1 {
                    g1 *= 0.5;
                }
                side = -1;
            } else {
                u1 = u;
                g1 = g;
                if side == 1 {
                    g0 *= 0.5;
                }
                side = 1;
            }
        }
        if g0.abs() <= g1.abs() { u0 } else { u1 }
    }

    /// Golden-section search for the extremum of `level` towards zero in `[u0, u2]`, given
    /// that the sample at `u1` is closer to zero than both ends and all three have the sign
    /// of `sign`. Returns a point where the sign flips, if the search finds one.
    fn find_dip(&self, o: DVec3, dir: DVec3, mut lo: f64, mut hi: f64, sign: f64) -> Option<(f64, f64)> {
        const INV_PHI: f64 = 0.618_033_988_749_894_8;
        let mut x1 = hi - INV_PHI * (hi - lo);
        let mut x2 = lo + INV_PHI * (hi - lo);
        let mut f1 = sign * self.level(o, dir, x1);
        let mut f2 = sign * self.level(o, dir, x2);
        for _ in 0..80 {
            if f1 <= 0.0 {
                return Some((x1, sign * f1));
            }
            if f2 <= 0.0 {
                return Some((x2, sign * f2));
            }
            if hi - lo <= 1e-13 {
                break;
            }
            if f1 < f2 {
                hi = x2;
                x2 = x1;
                f2 = f1;
                x1 = hi - INV_PHI * (hi - lo);
                f1 = sign * self.level(o, dir, x1);
            } else {
                lo = x1;
                x1 = x2;
                f1 = f2;
                x2 = lo + INV_PHI * (hi - lo);
                f2 = sign * self.level(o, dir, x2);
            }
        }
        None
    }

    /// The first root in `[lo, hi]` along `o + u dir` (|dir| = 1) accepted by `accept`, for
    /// the convex case.
    fn first_root_convex(&self, o: DVec3, dir: DVec3, lo: f64, hi: f64, accept: impl Fn(f64) -> bool) -> Option<f64> {
        let g_lo = self.level(o, dir, lo);
        if g_lo > 0.0 {
            match self.newton_convex(o, dir, lo, 1.0, lo, hi) {
                Some(u) if accept(u) => return Some(u),
                Some(_) => {}
                // Outside, and the function never comes down to zero: a miss.
                None => return None,
            }
        }
        // Inside at `lo` (or the entry was rejected): the exit, found from the far end.
        if self.level(o, dir, hi) > 0.0 {
            return self.newton_convex(o, dir, hi, -1.0, lo, hi).filter(|&u| accept(u));
        }
        None
    }

    /// The first root in `[lo, hi]` accepted by `accept`, for any exponents, by sampling.
    fn first_root_sampled(&self, o: DVec3, dir: DVec3, lo: f64, hi: f64, accept: impl Fn(f64) -> bool) -> Option<f64> {
        // Split points: the planes on which |x|, |y|, |z| change sign or order.
        let mut splits = [0.0; 11];
        let mut count = 0;
        splits[count] = lo;
        count += 1;
        let planes = [
            DVec3::X,
            DVec3::Y,
            DVec3::Z,
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(1.0, -1.0, 0.0),
            DVec3::new(1.0, 0.0, 1.0),
            DVec3::new(1.0, 0.0, -1.0),
            DVec3::new(0.0, 1.0, 1.0),
            DVec3::new(0.0, 1.0, -1.0),
        ];
        for normal in planes {
            let u = -normal.dot(o) / normal.dot(dir);
            if u > lo && u < hi {
                splits[count] = u;
                count += 1;
            }
        }
        splits[count] = hi;
        count += 1;
        let splits = &mut splits[..count];
        splits.sort_by(f64::total_cmp);

        // A sliding window over the samples: (u, value) for the last three.
        let mut window: [(f64, f64); 3] = [(lo, self.level(o, dir, lo)); 3];
        let mut filled = 1;
        if window[0].1 == 0.0 && accept(lo) {
            return Some(lo);
        }
        for piece in splits.windows(2) {
            let (s0, s1) = (piece[0], piece[1]);
            let steps = ((s1 - s0) / SAMPLE_SPACING).ceil().max(1.0) as usize;
            for j in 1..=steps {
                let u = if j == steps { s1 } else { s0 + (s1 - s0) * j as f64 / steps as f64 };
                let sample = (u, self.level(o, dir, u));
                window = [window[1], window[2], sample];
                filled += 1;
                let (u1, g1) = window[1];
                let (u2, g2) = window[2];
                if g2 == 0.0 {
                    if accept(u2) {
                        return Some(u2);
                    }
                    continue;
                }
                if g1 != 0.0 && (g1 < 0.0) != (g2 < 0.0) {
                    let root = self.refine(o, dir, u1, u2, g1, g2);
                    if accept(root) {
                        return Some(root);
                    }
                    continue;
                }
                if filled < 3 {
                    continue;
                }
                // A sampled extremum close to zero: look for a dip through the surface.
                let (u0, g0) = window[0];
                let sign = g1.signum();
                let (m0, m1, m2) = (sign * g0, sign * g1, sign * g2);
                if m0 > 0.0
                    && m1 > 0.0
                    && m1 < m0
                    && m1 < m2
                    && m1 < 2.0 * (m0 - m1).max(m2 - m1)
                    && let Some((um, gm)) = self.find_dip(o, dir, u0, u2, sign)
                {
                    for root in [self.refine(o, dir, u0, um, g0, gm), self.refine(o, dir, um, u2, gm, g2)] {
                        if accept(root) {
                            return Some(root);
                        }
                    }
                }
            }
        }
        None
    }
}

impl Shape for Superellipsoid {
    fn bounds(&self) -> Aabb {
        Aabb::from_corners(DVec3::splat(-1.0), DVec3::splat(1.0))
    }

    fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit> {
        // The surface touches the cube's faces: clip to a slightly larger cube so that the
        // face points are not lost to rounding.
        let slack = Aabb::from_corners(DVec3::splat(-1.0 - 1e-9), DVec3::splat(1.0 + 1e-9));
        let (t_enter, t_exit) = slack.ray_interval(ray, t_min, t_max)?;
        let length = ray.direction.length();
        if !(length > 0.0 && length.is_finite() && t_enter.is_finite() && t_exit.is_finite()) {
            return None;
        }
        let dir = ray.direction / length;
        let o = ray.at(t_enter);
        let span = (t_exit - t_enter) * length;
        let to_t = |u: f64| t_enter + u / length;
        let accept = |u: f64| {
            let t = to_t(u);
            t > t_min && t < t_max
        };
        let root = if self.is_convex() {
            self.first_root_convex(o, dir, 0.0, span, accept)
        } else {
            self.first_root_sampled(o, dir, 0.0, span, accept)
        };
        root.map(|u| Hit::at(to_t(u)))
    }

    fn surface(&self, ray: &Ray, hit: &Hit) -> Surface {
        let p = ray.at(hit.t);
        // G is homogeneous: p / G(p) lies exactly on the surface, along the radial direction.
        let g = self.gauge(p);
        let point = if g > 0.0 && g.is_finite() { p / g } else { p };
        let normal = self.normal(point);
        // Longitude around y and latitude from the south pole, as on the sphere (to which
        // the shape reduces for e = n = 1).
        let d = point.normalize_or(DVec3::Y);
        let u = 0.5 + d.z.atan2(-d.x) / TAU;
        let v = 0.5 + d.y.clamp(-1.0, 1.0).asin() / PI;
        Surface::new(point, normal, DVec2::new(u.rem_euclid(1.0), v))
    }

    fn to_pov(&self) -> Option<String> {
        // Even in z: the left-handed mapping (x, y, z) -> (x, y, -z) changes nothing.
        Some(format!("superellipsoid {{ <{}, {}> }}", pov::number(self.e), pov::number(self.n)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use prism_api::contract::{TestRng, check_shape};

    /// POV-Ray's implicit function, written as POV-Ray writes it.
    fn pov_function(s: &Superellipsoid, p: DVec3) -> f64 {
        (p.x.abs().powf(2.0 / s.e) + p.y.abs().powf(2.0 / s.e)).powf(s.e / s.n) + p.z.abs().powf(2.0 / s.n) - 1.0
    }

    fn hit(s: &Superellipsoid, origin: DVec3, dir: DVec3) -> Option<DVec3> {
        let ray = Ray::new(origin, dir);
        s.intersect(&ray, 1e-9, f64::INFINITY).map(|h| ray.at(h.t))
    }

    #[test]
    fn contract_holds() {
        check_shape(&Superellipsoid::new(1.0, 1.0));
        check_shape(&Superellipsoid::new(0.2, 0.5));
        check_shape(&Superellipsoid::new(1.0, 0.1));
        check_shape(&Superellipsoid::new(2.5, 3.0));
        check_shape(&Superellipsoid::new(0.5, 2.5));
    }

    #[test]
    fn gauge_matches_povs_function() {
        let mut rng = TestRng::new(11);
        for (e, n) in [(1.0, 1.0), (0.25, 0.5), (3.0, 0.3), (2.0, 2.0), (0.05, 4.0)] {
            let s = Superellipsoid::new(e, n);
            for _ in 0..1000 {
                let p = DVec3::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0), rng.range(-1.0, 1.0));
                let g = s.gauge(p);
                let f = pov_function(&s, p);
                assert_eq!(g < 1.0, f < 0.0, "<{e}, {n}> at {p}: G = {g}, f = {f}");
                if g > 0.0 {
                    assert!(pov_function(&s, p / g).abs() < 1e-9, "projection off the surface");
                }
            }
        }
    }

    #[test]
    fn sphere_for_unit_exponents() {
        let s = Superellipsoid::new(1.0, 1.0);
        let ray = Ray::new(DVec3::new(0.3, 0.2, 5.0), -DVec3::Z);
        let h = s.intersect(&ray, 1e-9, f64::INFINITY).unwrap();
        let expected = 5.0 - (1.0f64 - 0.09 - 0.04).sqrt();
        assert!((h.t - expected).abs() < 1e-12, "{} vs {expected}", h.t);
        let surface = s.surface(&ray, &h);
        assert!((surface.normal - surface.point.normalize()).length() < 1e-12);
    }

    #[test]
    fn rounded_box_faces_edges_and_inside() {
        let s = Superellipsoid::new(0.2, 0.2);
        // Head-on at a face centre: exactly on the cube face.
        let p = hit(&s, DVec3::new(0.0, 0.0, 7.0), -DVec3::Z).unwrap();
        assert!((p.z - 1.0).abs() < 1e-12);
        let n = s.normal(p);
        assert!((n - DVec3::Z).length() < 1e-9, "{n}");
        // Along an axis from inside (the centre) and from a point inside near a corner.
        let p = hit(&s, DVec3::ZERO, DVec3::Y).unwrap();
        assert!((p.y - 1.0).abs() < 1e-12);
        let p = hit(&s, DVec3::splat(0.5), DVec3::new(1.0, 0.3, 0.2)).unwrap();
        assert!(pov_function(&s, p).abs() < 1e-9, "{p}");
        // Along the diagonal the corner is rounded: the hit is inside the cube's corner.
        let p = hit(&s, DVec3::splat(5.0), -DVec3::ONE).unwrap();
        assert!(p.x < 1.0 && p.x > 0.8 && pov_function(&s, p).abs() < 1e-9, "{p}");
    }

    #[test]
    fn grazing_and_tangent_rays() {
        for s in [Superellipsoid::new(1.0, 1.0), Superellipsoid::new(0.5, 0.5), Superellipsoid::new(3.0, 3.0)] {
            // Tangent to the top (z = 1): a grazing line either misses or touches the top.
            if let Some(p) = hit(&s, DVec3::new(-5.0, 0.0, 1.0), DVec3::X) {
                assert!(s.gauge(p) - 1.0 < 1e-9, "{p}");
            }
            // A hair below the top: two close roots, the first found on the surface.
            let p = hit(&s, DVec3::new(-5.0, 0.0, 1.0 - 1e-6), DVec3::X)
                .unwrap_or_else(|| panic!("<{}, {}> lost a grazing hit", s.e, s.n));
            assert!((s.gauge(p) - 1.0).abs() < 1e-12, "{p}");
            assert!(p.x < 0.0);
            assert!(hit(&s, DVec3::new(-5.0, 0.0, 1.0 + 1e-9), DVec3::X).is_none());
        }
    }

    #[test]
    fn concave_shape_finds_every_wall() {
        // e = n = 4: thin arms along the axes with concave sides between them.
        let s = Superellipsoid::new(4.0, 4.0);
        let ray = Ray::new(DVec3::new(-3.0, 0.05, 0.05), DVec3::X);
        let mut walls = vec![];
        let mut t_min = 1e-9;
        while let Some(h) = s.intersect(&ray, t_min, f64::INFINITY) {
            walls.push(ray.at(h.t).x);
            t_min = h.t + 1e-9;
        }
        // The x arm (two walls), then the y and z arms crossed near the centre.
        assert!(walls.len() >= 2 && walls.len() % 2 == 0, "{walls:?}");
        for x in &walls {
            let p = DVec3::new(*x, 0.05, 0.05);
            assert!(pov_function(&s, p).abs() < 1e-8, "{p}");
        }
    }

    #[test]
    fn random_hits_lie_on_the_surface_and_agree_with_sampling() {
        let mut rng = TestRng::new(5);
        for (e, n) in [(1.0, 1.0), (0.3, 0.7), (0.01, 1.5), (2.0, 2.0)] {
            let s = Superellipsoid::new(e, n);
            let mut hits = 0;
            for _ in 0..5_000 {
                let origin = rng.unit_vector() * rng.range(0.0, 6.0);
                let target = rng.point_in(&s.bounds());
                let ray = Ray::new(origin, (target - origin) * rng.range(0.1, 10.0));
                let convex = s.intersect(&ray, 1e-9, f64::INFINITY);
                let sampled = (|| {
                    let (t0, t1) = s.bounds().ray_interval(&ray, 1e-9, f64::INFINITY)?;
                    let len = ray.direction.length();
                    let o = ray.at(t0);
                    let accept = |u: f64| t0 + u / len > 1e-9;
                    s.first_root_sampled(o, ray.direction / len, 0.0, (t1 - t0) * len, accept).map(|u| t0 + u / len)
                })();
                match (convex, sampled) {
                    (Some(h), Some(t)) => {
                        hits += 1;
                        assert!((s.gauge(ray.at(h.t)) - 1.0).abs() < 1e-12);
                        assert!((h.t - t).abs() < 1e-9 * (1.0 + t), "<{e}, {n}> {ray:?}: {} vs {t}", h.t);
                    }
                    (None, None) => {}
                    (a, b) => {
                        // Only tangent rays may disagree.
                        let t = a.map(|h| h.t).or(b).unwrap();
                        let grad = s.normal(ray.at(t));
                        assert!(grad.dot(ray.direction.normalize()).abs() < 1e-3, "<{e}, {n}> {ray:?}: {a:?} vs {b:?}");
                    }
                }
            }
            assert!(hits > 500, "{hits}");
        }
    }

    #[test]
    fn normals_are_unit_and_outward_even_at_tips_and_creases() {
        for s in [Superellipsoid::new(4.0, 4.0), Superellipsoid::new(2.0, 2.0), Superellipsoid::new(0.1, 0.1)] {
            for p in [DVec3::X, DVec3::Y, DVec3::Z, -DVec3::Z, DVec3::new(0.0, 0.0, 1.0)] {
                let n = s.normal(p);
                assert!((n.length() - 1.0).abs() < 1e-12 && n.dot(p) > 0.0, "<{}, {}> at {p}: {n}", s.e, s.n);
            }
        }
        // From outside along each axis, to the tips of a concave shape.
        let s = Superellipsoid::new(4.0, 4.0);
        for axis in [DVec3::X, DVec3::Y, DVec3::Z] {
            let ray = Ray::new(axis * 3.0, -axis);
            let h = s.intersect(&ray, 1e-9, f64::INFINITY).unwrap();
            assert!((h.t - 2.0).abs() < 1e-12);
            let surface = s.surface(&ray, &h);
            assert!(surface.uv.is_finite() && (surface.normal.length() - 1.0).abs() < 1e-12);
        }
    }

    #[test]
    fn distant_origins() {
        let s = Superellipsoid::new(0.5, 0.5);
        for distance in [1e3, 1e6, 1e8] {
            let origin = DVec3::new(0.2, 0.3, -distance);
            let p = hit(&s, origin, DVec3::Z * 3.0).unwrap();
            assert!(p.z < -0.99 && (s.gauge(p) - 1.0).abs() < 1e-15 * distance + 1e-12, "{p}");
        }
    }

    #[test]
    fn parameters_are_validated() {
        assert!(SuperellipsoidParams { e: 0.3, n: 2.5 }.build().is_ok());
        assert_eq!(SuperellipsoidParams { e: 0.0, n: 1.0 }.build().unwrap_err().key, "e");
        assert_eq!(SuperellipsoidParams { e: 1.0, n: -1.0 }.build().unwrap_err().key, "n");
        assert_eq!(SuperellipsoidParams { e: 1.0, n: 11.0 }.build().unwrap_err().key, "n");
        assert_eq!(SuperellipsoidParams { e: f64::INFINITY, n: 1.0 }.build().unwrap_err().key, "e");
    }

    #[test]
    fn parameters_deserialise_with_defaults_and_deny_unknown_keys() {
        use serde::de::IntoDeserializer;
        use serde::de::value::{Error, MapDeserializer};
        let parse = |entries: Vec<(&'static str, f64)>| {
            let map: MapDeserializer<'_, _, Error> = MapDeserializer::new(entries.into_iter());
            SuperellipsoidParams::deserialize(map.into_deserializer())
        };
        let defaults = parse(vec![]).unwrap();
        assert_eq!((defaults.e, defaults.n), (1.0, 1.0));
        assert!(parse(vec![("exponent", 1.0)]).unwrap_err().to_string().contains("unknown"));
    }

    #[test]
    fn exports_to_pov() {
        assert_eq!(Superellipsoid::new(0.25, 1.0).to_pov().unwrap(), "superellipsoid { <0.25, 1.0> }");
    }
}
