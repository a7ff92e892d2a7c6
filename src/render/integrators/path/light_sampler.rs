//! Light selection for next-event estimation. Point, spot, directional and area-grid sources
//! are few and cost one shadow ray each, so every one of them is sampled at every bounce
//! (up to [`EVERY_SOURCE_LIMIT`] of them); the emissive primitives and the environment, whose
//! samples are directions drawn over their extent, share one discrete distribution from
//! which one is chosen. Choosing among all lights by power instead starves a spot beside a
//! bright environment: a 40-degree spot got 3 % of the samples under a studio map, and the
//! patch it lit came out speckled where Mitsuba's is smooth. Beyond the limit the sources
//! join the distribution.
//!
//! The distribution depends on the shaded point when it holds at most [`SPATIAL_LIMIT`]
//! lights: each is weighed by an estimate of the irradiance it can give the point (its
//! intensity over the squared distance to its bounds' centre, never nearer than their
//! radius, times a bound on the cosine to the surface's normal over its bounds, either side,
//! at least [`MIN_COSINE`]; the environment's and a parallel light's the same everywhere),
//! so a lamp gets the samples near it and few far away or edge-on, where a choice by power
//! alone gives each of eight equal lamps along a corridor an eighth of the samples
//! everywhere. Occlusion is not estimated. With more lights the weights are their powers,
//! one distribution for the whole scene (weighing each at every vertex would cost more than
//! it saves). Either way the weights are positive for every light that gives light, and the
//! probability that MIS asks for a light hit from a point is computed as the choice made
//! there computed it.

use glam::{DVec2, DVec3};

use super::scatter::luminance;
use crate::geometry::csg::CsgShape;
use crate::render::extract::RenderScene;
use crate::render::lights::{EnvironmentMapLight, LightSource, SpotCone, emitting_materials};

/// What surrounds the scene under the path integrator.
#[derive(Clone, Debug)]
pub enum Environment {
    /// Black.
    None,
    /// The same radiance (W/(m^2 sr)) from every direction.
    Constant(DVec3),
    /// An HDR map.
    Map(EnvironmentMapLight),
}

impl Environment {
    /// The environment of `scene`: its map, else its background when not black.
    pub fn of(scene: &RenderScene) -> Self {
        let light = &scene.lights.environment;
        match &light.map {
            Some(map) => Environment::Map(map.clone()),
            None if light.radiance.max_element() > 0.0 => Environment::Constant(light.radiance),
            None => Environment::None,
        }
    }

    /// Radiance arriving from world direction `direction` (unit).
    pub fn radiance(&self, direction: DVec3) -> DVec3 {
        match self {
            Environment::None => DVec3::ZERO,
            Environment::Constant(c) => *c,
            Environment::Map(m) => m.radiance(direction),
        }
    }

    /// True when some direction has radiance.
    pub fn is_black(&self) -> bool {
        matches!(self, Environment::None)
    }

    /// ∫ luminance dω (W/(m^2 sr) · sr): with the scene's cross-section, its power.
    fn luminance_integral(&self) -> f64 {
        match self {
            Environment::None => 0.0,
            Environment::Constant(c) => 4.0 * std::f64::consts::PI * luminance(*c),
            Environment::Map(m) => m.map.power() * m.intensity,
        }
    }

    /// A direction toward the environment, its radiance and solid-angle density.
    fn sample(&self, u: DVec2) -> (DVec3, DVec3, f64) {
        match self {
            Environment::Map(m) => m.sample(u),
            _ => {
                let d = uniform_sphere(u);
                (d, self.radiance(d), UNIFORM_SPHERE_PDF)
            }
        }
    }

    /// Solid-angle density of `sample` at `direction`.
    fn pdf(&self, direction: DVec3) -> f64 {
        match self {
            Environment::Map(m) => m.pdf(direction),
            _ => UNIFORM_SPHERE_PDF,
        }
    }
}

