//! POV-Ray 3.7 pigment patterns: a colour that varies over space, evaluated in the object's
//! own space (a pattern moves with the object it is attached to, as POV-Ray's textures do).
//!
//! [`Pigment`] is the scene file's form (`pigment = { pattern = "checker", ... }`);
//! [`PigmentField`] is what shading evaluates. Each pattern is POV-Ray's function (its
//! `pattern.cpp`) of the point in POV-Ray's left-handed frame: Prism's object point `p`
//! goes through the inverse pattern transform and then to `(x, y, -z)`, the mirror the POV-Ray
//! exporter writes every scene through, so a scene and its export show the same picture.
//! Continuous patterns then get POV-Ray's `frequency`, `phase` and wave type and look up a
//! `color_map`; `checker`, `hexagon` and `brick` pick one of their listed colours.

use std::fmt;

use glam::{DAffine3, DMat3, DMat4, DVec3, EulerRot};
use prism_api::math::fmod;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::crackle::{CrackleParams, crackle};
use super::image_map::ImageMap;
use super::noise::{Octaves, dturbulence, for_each_octave, noise, noise_pair, turbulence};
use crate::color::Rgb;
use crate::limits::{MAX_COEFFICIENT, MAX_COLOR_COMPONENT};

/// POV-Ray's `EPSILON` (`configcore.h`), the offset of `checker`'s and `brick`'s cell edges.
const POV_EPSILON: f64 = 1.0e-10;

/// A pattern's name, as POV-Ray spells it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PatternKind {
    /// Alternating unit cubes, two colours.
    Checker,
    /// Hexagonal tiles in the x-z plane, three colours.
    Hexagon,
    /// Bricks and mortar, two colours (mortar first).
    Brick,
    /// A ramp along a vector.
    Gradient,
    /// The angle about the y axis.
    Radial,
    /// Concentric spheres.
    Onion,
    /// Regular spots: the square of the mean of sin x, sin y, sin z.
    Leopard,
    /// A spiral about the z axis (POV-Ray's frame).
    Spiral1,
    /// Two crossing spirals about the z axis (POV-Ray's frame).
    Spiral2,
    /// Solid noise.
    Bozo,
    /// Solid noise (the same function as `bozo`).
    Spotted,
    /// Six octaves of absolute noise.
    Granite,
    /// x plus scalar turbulence, triangle wave by default: veins across x.
    Marble,
    /// Rings about the z axis, bent by turbulence; triangle wave by default.
    Wood,
    /// Turbulence folded through a sine along z.
    Agate,
    /// Ten octaves of noise.
    Wrinkles,
    /// Distances to the nearest random points of a cell field (a Voronoi diagram).
    Crackle,
    /// Rounded cubes, shaped by two control points.
    Quilted,
    /// The weighted mean of its `pigment_map` entries (weights in place of values).
    Average,
}

impl PatternKind {
    /// Every pattern with its name.
    pub const ALL: [(PatternKind, &'static str); 19] = [
        (PatternKind::Checker, "checker"),
        (PatternKind::Hexagon, "hexagon"),
        (PatternKind::Brick, "brick"),
        (PatternKind::Gradient, "gradient"),
        (PatternKind::Radial, "radial"),
        (PatternKind::Onion, "onion"),
        (PatternKind::Leopard, "leopard"),
        (PatternKind::Spiral1, "spiral1"),
        (PatternKind::Spiral2, "spiral2"),
        (PatternKind::Bozo, "bozo"),
        (PatternKind::Spotted, "spotted"),
        (PatternKind::Granite, "granite"),
        (PatternKind::Marble, "marble"),
        (PatternKind::Wood, "wood"),
        (PatternKind::Agate, "agate"),
        (PatternKind::Wrinkles, "wrinkles"),
        (PatternKind::Crackle, "crackle"),
        (PatternKind::Quilted, "quilted"),
        (PatternKind::Average, "average"),
    ];

    /// The scene file's (and POV-Ray's) name.
    pub fn name(self) -> &'static str {
        Self::ALL.iter().find(|(k, _)| *k == self).map_or("", |(_, n)| n)
    }

    /// The wave type POV-Ray gives the pattern when none is written.
    pub fn default_wave(self) -> Wave {
        match self {
            PatternKind::Spiral1 | PatternKind::Spiral2 | PatternKind::Marble | PatternKind::Wood => Wave::Triangle,
            _ => Wave::Ramp,
        }
    }

    /// The frequency POV-Ray gives the pattern when none is written (`quilted` and the
    /// discrete patterns: 0, their values unwrapped).
    pub fn default_frequency(self) -> f64 {
        if self == PatternKind::Quilted || self.discrete_colors().is_some() { 0.0 } else { 1.0 }
    }

    /// The number of colours a discrete pattern lists (`None`: it takes a `color_map`).
    pub fn discrete_colors(self) -> Option<usize> {
        match self {
            PatternKind::Checker | PatternKind::Brick => Some(2),
            PatternKind::Hexagon => Some(3),
            _ => None,
        }
    }
}

impl fmt::Display for PatternKind {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl TryFrom<String> for PatternKind {
    type Error = String;

    fn try_from(name: String) -> Result<Self, String> {
        if let Some((kind, _)) = Self::ALL.iter().find(|(_, n)| *n == name) {
            return Ok(*kind);
        }
        let names: Vec<&str> = Self::ALL.iter().map(|(_, n)| *n).collect();
        let hint = crate::diagnostics::nearest_name(&name, names.iter().copied())
            .map_or(String::new(), |n| format!("did you mean `{n}`? "));
        Err(format!("unknown pattern `{name}`; {hint}known patterns: {}", names.join(", ")))
    }
}

impl From<PatternKind> for String {
    fn from(kind: PatternKind) -> String {
        kind.name().to_string()
    }
}

impl Serialize for PatternKind {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.name())
    }
}

impl<'de> Deserialize<'de> for PatternKind {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        PatternKind::try_from(String::deserialize(d)?).map_err(serde::de::Error::custom)
    }
}

impl JsonSchema for PatternKind {
    fn schema_name() -> std::borrow::Cow<'static, str> {
        "PatternKind".into()
    }

    fn json_schema(_: &mut schemars::SchemaGenerator) -> schemars::Schema {
        let names: Vec<&str> = Self::ALL.iter().map(|(_, n)| *n).collect();
        schemars::json_schema!({ "description": "A POV-Ray pigment pattern.", "enum": names })
    }
}

/// POV-Ray's wave types: how a continuous pattern's value in [0, 1) is shaped.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Wave {
    /// The value itself (POV-Ray's default).
    #[default]
    Ramp,
    /// `(1 + sin(2 pi v)) / 2`.
    Sine,
    /// Up from 0 to 1 at v = 0.5, back down to 0.
    Triangle,
    /// `|sin(pi v)|`.
    Scallop,
    /// `3 v^2 - 2 v^3`.
    Cubic,
}

/// A colour with POV-Ray's filter and transmit: written `[r, g, b]` or
/// `{ color = [r, g, b], filter = f, transmit = t }`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(untagged)]
pub enum MapColor {
    /// An opaque colour (linear RGB).
    Opaque(Rgb),
    /// A colour with filter and transmit.
    Filtered(FilteredColor),
}

/// The table form of a [`MapColor`].
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FilteredColor {
    /// Linear RGB.
    pub color: Rgb,
    /// Fraction of light passing through, tinted by the colour.
    #[serde(default)]
    pub filter: f64,
    /// Fraction of light passing through untinted.
    #[serde(default)]
    pub transmit: f64,
}

impl MapColor {
    /// The colour as POV-Ray's five components.
    pub fn rgbft(&self) -> Rgbft {
        match *self {
            MapColor::Opaque(c) => Rgbft { rgb: c.0, filter: 0.0, transmit: 0.0 },
            MapColor::Filtered(FilteredColor { color, filter, transmit }) => Rgbft { rgb: color.0, filter, transmit },
        }
    }
}

/// One `color_map` entry: `[value, colour]` (value usually in [0, 1]).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct MapEntry(pub f64, pub MapColor);

/// One `pigment_map` entry: `[value, pigment]` (value usually in [0, 1]).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct PigmentMapEntry(pub f64, pub Pigment);

/// How deeply `pigment_map`s may nest (an entry's map counts one more).
pub const MAX_PIGMENT_MAP_DEPTH: usize = 16;

/// The most entries a `pigment_map` takes (POV-Ray's `MAX_BLEND_MAP_ENTRIES`).
pub const MAX_PIGMENT_MAP_ENTRIES: usize = 256;

/// The most pigments one pigment may hold in all, nested maps and lists included: a lookup
/// evaluates at most every one of them, so this bounds the work per shading point (depth and
/// entry limits alone allow 256^16).
pub const MAX_NESTED_PIGMENTS: usize = 1024;

/// A pattern transform in the object's space, written and applied like an object's:
/// `scale`, then `rotate` (degrees about x, y, z), then `translate`; or `matrix` (four rows)
/// instead of the three.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(untagged)]
pub enum PatternScale {
    /// The same factor on every axis.
    Uniform(f64),
    /// One factor per axis.
    PerAxis([f64; 3]),
}

/// A turbulence amount: one number for every axis, or one per axis (of the pattern's frame).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(untagged)]
pub enum TurbulenceAmount {
    /// The same amount along every axis.
    Uniform(f64),
    /// One amount per axis.
    PerAxis([f64; 3]),
}

impl TurbulenceAmount {
    /// The amount per axis.
    pub fn vector(&self) -> DVec3 {
        match *self {
            TurbulenceAmount::Uniform(v) => DVec3::splat(v),
            TurbulenceAmount::PerAxis(v) => DVec3::from_array(v),
        }
    }
}

/// A pigment pattern as a scene file writes it (`pigment = { pattern = "...", ... }`), or an
/// image map (`pigment = { image_map = { file = "...", ... }, ... }`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Pigment {
    /// The pattern's POV-Ray name (exclusive with `image_map`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pattern: Option<PatternKind>,
    /// POV-Ray's `image_map`: a PNG image projected onto the object (exclusive with
    /// `pattern`; see [`ImageMap`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub image_map: Option<ImageMap>,
    /// `checker`, `brick` (mortar first): two colours; `hexagon`: three.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub colors: Vec<MapColor>,
    /// `checker`, `brick`, `hexagon`: whole pigments in place of `colors` (POV-Ray's
    /// `checker pigment { } pigment { }`), each read as a `pigment_map` entry is.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub pigments: Vec<Pigment>,
    /// The other patterns: `[value, colour]` entries, values ascending (usually in [0, 1]), interpolated
    /// linearly (below the first entry its colour, above the last the last's).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub color_map: Vec<MapEntry>,
    /// POV-Ray's `pigment_map` (instead of a `color_map`): `[value, pigment]` entries, each a
    /// whole pigment (a pattern, an image map, another `pigment_map`, or a plain
    /// `{ color = [r, g, b] }`), blended like colour map entries. `average`: `[weight, pigment]`
    /// entries (weights not negative, their sum above 0), averaged with those weights.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pigment_map: Option<Vec<PigmentMapEntry>>,
    /// A plain colour (linear RGB): a `pigment_map` entry without a pattern.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub color: Option<Rgb>,
    /// A plain colour's filter (default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub filter: Option<f64>,
    /// A plain colour's transmit (default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub transmit: Option<f64>,
    /// `gradient`'s direction (normalised, as POV-Ray's parser does: the pattern repeats every
    /// unit along it whatever its length).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub vector: Option<[f64; 3]>,
    /// `spiral1` / `spiral2`: the number of arms.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub arms: Option<i32>,
    /// `brick`: the size of a brick with its mortar (POV-Ray's default [8, 3, 4.5]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub brick_size: Option<[f64; 3]>,
    /// `brick`: the mortar's width (POV-Ray's default 0.5).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mortar: Option<f64>,
    /// `crackle`: the weights of the distances to the nearest, second and third nearest
    /// cell points (POV-Ray's default [-1, 1, 0]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub form: Option<[f64; 3]>,
    /// `crackle`: the exponent of the Minkowski metric distances are measured in (default 2,
    /// Euclidean; 1 is Manhattan), above 0 and at most 100.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub metric: Option<f64>,
    /// `crackle`: added to every distance (default 0; not negative).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub offset: Option<f64>,
    /// `crackle`: one value per cell (the noise at its point) instead of the distances.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub solid: Option<bool>,
    /// `quilted`: the first control point of the cubic that rounds the cubes (default 1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub control0: Option<f64>,
    /// `quilted`: the second control point (default 1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub control1: Option<f64>,
    /// Continuous patterns: how many times the colour map repeats per unit of the pattern
    /// (POV-Ray's default 1, `quilted`'s 0; 0 leaves the value unwrapped).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub frequency: Option<f64>,
    /// Continuous patterns: added to the value before wrapping (default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub phase: Option<f64>,
    /// Continuous patterns: the wave type (POV-Ray's default: `triangle` for the spirals,
    /// `ramp` for the others).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub wave: Option<Wave>,
    /// POV-Ray's `turbulence`: displaces the point by vector turbulence (noise octaves)
    /// times this amount, per axis of the pattern's frame, before the pattern reads it;
    /// `marble`, `wood` (and the spirals and `agate`, besides) use it in their own way.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub turbulence: Option<TurbulenceAmount>,
    /// Turbulence octaves, 1 to 10 (default 6).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub octaves: Option<u32>,
    /// Turbulence amplitude factor per octave (default 0.5).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub omega: Option<f64>,
    /// Turbulence frequency factor per octave (default 2).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lambda: Option<f64>,
    /// Pattern scale.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scale: Option<PatternScale>,
    /// Pattern rotation, degrees about x, then y, then z.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rotate: Option<[f64; 3]>,
    /// Pattern translation.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub translate: Option<[f64; 3]>,
    /// A 4x4 affine matrix (rows; the last [0, 0, 0, 1]) instead of scale, rotate, translate.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub matrix: Option<[[f64; 4]; 4]>,
}

