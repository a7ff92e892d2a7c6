//! `bsdf`: the scattering functions of the physically based `path` integrator, pure math in
//! a local shading frame (z is the shading normal), free of materials, textures and scenes.
//!
//! The equivalence target is Mitsuba 3 (3.9): each variant of [`Bsdf`] is one of Mitsuba's
//! BSDF plugins (`diffuse`, `conductor`/`roughconductor`, `dielectric`/`roughdielectric`,
//! `thindielectric`, `plastic`/`roughplastic`) in its RGB variants and radiance transport,
//! with the GGX distribution and visible-normal sampling, so the same BSDF written in
//! Mitsuba's XML has the same expected image. [`Bsdf::MetallicRoughness`] is glTF 2.0's
//! material model, which Mitsuba does not have.
//!
//! Conventions (Mitsuba's, with its `si.wi` called `wo` here): `wo` points toward the viewer
//! (the previous path vertex), `wi` toward the light (the next vertex), both away from the
//! surface. [`Bsdf::eval`] includes the cosine |cos θi|. Opaque BSDFs are one-sided like
//! Mitsuba's: they are black when `wo.z <= 0`; an integrator that wants two-sided surfaces
//! flips the frame toward `wo` first (Mitsuba's `twosided`).

mod conductor;
mod dielectric;
mod diffuse;
pub mod fresnel;
mod metallic_roughness;
pub mod microfacet;
mod plastic;

#[cfg(test)]
mod chi2;

use dielectric::Tints;
use glam::{DVec2, DVec3};

pub use fresnel::{fresnel_conductor, fresnel_dielectric};
pub use metallic_roughness::MetallicRoughnessBsdf;

/// An orthonormal shading frame; local z is the shading normal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// First tangent (local x).
    pub s: DVec3,
    /// Second tangent (local y), `n × s`.
    pub t: DVec3,
    /// Shading normal (local z).
    pub n: DVec3,
}

impl Frame {
    /// From a unit normal and a tangent hint (any vector not parallel to `n`; it is
    /// Gram-Schmidt orthogonalised against `n`). A hint parallel to `n` (or zero) falls back
    /// to an arbitrary tangent.
    pub fn new(n: DVec3, tangent_hint: DVec3) -> Self {
        let s = tangent_hint - n * n.dot(tangent_hint);
        let s = if s.length_squared() > 1e-20 { s.normalize() } else { n.any_orthonormal_vector() };
        Frame { s, t: n.cross(s), n }
    }

    /// World-space vector to this frame's local coordinates.
    pub fn to_local(&self, v: DVec3) -> DVec3 {
        DVec3::new(v.dot(self.s), v.dot(self.t), v.dot(self.n))
    }

    /// Local coordinates to world space.
    pub fn to_world(&self, v: DVec3) -> DVec3 {
        self.s * v.x + self.t * v.y + self.n * v.z
    }
}

