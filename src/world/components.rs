//! The ECS components a scene's entities carry, and the scene-wide settings.
//!
//! Every component is also the scene-file form of the thing it describes (serde both ways),
//! so `save` is the exact inverse of `load`.

use std::sync::Arc;

use glam::{DAffine3, DMat3, DMat4, DVec3, EulerRot};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::color::Rgb;
use crate::diagnostics::Location;
use crate::gamma::AssumedGamma;

/// A user-visible name (objects can be parents by name).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Name(pub String);

/// Where an entity was defined, for diagnostics found after loading.
#[derive(Clone, Debug, PartialEq)]
pub struct Origin(pub Location);

/// Where each key of an entity's own table was written, so that a diagnostic found after
/// loading points at the key's line rather than at the table's header.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct KeyLocations(pub std::collections::HashMap<String, Location>);

impl KeyLocations {
    /// The location of `key` (a path such as `point_at` or `texture.scale`, located by its
    /// first part), or `origin`'s child `key` when the table did not write it.
    pub fn locate(&self, origin: &Location, key: &str) -> Location {
        let (top, rest) = key.split_once('.').map_or((key, None), |(top, rest)| (top, Some(rest)));
        match (self.0.get(top), rest) {
            (Some(at), None) => at.clone(),
            (Some(at), Some(rest)) => at.child(rest),
            (None, _) => origin.child(key),
        }
    }
}

/// The parent whose world transform applies before this entity's own.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Parent(pub hecs::Entity);

/// A local transform: scale, then rotate about x, y, z (degrees, right-hand rule), then
/// translate; or a 4x4 matrix (rows) instead of all three.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Transform {
    /// Translation.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub translate: Option<[f64; 3]>,
    /// Rotation in degrees about x, then y, then z.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rotate: Option<[f64; 3]>,
    /// Uniform (a number) or per-axis (`[x, y, z]`) scale.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scale: Option<Scale>,
    /// A 4x4 affine matrix given as four rows (the last row must be [0, 0, 0, 1]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub matrix: Option<[[f64; 4]; 4]>,
}

/// A uniform or per-axis scale.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(untagged)]
pub enum Scale {
    /// The same factor on every axis.
    Uniform(f64),
    /// One factor per axis.
    PerAxis([f64; 3]),
}

impl Transform {
    /// True when nothing is set.
    pub fn is_identity(&self) -> bool {
        *self == Transform::default()
    }

    /// The affine map from this entity's space to its parent's space.
    pub fn parent_from_local(&self) -> DAffine3 {
        if let Some(rows) = self.matrix {
            return DAffine3::from_mat4(DMat4::from_cols_array_2d(&rows).transpose());
        }
        let scale = match self.scale {
            None => DVec3::ONE,
            Some(Scale::Uniform(s)) => DVec3::splat(s),
            Some(Scale::PerAxis(s)) => DVec3::from_array(s),
        };
        let r = DVec3::from_array(self.rotate.unwrap_or_default()) * (std::f64::consts::PI / 180.0);
        // x first, then y, then z: R = Rz * Ry * Rx.
        let rotation = DMat3::from_euler(EulerRot::ZYX, r.z, r.y, r.x);
        let translation = DVec3::from_array(self.translate.unwrap_or_default());
        DAffine3 { matrix3: rotation * DMat3::from_diagonal(scale), translation }
    }
}

/// The resolved transform from object space to world space (set by `resolve_transforms`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WorldTransform(pub DAffine3);

/// A shape: its type name, its parameters as written, and the built geometry.
#[derive(Clone, Debug)]
pub struct ShapeComponent {
    /// The registered type name (`shape = "..."`).
    pub kind: String,
    /// The parameters as written in the scene (for saving).
    pub params: toml::Table,
    /// The geometry in object space.
    pub geometry: Arc<dyn prism_api::Shape>,
    /// The keys of `params` that name files the shape read (a font), held as absolute paths
    /// and saved relative to the written scene where possible.
    pub files: Vec<String>,
}

/// The material of a shape, the name it was defined under and its authored form (for
/// saving). Objects naming one `[materials.NAME]`, and parts sharing one file material, share
/// one `Arc`: the render scene gives each `Arc` one id.
#[derive(Clone, Debug, PartialEq)]
pub struct MaterialComponent {
    /// `Some(name)` when the object referenced `[materials.name]`.
    pub name: Option<String>,
    /// The material as the scene wrote it; `None` for a mesh file's own materials.
    pub spec: Option<Arc<crate::material::MaterialSpec>>,
    /// The material itself.
    pub material: Arc<crate::material::Material>,
}

