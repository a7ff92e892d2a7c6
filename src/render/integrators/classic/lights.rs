//! The classic integrator's view of the lights: each light as the POV-Ray `light_source` it
//! renders as. A `[[light]]` is its physical light read with POV-Ray's conventions (the
//! colour times intensity reaches every distance unchanged unless faded, and POV-Ray's
//! unnormalised diffuse has no 1/pi) plus its POV-Ray parameters (fade, tightness,
//! shadowless); a light imported from a glTF file renders as the POV-Ray light source
//! [`pov_equivalent`] makes of its photometric value, which `export pov` writes as well.

use std::f64::consts::PI;

use glam::DVec3;

use super::pow;
use crate::render::lights::{AreaGrid, LightOrigin, LightSource, PovParams, RenderLight};
use crate::world::components::{Light, LightKind, PhotometricLight, PunctualKind};

/// Imported point and spot lights follow `I / (d^2 + LIGHT_CORE^2)` with d in file units
/// (metres): an inverse square law softened within a millimetre of the light.
pub const LIGHT_CORE: f64 = 1e-3;

/// Imported directional lights become parallel lights whose `position` lies this many file
/// units (metres) back along the light's direction from their node: POV-Ray's parallel lights
/// cast shadows only from objects in front of `position`.
pub const SUN_DISTANCE: f64 = 1e6;

/// POV-Ray light value per photometric unit: a light of `E` lux (or `I / d^2` from a point or
/// spot light) gets a POV-Ray intensity of `E / pi`, so a surface with Prism's `diffuse` d and
/// colour c shows `c d E / pi`, the radiance of a Lambertian surface of albedo `c d` (the
/// convention of physically based real-time renderers such as three.js).
pub const PHOTOMETRIC_SCALE: f64 = 1.0 / PI;

/// A light as POV-Ray shades it.
#[derive(Clone, Debug)]
pub(super) struct PovLight {
    /// A parallel light: `l` is `-axis` everywhere, and shadow rays end at the plane through
    /// `position` facing the light.
    pub parallel: bool,
    /// POV-Ray's `position` (an area light's centre).
    pub position: DVec3,
    /// POV-Ray's light colour (colour times intensity): what reaches a point at any distance
    /// before the cone and fade.
    pub color: DVec3,
    /// POV-Ray's `fade_distance`.
    pub fade_distance: f64,
    /// POV-Ray's `fade_power`.
    pub fade_power: f64,
    /// No shadows, no highlights.
    pub shadowless: bool,
    /// Unit axis of spot and parallel lights, the way the light shines.
    pub axis: DVec3,
    /// Spot parameters: cos(radius), cos(falloff), tightness. `None` for non-spot lights.
    pub spot: Option<(f64, f64, f64)>,
    /// The grid of an area light.
    pub area: Option<AreaGrid>,
}

impl PovLight {
    /// How the classic integrator renders `light`.
    pub(super) fn new(light: &RenderLight) -> Self {
        match &light.origin {
            LightOrigin::Scene(pov) => Self::from_physical(&light.source, pov),
            LightOrigin::Gltf(imported) => {
                let equivalent = RenderLight::from_scene(&pov_equivalent(imported));
                Self::new(&equivalent)
            }
        }
    }

    fn from_physical(source: &LightSource, pov: &PovParams) -> Self {
        let light = |position, color| PovLight {
            parallel: false,
            position,
            color,
            fade_distance: pov.fade_distance,
            fade_power: pov.fade_power,
            shadowless: pov.shadowless,
            axis: DVec3::NEG_Y,
            spot: None,
            area: None,
        };
        match source {
            LightSource::Point(p) => light(p.position, p.intensity),
            LightSource::Spot(s) => PovLight {
                axis: s.cone.axis,
                spot: Some((s.cone.cos_inner, s.cone.cos_outer, pov.tightness)),
                ..light(s.position, s.intensity)
            },
            LightSource::Directional(d) => {
                PovLight { parallel: true, axis: d.direction, ..light(pov.position, d.irradiance) }
            }
            LightSource::AreaGrid(a) => PovLight {
                axis: a.cone.map_or(DVec3::NEG_Y, |c| c.axis),
                spot: a.cone.map(|c| (c.cos_inner, c.cos_outer, pov.tightness)),
                area: Some(a.grid.clone()),
                ..light(a.centre, a.intensity)
            },
        }
    }
}