/// Scenes with at most this many point, spot, directional and area-grid sources sample each
/// of them at every bounce; with more, one light is chosen among all (each shadow ray costs
/// as much as the whole choice).
pub const EVERY_SOURCE_LIMIT: usize = 32;

/// Distributions of at most this many lights weigh them at each point; larger ones by power.
pub const SPATIAL_LIMIT: usize = 64;

/// The least cosine factor a light's weight gets: a light edge-on to a surface still gives
/// it light through bent shading normals and rough lobes, and no weight may be 0 for a
/// light that gives light.
pub const MIN_COSINE: f64 = 0.05;

/// Where a light is chosen for: a point and its surface's unit normal (either side counts).
#[derive(Clone, Copy, Debug)]
pub struct Receiver {
    /// The shaded point (world space).
    pub point: DVec3,
    /// The shading normal there.
    pub normal: DVec3,
}

/// How far a light of the distribution reaches, for weighing it at a point: an estimate of
/// the luminance of the irradiance it can give there (W/m^2 weighted as luminance).
#[derive(Clone, Copy, Debug)]
enum Reach {
    /// A light within `radius` of `centre`, of luminous-weighted intensity `intensity` (W/sr)
    /// at most: `intensity / d^2`, d no less than the radius.
    Near { centre: DVec3, radius: f64, intensity: f64 },
    /// The same everywhere (the environment, parallel light, unbounded emitters).
    Everywhere { irradiance: f64 },
}

impl Reach {
    fn weight(self, receiver: &Receiver) -> f64 {
        match self {
            Reach::Near { centre, radius, intensity } => {
                let to_centre = centre - receiver.point;
                let distance_squared = to_centre.length_squared();
                if distance_squared <= radius * radius {
                    return intensity / (radius * radius);
                }
                // The cosine to the normal (either side) at the centre plus the sine of the
                // half angle the bounds subtend, which is at least the largest cosine over
                // them (cos(a - b) <= cos a + sin b), for one square root.
                let inverse_distance = distance_squared.sqrt().recip();
                let bound = (receiver.normal.dot(to_centre).abs() + radius) * inverse_distance;
                intensity * inverse_distance * inverse_distance * bound.clamp(MIN_COSINE, 1.0)
            }
            Reach::Everywhere { irradiance } => irradiance,
        }
    }
}

/// One light in the selection distribution.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LightRef {
    /// `scene.lights.sources[i]`.
    Source(u32),
    /// The emissive primitive with this index.
    Emitter(u32),
    /// The environment.
    Environment,
}

/// The sources sampled at every bounce, and a discrete distribution over the other lights,
/// weighed at each point (at most [`SPATIAL_LIMIT`] of them) or by power.
#[derive(Clone, Debug)]
pub struct LightSampler {
    /// How many sources are sampled at every bounce: all of them, or none beyond
    /// [`EVERY_SOURCE_LIMIT`] (they are then in the distribution).
    every_source: u32,
    /// The lights of the distribution.
    lights: Vec<LightRef>,
    /// How the lights of the distribution are weighed.
    weights: Weights,
    /// For each primitive, its index in `lights` (`u32::MAX` when it does not emit).
    emitter_index: Vec<u32>,
    /// The environment's index in `lights`.
    environment_index: Option<usize>,
}

/// How a distribution weighs its lights.
#[derive(Clone, Debug)]
enum Weights {
    /// At each point, by how far each light reaches (at most [`SPATIAL_LIMIT`] lights).
    AtPoint(Vec<Reach>),
    /// By power, the same everywhere.
    ByPower {
        /// Cumulative probabilities, `cdf[i]` = P(index <= i); the last is 1.
        cdf: Vec<f64>,
        /// The probability of each light.
        probability: Vec<f64>,
    },
}

