//! The authored form of a material: what a scene file's `[materials.NAME]` table or inline
//! `material = { ... }` says, as serde reads and writes it (load, save, the schema and
//! `export pov` use it). Its keys are POV-Ray's pigment, finish and interior under POV-Ray's
//! meanings, plus an optional glTF metallic-roughness table `pbr`.
//! [`MaterialSpec::to_material`] turns it into the [`Material`] Prism renders with.
//!
//! Every default is POV-Ray 3.7's, except the colour, which is white (POV-Ray's default
//! pigment is black; the exporter always writes the colour).

use std::fmt;

use glam::DVec3;
use schemars::JsonSchema;
use serde::de::{self, Deserializer, MapAccess, SeqAccess, Visitor};
use serde::{Deserialize, Serialize};

use super::normal::{Normal, NormalField};
use super::pattern::{Pigment, PigmentField};
use super::{Emission, Finish, Interior, Layer, Material, MetallicRoughness, Physical, Scattering, SurfaceModel};
use crate::color::Rgb;
use crate::texture::{ColorSpace, TextureRef};

/// The most layers a layered material takes: every layer is shaded at every hit (a stack of
/// clear layers is walked to the bottom), so this bounds the work per hit.
pub const MAX_LAYERS: usize = 64;

/// A material as a scene file writes it (POV-Ray's meanings; see the module docs). The
/// schema keeps the name `Material`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
#[schemars(rename = "Material", description = "A surface and interior description.")]
pub struct MaterialSpec {
    /// Pigment colour (linear RGB).
    pub color: Rgb,
    /// Fraction of light that passes through, tinted by the colour (POV-Ray `filter`).
    pub filter: f64,
    /// Fraction of light that passes through untinted (POV-Ray `transmit`).
    pub transmit: f64,
    /// Ambient coefficient, multiplied by the world's `ambient_light` and the colour.
    pub ambient: Rgb,
    /// Light the surface emits by itself (multiplied by the colour, like ambient).
    pub emission: Rgb,
    /// Under `path`: emit from both sides of the surface, not only the side its normal
    /// points to (the classic integrator's emission is always two-sided).
    pub emission_two_sided: bool,
    /// Diffuse coefficient.
    pub diffuse: f64,
    /// Exponent on the diffuse cosine (1 = Lambert).
    pub brilliance: f64,
    /// Phong highlight strength.
    pub phong: f64,
    /// Phong exponent.
    pub phong_size: f64,
    /// Blinn specular highlight strength.
    pub specular: f64,
    /// Specular roughness; the exponent is 1 / roughness.
    pub roughness: f64,
    /// How much highlights take the pigment's colour (0..1).
    pub metallic: f64,
    /// Mirror reflection.
    pub reflection: Reflection,
    /// Scales transmitted light by (1 - reflection) so the surface does not create light.
    pub conserve_energy: bool,
    /// Index of refraction of the interior (1 = no refraction).
    pub ior: f64,
    /// Interior fade distance (0 = no fade).
    pub fade_distance: f64,
    /// Interior fade power (>= 1000 switches to exponential attenuation, as in POV-Ray).
    pub fade_power: f64,
    /// Colour the interior fades toward.
    pub fade_color: Rgb,
    /// Physically based absorption inside the object (glTF's `KHR_materials_volume`): the
    /// linear colour white light keeps after crossing `attenuation_distance` of the interior.
    /// Components between 0 and 1; needs `attenuation_distance`.
    pub attenuation_color: Rgb,
    /// The distance in scene units over which white light inside takes `attenuation_color`
    /// (Beer-Lambert: `attenuation_color ^ (d / attenuation_distance)` after a distance `d`).
    /// Absent (or `inf`): no absorption. Exclusive with POV-Ray's `fade_*`, which the classic
    /// integrator reads it as (an exponential fade).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub attenuation_distance: Option<f64>,
    /// An image whose (linear) colour multiplies `color`: a path relative to the scene file,
    /// or a table `{ file, wrap, offset, scale, rotation }`. Needs a shape with texture
    /// coordinates (meshes from glTF or OBJ files).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub texture: Option<TextureRef>,
    /// A POV-Ray pigment pattern (`{ pattern = "checker", colors = [...] }`, `{ pattern =
    /// "gradient", vector = [0, 1, 0], color_map = [[0, [1, 1, 1]], [1, [0, 0, 0]]] }`, see
    /// `docs/scene-format.md`): the colour, filter and transmit vary over the object, in its
    /// own space. It replaces `color`, `filter` and `transmit`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pigment: Option<Pigment>,
    /// A POV-Ray normal pattern (`{ pattern = "bumps", bump_size = 0.5, scale = 0.2 }`, see
    /// `docs/scene-format.md`): tilts the shading normal over the object, in its own space.
    /// The classic integrator shades with it; `path` ignores it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub normal: Option<Normal>,
    /// glTF metallic-roughness parameters. When present, the classic finish (diffuse,
    /// highlights, reflection) is derived from them at every hit (see `docs/meshes.md`)
    /// instead of read from the fields above.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pbr: Option<Pbr>,
    /// A physically based scattering model (`docs/scene-format.md`, "Physically based
    /// materials"): `{ type = "diffuse" | "conductor" | "dielectric" | "thin_dielectric" |
    /// "plastic", ... }`. With it, `color` and `texture` tint the model, `emission` is
    /// radiance (not multiplied by the colour), and the POV-Ray finish keys above may not be written:
    /// the classic integrator derives its finish from the model.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub bsdf: Option<BsdfSpec>,
    /// POV-Ray's layered texture: layers bottom first, as POV-Ray writes `texture { }` blocks
    /// (the last is on top, and each layer's `filter` and `transmit` let the layers below
    /// show through). Each layer takes the pigment and finish keys of a material (`color`,
    /// `filter`, `transmit`, `pigment`, `normal`, `texture`, `ambient`, `emission`,
    /// `diffuse`, ..., `reflection`, `conserve_energy`); the interior (`ior`, `fade_*`) is
    /// the object's and is written beside `layers`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub layers: Option<Vec<MaterialSpec>>,
}

