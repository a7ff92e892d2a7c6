//! The path integrator's view of a material: how the surface scatters light at one hit, as a
//! sum of at most [`MAX_LOBES`] weighted lobes (BSDFs, a delta mirror, a delta pass-through),
//! built from whichever surface model the material was written in.
//!
//! Readings (documented in `docs/scene-format.md`, "Materials under the path integrator"):
//! - `bsdf` tables are Mitsuba 3's BSDFs of the same name;
//! - glTF metallic-roughness is glTF 2.0's appendix B model; alpha blending is stochastic
//!   coverage (light passes straight through with probability 1 - alpha);
//! - a POV-Ray finish is a diffuse albedo `color` (0 unless `diffuse` is positive), plus a mirror of
//!   reflectivity `reflection` (the maximum of min and max), plus, when `filter` or
//!   `transmit` let light through, a smooth dielectric of the interior's `ior` tinted by
//!   `color * filter + transmit`; the opaque part is scaled by `1 - filter - transmit` and
//!   the diffuse part by `1 - reflection`, so no POV-Ray finish creates energy. Phong and
//!   specular highlights are the lights' reflections in Whitted tracing and have no extra
//!   lobe: under `path` they are what the mirror lobe (or nothing) reflects;
//! - a layered texture (POV-Ray's `texture { } texture { }`) sums its layers' readings as
//!   POV-Ray weighs them: each layer's opaque part is seen through the filter of the layers
//!   above, and what passes every layer is the dielectric, tinted by the product of filters
//!   (one diffuse lobe, one mirror, one dielectric in all; layer normals are ignored, as
//!   every normal pattern under `path`);
//! - OBJ/MTL: `Kd` (times `map_Kd`) diffuse, `Ks` with `Ns` a plastic-like glossy lobe
//!   (roughness from Phong's exponent), illum 3/5-7 a mirror, `d` < 1 a dielectric of `Ni`.

use glam::{DVec2, DVec3};

use crate::color::Rgb;
use crate::material::normal::NormalField;
use crate::material::{AlphaMode, Finish, Layer, Material, MetallicRoughness, Mtl, Physical, Scattering, SurfaceModel};
use crate::render::bsdf::{Bsdf, BsdfSample, MetallicRoughnessBsdf};

/// At most this many lobes at one hit.
pub const MAX_LOBES: usize = 3;

/// One part of a surface's scattering.
#[derive(Clone, Debug)]
pub enum Lobe {
    /// A BSDF in the shading frame. `two_sided` BSDFs scatter the same on both sides: they
    /// are evaluated with the frame turned toward the viewer. A one-sided one (a dielectric
    /// interface) sees the outward normal as its exterior.
    Bsdf {
        /// The BSDF.
        bsdf: Bsdf,
        /// True for reflection models that apply on either side.
        two_sided: bool,
    },
    /// Perfect mirror reflection.
    Mirror,
    /// Light passing straight through, unchanged in direction (alpha coverage).
    PassThrough,
}

/// The scattering at one hit: `weight[i] * lobe[i]` summed.
#[derive(Clone, Debug)]
pub struct Scatter {
    lobes: [Option<(DVec3, Lobe)>; MAX_LOBES],
    /// Probability of sampling each lobe (sums to 1 over the present lobes).
    probability: [f64; MAX_LOBES],
}

/// Surface data at a hit that the materials read.
#[derive(Clone, Copy, Debug)]
pub struct SurfacePoint {
    /// Texture coordinates.
    pub uv: DVec2,
    /// The point in the object's space (pigment patterns are evaluated there).
    pub object_point: DVec3,
}

/// Luminance of linear Rec. 709 RGB.
pub fn luminance(c: DVec3) -> f64 {
    0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z
}

