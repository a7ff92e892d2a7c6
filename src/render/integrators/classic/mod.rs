//! The `classic` integrator: Whitted-style recursive tracing with POV-Ray 3.7's shading
//! model, as measured in `shared/povray/REPORT.md` (sections 4.1-4.8): ambient, diffuse
//! with brilliance, phong and specular highlights (metallic), point/spot/parallel/area
//! lights with fade, filtered straight-line shadows, reflection (constant, falloff,
//! Fresnel, metallic, exponent), refraction with an interior stack, interior fade, and the
//! max_trace_level / adc_bailout limits that return black.

pub mod lights;

use glam::{DVec2, DVec3};
use prism_api::{Hit, Ray};

use crate::accel::primitive::{Primitive, leaf_of};
use crate::accel::scene_bvh::{ConvexHull, Gathered};
use crate::gamma::GammaCurve;
use crate::geometry::csg::CsgShape;
use crate::material::pov_view::{Pigment, PovFinish, PovView, ShadedFinish};
use crate::render::extract::RenderScene;
use crate::render::integrators::{FirstHit, Integrator, PixelSample};
use crate::render::lights::AreaGrid;
use crate::render::sampling::SampleStream;
use lights::{PovLight, attenuation};

/// POV-Ray ignores shadow-ray hits closer than this to the surface or the light.
const SHADOW_TOLERANCE: f64 = 1e-3;
/// Camera, reflected and refracted rays ignore hits closer than this to their origin, in world
/// units (POV-Ray's `MIN_ISECT_DEPTH`, which `Trace::FindIntersection` applies to the depth
/// along the unit world-space ray). Shadow rays ignore the larger [`SHADOW_TOLERANCE`].
const MIN_ISECT_DEPTH: f64 = 1e-4;
/// POV-Ray ignores intersections farther than this.
const MAX_DISTANCE: f64 = 1e7;
/// POV-Ray's `EPSILON`: index ratios and fade distances closer than this to 1 and 0 count
/// as equal, and light whose every channel is below it as none.
const POV_EPSILON: f64 = 1e-10;
/// Deepest nesting of interiors tracked (deeper ones are treated as leaving the outermost).
const MAX_INTERIORS: usize = 16;

thread_local! {
    /// Each render thread's memo of one area light's grid samples, stamped per use so that it
    /// never needs clearing (clearing and allocating it per shading point was a tenth of an
    /// area-lit render).
    static AREA_SAMPLES: std::cell::RefCell<(u32, Vec<(u32, DVec3)>)> = const { std::cell::RefCell::new((0, Vec::new())) };
}

/// One interior a ray can be inside, numbered by [`InteriorTable`]: an object's, told apart
/// within a CSG group by the material of the member crossed. POV-Ray gives a member with its
/// own texture an interior of its own (`prism export pov` writes one with it) and the others
/// the group's, so entering a glass member of a group is entering a new medium, not leaving
/// the group. A number rather than a pair keeps [`Interiors`], copied with every ray, small.
type InteriorId = u32;

/// The interiors a ray is inside, innermost last.
#[derive(Clone, Copy, Debug, Default)]
struct Interiors {
    items: [InteriorId; MAX_INTERIORS],
    len: usize,
}

impl Interiors {
    fn contains(&self, p: InteriorId) -> bool {
        self.items[..self.len].contains(&p)
    }

    fn innermost(&self) -> Option<InteriorId> {
        self.len.checked_sub(1).map(|i| self.items[i])
    }

    fn entering(mut self, p: InteriorId) -> Self {
        if self.len == MAX_INTERIORS {
            self.items.copy_within(1.., 0);
            self.len -= 1;
        }
        self.items[self.len] = p;
        self.len += 1;
        self
    }

    fn leaving(mut self, p: InteriorId) -> Self {
        if let Some(i) = self.items[..self.len].iter().position(|&q| q == p) {
            self.items.copy_within(i + 1..self.len, i);
            self.len -= 1;
        }
        self
    }
}

/// Per-sample state: the random stream, the rays traced and the first surface seen.
struct PathState {
    /// Random numbers of this pixel sample.
    stream: SampleStream,
    /// Next free random dimension.
    dimension: u64,
    /// Rays traced (camera, reflected, refracted, shadow).
    rays: u64,
    /// The first surface the camera ray met.
    first_hit: Option<FirstHit>,
}

impl Integrator for Classic<'_> {
    fn sample(&self, ray: &Ray, stream: SampleStream) -> PixelSample {
        let interiors = self.camera_interiors(ray.origin);
        let mut state = PathState { stream, dimension: 4, rays: 0, first_hit: None };
        let radiance = pov_output(self.trace(ray, 1, 1.0, interiors, &mut state));
        PixelSample { radiance, first_hit: state.first_hit, rays: state.rays }
    }

    fn working_gamma(&self) -> GammaCurve {
        self.scene.settings.assumed_gamma.curve()
    }

    fn keeps_nan_channels(&self) -> bool {
        true
    }
}

/// A traced colour as POV-Ray carries it to the pixel, channel by channel: an infinite
/// channel (a negative `phong_size` far from the highlight, a tiny reflection `exponent`)
/// saturates, so that it clips to white in a PNG, where the renderer's guard would zero the
/// whole sample; a NaN channel (`pow` of a negative reflected colour under a reflection
/// `exponent`, `0 x inf`) stays NaN: POV-Ray's antialiasing never finds it different from
/// its neighbours, it spreads through the pixel's mean, and the channel is written as 0
/// ([`Integrator::keeps_nan_channels`]).
fn pov_output(colour: DVec3) -> DVec3 {
    // As vector operations: an array's `map` was left as a call, and per-channel scalars
    // are stored one by one, which the caller's vector load of the result waits for (2 % of
    // a simple scene).
    let limit = DVec3::splat(f64::from(f32::MAX));
    DVec3::select(colour.is_nan_mask(), colour, colour.max(-limit).min(limit))
}

/// The scene's interiors: primitive `p`'s own is number `p`; a CSG group's members with
/// materials of their own (two members given the same named material share one, where
/// POV-Ray's export would part them) are numbered after the primitives.
struct InteriorTable {
    /// Per primitive, the interior of each CSG leaf (indexed like its leaf materials); `None`
    /// when every hit is the primitive's own.
    leaves: Vec<Option<Box<[InteriorId]>>>,
    /// The material of each interior (its medium: ior, fade).
    materials: Vec<u32>,
}

impl InteriorTable {
    fn new(scene: &RenderScene) -> Self {
        let mut materials: Vec<u32> = scene.primitives.iter().map(|p| p.material).collect();
        let leaves = scene
            .primitives
            .iter()
            .enumerate()
            .map(|(index, p)| {
                let leaf_materials = p.leaf_materials.as_deref()?;
                let mut own: Vec<(u32, InteriorId)> = Vec::new();
                let ids = leaf_materials.iter().map(|&m| {
                    if m == p.material {
                        return index as InteriorId;
                    }
                    if let Some(&(_, id)) = own.iter().find(|(material, _)| *material == m) {
                        return id;
                    }
                    let id = materials.len() as InteriorId;
                    materials.push(m);
                    own.push((m, id));
                    id
                });
                Some(ids.collect())
            })
            .collect();
        Self { leaves, materials }
    }

    /// The interior a hit on primitive `primitive` crosses into or out of.
    fn at(&self, primitive: u32, hit: &Hit) -> InteriorId {
        match &self.leaves[primitive as usize] {
            None => primitive,
            Some(leaves) => leaves.get(leaf_of(hit) as usize).copied().unwrap_or(primitive),
        }
    }
}

/// The classic integrator over one render scene.
pub struct Classic<'a> {
    scene: &'a RenderScene,
    /// The POV-Ray finish of each of the scene's materials (indexed like them): all this
    /// integrator reads of a material.
    views: Vec<PovView>,
    /// Angle between neighbouring camera rays (radians): ray footprints for texture filtering.
    pixel_spread: f64,
    /// Primitives that may hold a camera ray's origin: unbounded ones and those whose bounds
    /// meet the lens.
    camera_candidates: Vec<u32>,
    /// The interiors every camera ray starts in, when that is the same for all: a pinhole,
    /// or a lens no candidate's surface crosses.
    fixed_interiors: Option<Interiors>,
    /// The scene's lights as POV-Ray shades them.
    lights: Vec<PovLight>,
    /// The scene's interiors, CSG members' own among them.
    interiors: InteriorTable,
    /// Whether a camera ray's first hit carries its uv on untextured materials too (for the
    /// `uv` AOV; shading reads the uv of textured materials only).
    first_hit_uv: bool,
}