impl MaterialComponent {
    /// A component for a scene material (named or inline).
    pub fn authored(name: Option<String>, spec: Arc<crate::material::MaterialSpec>) -> Self {
        let material = Arc::new(spec.to_material());
        Self { name, spec: Some(spec), material }
    }
}

/// The materials of a CSG group's members.
#[derive(Clone, Debug, PartialEq)]
pub struct CsgMaterials {
    /// The material of each leaf (plain shape), depth first: the leaf's own, or the one it
    /// inherits from the nearest enclosing member or group that names one (as in POV-Ray).
    /// Inherited entries share the group's `Arc`, so they share its material id.
    pub leaves: Vec<MaterialComponent>,
    /// Every `[materials.NAME]` a member names (for saving).
    pub named: Vec<MaterialComponent>,
}

/// Per-object render flags.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct ObjectFlags {
    /// The object casts no shadows (POV-Ray `no_shadow`).
    pub no_shadow: bool,
}

/// The kind of a light.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum LightKind {
    /// An invisible point that shines in all directions.
    Point,
    /// A point light restricted to a cone around `point_at`.
    Spot,
    /// Parallel rays from the direction of `position` toward `point_at` (a sun).
    Parallel,
    /// A rectangular (or circular) grid of point lights: soft shadows.
    Area,
}

/// Every key of a `[[light]]` table besides `kind`, with the kinds that accept it: the one
/// list that loading, saving, the schema and the documentation's table follow.
pub const LIGHT_KEYS: [(&str, &[LightKind]); 20] = {
    use LightKind::{Area, Parallel, Point, Spot};
    const ALL: &[LightKind] = &[Point, Spot, Parallel, Area];
    const CONE: &[LightKind] = &[Spot, Area];
    [
        ("position", ALL),
        ("color", ALL),
        ("intensity", ALL),
        ("fade_distance", ALL),
        ("fade_power", ALL),
        ("shadowless", ALL),
        ("axis1", &[Area]),
        ("axis2", &[Area]),
        ("size1", &[Area]),
        ("size2", &[Area]),
        ("adaptive", &[Area]),
        ("jitter", &[Area]),
        ("circular", &[Area]),
        ("orient", &[Area]),
        ("area_illumination", &[Area]),
        ("point_at", &[Spot, Parallel, Area]),
        ("radius", CONE),
        ("falloff", CONE),
        ("tightness", CONE),
        ("spot", &[Area]),
    ]
};

impl LightKind {
    /// Every kind, in the order the scene format lists them.
    pub const ALL: [LightKind; 4] = [LightKind::Point, LightKind::Spot, LightKind::Parallel, LightKind::Area];

    /// The name a scene writes as `kind` (`"point"`, ...).
    pub fn name(self) -> &'static str {
        match self {
            LightKind::Point => "point",
            LightKind::Spot => "spot",
            LightKind::Parallel => "parallel",
            LightKind::Area => "area",
        }
    }

    /// True when a light of this kind accepts `key` (besides `kind`), by [`LIGHT_KEYS`].
    pub fn accepts(self, key: &str) -> bool {
        LIGHT_KEYS.iter().any(|(name, kinds)| *name == key && kinds.contains(&self))
    }

    /// The keys a light of this kind accepts (besides `kind`), in the order of [`LIGHT_KEYS`].
    pub fn keys(self) -> impl Iterator<Item = &'static str> {
        LIGHT_KEYS.iter().filter(move |(_, kinds)| kinds.contains(&self)).map(|(name, _)| *name)
    }
}