/// What a light sample says about the light: where it is and what arrives.
#[derive(Clone, Copy, Debug)]
pub enum LightSample {
    /// A point on a light at finite distance (point, spot, grid point): arrival radiance over
    /// a delta direction (`radiance` is the irradiance-like value I / d^2), `pdf` the discrete
    /// selection probability.
    Delta {
        /// Unit direction from the shaded point toward the light.
        direction: DVec3,
        /// Distance to the light (infinite for directional lights).
        distance: f64,
        /// Incident irradiance at normal incidence, W/m^2, already divided by the selection
        /// probability.
        irradiance: DVec3,
    },
    /// A direction toward an emissive primitive, whose radiance the integrator reads at the
    /// hit: solid-angle `pdf` including the selection probability.
    Emitter {
        /// The primitive.
        primitive: u32,
        /// Unit direction from the shaded point.
        direction: DVec3,
        /// Solid-angle density including the selection probability.
        pdf: f64,
    },
    /// A direction toward the environment.
    Environment {
        /// Unit direction.
        direction: DVec3,
        /// Radiance arriving from it, W/(m^2 sr).
        radiance: DVec3,
        /// Solid-angle density including the selection probability.
        pdf: f64,
    },
}

/// Radiance of the constant environment and its sampling: uniform over the sphere.
const UNIFORM_SPHERE_PDF: f64 = 1.0 / (4.0 * std::f64::consts::PI);

/// The spot cone's intensity factor in direction `cos` from its axis (see [`SpotCone`]).
/// A radius at or beyond the falloff is a hard edge at the radius, as POV-Ray (and
/// `classic`) light it: full intensity within it, none beyond.
pub fn spot_factor(cone: &SpotCone, cos: f64) -> f64 {
    if cone.cos_inner <= cone.cos_outer {
        return if cos > cone.cos_inner { 1.0 } else { 0.0 };
    }
    if cos <= cone.cos_outer {
        return 0.0;
    }
    if cos >= cone.cos_inner {
        return 1.0;
    }
    let p = (cos - cone.cos_outer) / (cone.cos_inner - cone.cos_outer);
    (3.0 - 2.0 * p) * p * p
}

/// A direction uniform on the unit sphere.
pub fn uniform_sphere(u: DVec2) -> DVec3 {
    let z = 1.0 - 2.0 * u.x;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = 2.0 * std::f64::consts::PI * u.y;
    DVec3::new(r * phi.cos(), r * phi.sin(), z)
}

