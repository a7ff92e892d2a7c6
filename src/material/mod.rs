//! Materials: what a surface is, independent of the integrator that renders it.
//!
//! A [`Material`] is a surface model (the POV-Ray finish a scene wrote, glTF 2.0's
//! metallic-roughness, or OBJ/MTL's parameters, each as written), an [`Interior`] and one
//! [`Emission`] in radiance units. Each integrator reads its own view of it: the classic
//! integrator reads the flat POV-Ray finish of [`pov_view`], the path integrator (coming)
//! reads the model. The scene file's form is [`spec::MaterialSpec`]; importers build
//! materials directly. `docs/meshes.md` documents the mappings.

pub mod crackle;
pub mod image_map;
pub mod metals;
pub mod noise;
pub mod normal;
pub mod pattern;
pub mod pov_view;
pub mod spec;

pub use spec::{MaterialSpec, Pbr, Reflection};

use glam::DVec3;

use crate::color::Rgb;
use crate::texture::TextureRef;

/// A surface model, an interior and an emission.
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    /// How the surface scatters light.
    pub surface: SurfaceModel,
    /// The medium behind the surface.
    pub interior: Interior,
    /// Light the surface emits by itself.
    pub emission: Emission,
}

impl Default for Material {
    /// The scene's default material: POV-Ray's default finish with a white pigment.
    fn default() -> Self {
        MaterialSpec::default().to_material()
    }
}

/// How the surface scatters light, in the terms of the source it was written in.
#[derive(Clone, Debug, PartialEq)]
pub enum SurfaceModel {
    /// POV-Ray's pigment and finish, as a scene wrote them.
    Finish(Finish),
    /// glTF 2.0 metallic-roughness, as a file or a scene's `pbr` table wrote it.
    MetallicRoughness(Box<MetallicRoughness>),
    /// OBJ/MTL parameters, as the `.mtl` file wrote them.
    Mtl(Mtl),
    /// A physically based scattering model, as a scene's `bsdf` table wrote it.
    Physical(Physical),
    /// POV-Ray's layered texture (`texture { } texture { }`), bottom layer first as written:
    /// each layer's filter and transmit let the layers below show through.
    Layered(Vec<Layer>),
}

/// One layer of a layered texture: its pigment and finish, and its finish's `emission`.
#[derive(Clone, Debug, PartialEq)]
pub struct Layer {
    /// The layer's pigment and finish.
    pub finish: Finish,
    /// POV-Ray's `emission` of this layer's finish (radiance per unit of colour).
    pub emission: Rgb,
}

/// A physically based surface: a scattering model and the colour (with its texture) that
/// tints it.
#[derive(Clone, Debug, PartialEq)]
pub struct Physical {
    /// The scattering model.
    pub scattering: Scattering,
    /// Linear RGB: the reflectance of `diffuse` and `plastic`'s base, the tint of the
    /// others' specular reflection (conductors) or transmission (dielectrics).
    pub color: Rgb,
    /// An image (linear after decoding) multiplying `color`.
    pub texture: Option<TextureRef>,
}

/// A physically based scattering model, in Mitsuba 3's terms (GGX `alpha` is the microfacet
/// roughness itself, glTF's perceptual roughness squared).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Scattering {
    /// Lambertian reflection.
    Diffuse,
    /// A metal: complex index of refraction `eta + i k` per channel, GGX roughness `alpha`
    /// (0 = mirror).
    Conductor {
        /// Real part of the index of refraction (linear RGB channels).
        eta: Rgb,
        /// Imaginary part (absorption).
        k: Rgb,
        /// GGX alpha (0 = smooth).
        alpha: f64,
    },
    /// An interface into glass or water: index of refraction inside over outside.
    Dielectric {
        /// Relative index of refraction (inside / outside).
        ior: f64,
        /// GGX alpha (0 = smooth).
        alpha: f64,
    },
    /// A thin slab of a dielectric (window pane, soap film): no refraction, internal
    /// reflections summed.
    ThinDielectric {
        /// Index of refraction of the slab.
        ior: f64,
    },
    /// A diffuse base under a dielectric coating (Mitsuba's `plastic` / `roughplastic`).
    Plastic {
        /// Index of refraction of the coating.
        ior: f64,
        /// GGX alpha of the coating (0 = smooth).
        alpha: f64,
    },
}