/// One BSDF at one surface point. Directions are local, unit, pointing away from the surface
/// (wo toward the viewer / previous vertex, wi toward the light / next vertex). Radiance
/// transport only.
///
/// RGB quantities are linear reflectances/transmittances in [0, 1] unless stated; `alpha` is
/// the GGX roughness (the width of the slope distribution, glTF's `roughness^2`), where
/// `alpha == 0` selects the smooth (delta) form of the variants that have one.
#[derive(Clone, Debug)]
pub enum Bsdf {
    /// Lambertian reflection (Mitsuba's `diffuse`).
    Diffuse {
        /// Hemispherical reflectance (albedo).
        reflectance: DVec3,
    },
    /// Smooth (alpha == 0) or GGX-rough conductor, complex IOR per RGB channel, times `tint`
    /// (Mitsuba's specular_reflectance).
    Conductor {
        /// Real part of the complex IOR, relative to the exterior medium.
        eta: DVec3,
        /// Imaginary part (extinction coefficient) of the complex IOR.
        k: DVec3,
        /// GGX roughness; 0 for a perfect mirror.
        alpha: f64,
        /// Factor on the reflected light (Mitsuba's `specular_reflectance`).
        tint: DVec3,
    },
    /// Smooth (alpha == 0) or rough (Walter et al. 2007, GGX) dielectric interface; `eta` =
    /// interior IOR / exterior IOR; the side with local z > 0 is the exterior. `reflect_tint`
    /// and `transmit_tint` are Mitsuba's specular_reflectance/specular_transmittance.
    ///
    /// `eta == 1` is an index-matched interface that passes light straight through whatever
    /// `alpha` is (a delta lobe; Mitsuba refuses `roughdielectric` with equal IORs).
    Dielectric {
        /// Relative IOR, interior / exterior.
        eta: f64,
        /// GGX roughness; 0 for a smooth interface.
        alpha: f64,
        /// Factor on reflected light (Mitsuba's `specular_reflectance`).
        reflect_tint: DVec3,
        /// Factor on transmitted light (Mitsuba's `specular_transmittance`).
        transmit_tint: DVec3,
    },
    /// A thin slab (window pane): Mitsuba's thindielectric (straight-through transmission,
    /// internal reflections summed).
    ThinDielectric {
        /// Relative IOR of the slab material, slab / surrounding medium.
        eta: f64,
        /// Factor on reflected light (Mitsuba's `specular_reflectance`).
        reflect_tint: DVec3,
        /// Factor on transmitted light (Mitsuba's `specular_transmittance`).
        transmit_tint: DVec3,
    },
    /// Mitsuba's `plastic` (alpha == 0) / `roughplastic` (nonlinear = false): a dielectric
    /// coating with IOR `eta` over a Lambertian base `diffuse`.
    ///
    /// Mitsuba's `roughplastic` defaults to Beckmann; this is its `distribution = "ggx"`.
    Plastic {
        /// Reflectance of the Lambertian base under the coating.
        diffuse: DVec3,
        /// Relative IOR of the coating, coating / exterior.
        eta: f64,
        /// GGX roughness of the coating; 0 for a smooth coating.
        alpha: f64,
    },
    /// glTF 2.0 metallic-roughness exactly as the glTF 2.0 specification's Appendix B defines
    /// it (Schlick Fresnel, GGX with separable Smith G, `alpha = roughness^2`), with
    /// KHR_materials_ior (`ior`, F0 = ((ior-1)/(ior+1))^2, default 1.5),
    /// KHR_materials_specular (`specular`, `specular_color`: the dielectric Fresnel's F0
    /// `min(F0 · specular_color, 1) · specular` and F90 `specular`, RGB),
    /// KHR_materials_transmission (`transmission`: the dielectric's diffuse part becomes a
    /// GGX rough transmission with the base colour as tint, thin-walled as the extension's
    /// spec describes) and KHR_materials_clearcoat (`clearcoat`, `clearcoat_alpha`: a GGX
    /// layer with F0 0.04 on top that attenuates the base by 1 - clearcoat * Fresnel).
    ///
    /// The roughnesses are clamped to the GGX minimum 1e-4 (no delta lobes). The clear coat's
    /// Fresnel weight is the extension's `fresnel_coat`, Schlick at N·V.
    MetallicRoughness(MetallicRoughnessBsdf),
}

/// What `Bsdf::sample` returns.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BsdfSample {
    /// Sampled direction (local, unit).
    pub wi: DVec3,
    /// f * |cos(wi)| / pdf (RGB), the path throughput factor. For delta lobes: the lobe's
    /// value / its selection probability.
    pub weight: DVec3,
    /// Solid-angle pdf of wi (for a delta lobe: the probability of choosing that lobe; the
    /// integrator does not MIS delta lobes).
    pub pdf: f64,
    /// True when wi was produced by a delta (perfectly specular) lobe.
    pub delta: bool,
}

