//! The classic integrator's view of a [`Material`]: the flat POV-Ray 3.7 finish it shades
//! with. A scene's finish is itself; glTF metallic-roughness and OBJ/MTL surfaces are mapped
//! to a finish here (the mappings are documented in `docs/meshes.md`). Everything that does
//! not vary over the surface is computed once per material ([`PovView::new`]); only
//! textured or metallic-roughness materials do work per hit ([`PovView::at_surface`]). A
//! layered texture is one view per layer, top first ([`PovView::layers`]).

use std::sync::Arc;

use glam::{DVec2, DVec3};

use super::normal::NormalField;
use super::pattern::PigmentField;
use super::{
    AlphaMode, Emission, Finish, Interior, Material, MetallicRoughness, MetallicRoughnessAt, Mtl, Physical, Reflection,
    Scattering, SurfaceModel,
};
use crate::color::Rgb;
use crate::texture::TextureRef;

/// A POV-Ray finish, pigment and interior at one point, every field with POV-Ray's meaning.
#[derive(Clone, Debug, PartialEq)]
pub struct PovFinish {
    /// Pigment and finish (`finish.texture` and `finish.pigment` are always `None`: textures
    /// and patterns are looked up into `finish.color`, `filter` and `transmit` at each hit).
    pub finish: Finish,
    /// `emission`, multiplied by the colour (like ambient).
    pub emission: Rgb,
    /// The interior (`ior` and POV-Ray's fade).
    pub interior: Interior,
}

impl PovFinish {
    /// True when light passes through the surface: filter or transmit not 0. A negative one
    /// (a bicubic image map overshooting at an alpha edge, say) passes light too, negated,
    /// as POV-Ray traces on wherever the filter's grey level is not 0.
    pub fn is_transparent(&self) -> bool {
        self.finish.filter != 0.0 || self.finish.transmit != 0.0
    }
}

/// What a pigment gives one point: POV-Ray's colour with its filter and transmit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pigment {
    /// The colour (linear RGB).
    pub color: DVec3,
    /// The share of light passing through, tinted by the colour.
    pub filter: f64,
    /// The share of light passing through untinted.
    pub transmit: f64,
}

impl Pigment {
    /// Opacity (1 - filter - transmit), as POV-Ray scales ambient and diffuse.
    pub fn opacity(&self) -> f64 {
        1.0 - self.filter - self.transmit
    }

    /// True when light passes through: filter or transmit not 0 (negative ones too, as in
    /// [`PovFinish::is_transparent`]).
    pub fn is_transparent(&self) -> bool {
        self.filter != 0.0 || self.transmit != 0.0
    }
}

/// The finish at one surface point.
#[derive(Debug)]
pub struct ShadedFinish<'a> {
    /// The finish to shade with but for its colour, filter and transmit, which are
    /// `pigment`'s (borrowed unless metallic-roughness parameters vary over the surface:
    /// a pattern's colour changes no other field, and copying the whole finish per hit for
    /// it cost 4 % of a patterned scene).
    pub finish: FinishAt<'a>,
    /// The pigment at the point, which replaces the finish's colour, filter and transmit.
    pub pigment: Pigment,
    /// Radiance emitted toward the viewer, W/(m^2 sr), added as is.
    pub emitted: DVec3,
}

impl<'a> ShadedFinish<'a> {
    /// The finish as it is everywhere on the surface.
    pub fn uniform(finish: &'a PovFinish) -> Self {
        let pigment =
            Pigment { color: finish.finish.color.0, filter: finish.finish.filter, transmit: finish.finish.transmit };
        Self { finish: FinishAt::Borrowed(finish), pigment, emitted: DVec3::ZERO }
    }
}

