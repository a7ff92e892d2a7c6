//! Small numerical helpers shared by shapes.

use std::f64::consts::TAU;
use std::ops::ControlFlow;

use glam::{DMat3, DVec3};

/// Real roots of `a t^2 + b t + c = 0` in ascending order, computed without catastrophic
/// cancellation (the citardauq form for the smaller-magnitude root).
pub fn solve_quadratic(a: f64, b: f64, c: f64) -> Option<(f64, f64)> {
    if a == 0.0 {
        if b == 0.0 {
            return None;
        }
        let t = -c / b;
        return Some((t, t));
    }
    let discriminant = b * b - 4.0 * a * c;
    if discriminant < 0.0 || !discriminant.is_finite() {
        return None;
    }
    let root = discriminant.sqrt();
    let q = -0.5 * (b + b.signum() * root);
    let (t0, t1) = if q == 0.0 { (0.0, 0.0) } else { (q / a, c / q) };
    Some(if t0 <= t1 { (t0, t1) } else { (t1, t0) })
}

/// A unit vector perpendicular to the unit vector `n`, continuous except near one pole
/// (Duff et al. 2017, "Building an orthonormal basis, revisited").
pub fn orthonormal_basis(n: DVec3) -> (DVec3, DVec3) {
    let sign = 1.0_f64.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    (DVec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x), DVec3::new(b, sign + n.y * n.y * a, -n.y))
}

/// A unit tangent perpendicular to the unit vector `n`: the first vector of
/// [`orthonormal_basis`]. [`crate::Surface::new`] gives it as `dpdu` where a shape has no
/// better one.
pub fn tangent(n: DVec3) -> DVec3 {
    orthonormal_basis(n).0
}

/// ∂p/∂u of the longitude `u = 0.5 + atan2(d.z, -d.x) / TAU` of the direction `d` of a
/// surface point from a centre, the latitude of `d` held fixed, as the sphere, the
/// superellipsoid and the blob map their uv: `offset` is the point minus that centre and
/// `normal` the unit normal there. Turning `d` about the y axis moves the point along
/// `w = TAU (offset.z, 0, -offset.x)` plus whatever along `d` keeps it on the surface:
/// `w - offset (normal · w) / (normal · offset)`. Where that degenerates (on the y axis
/// through the centre, or where `d` is tangent to the surface) it is [`tangent`]`(normal)`.
pub fn longitude_dpdu(offset: DVec3, normal: DVec3) -> DVec3 {
    let w = TAU * DVec3::new(offset.z, 0.0, -offset.x);
    let along = normal.dot(offset);
    let size = offset.length();
    if w.length() <= 1e-9 * size || along.abs() <= 1e-9 * size {
        return tangent(normal);
    }
    let dpdu = w - offset * (normal.dot(w) / along);
    if dpdu.is_finite() { dpdu } else { tangent(normal) }
}

/// A density with respect to area at `point` (unit `normal`) as a density with respect to
/// solid angle seen from `reference`: `pdf_area * distance^2 / |cos|`, where `cos` is between
/// the normal and the direction to the reference. 0 when that is not finite (the point at
/// the reference, or seen exactly edge-on).
pub fn area_to_solid_angle(pdf_area: f64, reference: DVec3, point: DVec3, normal: DVec3) -> f64 {
    let to_point = point - reference;
    let distance_squared = to_point.length_squared();
    let cos = normal.dot(to_point).abs() / distance_squared.sqrt();
    let pdf = pdf_area * distance_squared / cos;
    if pdf.is_finite() { pdf } else { 0.0 }
}

/// The factor by which the linear map `matrix3` (invertible) scales an area element whose
/// normal is `object_normal` (any non-zero length): `|det M| * |M^-T n| / |n|` (Nanson's
/// formula). A shape's area density in object space divided by it is the density in world
/// space: `pdf_world = pdf_area / area_scale(M, n)` for the object-to-world matrix `M`.
pub fn area_scale(matrix3: DMat3, object_normal: DVec3) -> f64 {
    let det = matrix3.determinant();
    let transformed = matrix3.inverse().transpose() * object_normal;
    det.abs() * transformed.length() / object_normal.length()
}