/// POV-Ray 3.7's pigment and finish. Every field has POV-Ray's meaning (and the scene
/// file's name), not a physical one: `roughness` is the Blinn highlight's (exponent
/// 1 / roughness), `metallic` a highlight tint, `ambient` a fraction of the world's
/// ambient light. POV-Ray's `emission` is [`Emission::times_color`].
#[derive(Clone, Debug, PartialEq)]
pub struct Finish {
    /// Pigment colour (linear RGB reflectance).
    pub color: Rgb,
    /// Fraction of light that passes through, tinted by the colour (POV-Ray `filter`).
    pub filter: f64,
    /// Fraction of light that passes through untinted (POV-Ray `transmit`).
    pub transmit: f64,
    /// POV-Ray's ambient coefficient, multiplied by the world's `ambient_light` and the colour.
    pub ambient: Rgb,
    /// POV-Ray's diffuse coefficient.
    pub diffuse: f64,
    /// POV-Ray's exponent on the diffuse cosine (1 = Lambert).
    pub brilliance: f64,
    /// POV-Ray's Phong highlight strength.
    pub phong: f64,
    /// POV-Ray's Phong exponent.
    pub phong_size: f64,
    /// POV-Ray's Blinn specular highlight strength.
    pub specular: f64,
    /// POV-Ray's specular roughness: the Blinn exponent is 1 / roughness (not GGX's).
    pub roughness: f64,
    /// POV-Ray's `metallic`: how much highlights take the pigment's colour (0..1).
    pub metallic: f64,
    /// POV-Ray's mirror reflection.
    pub reflection: Reflection,
    /// POV-Ray's `conserve_energy`: transmitted light is scaled by (1 - reflection).
    pub conserve_energy: bool,
    /// An image (linear after decoding) multiplying `color`.
    pub texture: Option<TextureRef>,
    /// A POV-Ray pigment pattern: where given, its colour, filter and transmit at the hit
    /// (in the object's space) replace `color`, `filter` and `transmit`.
    pub pigment: Option<std::sync::Arc<pattern::PigmentField>>,
    /// A POV-Ray normal pattern: tilts the shading normal over the surface (in the object's
    /// space); the classic integrator shades with the tilted normal.
    pub normal: Option<std::sync::Arc<normal::NormalField>>,
}

impl Default for Finish {
    /// POV-Ray's default finish with a white pigment.
    fn default() -> Self {
        match MaterialSpec::default().to_material().surface {
            SurfaceModel::Finish(f) => f,
            _ => unreachable!("a material without `pbr` is a finish"),
        }
    }
}

/// How glTF's base colour alpha covers the surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum AlphaMode {
    /// Alpha is ignored.
    Opaque,
    /// Alpha below `cutoff` cuts the surface away (the cut itself is the mesh's alpha mask).
    Mask {
        /// The alpha below which the surface is absent.
        cutoff: f64,
    },
    /// The surface is alpha-blended over what lies behind it.
    Blend,
}