/// A scene's `bsdf` table: a physically based scattering model and its parameters, named and
/// valued as Mitsuba 3's BSDF plugins (`alpha` is GGX's roughness itself).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum BsdfSpec {
    /// Lambertian reflection with reflectance `color`.
    Diffuse {},
    /// A metal: a named one (`metal = "Au"`; Au, Ag, Cu, Al, Cr, Fe, Ti) or a complex index
    /// of refraction `eta` + i `k` per RGB channel; `color` tints its reflection.
    Conductor {
        /// A named metal (exclusive with `eta` and `k`).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        metal: Option<String>,
        /// Real part of the index of refraction (linear RGB).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        eta: Option<Rgb>,
        /// Imaginary part of the index of refraction (linear RGB).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        k: Option<Rgb>,
        /// GGX roughness alpha, 0 (mirror) to 1.
        #[serde(default)]
        alpha: f64,
    },
    /// Glass or water: index of refraction `ior` (inside over outside, default 1.5); `color`
    /// tints transmitted light.
    Dielectric {
        /// Relative index of refraction.
        #[serde(default = "glass_ior")]
        ior: f64,
        /// GGX roughness alpha, 0 (smooth) to 1.
        #[serde(default)]
        alpha: f64,
    },
    /// A thin slab (window pane, soap film) of index `ior`: light passes straight through.
    ThinDielectric {
        /// Index of refraction of the slab.
        #[serde(default = "glass_ior")]
        ior: f64,
    },
    /// Diffuse `color` under a clear dielectric coating of index `ior` (Mitsuba's `plastic`,
    /// `roughplastic` when `alpha` > 0).
    Plastic {
        /// Index of refraction of the coating.
        #[serde(default = "plastic_ior")]
        ior: f64,
        /// GGX roughness alpha of the coating, 0 (smooth) to 1.
        #[serde(default)]
        alpha: f64,
    },
}

fn glass_ior() -> f64 {
    1.5
}

/// Mitsuba's default `int_ior` of plastic (polypropylene).
fn plastic_ior() -> f64 {
    1.49
}

impl BsdfSpec {
    /// The scattering model, with a named metal looked up; (key, message) when the
    /// parameters contradict each other.
    pub fn to_scattering(&self) -> Result<Scattering, (&'static str, String)> {
        Ok(match self {
            BsdfSpec::Diffuse {} => Scattering::Diffuse,
            BsdfSpec::Conductor { metal, eta, k, alpha } => {
                let (eta, k) = match (metal, eta, k) {
                    (Some(name), None, None) => super::metals::metal(name).ok_or_else(|| {
                        ("bsdf.metal", format!("unknown metal; known: {}", super::metals::METAL_NAMES.join(", ")))
                    })?,
                    (None, Some(eta), Some(k)) => (eta.0, k.0),
                    (Some(_), _, _) => return Err(("bsdf.metal", "give either `metal` or `eta` and `k`".into())),
                    (None, _, _) => return Err(("bsdf.eta", "a conductor needs `metal` or both `eta` and `k`".into())),
                };
                Scattering::Conductor { eta: Rgb(eta), k: Rgb(k), alpha: *alpha }
            }
            BsdfSpec::Dielectric { ior, alpha } => Scattering::Dielectric { ior: *ior, alpha: *alpha },
            BsdfSpec::ThinDielectric { ior } => Scattering::ThinDielectric { ior: *ior },
            BsdfSpec::Plastic { ior, alpha } => Scattering::Plastic { ior: *ior, alpha: *alpha },
        })
    }
}

