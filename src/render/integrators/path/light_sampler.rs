//! Light selection for next-event estimation. Point, spot, directional and area-grid sources
//! are few and cost one shadow ray each, so every one of them is sampled at every bounce
//! (up to [`EVERY_SOURCE_LIMIT`] of them); the emissive primitives and the environment, whose
//! samples are directions drawn over their extent, share one discrete distribution from
//! which one is chosen. Choosing among all lights by power instead starves a spot beside a
//! bright environment: a 40-degree spot got 3 % of the samples under a studio map, and the
//! patch it lit came out speckled where Mitsuba's is smooth. Beyond the limit the sources
//! join the distribution.
//!
//! The distribution depends on the shaded point: each light is weighed by an estimate of
//! the irradiance it can give the point ([`Reach::weight`]: its intensity over the squared
//! distance to its bounds' centre, never nearer than their radius, times a bound on the
//! cosine to the surface's normal over its bounds, either side, at least
//! [`light_reach::MIN_COSINE`]; the environment's and a parallel light's the same
//! everywhere), so a lamp gets the samples near it and few far away or edge-on, where a
//! choice by power alone gives each of eight equal lamps along a corridor an eighth of the
//! samples everywhere. Occlusion is not estimated. Up to [`SPATIAL_LIMIT`] lights are
//! weighed one by one; more are chosen through a [`LightTree`] (the lights that reach
//! everywhere weighed beside its root), at the cost of a walk from its root to one leaf.
//! Either way the weights are positive for every light that gives light, and the
//! probability that MIS asks for a light hit from a point is computed as the choice made
//! there computed it.
//!
//! [`light_reach::MIN_COSINE`]: super::light_reach::MIN_COSINE

use glam::{DVec2, DVec3};

use super::light_reach::{LightTree, ONE_BELOW, Reach, Receiver};
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

/// Distributions of at most this many lights weigh them one by one at each point; larger
/// ones through a [`LightTree`].
pub const SPATIAL_LIMIT: usize = 64;

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
/// weighed at each point (one by one, or through a tree beyond [`SPATIAL_LIMIT`] of them).
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
    /// One by one at each point, by how far each light reaches (at most [`SPATIAL_LIMIT`]
    /// lights).
    AtPoint(Vec<Reach>),
    /// Through a tree of the lights of bounded reach, beside the others.
    Tree(TreeWeights),
}

/// The weights of a large distribution: the lights that reach everywhere each weighed at the
/// point, beside a tree of the others weighed as one by its root's reach.
#[derive(Clone, Debug)]
struct TreeWeights {
    /// The lights that reach everywhere: their indices in the distribution and reaches.
    everywhere: Vec<(u32, Reach)>,
    /// The tree over the other lights, `None` when there are none.
    tree: Option<LightTree>,
    /// The index in the distribution of each of the tree's lights.
    in_tree: Vec<u32>,
    /// Where each light of the distribution is weighed.
    place: Vec<Place>,
}