/// glTF 2.0 metallic-roughness (`pbrMetallicRoughness` and the material's alpha) as written.
#[derive(Clone, Debug, PartialEq)]
pub struct MetallicRoughness {
    /// `finish.color` and `finish.texture` are the base colour factor (RGB, linear) and
    /// texture. Its other fields are the POV-Ray finish a scene wrote beside its `pbr` table
    /// (POV-Ray's defaults for imported files): where the classic view starts.
    pub finish: Finish,
    /// Metalness factor (0 = dielectric, 1 = metal).
    pub metallic: f64,
    /// Perceptual roughness factor (GGX alpha = roughness^2; 0 = mirror-smooth).
    pub roughness: f64,
    /// Texture whose blue channel multiplies `metallic` and green channel `roughness`.
    pub metallic_roughness_texture: Option<TextureRef>,
    /// Texture whose alpha channel multiplies the glossiness `1 - roughness` (a converted
    /// `KHR_materials_pbrSpecularGlossiness` texture).
    pub glossiness_texture: Option<TextureRef>,
    /// The alpha mode.
    pub alpha_mode: AlphaMode,
    /// The base colour factor's alpha (coverage, 0..1).
    pub alpha: f64,
    /// Index of refraction of the dielectric part (`KHR_materials_ior`; 1.5 by default).
    pub ior: f64,
    /// Strength of the dielectric part's specular reflection, 0..1 (`KHR_materials_specular`;
    /// 1 by default).
    pub specular: f64,
    /// Texture whose alpha channel multiplies `specular`.
    pub specular_texture: Option<TextureRef>,
    /// Colour of the dielectric's F0 (linear RGB, 1 by default; may exceed 1, the product
    /// with the ior's F0 is clamped to 1).
    pub specular_color: Rgb,
    /// Texture (sRGB) multiplying `specular_color`.
    pub specular_color_texture: Option<TextureRef>,
    /// Share of the dielectric part's diffuse base that passes through the surface instead
    /// (`KHR_materials_transmission`, thin-walled: straight through, blurred by the roughness,
    /// tinted by the base colour), 0..1.
    pub transmission: f64,
    /// Texture whose red channel multiplies `transmission`.
    pub transmission_texture: Option<TextureRef>,
    /// Strength of a clear coat over the material (`KHR_materials_clearcoat`: a GGX layer
    /// with F0 0.04), 0..1.
    pub clearcoat: f64,
    /// Texture whose red channel multiplies `clearcoat`.
    pub clearcoat_texture: Option<TextureRef>,
    /// Perceptual roughness of the clear coat (its GGX alpha is the square), 0..1.
    pub clearcoat_roughness: f64,
    /// Texture whose green channel multiplies `clearcoat_roughness`.
    pub clearcoat_roughness_texture: Option<TextureRef>,
}

impl MetallicRoughness {
    /// The core model's extension defaults: ior 1.5, no transmission, no clear coat.
    pub fn core(finish: Finish, metallic: f64, roughness: f64) -> Self {
        Self {
            finish,
            metallic,
            roughness,
            metallic_roughness_texture: None,
            glossiness_texture: None,
            alpha_mode: AlphaMode::Opaque,
            alpha: 1.0,
            ior: 1.5,
            specular: 1.0,
            specular_texture: None,
            specular_color: Rgb::WHITE,
            specular_color_texture: None,
            transmission: 0.0,
            transmission_texture: None,
            clearcoat: 0.0,
            clearcoat_texture: None,
            clearcoat_roughness: 0.0,
            clearcoat_roughness_texture: None,
        }
    }

    /// The parameters at texture coordinates `uv`, textures read over a footprint `footprint`
    /// wide in uv units (it selects the mip level; 0 for full resolution): each factor times
    /// its texture's channel there, not clamped. The metallic-roughness texture's blue and
    /// green multiply metallic and roughness, the glossiness texture's alpha the glossiness
    /// `1 - roughness`, the specular texture's alpha the strength, the specular colour
    /// texture's RGB the colour, red the transmission and the coat, green the coat's roughness.
    pub fn at(&self, uv: glam::DVec2, footprint: f64) -> MetallicRoughnessAt {
        let (mut metallic, mut roughness) = (self.metallic, self.roughness);
        if let Some(t) = &self.metallic_roughness_texture {
            let v = t.sample(uv, footprint);
            roughness *= f64::from(v.y);
            metallic *= f64::from(v.z);
        }
        if let Some(t) = &self.glossiness_texture {
            roughness = 1.0 - (1.0 - roughness) * f64::from(t.sample(uv, footprint).w);
        }
        let times = |factor: f64, texture: &Option<TextureRef>, channel: usize| {
            texture.as_ref().map_or(factor, |t| factor * f64::from(t.sample(uv, footprint)[channel]))
        };
        let specular_color = self.specular_color.0
            * self
                .specular_color_texture
                .as_ref()
                .map_or(glam::DVec3::ONE, |t| t.sample(uv, footprint).truncate().as_dvec3());
        MetallicRoughnessAt {
            metallic,
            roughness,
            specular: times(self.specular, &self.specular_texture, 3),
            specular_color,
            transmission: times(self.transmission, &self.transmission_texture, 0),
            clearcoat: times(self.clearcoat, &self.clearcoat_texture, 0),
            clearcoat_roughness: times(self.clearcoat_roughness, &self.clearcoat_roughness_texture, 1),
        }
    }

    /// The textures driving the extensions' factors.
    pub fn extension_textures(&self) -> impl Iterator<Item = &TextureRef> {
        [
            &self.glossiness_texture,
            &self.specular_texture,
            &self.specular_color_texture,
            &self.transmission_texture,
            &self.clearcoat_texture,
            &self.clearcoat_roughness_texture,
        ]
        .into_iter()
        .flatten()
    }
}