/// glTF 2.0 metallic-roughness parameters (the core material model plus emission).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct Pbr {
    /// Metalness factor (0 = dielectric, 1 = metal).
    pub metallic: f64,
    /// Perceptual roughness factor (0 = mirror-smooth, 1 = fully rough).
    pub roughness: f64,
    /// Texture whose blue channel multiplies `metallic` and green channel `roughness`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub metallic_roughness_texture: Option<TextureRef>,
    /// Emitted radiance (linear RGB, not multiplied by the colour).
    pub emissive: Rgb,
    /// Texture (sRGB) multiplying `emissive`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub emissive_texture: Option<TextureRef>,
    /// Index of refraction of the dielectric part: 0 (a Fresnel of 1 at every angle) or 1 to
    /// 5 (`KHR_materials_ior`).
    pub ior: f64,
    /// Strength of the dielectric's specular reflection, 0..1 (`KHR_materials_specular`).
    pub specular: f64,
    /// Texture (linear) whose alpha channel multiplies `specular`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub specular_texture: Option<TextureRef>,
    /// Colour of the dielectric's F0 (linear RGB, not negative; the product with the ior's F0
    /// is clamped to 1).
    pub specular_color: Rgb,
    /// Texture (sRGB) multiplying `specular_color`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub specular_color_texture: Option<TextureRef>,
    /// Share of the dielectric's diffuse base passing straight through instead, tinted by the
    /// colour (thin-walled `KHR_materials_transmission`), 0..1.
    pub transmission: f64,
    /// Texture (linear) whose red channel multiplies `transmission`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub transmission_texture: Option<TextureRef>,
    /// Clear coat strength (`KHR_materials_clearcoat`), 0..1.
    pub clearcoat: f64,
    /// Texture (linear) whose red channel multiplies `clearcoat`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub clearcoat_texture: Option<TextureRef>,
    /// Perceptual roughness of the clear coat, 0..1.
    pub clearcoat_roughness: f64,
    /// Texture (linear) whose green channel multiplies `clearcoat_roughness`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub clearcoat_roughness_texture: Option<TextureRef>,
}