/// Where a light of a [`TreeWeights`] is weighed.
#[derive(Clone, Copy, Debug)]
enum Place {
    /// Among the lights that reach everywhere, at this index.
    Everywhere(u32),
    /// In the tree, as its light with this index.
    Tree(u32),
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
    /// The distribution for `scene` under `environment`.
    pub fn new(scene: &RenderScene, environment: &Environment) -> Self {
        let pi = std::f64::consts::PI;
        let mut lights = Vec::new();
        let mut reach = Vec::new();
        let sources = &scene.lights.sources;
        let every_source = if sources.len() <= EVERY_SOURCE_LIMIT { sources.len() as u32 } else { 0 };
        let near = |centre: DVec3, radius: f64, intensity: f64| Reach::Near { centre, radius, intensity };
        for (i, light) in sources.iter().enumerate().skip(every_source as usize) {
            let r = match &light.source {
                LightSource::Point(l) => near(l.position, 0.0, luminance(l.intensity)),
                LightSource::Spot(l) => near(l.position, 0.0, luminance(l.intensity)),
                LightSource::Directional(l) => Reach::Everywhere { irradiance: luminance(l.irradiance) },
                LightSource::AreaGrid(l) => {
                    let half_diagonal = 0.5 * (l.grid.axis1.length_squared() + l.grid.axis2.length_squared()).sqrt();
                    near(l.centre, half_diagonal, luminance(l.intensity))
                }
            };
            lights.push(LightRef::Source(i as u32));
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
            // all directions (a convex body's mean projected area is a quarter of its area);
            // one without finite bounds gives at most a hemisphere of L, pi L.
            let bounds = &primitive.world_bounds;
            let half_diagonal = 0.5 * (bounds.max - bounds.min);
            let r = if bounds.is_bounded() && half_diagonal.is_finite() {
                near(bounds.center(), half_diagonal.length(), 0.25 * area * luminance(radiance))
            } else {
                Reach::Everywhere { irradiance: pi * luminance(radiance) }
            };
            lights.push(LightRef::Emitter(emitter.primitive));
            reach.push(r);
        }
        let mut environment_index = None;
        if !environment.is_black() {
            environment_index = Some(lights.len());
            lights.push(LightRef::Environment);
            // Irradiance of a uniform environment on a surface: pi times its mean radiance.
            reach.push(Reach::Everywhere { irradiance: environment.luminance_integral() / 4.0 });
        }
        let weights = if lights.len() <= SPATIAL_LIMIT { Weights::AtPoint(reach) } else { Weights::tree(&reach) };
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
            Weights::Tree(tree) => {
                let (index, probability) = tree.choose(receiver, u)?;
                return Some((self.lights[index as usize], probability));
            }
        };
        let mut weights = [0.0; SPATIAL_LIMIT];
        let total = point_weights(reach, receiver, &mut weights);
        let Some(total) = total else {
            let index = ((u * self.lights.len() as f64) as usize).min(last);
            return Some((self.lights[index], 1.0 / self.lights.len() as f64));
        };
        let (index, _) = pick(&weights[..=last], total, u)?;
        Some((self.lights[index], weights[index] / total))
    }

    /// The probability that the choice for `receiver` picks light `index` of the distribution.
    fn probability_at(&self, index: usize, receiver: &Receiver) -> f64 {
        let reach = match &self.weights {
            Weights::AtPoint(reach) => reach,
            Weights::Tree(tree) => return tree.probability(index, receiver),
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
    /// A tree over the lights of bounded `reach` (indexed like the distribution), the others
    /// weighed beside its root.
    fn tree(reach: &[Reach]) -> Self {
        let (mut everywhere, mut near, mut in_tree, mut place) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        for (index, &r) in reach.iter().enumerate() {
            match r {
                Reach::Everywhere { .. } => {
                    place.push(Place::Everywhere(everywhere.len() as u32));
                    everywhere.push((index as u32, r));
                }
                Reach::Near { .. } => {
                    place.push(Place::Tree(near.len() as u32));
                    near.push(r);
                    in_tree.push(index as u32);
                }
            }
        }
        Weights::Tree(TreeWeights { everywhere, tree: LightTree::new(&near), in_tree, place })
    }
}

impl TreeWeights {
    /// Calls `f` with the weights of the lights that reach everywhere, then the tree's
    /// root's, at `receiver`, and their sum; all 1 when that is not positive and finite (the
    /// choice among them is then uniform). On the stack for a few such lights.
    fn with_top_weights<R>(&self, receiver: &Receiver, f: impl FnOnce(&[f64], f64) -> R) -> R {
        const ON_STACK: usize = 8;
        let count = self.everywhere.len() + usize::from(self.tree.is_some());
        let mut stack = [0.0; ON_STACK];
        let mut heap = Vec::new();
        let weights: &mut [f64] = if count <= ON_STACK {
            &mut stack[..count]
        } else {
            heap.resize(count, 0.0);
            &mut heap
        };
        for (w, (_, r)) in weights.iter_mut().zip(&self.everywhere) {
            *w = r.weight(receiver);
        }
        if let Some(tree) = &self.tree {
            weights[count - 1] = tree.weight(receiver);
        }
        let total: f64 = weights.iter().sum();
        if total > 0.0 && total.is_finite() {
            return f(weights, total);
        }
        weights.iter_mut().for_each(|w| *w = 1.0);
        f(weights, count as f64)
    }

    /// The index in the distribution of the light chosen by `u` at `receiver`, and its
    /// probability.
    fn choose(&self, receiver: &Receiver, u: f64) -> Option<(u32, f64)> {
        let (top, rest, share) = self.with_top_weights(receiver, |weights, total| {
            let (top, rest) = pick(weights, total, u)?;
            Some((top, rest, weights[top] / total))
        })?;
        match self.everywhere.get(top) {
            Some(&(index, _)) => Some((index, share)),
            None => {
                let tree = self.tree.as_ref()?;
                let (light, probability) = tree.choose(receiver, rest);
                Some((self.in_tree[light as usize], share * probability))
            }
        }
    }

    /// The probability that [`TreeWeights::choose`] at `receiver` picks light `index` of
    /// the distribution, computed as the choice computes it.
    fn probability(&self, index: usize, receiver: &Receiver) -> f64 {
        let place = self.place[index];
        let share = self.with_top_weights(receiver, |weights, total| match place {
            Place::Everywhere(k) => weights[k as usize] / total,
            Place::Tree(_) => weights[weights.len() - 1] / total,
        });
        match (place, &self.tree) {
            (Place::Everywhere(_), _) => share,
            (Place::Tree(light), Some(tree)) => share * tree.probability(light, receiver),
            (Place::Tree(_), None) => 0.0,
        }
    }
}

/// The first of `weights` (summing to `total`, positive) whose cumulative share passes `u`
/// (the last positive one takes what rounding leaves), and `u`'s place within its share,
/// rescaled to [0, 1).
fn pick(weights: &[f64], total: f64, u: f64) -> Option<(usize, f64)> {
    let target = u * total;
    let mut cumulative = 0.0;
    for (index, &w) in weights.iter().enumerate() {
        let before = cumulative;
        cumulative += w;
        if target < cumulative && w > 0.0 {
            return Some((index, ((target - before) / w).clamp(0.0, ONE_BELOW)));
        }
    }
    let index = weights.iter().rposition(|&w| w > 0.0)?;
    Some((index, ONE_BELOW))
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
        sampler_of(SCENE)
    }

    fn sampler_of(text: &str) -> (RenderScene, LightSampler) {
        let text: &'static str = Box::leak(text.to_string().into_boxed_str());
        let files: &'static [(&'static str, &'static str)] = Box::leak(Box::new([("scene.toml", text)]));
        let embedded: &'static crate::scene::load::Embedded = Box::leak(Box::new(crate::scene::load::Embedded(files)));
        let path = std::path::Path::new("scene.toml");
        let mut scene = crate::scene::load::load_from(embedded, path, &crate::plugins::registry()).unwrap();
        let scene = crate::prepare(&mut scene).unwrap();
        let environment = Environment::of(&scene);
        let sampler = LightSampler::new(&scene, &environment);
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

    /// Beyond [`SPATIAL_LIMIT`] lights, the choice walks a tree beside the lights that reach
    /// everywhere (a sky, a parallel light among more than [`EVERY_SOURCE_LIMIT`] sources,
    /// an unbounded emitter): it follows the probabilities it reports, which sum to 1 and
    /// are those MIS asks for (Pearson's chi-square over 200 000 choices at each of several
    /// points).
    #[test]
    fn chi2_light_choice_through_the_tree() {
        let mut rng = TestRng::new(17);
        let mut text = String::from(
            "[world]\nbackground = 0.2\n\
             [[object]]\nshape = \"plane\"\nnormal = [0, -1, 0]\noffset = -20\nmaterial = { emission = 0.5 }\n",
        );
        for _ in 0..90 {
            text += &format!(
                "[[object]]\nshape = \"sphere\"\nradius = {}\ntransform = {{ translate = [{}, {}, {}] }}\nmaterial = {{ emission = {} }}\n",
                rng.range(0.05, 0.5),
                rng.range(-10.0, 10.0),
                rng.range(0.0, 5.0),
                rng.range(-10.0, 10.0),
                rng.range(1.0, 50.0)
            );
        }
        for _ in 0..40 {
            text += &format!(
                "[[light]]\nposition = [{}, {}, {}]\nintensity = {}\n",
                rng.range(-10.0, 10.0),
                rng.range(0.0, 5.0),
                rng.range(-10.0, 10.0),
                rng.range(1.0, 20.0)
            );
        }
        text += "[[light]]\nkind = \"parallel\"\nposition = [0, 10, 3]\nintensity = 2.0\n";
        let (_, sampler) = sampler_of(&text);
        let count = sampler.lights.len();
        assert_eq!(count, 90 + 1 + 41 + 1, "the emitters, the sources beyond the limit and the sky");
        assert!(matches!(&sampler.weights, Weights::Tree(t) if t.everywhere.len() == 3), "sky, parallel, plane");
        for _ in 0..4 {
            let receiver = Receiver {
                point: DVec3::new(rng.range(-10.0, 10.0), rng.range(0.0, 5.0), rng.range(-10.0, 10.0)),
                normal: rng.unit_vector(),
            };
            let probabilities: Vec<f64> = (0..count).map(|i| sampler.probability_at(i, &receiver)).collect();
            assert!((probabilities.iter().sum::<f64>() - 1.0).abs() < 1e-12);
            crate::test_support::chi2::assert_choice_fits(
                &format!("the choice at {receiver:?}"),
                &probabilities,
                200_000,
                20,
                || {
                    let (light, probability) = sampler.choose(&receiver, rng.uniform()).unwrap();
                    (sampler.lights.iter().position(|&l| l == light).unwrap(), probability)
                },
            );
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
        assert_eq!(edge_on.weight(&level), 9.0 / 9.0 * super::super::light_reach::MIN_COSINE);
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
