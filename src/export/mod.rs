//! Export: a loaded scene written in another renderer's scene language, so that the same
//! scene can be rendered by the reference renderer and the two images compared.
//!
//! [`pov`] writes POV-Ray 3.7 scene description language for everything the `classic`
//! integrator supports. Whatever it cannot express exactly is an error naming the object,
//! light or setting, never a silently different scene. [`mitsuba`] writes Mitsuba 3 XML for
//! the `path` integrator, under the same rule.

pub mod mitsuba;
pub mod pov;
