//! Lights as the renderer sees them, in physical units: point and spot lights (radiant
//! intensity, W/sr), directional lights (irradiance, W/m^2), POV-Ray's area grid, the
//! emissive primitives (area emitters, each naming its primitive) and the environment
//! (radiance, W/(m^2 sr)).
//!
//! Colours are linear RGB and Prism's radiometric unit is a "watt" per RGB channel: the unit
//! its images are in, with no spectrum behind it. The path integrator reads the physical
//! fields; the classic integrator renders each light as the POV-Ray `light_source` it came
//! from, so every light also records its origin: a `[[light]]`'s POV-Ray parameters that have
//! no physical counterpart ([`PovParams`]), or an imported glTF light's photometric value
//! ([`PhotometricLight`]), converted here with [`WATTS_PER_LUMEN`].

use glam::DVec3;

use crate::accel::primitive::Primitive;
use crate::material::Material;
use crate::world::components::{Light, LightKind, PhotometricLight, PunctualKind};

/// Prism's radiometric unit per photometric unit: a glTF light of 1 cd (lm/sr) is 1 W/sr of
/// Prism's RGB, and 1 lx (lm/m^2) is 1 W/m^2.
///
/// Not 1/683 (the luminous efficacy of 555 nm light): Prism's RGB has no wavelength to apply
/// it to, and glTF viewers (three.js, Babylon.js, model-viewer) take the file's number as the
/// light's strength in their RGB units, so at 1/683 a 10 cd lamp would light a scene 683
/// times darker than those viewers show it. Anything that writes Prism's lights for another
/// renderer in radiometric units (a future Mitsuba exporter) must use this same constant.
pub const WATTS_PER_LUMEN: f64 = 1.0;

/// A spot cone around an axis: full intensity within the inner half-angle, none beyond the
/// outer one, and between them a smoothstep `(3 - 2p) p^2` in
/// `p = (cos - cos_outer) / (cos_inner - cos_outer)` (POV-Ray's profile, and pbrt's).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpotCone {
    /// Unit vector along which the spot shines.
    pub axis: DVec3,
    /// Cosine of the half-angle of full intensity.
    pub cos_inner: f64,
    /// Cosine of the half-angle where the intensity reaches zero.
    pub cos_outer: f64,
}

/// A point that shines equally in all directions.
#[derive(Clone, Debug, PartialEq)]
pub struct PointLight {
    /// Where the light is (world space).
    pub position: DVec3,
    /// Radiant intensity in W/sr (linear RGB): a surface facing the light at world distance
    /// `d` receives an irradiance of `intensity / d^2` W/m^2.
    pub intensity: DVec3,
}

/// A point light restricted to a cone.
#[derive(Clone, Debug, PartialEq)]
pub struct SpotLight {
    /// Where the light is (world space).
    pub position: DVec3,
    /// Radiant intensity in W/sr (linear RGB) along the axis and within the inner cone.
    pub intensity: DVec3,
    /// The cone.
    pub cone: SpotCone,
}

/// Parallel light from infinitely far away (a sun).
#[derive(Clone, Debug, PartialEq)]
pub struct DirectionalLight {
    /// Unit vector along which the light travels.
    pub direction: DVec3,
    /// Irradiance in W/m^2 (linear RGB) on a surface facing the light.
    pub irradiance: DVec3,
}

/// POV-Ray's area light: a rectangle (or, `circular`, a disc) of `size1` x `size2` point
/// emitters around the light's centre, which soften its shadows.
///
/// Point (u, v) of the grid lies at `centre + axis1 * (u / (size1 - 1) - 1/2) +
/// axis2 * (v / (size2 - 1) - 1/2)` (the centre itself along an axis with one point), moved
/// by up to half a step along each axis when `jitter` is set (a pure function of the pixel
/// sample), and with `circular` mapped from the square onto the disc it encloses (POV-Ray's
/// mapping, offset by 0.001 from the centre). `orient` turns the grid, for each shaded
/// point, to lie across the direction toward it, both axes as long as `axis1`. The
/// shadow is POV-Ray's hierarchical average over the points, which splits the grid
/// `adaptive` levels deep before it looks at the samples.
#[derive(Clone, Debug, PartialEq)]
pub struct AreaGrid {
    /// First edge of the rectangle (world units), centred on the light.
    pub axis1: DVec3,
    /// Second edge of the rectangle (world units), centred on the light.
    pub axis2: DVec3,
    /// Points along `axis1`.
    pub size1: u32,
    /// Points along `axis2`.
    pub size2: u32,
    /// Levels always subdivided (POV-Ray's `adaptive`).
    pub adaptive: u32,
    /// Jittered point positions.
    pub jitter: bool,
    /// Grid mapped to a disc (set for every oriented grid, as POV-Ray does).
    pub circular: bool,
    /// Grid turned toward each shaded point.
    pub orient: bool,
    /// POV-Ray's `area_illumination`: the classic integrator shades with every point's own
    /// direction and distance, not the centre's.
    pub area_illumination: bool,
    /// The weight of each grid sample (row-major, `size1` per row) when `adaptive` is deep
    /// enough that POV-Ray's recursive average always subdivides down to neighbouring
    /// samples: the average is then this fixed weighted sum. `None` when the recursion
    /// depends on the samples.
    pub fixed_weights: Option<Vec<f64>>,
}

