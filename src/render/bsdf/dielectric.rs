//! Dielectric interfaces: Mitsuba's `dielectric` (smooth, delta reflection and refraction),
//! `roughdielectric` (Walter et al. 2007 with GGX and visible-normal sampling) and
//! `thindielectric` (a thin slab).
//!
//! Radiance transport: refracted radiance is scaled by `eta_ti^2`, with `eta_ti` from
//! `fresnel_dielectric(wo · m, eta)`: (IOR on `wo`'s side / IOR on `wi`'s side)^2, i.e.
//! `1/eta^2` when `wo` is outside and `eta^2` when it is inside (Mitsuba's
//! `TransportMode::Radiance` factor in `dielectric.cpp` and `roughdielectric.cpp`).

use glam::{DVec2, DVec3};

use super::BsdfSample;
use super::fresnel::{fresnel_dielectric, reflect, reflect_about, refract_about};
use super::microfacet::Ggx;

/// True when the interface has only delta lobes: smooth, or index-matched (no interface).
pub(crate) fn is_smooth(eta: f64, alpha: f64) -> bool {
    alpha == 0.0 || eta == 1.0
}

/// The generalised half vector of `wo` and `wi` (Walter et al.), turned to the exterior side,
/// and whether the pair is a reflection. `eta` is the relative IOR seen from `wo`'s side.
fn half_vector(eta: f64, wo: DVec3, wi: DVec3) -> (DVec3, bool, f64) {
    let reflect = wo.z * wi.z > 0.0;
    let eta_o = if wo.z > 0.0 { eta } else { 1.0 / eta };
    let h = (wo + wi * if reflect { 1.0 } else { eta_o }).normalize();
    (if h.z < 0.0 { -h } else { h }, reflect, eta_o)
}

/// What tints reflected and transmitted light (Mitsuba's `specular_reflectance` and
/// `specular_transmittance`).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Tints {
    /// Multiplies reflected light.
    pub reflect: DVec3,
    /// Multiplies transmitted light.
    pub transmit: DVec3,
}

/// f cos θi of the rough interface (0 for a smooth one).
pub(crate) fn eval(eta: f64, alpha: f64, tints: Tints, wo: DVec3, wi: DVec3) -> DVec3 {
    let Tints { reflect: reflect_tint, transmit: transmit_tint } = tints;
    if is_smooth(eta, alpha) || wo.z == 0.0 || wi.z == 0.0 {
        return DVec3::ZERO;
    }
    let (h, reflect, eta_o) = half_vector(eta, wo, wi);
    if !h.is_finite() {
        return DVec3::ZERO;
    }
    let ggx = Ggx::new(alpha);
    let d = ggx.d(h);
    let g = ggx.g(wo, wi, h);
    if d == 0.0 || g == 0.0 {
        return DVec3::ZERO;
    }
    let f = fresnel_dielectric(wo.dot(h), eta).0;
    if reflect {
        reflect_tint * (f * d * g / (4.0 * wo.z.abs()))
    } else {
        // Radiance: solid-angle compression 1/eta_o^2.
        let (doh, dih) = (wo.dot(h), wi.dot(h));
        let denom = doh + eta_o * dih;
        let value = ((1.0 - f) * d * g * doh * dih / (wo.z * denom * denom)).abs();
        transmit_tint * value
    }
}

/// Density of the rough interface's sample (0 for a smooth one).
pub(crate) fn pdf(eta: f64, alpha: f64, wo: DVec3, wi: DVec3) -> f64 {
    if is_smooth(eta, alpha) || wo.z == 0.0 || wi.z == 0.0 {
        return 0.0;
    }
    let (h, reflect, eta_o) = half_vector(eta, wo, wi);
    if !h.is_finite() || wo.dot(h) * wo.z <= 0.0 || wi.dot(h) * wi.z <= 0.0 {
        return 0.0;
    }
    let (doh, dih) = (wo.dot(h), wi.dot(h));
    let jacobian = if reflect {
        1.0 / (4.0 * dih)
    } else {
        let denom = doh + eta_o * dih;
        eta_o * eta_o * dih / (denom * denom)
    };
    let ggx = Ggx::new(alpha);
    let f = fresnel_dielectric(doh, eta).0;
    let lobe = if reflect { f } else { 1.0 - f };
    ggx.pdf_visible(wo * wo.z.signum(), h) * lobe * jacobian.abs()
}

