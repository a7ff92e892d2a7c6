//! Ray queries over all primitives: an 8-wide BVH (`accel::wide`) over the world
//! bounds of bounded primitives, one primitive per leaf, plus a short list of unbounded ones
//! (infinite planes) tested beside it, as POV-Ray does. A primitive whose shape has
//! [`SeparableParts`] (a CSG union) puts each part in the tree instead, as POV-Ray splits
//! unions into its bounding hierarchy. Shapes are intersected in f64 in their own object
//! space; the BVH works in f32 with conservatively enlarged boxes, and the closest hit is
//! decided in f64.

use std::any::Any;
use std::sync::Arc;

use glam::{DVec3, Vec3, Vec3A};
use obvhs::BvhBuildParams;
use prism_api::{Hit, Ray, Shape};
use prism_plane::Plane;

use super::mesh_bvh::TriangleBvh;
use super::primitive::{Placement, Primitive};
use super::simd::BoxRay;
use super::triangle::{WatertightRay, mesh_hit, plane_t};
use super::wide::{CollapseCost, EMPTY, LEAF, WIDTH, WideTree, build_binary, traverse_fastest, with_traversal_stack};

/// The acceleration structure.
pub struct Accel {
    /// The tree over bounded primitives whose triangles are not flattened; a leaf's
    /// reference is the primitive's index.
    tree: Option<WideTree>,
    /// Primitives that are not bounded (infinite planes, mostly).
    unbounded: Vec<Unbounded>,
    /// The world-space triangles of small meshes, in one tree of their own.
    flat: Option<FlatTriangles>,
    /// When triangles are flattened or parts separated: the tree over every bounded
    /// primitive, for [`Accel::gather`] (which names primitives, not triangles or parts).
    gather_tree: Option<WideTree>,
    /// The parts in `tree`: a leaf reference `r` at or past `primitive_count` names part
    /// `r - primitive_count`.
    parts: Vec<TreePart>,
    /// The shapes the parts belong to (one entry per separated primitive).
    separated: Vec<Arc<dyn SeparableParts>>,
    /// Number of primitives the structure was built over.
    primitive_count: u32,
}

/// A shape whose nearest hit along a ray is the nearest of its parts' own hits, each found
/// alone, the lowest part winning a tie (a CSG union that keeps its interior surfaces): each
/// part can be a leaf of the scene's tree, so that a ray meets the parts near it in the
/// scene's own traversal.
pub trait SeparableParts: Send + Sync {
    /// Number of parts.
    fn part_count(&self) -> usize;
    /// Bounds of part `index`'s surface in the shape's object space.
    fn part_bounds(&self, index: usize) -> prism_api::Aabb;
    /// The nearest hit of part `index` alone along the object-space `ray` with
    /// `t_min < t < t_max`, as the whole shape reports it.
    fn part_intersect(&self, index: usize, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit>;
}

/// One part of a separated primitive, as a leaf of the scene's tree.
#[derive(Clone, Copy, Debug)]
struct TreePart {
    primitive: u32,
    part: u32,
    /// Index into [`Accel::separated`].
    shape: u32,
}

/// What [`Accel::part_closest`] needs to know of the nearest hit found so far: its t, the
/// primitive it lies on (`u32::MAX` for none) and, when that primitive is a separated one,
/// the part (else any value: no part belongs to a whole primitive). Passed by value, so
/// that the hot loop's own variables never have their address taken.
#[derive(Clone, Copy)]
struct SoFar {
    t: f64,
    primitive: u32,
    part: u32,
}

/// An unbounded primitive. Every query tests each of them, so an infinite plane placed as
/// is (object space = world space) keeps a copy of itself that the queries (and
/// [`Accel::gather`]) call directly: through `dyn Shape` each test paid a call the compiler
/// cannot inline (the room, with five planes, renders 6 % faster at 4K; images identical).
#[derive(Clone, Debug)]
struct Unbounded {
    primitive: u32,
    plane: Option<Plane>,
}

impl Unbounded {
    fn new(index: u32, primitive: &Primitive) -> Self {
        let any: &dyn Any = primitive.shape.as_ref();
        let plane = match primitive.placement {
            Placement::Identity => any.downcast_ref::<Plane>().cloned(),
            _ => None,
        };
        Self { primitive: index, plane }
    }

