//! Transfer curves between linear light and encoded values, with POV-Ray 3.7's semantics
//! (`colourspace.cpp`): the working space a scene declares with `assumed_gamma`, the curves
//! image files are encoded with, and the transcoding between two of them.
//!
//! The arithmetic is single precision, as POV-Ray's, and the shortcuts are POV-Ray's too: a
//! power law within 1 % of gamma 1 is no curve at all, two curves that match cancel, and two
//! power laws combine into one. They matter for parity: an image whose file gamma matches
//! the working gamma is read without any `pow`, so its 8-bit values arrive exactly.

use std::borrow::Cow;
use std::fmt;

use schemars::{JsonSchema, Schema, SchemaGenerator, json_schema};
use serde::de::{self, Deserializer, Visitor};
use serde::{Deserialize, Serialize, Serializer};

/// A transfer curve: `encode` maps linear light to an encoded value, `decode` back.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum GammaCurve {
    /// The identity (linear values).
    Neutral,
    /// `encoded = max(linear, 0)^encoding`: a power law given by its encoding exponent
    /// (1 / the usual "gamma").
    PowerLaw {
        /// The encoding exponent, 1/2.2 for the common "gamma 2.2".
        encoding: f32,
    },
    /// The sRGB curve (IEC 61966-2-1).
    Srgb,
}

impl GammaCurve {
    /// The power law with decoding gamma `gamma` (POV-Ray's `GetByDecodingGamma`: the
    /// `assumed_gamma 2.2` of a scene is `power_law(2.2)`).
    pub fn power_law(gamma: f32) -> Self {
        Self::by_encoding(1.0 / gamma)
    }

    /// The power law with encoding exponent `encoding` (POV-Ray's `GetByEncodingGamma`, the
    /// value of a PNG file's `gAMA` chunk): neutral within 1 % of 1.
    pub fn by_encoding(encoding: f32) -> Self {
        if (1.0 - f64::from(encoding)).abs() <= 0.01 { GammaCurve::Neutral } else { GammaCurve::PowerLaw { encoding } }
    }

    /// True for the identity.
    pub fn is_neutral(self) -> bool {
        self == GammaCurve::Neutral
    }

    /// Linear light to the encoded value.
    pub fn encode(self, x: f32) -> f32 {
        match self {
            GammaCurve::Neutral => x,
            GammaCurve::PowerLaw { encoding } => x.max(0.0).powf(encoding),
            GammaCurve::Srgb => {
                if x <= 0.003_130_8 {
                    x * 12.92
                } else {
                    1.055 * x.powf(1.0 / 2.4) - 0.055
                }
            }
        }
    }

    /// The encoded value to linear light.
    pub fn decode(self, x: f32) -> f32 {
        match self {
            GammaCurve::Neutral => x,
            GammaCurve::PowerLaw { encoding } => x.max(0.0).powf(1.0 / encoding),
            GammaCurve::Srgb => {
                if x < 0.04045 {
                    x / 12.92
                } else {
                    ((x + 0.055) / 1.055).powf(2.4)
                }
            }
        }
    }

    /// The power law closest to the curve, as its decoding gamma (sRGB: 2.2).
    fn approximate_decoding_gamma(self) -> f32 {
        match self {
            GammaCurve::Neutral => 1.0,
            GammaCurve::PowerLaw { encoding } => 1.0 / encoding,
            GammaCurve::Srgb => 2.2,
        }
    }

    /// True when POV-Ray treats the two curves as the same.
    fn matches(self, other: GammaCurve) -> bool {
        match (self, other) {
            (GammaCurve::PowerLaw { encoding: a }, GammaCurve::PowerLaw { encoding: b }) => {
                (1.0 - f64::from(a / b)).abs() <= 0.01
            }
            (a, b) => a == b,
        }
    }
}

/// `colour`, in the working space `curve`, as linear light: channel by channel in single
/// precision as POV-Ray writes its pixels, with channels beyond f32's range saturated (as
/// the classic integrator saturates them) rather than infinite. The identity, bit for bit,
/// for the neutral curve.
pub fn decode_rgb(curve: GammaCurve, colour: glam::DVec3) -> glam::DVec3 {
    if curve.is_neutral() {
        return colour;
    }
    glam::DVec3::from_array(colour.to_array().map(|c| {
        let linear = curve.decode(c as f32);
        f64::from(if linear.is_nan() { linear } else { linear.clamp(-f32::MAX, f32::MAX) })
    }))
}

