//! The absorbing media a path travels through: the interiors of the objects whose surfaces it
//! crossed inward and not yet outward, innermost last, and Beer-Lambert transmittance along
//! a stretch of one of them.
//!
//! Membership changes only where a path crosses the surface of a material that encloses a
//! medium (a refracting interface: see [`super::scatter::PathMaterial::encloses_medium`]);
//! a thin sheet, alpha coverage and reflection leave it as it is. A camera ray starts inside
//! the solids that hold its origin (a camera under water).

use glam::DVec3;

/// Interiors nested deeper than this are not tracked (the innermost ones are lost).
const MAX_NESTING: usize = 8;

/// The interiors enclosing a point of a path, by material, outermost first.
#[derive(Clone, Copy, Debug, Default)]
pub struct Media {
    materials: [u32; MAX_NESTING],
    len: usize,
}

impl PartialEq for Media {
    /// The same interiors in the same order (whatever the unused slots hold).
    fn eq(&self, other: &Self) -> bool {
        self.materials[..self.len] == other.materials[..other.len]
    }
}

impl Media {
    /// The innermost enclosing interior's material, if any.
    pub fn innermost(&self) -> Option<u32> {
        self.materials[..self.len].last().copied()
    }

    /// The media after crossing a surface of `material`: inward (`entering`) adds its
    /// interior; outward removes the innermost interior of that material (none when the path
    /// never entered it, as a path that started inside).
    pub fn crossed(mut self, material: u32, entering: bool) -> Self {
        if entering {
            if self.len < MAX_NESTING {
                self.materials[self.len] = material;
                self.len += 1;
            }
        } else if let Some(i) = self.materials[..self.len].iter().rposition(|&m| m == material) {
            self.materials.copy_within(i + 1..self.len, i);
            self.len -= 1;
        }
        self
    }
}

/// The share of light (per linear RGB channel) that crosses `distance` scene units of a
/// medium absorbing `absorption` per unit: `exp(-absorption * distance)`. A channel that
/// absorbs nothing keeps everything even over an infinite distance.
pub fn transmittance(absorption: DVec3, distance: f64) -> DVec3 {
    let channel = |a: f64| if a > 0.0 { (-a * distance).exp() } else { 1.0 };
    DVec3::new(channel(absorption.x), channel(absorption.y), channel(absorption.z))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn leaving_removes_the_innermost_interior_of_that_material() {
        let glass_in_water = Media::default().crossed(1, true).crossed(2, true);
        assert_eq!(glass_in_water.innermost(), Some(2));
        assert_eq!(glass_in_water.crossed(2, false).innermost(), Some(1));
        // Overlapping objects: leaving the outer one first keeps the inner one.
        let overlapping = glass_in_water.crossed(1, false);
        assert_eq!(overlapping.innermost(), Some(2));
        assert_eq!(overlapping.crossed(2, false), Media::default());
        // Two nested objects of one material leave in order.
        let nested = Media::default().crossed(3, true).crossed(3, true).crossed(3, false);
        assert_eq!(nested.innermost(), Some(3));
        assert_eq!(nested.crossed(3, false).innermost(), None);
    }

    #[test]
    fn leaving_what_was_never_entered_changes_nothing() {
        let water = Media::default().crossed(1, true);
        assert_eq!(water.crossed(7, false), water);
        assert_eq!(Media::default().crossed(7, false), Media::default());
    }

    #[test]
    fn nesting_beyond_the_limit_keeps_the_outer_interiors() {
        let mut media = Media::default();
        for material in 0..(MAX_NESTING as u32 + 3) {
            media = media.crossed(material, true);
        }
        assert_eq!(media.innermost(), Some(MAX_NESTING as u32 - 1));
    }

    #[test]
    fn transmittance_is_beer_lambert_per_channel() {
        let t = transmittance(DVec3::new(0.0, 0.5, 2.0), 3.0);
        assert_eq!(t.x, 1.0);
        assert!((t.y - (-1.5f64).exp()).abs() < 1e-15);
        assert!((t.z - (-6.0f64).exp()).abs() < 1e-15);
        // Multiplicative over stretches: two halves are one whole.
        let half = transmittance(DVec3::splat(0.7), 1.25);
        assert!((half * half - transmittance(DVec3::splat(0.7), 2.5)).abs().max_element() < 1e-15);
        // An endless stretch: absorbing channels go dark, the others stay lit (no NaN).
        assert_eq!(transmittance(DVec3::new(0.0, 1e-9, 3.0), f64::INFINITY), DVec3::new(1.0, 0.0, 0.0));
    }
}