impl LightSampler {
    /// The distribution for `scene`, with `scene_radius` the radius of a sphere bounding the
    /// scene's finite geometry (it turns directional irradiance and environment radiance into
    /// powers comparable with the others').
    pub fn new(scene: &RenderScene, scene_radius: f64, environment: &Environment) -> Self {
        let pi = std::f64::consts::PI;
        let disc = pi * scene_radius * scene_radius;
        let mut lights = Vec::new();
        let mut power = Vec::new();
        let mut reach = Vec::new();
        let sources = &scene.lights.sources;
        let every_source = if sources.len() <= EVERY_SOURCE_LIMIT { sources.len() as u32 } else { 0 };
        let near = |centre: DVec3, radius: f64, intensity: f64| Reach::Near { centre, radius, intensity };
        for (i, light) in sources.iter().enumerate().skip(every_source as usize) {
            let (p, r) = match &light.source {
                LightSource::Point(l) => {
                    let intensity = luminance(l.intensity);
                    (4.0 * pi * intensity, near(l.position, 0.0, intensity))
                }
                LightSource::Spot(l) => {
                    let intensity = luminance(l.intensity);
                    let solid_angle = 2.0 * pi * (1.0 - 0.5 * (l.cone.cos_inner + l.cone.cos_outer));
                    (solid_angle * intensity, near(l.position, 0.0, intensity))
                }
                LightSource::Directional(l) => {
                    let irradiance = luminance(l.irradiance);
                    (disc * irradiance, Reach::Everywhere { irradiance })
                }
                LightSource::AreaGrid(l) => {
                    let intensity = luminance(l.intensity);
                    let half_diagonal = 0.5 * (l.grid.axis1.length_squared() + l.grid.axis2.length_squared()).sqrt();
                    (4.0 * pi * intensity, near(l.centre, half_diagonal, intensity))
                }
            };
            lights.push(LightRef::Source(i as u32));
            power.push(p.max(0.0));
            reach.push(r);
        }
        for emitter in &scene.lights.area_emitters {
            let primitive = &scene.primitives[emitter.primitive as usize];
            // Negative components emit nothing under path (`PathMaterial`'s emission); a CSG
            // group counts its brightest leaf material.
            let radiance = emitting_materials(primitive, &scene.materials)
                .map(|m| m.emission.radiance.0.max(DVec3::ZERO) + m.emission.times_color.0.max(DVec3::ZERO))
                .fold(DVec3::ZERO, DVec3::max);
            let area = match CsgShape::of(primitive.shape.as_ref()) {
                // About the area sampled, scaled as a uniform scale would.
                Some(group) => {
                    group.sampled_area() * primitive.world_from_object.matrix3.determinant().abs().powf(2.0 / 3.0)
                }
                None => {
                    primitive.shape.area().unwrap_or(1.0)
                        * primitive.shape.sample_area(DVec2::splat(0.5)).map_or(1.0, |s| primitive.area_scale(s.normal))
                }
            };
            // An emitter of area A and radiance L has the intensity L A / 4 on average over
            // all directions (a convex body's mean projected area is a quarter of its area),
            // its power over 4 pi, as a point light's; one without finite bounds gives at most
            // a hemisphere of L, pi L.
            let bounds = &primitive.world_bounds;
            let half_diagonal = 0.5 * (bounds.max - bounds.min);
            let r = if bounds.is_bounded() && half_diagonal.is_finite() {
                near(bounds.center(), half_diagonal.length(), 0.25 * area * luminance(radiance))
            } else {
                Reach::Everywhere { irradiance: pi * luminance(radiance) }
            };
            lights.push(LightRef::Emitter(emitter.primitive));
            power.push((pi * area * luminance(radiance)).max(0.0));
            reach.push(r);
        }
        let mut environment_index = None;
        if !environment.is_black() {
            environment_index = Some(lights.len());
            lights.push(LightRef::Environment);
            power.push(disc * environment.luminance_integral());
            // Irradiance of a uniform environment on a surface: pi times its mean radiance.
            reach.push(Reach::Everywhere { irradiance: environment.luminance_integral() / 4.0 });
        }
        let weights = if lights.len() <= SPATIAL_LIMIT { Weights::AtPoint(reach) } else { Weights::by_power(power) };
        let mut emitter_index = vec![u32::MAX; scene.primitives.len()];
        for (index, light) in lights.iter().enumerate() {
            if let LightRef::Emitter(i) = light {
                emitter_index[*i as usize] = index as u32;
            }
        }
        Self { every_source, lights, weights, emitter_index, environment_index }
    }

    /// The indices of the sources sampled at every bounce, each with
    /// [`LightSampler::sample_source`].
    pub fn every_source(&self) -> std::ops::Range<u32> {
        0..self.every_source
    }

    /// The light chosen by `u` for `receiver`, and its probability.
    pub fn choose(&self, receiver: &Receiver, u: f64) -> Option<(LightRef, f64)> {
        let last = self.lights.len().checked_sub(1)?;
        let reach = match &self.weights {
            Weights::AtPoint(reach) => reach,
            Weights::ByPower { cdf, probability } => {
                let index = cdf.partition_point(|&c| c <= u).min(last);
                return Some((self.lights[index], probability[index]));
            }
        };
        let mut weights = [0.0; SPATIAL_LIMIT];
        let total = point_weights(reach, receiver, &mut weights);
        let Some(total) = total else {
            let index = ((u * self.lights.len() as f64) as usize).min(last);
            return Some((self.lights[index], 1.0 / self.lights.len() as f64));
        };
        // The first light whose cumulative share passes u (the last takes what rounding
        // leaves), as the table's search finds it.
        let target = u * total;
        let mut cumulative = 0.0;
        for (index, &w) in weights[..=last].iter().enumerate() {
            cumulative += w;
            if target < cumulative && w > 0.0 {
                return Some((self.lights[index], w / total));
            }
        }
        let index = weights[..=last].iter().rposition(|&w| w > 0.0)?;
        Some((self.lights[index], weights[index] / total))
    }