    /// The primitive's hit along the world `ray` with `t_min < t < t_max`.
    #[inline(always)]
    fn intersect(&self, primitives: &[Primitive], ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit> {
        match &self.plane {
            Some(plane) => plane.intersect(ray, t_min, t_max),
            None => primitives[self.primitive as usize].intersect(ray, t_min, t_max),
        }
    }

    /// True when the primitive lies on the world `ray` within `(t_min, t_max)`.
    #[inline(always)]
    fn occluded(&self, primitives: &[Primitive], ray: &Ray, t_min: f64, t_max: f64) -> bool {
        match &self.plane {
            Some(plane) => plane.occluded(ray, t_min, t_max),
            None => primitives[self.primitive as usize].occluded(ray, t_min, t_max),
        }
    }
}

/// The triangles of several mesh primitives in world space, in one triangle BVH: a ray
/// meets them all in one traversal, with no per-mesh transform, tree or `dyn Shape` call.
struct FlatTriangles {
    bvh: TriangleBvh,
    /// For each triangle of `bvh`: its primitive and its slot in that primitive's mesh.
    owners: Vec<(u32, u32)>,
}

/// The closest hit of a ray: which primitive, the shape's hit record, and the object ray.
#[derive(Clone, Copy, Debug)]
pub struct ClosestHit {
    /// Index into the render scene's primitives.
    pub primitive: u32,
    /// The shape's hit (t is shared by world and object space): the primitive's
    /// [`Primitive::object_ray`] of the query's ray is the ray it lies on.
    pub hit: Hit,
}

fn to_obvhs_aabb(b: &prism_api::Aabb) -> obvhs::aabb::Aabb {
    // Round outward and pad, so f32 rounding of boxes and rays never loses a hit.
    let pad = 1e-5 * b.min.abs().max(b.max.abs()).max_element() + 1e-6;
    let min = (b.min - pad).as_vec3();
    let max = (b.max + pad).as_vec3();
    obvhs::aabb::Aabb { min: Vec3A::from(min), max: Vec3A::from(max) }
}

/// Whether primitive `index` (`primitive`) has a hit on `ray` in `(t_min, *best_t)`, taken
/// into `best` and `best_t` when it has. Always inlined: it is the traversal's leaf test,
/// and a leaf test out of line cost the room at 4K 5 % (see [`Accel::closest`]).
#[inline(always)]
fn closer_whole(
    primitive: &Primitive,
    index: u32,
    ray: &Ray,
    (t_min, best_t): (f64, &mut f64),
    best: &mut Option<(u32, Hit)>,
    accept: &impl Fn(u32) -> bool,
) -> bool {
    if !accept(index) {
        return false;
    }
    match primitive.intersect(ray, t_min, *best_t) {
        Some(hit) => {
            *best_t = hit.t;
            *best = Some((index, hit));
            true
        }
        None => false,
    }
}

/// The f32 ray the BVH traverses.
#[inline]
fn box_ray(ray: &Ray) -> BoxRay {
    BoxRay::new(ray.origin.as_vec3(), ray.direction.as_vec3())
}

/// `t` rounded up to f32, so that f32 pruning never drops a box holding a hit at exactly `t`.
#[inline]
fn f32_bound(t: f64) -> f32 {
    if t.is_finite() { (t as f32).next_up() } else { f32::INFINITY }
}

/// The tree over the world bounds of `primitives[i]` for each `i` in `bounded`.
fn primitive_tree(primitives: &[Primitive], bounded: &[u32]) -> Option<WideTree> {
    let items: Vec<_> = bounded.iter().map(|&i| (i, primitives[i as usize].world_bounds)).collect();
    reference_tree(&items)
}

/// The tree over `items`' world boxes, each a leaf holding its reference.
fn reference_tree(items: &[(u32, prism_api::Aabb)]) -> Option<WideTree> {
    (!items.is_empty()).then(|| {
        let boxes: Vec<_> = items.iter().map(|(_, b)| to_obvhs_aabb(b)).collect();
        // One item per leaf: the wide tree's leaves are single primitives or parts.
        let params = BvhBuildParams { max_prims_per_leaf: 1, ..BvhBuildParams::medium_build() };
        let bvh2 = build_binary(boxes, params);
        // One item per leaf; how costly each is does not change the collapse.
        let cost = CollapseCost { node: 1.0, leaf: |n| (n == 1).then_some(1.0) };
        WideTree::collapse(&bvh2, cost, |prims: &[u32]| {
            debug_assert_eq!(prims.len(), 1, "leaves hold one item");
            items[prims[0] as usize].0
        })
    })
}

impl Accel {
    /// Builds the BVH over `primitives`' world bounds (two levels for every mesh).
    pub fn build(primitives: &[Primitive]) -> Self {
        Self::build_flattening(primitives, &[], &[])
    }

