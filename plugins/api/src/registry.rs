use std::sync::Arc;

use schemars::{JsonSchema, Schema, SchemaGenerator};
use serde::de::DeserializeOwned;

use crate::{FileReader, Shape};

/// A problem with a shape's parameters: the key it concerns and what is wrong.
#[derive(Clone, Debug, PartialEq)]
pub struct ParamError {
    /// Dotted key path inside the shape's parameters (for example `radius`), empty when the
    /// problem concerns the parameters as a whole.
    pub key: String,
    /// What is wrong, as a sentence fragment ("must be positive, got -1").
    pub message: String,
}

impl ParamError {
    /// An error about `key`.
    pub fn new(key: impl Into<String>, message: impl Into<String>) -> Self {
        Self { key: key.into(), message: message.into() }
    }

    /// Fails unless `value` is finite and strictly positive.
    pub fn require_positive(key: &str, value: f64) -> Result<(), ParamError> {
        if value.is_finite() && value > 0.0 {
            Ok(())
        } else {
            Err(Self::new(key, format!("must be a finite number greater than 0, got {value}")))
        }
    }

    /// Fails unless `value` is finite and not negative.
    pub fn require_non_negative(key: &str, value: f64) -> Result<(), ParamError> {
        if value.is_finite() && value >= 0.0 {
            Ok(())
        } else {
            Err(Self::new(key, format!("must be a finite number of at least 0, got {value}")))
        }
    }

    /// Fails unless every component is finite.
    pub fn require_finite(key: &str, value: &[f64]) -> Result<(), ParamError> {
        if value.iter().all(|v| v.is_finite()) {
            Ok(())
        } else {
            Err(Self::new(key, format!("must be finite, got {value:?}")))
        }
    }
}

impl std::fmt::Display for ParamError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.key.is_empty() { f.write_str(&self.message) } else { write!(f, "`{}` {}", self.key, self.message) }
    }
}

impl std::error::Error for ParamError {}

/// A shape's parameter struct: deserialised from the scene, documented by its JSON schema,
/// validated and turned into the shape by [`ShapeParams::build`].
///
/// Derive `Deserialize` with `#[serde(deny_unknown_fields)]` and `JsonSchema`; doc comments
/// on the fields become the parameter descriptions `prism shapes` prints.
pub trait ShapeParams: DeserializeOwned + JsonSchema {
    /// Checks the parameters and builds the shape.
    fn build(self) -> Result<Arc<dyn Shape>, ParamError>;

    /// Checks the parameters and builds the shape, reading the files they name through
    /// `files` (see [`crate::files`]). Prism calls this one; the default ignores `files` and
    /// calls [`ShapeParams::build`], so only shapes that read files override it.
    fn build_with_files(self, files: &mut dyn FileReader) -> Result<Arc<dyn Shape>, ParamError> {
        let _ = files;
        self.build()
    }
}

/// Deserialises, validates and builds a shape from its parameters, reading the files they
/// name through the reader ([`ShapeType::build`]).
pub type BuildFn = fn(toml::Table, &mut dyn FileReader) -> Result<Arc<dyn Shape>, ParamError>;

/// A registered shape type: its scene name, a description, its parameter schema and a builder.
#[derive(Clone, Copy)]
pub struct ShapeType {
    /// The value of `shape = "..."` in a scene.
    pub name: &'static str,
    /// One sentence on what the shape is.
    pub description: &'static str,
    /// JSON schema of the parameters (generated from the parameter struct).
    pub schema: fn(&mut SchemaGenerator) -> Schema,
    /// Deserialises, validates and builds the shape from its parameters, reading the files
    /// they name through the reader.
    pub build: BuildFn,
}

impl std::fmt::Debug for ShapeType {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ShapeType").field("name", &self.name).finish_non_exhaustive()
    }
}

/// The registration record for parameter struct `P` under `name`.
pub fn shape_type<P: ShapeParams>(name: &'static str, description: &'static str) -> ShapeType {
    ShapeType { name, description, schema: P::json_schema, build: build_from_table::<P> }
}

fn build_from_table<P: ShapeParams>(
    params: toml::Table,
    files: &mut dyn FileReader,
) -> Result<Arc<dyn Shape>, ParamError> {
    let parsed: P = serde_path_to_error::deserialize(toml::Value::Table(params)).map_err(|e| {
        let key = e.path().to_string();
        let key = if key == "." { String::new() } else { key };
        ParamError::new(key, e.into_inner().message().to_string())
    })?;
    parsed.build_with_files(files)
}