/// The `[[light]]` (a POV-Ray light source) that renders like the imported `light`: POV-Ray's
/// lights do not fall off with distance, so point and spot lights get `fade_power = 2` with a
/// tiny `fade_distance`, which makes POV-Ray's fade `2 / (1 + (d / fade_distance)^2)` times
/// `I / (2 LIGHT_CORE^2)` the inverse square law `I / (LIGHT_CORE^2 + (d / s)^2)` in file
/// metres (s world units per metre), all scaled by [`PHOTOMETRIC_SCALE`]; a directional
/// light is a parallel light [`SUN_DISTANCE`] file metres away.
pub fn pov_equivalent(light: &PhotometricLight) -> Light {
    let position = light.position;
    let direction = light.direction;
    let scale = light.world_units_per_metre;
    let base = Light { color: light.color, position: position.to_array(), ..Light::default() };
    let inverse_square = Light {
        intensity: light.intensity * PHOTOMETRIC_SCALE / (2.0 * LIGHT_CORE * LIGHT_CORE),
        fade_distance: LIGHT_CORE * scale,
        fade_power: 2.0,
        ..base.clone()
    };
    match light.kind {
        PunctualKind::Point => Light { kind: LightKind::Point, ..inverse_square },
        PunctualKind::Spot { inner_cone_angle, outer_cone_angle } => Light {
            kind: LightKind::Spot,
            point_at: (position + direction).to_array(),
            radius: inner_cone_angle.to_degrees(),
            falloff: outer_cone_angle.to_degrees(),
            tightness: 0.0,
            ..inverse_square
        },
        PunctualKind::Directional => Light {
            kind: LightKind::Parallel,
            position: (position - direction * SUN_DISTANCE * scale).to_array(),
            point_at: position.to_array(),
            intensity: light.intensity * PHOTOMETRIC_SCALE,
            ..base
        },
    }
}

/// POV-Ray's `EPSILON`: a `fade_distance` no farther than this from 0 means no fade.
const FADE_EPSILON: f64 = 1e-10;

/// POV-Ray's `cubic_spline(low, high, pos)`: 0 below `low`, 1 from `high` on, and the
/// smoothstep `(3 - 2p) p^2` of `p = (pos - low) / (high - low)` between. The two bounds are
/// tested in this order, so with `low > high` (a spot whose radius exceeds its falloff) the
/// result is 0 below `low` and 1 from it on: a hard edge, never outside [0, 1].
fn cubic_spline(low: f64, high: f64, pos: f64) -> f64 {
    if pos < low {
        return 0.0;
    }
    if pos >= high {
        return 1.0;
    }
    let p = (pos - low) / (high - low);
    (3.0 - 2.0 * p) * p * p
}