/// The factor by which the linear map `matrix3` (invertible) scales a solid-angle element
/// around `object_direction` (any non-zero length) when directions are mapped by
/// `d -> M d / |M d|`: `|det M| / |M d̂|^3` for the unit `d̂`. It converts the object-space
/// solid-angle densities of [`crate::Shape::sample_toward`] and
/// [`crate::Shape::pdf_toward`] to world space at the transformed reference point:
/// `pdf_world = pdf_object / solid_angle_scale(M, d)`. Unlike a conversion through one
/// surface point it holds for the sum over all crossings of a direction too, since it
/// depends on the direction alone.
pub fn solid_angle_scale(matrix3: DMat3, object_direction: DVec3) -> f64 {
    let unit = object_direction / object_direction.length();
    matrix3.determinant().abs() / (matrix3 * unit).length().powi(3)
}

/// `v` read one component at a time. A vector its caller has only just stored (a ray built
/// for this very query) may sit in the store buffer as an (x, y) pair and a z; a load of the
/// (y, z) pair, which the compiler likes to make for dot products, spans both stores and waits
/// for them to reach the cache (a store-forwarding stall, measured at half the time of an
/// infinite plane's test). Single loads forward. `black_box` only keeps the compiler from
/// pairing the loads again; the value is `*v` exactly.
#[inline(always)]
pub fn load_components(v: &DVec3) -> DVec3 {
    DVec3::new(v.x, std::hint::black_box(v.y), v.z)
}

/// `x % y` (C's `fmod`: the exact remainder of `x` by `y`, with the sign of `x`), without the
/// library call where it can: for a quotient below 2^52 and a divisor of ordinary size, the
/// truncated quotient's product is made exact by Dekker's product (Veltkamp's split), so the
/// remainder comes out exact, bit for bit what `%` gives. Patterns wrap every value this way.
#[inline]
pub fn fmod(x: f64, y: f64) -> f64 {
    const SPLIT: f64 = 134_217_729.0; // 2^27 + 1
    const QUOTIENT_LIMIT: f64 = 4_503_599_627_370_496.0; // 2^52
    let (ax, ay) = (x.abs(), y.abs());
    // Keeps the split from overflowing and its low parts from underflowing; NaN and the
    // infinities fail the comparisons too.
    if !((1e-250..1e250).contains(&ay) && ax < ay * QUOTIENT_LIMIT) {
        return x % y;
    }
    if ax < ay {
        return x;
    }
    // x / y rounds up to the next whole number at most: then the remainder below is in
    // [-|y|, 0) and one |y| mends it (both sums exact: the results are representable).
    let quotient = (ax / ay).trunc();
    let product = quotient * ay;
    let split = |a: f64| {
        let c = SPLIT * a;
        let high = c - (c - a);
        (high, a - high)
    };
    let ((qh, ql), (yh, yl)) = (split(quotient), split(ay));
    let product_error = ((qh * yh - product) + qh * yl + ql * yh) + ql * yl;
    // |x| - product is exact (Sterbenz: they are within a factor of two), and the true
    // remainder is representable, so one rounding of its last step is exact.
    let mut remainder = (ax - product) - product_error;
    if remainder < 0.0 {
        remainder += ay;
    }
    remainder.copysign(x)
}

/// The largest polynomial degree [`polynomial_roots`] accepts.
pub const MAX_POLYNOMIAL_DEGREE: usize = 8;

/// The value of the polynomial `sum(coefficients[i] * t^i)` at `t` (Horner's scheme).
/// Coefficients are in ascending order: `coefficients[0]` is the constant term.
pub fn eval_polynomial(coefficients: &[f64], t: f64) -> f64 {
    coefficients.iter().rev().fold(0.0, |acc, &c| acc * t + c)
}