impl Scatter {
    /// The scattering from `lobes` (weight, lobe); lobes of zero weight are dropped. Each is
    /// sampled in proportion to its weight's luminance times its albedo's.
    pub fn new(lobes: impl IntoIterator<Item = (DVec3, Lobe)>) -> Self {
        let mut out = Self { lobes: [None, None, None], probability: [0.0; MAX_LOBES] };
        let mut count = 0;
        for (weight, lobe) in lobes {
            if count < MAX_LOBES && weight.max_element() > 0.0 {
                out.lobes[count] = Some((weight, lobe));
                count += 1;
            }
        }
        if count == 1 {
            // Most surfaces: no choice to weigh, so no albedo to estimate.
            out.probability[0] = 1.0;
            return out;
        }
        for (probability, (weight, lobe)) in out.probability.iter_mut().zip(out.lobes.iter().flatten()) {
            let albedo = match lobe {
                Lobe::Bsdf { bsdf, .. } => luminance(bsdf.albedo()).max(0.05),
                Lobe::Mirror | Lobe::PassThrough => 1.0,
            };
            *probability = luminance(*weight).max(1e-6) * albedo;
        }
        let total: f64 = out.probability.iter().sum();
        if total > 0.0 {
            for p in &mut out.probability {
                *p /= total;
            }
        }
        out
    }

    /// True when nothing scatters (a black surface): the path ends.
    pub fn is_black(&self) -> bool {
        self.lobes.iter().all(Option::is_none)
    }

    /// True when some lobe is not a delta lobe, so that light sampling can help.
    pub fn has_smooth_lobe(&self) -> bool {
        self.present().any(|(_, _, lobe)| matches!(lobe, Lobe::Bsdf { bsdf, .. } if bsdf.has_smooth_lobe()))
    }

    /// Reflectance estimate for the albedo AOV.
    pub fn albedo(&self) -> DVec3 {
        self.present()
            .map(|(_, weight, lobe)| match lobe {
                Lobe::Bsdf { bsdf, .. } => weight * bsdf.albedo(),
                Lobe::Mirror | Lobe::PassThrough => weight,
            })
            .sum::<DVec3>()
            .min(DVec3::ONE)
    }

    /// The lobes with their weights, in the order they were given.
    pub fn lobes(&self) -> impl Iterator<Item = (DVec3, &Lobe)> {
        self.lobes.iter().filter_map(|l| l.as_ref().map(|(w, lobe)| (*w, lobe)))
    }

    fn present(&self) -> impl Iterator<Item = (f64, DVec3, &Lobe)> {
        self.lobes.iter().zip(self.probability).filter_map(|(l, p)| l.as_ref().map(|(w, lobe)| (p, *w, lobe)))
    }

    /// The non-delta lobes as (selection probability, weight, BSDF, wo, wi), the directions
    /// oriented for the lobe's sidedness.
    fn smooth(&self, wo: DVec3, wi: DVec3) -> impl Iterator<Item = (f64, DVec3, &Bsdf, DVec3, DVec3)> {
        self.present().filter_map(move |(p, weight, lobe)| match lobe {
            Lobe::Bsdf { bsdf, two_sided } => {
                let (wo, wi) = oriented(*two_sided, wo, wi);
                Some((p, weight, bsdf, wo, wi))
            }
            Lobe::Mirror | Lobe::PassThrough => None,
        })
    }

    /// f * |cos wi| of the non-delta lobes, local directions.
    pub fn eval(&self, wo: DVec3, wi: DVec3) -> DVec3 {
        self.smooth(wo, wi).map(|(_, weight, bsdf, wo, wi)| weight * bsdf.eval(wo, wi)).sum()
    }

    /// Solid-angle pdf of `sample` producing wi through a non-delta lobe.
    pub fn pdf(&self, wo: DVec3, wi: DVec3) -> f64 {
        self.smooth(wo, wi).map(|(p, _, bsdf, wo, wi)| p * bsdf.pdf(wo, wi)).sum()
    }