    /// Builds the BVH; `flatten[i]`, when given, holds primitive `i`'s object-space
    /// triangles, indexed like the hits its shape reports, which it reports as
    /// [`mesh_hit`]s and nothing else (a mesh without alpha mask). Those go into the
    /// scene-level structure as world-space triangles instead of as one primitive with a
    /// tree of its own; hits on them are the shape's own (same primitive, `part` and
    /// barycentrics; `t` and barycentrics exactly the same when the primitive is not moved,
    /// else up to the rounding of its vertices to world space). `separable[i]`, when given,
    /// is primitive `i`'s shape as [`SeparableParts`]: a bounded one puts its parts into the
    /// tree one by one (hits exactly the shape's own).
    pub fn build_flattening(
        primitives: &[Primitive],
        flatten: &[Option<&[[Vec3; 3]]>],
        separable: &[Option<Arc<dyn SeparableParts>>],
    ) -> Self {
        let primitive_count = u32::try_from(primitives.len()).expect("primitives are numbered in u32");
        let mut all_bounded = Vec::new();
        let mut bounded = Vec::new();
        let mut parts = Vec::new();
        let mut separated: Vec<Arc<dyn SeparableParts>> = Vec::new();
        let mut unbounded = Vec::new();
        let mut triangles = Vec::new();
        let mut owners = Vec::new();
        for (i, p) in primitives.iter().enumerate() {
            if !p.world_bounds.is_bounded() {
                unbounded.push(Unbounded::new(i as u32, p));
                continue;
            }
            all_bounded.push(i as u32);
            // A mesh moved beyond f32's range (a translation of 1e39) would have infinite
            // world-space vertices, which the triangle tree cannot be built over; it keeps
            // its own object-space tree, as a primitive whose f32 box is infinite.
            let fits_f32 = p.world_bounds.min.as_vec3().is_finite() && p.world_bounds.max.as_vec3().is_finite();
            match flatten.get(i).copied().flatten().filter(|_| fits_f32) {
                Some(object) => {
                    for (slot, t) in object.iter().enumerate() {
                        triangles.push(t.map(|v| p.world_point(v.as_dvec3()).as_vec3()));
                        owners.push((i as u32, slot as u32));
                    }
                }
                None => match separable.get(i).cloned().flatten() {
                    Some(shape) => {
                        let shape_index = separated.len() as u32;
                        for part in 0..shape.part_count() {
                            let bounds = shape.part_bounds(part).transformed(&p.world_from_object);
                            // A part without a surface is never hit.
                            if bounds.is_empty() {
                                continue;
                            }
                            let reference = primitive_count as usize + parts.len();
                            // Leaf references live below the wide tree's leaf flag.
                            let reference = u32::try_from(reference).ok().filter(|&r| r & LEAF == 0 && r != EMPTY);
                            let reference = reference.expect("fewer than 2^31 primitives and parts");
                            bounded.push((reference, bounds));
                            parts.push(TreePart { primitive: i as u32, part: part as u32, shape: shape_index });
                        }
                        separated.push(shape);
                    }
                    None => bounded.push((i as u32, p.world_bounds)),
                },
            }
        }
        let flat = (!triangles.is_empty()).then(|| FlatTriangles { bvh: TriangleBvh::build(triangles), owners });
        let gather_tree =
            (flat.is_some() || !parts.is_empty()).then(|| primitive_tree(primitives, &all_bounded)).flatten();
        Self { tree: reference_tree(&bounded), unbounded, flat, gather_tree, parts, separated, primitive_count }
    }

    /// Number of separated parts in the tree (each a leaf in place of its primitive).
    pub fn separated_parts(&self) -> usize {
        self.parts.len()
    }

    /// The hit of tree part `part` nearer than `so_far`, and the primitive and part it lies
    /// on: a lower part of the same primitive wins a tie, as in the shape's own intersect.
    // Out of line: most scenes have no parts, and the traversal's leaf test stays small.
    #[inline(never)]
    fn part_closest(
        &self,
        primitives: &[Primitive],
        part: u32,
        ray: &Ray,
        t_min: f64,
        so_far: SoFar,
        accept: &impl Fn(u32) -> bool,
    ) -> Option<(u32, u32, Hit)> {
        let TreePart { primitive, part, shape } = self.parts[part as usize];
        if !accept(primitive) {
            return None;
        }
        let same = so_far.primitive == primitive && so_far.part > part;
        let limit = if same { so_far.t.next_up() } else { so_far.t };
        let object_ray = primitives[primitive as usize].object_ray_of(ray);
        let hit = self.separated[shape as usize].part_intersect(part as usize, &object_ray, t_min, limit)?;
        Some((primitive, part, hit))
    }

    /// True when tree part `part` lies on `ray` within `(t_min, t_max)`.
    // Out of line: most scenes have no parts, and the traversal's leaf test stays small.
    #[inline(never)]
    fn part_occludes(
        &self,
        primitives: &[Primitive],
        part: u32,
        ray: &Ray,
        t_min: f64,
        t_max: f64,
        accept: &impl Fn(u32) -> bool,
    ) -> bool {
        let TreePart { primitive, part, shape } = self.parts[part as usize];
        accept(primitive) && {
            let object_ray = primitives[primitive as usize].object_ray_of(ray);
            self.separated[shape as usize].part_intersect(part as usize, &object_ray, t_min, t_max).is_some()
        }
    }

    /// Number of triangles held in the scene-level structure itself.
    pub fn flattened_triangles(&self) -> usize {
        self.flat.as_ref().map_or(0, |f| f.owners.len())
    }

