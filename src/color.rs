//! Linear RGB colours as written in scenes: a number (grey) or `[r, g, b]`.

use std::borrow::Cow;
use std::fmt;

use glam::DVec3;
use schemars::{JsonSchema, Schema, SchemaGenerator, json_schema};
use serde::de::{self, Deserializer, SeqAccess, Visitor};
use serde::{Deserialize, Serialize, Serializer};

/// A linear RGB colour (scene values are linear, as with POV-Ray's `assumed_gamma 1.0`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Rgb(pub DVec3);

impl Rgb {
    /// Black.
    pub const BLACK: Rgb = Rgb(DVec3::ZERO);
    /// White.
    pub const WHITE: Rgb = Rgb(DVec3::ONE);

    /// A colour from components.
    pub const fn new(r: f64, g: f64, b: f64) -> Self {
        Rgb(DVec3::new(r, g, b))
    }

    /// The grey `v`.
    pub const fn grey(v: f64) -> Self {
        Rgb(DVec3::splat(v))
    }

    /// True when every component is finite.
    pub fn is_finite(&self) -> bool {
        self.0.is_finite()
    }
}

impl Serialize for Rgb {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        [self.0.x, self.0.y, self.0.z].serialize(s)
    }
}

impl<'de> Deserialize<'de> for Rgb {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(RgbVisitor)
    }
}

struct RgbVisitor;

impl<'de> Visitor<'de> for RgbVisitor {
    type Value = Rgb;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a colour: a number (grey) or an array of 3 numbers [r, g, b]")
    }

    fn visit_f64<E: de::Error>(self, v: f64) -> Result<Rgb, E> {
        Ok(Rgb::grey(v))
    }

    fn visit_i64<E: de::Error>(self, v: i64) -> Result<Rgb, E> {
        Ok(Rgb::grey(v as f64))
    }

    fn visit_u64<E: de::Error>(self, v: u64) -> Result<Rgb, E> {
        Ok(Rgb::grey(v as f64))
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Rgb, A::Error> {
        let mut c = [0.0; 3];
        for (i, slot) in c.iter_mut().enumerate() {
            *slot = seq.next_element()?.ok_or_else(|| de::Error::invalid_length(i, &self))?;
        }
        if seq.next_element::<f64>()?.is_some() {
            return Err(de::Error::invalid_length(4, &self));
        }
        Ok(Rgb::new(c[0], c[1], c[2]))
    }
}

impl JsonSchema for Rgb {
    fn schema_name() -> Cow<'static, str> {
        "Rgb".into()
    }

    fn json_schema(_: &mut SchemaGenerator) -> Schema {
        json_schema!({
            "description": "Linear RGB colour: a number (grey) or [r, g, b].",
            "oneOf": [
                { "type": "number" },
                { "type": "array", "items": { "type": "number" }, "minItems": 3, "maxItems": 3 }
            ]
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Deserialize)]
    struct Holder {
        c: Rgb,
    }

    #[test]
    fn number_or_triple() {
        let h: Holder = toml::from_str("c = 0.5").unwrap();
        assert_eq!(h.c, Rgb::grey(0.5));
        let h: Holder = toml::from_str("c = [1, 0.5, 0]").unwrap();
        assert_eq!(h.c, Rgb::new(1.0, 0.5, 0.0));
        assert!(toml::from_str::<Holder>("c = [1, 2]").is_err());
        assert!(toml::from_str::<Holder>("c = [1, 2, 3, 4]").is_err());
        assert!(toml::from_str::<Holder>("c = \"red\"").is_err());
    }
}