impl<'a> Classic<'a> {
    /// An integrator for `scene`.
    pub fn new(scene: &'a RenderScene) -> Self {
        let pixel_spread = scene.camera.up.length() / f64::from(scene.settings.height.max(1));
        let lens = scene.camera.lens_bounds();
        let camera_candidates = (0..scene.primitives.len() as u32)
            .filter(|&i| {
                let b = &scene.primitives[i as usize].world_bounds;
                b.min.cmple(lens.max).all() && b.max.cmpge(lens.min).all()
            })
            .collect::<Vec<u32>>();
        let lens_decides = camera_candidates.iter().all(|&i| Self::surface_misses_lens(scene, i, &lens));
        let views = scene.materials.iter().map(PovView::new).collect();
        let lights = scene.lights.sources.iter().map(PovLight::new).collect();
        let mut integrator = Self {
            scene,
            views,
            pixel_spread,
            camera_candidates,
            fixed_interiors: None,
            lights,
            interiors: InteriorTable::new(scene),
            first_hit_uv: false,
        };
        if scene.camera.has_single_origin() || lens_decides {
            integrator.fixed_interiors = Some(integrator.interiors_at(scene.camera.position));
        }
        integrator
    }

    /// True when the surface of primitive `index` certainly misses the world box `lens`
    /// ([`Shape::misses_hull`] of its corners), so that its inside test, which flips at each
    /// crossing, answers everywhere in the box as at the camera position (CSG groups, whose
    /// ray containers also depend on their boxes, are never taken to).
    ///
    /// [`Shape::misses_hull`]: prism_api::Shape::misses_hull
    fn surface_misses_lens(scene: &RenderScene, index: u32, lens: &prism_api::Aabb) -> bool {
        let p = &scene.primitives[index as usize];
        let corners: [DVec3; 8] = std::array::from_fn(|c| {
            let pick = |bit: usize, axis: usize| if c & bit == 0 { lens.min[axis] } else { lens.max[axis] };
            p.object_point(DVec3::new(pick(1, 0), pick(2, 1), pick(4, 2)))
        });
        CsgShape::of(p.shape.as_ref()).is_none() && p.shape.misses_hull(&corners)
    }

    /// The interiors a camera ray from `origin`, a point on the lens, starts in: the fixed
    /// ones, else [`Classic::interiors_at`] the origin.
    fn camera_interiors(&self, origin: DVec3) -> Interiors {
        self.fixed_interiors.unwrap_or_else(|| self.interiors_at(origin))
    }

    /// The same integrator, giving every first hit its uv when `uv` is true (the `uv` AOV),
    /// not only those on textured materials.
    pub fn with_first_hit_uv(self, uv: bool) -> Self {
        Self { first_hit_uv: uv, ..self }
    }

    /// The interiors a camera ray from `origin` starts in (POV-Ray's ray containers): every
    /// object whose solid holds it, in load order (the last counts as the innermost). As
    /// POV-Ray asks only objects whose bounding box holds the origin, a CSG group counts only
    /// within [`CsgShape::container_bounds`] (a union with an inverted member holds the
    /// points around it, but POV-Ray's box for it is finite).
    fn interiors_at(&self, origin: DVec3) -> Interiors {
        let mut interiors = Interiors::default();
        for &i in &self.camera_candidates {
            let p = &self.scene.primitives[i as usize];
            let point = p.object_point(origin);
            let boxed =
                CsgShape::of(p.shape.as_ref()).is_none_or(|group| group.container_bounds().contains(point, 0.0));
            if boxed && p.shape.inside(point) {
                interiors = interiors.entering(i);
            }
        }
        interiors
    }