    /// The closest hit with `t_min < t < t_max` among primitives for which `accept` is true.
    pub fn closest(
        &self,
        primitives: &[Primitive],
        ray: &Ray,
        t_min: f64,
        t_max: f64,
        accept: impl Fn(u32) -> bool,
    ) -> Option<ClosestHit> {
        let mut best: Option<(u32, Hit)> = None;
        let mut best_t = t_max;
        // The part the best hit lies on, when it is a separated primitive's (whole primitives
        // are never separated ones, so a hit on one needs no reset).
        let mut best_part = u32::MAX;
        let test = |index: u32, best_t: &mut f64, best: &mut Option<(u32, Hit)>| {
            closer_whole(&primitives[index as usize], index, ray, (t_min, best_t), best, &accept)
        };
        for unbounded in &self.unbounded {
            if accept(unbounded.primitive)
                && let Some(hit) = unbounded.intersect(primitives, ray, t_min, best_t)
            {
                best_t = hit.t;
                best = Some((unbounded.primitive, hit));
            }
        }
        if let Some(flat) = &self.flat
            && let Some(wray) = WatertightRay::new(ray.origin.as_vec3(), ray.direction.as_vec3())
        {
            // What `MeshShape::intersect` does, over the triangles of every flattened mesh.
            flat.bvh.closest(&wray, f32_bound(best_t), |index, h, [a, b, c]| {
                let (primitive, slot) = flat.owners[index];
                let t = plane_t(ray.origin, ray.direction, a, b, c).unwrap_or(f64::from(h.t));
                if t <= t_min || t >= best_t || !accept(primitive) {
                    return None;
                }
                best_t = t;
                best = Some((primitive, mesh_hit(t, slot, h)));
                // Round up so the f32 traversal never prunes a box holding an equal hit.
                Some(f32_bound(t))
            });
        }
        if let Some(tree) = &self.tree {
            let r = box_ray(ray);
            let limit = f32_bound(best_t);
            // Without parts, the leaf test is the whole primitive's alone: the part branch, even
            // never taken, kept the traversal from inlining it (3-5 % of the room at 4K).
            with_traversal_stack(tree.stack_size, |stack| {
                if self.parts.is_empty() {
                    return traverse_fastest::<true>(&tree.nodes, &r, limit, stack, |primitive, bound| {
                        if test(primitive, &mut best_t, &mut best) {
                            // Round up so the f32 traversal never prunes a box holding an equal hit.
                            *bound = f32_bound(best_t);
                        }
                        false
                    });
                }
                traverse_fastest::<true>(&tree.nodes, &r, limit, stack, |reference, bound| {
                    let found = if reference < self.primitive_count {
                        test(reference, &mut best_t, &mut best)
                    } else {
                        let primitive = best.map_or(u32::MAX, |(p, _)| p);
                        let so_far = SoFar { t: best_t, primitive, part: best_part };
                        let part = reference - self.primitive_count;
                        match self.part_closest(primitives, part, ray, t_min, so_far, &accept) {
                            Some((primitive, part, hit)) => {
                                (best_t, best, best_part) = (hit.t, Some((primitive, hit)), part);
                                true
                            }
                            None => false,
                        }
                    };
                    if found {
                        // Round up so the f32 traversal never prunes a box holding an equal hit.
                        *bound = f32_bound(best_t);
                    }
                    false
                })
            });
        }
        best.map(|(primitive, hit)| ClosestHit { primitive, hit })
    }

    /// True when any primitive for which `accept` is true lies on the ray in (t_min, t_max).
    pub fn occluded(
        &self,
        primitives: &[Primitive],
        ray: &Ray,
        t_min: f64,
        t_max: f64,
        accept: impl Fn(u32) -> bool,
    ) -> bool {
        self.occluded_among(primitives, None, ray, t_min, t_max, accept)
    }

    /// [`Accel::occluded`] among `candidates` when given (which must hold every primitive
    /// the ray may meet, see [`Accel::gather`]), else among all.
    pub fn occluded_among(
        &self,
        primitives: &[Primitive],
        candidates: Option<&[u32]>,
        ray: &Ray,
        t_min: f64,
        t_max: f64,
        accept: impl Fn(u32) -> bool,
    ) -> bool {
        let test = |index: u32| -> bool {
            if !accept(index) {
                return false;
            }
            primitives[index as usize].occluded(ray, t_min, t_max)
        };
        if let Some(candidates) = candidates {
            return candidates.iter().any(|&i| test(i));
        }
        if let Some(flat) = &self.flat
            && let Some(wray) = WatertightRay::new(ray.origin.as_vec3(), ray.direction.as_vec3())
            && flat.bvh.any(&wray, f32_bound(t_max), |index, h, [a, b, c]| {
                let t = plane_t(ray.origin, ray.direction, a, b, c).unwrap_or(f64::from(h.t));
                t > t_min && t < t_max && accept(flat.owners[index].0)
            })
        {
            return true;
        }
        if let Some(tree) = &self.tree {
            let r = box_ray(ray);
            let limit = f32_bound(t_max);
            if with_traversal_stack(tree.stack_size, |stack| {
                // Without parts, the leaf test alone (see `closest`).
                if self.parts.is_empty() {
                    return traverse_fastest::<false>(&tree.nodes, &r, limit, stack, |primitive, _| test(primitive));
                }
                traverse_fastest::<false>(&tree.nodes, &r, limit, stack, |reference, _| {
                    if reference < self.primitive_count {
                        test(reference)
                    } else {
                        let part = reference - self.primitive_count;
                        self.part_occludes(primitives, part, ray, t_min, t_max, &accept)
                    }
                })
            }) {
                return true;
            }
        }
        // The unbounded ones (planes, mostly) last: the ray was just written, and a plane
        // that reads it back at once waits for those stores (4-6 % of a scene with a floor);
        // they seldom cast the shadow, so nothing is lost by asking them after the rest.
        self.unbounded.iter().any(|u| accept(u.primitive) && u.occluded(primitives, ray, t_min, t_max))
    }