impl BsdfSample {
    /// A non-delta sample, `None` unless its pdf is positive and its weight finite.
    pub(crate) fn smooth(wi: DVec3, weight: DVec3, pdf: f64) -> Option<Self> {
        (pdf > 0.0 && pdf.is_finite() && weight.is_finite()).then_some(BsdfSample { wi, weight, pdf, delta: false })
    }

    /// A delta-lobe sample chosen with probability `pdf`.
    pub(crate) fn delta(wi: DVec3, weight: DVec3, pdf: f64) -> Option<Self> {
        (pdf > 0.0 && weight.is_finite()).then_some(BsdfSample { wi, weight, pdf, delta: true })
    }
}

impl Bsdf {
    /// f(wo, wi) * |cos wi| of the non-delta lobes (0 for delta-only BSDFs), RGB.
    pub fn eval(&self, wo: DVec3, wi: DVec3) -> DVec3 {
        match *self {
            Bsdf::Diffuse { reflectance } => diffuse::eval(reflectance, wo, wi),
            Bsdf::Conductor { eta, k, alpha, tint } => conductor::eval(eta, k, alpha, tint, wo, wi),
            Bsdf::Dielectric { eta, alpha, reflect_tint, transmit_tint } => {
                dielectric::eval(eta, alpha, Tints { reflect: reflect_tint, transmit: transmit_tint }, wo, wi)
            }
            Bsdf::ThinDielectric { .. } => DVec3::ZERO,
            Bsdf::Plastic { diffuse, eta, alpha } => plastic::eval(diffuse, eta, alpha, wo, wi),
            Bsdf::MetallicRoughness(m) => m.eval(wo, wi),
        }
    }

    /// Solid-angle pdf with which `sample` produces wi via its non-delta lobes.
    pub fn pdf(&self, wo: DVec3, wi: DVec3) -> f64 {
        match *self {
            Bsdf::Diffuse { .. } => diffuse::pdf(wo, wi),
            Bsdf::Conductor { alpha, .. } => conductor::pdf(alpha, wo, wi),
            Bsdf::Dielectric { eta, alpha, .. } => dielectric::pdf(eta, alpha, wo, wi),
            Bsdf::ThinDielectric { .. } => 0.0,
            Bsdf::Plastic { diffuse, eta, alpha } => plastic::pdf(diffuse, eta, alpha, wo, wi),
            Bsdf::MetallicRoughness(m) => m.pdf(wo, wi),
        }
    }

    /// Samples wi with one uniform `u_lobe` for lobe choice and `u` for the direction.
    /// `None` when the sample is invalid (below the surface, zero pdf).
    pub fn sample(&self, wo: DVec3, u_lobe: f64, u: DVec2) -> Option<BsdfSample> {
        match *self {
            Bsdf::Diffuse { reflectance } => diffuse::sample(reflectance, wo, u),
            Bsdf::Conductor { eta, k, alpha, tint } => conductor::sample(eta, k, alpha, tint, wo, u),
            Bsdf::Dielectric { eta, alpha, reflect_tint, transmit_tint } => {
                dielectric::sample(eta, alpha, Tints { reflect: reflect_tint, transmit: transmit_tint }, wo, u_lobe, u)
            }
            Bsdf::ThinDielectric { eta, reflect_tint, transmit_tint } => {
                dielectric::sample_thin(eta, Tints { reflect: reflect_tint, transmit: transmit_tint }, wo, u_lobe)
            }
            Bsdf::Plastic { diffuse, eta, alpha } => plastic::sample(diffuse, eta, alpha, wo, u_lobe, u),
            Bsdf::MetallicRoughness(m) => m.sample(wo, u_lobe, u),
        }
    }

    /// True when every lobe is a delta lobe (no light sampling helps).
    pub fn is_delta(&self) -> bool {
        match *self {
            Bsdf::Diffuse { .. } | Bsdf::Plastic { .. } | Bsdf::MetallicRoughness(_) => false,
            Bsdf::Conductor { alpha, .. } => alpha == 0.0,
            Bsdf::Dielectric { eta, alpha, .. } => dielectric::is_smooth(eta, alpha),
            Bsdf::ThinDielectric { .. } => true,
        }
    }