/// The value, the first derivative and half the second derivative of the polynomial at `t`
/// (ascending coefficients), from one Horner pass.
fn eval_polynomial_with_derivatives(coefficients: &[f64], t: f64) -> (f64, f64, f64) {
    let (mut value, mut derivative, mut half_second) = (0.0, 0.0, 0.0);
    for &c in coefficients.iter().rev() {
        half_second = half_second * t + derivative;
        derivative = derivative * t + value;
        value = value * t + c;
    }
    (value, derivative, half_second)
}

/// Up to [`MAX_POLYNOMIAL_DEGREE`] real roots, in ascending order.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PolynomialRoots {
    len: usize,
    values: [f64; MAX_POLYNOMIAL_DEGREE],
}

impl PolynomialRoots {
    /// The roots, ascending.
    pub fn as_slice(&self) -> &[f64] {
        &self.values[..self.len]
    }

    /// The number of roots.
    pub fn len(&self) -> usize {
        self.len
    }

    /// True when there is no root.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    fn push(&mut self, t: f64) {
        // Roots arrive in ascending order; a root shared by two segments is kept once.
        if self.len > 0 && self.values[self.len - 1] >= t {
            return;
        }
        if self.len < MAX_POLYNOMIAL_DEGREE {
            self.values[self.len] = t;
            self.len += 1;
        }
    }
}

/// The real roots in `[lo, hi]` of the polynomial `sum(coefficients[i] * t^i)` (ascending
/// coefficients, degree at most [`MAX_POLYNOMIAL_DEGREE`]), in ascending order.
///
/// Robust by construction rather than by formula (no Ferrari/Cardano): the roots of the
/// derivative (found recursively) split `[lo, hi]` into pieces on which the polynomial is
/// monotonic, so each piece holds at most one root, present exactly when the values at the
/// piece's ends differ in sign; it is then found by Halley's method safeguarded with
/// bisection, to full double precision. Nothing divides by the leading coefficient, so a
/// vanishing leading term only moves critical points out of the interval. A root of even
/// multiplicity (a tangent) is reported only when the polynomial evaluates to exactly 0 at a
/// critical point; rounding decides grazing cases, as it must. Keep the interval and the
/// coefficients well scaled (shift the variable so that the interval starts near 0) for the
/// best accuracy.
///
/// # Panics
///
/// When the degree exceeds [`MAX_POLYNOMIAL_DEGREE`].
pub fn polynomial_roots(coefficients: &[f64], lo: f64, hi: f64) -> PolynomialRoots {
    let mut roots = PolynomialRoots::default();
    let _ = visit_polynomial_roots(coefficients, lo, hi, &mut |t| {
        roots.push(t);
        ControlFlow::Continue(())
    });
    roots
}

