//! The scene file: TOML (with includes and named materials) to a [`crate::world::Scene`]
//! (`load`), and back (`save`); the JSON schema of the format (`schema`). Knows nothing of
//! rendering.

pub mod load;
pub mod save;
pub mod schema;
pub mod source;
