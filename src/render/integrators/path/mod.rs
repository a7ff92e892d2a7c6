//! The `path` integrator: unidirectional path tracing with next-event estimation and
//! multiple importance sampling (power heuristic) between BSDF and light sampling, Russian
//! roulette, and delta lobes and delta lights handled apart (they are never weighted).
//!
//! Path length follows Mitsuba 3: `max_depth` counts segments, the camera ray's being the
//! first, so `max_depth = 1` shows only emitters seen directly. Every random number of a
//! path comes from its sample's stream at fixed dimensions per bounce, so the image is a pure
//! function of (pixel, sample, dimension, seed); the numbers are stratified over each pixel's
//! samples (padded Owen-scrambled Sobol, [`SampleStream::stratified2`]).
//!
//! Inside an object whose interior absorbs ([`medium`]), every stretch of a path, and every
//! shadow ray, carries the Beer-Lambert transmittance of the medium it crosses.

pub mod light_reach;
pub mod light_sampler;
pub mod medium;
pub mod scatter;

use glam::{DVec2, DVec3};
use prism_api::Ray;

use super::{FirstHit, Integrator, PixelSample};
use crate::accel::scene_bvh::ClosestHit;
use crate::geometry::mesh::shading_normal_for_view;
use crate::material::normal::NormalField;
use crate::render::bsdf::Frame;
use crate::render::extract::RenderScene;
use crate::render::sampling::SampleStream;
use light_reach::Receiver;
use light_sampler::{Environment, LightSample, LightSampler};
use medium::{Media, transmittance};
use scatter::{PathMaterial, SurfacePoint};

/// Rays start this far (relative to the scene's scale at the hit) beyond their origin.
const RAY_EPSILON: f64 = 1e-6;
/// Rays end this far away.
const MAX_DISTANCE: f64 = 1e7;
/// The scheduler's dimensions (pixel and lens position) come first.
const FIRST_DIMENSION: u64 = 4;
/// Dimensions each bounce draws: light choice, light position (2), lobe, direction (2),
/// Russian roulette.
const DIMENSIONS_PER_BOUNCE: u64 = 8;
/// Russian roulette never keeps a path with more than this probability.
const MAX_SURVIVAL: f64 = 0.95;

/// The path tracer over one render scene.
pub struct Path<'a> {
    scene: &'a RenderScene,
    materials: Vec<PathMaterial>,
    lights: LightSampler,
    environment: Environment,
    /// Whether a camera ray's first hit carries its uv on untextured materials too (for the
    /// `uv` AOV; shading reads the uv of textured materials only).
    first_hit_uv: bool,
    /// Whether some material's interior absorbs (otherwise no path tracks its media).
    absorbing: bool,
    /// Primitives whose interior may hold a camera ray's origin (solids of a material that
    /// encloses a medium, bounds touching the lens), in load order; empty when nothing absorbs.
    camera_containers: Vec<u32>,
}

/// The power heuristic (beta = 2) weight of a strategy with density `a` against one with `b`.
fn power_heuristic(a: f64, b: f64) -> f64 {
    let (a2, b2) = (a * a, b * b);
    if a2 + b2 > 0.0 { a2 / (a2 + b2) } else { 0.0 }
}

/// The stratified pair `u` shifted by the `k`-th point of the R2 sequence, modulo 1 (a
/// Cranley-Patterson rotation): each source sampled at a bounce gets points as well spread
/// over the pixel's samples as `u`'s, not the same ones.
fn rotated(u: DVec2, k: u32) -> DVec2 {
    // 1 / g and 1 / g^2 for the plastic number g, the root of x^3 = x + 1.
    const STEP: DVec2 = DVec2::new(0.754_877_666_246_692_8, 0.569_840_290_998_053_2);
    // k = 0 leaves u as it is (u lies in [0, 1)).
    (u + STEP * f64::from(k)).fract()
}