/// The finish at one surface point: the view's own, or one made for the point. The made one
/// is boxed because the finish is large (over 400 bytes) and a [`ShadedFinish`] is returned
/// by value on every hit: held inline, as a `Cow` holds it, every hit copied that much (5 %
/// of a patterned scene's time).
#[derive(Debug)]
pub enum FinishAt<'a> {
    /// The view's finish, unchanged at this point.
    Borrowed(&'a PovFinish),
    /// A finish made for this point.
    Owned(Box<PovFinish>),
}

impl FinishAt<'_> {
    /// The finish to change, copied out of the view first if it is the view's.
    pub fn to_mut(&mut self) -> &mut PovFinish {
        if let FinishAt::Borrowed(finish) = *self {
            *self = FinishAt::Owned(Box::new(finish.clone()));
        }
        match self {
            FinishAt::Owned(finish) => finish,
            FinishAt::Borrowed(_) => unreachable!("made owned above"),
        }
    }
}

impl std::ops::Deref for FinishAt<'_> {
    type Target = PovFinish;

    fn deref(&self) -> &PovFinish {
        match self {
            FinishAt::Borrowed(finish) => finish,
            FinishAt::Owned(finish) => finish,
        }
    }
}

/// A material as the classic integrator reads it: the finish where the surface is not
/// textured, plus what varies over it.
#[derive(Clone, Debug)]
pub struct PovView {
    /// The finish before textures (the whole finish of an untextured material; a layered
    /// texture's top layer, with the interior every layer shares).
    pub base: PovFinish,
    varying: Option<Varying>,
    /// A normal pattern tilting the shading normal.
    normal: Option<Arc<NormalField>>,
    /// A layered texture's layers under this one, top first (POV-Ray's order after the top
    /// layer, which is this view); empty for a single texture.
    below: Vec<PovView>,
}

/// What a hit looks up.
#[derive(Clone, Debug)]
struct Varying {
    /// Multiplies the colour.
    texture: Option<TextureRef>,
    /// glTF parameters turned into the finish at each hit.
    pbr: Option<MetallicRoughness>,
    /// Emitted radiance (W/(m^2 sr)) and its texture, added as is.
    emitted: Option<(Rgb, Option<TextureRef>)>,
    /// A pigment pattern giving colour, filter and transmit.
    pigment: Option<Arc<PigmentField>>,
}

