//! Fresnel reflectance of dielectric and conductor interfaces (unpolarised light), with the
//! conventions of Mitsuba 3's `include/mitsuba/render/fresnel.h`.

use glam::DVec3;

/// Unpolarised Fresnel reflectance of a smooth dielectric interface.
///
/// `cos_theta_i` is the signed cosine between the incident direction (pointing away from the
/// surface) and the normal: positive on the exterior side, negative on the interior side.
/// `eta` is the relative IOR, interior / exterior (> 1 when the normal points into the less
/// dense medium).
///
/// Returns `(r, cos_theta_t, eta_it, eta_ti)`:
/// - `r`: the reflected fraction of power in [0, 1] (1 under total internal reflection, 0
///   when `eta == 1`, 1 at exactly grazing incidence);
/// - `cos_theta_t`: the signed cosine of the transmitted direction (opposite sign to
///   `cos_theta_i`; 0 under total internal reflection);
/// - `eta_it`: the relative IOR in the direction of travel (`eta` from outside, `1/eta` from
///   inside);
/// - `eta_ti`: its reciprocal, the factor that scales the tangential components of the
///   refracted direction.
pub fn fresnel_dielectric(cos_theta_i: f64, eta: f64) -> (f64, f64, f64, f64) {
    let outside = cos_theta_i >= 0.0;
    let (eta_it, eta_ti) = if outside { (eta, 1.0 / eta) } else { (1.0 / eta, eta) };
    // Snell's law: the squared cosine of the transmitted direction.
    let cos_t_sqr = 1.0 - (1.0 - cos_theta_i * cos_theta_i) * eta_ti * eta_ti;
    let cos_i = cos_theta_i.abs();
    let cos_t = cos_t_sqr.max(0.0).sqrt();
    let r = if eta == 1.0 {
        0.0
    } else if cos_i == 0.0 {
        1.0
    } else {
        let a_s = (cos_i - eta_it * cos_t) / (cos_i + eta_it * cos_t);
        let a_p = (cos_t - eta_it * cos_i) / (cos_t + eta_it * cos_i);
        0.5 * (a_s * a_s + a_p * a_p)
    };
    let cos_theta_t = if cos_theta_i >= 0.0 { -cos_t } else { cos_t };
    (r, cos_theta_t, eta_it, eta_ti)
}

/// Unpolarised Fresnel reflectance of a conductor, per RGB channel: the exact formula for a
/// complex relative IOR `eta + i k` (light arriving from outside, `cos_theta_i` in [0, 1]).
pub fn fresnel_conductor(cos_theta_i: f64, eta: DVec3, k: DVec3) -> DVec3 {
    let one = |e: f64, k: f64| {
        let cos2 = cos_theta_i * cos_theta_i;
        let sin2 = 1.0 - cos2;
        let sin4 = sin2 * sin2;
        let temp = e * e - k * k - sin2;
        let a2_plus_b2 = (temp * temp + 4.0 * k * k * e * e).max(0.0).sqrt();
        let a = (0.5 * (a2_plus_b2 + temp)).max(0.0).sqrt();
        let term1 = a2_plus_b2 + cos2;
        let term2 = 2.0 * cos_theta_i * a;
        let r_s = (term1 - term2) / (term1 + term2);
        let term3 = a2_plus_b2 * cos2 + sin4;
        let term4 = term2 * sin2;
        let r_p = r_s * (term3 - term4) / (term3 + term4);
        let r = 0.5 * (r_s + r_p);
        if r.is_finite() { r } else { 1.0 }
    };
    DVec3::new(one(eta.x, k.x), one(eta.y, k.y), one(eta.z, k.z))
}

/// Schlick's approximation `f0 + (1 - f0) (1 - cos)^5` (the glTF 2.0 Fresnel term).
pub(crate) fn schlick(f0: DVec3, cos: f64) -> DVec3 {
    let m = (1.0 - cos.abs()).clamp(0.0, 1.0);
    let m5 = (m * m) * (m * m) * m;
    f0 + (DVec3::ONE - f0) * m5
}

/// Mitsuba's `fresnel_diffuse_reflectance`: the hemispherical average of the dielectric
/// Fresnel reflectance for relative IOR `eta` (fits by Egan & Hilgeman for `eta < 1` and by
/// d'Eon & Irving otherwise).
pub(crate) fn diffuse_reflectance(eta: f64) -> f64 {
    let inv = 1.0 / eta;
    if eta < 1.0 {
        0.0636 * inv + eta * (eta * -1.4399 + 0.7099) + 0.6681
    } else {
        // Horner's scheme in 1/eta.
        [0.919317, -3.4793, 6.75335, -7.80989, 4.98554, -1.36881].iter().rev().fold(0.0, |acc, c| acc * inv + c)
    }
}

/// Mirror reflection of `v` about the local normal (0, 0, 1).
pub(crate) fn reflect(v: DVec3) -> DVec3 {
    DVec3::new(-v.x, -v.y, v.z)
}