/// Absorption coefficients (per scene unit) that shadow rays leaving a vertex cross: on the
/// side its geometric normal points to, and on the other.
struct ShadowAbsorption {
    front: DVec3,
    back: DVec3,
}

impl ShadowAbsorption {
    /// The transmittance of a shadow ray leaving along `direction` (unit) over `distance`.
    fn transmittance(&self, geometric_normal: DVec3, direction: DVec3, distance: f64) -> DVec3 {
        let absorption = if direction.dot(geometric_normal) >= 0.0 { self.front } else { self.back };
        if absorption == DVec3::ZERO { DVec3::ONE } else { transmittance(absorption, distance) }
    }
}

/// A hit with what the path needs from it, in world space.
struct Vertex {
    point: DVec3,
    /// Unit geometric normal, pointing out of the shape (its front side).
    geometric_normal: DVec3,
    /// Unit shading normal on the same side as `geometric_normal`.
    shading_normal: DVec3,
    tangent: DVec3,
    uv: DVec2,
    /// The hit in the primitive's object space (where pigment patterns are evaluated).
    object_point: DVec3,
    primitive: u32,
    material: u32,
    distance: f64,
}

impl<'a> Path<'a> {
    /// The path integrator for `scene`.
    pub fn new(scene: &'a RenderScene) -> Self {
        let materials: Vec<PathMaterial> = scene.materials.iter().map(PathMaterial::new).collect();
        let absorbing = materials.iter().any(|m| m.absorption() != DVec3::ZERO);
        let lens = scene.camera.lens_bounds();
        // A CSG group whose members differ in material is left out: its crossings name the
        // members' materials, its inside test only the whole.
        let camera_containers = (0..scene.primitives.len() as u32)
            .filter(|&i| {
                let p = &scene.primitives[i as usize];
                absorbing
                    && p.leaf_materials.is_none()
                    && materials[p.material as usize].encloses_medium()
                    && p.world_bounds.min.cmple(lens.max).all()
                    && p.world_bounds.max.cmpge(lens.min).all()
            })
            .collect();
        let environment = Environment::of(scene);
        let lights = LightSampler::new(scene, &environment);
        Self { scene, materials, lights, environment, first_hit_uv: false, absorbing, camera_containers }
    }

    /// The same integrator, giving every first hit its uv when `uv` is true (the `uv` AOV),
    /// not only those on textured materials.
    pub fn with_first_hit_uv(self, uv: bool) -> Self {
        Self { first_hit_uv: uv, ..self }
    }

    /// The interiors a camera ray from `origin` starts in: those of the solids that hold it, in
    /// load order (the last counts as the innermost), as the classic integrator's camera rays.
    fn media_at(&self, origin: DVec3) -> Media {
        self.camera_containers.iter().fold(Media::default(), |media, &i| {
            let p = &self.scene.primitives[i as usize];
            if p.shape.inside(p.object_point(origin)) { media.crossed(p.material, true) } else { media }
        })
    }

    /// The absorption coefficient (per scene unit) inside `media`'s innermost interior.
    fn absorption(&self, media: &Media) -> DVec3 {
        media.innermost().map_or(DVec3::ZERO, |m| self.materials[m as usize].absorption())
    }

    /// The absorption that shadow rays leaving `vertex` meet on its front (geometric normal's)
    /// side and on its back, for a path that arrived along `direction` inside `media`.
    fn shadow_absorption(&self, media: &Media, vertex: &Vertex, direction: DVec3) -> ShadowAbsorption {
        let here = self.absorption(media);
        let material = &self.materials[vertex.material as usize];
        let from_front = direction.dot(vertex.geometric_normal) < 0.0;
        let beyond = if material.encloses_medium() {
            // A ray to the far side crosses the surface: into the interior from outside,
            // out of it from inside.
            self.absorption(&media.crossed(vertex.material, from_front))
        } else {
            here
        };
        if from_front {
            ShadowAbsorption { front: here, back: beyond }
        } else {
            ShadowAbsorption { front: beyond, back: here }
        }
    }

