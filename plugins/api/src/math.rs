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
    (
        DVec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
        DVec3::new(b, sign + n.y * n.y * a, -n.y),
    )
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
}