    /// The finish at a hit with textures looked up: the footprint of a pixel's ray cone
    /// (from the camera, or from the last bounce for deeper rays, which underestimates it)
    /// picks the mip level. `textured` is the full surface, there when the material varies
    /// over it.
    fn shade<'m>(
        &self,
        view: &'m PovView,
        primitive: &Primitive,
        textured: Option<&prism_api::Surface>,
        distance: f64,
        cosine: f64,
    ) -> ShadedFinish<'m> {
        let Some(surface) = textured.filter(|_| view.varies_over_surface()) else {
            return ShadedFinish::uniform(&view.base);
        };
        let area_scale = primitive.area_scale(surface.normal);
        // A pixel's ray cone widens with distance; an orthographic pixel is a fixed width.
        let width = if self.scene.camera.orthographic { self.pixel_spread } else { self.pixel_spread * distance };
        let footprint = crate::texture::uv_footprint(width, surface.uv_density, area_scale, cosine);
        view.at_surface(surface.point, surface.uv, footprint)
    }

    fn medium_ior(&self, interiors: &Interiors) -> f64 {
        interiors.innermost().map_or(1.0, |p| self.material_of(p).interior.ior)
    }

    fn material_of(&self, interior: InteriorId) -> &PovFinish {
        &self.views[self.interiors.materials[interior as usize] as usize].base
    }

    /// The relative index (n_to / n_from) POV-Ray's Fresnel reflection uses for a ray inside
    /// `interiors` hitting primitive `p` (`ComputeRelativeIOR`). Unlike refraction, leaving a
    /// nested object compares it with the innermost interior the ray is in, which is the
    /// object itself: Fresnel then sees no index change (a POV-Ray quirk kept for parity).
    fn fresnel_eta(&self, interiors: &Interiors, p: InteriorId, ior: f64) -> f64 {
        match interiors.innermost() {
            None => ior,
            Some(_) if interiors.contains(p) && interiors.len == 1 => 1.0 / ior,
            Some(back) if interiors.contains(p) => self.material_of(back).interior.ior / ior,
            Some(back) => ior / self.material_of(back).interior.ior,
        }
    }

    fn trace(&self, ray: &Ray, level: u32, weight: f64, interiors: Interiors, state: &mut PathState) -> DVec3 {
        let scene = self.scene;
        if level > scene.settings.max_depth || weight < scene.settings.adc_bailout {
            return DVec3::ZERO;
        }
        state.rays += 1;
        // Camera rays need not be of unit length; the limit is a world distance.
        let t_min = MIN_ISECT_DEPTH / ray.direction.length();
        // Read in place, field by field: a copy of the whole hit would load pairs of fields
        // the query has just stored one by one, and wait for the stores to retire.
        let found = scene.accel.closest(&scene.primitives, ray, t_min, MAX_DISTANCE, |_| true);
        let Some(closest) = &found else {
            return scene.environment.background.0;
        };
        let primitive = &scene.primitives[closest.primitive as usize];
        let material_id = primitive.material_at(&closest.hit);
        let view = &self.views[material_id as usize];
        let object_ray = &*primitive.object_ray_of(ray);
        // The uv costs trigonometry on curved shapes, and the tangent square roots; only
        // textured materials look at them.
        let textured = view.varies_over_surface().then(|| primitive.shape.surface(object_ray, &closest.hit));
        let surface = match &textured {
            Some(surface) => surface.point_and_normals(),
            None => primitive.shape.hit_point(object_ray, &closest.hit),
        };
        let point = primitive.world_point(surface.point);
        let shading = primitive.world_normal(surface.shading_normal);
        let d = ray.direction;
        // Two-sided: shade with the normal facing the viewer.
        let facing = shading.dot(d) > 0.0;
        let raw = if facing { -shading } else { shading };
        let object_normal = if facing { -surface.shading_normal } else { surface.shading_normal };
        let distance = closest.hit.t * d.length();
        let here = self.interiors.at(closest.primitive, &closest.hit);
        let entering = !interiors.contains(here);

        // POV-Ray's `ComputeLightedTexture`: the layers from the top down, each lit with its
        // own finish and normal and seen through the filter of the layers above it
        // (`filter`, POV-Ray's filCol), until too little shows through (`trans`).
        let mut colour = DVec3::ZERO;
        let mut filter = DVec3::ONE;
        let mut trans = 1.0;
        let mut top_normal = raw;
        let mut reflections = LayerReflections::default();
        // Each light's shadow, traced once per hit and shared by the layers (POV-Ray's
        // `lightColorCache`); a single layer needs no memo.
        let mut shadows = if view.is_layered() { vec![None; self.lights.len()] } else { Vec::new() };
        for (index, layer) in view.layers().enumerate() {
            if trans <= scene.settings.adc_bailout {
                break;
            }
            // A normal pattern tilts the facing normal (POV-Ray's `Perturb_Normal`, in the
            // object's space); the layer shades and reflects with it.
            let n = match layer.normal() {
                // `no_bump_scale` keeps the length the object's transform gives POV-Ray's unit
                // world normal on its way into the pattern's frame.
                Some(field) if !field.scales_bumps() => {
                    primitive.world_normal(field.perturb(surface.point, primitive.object_covector(raw))).normalize()
                }
                Some(field) => primitive.world_normal(field.perturb(surface.point, object_normal)).normalize(),
                None => raw,
            };
            let shaded = self.shade(layer, primitive, textured.as_ref(), distance, n.dot(d) / d.length());
            let material: &PovFinish = &shaded.finish;
            let pigment = &shaded.pigment;
            if index == 0 {
                top_normal = n;
                if level == 1 && state.first_hit.is_none() {
                    state.first_hit = Some(FirstHit {
                        albedo: pigment.color,
                        normal: n,
                        position: point,
                        depth: distance,
                        uv: match &textured {
                            Some(surface) => surface.uv,
                            None if self.first_hit_uv => primitive.shape.surface(object_ray, &closest.hit).uv,
                            None => DVec2::ZERO,
                        },
                        primitive: closest.primitive,
                        material: material_id,
                    });
                }
            }
            let reflection = &material.finish.reflection;
            let mut rf = DVec3::ZERO;
            if reflection.is_reflective() {
                let c = -d.dot(n);
                let (min, max) = (reflection.min.0, reflection.max.0);
                let reflect_weight;
                (rf, reflect_weight) = if reflection.fresnel {
                    let eta = self.fresnel_eta(&interiors, here, material.interior.ior);
                    let rf = min + (max - min) * fresnel(eta, c);
                    (rf, rf.max_element())
                } else {
                    let rf = min + (max - min) * (1.0 - c).max(0.0).powf(reflection.falloff);
                    (rf, min.max_element().max(max.max_element()))
                };
                if reflection.metallic != 0.0 {
                    rf *= DVec3::ONE + reflection.metallic * (1.0 - metallic_fresnel(c)) * (pigment.color - DVec3::ONE);
                }
                reflections.push(LayerReflection {
                    normal: n,
                    rf,
                    weight: weight * trans * reflect_weight,
                    exponent: reflection.exponent,
                });
            }
            let lit = self.local_shading(point, n, d, &shaded, &interiors, &mut shadows, state);
            colour += filter * (lit + shaded.emitted);
            if !pigment.is_transparent() {
                // Nothing below shows through, and nothing refracts.
                trans = 0.0;
                break;
            }
            filter *= pigment.color * pigment.filter + DVec3::splat(pigment.transmit);
            if material.finish.conserve_energy {
                filter *= (DVec3::ONE - rf).min(DVec3::ONE);
            }
            trans = (0.297 * filter.x + 0.589 * filter.y + 0.114 * filter.z).abs().min(1.0);
        }

        // Refraction about the top layer's normal, filtered by every layer.
        let n = top_normal;
        let mut total_internal = false;
        if trans > scene.settings.adc_bailout {
            let c = -d.dot(n);
            let n_from = self.medium_ior(&interiors);
            let inner = if entering { interiors.entering(here) } else { interiors.leaving(here) };
            let interior = &view.base;
            let n_to = if entering { interior.interior.ior } else { self.medium_ior(&inner) };
            let child_weight = weight * filter.abs().max_element();
            let eta = n_from / n_to;
            let transmitted = if (eta - 1.0).abs() < POV_EPSILON {
                // No refraction: the ray continues at the same level, but POV-Ray still
                // tests the level limit first, as if it were one deeper.
                if level >= scene.settings.max_depth {
                    DVec3::ZERO
                } else {
                    filter * self.trace(&Ray::new(point, d), level, child_weight, inner, state)
                }
            } else {
                // POV-Ray refracts about the layer normal turned to face the ray (a tilted
                // normal may face away).
                let (c, toward) = if c < 0.0 { (-c, -n) } else { (c, n) };
                let k = 1.0 + eta * eta * (c * c - 1.0);
                if k < 0.0 {
                    // Total internal reflection: traced without the filter colour.
                    total_internal = true;
                    let mirror = Ray::new(point, reflect(d, n, raw));
                    self.trace(&mirror, level + 1, child_weight, interiors, state)
                } else {
                    let direction = (eta * d + (eta * c - k.sqrt()) * toward).normalize();
                    filter * self.trace(&Ray::new(point, direction), level + 1, child_weight, inner, state)
                }
            };
            // Interior fade applies where the ray leaves the object, over the distance it
            // travelled inside, and only to the light coming through (POV-Ray's attCol).
            colour += if entering { transmitted } else { transmitted * interior_fade(interior, distance, false) };
        }

        // Each layer's reflection, unfiltered by the layers above (POV-Ray adds them); after
        // total internal reflection, those about the top normal were already traced.
        for r in reflections.iter() {
            if total_internal && (r.normal - top_normal).abs().max_element() <= POV_EPSILON {
                continue;
            }
            let mirror = Ray::new(point, reflect(d, r.normal, raw));
            let mut reflected = self.trace(&mirror, level + 1, r.weight, interiors, state);
            // POV-Ray's `pow`: a negative channel (a colour with filter + transmit above 1
            // mirrored) becomes NaN and blackens the pixel's channel, as it does there.
            if r.exponent != 1.0 {
                reflected = reflected.powf(1.0 / r.exponent);
            }
            colour += r.rf * reflected;
        }
        colour
    }
    /// Ambient, emission, diffuse and highlights from every light. `shadows`, when not
    /// empty, memoises each light's shadow at `point` (indexed like the lights).
    #[allow(clippy::too_many_arguments, reason = "the shading point and frame, the finish, and the per-ray state")]
    // Its one call is in `trace`'s hottest path; whether LLVM inlines it otherwise flips
    // with unrelated changes elsewhere in the crate (5 % of a simple scene's time).
    #[inline(always)]
    fn local_shading(
        &self,
        point: DVec3,
        n: DVec3,
        d: DVec3,
        shaded: &ShadedFinish,
        interiors: &Interiors,
        shadows: &mut [Option<DVec3>],
        state: &mut PathState,
    ) -> DVec3 {
        let scene = self.scene;
        let m: &PovFinish = &shaded.finish;
        let pigment = shaded.pigment.color;
        let opacity = shaded.pigment.opacity();
        let mut colour = pigment * opacity * (m.finish.ambient.0 * scene.environment.ambient_light.0 + m.emission.0);
        // POV-Ray lights only the positive terms (ComputeDiffuseColour, ComputeOneDiffuseLight):
        // a negative diffuse, phong or specular adds nothing rather than darkening.
        if m.finish.diffuse <= 0.0 && m.finish.phong <= 0.0 && m.finish.specular <= 0.0 {
            return colour;
        }
        let mirror = d - 2.0 * d.dot(n) * n;
        for (index, light) in self.lights.iter().enumerate() {
            let (l, distance) = if light.parallel {
                let l = -light.axis;
                (l, (light.position - point).dot(l))
            } else {
                let to_light = light.position - point;
                let distance = to_light.length();
                (to_light / distance, distance)
            };
            // Under `area_illumination` each grid point is shaded from its own direction, so
            // neither the centre's side of the surface nor its cone and fade decide anything.
            let area_illumination = light.area.as_ref().filter(|grid| grid.area_illumination);
            let n_dot_l = n.dot(l);
            if area_illumination.is_none() && n_dot_l < 1e-10 {
                continue;
            }
            let mut e =
                if area_illumination.is_some() { light.color } else { light.color * attenuation(light, l, distance) };
            if e == DVec3::ZERO {
                continue;
            }
            if !light.shadowless {
                e *= match shadows.get(index).copied().flatten() {
                    Some(visibility) => visibility,
                    None => {
                        let start = ShadowStart { interiors, light_colour: e };
                        let visibility = match &light.area {
                            Some(grid) => self.area_visibility(point, l, light, grid, start, state),
                            None => self.transmittance(point, l, distance, start, None, state),
                        };
                        if let Some(slot) = shadows.get_mut(index) {
                            *slot = Some(visibility);
                        }
                        // Returned through memory just now: read singly, as a pair load would
                        // wait for the callee's stores.
                        prism_api::math::load_components(&visibility)
                    }
                };
                if e == DVec3::ZERO {
                    continue;
                }
            }
            let surface = LitSurface { point, normal: n, view: d, mirror, finish: m, pigment: &shaded.pigment };
            colour += match area_illumination {
                Some(grid) => surface.area_illuminated(light, grid, l, e, state),
                None => surface.lit(l, n_dot_l, e, !light.shadowless),
            };
        }
        colour
    }

    /// Light that reaches `point` from `distance` along `l`: 1 when unblocked, 0 behind an
    /// opaque object, and filtered by every transparent surface crossed (straight through),
    /// faded over each stretch inside an object with interior fade. The shadow ray starts as
    /// `start` says (in the interiors of the ray that found `point`) and, like POV-Ray's,
    /// restarts at each surface it crosses, ignoring hits within `SHADOW_TOLERANCE` of either
    /// end. In a scene without transparency, `blockers` (when given) holds every primitive
    /// that can lie on this shadow ray.
    // The opaque case inlined into the shading loop, the filtered one a call (inlining it
    // whole made the opaque case a call too: 4 % of a simple scene).
    #[inline(always)]
    fn transmittance(
        &self,
        point: DVec3,
        l: DVec3,
        distance: f64,
        start: ShadowStart,
        blockers: Option<&[u32]>,
        state: &mut PathState,
    ) -> DVec3 {
        let scene = self.scene;
        let t_max = distance - SHADOW_TOLERANCE;
        if t_max <= SHADOW_TOLERANCE {
            return DVec3::ONE;
        }
        state.rays += 1;
        if !scene.has_transparency {
            let casts = |p: u32| !scene.primitives[p as usize].no_shadow;
            let ray = Ray::new(point, l);
            let blocked = scene.accel.occluded_among(&scene.primitives, blockers, &ray, SHADOW_TOLERANCE, t_max, casts);
            return if blocked { DVec3::ZERO } else { DVec3::ONE };
        }
        self.filtered_transmittance(point, l, distance, start)
    }

    /// [`Self::transmittance`] through a scene with transparency: the shadow ray followed
    /// from surface to surface.
    #[inline(never)]
    fn filtered_transmittance(&self, point: DVec3, l: DVec3, distance: f64, start: ShadowStart) -> DVec3 {
        let scene = self.scene;
        let casts = |p: u32| !scene.primitives[p as usize].no_shadow;
        let mut filter = DVec3::ONE;
        let mut inside = *start.interiors;
        let mut origin = point;
        let mut remaining = distance;
        loop {
            let ray = Ray::new(origin, l);
            let t_max = remaining - SHADOW_TOLERANCE;
            if t_max <= SHADOW_TOLERANCE {
                return filter;
            }
            // In place, as in `trace`.
            let found = scene.accel.closest(&scene.primitives, &ray, SHADOW_TOLERANCE, t_max, casts);
            let Some(hit) = &found else {
                return filter;
            };
            let primitive = &scene.primitives[hit.primitive as usize];
            let view = &self.views[primitive.material_at(&hit.hit) as usize];
            if !view.is_transparent() {
                return DVec3::ZERO;
            }
            let here = self.interiors.at(hit.primitive, &hit.hit);
            // Patterns' filter and transmit vary: they are looked up where the shadow ray
            // crosses (in the object's space, as shading does), every layer's.
            filter *= view.shadow_filter(primitive.object_ray_of(&ray).at(hit.hit.t));
            let m = &view.base;
            let leaving = inside.contains(here);
            if leaving {
                filter *= interior_fade(m, hit.hit.t, true);
            }
            // POV-Ray (ComputeShadowMedia) notes the crossing only while some channel of the
            // light left is at least its EPSILON: past a surface that turns the light
            // negative or nearly black, the shadow ray is not taken to be inside the object
            // (so its far side fades nothing).
            if (start.light_colour * filter).cmpge(DVec3::splat(POV_EPSILON)).any() {
                inside = if leaving { inside.leaving(here) } else { inside.entering(here) };
            }
            // POV-Ray follows the shadow ray on while any channel is not 0, negative too.
            if filter == DVec3::ZERO {
                return DVec3::ZERO;
            }
            origin = ray.at(hit.hit.t);
            remaining -= hit.hit.t;
        }
    }

    /// POV-Ray's hierarchical (trapezoid-like) average of the shadow over the area grid.
    fn area_visibility(
        &self,
        point: DVec3,
        l: DVec3,
        light: &PovLight,
        grid: &AreaGrid,
        start: ShadowStart,
        state: &mut PathState,
    ) -> DVec3 {
        let (axis1, axis2) = if grid.orient { oriented_axes(l, grid.axis1.length()) } else { (grid.axis1, grid.axis2) };
        let (n1, n2) = (grid.size1 as usize, grid.size2 as usize);
        let jitter_base = state.dimension;
        state.dimension += 2 * (n1 * n2) as u64;
        AREA_SAMPLES.with_borrow_mut(|(stamp, cache)| {
            *stamp = stamp.wrapping_add(1);
            if *stamp == 0 {
                cache.fill((0, DVec3::ZERO));
                *stamp = 1;
            }
            if cache.len() < n1 * n2 {
                cache.resize(n1 * n2, (0, DVec3::ZERO));
            }
            self.area_grid_average(point, light, grid, (axis1, axis2), start, jitter_base, (*stamp, cache), state)
        })
    }

    /// The hierarchical average of one area light's shadow at `point`: a fixed weighted sum
    /// when the grid always subdivides fully, else POV-Ray's recursion, memoising grid
    /// samples in `cache` under `stamp`.
    #[allow(
        clippy::too_many_arguments,
        reason = "the shading point, the light and its grid, and the per-ray state the recursion carries"
    )]
    fn area_grid_average(
        &self,
        point: DVec3,
        light: &PovLight,
        grid: &AreaGrid,
        axes: (DVec3, DVec3),
        start: ShadowStart,
        jitter_base: u64,
        (stamp, cache): (u32, &mut [(u32, DVec3)]),
        state: &mut PathState,
    ) -> DVec3 {
        let n1 = grid.size1 as usize;
        let lattice = GridLattice::new(grid, axes, jitter_base);
        // Shadow rays only meet what lies in the frustum from the point to the light: find
        // that once, not per sample (opaque scenes; transparent ones follow every ray). With
        // nothing there, every sample sees the light.
        let mut gathered = Gathered::default();
        let scene = self.scene;
        let blockers = (!scene.has_transparency
            && scene.accel.gather(&scene.primitives, &lattice.frustum(point, light.position), &mut gathered))
        .then(|| gathered.as_slice());
        if blockers.is_some_and(|b| b.is_empty()) {
            return DVec3::ONE;
        }
        if let Some(weights) = &grid.fixed_weights {
            let mut sum = DVec3::ZERO;
            for (index, &weight) in weights.iter().enumerate() {
                let target = lattice.point(light.position, index % n1, index / n1, state);
                sum += weight * self.area_sample_visibility(point, target, start, blockers, state);
            }
            return sum;
        }
        let mut sample = |u: usize, v: usize, state: &mut PathState| -> DVec3 {
            let (seen, c) = cache[v * n1 + u];
            if seen == stamp {
                return c;
            }
            let target = lattice.point(light.position, u, v, state);
            let c = self.area_sample_visibility(point, target, start, blockers, state);
            cache[v * n1 + u] = (stamp, c);
            c
        };
        let refinement = GridRefinement { adaptive: grid.adaptive, light_colour: start.light_colour };
        block(&mut sample, 0, 0, n1 - 1, grid.size2 as usize - 1, 0, refinement, state)
    }

    /// The light reaching `point` from one area-light sample at `target`.
    #[inline]
    fn area_sample_visibility(
        &self,
        point: DVec3,
        target: DVec3,
        start: ShadowStart,
        blockers: Option<&[u32]>,
        state: &mut PathState,
    ) -> DVec3 {
        let to = target - point;
        let distance = to.length();
        self.transmittance(point, to * distance.recip(), distance, start, blockers, state)
    }
}

