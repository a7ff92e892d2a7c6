//! POV-Ray 3.7 normal perturbation: `normal { bumps 0.5 scale 0.2 }` and its kin, which tilt
//! the shading normal over the surface without moving it.
//!
//! [`Normal`] is the scene file's form (`normal = { pattern = "bumps", bump_size = 0.5, ... }`,
//! shaped like `pigment` and sharing its transform and turbulence keys); [`NormalField`] is
//! what shading evaluates. As in POV-Ray's `Perturb_Normal` (`normal.cpp`), the normal facing
//! the ray goes into the pattern's frame (object space, the inverse pattern transform, then
//! POV-Ray's mirrored `(x, y, -z)` frame) and is normalised, the pattern adds its vector
//! there at the point (turbulence applied first), and the sum goes back and is normalised.
//!
//! Any continuous pigment pattern also serves as a normal (`normal { granite 0.5 }`): as in
//! `Perturb_Normal`'s last branch, the pattern is read at four points around the point, a
//! tetrahedron of radius `accuracy`, and each value pushes the normal along its vertex, so the
//! normal leans down the pattern's numerical gradient.
//!
//! A `slope_map` reshapes those values; a `normal_map` (or `average`) blends whole normals,
//! picked by a pigment pattern's value or a normal-only pattern's own (`Evaluate_TPat`); a
//! discrete pattern (`checker`, `hexagon`, `brick`) takes a list of whole normals, one per
//! value; a `bump_map` replaces the normal by the normal of an image's height field
//! (`bump_map` in `imageutil.cpp`), the image loaded and mapped as an `image_map`'s.
//! `no_bump_scale` skips the normalisations on the way into the pattern's frame and back.

use std::fmt;
use std::sync::OnceLock;

use glam::{DMat3, DVec3};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::crackle::nearest_facet_point;
use super::image_map::ImageMap;
use super::noise::{Octaves, dnoise, dnoise_pair, dturbulence, for_each_octave, noise};
use super::pattern::{
    MAX_METRIC, MAX_NESTED_PIGMENTS, MAX_PIGMENT_MAP_DEPTH, MAX_PIGMENT_MAP_ENTRIES, PatternKind, PatternScale,
    Pigment, PigmentField, TurbulenceAmount, Wave, check_map_values, check_transform, check_turbulence, check_weights,
    cycloidal, octaves_of, pattern_transform, quilt_vector, quilted, search_blend_map, shape_wave, single,
    warps_with_turbulence, wrinkles,
};

/// POV-Ray's default `bump_size` (`Create_Tnormal`).
pub const DEFAULT_BUMP_SIZE: f64 = 0.5;

/// POV-Ray's default `accuracy` (`Create_Tnormal`'s `Delta`): the radius of the points a
/// pigment pattern is read at.
pub const DEFAULT_ACCURACY: f64 = 0.02;

/// POV-Ray's default facet `size`.
pub const DEFAULT_FACET_SIZE: f64 = 0.1;

/// The smallest `accuracy`: closer points differ from the centre only by rounding.
pub const MIN_ACCURACY: f64 = 1.0e-6;

/// POV-Ray's `Pyramid_Vect`: the vertices of a regular tetrahedron about the origin.
const PYRAMID: [DVec3; 4] = [
    DVec3::new(0.942809041, -0.333333333, 0.0),
    DVec3::new(-0.471404521, -0.333333333, 0.816496581),
    DVec3::new(-0.471404521, -0.333333333, -0.816496581),
    DVec3::new(0.0, 1.0, 0.0),
];

/// POV-Ray's default number of wave sources for `ripples` and `waves` (`global_settings {
/// number_of_waves }`, which Prism does not expose).
const NUMBER_OF_WAVES: usize = 10;

/// A normal pattern's name, as POV-Ray spells it: one of its normal-only patterns or a
/// continuous pigment pattern read through its gradient.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NormalKind {
    /// The gradient of solid noise.
    Bumps,
    /// Bumps scaled by the cube of the noise: sparse dents.
    Dents,
    /// Concentric rings about ten fixed sources.
    Ripples,
    /// Ripples with a different frequency (and amplitude) per source.
    Waves,
    /// Ten octaves of absolute noise gradients.
    Wrinkles,
    /// The offset from each unit cube's centre, rounded by two control points.
    Quilted,
    /// Flat facets: the normal replaced by the direction of the nearest crackle cell point.
    Facets,
    /// The weighted mean of its `normal_map` entries' normals (weights in place of values).
    Average,
    /// An image read as a height field (`bump_map`, written in place of a `pattern`).
    BumpMap,
    /// A continuous pigment pattern (not `wrinkles` or `quilted`, whose normal forms
    /// above take their names), read through its numerical gradient.
    Pattern(PatternKind),
}

impl NormalKind {
    /// POV-Ray's normal-only patterns with their names.
    pub const NORMAL_ONLY: [(NormalKind, &'static str); 8] = [
        (NormalKind::Bumps, "bumps"),
        (NormalKind::Dents, "dents"),
        (NormalKind::Ripples, "ripples"),
        (NormalKind::Waves, "waves"),
        (NormalKind::Wrinkles, "wrinkles"),
        (NormalKind::Quilted, "quilted"),
        (NormalKind::Facets, "facets"),
        (NormalKind::Average, "average"),
    ];

    /// The scene file's (and POV-Ray's) name.
    pub fn name(self) -> &'static str {
        match self {
            NormalKind::Pattern(kind) => kind.name(),
            NormalKind::BumpMap => "bump_map",
            _ => Self::NORMAL_ONLY.iter().find(|(k, _)| *k == self).map_or("", |(_, n)| n),
        }
    }

    /// Every name a normal pattern takes: the normal-only ones, then the continuous
    /// pigment patterns.
    pub fn names() -> Vec<&'static str> {
        let mut names: Vec<&str> = Self::NORMAL_ONLY.iter().map(|(_, n)| *n).collect();
        for (_, name) in PatternKind::ALL {
            if !names.contains(&name) {
                names.push(name);
            }
        }
        names
    }

    fn has_waves(self) -> bool {
        matches!(self, NormalKind::Ripples | NormalKind::Waves)
    }

    /// The number of normals a discrete pattern (`checker`, `hexagon`, `brick`) lists.
    fn discrete_normals(self) -> Option<usize> {
        self.pigment_pattern().and_then(PatternKind::discrete_colors)
    }

    /// True for the normal-only patterns that also have a value a `normal_map` can blend by
    /// (POV-Ray's `Evaluate_TPat` knows them): not `facets`, `average` or a bump map.
    fn has_value(self) -> bool {
        matches!(
            self,
            NormalKind::Bumps
                | NormalKind::Dents
                | NormalKind::Ripples
                | NormalKind::Waves
                | NormalKind::Wrinkles
                | NormalKind::Quilted
        )
    }

    /// The pigment pattern read through its gradient, if this is one.
    pub fn pigment_pattern(self) -> Option<PatternKind> {
        match self {
            NormalKind::Pattern(kind) => Some(kind),
            _ => None,
        }
    }
}

impl fmt::Display for NormalKind {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl Serialize for NormalKind {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.name())
    }
}

impl<'de> Deserialize<'de> for NormalKind {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let name = String::deserialize(d)?;
        if let Some((kind, _)) = Self::NORMAL_ONLY.iter().find(|(_, n)| *n == name) {
            return Ok(*kind);
        }
        if let Some((kind, _)) = PatternKind::ALL.iter().find(|(_, n)| *n == name) {
            return Ok(NormalKind::Pattern(*kind));
        }
        let names = Self::names();
        let hint = crate::diagnostics::nearest_name(&name, names.iter().copied())
            .map_or(String::new(), |n| format!("did you mean `{n}`? "));
        Err(serde::de::Error::custom(format!(
            "unknown normal pattern `{name}`; {hint}known normal patterns: {}",
            names.join(", ")
        )))
    }
}

impl JsonSchema for NormalKind {
    fn schema_name() -> std::borrow::Cow<'static, str> {
        "NormalKind".into()
    }

    fn json_schema(_: &mut schemars::SchemaGenerator) -> schemars::Schema {
        let names = Self::names();
        schemars::json_schema!({
            "description": "A POV-Ray normal pattern, or a continuous pigment pattern read through its gradient.",
            "enum": names
        })
    }
}

/// One `slope_map` entry: `[value, [height, slope]]` (value usually in [0, 1]).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct SlopeMapEntry(pub f64, pub [f64; 2]);

/// One `normal_map` entry: `[value, normal]` (value usually in [0, 1]).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct NormalMapEntry(pub f64, pub Normal);