    /// Samples a direction: a lobe by `u_lobe`, then a direction from it by `u_dir`.
    pub fn sample(&self, wo: DVec3, u_lobe: f64, u_dir: DVec2) -> Option<BsdfSample> {
        let mut chosen = None;
        let mut cumulative = 0.0;
        let mut u = u_lobe;
        for (p, weight, lobe) in self.present() {
            cumulative += p;
            chosen = Some((p, weight, lobe));
            if u_lobe < cumulative {
                // Rescale the lobe's share of the uniform for the BSDF's own lobe choice.
                u = ((u_lobe - (cumulative - p)) / p).clamp(0.0, 1.0 - f64::EPSILON);
                break;
            }
        }
        let (p, weight, lobe) = chosen?;
        match lobe {
            Lobe::Mirror => {
                Some(BsdfSample { wi: DVec3::new(-wo.x, -wo.y, wo.z), weight: weight / p, pdf: p, delta: true })
            }
            Lobe::PassThrough => Some(BsdfSample { wi: -wo, weight: weight / p, pdf: p, delta: true }),
            Lobe::Bsdf { bsdf, two_sided } => {
                let flip = *two_sided && wo.z < 0.0;
                let local_wo = if flip { flip_z(wo) } else { wo };
                let mut s = bsdf.sample(local_wo, u, u_dir)?;
                if flip {
                    s.wi = flip_z(s.wi);
                }
                if s.delta {
                    s.weight *= weight / p;
                    s.pdf *= p;
                    return Some(s);
                }
                // A smooth direction could have come from any smooth lobe: weigh by all.
                let pdf = self.pdf(wo, s.wi);
                let value = self.eval(wo, s.wi);
                (pdf > 0.0).then(|| BsdfSample { wi: s.wi, weight: value / pdf, pdf, delta: false })
            }
        }
    }
}

fn flip_z(v: DVec3) -> DVec3 {
    DVec3::new(v.x, v.y, -v.z)
}

/// The directions a two-sided lobe sees: the frame turned toward `wo`.
fn oriented(two_sided: bool, wo: DVec3, wi: DVec3) -> (DVec3, DVec3) {
    if two_sided && wo.z < 0.0 { (flip_z(wo), flip_z(wi)) } else { (wo, wi) }
}

/// A material as the path integrator reads it: what it looks up per hit.
#[derive(Clone, Debug)]
pub struct PathMaterial {
    material: Material,
    /// The emitted radiance when it is the same at every point (see
    /// [`PathMaterial::uniform_emission`]).
    uniform_emission: Option<DVec3>,
    /// See [`PathMaterial::encloses_medium`].
    encloses_medium: bool,
    /// Beer-Lambert absorption of the interior, per scene unit (linear RGB).
    absorption: DVec3,
}

/// What a hit needs to know besides the scattering: the surface colour (for emission).
pub struct Shaded {
    /// How the surface scatters.
    pub scatter: Scatter,
    /// Emitted radiance W/(m^2 sr), linear RGB, on the emitting side.
    pub emitted: DVec3,
}

fn texel(texture: &Option<crate::texture::TextureRef>, uv: DVec2) -> glam::Vec4 {
    // Footprint 0: the full-resolution level, bilinear (Mitsuba's bitmap textures).
    texture.as_ref().map_or(glam::Vec4::ONE, |t| t.sample(uv, 0.0))
}

fn rgb_of(v: glam::Vec4) -> DVec3 {
    v.truncate().as_dvec3()
}

impl PathMaterial {
    /// The path integrator's view of `material`.
    pub fn new(material: &Material) -> Self {
        // Light that crosses a refracting interface enters (or leaves) the interior; thin
        // sheets and glTF's thin-walled transmission have no inside to enter.
        let encloses_medium = match &material.surface {
            SurfaceModel::Physical(p) => !matches!(p.scattering, Scattering::ThinDielectric { .. }),
            SurfaceModel::MetallicRoughness(_) => false,
            SurfaceModel::Finish(_) | SurfaceModel::Layered(_) | SurfaceModel::Mtl(_) => true,
        };
        let absorption = if encloses_medium { material.interior.absorption_coefficient() } else { DVec3::ZERO };
        let mut path_material =
            Self { material: material.clone(), uniform_emission: None, encloses_medium, absorption };
        let e = &material.emission;
        let patterned = match &material.surface {
            SurfaceModel::Finish(f) => f.pigment.is_some(),
            SurfaceModel::Layered(_) => true,
            _ => false,
        };
        let uniform_color = !patterned && !material.is_textured();
        if e.texture.is_none() && (e.times_color.0 == DVec3::ZERO || uniform_color) {
            let anywhere = SurfacePoint { uv: DVec2::ZERO, object_point: DVec3::ZERO };
            path_material.uniform_emission = Some(path_material.emitted(&anywhere));
        }
        path_material
    }