impl AreaGrid {
    /// The sample weights of POV-Ray's hierarchical average when it never depends on the
    /// samples, or `None`. The recursion mirrors the classic integrator's: a block whose
    /// corners are further apart than neighbours splits into four at its midpoints (sharing
    /// the middle row and column when the span is even), and a block that no longer splits
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

/// A POV-Ray area light: its grid of point emitters, optionally restricted to a spot cone.
#[derive(Clone, Debug, PartialEq)]
pub struct AreaGridLight {
    /// The centre of the grid (world space).
    pub centre: DVec3,
    /// Radiant intensity of the whole grid in W/sr (linear RGB); its points share it.
    pub intensity: DVec3,
    /// Where the points are.
    pub grid: AreaGrid,
    /// The cone every point shines into (POV-Ray's `spotlight` area light), if any.
    pub cone: Option<SpotCone>,
}

/// A light source of the scene, in physical units.
#[derive(Clone, Debug, PartialEq)]
pub enum LightSource {
    /// A point light.
    Point(PointLight),
    /// A spot light.
    Spot(SpotLight),
    /// A directional light.
    Directional(DirectionalLight),
    /// A POV-Ray area light.
    AreaGrid(AreaGridLight),
}

/// The parameters of a `[[light]]` that POV-Ray has and physics has not. Only the classic
/// integrator reads them.
#[derive(Clone, Debug, PartialEq)]
pub struct PovParams {
    /// POV-Ray's `position`. For a parallel light, the point it comes from, which the
    /// physical light has not: POV-Ray ends its shadow rays at the plane through it. For the
    /// other kinds it is the physical light's position.
    pub position: DVec3,
    /// POV-Ray's `fade_distance` (world units): the light fades by
    /// `2 / (1 + (d / fade_distance)^fade_power)` at distance `d`. 0 = no fade.
    pub fade_distance: f64,
    /// POV-Ray's `fade_power`; 0 = no fade.
    pub fade_power: f64,
    /// POV-Ray's spot `tightness`: the cone's intensity is multiplied by `cos^tightness`.
    pub tightness: f64,
    /// No shadows and no highlights.
    pub shadowless: bool,
}

/// Where a light came from, with what the classic integrator needs to render it as before.
#[derive(Clone, Debug, PartialEq)]
pub enum LightOrigin {
    /// A `[[light]]` of the scene.
    Scene(PovParams),
    /// A light imported from a glTF file, with its photometric value.
    Gltf(PhotometricLight),
}

/// One light of the render scene.
#[derive(Clone, Debug, PartialEq)]
pub struct RenderLight {
    /// What it emits, in physical units.
    pub source: LightSource,
    /// Where it came from.
    pub origin: LightOrigin,
}

impl RenderLight {
    /// A `[[light]]` of the scene: `color * intensity` is the radiant intensity in W/sr of a
    /// point, spot or area light (an area light's whole grid), and the irradiance in W/m^2
    /// of a parallel light; spot angles are in degrees; the light shines from `position`
    /// toward `point_at`.
    pub fn from_scene(light: &Light) -> Self {
        let position = DVec3::from_array(light.position);
        let point_at = DVec3::from_array(light.point_at);
        let axis = (point_at - position).normalize_or(DVec3::NEG_Y);
        let power = light.color.0 * light.intensity;
        let cone =
            SpotCone { axis, cos_inner: light.radius.to_radians().cos(), cos_outer: light.falloff.to_radians().cos() };
        let source = match light.kind {
            LightKind::Point => LightSource::Point(PointLight { position, intensity: power }),
            LightKind::Spot => LightSource::Spot(SpotLight { position, intensity: power, cone }),
            LightKind::Parallel => LightSource::Directional(DirectionalLight { direction: axis, irradiance: power }),
            LightKind::Area => LightSource::AreaGrid(AreaGridLight {
                centre: position,
                intensity: power,
                grid: AreaGrid {
                    axis1: DVec3::from_array(light.axis1),
                    axis2: DVec3::from_array(light.axis2),
                    size1: light.size1,
                    size2: light.size2,
                    adaptive: light.adaptive,
                    jitter: light.jitter,
                    // POV-Ray makes an oriented area light circular.
                    circular: light.circular || light.orient,
                    orient: light.orient,
                    area_illumination: light.area_illumination,
                    fixed_weights: AreaGrid::fixed_weights(light.size1, light.size2, light.adaptive),
                },
                cone: light.spot.then_some(cone),
            }),
        };
        let pov = PovParams {
            position,
            fade_distance: light.fade_distance,
            fade_power: light.fade_power,
            tightness: light.tightness,
            shadowless: light.shadowless,
        };
        Self { source, origin: LightOrigin::Scene(pov) }
    }