    /// Collects into `out` the primitives that may meet `hull`: unbounded ones that do not
    /// rule it out ([`prism_api::Shape::misses_hull`]) and bounded ones whose BVH boxes
    /// reach into it. False (with `out` incomplete) when there are more than it holds.
    pub fn gather(&self, primitives: &[Primitive], hull: &ConvexHull, out: &mut Gathered) -> bool {
        out.len = 0;
        let push = |index: u32, out: &mut Gathered| {
            if out.len == out.items.len() {
                return false;
            }
            out.items[out.len] = index;
            out.len += 1;
            true
        };
        for unbounded in &self.unbounded {
            let misses = match &unbounded.plane {
                // Object space is world space.
                Some(plane) => plane.misses_hull(hull.vertices()),
                None => {
                    let p = &primitives[unbounded.primitive as usize];
                    let mut corners = [DVec3::ZERO; 8];
                    for (corner, &v) in corners.iter_mut().zip(hull.vertices()) {
                        *corner = p.object_point(v);
                    }
                    p.shape.misses_hull(&corners[..hull.vertices().len()])
                }
            };
            if !misses && !push(unbounded.primitive, out) {
                return false;
            }
        }
        let Some(tree) = self.gather_tree.as_ref().or(self.tree.as_ref()) else { return true };
        let mut stack = [0u32; 64];
        let mut sp = 1;
        while sp > 0 {
            sp -= 1;
            let node = &tree.nodes[stack[sp] as usize];
            for slot in 0..WIDTH {
                let child = node.child[slot];
                if child == EMPTY {
                    continue;
                }
                let b = &node.bounds.planes;
                let min = DVec3::new(b[0][slot].into(), b[1][slot].into(), b[2][slot].into());
                let max = DVec3::new(b[3][slot].into(), b[4][slot].into(), b[5][slot].into());
                if hull.excludes(min, max) {
                    continue;
                }
                if child & LEAF != 0 {
                    if !push(child & !LEAF, out) {
                        return false;
                    }
                } else {
                    if sp == stack.len() {
                        return false;
                    }
                    stack[sp] = child;
                    sp += 1;
                }
            }
        }
        true
    }
}

/// A few primitives gathered by [`Accel::gather`], kept on the stack.
#[derive(Clone, Copy, Debug, Default)]
pub struct Gathered {
    items: [u32; 8],
    len: usize,
}

impl Gathered {
    /// The gathered primitive indices.
    pub fn as_slice(&self) -> &[u32] {
        &self.items[..self.len]
    }
}

/// A convex polyhedron by its face planes and its vertices, used to cull what a bundle of
/// rays inside it can meet. Culling is conservative: a box counts as outside only when it
/// lies beyond one face plane by more than a small margin.
#[derive(Clone, Copy, Debug)]
pub struct ConvexHull {
    /// The faces, each inside where `normal . x <= limit`: an outward normal of any length,
    /// its components' magnitudes, and the plane's offset with the margin beyond it (a
    /// distance scaled by the normal's length).
    faces: [HullFace; 6],
    face_count: usize,
    vertices: [DVec3; 8],
    vertex_count: usize,
}

/// One face of a [`ConvexHull`].
#[derive(Clone, Copy, Debug, Default)]
struct HullFace {
    normal: DVec3,
    normal_abs: DVec3,
    limit: f64,
}

impl ConvexHull {
    /// The hull of the shadow rays from `apex` to the parallelogram `centre +- edge1 +-
    /// edge2`, from `skip` along each ray on (shadow rays ignore hits nearer than that). It
    /// is the pyramid over the parallelogram, cut by a plane across the central direction
    /// that every ray crosses no sooner than at `skip`; when the parallelogram spans a half
    /// space around the apex there is no such plane, and the hull is the whole pyramid.
    ///
    /// Built once per shaded point and area light, so it avoids square roots and divisions
    /// where it can (they were a sixth of a scene of area lights): face normals keep the
    /// length the cross product gives them, and the margin is scaled by their 1-norm, which
    /// is at least their length (a margin up to sqrt(3) times wider only culls less).
    pub fn shadow_frustum(apex: DVec3, centre: DVec3, edge1: DVec3, edge2: DVec3, skip: f64) -> Self {
        let corners = [centre - edge1 - edge2, centre + edge1 - edge2, centre + edge1 + edge2, centre - edge1 + edge2];
        let inner = (apex + centre * 4.0) / 5.0;
        // The 1-norms bound the edges' lengths from above.
        let scale = apex.abs().max(centre.abs()).max_element() + edge1.abs().element_sum() + edge2.abs().element_sum();
        let margin = 1e-7 * scale.max(1.0);
        let mut hull =
            Self { faces: [HullFace::default(); 6], face_count: 0, vertices: [DVec3::ZERO; 8], vertex_count: 0 };
        // A face too thin to have a direction, or one the inner point does not lie clearly
        // inside of (a flat pyramid), is left out: fewer faces only cull less.
        let face = |hull: &mut Self, n: DVec3, a: DVec3| {
            let length_bound = n.abs().element_sum();
            if !(length_bound > 0.0 && length_bound.is_finite()) {
                return;
            }
            let depth = n.dot(inner - a);
            if depth.abs() <= margin * length_bound {
                return;
            }
            let normal = if depth > 0.0 { -n } else { n };
            let limit = normal.dot(a) + margin * length_bound;
            hull.faces[hull.face_count] = HullFace { normal, normal_abs: normal.abs(), limit };
            hull.face_count += 1;
        };
        for i in 0..4 {
            face(&mut hull, (corners[i] - apex).cross(corners[(i + 1) % 4] - apex), apex);
        }
        face(&mut hull, (corners[1] - corners[0]).cross(corners[3] - corners[0]), corners[0]);
        hull.vertices[..4].copy_from_slice(&corners);
        // Along the central direction every ray has gone at least `skip` times the smallest
        // cosine between it and a corner direction (the cone's widest rays are its corners).
        let axis = (centre - apex).normalize_or_zero();
        let toward = corners.map(|c| c - apex);
        let along = toward.map(|u| u.dot(axis));
        // The corner of least cosine, compared as (u . axis)^2 |v|^2 < (v . axis)^2 |u|^2
        // between corners ahead of the apex: one square root and one division in all.
        let ahead = along.iter().all(|&a| a > 0.0);
        let widest = (1..4).fold(0, |w, i| {
            let (a, b) = (along[i], along[w]);
            if a * a * toward[w].length_squared() < b * b * toward[i].length_squared() { i } else { w }
        });
        let cos_min = if ahead { along[widest] / toward[widest].length() } else { 0.0 };
        if cos_min > 1e-3 && skip > 0.0 {
            let near = skip * cos_min;
            // The cut sits a margin nearer the apex than the rays' first points.
            let cut = near - margin;
            if cut > 0.0 {
                let limit = -(axis.dot(apex) + cut) + margin;
                hull.faces[hull.face_count] = HullFace { normal: -axis, normal_abs: axis.abs(), limit };
                hull.face_count += 1;
                for i in 0..4 {
                    hull.vertices[4 + i] = apex + toward[i] * (cut / along[i]);
                }
                hull.vertex_count = 8;
                return hull;
            }
        }
        hull.vertices[4] = apex;
        hull.vertex_count = 5;
        hull
    }