impl Default for Pbr {
    fn default() -> Self {
        Self {
            metallic: 1.0,
            roughness: 1.0,
            metallic_roughness_texture: None,
            emissive: Rgb::BLACK,
            emissive_texture: None,
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
}

impl Default for MaterialSpec {
    fn default() -> Self {
        Self {
            color: Rgb::WHITE,
            filter: 0.0,
            transmit: 0.0,
            ambient: Rgb::grey(0.1),
            emission: Rgb::BLACK,
            emission_two_sided: false,
            diffuse: 0.6,
            brilliance: 1.0,
            phong: 0.0,
            phong_size: 40.0,
            specular: 0.0,
            roughness: 0.05,
            metallic: 0.0,
            reflection: Reflection::default(),
            conserve_energy: false,
            ior: 1.0,
            fade_distance: 0.0,
            fade_power: 0.0,
            fade_color: Rgb::BLACK,
            attenuation_color: Rgb::WHITE,
            attenuation_distance: None,
            texture: None,
            pigment: None,
            normal: None,
            pbr: None,
            bsdf: None,
            layers: None,
        }
    }
}

impl MaterialSpec {
    /// The first non-finite or out-of-range parameter, or misplaced key, as (key path under
    /// the material, message).
    pub fn check(&self) -> Result<(), (String, String)> {
        let owned = |(key, message): (&str, String)| (key.to_string(), message);
        let Some(layers) = &self.layers else {
            self.check_single().map_err(owned)?;
            self.check_pigment()?;
            return self.check_normal();
        };
        if layers.is_empty() {
            return Err((
                "layers".into(),
                "needs at least one layer (POV-Ray's `texture { }` blocks, bottom first)".into(),
            ));
        }
        if layers.len() > MAX_LAYERS {
            return Err((
                "layers".into(),
                format!("has {} layers; at most {MAX_LAYERS} (each is shaded at every hit)", layers.len()),
            ));
        }
        if let Some(key) = self.layer_keys_written().first() {
            return Err((
                key.to_string(),
                "belongs to a layer: write it inside one of `layers` (beside `layers` only the interior, \
                 `ior`, `fade_*` and `attenuation_*`, and `emission_two_sided` may be written)"
                    .into(),
            ));
        }
        Self { layers: None, ..self.clone() }.check_single().map_err(owned)?;
        for (i, layer) in layers.iter().enumerate() {
            let at = |key: &str| format!("layers[{i}].{key}");
            if layer.layers.is_some() {
                return Err((at("layers"), "layers do not nest: list every layer in one `layers`".into()));
            }
            for (key, written) in [("pbr", layer.pbr.is_some()), ("bsdf", layer.bsdf.is_some())] {
                if written {
                    return Err((
                        at(key),
                        format!("a layer is a POV-Ray pigment and finish: `{key}` has no layered form"),
                    ));
                }
            }
            let d = Self::default();
            let interior = [
                ("ior", layer.ior != d.ior),
                ("fade_distance", layer.fade_distance != d.fade_distance),
                ("fade_power", layer.fade_power != d.fade_power),
                ("fade_color", layer.fade_color != d.fade_color),
                ("attenuation_color", layer.attenuation_color != d.attenuation_color),
                ("attenuation_distance", layer.attenuation_distance != d.attenuation_distance),
                ("emission_two_sided", layer.emission_two_sided != d.emission_two_sided),
            ];
            if let Some((key, _)) = interior.iter().find(|(_, w)| *w) {
                return Err((at(key), "is the object's, shared by every layer: write it beside `layers`".into()));
            }
            layer.check_single().map_err(|(key, message)| (at(key), message))?;
            layer.check_pigment().map_err(|(key, message)| (at(&key), message))?;
            layer.check_normal().map_err(|(key, message)| (at(&key), message))?;
        }
        Ok(())
    }

    /// The pigment and finish keys written (differing from the defaults): a layer's keys.
    fn layer_keys_written(&self) -> Vec<&'static str> {
        let d = Self::default();
        [
            ("color", self.color != d.color),
            ("filter", self.filter != d.filter),
            ("transmit", self.transmit != d.transmit),
            ("ambient", self.ambient != d.ambient),
            ("emission", self.emission != d.emission),
            ("diffuse", self.diffuse != d.diffuse),
            ("brilliance", self.brilliance != d.brilliance),
            ("phong", self.phong != d.phong),
            ("phong_size", self.phong_size != d.phong_size),
            ("specular", self.specular != d.specular),
            ("roughness", self.roughness != d.roughness),
            ("metallic", self.metallic != d.metallic),
            ("reflection", self.reflection != d.reflection),
            ("conserve_energy", self.conserve_energy != d.conserve_energy),
            ("texture", self.texture.is_some()),
            ("pigment", self.pigment.is_some()),
            ("normal", self.normal.is_some()),
            ("pbr", self.pbr.is_some()),
            ("bsdf", self.bsdf.is_some()),
        ]
        .into_iter()
        .filter_map(|(key, written)| written.then_some(key))
        .collect()
    }

    /// [`Self::check`] of a material without layers, its pigment apart.
    fn check_single(&self) -> Result<(), (&'static str, String)> {
        let finish = self.finish();
        super::check_finish(&finish)?;
        super::check_finite(
            &[("emission", self.emission), ("fade_color", self.fade_color)],
            &[("ior", self.ior), ("fade_distance", self.fade_distance), ("fade_power", self.fade_power)],
        )?;
        if self.ior <= 0.0 || self.ior > crate::limits::MAX_IOR {
            return Err((
                "ior",
                format!("must be greater than 0 and at most {}, got {}", crate::limits::MAX_IOR, self.ior),
            ));
        }
        self.check_attenuation()?;
        if let Some(bsdf) = &self.bsdf {
            self.check_only_bsdf()?;
            bsdf.to_scattering()?.check()?;
            if self.emission.0.min_element() < 0.0 {
                return Err((
                    "emission",
                    format!("radiance must not be negative, got {:?}", self.emission.0.to_array()),
                ));
            }
        }
        if let Some(p) = &self.pbr {
            for (key, v) in [
                ("pbr.metallic", p.metallic),
                ("pbr.roughness", p.roughness),
                ("pbr.specular", p.specular),
                ("pbr.transmission", p.transmission),
                ("pbr.clearcoat", p.clearcoat),
                ("pbr.clearcoat_roughness", p.clearcoat_roughness),
            ] {
                if !(0.0..=1.0).contains(&v) {
                    return Err((key, format!("must be between 0 and 1, got {v}")));
                }
            }
            super::check_ior(p.ior).map_err(|(_, message)| ("pbr.ior", message))?;
            super::check_finite(&[("pbr.specular_color", p.specular_color)], &[])?;
            if p.specular_color.0.min_element() < 0.0 {
                return Err(("pbr.specular_color", "must not be negative".into()));
            }
            // A colour like `emission` (finite, within the limit beyond which its products
            // overflow), and radiance, so not negative.
            super::check_finite(&[("pbr.emissive", p.emissive)], &[])?;
            if p.emissive.0.min_element() < 0.0 {
                return Err(("pbr.emissive", "must not be negative".into()));
            }
            let textures = [
                &p.metallic_roughness_texture,
                &p.emissive_texture,
                &p.specular_texture,
                &p.specular_color_texture,
                &p.transmission_texture,
                &p.clearcoat_texture,
                &p.clearcoat_roughness_texture,
            ];
            for t in textures.into_iter().flatten() {
                t.check()?;
            }
        }
        Ok(())
    }

    /// The pigment's first problem (its key path, e.g. `pigment.pigment_map[1].color_map`),
    /// or a key written beside it that it replaces or that belongs to another surface model.
    fn check_pigment(&self) -> Result<(), (String, String)> {
        let Some(pigment) = &self.pigment else { return Ok(()) };
        let d = Self::default();
        let beside = [
            ("color", self.color != d.color, "the pigment gives the colour"),
            ("filter", self.filter != d.filter, "the pigment's colours give filter"),
            ("transmit", self.transmit != d.transmit, "the pigment's colours give transmit"),
            ("texture", self.texture.is_some(), "a pigment pattern and an image texture do not combine"),
            ("bsdf", self.bsdf.is_some(), "a pigment pattern needs a POV-Ray finish, not a `bsdf`"),
            ("pbr", self.pbr.is_some(), "a pigment pattern needs a POV-Ray finish, not `pbr`"),
        ];
        if let Some((key, _, why)) = beside.iter().find(|(_, written, _)| *written) {
            return Err((key.to_string(), format!("cannot be written beside `pigment`: {why}")));
        }
        pigment.check().map_err(|(key, message)| (format!("pigment.{key}"), message))
    }

    /// The normal pattern's first problem (its key path, e.g. `normal.normal_map[0][1].scale`),
    /// or a surface model it does not apply to.
    fn check_normal(&self) -> Result<(), (String, String)> {
        let Some(normal) = &self.normal else { return Ok(()) };
        if self.bsdf.is_some() {
            return Err(("bsdf".into(), "a normal pattern needs a POV-Ray finish, not a `bsdf`".into()));
        }
        if self.pbr.is_some() {
            return Err(("pbr".into(), "a normal pattern needs a POV-Ray finish, not `pbr`".into()));
        }
        normal.check().map_err(|(key, message)| (format!("normal.{key}"), message))
    }

    /// With a `bsdf`, the first POV-Ray finish or interior key (or `pbr`) written beside it:
    /// those belong to another model.
    fn check_only_bsdf(&self) -> Result<(), (&'static str, String)> {
        let d = Self::default();
        let written = [
            ("filter", self.filter != d.filter),
            ("transmit", self.transmit != d.transmit),
            ("ambient", self.ambient != d.ambient),
            ("diffuse", self.diffuse != d.diffuse),
            ("brilliance", self.brilliance != d.brilliance),
            ("phong", self.phong != d.phong),
            ("phong_size", self.phong_size != d.phong_size),
            ("specular", self.specular != d.specular),
            ("roughness", self.roughness != d.roughness),
            ("metallic", self.metallic != d.metallic),
            ("reflection", self.reflection != d.reflection),
            ("conserve_energy", self.conserve_energy != d.conserve_energy),
            ("ior", self.ior != d.ior),
            ("fade_distance", self.fade_distance != d.fade_distance),
            ("fade_power", self.fade_power != d.fade_power),
            ("fade_color", self.fade_color != d.fade_color),
            ("pbr", self.pbr.is_some()),
        ];
        match written.iter().find(|(_, w)| *w) {
            Some((key, _)) => Err((
                key,
                "is a POV-Ray finish key, and this material has a `bsdf`: write the model's own \
                 parameters inside `bsdf` (the classic integrator derives its finish from it)"
                    .into(),
            )),
            None => Ok(()),
        }
    }

    /// Every image map of the material's pigments (its layers' and `pigment_map` entries'
    /// included) and every bump map of its normals (theirs and `normal_map` entries'), with
    /// its key path under the material (`pigment.image_map`, `normal.bump_map`,
    /// `layers[1].pigment.pigment_map[0][1].image_map`) and whether it is a bump map (read
    /// without gamma, as POV-Ray reads one).
    pub fn image_maps_mut(&mut self) -> Vec<(String, &mut super::image_map::ImageMap, bool)> {
        let mut out = Vec::new();
        if let Some(p) = self.pigment.as_mut() {
            out.extend(p.image_maps_mut().into_iter().map(|(key, map)| (format!("pigment.{key}"), map, false)));
        }
        if let Some(n) = self.normal.as_mut() {
            out.extend(n.bump_maps_mut().into_iter().map(|(key, map)| (format!("normal.{key}"), map, true)));
        }
        for (i, layer) in self.layers.iter_mut().flatten().enumerate() {
            out.extend(
                layer.image_maps_mut().into_iter().map(|(key, map, raw)| (format!("layers[{i}].{key}"), map, raw)),
            );
        }
        out
    }

    /// Every texture reference of the material with the colour space of its image, for
    /// loading the images.
    pub fn textures_mut(&mut self) -> Vec<(&mut TextureRef, ColorSpace)> {
        let mut out: Vec<(&mut TextureRef, ColorSpace)> = Vec::new();
        if let Some(t) = self.texture.as_mut() {
            out.push((t, ColorSpace::Srgb));
        }
        if let Some(p) = self.pbr.as_mut() {
            if let Some(t) = p.metallic_roughness_texture.as_mut() {
                out.push((t, ColorSpace::Linear));
            }
            if let Some(t) = p.emissive_texture.as_mut() {
                out.push((t, ColorSpace::Srgb));
            }
            if let Some(t) = p.specular_color_texture.as_mut() {
                out.push((t, ColorSpace::Srgb));
            }
            let linear = [
                &mut p.specular_texture,
                &mut p.transmission_texture,
                &mut p.clearcoat_texture,
                &mut p.clearcoat_roughness_texture,
            ];
            for t in linear.into_iter().flatten() {
                out.push((t, ColorSpace::Linear));
            }
        }
        for layer in self.layers.iter_mut().flatten() {
            out.extend(layer.textures_mut());
        }
        out
    }

    /// The POV-Ray pigment and finish the fields write.
    fn finish(&self) -> Finish {
        Finish {
            color: self.color,
            filter: self.filter,
            transmit: self.transmit,
            ambient: self.ambient,
            diffuse: self.diffuse,
            brilliance: self.brilliance,
            phong: self.phong,
            phong_size: self.phong_size,
            specular: self.specular,
            roughness: self.roughness,
            metallic: self.metallic,
            reflection: self.reflection,
            conserve_energy: self.conserve_energy,
            texture: self.texture.clone(),
            pigment: self.pigment.as_ref().map(|p| std::sync::Arc::new(PigmentField::new(p))),
            normal: self.normal.as_ref().map(|n| std::sync::Arc::new(NormalField::new(n))),
        }
    }

    /// The material Prism renders with: the POV-Ray finish as written (a metallic-roughness
    /// surface when `pbr` is given, starting from the finish written beside it), the
    /// interior, and the emission read in radiance units (`emission` times the colour, plus
    /// `pbr.emissive` times its texture).
    pub fn to_material(&self) -> Material {
        let finish = self.finish();
        let mut emission = Emission { times_color: self.emission, ..Emission::default() };
        let physical = self.bsdf.as_ref().and_then(|b| b.to_scattering().ok());
        if physical.is_some() {
            // A physical model's emission is radiance, not radiance per unit of colour.
            emission = Emission { radiance: self.emission, ..Emission::default() };
        }
        emission.two_sided = self.emission_two_sided;
        if let Some(layers) = &self.layers {
            let layers: Vec<Layer> =
                layers.iter().map(|l| Layer { finish: l.finish(), emission: l.emission }).collect();
            // Shading reads each layer's emission; this says whether any layer glows.
            emission.times_color =
                Rgb(layers.iter().map(|l| l.emission.0.abs()).fold(glam::DVec3::ZERO, glam::DVec3::max));
            return Material { surface: SurfaceModel::Layered(layers), interior: self.interior(), emission };
        }
        let surface = match (&self.pbr, physical) {
            (_, Some(scattering)) => {
                SurfaceModel::Physical(Physical { scattering, color: self.color, texture: self.texture.clone() })
            }
            (None, None) => SurfaceModel::Finish(finish),
            (Some(p), None) => {
                emission.radiance = p.emissive;
                emission.texture = p.emissive_texture.clone();
                SurfaceModel::MetallicRoughness(Box::new(MetallicRoughness {
                    metallic_roughness_texture: p.metallic_roughness_texture.clone(),
                    ior: p.ior,
                    specular: p.specular,
                    specular_texture: p.specular_texture.clone(),
                    specular_color: p.specular_color,
                    specular_color_texture: p.specular_color_texture.clone(),
                    transmission: p.transmission,
                    transmission_texture: p.transmission_texture.clone(),
                    clearcoat: p.clearcoat,
                    clearcoat_texture: p.clearcoat_texture.clone(),
                    clearcoat_roughness: p.clearcoat_roughness,
                    clearcoat_roughness_texture: p.clearcoat_roughness_texture.clone(),
                    ..MetallicRoughness::core(finish, p.metallic, p.roughness)
                }))
            }
        };
        Material { surface, interior: self.interior(), emission }
    }

    fn interior(&self) -> Interior {
        Interior {
            ior: self.ior,
            fade_distance: self.fade_distance,
            fade_power: self.fade_power,
            fade_color: self.fade_color,
            absorption: Interior::absorption_of(
                self.attenuation_color,
                self.attenuation_distance.unwrap_or(f64::INFINITY),
            ),
        }
    }

    /// `attenuation_color` in 0..1 and `attenuation_distance` positive, given together and not
    /// beside POV-Ray's fade.
    fn check_attenuation(&self) -> Result<(), (&'static str, String)> {
        let c = self.attenuation_color.0;
        if !(c.cmpge(DVec3::ZERO).all() && c.cmple(DVec3::ONE).all()) {
            return Err((
                "attenuation_color",
                format!("components must lie between 0 and 1 (the share of light kept), got {:?}", c.to_array()),
            ));
        }
        let Some(distance) = self.attenuation_distance else {
            if self.attenuation_color != Rgb::WHITE {
                return Err((
                    "attenuation_color",
                    "needs `attenuation_distance`, the distance over which white light takes this colour".into(),
                ));
            }
            return Ok(());
        };
        if distance.is_nan() || distance <= 0.0 {
            return Err((
                "attenuation_distance",
                format!("must be greater than 0 (or `inf` for no absorption), got {distance}"),
            ));
        }
        let absorption = Interior::absorption_of(self.attenuation_color, distance).0.max_element();
        if absorption > crate::limits::MAX_COLOR_COMPONENT {
            return Err((
                "attenuation_distance",
                format!("{distance} is too short: the absorption per unit length ({absorption:e}) would overflow"),
            ));
        }
        if self.fade_distance != 0.0 {
            return Err((
                "attenuation_distance",
                "is written beside POV-Ray's `fade_distance`: give the interior either the physical \
                 attenuation or POV-Ray's fade"
                    .into(),
            ));
        }
        Ok(())
    }
}

/// Mirror reflection: written as a number, a colour, or a table
/// `{ min, max, falloff, fresnel, metallic, exponent }` (POV-Ray's `reflection { }`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Reflection {
    /// Reflectivity facing the viewer head-on.
    pub min: Rgb,
    /// Reflectivity at grazing angles.
    pub max: Rgb,
    /// Exponent of the falloff from max to min.
    pub falloff: f64,
    /// Use Fresnel's equations (needs an `ior`) between min and max.
    pub fresnel: bool,
    /// Tint the reflection by the pigment (0..1).
    pub metallic: f64,
    /// The reflected colour enters as L^(1 / exponent).
    pub exponent: f64,
}

