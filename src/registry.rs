//! The table of shape types a scene may use.

use prism_api::ShapeType;

/// Registered shape types, in registration order.
#[derive(Debug, Default)]
pub struct ShapeRegistry {
    types: Vec<ShapeType>,
}

impl ShapeRegistry {
    /// An empty registry.
    pub fn new() -> Self {
        Self::default()
    }

    /// Registers a shape type. Registering one name twice is a programming error.
    pub fn add(&mut self, shape_type: ShapeType) -> &mut Self {
        assert!(self.get(shape_type.name).is_none(), "shape type `{}` registered twice", shape_type.name);
        self.types.push(shape_type);
        self
    }

    /// The type registered under `name`.
    pub fn get(&self, name: &str) -> Option<&ShapeType> {
        self.types.iter().find(|t| t.name == name)
    }

    /// Every registered type.
    pub fn iter(&self) -> impl Iterator<Item = &ShapeType> {
        self.types.iter()
    }

    /// Every registered name.
    pub fn names(&self) -> impl Iterator<Item = &'static str> + '_ {
        self.types.iter().map(|t| t.name)
    }
}

/// A human-readable listing of every shape type and its parameters (name, type, default,
/// description), generated from the plugins' own parameter schemas.
pub fn describe(registry: &ShapeRegistry) -> String {
    let mut out = String::new();
    for t in registry.iter() {
        out.push_str(&format!("{}\n    {}\n", t.name, t.description));
        let mut generator = schemars::SchemaGenerator::default();
        let schema = (t.schema)(&mut generator).to_value();
        let required: Vec<&str> = schema
            .get("required")
            .and_then(|r| r.as_array())
            .map(|r| r.iter().filter_map(|v| v.as_str()).collect())
            .unwrap_or_default();
        if let Some(props) = schema.get("properties").and_then(|p| p.as_object()) {
            for (name, prop) in props {
                let ty = type_name(prop);
                let default = match prop.get("default") {
                    Some(d) => format!("default {d}"),
                    None if required.contains(&name.as_str()) => "required".to_string(),
                    None => "optional".to_string(),
                };
                let description = prop.get("description").and_then(|d| d.as_str()).unwrap_or("");
                out.push_str(&format!("    {name:<14} {ty:<12} {default:<24} {description}\n"));
            }
        }
        out.push('\n');
    }
    out
}

fn type_name(prop: &serde_json::Value) -> String {
    match prop.get("type") {
        Some(serde_json::Value::String(t)) if t == "array" => {
            let len = prop.get("maxItems").and_then(|v| v.as_u64());
            let item = prop.get("items").map(type_name).unwrap_or_else(|| "value".into());
            match len {
                Some(n) => format!("[{item}; {n}]"),
                None => format!("[{item}]"),
            }
        }
        Some(serde_json::Value::String(t)) => t.clone(),
        Some(serde_json::Value::Array(ts)) => {
            ts.iter().filter_map(|t| t.as_str()).filter(|t| *t != "null").collect::<Vec<_>>().join("|")
        }
        _ => "value".into(),
    }
}
