//! Prism: a ray tracer for scenes written as TOML.
//!
//! Data flows one way, each step a plain function:
//! [`scene::load`] (TOML -> hecs `World`), [`scene::transforms::resolve_transforms`],
//! [`scene::validate::validate`], [`render::scene::extract`] (world -> immutable render
//! scene with its BVH), [`render::render`] (tiles in parallel -> [`render::film::Film`]) and
//! [`output`] (film -> EXR / PNG / ...). [`scene::save`] is the inverse of `load`.

pub mod builtin;
pub mod color;
pub mod diagnostics;
pub mod export;
pub mod material;
pub mod mesh;
pub mod output;
pub mod plugins;
pub mod registry;
pub mod render;
pub mod scene;
pub mod schema;
pub(crate) mod wide_bvh;

use diagnostics::SceneError;
use render::scene::RenderScene;
use scene::Scene;

/// Resolves transforms, validates and extracts: a loaded scene to a render scene.
pub fn prepare(scene: &mut Scene) -> Result<RenderScene, SceneError> {
    scene::transforms::resolve_transforms(scene)?;
    scene::validate::validate(scene)?;
    Ok(render::scene::extract(scene))
}
