//! The isotropic GGX (Trowbridge-Reitz) microfacet distribution with Smith shadowing and
//! visible-normal sampling, with the conventions of Mitsuba 3's
//! `include/mitsuba/render/microfacet.h` (`MicrofacetDistribution`, type `ggx`,
//! `sample_visible = true`).
//!
//! All vectors are in the local shading frame (z is the macro-surface normal) and unit length.

use glam::{DVec2, DVec3};

use crate::render::sampling::concentric_disc;

/// Smallest roughness: Mitsuba clamps `alpha` to 1e-4 the same way.
pub const MIN_ALPHA: f64 = 1e-4;

/// An isotropic GGX distribution of microfacet normals.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ggx {
    /// Roughness: the GGX width parameter (glTF's `roughness^2`), clamped to [`MIN_ALPHA`].
    pub alpha: f64,
}

impl Ggx {
    /// A distribution of roughness `alpha` (clamped to at least [`MIN_ALPHA`]).
    pub fn new(alpha: f64) -> Self {
        Ggx { alpha: alpha.max(MIN_ALPHA) }
    }

    /// The microfacet normal density D(m), per steradian of m, normalised so that
    /// ∫ D(m) cos θm dωm = 1. Zero for m below the surface.
    pub fn d(&self, m: DVec3) -> f64 {
        let a2 = self.alpha * self.alpha;
        let t = (m.x * m.x + m.y * m.y) / a2 + m.z * m.z;
        let result = 1.0 / (std::f64::consts::PI * a2 * t * t);
        if result * m.z > 1e-20 { result } else { 0.0 }
    }

    /// Smith's monodirectional shadowing-masking G1(v, m) in [0, 1]: zero when v sees the
    /// back of m relative to the side of the macro-surface it lies on.
    pub fn smith_g1(&self, v: DVec3, m: DVec3) -> f64 {
        if v.dot(m) * v.z <= 0.0 {
            return 0.0;
        }
        let xy_alpha2 = self.alpha * self.alpha * (v.x * v.x + v.y * v.y);
        if xy_alpha2 == 0.0 {
            return 1.0;
        }
        let tan_alpha2 = xy_alpha2 / (v.z * v.z);
        2.0 / (1.0 + (1.0 + tan_alpha2).sqrt())
    }

    /// Mitsuba's separable Smith shadowing-masking G(wi, wo, m) = G1(wi, m) G1(wo, m).
    pub fn g(&self, wi: DVec3, wo: DVec3, m: DVec3) -> f64 {
        self.smith_g1(wi, m) * self.smith_g1(wo, m)
    }

    /// Samples a microfacet normal from the distribution of normals visible from `wi`
    /// (`wi.z > 0`; Heitz 2018, "Sampling the GGX Distribution of Visible Normals", with the
    /// concentric disc mapping Mitsuba also uses). Its density is [`Ggx::pdf_visible`].
    pub fn sample_visible(&self, wi: DVec3, u: DVec2) -> DVec3 {
        // Stretch the view direction to the configuration of a unit-roughness hemisphere.
        let vh = DVec3::new(self.alpha * wi.x, self.alpha * wi.y, wi.z).normalize();
        let len2 = vh.x * vh.x + vh.y * vh.y;
        let t1 = if len2 > 0.0 { DVec3::new(-vh.y, vh.x, 0.0) / len2.sqrt() } else { DVec3::X };
        let t2 = vh.cross(t1);
        // A point on the disc, warped to the projected visible half of the hemisphere.
        let p = concentric_disc(u);
        let s = 0.5 * (1.0 + vh.z);
        let py = (1.0 - s) * (1.0 - p.x * p.x).max(0.0).sqrt() + s * p.y;
        let nh = p.x * t1 + py * t2 + (1.0 - p.x * p.x - py * py).max(0.0).sqrt() * vh;
        // Unstretch.
        DVec3::new(self.alpha * nh.x, self.alpha * nh.y, nh.z.max(1e-12)).normalize()
    }