    /// The normal pattern that tilts the shading normal, when the material has one (a
    /// layered texture's top layer's).
    pub fn normal_pattern(&self) -> Option<&NormalField> {
        match &self.material.surface {
            SurfaceModel::Finish(f) => f.normal.as_deref(),
            SurfaceModel::Layered(layers) => layers.last()?.finish.normal.as_deref(),
            _ => None,
        }
    }

    /// True when shading reads the surface's uv (an image drives some parameter).
    pub fn is_textured(&self) -> bool {
        self.material.is_textured()
    }

    /// True when a path that crosses this surface enters or leaves the object's interior (a
    /// refracting interface: a dielectric, a POV-Ray finish that lets light through, a
    /// dissolved MTL material), so that the interior's absorption applies inside.
    pub fn encloses_medium(&self) -> bool {
        self.encloses_medium
    }

    /// Beer-Lambert absorption of the interior, per scene unit (linear RGB; zero for
    /// materials that enclose no medium).
    pub fn absorption(&self) -> DVec3 {
        self.absorption
    }

    /// True when a surface of this material may emit.
    pub fn can_emit(&self) -> bool {
        self.material.emission.can_emit()
    }

    /// The emitted radiance, W/(m^2 sr), when it is the same all over the surface (no
    /// emission texture and no pattern or texture in a colour it is a multiple of): emitter
    /// hits then need no surface point.
    pub fn uniform_emission(&self) -> Option<DVec3> {
        self.uniform_emission
    }

    /// True when the surface emits from both sides.
    pub fn emits_both_sides(&self) -> bool {
        self.material.emission.two_sided
    }

    /// The emitted radiance where the surface colour is `color` (before the emission texture).
    /// Radiance is not negative: a negative component (POV-Ray's darkening `emission`, which
    /// classic reads as written) emits nothing here.
    fn emission(&self, color: DVec3, uv: DVec2) -> DVec3 {
        let e = &self.material.emission;
        if !e.can_emit() {
            return DVec3::ZERO;
        }
        e.radiance_at(Rgb(color), Rgb(rgb_of(texel(&e.texture, uv)))).0.max(DVec3::ZERO)
    }

    /// Emitted radiance alone at `point` (no scattering built), for emitter hits.
    pub fn emitted(&self, point: &SurfacePoint) -> DVec3 {
        if !self.can_emit() {
            return DVec3::ZERO;
        }
        if let SurfaceModel::Layered(layers) = &self.material.surface {
            return layered_scatter(layers, point, self.material.interior.ior).emitted.max(DVec3::ZERO);
        }
        self.emission(self.surface_color(point).0, point.uv)
    }

    /// The surface colour at `point`, and the finish with a pigment pattern's filter and
    /// transmit there (borrowed when the material has no pattern).
    fn surface_color(&self, point: &SurfacePoint) -> (DVec3, Option<Finish>) {
        let uv = point.uv;
        let color = match &self.material.surface {
            SurfaceModel::Finish(f) => return layer_color(f, point),
            SurfaceModel::MetallicRoughness(m) => m.finish.color.0 * rgb_of(texel(&m.finish.texture, uv)),
            SurfaceModel::Mtl(m) => m.kd.unwrap_or(Rgb::WHITE).0 * rgb_of(texel(&m.map_kd, uv)),
            SurfaceModel::Physical(p) => p.color.0 * rgb_of(texel(&p.texture, uv)),
            SurfaceModel::Layered(layers) => match layers.last() {
                Some(top) => return layer_color(&top.finish, point),
                None => DVec3::ZERO,
            },
        };
        (color, None)
    }

    /// The scattering and emission at `point`.
    pub fn shade(&self, point: &SurfacePoint) -> Shaded {
        if let SurfaceModel::Layered(layers) = &self.material.surface {
            let shaded = layered_scatter(layers, point, self.material.interior.ior);
            return Shaded { emitted: shaded.emitted.max(DVec3::ZERO), ..shaded };
        }
        let uv = point.uv;
        let (color, patterned) = self.surface_color(point);
        let scatter = match &self.material.surface {
            SurfaceModel::Finish(f) => {
                finish_scatter(patterned.as_ref().unwrap_or(f), color, self.material.interior.ior)
            }
            SurfaceModel::MetallicRoughness(m) => metallic_roughness_scatter(m, color, uv),
            SurfaceModel::Mtl(m) => mtl_scatter(m, color),
            SurfaceModel::Physical(p) => physical_scatter(p, color),
            SurfaceModel::Layered(_) => unreachable!("layered surfaces return above"),
        };
        Shaded { scatter, emitted: self.emission(color, uv) }
    }
}

