//! Export: a loaded scene written in another renderer's scene language, so that the same
//! scene can be rendered by the reference renderer and the two images compared.
//!
//! [`pov`] writes POV-Ray 3.7 scene description language for everything the `classic`
//! integrator supports. Whatever it cannot express exactly is an error naming the object,
//! light or setting, never a silently different scene. [`mitsuba`] writes Mitsuba 3 XML for
//! the `path` integrator, under the same rule.

pub mod mitsuba;
pub mod pov;

use crate::diagnostics::{Diagnostic, SceneError};

/// An exporter's errors in file order, once each (the objects a model file expands to share
/// one location).
fn in_file_order(mut errors: Vec<Diagnostic>) -> SceneError {
    errors.sort_by(|a, b| {
        let key = |d: &Diagnostic| (d.location.file.clone(), d.location.line, d.location.column);
        key(a).cmp(&key(b))
    });
    errors.dedup();
    SceneError { diagnostics: errors }
}