impl Default for Reflection {
    fn default() -> Self {
        Self { min: Rgb::BLACK, max: Rgb::BLACK, falloff: 1.0, fresnel: false, metallic: 0.0, exponent: 1.0 }
    }
}

impl Reflection {
    /// True when the surface reflects anything.
    pub fn is_reflective(&self) -> bool {
        self.min.0.max_element() > 0.0 || self.max.0.max_element() > 0.0
    }
}

impl JsonSchema for Reflection {
    fn schema_name() -> std::borrow::Cow<'static, str> {
        "Reflection".into()
    }

    fn json_schema(generator: &mut schemars::SchemaGenerator) -> schemars::Schema {
        let table = generator.subschema_for::<ReflectionTable>();
        let color = generator.subschema_for::<Rgb>();
        schemars::json_schema!({
            "description": "Mirror reflection: a number or colour (constant), or a table.",
            "anyOf": [color, table]
        })
    }
}

/// The table form of `reflection`.
#[derive(Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
struct ReflectionTable {
    /// Reflectivity facing the viewer.
    min: Option<Rgb>,
    /// Reflectivity at grazing angles.
    max: Option<Rgb>,
    /// Exponent of the change from max to min.
    #[serde(default = "one")]
    falloff: f64,
    /// Use Fresnel's equations (needs an `ior`).
    #[serde(default)]
    fresnel: bool,
    /// Tint the reflection by the pigment (0..1).
    #[serde(default)]
    metallic: f64,
    /// The reflected colour enters as L^(1 / exponent).
    #[serde(default = "one")]
    exponent: f64,
}