    fn closest(&self, ray: &Ray, t_max: f64) -> Option<ClosestHit> {
        self.scene.accel.closest(&self.scene.primitives, ray, RAY_EPSILON, t_max, |_| true)
    }

    fn vertex(&self, ray: &Ray, closest: &ClosestHit) -> Vertex {
        let primitive = &self.scene.primitives[closest.primitive as usize];
        // The uv costs trigonometry on curved shapes; only textured materials look at it.
        let material = primitive.material_at(&closest.hit);
        let object_ray = &*primitive.object_ray_of(ray);
        let surface = if self.materials[material as usize].is_textured() {
            primitive.shape.surface(object_ray, &closest.hit)
        } else {
            primitive.shape.surface_geometry(object_ray, &closest.hit)
        };
        let geometric_normal = primitive.world_normal(surface.normal);
        let mut shading_normal = primitive.world_normal(surface.shading_normal);
        if shading_normal.dot(geometric_normal) < 0.0 {
            shading_normal = -shading_normal;
        }
        // Interpolated and mapped normals (meshes') get the terminator fix; a shading normal
        // equal to the geometric one is the true normal and stays unbent even at grazing views.
        if surface.shading_normal != surface.normal {
            shading_normal = shading_normal_for_view(shading_normal, geometric_normal, ray.direction);
        }
        let tangent = match primitive.placement {
            crate::accel::primitive::Placement::Affine => primitive.world_from_object.transform_vector3(surface.dpdu),
            _ => surface.dpdu,
        };
        Vertex {
            point: primitive.world_point(surface.point),
            geometric_normal,
            shading_normal,
            tangent,
            uv: surface.uv,
            object_point: surface.point,
            primitive: closest.primitive,
            material,
            distance: closest.hit.t * ray.direction.length(),
        }
    }

    /// Radiance a vertex emits toward direction `toward` (unit, away from the surface):
    /// emitters shine from their front side, two-sided ones from both.
    fn emitted(&self, vertex: &Vertex, toward: DVec3) -> DVec3 {
        let material = &self.materials[vertex.material as usize];
        if !material.can_emit() || (!material.emits_both_sides() && vertex.geometric_normal.dot(toward) <= 0.0) {
            return DVec3::ZERO;
        }
        material.emitted(&SurfacePoint { uv: vertex.uv, object_point: vertex.object_point })
    }

    /// Solid-angle density with which light sampling for `receiver` picks `direction` toward
    /// the emissive primitive `primitive`, selection included.
    fn emitter_pdf(&self, primitive: u32, receiver: &Receiver, direction: DVec3) -> f64 {
        let probability = self.lights.emitter_probability(primitive, receiver);
        if probability <= 0.0 {
            return 0.0;
        }
        let p = &self.scene.primitives[primitive as usize];
        let reference = p.object_point(receiver.point);
        let object_direction = match p.placement {
            crate::accel::primitive::Placement::Affine => p.object_from_world.transform_vector3(direction),
            _ => direction,
        };
        let pdf = p.shape.pdf_toward(reference, object_direction) / p.solid_angle_scale(object_direction);
        if pdf.is_finite() { pdf * probability } else { 0.0 }
    }

    /// A point just off the surface on the side of `direction`.
    fn offset_origin(vertex: &Vertex, direction: DVec3) -> DVec3 {
        let scale = RAY_EPSILON * (1.0 + vertex.point.abs().max_element());
        let side = if direction.dot(vertex.geometric_normal) >= 0.0 { 1.0 } else { -1.0 };
        vertex.point + vertex.geometric_normal * (side * scale)
    }