/// A normal pattern as a scene file writes it (`normal = { pattern = "bumps", ... }`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Normal {
    /// The pattern's POV-Ray name (none with a `bump_map`).
    #[serde(default = "bump_map_kind", skip_serializing_if = "is_bump_map")]
    pub pattern: NormalKind,
    /// POV-Ray's `bump_map` (in place of a `pattern`): a PNG read as a height field, its
    /// grey level (0.297 R + 0.589 G + 0.114 B of the samples as stored, no gamma) times
    /// `bump_size` the height; the image is mapped as an `image_map` is (`map_type`,
    /// `interpolate`, `once`, `repeat`, `offset`; no `filter_all` or `transmit_all`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bump_map: Option<ImageMap>,
    /// How far the pattern tilts the normal (POV-Ray's `bump_size`, the number after the
    /// pattern's keyword; default 0.5; negative inverts).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bump_size: Option<f64>,
    /// Pigment patterns: the radius of the four points the pattern is read at around the
    /// point (POV-Ray's default 0.02; at least 1e-6).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub accuracy: Option<f64>,
    /// `ripples`, `waves`: rings per unit of distance from a source (default 1); pigment
    /// patterns: as in a pigment.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub frequency: Option<f64>,
    /// `ripples`, `waves`: shifts the rings (default 0); pigment patterns: as in a pigment.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub phase: Option<f64>,
    /// Pigment patterns: the wave type, as in a pigment.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub wave: Option<Wave>,
    /// `gradient`: its direction, as in a pigment.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub vector: Option<[f64; 3]>,
    /// `spiral1` / `spiral2`: the number of arms.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub arms: Option<i32>,
    /// `brick`: the brick's size, as in a pigment.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub brick_size: Option<[f64; 3]>,
    /// `brick`: the mortar's width, as in a pigment.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mortar: Option<f64>,
    /// `crackle`: the distance weights, as in a pigment.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub form: Option<[f64; 3]>,
    /// `crackle`: the metric, as in a pigment.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub metric: Option<f64>,
    /// `crackle`: the offset, as in a pigment.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub offset: Option<f64>,
    /// `crackle`: one value per cell, as in a pigment.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub solid: Option<bool>,
    /// `facets`: the size of the facets (default 0.1; above 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub size: Option<f64>,
    /// `facets`: 0 (default) facets the normal's directions; otherwise facets by position,
    /// tilting each by this much of the noise gradient at its cell point.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub coords: Option<f64>,
    /// `quilted`: the first control point (default 1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub control0: Option<f64>,
    /// `quilted`: the second control point (default 1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub control1: Option<f64>,
    /// Pigment patterns: POV-Ray's `slope_map`, `[value, [height, slope]]` entries (values
    /// ascending) that reshape the pattern's value before its gradient is taken:
    /// between two entries a cubic through both heights with both slopes (POV-Ray's
    /// `Hermite_Cubic`), outside them the nearest entry's height.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub slope_map: Option<Vec<SlopeMapEntry>>,
    /// Pigment patterns: POV-Ray's `normal_map`, `[value, normal]` entries (values
    /// ascending), each a whole normal (another `normal_map` included); the pattern's value
    /// picks the two entries around it and blends their perturbed normals linearly, as a
    /// `pigment_map` blends pigments. The pattern's own `bump_size` and `accuracy` do not apply.
    /// `average`: `[weight, normal]` entries (weights not negative, their sum above 0), whose
    /// normals are averaged with those weights.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub normal_map: Option<Vec<NormalMapEntry>>,
    /// The discrete patterns (`checker`, `brick`: 2; `hexagon`: 3): POV-Ray's list of normals
    /// (`normal { checker normal { bumps }, normal { ripples } }`), one whole normal per
    /// value of the pattern, as many as it has values.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub normals: Option<Vec<Normal>>,
    /// POV-Ray's `no_bump_scale`: the normal enters the pattern's frame (the object's and the
    /// pattern's transforms) and leaves it without being normalised, so the relief keeps its
    /// height when the pattern is scaled (a pattern twice as large is half as steep); the
    /// entries of its `normal_map` or list inherit it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub no_bump_scale: Option<bool>,
    /// POV-Ray's classic `turbulence`: displaces the point before the pattern reads it.
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

fn bump_map_kind() -> NormalKind {
    NormalKind::BumpMap
}

fn is_bump_map(kind: &NormalKind) -> bool {
    *kind == NormalKind::BumpMap
}

/// The first problem of a map's number of entries (under `key`).
fn check_map_len(key: &'static str, len: usize) -> Result<(), (&'static str, String)> {
    if len == 0 {
        return Err((key, "needs at least one entry".into()));
    }
    if len > MAX_PIGMENT_MAP_ENTRIES {
        return Err((key, format!("has {len} entries; at most {MAX_PIGMENT_MAP_ENTRIES} (POV-Ray's limit)")));
    }
    Ok(())
}

impl Normal {
    /// The pattern transform (pattern space to object space, Prism's frame).
    pub fn object_from_pattern(&self) -> glam::DAffine3 {
        pattern_transform(self.scale, self.rotate, self.translate, self.matrix)
    }

    /// The pigment pattern's keys as a pigment (no colours), when the pattern is one.
    pub fn as_pigment(&self) -> Option<Pigment> {
        let pattern = self.pattern.pigment_pattern()?;
        Some(Pigment {
            pattern: Some(pattern),
            image_map: None,
            colors: Vec::new(),
            pigments: Vec::new(),
            color_map: Vec::new(),
            pigment_map: None,
            color: None,
            filter: None,
            transmit: None,
            vector: self.vector,
            arms: self.arms,
            brick_size: self.brick_size,
            mortar: self.mortar,
            form: self.form,
            metric: self.metric,
            offset: self.offset,
            solid: self.solid,
            control0: self.control0,
            control1: self.control1,
            frequency: self.frequency,
            phase: self.phase,
            wave: self.wave,
            turbulence: self.turbulence,
            octaves: self.octaves,
            omega: self.omega,
            lambda: self.lambda,
            scale: self.scale,
            rotate: self.rotate,
            translate: self.translate,
            matrix: self.matrix,
        })
    }

    /// The first out-of-range or misplaced parameter, as (key path under `normal`, e.g.
    /// `normal_map[1][1].bump_size`, message).
    pub fn check(&self) -> Result<(), (String, String)> {
        self.check_at(0)?;
        let total = self.nested_count();
        if total > MAX_NESTED_PIGMENTS {
            return Err((
                "normal_map".into(),
                format!("holds {total} normals in all (nested ones included); at most {MAX_NESTED_PIGMENTS}"),
            ));
        }
        Ok(())
    }

    /// Every bump map of the normal, its `normal_map` entries' included, with its key path
    /// under `normal` (`bump_map`, `normal_map[1][1].bump_map`: the TOML path of its table).
    pub fn bump_maps_mut(&mut self) -> Vec<(String, &mut ImageMap)> {
        fn collect<'a>(n: &'a mut Normal, prefix: String, out: &mut Vec<(String, &'a mut ImageMap)>) {
            if let Some(map) = n.bump_map.as_mut() {
                out.push((format!("{prefix}bump_map"), map));
            }
            for (i, NormalMapEntry(_, entry)) in n.normal_map.iter_mut().flatten().enumerate() {
                collect(entry, format!("{prefix}normal_map[{i}][1]."), out);
            }
            for (i, entry) in n.normals.iter_mut().flatten().enumerate() {
                collect(entry, format!("{prefix}normals[{i}]."), out);
            }
        }
        let mut out = Vec::new();
        collect(self, String::new(), &mut out);
        out
    }

    /// Every bump map of the normal, its `normal_map` entries' included.
    pub fn bump_maps(&self) -> Vec<&ImageMap> {
        let mut out: Vec<&ImageMap> = self.bump_map.iter().collect();
        for (_, entry) in self.nested() {
            out.extend(entry.bump_maps());
        }
        out
    }

    /// The normals this one holds directly, `normal_map` entries then the list of a discrete
    /// pattern, each with its key path under this normal (`normal_map[1][1]`, `normals[0]`).
    pub fn nested(&self) -> Vec<(String, &Normal)> {
        let map = self.normal_map().iter().enumerate().map(|(i, e)| (format!("normal_map[{i}][1]"), &e.1));
        let list = self.normals.iter().flatten().enumerate().map(|(i, n)| (format!("normals[{i}]"), n));
        map.chain(list).collect()
    }

    /// The `normal_map` entries (none without a map).
    pub fn normal_map(&self) -> &[NormalMapEntry] {
        self.normal_map.as_deref().unwrap_or_default()
    }

    /// How many normals this one holds, nested ones included (after [`Self::check_at`] has
    /// bounded the depth). Stops counting past [`MAX_NESTED_PIGMENTS`].
    fn nested_count(&self) -> usize {
        let mut total = 0;
        for (_, entry) in self.nested() {
            total += 1 + entry.nested_count();
            if total > MAX_NESTED_PIGMENTS {
                break;
            }
        }
        total
    }

    /// [`Self::check`] of a normal `depth` `normal_map`s deep.
    fn check_at(&self, depth: usize) -> Result<(), (String, String)> {
        let owned = |(key, message): (&str, String)| (key.to_string(), message);
        self.check_own().map_err(owned)?;
        self.check_maps().map_err(owned)?;
        let nested = self.nested();
        if nested.is_empty() {
            return Ok(());
        }
        if depth >= MAX_PIGMENT_MAP_DEPTH {
            let key = if self.normals.is_some() { "normals" } else { "normal_map" };
            return Err((
                key.into(),
                format!("normals in normal maps and lists nest at most {MAX_PIGMENT_MAP_DEPTH} deep"),
            ));
        }
        for (path, entry) in nested {
            entry.check_at(depth + 1).map_err(|(k, message)| (format!("{path}.{k}"), message))?;
        }
        Ok(())
    }

