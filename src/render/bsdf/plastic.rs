//! Plastics: a dielectric coating of relative IOR `eta` over a Lambertian base, Mitsuba's
//! `plastic` (smooth coating: delta specular + diffuse) and `roughplastic` (GGX coating,
//! `nonlinear = false`).
//!
//! The diffuse part is `diffuse / (1 - Fdr) · (1/eta^2) · T(wo) T(wi) · cos θi / π`, where
//! `Fdr` is the coating's internal diffuse reflectance and T its transmittance: `1 - F` of
//! the smooth interface, or for the rough coating Mitsuba's precomputed transmittance table
//! (64 cosines, Gauss-Legendre quadrature of the rough interface, linear interpolation).
//! Lobe selection weighs the specular lobe by `(1 - T(wo))` and the diffuse one by
//! `T(wo) · mean(diffuse)` against a specular weight 1 (Mitsuba's
//! `m_specular_sampling_weight`).

use std::cell::RefCell;
use std::collections::HashMap;
use std::f64::consts::FRAC_1_PI;
use std::rc::Rc;

use glam::{DVec2, DVec3};

use super::conductor::reflection_pdf;
use super::fresnel::{diffuse_reflectance, fresnel_dielectric, reflect, reflect_about, refract_about};
use super::microfacet::Ggx;
use super::{BsdfSample, cosine_hemisphere};

/// Entries of the rough coating's transmittance table (Mitsuba's `MI_ROUGH_TRANSMITTANCE_RES`).
const TABLE_RES: usize = 64;

/// Mitsuba's specular sampling weight: the specular reflectance mean (1) against the
/// diffuse reflectance mean.
fn specular_weight(diffuse: DVec3) -> f64 {
    let d_mean = (diffuse.x + diffuse.y + diffuse.z) / 3.0;
    1.0 / (d_mean + 1.0)
}

/// The probability of choosing the specular lobe given the coating's transmittance toward
/// `wo`.
fn specular_probability(diffuse: DVec3, t_o: f64) -> f64 {
    let w = specular_weight(diffuse);
    let (s, d) = ((1.0 - t_o) * w, t_o * (1.0 - w));
    if s + d > 0.0 { s / (s + d) } else { 0.0 }
}

/// f cos θi of the non-delta lobes.
pub(crate) fn eval(diffuse: DVec3, eta: f64, alpha: f64, wo: DVec3, wi: DVec3) -> DVec3 {
    if wo.z <= 0.0 || wi.z <= 0.0 {
        return DVec3::ZERO;
    }
    let inv_eta2 = 1.0 / (eta * eta);
    if alpha == 0.0 {
        let (f_o, f_i) = (fresnel_dielectric(wo.z, eta).0, fresnel_dielectric(wi.z, eta).0);
        let fdr_int = diffuse_reflectance(1.0 / eta);
        return diffuse / (1.0 - fdr_int) * (wi.z * FRAC_1_PI * inv_eta2 * (1.0 - f_o) * (1.0 - f_i));
    }
    let ggx = Ggx::new(alpha);
    let h = (wo + wi).normalize();
    let specular = fresnel_dielectric(wo.dot(h), eta).0 * ggx.d(h) * ggx.g(wo, wi, h) / (4.0 * wo.z);
    let tables = rough_tables(eta, alpha);
    let (t_o, t_i) = (tables.transmittance(wo.z), tables.transmittance(wi.z));
    let base = diffuse / (1.0 - tables.internal_reflectance);
    DVec3::splat(specular) + base * (FRAC_1_PI * inv_eta2 * wi.z * t_o * t_i)
}

/// Density of the non-delta lobes.
pub(crate) fn pdf(diffuse: DVec3, eta: f64, alpha: f64, wo: DVec3, wi: DVec3) -> f64 {
    if wo.z <= 0.0 || wi.z <= 0.0 {
        return 0.0;
    }
    if alpha == 0.0 {
        let p_spec = specular_probability(diffuse, 1.0 - fresnel_dielectric(wo.z, eta).0);
        return (1.0 - p_spec) * wi.z * FRAC_1_PI;
    }
    let p_spec = specular_probability(diffuse, rough_tables(eta, alpha).transmittance(wo.z));
    p_spec * reflection_pdf(Ggx::new(alpha), wo, wi) + (1.0 - p_spec) * wi.z * FRAC_1_PI
}

