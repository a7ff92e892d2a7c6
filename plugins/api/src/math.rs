//! Small numerical helpers shared by shapes.

use glam::DVec3;

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

/// The largest polynomial degree [`polynomial_roots`] accepts.
pub const MAX_POLYNOMIAL_DEGREE: usize = 8;

/// The value of the polynomial `sum(coefficients[i] * t^i)` at `t` (Horner's scheme).
/// Coefficients are in ascending order: `coefficients[0]` is the constant term.
pub fn eval_polynomial(coefficients: &[f64], t: f64) -> f64 {
    coefficients.iter().rev().fold(0.0, |acc, &c| acc * t + c)
}

/// The value and the first derivative of the polynomial at `t` (ascending coefficients).
fn eval_polynomial_with_derivative(coefficients: &[f64], t: f64) -> (f64, f64) {
    let mut value = 0.0;
    let mut derivative = 0.0;
    for &c in coefficients.iter().rev() {
        derivative = derivative * t + value;
        value = value * t + c;
    }
    (value, derivative)
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
/// piece's ends differ in sign; it is then found by Newton's method safeguarded with
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
    let degree = coefficients.iter().rposition(|&c| c != 0.0).unwrap_or(0);
    assert!(
        degree <= MAX_POLYNOMIAL_DEGREE,
        "polynomial_roots supports degree {MAX_POLYNOMIAL_DEGREE} at most, got {degree}"
    );
    // Also rejects NaN bounds.
    let ordered = lo <= hi;
    if !ordered || !coefficients.iter().all(|c| c.is_finite()) {
        return roots;
    }
    let coefficients = &coefficients[..=degree];
    match degree {
        0 => {}
        1 => {
            let t = -coefficients[0] / coefficients[1];
            if t >= lo && t <= hi {
                roots.push(t);
            }
        }
        _ => {
            let mut derivative = [0.0; MAX_POLYNOMIAL_DEGREE];
            for i in 1..=degree {
                derivative[i - 1] = coefficients[i] * i as f64;
            }
            let critical = polynomial_roots(&derivative[..degree], lo, hi);
            let tolerance = 4.0 * f64::EPSILON * lo.abs().max(hi.abs());
            let mut x0 = lo;
            let mut y0 = eval_polynomial(coefficients, lo);
            for &x1 in critical.as_slice().iter().chain(std::iter::once(&hi)) {
                if x1 <= x0 && x1 != hi {
                    continue;
                }
                let y1 = eval_polynomial(coefficients, x1);
                if y0 == 0.0 {
                    roots.push(x0);
                } else if y1 != 0.0 && (y0 < 0.0) != (y1 < 0.0) {
                    roots.push(refine_root(coefficients, x0, x1, y0, tolerance));
                }
                x0 = x1;
                y0 = y1;
            }
            if y0 == 0.0 {
                roots.push(x0);
            }
        }
    }
    roots
}

/// The root of a polynomial that is monotonic on `[a, b]` and changes sign there
/// (`ya` = p(a) != 0): Newton steps kept inside a shrinking bracket, bisection otherwise.
fn refine_root(coefficients: &[f64], mut a: f64, mut b: f64, ya: f64, tolerance: f64) -> f64 {
    let a_negative = ya < 0.0;
    let mut x = 0.5 * (a + b);
    for _ in 0..200 {
        let (y, dy) = eval_polynomial_with_derivative(coefficients, x);
        if y == 0.0 {
            return x;
        }
        if (y < 0.0) == a_negative {
            a = x;
        } else {
            b = x;
        }
        let newton = x - y / dy;
        let next = if newton > a && newton < b { newton } else { 0.5 * (a + b) };
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
    fn polynomial_double_root_exactly_at_a_critical_point() {
        // (t - 1)^2 (t + 3): tangent at 1, crossing at -3.
        let roots = polynomial_roots(&[3.0, -5.0, 1.0, 1.0], -4.0, 4.0);
        assert_eq!(roots.as_slice(), &[-3.0, 1.0]);
    }
}