    /// The first problem of the `slope_map` or `normal_map` (their entries' normals apart).
    fn check_maps(&self) -> Result<(), (&'static str, String)> {
        let kind = self.pattern;
        if self.normals.is_some() && kind.discrete_normals().is_none() {
            return Err((
                "normals",
                format!("belongs to the discrete patterns (checker, hexagon, brick), not `{kind}`"),
            ));
        }
        if kind == NormalKind::Average {
            if let Some(key) = [("slope_map", self.slope_map.is_some()), ("bump_size", self.bump_size.is_some())]
                .into_iter()
                .find_map(|(key, written)| written.then_some(key))
            {
                return Err((key, "has no effect on `average`: give it to the map's entries".into()));
            }
            let Some(map) = &self.normal_map else {
                return Err(("normal_map", "`average` needs a `normal_map` of `[weight, normal]` entries".into()));
            };
            return check_weights("normal_map", map.iter().map(|e| e.0));
        }
        if let Some(count) = kind.discrete_normals() {
            for (key, written) in [("slope_map", self.slope_map.is_some()), ("normal_map", self.normal_map.is_some())] {
                if written {
                    return Err((
                        key,
                        format!("does not go with `{kind}` (POV-Ray refuses it): give it a list of `normals`"),
                    ));
                }
            }
            if let Some(list) = &self.normals {
                // POV-Ray 3.7 crashes on a shorter list (its `Post_Tnormal` follows the missing
                // entries' null pointers).
                if list.len() != count {
                    return Err((
                        "normals",
                        format!("`{kind}` takes {count} normals (one per value), got {}", list.len()),
                    ));
                }
                for (key, written) in [("bump_size", self.bump_size.is_some()), ("accuracy", self.accuracy.is_some())] {
                    if written {
                        return Err((
                            key,
                            "has no effect with a list of `normals`: give it to the normals (POV-Ray ignores it)"
                                .into(),
                        ));
                    }
                }
            }
        }
        if self.slope_map.is_some() && kind.pigment_pattern().is_none() {
            return Err((
                "slope_map",
                format!(
                    "belongs to pigment patterns read as normals (e.g. `bozo`, the noise of `bumps`), not `{kind}`"
                ),
            ));
        }
        if self.normal_map.is_some() && kind.pigment_pattern().is_none() && !kind.has_value() {
            return Err((
                "normal_map",
                format!("does not go with `{kind}` (POV-Ray refuses it): it has no value to pick entries by"),
            ));
        }
        if let Some(map) = &self.slope_map {
            if self.normal_map.is_some() {
                return Err(("slope_map", "give either a `slope_map` or a `normal_map`, not both".into()));
            }
            check_map_len("slope_map", map.len())?;
            check_map_values("slope_map", map.iter().map(|e| e.0))?;
            if let Some(i) = map.iter().position(|e| !(e.1[0].is_finite() && e.1[1].is_finite())) {
                return Err(("slope_map", format!("entry {i}: height and slope must be finite")));
            }
        }
        if let Some(map) = &self.normal_map {
            check_map_len("normal_map", map.len())?;
            check_map_values("normal_map", map.iter().map(|e| e.0))?;
            for (key, written) in [("bump_size", self.bump_size.is_some()), ("accuracy", self.accuracy.is_some())] {
                if written {
                    return Err((
                        key,
                        "has no effect with a `normal_map`: give it to the map's entries (POV-Ray ignores it)".into(),
                    ));
                }
            }
        }
        Ok(())
    }

    /// This normal's own first problem (its maps apart), as (key under `normal`, message).
    fn check_own(&self) -> Result<(), (&'static str, String)> {
        match (self.pattern, &self.bump_map) {
            (NormalKind::BumpMap, None) => return Err(("pattern", "needs a `pattern` or a `bump_map`".into())),
            (NormalKind::BumpMap, Some(map)) => {
                for (key, given) in [
                    ("bump_map.filter_all", map.filter_all.is_some()),
                    ("bump_map.transmit_all", map.transmit_all.is_some()),
                ] {
                    if given {
                        return Err((key, "belongs to an `image_map` pigment, not to a `bump_map`".into()));
                    }
                }
                map.check().map_err(|(key, message)| {
                    let key = match key {
                        "file" => "bump_map.file",
                        "repeat" => "bump_map.repeat",
                        "offset" => "bump_map.offset",
                        _ => "bump_map",
                    };
                    (key, message)
                })?;
            }
            (_, Some(_)) => return Err(("bump_map", "give either a `pattern` or a `bump_map`, not both".into())),
            (_, None) => {}
        }
        if let Some(b) = self.bump_size
            && !b.is_finite()
        {
            return Err(("bump_size", format!("must be a finite number, got {b}")));
        }
        let kind = self.pattern;
        if let Some(a) = self.accuracy {
            if kind.pigment_pattern().is_none() {
                return Err(("accuracy", format!("belongs to pigment patterns, not `{kind}`")));
            }
            if !(a.is_finite() && a >= MIN_ACCURACY) {
                return Err(("accuracy", format!("must be finite and at least {MIN_ACCURACY:e}, got {a}")));
            }
        }
        for (key, v) in [("size", self.size), ("coords", self.coords)] {
            if let Some(v) = v {
                if kind != NormalKind::Facets {
                    return Err((key, format!("belongs to facets, not `{kind}`")));
                }
                if !v.is_finite() {
                    return Err((key, format!("must be finite, got {v}")));
                }
            }
        }
        if let Some(size) = self.size
            && size <= 0.0
        {
            return Err(("size", format!("must be above 0, got {size}")));
        }
        if let Some(pigment) = self.as_pigment() {
            return pigment.check_keys();
        }
        if kind == NormalKind::Facets
            && let Some(m) = self.metric
            && !(m > 0.0 && m <= MAX_METRIC)
        {
            return Err(("metric", format!("must be above 0 and at most {MAX_METRIC}, got {m}")));
        }
        // With a `normal_map`, a normal-only pattern's value is shaped as a pigment's.
        let shaped = kind.has_value() && self.normal_map.is_some();
        for (key, v) in [("frequency", self.frequency), ("phase", self.phase)] {
            if let Some(v) = v {
                if !(kind.has_waves() || shaped) {
                    return Err((
                        key,
                        format!(
                            "belongs to ripples and waves (and pigment patterns, and normal patterns with a `normal_map`), not `{kind}`"
                        ),
                    ));
                }
                if !v.is_finite() {
                    return Err((key, format!("must be finite, got {v}")));
                }
            }
        }
        let pigment_keys = [
            ("wave", self.wave.is_some() && !shaped),
            ("brick_size", self.brick_size.is_some()),
            ("mortar", self.mortar.is_some()),
            ("vector", self.vector.is_some()),
            ("arms", self.arms.is_some()),
            ("form", self.form.is_some()),
            ("metric", self.metric.is_some() && kind != NormalKind::Facets),
            ("offset", self.offset.is_some()),
            ("solid", self.solid.is_some()),
        ];
        if let Some((key, _)) = pigment_keys.iter().find(|(_, given)| *given) {
            return Err((key, format!("belongs to pigment patterns, not `{kind}`")));
        }
        for (key, v) in [("control0", self.control0), ("control1", self.control1)] {
            if let Some(v) = v {
                if kind != NormalKind::Quilted {
                    return Err((key, format!("belongs to quilted, not `{kind}`")));
                }
                if !v.is_finite() {
                    return Err((key, format!("must be finite, got {v}")));
                }
            }
        }
        check_turbulence(self.turbulence, self.octaves, self.omega, self.lambda, false)?;
        check_transform(self.scale, self.rotate, self.translate, self.matrix)
    }
}

/// A normal pattern ready to evaluate.
#[derive(Clone, Debug, PartialEq)]
pub struct NormalField {
    /// The pattern as written.
    pub spec: Normal,
    /// Object point to pattern point (Prism's frame, before the mirror).
    pattern_from_object: glam::DAffine3,
    /// Object normal into the pattern's frame (the transpose of the pattern transform's
    /// linear part), and back (its inverse).
    normal_in: DMat3,
    normal_out: DMat3,
    turbulence: Option<DVec3>,
    octaves: Octaves,
    /// A pigment pattern's values (its own transform unused: this field's is applied).
    pigment: Option<PigmentField>,
    /// `quilted`'s control points, in single precision as POV-Ray holds them.
    quilt_controls: (f64, f64),
    /// The `slope_map` entries, values in single precision as POV-Ray holds them (empty
    /// without a map).
    slope_map: Vec<SlopeMapEntry>,
    /// The `normal_map` entries' values (single precision) and fields, or a discrete
    /// pattern's list of normals at values 0, 1, ...; empty without either.
    entries: Vec<(f64, NormalField)>,
    /// False under `no_bump_scale` (its own or a containing normal's): the normal is not
    /// normalised on its way into the pattern's frame and back.
    scales_bumps: bool,
}

/// POV-Ray's `(x, y, -z)` mirror between Prism's frame and its own.
const MIRROR: DVec3 = DVec3::new(1.0, 1.0, -1.0);

impl NormalField {
    /// The field of `spec` (which must have passed [`Normal::check`]).
    pub fn new(spec: &Normal) -> Self {
        Self::within(spec, false)
    }

    /// The field of `spec`, inside a normal with `no_bump_scale` when `no_bump_scale` is true
    /// (POV-Ray's `Post_Tnormal` hands the flag down to the map's entries).
    fn within(spec: &Normal, no_bump_scale: bool) -> Self {
        let no_bump_scale = no_bump_scale || spec.no_bump_scale == Some(true);
        let entries = match &spec.normals {
            Some(list) => {
                list.iter().enumerate().map(|(i, n)| (i as f64, NormalField::within(n, no_bump_scale))).collect()
            }
            None => spec
                .normal_map()
                .iter()
                .map(|e| (f64::from(e.0 as f32), NormalField::within(&e.1, no_bump_scale)))
                .collect(),
        };
        let object_from_pattern = spec.object_from_pattern();
        let normal_in = object_from_pattern.matrix3.transpose();
        let single = |v: Option<f64>| f64::from(v.unwrap_or(1.0) as f32);
        // Marble and wood turn their turbulence into their own value, not a warp.
        let warp = match spec.pattern {
            NormalKind::Pattern(kind) => warps_with_turbulence(kind, spec.turbulence.is_some()),
            _ => spec.turbulence.is_some(),
        };
        Self {
            spec: spec.clone(),
            pattern_from_object: object_from_pattern.inverse(),
            normal_in,
            normal_out: normal_in.inverse(),
            turbulence: spec.turbulence.filter(|_| warp).map(|t| t.vector()),
            octaves: octaves_of(spec.octaves, spec.omega, spec.lambda),
            pigment: spec.as_pigment().map(|p| PigmentField::new(&p)),
            quilt_controls: (single(spec.control0), single(spec.control1)),
            slope_map: spec.slope_map.iter().flatten().map(|e| SlopeMapEntry(f64::from(e.0 as f32), e.1)).collect(),
            entries,
            scales_bumps: !no_bump_scale,
        }
    }

