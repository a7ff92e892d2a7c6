//! Scenes compiled into the binary: `prism` with no arguments renders the seed's room.

use crate::scene::load::Embedded;

/// Path of the built-in default scene.
pub const DEFAULT_SCENE: &str = "scenes/room.toml";

/// The scene files embedded in the binary.
pub const FILES: Embedded = Embedded(&[
    ("scenes/room.toml", include_str!("../scenes/room.toml")),
    ("scenes/base/room.toml", include_str!("../scenes/base/room.toml")),
]);