    /// The probability that the choice for `receiver` picks light `index` of the distribution.
    fn probability_at(&self, index: usize, receiver: &Receiver) -> f64 {
        let reach = match &self.weights {
            Weights::AtPoint(reach) => reach,
            Weights::ByPower { probability, .. } => return probability[index],
        };
        let mut weights = [0.0; SPATIAL_LIMIT];
        match point_weights(reach, receiver, &mut weights) {
            Some(total) => weights[index] / total,
            None => 1.0 / self.lights.len() as f64,
        }
    }

    /// The probability that the choice for `receiver` picks the emissive primitive `primitive`.
    pub fn emitter_probability(&self, primitive: u32, receiver: &Receiver) -> f64 {
        match self.emitter_index.get(primitive as usize) {
            Some(&index) if index != u32::MAX => self.probability_at(index as usize, receiver),
            _ => 0.0,
        }
    }

    /// Samples a light and a direction toward it for `receiver`.
    pub fn sample(
        &self,
        scene: &RenderScene,
        environment: &Environment,
        receiver: &Receiver,
        u_select: f64,
        u: DVec2,
    ) -> Option<LightSample> {
        let point = receiver.point;
        let (light, probability) = self.choose(receiver, u_select)?;
        if probability <= 0.0 {
            return None;
        }
        match light {
            LightRef::Source(i) => Self::sample_source(scene, i, point, u, probability),
            LightRef::Emitter(index) => {
                let primitive = &scene.primitives[index as usize];
                let reference = primitive.object_point(point);
                let sample = primitive.shape.sample_toward(reference, u)?;
                let world_point = primitive.world_point(sample.point);
                let to_light = world_point - point;
                let distance = to_light.length();
                let pdf = sample.pdf_solid_angle / primitive.solid_angle_scale(sample.point - reference) * probability;
                (distance > 0.0 && pdf > 0.0 && pdf.is_finite()).then_some(LightSample::Emitter {
                    primitive: index,
                    direction: to_light / distance,
                    pdf,
                })
            }
            LightRef::Environment => {
                let (direction, radiance, pdf) = environment.sample(u);
                (pdf > 0.0).then_some(LightSample::Environment { direction, radiance, pdf: pdf * probability })
            }
        }
    }

    /// A sample of source `index` (of `scene.lights.sources`) from `point`, its arrival
    /// divided by `probability`, the chance it was chosen (1 when every source is sampled).
    /// `u` picks the point of an area grid.
    pub fn sample_source(
        scene: &RenderScene,
        index: u32,
        point: DVec3,
        u: DVec2,
        probability: f64,
    ) -> Option<LightSample> {
        let (position, intensity) = match &scene.lights.sources[index as usize].source {
            LightSource::Point(l) => (l.position, l.intensity),
            LightSource::Spot(l) => {
                let d = (point - l.position).normalize_or_zero();
                (l.position, l.intensity * spot_factor(&l.cone, d.dot(l.cone.axis)))
            }
            LightSource::Directional(l) => {
                return Some(LightSample::Delta {
                    direction: -l.direction,
                    distance: f64::INFINITY,
                    irradiance: l.irradiance / probability,
                });
            }
            LightSource::AreaGrid(l) => {
                // POV-Ray's grid as its points: one chosen uniformly (with its share
                // of the grid's intensity times the count, over its probability).
                let (n1, n2) = (l.grid.size1.max(1), l.grid.size2.max(1));
                let i = ((u.x * f64::from(n1)) as u32).min(n1 - 1);
                let j = ((u.y * f64::from(n2)) as u32).min(n2 - 1);
                let at = |index: u32, n: u32| if n > 1 { f64::from(index) / f64::from(n - 1) - 0.5 } else { 0.0 };
                let position = l.centre + l.grid.axis1 * at(i, n1) + l.grid.axis2 * at(j, n2);
                let d = (point - position).normalize_or_zero();
                let cone = l.cone.as_ref().map_or(1.0, |c| spot_factor(c, d.dot(c.axis)));
                (position, l.intensity * cone)
            }
        };
        let to_light = position - point;
        let distance = to_light.length();
        if distance.is_nan() || distance <= 0.0 || intensity.max_element() <= 0.0 {
            return None;
        }
        Some(LightSample::Delta {
            direction: to_light / distance,
            distance,
            irradiance: intensity / (distance * distance * probability),
        })
    }