    /// False under `no_bump_scale`: [`Self::perturb`] then wants the normal as POV-Ray's
    /// unit world normal taken into object space by the transpose of the object's transform.
    pub fn scales_bumps(&self) -> bool {
        self.scales_bumps
    }

    /// The perturbed normal at object point `p` with object-space normal `n` (facing the ray;
    /// any length, unless [`Self::scales_bumps`] is false: then its length matters). Unit,
    /// except under `no_bump_scale` without a map (the caller normalises it, as POV-Ray's
    /// trace does).
    pub fn perturb(&self, p: DVec3, n: DVec3) -> DVec3 {
        let mut q = self.pattern_from_object.transform_point3(p) * MIRROR;
        if let Some(amount) = self.turbulence {
            q += dturbulence(q, &self.octaves) * amount;
        }
        // POV-Ray's `Warp_Normal` and `UnWarp_Normal`: normalised on the way in and out unless
        // the bumps keep their scale.
        let unit = |v: DVec3| if self.scales_bumps { v.normalize() } else { v };
        let n_pattern = unit((self.normal_in * n) * MIRROR);
        let blended = self.spec.pattern != NormalKind::Average && !self.entries.is_empty();
        let tilted = if self.spec.pattern == NormalKind::Average {
            self.average(q, n_pattern)
        } else if blended {
            self.blend_entries(q, n_pattern)
        } else if self.spec.pattern == NormalKind::Facets {
            self.facet(q, n_pattern)
        } else if self.spec.pattern == NormalKind::BumpMap {
            self.bump(q, n_pattern)
        } else {
            n_pattern + self.offset(q)
        };
        let out = unit(self.normal_out * (tilted * MIRROR));
        // A normal map's blend is normalised whatever the flag.
        if blended { out.normalize() } else { out }
    }

    /// POV-Ray's `normal_map` (`Perturb_Normal`'s blend map branch): the pattern's value at
    /// the (warped) pattern point `q` picks the entries around it; each perturbs the unit
    /// normal `n` (pattern frame) at `q` through its own transform, and the two results are
    /// blended linearly (one where the value sits on an entry or outside the map).
    fn blend_entries(&self, q: DVec3, n: DVec3) -> DVec3 {
        let value = self.value(q);
        let entries = &self.entries;
        let (prev, cur, weight) = search_blend_map(entries.len(), |i| entries[i].0, value);
        // Back to Prism's frame: each entry's `perturb` mirrors its own point and normal.
        let (p, m) = (q * MIRROR, n * MIRROR);
        let current = entries[cur].1.perturb(p, m) * MIRROR;
        if prev == cur {
            return current;
        }
        let below = entries[prev].1.perturb(p, m) * MIRROR;
        (1.0 - weight) * below + weight * current
    }

    /// The pattern's value at the (warped) pattern point `q` that picks `normal_map` entries
    /// (POV-Ray's `Evaluate_TPat`): a pigment pattern's value (a discrete pattern's index);
    /// a normal-only pattern's own value function, then frequency, phase and wave.
    fn value(&self, q: DVec3) -> f64 {
        if let Some(pigment) = &self.pigment {
            return pigment.value(q);
        }
        let spec = &self.spec;
        let frequency = single(spec.frequency.unwrap_or(if spec.pattern == NormalKind::Quilted { 0.0 } else { 1.0 }));
        let phase = single(spec.phase.unwrap_or(0.0));
        // `ripples_pattern` and `waves_pattern`: the rings' mean cycloid.
        let mean_cycloid = |waves: bool| {
            let terms = wave_rings(q, frequency, phase, waves).map(|(_, _, f, c)| if waves { c / f } else { c });
            terms.sum::<f64>() / NUMBER_OF_WAVES as f64
        };
        let raw = match spec.pattern {
            NormalKind::Bumps => noise(q),
            NormalKind::Dents => noise(q).powi(3),
            NormalKind::Ripples => 0.5 * (1.0 + mean_cycloid(false)),
            NormalKind::Waves => 0.2 * (2.5 + mean_cycloid(true)),
            NormalKind::Wrinkles => wrinkles(q),
            NormalKind::Quilted => quilted(q, self.quilt_controls),
            _ => 0.0,
        };
        shape_wave(raw, frequency, phase, spec.wave.unwrap_or(Wave::Ramp))
    }

    /// POV-Ray's `Do_Average_Normals`: every `normal_map` entry perturbs the unit normal `n`
    /// (pattern frame) at the (warped) pattern point `q`; the results are weighted by the
    /// entries' values and divided by the weights' sum (weights and sum in single precision).
    fn average(&self, q: DVec3, n: DVec3) -> DVec3 {
        let (p, m) = (q * MIRROR, n * MIRROR);
        let mut sum = DVec3::ZERO;
        let mut total = 0.0f32;
        for (weight, entry) in &self.entries {
            let weight = *weight as f32;
            sum += f64::from(weight) * (entry.perturb(p, m) * MIRROR);
            total += weight;
        }
        sum / f64::from(total)
    }

    /// POV-Ray's `bump_map` (`imageutil.cpp`): the heights (grey level times `bump_size`) at
    /// the point's texel and at the texels one left and one right of it a row down make a
    /// triangle, whose normal replaces the unit normal `n` (pattern frame) in a frame built
    /// about `n` and the y axis. Off the image (`once`) the normal is left as it is.
    fn bump(&self, q: DVec3, n: DVec3) -> DVec3 {
        let Some(map) = &self.spec.bump_map else { return n };
        let Some(image) = map.image.as_deref() else { return n };
        let Some((x, y)) = map.image_coords(image, q) else { return n };
        let (w, h) = (image.width as f64, image.height as f64);
        let amount = f64::from(self.spec.bump_size.unwrap_or(DEFAULT_BUMP_SIZE) as f32);
        let grey = |x: f64, y: f64| {
            let c = map.colour_at(image, x, y).rgb;
            // POV-Ray's single-precision greyscale.
            f64::from((0.297 * c.x + 0.589 * c.y + 0.114 * c.z) as f32)
        };
        // POV-Ray steps one texel and wraps once by hand.
        let wrap_once = |v: f64, size: f64| {
            if v < 0.0 {
                v + size
            } else if v >= size {
                v - size
            } else {
                v
            }
        };
        let (x2, y2) = (wrap_once(x - 1.0, w), wrap_once(y + 1.0, h));
        let x3 = wrap_once(x2 + 2.0, w);
        let points = [(x, y), (x2, y2), (x3, y2)];
        // `use_index` reads a palette image's indices (all three must have one), else colours.
        let indices = match map.use_index.then(|| points.map(|(x, y)| map.index_at(image, x, y))) {
            Some([Some(a), Some(b), Some(c)]) => Some([a, b, c]),
            _ => None,
        };
        let [h1, h2, h3] = indices.unwrap_or_else(|| points.map(|(x, y)| grey(x, y))).map(|v| amount * v);
        let p1 = DVec3::new(0.0, h1, 0.0);
        let p2 = DVec3::new(-1.0, h2, 1.0);
        let p3 = DVec3::new(1.0, h3, 1.0);
        let bump = (p3 - p2).cross(p1 - p2).normalize();
        let mut y_axis = n;
        let mut x_axis = n.cross(DVec3::Y);
        let mut length = x_axis.length();
        if length < 1.0e-10 {
            y_axis = if (n.y - 1.0).abs() < 1.0e-10 { DVec3::Y } else { DVec3::NEG_Y };
            x_axis = DVec3::X;
            length = 1.0;
        }
        x_axis /= length;
        let z_axis = x_axis.cross(y_axis).normalize();
        x_axis * bump.x + y_axis * bump.y - z_axis * bump.z
    }

    /// POV-Ray's `Do_Slope_Map`: a pattern value reshaped by the `slope_map` (unchanged
    /// without one).
    fn slope(&self, value: f64) -> f64 {
        let map = &self.slope_map;
        if map.is_empty() {
            return value;
        }
        let (prev, cur, t) = search_blend_map(map.len(), |i| map[i].0, value);
        if prev == cur {
            return map[cur].1[0];
        }
        hermite_cubic(t, map[prev].1, map[cur].1)
    }

    /// POV-Ray's `facets`: the normal (pattern frame, normalised first) replaced by the nearest cell point
    /// to it scaled by 1 / size, or with `coords` by the one nearest the point, whose noise
    /// gradient (less its part along the normal) tilts the normal.
    fn facet(&self, q: DVec3, n: DVec3) -> DVec3 {
        let spec = &self.spec;
        let size = spec.size.unwrap_or(DEFAULT_FACET_SIZE);
        let scale = if size < 1e-6 { 1e6 } else { 1.0 / size };
        let coords = spec.coords.unwrap_or(0.0);
        let metric = spec.metric.unwrap_or(2.0);
        // POV-Ray's `facets` normalises the normal first, so under `no_bump_scale` its length
        // picks no other facet.
        let n = n.normalize();
        if coords == 0.0 {
            return nearest_facet_point(n * scale, metric);
        }
        let pert = dnoise(nearest_facet_point(q * scale, metric));
        n + coords * (pert - n * pert.dot(n))
    }