/// Mirror reflection of `v` about the unit microfacet normal `m`.
pub(crate) fn reflect_about(v: DVec3, m: DVec3) -> DVec3 {
    2.0 * v.dot(m) * m - v
}

/// Refraction of `v` through the unit microfacet normal `m`, given `cos_theta_t` and `eta_ti`
/// from [`fresnel_dielectric`] of `v · m` (Mitsuba's `refract(wi, m, cos_theta_t, eta_ti)`).
pub(crate) fn refract_about(v: DVec3, m: DVec3, cos_theta_t: f64, eta_ti: f64) -> DVec3 {
    m * (v.dot(m) * eta_ti + cos_theta_t) - v * eta_ti
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dielectric_normal_incidence() {
        for eta in [1.33, 1.5, 2.4, 1.0 / 1.5] {
            let (r, cos_t, eta_it, eta_ti) = fresnel_dielectric(1.0, eta);
            let expected = ((eta - 1.0) / (eta + 1.0)).powi(2);
            assert!((r - expected).abs() < 1e-12, "eta {eta}: {r} vs {expected}");
            assert!((cos_t + 1.0).abs() < 1e-12);
            assert_eq!((eta_it, eta_ti), (eta, 1.0 / eta));
            // From inside at normal incidence: the same reflectance.
            let (r_in, cos_t_in, eta_it_in, _) = fresnel_dielectric(-1.0, eta);
            assert!((r_in - expected).abs() < 1e-12);
            assert!((cos_t_in - 1.0).abs() < 1e-12);
            assert_eq!(eta_it_in, 1.0 / eta);
        }
    }

    #[test]
    fn dielectric_total_internal_reflection() {
        let eta: f64 = 1.5;
        let critical = (1.0 / eta).asin();
        // From inside, beyond the critical angle: everything reflects.
        for theta in [critical + 1e-6, critical + 0.1, 1.2, 1.5] {
            let (r, cos_t, _, _) = fresnel_dielectric(-f64::cos(theta), eta);
            assert_eq!(r, 1.0, "theta {theta}");
            assert_eq!(cos_t, 0.0);
        }
        // Just inside the critical angle something is transmitted.
        let (r, _, _, _) = fresnel_dielectric(-f64::cos(critical - 0.01), eta);
        assert!(r < 1.0);
        // Grazing from outside reflects everything, index matching nothing.
        assert_eq!(fresnel_dielectric(0.0, eta).0, 1.0);
        assert_eq!(fresnel_dielectric(0.3, 1.0).0, 0.0);
        assert!((fresnel_dielectric(-0.3, 1.0).1 - 0.3).abs() < 1e-12);
    }

    #[test]
    fn dielectric_snell() {
        let eta = 1.5;
        let cos_i: f64 = 0.6;
        let (r, cos_t, _, eta_ti) = fresnel_dielectric(cos_i, eta);
        let sin_t = (1.0 - cos_t * cos_t).sqrt();
        assert!((sin_t - (1.0 - cos_i * cos_i).sqrt() * eta_ti).abs() < 1e-12);
        assert!(r > 0.0 && r < 1.0);
        // Reciprocity of the interface: the same reflectance from the other side along the
        // refracted direction.
        let (r_back, cos_back, _, _) = fresnel_dielectric(cos_t, eta);
        assert!((r - r_back).abs() < 1e-12);
        assert!((cos_back - cos_i).abs() < 1e-12);
    }

    #[test]
    fn conductor_normal_incidence_and_grazing() {
        let eta = DVec3::new(0.2, 0.92, 1.1);
        let k = DVec3::new(3.9, 2.45, 2.14);
        let f = fresnel_conductor(1.0, eta, k);
        for c in 0..3 {
            let (e, k) = (eta[c], k[c]);
            let expected = ((e - 1.0).powi(2) + k * k) / ((e + 1.0).powi(2) + k * k);
            assert!((f[c] - expected).abs() < 1e-12, "{} vs {expected}", f[c]);
        }
        let grazing = fresnel_conductor(0.0, eta, k);
        assert!((grazing - DVec3::ONE).abs().max_element() < 1e-12);
        // k = 0 reduces to the dielectric formula.
        let d = fresnel_conductor(0.7, DVec3::splat(1.5), DVec3::ZERO);
        assert!((d.x - fresnel_dielectric(0.7, 1.5).0).abs() < 1e-12);
    }

    #[test]
    fn diffuse_reflectance_matches_integral() {
        // 2 * integral of F(cos) cos dcos over [0, 1].
        for eta in [1.5, 1.0 / 1.5, 1.33] {
            let n = 100_000;
            let mut sum = 0.0;
            for i in 0..n {
                let c = (i as f64 + 0.5) / n as f64;
                sum += fresnel_dielectric(c, eta).0 * c;
            }
            let integral = 2.0 * sum / n as f64;
            assert!((integral - diffuse_reflectance(eta)).abs() < 0.01 * integral.max(0.05), "eta {eta}: {integral}");
        }
    }
}
