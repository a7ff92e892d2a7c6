//! Lambertian reflection, Mitsuba's `diffuse`: f = reflectance / π on the front side.

use glam::{DVec2, DVec3};

use super::{BsdfSample, cosine_hemisphere};
use std::f64::consts::FRAC_1_PI;

/// f cos θi: `reflectance cos θi / π` when both directions are above the surface.
pub(crate) fn eval(reflectance: DVec3, wo: DVec3, wi: DVec3) -> DVec3 {
    if wo.z > 0.0 && wi.z > 0.0 { reflectance * (wi.z * FRAC_1_PI) } else { DVec3::ZERO }
}

/// Cosine-weighted hemisphere density.
pub(crate) fn pdf(wo: DVec3, wi: DVec3) -> f64 {
    if wo.z > 0.0 && wi.z > 0.0 { wi.z * FRAC_1_PI } else { 0.0 }
}

/// Cosine-weighted sample; its weight is the reflectance.
pub(crate) fn sample(reflectance: DVec3, wo: DVec3, u: DVec2) -> Option<BsdfSample> {
    if wo.z <= 0.0 {
        return None;
    }
    let wi = cosine_hemisphere(u);
    if wi.z <= 0.0 {
        return None;
    }
    BsdfSample::smooth(wi, reflectance, wi.z * FRAC_1_PI)
}

#[cfg(test)]
mod tests {
    use crate::render::bsdf::Bsdf;
    use crate::render::bsdf::chi2::{self, Rng};
    use glam::DVec3;

    #[test]
    fn chi2_diffuse() {
        let bsdf = Bsdf::Diffuse { reflectance: DVec3::new(0.8, 0.5, 0.2) };
        for cos in chi2::COS_WO {
            chi2::check(&bsdf, chi2::wo_at(cos), "diffuse");
        }
    }

    #[test]
    fn white_lambert_albedo_is_one() {
        let bsdf = Bsdf::Diffuse { reflectance: DVec3::ONE };
        let mut rng = Rng::new(3);
        let wo = chi2::wo_at(0.5);
        // Weight is exactly the reflectance for every sample; also integrate eval uniformly.
        let (mean, sigma) = chi2::directional_albedo(&bsdf, wo, 100_000, &mut rng);
        assert!((mean - DVec3::ONE).abs().max_element() < 1e-12, "{mean} ± {sigma}");
        let (mean, sigma) = chi2::uniform_albedo(&bsdf, wo, 200_000, &mut rng);
        assert!((mean.x - 1.0).abs() < 3.0 * sigma.x, "{mean} ± {sigma}");
    }
}