/// Spotlight cone and distance fade, as POV-Ray computes them (`Attenuate_Light`).
pub(super) fn attenuation(light: &PovLight, l: DVec3, distance: f64) -> f64 {
    let mut a = 1.0;
    if let Some((cos_radius, cos_falloff, tightness)) = light.spot {
        let cos_theta = light.axis.dot(-l);
        if cos_theta <= 0.0 {
            return 0.0;
        }
        a = if tightness != 0.0 { pow(cos_theta, tightness) } else { 1.0 };
        // A radius of 90 degrees or more (cosine <= 0) turns the cone off in POV-Ray.
        if cos_radius > 0.0 && cos_theta < cos_radius {
            a *= cubic_spline(cos_falloff, cos_radius, cos_theta);
        }
    }
    if light.fade_power > 0.0 && light.fade_distance.abs() > FADE_EPSILON {
        a *= 2.0 / (1.0 + pow(distance / light.fade_distance, light.fade_power));
    }
    a
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::color::Rgb;

    fn point_light(fade_distance: f64, fade_power: f64) -> PovLight {
        PovLight {
            parallel: false,
            position: DVec3::ZERO,
            color: DVec3::ONE,
            fade_distance,
            fade_power,
            shadowless: false,
            axis: DVec3::NEG_Y,
            spot: None,
            area: None,
        }
    }

    #[test]
    fn spotlight_cone() {
        // radius 10, falloff 20, tightness 10, 15 degrees off axis: cos^10 times the
        // smoothstep (3 - 2p) p^2 of p = (cos15 - cos20) / (cos10 - cos20).
        let light = PovLight {
            spot: Some((10f64.to_radians().cos(), 20f64.to_radians().cos(), 10.0)),
            ..point_light(0.0, 0.0)
        };
        let dir = DVec3::new(15f64.to_radians().sin(), -15f64.to_radians().cos(), 0.0);
        let (c15, c10, c20) = (15f64.to_radians().cos(), 10f64.to_radians().cos(), 20f64.to_radians().cos());
        let p = (c15 - c20) / (c10 - c20);
        let expected = c15.powi(10) * (3.0 - 2.0 * p) * p * p;
        assert!((attenuation(&light, -dir, 1.0) - expected).abs() < 1e-12);
        assert_eq!(attenuation(&light, DVec3::new(0.0, -1.0, 0.0), 1.0), 0.0, "behind the spot");
        assert!((attenuation(&light, DVec3::Y, 1.0) - 1.0).abs() < 1e-12, "on the axis");
    }

    /// A spot light with POV-Ray's radius and falloff in degrees, no tightness.
    fn spot(radius: f64, falloff: f64) -> PovLight {
        PovLight { spot: Some((radius.to_radians().cos(), falloff.to_radians().cos(), 0.0)), ..point_light(0.0, 0.0) }
    }

    /// The attenuation of `light` (shining down -y) toward a point `degrees` off its axis.
    fn off_axis(light: &PovLight, degrees: f64) -> f64 {
        let (s, c) = (degrees.to_radians().sin(), degrees.to_radians().cos());
        attenuation(light, -DVec3::new(s, -c, 0.0), 1.0)
    }

    #[test]
    fn radius_beyond_falloff_is_a_hard_edge_at_radius() {
        // POV-Ray: cubic_spline(cos 20, cos 30, cos) is 0 below cos 20 and 1 from it on, but it
        // is only consulted outside the radius (cos < cos 30): full inside 30 degrees, dark out.
        let light = spot(30.0, 20.0);
        for degrees in [0.0, 15.0, 25.0, 29.9] {
            assert_eq!(off_axis(&light, degrees), 1.0, "{degrees} degrees");
        }
        for degrees in [30.1, 40.0, 60.0, 89.0] {
            assert_eq!(off_axis(&light, degrees), 0.0, "{degrees} degrees");
        }
        // Falloff 0 likewise: a hard cone of the radius.
        let light = spot(10.0, 0.0);
        assert_eq!((off_axis(&light, 9.0), off_axis(&light, 11.0)), (1.0, 0.0));
    }

    #[test]
    fn degenerate_cones_follow_pov_ray() {
        // radius == falloff: a hard edge, no division by zero.
        let light = spot(20.0, 20.0);
        assert_eq!((off_axis(&light, 19.0), off_axis(&light, 21.0)), (1.0, 0.0));
        // A radius of 90 degrees or more turns the cone off: the whole front half-space.
        let light = spot(100.0, 120.0);
        assert_eq!((off_axis(&light, 10.0), off_axis(&light, 85.0), off_axis(&light, 95.0)), (1.0, 1.0, 0.0));
        // radius 0 (cosine 1): everywhere off the axis is in the falloff band.
        let light = spot(0.0, 40.0);
        let c = 20f64.to_radians().cos();
        let p = (c - 40f64.to_radians().cos()) / (1.0 - 40f64.to_radians().cos());
        assert!((off_axis(&light, 20.0) - (3.0 - 2.0 * p) * p * p).abs() < 1e-12);
        // Negative tightness brightens away from the axis: pow(cos, -2).
        let light =
            PovLight { spot: Some((1.0f64.to_radians().cos(), 80f64.to_radians().cos(), -2.0)), ..spot(0.0, 0.0) };
        let expected = c.powi(-2) * {
            let (cr, cf) = (1f64.to_radians().cos(), 80f64.to_radians().cos());
            let p = (c - cf) / (cr - cf);
            (3.0 - 2.0 * p) * p * p
        };
        assert!((off_axis(&light, 20.0) - expected).abs() < 1e-12);
    }

    #[test]
    fn fade_needs_a_positive_power_and_a_distance_beyond_epsilon() {
        // POV-Ray fades only when fade_power > 0 and |fade_distance| > EPSILON (1e-10).
        for (distance, power) in [(5.0, 0.0), (5.0, -1.0), (1e-11, 2.0), (0.0, 2.0)] {
            assert_eq!(attenuation(&point_light(distance, power), DVec3::X, 10.0), 1.0, "{distance} {power}");
        }
        // A negative distance with a whole power fades like its magnitude.
        assert!((attenuation(&point_light(-5.0, 2.0), DVec3::X, 10.0) - 0.4).abs() < 1e-12);
    }

    #[test]
    fn fade_has_povs_factor_two() {
        let light = point_light(5.0, 2.0);
        assert!((attenuation(&light, DVec3::X, 10.0) - 0.4).abs() < 1e-12);
        assert!((attenuation(&light, DVec3::X, 5.0) - 1.0).abs() < 1e-12);
    }

    fn imported(kind: PunctualKind, world_units_per_metre: f64) -> PhotometricLight {
        PhotometricLight {
            kind,
            position: DVec3::new(1.0, 2.0, 3.0),
            direction: DVec3::NEG_Y,
            color: Rgb::new(1.0, 0.5, 0.25),
            intensity: 10.0,
            world_units_per_metre,
        }
    }

    /// What the classic integrator shows of `light` at world distance `d` on its axis.
    fn value_at(light: &PhotometricLight, d: f64) -> DVec3 {
        let pov = PovLight::new(&RenderLight::from_photometric(light));
        pov.color * attenuation(&pov, -pov.axis, d)
    }

    #[test]
    fn imported_point_and_spot_lights_fall_off_with_the_inverse_square_in_file_metres() {
        for kind in [PunctualKind::Point, PunctualKind::Spot { inner_cone_angle: 0.2, outer_cone_angle: 0.4 }] {
            let light = imported(kind, 1.0);
            for d in [0.5, 2.0, 10.0] {
                let expected = DVec3::new(1.0, 0.5, 0.25) * 10.0 / PI / (d * d);
                let got = value_at(&light, d);
                assert!((got / expected - DVec3::ONE).abs().max_element() < 1e-5, "{kind:?} at {d}: {got}");
            }
            // A model scaled by 100: the light 100 world units away lights as it did 1 metre away.
            let scaled = imported(kind, 100.0);
            assert!((value_at(&scaled, 100.0) / value_at(&light, 1.0) - DVec3::ONE).abs().max_element() < 1e-9);
        }
    }

    #[test]
    fn imported_lights_are_the_pov_ray_lights_they_were_imported_as() {
        let spot = pov_equivalent(&imported(PunctualKind::Spot { inner_cone_angle: 0.2, outer_cone_angle: 0.4 }, 1.0));
        assert_eq!(spot.kind, LightKind::Spot);
        assert_eq!(spot.position, [1.0, 2.0, 3.0]);
        assert_eq!(spot.point_at, [1.0, 1.0, 3.0]);
        assert!(
            (spot.radius - 0.2f64.to_degrees()).abs() < 1e-12 && (spot.falloff - 0.4f64.to_degrees()).abs() < 1e-12
        );
        assert_eq!((spot.fade_power, spot.fade_distance, spot.tightness), (2.0, LIGHT_CORE, 0.0));

        let sun = pov_equivalent(&imported(PunctualKind::Directional, 2.0));
        assert_eq!(sun.kind, LightKind::Parallel);
        assert_eq!((sun.fade_power, sun.fade_distance), (0.0, 0.0));
        assert!((sun.intensity - 10.0 / PI).abs() < 1e-12);
        let from = DVec3::from_array(sun.position);
        assert!((from - DVec3::new(1.0, 2.0 + 2.0 * SUN_DISTANCE, 3.0)).length() < 1e-6, "{from}");
        assert_eq!(sun.point_at, [1.0, 2.0, 3.0]);
        let pov = PovLight::new(&RenderLight::from_photometric(&imported(PunctualKind::Directional, 2.0)));
        assert!(pov.parallel && (pov.axis - DVec3::NEG_Y).length() < 1e-12);
        assert_eq!(pov.color, DVec3::new(1.0, 0.5, 0.25) * (10.0 * PHOTOMETRIC_SCALE));
    }
}