/// [`MetallicRoughness`] at one surface point ([`MetallicRoughness::at`]): factors times
/// their textures, not clamped.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MetallicRoughnessAt {
    /// Metalness.
    pub metallic: f64,
    /// Perceptual roughness.
    pub roughness: f64,
    /// Strength of the dielectric's specular reflection.
    pub specular: f64,
    /// Colour of the dielectric's F0 (linear RGB).
    pub specular_color: glam::DVec3,
    /// Thin-walled transmission.
    pub transmission: f64,
    /// Clear coat strength.
    pub clearcoat: f64,
    /// Perceptual roughness of the clear coat.
    pub clearcoat_roughness: f64,
}

/// OBJ/MTL parameters as the `.mtl` file wrote them (`None` where it did not). `Ke` is the
/// material's [`Emission::radiance`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mtl {
    /// `Kd`: diffuse reflectance (linear RGB).
    pub kd: Option<Rgb>,
    /// `Ks`: specular reflectance (linear RGB).
    pub ks: Option<Rgb>,
    /// `Ns`: Phong specular exponent.
    pub ns: Option<f64>,
    /// `Ni`: index of refraction.
    pub ni: Option<f64>,
    /// `d` (dissolve, 1 = opaque), or `1 - Tr` when only `Tr` is given.
    pub d: Option<f64>,
    /// `illum`: the illumination model number.
    pub illum: Option<u8>,
    /// `map_Kd`: an image multiplying `Kd`.
    pub map_kd: Option<TextureRef>,
}

/// The medium behind a surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Interior {
    /// Index of refraction (1 = no refraction).
    pub ior: f64,
    /// POV-Ray's interior fade distance in scene units (0 = no fade).
    pub fade_distance: f64,
    /// POV-Ray's fade power (>= 1000 switches to exponential attenuation).
    pub fade_power: f64,
    /// The colour POV-Ray's fade tends toward.
    pub fade_color: Rgb,
    /// Beer-Lambert absorption coefficient of the medium, per scene unit of length (linear
    /// RGB, not negative): light crossing a distance `d` inside keeps `exp(-absorption * d)`.
    pub absorption: Rgb,
}

impl Default for Interior {
    /// Vacuum-like: no refraction, no fade, no absorption.
    fn default() -> Self {
        Self { ior: 1.0, fade_distance: 0.0, fade_power: 0.0, fade_color: Rgb::BLACK, absorption: Rgb::BLACK }
    }
}

/// A transmitted colour below this counts as this (an absorption coefficient of at most
/// `-ln(1e-6) = 13.8` per attenuation distance: white light keeps a millionth).
const DARKEST_ATTENUATION: f64 = 1e-6;

impl Interior {
    /// The absorption coefficient under which white light that crosses `distance` scene units
    /// of the medium keeps the linear colour `color` (glTF's `KHR_materials_volume`
    /// attenuation colour and distance): `-ln(color) / distance`. An infinite distance
    /// absorbs nothing; a colour channel of 0 keeps a millionth.
    pub fn absorption_of(color: Rgb, distance: f64) -> Rgb {
        if distance.is_infinite() {
            return Rgb::BLACK;
        }
        let keep = color.0.clamp(DVec3::splat(DARKEST_ATTENUATION), DVec3::ONE);
        Rgb(DVec3::new(-keep.x.ln(), -keep.y.ln(), -keep.z.ln()) / distance)
    }

    /// The Beer-Lambert absorption coefficient (per scene unit, linear RGB) a physically based
    /// integrator reads: `absorption` plus POV-Ray's exponential fade (`fade_power` of 1000 or
    /// more), which is Beer-Lambert absorption of `(1 - fade_color) / fade_distance`. Negative
    /// parts, which would amplify light, are taken as 0. POV-Ray's polynomial fades are not
    /// absorption by a medium and add none.
    pub fn absorption_coefficient(&self) -> DVec3 {
        let fade = if self.fade_power >= 1000.0 && self.fade_distance > 0.0 {
            (DVec3::ONE - self.fade_color.0) / self.fade_distance
        } else {
            DVec3::ZERO
        };
        (self.absorption.0 + fade).max(DVec3::ZERO)
    }
}