    /// The solid-angle density, including selection, with which [`LightSampler::sample`]
    /// for `receiver` picks `direction` toward the environment.
    pub fn environment_pdf(&self, environment: &Environment, receiver: &Receiver, direction: DVec3) -> f64 {
        match self.environment_index {
            Some(index) => environment.pdf(direction) * self.probability_at(index, receiver),
            None => 0.0,
        }
    }
}

impl Weights {
    /// The distribution in proportion to `power` (uniform when the powers sum to nothing or
    /// overflow).
    fn by_power(power: Vec<f64>) -> Self {
        let total: f64 = power.iter().sum();
        let probability = if total > 0.0 && total.is_finite() {
            power.iter().map(|p| p / total).collect()
        } else {
            vec![1.0 / power.len().max(1) as f64; power.len()]
        };
        let mut cdf: Vec<f64> = probability
            .iter()
            .scan(0.0, |sum, p| {
                *sum += p;
                Some(*sum)
            })
            .collect();
        if let Some(last) = cdf.last_mut() {
            *last = 1.0;
        }
        Weights::ByPower { cdf, probability }
    }
}

/// Each light's weight for `receiver` into `weights` (not negative; NaN counts as 0), and
/// their sum, `None` when it is not positive and finite (the choice is then uniform).
fn point_weights(reach: &[Reach], receiver: &Receiver, weights: &mut [f64; SPATIAL_LIMIT]) -> Option<f64> {
    let mut total = 0.0;
    for (w, r) in weights.iter_mut().zip(reach) {
        *w = r.weight(receiver).max(0.0);
        total += *w;
    }
    (total > 0.0 && total.is_finite()).then_some(total)
}

#[cfg(test)]
mod tests {
    use super::*;
    use prism_api::contract::{TestRng, chi_square_p_value};

    /// Five emitters of different shapes, sizes and radiances, and a sky.
    fn sampler() -> (RenderScene, LightSampler) {
        const SCENE: &str = "[world]\nbackground = 0.3\n\
            [[object]]\nshape = \"sphere\"\nradius = 0.1\ntransform = { translate = [0, 0.5, 0] }\nmaterial = { emission = 100.0 }\n\
            [[object]]\nshape = \"sphere\"\nradius = 0.3\ntransform = { translate = [4, 2, 0] }\nmaterial = { emission = 5.0 }\n\
            [[object]]\nshape = \"rectangle\"\ntransform = { translate = [-3, 3, 1] }\nmaterial = { emission = 2.0 }\n\
            [[object]]\nshape = \"disc\"\nradius = 0.2\ntransform = { translate = [0, 0.05, 6] }\nmaterial = { emission = 50.0 }\n\
            [[object]]\nshape = \"box\"\ntransform = { scale = 0.2, translate = [1, 1, -5] }\nmaterial = { emission = [1, 8, 0.5] }\n";
        let files: &'static [(&'static str, &'static str)] = Box::leak(Box::new([("scene.toml", SCENE)]));
        let embedded: &'static crate::scene::load::Embedded = Box::leak(Box::new(crate::scene::load::Embedded(files)));
        let path = std::path::Path::new("scene.toml");
        let mut scene = crate::scene::load::load_from(embedded, path, &crate::plugins::registry()).unwrap();
        let scene = crate::prepare(&mut scene).unwrap();
        let environment = Environment::of(&scene);
        let sampler = LightSampler::new(&scene, 10.0, &environment);
        (scene, sampler)
    }