/// Samples reflection with probability F and refraction otherwise, about a visible normal
/// sampled from `wo`'s side (smooth: about the macro normal, as delta lobes).
pub(crate) fn sample(eta: f64, alpha: f64, tints: Tints, wo: DVec3, u_lobe: f64, u: DVec2) -> Option<BsdfSample> {
    let Tints { reflect: reflect_tint, transmit: transmit_tint } = tints;
    if wo.z == 0.0 {
        return None;
    }
    if eta == 1.0 {
        // No interface: straight through, exactly.
        return BsdfSample::delta(-wo, transmit_tint, 1.0);
    }
    if is_smooth(eta, alpha) {
        let (r, cos_t, _, eta_ti) = fresnel_dielectric(wo.z, eta);
        return if u_lobe < r {
            BsdfSample::delta(reflect(wo), reflect_tint, r)
        } else {
            let wi = DVec3::new(-eta_ti * wo.x, -eta_ti * wo.y, cos_t);
            BsdfSample::delta(wi, transmit_tint * (eta_ti * eta_ti), 1.0 - r)
        };
    }
    let ggx = Ggx::new(alpha);
    let side = wo.z.signum();
    let m = ggx.sample_visible(wo * side, u);
    let mut pdf = ggx.pdf_visible(wo * side, m);
    if pdf == 0.0 {
        return None;
    }
    let (f, cos_t, eta_it, eta_ti) = fresnel_dielectric(wo.dot(m), eta);
    let (wi, mut weight, jacobian) = if u_lobe < f {
        pdf *= f;
        let wi = reflect_about(wo, m);
        (wi, reflect_tint, 1.0 / (4.0 * wi.dot(m)))
    } else {
        pdf *= 1.0 - f;
        let wi = refract_about(wo, m, cos_t, eta_ti);
        let denom = wo.dot(m) + eta_it * wi.dot(m);
        (wi, transmit_tint * (eta_ti * eta_ti), eta_it * eta_it * wi.dot(m) / (denom * denom))
    };
    // A reflection must stay on wo's side, a refraction must cross.
    let reflected = u_lobe < f;
    if wi.z == 0.0 || (wi.z * wo.z > 0.0) != reflected {
        return None;
    }
    weight *= ggx.smith_g1(wi, m);
    pdf *= jacobian.abs();
    let wi = wi.normalize();
    BsdfSample::smooth(wi, weight, pdf)
}

/// Mitsuba's `thindielectric`: reflectance `R = r + t r t + t r^3 t + … = 2r / (1 + r)` of a
/// slab whose interfaces each reflect r, transmission `1 - R` straight through (no
/// refraction offset: the slab is thin), both delta lobes.
pub(crate) fn sample_thin(eta: f64, tints: Tints, wo: DVec3, u_lobe: f64) -> Option<BsdfSample> {
    let Tints { reflect: reflect_tint, transmit: transmit_tint } = tints;
    if wo.z == 0.0 {
        return None;
    }
    let r = fresnel_dielectric(wo.z.abs(), eta).0;
    let r = r * 2.0 / (1.0 + r);
    if u_lobe < r {
        BsdfSample::delta(reflect(wo), reflect_tint, r)
    } else {
        BsdfSample::delta(-wo, transmit_tint, 1.0 - r)
    }
}

#[cfg(test)]
mod tests {
    use crate::render::bsdf::chi2::{self, Rng};
    use crate::render::bsdf::{Bsdf, fresnel_dielectric};
    use glam::{DVec2, DVec3};

    fn glass(eta: f64, alpha: f64) -> Bsdf {
        Bsdf::Dielectric { eta, alpha, reflect_tint: DVec3::ONE, transmit_tint: DVec3::ONE }
    }

    #[test]
    fn chi2_rough_dielectric() {
        for alpha in chi2::ALPHAS {
            for cos in chi2::COS_WO {
                // From outside and from inside (where total internal reflection occurs).
                chi2::check(&glass(1.5, alpha), chi2::wo_at(cos), &format!("dielectric alpha {alpha} outside"));
                chi2::check(&glass(1.5, alpha), chi2::wo_at(-cos), &format!("dielectric alpha {alpha} inside"));
            }
        }
        // A coating thinner than its surroundings (eta < 1).
        chi2::check(&glass(1.0 / 1.33, 0.3), chi2::wo_at(0.5), "dielectric eta 0.75");
    }

    #[test]
    fn chi2_smooth_dielectrics() {
        for cos in chi2::COS_WO {
            for wo in [chi2::wo_at(cos), chi2::wo_at(-cos)] {
                chi2::check(&glass(1.5, 0.0), wo, "smooth dielectric");
                let thin = Bsdf::ThinDielectric { eta: 1.5, reflect_tint: DVec3::ONE, transmit_tint: DVec3::ONE };
                chi2::check(&thin, wo, "thin dielectric");
            }
        }
    }