/// Light a surface emits by itself, in radiance units: at a point with surface colour `c`
/// (pigment times texture) it emits `radiance * texture + times_color * c` W/(m^2 sr),
/// linear RGB, the same in every direction.
///
/// Readings: a scene's `emission` key is `times_color` (POV-Ray multiplies emission by the
/// pigment) and its `pbr.emissive` is `radiance` with `pbr.emissive_texture`; glTF's
/// `emissiveFactor` times `KHR_materials_emissive_strength` is `radiance` with the emissive
/// texture; OBJ's `Ke` is `radiance`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Emission {
    /// Emitted radiance in W/(m^2 sr) (linear RGB), before `texture`.
    pub radiance: Rgb,
    /// An image (linear after decoding) multiplying `radiance`.
    pub texture: Option<TextureRef>,
    /// Emitted radiance per unit of surface colour, W/(m^2 sr) (POV-Ray's `emission`). For a
    /// layered texture, the largest of its layers' (so that [`Self::can_emit`] says whether
    /// any layer glows); shading reads each [`Layer::emission`].
    pub times_color: Rgb,
    /// Emits from both sides of the surface. Otherwise (physically based integrators) only
    /// from the side the shape's normal points to; POV-Ray's emission is always two-sided.
    pub two_sided: bool,
}

impl Emission {
    /// True when this emission can be non-zero somewhere: some radiance or some radiance per
    /// unit of colour (a texture only scales `radiance`).
    pub fn can_emit(&self) -> bool {
        self.radiance.0 != glam::DVec3::ZERO || self.times_color.0 != glam::DVec3::ZERO
    }

    /// The emitted radiance in W/(m^2 sr) where the surface colour is `color` and the
    /// emission texture reads `texel` (linear RGB; 1 without a texture).
    pub fn radiance_at(&self, color: Rgb, texel: Rgb) -> Rgb {
        Rgb(self.radiance.0 * texel.0 + self.times_color.0 * color.0)
    }
}

impl Material {
    /// True when an image drives any of its parameters (so shading needs the surface's uv).
    pub fn is_textured(&self) -> bool {
        self.emission.texture.is_some()
            || match &self.surface {
                SurfaceModel::Finish(f) => f.texture.is_some(),
                SurfaceModel::MetallicRoughness(m) => {
                    m.finish.texture.is_some()
                        || m.metallic_roughness_texture.is_some()
                        || m.extension_textures().next().is_some()
                }
                SurfaceModel::Mtl(m) => m.map_kd.is_some(),
                SurfaceModel::Physical(p) => p.texture.is_some(),
                SurfaceModel::Layered(layers) => layers.iter().any(|l| l.finish.texture.is_some()),
            }
    }

    /// The first non-finite or out-of-range parameter, as (key, message); keys are the
    /// scene file's for finishes and glTF's or MTL's names for imported surfaces.
    pub fn check(&self) -> Result<(), (&'static str, String)> {
        let mut colors = vec![
            ("emission", self.emission.times_color),
            ("emissive", self.emission.radiance),
            ("fade_color", self.interior.fade_color),
            ("attenuation_distance", self.interior.absorption),
        ];
        let mut numbers = vec![
            ("ior", self.interior.ior),
            ("fade_distance", self.interior.fade_distance),
            ("fade_power", self.interior.fade_power),
        ];
        let mut textures: Vec<&TextureRef> = self.emission.texture.iter().collect();
        match &self.surface {
            SurfaceModel::Finish(f) => check_finish(f)?,
            SurfaceModel::Layered(layers) => {
                for layer in layers {
                    check_finish(&layer.finish)?;
                    check_finite(&[("emission", layer.emission)], &[])?;
                }
            }
            SurfaceModel::MetallicRoughness(p) => {
                check_finish(&p.finish)?;
                for (key, v) in [
                    ("metallic", p.metallic),
                    ("roughness", p.roughness),
                    ("specular", p.specular),
                    ("transmission", p.transmission),
                    ("clearcoat", p.clearcoat),
                    ("clearcoat_roughness", p.clearcoat_roughness),
                ] {
                    if !(0.0..=1.0).contains(&v) {
                        return Err((key, format!("must be between 0 and 1, got {v}")));
                    }
                }
                check_ior(p.ior)?;
                colors.push(("specularColorFactor", p.specular_color));
                if p.specular_color.0.min_element() < 0.0 {
                    return Err(("specularColorFactor", "must not be negative".into()));
                }
                numbers.push(("alpha", p.alpha));
                if let AlphaMode::Mask { cutoff } = p.alpha_mode {
                    numbers.push(("alphaCutoff", cutoff));
                }
                textures.extend(&p.metallic_roughness_texture);
                textures.extend(p.extension_textures());
            }
            SurfaceModel::Physical(p) => {
                colors.push(("color", p.color));
                textures.extend(&p.texture);
                check_finite(&colors, &numbers)?;
                p.scattering.check()?;
            }
            SurfaceModel::Mtl(m) => {
                colors.extend([("Kd", m.kd), ("Ks", m.ks)].into_iter().filter_map(|(k, c)| Some((k, c?))));
                numbers.extend([("Ns", m.ns), ("Ni", m.ni), ("d", m.d)].into_iter().filter_map(|(k, v)| Some((k, v?))));
                textures.extend(&m.map_kd);
            }
        }
        check_finite(&colors, &numbers)?;
        if self.interior.ior <= 0.0 || self.interior.ior > crate::limits::MAX_IOR {
            let max = crate::limits::MAX_IOR;
            return Err(("ior", format!("must be greater than 0 and at most {max}, got {}", self.interior.ior)));
        }
        for t in textures {
            t.check()?;
        }
        Ok(())
    }
}