impl PovView {
    /// The view of `material`.
    pub fn new(material: &Material) -> Self {
        let interior = &pov_interior(&material.interior);
        let emission = &material.emission;
        let finish = |f: &Finish, emission: Rgb| PovFinish {
            finish: Finish { texture: None, pigment: None, normal: None, ..f.clone() },
            emission,
            interior: *interior,
        };
        let emitted = || (emission.radiance, emission.texture.clone());
        match &material.surface {
            SurfaceModel::Finish(f) => {
                let glows = emission.radiance != Rgb::BLACK || emission.texture.is_some();
                let varying = (f.texture.is_some() || glows || f.pigment.is_some()).then(|| Varying {
                    texture: f.texture.clone(),
                    pbr: None,
                    emitted: glows.then(emitted),
                    pigment: f.pigment.clone(),
                });
                let mut base = finish(f, emission.times_color);
                if let Some(p) = &f.pigment {
                    // What does not vary (transparency tests, interiors) sees the pigment's
                    // most transparent colours; every hit looks the pigment up.
                    let colors = p.spec.colors();
                    let first = colors.first().map_or(DVec3::ONE, |c| c.rgb);
                    base.finish.color = Rgb(first);
                    // The largest in size: a negative filter or transmit passes light too.
                    let largest = |a: f64, v: f64| if v.abs() > a.abs() { v } else { a };
                    base.finish.filter = colors.iter().map(|c| c.filter).fold(0.0, largest);
                    base.finish.transmit = colors.iter().map(|c| c.transmit).fold(0.0, largest);
                }
                Self { base, varying, normal: f.normal.clone(), below: Vec::new() }
            }
            SurfaceModel::MetallicRoughness(p) => {
                let mut base = finish(&p.finish, emission.times_color);
                if p.alpha_mode == AlphaMode::Blend {
                    // Whitted tracing has no partial coverage: blending becomes transmission.
                    base.finish.transmit = (1.0 - p.alpha).clamp(0.0, 1.0);
                }
                // Thin-walled transmission as a filter (the factors' here, for shadows; each
                // hit looks its textures up).
                base.finish.filter = transmission_filter(p.transmission, p.metallic, base.finish.transmit);
                let varying = Varying {
                    texture: p.finish.texture.clone(),
                    pbr: Some((**p).clone()),
                    emitted: Some(emitted()),
                    pigment: None,
                };
                Self { base, varying: Some(varying), normal: None, below: Vec::new() }
            }
            SurfaceModel::Physical(p) => {
                let (derived, ior) = physical_finish(p);
                let mut base = finish(&derived, emission.times_color);
                base.interior.ior = ior;
                let glows = emission.radiance != Rgb::BLACK || emission.texture.is_some();
                let varying = (p.texture.is_some() || glows).then(|| Varying {
                    texture: p.texture.clone(),
                    pbr: None,
                    emitted: glows.then(emitted),
                    pigment: None,
                });
                Self { base, varying, normal: None, below: Vec::new() }
            }
            SurfaceModel::Mtl(m) => {
                let (mapped, texture) = mtl_finish(m, emission.radiance, interior.ior);
                let mut base = finish(&mapped.finish, mapped.emission);
                base.interior.ior = mapped.ior;
                let varying = texture.map(|t| Varying { texture: Some(t), pbr: None, emitted: None, pigment: None });
                Self { base, varying, normal: None, below: Vec::new() }
            }
            SurfaceModel::Layered(layers) => {
                let mut views = layers.iter().rev().map(|layer| {
                    Self::new(&Material {
                        surface: SurfaceModel::Finish(layer.finish.clone()),
                        interior: *interior,
                        emission: Emission { times_color: layer.emission, ..Emission::default() },
                    })
                });
                let top = views.next();
                let below = views.collect();
                let top = top.unwrap_or_else(|| Self::new(&Material { interior: *interior, ..Material::default() }));
                Self { below, ..top }
            }
        }
    }

    /// The layers, top first (one for a single texture): POV-Ray's texture list.
    pub fn layers(&self) -> impl Iterator<Item = &PovView> {
        std::iter::once(self).chain(&self.below)
    }

    /// True when the material has more than one layer.
    pub fn is_layered(&self) -> bool {
        !self.below.is_empty()
    }

    /// True when light can pass through every layer somewhere (the most transparent colours
    /// of patterns).
    pub fn is_transparent(&self) -> bool {
        self.base.is_transparent() && self.below.iter().all(|l| l.base.is_transparent())
    }

    /// What a shadow ray crossing the surface at object-space `point` keeps of the light:
    /// the product over the layers of `colour * filter + transmit` (POV-Ray's
    /// `ComputeShadowTexture`), patterns looked up at the point.
    pub fn shadow_filter(&self, point: DVec3) -> DVec3 {
        let filter = |l: &PovView| match l.pigment() {
            Some(p) => {
                let c = p.at(point);
                c.rgb * c.filter + DVec3::splat(c.transmit)
            }
            None => l.base.finish.color.0 * l.base.finish.filter + DVec3::splat(l.base.finish.transmit),
        };
        self.below.iter().fold(filter(self), |f, l| f * filter(l))
    }

    /// True when the finish depends on where the surface is hit: only then does shading need
    /// the surface's uv.
    pub fn varies_over_surface(&self) -> bool {
        self.varying.is_some() || self.below.iter().any(PovView::varies_over_surface)
    }

    /// The normal pattern, when the material has one.
    pub fn normal(&self) -> Option<&NormalField> {
        self.normal.as_deref()
    }

    /// The pigment pattern, when the material has one.
    pub fn pigment(&self) -> Option<&PigmentField> {
        self.varying.as_ref()?.pigment.as_deref()
    }