/// A `[[light]]` of the scene as written: one flat record whose keys are POV-Ray's
/// `light_source` parameters; which keys apply depends on `kind` ([`LIGHT_KEYS`]). Defaults
/// are POV-Ray's. `render::lights` reads it as a physical light (`color * intensity` is a
/// radiant intensity in W/sr, or for `parallel` an irradiance in W/m^2) plus the POV-Ray
/// parameters only the classic integrator uses (fade, tightness, shadowless).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct Light {
    /// What kind of light.
    pub kind: LightKind,
    /// Position (for parallel lights: a point the light comes from).
    pub position: [f64; 3],
    /// Colour (linear RGB).
    pub color: Rgb,
    /// Multiplies the colour: `color * intensity` is the radiant intensity in W/sr (point,
    /// spot; for area the whole grid's), or for parallel the irradiance in W/m^2 on a surface
    /// facing the light.
    pub intensity: f64,
    /// POV-Ray's distance at which the light has its nominal colour (0 = no fading; read by
    /// the classic integrator only).
    pub fade_distance: f64,
    /// POV-Ray's power of the distance fade (0 = no fading; classic integrator only).
    pub fade_power: f64,
    /// Casts no shadows and makes no highlights (classic integrator only).
    pub shadowless: bool,
    /// Where a spot or parallel light points.
    pub point_at: [f64; 3],
    /// Spot: full-intensity cone half-angle in degrees.
    pub radius: f64,
    /// Spot: half-angle in degrees where the light reaches zero.
    pub falloff: f64,
    /// Spot: POV-Ray's exponent that concentrates the light toward the axis (classic
    /// integrator only).
    pub tightness: f64,
    /// Area: makes the area light a spotlight too.
    pub spot: bool,
    /// Area: first edge vector of the light's rectangle.
    pub axis1: [f64; 3],
    /// Area: second edge vector.
    pub axis2: [f64; 3],
    /// Area: samples along axis1.
    pub size1: u32,
    /// Area: samples along axis2.
    pub size2: u32,
    /// Area: subdivision levels always taken (POV-Ray `adaptive`, 100 = full grid).
    pub adaptive: u32,
    /// Area: jitter the sample positions (deterministic per pixel).
    pub jitter: bool,
    /// Area: map the grid to a disc.
    pub circular: bool,
    /// Area: turn the grid to face each shaded point.
    pub orient: bool,
    /// Area: POV-Ray's `area_illumination`: the classic integrator shades with each grid
    /// point's own direction and distance (diffuse, highlights, spot cone and fade per point),
    /// not only its shadow, so a large light close to a surface lights it as an area does.
    pub area_illumination: bool,
}

impl Light {
    /// The key that makes `color * intensity` negative in some channel (POV-Ray's negative
    /// light, which takes light away): `intensity` when it is negative, else `color`; `None`
    /// for a light that emits.
    pub fn negative_key(&self) -> Option<&'static str> {
        let power = self.color.0 * self.intensity;
        (power.min_element() < 0.0).then_some(if self.intensity < 0.0 { "intensity" } else { "color" })
    }
}

impl Default for Light {
    fn default() -> Self {
        Self {
            kind: LightKind::Point,
            position: [0.0; 3],
            color: Rgb::WHITE,
            intensity: 1.0,
            fade_distance: 0.0,
            fade_power: 0.0,
            shadowless: false,
            point_at: [0.0, 0.0, 0.0],
            radius: 30.0,
            falloff: 45.0,
            tightness: 0.0,
            spot: false,
            axis1: [1.0, 0.0, 0.0],
            axis2: [0.0, 0.0, 1.0],
            size1: 2,
            size2: 2,
            adaptive: 100,
            jitter: false,
            circular: false,
            orient: false,
            area_illumination: false,
        }
    }
}

/// The kind of a `KHR_lights_punctual` light (of a glTF file, or imported from one).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PunctualKind {
    /// Shines in all directions from the node's origin; intensity in candela.
    Point,
    /// Shines down the node's -z within a cone; intensity in candela.
    Spot {
        /// Angle in radians from the axis where the falloff begins.
        inner_cone_angle: f64,
        /// Angle in radians from the axis where the light reaches zero.
        outer_cone_angle: f64,
    },
    /// Parallel light down the node's -z, infinitely far; intensity in lux.
    Directional,
}

/// A light imported from a glTF file (`import_lights`), placed in the world by its node, with
/// the photometric value the file gives: it is not a `[[light]]`, so it has no POV-Ray
/// parameters. `render::lights` converts it to radiometric units.
#[derive(Clone, Debug, PartialEq)]
pub struct PhotometricLight {
    /// Point, spot (with its cone) or directional.
    pub kind: PunctualKind,
    /// The node's origin in world space.
    pub position: DVec3,
    /// The node's -z in world space, unit length: where a spot or directional light shines.
    pub direction: DVec3,
    /// Linear RGB colour, as in the file.
    pub color: Rgb,
    /// Luminous intensity in candela (point, spot) or illuminance in lux (directional), as in
    /// the file.
    pub intensity: f64,
    /// World units per metre of the file: the uniform scale of the mesh object's transform
    /// (glTF lengths are metres, so the inverse-square falloff is measured in file metres).
    pub world_units_per_metre: f64,
}