impl Scattering {
    /// The first out-of-range parameter, as (key under `bsdf`, message).
    pub fn check(&self) -> Result<(), (&'static str, String)> {
        let (alpha, ior) = match *self {
            Scattering::Diffuse => (None, None),
            Scattering::Conductor { eta, k, alpha } => {
                check_finite(&[("bsdf.eta", eta), ("bsdf.k", k)], &[])?;
                for (key, c) in [("bsdf.eta", eta), ("bsdf.k", k)] {
                    if c.0.min_element() < 0.0 {
                        return Err((key, format!("must not be negative, got {:?}", c.0.to_array())));
                    }
                }
                (Some(alpha), None)
            }
            Scattering::Dielectric { ior, alpha } | Scattering::Plastic { ior, alpha } => (Some(alpha), Some(ior)),
            Scattering::ThinDielectric { ior } => (None, Some(ior)),
        };
        if let Some(alpha) = alpha
            && !(0.0..=1.0).contains(&alpha)
        {
            return Err(("bsdf.alpha", format!("must be between 0 and 1, got {alpha}")));
        }
        if let Some(ior) = ior
            && !(ior.is_finite() && (MIN_IOR..=MAX_IOR).contains(&ior))
        {
            return Err(("bsdf.ior", format!("must be between {MIN_IOR} and {MAX_IOR}, got {ior}")));
        }
        Ok(())
    }
}

/// The smallest relative index of refraction a `bsdf` accepts (an air bubble in diamond is
/// about 0.41).
pub const MIN_IOR: f64 = 0.2;
/// The largest relative index of refraction a `bsdf` accepts (diamond is 2.42; 5 leaves
/// room for exotic media while catching typos such as 15).
pub const MAX_IOR: f64 = 5.0;

/// A metallic-roughness index of refraction: 0 (`KHR_materials_ior`'s Fresnel of 1 at every
/// angle) or between 1 and [`MAX_IOR`].
pub(crate) fn check_ior(ior: f64) -> Result<(), (&'static str, String)> {
    if ior == 0.0 || (1.0..=MAX_IOR).contains(&ior) {
        Ok(())
    } else {
        Err(("ior", format!("must be 0 or between 1 and {MAX_IOR}, got {}", crate::diagnostics::shown_number(ior))))
    }
}