fn diffuse(reflectance: DVec3) -> Lobe {
    Lobe::Bsdf { bsdf: Bsdf::Diffuse { reflectance }, two_sided: true }
}

fn smooth_dielectric(ior: f64, transmit_tint: DVec3) -> Lobe {
    Lobe::Bsdf {
        bsdf: Bsdf::Dielectric { eta: ior, alpha: 0.0, reflect_tint: DVec3::ONE, transmit_tint },
        two_sided: false,
    }
}

fn finish_scatter(f: &Finish, color: DVec3, ior: f64) -> Scatter {
    stacked_scatter(std::iter::once((f, color)), ior)
}

/// A stack of POV-Ray finishes, top first, each with its colour at the hit, as one diffuse
/// lobe, one mirror and one pass-through: each layer's opaque part is seen through the
/// filter (`colour * filter + transmit`) of the layers above it, as POV-Ray weighs layers,
/// and what passes every layer is a dielectric of the interior's `ior` tinted by the
/// product of the filters. One layer is [`finish_scatter`]'s reading.
fn stacked_scatter<'a>(layers: impl Iterator<Item = (&'a Finish, DVec3)>, ior: f64) -> Scatter {
    let (mut diffuse_weight, mut mirror_weight) = (DVec3::ZERO, DVec3::ZERO);
    // What the layers so far let through: tinted, and as a fraction of the light.
    let (mut transmitted, mut share) = (DVec3::ONE, 1.0);
    for (f, color) in layers {
        let opacity = (1.0 - f.filter - f.transmit).clamp(0.0, 1.0);
        let mirror = f.reflection.min.0.max(f.reflection.max.0).clamp(DVec3::ZERO, DVec3::ONE);
        let albedo = if f.diffuse > 0.0 { color.clamp(DVec3::ZERO, DVec3::ONE) } else { DVec3::ZERO };
        diffuse_weight += transmitted * opacity * (DVec3::ONE - mirror) * albedo;
        mirror_weight += transmitted * opacity * mirror;
        transmitted *= f.filter * color + DVec3::splat(f.transmit);
        share *= 1.0 - opacity;
    }
    // The transparent share is a dielectric whose transmission carries the filters' tint.
    let through = (share > 0.0 && transmitted.max_element() > 0.0)
        .then(|| (DVec3::splat(share), smooth_dielectric(ior, (transmitted / share).min(DVec3::ONE))));
    Scatter::new([(diffuse_weight, diffuse(DVec3::ONE)), (mirror_weight, Lobe::Mirror)].into_iter().chain(through))
}

/// The colour of one layer at `point`, and its finish with a pigment pattern's filter and
/// transmit there when it has one.
fn layer_color(f: &Finish, point: &SurfacePoint) -> (DVec3, Option<Finish>) {
    match &f.pigment {
        Some(p) => {
            let c = p.at(point.object_point);
            (c.rgb, Some(Finish { filter: c.filter, transmit: c.transmit, ..f.clone() }))
        }
        None => (f.color.0 * rgb_of(texel(&f.texture, point.uv)), None),
    }
}

/// A layered texture (`layers`, bottom first) read by [`stacked_scatter`], with each layer's
/// emission times its colour seen through the layers above.
fn layered_scatter(layers: &[Layer], point: &SurfacePoint, ior: f64) -> Shaded {
    let looked_up: Vec<(DVec3, Option<Finish>)> = layers.iter().rev().map(|l| layer_color(&l.finish, point)).collect();
    let finishes = layers
        .iter()
        .rev()
        .zip(&looked_up)
        .map(|(l, (color, patterned))| (patterned.as_ref().unwrap_or(&l.finish), *color));
    let scatter = stacked_scatter(finishes.clone(), ior);
    let mut emitted = DVec3::ZERO;
    let mut transmitted = DVec3::ONE;
    for ((f, color), layer) in finishes.zip(layers.iter().rev()) {
        emitted += transmitted * layer.emission.0 * color;
        transmitted *= f.filter * color + DVec3::splat(f.transmit);
    }
    Shaded { scatter, emitted }
}