    /// The finish at object-space point `point` with texture coordinates `uv`, for a ray
    /// footprint `footprint` wide in uv units (it selects the mip level).
    ///
    /// The finish derived from glTF parameters (documented in `docs/meshes.md`): with `m` =
    /// metallic, `r` = roughness and `g = (1 - r)^2`: diffuse `0.6 (1 - m)`, Blinn specular
    /// `g (0.25 + 0.75 m)` (less `g 0.25 (1 - m) (1 - s)` for a specular strength `s`) with
    /// POV-Ray roughness `a^2 / (2 - 2 a^2)` for GGX `a = r^2` (exponent 2 / a^2 - 2),
    /// highlights and reflection tinted by the base colour by `m`, mirror reflection `m g`,
    /// `filter` the thin-walled transmission's dielectric share.
    pub fn at_surface(&self, point: DVec3, uv: DVec2, footprint: f64) -> ShadedFinish<'_> {
        let mut shaded = ShadedFinish::uniform(&self.base);
        let Some(varying) = &self.varying else {
            return shaded;
        };
        if let Some(p) = &varying.pigment {
            let c = p.at(point);
            shaded.pigment = Pigment { color: c.rgb, filter: c.filter, transmit: c.transmit };
        }
        if let Some(t) = &varying.texture {
            let texel = t.sample(uv, footprint);
            shaded.pigment.color *= texel.truncate().as_dvec3();
        }
        if let Some(p) = &varying.pbr {
            // The specular colour and the clear coat have no place in POV-Ray's finish.
            let MetallicRoughnessAt { metallic, roughness, specular: strength, transmission, .. } = p.at(uv, footprint);
            let gloss = (1.0 - roughness).powi(2);
            let alpha2 = roughness.powi(4).max(1e-4);
            let m = &mut shaded.finish.to_mut().finish;
            m.diffuse = 0.6 * (1.0 - metallic);
            // The dielectric's share of the highlight, g 0.25 (1 - m), scales with
            // KHR_materials_specular's strength s (written so that s = 1 changes nothing).
            m.specular = gloss * (0.25 + 0.75 * metallic - 0.25 * (1.0 - metallic) * (1.0 - strength));
            m.roughness = (alpha2 / (2.0 - 2.0 * alpha2)).clamp(5e-4, 1.0);
            m.metallic = metallic;
            m.phong = 0.0;
            let mirror = metallic * gloss;
            m.reflection =
                Reflection { min: Rgb::grey(mirror), max: Rgb::grey(mirror), metallic, ..Reflection::default() };
            // Thin-walled transmission passes light straight through, tinted by the base
            // colour: POV-Ray's filter (added to a blended material's transmit).
            shaded.pigment.filter = transmission_filter(transmission, metallic, shaded.pigment.transmit);
        }
        if let Some((radiance, texture)) = &varying.emitted {
            shaded.emitted = radiance.0;
            if let Some(t) = texture {
                shaded.emitted *= t.sample(uv, footprint).truncate().as_dvec3();
            }
        }
        shaded
    }
}

/// The interior as POV-Ray writes it: a physical absorption coefficient `a` becomes an
/// exponential fade (`fade_power` 1000), which POV-Ray computes as `exp(-(1 - fade_color) *
/// d / fade_distance)`: `fade_distance = 1 / max(a)` and `fade_color = 1 - a / max(a)` keep
/// the fade colour within 0..1. An interior with POV-Ray's own fade keeps it.
fn pov_interior(interior: &Interior) -> Interior {
    let strongest = interior.absorption.0.max_element();
    if strongest <= 0.0 || interior.fade_distance != 0.0 {
        return *interior;
    }
    Interior {
        // POV-Ray takes a fade distance within its EPSILON (1e-10) of 0 as no fade at all; a
        // medium this dense is black over any distance the scene resolves anyway.
        fade_distance: (1.0 / strongest).max(1e-9),
        fade_power: 1000.0,
        fade_color: Rgb(DVec3::ONE - interior.absorption.0 / strongest),
        ..*interior
    }
}