/// Where a shadow ray starts: inside the interiors of the ray that found the shaded point
/// (POV-Ray copies that ray), carrying the light's colour as it leaves the light (colour
/// times fade and spot falloff), which decides whether a crossing counts as entering.
#[derive(Clone, Copy)]
struct ShadowStart<'a> {
    interiors: &'a Interiors,
    light_colour: DVec3,
}

/// What one layer's reflection needs once refraction has been traced.
#[derive(Clone, Copy, Debug)]
struct LayerReflection {
    /// The layer's shading normal.
    normal: DVec3,
    /// Its reflectivity toward the viewer.
    rf: DVec3,
    /// The reflected ray's weight (for `adc_bailout`).
    weight: f64,
    /// POV-Ray's reflection `exponent`.
    exponent: f64,
}

/// The reflecting layers of one hit, top first: the first held inline (most materials have
/// one layer), the rest in a vector.
#[derive(Default)]
struct LayerReflections {
    first: Option<LayerReflection>,
    rest: Vec<LayerReflection>,
}

impl LayerReflections {
    fn push(&mut self, r: LayerReflection) {
        if self.first.is_none() {
            self.first = Some(r);
        } else {
            self.rest.push(r);
        }
    }

    fn iter(&self) -> impl Iterator<Item = &LayerReflection> {
        self.first.iter().chain(&self.rest)
    }
}

