//! Integrators: what turns one camera ray into a pixel sample. The scheduler
//! ([`crate::render::render`]) makes the camera rays and their random streams and never
//! knows which integrator runs; an integrator never knows about tiles, threads or films.

pub mod classic;
pub mod path;

use glam::{DVec2, DVec3};
use prism_api::Ray;

use super::sampling::SampleStream;
use crate::gamma::GammaCurve;

/// The first surface a camera ray sees, for AOV layers.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FirstHit {
    /// Reflectance there (linear RGB): the surface colour as the integrator reads it.
    pub albedo: DVec3,
    /// World-space unit shading normal, facing the camera.
    pub normal: DVec3,
    /// World-space hit point.
    pub position: DVec3,
    /// Distance from the ray's origin (scene units).
    pub depth: f64,
    /// Texture coordinates.
    pub uv: DVec2,
    /// The primitive's index in the render scene (load order).
    pub primitive: u32,
    /// The material's index in the render scene's material table.
    pub material: u32,
}

/// What an integrator returns for one camera ray.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PixelSample {
    /// Radiance arriving along the ray (linear RGB). NaN or infinite only when extreme but
    /// accepted inputs overflow; the scheduler counts such samples and drops them as black.
    pub radiance: DVec3,
    /// The first surface the ray met, `None` when it escaped.
    pub first_hit: Option<FirstHit>,
    /// Rays traced for this sample (camera, reflected, refracted, shadow).
    pub rays: u64,
}

/// A light transport algorithm over one render scene.
pub trait Integrator: Sync {
    /// The sample for camera ray `ray`, drawing its random numbers from `stream` (dimensions
    /// 0 to 3 are the scheduler's: pixel and lens position).
    fn sample(&self, ray: &Ray, stream: SampleStream) -> PixelSample;

    /// The space the samples' values are in: linear light (the default), or the scene's
    /// working space under `classic` with a POV-Ray `assumed_gamma`. The scheduler averages
    /// a pixel's samples in this space, as POV-Ray does, and decodes the mean to linear light.
    fn working_gamma(&self) -> GammaCurve {
        GammaCurve::Neutral
    }

    /// Whether a NaN channel of a sample is part of the integrator's answer (`classic`, as
    /// POV-Ray: under POV-Ray's antialiasing it spreads through the pixel's mean and that
    /// channel of the pixel is written as 0; otherwise that channel of the sample is 0)
    /// rather than a defect (the default: the whole sample is dropped and counted).
    fn keeps_nan_channels(&self) -> bool {
        false
    }
}