    /// With white tints, R + T = 1 for every incidence: each sample's weight, with the
    /// radiance factor eta_ti^2 of refraction undone, is exactly 1 (so the estimate of the
    /// scattered power is exact per sample), and reflection is chosen with probability r.
    #[test]
    fn smooth_dielectric_conserves_energy() {
        let bsdf = glass(1.5, 0.0);
        for cos in [0.9, 0.5, 0.1, -0.9, -0.5, -0.1, -0.7] {
            let wo = chi2::wo_at(cos);
            let (r, _, _, eta_ti) = fresnel_dielectric(wo.z, 1.5);
            let n = 1000;
            let mut reflections = 0;
            for i in 0..n {
                let u_lobe = (i as f64 + 0.5) / n as f64;
                let s = bsdf.sample(wo, u_lobe, DVec2::splat(0.5)).expect("smooth glass always scatters");
                assert!(s.delta && (s.wi.length() - 1.0).abs() < 1e-12);
                let reflected = s.wi.z * wo.z > 0.0;
                reflections += usize::from(reflected);
                let power = if reflected { s.weight.x } else { s.weight.x / (eta_ti * eta_ti) };
                assert!((power - 1.0).abs() < 1e-12, "cos {cos}: {s:?}");
                assert!((s.pdf - if reflected { r } else { 1.0 - r }).abs() < 1e-12);
                if !reflected {
                    // Snell: the tangential component scales by eta_ti.
                    assert!((s.wi.x + eta_ti * wo.x).abs() < 1e-12 && s.wi.z * wo.z < 0.0);
                }
            }
            assert!((reflections as f64 / n as f64 - r).abs() <= 1.0 / n as f64, "cos {cos}");
        }
    }

    /// Rough glass with white tints: reflected plus transmitted power (undoing the radiance
    /// factor) is at most 1 and close to 1 for a smooth-ish interface.
    #[test]
    fn rough_dielectric_energy_bounded() {
        let mut rng = Rng::new(5);
        for alpha in [0.05, 0.3, 0.8] {
            for cos in [0.9, 0.5, -0.9, -0.5] {
                let bsdf = glass(1.5, alpha);
                let wo = chi2::wo_at(cos);
                let (n, mut sum, mut sum2) = (100_000, 0.0, 0.0);
                for _ in 0..n {
                    if let Some(s) = bsdf.sample(wo, rng.next(), rng.next2()) {
                        let eta_ti2 = if wo.z > 0.0 { 1.0 / (1.5 * 1.5) } else { 1.5 * 1.5 };
                        let power = if s.wi.z * wo.z > 0.0 { s.weight.x } else { s.weight.x / eta_ti2 };
                        sum += power;
                        sum2 += power * power;
                    }
                }
                let mean = sum / n as f64;
                let sigma = ((sum2 / n as f64 - mean * mean) / n as f64).sqrt();
                assert!(mean <= 1.0 + 3.0 * sigma, "alpha {alpha} cos {cos}: {mean} ± {sigma}");
                if alpha == 0.05 {
                    assert!(mean > 0.95, "alpha {alpha} cos {cos}: {mean} ± {sigma}");
                }
            }
        }
    }

    #[test]
    fn index_matched_passes_straight_through() {
        for alpha in [0.0, 0.3] {
            let bsdf = glass(1.0, alpha);
            assert!(bsdf.is_delta());
            for cos in [0.9, -0.4, 1e-9] {
                let wo = chi2::wo_at(cos);
                let s = bsdf.sample(wo, 0.5, DVec2::new(0.3, 0.6)).unwrap();
                assert!(s.delta && s.pdf == 1.0, "{s:?}");
                assert!((s.wi + wo).length() < 1e-12 && s.weight == DVec3::ONE, "{s:?}");
                assert_eq!(bsdf.eval(wo, -wo), DVec3::ZERO);
            }
        }
        let thin = Bsdf::ThinDielectric { eta: 1.0, reflect_tint: DVec3::ONE, transmit_tint: DVec3::ONE };
        let s = thin.sample(chi2::wo_at(0.3), 0.0, DVec2::ZERO).unwrap();
        assert!((s.wi + chi2::wo_at(0.3)).length() < 1e-12 && s.pdf == 1.0);
    }

    #[test]
    fn thin_dielectric_sums_internal_reflections() {
        let thin = Bsdf::ThinDielectric { eta: 1.5, reflect_tint: DVec3::ONE, transmit_tint: DVec3::splat(0.5) };
        let wo = chi2::wo_at(1.0);
        let r = 0.04;
        let expected = 2.0 * r / (1.0 + r);
        let s = thin.sample(wo, 0.0, DVec2::ZERO).unwrap();
        assert!((s.pdf - expected).abs() < 1e-12 && s.weight == DVec3::ONE);
        let t = thin.sample(wo, 0.99, DVec2::ZERO).unwrap();
        assert!((t.pdf - (1.0 - expected)).abs() < 1e-12 && t.weight == DVec3::splat(0.5));
        assert!((t.wi + wo).length() < 1e-12);
    }
}