/// Picks the specular or the diffuse lobe with `u_lobe`, then a direction with `u`.
pub(crate) fn sample(diffuse: DVec3, eta: f64, alpha: f64, wo: DVec3, u_lobe: f64, u: DVec2) -> Option<BsdfSample> {
    if wo.z <= 0.0 {
        return None;
    }
    if alpha == 0.0 {
        let f_o = fresnel_dielectric(wo.z, eta).0;
        let p_spec = specular_probability(diffuse, 1.0 - f_o);
        if u_lobe < p_spec {
            return BsdfSample::delta(reflect(wo), DVec3::splat(f_o / p_spec), p_spec);
        }
        let wi = cosine_hemisphere(u);
        if wi.z <= 0.0 {
            return None;
        }
        let p_diffuse = 1.0 - p_spec;
        let f_i = fresnel_dielectric(wi.z, eta).0;
        let fdr_int = diffuse_reflectance(1.0 / eta);
        let weight = diffuse / (1.0 - fdr_int) * ((1.0 - f_o) * (1.0 - f_i) / (eta * eta * p_diffuse));
        return BsdfSample::smooth(wi, weight, p_diffuse * wi.z * FRAC_1_PI);
    }
    let p_spec = specular_probability(diffuse, rough_tables(eta, alpha).transmittance(wo.z));
    let wi =
        if u_lobe < p_spec { reflect_about(wo, Ggx::new(alpha).sample_visible(wo, u)) } else { cosine_hemisphere(u) };
    let pdf = pdf(diffuse, eta, alpha, wo, wi);
    if pdf <= 0.0 {
        return None;
    }
    BsdfSample::smooth(wi, eval(diffuse, eta, alpha, wo, wi) / pdf, pdf)
}

/// The rough coating's precomputed quantities (Mitsuba's `parameters_changed`).
#[derive(Debug)]
struct RoughTables {
    /// Transmittance into the coating at cos θ = i / (TABLE_RES - 1).
    transmittance: [f64; TABLE_RES],
    /// Cosine-weighted hemispherical reflectance of the coating from inside.
    internal_reflectance: f64,
}

impl RoughTables {
    fn new(eta: f64, alpha: f64) -> Self {
        let ggx = Ggx::new(alpha);
        let mut transmittance = [0.0; TABLE_RES];
        let mut internal = 0.0;
        for (i, t) in transmittance.iter_mut().enumerate() {
            // Mitsuba computes in single precision and clamps cos θ to 1e-6.
            let mu = (i as f64 / (TABLE_RES - 1) as f64).max(1e-6);
            let wi = DVec3::new((1.0 - mu * mu).sqrt(), 0.0, mu);
            *t = rough_transmittance(ggx, wi, eta);
            internal += rough_reflectance(ggx, wi, 1.0 / eta) * mu;
        }
        RoughTables { transmittance, internal_reflectance: internal / TABLE_RES as f64 * 2.0 }
    }

    /// Linear interpolation in the table (Mitsuba's `lerp_gather`).
    fn transmittance(&self, cos: f64) -> f64 {
        let x = cos * (TABLE_RES - 1) as f64;
        let index = (x.max(0.0) as usize).min(TABLE_RES - 2);
        let (v0, v1) = (self.transmittance[index], self.transmittance[index + 1]);
        v0 + (v1 - v0) * (x - index as f64)
    }
}

/// Gauss-Legendre quadrature of a function of visible-normal samples over [0, 1]^2, with
/// Mitsuba's resolution: 32 x 32 nodes when `eta > 1`, 128 x 128 otherwise.
fn quadrature(eta: f64, mut f: impl FnMut(DVec2) -> f64) -> f64 {
    let (nodes, weights) = gauss_legendre(if eta > 1.0 { 32 } else { 128 });
    let mut sum = 0.0;
    for (&y, &wy) in nodes.iter().zip(&weights) {
        for (&x, &wx) in nodes.iter().zip(&weights) {
            sum += f(DVec2::new(0.5 * x + 0.5, 0.5 * y + 0.5)) * wx * wy * 0.25;
        }
    }
    sum
}

/// Directional transmittance of a rough interface from `wi` (Mitsuba's `eval_transmittance`).
fn rough_transmittance(ggx: Ggx, wi: DVec3, eta: f64) -> f64 {
    quadrature(eta, |u| {
        let m = ggx.sample_visible(wi, u);
        let (f, cos_t, _, eta_ti) = fresnel_dielectric(wi.dot(m), eta);
        let wo = refract_about(wi, m, cos_t, eta_ti);
        if wo.z * wi.z >= 0.0 { 0.0 } else { ggx.smith_g1(wo, m) * (1.0 - f) }
    })
}

/// Directional single-scattering reflectance of a rough interface (Mitsuba's
/// `eval_reflectance`).
fn rough_reflectance(ggx: Ggx, wi: DVec3, eta: f64) -> f64 {
    quadrature(eta, |u| {
        let m = ggx.sample_visible(wi, u);
        let wo = reflect_about(wi, m);
        if wo.z <= 0.0 || wi.z <= 0.0 { 0.0 } else { ggx.smith_g1(wo, m) * fresnel_dielectric(wi.dot(m), eta).0 }
    })
}

