//! Prism: a ray tracer for scenes written as TOML.
//!
//! Data flows one way, each step a plain function:
//! [`scene::load`] (TOML -> hecs `World`), [`world::transforms::resolve_transforms`],
//! [`world::validate::validate`], [`render::extract::extract`] (world -> immutable render
//! scene with its BVH), [`render::render`] (any integrator over a region, tiles in parallel -> [`film::Film`]) and
//! [`output`] (film -> EXR / PNG / ...). [`scene::save`] is the inverse of `load`.

pub mod accel;
pub mod builtin;
pub mod checkpoint;
pub mod color;
pub mod denoise;
pub mod diagnostics;
pub mod export;
pub mod farm;
pub mod files;
pub mod film;
pub mod gamma;
pub mod geometry;
pub mod import;
pub mod limits;
pub mod material;
pub mod output;
pub mod partial;
pub mod plugins;
pub mod preview;
pub mod registry;
pub mod render;
pub mod scene;
pub mod texture;
pub mod watch;
pub mod world;

use diagnostics::SceneError;
use render::extract::RenderScene;
use world::Scene;

/// Resolves transforms, validates and extracts: a loaded scene to a render scene.
pub fn prepare(scene: &mut Scene) -> Result<RenderScene, SceneError> {
    world::transforms::resolve_transforms(scene)?;
    world::validate::validate(scene)?;
    Ok(render::extract::extract(scene))
}

#[cfg(test)]
pub(crate) mod test_support;