/// [`polynomial_roots`] one root at a time: `visit` gets each root in ascending order until
/// it breaks, and no root beyond the one it breaks at is searched for (nor are the
/// derivatives' roots beyond it). The nearest hit of a ray wants the first root past its
/// start, not all of them. The roots visited are exactly those [`polynomial_roots`] lists.
///
/// # Panics
///
/// When the degree exceeds [`MAX_POLYNOMIAL_DEGREE`].
pub fn visit_polynomial_roots(
    coefficients: &[f64],
    lo: f64,
    hi: f64,
    visit: &mut dyn FnMut(f64) -> ControlFlow<()>,
) -> ControlFlow<()> {
    let degree = coefficients.iter().rposition(|&c| c != 0.0).unwrap_or(0);
    assert!(
        degree <= MAX_POLYNOMIAL_DEGREE,
        "polynomial_roots supports degree {MAX_POLYNOMIAL_DEGREE} at most, got {degree}"
    );
    // Also rejects NaN bounds.
    let ordered = lo <= hi;
    if !ordered || !coefficients.iter().all(|c| c.is_finite()) {
        return ControlFlow::Continue(());
    }
    let coefficients = &coefficients[..=degree];
    // Roots arrive in ascending order; a root shared by two pieces is visited once, and no
    // more than the degree allows.
    let (mut last, mut count) = (f64::NEG_INFINITY, 0);
    let mut emit = |t: f64| {
        if (count > 0 && last >= t) || count == MAX_POLYNOMIAL_DEGREE {
            return ControlFlow::Continue(());
        }
        (last, count) = (t, count + 1);
        visit(t)
    };
    match degree {
        0 => ControlFlow::Continue(()),
        1 => {
            let t = -coefficients[0] / coefficients[1];
            if t >= lo && t <= hi { emit(t) } else { ControlFlow::Continue(()) }
        }
        2 if let Some((r0, r1)) = distinct_quadratic_roots(coefficients) => {
            for r in [r0, r1] {
                if r >= lo && r <= hi {
                    emit(r)?;
                }
            }
            ControlFlow::Continue(())
        }
        _ => {
            let mut derivative = [0.0; MAX_POLYNOMIAL_DEGREE];
            for i in 1..=degree {
                derivative[i - 1] = coefficients[i] * i as f64;
            }
            let tolerance = 4.0 * f64::EPSILON * lo.abs().max(hi.abs());
            // The piece from the last critical point (x0, with value y0) to the next.
            let (mut x0, mut y0) = (lo, eval_polynomial(coefficients, lo));
            let mut piece = |x1: f64| {
                if x1 <= x0 && x1 != hi {
                    return ControlFlow::Continue(());
                }
                let y1 = eval_polynomial(coefficients, x1);
                let flow = if y0 == 0.0 {
                    emit(x0)
                } else if y1 != 0.0 && (y0 < 0.0) != (y1 < 0.0) {
                    emit(refine_root(coefficients, x0, x1, y0, tolerance))
                } else {
                    ControlFlow::Continue(())
                };
                (x0, y0) = (x1, y1);
                flow
            };
            visit_polynomial_roots(&derivative[..degree], lo, hi, &mut piece)?;
            piece(hi)?;
            if y0 == 0.0 { emit(x0) } else { ControlFlow::Continue(()) }
        }
    }
}

/// The two distinct real roots of the quadratic `c + b t + a t^2` (ascending coefficients,
/// `a` != 0), ascending, from the formula in its stable form; `None` when the discriminant
/// is not positive (a double root or none, left to the search, which reports a double root
/// only where the quadratic is exactly 0) or overflows.
fn distinct_quadratic_roots(coefficients: &[f64]) -> Option<(f64, f64)> {
    let [c, b, a] = *coefficients else { return None };
    let discriminant = b * b - 4.0 * a * c;
    if !(discriminant > 0.0 && discriminant.is_finite()) {
        return None;
    }
    // |q| >= sqrt(discriminant) / 2 > 0: no division by zero, and no cancellation.
    let q = -0.5 * (b + b.signum() * discriminant.sqrt());
    let (r0, r1) = (q / a, c / q);
    Some(if r0 <= r1 { (r0, r1) } else { (r1, r0) })
}