    /// The hull's vertices.
    fn vertices(&self) -> &[DVec3] {
        &self.vertices[..self.vertex_count]
    }

    /// True when the box `min..max` lies wholly outside the hull's face planes' margin.
    #[inline]
    pub fn excludes(&self, min: DVec3, max: DVec3) -> bool {
        let centre = (min + max) * 0.5;
        let half = (max - min) * 0.5;
        self.faces[..self.face_count].iter().any(|f| f.normal.dot(centre) - f.normal_abs.dot(half) > f.limit)
    }
}

#[cfg(test)]
mod tests {
    use glam::DAffine3;
    use prism_api::contract::TestRng;
    use prism_sphere::Sphere;

    use super::*;

    fn primitive(shape: Arc<dyn Shape>) -> Primitive {
        Primitive::new(shape, DAffine3::IDENTITY, 0, false)
    }

    /// Hundreds of spheres (a tree several nodes deep) and planes (two placed as they are,
    /// tested directly, and one moved, tested through its primitive): the closest hit and the
    /// occlusion answer equal a brute-force loop, with every primitive accepted and with the
    /// first plane refused, and gathering for a frustum never leaves out a primitive that a
    /// shadow ray inside it hits.
    #[test]
    fn queries_equal_brute_force() {
        let mut rng = TestRng::new(11);
        let mut primitives: Vec<Primitive> = (0..500)
            .map(|_| {
                let center = DVec3::new(rng.range(-10.0, 10.0), rng.range(-10.0, 10.0), rng.range(-10.0, 10.0));
                primitive(Arc::new(Sphere { center, radius: rng.range(0.05, 0.8) }))
            })
            .collect();
        // Planes through the region, so that they block many of the rays.
        primitives.push(primitive(Arc::new(Plane::new(DVec3::Y, -3.0))));
        primitives.push(primitive(Arc::new(Plane::new(DVec3::new(0.6, 0.0, 0.8), 2.0))));
        let moved = DAffine3::from_translation(DVec3::new(1.0, 2.0, 0.5)) * DAffine3::from_rotation_z(0.4);
        primitives.push(Primitive::new(Arc::new(Plane::new(DVec3::X, 4.0)), moved, 0, false));
        let refused = 500;
        let accel = Accel::build(&primitives);
        assert_eq!(accel.unbounded.iter().filter(|u| u.plane.is_some()).count(), 2, "planes tested directly");
        let brute_among = |ray: &Ray, t_min: f64, t_max: f64, accept: &dyn Fn(u32) -> bool| -> Option<(u32, f64)> {
            let hits = primitives
                .iter()
                .enumerate()
                .filter(|&(i, _)| accept(i as u32))
                .filter_map(|(i, p)| p.intersect(ray, t_min, t_max).map(|h| (i as u32, h.t)));
            hits.min_by(|a, b| a.1.total_cmp(&b.1))
        };
        let brute = |ray: &Ray, t_min: f64, t_max: f64| brute_among(ray, t_min, t_max, &|_| true);
        for case in 0..3000 {
            let origin = DVec3::new(rng.range(-12.0, 12.0), rng.range(-12.0, 12.0), rng.range(-12.0, 12.0));
            let ray = Ray::new(origin, rng.unit_vector());
            let t_max = if case % 3 == 0 { rng.range(0.5, 20.0) } else { f64::INFINITY };
            let expected = brute(&ray, 1e-6, t_max);
            let found = accel.closest(&primitives, &ray, 1e-6, t_max, |_| true).map(|h| (h.primitive, h.hit.t));
            assert_eq!(found, expected, "case {case}: {ray:?}");
            let occluded = accel.occluded(&primitives, &ray, 1e-6, t_max, |_| true);
            assert_eq!(occluded, expected.is_some(), "case {case}: occlusion of {ray:?}");
            let accept = |i: u32| i != refused;
            let expected = brute_among(&ray, 1e-6, t_max, &accept);
            let found = accel.closest(&primitives, &ray, 1e-6, t_max, accept).map(|h| (h.primitive, h.hit.t));
            assert_eq!(found, expected, "case {case}, plane {refused} refused: {ray:?}");
            let occluded = accel.occluded(&primitives, &ray, 1e-6, t_max, accept);
            assert_eq!(occluded, expected.is_some(), "case {case}, plane {refused} refused: occlusion of {ray:?}");
        }
        let mut gathers = 0;
        for case in 0..400 {
            let apex = DVec3::new(rng.range(-9.0, 9.0), rng.range(-9.0, 9.0), rng.range(-9.0, 9.0));
            let centre = apex + rng.unit_vector() * rng.range(1.0, 6.0);
            let (edge1, edge2) = (rng.unit_vector() * rng.range(0.0, 0.4), rng.unit_vector() * rng.range(0.0, 0.4));
            let mut gathered = Gathered::default();
            let hull = ConvexHull::shadow_frustum(apex, centre, edge1, edge2, 1e-3);
            if !accel.gather(&primitives, &hull, &mut gathered) {
                continue;
            }
            gathers += 1;
            for _ in 0..64 {
                let target = centre + edge1 * rng.range(-1.0, 1.0) + edge2 * rng.range(-1.0, 1.0);
                let distance = apex.distance(target);
                let ray = Ray::new(apex, (target - apex) / distance);
                let among =
                    accel.occluded_among(&primitives, Some(gathered.as_slice()), &ray, 1e-3, distance, |_| true);
                assert_eq!(among, brute(&ray, 1e-3, distance).is_some(), "case {case}: {ray:?}");
            }
        }
        assert!(gathers > 200, "most frusta gather few enough primitives ({gathers})");
    }