/// POV-Ray's default brick size.
pub const DEFAULT_BRICK_SIZE: [f64; 3] = [8.0, 3.0, 4.5];
/// POV-Ray's default mortar width.
pub const DEFAULT_MORTAR: f64 = 0.5;

/// A colour with POV-Ray's filter and transmit, the value a pigment gives at a point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rgbft {
    /// Linear RGB.
    pub rgb: DVec3,
    /// Filtered transmission (tinted by `rgb`).
    pub filter: f64,
    /// Unfiltered transmission.
    pub transmit: f64,
}

impl Rgbft {
    fn blend(a: Rgbft, wa: f64, b: Rgbft, wb: f64) -> Rgbft {
        Rgbft {
            rgb: a.rgb * wa + b.rgb * wb,
            filter: a.filter * wa + b.filter * wb,
            transmit: a.transmit * wa + b.transmit * wb,
        }
    }
}

impl Pigment {
    /// The pattern transform (pattern space to object space, Prism's frame).
    pub fn object_from_pattern(&self) -> DAffine3 {
        pattern_transform(self.scale, self.rotate, self.translate, self.matrix)
    }

    /// Every colour the pigment can give (its list or its map's, its `pigment_map` entries',
    /// an image map's clearest).
    pub fn colors(&self) -> Vec<Rgbft> {
        let mut out: Vec<Rgbft> = self.own_colors().collect();
        for entry in self.nested() {
            out.extend(entry.colors());
        }
        out
    }

    /// The colours written in this pigment itself (not in its `pigment_map` entries).
    fn own_colors(&self) -> impl Iterator<Item = Rgbft> + '_ {
        self.colors
            .iter()
            .map(MapColor::rgbft)
            .chain(self.color_map.iter().map(|e| e.1.rgbft()))
            .chain(self.image_map.iter().map(ImageMap::clearest))
            .chain(self.plain_color())
    }

    /// The `pigment_map` entries (none without a map).
    pub fn pigment_map(&self) -> &[PigmentMapEntry] {
        self.pigment_map.as_deref().unwrap_or_default()
    }

    /// The pigments this one holds: its `pigment_map` entries', or a discrete pattern's
    /// `pigments`.
    fn nested(&self) -> impl Iterator<Item = &Pigment> {
        self.pigment_map().iter().map(|e| &e.1).chain(&self.pigments)
    }

    /// Every image map of the pigment, its `pigment_map` entries' included, with its key path
    /// under `pigment` (`image_map`, `pigment_map[2][1].image_map`: the TOML path of its table).
    pub fn image_maps_mut(&mut self) -> Vec<(String, &mut ImageMap)> {
        fn collect<'a>(p: &'a mut Pigment, prefix: String, out: &mut Vec<(String, &'a mut ImageMap)>) {
            if let Some(map) = p.image_map.as_mut() {
                out.push((format!("{prefix}image_map"), map));
            }
            for (i, PigmentMapEntry(_, entry)) in p.pigment_map.iter_mut().flatten().enumerate() {
                collect(entry, format!("{prefix}pigment_map[{i}][1]."), out);
            }
            for (i, entry) in p.pigments.iter_mut().enumerate() {
                collect(entry, format!("{prefix}pigments[{i}]."), out);
            }
        }
        let mut out = Vec::new();
        collect(self, String::new(), &mut out);
        out
    }

    /// Every image map of the pigment, its `pigment_map` entries' included.
    pub fn image_maps(&self) -> Vec<&ImageMap> {
        let mut out: Vec<&ImageMap> = self.image_map.iter().collect();
        for entry in self.nested() {
            out.extend(entry.image_maps());
        }
        out
    }

    /// A plain pigment's colour (`color` with its filter and transmit), as a `pigment_map`
    /// entry writes it.
    pub fn plain_color(&self) -> Option<Rgbft> {
        self.color.map(|c| Rgbft {
            rgb: c.0,
            filter: self.filter.unwrap_or(0.0),
            transmit: self.transmit.unwrap_or(0.0),
        })
    }

    /// The first out-of-range or contradictory parameter, as (key path under `pigment`, e.g.
    /// `pigment_map[2].color_map`, message).
    pub fn check(&self) -> Result<(), (String, String)> {
        self.check_at(0)?;
        let total = self.nested_count();
        if total > MAX_NESTED_PIGMENTS {
            let key = if self.pigments.is_empty() { "pigment_map" } else { "pigments" };
            return Err((
                key.into(),
                format!("holds {total} pigments in all (nested ones included); at most {MAX_NESTED_PIGMENTS}"),
            ));
        }
        Ok(())
    }

    /// How many pigments this one holds, nested ones included (after [`Self::check_at`] has
    /// bounded the depth). Stops counting past [`MAX_NESTED_PIGMENTS`].
    fn nested_count(&self) -> usize {
        let nested: Box<dyn Iterator<Item = &Pigment>> = if self.pigments.is_empty() {
            Box::new(self.pigment_map().iter().map(|e| &e.1))
        } else {
            Box::new(self.pigments.iter())
        };
        let mut total = 0;
        for entry in nested {
            total += 1 + entry.nested_count();
            if total > MAX_NESTED_PIGMENTS {
                break;
            }
        }
        total
    }

    /// [`Self::check`] of a pigment `depth` `pigment_map`s deep.
    fn check_at(&self, depth: usize) -> Result<(), (String, String)> {
        let owned = |(key, message): (&str, String)| (key.to_string(), message);
        if self.color.is_some() || self.filter.is_some() || self.transmit.is_some() {
            return self.check_plain(depth).map_err(owned);
        }
        self.check_own().map_err(owned)?;
        let (key, nested): (&str, Vec<&Pigment>) = if self.pigments.is_empty() {
            ("pigment_map", self.pigment_map().iter().map(|e| &e.1).collect())
        } else {
            ("pigments", self.pigments.iter().collect())
        };
        if nested.is_empty() {
            return Ok(());
        }
        if depth >= MAX_PIGMENT_MAP_DEPTH {
            return Err((key.into(), format!("pigments in pigments nest at most {MAX_PIGMENT_MAP_DEPTH} deep")));
        }
        for (i, entry) in nested.into_iter().enumerate() {
            entry.check_at(depth + 1).map_err(|(k, message)| (format!("{key}[{i}].{k}"), message))?;
        }
        Ok(())
    }

    /// A plain colour pigment's first problem: it is a `pigment_map` entry's and has no
    /// pattern keys.
    fn check_plain(&self, depth: usize) -> Result<(), (&'static str, String)> {
        if depth == 0 {
            return Err((
                "color",
                "a plain colour pigment is a `pigment_map` entry's: give the material's `color`, `filter` \
                 and `transmit` instead of a `pigment`"
                    .into(),
            ));
        }
        let Some(color) = self.color else {
            return Err(("color", "`filter` and `transmit` belong to a plain `color`".into()));
        };
        let source = [("pattern", self.pattern.is_some()), ("image_map", self.image_map.is_some())];
        let warp_and_transform = [
            ("turbulence", self.turbulence.is_some()),
            ("octaves", self.octaves.is_some()),
            ("omega", self.omega.is_some()),
            ("lambda", self.lambda.is_some()),
            ("scale", self.scale.is_some()),
            ("rotate", self.rotate.is_some()),
            ("translate", self.translate.is_some()),
            ("matrix", self.matrix.is_some()),
        ];
        let mut written = source.into_iter().chain(self.pattern_keys_written()).chain(warp_and_transform);
        if let Some((key, _)) = written.find(|(_, given)| *given) {
            return Err((key, "belongs to a pattern: a plain `color` has no pattern keys".into()));
        }
        // A material's limits: larger values overflow their products.
        super::check_finite(
            &[("color", color)],
            &[("filter", self.filter.unwrap_or(0.0)), ("transmit", self.transmit.unwrap_or(0.0))],
        )
    }

    /// This pigment's own first problem (its `pigment_map` entries apart).
    fn check_own(&self) -> Result<(), (&'static str, String)> {
        let kind = match (self.pattern, &self.image_map) {
            (Some(_), Some(_)) => {
                return Err(("image_map", "give either a `pattern` or an `image_map`, not both".into()));
            }
            (None, Some(map)) => return self.check_image_map(map),
            (None, None) => {
                return Err((
                    "pattern",
                    "needs a `pattern` or an `image_map` (or, in a `pigment_map`, a `color`)".into(),
                ));
            }
            (Some(kind), None) => kind,
        };
        if kind == PatternKind::Average {
            return self.check_average();
        }
        match kind.discrete_colors() {
            Some(n) => {
                if self.pigment_map.is_some() {
                    return Err((
                        "pigment_map",
                        format!("`{kind}` takes `colors` or `pigments`, not a `pigment_map` (as in POV-Ray)"),
                    ));
                }
                if !self.pigments.is_empty() {
                    if !self.colors.is_empty() {
                        return Err(("pigments", "give either `colors` or `pigments`, not both".into()));
                    }
                    if self.pigments.len() != n {
                        return Err(("pigments", format!("`{kind}` takes {n} pigments, got {}", self.pigments.len())));
                    }
                } else if self.colors.len() != n {
                    return Err(("colors", format!("`{kind}` takes {n} colours, got {}", self.colors.len())));
                }
                if !self.color_map.is_empty() {
                    return Err(("color_map", format!("`{kind}` takes `colors`, not a `color_map`")));
                }
                for (key, given) in [
                    ("frequency", self.frequency.is_some()),
                    ("phase", self.phase.is_some()),
                    ("wave", self.wave.is_some()),
                ] {
                    if given {
                        return Err((key, format!("has no effect on the discrete pattern `{kind}`")));
                    }
                }
            }
            None => {
                if !self.colors.is_empty() {
                    return Err(("colors", format!("`{kind}` takes a `color_map`, not `colors`")));
                }
                if !self.pigments.is_empty() {
                    return Err(("pigments", format!("`{kind}` takes a `pigment_map`, not `pigments`")));
                }
                if let Some(pigment_map) = &self.pigment_map {
                    if !self.color_map.is_empty() {
                        return Err(("pigment_map", "give either a `color_map` or a `pigment_map`, not both".into()));
                    }
                    if pigment_map.is_empty() {
                        return Err(("pigment_map", format!("`{kind}` needs at least one `pigment_map` entry")));
                    }
                    if pigment_map.len() > MAX_PIGMENT_MAP_ENTRIES {
                        return Err((
                            "pigment_map",
                            format!(
                                "has {} entries; at most {MAX_PIGMENT_MAP_ENTRIES} (POV-Ray's limit)",
                                pigment_map.len()
                            ),
                        ));
                    }
                    check_map_values("pigment_map", pigment_map.iter().map(|e| e.0))?;
                } else {
                    if self.color_map.is_empty() {
                        return Err((
                            "color_map",
                            format!("`{kind}` needs a `color_map` (or a `pigment_map`) with at least one entry"),
                        ));
                    }
                    check_map_values("color_map", self.color_map.iter().map(|e| e.0))?;
                }
            }
        }
        self.check_written_colors()?;
        self.check_keys()
    }

    /// The first colour of this pattern's `colors` or `color_map` outside a material's
    /// limits: components within ±1e30, filter and transmit within ±1e9, whose products
    /// cannot overflow.
    fn check_written_colors(&self) -> Result<(), (&'static str, String)> {
        let listed = |key: &'static str, i: usize, c: Rgbft| {
            if !(c.rgb.is_finite() && c.filter.is_finite() && c.transmit.is_finite()) {
                return Err((key, format!("entry {i}: colour, filter and transmit must be finite")));
            }
            let parts = [
                ("colour components", c.rgb.abs().max_element(), MAX_COLOR_COMPONENT),
                ("filter", c.filter.abs(), MAX_COEFFICIENT),
                ("transmit", c.transmit.abs(), MAX_COEFFICIENT),
            ];
            match parts.into_iter().find(|(_, v, limit)| v > limit) {
                Some((part, v, limit)) => Err((
                    key,
                    format!(
                        "entry {i}: {part} must lie within ±{limit:e} (products would overflow), got {}",
                        crate::diagnostics::shown_number(v)
                    ),
                )),
                None => Ok(()),
            }
        };
        for (i, c) in self.colors.iter().enumerate() {
            listed("colors", i, c.rgbft())?;
        }
        for (i, e) in self.color_map.iter().enumerate() {
            listed("color_map", i, e.1.rgbft())?;
        }
        Ok(())
    }

    /// `average`'s first problem: it takes a `pigment_map` of weighted pigments and no
    /// colours or wave.
    fn check_average(&self) -> Result<(), (&'static str, String)> {
        let misplaced = [
            ("colors", !self.colors.is_empty()),
            ("pigments", !self.pigments.is_empty()),
            ("color_map", !self.color_map.is_empty()),
            ("frequency", self.frequency.is_some()),
            ("phase", self.phase.is_some()),
            ("wave", self.wave.is_some()),
        ];
        if let Some((key, _)) = misplaced.iter().find(|(_, given)| *given) {
            return Err((key, "`average` takes a `pigment_map` of `[weight, pigment]` entries, not this".into()));
        }
        let Some(map) = &self.pigment_map else {
            return Err(("pigment_map", "`average` needs a `pigment_map` of `[weight, pigment]` entries".into()));
        };
        check_weights("pigment_map", map.iter().map(|e| e.0))?;
        self.check_keys()
    }

    /// The first problem of the pattern's own keys, turbulence and transform (everything but
    /// its colours), as (key, message): what a pattern read as a normal shares.
    pub fn check_keys(&self) -> Result<(), (&'static str, String)> {
        let Some(kind) = self.pattern else {
            return Err(("pattern", "needs a `pattern`".into()));
        };
        let only = |key: &'static str, given: bool, kinds: &[PatternKind]| {
            if given && !kinds.contains(&kind) {
                let names: Vec<&str> = kinds.iter().map(|k| k.name()).collect();
                return Err((key, format!("belongs to {}, not `{kind}`", names.join(" and "))));
            }
            Ok(())
        };
        only("vector", self.vector.is_some(), &[PatternKind::Gradient])?;
        only("arms", self.arms.is_some(), &[PatternKind::Spiral1, PatternKind::Spiral2])?;
        only("brick_size", self.brick_size.is_some(), &[PatternKind::Brick])?;
        only("mortar", self.mortar.is_some(), &[PatternKind::Brick])?;
        for (key, given) in [
            ("form", self.form.is_some()),
            ("metric", self.metric.is_some()),
            ("offset", self.offset.is_some()),
            ("solid", self.solid.is_some()),
        ] {
            only(key, given, &[PatternKind::Crackle])?;
        }
        only("control0", self.control0.is_some(), &[PatternKind::Quilted])?;
        only("control1", self.control1.is_some(), &[PatternKind::Quilted])?;
        check_crackle(self.form, self.metric, self.offset)?;
        for (key, v) in [("control0", self.control0), ("control1", self.control1)] {
            if let Some(v) = v
                && !v.is_finite()
            {
                return Err((key, format!("must be finite, got {v}")));
            }
        }
        if kind == PatternKind::Gradient && self.vector.is_none() {
            return Err(("vector", "`gradient` needs its direction `vector = [x, y, z]`".into()));
        }
        if matches!(kind, PatternKind::Spiral1 | PatternKind::Spiral2) && self.arms.is_none() {
            return Err(("arms", format!("`{kind}` needs its number of `arms`")));
        }
        if let Some(v) = self.vector
            && !(v.iter().all(|c| c.is_finite()) && DVec3::from_array(v) != DVec3::ZERO)
        {
            return Err(("vector", "must be finite and not zero".into()));
        }
        if let Some(size) = self.brick_size
            && !size.iter().all(|s| s.is_finite() && *s > 0.0)
        {
            return Err(("brick_size", format!("every side must be finite and positive, got {size:?}")));
        }
        if let Some(m) = self.mortar
            && !(m.is_finite() && m >= 0.0)
        {
            return Err(("mortar", format!("must be finite and not negative, got {m}")));
        }
        check_turbulence(self.turbulence, self.octaves, self.omega, self.lambda, kind == PatternKind::Agate)?;
        for (key, v) in [("frequency", self.frequency), ("phase", self.phase)] {
            if let Some(v) = v
                && !v.is_finite()
            {
                return Err((key, format!("must be finite, got {v}")));
            }
        }
        check_transform(self.scale, self.rotate, self.translate, self.matrix)?;
        Ok(())
    }

    /// The keys only a pattern takes (its colours and its own parameters), each with whether
    /// it is written.
    fn pattern_keys_written(&self) -> [(&'static str, bool); 17] {
        [
            ("colors", !self.colors.is_empty()),
            ("pigments", !self.pigments.is_empty()),
            ("color_map", !self.color_map.is_empty()),
            ("pigment_map", self.pigment_map.is_some()),
            ("vector", self.vector.is_some()),
            ("arms", self.arms.is_some()),
            ("brick_size", self.brick_size.is_some()),
            ("mortar", self.mortar.is_some()),
            ("form", self.form.is_some()),
            ("metric", self.metric.is_some()),
            ("offset", self.offset.is_some()),
            ("solid", self.solid.is_some()),
            ("control0", self.control0.is_some()),
            ("control1", self.control1.is_some()),
            ("frequency", self.frequency.is_some()),
            ("phase", self.phase.is_some()),
            ("wave", self.wave.is_some()),
        ]
    }

    /// An image map's first problem, or a pattern key written beside it.
    fn check_image_map(&self, map: &ImageMap) -> Result<(), (&'static str, String)> {
        if let Some((key, _)) = self.pattern_keys_written().into_iter().find(|(_, given)| *given) {
            return Err((key, "belongs to a `pattern`, not to an `image_map`".into()));
        }
        if map.use_index {
            return Err(("image_map.use_index", "belongs to a `bump_map`, not to an `image_map` pigment".into()));
        }
        map.check().map_err(|(key, message)| {
            let key = match key {
                "filter_all" => "image_map.filter_all",
                "transmit_all" => "image_map.transmit_all",
                "file" => "image_map.file",
                "repeat" => "image_map.repeat",
                "offset" => "image_map.offset",
                _ => "image_map",
            };
            (key, message)
        })?;
        check_turbulence(self.turbulence, self.octaves, self.omega, self.lambda, false)?;
        check_transform(self.scale, self.rotate, self.translate, self.matrix)
    }
}