    fn trace(&self, camera_ray: &Ray, stream: SampleStream) -> PixelSample {
        let scene = self.scene;
        let max_depth = scene.settings.max_depth;
        let rr_depth = scene.settings.rr_depth;
        let mut radiance = DVec3::ZERO;
        let mut throughput = DVec3::ONE;
        let mut ray = *camera_ray;
        let mut first_hit = None;
        let mut rays = 0u64;
        // The previous scattering: its solid-angle pdf (0 after a delta lobe) and its point.
        let mut previous_pdf = 0.0;
        let mut previous_delta = true;
        let mut previous = Receiver { point: ray.origin, normal: DVec3::ZERO };
        let mut depth = 1u32;
        // The interiors around the path, and the innermost one's absorption.
        let mut media = if self.camera_containers.is_empty() { Media::default() } else { self.media_at(ray.origin) };
        let mut absorption = self.absorption(&media);
        loop {
            rays += 1;
            let direction = ray.direction.normalize();
            // Read in place, field by field (a copy of the whole hit would wait for the
            // query's stores to retire).
            let found = self.closest(&ray, MAX_DISTANCE);
            if absorption != DVec3::ZERO {
                let distance = found.as_ref().map_or(f64::INFINITY, |c| c.hit.t * ray.direction.length());
                throughput *= transmittance(absorption, distance);
            }
            let Some(closest) = &found else {
                if !self.environment.is_black() {
                    let weight = if previous_delta {
                        1.0
                    } else {
                        power_heuristic(
                            previous_pdf,
                            self.lights.environment_pdf(&self.environment, &previous, direction),
                        )
                    };
                    radiance += throughput * self.environment.radiance(direction) * weight;
                }
                break;
            };
            let mut vertex = self.vertex(&ray, closest);
            if depth == 1 && self.first_hit_uv && !self.materials[vertex.material as usize].is_textured() {
                // For the uv AOV only: an untextured material does not read it.
                let primitive = &scene.primitives[closest.primitive as usize];
                vertex.uv = primitive.shape.surface(&primitive.object_ray_of(&ray), &closest.hit).uv;
            }
            let emitted = self.emitted(&vertex, -direction);
            if emitted.max_element() > 0.0 {
                let weight = if previous_delta {
                    1.0
                } else {
                    power_heuristic(previous_pdf, self.emitter_pdf(vertex.primitive, &previous, direction))
                };
                radiance += throughput * emitted * weight;
            }
            if depth >= max_depth {
                if first_hit.is_none() && depth == 1 {
                    first_hit = Some(self.first_hit(&vertex, -direction));
                }
                break;
            }
            let material = &self.materials[vertex.material as usize];
            if let Some(field) = material.normal_pattern() {
                vertex.shading_normal = self.tilted_normal(&vertex, field, direction);
            }
            let shaded = material.shade(&SurfacePoint { uv: vertex.uv, object_point: vertex.object_point });
            let scatter = &shaded.scatter;
            if depth == 1 {
                first_hit = Some(FirstHit { albedo: scatter.albedo(), ..self.first_hit(&vertex, -direction) });
            }
            if scatter.is_black() {
                break;
            }
            let frame = Frame::new(vertex.shading_normal, vertex.tangent);
            let wo = frame.to_local(-direction);
            let base = FIRST_DIMENSION + u64::from(depth - 1) * DIMENSIONS_PER_BOUNCE;

            // Lights are sampled from just off the surface on the viewer's side, so that a
            // shape sampled from a point on itself (the inside of an emitting sphere) never
            // counts the point as a crossing; the BSDF-sampled hit's MIS weight uses the
            // same reference point.
            let reference = Self::offset_origin(&vertex, -direction);
            let receiver = Receiver { point: reference, normal: vertex.shading_normal };
            let shadow_absorption = (self.absorbing && (absorption != DVec3::ZERO || material.encloses_medium()))
                .then(|| self.shadow_absorption(&media, &vertex, direction));

            // Next-event estimation: every source, then one of the other lights.
            if scatter.has_smooth_lobe() {
                let u_source = stream.stratified2(base + 1);
                for source in self.lights.every_source() {
                    let u = rotated(u_source, source);
                    if let Some(sample) = LightSampler::sample_source(scene, source, reference, u, 1.0) {
                        rays += 1;
                        radiance +=
                            throughput * self.direct(&vertex, &frame, wo, scatter, sample, shadow_absorption.as_ref());
                    }
                }
                let sample = self.lights.sample(
                    scene,
                    &self.environment,
                    &receiver,
                    stream.stratified(base),
                    stream.stratified2(base + 1),
                );
                if let Some(sample) = sample {
                    rays += 1;
                    radiance +=
                        throughput * self.direct(&vertex, &frame, wo, scatter, sample, shadow_absorption.as_ref());
                }
            }

            // Continue the path by sampling the scattering.
            let Some(s) = scatter.sample(wo, stream.stratified(base + 3), stream.stratified2(base + 4)) else { break };
            if !(s.weight.is_finite() && s.weight.max_element() > 0.0) {
                break;
            }
            let next = frame.to_world(s.wi);
            let into_back = next.dot(vertex.geometric_normal) < 0.0;
            if self.absorbing
                && material.encloses_medium()
                && into_back != (direction.dot(vertex.geometric_normal) > 0.0)
            {
                // The path crossed the surface: into the interior against the outward normal.
                media = media.crossed(vertex.material, into_back);
                absorption = self.absorption(&media);
            }
            throughput *= s.weight;
            previous_pdf = s.pdf;
            previous_delta = s.delta;
            previous = receiver;
            ray = Ray::new(Self::offset_origin(&vertex, next), next);
            depth += 1;
            if depth > rr_depth {
                let survival = throughput.max_element().min(MAX_SURVIVAL);
                if stream.stratified(base + 6) >= survival {
                    break;
                }
                throughput /= survival;
            }
        }
        // A non-finite estimate passes through for the scheduler to count and drop (with a
        // warning naming the cause), not to vanish here in silence.
        let radiance = if radiance.is_finite() { radiance.max(DVec3::ZERO) } else { radiance };
        PixelSample { radiance, first_hit, rays }
    }

