//! Materials: one description that serves both integrators.
//!
//! The classic integrator reads the POV-Ray finish (ambient, diffuse, brilliance, phong,
//! specular, metallic, reflection, filter/transmit, interior). The path integrator will
//! read the same struct through a documented mapping (colour as base colour, reflection and
//! metallic as conductor weight, ior and transmit as dielectric), so a scene renders with
//! either. Every default is POV-Ray 3.7's, except the colour, which is white (POV-Ray's
//! default pigment is black; the exporter always writes the colour).

use std::borrow::Cow;
use std::fmt;

use glam::{DVec2, DVec3};
use schemars::JsonSchema;
use serde::de::{self, Deserializer, MapAccess, SeqAccess, Visitor};
use serde::{Deserialize, Serialize};

use crate::color::Rgb;
use crate::texture::{ColorSpace, TextureRef};

/// A surface and interior description.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct Material {
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
    /// An image whose (linear) colour multiplies `color`: a path relative to the scene file,
    /// or a table `{ file, wrap, offset, scale, rotation }`. Needs a shape with texture
    /// coordinates (meshes from glTF or OBJ files).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub texture: Option<TextureRef>,
    /// glTF metallic-roughness parameters. When present, the classic finish (diffuse,
    /// highlights, reflection) is derived from them at every hit (see `docs/meshes.md`)
    /// instead of read from the fields above.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pbr: Option<Pbr>,
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
}

impl Default for Pbr {
    fn default() -> Self {
        Self {
            metallic: 1.0,
            roughness: 1.0,
            metallic_roughness_texture: None,
            emissive: Rgb::BLACK,
            emissive_texture: None,
        }
    }
}

/// A material resolved at one surface point: textures looked up and the glTF parameters
/// turned into the classic finish.
#[derive(Debug)]
pub struct ShadedMaterial<'a> {
    /// The finish to shade with (borrowed when the material has no maps).
    pub material: Cow<'a, Material>,
    /// Radiance emitted toward the viewer, added as is.
    pub emitted: DVec3,
}

impl Default for Material {
    fn default() -> Self {
        Self {
            color: Rgb::WHITE,
            filter: 0.0,
            transmit: 0.0,
            ambient: Rgb::grey(0.1),
            emission: Rgb::BLACK,
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
            texture: None,
            pbr: None,
        }
    }
}