/// The first problem of a map's entry values (under `key`): each finite, ascending. As in
/// POV-Ray, values need not lie in [0, 1] (`[1.01 colour]` is common in its scenes, and
/// changes the blend below it).
pub(super) fn check_map_values(
    key: &'static str,
    values: impl Iterator<Item = f64>,
) -> Result<(), (&'static str, String)> {
    let mut previous = f64::NEG_INFINITY;
    for (i, value) in values.enumerate() {
        if !value.is_finite() {
            return Err((key, format!("entry {i}: value {value} is not a finite number")));
        }
        if value < previous {
            return Err((
                key,
                format!("entry {i}: value {value} is below the previous entry's {previous} (ascending order)"),
            ));
        }
        previous = value;
    }
    Ok(())
}

/// The first problem of an `average`'s map of weights (under `key`): one to 256 entries, each
/// weight finite and not negative, their sum above 0.
pub(super) fn check_weights(
    key: &'static str,
    weights: impl Iterator<Item = f64>,
) -> Result<(), (&'static str, String)> {
    let mut total = 0.0f32;
    let mut count = 0;
    for (i, weight) in weights.enumerate() {
        if !(weight.is_finite() && weight >= 0.0) {
            return Err((key, format!("entry {i}: the weight must be finite and not negative, got {weight}")));
        }
        total += weight as f32;
        count += 1;
    }
    if count == 0 {
        return Err((key, "needs at least one entry".into()));
    }
    if count > MAX_PIGMENT_MAP_ENTRIES {
        return Err((key, format!("has {count} entries; at most {MAX_PIGMENT_MAP_ENTRIES} (POV-Ray's limit)")));
    }
    if !(total > 0.0 && total.is_finite()) {
        return Err((key, "the weights must add up to a finite number above 0".into()));
    }
    Ok(())
}

/// The first out-of-range crackle key, as (key, message).
fn check_crackle(
    form: Option<[f64; 3]>,
    metric: Option<f64>,
    offset: Option<f64>,
) -> Result<(), (&'static str, String)> {
    if let Some(f) = form
        && !f.iter().all(|v| v.is_finite())
    {
        return Err(("form", format!("must be finite, got {f:?}")));
    }
    if let Some(m) = metric
        && !(m > 0.0 && m <= MAX_METRIC)
    {
        return Err(("metric", format!("must be above 0 and at most {MAX_METRIC}, got {m}")));
    }
    if let Some(o) = offset
        && !(o.is_finite() && o >= 0.0)
    {
        return Err(("offset", format!("must be finite and not negative, got {o}")));
    }
    Ok(())
}

/// The largest crackle `metric`: beyond it the powered distances of neighbouring cells
/// (below 3) overflow or vanish.
pub const MAX_METRIC: f64 = 100.0;

/// The transform `scale`, `rotate` (degrees about x, then y, then z), `translate` (or
/// `matrix`) of a pattern: pattern space to object space, Prism's frame.
pub fn pattern_transform(
    scale: Option<PatternScale>,
    rotate: Option<[f64; 3]>,
    translate: Option<[f64; 3]>,
    matrix: Option<[[f64; 4]; 4]>,
) -> DAffine3 {
    if let Some(rows) = matrix {
        return DAffine3::from_mat4(DMat4::from_cols_array_2d(&rows).transpose());
    }
    let scale = match scale {
        None => DVec3::ONE,
        Some(PatternScale::Uniform(s)) => DVec3::splat(s),
        Some(PatternScale::PerAxis(s)) => DVec3::from_array(s),
    };
    let r = DVec3::from_array(rotate.unwrap_or_default()) * (std::f64::consts::PI / 180.0);
    let rotation = DMat3::from_euler(EulerRot::ZYX, r.z, r.y, r.x);
    let translation = DVec3::from_array(translate.unwrap_or_default());
    DAffine3 { matrix3: rotation * DMat3::from_diagonal(scale), translation }
}

/// The first problem of a pattern transform, as (key, message).
pub fn check_transform(
    scale: Option<PatternScale>,
    rotate: Option<[f64; 3]>,
    translate: Option<[f64; 3]>,
    matrix: Option<[[f64; 4]; 4]>,
) -> Result<(), (&'static str, String)> {
    if matrix.is_some() && (scale.is_some() || rotate.is_some() || translate.is_some()) {
        return Err(("matrix", "give either `matrix` or `scale`, `rotate` and `translate`".into()));
    }
    if let Some(rows) = matrix
        && rows[3] != [0.0, 0.0, 0.0, 1.0]
    {
        return Err(("matrix", "the last row must be [0, 0, 0, 1]".into()));
    }
    let m = pattern_transform(scale, rotate, translate, matrix);
    if !(m.matrix3.determinant().abs() > 1e-12 && m.to_cols_array().iter().all(|v| v.is_finite())) {
        return Err(("scale", "the pattern transform must be finite and invertible".into()));
    }
    Ok(())
}