/// The root of a polynomial that is monotonic on `[a, b]` and changes sign there
/// (`ya` = p(a) != 0): Halley steps kept inside a shrinking bracket, bisection otherwise.
fn refine_root(coefficients: &[f64], mut a: f64, mut b: f64, ya: f64, tolerance: f64) -> f64 {
    let a_negative = ya < 0.0;
    let mut x = 0.5 * (a + b);
    for _ in 0..200 {
        let (y, dy, half_d2) = eval_polynomial_with_derivatives(coefficients, x);
        if y == 0.0 {
            return x;
        }
        if (y < 0.0) == a_negative {
            a = x;
        } else {
            b = x;
        }
        // Halley's step (cubic convergence: a third fewer steps than Newton's on the torus's
        // quartics and their derivatives, each as long, the derivatives being parallel chains).
        let halley = x - y * dy / (dy * dy - y * half_d2);
        let next = if halley > a && halley < b { halley } else { 0.5 * (a + b) };
        let step = (next - x).abs();
        x = next;
        if step <= tolerance.max(4.0 * f64::EPSILON * x.abs()) || b - a <= tolerance {
            break;
        }
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The inline remainder is `%` bit for bit: random magnitudes and signs, whole numbers,
    /// quotients at and beyond the fast path's limit, near-whole quotients, and the specials.
    #[test]
    fn fmod_is_the_remainder_operator_bit_for_bit() {
        let mut rng = crate::contract::TestRng::new(17);
        let check = |x: f64, y: f64| {
            let (fast, library) = (fmod(x, y), x % y);
            assert!(
                fast.to_bits() == library.to_bits() || (fast.is_nan() && library.is_nan()),
                "fmod({x:e}, {y:e}) = {fast:e}, % gives {library:e}"
            );
        };
        for _ in 0..200_000 {
            let x = rng.range(-1.0, 1.0) * 10f64.powf(rng.range(-8.0, 17.0));
            let y = rng.range(-1.0, 1.0) * 10f64.powf(rng.range(-6.0, 6.0));
            check(x, y);
            // Quotients just beside whole numbers, where x / y rounds onto one.
            let whole = (rng.range(1.0, 1e6)).round();
            for nudge in [-2.0, -1.0, 0.0, 1.0, 2.0] {
                let near = whole * y + nudge * f64::EPSILON * (whole * y).abs();
                check(near, y);
                check(-near, y);
            }
            check(rng.range(-5e3, 5e3).round(), rng.range(1.0, 300.0).round());
            check(x, 1.00001);
            check(x, 1.0);
        }
        let limit = 4_503_599_627_370_496.0;
        for (x, y) in [
            (limit, 1.0),
            (limit * 3.0, 3.0),
            (limit * 0.75, 0.75),
            (1e300, 1.00001),
            (-0.0, 1.0),
            (0.0, -2.0),
            (5.0, 0.0),
            (f64::INFINITY, 2.0),
            (2.0, f64::INFINITY),
            (f64::NAN, 1.0),
            (1.0, f64::NAN),
            (1e-300, 3e-300),
            (7e-251, 1e-251),
            (1e250, 3e249),
            (f64::MIN_POSITIVE, 1.0),
            (-6.0, 3.0),
            (6.0, -3.0),
        ] {
            check(x, y);
        }
    }

    #[test]
    fn quadratic_roots_are_accurate_when_b_dominates() {
        let (t0, t1) = solve_quadratic(1.0, -1e8, 1.0).unwrap();
        assert!((t0 - 1e-8).abs() < 1e-20);
        assert!((t1 - 1e8).abs() < 1e-6);
    }

    #[test]
    fn quadratic_without_real_roots() {
        assert_eq!(solve_quadratic(1.0, 0.0, 1.0), None);
    }

    #[test]
    fn basis_is_orthonormal() {
        for n in [DVec3::X, DVec3::Y, DVec3::Z, -DVec3::Z, DVec3::new(1.0, 2.0, -3.0).normalize()] {
            let (t, b) = orthonormal_basis(n);
            assert!((t.length() - 1.0).abs() < 1e-12 && (b.length() - 1.0).abs() < 1e-12);
            assert!(t.dot(n).abs() < 1e-12 && b.dot(n).abs() < 1e-12 && t.dot(b).abs() < 1e-12);
        }
    }
    /// A few invertible maps: a rotation with non-uniform scale, a shear, a reflection.
    fn maps() -> [DMat3; 3] {
        [
            DMat3::from_quat(glam::DQuat::from_axis_angle(DVec3::new(1.0, 2.0, 3.0).normalize(), 0.7))
                * DMat3::from_diagonal(DVec3::new(0.5, 2.0, 3.0)),
            DMat3::from_cols(DVec3::new(1.0, 0.3, 0.0), DVec3::new(-0.4, 1.5, 0.2), DVec3::new(0.1, 0.0, 0.8)),
            DMat3::from_diagonal(DVec3::new(-1.0, 2.0, 0.25)),
        ]
    }

    #[test]
    fn area_scale_matches_a_mapped_parallelogram() {
        for m in maps() {
            for n in [DVec3::X, DVec3::new(0.3, -0.5, 2.0), DVec3::new(-1.0, 1.0, 1e-3)] {
                // A small parallelogram around a point of the plane with normal n, mapped.
                let (a, b) = orthonormal_basis(n.normalize());
                let (a, b) = (a * 1e-3, (a * 0.4 + b) * 2e-3);
                let p = DVec3::new(0.2, -1.0, 0.5);
                let corners = [p, p + a, p + b].map(|c| m * c);
                let mapped = (corners[1] - corners[0]).cross(corners[2] - corners[0]).length();
                let scale = mapped / a.cross(b).length();
                let expected = area_scale(m, n);
                assert!((scale - expected).abs() < 1e-12 * expected, "{scale} vs {expected} for {n}");
                assert!((area_scale(m, n * 7.0) - expected).abs() < 1e-12 * expected, "any length of n");
            }
        }
        assert!((area_scale(DMat3::from_diagonal(DVec3::splat(2.0)), DVec3::Y) - 4.0).abs() < 1e-15);
    }

    #[test]
    fn solid_angle_scale_matches_a_mapped_cone_of_directions() {
        // The solid angle of the small spherical triangle spanned by three unit vectors
        // (Van Oosterom and Strackee), before and after mapping them.
        let solid_angle = |[a, b, c]: [DVec3; 3]| {
            let (a, b, c) = (a.normalize(), b.normalize(), c.normalize());
            2.0 * a.dot(b.cross(c)).abs().atan2(1.0 + a.dot(b) + b.dot(c) + c.dot(a))
        };
        for m in maps() {
            for d in [DVec3::Z, DVec3::new(1.0, -2.0, 0.5), DVec3::new(-0.1, 0.2, -3.0)] {
                let d = d.normalize();
                let (a, b) = orthonormal_basis(d);
                let corners = [d, d + a * 1e-4, d + b * 1e-4];
                let ratio = solid_angle(corners.map(|c| m * c)) / solid_angle(corners);
                let expected = solid_angle_scale(m, d);
                assert!((ratio - expected).abs() < 1e-3 * expected, "{ratio} vs {expected} for {d}");
                assert!((solid_angle_scale(m, d * 3.0) - expected).abs() < 1e-12 * expected);
            }
        }
    }

    #[test]
    fn area_density_becomes_solid_angle_density() {
        // 1 / area at distance 2 seen at 60 degrees from the normal: 4 / cos = 8 times it.
        let normal = DVec3::Y;
        let point = DVec3::new(2.0 * 60f64.to_radians().sin(), 2.0 * 60f64.to_radians().cos(), 0.0);
        let pdf = area_to_solid_angle(0.25, DVec3::ZERO, point, normal);
        assert!((pdf - 2.0).abs() < 1e-12, "{pdf}");
        assert_eq!(area_to_solid_angle(1.0, DVec3::ZERO, DVec3::X, DVec3::Y), 0.0, "edge-on");
        assert_eq!(area_to_solid_angle(1.0, DVec3::X, DVec3::X, DVec3::Y), 0.0, "at the reference");
    }

    #[test]
    fn longitude_tangent_keeps_the_latitude_and_the_surface() {
        // On an ellipsoid x^2 / 4 + y^2 + z^2 / 9 = 1, moving along dpdu keeps the point on the
        // surface and its latitude about the origin, and turns the longitude by du.
        let on_surface = |d: DVec3| d / (d.x * d.x / 4.0 + d.y * d.y + d.z * d.z / 9.0).sqrt();
        let normal_at = |p: DVec3| DVec3::new(p.x / 4.0, p.y, p.z / 9.0).normalize();
        let longitude = |p: DVec3| p.z.atan2(-p.x) / TAU;
        let latitude = |p: DVec3| (p.y / p.length()).asin();
        for d in [DVec3::new(1.0, 0.5, 0.3), DVec3::new(-0.2, -0.9, 0.4), DVec3::new(0.0, 0.1, -1.0)] {
            let p = on_surface(d);
            let dpdu = longitude_dpdu(p, normal_at(p));
            assert!(dpdu.dot(normal_at(p)).abs() < 1e-12 * dpdu.length());
            let h = 1e-6;
            let q = on_surface(p + dpdu * h);
            assert!((q - (p + dpdu * h)).length() < 1e-9, "stays on the surface to first order");
            assert!((latitude(q) - latitude(p)).abs() < 1e-9, "latitude kept");
            assert!((longitude(q) - longitude(p) - h).abs() < 1e-9, "longitude turns by du");
        }
        let pole = longitude_dpdu(DVec3::Y, DVec3::Y);
        assert!((pole.length() - 1.0).abs() < 1e-15 && pole.dot(DVec3::Y).abs() < 1e-15, "a unit tangent");
    }

    #[test]
    fn polynomial_roots_of_a_quartic_with_four_roots() {
        // (t - 1)(t - 2)(t - 3)(t - 4) = t^4 - 10 t^3 + 35 t^2 - 50 t + 24.
        let c = [24.0, -50.0, 35.0, -10.0, 1.0];
        let roots = polynomial_roots(&c, -10.0, 10.0);
        assert_eq!(roots.len(), 4);
        for (r, expected) in roots.as_slice().iter().zip([1.0, 2.0, 3.0, 4.0]) {
            assert!((r - expected).abs() < 1e-13, "{r} vs {expected}");
        }
        let inner = polynomial_roots(&c, 1.5, 3.5);
        assert_eq!(inner.as_slice().len(), 2);
        assert!(polynomial_roots(&c, 4.5, 9.0).is_empty());
    }

    #[test]
    fn polynomial_roots_close_together_and_tiny_leading_term() {
        // (t - 1)(t - 1 - 1e-7)(t^2 + 1): two close roots and a complex pair.
        let e = 1e-7;
        let c = [1.0 + e, -2.0 - e, 2.0 + e, -2.0 - e, 1.0];
        let roots = polynomial_roots(&c, 0.0, 2.0);
        assert_eq!(roots.len(), 2, "{roots:?}");
        // Close roots are ill-conditioned: rounding of about 1e-16 in the values moves them
        // by about 1e-16 / p'(root) = 1e-16 / 2e-7.
        assert!((roots.as_slice()[0] - 1.0).abs() < 1e-8);
        assert!((roots.as_slice()[1] - 1.0 - e).abs() < 1e-8);
        // A quadratic written as a quartic with a vanishing leading coefficient.
        let roots = polynomial_roots(&[-2.0, 0.0, 1.0, 0.0, 1e-30], -5.0, 5.0);
        assert_eq!(roots.len(), 2);
        assert!((roots.as_slice()[1] - 2f64.sqrt()).abs() < 1e-15);
        assert_eq!(eval_polynomial(&[1.0, 2.0, 3.0], 2.0), 17.0);
    }

    #[test]
    fn quadratics_are_solved_accurately_in_every_case() {
        // b dominates: the small root needs the stable form (1e-8 and 1e8).
        let roots = polynomial_roots(&[1.0, -1e8 - 1e-8, 1.0], -1.0, 2e8);
        assert_eq!(roots.len(), 2);
        assert!((roots.as_slice()[0] - 1e-8).abs() < 1e-23, "{roots:?}");
        assert!((roots.as_slice()[1] - 1e8).abs() < 1e-7, "{roots:?}");
        // Only the roots inside the interval, a negative leading coefficient.
        assert_eq!(polynomial_roots(&[6.0, 1.0, -1.0], 0.0, 10.0).as_slice(), &[3.0]);
        assert_eq!(polynomial_roots(&[6.0, 1.0, -1.0], -10.0, 10.0).as_slice(), &[-2.0, 3.0]);
        // A double root is reported where the quadratic is exactly 0, once; none without roots.
        assert_eq!(polynomial_roots(&[1.0, -2.0, 1.0], -5.0, 5.0).as_slice(), &[1.0]);
        assert!(polynomial_roots(&[1.0, 0.0, 1.0], -5.0, 5.0).is_empty());
        // Roots at the interval's ends count.
        assert_eq!(polynomial_roots(&[-1.0, 0.0, 1.0], -1.0, 1.0).as_slice(), &[-1.0, 1.0]);
    }

    #[test]
    fn visiting_roots_finds_known_roots_in_order_and_stops_when_asked() {
        let mut rng = crate::contract::TestRng::new(0x9e37_79b9_7f4a_7c15);
        // Multiplies the ascending coefficients by (t - r).
        let times_root = |c: &[f64], r: f64| -> Vec<f64> {
            let mut out = vec![0.0; c.len() + 1];
            for (i, &ci) in c.iter().enumerate() {
                out[i + 1] += ci;
                out[i] -= r * ci;
            }
            out
        };
        for case in 0..6000 {
            // 1 to 4 real roots at least 0.1 apart, times (t^2 + 1) in every other case, and a
            // leading coefficient of either sign.
            let count = 1 + case % 4;
            let mut roots: Vec<f64> = Vec::new();
            while roots.len() < count {
                let r = rng.range(-3.0, 3.0);
                if roots.iter().all(|q| (q - r).abs() > 0.1) {
                    roots.push(r);
                }
            }
            roots.sort_by(f64::total_cmp);
            let scale = rng.range(-2.0, 2.0).max(0.1);
            let mut coefficients = if case % 2 == 0 { vec![scale] } else { vec![scale, 0.0, scale] };
            for &r in &roots {
                coefficients = times_root(&coefficients, r);
            }
            let (lo, hi) = (rng.range(-3.5, 0.5), rng.range(-0.5, 3.5));
            let expected: Vec<f64> = roots.iter().copied().filter(|r| (lo..=hi).contains(r)).collect();
            let mut visited = Vec::new();
            let _ = visit_polynomial_roots(&coefficients, lo, hi, &mut |t| {
                visited.push(t);
                ControlFlow::Continue(())
            });
            assert_eq!(visited.len(), expected.len(), "{coefficients:?} on [{lo}, {hi}]: {visited:?} vs {expected:?}");
            for (found, root) in visited.iter().zip(&expected) {
                assert!((found - root).abs() < 1e-9, "{found} vs {root} of {coefficients:?}");
            }
            assert_eq!(polynomial_roots(&coefficients, lo, hi).as_slice(), visited, "the list is the visits");
            // Breaking at the k-th root visits exactly the first k.
            for stop in 1..visited.len() {
                let mut first = Vec::new();
                let flow = visit_polynomial_roots(&coefficients, lo, hi, &mut |t| {
                    first.push(t);
                    if first.len() == stop { ControlFlow::Break(()) } else { ControlFlow::Continue(()) }
                });
                assert!(flow.is_break());
                assert_eq!(first, visited[..stop]);
            }
        }
    }

    #[test]
    fn polynomial_double_root_exactly_at_a_critical_point() {
        // (t - 1)^2 (t + 3): tangent at 1, crossing at -3.
        let roots = polynomial_roots(&[3.0, -5.0, 1.0, 1.0], -4.0, 4.0);
        assert_eq!(roots.as_slice(), &[-3.0, 1.0]);
    }
}