/// A point being shaded, with what every light's contribution there needs.
struct LitSurface<'m> {
    point: DVec3,
    /// Unit shading normal, facing the viewer.
    normal: DVec3,
    /// Unit direction of the ray that found the point.
    view: DVec3,
    /// `view` mirrored about `normal` (Phong's reflection vector).
    mirror: DVec3,
    finish: &'m PovFinish,
    /// The pigment at the point (the finish's own colour, filter and transmit are not read).
    pigment: &'m Pigment,
}

impl LitSurface<'_> {
    /// Diffuse light and, with `highlights`, Phong and specular highlights from light `e`
    /// (POV-Ray's light colour, already attenuated and shadowed) arriving along unit `l`,
    /// with `n_dot_l` > 0.
    fn lit(&self, l: DVec3, n_dot_l: f64, e: DVec3, highlights: bool) -> DVec3 {
        let m = self.finish;
        let pigment = self.pigment.color;
        let mut colour = DVec3::ZERO;
        if m.finish.diffuse > 0.0 {
            let cosine = if m.finish.brilliance == 1.0 { n_dot_l } else { pow(n_dot_l, m.finish.brilliance) };
            colour += m.finish.diffuse * self.pigment.opacity() * cosine * pigment * e;
        }
        if !highlights {
            return colour;
        }
        let highlight = if m.finish.metallic != 0.0 {
            e * (DVec3::ONE + m.finish.metallic * (1.0 - metallic_fresnel(n_dot_l)) * (pigment - DVec3::ONE))
        } else {
            e
        };
        if m.finish.phong > 0.0 {
            let r_dot_l = self.mirror.dot(l);
            if r_dot_l > 0.0 && !(m.finish.phong_size >= 60.0 && r_dot_l <= 0.0008) {
                colour += m.finish.phong * pow(r_dot_l, m.finish.phong_size) * highlight;
            }
        }
        if m.finish.specular > 0.0 {
            let h = (l - self.view).normalize();
            let n_dot_h = self.normal.dot(h);
            if n_dot_h > 0.0 {
                colour += m.finish.specular * pow(n_dot_h, 1.0 / m.finish.roughness) * highlight;
            }
        }
        colour
    }

    /// POV-Ray 3.7's `area_illumination`: light `e` (the unattenuated colour times the
    /// grid's shadow average) split evenly over every point of the full grid, each shading
    /// the surface from its own (jittered, oriented, circular) position with its own spot
    /// cone and fade, and skipped when it lies behind the surface. The grid is walked
    /// whole, not adaptively, as POV-Ray does; jitter draws its own numbers.
    fn area_illuminated(&self, light: &PovLight, grid: &AreaGrid, l: DVec3, e: DVec3, state: &mut PathState) -> DVec3 {
        let axes = if grid.orient { oriented_axes(l, grid.axis1.length()) } else { (grid.axis1, grid.axis2) };
        let (n1, n2) = (grid.size1 as usize, grid.size2 as usize);
        let lattice = GridLattice::new(grid, axes, state.dimension);
        state.dimension += 2 * (n1 * n2) as u64;
        let share = e / (n1 * n2) as f64;
        let mut colour = DVec3::ZERO;
        for v in 0..n2 {
            for u in 0..n1 {
                let to_point = lattice.point(light.position, u, v, state) - self.point;
                let distance = to_point.length();
                let l = to_point / distance;
                let n_dot_l = self.normal.dot(l);
                if n_dot_l < 1e-10 {
                    continue;
                }
                let e = share * attenuation(light, l, distance);
                if e != DVec3::ZERO {
                    colour += self.lit(l, n_dot_l, e, !light.shadowless);
                }
            }
        }
        colour
    }
}

/// Where the samples of one area light lie for one shading point: the grid's (possibly
/// oriented) axes and steps, and where its jitter numbers start.
struct GridLattice<'a> {
    grid: &'a AreaGrid,
    axis1: DVec3,
    axis2: DVec3,
    /// Grid steps as fractions of the light's size, multiplied rather than divided per sample.
    step1: f64,
    step2: f64,
    jitter_base: u64,
}

impl<'a> GridLattice<'a> {
    fn new(grid: &'a AreaGrid, (axis1, axis2): (DVec3, DVec3), jitter_base: u64) -> Self {
        let step = |n: u32| if n > 1 { 1.0 / (n - 1) as f64 } else { 0.0 };
        Self { grid, axis1, axis2, step1: step(grid.size1), step2: step(grid.size2), jitter_base }
    }

    /// The world position of sample (u, v) of a light centred at `centre`, jittered and
    /// mapped to a disc as the grid asks (POV-Ray's positions).
    #[inline]
    fn point(&self, centre: DVec3, u: usize, v: usize, state: &mut PathState) -> DVec3 {
        let grid = self.grid;
        let (mut ju, mut jv) = (u as f64, v as f64);
        if grid.jitter {
            let k = self.jitter_base + 2 * (v * grid.size1 as usize + u) as u64;
            ju += state.stream.uniform(k) - 0.5;
            jv += state.stream.uniform(k + 1) - 0.5;
        }
        let mut fu = if grid.size1 > 1 { ju * self.step1 - 0.5 } else { 0.0 };
        let mut fv = if grid.size2 > 1 { jv * self.step2 - 0.5 } else { 0.0 };
        if grid.circular {
            fu += 0.001;
            fv += 0.001;
            let s = fu.abs().max(fv.abs()) / (fu * fu + fv * fv).sqrt();
            fu *= s;
            fv *= s;
        }
        centre + self.axis1 * fu + self.axis2 * fv
    }

    /// A frustum holding every shadow ray from `apex` to a sample of the light centred at
    /// `centre` (past the shadow tolerance): the light's parallelogram is widened by the
    /// jitter's half step and the circular mapping's offset.
    fn frustum(&self, apex: DVec3, centre: DVec3) -> ConvexHull {
        let grid = self.grid;
        let jitter = if grid.jitter { 0.5 } else { 0.0 };
        let reach = |step: f64| 0.5 + jitter * step + 0.002;
        let (edge1, edge2) = (self.axis1 * reach(self.step1), self.axis2 * reach(self.step2));
        ConvexHull::shadow_frustum(apex, centre, edge1, edge2, SHADOW_TOLERANCE)
    }
}

