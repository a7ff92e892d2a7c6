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
//!   every 0.05 units, and every sign change is refined by Newton's method safeguarded by
//!   bisection; sampled local minima of |G - 1| that come close to the surface are refined
//!   with a golden-section search so that grazing hits between samples are not lost. G
//!   increases with each |coordinate|, which bounds it over a whole stretch of the ray with
//!   one evaluation: samples are only evaluated where such bounds do not already rule out
//!   the surface.

#![forbid(unsafe_code)]

use std::f64::consts::{PI, TAU};
use std::sync::Arc;

use prism_api::{Aabb, DVec2, DVec3, Hit, HitPoint, ParamError, Ray, Shape, ShapeParams, Surface, math, pov};
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
    a: Exponent,
    /// 2 / n: the power of the outer norm.
    b: Exponent,
}

/// `x -> x^k` for `x >= 0`. `powf` dominates the cost of the shape, so exponents that are
/// multiples of 1/8 up to 10 (`2 / e` for `e` = 0.2, 0.25, 0.5, 1, 4, ..., `e / 2` for `e` =
/// 0.25, 0.5, 1, 1.5, 2.5, 3, ...) take a path without it: repeated squaring for the whole
/// part and square roots for the eighths, all correctly rounded steps, which stays within 5
/// epsilons (relative) of `powf`. Larger whole parts would lose more by squaring.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Power {
    /// `k = whole + eighths / 8`.
    Eighths { whole: u32, eighths: u32 },
    /// Any other exponent.
    General(f64),
}

impl Power {
    fn new(k: f64) -> Self {
        let scaled = k * 8.0;
        if scaled > 0.0 && scaled <= 80.0 && scaled.fract() == 0.0 {
            let scaled = scaled as u32;
            Power::Eighths { whole: scaled / 8, eighths: scaled % 8 }
        } else {
            Power::General(k)
        }
    }

    #[inline]
    fn of(self, x: f64) -> f64 {
        match self {
            Power::General(k) => x.powf(k),
            Power::Eighths { whole, eighths } => {
                let mut result = 1.0;
                let (mut base, mut bits) = (x, whole);
                while bits > 0 {
                    if bits & 1 == 1 {
                        result *= base;
                    }
                    bits >>= 1;
                    if bits > 0 {
                        base *= base;
                    }
                }
                if eighths != 0 {
                    let half = x.sqrt();
                    if eighths & 4 != 0 {
                        result *= half;
                    }
                    if eighths & 3 != 0 {
                        let quarter = half.sqrt();
                        if eighths & 2 != 0 {
                            result *= quarter;
                        }
                        if eighths & 1 != 0 {
                            result *= quarter.sqrt();
                        }
                    }
                }
                result
            }
        }
    }
}

/// The norm `N_k(u, v) = (u^k + v^k)^(1/k)` for one exponent `k`.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Exponent {
    /// The exponent itself.
    k: f64,
    /// `x^k`.
    power: Power,
    /// `x^(1/k)`.
    root: Power,
}

impl Exponent {
    /// The exponent `k = 2 / e` (`1 / k = e / 2` exactly).
    fn from_shape_exponent(e: f64) -> Self {
        Self { k: 2.0 / e, power: Power::new(2.0 / e), root: Power::new(0.5 * e) }
    }

    /// `N_k(u, v)` for `u, v >= 0`, scaled so that nothing overflows.
    #[inline]
    fn norm(&self, u: f64, v: f64) -> f64 {
        let m = u.max(v);
        if m == 0.0 {
            return 0.0;
        }
        let s = u.min(v) / m;
        m * self.root.of(1.0 + self.power.of(s))
    }

    /// `N_k(u, v)` and its partial derivatives along `u` and `v`, from the same two powers:
    /// with `m` the larger component, `s` the ratio of the smaller to it, `t = s^k` and
    /// `r = (1 + t)^(1/k)`, `N = m r`, the partial along the larger component is
    /// `r^(1-k) = r / (1 + t)` and along the smaller `(s / r)^(k-1) = (t / s) r / (1 + t)`.
    /// At `s = 0` the latter is `0^(k-1)`: 0, 1, or infinite (a spike's tip) for `k` above,
    /// at or below 1. All zero at the origin.
    #[inline]
    fn norm_and_partials(&self, u: f64, v: f64) -> (f64, f64, f64) {
        let m = u.max(v);
        if m == 0.0 {
            return (0.0, 0.0, 0.0);
        }
        let s = u.min(v) / m;
        let t = self.power.of(s);
        let r = self.root.of(1.0 + t);
        let larger = r / (1.0 + t);
        let smaller = if s > 0.0 {
            t / s * larger
        } else if self.k > 1.0 {
            0.0
        } else if self.k < 1.0 {
            f64::INFINITY
        } else {
            1.0
        };
        let (du, dv) = if u >= v { (larger, smaller) } else { (smaller, larger) };
        (m * r, du, dv)
    }
}