    /// Rays whose slab distances are NaN in f32 (a NaN origin or direction, an origin so far
    /// away that origin / direction overflows) enter the tree's empty lanes; the traversal
    /// must skip them instead of reading a primitive that does not exist (the panic of an
    /// `ior` of 1e17, whose refracted rays left for 1e30 and beyond), and still find what a
    /// brute-force loop finds.
    #[test]
    fn non_finite_and_far_rays_never_reach_an_empty_lane() {
        // 13 spheres: nodes with empty lanes.
        let primitives: Vec<Primitive> = (0..13)
            .map(|i| primitive(Arc::new(Sphere { center: DVec3::new(f64::from(i) * 2.0, 0.0, 0.0), radius: 0.5 })))
            .collect();
        let accel = Accel::build(&primitives);
        let brute = |ray: &Ray| {
            let hits = primitives.iter().enumerate();
            let hits = hits.filter_map(|(i, p)| p.shape.intersect(ray, 1e-6, f64::INFINITY).map(|h| (i as u32, h.t)));
            hits.min_by(|a, b| a.1.total_cmp(&b.1))
        };
        let non_finite = [
            Ray { origin: DVec3::NAN, direction: DVec3::X },
            Ray { origin: DVec3::ZERO, direction: DVec3::NAN },
            Ray { origin: DVec3::new(f64::INFINITY, 0.0, 0.0), direction: -DVec3::X },
        ];
        for ray in non_finite {
            assert_eq!(brute(&ray), None);
            assert!(accel.closest(&primitives, &ray, 1e-6, f64::INFINITY, |_| true).is_none(), "{ray:?}");
            assert!(!accel.occluded(&primitives, &ray, 1e-6, f64::INFINITY, |_| true), "{ray:?}");
        }
        // So far away that f32 cannot tell the spheres apart: whatever is found is a real
        // primitive (at 1e30 the f64 hit itself is luck).
        let far = 1e30;
        let far_rays = [
            Ray { origin: DVec3::new(-far, 0.0, 0.0), direction: DVec3::X },
            Ray { origin: DVec3::new(far, far, far), direction: DVec3::new(-1.0, -1.0, -1.0).normalize() },
            Ray { origin: DVec3::new(-far, 1e-3, 0.0), direction: DVec3::new(1.0, 1e-31, 0.0).normalize() },
        ];
        for ray in far_rays {
            if let Some(hit) = accel.closest(&primitives, &ray, 1e-6, f64::INFINITY, |_| true) {
                assert!((hit.primitive as usize) < primitives.len(), "{ray:?}");
            }
            accel.occluded(&primitives, &ray, 1e-6, f64::INFINITY, |_| true);
        }
    }