/// The camera. Without a `[camera]` table this is the seed's camera: the eye one unit
/// behind a viewport of height 2 centred on the origin, looking down -z (90 degree
/// vertical field of view).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct Camera {
    /// Eye position.
    pub position: [f64; 3],
    /// The point looked at (the centre of the image).
    pub look_at: [f64; 3],
    /// The up direction (the image's vertical follows it).
    pub up: [f64; 3],
    /// Vertical field of view in degrees.
    pub vfov: f64,
    /// Width / height of the viewport; the image's pixel aspect when absent.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub aspect: Option<f64>,
    /// Lens diameter for depth of field (0 = pinhole).
    pub aperture: f64,
    /// Distance of the sharp plane; the distance to `look_at` when absent.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub focal_distance: Option<f64>,
    /// POV-Ray's adaptive focal blur (`variance`), classic integrator with an aperture: a
    /// pixel stops taking lens samples once the variance of its mean is below this, scaled by
    /// POV-Ray's chi-square ratio (0 to 1; absent or 0: always `[render] samples`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub blur_variance: Option<f64>,
    /// POV-Ray's focal blur `confidence`, in (0, 1) (default 0.9); needs `blur_variance`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub blur_confidence: Option<f64>,
    /// The fewest lens samples a pixel takes under adaptive focal blur (POV-Ray's
    /// `blur_samples min, max` first value; 1 to `samples`, default 1); needs `blur_variance`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub blur_min_samples: Option<u32>,
    /// How rays leave the camera: from the eye through the viewport (`perspective`), or all
    /// parallel to the view axis from a rectangle around the eye (`orthographic`).
    #[serde(skip_serializing_if = "Projection::is_perspective")]
    pub projection: Projection,
    /// Orthographic: the height of the view in scene units; the height `vfov` spans at
    /// `look_at` when absent, so switching projection keeps the framing there.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub view_height: Option<f64>,
}

/// POV-Ray's default focal blur `confidence`.
pub const DEFAULT_BLUR_CONFIDENCE: f64 = 0.9;

/// A camera's adaptive focal blur settings, as [`Camera::adaptive_blur`] resolves them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AdaptiveBlur {
    /// POV-Ray's `variance` (positive).
    pub variance: f64,
    /// POV-Ray's `confidence`.
    pub confidence: f64,
    /// The fewest lens samples a pixel takes.
    pub min_samples: u32,
}

impl Camera {
    /// The adaptive focal blur this camera asks for: an aperture and a positive
    /// `blur_variance`, with the defaults filled in (`None`: the fixed count).
    pub fn adaptive_blur(&self) -> Option<AdaptiveBlur> {
        let variance = self.blur_variance.filter(|v| *v > 0.0)?;
        (self.aperture > 0.0).then(|| AdaptiveBlur {
            variance,
            confidence: self.blur_confidence.unwrap_or(DEFAULT_BLUR_CONFIDENCE),
            min_samples: self.blur_min_samples.unwrap_or(1),
        })
    }
}

/// A camera's projection.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Projection {
    /// A pinhole or thin lens: rays from the eye (or the lens) through the viewport.
    #[default]
    Perspective,
    /// Parallel rays along the view axis, from a `view_height`-high rectangle centred on the
    /// eye (no depth of field).
    Orthographic,
}

impl Projection {
    /// True for the default, perspective projection.
    pub fn is_perspective(&self) -> bool {
        *self == Projection::Perspective
    }
}

impl Default for Camera {
    fn default() -> Self {
        Self {
            position: [0.0, 0.0, 1.0],
            look_at: [0.0, 0.0, 0.0],
            up: [0.0, 1.0, 0.0],
            vfov: 90.0,
            aspect: None,
            aperture: 0.0,
            focal_distance: None,
            blur_variance: None,
            blur_confidence: None,
            blur_min_samples: None,
            projection: Projection::Perspective,
            view_height: None,
        }
    }
}