    /// A light imported from a glTF file: `I` candela become `I * WATTS_PER_LUMEN * s^2`
    /// W/sr, with `s` the world units per file metre (so that the inverse-square law in world
    /// units is glTF's in the file's metres), and `E` lux become `E * WATTS_PER_LUMEN` W/m^2.
    pub fn from_photometric(light: &PhotometricLight) -> Self {
        let s = light.world_units_per_metre;
        let intensity = light.color.0 * (light.intensity * WATTS_PER_LUMEN * s * s);
        let position = light.position;
        let source = match light.kind {
            PunctualKind::Point => LightSource::Point(PointLight { position, intensity }),
            PunctualKind::Spot { inner_cone_angle, outer_cone_angle } => LightSource::Spot(SpotLight {
                position,
                intensity,
                cone: SpotCone {
                    axis: light.direction,
                    cos_inner: inner_cone_angle.cos(),
                    cos_outer: outer_cone_angle.cos(),
                },
            }),
            PunctualKind::Directional => LightSource::Directional(DirectionalLight {
                direction: light.direction,
                irradiance: light.color.0 * (light.intensity * WATTS_PER_LUMEN),
            }),
        };
        Self { source, origin: LightOrigin::Gltf(light.clone()) }
    }
}

/// A primitive whose material emits: a light with the primitive's shape.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct AreaEmitter {
    /// Index into the render scene's primitives.
    pub primitive: u32,
}

/// What surrounds the scene, as a light.
#[derive(Clone, Debug, PartialEq)]
pub struct EnvironmentLight {
    /// Radiance in W/(m^2 sr) (linear RGB) arriving from every direction: `[world]
    /// background` (the classic integrator's background; the path integrator's environment
    /// when there is no map).
    pub radiance: DVec3,
    /// The environment map, which replaces `radiance` for the path integrator.
    pub map: Option<EnvironmentMapLight>,
}

/// An HDR environment map placed around the scene.
#[derive(Clone, Debug)]
pub struct EnvironmentMapLight {
    /// The image and its sampling distribution.
    pub map: std::sync::Arc<crate::texture::environment::EnvironmentMap>,
    /// Multiplies the image's radiance.
    pub intensity: f64,
    /// World directions from the map's local frame (a rotation about +y).
    pub world_from_map: glam::DMat3,
}

impl PartialEq for EnvironmentMapLight {
    fn eq(&self, other: &Self) -> bool {
        std::sync::Arc::ptr_eq(&self.map, &other.map)
            && self.intensity == other.intensity
            && self.world_from_map == other.world_from_map
    }
}

impl EnvironmentMapLight {
    /// The light of `[world] environment`, if its image was loaded.
    pub fn new(spec: &crate::world::components::EnvironmentMapRef) -> Option<Self> {
        Some(Self {
            map: spec.map.clone()?,
            intensity: spec.intensity,
            world_from_map: glam::DMat3::from_rotation_y(spec.rotate.to_radians()),
        })
    }

    /// Radiance W/(m^2 sr) arriving from world direction `direction` (unit).
    pub fn radiance(&self, direction: DVec3) -> DVec3 {
        self.map.eval(self.world_from_map.transpose() * direction) * self.intensity
    }

    /// Solid-angle density of [`EnvironmentMapLight::sample`] at world direction `direction`.
    pub fn pdf(&self, direction: DVec3) -> f64 {
        self.map.pdf(self.world_from_map.transpose() * direction)
    }