/// Nodes and weights of the n-point Gauss-Legendre rule on [-1, 1] (Newton's method on the
/// Legendre polynomial from the Chebyshev initial guesses).
fn gauss_legendre(n: usize) -> (Vec<f64>, Vec<f64>) {
    let mut nodes = vec![0.0; n];
    let mut weights = vec![0.0; n];
    for i in 0..n {
        let mut x = -(std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut derivative = 1.0;
        for _ in 0..100 {
            // P_n(x) and P_n'(x) by the three-term recurrence.
            let (mut p0, mut p1) = (1.0, x);
            for k in 2..=n {
                let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                p0 = p1;
                p1 = p2;
            }
            let pn = if n == 1 { x } else { p1 };
            let pn1 = if n == 1 { 1.0 } else { p0 };
            derivative = n as f64 * (x * pn - pn1) / (x * x - 1.0);
            let step = pn / derivative;
            x -= step;
            if step.abs() < 1e-15 {
                break;
            }
        }
        nodes[i] = x;
        weights[i] = 2.0 / ((1.0 - x * x) * derivative * derivative);
    }
    (nodes, weights)
}

thread_local! {
    /// Tables per (eta, alpha) bit pattern: they cost ~10^6 microfacet samples to build.
    static TABLES: RefCell<HashMap<(u64, u64), Rc<RoughTables>>> = RefCell::new(HashMap::new());
}

/// The cached tables of a rough coating.
fn rough_tables(eta: f64, alpha: f64) -> Rc<RoughTables> {
    let key = (eta.to_bits(), alpha.to_bits());
    TABLES.with(|cache| {
        let mut cache = cache.borrow_mut();
        if let Some(t) = cache.get(&key) {
            return t.clone();
        }
        // Bound the cache: per-texel roughness would otherwise grow it without end.
        if cache.len() >= 256 {
            cache.clear();
        }
        let tables = Rc::new(RoughTables::new(eta, alpha));
        cache.insert(key, tables.clone());
        tables
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::bsdf::Bsdf;
    use crate::render::bsdf::chi2::{self, Rng};

    fn plastic(alpha: f64) -> Bsdf {
        Bsdf::Plastic { diffuse: DVec3::new(0.7, 0.4, 0.1), eta: 1.5, alpha }
    }

    #[test]
    fn chi2_plastic() {
        for alpha in [0.0, 0.05, 0.3, 0.8] {
            for cos in chi2::COS_WO {
                chi2::check(&plastic(alpha), chi2::wo_at(cos), &format!("plastic alpha {alpha}"));
            }
        }
    }

    #[test]
    fn gauss_legendre_integrates_polynomials() {
        for n in [1, 2, 5, 32, 128] {
            let (x, w) = gauss_legendre(n);
            assert!((w.iter().sum::<f64>() - 2.0).abs() < 1e-12, "n {n}");
            let degree = 2 * n - 1;
            let integral: f64 = x.iter().zip(&w).map(|(x, w)| w * x.powi(degree as i32 - 1)).sum();
            let expected = if (degree - 1) % 2 == 0 { 2.0 / degree as f64 } else { 0.0 };
            assert!((integral - expected).abs() < 1e-12, "n {n}: {integral} vs {expected}");
        }
    }

    /// The rough coating's transmittance tends to the smooth interface's 1 - F as alpha
    /// shrinks, and its internal reflectance to the hemispherical average Fdr.
    #[test]
    fn rough_tables_approach_smooth_limit() {
        let tables = RoughTables::new(1.5, 0.002);
        for cos in [0.3, 0.6, 0.95] {
            let smooth = 1.0 - fresnel_dielectric(cos, 1.5).0;
            assert!((tables.transmittance(cos) - smooth).abs() < 0.01, "cos {cos}");
        }
        let fdr = diffuse_reflectance(1.0 / 1.5);
        assert!((tables.internal_reflectance - fdr).abs() < 0.02, "{} vs {fdr}", tables.internal_reflectance);
    }

    #[test]
    fn reciprocity() {
        for alpha in [0.0, 0.05, 0.3] {
            chi2::check_reciprocity(&plastic(alpha));
        }
    }

    /// A white plastic reflects at most what falls on it (up to the Fdr fit's accuracy).
    #[test]
    fn white_plastic_energy_bounded() {
        let mut rng = Rng::new(17);
        for alpha in [0.0, 0.1, 0.5] {
            let bsdf = Bsdf::Plastic { diffuse: DVec3::ONE, eta: 1.5, alpha };
            for cos in chi2::COS_WO {
                let (mean, sigma) = chi2::directional_albedo(&bsdf, chi2::wo_at(cos), 100_000, &mut rng);
                // Mitsuba's Fdr fit is good to ~0.1%: a smooth white plastic sits at 1.
                assert!(mean.x <= 1.002 + 3.0 * sigma.x, "alpha {alpha} cos {cos}: {mean} ± {sigma}");
            }
        }
    }
}