/// How the PNG (or other 8-bit output) maps linear radiance to display values.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum ToneMap {
    /// Clip to [0, 1] (what POV-Ray writes).
    #[default]
    Clamp,
    /// Reinhard: x / (1 + x).
    Reinhard,
    /// The ACES filmic fit of Narkowicz (2015).
    Aces,
}

/// Which light transport algorithm renders the image.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum IntegratorKind {
    /// Whitted-style tracing with POV-Ray 3.7's shading model.
    #[default]
    Classic,
    /// Physically based unidirectional path tracing (next-event estimation with multiple
    /// importance sampling).
    Path,
}

/// How each pixel is sampled: `antialias = { method = "stratified" }` (the default) or one of
/// POV-Ray's methods, `antialias = { method = "pov1", threshold = 0.3, depth = 3 }`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(tag = "method", rename_all = "snake_case", deny_unknown_fields)]
pub enum Antialias {
    /// `samples` stratified (correlated multi-jittered) samples per pixel; one sample is the
    /// pixel centre, as POV-Ray without antialiasing. (A struct variant: serde does not
    /// refuse unknown keys beside the tag of a unit variant, such as a stray `depth`.)
    Stratified {},
    /// POV-Ray's method 1 without jitter (`+AM1 +A<threshold> +R<depth> -J`): pixels that
    /// differ from a neighbour get depth x depth extra samples. With an aperture, each
    /// position traced averages `samples` lens samples (POV-Ray's `blur_samples`).
    Pov1 {
        /// Colour distance (after POV-Ray's antialiasing gamma 2.5) that triggers supersampling.
        #[serde(default = "default_aa_threshold")]
        threshold: f64,
        /// Samples per axis of a supersampled pixel (1 to 9).
        #[serde(default = "default_aa_depth")]
        depth: u32,
    },
    /// POV-Ray's method 2 without jitter (`+AM2 +A<threshold> +R<depth> -J`): adaptive
    /// subdivision of pixels whose corners differ, down to 1 / 2^(depth - 1) pixel.
    Pov2 {
        /// Colour distance (after POV-Ray's antialiasing gamma 2.5) that triggers subdivision.
        #[serde(default = "default_aa_threshold")]
        threshold: f64,
        /// Subdivision depth (1 to 9).
        #[serde(default = "default_aa_depth")]
        depth: u32,
    },
}

impl Default for Antialias {
    /// Stratified sampling.
    fn default() -> Self {
        Antialias::Stratified {}
    }
}

fn default_aa_threshold() -> f64 {
    0.3
}

fn default_aa_depth() -> u32 {
    3
}

/// A pixel reconstruction filter (Mitsuba 3's `rfilter` plugins, same parameters): each
/// pixel is the filter-weighted mean of the radiance around its centre, offsets in pixels.
/// Written as a table: `filter = { type = "gaussian" }`, `{ type = "gaussian", stddev = 0.4 }`,
/// `{ type = "mitchell", B = 0.3, C = 0.35 }`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum PixelFilter {
    /// The pixel's own square, weighted equally (radius 0.5). (A struct variant, so that
    /// unknown keys beside the tag are refused.)
    Box {},
    /// A Gaussian of standard deviation `stddev` pixels, cut off at 4 `stddev` and shifted
    /// down to reach 0 there (Mitsuba's default filter).
    Gaussian {
        /// Standard deviation in pixels.
        #[serde(default = "default_gaussian_stddev")]
        stddev: f64,
    },
    /// Mitchell and Netravali's cubic, radius 2 pixels (negative lobes sharpen).
    Mitchell {
        /// The `B` parameter of the paper.
        #[serde(default = "one_third", rename = "B")]
        b: f64,
        /// The `C` parameter of the paper.
        #[serde(default = "one_third", rename = "C")]
        c: f64,
    },
}

impl Default for PixelFilter {
    /// The box filter.
    fn default() -> Self {
        PixelFilter::Box {}
    }
}

fn default_gaussian_stddev() -> f64 {
    0.5
}

fn one_third() -> f64 {
    1.0 / 3.0
}

impl PixelFilter {
    /// True for the default box filter.
    pub fn is_box(&self) -> bool {
        *self == PixelFilter::Box {}
    }
}