fn one() -> f64 {
    1.0
}

impl<'de> Deserialize<'de> for Reflection {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(ReflectionVisitor)
    }
}

struct ReflectionVisitor;

impl ReflectionVisitor {
    fn constant(c: Rgb) -> Reflection {
        Reflection { min: c, max: c, ..Reflection::default() }
    }
}

impl<'de> Visitor<'de> for ReflectionVisitor {
    type Value = Reflection;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a reflection: a number, [r, g, b], or a table { min, max, falloff, fresnel, metallic, exponent }")
    }

    fn visit_f64<E: de::Error>(self, v: f64) -> Result<Reflection, E> {
        Ok(Self::constant(Rgb::grey(v)))
    }

    fn visit_i64<E: de::Error>(self, v: i64) -> Result<Reflection, E> {
        Ok(Self::constant(Rgb::grey(v as f64)))
    }

    fn visit_u64<E: de::Error>(self, v: u64) -> Result<Reflection, E> {
        Ok(Self::constant(Rgb::grey(v as f64)))
    }

    fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<Reflection, A::Error> {
        let c = Rgb::deserialize(de::value::SeqAccessDeserializer::new(seq))?;
        Ok(Self::constant(c))
    }

    fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<Reflection, A::Error> {
        let t = ReflectionTable::deserialize(de::value::MapAccessDeserializer::new(map))?;
        // POV-Ray: one colour means min = max; with fresnel and one colour, min is 0.
        let (min, max) = match (t.min, t.max) {
            (Some(min), Some(max)) => (min, max),
            (None, Some(max)) if t.fresnel => (Rgb::BLACK, max),
            (Some(c), None) | (None, Some(c)) => (c, c),
            (None, None) => (Rgb::BLACK, Rgb::BLACK),
        };
        Ok(Reflection { min, max, falloff: t.falloff, fresnel: t.fresnel, metallic: t.metallic, exponent: t.exponent })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_pov_ray_defaults() {
        let m: MaterialSpec = toml::from_str("").unwrap();
        assert_eq!(m.ambient, Rgb::grey(0.1));
        assert_eq!(m.diffuse, 0.6);
        assert_eq!(m.phong_size, 40.0);
        assert_eq!(m.roughness, 0.05);
        assert_eq!(m.ior, 1.0);
    }

    #[test]
    fn attenuation_is_the_interiors_beer_lambert_absorption() {
        let m: MaterialSpec = toml::from_str("attenuation_color = [0.5, 1.0, 0.0]\nattenuation_distance = 2").unwrap();
        assert!(m.check().is_ok());
        let a = m.to_material().interior.absorption.0;
        // White light keeps the colour after the distance: exp(-a d) = c.
        assert!(((-a.x * 2.0).exp() - 0.5).abs() < 1e-15 && a.y == 0.0, "{a}");
        // A channel of 0 keeps a millionth, not infinity.
        assert!(((-a.z * 2.0).exp() - 1e-6).abs() < 1e-18, "{a}");
        let none: MaterialSpec = toml::from_str("attenuation_distance = inf").unwrap();
        assert!(none.check().is_ok());
        assert_eq!(none.to_material().interior.absorption, Rgb::BLACK);
        assert_eq!(MaterialSpec::default().to_material().interior.absorption, Rgb::BLACK);
    }

    #[test]
    fn reflection_forms() {
        let m: MaterialSpec = toml::from_str("reflection = 0.8").unwrap();
        assert_eq!(m.reflection.min, Rgb::grey(0.8));
        let m: MaterialSpec = toml::from_str("reflection = { min = 0.1, max = 0.9, falloff = 2 }").unwrap();
        assert_eq!((m.reflection.min, m.reflection.max, m.reflection.falloff), (Rgb::grey(0.1), Rgb::grey(0.9), 2.0));
        let m: MaterialSpec = toml::from_str("reflection = { max = 1, fresnel = true }").unwrap();
        assert_eq!(m.reflection.min, Rgb::BLACK);
        assert!(toml::from_str::<MaterialSpec>("reflection = { mni = 1 }").is_err());
    }

    #[test]
    fn layers_are_materials_bottom_first_under_one_interior() {
        let m: MaterialSpec = toml::from_str(
            "ior = 1.5\n[[layers]]\ncolor = [1, 0, 0]\nemission = 0.5\n[[layers]]\ntransmit = 0.8\nphong = 1",
        )
        .unwrap();
        assert!(m.check().is_ok());
        let material = m.to_material();
        let SurfaceModel::Layered(layers) = &material.surface else { panic!("layered") };
        assert_eq!(layers.len(), 2);
        assert_eq!((layers[0].finish.color, layers[0].emission), (Rgb::new(1.0, 0.0, 0.0), Rgb::grey(0.5)));
        assert_eq!((layers[1].finish.transmit, layers[1].finish.phong), (0.8, 1.0));
        assert_eq!(material.interior.ior, 1.5);
        assert!(material.emission.can_emit());
        let back: MaterialSpec = toml::from_str(&toml::to_string(&m).unwrap()).unwrap();
        assert_eq!(m, back);
    }

    #[test]
    fn misplaced_layer_keys_are_named() {
        let err = |text: &str| toml::from_str::<MaterialSpec>(text).unwrap().check().unwrap_err().0;
        assert_eq!(err("layers = []"), "layers");
        assert_eq!(err("phong = 1\nlayers = [{}]"), "phong");
        assert_eq!(err("pigment = { pattern = \"checker\" }\nlayers = [{}]"), "pigment");
        assert_eq!(err("layers = [{}, { bsdf = { type = \"diffuse\" } }]"), "layers[1].bsdf");
        assert_eq!(err("layers = [{ pbr = {} }]"), "layers[0].pbr");
        assert_eq!(err("layers = [{ fade_distance = 2 }]"), "layers[0].fade_distance");
        assert_eq!(err("layers = [{ layers = [{}] }]"), "layers[0].layers");
        let layers = |n: usize| format!("layers = [{}]", vec!["{ transmit = 1 }"; n].join(", "));
        assert!(toml::from_str::<MaterialSpec>(&layers(MAX_LAYERS)).unwrap().check().is_ok());
        assert_eq!(err(&layers(MAX_LAYERS + 1)), "layers");
        assert_eq!(err("layers = [{}, { reflection = { exponent = 0 } }]"), "layers[1].reflection.exponent");
        assert_eq!(err("layers = [{ normal = { pattern = \"bumps\", scale = 0 } }]"), "layers[0].normal.scale");
        assert_eq!(err("ior = -1\nlayers = [{}]"), "ior");
    }

    #[test]
    fn pbr_emission_keeps_the_colour_limit() {
        let check = |text: &str| toml::from_str::<MaterialSpec>(text).unwrap().check();
        assert_eq!(check("pbr = { emissive = [1e31, 0, 0] }").unwrap_err().0, "pbr.emissive");
        assert_eq!(check("pbr = { emissive = [0, -1, 0] }").unwrap_err().0, "pbr.emissive");
        assert!(check("pbr = { emissive = [1e30, 0, 0] }").is_ok());
    }

    /// The glTF extensions' keys of `pbr`: their ranges named with the key, their values in
    /// the model, and a round trip through TOML.
    #[test]
    fn pbr_extension_keys_reach_the_model_within_their_ranges() {
        let check = |text: &str| toml::from_str::<MaterialSpec>(text).unwrap().check();
        for (text, key) in [
            ("pbr = { transmission = 1.5 }", "pbr.transmission"),
            ("pbr = { specular = 1.1 }", "pbr.specular"),
            ("pbr = { specular_color = [1, -0.5, 1] }", "pbr.specular_color"),
            ("pbr = { specular_color = [1, 1e31, 1] }", "pbr.specular_color"),
            ("pbr = { clearcoat = -0.1 }", "pbr.clearcoat"),
            ("pbr = { clearcoat_roughness = 2 }", "pbr.clearcoat_roughness"),
            ("pbr = { ior = 0.5 }", "pbr.ior"),
            ("pbr = { ior = 6 }", "pbr.ior"),
            ("pbr = { ior = nan }", "pbr.ior"),
        ] {
            assert_eq!(check(text).unwrap_err().0, key, "{text}");
        }
        for ior in ["0", "1", "5"] {
            assert!(check(&format!("pbr = {{ ior = {ior} }}")).is_ok(), "ior {ior}");
        }
        let text = "pbr = { metallic = 0.1, roughness = 0.2, ior = 1.3, transmission = 0.4, clearcoat = 0.5, \
                    clearcoat_roughness = 0.6, transmission_texture = { file = \"t.png\" }, specular = 0.7, \
                    specular_color = [1.5, 1, 0.5] }";
        let spec: MaterialSpec = toml::from_str(text).unwrap();
        let SurfaceModel::MetallicRoughness(m) = spec.to_material().surface else { panic!("metallic-roughness") };
        assert_eq!((m.ior, m.transmission, m.clearcoat, m.clearcoat_roughness), (1.3, 0.4, 0.5, 0.6));
        assert_eq!((m.specular, m.specular_color), (0.7, Rgb::new(1.5, 1.0, 0.5)));
        assert_eq!(m.transmission_texture.as_ref().map(|t| t.file.as_str()), Some("t.png"));
        let back: MaterialSpec = toml::from_str(&toml::to_string(&spec).unwrap()).unwrap();
        assert_eq!(spec, back);
        let defaults: MaterialSpec = toml::from_str("pbr = {}").unwrap();
        let SurfaceModel::MetallicRoughness(m) = defaults.to_material().surface else { panic!("metallic-roughness") };
        assert_eq!(
            (m.ior, m.transmission, m.clearcoat, m.specular, m.specular_color),
            (1.5, 0.0, 0.0, 1.0, Rgb::WHITE)
        );
    }

    #[test]
    fn round_trips_through_toml() {
        let m: MaterialSpec =
            toml::from_str("color = [0.9, 0.3, 0.1]\nphong = 0.5\nreflection = { min = 0.1, max = 0.9 }").unwrap();
        let text = toml::to_string(&m).unwrap();
        let back: MaterialSpec = toml::from_str(&text).unwrap();
        assert_eq!(m, back);
    }
}