    /// Density of [`Ggx::sample_visible`], per steradian of m:
    /// G1(wi, m) |wi · m| D(m) / |cos θi|.
    pub fn pdf_visible(&self, wi: DVec3, m: DVec3) -> f64 {
        if wi.z == 0.0 {
            return 0.0;
        }
        self.smith_g1(wi, m) * wi.dot(m).abs() * self.d(m) / wi.z.abs()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::bsdf::chi2::Rng;

    /// Midpoint quadrature over the upper hemisphere with cosine spacing concentrated near
    /// the pole (cos = 1 - x^2): calls `f(m, solid angle of m's cell)`.
    fn hemisphere_quadrature(nt: usize, np: usize, mut f: impl FnMut(DVec3, f64)) {
        for i in 0..nt {
            let x = (i as f64 + 0.5) / nt as f64;
            let cos = 1.0 - x * x;
            let dcos = 2.0 * x / nt as f64;
            let sin = (1.0 - cos * cos).max(0.0).sqrt();
            for j in 0..np {
                let phi = (j as f64 + 0.5) / np as f64 * std::f64::consts::TAU;
                f(DVec3::new(sin * phi.cos(), sin * phi.sin(), cos), dcos * std::f64::consts::TAU / np as f64);
            }
        }
    }

    /// ∫ D(m) cos θm dωm = 1 and ∫ pdf_visible dωm = 1 (midpoint rule in (cos θ, φ), on a grid
    /// that resolves the lobe).
    #[test]
    fn normalisation() {
        for alpha in [0.05, 0.3, 0.8] {
            let wi = DVec3::new(0.6, 0.0, 0.8);
            let ggx = Ggx::new(alpha);
            let (mut sum_d, mut sum_v) = (0.0, 0.0);
            hemisphere_quadrature(4000, 256, |m, w| {
                sum_d += ggx.d(m) * m.z * w;
                sum_v += ggx.pdf_visible(wi, m) * w;
            });
            assert!((sum_d - 1.0).abs() < 2e-3, "alpha {alpha}: ∫D cos = {sum_d}");
            assert!((sum_v - 1.0).abs() < 2e-3, "alpha {alpha}: ∫pdf_visible = {sum_v}");
        }
    }

    /// The visible-normal sampler's mean of any function matches its density's: checked on
    /// the moments E[m] against the numerical integral.
    #[test]
    fn sample_visible_moments() {
        let mut rng = Rng::new(7);
        for alpha in [0.1, 0.5] {
            let ggx = Ggx::new(alpha);
            let wi = DVec3::new(0.8, 0.0, 0.6);
            let n = 200_000;
            let mut mean = DVec3::ZERO;
            for _ in 0..n {
                let m = ggx.sample_visible(wi, rng.next2());
                assert!(m.z > 0.0 && (m.length() - 1.0).abs() < 1e-9);
                mean += m;
            }
            mean /= n as f64;
            // Numerical E[m] under pdf_visible.
            let mut expect = DVec3::ZERO;
            hemisphere_quadrature(2000, 256, |m, w| expect += m * ggx.pdf_visible(wi, m) * w);
            assert!((mean - expect).abs().max_element() < 5e-3, "alpha {alpha}: {mean} vs {expect}");
        }
    }

    #[test]
    fn smith_g1_limits() {
        let ggx = Ggx::new(0.5);
        let n = DVec3::Z;
        assert_eq!(ggx.smith_g1(n, n), 1.0);
        // Back-facing microfacet: zero.
        assert_eq!(ggx.smith_g1(DVec3::new(0.6, 0.0, 0.8), DVec3::new(-0.8, 0.0, 0.6)), 0.0);
        // Decreasing toward grazing.
        let g = |c: f64| ggx.smith_g1(DVec3::new((1.0 - c * c).sqrt(), 0.0, c), n);
        assert!(g(0.9) > g(0.5) && g(0.5) > g(0.1) && g(0.1) > 0.0);
    }
}
