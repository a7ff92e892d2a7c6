//! Conductors: Mitsuba's `conductor` (alpha == 0, a delta mirror) and `roughconductor` with
//! the GGX distribution and visible-normal sampling.
//!
//! Rough: f cos θi = F(wo · h) D(h) G1(wo, h) G1(wi, h) / (4 cos θo), with h the half vector;
//! sampling reflects `wo` about a visible normal, weight F G1(wi, m) tint.

use glam::{DVec2, DVec3};

use super::BsdfSample;
use super::fresnel::{fresnel_conductor, reflect, reflect_about};
use super::microfacet::Ggx;

/// f cos θi of the rough conductor (0 for the smooth one).
pub(crate) fn eval(eta: DVec3, k: DVec3, alpha: f64, tint: DVec3, wo: DVec3, wi: DVec3) -> DVec3 {
    if alpha == 0.0 || wo.z <= 0.0 || wi.z <= 0.0 {
        return DVec3::ZERO;
    }
    let h = (wo + wi).normalize();
    let ggx = Ggx::new(alpha);
    let d = ggx.d(h);
    if d == 0.0 {
        return DVec3::ZERO;
    }
    let value = d * ggx.g(wo, wi, h) / (4.0 * wo.z);
    fresnel_conductor(wo.dot(h), eta, k) * tint * value
}

/// Density of the visible-normal reflection sample (0 for the smooth conductor).
pub(crate) fn pdf(alpha: f64, wo: DVec3, wi: DVec3) -> f64 {
    if alpha == 0.0 {
        return 0.0;
    }
    reflection_pdf(Ggx::new(alpha), wo, wi)
}

/// Solid-angle density of reflecting `wo` about a normal sampled from the visible normals:
/// D(h) G1(wo, h) / (4 cos θo) for the half vector h (Mitsuba's roughconductor `pdf`).
pub(crate) fn reflection_pdf(ggx: Ggx, wo: DVec3, wi: DVec3) -> f64 {
    if wo.z <= 0.0 || wi.z <= 0.0 {
        return 0.0;
    }
    let h = (wo + wi).normalize();
    if wo.dot(h) <= 0.0 || wi.dot(h) <= 0.0 {
        return 0.0;
    }
    ggx.d(h) * ggx.smith_g1(wo, h) / (4.0 * wo.z)
}

/// Smooth: the mirror direction with weight F tint (pdf 1). Rough: a visible-normal sample.
pub(crate) fn sample(eta: DVec3, k: DVec3, alpha: f64, tint: DVec3, wo: DVec3, u: DVec2) -> Option<BsdfSample> {
    if wo.z <= 0.0 {
        return None;
    }
    if alpha == 0.0 {
        return BsdfSample::delta(reflect(wo), fresnel_conductor(wo.z, eta, k) * tint, 1.0);
    }
    let ggx = Ggx::new(alpha);
    let m = ggx.sample_visible(wo, u);
    let wi = reflect_about(wo, m);
    if wi.z <= 0.0 {
        return None;
    }
    let pdf = ggx.pdf_visible(wo, m) / (4.0 * wi.dot(m));
    let weight = fresnel_conductor(wo.dot(m), eta, k) * tint * ggx.smith_g1(wi, m);
    BsdfSample::smooth(wi, weight, pdf)
}

#[cfg(test)]
mod tests {
    use crate::render::bsdf::chi2::{self, Rng};
    use crate::render::bsdf::{Bsdf, fresnel_conductor, metal};
    use glam::DVec3;

    fn gold(alpha: f64) -> Bsdf {
        let (eta, k) = metal("Au").unwrap();
        Bsdf::Conductor { eta, k, alpha, tint: DVec3::new(1.0, 0.9, 0.8) }
    }

    #[test]
    fn chi2_rough_conductor() {
        for alpha in chi2::ALPHAS {
            for cos in chi2::COS_WO {
                chi2::check(&gold(alpha), chi2::wo_at(cos), &format!("conductor alpha {alpha}"));
            }
        }
    }

    #[test]
    fn smooth_conductor_is_a_mirror() {
        let bsdf = gold(0.0);
        let wo = chi2::wo_at(0.5);
        let s = bsdf.sample(wo, 0.3, glam::DVec2::new(0.2, 0.7)).unwrap();
        assert!(s.delta && s.pdf == 1.0);
        assert!((s.wi - DVec3::new(-wo.x, -wo.y, wo.z)).length() < 1e-12);
        let (eta, k) = metal("Au").unwrap();
        assert!((s.weight - fresnel_conductor(0.5, eta, k) * DVec3::new(1.0, 0.9, 0.8)).length() < 1e-12);
        assert_eq!(bsdf.eval(wo, s.wi), DVec3::ZERO);
        assert_eq!(bsdf.pdf(wo, s.wi), 0.0);
        chi2::check(&bsdf, wo, "smooth conductor");
    }

    /// A perfect mirror's rough version loses only the energy of the paths that would
    /// scatter more than once: between 0.9 and 1 at alpha 0.1 (away from grazing), decreasing with alpha.
    #[test]
    fn rough_mirror_loses_only_multiple_scattering() {
        let mut rng = Rng::new(11);
        for cos in chi2::COS_WO {
            let wo = chi2::wo_at(cos);
            let mut previous = f64::INFINITY;
            for alpha in [0.1, 0.3, 0.6, 1.0] {
                let mirror = Bsdf::Conductor { eta: DVec3::ZERO, k: DVec3::splat(1e6), alpha, tint: DVec3::ONE };
                let (mean, sigma) = chi2::directional_albedo(&mirror, wo, 100_000, &mut rng);
                let (a, s) = (mean.x, sigma.x);
                assert!(a <= 1.0 + 3.0 * s, "cos {cos} alpha {alpha}: {a} ± {s}");
                // At grazing incidence (cos 0.1) single scattering keeps only ~0.87.
                if alpha == 0.1 && cos >= 0.5 {
                    assert!(a > 0.9, "cos {cos} alpha {alpha}: {a} ± {s}");
                }
                assert!(a < previous + 3.0 * s, "cos {cos} alpha {alpha}: {a} after {previous}");
                previous = a;
            }
        }
    }

    #[test]
    fn reciprocity() {
        chi2::check_reciprocity(&gold(0.3));
        chi2::check_reciprocity(&gold(0.05));
    }
}