    /// A mesh moved beyond f32's range (its world-space vertices would be infinite) is not
    /// flattened into the scene's triangle tree, whose build failed on them (an internal
    /// error); it stays a primitive of its own, and a nearby one is still found.
    #[test]
    fn primitives_beyond_f32_are_not_flattened() {
        let triangle = [[Vec3::new(-1.0, -1.0, 0.0), Vec3::new(1.0, -1.0, 0.0), Vec3::new(0.0, 1.0, 0.0)]];
        let far = DAffine3::from_translation(DVec3::new(1e39, 0.0, 0.0));
        let primitives = vec![
            Primitive::new(Arc::new(Sphere { center: DVec3::ZERO, radius: 1.0 }), far, 0, false),
            primitive(Arc::new(Sphere { center: DVec3::ZERO, radius: 1.0 })),
            primitive(Arc::new(Sphere { center: DVec3::new(3.0, 0.0, 0.0), radius: 1.0 })),
        ];
        let flatten: Vec<Option<&[[Vec3; 3]]>> = vec![Some(&triangle), Some(&triangle), None];
        let accel = Accel::build_flattening(&primitives, &flatten, &[]);
        assert_eq!(accel.flattened_triangles(), 1, "only the primitive within f32's range is flattened");
        let ray = Ray::new(DVec3::new(3.0, 0.0, 5.0), -DVec3::Z);
        let hit = accel.closest(&primitives, &ray, 1e-6, f64::INFINITY, |_| true).unwrap();
        assert_eq!(hit.primitive, 2);
    }

    /// Random shadow frusta: every shadow segment (from `skip` along the ray to the light
    /// sample) lies inside every face, and a plane with all vertices on one side never
    /// separates two of its points.
    #[test]
    fn shadow_frusta_hold_every_shadow_segment() {
        let mut rng = TestRng::new(7);
        let mut cut = 0;
        for case in 0..400 {
            let apex = DVec3::new(rng.range(-5.0, 5.0), rng.range(-5.0, 5.0), rng.range(-5.0, 5.0));
            let centre = apex + rng.unit_vector() * rng.range(0.05, 8.0);
            let (edge1, edge2) = (rng.unit_vector() * rng.range(0.0, 2.0), rng.unit_vector() * rng.range(0.0, 2.0));
            let skip = if case % 4 == 0 { 0.0 } else { rng.range(1e-4, 0.3) };
            let hull = ConvexHull::shadow_frustum(apex, centre, edge1, edge2, skip);
            cut += usize::from(hull.vertex_count == 8);
            let vertices = hull.vertices();
            let planes: Vec<(DVec3, f64)> = (0..8).map(|_| (rng.unit_vector(), rng.range(-6.0, 6.0))).collect();
            for _ in 0..64 {
                let target = centre + edge1 * rng.range(-1.0, 1.0) + edge2 * rng.range(-1.0, 1.0);
                let length = apex.distance(target);
                if length <= 2.0 * skip {
                    continue;
                }
                let l = (target - apex) / length;
                let point = apex + l * rng.range(skip, length);
                assert!(!hull.excludes(point, point), "case {case}: {point} on a shadow ray lies outside {hull:?}");
                for (n, d) in &planes {
                    let above = vertices.iter().all(|v| n.dot(*v) > *d);
                    let below = vertices.iter().all(|v| n.dot(*v) < *d);
                    let side = n.dot(point) - d;
                    let crossed = (above && side < -1e-9) || (below && side > 1e-9);
                    assert!(!crossed, "case {case}: the vertices are on one side of a plane, a point is not");
                }
            }
        }
        assert!(cut > 100, "the near cut is made in most cases ({cut})");
        // A box behind the apex, or beside the light, is culled; one on the way is not.
        let hull = ConvexHull::shadow_frustum(DVec3::ZERO, DVec3::new(0.0, 4.0, 0.0), DVec3::X, DVec3::Z, 1e-3);
        assert!(hull.excludes(DVec3::new(-1.0, -2.0, -1.0), DVec3::new(1.0, -1.0, 1.0)));
        assert!(hull.excludes(DVec3::new(3.0, 3.0, -1.0), DVec3::new(4.0, 4.0, 1.0)));
        assert!(hull.excludes(DVec3::new(-1.0, -1.0, -1.0), DVec3::new(1.0, 1e-5, 1.0)), "within the skip");
        assert!(!hull.excludes(DVec3::new(-0.2, 2.0, -0.2), DVec3::new(0.2, 2.5, 0.2)));
    }
}