/// POV-Ray's filter for glTF's thin-walled transmission: the dielectric part's share
/// (`transmission * (1 - metallic)`), within what `transmit` leaves.
fn transmission_filter(transmission: f64, metallic: f64, transmit: f64) -> f64 {
    (transmission * (1.0 - metallic)).clamp(0.0, (1.0 - transmit).max(0.0))
}

/// A physically based model read as a POV-Ray finish (documented in `docs/scene-format.md`):
/// `diffuse` is POV-Ray's default finish in the colour; a conductor is a mirror whose
/// reflectivity is its normal-incidence Fresnel reflectance times the colour, with a Blinn
/// highlight when rough; a dielectric is fully transmitting glass of its index with Fresnel
/// reflection; a thin dielectric transmits without bending; plastic is the diffuse colour with
/// Fresnel reflection and a highlight. Returns the finish and the interior's index.
fn physical_finish(p: &Physical) -> (Finish, f64) {
    let mut finish = Finish { color: p.color, texture: p.texture.clone(), ..Finish::default() };
    let fresnel = Reflection { min: Rgb::BLACK, max: Rgb::WHITE, fresnel: true, ..Reflection::default() };
    let highlight = |finish: &mut Finish, alpha: f64| {
        if alpha > 0.0 {
            finish.specular = 1.0;
            // Blinn's exponent 2 / alpha^2 - 2 is GGX's best match (Walter et al.).
            let alpha2 = (alpha * alpha).min(0.999);
            finish.roughness = (alpha2 / (2.0 - 2.0 * alpha2)).clamp(5e-4, 1.0);
        }
    };
    let ior = match p.scattering {
        Scattering::Diffuse => 1.0,
        Scattering::Conductor { eta, k, alpha } => {
            let (eta, k) = (eta.0, k.0);
            let f0 = ((eta - 1.0) * (eta - 1.0) + k * k) / ((eta + 1.0) * (eta + 1.0) + k * k);
            let tint = Rgb(f0 * p.color.0);
            finish.diffuse = 0.0;
            finish.ambient = Rgb::BLACK;
            finish.metallic = 1.0;
            finish.color = tint;
            finish.reflection = Reflection { min: tint, max: tint, ..Reflection::default() };
            highlight(&mut finish, alpha);
            1.0
        }
        Scattering::Dielectric { ior, alpha } => {
            finish.diffuse = 0.0;
            finish.ambient = Rgb::BLACK;
            finish.filter = 1.0;
            finish.reflection = fresnel;
            finish.conserve_energy = true;
            highlight(&mut finish, alpha);
            ior
        }
        Scattering::ThinDielectric { ior } => {
            finish.diffuse = 0.0;
            finish.ambient = Rgb::BLACK;
            finish.filter = 1.0;
            let r0 = ((ior - 1.0) / (ior + 1.0)).powi(2);
            let r = 2.0 * r0 / (1.0 + r0);
            finish.reflection =
                Reflection { min: Rgb::grey(r), max: Rgb::WHITE, falloff: 5.0, ..Reflection::default() };
            finish.conserve_energy = true;
            1.0
        }
        Scattering::Plastic { ior, alpha } => {
            finish.reflection = fresnel;
            highlight(&mut finish, alpha.max(0.05));
            ior
        }
    };
    (finish, ior)
}

/// A finish with the emission coefficient and index of refraction MTL gives it.
struct MtlFinish {
    finish: Finish,
    emission: Rgb,
    ior: f64,
}