/// `[render]`: image size, sampling and recursion.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct RenderSettings {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Samples per pixel.
    pub samples: u32,
    /// Maximum path length in segments, the camera ray's being the first: POV-Ray's
    /// `max_trace_level` under `classic`, Mitsuba's `max_depth` under `path` (1 = only
    /// emitters seen directly).
    pub max_depth: u32,
    /// Under `path`: Russian roulette may end paths from this many segments on (Mitsuba's
    /// `rr_depth`).
    pub rr_depth: u32,
    /// Rays whose weight falls below this return black (POV-Ray `adc_bailout`).
    pub adc_bailout: f64,
    /// Seed of every random number (samples are a pure function of pixel, sample and seed).
    pub seed: u64,
    /// The light transport algorithm.
    pub integrator: IntegratorKind,
    /// How pixels are sampled.
    pub antialias: Antialias,
    /// The pixel reconstruction filter of `stratified` sampling: `{ type = "box" }` (the
    /// default), `gaussian` or `mitchell`.
    #[serde(skip_serializing_if = "PixelFilter::is_box")]
    pub filter: PixelFilter,
    /// Exposure in stops applied before tone mapping (PNG only; the EXR stays linear).
    pub exposure: f64,
    /// Tone-mapping operator for 8-bit output.
    pub tone_map: ToneMap,
    /// Adaptive sampling: the largest estimated error a pixel's displayed luminance (after
    /// exposure and tone map, clipped to [0, 1]; so in units of display white) may keep, in
    /// (0, 1). Each pixel takes samples in proportion to the spread of its displayed
    /// values, which for a given time gives the lowest RMSE, stopping at or below this
    /// error, or at `samples`. Stratified sampling only.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub noise: Option<f64>,
    /// AOV layers written into the OpenEXR output besides the beauty image (`albedo`,
    /// `normal`, `depth`, `position`, `uv`, `object_id`, `material_id`, `variance`,
    /// `samples`).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub aovs: Vec<String>,
    /// The working space of the scene's colours under `classic` (POV-Ray's
    /// `assumed_gamma`): a power law's decoding gamma (1, the default, is linear) or
    /// `"srgb"`. Colours and image maps are in that space, shading runs on its values, and
    /// a pixel is decoded to linear light once its samples are averaged.
    #[serde(skip_serializing_if = "AssumedGamma::is_linear")]
    pub assumed_gamma: AssumedGamma,
}

impl Default for RenderSettings {
    fn default() -> Self {
        Self {
            width: 1000,
            height: 563,
            samples: 1,
            max_depth: 5,
            rr_depth: 5,
            adc_bailout: 1.0 / 255.0,
            seed: 0,
            integrator: IntegratorKind::Classic,
            antialias: Antialias::Stratified {},
            filter: PixelFilter::Box {},
            exposure: 0.0,
            tone_map: ToneMap::Clamp,
            noise: None,
            aovs: Vec::new(),
            assumed_gamma: AssumedGamma::default(),
        }
    }
}

/// Marks the camera entity when the camera comes from a file (`import_camera`): loading
/// recreates it, so `save` writes only the lens keys of `[camera]`.
#[derive(Clone, Debug, PartialEq)]
pub struct ImportedCamera {
    /// The file's aspect ratio for the camera, if it gives one (the image's is used).
    pub aspect_ratio: Option<f64>,
    /// `file.gltf: camera 0 ...`, for messages.
    pub description: String,
}

/// `[world]`: what surrounds the objects.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct Environment {
    /// Colour of rays that escape the scene: under `path`, the radiance (W/(m^2 sr)) of a
    /// constant environment.
    pub background: Rgb,
    /// Global ambient light, multiplied by each material's `ambient`.
    pub ambient_light: Rgb,
    /// Under `path`: an HDR latitude-longitude image around the scene, replacing
    /// `background` as the environment's radiance.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub environment: Option<EnvironmentMapRef>,
}

impl Default for Environment {
    fn default() -> Self {
        Self { background: Rgb::BLACK, ambient_light: Rgb::WHITE, environment: None }
    }
}

/// `[world] environment = { file = "sky.exr", intensity = 1, rotate = 0 }`: an HDR
/// latitude-longitude map (2:1, OpenEXR or Radiance `.hdr`) in Mitsuba 3's `envmap`
/// orientation, scaled by `intensity` and turned by `rotate` degrees about +y.
#[derive(Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct EnvironmentMapRef {
    /// The image file, relative to the scene file (absolute once loaded).
    pub file: String,
    /// Multiplies the image's radiance.
    #[serde(default = "unit_intensity")]
    pub intensity: f64,
    /// Rotation about +y in degrees (right-hand rule).
    #[serde(default)]
    pub rotate: f64,
    /// The decoded map (set by the loader).
    #[serde(skip)]
    #[schemars(skip)]
    pub map: Option<std::sync::Arc<crate::texture::environment::EnvironmentMap>>,
}

