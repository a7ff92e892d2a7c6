//! Named metals: complex indices of refraction as linear RGB (eta, k). TEMPORARY values
//! until the table computed from Mitsuba's spectral data lands.

use glam::DVec3;

/// The names `metal` accepts.
pub const METAL_NAMES: [&str; 7] = ["Au", "Ag", "Cu", "Al", "Cr", "Fe", "Ti"];

/// The (eta, k) of a named metal.
pub fn metal(name: &str) -> Option<(DVec3, DVec3)> {
    let (eta, k) = match name {
        "Au" => ([0.143, 0.374, 1.442], [3.983, 2.385, 1.603]),
        "Ag" => ([0.155, 0.117, 0.138], [4.828, 3.122, 2.147]),
        "Cu" => ([0.200, 0.924, 1.102], [3.912, 2.452, 2.142]),
        "Al" => ([1.657, 0.880, 0.521], [9.224, 6.270, 4.837]),
        "Cr" => ([4.368, 2.916, 1.654], [5.204, 4.231, 3.754]),
        "Fe" => ([2.950, 2.930, 2.650], [3.000, 2.950, 2.800]),
        "Ti" => ([2.160, 1.940, 1.730], [2.930, 2.600, 2.370]),
        _ => return None,
    };
    Some((DVec3::from_array(eta), DVec3::from_array(k)))
}