impl Material {
    /// The first non-finite or out-of-range parameter, as (key, message).
    pub fn check(&self) -> Result<(), (&'static str, String)> {
        let colors = [
            ("color", self.color),
            ("ambient", self.ambient),
            ("emission", self.emission),
            ("fade_color", self.fade_color),
            ("reflection.min", self.reflection.min),
            ("reflection.max", self.reflection.max),
        ];
        for (key, c) in colors {
            if !c.is_finite() {
                return Err((key, format!("must be finite, got {:?}", c.0.to_array())));
            }
        }
        let numbers = [
            ("filter", self.filter),
            ("transmit", self.transmit),
            ("diffuse", self.diffuse),
            ("brilliance", self.brilliance),
            ("phong", self.phong),
            ("phong_size", self.phong_size),
            ("specular", self.specular),
            ("roughness", self.roughness),
            ("metallic", self.metallic),
            ("reflection.falloff", self.reflection.falloff),
            ("reflection.exponent", self.reflection.exponent),
            ("reflection.metallic", self.reflection.metallic),
            ("ior", self.ior),
            ("fade_distance", self.fade_distance),
            ("fade_power", self.fade_power),
        ];
        for (key, v) in numbers {
            if !v.is_finite() {
                return Err((key, format!("must be finite, got {v}")));
            }
        }
        if self.roughness <= 0.0 {
            return Err(("roughness", format!("must be greater than 0, got {}", self.roughness)));
        }
        if self.ior <= 0.0 {
            return Err(("ior", format!("must be greater than 0, got {}", self.ior)));
        }
        if self.reflection.exponent <= 0.0 {
            return Err(("reflection.exponent", "must be greater than 0".into()));
        }
        if let Some(t) = &self.texture {
            t.check()?;
        }
        if let Some(p) = &self.pbr {
            for (key, v) in [("pbr.metallic", p.metallic), ("pbr.roughness", p.roughness)] {
                if !(0.0..=1.0).contains(&v) {
                    return Err((key, format!("must be between 0 and 1, got {v}")));
                }
            }
            if !p.emissive.is_finite() {
                return Err(("pbr.emissive", "must be finite".into()));
            }
            for t in [&p.metallic_roughness_texture, &p.emissive_texture].into_iter().flatten() {
                t.check()?;
            }
        }
        Ok(())
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
        }
        out
    }

    /// True when the material depends on where it is hit (a texture or glTF parameters):
    /// only then does shading need the surface's uv.
    pub fn varies_over_surface(&self) -> bool {
        self.texture.is_some() || self.pbr.is_some()
    }

    /// The material at a surface point with texture coordinates `uv`, for a ray footprint
    /// `footprint` wide in uv units (it selects the mip level). Without textures or glTF
    /// parameters this is the material itself.
    ///
    /// The classic finish derived from glTF parameters (documented in `docs/meshes.md`):
    /// with `m` = metallic, `r` = roughness and `g = (1 - r)^2`: diffuse `0.6 (1 - m)`,
    /// Blinn specular `g (0.25 + 0.75 m)` with POV-Ray roughness `a^2 / (2 - 2 a^2)` for GGX
    /// `a = r^2` (exponent 2 / a^2 - 2), highlights and reflection tinted by the base colour
    /// by `m`, mirror reflection `m g`.
    pub fn at_surface(&self, uv: DVec2, footprint: f64) -> ShadedMaterial<'_> {
        if !self.varies_over_surface() {
            return ShadedMaterial { material: Cow::Borrowed(self), emitted: DVec3::ZERO };
        }
        let mut m = self.without_maps();
        if let Some(t) = &self.texture {
            let texel = t.sample(uv, footprint);
            m.color = Rgb(m.color.0 * texel.truncate().as_dvec3());
        }
        let mut emitted = DVec3::ZERO;
        if let Some(p) = &self.pbr {
            let (mut metallic, mut roughness) = (p.metallic, p.roughness);
            if let Some(t) = &p.metallic_roughness_texture {
                let texel = t.sample(uv, footprint);
                roughness *= f64::from(texel.y);
                metallic *= f64::from(texel.z);
            }
            emitted = p.emissive.0;
            if let Some(t) = &p.emissive_texture {
                emitted *= t.sample(uv, footprint).truncate().as_dvec3();
            }
            let gloss = (1.0 - roughness).powi(2);
            let alpha2 = roughness.powi(4).max(1e-4);
            m.diffuse = 0.6 * (1.0 - metallic);
            m.specular = gloss * (0.25 + 0.75 * metallic);
            m.roughness = (alpha2 / (2.0 - 2.0 * alpha2)).clamp(5e-4, 1.0);
            m.metallic = metallic;
            m.phong = 0.0;
            let mirror = metallic * gloss;
            m.reflection =
                Reflection { min: Rgb::grey(mirror), max: Rgb::grey(mirror), metallic, ..Reflection::default() };
        }
        ShadedMaterial { material: Cow::Owned(m), emitted }
    }

    /// A copy without textures or glTF parameters (cheap: nothing to allocate).
    fn without_maps(&self) -> Material {
        Material {
            color: self.color,
            filter: self.filter,
            transmit: self.transmit,
            ambient: self.ambient,
            emission: self.emission,
            diffuse: self.diffuse,
            brilliance: self.brilliance,
            phong: self.phong,
            phong_size: self.phong_size,
            specular: self.specular,
            roughness: self.roughness,
            metallic: self.metallic,
            reflection: self.reflection,
            conserve_energy: self.conserve_energy,
            ior: self.ior,
            fade_distance: self.fade_distance,
            fade_power: self.fade_power,
            fade_color: self.fade_color,
            texture: None,
            pbr: None,
        }
    }

    /// Opacity (1 - filter - transmit), as POV-Ray scales ambient and diffuse.
    pub fn opacity(&self) -> f64 {
        1.0 - self.filter - self.transmit
    }

    /// True when light passes through the surface.
    pub fn is_transparent(&self) -> bool {
        self.filter > 0.0 || self.transmit > 0.0
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
        let m: Material = toml::from_str("").unwrap();
        assert_eq!(m.ambient, Rgb::grey(0.1));
        assert_eq!(m.diffuse, 0.6);
        assert_eq!(m.phong_size, 40.0);
        assert_eq!(m.roughness, 0.05);
        assert_eq!(m.ior, 1.0);
    }

    #[test]
    fn reflection_forms() {
        let m: Material = toml::from_str("reflection = 0.8").unwrap();
        assert_eq!(m.reflection.min, Rgb::grey(0.8));
        let m: Material = toml::from_str("reflection = { min = 0.1, max = 0.9, falloff = 2 }").unwrap();
        assert_eq!((m.reflection.min, m.reflection.max, m.reflection.falloff), (Rgb::grey(0.1), Rgb::grey(0.9), 2.0));
        let m: Material = toml::from_str("reflection = { max = 1, fresnel = true }").unwrap();
        assert_eq!(m.reflection.min, Rgb::BLACK);
        assert!(toml::from_str::<Material>("reflection = { mni = 1 }").is_err());
    }

    #[test]
    fn round_trips_through_toml() {
        let m: Material =
            toml::from_str("color = [0.9, 0.3, 0.1]\nphong = 0.5\nreflection = { min = 0.1, max = 0.9 }").unwrap();
        let text = toml::to_string(&m).unwrap();
        let back: Material = toml::from_str(&text).unwrap();
        assert_eq!(m, back);
    }
}