/// The first problem of a pattern's turbulence keys, as (key, message). `octaves`, `omega`
/// and `lambda` need a `turbulence` amount unless `octaves_alone` (agate's own turbulence).
pub fn check_turbulence(
    amount: Option<TurbulenceAmount>,
    octaves: Option<u32>,
    omega: Option<f64>,
    lambda: Option<f64>,
    octaves_alone: bool,
) -> Result<(), (&'static str, String)> {
    if let Some(t) = amount
        && !t.vector().is_finite()
    {
        return Err(("turbulence", "must be finite".into()));
    }
    if let Some(n) = octaves
        && !(1..=10).contains(&n)
    {
        return Err(("octaves", format!("must be between 1 and 10 (POV-Ray's limits), got {n}")));
    }
    let octave_keys = [("octaves", octaves.is_some()), ("omega", omega.is_some()), ("lambda", lambda.is_some())];
    if amount.is_none()
        && !octaves_alone
        && let Some((key, _)) = octave_keys.iter().find(|(_, given)| *given)
    {
        return Err((key, "shapes `turbulence`, which this pattern does not have".into()));
    }
    for (key, v) in [("omega", omega), ("lambda", lambda)] {
        if let Some(v) = v
            && !v.is_finite()
        {
            return Err((key, format!("must be finite, got {v}")));
        }
    }
    Ok(())
}

/// The turbulence octaves a pattern writes, with POV-Ray's defaults.
pub fn octaves_of(octaves: Option<u32>, omega: Option<f64>, lambda: Option<f64>) -> Octaves {
    let d = Octaves::default();
    Octaves {
        octaves: octaves.unwrap_or(d.octaves),
        omega: omega.unwrap_or(d.omega),
        lambda: lambda.unwrap_or(d.lambda),
    }
}

/// A pigment ready to evaluate: the pattern with its transform inverted.
#[derive(Clone, Debug, PartialEq)]
pub struct PigmentField {
    /// The pigment as written.
    pub spec: Pigment,
    /// The pattern (unused with an image map).
    kind: PatternKind,
    /// Object space (Prism's frame) to pattern space.
    pattern_from_object: DAffine3,
    /// The turbulence amount per axis (zero without turbulence).
    turbulence: DVec3,
    /// The turbulence octaves.
    octaves: Octaves,
    /// `crackle`'s parameters with POV-Ray's defaults.
    crackle: CrackleParams,
    /// `quilted`'s control points, in single precision as POV-Ray holds them.
    quilt_controls: (f64, f64),
    /// A plain colour (a `pigment_map` entry without a pattern).
    plain: Option<Rgbft>,
    /// The `pigment_map` entries' values and fields, or a discrete pattern's `pigments` at
    /// their indices (empty without either).
    entries: Vec<(f64, PigmentField)>,
}

impl PigmentField {
    /// The field of `spec` (which passed [`Pigment::check`], or for a normal
    /// [`Pigment::check_keys`]).
    pub fn new(spec: &Pigment) -> Self {
        let d = CrackleParams::default();
        let single = |v: Option<f64>| f64::from(v.unwrap_or(1.0) as f32);
        Self {
            spec: spec.clone(),
            kind: spec.pattern.unwrap_or(PatternKind::Checker),
            pattern_from_object: spec.object_from_pattern().inverse(),
            turbulence: spec.turbulence.map_or(DVec3::ZERO, |t| t.vector()),
            octaves: octaves_of(spec.octaves, spec.omega, spec.lambda),
            crackle: CrackleParams {
                form: spec.form.map_or(d.form, DVec3::from_array),
                metric: spec.metric.unwrap_or(d.metric),
                offset: spec.offset.unwrap_or(d.offset),
                solid: spec.solid.unwrap_or(d.solid),
            },
            quilt_controls: (single(spec.control0), single(spec.control1)),
            plain: spec.plain_color(),
            entries: spec
                .pigment_map()
                .iter()
                .map(|PigmentMapEntry(v, p)| (*v, PigmentField::new(p)))
                .chain(spec.pigments.iter().enumerate().map(|(i, p)| (i as f64, PigmentField::new(p))))
                .collect(),
        }
    }

    /// True when some colour of the pigment lets light through.
    pub fn can_transmit(&self) -> bool {
        self.spec.colors().iter().any(|c| c.filter != 0.0 || c.transmit != 0.0)
    }

    /// The colour at object-space point `p` (Prism's frame).
    pub fn at(&self, p: DVec3) -> Rgbft {
        if let Some(c) = self.plain {
            return c;
        }
        let mut q = self.pattern_from_object.transform_point3(p) * DVec3::new(1.0, 1.0, -1.0);
        let spec = &self.spec;
        // An image map's kind reads as checker here: it warps like every plain pattern.
        if warps_with_turbulence(self.kind, spec.turbulence.is_some()) {
            q += dturbulence(q, &self.octaves) * self.turbulence;
        }
        if let Some(map) = &spec.image_map {
            return map.at(q);
        }
        if self.kind == PatternKind::Average {
            return self.average(q);
        }
        match self.kind.discrete_colors() {
            Some(_) => {
                let index = discrete_value(self.kind, spec, q);
                if !self.entries.is_empty() {
                    // POV-Ray's list of pigments: the entry at the index, read as a map's.
                    let entry = &self.entries[index.min(self.entries.len() - 1)].1;
                    return entry.at(q * DVec3::new(1.0, 1.0, -1.0));
                }
                spec.colors[index.min(spec.colors.len() - 1)].rgbft()
            }
            None if !self.entries.is_empty() => self.blend_entries(self.value(q), q),
            None => map_lookup(&spec.color_map, self.value(q)),
        }
    }

    /// The `pigment_map` colour for pattern value `value` at the (warped) pattern point `q`:
    /// POV-Ray's `Compute_Pigment` with a pigment blend map. The two neighbouring entries
    /// (one where the value sits on an entry or outside the map) are evaluated at the point
    /// as this pigment's transform and turbulence left it, each through its own, and blended
    /// linearly in all five components.
    fn blend_entries(&self, value: f64, q: DVec3) -> Rgbft {
        let entries = &self.entries;
        let (prev, cur, fraction) = search_blend_map(entries.len(), |i| entries[i].0, value);
        // Back to Prism's frame: each entry's `at` mirrors its own pattern point.
        let p = q * DVec3::new(1.0, 1.0, -1.0);
        let colour = entries[cur].1.at(p);
        if prev == cur {
            return colour;
        }
        let below = entries[prev].1.at(p);
        Rgbft {
            rgb: below.rgb + fraction * (colour.rgb - below.rgb),
            filter: below.filter + fraction * (colour.filter - below.filter),
            transmit: below.transmit + fraction * (colour.transmit - below.transmit),
        }
    }

    /// POV-Ray's `Do_Average_Pigments`: every `pigment_map` entry evaluated at the (warped)
    /// pattern point `q`, weighted by its value, the sum divided by the weights' (weights and
    /// their sum in single precision, as POV-Ray holds them).
    fn average(&self, q: DVec3) -> Rgbft {
        let p = q * DVec3::new(1.0, 1.0, -1.0);
        let mut sum = Rgbft { rgb: DVec3::ZERO, filter: 0.0, transmit: 0.0 };
        let mut total = 0.0f32;
        for (weight, entry) in &self.entries {
            let weight = *weight as f32;
            sum = Rgbft::blend(sum, 1.0, entry.at(p), f64::from(weight));
            total += weight;
        }
        let total = f64::from(total);
        Rgbft { rgb: sum.rgb / total, filter: sum.filter / total, transmit: sum.transmit / total }
    }

    /// The pattern's value at the (warped) pattern point `q`, POV-Ray's frame, after
    /// frequency, phase and wave (POV-Ray's `Evaluate_TPat`): a discrete pattern's is its
    /// colour index (checker 0 or 1, hexagon 0 to 2), which is how a normal reads it.
    pub fn value(&self, q: DVec3) -> f64 {
        let spec = &self.spec;
        let turbulent = spec.turbulence.is_some();
        // Scalar turbulence, as marble and the spirals add it.
        let turb_x = || if turbulent { self.turbulence.x * turbulence(q, &self.octaves) } else { 0.0 };
        let raw = match self.kind {
            PatternKind::Gradient => gradient(q, pov_vector(spec.vector.unwrap_or([0.0, 1.0, 0.0])).normalize()),
            PatternKind::Radial => radial(q),
            PatternKind::Onion => onion(q),
            PatternKind::Leopard => leopard(q),
            PatternKind::Spiral1 => spiral1(q, spec.arms.unwrap_or(0)) + turb_x(),
            PatternKind::Spiral2 => spiral2(q, spec.arms.unwrap_or(0), turb_x()),
            PatternKind::Bozo | PatternKind::Spotted => noise(q),
            PatternKind::Granite => granite(q),
            PatternKind::Marble => q.x + turb_x(),
            PatternKind::Wood => wood(q, turbulent.then_some((self.turbulence, &self.octaves))),
            PatternKind::Agate => agate(q, &self.octaves),
            PatternKind::Wrinkles => wrinkles(q),
            PatternKind::Crackle => crackle(q, &self.crackle),
            PatternKind::Quilted => quilted(q, self.quilt_controls),
            PatternKind::Checker | PatternKind::Hexagon | PatternKind::Brick => {
                discrete_value(self.kind, spec, q) as f64
            }
            PatternKind::Average => 0.0,
        };
        shape_wave(
            raw,
            single(spec.frequency.unwrap_or(self.kind.default_frequency())),
            single(spec.phase.unwrap_or(0.0)),
            spec.wave.unwrap_or(self.kind.default_wave()),
        )
    }
}

/// POV-Ray's `Search_Blend_Map` over `len` (at least one) ascending entry values `value_at(i)`:
/// the entries below and above `value` and the upper one's weight (where the value sits on an
/// entry, or below the first or above the last, both are that entry, of weight 1).
pub fn search_blend_map(len: usize, value_at: impl Fn(usize) -> f64, value: f64) -> (usize, usize, f64) {
    let last = len - 1;
    if value >= value_at(last) {
        return (last, last, 1.0);
    }
    let cur = (0..len).find(|&i| value <= value_at(i)).unwrap_or(last);
    if cur == 0 || value == value_at(cur) {
        return (cur, cur, 1.0);
    }
    let (below, above) = (value_at(cur - 1), value_at(cur));
    (cur - 1, cur, (value - below) / (above - below))
}

/// True when POV-Ray's classic turbulence warp moves the point before `kind` reads it (with
/// a turbulence amount written): `marble` and `wood` apply their turbulence themselves.
pub fn warps_with_turbulence(kind: PatternKind, turbulent: bool) -> bool {
    turbulent && !matches!(kind, PatternKind::Marble | PatternKind::Wood)
}

/// A discrete pattern's colour index at pattern-space point `q` (POV-Ray's frame).
fn discrete_value(kind: PatternKind, spec: &Pigment, q: DVec3) -> usize {
    match kind {
        PatternKind::Checker => checker(q),
        PatternKind::Hexagon => hexagon(q),
        PatternKind::Brick => brick(
            q,
            DVec3::from_array(spec.brick_size.unwrap_or(DEFAULT_BRICK_SIZE)),
            spec.mortar.unwrap_or(DEFAULT_MORTAR),
        ),
        _ => 0,
    }
}

/// A Prism-frame direction in POV-Ray's frame.
fn pov_vector(v: [f64; 3]) -> DVec3 {
    DVec3::new(v[0], v[1], -v[2])
}

/// POV-Ray's frequency, phase and wave shaping of a raw pattern value.
pub fn shape_wave(raw: f64, frequency: f64, phase: f64, wave: Wave) -> f64 {
    let mut value = raw;
    if frequency != 0.0 {
        // POV-Ray wraps at 1.00001, not 1 (a value of exactly 1 stays 1).
        value = fmod(value * frequency + phase, 1.00001);
    }
    if value < 0.0 {
        value -= value.floor();
    }
    match wave {
        Wave::Ramp => value,
        Wave::Sine => (1.0 + cycloidal(value)) * 0.5,
        Wave::Triangle => triangle_wave(value),
        Wave::Scallop => cycloidal(value * 0.5).abs(),
        Wave::Cubic => value * value * (3.0 - 2.0 * value),
    }
}

/// `v` rounded to single precision, as POV-Ray stores a pattern's `frequency` and `phase`
/// (`SNGL` fields of `TPATTERN`): with a large pattern value (far along a gradient, say)
/// the rounding shows.
pub(super) fn single(v: f64) -> f64 {
    f64::from(v as f32)
}