fn metallic_roughness_scatter(m: &MetallicRoughness, base_color: DVec3, uv: DVec2) -> Scatter {
    let at = m.at(uv, 0.0);
    let bsdf = Bsdf::MetallicRoughness(MetallicRoughnessBsdf {
        base_color: base_color.clamp(DVec3::ZERO, DVec3::ONE),
        metallic: at.metallic.clamp(0.0, 1.0),
        alpha: (at.roughness * at.roughness).clamp(0.0, 1.0),
        ior: m.ior,
        specular: at.specular.clamp(0.0, 1.0),
        specular_color: at.specular_color.max(DVec3::ZERO),
        transmission: at.transmission.clamp(0.0, 1.0),
        clearcoat: at.clearcoat.clamp(0.0, 1.0),
        clearcoat_alpha: (at.clearcoat_roughness * at.clearcoat_roughness).clamp(0.0, 1.0),
    });
    let coverage = match m.alpha_mode {
        AlphaMode::Blend => m.alpha.clamp(0.0, 1.0),
        AlphaMode::Opaque | AlphaMode::Mask { .. } => 1.0,
    };
    Scatter::new([
        (DVec3::splat(coverage), Lobe::Bsdf { bsdf, two_sided: true }),
        (DVec3::splat(1.0 - coverage), Lobe::PassThrough),
    ])
}

fn mtl_scatter(m: &Mtl, kd: DVec3) -> Scatter {
    let ks = m.ks.unwrap_or(Rgb::BLACK).0.clamp(DVec3::ZERO, DVec3::ONE);
    let dissolve = m.d.unwrap_or(1.0).clamp(0.0, 1.0);
    let mirror = matches!(m.illum.unwrap_or(2), 3 | 5..=7);
    // Phong's exponent n matches GGX alpha = sqrt(2 / (n + 2)) (Walter et al. 2007).
    let alpha = (2.0 / (m.ns.unwrap_or(10.0).max(0.0) + 2.0)).sqrt();
    let glossy = if ks.max_element() > 0.0 && !mirror {
        let bsdf = Bsdf::Conductor { eta: DVec3::ZERO, k: DVec3::splat(1e4), alpha, tint: ks };
        Some((DVec3::splat(dissolve), Lobe::Bsdf { bsdf, two_sided: true }))
    } else {
        None
    };
    let ior = m.ni.filter(|n| n.is_finite() && *n > 0.0).unwrap_or(1.0);
    let kd = kd.clamp(DVec3::ZERO, DVec3::ONE) * (DVec3::ONE - ks);
    Scatter::new(
        [
            (dissolve * kd, diffuse(DVec3::ONE)),
            (if mirror { dissolve * ks } else { DVec3::ZERO }, Lobe::Mirror),
            (DVec3::splat(1.0 - dissolve), smooth_dielectric(ior, DVec3::ONE)),
        ]
        .into_iter()
        .chain(glossy),
    )
}