/// MTL to a POV-Ray finish: Kd -> colour (map_Kd multiplies it), Ks and Ns -> Blinn specular
/// (strength = mean of Ks, POV-Ray roughness = 1 / Ns), illum 3 or 5-7 -> mirror reflection
/// Ks, d < 1 (or Tr) -> transmit 1 - d with ior Ni, Ke -> emission Ke / Kd (POV-Ray
/// multiplies emission by the colour). Returns the finish and the colour texture.
fn mtl_finish(m: &Mtl, ke: Rgb, default_ior: f64) -> (MtlFinish, Option<TextureRef>) {
    let mut finish = Finish::default();
    let mut ior = default_ior;
    if let Some(kd) = m.kd {
        finish.color = kd;
    }
    let ks = m.ks.unwrap_or(Rgb::BLACK);
    let strength = (ks.0.x + ks.0.y + ks.0.z) / 3.0;
    if strength > 0.0 {
        finish.specular = strength.clamp(0.0, 1.0);
        let ns = m.ns.unwrap_or(10.0).max(1.0);
        finish.roughness = (1.0 / ns).clamp(5e-4, 1.0);
    }
    let illum = m.illum.unwrap_or(2);
    if matches!(illum, 3 | 5 | 6 | 7) && strength > 0.0 {
        finish.reflection = Reflection { min: ks, max: ks, ..Reflection::default() };
    }
    let dissolve = m.d.unwrap_or(1.0).clamp(0.0, 1.0);
    if dissolve < 1.0 {
        finish.transmit = 1.0 - dissolve;
        ior = m.ni.filter(|&n| n.is_finite() && n > 0.0).unwrap_or(1.0);
    }
    let mut emission = Rgb::BLACK;
    if ke.0.to_array().iter().any(|&c| c > 0.0) {
        let c = finish.color.0;
        let ke = ke.0;
        let ratio = |e: f64, c: f64| if c > 0.0 { e / c } else { e };
        emission = Rgb::new(ratio(ke.x, c.x), ratio(ke.y, c.y), ratio(ke.z, c.z));
    }
    (MtlFinish { finish, emission, ior }, m.map_kd.clone())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::{Emission, Interior};

    fn mtl(m: Mtl, ke: Rgb) -> PovFinish {
        let material = Material {
            surface: SurfaceModel::Mtl(m),
            emission: Emission { radiance: ke, ..Emission::default() },
            ..Material::default()
        };
        let view = PovView::new(&material);
        assert!(!view.varies_over_surface());
        view.base
    }

    #[test]
    fn mtl_maps_to_blinn_mirror_transmit_and_emission_over_kd() {
        let f = mtl(
            Mtl {
                kd: Some(Rgb::new(0.5, 0.0, 1.0)),
                ks: Some(Rgb::grey(0.5)),
                ns: Some(100.0),
                ni: Some(1.5),
                d: Some(0.2),
                illum: Some(3),
                map_kd: None,
            },
            Rgb::new(0.5, 1.0, 0.0),
        );
        assert_eq!(f.finish.color, Rgb::new(0.5, 0.0, 1.0));
        assert_eq!((f.finish.specular, f.finish.roughness), (0.5, 0.01));
        assert_eq!((f.finish.reflection.min, f.finish.reflection.max), (Rgb::grey(0.5), Rgb::grey(0.5)));
        assert_eq!((f.finish.transmit, f.interior.ior), (1.0 - 0.2, 1.5));
        // Ke / Kd where Kd > 0, Ke itself where Kd is 0.
        assert_eq!(f.emission, Rgb::new(1.0, 1.0, 0.0));
        assert_eq!((f.finish.ambient, f.finish.diffuse, f.finish.phong), (Rgb::grey(0.1), 0.6, 0.0));
    }

    #[test]
    fn mtl_defaults_and_illum_2_stay_pov_ray_defaults() {
        let f = mtl(Mtl { ks: Some(Rgb::grey(0.3)), illum: Some(2), ..Mtl::default() }, Rgb::BLACK);
        assert_eq!((f.finish.color, f.finish.specular, f.finish.roughness), (Rgb::WHITE, (0.3 + 0.3 + 0.3) / 3.0, 0.1));
        assert!(!f.finish.reflection.is_reflective());
        assert_eq!((f.finish.transmit, f.interior.ior, f.emission), (0.0, 1.0, Rgb::BLACK));
        // Opaque: Ni is ignored; Ns below 1 is 1.
        let f = mtl(Mtl { ks: Some(Rgb::grey(1.0)), ns: Some(0.5), ni: Some(2.0), ..Mtl::default() }, Rgb::BLACK);
        assert_eq!((f.finish.roughness, f.interior.ior), (1.0, 1.0));
    }

    fn gltf(metallic: f64, roughness: f64, alpha_mode: AlphaMode, alpha: f64) -> PovView {
        let surface = SurfaceModel::MetallicRoughness(Box::new(MetallicRoughness {
            alpha_mode,
            alpha,
            ..MetallicRoughness::core(
                Finish { color: Rgb::new(0.8, 0.4, 0.2), ..Finish::default() },
                metallic,
                roughness,
            )
        }));
        let emission = Emission { radiance: Rgb::new(1.0, 2.0, 3.0), ..Emission::default() };
        PovView::new(&Material { surface, emission, interior: Interior::default() })
    }

    #[test]
    fn metallic_roughness_maps_to_the_classic_finish() {
        let view = gltf(1.0, 0.0, AlphaMode::Opaque, 1.0);
        let shaded = view.at_surface(DVec3::ZERO, DVec2::ZERO, 0.0);
        let f = &shaded.finish;
        assert_eq!(
            (f.finish.diffuse, f.finish.specular, f.finish.roughness, f.finish.metallic, f.finish.phong),
            (0.0, 1.0, 5e-4, 1.0, 0.0)
        );
        assert_eq!((f.finish.reflection.min, f.finish.reflection.metallic), (Rgb::grey(1.0), 1.0));
        assert_eq!((shaded.pigment.color, shaded.pigment.transmit), (DVec3::new(0.8, 0.4, 0.2), 0.0));
        assert_eq!(shaded.emitted, DVec3::new(1.0, 2.0, 3.0));

        let view = gltf(0.0, 0.5, AlphaMode::Blend, 0.25);
        let shaded = view.at_surface(DVec3::ZERO, DVec2::ZERO, 0.0);
        let f = &shaded.finish;
        assert_eq!((f.finish.diffuse, f.finish.specular, f.finish.metallic), (0.6, 0.25 * 0.25, 0.0));
        assert_eq!(f.finish.roughness, 0.0625 / (2.0 - 2.0 * 0.0625));
        assert!(!f.finish.reflection.is_reflective());
        assert_eq!(shaded.pigment.transmit, 0.75);
        assert!(view.base.is_transparent() && view.varies_over_surface());
    }

    /// Thin-walled transmission is POV-Ray's filter: the dielectric share `transmission (1 -
    /// metallic)`, within what a blended material's transmit leaves; shadows through it are
    /// tinted by the base colour.
    #[test]
    fn gltf_transmission_is_a_filter() {
        let view = |metallic: f64, transmission: f64, alpha_mode: AlphaMode, alpha: f64| {
            let surface = SurfaceModel::MetallicRoughness(Box::new(MetallicRoughness {
                alpha_mode,
                alpha,
                transmission,
                ..MetallicRoughness::core(Finish { color: Rgb::new(0.8, 0.4, 0.2), ..Finish::default() }, metallic, 0.5)
            }));
            PovView::new(&Material { surface, emission: Emission::default(), interior: Interior::default() })
        };
        let half_metal = view(0.5, 0.6, AlphaMode::Opaque, 1.0);
        let shaded = half_metal.at_surface(DVec3::ZERO, DVec2::ZERO, 0.0);
        assert_eq!((shaded.pigment.filter, shaded.pigment.transmit), (0.3, 0.0));
        assert!(half_metal.is_transparent());
        assert_eq!(half_metal.shadow_filter(DVec3::ZERO), DVec3::new(0.8, 0.4, 0.2) * 0.3);
        let blended = view(0.0, 1.0, AlphaMode::Blend, 0.25);
        let shaded = blended.at_surface(DVec3::ZERO, DVec2::ZERO, 0.0);
        assert_eq!((shaded.pigment.filter, shaded.pigment.transmit), (0.25, 0.75));
        assert!(!view(0.0, 0.0, AlphaMode::Opaque, 1.0).is_transparent());
    }

    /// KHR_materials_specular's strength scales the dielectric's share of the highlight and
    /// leaves the metal's.
    #[test]
    fn gltf_specular_strength_scales_the_dielectric_highlight() {
        let highlight = |metallic: f64, specular: f64| {
            let surface = SurfaceModel::MetallicRoughness(Box::new(MetallicRoughness {
                specular,
                ..MetallicRoughness::core(Finish::default(), metallic, 0.0)
            }));
            let view =
                PovView::new(&Material { surface, emission: Emission::default(), interior: Interior::default() });
            view.at_surface(DVec3::ZERO, DVec2::ZERO, 0.0).finish.finish.specular
        };
        assert_eq!((highlight(0.0, 1.0), highlight(0.0, 0.0), highlight(0.0, 0.5)), (0.25, 0.0, 0.125));
        assert_eq!((highlight(1.0, 1.0), highlight(1.0, 0.0)), (1.0, 1.0));
        assert_eq!(highlight(0.5, 0.0), 0.5);
    }

    #[test]
    fn a_scene_finish_is_its_own_view() {
        let spec: crate::material::MaterialSpec =
            toml::from_str("color = [1, 0.5, 0]\nphong = 0.7\nemission = 0.25\nior = 1.33\nfade_distance = 3").unwrap();
        let view = PovView::new(&spec.to_material());
        assert!(!view.varies_over_surface());
        let f = view.base;
        assert_eq!((f.finish.color, f.finish.phong, f.emission), (spec.color, 0.7, Rgb::grey(0.25)));
        assert_eq!(
            (f.interior.ior, f.interior.fade_distance, f.finish.roughness, f.finish.ambient),
            (1.33, 3.0, 0.05, Rgb::grey(0.1))
        );
    }

    /// Physical absorption reaches POV-Ray as its exponential fade, which attenuates by
    /// `exp(-(1 - fade_color) d / fade_distance)`: the same Beer-Lambert law, every channel.
    #[test]
    fn absorption_is_an_exponential_fade_for_pov_ray() {
        let spec: crate::material::MaterialSpec =
            toml::from_str("color = 1\nfilter = 1\nattenuation_color = [0.5, 1.0, 0.1]\nattenuation_distance = 2")
                .unwrap();
        let material = spec.to_material();
        let interior = PovView::new(&material).base.interior;
        assert!(interior.fade_power >= 1000.0, "{interior:?}");
        let fade_color = interior.fade_color.0;
        assert!(fade_color.cmpge(DVec3::ZERO).all() && fade_color.cmple(DVec3::ONE).all(), "{fade_color}");
        let d = 3.0;
        let fade = (-(DVec3::ONE - fade_color) * (d / interior.fade_distance)).exp();
        let beer = (-material.interior.absorption.0 * d).exp();
        assert!((fade - beer).abs().max_element() < 1e-12, "{fade} against {beer}");
        // POV-Ray's own fade is kept as written.
        let pov: crate::material::MaterialSpec =
            toml::from_str("fade_distance = 3\nfade_power = 2\nfade_color = 0.5").unwrap();
        let kept = PovView::new(&pov.to_material()).base.interior;
        assert_eq!((kept.fade_distance, kept.fade_power, kept.fade_color), (3.0, 2.0, Rgb::grey(0.5)));
    }
}