    /// A world direction by importance (luminance), its radiance and solid-angle density.
    pub fn sample(&self, u: glam::DVec2) -> (DVec3, DVec3, f64) {
        let s = self.map.sample(u);
        (self.world_from_map * s.direction, s.radiance * self.intensity, s.pdf)
    }
}

/// Every light of a render scene.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneLights {
    /// The `[[light]]`s and imported lights, in load order.
    pub sources: Vec<RenderLight>,
    /// The emissive primitives, in primitive order.
    pub area_emitters: Vec<AreaEmitter>,
    /// For each primitive, the index of its entry in `area_emitters`, if it emits.
    pub emitter_of_primitive: Vec<Option<u32>>,
    /// The environment.
    pub environment: EnvironmentLight,
}

impl SceneLights {
    /// The lights of a scene: `sources`, an area emitter for every primitive whose material
    /// emits ([`emits`]), and `background` (linear RGB radiance) as the environment.
    pub fn new(
        sources: Vec<RenderLight>,
        primitives: &[Primitive],
        materials: &[Material],
        environment: &crate::world::components::Environment,
    ) -> Self {
        let mut area_emitters = Vec::new();
        let emitter_of_primitive = (0..primitives.len() as u32)
            .map(|primitive| {
                emitting_materials(&primitives[primitive as usize], materials).next().is_some().then(|| {
                    area_emitters.push(AreaEmitter { primitive });
                    area_emitters.len() as u32 - 1
                })
            })
            .collect();
        let environment = EnvironmentLight {
            radiance: environment.background.0,
            map: environment.environment.as_ref().and_then(EnvironmentMapLight::new),
        };
        Self { sources, area_emitters, emitter_of_primitive, environment }
    }

    /// The area emitter of `primitive`, if its material emits.
    pub fn emitter_of(&self, primitive: u32) -> Option<&AreaEmitter> {
        let index = (*self.emitter_of_primitive.get(primitive as usize)?)?;
        Some(&self.area_emitters[index as usize])
    }
}

/// The materials of `primitive` that emit light ([`emits`]): its own, or for a CSG group
/// its leaves' (each its own or the group's it inherits; they may repeat).
pub fn emitting_materials<'m>(primitive: &Primitive, materials: &'m [Material]) -> impl Iterator<Item = &'m Material> {
    let own = std::slice::from_ref(&primitive.material);
    primitive.leaf_materials.as_deref().unwrap_or(own).iter().map(|&m| &materials[m as usize]).filter(|m| emits(m))
}