    /// What the pattern adds to the unit normal at pattern point `q` (POV-Ray's frame).
    fn offset(&self, q: DVec3) -> DVec3 {
        let spec = &self.spec;
        // POV-Ray holds bump_size (and accuracy) in single precision.
        let amount = f64::from(spec.bump_size.unwrap_or(DEFAULT_BUMP_SIZE) as f32);
        match spec.pattern {
            NormalKind::Pattern(_) => {
                let Some(pigment) = &self.pigment else { return DVec3::ZERO };
                let delta = f64::from(spec.accuracy.unwrap_or(DEFAULT_ACCURACY) as f32);
                // POV-Ray's fudge factor -5, and 0.02 / accuracy to keep the slope's scale.
                let weight = amount * -5.0 * (0.02 / delta);
                PYRAMID.iter().map(|v| (self.slope(pigment.value(q + delta * *v)) * weight) * *v).sum()
            }
            NormalKind::Quilted => amount * quilt_vector(q, self.quilt_controls),
            NormalKind::Facets | NormalKind::Average | NormalKind::BumpMap => DVec3::ZERO,
            NormalKind::Bumps => amount * dnoise(q),
            NormalKind::Dents => noise(q).powi(3) * amount * dnoise(q),
            NormalKind::Ripples | NormalKind::Waves => {
                let frequency = single(spec.frequency.unwrap_or(1.0));
                let phase = single(spec.phase.unwrap_or(0.0));
                let waves = spec.pattern == NormalKind::Waves;
                let mut sum = DVec3::ZERO;
                for (v, length, f, cycloid) in wave_rings(q, frequency, phase, waves) {
                    let scalar = if waves { cycloid * amount / f } else { cycloid * amount };
                    sum += (scalar / (length * NUMBER_OF_WAVES as f64)) * v;
                }
                sum
            }
            NormalKind::Wrinkles => {
                // |dnoise(q 2^i)| 2^-i (powers of two: the same as dividing by 2^i).
                let mut sum = DVec3::ZERO;
                for_each_octave(q, &Octaves::halving(10), dnoise, dnoise_pair, |w, n| sum += (n * w).abs());
                amount * sum
            }
        }
    }
}

/// Each of POV-Ray's wave sources seen from pattern point `q`, as `ripples` and `waves` read
/// them: the offset from the source, its length (1 where it is 0, as POV-Ray takes it), the
/// source's frequency, and the cycloid of its ring, `length frequency + phase` (for `waves`
/// the frequency times the source's own).
fn wave_rings(q: DVec3, frequency: f64, phase: f64, waves: bool) -> impl Iterator<Item = (DVec3, f64, f64, f64)> {
    let (sources, frequencies) = wave_sources();
    sources.iter().zip(frequencies).map(move |(source, &f)| {
        let v = q - *source;
        let mut length = v.length();
        if length == 0.0 {
            length = 1.0;
        }
        let cycloid =
            if waves { cycloidal(length * frequency * f + phase) } else { cycloidal(length * frequency + phase) };
        (v, length, f, cycloid)
    })
}

/// POV-Ray's `Hermite_Cubic`: the cubic from `a` = (height, slope) at t = 0 to `b` at t = 1
/// (slopes per unit of t, not of the pattern value, as POV-Ray takes them).
fn hermite_cubic(t: f64, a: [f64; 2], b: [f64; 2]) -> f64 {
    let (tt, ttt) = (t * t, t * t * t);
    ttt * (a[1] + b[1] + 2.0 * (a[0] - b[0])) - tt * (2.0 * a[1] + b[1] + 3.0 * (a[0] - b[0])) + t * a[1] + a[0]
}

