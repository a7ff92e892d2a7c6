//! Named metals: RGB complex indices of refraction (eta, k) relative to air/vacuum.
//!
//! `Au`, `Ag`, `Cu`, `Al` and `Cr` are the numbers Mitsuba 3's RGB variants use for the
//! `material` presets of `conductor`/`roughconductor`: Mitsuba's `complex_ior_from_file`
//! turns the spectral data of `data/ior/<name>.{eta,k}.spd` into linear sRGB with
//! `spectrum_list_to_srgb` (CIE 1931 integration over 360-830 nm, no illuminant, negative
//! channels clamped). `scripts/mitsuba_metal_rgb.py` reproduces that reduction from
//! Mitsuba's data files; its output is pasted below (6 significant digits).
//!
//! Mitsuba ships no `Fe` or `Ti` preset. Their numbers are RefractiveIndex.INFO's values at
//! 650 nm (red), 550 nm (green) and 450 nm (blue), as tabulated for renderers at
//! <https://chris.hindefjord.se/resources/rgb-ior-metals/>: point samples, not integrals, so
//! they are not directly comparable to the five above. The Mitsuba exporter writes numbers,
//! never these names, so a scene renders the same in both.

use glam::DVec3;

/// The metal names [`metal`] knows, in table order.
pub const METAL_NAMES: [&str; 7] = ["Au", "Ag", "Cu", "Al", "Cr", "Fe", "Ti"];

/// (name, eta, k) per metal, RGB.
const METALS: [(&str, DVec3, DVec3); 7] = [
    ("Au", DVec3::new(0.143036, 0.375307, 1.44205), DVec3::new(3.983, 2.38556, 1.60336)),
    ("Ag", DVec3::new(0.155276, 0.116728, 0.138388), DVec3::new(4.82835, 3.12222, 2.1469)),
    ("Cu", DVec3::new(0.201006, 0.923749, 1.10222), DVec3::new(3.91326, 2.45305, 2.14209)),
    ("Al", DVec3::new(1.6575, 0.880405, 0.521244), DVec3::new(9.22381, 6.2695, 4.837)),
    ("Cr", DVec3::new(4.36967, 2.91651, 1.6549), DVec3::new(5.20655, 4.23131, 3.7547)),
    ("Fe", DVec3::new(2.9114, 2.9497, 2.5845), DVec3::new(3.0893, 2.9318, 2.767)),
    ("Ti", DVec3::new(2.7407, 2.5418, 2.267), DVec3::new(3.8143, 3.4345, 3.0385)),
];

/// The RGB (eta, k) of a named metal (case-sensitive chemical symbol, one of
/// [`METAL_NAMES`]), or `None` for an unknown name.
pub fn metal(name: &str) -> Option<(DVec3, DVec3)> {
    METALS.iter().find(|(n, _, _)| *n == name).map(|&(_, eta, k)| (eta, k))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Reflectance at normal incidence of a conductor.
    fn fresnel_conductor(_cos: f64, eta: DVec3, k: DVec3) -> DVec3 {
        ((eta - 1.0) * (eta - 1.0) + k * k) / ((eta + 1.0) * (eta + 1.0) + k * k)
    }

    #[test]
    fn every_name_resolves_to_a_plausible_metal() {
        for name in METAL_NAMES {
            let (eta, k) = metal(name).unwrap_or_else(|| panic!("{name} missing"));
            assert!(eta.min_element() > 0.0 && k.min_element() > 1.0, "{name}");
            let f0 = fresnel_conductor(1.0, eta, k);
            assert!(f0.min_element() > 0.3 && f0.max_element() < 1.0, "{name}: {f0}");
        }
        assert_eq!(metal("Unobtainium"), None);
        // Gold and copper are warm: red reflects more than blue.
        for name in ["Au", "Cu"] {
            let (eta, k) = metal(name).unwrap();
            let f0 = fresnel_conductor(1.0, eta, k);
            assert!(f0.x > f0.z + 0.2, "{name}: {f0}");
        }
    }
}
