//! Lights as the renderer sees them.

use glam::DVec3;

use crate::world::components::{Light, LightKind};

/// A light ready for shading.
#[derive(Clone, Debug)]
pub struct RenderLight {
    /// The light as described in the scene.
    pub kind: LightKind,
    /// Centre.
    pub position: DVec3,
    /// Colour times intensity.
    pub color: DVec3,
    /// Fade distance and power (POV-Ray semantics).
    pub fade_distance: f64,
    /// See `fade_distance`.
    pub fade_power: f64,
    /// No shadows, no highlights.
    pub shadowless: bool,
    /// Unit axis for spot and parallel lights (from the light toward point_at).
    pub axis: DVec3,
    /// Spot parameters: cos(radius), cos(falloff), tightness. `None` for non-spot lights.
    pub spot: Option<(f64, f64, f64)>,
    /// Area grid: axis vectors and sample counts, POV-Ray flags.
    pub area: Option<AreaGrid>,
}

/// The grid of an area light.
#[derive(Clone, Debug)]
pub struct AreaGrid {
    /// First edge.
    pub axis1: DVec3,
    /// Second edge.
    pub axis2: DVec3,
    /// Samples along axis1.
    pub size1: u32,
    /// Samples along axis2.
    pub size2: u32,
    /// Levels always subdivided.
    pub adaptive: u32,
    /// Jittered sample positions.
    pub jitter: bool,
    /// Grid mapped to a disc.
    pub circular: bool,
    /// Grid turned toward each shaded point.
    pub orient: bool,
    /// The weight of each grid sample (row-major, `size1` per row) when `adaptive` is deep
    /// enough that POV-Ray's recursive average always subdivides down to neighbouring
    /// samples: the average is then this fixed weighted sum. `None` when the recursion
    /// depends on the samples.
    pub fixed_weights: Option<Vec<f64>>,
}

impl AreaGrid {
    /// The sample weights of POV-Ray's hierarchical average when it never depends on the
    /// samples, or `None`. The recursion mirrors `classic::block`: a block whose corners
    /// are further apart than neighbours splits into four at its midpoints (sharing the
    /// middle row and column when the span is even), and a block that no longer splits
    /// gives each of its four corners a quarter of its weight.
    pub fn fixed_weights(size1: u32, size2: u32, adaptive: u32) -> Option<Vec<f64>> {
        fn split(
            weights: &mut [f64],
            n1: usize,
            (u1, v1, u2, v2): (usize, usize, usize, usize),
            level: u32,
            adaptive: u32,
            weight: f64,
        ) -> bool {
            let large = u2 - u1 > 1 || v2 - v1 > 1;
            if !large {
                for (u, v) in [(u1, v1), (u2, v1), (u1, v2), (u2, v2)] {
                    weights[v * n1 + u] += 0.25 * weight;
                }
                return true;
            }
            if level >= adaptive {
                return false;
            }
            let (lo_u, lo_v) = ((u1 + u2) / 2, (v1 + v2) / 2);
            let (hi_u, hi_v) = ((u1 + u2).div_ceil(2), (v1 + v2).div_ceil(2));
            let quarter = 0.25 * weight;
            [(u1, v1, lo_u, lo_v), (hi_u, v1, u2, lo_v), (u1, hi_v, lo_u, v2), (hi_u, hi_v, u2, v2)]
                .into_iter()
                .all(|block| split(weights, n1, block, level + 1, adaptive, quarter))
        }
        let (n1, n2) = (size1.max(1) as usize, size2.max(1) as usize);
        let mut weights = vec![0.0; n1 * n2];
        split(&mut weights, n1, (0, 0, n1 - 1, n2 - 1), 0, adaptive, 1.0).then_some(weights)
    }
}

pub(crate) fn render_light(light: &Light) -> RenderLight {
    let position = DVec3::from_array(light.position);
    let point_at = DVec3::from_array(light.point_at);
    let axis = (point_at - position).normalize_or(DVec3::NEG_Y);
    let is_spot = light.kind == LightKind::Spot || (light.kind == LightKind::Area && light.spot);
    RenderLight {
        kind: light.kind,
        position,
        color: light.color.0 * light.intensity,
        fade_distance: light.fade_distance,
        fade_power: light.fade_power,
        shadowless: light.shadowless,
        axis,
        spot: is_spot.then(|| (light.radius.to_radians().cos(), light.falloff.to_radians().cos(), light.tightness)),
        area: (light.kind == LightKind::Area).then(|| AreaGrid {
            axis1: DVec3::from_array(light.axis1),
            axis2: DVec3::from_array(light.axis2),
            size1: light.size1,
            size2: light.size2,
            adaptive: light.adaptive,
            jitter: light.jitter,
            // POV-Ray makes an oriented area light circular.
            circular: light.circular || light.orient,
            orient: light.orient,
            fixed_weights: AreaGrid::fixed_weights(light.size1, light.size2, light.adaptive),
        }),
    }
}