    /// The light-sampling estimate of one sampled light at `vertex`, MIS-weighted, through
    /// the absorbing media the shadow ray crosses (none when `absorption` is `None`).
    fn direct(
        &self,
        vertex: &Vertex,
        frame: &Frame,
        wo: DVec3,
        scatter: &scatter::Scatter,
        sample: LightSample,
        absorption: Option<&ShadowAbsorption>,
    ) -> DVec3 {
        let scene = self.scene;
        let through = |direction: DVec3, distance: f64| {
            absorption.map_or(DVec3::ONE, |a| a.transmittance(vertex.geometric_normal, direction, distance))
        };
        match sample {
            LightSample::Delta { direction, distance, irradiance } => {
                let f = scatter.eval(wo, frame.to_local(direction));
                if f.max_element() <= 0.0 {
                    return DVec3::ZERO;
                }
                let origin = Self::offset_origin(vertex, direction);
                let t_max = if distance.is_finite() { distance * (1.0 - 1e-7) } else { MAX_DISTANCE };
                let shadow = Ray::new(origin, direction);
                if scene.accel.occluded(&scene.primitives, &shadow, RAY_EPSILON, t_max, |i| {
                    !scene.primitives[i as usize].no_shadow
                }) {
                    return DVec3::ZERO;
                }
                f * irradiance * through(direction, distance)
            }
            LightSample::Emitter { primitive, direction, pdf } => {
                let wi = frame.to_local(direction);
                let f = scatter.eval(wo, wi);
                if f.max_element() <= 0.0 {
                    return DVec3::ZERO;
                }
                let origin = Self::offset_origin(vertex, direction);
                let ray = Ray::new(origin, direction);
                // Unoccluded when the nearest hit along the ray is the emitter itself. No
                // distance limit: a mesh emitter seen at a grazing angle is hit in f32 with
                // an error in `t` far beyond any fixed margin (the Cornell box's walls lost
                // half their light near the lamp's plane), while anything in front of the
                // emitter is hit first anyway.
                let Some(hit) = self.closest(&ray, MAX_DISTANCE) else {
                    return DVec3::ZERO;
                };
                if hit.primitive != primitive {
                    return DVec3::ZERO;
                }
                let emitter = &self.scene.primitives[primitive as usize];
                let material = &self.materials[emitter.material_at(&hit.hit) as usize];
                // The side is read where the ray crossed the emitter, not at the sampled point:
                // a non-convex emitter (or the vertex's own surface, which an emitting glass
                // sphere sampled from just above it finds below the vertex through the
                // transmission lobe) can be crossed first elsewhere, on its back.
                let emitted = match material.uniform_emission() {
                    Some(radiance) if material.emits_both_sides() => radiance,
                    Some(radiance) => {
                        let crossed = emitter.shape.hit_point(&emitter.object_ray_of(&ray), &hit.hit);
                        if emitter.world_normal(crossed.normal).dot(direction) >= 0.0 {
                            return DVec3::ZERO;
                        }
                        radiance
                    }
                    None => self.emitted(&self.vertex(&ray, &hit), -direction),
                };
                let weight = power_heuristic(pdf, scatter.pdf(wo, wi));
                f * emitted * (weight / pdf) * through(direction, hit.hit.t * direction.length())
            }
            LightSample::Environment { direction, radiance, pdf } => {
                let wi = frame.to_local(direction);
                let f = scatter.eval(wo, wi);
                if f.max_element() <= 0.0 {
                    return DVec3::ZERO;
                }
                let shadow = Ray::new(Self::offset_origin(vertex, direction), direction);
                if scene.accel.occluded(&scene.primitives, &shadow, RAY_EPSILON, MAX_DISTANCE, |i| {
                    !scene.primitives[i as usize].no_shadow
                }) {
                    return DVec3::ZERO;
                }
                let weight = power_heuristic(pdf, scatter.pdf(wo, wi));
                f * radiance * (weight / pdf) * through(direction, f64::INFINITY)
            }
        }
    }

