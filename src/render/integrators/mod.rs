//! Integrators: what turns a camera ray into radiance.

pub mod classic;