/// True when a surface of this material emits light ([`Emission::can_emit`]). The classic
/// integrator shades emission from the material at each hit and does not sample emitters;
/// this only decides which primitives are area emitters.
///
/// [`Emission::can_emit`]: crate::material::Emission::can_emit
pub fn emits(material: &Material) -> bool {
    material.emission.can_emit()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::load::{Embedded, load_from};

    #[test]
    fn primitives_reach_their_emitters_and_back() {
        const SCENE: Embedded = Embedded(&[(
            "s.toml",
            "[materials.lamp]\nemission = 2.0\n\
             [[object]]\nshape = \"sphere\"\nradius = 1.0\n\
             [[object]]\nshape = \"sphere\"\nradius = 1.0\nmaterial = \"lamp\"\n\
             [[object]]\nshape = \"sphere\"\nradius = 1.0\nmaterial = { pbr = { emissive = [0.0, 0.5, 0.0] } }\n\
             [[object]]\nshape = \"sphere\"\nradius = 1.0\nmaterial = { pbr = { metallic = 0.0 } }\n\
             [[object]]\nshape = \"sphere\"\nradius = 1.0\nmaterial = \"lamp\"\n",
        )]);
        let mut scene = load_from(&SCENE, std::path::Path::new("s.toml"), &crate::plugins::registry()).unwrap();
        let scene = crate::prepare(&mut scene).unwrap();
        let lights = &scene.lights;
        assert_eq!(lights.emitter_of_primitive.len(), scene.primitives.len());
        let emitting: Vec<u32> = lights.area_emitters.iter().map(|e| e.primitive).collect();
        assert_eq!(emitting, [1, 2, 4]);
        for (primitive, emitter) in lights.emitter_of_primitive.iter().enumerate() {
            let material = &scene.materials[scene.primitives[primitive].material as usize];
            assert_eq!(emitter.is_some(), emits(material), "primitive {primitive}");
            if let Some(e) = emitter {
                assert_eq!(lights.area_emitters[*e as usize].primitive, primitive as u32);
                assert_eq!(lights.emitter_of(primitive as u32), Some(&lights.area_emitters[*e as usize]));
            }
        }
        for (index, emitter) in lights.area_emitters.iter().enumerate() {
            assert_eq!(lights.emitter_of_primitive[emitter.primitive as usize], Some(index as u32));
        }
        assert_eq!(lights.emitter_of(99), None);
    }

    #[test]
    fn a_csg_group_emits_when_a_leaf_material_does() {
        const SCENE: Embedded = Embedded(&[(
            "s.toml",
            "[materials.lamp]\nemission = 2.0\n\
             [[object]]\nshape = \"union\"\nmembers = [{ shape = \"sphere\" }, { shape = \"sphere\", material = \"lamp\" }]\n\
             [[object]]\nshape = \"union\"\nmaterial = \"lamp\"\nmembers = [{ shape = \"sphere\", material = { color = 1.0 } }]\n\
             [[object]]\nshape = \"union\"\nmaterial = \"lamp\"\nmembers = [{ shape = \"sphere\" }]\n",
        )]);
        let mut scene = load_from(&SCENE, std::path::Path::new("s.toml"), &crate::plugins::registry()).unwrap();
        let scene = crate::prepare(&mut scene).unwrap();
        let emitting: Vec<u32> = scene.lights.area_emitters.iter().map(|e| e.primitive).collect();
        // A member's own emissive material makes the group a light; the group's material
        // does only where a member inherits it.
        assert_eq!(emitting, [0, 2]);
    }

    #[test]
    fn scene_lights_read_color_times_intensity_as_physical_units() {
        let light = Light {
            kind: LightKind::Spot,
            position: [0.0, 2.0, 0.0],
            point_at: [0.0, 0.0, 0.0],
            color: crate::color::Rgb::new(1.0, 0.5, 0.25),
            intensity: 4.0,
            radius: 60.0,
            falloff: 90.0,
            tightness: 3.0,
            fade_distance: 2.0,
            fade_power: 1.0,
            ..Light::default()
        };
        let l = RenderLight::from_scene(&light);
        let LightSource::Spot(spot) = &l.source else { panic!("{l:?}") };
        assert_eq!(spot.intensity, DVec3::new(4.0, 2.0, 1.0));
        assert_eq!(spot.cone.axis, DVec3::NEG_Y);
        assert!((spot.cone.cos_inner - 0.5).abs() < 1e-15 && spot.cone.cos_outer.abs() < 1e-15);
        let LightOrigin::Scene(pov) = &l.origin else { panic!() };
        assert_eq!((pov.tightness, pov.fade_distance, pov.fade_power), (3.0, 2.0, 1.0));

        let sun = RenderLight::from_scene(&Light { kind: LightKind::Parallel, position: [0.0, 0.0, 5.0], ..light });
        let LightSource::Directional(d) = &sun.source else { panic!("{sun:?}") };
        assert_eq!((d.direction, d.irradiance), (DVec3::NEG_Z, DVec3::new(4.0, 2.0, 1.0)));
        let LightOrigin::Scene(pov) = &sun.origin else { panic!() };
        assert_eq!(pov.position, DVec3::new(0.0, 0.0, 5.0));
    }

    #[test]
    fn photometric_lights_become_radiometric_by_watts_per_lumen() {
        let bulb = PhotometricLight {
            kind: PunctualKind::Spot { inner_cone_angle: 0.25, outer_cone_angle: 0.5 },
            position: DVec3::new(1.0, 2.0, 3.0),
            direction: DVec3::NEG_Z,
            color: crate::color::Rgb::new(1.0, 0.5, 0.25),
            intensity: 8.0,
            world_units_per_metre: 2.0,
        };
        let l = RenderLight::from_photometric(&bulb);
        let LightSource::Spot(spot) = &l.source else { panic!("{l:?}") };
        // 8 cd seen from 2 file metres (4 world units): 2 lx, so 32 W/sr in world units.
        assert_eq!(spot.intensity, DVec3::new(32.0, 16.0, 8.0) * WATTS_PER_LUMEN);
        assert_eq!((spot.cone.cos_inner, spot.cone.cos_outer), (0.25f64.cos(), 0.5f64.cos()));
        assert_eq!(l.origin, LightOrigin::Gltf(bulb.clone()));

        let sun = RenderLight::from_photometric(&PhotometricLight { kind: PunctualKind::Directional, ..bulb });
        let LightSource::Directional(d) = &sun.source else { panic!("{sun:?}") };
        assert_eq!((d.direction, d.irradiance), (DVec3::NEG_Z, DVec3::new(8.0, 4.0, 2.0) * WATTS_PER_LUMEN));
    }
}