/// How [`Superellipsoid::newton_convex`] ended.
enum Newton {
    /// The start point is not outside the shape (G <= 1, or undefined).
    Inside,
    /// The nearest root in the search direction.
    Root(f64),
    /// No root that way within the bounds.
    Miss,
}

/// Normals of the planes through the centre on which |x|, |y|, |z| change sign or order:
/// the non-convex case splits rays there (as POV-Ray does).
const SPLIT_PLANES: [DVec3; 9] = [
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

/// Spacing of the samples along the ray in the non-convex case, in object-space units.
const SAMPLE_SPACING: f64 = 0.05;

impl Superellipsoid {
    /// The superellipsoid `<e, n>` (exponents not checked here; [`SuperellipsoidParams`]
    /// validates).
    pub fn new(e: f64, n: f64) -> Self {
        Self { e, n, a: Exponent::from_shape_exponent(e), b: Exponent::from_shape_exponent(n) }
    }

    /// True when the shape is convex (both exponents at most 2).
    pub fn is_convex(&self) -> bool {
        self.e <= 2.0 && self.n <= 2.0
    }

    /// The gauge G(p): 1 on the surface, less inside, homogeneous of degree one.
    pub fn gauge(&self, p: DVec3) -> f64 {
        self.b.norm(self.a.norm(p.x.abs(), p.y.abs()), p.z.abs())
    }

    /// The gauge and its gradient, for the cost of the gauge alone. Gradient components may
    /// be infinite at the tips of a concave shape and undefined on creases (a subgradient is
    /// returned there); the gradient is zero at the origin.
    fn gauge_and_gradient(&self, p: DVec3) -> (f64, DVec3) {
        let (ax, ay, az) = (p.x.abs(), p.y.abs(), p.z.abs());
        let (u, du_dx, du_dy) = self.a.norm_and_partials(ax, ay);
        let (g, dg_du, dz) = self.b.norm_and_partials(u, az);
        let (dx, dy) = if u > 0.0 { (dg_du * du_dx, dg_du * du_dy) } else { (0.0, 0.0) };
        (g, DVec3::new(1f64.copysign(p.x) * dx, 1f64.copysign(p.y) * dy, 1f64.copysign(p.z) * dz))
    }

    /// The unit outward normal at `p`: see [`Self::normal_from_gradient`].
    #[cfg(test)]
    fn normal(&self, p: DVec3) -> DVec3 {
        Self::normal_from_gradient(self.gauge_and_gradient(p).1, p)
    }

    /// The unit outward normal at `p`, given the gauge's gradient there (or at any point on
    /// the same ray from the centre: the gradient is homogeneous of degree zero): the
    /// normalised gradient, or, at the tip of a spike (where the gradient is infinite: every
    /// direction across the spike is a limit of the normal) and where it vanishes, the radial
    /// direction, which points along the spike.
    fn normal_from_gradient(grad: DVec3, p: DVec3) -> DVec3 {
        let grad = if grad.is_finite() { grad } else { DVec3::ZERO };
        grad.try_normalize().or_else(|| p.try_normalize()).unwrap_or(DVec3::Y)
    }

    /// G - 1 along the ray `o + u dir`.
    fn level(&self, o: DVec3, dir: DVec3, u: f64) -> f64 {
        self.gauge(o + u * dir) - 1.0
    }

    /// Newton's method on the convex function G(o + u dir) - 1 from `u`, moving in direction
    /// `sense` (+1 forward, -1 backward). [`Newton::Inside`] when the function is not positive
    /// at `u`; otherwise convexity makes the iterates approach the nearest root from outside
    /// without passing it, and [`Newton::Miss`] means the function stopped decreasing (no root
    /// that way) or the iterate left `[lo, hi]`.
    fn newton_convex(&self, o: DVec3, dir: DVec3, mut u: f64, sense: f64, lo: f64, hi: f64) -> Newton {
        for i in 0..200 {
            let p = o + u * dir;
            let (g, grad) = self.gauge_and_gradient(p);
            let value = g - 1.0;
            if i == 0 && (value <= 0.0 || value.is_nan()) {
                return Newton::Inside;
            }
            if value <= 0.0 {
                return Newton::Root(u);
            }
            let slope = grad.dot(dir) * sense;
            // Not decreasing (or NaN): no root in this direction.
            if slope.is_nan() || slope >= 0.0 {
                return Newton::Miss;
            }
            let step = -value / slope * sense;
            u += step;
            if u < lo || u > hi {
                return Newton::Miss;
            }
            if step.abs() <= 1e-15 * (1.0 + u.abs()) {
                return Newton::Root(u);
            }
        }
        // Creeping towards a tangent point: a grazing miss.
        Newton::Miss
    }

    /// The root of `level` in `[u0, u1]`, where its values `g0` and `g1` differ in sign, to a
    /// bracket of width 1e-15 (relative): Newton's method from the secant point (the slope
    /// comes with the value at no extra cost), kept inside the shrinking bracket and replaced
    /// by bisection when a step leaves it or fails to halve.
    fn refine(&self, o: DVec3, dir: DVec3, mut u0: f64, mut u1: f64, mut g0: f64, mut g1: f64) -> f64 {
        let tolerance = |u0: f64, u1: f64| 1e-15 * (1.0 + u0.abs().max(u1.abs()));
        let secant = u0 - g0 * (u1 - u0) / (g1 - g0);
        let mut u = if secant > u0 && secant < u1 { secant } else { 0.5 * (u0 + u1) };
        let mut last_step = u1 - u0;
        for _ in 0..100 {
            if u1 - u0 <= tolerance(u0, u1) {
                break;
            }
            let (g, grad) = self.gauge_and_gradient(o + u * dir);
            let g = g - 1.0;
            if g == 0.0 {
                return u;
            }
            if (g < 0.0) == (g0 < 0.0) {
                u0 = u;
                g0 = g;
            } else {
                u1 = u;
                g1 = g;
            }
            let step = -g / grad.dot(dir);
            // A step below the tolerance is lengthened to half of it, to land just past the
            // root and close the bracket; if that fails (an infinite slope at a spike's tip),
            // the step is not allowed to repeat and bisection takes over.
            let half_tolerance = 0.5 * tolerance(u0, u1);
            let (next, next_limit) = if step.abs() < half_tolerance {
                (u + half_tolerance.copysign(step), 0.0)
            } else {
                (u + step, step.abs())
            };
            if next > u0 && next < u1 && step.abs() < 0.5 * last_step {
                last_step = next_limit;
                u = next;
            } else {
                last_step = u1 - u0;
                u = 0.5 * (u0 + u1);
            }
        }
        if g0.abs() <= g1.abs() { u0 } else { u1 }
    }

    /// Golden-section search for the extremum of `level` towards zero in `[u0, u2]`, given
    /// that the sample at `u1` is closer to zero than both ends and all three have the sign
    /// of `sign`. Returns a point where the sign flips, if the search finds one.
    ///
    /// Once the bracket is narrow next to how far the probes are from zero, it is checked
    /// with [`Self::sign_margin`]: when the sign cannot flip inside it, no later probe (they
    /// all lie inside) can find a flip, and the search stops early with the same answer.
    fn find_dip(&self, o: DVec3, dir: DVec3, mut lo: f64, mut hi: f64, sign: f64) -> Option<(f64, f64)> {
        const INV_PHI: f64 = 0.618_033_988_749_894_8;
        let mut x1 = hi - INV_PHI * (hi - lo);
        let mut x2 = lo + INV_PHI * (hi - lo);
        let mut f1 = sign * self.level(o, dir, x1);
        let mut f2 = sign * self.level(o, dir, x2);
        let mut next_check = hi - lo;
        for _ in 0..80 {
            if f1 <= 0.0 {
                return Some((x1, sign * f1));
            }
            if f2 <= 0.0 {
                return Some((x2, sign * f2));
            }
            let width = hi - lo;
            if width <= 1e-13 {
                break;
            }
            if width <= next_check && f1.min(f2) > width {
                if self.sign_margin(o, dir, lo, hi, sign) > 0.0 {
                    return None;
                }
                next_check = 0.25 * width;
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
        match self.newton_convex(o, dir, lo, 1.0, lo, hi) {
            Newton::Root(u) if accept(u) => return Some(u),
            Newton::Root(_) | Newton::Inside => {}
            // Outside, and the function never comes down to zero: a miss.
            Newton::Miss => return None,
        }
        // Inside at `lo` (or the entry was rejected): the exit, found from the far end.
        match self.newton_convex(o, dir, hi, -1.0, lo, hi) {
            Newton::Root(u) if accept(u) => Some(u),
            _ => None,
        }
    }

    /// A lower bound of `sign * (G - 1)` all along the ray between `u0` and `u1`, less room
    /// for rounding: when positive, G - 1 has the sign of `sign` on the whole segment. G
    /// increases with each |coordinate|, and along a segment each |coordinate| lies between
    /// its values at the ends (or zero where it changes sign), so one evaluation at the
    /// componentwise extremes bounds G on the whole segment.
    fn sign_margin(&self, o: DVec3, dir: DVec3, u0: f64, u1: f64, sign: f64) -> f64 {
        /// Room for the rounding of G at the extremes and at the points sampled later.
        const MARGIN: f64 = 1e-12;
        let (p0, p1) = (o + u0 * dir, o + u1 * dir);
        // Room for the rounding of the points computed along the segment (|dir| = 1).
        let slack = 1e-14 * (1.0 + o.abs().max_element() + u0.abs().max(u1.abs()));
        if sign > 0.0 {
            let least = |a: f64, b: f64| if a * b <= 0.0 { 0.0 } else { (a.abs().min(b.abs()) - slack).max(0.0) };
            self.gauge(DVec3::new(least(p0.x, p1.x), least(p0.y, p1.y), least(p0.z, p1.z))) - 1.0 - MARGIN
        } else {
            let most = |a: f64, b: f64| a.abs().max(b.abs()) + slack;
            1.0 - self.gauge(DVec3::new(most(p0.x, p1.x), most(p0.y, p1.y), most(p0.z, p1.z))) - MARGIN
        }
    }

    /// The first root in `[lo, hi]` accepted by `accept`, for any exponents, by sampling.
    ///
    /// The samples and the decisions taken on them (sign changes refined, sampled dips
    /// searched) are those of a plain scan, but a sample is only evaluated when some decision
    /// needs its value: stretches of the ray where [`Self::sign_margin`] shows that G - 1 keeps
    /// its sign hold no root, so no decision about them can find one.
    fn first_root_sampled(&self, o: DVec3, dir: DVec3, lo: f64, hi: f64, accept: impl Fn(f64) -> bool) -> Option<f64> {
        // Split points: the planes on which |x|, |y|, |z| change sign or order.
        let mut splits = [0.0; 11];
        let mut count = 0;
        splits[count] = lo;
        count += 1;
        for normal in SPLIT_PLANES {
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

        // The samples: the split points and even steps of at most SAMPLE_SPACING between them.
        let mut piece_steps = [0; 10];
        let mut total = 1;
        for (piece, steps) in splits.windows(2).zip(&mut piece_steps) {
            *steps = ((piece[1] - piece[0]) / SAMPLE_SPACING).ceil().max(1.0) as usize;
            total += *steps;
        }
        // At most 80 across the cube (a diagonal of 69.3 spacings, plus one per piece); longer
        // spans go to the heap.
        let mut stack = [Sample::default(); 80];
        let mut heap = Vec::new();
        let samples: &mut [Sample] = if total <= stack.len() {
            &mut stack[..total]
        } else {
            heap.resize(total, Sample::default());
            &mut heap
        };
        samples[0].u = lo;
        let mut k = 1;
        for (piece, &steps) in splits.windows(2).zip(&piece_steps) {
            let (s0, s1) = (piece[0], piece[1]);
            for j in 1..=steps {
                samples[k].u = if j == steps { s1 } else { s0 + (s1 - s0) * j as f64 / steps as f64 };
                k += 1;
            }
        }
        let mut scan = Scan { shape: self, o, dir, samples, decided: 0, chunk: 8, sign: 1.0 };

        if !scan.proven(0) && scan.value(0) == 0.0 && accept(lo) {
            return Some(lo);
        }
        for j in 1..total {
            // The window of the last three samples, j - 2, j - 1 and j.
            if !scan.proven(j - 1) {
                let (u1, u2) = (scan.samples[j - 1].u, scan.samples[j].u);
                let g2 = scan.value(j);
                if g2 == 0.0 {
                    if accept(u2) {
                        return Some(u2);
                    }
                    continue;
                }
                let g1 = scan.value(j - 1);
                if g1 != 0.0 && (g1 < 0.0) != (g2 < 0.0) {
                    let root = self.refine(o, dir, u1, u2, g1, g2);
                    if accept(root) {
                        return Some(root);
                    }
                    continue;
                }
            }
            // Without a sign change: a sampled extremum close to zero may hide a dip through
            // the surface, unless the whole window keeps its sign.
            if j < 2 || (scan.proven(j - 2) && scan.proven(j - 1)) {
                continue;
            }
            let (u0, g0) = (scan.samples[j - 2].u, scan.value(j - 2));
            let g1 = scan.value(j - 1);
            let (u2, g2) = (scan.samples[j].u, scan.value(j));
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
        None
    }
}

/// One sample of [`Superellipsoid::first_root_sampled`].
#[derive(Clone, Copy, Default)]
struct Sample {
    /// Distance along the ray.
    u: f64,
    /// G - 1 there, once evaluated.
    value: Option<f64>,
    /// Whether G - 1 provably keeps its sign from this sample to the next, once decided.
    proven: bool,
}

/// The lazily evaluated samples of [`Superellipsoid::first_root_sampled`].
struct Scan<'a> {
    shape: &'a Superellipsoid,
    o: DVec3,
    dir: DVec3,
    samples: &'a mut [Sample],
    /// The segments (from a sample to the next) before this one are decided.
    decided: usize,
    /// How many segments the next attempt at a proof covers when nothing better is known.
    chunk: usize,
    /// The sign of G - 1 that the next attempt tries to prove.
    sign: f64,
}

impl Scan<'_> {
    /// The longest stretch one proof attempts, in segments.
    const MAX_CHUNK: usize = 32;

    /// G - 1 at sample `j`, evaluated on first use.
    fn value(&mut self, j: usize) -> f64 {
        let sample = &mut self.samples[j];
        *sample.value.get_or_insert_with(|| self.shape.level(self.o, self.dir, sample.u))
    }

    /// Whether G - 1 keeps its sign on segment `i`. Segments are decided in order, several
    /// at a time: which ones are proven only affects how many samples are evaluated, never
    /// the answer.
    #[inline]
    fn proven(&mut self, i: usize) -> bool {
        while self.decided <= i {
            self.decide();
        }
        self.samples[i].proven
    }

    /// Decides the next segment or stretch of segments.
    fn decide(&mut self) {
        let d = self.decided;
        let last = self.samples.len() - 1;
        let mut chunk = self.chunk;
        if let Some(g) = self.samples[d].value {
            // G - 1 changes about as fast as the distance along the ray: a proof can only
            // hold over a stretch shorter than its distance from zero.
            self.sign = g.signum();
            let reach = self.samples[d].u + 0.5 * g.abs();
            chunk = (1..=Self::MAX_CHUNK.min(last - d)).take_while(|&c| self.samples[d + c].u <= reach).count();
            if chunk == 0 {
                self.decided += 1;
                self.chunk = 1;
                return;
            }
        }
        loop {
            let end = (d + chunk).min(last);
            let (u0, u1) = (self.samples[d].u, self.samples[end].u);
            let margin = self.shape.sign_margin(self.o, self.dir, u0, u1, self.sign);
            if margin > 0.0 {
                for sample in &mut self.samples[d..end] {
                    sample.proven = true;
                }
                self.decided = end;
                // A stretch twice as long next time only if the bound clears zero by more than
                // twice this one's length (as for `reach` above).
                let grow = if margin > 2.0 * (u1 - u0) { 2 } else { 1 };
                self.chunk = (grow * (end - d)).min(Self::MAX_CHUNK);
                return;
            }
            if end - d <= 1 {
                self.decided += 1;
                self.chunk = 1;
                return;
            }
            chunk = ((end - d) / 4).max(1);
        }
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

    fn inside(&self, point: DVec3) -> bool {
        // POV-Ray's test, with its skin counted inside.
        self.gauge(point) - 1.0 < prism_api::pov::EPSILON
    }

    fn surface(&self, ray: &Ray, hit: &Hit) -> Surface {
        let mut surface = self.surface_geometry(ray, hit);
        // Longitude around y and latitude from the south pole, as on the sphere (to which
        // the shape reduces for e = n = 1).
        let d = surface.point.normalize_or(DVec3::Y);
        let u = 0.5 + d.z.atan2(-d.x) / TAU;
        let v = 0.5 + d.y.clamp(-1.0, 1.0).asin() / PI;
        surface.uv = DVec2::new(u.rem_euclid(1.0), v);
        surface
    }

    fn surface_geometry(&self, ray: &Ray, hit: &Hit) -> Surface {
        let HitPoint { point, normal, .. } = self.hit_point(ray, hit);
        Surface::new(point, normal, DVec2::ZERO).with_dpdu(math::longitude_dpdu(point, normal))
    }

    fn hit_point(&self, ray: &Ray, hit: &Hit) -> HitPoint {
        let p = ray.at(hit.t);
        // G is homogeneous: p / G(p) lies exactly on the surface, along the radial direction.
        let (g, grad) = self.gauge_and_gradient(p);
        let point = if g > 0.0 && g.is_finite() { p / g } else { p };
        HitPoint::new(point, Self::normal_from_gradient(grad, point))
    }

    /// No: the superellipsoid's area has no closed form, and uniform area sampling would
    /// need a tabulated parameterisation (its uv is far from area-preserving for small
    /// exponents), so it cannot be an area light.
    fn can_emit(&self) -> bool {
        false
    }

    fn to_pov(&self) -> Option<String> {
        // Even in z: the left-handed mapping (x, y, z) -> (x, y, -z) changes nothing.
        Some(format!("superellipsoid {{ <{}, {}> }}", pov::number(self.e), pov::number(self.n)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// POV-Ray's `Superellipsoid::Inside`: a skin of 1e-10 (of the gauge) outside is inside.
    #[test]
    fn the_skin_outside_is_inside() {
        let s = Superellipsoid::new(0.5, 0.5);
        assert!(s.inside(DVec3::X * (1.0 + 5e-11)) && !s.inside(DVec3::X * (1.0 + 2e-10)));
    }
    use prism_api::contract::{TestRng, check_dpdu, check_shape};

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
        check_dpdu(&Superellipsoid::new(0.5, 2.5));
        assert!(!Superellipsoid::new(1.0, 1.0).can_emit());
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

    #[test]
    fn fast_powers_stay_within_a_few_epsilons_of_powf() {
        let mut rng = TestRng::new(3);
        for eighths in 1..=80 {
            let k = eighths as f64 / 8.0;
            let power = Power::new(k);
            assert!(matches!(power, Power::Eighths { .. }), "{k}");
            for i in 0..20_000 {
                // Ratios in [0, 1] (powers) and sums in [1, 2] (roots).
                let x = if i % 2 == 0 { rng.uniform() } else { 1.0 + rng.uniform() };
                let exact = x.powf(k);
                let error = (power.of(x) - exact).abs();
                assert!(error <= 5.0 * f64::EPSILON * exact || exact < 1e-290, "{x}^{k}: {} vs {exact}", power.of(x));
            }
            assert_eq!(power.of(0.0), 0.0);
            assert_eq!(power.of(1.0), 1.0);
        }
        for k in [0.8, 2.0 / 3.0, 1.0 / 3.0, 10.125, 20.0, 0.1] {
            assert_eq!(Power::new(k), Power::General(k));
        }
    }

    /// The gradient as it was computed before the gauge and its gradient were merged: from
    /// separate norms and one `powf` per partial derivative.
    fn reference_gradient(s: &Superellipsoid, p: DVec3) -> DVec3 {
        let norm = |u: f64, v: f64, k: f64| {
            let m = u.max(v);
            if m == 0.0 { 0.0 } else { m * (1.0 + (u.min(v) / m).powf(k)).powf(1.0 / k) }
        };
        let partial = |ratio: f64, k: f64| if k == 1.0 { 1.0 } else { ratio.powf(k - 1.0) };
        let (a, b) = (2.0 / s.e, 2.0 / s.n);
        let (ax, ay, az) = (p.x.abs(), p.y.abs(), p.z.abs());
        let u = norm(ax, ay, a);
        let g = norm(u, az, b);
        if g == 0.0 {
            return DVec3::ZERO;
        }
        let du = partial(u / g, b);
        let (dx, dy) = if u > 0.0 { (du * partial(ax / u, a), du * partial(ay / u, a)) } else { (0.0, 0.0) };
        let dz = partial(az / g, b);
        DVec3::new(1f64.copysign(p.x) * dx, 1f64.copysign(p.y) * dy, 1f64.copysign(p.z) * dz)
    }

    #[test]
    fn gradient_matches_separate_partials_even_at_tips_and_creases() {
        let mut rng = TestRng::new(17);
        let special = [
            DVec3::ZERO,
            DVec3::X,
            -DVec3::Y,
            DVec3::Z,
            DVec3::new(0.5, 0.0, 0.3),
            DVec3::new(0.0, -0.4, 0.3),
            DVec3::new(0.3, 0.3, 0.0),
            DVec3::new(-0.3, 0.3, 0.3),
            DVec3::new(0.7, 1e-200, 0.0),
        ];
        for (e, n) in
            [(1.0, 1.0), (0.25, 0.25), (2.0, 2.0), (2.5, 1.5), (4.0, 4.0), (0.3, 3.0), (2.0, 0.7), (10.0, 0.1)]
        {
            let s = Superellipsoid::new(e, n);
            let random = (0..2000).map(|_| rng.point_in(&Aabb::from_corners(DVec3::splat(-1.5), DVec3::splat(1.5))));
            for p in special.into_iter().chain(random) {
                let (g, grad) = s.gauge_and_gradient(p);
                assert!((g - s.gauge(p)).abs() <= 1e-15 * g, "<{e}, {n}> at {p}");
                let expected = reference_gradient(&s, p);
                for axis in 0..3 {
                    let (got, want) = (grad[axis], expected[axis]);
                    // Partials below 1e-100 may differ by underflow (the 1e-200 coordinate).
                    let close = if want.is_infinite() || want == 0.0 {
                        got == want
                    } else {
                        (got - want).abs() <= 1e-12 * want.abs().max(1e-100)
                    };
                    assert!(close, "<{e}, {n}> at {p}: {grad} vs {expected}");
                }
            }
        }
    }

    /// The golden-section search without the early exit on a proven bracket.
    fn reference_find_dip(
        s: &Superellipsoid,
        o: DVec3,
        dir: DVec3,
        mut lo: f64,
        mut hi: f64,
        sign: f64,
    ) -> Option<(f64, f64)> {
        const INV_PHI: f64 = 0.618_033_988_749_894_8;
        let mut x1 = hi - INV_PHI * (hi - lo);
        let mut x2 = lo + INV_PHI * (hi - lo);
        let mut f1 = sign * s.level(o, dir, x1);
        let mut f2 = sign * s.level(o, dir, x2);
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
                (hi, x2, f2) = (x2, x1, f1);
                x1 = hi - INV_PHI * (hi - lo);
                f1 = sign * s.level(o, dir, x1);
            } else {
                (lo, x1, f1) = (x1, x2, f2);
                x2 = lo + INV_PHI * (hi - lo);
                f2 = sign * s.level(o, dir, x2);
            }
        }
        None
    }

    #[test]
    fn dip_search_stops_early_only_where_it_would_find_nothing() {
        let mut rng = TestRng::new(29);
        let cube = Aabb::from_corners(DVec3::splat(-1.0), DVec3::splat(1.0));
        for (e, n) in [(2.5, 1.5), (4.0, 4.0), (3.0, 0.3), (0.5, 2.5), (1.0, 1.0)] {
            let s = Superellipsoid::new(e, n);
            let mut found = 0;
            for _ in 0..5000 {
                let o = rng.point_in(&cube);
                let dir = rng.unit_vector();
                let lo = rng.range(0.0, 1.0);
                let hi = lo + rng.range(0.01, 0.5);
                let sign = s.level(o, dir, lo).signum();
                let dip = s.find_dip(o, dir, lo, hi, sign);
                assert_eq!(dip, reference_find_dip(&s, o, dir, lo, hi, sign), "<{e}, {n}> from {o} along {dir}");
                found += usize::from(dip.is_some());
            }
            assert!(found > 50, "<{e}, {n}>: {found}");
        }
    }

    /// The scan of `first_root_sampled` with every sample evaluated, in order.
    fn plain_scan(
        s: &Superellipsoid,
        o: DVec3,
        dir: DVec3,
        lo: f64,
        hi: f64,
        accept: impl Fn(f64) -> bool,
    ) -> Option<f64> {
        let mut splits = vec![lo, hi];
        splits.extend(SPLIT_PLANES.iter().map(|n| -n.dot(o) / n.dot(dir)).filter(|&u| u > lo && u < hi));
        splits.sort_by(f64::total_cmp);
        let mut window = [(lo, s.level(o, dir, lo)); 3];
        let mut filled = 1;
        if window[0].1 == 0.0 && accept(lo) {
            return Some(lo);
        }
        for piece in splits.windows(2) {
            let (s0, s1) = (piece[0], piece[1]);
            let steps = ((s1 - s0) / SAMPLE_SPACING).ceil().max(1.0) as usize;
            for j in 1..=steps {
                let u = if j == steps { s1 } else { s0 + (s1 - s0) * j as f64 / steps as f64 };
                window = [window[1], window[2], (u, s.level(o, dir, u))];
                filled += 1;
                let [(u0, g0), (u1, g1), (u2, g2)] = window;
                if g2 == 0.0 {
                    if accept(u2) {
                        return Some(u2);
                    }
                    continue;
                }
                if g1 != 0.0 && (g1 < 0.0) != (g2 < 0.0) {
                    let root = s.refine(o, dir, u1, u2, g1, g2);
                    if accept(root) {
                        return Some(root);
                    }
                    continue;
                }
                let sign = g1.signum();
                let (m0, m1, m2) = (sign * g0, sign * g1, sign * g2);
                if filled >= 3
                    && m0 > 0.0
                    && m1 > 0.0
                    && m1 < m0
                    && m1 < m2
                    && m1 < 2.0 * (m0 - m1).max(m2 - m1)
                    && let Some((um, gm)) = reference_find_dip(s, o, dir, u0, u2, sign)
                {
                    for root in [s.refine(o, dir, u0, um, g0, gm), s.refine(o, dir, um, u2, gm, g2)] {
                        if accept(root) {
                            return Some(root);
                        }
                    }
                }
            }
        }
        None
    }

    #[test]
    fn lazy_scan_finds_exactly_what_the_plain_scan_finds() {
        let mut rng = TestRng::new(23);
        let cube = Aabb::from_corners(DVec3::splat(-1.0), DVec3::splat(1.0));
        for (e, n) in [(2.5, 1.5), (4.0, 4.0), (0.5, 2.5), (2.5, 3.0), (10.0, 10.0), (3.0, 0.3), (1.0, 1.0), (0.3, 0.7)]
        {
            let s = Superellipsoid::new(e, n);
            let (mut hits, mut rejected) = (0, 0);
            for i in 0..4000 {
                // From outside, from inside the cube, and along the planes the scan splits at.
                let origin = match i % 4 {
                    0 | 1 => rng.unit_vector() * 3.0,
                    2 => rng.point_in(&cube),
                    _ => DVec3::new(rng.range(-3.0, 3.0), 0.0, rng.range(-3.0, 3.0)),
                };
                let mut target = rng.point_in(&cube);
                if i % 4 == 3 {
                    target.y = 0.0;
                }
                let ray = Ray::new(origin, target - origin);
                let Some((t0, t1)) = cube.ray_interval(&ray, 0.0, f64::INFINITY) else { continue };
                let len = ray.direction.length();
                let (o, dir, span) = (ray.at(t0), ray.direction / len, (t1 - t0) * len);
                // Half the rays reject roots before a random point, as after a first hit.
                let u_min = if i % 2 == 0 { 0.0 } else { rng.range(0.0, span) };
                let accept = |u: f64| u > u_min;
                let lazy = s.first_root_sampled(o, dir, 0.0, span, accept);
                assert_eq!(lazy, plain_scan(&s, o, dir, 0.0, span, accept), "<{e}, {n}> {ray:?} after {u_min}");
                if let Some(u) = lazy {
                    hits += 1;
                    rejected += usize::from(u_min > 0.0);
                    // On the surface, unless at a coordinate plane where exponents below 1 give G
                    // a cusp, so steep that the dip through the surface can be thinner than
                    // rounding: there, a sign change within the refinement's tolerance.
                    let w = 2e-15 * (1.0 + u);
                    let inside = [u - w, u, u + w].map(|v| s.level(o, dir, v) < 0.0);
                    let crossing = inside.contains(&true) && inside.contains(&false);
                    let cusp = (o + u * dir).abs().min_element() < 1e-9;
                    assert!(s.level(o, dir, u).abs() < 1e-9 || crossing || cusp, "<{e}, {n}> {ray:?}");
                }
            }
            assert!(hits > 300 && rejected > 100, "<{e}, {n}>: {hits} hits, {rejected} past a point");
        }
    }
}