/// POV-Ray's `cycloidal`: sin(2 pi v) of v's fractional part, odd in v.
pub(super) fn cycloidal(v: f64) -> f64 {
    if v >= 0.0 {
        ((v - v.floor()) * std::f64::consts::TAU).sin()
    } else {
        -((-(v + (-v).floor())) * std::f64::consts::TAU).sin()
    }
}

/// POV-Ray's `Triangle_Wave`: 0 at integers, 1 halfway between.
fn triangle_wave(v: f64) -> f64 {
    let offset = if v >= 0.0 { v - v.floor() } else { v + 1.0 + v.abs().floor() };
    if offset >= 0.5 { 2.0 * (1.0 - offset) } else { 2.0 * offset }
}

/// POV-Ray's colour map search: the first entry at or below its value, the last above it,
/// linear in between; where entries share a value the lower one owns it exactly.
pub fn map_lookup(map: &[MapEntry], value: f64) -> Rgbft {
    let last = map.len() - 1;
    if value >= map[last].0 {
        return map[last].1.rgbft();
    }
    let next = map.iter().position(|e| value <= e.0).unwrap_or(last);
    if next == 0 || value == map[next].0 {
        return map[next].1.rgbft();
    }
    let (prev, next) = (&map[next - 1], &map[next]);
    let w_prev = (next.0 - value) / (next.0 - prev.0);
    Rgbft::blend(prev.1.rgbft(), w_prev, next.1.rgbft(), 1.0 - w_prev)
}

fn checker(q: DVec3) -> usize {
    let sum = (q.x + POV_EPSILON).floor() + (q.y + POV_EPSILON).floor() + (q.z + POV_EPSILON).floor();
    (sum as i64 & 1) as usize
}

/// POV-Ray's hexagon tiling: 0, 1 or 2.
fn hexagon(q: DVec3) -> usize {
    // Width and height factors of the grid of half-triangles.
    const X_FACTOR: f64 = 0.5;
    const Z_FACTOR: f64 = 0.866025404;
    let x = q.x.abs();
    // The grid is 6 blocks high (6 * sqrt(3) / 2): negative z is shifted, not mirrored.
    let z = if q.z < 0.0 { 5.196152424 - q.z.abs() } else { q.z };
    let mut xs = x / X_FACTOR;
    let mut zs = z / Z_FACTOR;
    xs -= (xs / 6.0).floor() * 6.0;
    zs -= (zs / 6.0).floor() * 6.0;
    let xm = (xs.floor() as i64).rem_euclid(6);
    let zm = (zs.floor() as i64).rem_euclid(6);
    match xm {
        0 | 5 => match zm {
            0 | 5 => 0,
            1 | 2 => 1,
            _ => 2,
        },
        2 | 3 => match zm {
            0 | 1 => 2,
            2 | 3 => 0,
            _ => 1,
        },
        _ => {
            let mut xl = xs - xm as f64;
            let zl = zs - zm as f64;
            if (xm + zm) % 2 == 1 {
                xl = 1.0 - xl;
            }
            if xl == 0.0 {
                xl = 0.0001;
            }
            if zl / xl < 1.0 {
                match zm {
                    0 | 3 => 0,
                    2 | 5 => 1,
                    _ => 2,
                }
            } else {
                match zm {
                    0 | 3 => 2,
                    2 | 5 => 0,
                    _ => 1,
                }
            }
        }
    }
}

/// The fractional part as POV-Ray's brick takes it: truncate toward zero, then lift
/// negatives into [0, 1).
fn brick_fraction(v: f64) -> f64 {
    let f = v - v.trunc();
    if f < 0.0 { f + 1.0 } else { f }
}

/// POV-Ray's brick: 0 in the mortar, 1 in a brick.
fn brick(q: DVec3, size: DVec3, mortar: f64) -> usize {
    let fudge = POV_EPSILON + mortar;
    let p = q + DVec3::splat(fudge);
    let m = DVec3::splat(mortar) / size;
    if brick_fraction(p.y / size.y) <= m.y {
        return 0;
    }
    // Which course (odd or even row) the point is in.
    let upper = brick_fraction(p.y / size.y * 0.5) > 0.5;
    let ends = brick_fraction(p.x / size.x);
    let ends_shifted = brick_fraction(p.x / size.x + 0.5);
    let faces = brick_fraction(p.z / size.z);
    let faces_shifted = brick_fraction(p.z / size.z + 0.5);
    // Head and face joints alternate by half a brick from one course to the next.
    let mortar_here = if upper { ends_shifted <= m.x || faces <= m.z } else { ends <= m.x || faces_shifted <= m.z };
    usize::from(!mortar_here)
}

/// POV-Ray's gradient: the projection on `v`, wrapped above 1.
fn gradient(q: DVec3, v: DVec3) -> f64 {
    let r = q.dot(v);
    if r > 1.0 { fmod(r, 1.0) } else { r }
}

/// POV-Ray's radial: the angle about y from +z (POV-Ray's frame), a quarter turn added.
fn radial(q: DVec3) -> f64 {
    if q.x.abs() < 0.001 && q.z.abs() < 0.001 {
        0.25
    } else {
        0.25 + (q.x.atan2(q.z) + std::f64::consts::PI) / std::f64::consts::TAU
    }
}

fn onion(q: DVec3) -> f64 {
    fmod(q.length(), 1.0)
}

fn leopard(q: DVec3) -> f64 {
    let s = (q.x.sin() + q.y.sin() + q.z.sin()) / 3.0;
    s * s
}

/// Distance from the z axis and the angle about it (0..2 pi, POV-Ray's convention).
fn spiral_polar(q: DVec3) -> (f64, f64) {
    let rad = (q.x * q.x + q.y * q.y).sqrt();
    let phi = if rad == 0.0 {
        0.0
    } else if q.x < 0.0 {
        3.0 * std::f64::consts::FRAC_PI_2 - (q.y / rad).asin()
    } else {
        std::f64::consts::FRAC_PI_2 + (q.y / rad).asin()
    };
    (rad, phi)
}

fn spiral1(q: DVec3, arms: i32) -> f64 {
    let (rad, phi) = spiral_polar(q);
    q.z + rad + f64::from(arms) * phi / std::f64::consts::TAU
}

fn spiral2(q: DVec3, arms: i32, turbulence: f64) -> f64 {
    let (rad, phi) = spiral_polar(q);
    triangle_wave(rad) + triangle_wave(q.z + rad + f64::from(arms) * phi / std::f64::consts::TAU + turbulence)
}

/// POV-Ray 3.7's granite (noise generator 2): six octaves of |1 - 2 noise|, each at most 0.5.
fn granite(q: DVec3) -> f64 {
    // Octaves at 4 q 2^i weighted 2^-i (powers of two: the same as dividing by 2^i).
    let mut value = 0.0;
    for_each_octave(q * 4.0, &Octaves::halving(6), noise, noise_pair, |w, n| {
        value += (1.0 - 2.0 * n).abs().min(0.5) * w
    });
    value
}

/// POV-Ray's `quilt_cubic`: the Bezier cubic from 0 to 1 with control values `c0` and `c1`,
/// over sqrt(3/4).
pub fn quilt_cubic(t: f64, c0: f64, c1: f64) -> f64 {
    const INV_SQRT_3_4: f64 = 1.154700538;
    let it = 1.0 - t;
    (t * t * t + 3.0 * t * it * it * c0 + 3.0 * t * t * it * c1) * INV_SQRT_3_4
}

/// POV-Ray's `FLOOR`: one below at negative integers (`0 - floor(-x) - 1`).
fn pov_floor(x: f64) -> f64 {
    if x >= 0.0 { x.floor() } else { 0.0 - (0.0 - x).floor() - 1.0 }
}

/// The offset of `q` from the centre of its unit cube, scaled by the quilting cubic of its
/// length (POV-Ray's quilted pattern and normal share it).
pub fn quilt_vector(q: DVec3, (c0, c1): (f64, f64)) -> DVec3 {
    let v = DVec3::new(q.x - pov_floor(q.x) - 0.5, q.y - pov_floor(q.y) - 0.5, q.z - pov_floor(q.z) - 0.5);
    v * quilt_cubic(v.length(), c0, c1)
}

/// POV-Ray's quilted pigment: the mean absolute component of the quilting vector.
pub(super) fn quilted(q: DVec3, controls: (f64, f64)) -> f64 {
    let v = quilt_vector(q, controls);
    (v.x.abs() + v.y.abs() + v.z.abs()) / 3.0
}

/// POV-Ray's wood: the distance from the z axis, its x and y bent by vector turbulence
/// through a sine when the pigment has turbulence (`amount` and octaves).
fn wood(q: DVec3, turbulence: Option<(DVec3, &Octaves)>) -> f64 {
    let (mut x, mut y) = (q.x, q.y);
    if let Some((amount, octaves)) = turbulence {
        let w = dturbulence(q, octaves);
        x += cycloidal((q.x + w.x) * amount.x);
        y += cycloidal((q.y + w.y) * amount.y);
    }
    (x * x + y * y).sqrt()
}

/// POV-Ray's agate (its `agate_turb` scale 1): scalar turbulence (always, with the pigment's
/// octaves) folded through a sine along z, then raised to 0.77.
fn agate(q: DVec3, octaves: &Octaves) -> f64 {
    let t = turbulence(q, octaves);
    let v = 0.5 * (cycloidal(1.3 * t + 1.1 * q.z) + 1.0);
    if v < 0.0 { 0.0 } else { v.min(1.0).powf(0.77) }
}