fn unit_intensity() -> f64 {
    1.0
}

impl std::fmt::Debug for EnvironmentMapRef {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("EnvironmentMapRef")
            .field("file", &self.file)
            .field("intensity", &self.intensity)
            .field("rotate", &self.rotate)
            .field("loaded", &self.map.is_some())
            .finish()
    }
}

impl PartialEq for EnvironmentMapRef {
    /// Equal when they name the same file the same way (the image follows from that).
    fn eq(&self, other: &Self) -> bool {
        self.file == other.file && self.intensity == other.intensity && self.rotate == other.rotate
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_documented_light_keys_are_the_key_table() {
        let doc = include_str!("../../docs/scene-format.md");
        let section = doc.split("\n## Lights\n").nth(1).expect("a Lights section").split("\n#").next().unwrap();
        let mut documented: Vec<(&str, Vec<LightKind>)> = Vec::new();
        for row in section.lines().filter(|l| l.starts_with("| `")) {
            let cells: Vec<&str> = row.split('|').map(str::trim).collect();
            let kinds = if cells[2] == "all" {
                LightKind::ALL.to_vec()
            } else {
                cells[2].split(", ").map(|k| *LightKind::ALL.iter().find(|kind| kind.name() == k).expect(k)).collect()
            };
            for key in cells[1].split(", ") {
                documented.push((key.trim_matches('`'), kinds.clone()));
            }
        }
        let mut table: Vec<(&str, Vec<LightKind>)> = LIGHT_KEYS.iter().map(|(k, kinds)| (*k, kinds.to_vec())).collect();
        documented.sort_by_key(|(k, _)| *k);
        table.sort_by_key(|(k, _)| *k);
        assert_eq!(documented, table);
    }

    #[test]
    fn every_key_is_a_field_and_spot_lights_take_spot_keys() {
        let toml::Value::Table(fields) = toml::Value::try_from(Light::default()).unwrap() else { panic!() };
        let names: Vec<&str> = LIGHT_KEYS.iter().map(|(k, _)| *k).collect();
        let mut expected: Vec<&str> = fields.keys().map(String::as_str).filter(|k| *k != "kind").collect();
        expected.sort_unstable();
        let mut sorted = names.clone();
        sorted.sort_unstable();
        assert_eq!(sorted, expected);
        assert_eq!(LightKind::Point.keys().count(), 6);
        assert!(LightKind::Spot.accepts("tightness") && !LightKind::Point.accepts("tightness"));
        assert!(!LightKind::Parallel.accepts("radius") && !LightKind::Area.accepts("kind"));
        let serialised = LightKind::ALL.map(|k| toml::Value::try_from(k).unwrap().as_str().unwrap().to_string());
        assert_eq!(serialised, LightKind::ALL.map(|k| k.name().to_string()));
    }

    #[test]
    fn rotation_order_is_x_then_y_then_z() {
        let t = Transform { rotate: Some([90.0, 90.0, 0.0]), ..Default::default() };
        // +y rotated 90 about x -> +z; then 90 about y -> +x.
        let v = t.parent_from_local().transform_vector3(DVec3::Y);
        assert!((v - DVec3::X).length() < 1e-12, "{v}");
    }

    #[test]
    fn scale_then_rotate_then_translate() {
        let t = Transform {
            translate: Some([1.0, 2.0, 3.0]),
            rotate: Some([0.0, 0.0, 90.0]),
            scale: Some(Scale::PerAxis([2.0, 1.0, 1.0])),
            matrix: None,
        };
        let p = t.parent_from_local().transform_point3(DVec3::X);
        assert!((p - DVec3::new(1.0, 4.0, 3.0)).length() < 1e-12, "{p}");
    }

    #[test]
    fn matrix_rows() {
        let t = Transform {
            matrix: Some([[1.0, 0.0, 0.0, 5.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0]]),
            ..Default::default()
        };
        assert_eq!(t.parent_from_local().transform_point3(DVec3::ZERO), DVec3::new(5.0, 0.0, 0.0));
    }
}