/// A value encoded in one working space re-encoded in another (POV-Ray's
/// `TranscodingGammaCurve`): `encode(x)` is `target.encode(working.decode(x))`, `decode(x)` is
/// `working.encode(target.decode(x))`. Built by [`Transcoding::new`], which reduces it to
/// one curve where POV-Ray does.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Transcoding {
    /// One curve does it.
    Single(GammaCurve),
    /// Both curves, in turn.
    Combined {
        /// The space values are in.
        working: GammaCurve,
        /// The space they go to (`encode`) or come from (`decode`).
        target: GammaCurve,
    },
}

impl Transcoding {
    /// From the working space `working` to `target` (POV-Ray's `TranscodingGammaCurve::Get`).
    pub fn new(working: GammaCurve, target: GammaCurve) -> Self {
        if working.is_neutral() {
            return Transcoding::Single(target);
        }
        if working.matches(target) {
            return Transcoding::Single(GammaCurve::Neutral);
        }
        if let GammaCurve::PowerLaw { .. } = working {
            let working_gamma = working.approximate_decoding_gamma();
            match target {
                GammaCurve::Neutral => return Transcoding::Single(GammaCurve::by_encoding(working_gamma)),
                GammaCurve::PowerLaw { .. } => {
                    return Transcoding::Single(GammaCurve::by_encoding(
                        working_gamma / target.approximate_decoding_gamma(),
                    ));
                }
                GammaCurve::Srgb => {}
            }
        }
        Transcoding::Combined { working, target }
    }

    /// A working-space value in the target space.
    pub fn encode(self, x: f32) -> f32 {
        match self {
            Transcoding::Single(curve) => curve.encode(x),
            Transcoding::Combined { working, target } => target.encode(working.decode(x)),
        }
    }

    /// A target-space value in the working space.
    pub fn decode(self, x: f32) -> f32 {
        match self {
            Transcoding::Single(curve) => curve.decode(x),
            Transcoding::Combined { working, target } => working.encode(target.decode(x)),
        }
    }

    /// True when values pass unchanged.
    pub fn is_neutral(self) -> bool {
        self == Transcoding::Single(GammaCurve::Neutral)
    }
}

/// `[render] assumed_gamma`: the working space of the scene's colours under `classic`
/// (POV-Ray's `assumed_gamma`). Written as a number (the decoding gamma of a power law,
/// above 0; 1, the default, is linear) or `"srgb"`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum AssumedGamma {
    /// A power law with this decoding gamma (1: linear).
    Power(f64),
    /// The sRGB curve.
    Srgb,
}

impl Default for AssumedGamma {
    fn default() -> Self {
        AssumedGamma::Power(1.0)
    }
}

impl AssumedGamma {
    /// True for the default, linear working space (`assumed_gamma = 1`).
    pub fn is_linear(&self) -> bool {
        *self == AssumedGamma::Power(1.0)
    }

    /// True when the value can be used: `"srgb"` or a finite power above 0.
    pub fn is_valid(&self) -> bool {
        match *self {
            AssumedGamma::Power(g) => g.is_finite() && g > 0.0 && (g as f32).is_normal(),
            AssumedGamma::Srgb => true,
        }
    }

    /// The working space's curve (neutral for gammas within 1 % of 1, as POV-Ray's).
    pub fn curve(&self) -> GammaCurve {
        match *self {
            AssumedGamma::Power(g) => GammaCurve::power_law(g as f32),
            AssumedGamma::Srgb => GammaCurve::Srgb,
        }
    }
}

impl fmt::Display for AssumedGamma {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            AssumedGamma::Power(g) => write!(f, "{g}"),
            AssumedGamma::Srgb => f.write_str("\"srgb\""),
        }
    }
}

impl Serialize for AssumedGamma {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            AssumedGamma::Power(g) => s.serialize_f64(*g),
            AssumedGamma::Srgb => s.serialize_str("srgb"),
        }
    }
}

impl<'de> Deserialize<'de> for AssumedGamma {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(AssumedGammaVisitor)
    }
}

struct AssumedGammaVisitor;

impl Visitor<'_> for AssumedGammaVisitor {
    type Value = AssumedGamma;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a gamma above 0 (1 is linear, 2.2 a common display gamma) or \"srgb\"")
    }

    fn visit_f64<E: de::Error>(self, v: f64) -> Result<AssumedGamma, E> {
        Ok(AssumedGamma::Power(v))
    }

    fn visit_i64<E: de::Error>(self, v: i64) -> Result<AssumedGamma, E> {
        Ok(AssumedGamma::Power(v as f64))
    }

    fn visit_u64<E: de::Error>(self, v: u64) -> Result<AssumedGamma, E> {
        Ok(AssumedGamma::Power(v as f64))
    }

    fn visit_str<E: de::Error>(self, v: &str) -> Result<AssumedGamma, E> {
        if v == "srgb" { Ok(AssumedGamma::Srgb) } else { Err(E::invalid_value(de::Unexpected::Str(v), &self)) }
    }
}