/// POV-Ray's wave sources and their frequencies (`Initialize_Waves`): source i is the unit
/// vector along `DNoise(i, 0, 0)`; the frequencies come from its 32-bit random sequence.
fn wave_sources() -> &'static ([DVec3; NUMBER_OF_WAVES], [f64; NUMBER_OF_WAVES]) {
    static SOURCES: OnceLock<([DVec3; NUMBER_OF_WAVES], [f64; NUMBER_OF_WAVES])> = OnceLock::new();
    SOURCES.get_or_init(|| {
        let mut sources = [DVec3::ZERO; NUMBER_OF_WAVES];
        let mut frequencies = [0.0; NUMBER_OF_WAVES];
        let mut next: i32 = -560_851_967;
        for i in 0..NUMBER_OF_WAVES {
            sources[i] = dnoise(DVec3::new(i as f64, 0.0, 0.0)).normalize();
            next = (i64::from(next) * 1_812_433_253 + 12_345) as i32;
            frequencies[i] = f64::from((next >> 16) & 0x7FFF) * 0.000030518509476 + 0.01;
        }
        (sources, frequencies)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn field(text: &str) -> NormalField {
        let n: Normal = toml::from_str(text).unwrap();
        n.check().unwrap();
        NormalField::new(&n)
    }

    const POINTS: [DVec3; 4] = [
        DVec3::new(0.31, -1.27, 2.45),
        DVec3::new(-3.5, 0.25, 0.125),
        DVec3::new(10.2, 4.4, -7.9),
        DVec3::new(0.0, 0.0, 0.0),
    ];

    #[test]
    fn bump_size_zero_leaves_the_normal_unchanged() {
        for kind in ["bumps", "dents", "ripples", "waves", "wrinkles"] {
            let f = field(&format!("pattern = \"{kind}\"\nbump_size = 0\nscale = [0.5, 2, 1]\nrotate = [10, 20, 30]"));
            for p in POINTS {
                let n = DVec3::new(0.3, 0.9, -0.2).normalize();
                assert!((f.perturb(p, n) - n).length() < 1e-12, "{kind} at {p}");
            }
        }
    }

    #[test]
    fn perturbed_normals_are_unit_and_tilted() {
        for kind in ["bumps", "dents", "ripples", "waves", "wrinkles"] {
            let f = field(&format!("pattern = \"{kind}\"\nbump_size = 0.8\nturbulence = 0.3\nscale = 0.4"));
            let mut moved = 0;
            for p in POINTS {
                let m = f.perturb(p, DVec3::new(0.0, 2.0, 0.0));
                assert!((m.length() - 1.0).abs() < 1e-12, "{kind} at {p}");
                moved += usize::from((m - DVec3::Y).length() > 1e-6);
            }
            assert!(moved >= 2, "{kind} barely moves the normal");
        }
    }

    #[test]
    fn wave_sources_follow_povray() {
        let (sources, frequencies) = wave_sources();
        // The first random number: (-560851967 * 1812433253 + 12345) mod 2^32 as i32.
        let first = (-560_851_967_i64 * 1_812_433_253 + 12_345) as i32;
        assert_eq!(frequencies[0], f64::from((first >> 16) & 0x7FFF) * 0.000030518509476 + 0.01);
        for (s, f) in sources.iter().zip(frequencies) {
            assert!((s.length() - 1.0).abs() < 1e-12);
            assert!((0.01..=1.01).contains(f));
        }
    }

    #[test]
    fn ripples_known_value() {
        // With the identity transform, the POV-Ray point of Prism's (x, y, z) is (x, y, -z).
        let f = field("pattern = \"ripples\"\nbump_size = 0.6\nfrequency = 2\nphase = 0.1");
        let p = DVec3::new(0.7, -0.2, 0.4);
        let q = p * MIRROR;
        let (sources, _) = wave_sources();
        let mut offset = DVec3::ZERO;
        for s in sources {
            let v = q - *s;
            let l = v.length();
            // bump_size and phase in single precision, as POV-Ray holds them.
            let phase = f64::from(0.1f32);
            offset += (f64::from(0.6f32) * ((l * 2.0 + phase) * std::f64::consts::TAU).sin() / (l * 10.0)) * v;
        }
        let expected = ((DVec3::Y + offset) * MIRROR).normalize();
        assert!((f.perturb(p, DVec3::Y) - expected).length() < 1e-12);
    }

    #[test]
    fn the_pattern_transform_carries_the_normal() {
        // Rotating the pattern 90 degrees about z: bumps seen by a normal along +x equal the
        // unrotated bumps seen along -y at the rotated point, rotated back.
        let plain = field("pattern = \"bumps\"");
        let rotated = field("pattern = \"bumps\"\nrotate = [0, 0, 90]");
        let p = DVec3::new(0.3, 1.1, -0.6);
        let r = glam::DMat3::from_rotation_z(std::f64::consts::FRAC_PI_2);
        let expected = r * plain.perturb(r.transpose() * p, r.transpose() * DVec3::X);
        assert!((rotated.perturb(p, DVec3::X) - expected).length() < 1e-9);
    }

    #[test]
    fn a_linear_gradient_tilts_the_normal_down_its_slope() {
        // Four samples on a regular tetrahedron of radius d: sum of v v^T is 4/3 I, so a
        // linear value g.q gives the offset -5 bump_size (0.02 / d) d (4/3) g, whatever d.
        for accuracy in [0.02, 0.05, 0.003] {
            for (vector, slope) in [([1.0, 0.0, 0.0], DVec3::X), ([0.0, 0.0, 2.0], DVec3::Z)] {
                let f = field(&format!(
                    "pattern = \"gradient\"\nvector = {vector:?}\nbump_size = 0.6\naccuracy = {accuracy}"
                ));
                let p = DVec3::new(0.25, 0.3, 0.2);
                let k = f64::from(0.6f32) * 5.0 * 0.02 * 4.0 / 3.0;
                let expected = (DVec3::Y - k * slope).normalize();
                let got = f.perturb(p, DVec3::Y);
                assert!((got - expected).length() < 1e-8, "{vector:?} at accuracy {accuracy}: {got} vs {expected}");
            }
        }
    }

    #[test]
    fn pigment_patterns_as_normals_read_the_pattern_at_four_points() {
        let f = field("pattern = \"crackle\"\nbump_size = 0.3\nscale = 0.5\nmetric = 1");
        let pigment = PigmentField::new(&f.spec.as_pigment().unwrap());
        let p = DVec3::new(0.37, -0.21, 0.64);
        // No transform but the scale: the POV-Ray point is (2 x, 2 y, -2 z).
        let q = p * 2.0 * MIRROR;
        let delta = f64::from(0.02f32);
        let weight = f64::from(0.3f32) * -5.0 * (0.02 / delta);
        let offset: DVec3 = PYRAMID.iter().map(|v| (pigment.value(q + delta * *v) * weight) * *v).sum();
        // The normal's transform: scale 0.5, so its inverse transpose scales normals by 2.
        let expected = ((DVec3::Y + offset) * MIRROR * 0.5).normalize();
        assert!((f.perturb(p, DVec3::Y) - expected).length() < 1e-12);
        assert!((f.perturb(p, DVec3::Y) - DVec3::Y).length() > 1e-4, "crackle tilts the normal");
    }

    #[test]
    fn quilted_normal_adds_the_quilting_vector() {
        let f = field("pattern = \"quilted\"\nbump_size = 0.8\ncontrol0 = 0.3\ncontrol1 = 0.9");
        let p = DVec3::new(0.2, 1.7, -0.35);
        let q = p * MIRROR;
        let c = (f64::from(0.3f32), f64::from(0.9f32));
        let expected = ((DVec3::Y + f64::from(0.8f32) * quilt_vector(q, c)) * MIRROR).normalize();
        assert!((f.perturb(p, DVec3::Y) - expected).length() < 1e-12);
    }

    #[test]
    fn facets_point_the_normal_at_the_nearest_cell_point() {
        let f = field("pattern = \"facets\"\nsize = 0.2");
        let n = DVec3::new(0.3, 0.9, -0.2).normalize();
        // The POV-Ray normal (x, y, -z), scaled by 1 / size, picks its nearest cell point.
        let c = nearest_facet_point(n * MIRROR * 5.0, 2.0);
        assert!((f.perturb(DVec3::new(1.0, 2.0, 3.0), n) - (c * MIRROR).normalize()).length() < 1e-12);
        // Nearby normals share the facet; the position does not matter.
        let m = (n + DVec3::new(0.001, -0.002, 0.0)).normalize();
        assert_eq!(f.perturb(DVec3::ZERO, m), f.perturb(DVec3::ONE, n));
        // coords: the nearest point to the position tilts the normal by its noise gradient.
        let f = field("pattern = \"facets\"\ncoords = 0.5\nmetric = 3");
        let p = DVec3::new(0.4, -1.3, 2.2);
        let pert = dnoise(nearest_facet_point(p * MIRROR * 10.0, 3.0));
        let nq = n * MIRROR;
        let expected = ((nq + 0.5 * (pert - nq * pert.dot(nq))) * MIRROR).normalize();
        assert!((f.perturb(p, n) - expected).length() < 1e-12);
    }

    #[test]
    fn facets_normalise_the_normal_under_no_bump_scale() {
        // Under no_bump_scale the normal arrives with the length the object's transform gave
        // it (1 / 1.358 for an object scaled by 1.358); POV-Ray's `facets` normalises it
        // before it picks the cell point, so the facet is the unit normal's.
        let f = field("pattern = \"facets\"\nsize = 0.2\nno_bump_scale = true");
        let n = DVec3::new(0.3, 0.9, -0.2).normalize();
        let c = nearest_facet_point(n * MIRROR * 5.0, 2.0);
        let got = f.perturb(DVec3::ZERO, n / 1.358).normalize();
        assert!((got - (c * MIRROR).normalize()).length() < 1e-12, "{got} against {c}");
    }

    #[test]
    fn marble_as_a_normal_keeps_its_turbulence_out_of_the_warp() {
        let f = field("pattern = \"marble\"\nturbulence = 0.5");
        assert!(f.turbulence.is_none());
        let f = field("pattern = \"granite\"\nturbulence = 0.5");
        assert!(f.turbulence.is_some());
    }

    #[test]
    fn slope_map_known_values() {
        // Heights 0 and 1 with slopes 0: the smoothstep 3t^2 - 2t^3 between the entries.
        let f = field("pattern = \"granite\"\nslope_map = [[0.2, [0, 0]], [0.6, [1, 0]]]");
        let t = (0.5 - f64::from(0.2f32)) / (f64::from(0.6f32) - f64::from(0.2f32));
        assert!((f.slope(0.5) - (3.0 * t * t - 2.0 * t * t * t)).abs() < 1e-12);
        // Outside the entries, and on one: that entry's height.
        assert_eq!(f.slope(0.1), 0.0);
        assert_eq!(f.slope(0.9), 1.0);
        assert_eq!(f.slope(f64::from(0.6f32)), 1.0);
        // POV-Ray's Hermite cubic: its slopes are per unit of t, and it meets both ends.
        let (a, b) = ([0.3, 1.5], [0.8, -0.5]);
        assert!((hermite_cubic(0.0, a, b) - 0.3).abs() < 1e-15);
        assert!((hermite_cubic(1.0, a, b) - 0.8).abs() < 1e-15);
        let h = 1e-6;
        assert!(((hermite_cubic(h, a, b) - hermite_cubic(0.0, a, b)) / h - 1.5).abs() < 1e-5);
        assert!(((hermite_cubic(1.0, a, b) - hermite_cubic(1.0 - h, a, b)) / h + 0.5).abs() < 1e-5);
        // The identity map [0, <0, 1>] .. [1, <1, 1>] leaves a gradient normal as it was.
        let plain = field("pattern = \"gradient\"\nvector = [1, 0, 0]\nbump_size = 0.6");
        let mapped = field(
            "pattern = \"gradient\"\nvector = [1, 0, 0]\nbump_size = 0.6\nslope_map = [[0, [0, 1]], [1, [1, 1]]]",
        );
        let p = DVec3::new(0.25, 0.3, 0.2);
        assert!((plain.perturb(p, DVec3::Y) - mapped.perturb(p, DVec3::Y)).length() < 1e-12);
    }

    #[test]
    fn a_one_entry_normal_map_is_its_entry() {
        let entry = field("pattern = \"bumps\"\nbump_size = 0.7\nscale = 0.3\nrotate = [10, 0, 20]");
        let map = field(
            "pattern = \"bozo\"\nnormal_map = [[0.4, { pattern = \"bumps\", bump_size = 0.7, scale = 0.3, rotate = [10, 0, 20] }]]",
        );
        for p in POINTS {
            let n = DVec3::new(0.3, 0.9, -0.2);
            assert!((map.perturb(p, n) - entry.perturb(p, n)).length() < 1e-12, "at {p}");
        }
    }

    #[test]
    fn a_discrete_pattern_picks_the_normal_of_its_value() {
        // checker: value 0 where floor(x) + floor(y) + floor(z) is even (POV-Ray's frame).
        let list = field(
            "pattern = \"checker\"\nnormals = [{ pattern = \"bumps\", bump_size = 0.7, scale = 0.3 }, { pattern = \"ripples\", frequency = 2 }]",
        );
        let bumps = field("pattern = \"bumps\"\nbump_size = 0.7\nscale = 0.3");
        let ripples = field("pattern = \"ripples\"\nfrequency = 2");
        let n = DVec3::new(0.3, 0.9, -0.2);
        let even = DVec3::new(0.5, 0.5, -0.5);
        let odd = DVec3::new(1.5, 0.5, -0.5);
        assert!((list.perturb(even, n) - bumps.perturb(even, n)).length() < 1e-12);
        assert!((list.perturb(odd, n) - ripples.perturb(odd, n)).length() < 1e-12);
        // hexagon's three values pick three different normals.
        let hexagon = field(
            "pattern = \"hexagon\"\nnormals = [{ pattern = \"bumps\", bump_size = 0 }, { pattern = \"dents\", bump_size = 3 }, { pattern = \"wrinkles\" }]",
        );
        let normals: Vec<DVec3> = [DVec3::ZERO, DVec3::new(1.5, 0.0, 0.0), DVec3::new(0.75, 0.0, -1.299)]
            .map(|p| hexagon.perturb(p, DVec3::Y))
            .into();
        assert!((normals[0] - DVec3::Y).length() < 1e-12, "{normals:?}");
        assert!(normals[1] != normals[0] && normals[2] != normals[0] && normals[1] != normals[2], "{normals:?}");
    }

    #[test]
    fn a_discrete_pattern_without_a_list_tilts_only_at_its_edges() {
        let checker = field("pattern = \"checker\"\nbump_size = 0.5");
        let n = DVec3::Y;
        // Inside a cell all four points read the same value: no tilt.
        assert!((checker.perturb(DVec3::new(0.5, 0.5, -0.5), n) - n).length() < 1e-12);
        // Within accuracy (0.02) of the x = 1 face the normal leans across it.
        let tilted = checker.perturb(DVec3::new(0.995, 0.5, -0.5), n);
        assert!(tilted.x.abs() > 0.05 && (tilted.length() - 1.0).abs() < 1e-12, "{tilted}");
    }

    #[test]
    fn normal_only_patterns_pick_normal_map_entries_by_their_own_value() {
        // bumps' value is bozo's noise (POV-Ray's `Evaluate_TPat`): the same map picks the same.
        let entries = "normal_map = [[0.3, { pattern = \"ripples\", bump_size = 0.9 }], [0.7, { pattern = \"dents\", bump_size = 2, scale = 0.2 }]]";
        let bumps = field(&format!("pattern = \"bumps\"\nscale = 0.4\n{entries}"));
        let bozo = field(&format!("pattern = \"bozo\"\nscale = 0.4\n{entries}"));
        let mut differs = false;
        for p in POINTS {
            let n = DVec3::new(0.3, 0.9, -0.2);
            assert!((bumps.perturb(p, n) - bozo.perturb(p, n)).length() < 1e-12, "at {p}");
            differs |= (bumps.perturb(p, n) - n.normalize()).length() > 1e-3;
        }
        assert!(differs);
        // ripples' value: its rings' mean cycloid mapped to [0, 1], then frequency and phase
        // applied again (`Evaluate_TPat` after `ripples_pattern`), recomputed here.
        let ripples = field(
            "pattern = \"ripples\"\nfrequency = 1.3\nphase = 0.2\nnormal_map = [[0, { pattern = \"gradient\", vector = [1, 0, 0], bump_size = 0 }], [1, { pattern = \"facets\" }]]",
        );
        let (sources, _) = wave_sources();
        for p in POINTS {
            let q = p * MIRROR;
            let f = f64::from(1.3f32);
            let phase = f64::from(0.2f32);
            let mean = sources.iter().map(|s| cycloidal((q - *s).length() * f + phase)).sum::<f64>() / 10.0;
            let expected = (0.5 * (1.0 + mean) * f + phase) % 1.00001;
            assert!((ripples.value(q) - expected).abs() < 1e-12, "at {p}");
        }
    }

    #[test]
    fn no_bump_scale_keeps_the_relief_height_when_the_pattern_grows() {
        // Scaled s times with s times the bump size (both exact in single precision), the relief is the same surface stretched:
        // without no_bump_scale the slope grows s times, with it the normal is unchanged.
        let plain = field("pattern = \"bumps\"\nbump_size = 0.5");
        let kept = field("pattern = \"bumps\"\nbump_size = 1.5\nscale = 3\nno_bump_scale = true");
        let scaled = field("pattern = \"bumps\"\nbump_size = 1.5\nscale = 3");
        for p in POINTS {
            let n = DVec3::new(0.3, 0.9, -0.2).normalize();
            let expected = plain.perturb(p, n);
            assert!((kept.perturb(3.0 * p, n).normalize() - expected).length() < 1e-12, "at {p}");
            if p != DVec3::ZERO {
                assert!((scaled.perturb(3.0 * p, n) - expected).length() > 1e-3, "at {p}");
            }
        }
        // A normal map's entries inherit the flag.
        let map = field(
            "pattern = \"bozo\"\nno_bump_scale = true\nnormal_map = [[0.5, { pattern = \"bumps\", bump_size = 1.5, scale = 3 }]]",
        );
        for p in POINTS {
            let n = DVec3::new(0.3, 0.9, -0.2).normalize();
            assert!((map.perturb(3.0 * p, n) - plain.perturb(p, n)).length() < 1e-12, "at {p}");
        }
    }

    #[test]
    fn a_normal_map_blends_its_entries_by_the_value() {
        // gradient x over [0, 1): the value is x's fraction; halfway between the entries the
        // two perturbed normals are averaged, then normalised.
        let f = field(
            "pattern = \"gradient\"\nvector = [1, 0, 0]\n\
             normal_map = [[0.2, { pattern = \"bumps\", bump_size = 0.8 }], [0.6, { pattern = \"dents\", bump_size = 2 }]]",
        );
        let bumps = field("pattern = \"bumps\"\nbump_size = 0.8");
        let dents = field("pattern = \"dents\"\nbump_size = 2");
        let p = DVec3::new(0.4, 0.35, -0.7);
        let w = (0.4 - f64::from(0.2f32)) / (f64::from(0.6f32) - f64::from(0.2f32));
        let expected = ((1.0 - w) * bumps.perturb(p, DVec3::Y) + w * dents.perturb(p, DVec3::Y)).normalize();
        assert!((f.perturb(p, DVec3::Y) - expected).length() < 1e-12);
        // Below the first entry only it applies; above the last only the last.
        let low = DVec3::new(0.1, 0.35, -0.7);
        assert!((f.perturb(low, DVec3::Y) - bumps.perturb(low, DVec3::Y)).length() < 1e-12);
        let high = DVec3::new(0.9, 0.35, -0.7);
        assert!((f.perturb(high, DVec3::Y) - dents.perturb(high, DVec3::Y)).length() < 1e-12);
    }

    #[test]
    fn average_weights_its_entries_normals() {
        let f = field(
            "pattern = \"average\"\nscale = 0.5\n\
             normal_map = [[1, { pattern = \"bumps\", bump_size = 0.8 }], [3, { pattern = \"ripples\", bump_size = 0.5 }]]",
        );
        let bumps = field("pattern = \"bumps\"\nbump_size = 0.8\nscale = 0.5");
        let ripples = field("pattern = \"ripples\"\nbump_size = 0.5\nscale = 0.5");
        for p in POINTS {
            let n = DVec3::new(0.2, 1.0, 0.4);
            let expected = ((bumps.perturb(p, n) + 3.0 * ripples.perturb(p, n)) / 4.0).normalize();
            assert!((f.perturb(p, n) - expected).length() < 1e-12, "at {p}");
        }
        let err = |text: &str| toml::from_str::<Normal>(text).unwrap().check().unwrap_err();
        assert_eq!(err("pattern = \"average\"").0, "normal_map");
        assert_eq!(
            err("pattern = \"average\"\nbump_size = 1\nnormal_map = [[1, { pattern = \"bumps\" }]]").0,
            "bump_size"
        );
        assert_eq!(err("pattern = \"average\"\nslope_map = [[0, [0, 1]]]").0, "slope_map");
        assert!(err("pattern = \"average\"\nnormal_map = [[-1, { pattern = \"bumps\" }]]").1.contains("not negative"));
        assert!(err("pattern = \"average\"\nnormal_map = [[0, { pattern = \"bumps\" }]]").1.contains("above 0"));
        assert_eq!(
            err("pattern = \"average\"\nnormal_map = [[1, { pattern = \"bumps\", scale = 0 }]]").0,
            "normal_map[0][1].scale"
        );
    }

    /// A bump map over `texels` (grey levels, rows from the top) of a `width`-wide image.
    fn bump_field(text: &str, width: usize, texels: &[f32]) -> NormalField {
        let mut n: Normal = toml::from_str(text).unwrap();
        n.check().unwrap();
        let image = super::super::image_map::MapImage {
            width,
            height: texels.len() / width,
            texels: texels.iter().map(|&g| [g, g, g, 1.0]).collect(),
            indexed: false,
            has_alpha: false,
            indices: Vec::new(),
        };
        n.bump_map.as_mut().unwrap().image = Some(std::sync::Arc::new(image));
        NormalField::new(&n)
    }

    #[test]
    fn a_flat_bump_map_leaves_the_normal_and_a_slope_tilts_it() {
        let flat = bump_field("bump_map = { file = \"h.png\" }\nbump_size = 3", 2, &[0.4; 4]);
        for p in POINTS {
            let n = DVec3::new(0.3, 0.9, -0.2).normalize();
            assert!((flat.perturb(p, n) - n).length() < 1e-12, "at {p}");
        }
        // Heights rising to the right (image x is POV-Ray's x): the triangle's normal, in the
        // frame about +y, leans to -x; with the normal along -z (POV-Ray's +z), built from
        // n x y = +x (POV-Ray) and z = x x n.
        let ramp = bump_field("bump_map = { file = \"h.png\" }\nbump_size = 2", 4, &[0.0, 0.25, 0.5, 0.75].repeat(4));
        let p = DVec3::new(0.3, 0.6, 0.0);
        let m = ramp.perturb(p, DVec3::Y);
        assert!((m.length() - 1.0).abs() < 1e-12);
        assert!(m.x < -0.1 && m.y > 0.5 && m.z.abs() < 1e-12, "{m}");
        // The triangle by hand: heights 2 * 0.25 at the texel, 2 * 0 and 2 * 0.5 at its
        // neighbours; its normal (-1, 2, 0) / sqrt(5), about y = n, x = n x Y = 0: the
        // degenerate frame takes x = +x, z = x x y = +z (POV-Ray), flipped.
        assert!((m - DVec3::new(-1.0, 2.0, 0.0).normalize()).length() < 1e-6, "{m}");
        // `once`: off the image the normal is left as it is.
        let once = bump_field(
            "bump_map = { file = \"h.png\", once = true }\nbump_size = 2",
            4,
            &[0.0, 0.25, 0.5, 0.75].repeat(4),
        );
        assert!((once.perturb(DVec3::new(1.5, 0.5, 0.0), DVec3::Y) - DVec3::Y).length() < 1e-12);
        assert!((once.perturb(p, DVec3::Y) - m).length() < 1e-12);
        // `use_index`: a palette image's indices are the heights (here the same ramp, 0 to 3,
        // times bump_size / 4); an image without a palette is read by its colours.
        let mut indexed = bump_field(
            "bump_map = { file = \"h.png\", use_index = true }\nbump_size = 0.5",
            4,
            &[0.0, 0.25, 0.5, 0.75].repeat(4),
        );
        // No palette: the colours, a slope of 0.125 per texel.
        let colours = indexed.perturb(p, DVec3::Y);
        assert!((colours - DVec3::new(-0.125, 1.0, 0.0).normalize()).length() < 1e-6, "{colours}");
        if let Some(map) = indexed.spec.bump_map.as_mut() {
            let mut image = (**map.image.as_ref().unwrap()).clone();
            image.indexed = true;
            image.indices = [0, 1, 2, 3].repeat(4);
            map.image = Some(std::sync::Arc::new(image));
        }
        assert!((indexed.perturb(p, DVec3::Y) - m).length() < 1e-6);
        let err = |text: &str| toml::from_str::<Normal>(text).unwrap().check().unwrap_err();
        assert_eq!(err("bump_size = 1").0, "pattern");
        assert_eq!(err("pattern = \"bumps\"\nbump_map = { file = \"h.png\" }").0, "bump_map");
        assert_eq!(err("bump_map = { file = \"h.png\", filter_all = 0.5 }").0, "bump_map.filter_all");
        assert_eq!(err("bump_map = { file = \"\" }").0, "bump_map.file");
        assert_eq!(err("bump_map = { file = \"h.png\" }\nfrequency = 2").0, "frequency");
        assert_eq!(err("bump_map = { file = \"h.png\" }\nslope_map = [[0, [0, 1]]]").0, "slope_map");
        let e =
            toml::from_str::<Normal>("bump_map = { file = \"h.png\", map_typ = \"planar\" }").unwrap_err().to_string();
        assert!(e.contains("unknown field `map_typ`"), "{e}");
    }

    #[test]
    fn bad_maps_name_their_key() {
        let err = |text: &str| toml::from_str::<Normal>(text).unwrap().check().unwrap_err();
        let key = |text: &str| err(text).0;
        assert_eq!(key("pattern = \"bumps\"\nslope_map = [[0, [0, 1]]]"), "slope_map");
        assert_eq!(key("pattern = \"facets\"\nnormal_map = [[0, { pattern = \"bumps\" }]]"), "normal_map");
        assert_eq!(key("pattern = \"bozo\"\nnormal_map = []"), "normal_map");
        assert!(err("pattern = \"bozo\"\nslope_map = []").1.contains("at least one entry"));
        assert_eq!(key("pattern = \"bozo\"\nslope_map = [[0.5, [0, 1]], [0.2, [1, 0]]]"), "slope_map");
        assert!(err("pattern = \"bozo\"\nslope_map = [[inf, [0, 1]]]").1.contains("not a finite number"));
        assert!(
            toml::from_str::<Normal>("pattern = \"bozo\"\nslope_map = [[-0.5, [0, 1]], [1.5, [1, 1]]]")
                .unwrap()
                .check()
                .is_ok()
        );
        assert_eq!(key("pattern = \"bozo\"\nslope_map = [[0.5, [nan, 1]]]"), "slope_map");
        assert_eq!(
            key("pattern = \"bozo\"\nslope_map = [[0, [0, 1]]]\nnormal_map = [[0, { pattern = \"bumps\" }]]"),
            "slope_map"
        );
        assert_eq!(key("pattern = \"bozo\"\nbump_size = 1\nnormal_map = [[0, { pattern = \"bumps\" }]]"), "bump_size");
        assert_eq!(
            key(
                "pattern = \"bozo\"\nnormal_map = [[0, { pattern = \"bumps\" }], [1, { pattern = \"dents\", scale = 0 }]]"
            ),
            "normal_map[1][1].scale"
        );
        let inner = (0..MAX_PIGMENT_MAP_DEPTH).fold("pattern = \"bumps\"".to_string(), |inner, _| {
            format!("pattern = \"bozo\", normal_map = [[0, {{ {inner} }}]]")
        });
        assert!(err(&format!("pattern = \"bozo\"\nnormal_map = [[0, {{ {inner} }}]]")).1.contains("nest at most"));
        let many: Vec<String> = (0..=MAX_PIGMENT_MAP_ENTRIES).map(|_| "[0, { pattern = \"bumps\" }]".into()).collect();
        assert!(err(&format!("pattern = \"bozo\"\nnormal_map = [{}]", many.join(", "))).1.contains("at most"));
        let e =
            toml::from_str::<Normal>("pattern = \"bozo\"\nnormal_map = [[0, { pattern = \"bumps\", bumpsize = 1 }]]")
                .unwrap_err()
                .to_string();
        assert!(e.contains("unknown field `bumpsize`"), "{e}");
    }

    #[test]
    fn bad_normals_name_their_key() {
        let err = |text: &str| toml::from_str::<Normal>(text).unwrap().check().unwrap_err().0;
        assert_eq!(err("pattern = \"bumps\"\nbump_size = nan"), "bump_size");
        assert_eq!(err("pattern = \"bumps\"\nbump_size = inf"), "bump_size");
        assert_eq!(err("pattern = \"bumps\"\nfrequency = 2"), "frequency");
        assert_eq!(err("pattern = \"ripples\"\nphase = inf"), "phase");
        assert_eq!(err("pattern = \"dents\"\noctaves = 3"), "octaves");
        assert_eq!(err("pattern = \"dents\"\nscale = 0"), "scale");
        assert_eq!(err("pattern = \"bumps\"\naccuracy = 0.01"), "accuracy");
        assert_eq!(err("pattern = \"granite\"\naccuracy = 0"), "accuracy");
        assert_eq!(err("pattern = \"granite\"\naccuracy = -0.1"), "accuracy");
        assert_eq!(err("pattern = \"crackle\"\nmetric = 0"), "metric");
        assert_eq!(err("pattern = \"crackle\"\noffset = -1"), "offset");
        assert_eq!(err("pattern = \"granite\"\nform = [1, 0, 0]"), "form");
        assert_eq!(err("pattern = \"bumps\"\nsolid = true"), "solid");
        assert_eq!(err("pattern = \"gradient\""), "vector");
        assert_eq!(err("pattern = \"ripples\"\ncontrol0 = 1"), "control0");
        assert_eq!(err("pattern = \"bumps\"\nsize = 0.1"), "size");
        assert_eq!(err("pattern = \"granite\"\ncoords = 1"), "coords");
        assert_eq!(err("pattern = \"facets\"\nsize = 0"), "size");
        assert_eq!(err("pattern = \"facets\"\nmetric = -1"), "metric");
        assert!(toml::from_str::<Normal>("pattern = \"facets\"\nmetric = 1\ncoords = 0.3").unwrap().check().is_ok());
        assert!(
            toml::from_str::<Normal>("pattern = \"granite\"\nfrequency = 2\nwave = \"sine\"").unwrap().check().is_ok()
        );
        assert!(toml::from_str::<Normal>("pattern = \"checker\"").unwrap().check().is_ok());
        let one = "normals = [{ pattern = \"bumps\" }]";
        let two = "normals = [{ pattern = \"bumps\" }, { pattern = \"dents\" }]";
        assert_eq!(err(&format!("pattern = \"checker\"\n{one}")), "normals");
        assert_eq!(err(&format!("pattern = \"hexagon\"\n{two}")), "normals");
        assert_eq!(err(&format!("pattern = \"granite\"\n{two}")), "normals");
        assert_eq!(err(&format!("pattern = \"bumps\"\n{two}")), "normals");
        assert_eq!(
            err(&format!("pattern = \"average\"\nnormal_map = [[1, {{ pattern = \"bumps\" }}]]\n{two}")),
            "normals"
        );
        assert_eq!(err(&format!("pattern = \"checker\"\nbump_size = 1\n{two}")), "bump_size");
        assert_eq!(err("pattern = \"checker\"\nnormal_map = [[0, { pattern = \"bumps\" }]]"), "normal_map");
        assert_eq!(err("pattern = \"brick\"\nslope_map = [[0, [0, 1]]]"), "slope_map");
        assert_eq!(err("pattern = \"facets\"\nnormal_map = [[0, { pattern = \"bumps\" }]]"), "normal_map");
        assert_eq!(err("pattern = \"bumps\"\nslope_map = [[0, [0, 1]]]"), "slope_map");
        assert_eq!(err("pattern = \"bumps\"\nwave = \"sine\""), "wave");
        assert_eq!(err("pattern = \"checker\"\nmortar = 0.1"), "mortar");
        assert_eq!(err("pattern = \"bumps\"\nbrick_size = [1, 1, 1]"), "brick_size");
        assert_eq!(
            err("pattern = \"checker\"\nnormals = [{ pattern = \"bumps\", scale = 0 }, { pattern = \"dents\" }]"),
            "normals[0].scale"
        );
        let map = "normal_map = [[0, { pattern = \"bumps\" }]]";
        let shaped = format!("pattern = \"wrinkles\"\nfrequency = 2\nphase = 0.1\nwave = \"cubic\"\n{map}");
        assert!(toml::from_str::<Normal>(&shaped).unwrap().check().is_ok());
        let e = toml::from_str::<Normal>("pattern = \"crakle\"").unwrap_err().to_string();
        assert!(e.contains("did you mean `crackle`?"), "{e}");
        let e = toml::from_str::<Normal>("pattern = \"bumsp\"").unwrap_err().to_string();
        assert!(e.contains("did you mean `bumps`?"), "{e}");
        let e = toml::from_str::<Normal>("pattern = \"bumps\"\nbumpsize = 2").unwrap_err().to_string();
        assert!(e.contains("unknown field `bumpsize`"), "{e}");
    }
}