    /// The choice at a point follows the probabilities it reports, which are those MIS asks
    /// for: Pearson's chi-square over 40 000 choices at each of several points.
    #[test]
    fn chi2_light_choice_at_a_point() {
        let (_, sampler) = sampler();
        assert_eq!(sampler.lights.len(), 6, "five emitters and the sky");
        let mut rng = TestRng::new(7);
        for _ in 0..8 {
            let receiver = Receiver {
                point: DVec3::new(rng.range(-5.0, 5.0), rng.range(0.0, 3.0), rng.range(-6.0, 6.0)),
                normal: rng.unit_vector(),
            };
            let probabilities: Vec<f64> = (0..6).map(|i| sampler.probability_at(i, &receiver)).collect();
            assert!((probabilities.iter().sum::<f64>() - 1.0).abs() < 1e-12);
            let draws = 40_000;
            let mut counts = [0u32; 6];
            for _ in 0..draws {
                let (light, probability) = sampler.choose(&receiver, rng.uniform()).unwrap();
                let index = sampler.lights.iter().position(|&l| l == light).unwrap();
                assert_eq!(probability, probabilities[index], "the probability reported is MIS's");
                counts[index] += 1;
            }
            let statistic: f64 = counts
                .iter()
                .zip(&probabilities)
                .map(|(&c, &p)| (f64::from(c) - p * f64::from(draws)).powi(2) / (p * f64::from(draws)))
                .sum();
            let p_value = chi_square_p_value(statistic, 5);
            assert!(p_value > 1e-4, "choice at {receiver:?}: counts {counts:?}, probabilities {probabilities:?}");
        }
    }

    /// A lamp gets most of the choice at a point just below it and little far away; a lamp
    /// edge-on to the surface keeps at least `MIN_COSINE` of its weight.
    #[test]
    fn a_lamp_is_chosen_where_it_lights() {
        let (scene, sampler) = sampler();
        let lamp = scene.lights.area_emitters[0].primitive;
        let below = Receiver { point: DVec3::new(0.0, 0.0, 0.0), normal: DVec3::Y };
        let far = Receiver { point: DVec3::new(-4.0, 0.0, 5.0), normal: DVec3::Y };
        assert!(sampler.emitter_probability(lamp, &below) > 0.9);
        assert!(sampler.emitter_probability(lamp, &far) < 0.05);
        let level = Receiver { point: DVec3::new(3.0, 0.5, 0.0), normal: DVec3::Y };
        let edge_on = Reach::Near { centre: DVec3::new(0.0, 0.5, 0.0), radius: 0.0, intensity: 9.0 };
        assert_eq!(edge_on.weight(&level), 9.0 / 9.0 * MIN_COSINE);
    }

    #[test]
    fn a_radius_beyond_the_falloff_is_a_hard_edge_at_the_radius() {
        let axis = DVec3::Y;
        let cos = |degrees: f64| degrees.to_radians().cos();
        let wide = SpotCone { axis, cos_inner: cos(60.0), cos_outer: cos(20.0) };
        assert_eq!(spot_factor(&wide, cos(10.0)), 1.0);
        assert_eq!(spot_factor(&wide, cos(40.0)), 1.0, "beyond the falloff, within the radius");
        assert_eq!(spot_factor(&wide, cos(61.0)), 0.0);
        let hard = SpotCone { axis, cos_inner: cos(30.0), cos_outer: cos(30.0) };
        assert_eq!((spot_factor(&hard, cos(29.0)), spot_factor(&hard, cos(31.0))), (1.0, 0.0));
        let soft = SpotCone { axis, cos_inner: cos(20.0), cos_outer: cos(40.0) };
        let middle = spot_factor(&soft, cos(30.0));
        assert!(middle > 0.0 && middle < 1.0 && spot_factor(&soft, cos(41.0)) == 0.0);
    }
}