/// The axes, both of length `length`, of an `orient` area light seen along `l` (unit, from
/// the shaded point to the light), as POV-Ray constructs them: `axis1 = l x t` with `t` the
/// z axis (the y axis when `l` is within 0.01 of vertical in z), `axis2 = l x axis1`.
/// POV-Ray takes these cross products in its left-handed frame, i.e. of the exported
/// `(x, y, -z)` vectors; a cross product of mirrored vectors is the mirrored cross product
/// negated, so in Prism's frame `axis1 = t' x l` (t' the mirrored t: -z or y) and
/// `axis2 = axis1 x l`. With the circular grid's 0.001 offset, the sign of each axis moves
/// the samples.
/// The mirror direction of `d` about the shading normal `n`, as POV-Ray's
/// `ComputeReflection`: a direction that a tilted normal sends below the surface (the
/// facing geometric normal `raw`) is reflected about `raw` instead, or reflected back
/// above it.
fn reflect(d: DVec3, n: DVec3, raw: DVec3) -> DVec3 {
    let mut r = d - 2.0 * d.dot(n) * n;
    if n != raw && r.dot(raw) < 0.0 {
        r = if r.dot(n) < 0.0 { d - 2.0 * d.dot(raw) * raw } else { r - 2.0 * r.dot(raw) * raw };
    }
    r.normalize()
}

fn oriented_axes(l: DVec3, length: f64) -> (DVec3, DVec3) {
    let t = if (l.z.abs() - 1.0).abs() < 0.01 { DVec3::Y } else { DVec3::NEG_Z };
    let axis1 = t.cross(l).normalize();
    let axis2 = axis1.cross(l).normalize();
    (axis1 * length, axis2 * length)
}

/// When POV-Ray subdivides a region of an area light's grid.
#[derive(Clone, Copy, Debug)]
struct GridRefinement {
    /// Levels subdivided whatever the samples (`adaptive`).
    adaptive: u32,
    /// The light's colour the samples filter (its colour times fade and spot falloff, or its
    /// bare colour under `area_illumination`): POV-Ray compares the light that arrives, so
    /// corners subdivide when that differs by more than 0.1 summed over the channels.
    light_colour: DVec3,
}

/// One region of POV-Ray's recursive area-light average.
#[allow(clippy::too_many_arguments, reason = "a region is its two corners (four numbers) plus the recursion's state")]
fn block(
    sample: &mut impl FnMut(usize, usize, &mut PathState) -> DVec3,
    u1: usize,
    v1: usize,
    u2: usize,
    v2: usize,
    level: u32,
    refinement: GridRefinement,
    state: &mut PathState,
) -> DVec3 {
    let c00 = sample(u1, v1, state);
    let c10 = sample(u2, v1, state);
    let c01 = sample(u1, v2, state);
    let c11 = sample(u2, v2, state);
    let differ = |a: DVec3, b: DVec3| ((a - b) * refinement.light_colour).abs().element_sum() > 0.1;
    let large = u2 - u1 > 1 || v2 - v1 > 1;
    if large
        && (level < refinement.adaptive || differ(c00, c10) || differ(c00, c01) || differ(c10, c11) || differ(c01, c11))
    {
        let (mid_u_lo, mid_v_lo) = ((u1 + u2) / 2, (v1 + v2) / 2);
        let (mid_u_hi, mid_v_hi) = ((u1 + u2).div_ceil(2), (v1 + v2).div_ceil(2));
        let a = block(sample, u1, v1, mid_u_lo, mid_v_lo, level + 1, refinement, state);
        let b = block(sample, mid_u_hi, v1, u2, mid_v_lo, level + 1, refinement, state);
        let c = block(sample, u1, mid_v_hi, mid_u_lo, v2, level + 1, refinement, state);
        let d = block(sample, mid_u_hi, mid_v_hi, u2, v2, level + 1, refinement, state);
        (a + b + c + d) * 0.25
    } else {
        (c00 + c10 + c01 + c11) * 0.25
    }
}

/// `x^e`, with whole exponents (phong sizes, tightness, fade powers are usually whole) by
/// repeated multiplication, which is several times faster than `powf` and as accurate.
#[inline]
fn pow(x: f64, e: f64) -> f64 {
    if e.fract() == 0.0 && e.abs() <= 1024.0 { x.powi(e as i32) } else { x.powf(e) }
}

/// POV-Ray's approximate Fresnel term for metallic highlights and reflection.
fn metallic_fresnel(cosine: f64) -> f64 {
    let x = cosine.clamp(-1.0, 1.0).acos() / std::f64::consts::FRAC_PI_2;
    (0.014567225 / ((x - 1.12) * (x - 1.12)) - 0.011612903).clamp(0.0, 1.0)
}

/// Unpolarised Fresnel reflectance for relative index `eta` (n_to / n_from) and cosine `c`.
fn fresnel(eta: f64, c: f64) -> f64 {
    let g2 = eta * eta + c * c - 1.0;
    if g2 <= 0.0 {
        return 1.0;
    }
    let g = g2.sqrt();
    let a = (g - c) / (g + c);
    let b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
    // A normal tilted by a pattern may face away from the ray (c < 0), where the formula
    // leaves [0, 1] (57 at c = -0.9 for ior 1.32): POV-Ray clamps it.
    (0.5 * a * a * (1.0 + b * b)).clamp(0.0, 1.0)
}