/// The first of `colors`, then of `numbers`, that is not finite, as (key, message).
pub(crate) fn check_finite(
    colors: &[(&'static str, Rgb)],
    numbers: &[(&'static str, f64)],
) -> Result<(), (&'static str, String)> {
    use crate::limits::{MAX_COEFFICIENT, MAX_COLOR_COMPONENT};
    if let Some((key, c)) = colors.iter().find(|(_, c)| !c.is_finite()) {
        return Err((key, format!("must be finite, got {:?}", c.0.to_array())));
    }
    if let Some((key, c)) = colors.iter().find(|(_, c)| c.0.abs().max_element() > MAX_COLOR_COMPONENT) {
        return Err((
            key,
            format!(
                "components must lie within ±{MAX_COLOR_COMPONENT:e} (products would overflow), got {:?}",
                c.0.to_array()
            ),
        ));
    }
    if let Some((key, v)) = numbers.iter().find(|(_, v)| !v.is_finite()) {
        return Err((key, format!("must be finite, got {v}")));
    }
    if let Some((key, v)) = numbers.iter().find(|(_, v)| v.abs() > MAX_COEFFICIENT) {
        let v = crate::diagnostics::shown_number(*v);
        return Err((key, format!("must lie within ±{MAX_COEFFICIENT:e} (products would overflow), got {v}")));
    }
    Ok(())
}

/// The checks of [`MaterialSpec::check`] on a finish's own fields.
fn check_finish(f: &Finish) -> Result<(), (&'static str, String)> {
    let colors = [
        ("color", f.color),
        ("ambient", f.ambient),
        ("reflection.min", f.reflection.min),
        ("reflection.max", f.reflection.max),
    ];
    let numbers = [
        ("filter", f.filter),
        ("transmit", f.transmit),
        ("diffuse", f.diffuse),
        ("brilliance", f.brilliance),
        ("phong", f.phong),
        ("phong_size", f.phong_size),
        ("specular", f.specular),
        ("roughness", f.roughness),
        ("metallic", f.metallic),
        ("reflection.falloff", f.reflection.falloff),
        ("reflection.exponent", f.reflection.exponent),
        ("reflection.metallic", f.reflection.metallic),
    ];
    check_finite(&colors, &numbers)?;
    if f.roughness <= 0.0 {
        return Err(("roughness", format!("must be greater than 0, got {}", f.roughness)));
    }
    if f.reflection.exponent <= 0.0 {
        return Err(("reflection.exponent", "must be greater than 0".into()));
    }
    if let Some(t) = &f.texture {
        t.check()?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec(text: &str) -> Material {
        toml::from_str::<MaterialSpec>(text).unwrap().to_material()
    }

    #[test]
    fn a_scene_emission_is_radiance_times_the_colour() {
        let m = spec("color = [0.5, 1, 0.25]\nemission = 2");
        assert_eq!(m.emission.times_color, Rgb::grey(2.0));
        assert_eq!(m.emission.radiance, Rgb::BLACK);
        let SurfaceModel::Finish(f) = &m.surface else { panic!("a finish") };
        assert_eq!(m.emission.radiance_at(f.color, Rgb::WHITE), Rgb::new(1.0, 2.0, 0.5));
    }

    #[test]
    fn a_scene_pbr_emissive_is_radiance_beside_the_finish_emission() {
        let m = spec("color = 0.5\nemission = 1\npbr = { metallic = 0.2, roughness = 0.4, emissive = [3, 0, 0] }");
        assert_eq!(m.emission.radiance, Rgb::new(3.0, 0.0, 0.0));
        let SurfaceModel::MetallicRoughness(p) = &m.surface else { panic!("metallic-roughness") };
        assert_eq!((p.metallic, p.roughness, p.alpha_mode), (0.2, 0.4, AlphaMode::Opaque));
        assert_eq!(m.emission.radiance_at(p.finish.color, Rgb::WHITE), Rgb::new(3.5, 0.5, 0.5));
    }

    #[test]
    fn interior_and_finish_keep_the_written_values() {
        let m = spec("ior = 1.5\nfade_distance = 2\nfade_power = 1001\nroughness = 0.01\nmetallic = 0.5");
        assert_eq!(
            m.interior,
            Interior {
                ior: 1.5,
                fade_distance: 2.0,
                fade_power: 1001.0,
                fade_color: Rgb::BLACK,
                absorption: Rgb::BLACK
            }
        );
        let SurfaceModel::Finish(f) = &m.surface else { panic!("a finish") };
        assert_eq!((f.roughness, f.metallic), (0.01, 0.5));
        assert!(m.check().is_ok());
    }

    #[test]
    fn check_rejects_non_finite_mtl_values() {
        let mut m = Material {
            surface: SurfaceModel::Mtl(Mtl { ns: Some(f64::NAN), ..Mtl::default() }),
            ..Material::default()
        };
        assert_eq!(m.check().unwrap_err().0, "Ns");
        m.surface = SurfaceModel::Mtl(Mtl::default());
        assert!(m.check().is_ok());
    }
}