/// POV-Ray 3.7's wrinkles pigment (noise generator 2): ten octaves of 2 noise - 0.5, each
/// clamped to [0, 1], halved.
pub(super) fn wrinkles(q: DVec3) -> f64 {
    let mut value = 0.0;
    for_each_octave(q, &Octaves::halving(10), noise, noise_pair, |w, n| value += w * (2.0 * n - 0.5).clamp(0.0, 1.0));
    value / 2.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn map_values_beyond_one_shift_the_blend_below_them() {
        // POV-Ray's common `[0.8 A] [1.01 B]`: at value 1 the colour is not quite B.
        let pigment: Pigment =
            toml::from_str("pattern = \"bozo\"\ncolor_map = [[-0.2, [0, 0, 0]], [0.8, [0, 0, 0]], [1.01, [1, 1, 1]]]")
                .unwrap();
        pigment.check().unwrap();
        let c = map_lookup(&pigment.color_map, 1.0);
        assert!((c.rgb.x - 0.2 / 0.21).abs() < 1e-12, "{c:?}");
        let bad: Pigment =
            toml::from_str("pattern = \"bozo\"\ncolor_map = [[0, [0, 0, 0]], [nan, [1, 1, 1]]]").unwrap();
        assert_eq!(bad.check().unwrap_err().0, "color_map");
    }

    fn pigment(text: &str) -> Pigment {
        let p: Pigment = toml::from_str(text).unwrap();
        p.check().unwrap();
        p
    }

    /// A point given in POV-Ray's frame, as Prism's object point.
    fn prism(x: f64, y: f64, z: f64) -> DVec3 {
        DVec3::new(x, y, -z)
    }

    const BW: &str = "color_map = [[0, [0, 0, 0]], [1, [1, 1, 1]]]";

    #[test]
    fn checker_alternates_unit_cubes_including_negative_cells() {
        let f = PigmentField::new(&pigment("pattern = \"checker\"\ncolors = [[1, 0, 0], [0, 0, 1]]"));
        // floor sums: 0 -> even -> first colour; 1 -> odd -> second.
        assert_eq!(f.at(prism(0.5, 0.5, 0.5)).rgb, DVec3::X);
        assert_eq!(f.at(prism(1.5, 0.5, 0.5)).rgb, DVec3::Z);
        // -0.5 floors to -1: odd.
        assert_eq!(f.at(prism(-0.5, 0.5, 0.5)).rgb, DVec3::Z);
        assert_eq!(f.at(prism(-0.5, -0.5, 0.5)).rgb, DVec3::X);
        // The cell edge belongs to the upper cell (floor(x + 1e-10)).
        assert_eq!(f.at(prism(1.0 - 1e-11, 0.5, 0.5)).rgb, DVec3::Z);
    }

    #[test]
    fn checker_is_read_in_pov_ray_frame() {
        // POV-Ray's z is Prism's -z: z = 0.5 in Prism is -0.5 there, an odd cell.
        let f = PigmentField::new(&pigment("pattern = \"checker\"\ncolors = [[1, 0, 0], [0, 0, 1]]"));
        assert_eq!(f.at(DVec3::new(0.5, 0.5, 0.5)).rgb, DVec3::Z);
    }

    #[test]
    fn hexagon_known_cells() {
        let p = |x, z| hexagon(DVec3::new(x, 0.0, z));
        // xs = x / 0.5, zs = z / 0.866: block (0, 0) -> 0; (0, 1) -> 1; (0, 3) -> 2; (2, 0) -> 2.
        assert_eq!(p(0.1, 0.1), 0);
        assert_eq!(p(0.1, 1.0), 1);
        assert_eq!(p(0.1, 3.0), 2);
        assert_eq!(p(1.1, 0.1), 2);
        assert_eq!(p(1.1, 2.0), 0);
        // Block (1, 0) is split by its diagonal: xm + zm odd flips x; xl = 1 - 0.2 = 0.8.
        // zl / xl = 0.1 / 0.8 < 1 -> zm 0 gives 0; zl = 0.9 -> 0.9 / 0.8 >= 1 -> 2.
        assert_eq!(p(0.6, 0.1 * 0.866025404), 0);
        assert_eq!(p(0.6, 0.9 * 0.866025404), 2);
        // x is mirrored (|x|), z < 0 shifted by the grid height: z = -0.1 is zs = 5.9.
        assert_eq!(p(-0.1, 0.1), 0);
        assert_eq!(p(0.1, -0.1), 0);
        // z = -1 -> 4.196 -> zs = 4.845: block (0, 4) -> 2 (mirrored, it would be block (0, 1) -> 1).
        assert_eq!(p(0.1, -1.0), 2);
    }

    #[test]
    fn brick_mortar_and_courses() {
        let size = DVec3::new(8.0, 3.0, 4.5);
        let b = |x, y, z| brick(DVec3::new(x, y, z), size, 0.5);
        // y + 0.5 = 0.3: 0.3 / 3 = 0.1 <= 0.5 / 3 -> mortar (bed joint).
        assert_eq!(b(3.0, -0.2, 1.0), 0);
        // Middle of the first course: y = 1.5 -> y' = 2 -> 0.667 > 0.1667; course fraction
        // 0.333 <= 0.5 (lower course): head joint at x' / 8 <= 1/16, i.e. x' <= 0.5.
        assert_eq!(b(3.0, 1.5, 1.0), 1);
        assert_eq!(b(-0.25, 1.5, 1.0), 0);
        // The lower course's face joints are shifted by half a brick in z: z' / 4.5 + 0.5
        // has fraction <= 0.5 / 4.5 at z' = 2.25 .. 2.75.
        assert_eq!(b(3.0, 1.5, 2.0), 0);
        // Upper course (y' = 5 -> 5 / 6 = 0.833 > 0.5): head joints shifted by half a brick.
        assert_eq!(b(3.5, 4.5, 1.0), 0);
        assert_eq!(b(-0.25, 4.5, 1.0), 1);
        // ... and face joints unshifted: z' = 0.25 -> 0.25 / 4.5 <= 1/9.
        assert_eq!(b(1.0, 4.5, -0.25), 0);
    }

    #[test]
    fn gradient_wraps_above_one_and_keeps_negatives_for_the_wave() {
        assert_eq!(gradient(DVec3::new(0.0, 0.25, 0.0), DVec3::Y), 0.25);
        assert_eq!(gradient(DVec3::new(0.0, 1.0, 0.0), DVec3::Y), 1.0);
        assert!((gradient(DVec3::new(0.0, 2.75, 0.0), DVec3::Y) - 0.75).abs() < 1e-15);
        assert_eq!(gradient(DVec3::new(0.0, -0.25, 0.0), DVec3::Y), -0.25);
        // The wave step lifts negatives: -0.25 -> 0.75.
        assert!((shape_wave(-0.25, 1.0, 0.0, Wave::Ramp) - 0.75).abs() < 1e-12);
        // A gradient along Prism's z is along POV-Ray's -z, so the ramp follows Prism's z.
        let f = PigmentField::new(&pigment(&format!("pattern = \"gradient\"\nvector = [0, 0, 1]\n{BW}")));
        assert!((f.at(DVec3::new(0.0, 0.0, 0.3)).rgb - DVec3::splat(0.3)).abs().max_element() < 1e-12);
        // POV-Ray normalises the vector: its length does not change the period.
        let f = PigmentField::new(&pigment(&format!("pattern = \"gradient\"\nvector = [0, 3, 4]\n{BW}")));
        assert!((f.at(DVec3::new(0.0, 0.3, 0.4)).rgb - DVec3::splat(0.5)).abs().max_element() < 1e-12);
    }

    #[test]
    fn radial_onion_leopard_spirals() {
        // +x in POV-Ray's frame: atan2(1, 0) = pi / 2 -> 0.25 + 0.75 = 1.0.
        assert!((radial(DVec3::X) - 1.0).abs() < 1e-15);
        // +z: atan2(0, 1) = 0 -> 0.75; on the axis 0.25.
        assert!((radial(DVec3::Z) - 0.75).abs() < 1e-15);
        assert_eq!(radial(DVec3::Y), 0.25);
        assert!((onion(DVec3::new(3.0, 4.0, 0.0)) - 0.0).abs() < 1e-15);
        assert!((onion(DVec3::new(0.0, 1.5, 0.0)) - 0.5).abs() < 1e-15);
        let half_pi = std::f64::consts::FRAC_PI_2;
        assert!((leopard(DVec3::new(half_pi, half_pi, half_pi)) - 1.0).abs() < 1e-15);
        assert!((leopard(DVec3::new(half_pi, 0.0, 0.0)) - 1.0 / 9.0).abs() < 1e-15);
        // On +x: rad 1, phi = pi / 2 + asin(0) -> z + 1 + arms / 4.
        assert!((spiral1(DVec3::new(1.0, 0.0, 0.5), 2) - 2.0).abs() < 1e-15);
        // On -y: x = 0 (not < 0) -> phi = pi / 2 + asin(-1) = 0.
        assert!((spiral1(DVec3::new(0.0, -2.0, 0.0), 3) - 2.0).abs() < 1e-15);
        // spiral2: tw(rad) + tw(z + rad + arms phi / 2 pi); rad 0.25 -> 0.5, 0.25 + 0.5 -> 0.5.
        assert!((spiral2(DVec3::new(0.25, 0.0, 0.0), 2, 0.0) - 1.0).abs() < 1e-15);
    }

    #[test]
    fn spirals_default_to_the_triangle_wave() {
        let map = "color_map = [[0, [0, 0, 0]], [1, [1, 1, 1]]]";
        let f = PigmentField::new(&pigment(&format!("pattern = \"spiral1\"\narms = 1\n{map}")));
        // POV-Ray point (0.25, 0, 0): raw 0.25 + 1 * (pi / 2) / (2 pi) = 0.5 -> triangle 1.
        assert!((f.at(prism(0.25, 0.0, 0.0)).rgb.x - 1.0).abs() < 1e-9);
        let f = PigmentField::new(&pigment(&format!("pattern = \"spiral1\"\narms = 1\nwave = \"ramp\"\n{map}")));
        assert!((f.at(prism(0.25, 0.0, 0.0)).rgb.x - 0.5).abs() < 1e-9);
    }

    #[test]
    fn waves_frequency_and_phase() {
        assert!((shape_wave(0.3, 2.0, 0.0, Wave::Ramp) - 0.6).abs() < 1e-12);
        assert!((shape_wave(0.3, 2.0, 0.5, Wave::Ramp) - (1.1 % 1.00001)).abs() < 1e-12);
        // Frequency 0 leaves the value unwrapped (a negative one is still lifted).
        assert_eq!(shape_wave(1.5, 0.0, 0.0, Wave::Ramp), 1.5);
        // A value of exactly 1 is kept (POV-Ray wraps at 1.00001).
        assert_eq!(shape_wave(1.0, 1.0, 0.0, Wave::Ramp), 1.0);
        assert!((shape_wave(0.25, 1.0, 0.0, Wave::Sine) - 1.0).abs() < 1e-12);
        assert!((shape_wave(0.75, 1.0, 0.0, Wave::Sine) - 0.0).abs() < 1e-12);
        assert!((shape_wave(0.25, 1.0, 0.0, Wave::Triangle) - 0.5).abs() < 1e-12);
        assert!((shape_wave(0.75, 1.0, 0.0, Wave::Triangle) - 0.5).abs() < 1e-12);
        assert!((shape_wave(0.5, 1.0, 0.0, Wave::Scallop) - 1.0).abs() < 1e-12);
        assert!((shape_wave(0.25, 1.0, 0.0, Wave::Scallop) - (std::f64::consts::FRAC_PI_4).sin()).abs() < 1e-12);
        assert!((shape_wave(0.5, 1.0, 0.0, Wave::Cubic) - 0.5).abs() < 1e-12);
        assert!((shape_wave(0.25, 1.0, 0.0, Wave::Cubic) - 0.15625).abs() < 1e-12);
    }

    #[test]
    fn frequency_and_phase_are_single_precision_as_in_pov_ray() {
        // Far along a gradient the rounding of 3.81 to f32 moves the wrapped value by ~1e-4:
        // found by a random scene whose floor differed from POV-Ray at the horizon.
        let field = PigmentField::new(&pigment(
            "pattern = \"gradient\"\nvector = [1, 0, 0]\nfrequency = 3.81\nphase = 0.11\n\
             color_map = [[0, [0, 0, 0]], [1, [1, 1, 1]]]",
        ));
        // A gradient only wraps values above 1: far on its negative side the value is large.
        let x = -1234.5678;
        let value = field.value(DVec3::new(x, 0.0, 0.0));
        let pov = shape_wave(x, f64::from(3.81f32), f64::from(0.11f32), Wave::Ramp);
        assert_eq!(value, pov);
        assert!((value - shape_wave(x, 3.81, 0.11, Wave::Ramp)).abs() > 1e-5);
    }

    #[test]
    fn color_map_edges() {
        let p = pigment(
            "pattern = \"onion\"\ncolor_map = [[0.2, [1, 0, 0]], [0.5, [0, 1, 0]], [0.5, [0, 0, 1]], \
             [0.8, { color = [1, 1, 1], filter = 0.5, transmit = 0.25 }]]",
        );
        let map = &p.color_map;
        // Below the first entry: the first colour; above the last: the last.
        assert_eq!(map_lookup(map, 0.0).rgb, DVec3::X);
        assert_eq!(map_lookup(map, 0.95), Rgbft { rgb: DVec3::ONE, filter: 0.5, transmit: 0.25 });
        // Between 0.2 and 0.5: linear.
        let c = map_lookup(map, 0.35).rgb;
        assert!((c - DVec3::new(0.5, 0.5, 0.0)).abs().max_element() < 1e-12, "{c}");
        // Two entries at 0.5: exactly 0.5 is the first; just above, interpolation starts
        // from the second.
        assert_eq!(map_lookup(map, 0.5).rgb, DVec3::Y);
        let c = map_lookup(map, 0.65);
        assert!((c.rgb - DVec3::new(0.5, 0.5, 1.0)).abs().max_element() < 1e-12, "{:?}", c);
        assert!((c.filter - 0.25).abs() < 1e-12 && (c.transmit - 0.125).abs() < 1e-12);
        // One entry: everywhere that colour.
        let one = [MapEntry(0.5, MapColor::Opaque(Rgb::grey(0.3)))];
        assert_eq!(map_lookup(&one, 0.1).rgb, DVec3::splat(0.3));
        assert_eq!(map_lookup(&one, 0.9).rgb, DVec3::splat(0.3));
    }

    #[test]
    fn pattern_transform_scales_rotates_translates_in_object_space() {
        // Scale 2 then translate 1 along x: the checker's cell [1, 3) in x is one cell.
        let f = PigmentField::new(&pigment(
            "pattern = \"checker\"\ncolors = [[1, 1, 1], [0, 0, 0]]\nscale = 2\ntranslate = [1, 0, 0]",
        ));
        let a = f.at(prism(1.1, 0.5, 0.5)).rgb;
        assert_eq!(f.at(prism(2.9, 0.5, 0.5)).rgb, a);
        assert_ne!(f.at(prism(3.1, 0.5, 0.5)).rgb, a);
        assert_ne!(f.at(prism(0.9, 0.5, 0.5)).rgb, a);
        // A gradient along x rotated 90 degrees about z runs along y.
        let f = PigmentField::new(&pigment(&format!(
            "pattern = \"gradient\"\nvector = [1, 0, 0]\nrotate = [0, 0, 90]\n{BW}"
        )));
        assert!((f.at(DVec3::new(0.0, 0.4, 0.0)).rgb.x - 0.4).abs() < 1e-12);
        assert!((f.at(DVec3::new(0.4, 0.0, 0.0)).rgb.x - 0.0).abs() < 1e-12);
    }

    #[test]
    fn noise_patterns_follow_povray_definitions() {
        let p = DVec3::new(0.31, -1.27, 2.45);
        // granite: sum over six octaves of min(|1 - 2 n(4 p 2^i)|, 0.5) / 2^i.
        let expected: f64 = (0..6)
            .map(|i| {
                let f = f64::from(1 << i);
                (1.0 - 2.0 * noise(p * 4.0 * f)).abs().min(0.5) / f
            })
            .sum();
        assert_eq!(granite(p), expected);
        // wood without turbulence: the distance from the z axis.
        assert_eq!(wood(DVec3::new(3.0, 4.0, 9.0), None), 5.0);
        // wrinkles is at most (1 + 0.5 + ... ) / 2 < 1 and at least 0.
        assert!((0.0..1.0).contains(&wrinkles(p)));
        // wrinkles: ten octaves of 2 n(p 2^i) - 0.5 clamped to [0, 1], weighted 2^-i, halved.
        for q in [p, DVec3::new(-7.3, 0.04, 11.9), DVec3::new(123.4, -56.7, 0.001)] {
            let mut sequential = (2.0 * noise(q) - 0.5).clamp(0.0, 1.0);
            for i in 1..10 {
                let f = f64::from(1 << i);
                sequential += (2.0 * noise(q * f) - 0.5).clamp(0.0, 1.0) / f;
            }
            assert_eq!(wrinkles(q).to_bits(), (sequential / 2.0).to_bits(), "at {q}");
        }
        // agate is in [0, 1] and uses turbulence even without a turbulence amount.
        let a = agate(p, &Octaves::default());
        assert!((0.0..=1.0).contains(&a));
        // marble and wood default to the triangle wave, bozo to the ramp.
        assert_eq!(PatternKind::Marble.default_wave(), Wave::Triangle);
        assert_eq!(PatternKind::Bozo.default_wave(), Wave::Ramp);
    }

    #[test]
    fn turbulence_displaces_the_point_except_for_marble_and_wood() {
        let map = "color_map = [[0, [0, 0, 0]], [1, [1, 1, 1]]]";
        let plain =
            PigmentField::new(&pigment(&format!("pattern = \"gradient\"\nvector = [1, 0, 0]\nfrequency = 0\n{map}")));
        let turbulent = PigmentField::new(&pigment(&format!(
            "pattern = \"gradient\"\nvector = [1, 0, 0]\nfrequency = 0\nturbulence = [0.3, 0, 0]\noctaves = 3\n{map}"
        )));
        let p = prism(0.4, 0.2, 0.1);
        let q = DVec3::new(0.4, 0.2, 0.1);
        let o = Octaves { octaves: 3, ..Octaves::default() };
        let expected = (0.4 + 0.3 * dturbulence(q, &o).x).clamp(0.0, 1.0);
        assert!((turbulent.at(p).rgb.x - expected).abs() < 1e-12);
        assert!((plain.at(p).rgb.x - 0.4).abs() < 1e-12);
        // Marble: x + amount.x * scalar turbulence at the undisplaced point, triangle wave.
        let marble = PigmentField::new(&pigment(&format!("pattern = \"marble\"\nturbulence = 0.5\n{map}")));
        let raw = 0.4 + 0.5 * turbulence(q, &Octaves::default());
        let expected = shape_wave(raw, 1.0, 0.0, Wave::Triangle);
        assert!((marble.at(p).rgb.x - expected).abs() < 1e-12);
        // Deterministic.
        assert_eq!(marble.at(p), marble.at(p));
    }

    #[test]
    fn crackle_pigment_reads_the_cell_field_with_its_keys() {
        use crate::material::crackle::{CrackleParams, crackle};
        let f = PigmentField::new(&pigment(&format!(
            "pattern = \"crackle\"\nform = [0.5, 0.25, 0.1]\nmetric = 3\noffset = 0.2\nscale = 0.5\n{BW}"
        )));
        let params = CrackleParams { form: DVec3::new(0.5, 0.25, 0.1), metric: 3.0, offset: 0.2, solid: false };
        let p = DVec3::new(0.3, -0.8, 1.4);
        let expected = crackle(prism(0.6, -1.6, 2.8), &params);
        assert!((f.at(p).rgb.x - expected).abs() < 1e-12);
        // The defaults: form [-1, 1, 0], metric 2, offset 0.
        let f = PigmentField::new(&pigment(&format!("pattern = \"crackle\"\n{BW}")));
        assert_eq!(f.at(prism(0.3, 0.4, 0.5)).rgb.x, crackle(DVec3::new(0.3, 0.4, 0.5), &CrackleParams::default()));
        // Solid: one colour per cell.
        let f = PigmentField::new(&pigment(&format!("pattern = \"crackle\"\nsolid = true\n{BW}")));
        let a = crate::material::crackle::cell_point(1, 2, -3);
        assert_eq!(f.at(a * DVec3::new(1.0, 1.0, -1.0)).rgb.x, noise(a));
    }

    #[test]
    fn quilted_follows_povray_and_is_unwrapped_by_default() {
        // At a cube's centre the vector is zero; along an axis it is (t, 0, 0) scaled by the
        // cubic of |t|, so the value is |t| quilt_cubic(|t|) / 3.
        assert_eq!(quilted(DVec3::splat(0.5), (1.0, 1.0)), 0.0);
        let t: f64 = 0.3;
        let expected = t * quilt_cubic(t, 1.0, 1.0) / 3.0;
        assert!((quilted(DVec3::new(0.8, 0.5, 0.5), (1.0, 1.0)) - expected).abs() < 1e-15);
        // POV-Ray's FLOOR puts -1 in the cube below: -1 - (-2) - 0.5 = 0.5.
        assert_eq!(pov_floor(-1.0), -2.0);
        assert_eq!(pov_floor(-0.5), -1.0);
        // quilt_cubic with both controls 0: t^3 / sqrt(3/4).
        assert!((quilt_cubic(0.5, 0.0, 0.0) - 0.125 * 1.154700538).abs() < 1e-15);
        assert_eq!(PatternKind::Quilted.default_frequency(), 0.0);
        assert_eq!(PatternKind::Crackle.default_frequency(), 1.0);
    }

    #[test]
    fn bad_pigments_name_their_key() {
        let err = |text: &str| toml::from_str::<Pigment>(text).unwrap().check().unwrap_err();
        assert_eq!(err("pattern = \"onion\"").0, "color_map");
        assert_eq!(err("pattern = \"onion\"\ncolor_map = [[0.5, [1, 1, 1]], [0.2, [0, 0, 0]]]").0, "color_map");
        assert_eq!(err("pattern = \"onion\"\ncolor_map = [[inf, [1, 1, 1]]]").0, "color_map");
        // Colours, filter and transmit within a material's limits (their products overflow).
        assert_eq!(err("pattern = \"onion\"\ncolor_map = [[0, [1e31, 1, 1]]]").0, "color_map");
        assert_eq!(err("pattern = \"onion\"\ncolor_map = [[0, { color = 1, filter = 1e300 }]]").0, "color_map");
        assert_eq!(err("pattern = \"checker\"\ncolors = [1, { color = 1, transmit = -1e10 }]").0, "colors");
        let nested = "pattern = \"onion\"\npigment_map = [[0, { color = 1, filter = 1e300 }]]";
        assert_eq!(err(nested).0, "pigment_map[0].filter");
        let at_limits = "pattern = \"onion\"\ncolor_map = [[0, { color = 1e30, filter = 1e9, transmit = -1e9 }]]";
        toml::from_str::<Pigment>(at_limits).unwrap().check().unwrap();
        assert_eq!(err("pattern = \"checker\"\ncolors = [[1, 1, 1]]").0, "colors");
        assert_eq!(err("pattern = \"checker\"\ncolors = [[1, 1, 1], [0, 0, 0]]\nfrequency = 2").0, "frequency");
        assert_eq!(err(&format!("pattern = \"gradient\"\n{BW}")).0, "vector");
        assert_eq!(err(&format!("pattern = \"onion\"\nvector = [1, 0, 0]\n{BW}")).0, "vector");
        assert_eq!(err(&format!("pattern = \"spiral1\"\n{BW}")).0, "arms");
        assert_eq!(err(&format!("pattern = \"onion\"\nscale = 0\n{BW}")).0, "scale");
        assert_eq!(err(&format!("pattern = \"bozo\"\nturbulence = 1\noctaves = 11\n{BW}")).0, "octaves");
        assert_eq!(err(&format!("pattern = \"bozo\"\nturbulence = 1\noctaves = 0\n{BW}")).0, "octaves");
        assert_eq!(err(&format!("pattern = \"bozo\"\nomega = 0.3\n{BW}")).0, "omega");
        assert_eq!(err(&format!("pattern = \"crackle\"\nmetric = 0\n{BW}")).0, "metric");
        assert_eq!(err(&format!("pattern = \"crackle\"\nmetric = 101\n{BW}")).0, "metric");
        assert_eq!(err(&format!("pattern = \"crackle\"\nmetric = nan\n{BW}")).0, "metric");
        assert_eq!(err(&format!("pattern = \"crackle\"\noffset = -0.5\n{BW}")).0, "offset");
        assert_eq!(err(&format!("pattern = \"crackle\"\nform = [1, inf, 0]\n{BW}")).0, "form");
        assert_eq!(err(&format!("pattern = \"granite\"\nsolid = true\n{BW}")).0, "solid");
        assert_eq!(err(&format!("pattern = \"granite\"\nmetric = 1\n{BW}")).0, "metric");
        assert_eq!(err(&format!("pattern = \"crackle\"\ncontrol0 = 1\n{BW}")).0, "control0");
        assert_eq!(err(&format!("pattern = \"quilted\"\ncontrol1 = nan\n{BW}")).0, "control1");
        let e = toml::from_str::<Pigment>("pattern = \"chekcer\"").unwrap_err().to_string();
        assert!(e.contains("did you mean `checker`?"), "{e}");
        let e = toml::from_str::<Pigment>("pattern = \"onion\"\nfrequncy = 2").unwrap_err().to_string();
        assert!(e.contains("unknown field `frequncy`"), "{e}");
    }

    /// Two plain entries, red below and see-through blue above, over a gradient along x.
    const RED_TO_BLUE: &str =
        "pigment_map = [[0.0, { color = [1, 0, 0] }], [1.0, { color = [0, 0, 1], transmit = 1 }]]";

    #[test]
    fn pigment_map_blends_neighbouring_entries_in_all_five_components() {
        let f = PigmentField::new(&pigment(&format!("pattern = \"gradient\"\nvector = [1, 0, 0]\n{RED_TO_BLUE}")));
        let c = f.at(DVec3::new(0.5, 0.0, 0.0));
        assert!((c.rgb - DVec3::new(0.5, 0.0, 0.5)).abs().max_element() < 1e-12, "{c:?}");
        assert!((c.transmit - 0.5).abs() < 1e-12 && c.filter == 0.0);
        let c = f.at(DVec3::new(0.25, 0.0, 0.0));
        assert!((c.rgb - DVec3::new(0.75, 0.0, 0.25)).abs().max_element() < 1e-12, "{c:?}");
        assert!(f.can_transmit());
    }

    #[test]
    fn pigment_map_entries_at_equal_values_give_a_sharp_edge() {
        let f = PigmentField::new(&pigment(
            "pattern = \"gradient\"\nvector = [1, 0, 0]\npigment_map = [[0.2, { color = [1, 0, 0] }], \
             [0.5, { color = [0, 1, 0] }], [0.5, { color = [0, 0, 1] }], [0.8, { color = [1, 1, 1] }]]",
        ));
        let at = |x: f64| f.at(DVec3::new(x, 0.0, 0.0)).rgb;
        // Below the first entry its colour, above the last the last's.
        assert_eq!(at(0.1), DVec3::X);
        assert_eq!(at(0.9), DVec3::ONE);
        // Exactly 0.5 is the lower entry's; just above, the blend starts from the upper one.
        assert_eq!(at(0.5), DVec3::Y);
        assert!((at(0.5 + 1e-9) - DVec3::Z).abs().max_element() < 1e-6);
        assert!((at(0.65) - DVec3::new(0.5, 0.5, 1.0)).abs().max_element() < 1e-12);
        assert!((at(0.35) - DVec3::new(0.5, 0.5, 0.0)).abs().max_element() < 1e-12);
    }

    #[test]
    fn pigment_map_entries_read_the_point_through_the_outer_transform_then_their_own() {
        // The outer gradient is scaled by 2 and its checker entries by 0.25: the entries
        // repeat every 0.5 in object space (POV-Ray hands an entry the outer pattern point).
        let checker = "{ pattern = \"checker\", colors = [[1, 1, 1], [0, 0, 0]], scale = 0.25 }";
        let f = PigmentField::new(&pigment(&format!(
            "pattern = \"gradient\"\nvector = [1, 0, 0]\nscale = 2\npigment_map = [[0.0, {checker}], [1.0, {checker}]]"
        )));
        let direct = PigmentField::new(&pigment("pattern = \"checker\"\ncolors = [[1, 1, 1], [0, 0, 0]]\nscale = 0.5"));
        for p in [
            DVec3::new(0.1, 0.2, 0.3),
            DVec3::new(0.6, 0.2, 0.3),
            DVec3::new(0.3, -0.7, 1.2),
            DVec3::new(1.3, 0.1, -0.4),
        ] {
            assert_eq!(f.at(p).rgb, direct.at(p).rgb, "{p}");
        }
    }

    #[test]
    fn pigment_map_entries_see_the_outer_turbulence_except_marble_and_wood() {
        let entry = "{ pattern = \"gradient\", vector = [1, 0, 0], frequency = 0, color_map = [[0, [0, 0, 0]], [1, [1, 1, 1]]] }";
        let map = format!("pigment_map = [[0.0, {entry}], [1.0, {entry}]]");
        let p = prism(0.4, 0.2, 0.1);
        let q = DVec3::new(0.4, 0.2, 0.1);
        let o = Octaves { octaves: 3, ..Octaves::default() };
        let f = PigmentField::new(&pigment(&format!("pattern = \"bozo\"\nturbulence = 0.3\noctaves = 3\n{map}")));
        let expected = (q.x + 0.3 * dturbulence(q, &o).x).clamp(0.0, 1.0);
        assert!((f.at(p).rgb.x - expected).abs() < 1e-12);
        // Marble's turbulence bends its value, not the point its entries read.
        let f = PigmentField::new(&pigment(&format!("pattern = \"marble\"\nturbulence = 0.3\noctaves = 3\n{map}")));
        assert!((f.at(p).rgb.x - 0.4).abs() < 1e-12);
    }

    #[test]
    fn average_weights_its_entries_in_all_five_components() {
        let f = PigmentField::new(&pigment(
            "pattern = \"average\"\npigment_map = [\n  [1, { color = [1, 0, 0], transmit = 0.4 }],\n  \
             [3, { color = [0, 0, 1], filter = 0.8 }],\n  [0, { color = [0, 1, 0] }],\n]",
        ));
        let c = f.at(DVec3::new(0.3, -2.0, 5.0));
        assert!((c.rgb - DVec3::new(0.25, 0.0, 0.75)).length() < 1e-12, "{:?}", c.rgb);
        assert!((c.filter - 0.6).abs() < 1e-12 && (c.transmit - 0.1).abs() < 1e-12);
        // A one-entry average is its entry, read through the average's transform.
        let entry = "{ pattern = \"bozo\", color_map = [[0, [0, 0, 0]], [1, [1, 1, 1]]], scale = 0.3 }";
        let one =
            PigmentField::new(&pigment(&format!("pattern = \"average\"\nscale = 2\npigment_map = [[0.5, {entry}]]")));
        let alone = PigmentField::new(&pigment(
            "pattern = \"bozo\"\ncolor_map = [[0, [0, 0, 0]], [1, [1, 1, 1]]]\nscale = 0.6",
        ));
        for p in [DVec3::new(0.3, 0.7, -1.1), DVec3::new(-4.0, 2.5, 0.25)] {
            assert!((one.at(p).rgb - alone.at(p).rgb).length() < 1e-9, "at {p}");
        }
        let err = |text: &str| toml::from_str::<Pigment>(text).unwrap().check().unwrap_err();
        assert_eq!(err("pattern = \"average\"").0, "pigment_map");
        assert!(err("pattern = \"average\"\npigment_map = []").1.contains("at least one"));
        assert!(err("pattern = \"average\"\npigment_map = [[-1, { color = [1, 1, 1] }]]").1.contains("not negative"));
        assert!(err("pattern = \"average\"\npigment_map = [[0, { color = [1, 1, 1] }]]").1.contains("above 0"));
        assert_eq!(err("pattern = \"average\"\ncolor_map = [[0, [1, 1, 1]]]").0, "color_map");
        assert_eq!(
            err("pattern = \"average\"\nfrequency = 2\npigment_map = [[1, { color = [1, 1, 1] }]]").0,
            "frequency"
        );
        // Weights need not be ascending or at most 1.
        pigment("pattern = \"average\"\npigment_map = [[5, { color = [1, 1, 1] }], [2, { color = [0, 0, 0] }]]");
    }

    #[test]
    fn pigment_maps_nest() {
        let inner = format!("{{ pattern = \"gradient\", vector = [0, 1, 0], {RED_TO_BLUE} }}");
        let f = PigmentField::new(&pigment(&format!(
            "pattern = \"gradient\"\nvector = [1, 0, 0]\npigment_map = [[0.0, {{ color = [0, 1, 0] }}], [0.5, {inner}]]"
        )));
        // x = 0.75 is above the last entry: the inner map alone, read along y.
        let c = f.at(DVec3::new(0.75, 0.5, 0.0));
        assert!((c.rgb - DVec3::new(0.5, 0.0, 0.5)).abs().max_element() < 1e-12 && (c.transmit - 0.5).abs() < 1e-12);
        // x = 0.25: halfway between green and the inner map's colour at y = 0.5.
        let c = f.at(DVec3::new(0.25, 0.5, 0.0));
        assert!((c.rgb - DVec3::new(0.25, 0.5, 0.25)).abs().max_element() < 1e-12, "{c:?}");
        assert!((c.transmit - 0.25).abs() < 1e-12);
        assert_eq!(f.spec.colors().len(), 3);
    }

    #[test]
    fn bad_pigment_maps_name_their_key() {
        let err = |text: &str| toml::from_str::<Pigment>(text).unwrap().check().unwrap_err();
        let red = "{ color = [1, 0, 0] }";
        let e = err("pattern = \"onion\"\npigment_map = []");
        assert_eq!(e.0, "pigment_map");
        assert!(e.1.contains("at least one"), "{}", e.1);
        let e = err(&format!("pattern = \"onion\"\npigment_map = [[0.6, {red}], [0.2, {red}]]"));
        assert_eq!(e.0, "pigment_map");
        assert!(e.1.contains("entry 1") && e.1.contains("ascending"), "{}", e.1);
        assert_eq!(err(&format!("pattern = \"onion\"\npigment_map = [[nan, {red}]]")).0, "pigment_map");
        let e = err(&format!("pattern = \"checker\"\ncolors = [[1, 1, 1], [0, 0, 0]]\npigment_map = [[0, {red}]]"));
        assert_eq!(e.0, "pigment_map");
        assert!(e.1.contains("takes `colors`"), "{}", e.1);
        let e = err(&format!("pattern = \"onion\"\n{BW}\npigment_map = [[0, {red}]]"));
        assert!(e.0 == "pigment_map" && e.1.contains("not both"), "{e:?}");
        assert_eq!(err(&format!("image_map = {{ file = \"a.png\" }}\npigment_map = [[0, {red}]]")).0, "pigment_map");
        // Entries' problems carry their path.
        let e = err(&format!("pattern = \"onion\"\npigment_map = [[0, {red}], [1, {{ pattern = \"onion\" }}]]"));
        assert_eq!(e.0, "pigment_map[1].color_map");
        let e = err("pattern = \"onion\"\npigment_map = [[0, { color = [1, 0, 0], scale = 2 }]]");
        assert!(e.0 == "pigment_map[0].scale" && e.1.contains("plain `color`"), "{e:?}");
        assert_eq!(err("pattern = \"onion\"\npigment_map = [[0, { color = [1, 0, nan] }]]").0, "pigment_map[0].color");
        assert_eq!(err("pattern = \"onion\"\npigment_map = [[0, { transmit = 0.5 }]]").0, "pigment_map[0].color");
        assert_eq!(err("pattern = \"onion\"\npigment_map = [[0, { }]]").0, "pigment_map[0].pattern");
        // A plain colour is an entry's, not a material's pigment.
        assert_eq!(err("color = [1, 0, 0]").0, "color");
        // Nesting is bounded: 16 maps deep pass, 17 do not.
        let nested = |depth: usize| {
            let mut text = red.to_string();
            for _ in 0..depth {
                text = format!("{{ pattern = \"onion\", pigment_map = [[0, {text}]] }}");
            }
            format!("pattern = \"onion\"\npigment_map = [[0, {text}]]")
        };
        assert!(toml::from_str::<Pigment>(&nested(MAX_PIGMENT_MAP_DEPTH - 1)).unwrap().check().is_ok());
        let e = err(&nested(MAX_PIGMENT_MAP_DEPTH));
        assert_eq!(e.0, format!("{}pigment_map", "pigment_map[0].".repeat(MAX_PIGMENT_MAP_DEPTH)));
        assert!(e.1.contains("at most 16"), "{}", e.1);
        // So is the total: 200 entries of 5 each are 1200 pigments, past 1024.
        let five = format!("{{ pattern = \"onion\", pigment_map = [{}] }}", vec![format!("[0, {red}]"); 5].join(", "));
        let wide =
            |n: usize| format!("pattern = \"onion\"\npigment_map = [{}]", vec![format!("[0, {five}]"); n].join(", "));
        assert!(toml::from_str::<Pigment>(&wide(170)).unwrap().check().is_ok());
        let e = err(&wide(200));
        assert!(e.0 == "pigment_map" && e.1.contains("1024"), "{e:?}");
    }

    #[test]
    fn discrete_patterns_take_pigments_as_their_list() {
        let f = PigmentField::new(&pigment(&format!(
            "pattern = \"checker\"\npigments = [{{ color = [1, 0, 0] }}, \
             {{ pattern = \"gradient\", vector = [1, 0, 0], scale = 2, {BW} }}]"
        )));
        assert_eq!(f.at(prism(0.5, 0.5, 0.5)).rgb, DVec3::X);
        // An odd cell: the gradient entry, scaled by 2, at x = 1.5.
        assert!((f.at(prism(1.5, 0.5, 0.5)).rgb - DVec3::splat(0.75)).abs().max_element() < 1e-12);
        let err = |text: &str| toml::from_str::<Pigment>(text).unwrap().check().unwrap_err();
        let red = "{ color = [1, 0, 0] }";
        let e = err(&format!("pattern = \"checker\"\npigments = [{red}]"));
        assert!(e.0 == "pigments" && e.1.contains("takes 2 pigments"), "{e:?}");
        let e = err(&format!("pattern = \"checker\"\ncolors = [[1, 1, 1], [0, 0, 0]]\npigments = [{red}, {red}]"));
        assert!(e.0 == "pigments" && e.1.contains("not both"), "{e:?}");
        assert_eq!(err(&format!("pattern = \"onion\"\npigments = [{red}]")).0, "pigments");
        assert_eq!(
            err(&format!("pattern = \"hexagon\"\npigments = [{red}, {red}, {{ pattern = \"onion\" }}]")).0,
            "pigments[2].color_map"
        );
    }

    #[test]
    fn pigment_map_round_trips_through_toml() {
        let p = pigment(&format!(
            "pattern = \"bozo\"\nturbulence = 0.4\npigment_map = [[0.2, {{ pattern = \"wrinkles\", scale = 0.3, {BW} }}], \
             [0.7, {{ color = [0.2, 0.9, 0.3], filter = 0.5, transmit = 0.2 }}]]"
        ));
        let back: Pigment = toml::from_str(&toml::to_string(&p).unwrap()).unwrap();
        assert_eq!(back, p);
    }

    #[test]
    fn round_trips_through_toml() {
        let p = pigment(
            "pattern = \"spiral2\"\narms = 3\nfrequency = 2\nphase = 0.25\nwave = \"sine\"\nscale = [1, 2, 3]\n\
             rotate = [0, 30, 0]\ncolor_map = [[0, [1, 0, 0]], [1, { color = [0, 0, 1], transmit = 0.5 }]]",
        );
        let back: Pigment = toml::from_str(&toml::to_string(&p).unwrap()).unwrap();
        assert_eq!(back, p);
    }
}