/// Interior attenuation over path length `s`. POV-Ray tests the two ray kinds differently:
/// a camera-side ray fades whenever `fade_distance` is not 0 (with `fade_power` 0 that is a
/// constant halfway blend), a shadow ray only when `fade_power` is positive as well.
fn interior_fade(m: &PovFinish, s: f64, shadow: bool) -> DVec3 {
    if m.interior.fade_distance.abs() <= POV_EPSILON || (shadow && m.interior.fade_power <= 0.0) {
        return DVec3::ONE;
    }
    let fade_color = m.interior.fade_color.0;
    if m.interior.fade_power >= 1000.0 {
        let k = (DVec3::ONE - fade_color) * (s / m.interior.fade_distance);
        DVec3::new((-k.x).exp(), (-k.y).exp(), (-k.z).exp())
    } else {
        fade_color + (DVec3::ONE - fade_color) / (1.0 + (s / m.interior.fade_distance).powf(m.interior.fade_power))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn oriented_axes_are_pov_rays_in_the_exported_frame() {
        // POV-Ray, light along its +x: axis1 = x cross z = -y, axis2 = x cross -y = -z, which is
        // +z in Prism's frame (z mirrored).
        let (a1, a2) = oriented_axes(DVec3::X, 2.0);
        assert!((a1 - DVec3::new(0.0, -2.0, 0.0)).length() < 1e-12, "{a1}");
        assert!((a2 - DVec3::new(0.0, 0.0, 2.0)).length() < 1e-12, "{a2}");
        // Light straight up Prism's -z (POV-Ray's +z): t = y, axis1 = z cross y = -x,
        // axis2 = z cross -x = -y, unchanged by the mirror.
        let (a1, a2) = oriented_axes(DVec3::NEG_Z, 1.0);
        assert!((a1 - DVec3::NEG_X).length() < 1e-12, "{a1}");
        assert!((a2 - DVec3::NEG_Y).length() < 1e-12, "{a2}");
    }

    #[test]
    fn reflection_about_a_tilted_normal_stays_above_the_surface() {
        let raw = DVec3::Y;
        // Untilted: the plain mirror.
        let d = DVec3::new(1.0, -1.0, 0.0).normalize();
        assert!((reflect(d, raw, raw) - DVec3::new(1.0, 1.0, 0.0).normalize()).length() < 1e-12);
        // A steep ray and a normal tilted nearly flat: the mirror about the tilted normal goes
        // below the surface but stays on the tilted normal's side, so POV-Ray reflects it back
        // up about the raw normal.
        let d = DVec3::NEG_Y;
        let n = DVec3::new(1.0, 0.1, 0.0).normalize();
        let tilted = d - 2.0 * d.dot(n) * n;
        assert!(tilted.dot(raw) < 0.0 && tilted.dot(n) > 0.0, "{tilted}");
        let expected = (tilted - 2.0 * tilted.dot(raw) * raw).normalize();
        let r = reflect(d, n, raw);
        assert!((r - expected).length() < 1e-12 && r.y > 0.0, "{r}");
        // A normal tilted away from the ray: the mirror falls behind it too, and POV-Ray
        // mirrors about the raw normal instead.
        let d = DVec3::new(0.2, -1.0, 0.0).normalize();
        let n = DVec3::new(1.0, 0.05, 0.0).normalize();
        let tilted = d - 2.0 * d.dot(n) * n;
        assert!(tilted.dot(raw) < 0.0 && tilted.dot(n) < 0.0, "{tilted}");
        assert!((reflect(d, n, raw) - (d - 2.0 * d.dot(raw) * raw).normalize()).length() < 1e-12);
    }

    #[test]
    fn fresnel_matches_pov_ray_measurement() {
        // REPORT.md 7: ior 1.5 at 60 degrees -> 0.08919.
        assert!((fresnel(1.5, 60f64.to_radians().cos()) - 0.08919).abs() < 1e-5);
        assert_eq!(fresnel(1.0 / 1.5, 0.1), 1.0, "total internal reflection");
        // Facing away (a tilted normal): clamped to [0, 1] as in POV-Ray's ComputeReflectivity.
        for c in [-0.9, -0.5, -0.1] {
            let f = fresnel(1.32, c);
            assert!((0.0..=1.0).contains(&f), "{c}: {f}");
        }
        assert_eq!(fresnel(1.32, -0.5), 1.0);
    }

    /// POV-Ray's recursive average over samples `value(u, v)` of an `n1` x `n2` grid.
    fn recursive_average(n1: usize, n2: usize, adaptive: u32, value: impl Fn(usize, usize) -> DVec3) -> DVec3 {
        let mut state = PathState { stream: SampleStream::new(0, 0, 0), dimension: 0, rays: 0, first_hit: None };
        let refinement = GridRefinement { adaptive, light_colour: DVec3::ONE };
        block(&mut |u, v, _: &mut PathState| value(u, v), 0, 0, n1 - 1, n2 - 1, 0, refinement, &mut state)
    }

    #[test]
    fn fixed_area_weights_equal_the_recursion_whenever_they_exist() {
        // Samples far apart, so that the recursion would split wherever it may.
        let value = |u: usize, v: usize| DVec3::new((u * 7 + v * 3) as f64 % 5.0, (u ^ v) as f64, (u * v) as f64 * 0.3);
        for n1 in 1..=9 {
            for n2 in 1..=9 {
                for adaptive in 0..5 {
                    let Some(weights) = AreaGrid::fixed_weights(n1 as u32, n2 as u32, adaptive) else {
                        assert!(n1 > 2 || n2 > 2, "{n1}x{n2} never splits, so it is always fixed");
                        continue;
                    };
                    assert!((weights.iter().sum::<f64>() - 1.0).abs() < 1e-12);
                    let sum: DVec3 = weights.iter().enumerate().map(|(i, w)| *w * value(i % n1, i / n1)).sum();
                    let expected = recursive_average(n1, n2, adaptive, value);
                    assert!((sum - expected).abs().max_element() < 1e-12, "{n1}x{n2} adaptive {adaptive}");
                }
            }
        }
        // Full subdivision of 5 samples weighs them 1, 2, 2, 2, 1 (POV-Ray's pattern).
        let weights = AreaGrid::fixed_weights(5, 1, 100).unwrap();
        let expected = [1.0, 2.0, 2.0, 2.0, 1.0].map(|w| w / 8.0);
        assert!(weights.iter().zip(expected).all(|(w, e)| (w - e).abs() < 1e-15), "{weights:?}");
        // A shallow adaptive level leaves the rest to the samples.
        assert!(AreaGrid::fixed_weights(5, 5, 1).is_none());
        assert!(AreaGrid::fixed_weights(5, 5, 2).is_some());
    }

    /// Camera rays start inside the objects whose solids hold the camera: with and without
    /// an aperture, through transforms, and a plane whose normal faces away.
    /// A white floor seen straight down at the point under a two-point area light whose
    /// points stand 45 degrees off the vertical: shaded from the centre (straight above) the
    /// diffuse light is the light's colour; with `area_illumination` each point brings half
    /// of it at cos 45, 1/sqrt(2) in all (POV-Ray 3.7's `ComputeFullAreaDiffuseLight`).
    #[test]
    fn area_illumination_shades_from_every_grid_point() {
        use crate::scene::load::{Embedded, load_from};
        macro_rules! scene {
            ($flag:literal) => {
                concat!(
                    "[render]\nwidth = 1\nheight = 1\n",
                    "[camera]\nposition = [0.0, 0.5, 0.001]\nlook_at = [0.0, 0.0, 0.0]\nvfov = 0.01\n",
                    "[[object]]\nshape = \"plane\"\nnormal = [0.0, 1.0, 0.0]\noffset = 0.0\n",
                    "material = { color = [1.0, 1.0, 1.0], diffuse = 1.0, ambient = [0.0, 0.0, 0.0] }\n",
                    "[[light]]\nkind = \"area\"\nposition = [0.0, 1.0, 0.0]\naxis1 = [2.0, 0.0, 0.0]\n",
                    "axis2 = [0.0, 0.0, 1.0]\nsize1 = 2\nsize2 = 1\n",
                    $flag,
                )
            };
        }
        const CENTRE: Embedded = Embedded(&[("s.toml", scene!(""))]);
        const EVERY_POINT: Embedded = Embedded(&[("s.toml", scene!("area_illumination = true\n"))]);
        for (files, expected) in [(CENTRE, 1.0), (EVERY_POINT, std::f64::consts::FRAC_1_SQRT_2)] {
            let mut scene = load_from(&files, std::path::Path::new("s.toml"), &crate::plugins::registry()).unwrap();
            let scene = crate::prepare(&mut scene).unwrap();
            let (film, _) = crate::render::render_frame(&scene, &Default::default()).unwrap();
            let value = f64::from(film.pixels[0][1]);
            assert!((value - expected).abs() < 1e-4, "{value} against {expected}");
        }
    }

    /// A small frame of a sphere of material `material` (a TOML inline table) over a
    /// patterned floor, lit by a point light: its pixels.
    fn render_sphere(material: &str) -> Vec<[f32; 3]> {
        use crate::scene::load::{Embedded, load_from};
        let text = format!(
            "[render]\nwidth = 24\nheight = 16\nmax_depth = 6\n\
             [camera]\nposition = [0.0, 1.0, 3.0]\nlook_at = [0.0, 0.0, 0.0]\nvfov = 50.0\n\
             [[object]]\nshape = \"plane\"\nnormal = [0.0, 1.0, 0.0]\noffset = -1.0\n\
             material = {{ pigment = {{ pattern = \"checker\", colors = [[0.9, 0.9, 0.9], [0.1, 0.2, 0.5]], scale = 0.5 }} }}\n\
             [[object]]\nshape = \"sphere\"\nradius = 1.0\nmaterial = {material}\n\
             [[light]]\nposition = [2.0, 4.0, 3.0]\n"
        );
        let text: &'static str = Box::leak(text.into_boxed_str());
        let files = Embedded(Box::leak(Box::new([("s.toml", text)])));
        let mut scene = load_from(&files, std::path::Path::new("s.toml"), &crate::plugins::registry()).unwrap();
        let scene = crate::prepare(&mut scene).unwrap();
        crate::render::render_frame(&scene, &Default::default()).unwrap().0.pixels
    }

    /// POV-Ray stops at a layer nothing shows through: an opaque top layer hides every layer
    /// below it, in shading, reflection, refraction and shadows.
    #[test]
    fn an_opaque_top_layer_is_that_layer_alone() {
        let top = "{ color = [0.8, 0.2, 0.1], phong = 0.7, reflection = 0.2, normal = { pattern = \"bumps\", bump_size = 0.5, scale = 0.2 } }";
        let below = "{ color = [0.2, 0.9, 0.3], filter = 0.6, reflection = 0.5, specular = 1.0 }";
        let layered = render_sphere(&format!("{{ ior = 1.3, layers = [{below}, {top}] }}"));
        let alone = render_sphere(&format!("{{ ior = 1.3, {} }}", &top[2..top.len() - 2]));
        assert_eq!(layered, alone);
    }

    /// A clear top layer (transmit 1, no highlights or reflection) adds nothing and filters
    /// nothing: the layer below is seen, reflects, refracts and casts its shadow as it does
    /// alone. (POV-Ray refracts about the top layer's normal, so a normal pattern below
    /// changes refraction: that case is compared without refraction.)
    #[test]
    fn a_fully_transmitting_top_layer_shows_the_layer_below() {
        let below = "color = [0.9, 0.5, 0.2], filter = 0.5, phong = 0.5, reflection = 0.1";
        let dents = "normal = { pattern = \"dents\", scale = 0.3 }";
        for (ior, below) in [(1.3, below.to_string()), (1.0, format!("{below}, {dents}"))] {
            let layered = render_sphere(&format!("{{ ior = {ior}, layers = [{{ {below} }}, {{ transmit = 1.0 }}] }}"));
            let alone = render_sphere(&format!("{{ ior = {ior}, {below} }}"));
            assert_eq!(layered, alone, "ior {ior}");
        }
        // The layers do matter: the same top layer with some opacity changes the picture, and
        // so does refraction about the clear layer's normal instead of the dented one below.
        let dented = format!("{below}, {dents}");
        let tinted = render_sphere(&format!("{{ ior = 1.3, layers = [{{ {below} }}, {{ transmit = 0.7 }}] }}"));
        assert_ne!(tinted, render_sphere(&format!("{{ ior = 1.3, {below} }}")));
        let layered = render_sphere(&format!("{{ ior = 1.3, layers = [{{ {dented} }}, {{ transmit = 1.0 }}] }}"));
        assert_ne!(layered, render_sphere(&format!("{{ ior = 1.3, {dented} }}")));
    }

    #[test]
    fn camera_rays_start_in_the_interiors_around_the_camera() {
        use crate::scene::load::{Embedded, load_from};
        macro_rules! scene {
            ($lens:literal) => {
                concat!(
                    "[camera]\nposition = [0.0, 0.0, 0.0]\nlook_at = [0.0, 0.0, -1.0]\n",
                    $lens,
                    "[[object]]\nshape = \"sphere\"\nradius = 1.0\ntransform = { translate = [0.3, 0.0, 0.0] }\n",
                    "[[object]]\nshape = \"sphere\"\nradius = 1.0\ntransform = { translate = [3.0, 0.0, 0.0] }\n",
                    "[[object]]\nshape = \"plane\"\nnormal = [0.0, 0.0, 1.0]\noffset = -5.0\n",
                    "[[object]]\nshape = \"plane\"\nnormal = [0.0, 0.0, -1.0]\noffset = 5.0\n",
                )
            };
        }
        const PINHOLE: Embedded = Embedded(&[("s.toml", scene!(""))]);
        const LENS: Embedded = Embedded(&[("s.toml", scene!("aperture = 0.2\n"))]);
        for (files, aperture) in [(PINHOLE, false), (LENS, true)] {
            let mut scene = load_from(&files, std::path::Path::new("s.toml"), &crate::plugins::registry()).unwrap();
            let scene = crate::prepare(&mut scene).unwrap();
            let integrator = Classic::new(&scene);
            let inside = integrator.interiors_at(DVec3::ZERO);
            assert_eq!(&inside.items[..inside.len], &[0, 3], "aperture {aperture}");
            assert_eq!(integrator.fixed_interiors.is_some(), !aperture);
            let outside = integrator.interiors_at(DVec3::new(0.0, 0.0, -7.0));
            assert_eq!(&outside.items[..outside.len], &[2], "beyond the far plane");
        }
    }

    #[test]
    fn a_lens_no_surface_crosses_starts_every_ray_in_the_same_interiors() {
        use crate::scene::load::{Embedded, load_from};
        // A lens of radius 0.1 at the origin, behind a floor plane (inside it) and in front
        // of a wall (outside it); the third plane's surface, x = 0.05, crosses the lens.
        macro_rules! scene {
            ($third:literal) => {
                concat!(
                    "[camera]\nposition = [0.0, 0.0, 0.0]\nlook_at = [0.0, 0.0, -1.0]\naperture = 0.2\n",
                    "[[object]]\nshape = \"plane\"\nnormal = [0.0, 1.0, 0.0]\noffset = 1.0\n",
                    "[[object]]\nshape = \"plane\"\nnormal = [0.0, 0.0, 1.0]\noffset = -3.0\n",
                    "[[object]]\nshape = \"plane\"\nnormal = [1.0, 0.0, 0.0]\n",
                    $third,
                    "\n",
                )
            };
        }
        const APART: Embedded = Embedded(&[("s.toml", scene!("offset = 0.5"))]);
        const ACROSS: Embedded = Embedded(&[("s.toml", scene!("offset = 0.05"))]);
        for (files, crossed) in [(APART, false), (ACROSS, true)] {
            let mut scene = load_from(&files, std::path::Path::new("s.toml"), &crate::plugins::registry()).unwrap();
            let scene = crate::prepare(&mut scene).unwrap();
            let integrator = Classic::new(&scene);
            assert_eq!(integrator.fixed_interiors.is_none(), crossed);
            for (x, y) in [(-0.1, 0.0), (0.0, 0.1), (0.09, -0.02), (0.04, 0.05)] {
                let origin = DVec3::new(x, y, 0.0);
                let asked = integrator.interiors_at(origin);
                let got = integrator.camera_interiors(origin);
                assert_eq!(&got.items[..got.len], &asked.items[..asked.len], "lens point {origin}, crossed {crossed}");
                let third_holds = !crossed || x < 0.05;
                let expected: &[u32] = if third_holds { &[0, 2] } else { &[0] };
                assert_eq!(&got.items[..got.len], expected, "lens point {origin}, crossed {crossed}");
            }
        }
    }

    #[test]
    fn csg_members_with_materials_of_their_own_are_interiors_of_their_own() {
        use crate::scene::load::{Embedded, load_from};
        const SCENE: Embedded = Embedded(&[(
            "s.toml",
            "[materials.glass]\nior = 1.5\n\
             [[object]]\nshape = \"sphere\"\nradius = 1.0\n\
             [[object]]\nshape = \"union\"\nmaterial = { ior = 1.2 }\nmembers = [\
             { shape = \"sphere\", radius = 1.0 }, \
             { shape = \"sphere\", radius = 0.5, material = \"glass\" }, \
             { shape = \"sphere\", radius = 0.4, material = { ior = 1.3 } }, \
             { shape = \"sphere\", radius = 0.3, material = \"glass\" }]\n",
        )]);
        let mut scene = load_from(&SCENE, std::path::Path::new("s.toml"), &crate::plugins::registry()).unwrap();
        let scene = crate::prepare(&mut scene).unwrap();
        let table = InteriorTable::new(&scene);
        assert!(table.leaves[0].is_none());
        // The group's own leaf shares its interior (1); the named glass is one interior (2),
        // the inline material another (3).
        assert_eq!(table.leaves[1].as_deref(), Some(&[1, 2, 3, 2][..]));
        let ior = |id: usize| scene.materials[table.materials[id] as usize].interior.ior;
        assert_eq!([ior(1), ior(2), ior(3)], [1.2, 1.5, 1.3]);
    }

    #[test]
    fn interiors_stack() {
        let s = Interiors::default().entering(3).entering(5);
        assert_eq!(s.innermost(), Some(5));
        let s = s.leaving(3);
        assert!(!s.contains(3) && s.contains(5));
    }

    #[test]
    fn interior_fade_tests_camera_and_shadow_rays_as_pov_ray_does() {
        let grey = crate::color::Rgb::grey(0.2);
        let base = PovView::new(&crate::material::Material::default()).base;
        let mut m = base;
        m.interior.fade_distance = 2.0;
        m.interior.fade_power = 0.0;
        m.interior.fade_color = grey;
        // fade_power 0: a constant halfway blend for camera-side rays, nothing for shadows.
        assert!((interior_fade(&m, 5.0, false) - DVec3::splat(0.6)).length() < 1e-12);
        assert_eq!(interior_fade(&m, 5.0, true), DVec3::ONE);
        m.interior.fade_power = 2.0;
        let expected = 0.2 + 0.8 / (1.0 + 2.5f64 * 2.5);
        for shadow in [false, true] {
            assert!((interior_fade(&m, 5.0, shadow) - DVec3::splat(expected)).length() < 1e-12);
        }
        m.interior.fade_power = 1000.0;
        assert!((interior_fade(&m, 5.0, true) - DVec3::splat((-0.8f64 * 2.5).exp())).length() < 1e-12);
        let mut none = m;
        none.interior.fade_distance = 0.0;
        none.interior.fade_power = 2.0;
        assert_eq!(interior_fade(&none, 5.0, false), DVec3::ONE);
    }
}