impl JsonSchema for AssumedGamma {
    fn schema_name() -> Cow<'static, str> {
        "AssumedGamma".into()
    }

    fn json_schema(_: &mut SchemaGenerator) -> Schema {
        json_schema!({
            "description": "The working space of the scene's colours under `classic` (POV-Ray's `assumed_gamma`): the decoding gamma of a power law (above 0; 1 is linear) or \"srgb\".",
            "oneOf": [
                { "type": "number", "exclusiveMinimum": 0 },
                { "const": "srgb" }
            ]
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn power_laws_near_one_are_neutral_and_matching_curves_cancel() {
        assert!(GammaCurve::power_law(1.0).is_neutral());
        assert!(GammaCurve::power_law(1.009).is_neutral());
        assert!(!GammaCurve::power_law(1.02).is_neutral());
        let working = GammaCurve::power_law(2.2);
        // A PNG whose gAMA says 1/2.2 (0.45455) is read unchanged in a 2.2 working space.
        assert!(Transcoding::new(working, GammaCurve::by_encoding(0.45455)).is_neutral());
        assert!(Transcoding::new(GammaCurve::Srgb, GammaCurve::Srgb).is_neutral());
        // Linear working space: the target curve alone.
        assert_eq!(Transcoding::new(GammaCurve::Neutral, GammaCurve::Srgb), Transcoding::Single(GammaCurve::Srgb));
    }

    #[test]
    fn power_laws_combine_into_one() {
        // POV-Ray's antialiasing curve in a 2.2 working space: decoding 2.2, encoding 1/2.5.
        let aa = Transcoding::new(GammaCurve::power_law(2.2), GammaCurve::power_law(2.5));
        let Transcoding::Single(GammaCurve::PowerLaw { encoding }) = aa else { panic!("{aa:?}") };
        assert!((encoding - 0.88).abs() < 1e-6);
        assert!((aa.encode(0.5) - 0.5f32.powf(0.88)).abs() < 1e-7);
        // To linear: decoding the working gamma.
        let linear = Transcoding::new(GammaCurve::power_law(2.2), GammaCurve::Neutral);
        assert!((linear.encode(0.5) - 0.5f32.powf(2.2)).abs() < 1e-7);
    }

    #[test]
    fn srgb_and_power_law_go_through_linear() {
        let t = Transcoding::new(GammaCurve::power_law(2.2), GammaCurve::Srgb);
        assert!(matches!(t, Transcoding::Combined { .. }));
        // An sRGB file's 0.5 is 0.214 linear, 0.2140^(1/2.2) in the working space.
        let expected = GammaCurve::Srgb.decode(0.5).powf(1.0 / 2.2);
        assert!((t.decode(0.5) - expected).abs() < 1e-6, "{}", t.decode(0.5));
        for x in [0.0f32, 0.001, 0.02, 0.3, 0.9, 1.0] {
            assert!((t.encode(t.decode(x)) - x).abs() < 1e-5, "{x}");
        }
    }

    #[test]
    fn srgb_curve_is_povs() {
        assert_eq!(GammaCurve::Srgb.encode(0.0), 0.0);
        assert!((GammaCurve::Srgb.encode(1.0) - 1.0).abs() < 1e-6);
        assert_eq!(GammaCurve::Srgb.decode(0.04), 0.04 / 12.92);
        // Negative values pass the sRGB curve's linear segment; power laws clamp them.
        assert!(GammaCurve::Srgb.decode(-0.1) < 0.0);
        assert_eq!(GammaCurve::power_law(2.2).decode(-0.1), 0.0);
    }

    #[test]
    fn assumed_gamma_reads_numbers_and_srgb() {
        #[derive(Deserialize)]
        struct T {
            g: AssumedGamma,
        }
        let read = |s: &str| toml::from_str::<T>(s).map(|t| t.g);
        assert_eq!(read("g = 2.2").unwrap(), AssumedGamma::Power(2.2));
        assert_eq!(read("g = 1").unwrap(), AssumedGamma::Power(1.0));
        assert_eq!(read("g = \"srgb\"").unwrap(), AssumedGamma::Srgb);
        assert!(read("g = \"sRGB-ish\"").is_err());
        assert!(!AssumedGamma::Power(0.0).is_valid() && !AssumedGamma::Power(-2.2).is_valid());
        assert!(!AssumedGamma::Power(f64::NAN).is_valid() && !AssumedGamma::Power(1e300).is_valid());
        assert!(AssumedGamma::Power(2.2).is_valid() && AssumedGamma::default().is_linear());
    }
}