fn physical_scatter(p: &Physical, color: DVec3) -> Scatter {
    let bsdf = match p.scattering {
        Scattering::Diffuse => Bsdf::Diffuse { reflectance: color.clamp(DVec3::ZERO, DVec3::ONE) },
        Scattering::Conductor { eta, k, alpha } => Bsdf::Conductor { eta: eta.0, k: k.0, alpha, tint: color },
        Scattering::Dielectric { ior, alpha } => {
            Bsdf::Dielectric { eta: ior, alpha, reflect_tint: DVec3::ONE, transmit_tint: color }
        }
        Scattering::ThinDielectric { ior } => {
            Bsdf::ThinDielectric { eta: ior, reflect_tint: DVec3::ONE, transmit_tint: color }
        }
        Scattering::Plastic { ior, alpha } => {
            Bsdf::Plastic { diffuse: color.clamp(DVec3::ZERO, DVec3::ONE), eta: ior, alpha }
        }
    };
    let two_sided = !matches!(p.scattering, Scattering::Dielectric { .. });
    Scatter::new([(DVec3::ONE, Lobe::Bsdf { bsdf, two_sided })])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_pigment_pattern_gives_the_albedo_and_transmission_at_the_object_point() {
        let spec: crate::material::MaterialSpec = toml::from_str(
            "diffuse = 0.7\npigment = { pattern = \"checker\", colors = [[1, 0, 0], { color = [0, 0, 1], transmit = 0.5 }] }",
        )
        .unwrap();
        let material = PathMaterial::new(&spec.to_material());
        let at = |x: f64| material.shade(&SurfacePoint { uv: DVec2::ZERO, object_point: DVec3::new(x, 0.5, -0.5) });
        // POV-Ray point (0.5, 0.5, 0.5): an even cell, the first colour, opaque: one diffuse lobe.
        let red = at(0.5).scatter;
        let weights: Vec<DVec3> = red.lobes().map(|(w, _)| w).collect();
        assert_eq!(weights, [DVec3::new(1.0, 0.0, 0.0)]);
        // (1.5, 0.5, 0.5): odd, the second colour; transmit 0.5 halves the diffuse lobe and
        // adds a transmitting one of weight 0.5.
        let blue = at(1.5).scatter;
        let weights: Vec<DVec3> = blue.lobes().map(|(w, _)| w).collect();
        assert_eq!(weights, [DVec3::new(0.0, 0.0, 0.5), DVec3::splat(0.5)]);
    }

    /// glTF's extensions under `path`: thin-walled transmission sends light through the back,
    /// times its texture's red channel; the clear coat's strength is times its texture's red,
    /// its roughness times its texture's green.
    #[test]
    fn gltf_extensions_and_their_textures_reach_the_bsdf() {
        use crate::texture::{ColorSpace, Texture, TextureRef};
        let texel_alpha = |r: u8, g: u8, a: u8| {
            let mut t = TextureRef::new("t.png");
            t.texture = Some(std::sync::Arc::new(Texture::from_rgba8(1, 1, vec![[r, g, 0, a]], ColorSpace::Linear)));
            t
        };
        let texel = |r: u8, g: u8| texel_alpha(r, g, 255);
        let wo = DVec3::new(0.3, 0.0, 1.0).normalize();
        let (below, mirror) = (DVec3::new(-0.3, 0.0, -1.0).normalize(), DVec3::new(-0.3, 0.0, 1.0).normalize());
        let eval = |m: &MetallicRoughness, wi: DVec3| {
            metallic_roughness_scatter(m, DVec3::splat(0.8), DVec2::splat(0.5)).eval(wo, wi).x
        };
        let clear = MetallicRoughness::core(Finish::default(), 0.0, 0.5);
        let through = MetallicRoughness { transmission: 1.0, ..clear.clone() };
        assert_eq!(eval(&clear, below), 0.0);
        assert!(eval(&through, below) > 0.0);
        let masked = MetallicRoughness { transmission_texture: Some(texel(0, 0)), ..through.clone() };
        assert_eq!(eval(&masked, below), 0.0);
        let full = MetallicRoughness { transmission_texture: Some(texel(255, 0)), ..through.clone() };
        assert_eq!(eval(&full, below), eval(&through, below));

        let coated = MetallicRoughness { clearcoat: 1.0, clearcoat_roughness: 0.1, ..clear.clone() };
        assert!(eval(&coated, mirror) > 2.0 * eval(&clear, mirror), "a smooth coat adds a sharp lobe");
        let uncoated = MetallicRoughness { clearcoat_texture: Some(texel(0, 255)), ..coated.clone() };
        assert_eq!(eval(&uncoated, mirror), eval(&clear, mirror));
        let rough = MetallicRoughness { clearcoat_roughness: 1.0, ..coated.clone() };
        let roughened = MetallicRoughness { clearcoat_roughness_texture: Some(texel(0, 255)), ..rough.clone() };
        let smoothed = MetallicRoughness { clearcoat_roughness_texture: Some(texel(255, 26)), ..rough.clone() };
        assert_eq!(eval(&roughened, mirror), eval(&rough, mirror));
        assert!(eval(&smoothed, mirror) > 2.0 * eval(&rough, mirror), "green 0.1 times roughness 1 is smooth");

        // KHR_materials_specular: the strength times the texture's alpha, the colour times
        // the texture's RGB.
        let glossy = MetallicRoughness::core(Finish::default(), 0.0, 0.2);
        let unlit = MetallicRoughness { specular: 0.0, ..glossy.clone() };
        let alpha_zero = MetallicRoughness { specular_texture: Some(texel_alpha(255, 255, 0)), ..glossy.clone() };
        assert!(eval(&glossy, mirror) > 2.0 * eval(&unlit, mirror));
        assert_eq!(eval(&alpha_zero, mirror), eval(&unlit, mirror));
        let tinted = MetallicRoughness { specular_color: Rgb::new(0.0, 1.0, 1.0), ..glossy.clone() };
        let untinted = MetallicRoughness { specular_color_texture: Some(texel(0, 255)), ..tinted.clone() };
        assert_eq!(eval(&tinted, mirror), eval(&untinted, mirror), "red 0 in the colour texture changes no red");
        // A converted specular-glossiness texture: its alpha multiplies the glossiness.
        let matte = MetallicRoughness::core(Finish::default(), 0.0, 1.0);
        let glossed =
            MetallicRoughness { roughness: 0.8, glossiness_texture: Some(texel_alpha(0, 0, 255)), ..matte.clone() };
        let dulled = MetallicRoughness { glossiness_texture: Some(texel_alpha(255, 255, 0)), ..glossy.clone() };
        assert_eq!(eval(&glossed, mirror), eval(&MetallicRoughness { roughness: 0.8, ..matte.clone() }, mirror));
        assert_eq!(eval(&dulled, mirror), eval(&matte, mirror), "alpha 0: glossiness 0, roughness 1");
        let blacked = MetallicRoughness { specular_color_texture: Some(texel(0, 255)), ..glossy.clone() };
        assert!(eval(&blacked, mirror) < eval(&glossy, mirror), "red 0 in the colour texture lowers the red F0");
    }

    fn shaded(text: &str) -> Shaded {
        let spec: crate::material::MaterialSpec = toml::from_str(text).unwrap();
        PathMaterial::new(&spec.to_material()).shade(&SurfacePoint { uv: DVec2::ZERO, object_point: DVec3::ZERO })
    }

    fn lobes(s: &Shaded) -> Vec<String> {
        s.scatter.lobes().map(|(w, lobe)| format!("{w:?} {lobe:?}")).collect()
    }

    #[test]
    fn layers_weigh_as_pov_ray_sees_them() {
        let lines = |inline: &str| inline.replace("; ", "\n");
        let inline = |text: &str| text.replace("; ", ", ");
        let below = "color = [0.2, 0.9, 0.3]; filter = 0.5; reflection = 0.25; emission = 0.5";
        let alone = shaded(&format!("ior = 1.4\n{}", lines(below)));
        let below = inline(below);
        // An opaque top layer is that layer alone; a clear one shows the layer below alone.
        let top = "color = [0.8, 0.2, 0.1]; reflection = 0.2";
        let opaque = shaded(&format!("ior = 1.4\nlayers = [{{ {below} }}, {{ {} }}]", inline(top)));
        assert_eq!(lobes(&opaque), lobes(&shaded(&format!("ior = 1.4\n{}", lines(top)))));
        let clear = shaded(&format!("ior = 1.4\nlayers = [{{ {below} }}, {{ transmit = 1 }}]"));
        assert_eq!((lobes(&clear), clear.emitted), (lobes(&alone), alone.emitted));
        // A half-transmitting white top layer: half its own diffuse, the rest the layer below
        // at half weight; the emission below is seen through it.
        let half = shaded(&format!("ior = 1.4\nlayers = [{{ {below} }}, {{ transmit = 0.5 }}]"));
        let weights: Vec<DVec3> = half.scatter.lobes().map(|(w, _)| w).collect();
        let below_diffuse = 0.5 * 0.75 * DVec3::new(0.2, 0.9, 0.3);
        assert!((weights[0] - (DVec3::splat(0.5) + 0.5 * below_diffuse)).abs().max_element() < 1e-12);
        assert!((weights[1] - DVec3::splat(0.5 * 0.5 * 0.25)).abs().max_element() < 1e-12);
        assert!((weights[2] - DVec3::splat(0.25)).abs().max_element() < 1e-12);
        assert!((half.emitted - 0.5 * alone.emitted).abs().max_element() < 1e-12);
    }
}