    /// True when it has any non-delta lobe.
    pub fn has_smooth_lobe(&self) -> bool {
        !self.is_delta()
    }

    /// A reflectance estimate for AOVs/denoising albedo (RGB in \[0,1\]): the diffuse colour,
    /// the conductor's normal-incidence Fresnel times tint, 1 for dielectrics, the base colour
    /// of plastics and glTF materials.
    pub fn albedo(&self) -> DVec3 {
        let albedo = match *self {
            Bsdf::Diffuse { reflectance } => reflectance,
            Bsdf::Conductor { eta, k, tint, .. } => fresnel_conductor(1.0, eta, k) * tint,
            Bsdf::Dielectric { .. } | Bsdf::ThinDielectric { .. } => DVec3::ONE,
            Bsdf::Plastic { diffuse, .. } => diffuse,
            Bsdf::MetallicRoughness(m) => m.base_color,
        };
        let albedo = albedo.clamp(DVec3::ZERO, DVec3::ONE);
        if albedo.is_finite() { albedo } else { DVec3::ZERO }
    }
}

/// Cosine-weighted hemisphere sample (Mitsuba's `square_to_cosine_hemisphere`: the concentric
/// disc lifted to the hemisphere); its density is `cos θ / π`.
pub(crate) fn cosine_hemisphere(u: DVec2) -> DVec3 {
    let p = crate::render::sampling::concentric_disc(u);
    let z = (1.0 - p.length_squared()).max(0.0).sqrt();
    DVec3::new(p.x, p.y, z)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::metals::metal;

    #[test]
    fn frame_round_trip() {
        let n = DVec3::new(1.0, 2.0, 3.0).normalize();
        let frame = Frame::new(n, DVec3::X);
        assert!(frame.s.dot(n).abs() < 1e-12 && frame.t.dot(n).abs() < 1e-12 && frame.s.dot(frame.t).abs() < 1e-12);
        assert!((frame.s.length() - 1.0).abs() < 1e-12 && (frame.t.length() - 1.0).abs() < 1e-12);
        // Right-handed: s × t = n.
        assert!((frame.s.cross(frame.t) - n).length() < 1e-12);
        assert!((frame.to_local(n) - DVec3::Z).length() < 1e-12);
        let v = DVec3::new(-0.3, 0.5, 0.7);
        assert!((frame.to_world(frame.to_local(v)) - v).length() < 1e-12);
        // A hint parallel to n still gives a frame.
        let f = Frame::new(DVec3::Z, DVec3::Z * 2.0);
        assert!(f.s.dot(DVec3::Z).abs() < 1e-12 && (f.s.length() - 1.0).abs() < 1e-12);
    }

    /// Every variant at extreme parameters (alpha 1e-4, eta 1, black and white colours)
    /// returns finite eval, pdf and samples for random, grazing (cos 1e-9), tangent and
    /// below-surface directions.
    #[test]
    fn finite_everywhere() {
        use chi2::Rng;
        let (eta_au, k_au) = metal("Au").unwrap();
        let mut bsdfs = vec![Bsdf::Diffuse { reflectance: DVec3::ONE }, Bsdf::Diffuse { reflectance: DVec3::ZERO }];
        for alpha in [0.0, 1e-4, 0.3, 1.0] {
            bsdfs.push(Bsdf::Conductor { eta: eta_au, k: k_au, alpha, tint: DVec3::ONE });
            bsdfs.push(Bsdf::Conductor { eta: DVec3::ZERO, k: DVec3::ZERO, alpha, tint: DVec3::ONE });
            for eta in [1.0, 1.5, 1.0 / 1.5, 3.0] {
                bsdfs.push(Bsdf::Dielectric { eta, alpha, reflect_tint: DVec3::ONE, transmit_tint: DVec3::ONE });
                bsdfs.push(Bsdf::Plastic { diffuse: DVec3::splat(0.5), eta, alpha });
                for (metallic, transmission, clearcoat) in [(0.0, 0.0, 0.0), (1.0, 0.0, 1.0), (0.0, 1.0, 1.0)] {
                    bsdfs.push(Bsdf::MetallicRoughness(MetallicRoughnessBsdf {
                        base_color: DVec3::new(1.0, 0.5, 0.0),
                        metallic,
                        alpha,
                        ior: eta,
                        specular: 1.0,
                        specular_color: DVec3::ONE,
                        transmission,
                        clearcoat,
                        clearcoat_alpha: alpha,
                    }));
                }
            }
            bsdfs.push(Bsdf::Plastic { diffuse: DVec3::ZERO, eta: 1.5, alpha });
            bsdfs.push(Bsdf::Plastic { diffuse: DVec3::ONE, eta: 1.0, alpha });
        }
        for eta in [1.0, 1.5] {
            bsdfs.push(Bsdf::ThinDielectric { eta, reflect_tint: DVec3::ONE, transmit_tint: DVec3::ONE });
        }
        let mut rng = Rng::new(99);
        let mut directions = vec![DVec3::Z, -DVec3::Z, DVec3::X, DVec3::new(0.6, -0.8, 0.0)];
        for cos in [1e-9, -1e-9, 1e-5, 0.999_999] {
            directions.push(chi2::wo_at(cos));
        }
        for _ in 0..40 {
            let u = rng.next2();
            let cos = 1.0 - 2.0 * u.x;
            let sin = (1.0 - cos * cos).sqrt();
            directions.push(DVec3::new(sin * (6.3 * u.y).cos(), sin * (6.3 * u.y).sin(), cos));
        }
        for bsdf in &bsdfs {
            assert!(bsdf.albedo().is_finite());
            for &wo in &directions {
                for &wi in &directions {
                    let (f, p) = (bsdf.eval(wo, wi), bsdf.pdf(wo, wi));
                    assert!(f.is_finite() && f.min_element() >= 0.0, "{bsdf:?} eval({wo}, {wi}) = {f}");
                    assert!(p.is_finite() && p >= 0.0, "{bsdf:?} pdf({wo}, {wi}) = {p}");
                }
                for _ in 0..20 {
                    if let Some(s) = bsdf.sample(wo, rng.next(), rng.next2()) {
                        assert!(
                            s.wi.is_finite() && s.weight.is_finite() && s.pdf.is_finite() && s.pdf > 0.0,
                            "{bsdf:?} wo {wo}: {s:?}"
                        );
                        assert!(s.weight.min_element() >= 0.0, "{bsdf:?} wo {wo}: {s:?}");
                    }
                }
            }
        }
    }

    #[test]
    fn albedo_values() {
        assert_eq!(Bsdf::Diffuse { reflectance: DVec3::splat(0.3) }.albedo(), DVec3::splat(0.3));
        let (eta, k) = metal("Au").unwrap();
        let gold = Bsdf::Conductor { eta, k, alpha: 0.1, tint: DVec3::ONE };
        assert!((gold.albedo() - fresnel_conductor(1.0, eta, k)).length() < 1e-12);
        let glass = Bsdf::Dielectric { eta: 1.5, alpha: 0.0, reflect_tint: DVec3::ONE, transmit_tint: DVec3::ONE };
        assert_eq!(glass.albedo(), DVec3::ONE);
        assert!(glass.is_delta() && !glass.has_smooth_lobe());
        assert!(!gold.is_delta() && gold.has_smooth_lobe());
        let plastic = Bsdf::Plastic { diffuse: DVec3::new(0.5, 0.2, 0.1), eta: 1.5, alpha: 0.0 };
        assert!(!plastic.is_delta() && plastic.has_smooth_lobe());
    }
}