    /// The shading normal tilted by a normal pattern, as `classic` tilts it (POV-Ray's
    /// `Perturb_Normal`, on the normal facing the ray, in the object's space), then bent where
    /// it would mirror the view below the surface (the shading-normal terminator fix meshes
    /// use), and returned on the geometric normal's side like every vertex's shading normal.
    fn tilted_normal(&self, vertex: &Vertex, field: &NormalField, direction: DVec3) -> DVec3 {
        let primitive = &self.scene.primitives[vertex.primitive as usize];
        let front = vertex.shading_normal.dot(direction) <= 0.0;
        let facing = if front { vertex.shading_normal } else { -vertex.shading_normal };
        // The covector carries the unit world normal into object space as POV-Ray does (its
        // length matters under `no_bump_scale`; otherwise the pattern normalises it).
        let object_tilted = field.perturb(vertex.object_point, primitive.object_covector(facing));
        let tilted = primitive.world_normal(object_tilted).normalize_or_zero();
        // Zero also when the pattern gave a non-finite normal.
        if tilted == DVec3::ZERO {
            return vertex.shading_normal;
        }
        let on_front_side = if front { tilted } else { -tilted };
        shading_normal_for_view(on_front_side, vertex.geometric_normal, direction)
    }

    fn first_hit(&self, vertex: &Vertex, toward_viewer: DVec3) -> FirstHit {
        let normal =
            if vertex.shading_normal.dot(toward_viewer) < 0.0 { -vertex.shading_normal } else { vertex.shading_normal };
        FirstHit {
            albedo: DVec3::ZERO,
            normal,
            position: vertex.point,
            depth: vertex.distance,
            uv: vertex.uv,
            primitive: vertex.primitive,
            material: vertex.material,
        }
    }
}

impl Integrator for Path<'_> {
    fn sample(&self, ray: &Ray, stream: SampleStream) -> PixelSample {
        self.trace(ray, stream)
    }
}
