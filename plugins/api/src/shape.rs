use std::any::Any;
use std::fmt::Debug;
use std::ops::ControlFlow;

use glam::{DVec2, DVec3};

use crate::{Aabb, Ray, math};

/// The cheap result of [`Shape::intersect`]: the ray parameter plus scratch values the
/// shape may keep to finish the job in [`Shape::surface`] (which part was hit, barycentrics...).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Hit {
    /// Ray parameter of the hit.
    pub t: f64,
    /// Which part of the shape was hit (for example 0 = side, 1 = base cap, 2 = top cap).
    pub part: u32,
    /// Free scratch space for the shape.
    pub scratch: DVec3,
}

impl Hit {
    /// A hit at `t` on part 0 with no scratch data.
    pub fn at(t: f64) -> Self {
        Self { t, ..Self::default() }
    }

    /// A hit at `t` on `part`.
    pub fn on_part(t: f64, part: u32) -> Self {
        Self { t, part, scratch: DVec3::ZERO }
    }
}

/// Geometry at a hit, in object space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Surface {
    /// The hit point.
    pub point: DVec3,
    /// Unit geometric normal, pointing out of the shape (for open surfaces: the shape's own
    /// front side). The integrators flip it toward the viewer; they never rely on its sign
    /// for shading, only for entering and leaving interiors.
    pub normal: DVec3,
    /// Unit shading normal (interpolated on meshes); equal to `normal` on analytic shapes.
    pub shading_normal: DVec3,
    /// Surface parameterisation for texturing, each component in [0, 1] where defined.
    pub uv: DVec2,
    /// How fast `uv` changes along the surface: uv units per unit of object-space length
    /// (the square root of the uv-to-surface area ratio; meshes know it per triangle). Texture
    /// filtering turns a ray's footprint into texels with it; 0 when unknown.
    pub uv_density: f64,
    /// Tangent ∂p/∂u: how the point moves per unit of `uv.x` with `uv.y` held fixed (object
    /// space, not normalised), perpendicular to `normal`. Where the uv has no such derivative
    /// (no parameterisation, or a point where it degenerates: a sphere's poles, a disc's
    /// centre, a cone's tip) it is any unit vector perpendicular to `normal`. Always finite
    /// and non-zero, so shading frames and anisotropic materials can be built from it.
    pub dpdu: DVec3,
}

impl Surface {
    /// A surface point whose shading normal is its geometric normal, with a unit tangent
    /// [`math::tangent`] built from the normal as `dpdu`; set the real ∂p/∂u with
    /// [`Surface::with_dpdu`] where the uv has one.
    pub fn new(point: DVec3, normal: DVec3, uv: DVec2) -> Self {
        Self { point, normal, shading_normal: normal, uv, uv_density: 0.0, dpdu: math::tangent(normal) }
    }

    /// The point and normals of this surface, without its uv and tangent.
    pub fn point_and_normals(&self) -> HitPoint {
        HitPoint { point: self.point, normal: self.normal, shading_normal: self.shading_normal }
    }

    /// The same surface with tangent `dpdu`, which must be perpendicular to the normal. Where
    /// it cannot be normalised (zero or not finite: a degenerate point of the
    /// parameterisation, a disc's centre) the unit tangent of [`Surface::new`] is kept.
    pub fn with_dpdu(self, dpdu: DVec3) -> Self {
        let length_squared = dpdu.length_squared();
        // What `try_normalize` accepts, without its square root and division.
        if length_squared > 0.0 && length_squared.is_finite() { Self { dpdu, ..self } } else { self }
    }
}

/// A hit point and its normals, in object space: all of a [`Surface`] that shading without
/// textures or tangents needs (the classic integrator's untextured finishes).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HitPoint {
    /// The hit point.
    pub point: DVec3,
    /// Unit geometric normal, as [`Surface::normal`].
    pub normal: DVec3,
    /// Unit shading normal, as [`Surface::shading_normal`].
    pub shading_normal: DVec3,
}

impl HitPoint {
    /// A point on an analytic surface: its shading normal is its geometric normal.
    pub fn new(point: DVec3, normal: DVec3) -> Self {
        Self { point, normal, shading_normal: normal }
    }
}

/// A point sampled uniformly on a shape's surface (object space).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AreaSample {
    /// The sampled point.
    pub point: DVec3,
    /// Unit outward normal there.
    pub normal: DVec3,
    /// Probability density with respect to area (1 / area for uniform sampling); equal to
    /// [`Shape::pdf_area`] at `point`.
    pub pdf_area: f64,
}

/// A direction from a reference point toward a shape, sampled by [`Shape::sample_toward`]
/// (object space).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DirectionSample {
    /// The nearest point of the shape along the sampled direction: the point the reference
    /// sees, so a shadow ray toward it tests only the other objects. (A sampler that picks a
    /// point hidden behind a nearer part of the same surface reports that nearer crossing.)
    pub point: DVec3,
    /// Unit outward normal at `point`.
    pub normal: DVec3,
    /// Probability density of the direction `point - reference` with respect to solid angle
    /// at the reference, measured in object space: [`Shape::pdf_toward`] of that direction.
    /// Convert it to world space with [`crate::math::solid_angle_scale`].
    pub pdf_solid_angle: f64,
}

/// Crossings of one ray after another are looked for this fraction of the shape's size
/// beyond the previous one, so that rounding cannot find the same crossing twice.
pub const CROSSING_GAP: f64 = 1e-9;

/// At most this many crossings are visited along one ray by [`for_each_crossing`].
pub const MAX_CROSSINGS: usize = 4096;

/// Calls `visit` with every crossing of `ray` with `shape` at `t > 0`, nearest first: the hit
/// and its [`Shape::surface_geometry`]. Each search starts a hair ([`CROSSING_GAP`] of the
/// shape's size) beyond the previous crossing, so two crossings closer than that (a ray all
/// but tangent to the surface) count once. The default [`Shape::pdf_toward`] and the
/// contract kit's area estimate are built on it.
pub fn for_each_crossing<S: Shape + ?Sized>(shape: &S, ray: &Ray, mut visit: impl FnMut(&Hit, &Surface)) {
    shape.crossings(ray, 0.0, f64::INFINITY, &mut |hit| {
        visit(hit, &shape.surface_geometry(ray, hit));
        ControlFlow::Continue(())
    });
}

/// [`Shape::crossings`] built on [`Shape::intersect`], the trait's default: the nearest hit
/// in the range, then the nearest one a hair ([`CROSSING_GAP`] of the shape's size) beyond
/// it, and so on, at most [`MAX_CROSSINGS`] of them, until `visit` breaks.
pub fn crossings_by_intersect<S: Shape + ?Sized>(
    shape: &S,
    ray: &Ray,
    t_min: f64,
    t_max: f64,
    visit: &mut dyn FnMut(&Hit) -> ControlFlow<()>,
) {
    let step = CrossingStep::along(&shape.bounds(), ray);
    let mut t_min = t_min;
    for _ in 0..MAX_CROSSINGS {
        let Some(hit) = shape.intersect(ray, t_min, t_max) else { return };
        if visit(&hit).is_break() {
            return;
        }
        t_min = step.beyond(hit.t);
    }
}

/// [`Shape::crossings`] for a shape that finds all its crossings along a ray at once (the
/// roots of one equation, the slabs of one test): visits those of `hits` (nearest first)
/// that [`crossings_by_intersect`] would, in `(t_min, t_max)` and each a hair beyond the
/// one visited before it, until `visit` breaks. `bounds` are the shape's.
pub fn visit_solved_crossings(
    bounds: &Aabb,
    ray: &Ray,
    t_min: f64,
    t_max: f64,
    hits: impl IntoIterator<Item = Hit>,
    visit: &mut dyn FnMut(&Hit) -> ControlFlow<()>,
) {
    // The step costs a square root and a division; most visits break at the first crossing.
    let mut step = None;
    let mut t_min = t_min;
    let mut visited: Option<f64> = None;
    for hit in hits {
        if let Some(t) = visited.take() {
            t_min = step.get_or_insert_with(|| CrossingStep::along(bounds, ray)).beyond(t);
        }
        if hit.t > t_min && hit.t < t_max {
            if visit(&hit).is_break() {
                return;
            }
            visited = Some(hit.t);
        }
    }
}

/// How far past one crossing the next is looked for along a ray: [`CROSSING_GAP`] of the
/// shape's size, or a relative step where that is smaller (unbounded shapes, far crossings).
#[derive(Clone, Copy)]
struct CrossingStep {
    gap: f64,
}

impl CrossingStep {
    fn along(bounds: &Aabb, ray: &Ray) -> Self {
        let size = if bounds.is_bounded() { (bounds.max - bounds.min).max_element() } else { 0.0 };
        Self { gap: CROSSING_GAP * size / ray.direction.length() }
    }

    /// The start of the search after a crossing at `t`.
    fn beyond(self, t: f64) -> f64 {
        t + self.gap.max(t.abs() * 1e-14)
    }
}

/// A shape in its own object space. Prism transforms rays into this space; `t` is shared
/// between spaces because the direction is not renormalised.
///
/// `Any` lets the renderer recognise its own shapes behind `Arc<dyn Shape>` (a small
/// triangle mesh's triangles go into the scene-level BVH); plugins need do nothing for it.
pub trait Shape: Any + Send + Sync + Debug {
    /// Object-space bounds; [`Aabb::INFINITE`] for unbounded shapes.
    fn bounds(&self) -> Aabb;

    /// The nearest hit with `t_min < t < t_max`, if any. Keep it cheap: the full surface
    /// is computed once, for the winning hit, by [`Shape::surface`].
    fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit>;

    /// The surface at a hit this shape returned for this ray.
    fn surface(&self, ray: &Ray, hit: &Hit) -> Surface;

    /// The surface at a hit without its texture coordinates: `point`, `normal`,
    /// `shading_normal` and `dpdu` exactly as [`Shape::surface`] gives them, while `uv` and
    /// `uv_density` may be left 0. Prism calls it for untextured materials, which is most
    /// hits; override it when the uv costs trigonometry (longitudes, latitudes), and let
    /// `surface` add the uv to it so the two cannot drift apart. The default is `surface`.
    fn surface_geometry(&self, ray: &Ray, hit: &Hit) -> Surface {
        self.surface(ray, hit)
    }

    /// The hit point and normals alone: exactly [`Shape::surface`]'s `point`, `normal` and
    /// `shading_normal`. The classic integrator calls it for untextured materials, which
    /// read neither uv nor tangent; override it where the tangent costs work the normals do
    /// not need (a sphere's longitude tangent takes two square roots and a division), and
    /// let `surface_geometry` build on it so the two cannot drift apart. The default takes
    /// them from `surface_geometry`.
    fn hit_point(&self, ray: &Ray, hit: &Hit) -> HitPoint {
        self.surface_geometry(ray, hit).point_and_normals()
    }

    /// True when `point` (object space) lies inside the solid. Prism asks it once per render
    /// for the camera position, as POV-Ray does: a camera inside a glass or water object sees
    /// through that interior first (its rays leave the object rather than enter it), and CSG
    /// asks it of every member. The default, false, suits surfaces without an inside
    /// (triangles, meshes); closed shapes should answer it, with POV-Ray's answer on the
    /// surface itself where the shape is POV-Ray's (see [`crate::pov::EPSILON`]).
    fn inside(&self, point: DVec3) -> bool {
        let _ = point;
        false
    }

    /// False for a shape that bounds no solid (a flat rectangle or triangle, an open mesh):
    /// its [`Shape::inside`] is false everywhere, and CSG takes it to be inside nothing even
    /// where it inverts it (`inverse`, or a member a difference subtracts), as POV-Ray does,
    /// whose `Inside` of a triangle, a polygon or a mesh without `inside_vector` answers
    /// false before looking at the inversion. The default, true, suits closed shapes.
    fn has_inside(&self) -> bool {
        true
    }

    /// A box holding every point [`Shape::inside`] accepts. The default, [`Shape::bounds`],
    /// suits shapes whose inside their surface encloses; a shape whose inside reaches past
    /// its surface (a disc's is the half-space behind it, as in POV-Ray) answers an infinite
    /// box, so that CSG does not take points beyond the surface's box to be outside it.
    fn inside_bounds(&self) -> Aabb {
        self.bounds()
    }

    /// Calls `visit` with every crossing of `ray` with the surface at `t_min < t < t_max`,
    /// nearest first, until it breaks. CSG walks its members' crossings with it and keeps
    /// those on the combined solid's boundary, so for a closed shape each crossing must flip
    /// [`Shape::inside`] (the contract kit's `check_inside_agrees_with_crossings` checks it).
    /// The default, [`crossings_by_intersect`], asks [`Shape::intersect`] again beyond each
    /// crossing; override it when all crossings come cheaper at once.
    fn crossings(&self, ray: &Ray, t_min: f64, t_max: f64, visit: &mut dyn FnMut(&Hit) -> ControlFlow<()>) {
        crossings_by_intersect(self, ray, t_min, t_max, visit);
    }

    /// True when anything lies on the ray with `t_min < t < t_max` (shadow rays).
    fn occluded(&self, ray: &Ray, t_min: f64, t_max: f64) -> bool {
        self.intersect(ray, t_min, t_max).is_some()
    }

    /// True when the shape certainly does not meet the convex hull of `points` (object
    /// space). Prism asks unbounded shapes this to skip them for a whole bundle of rays (the
    /// shadow rays from a point to an area light); bounded shapes are culled by their
    /// bounds instead. It also asks it of the box around a camera's lens, and then takes
    /// [`Shape::inside`] to answer everywhere in the hull as it does at one point of it (the
    /// inside test flips only where a ray crosses the surface). The default, false, is
    /// always correct; a `true` must be certain, with a margin for rounding.
    fn misses_hull(&self, points: &[DVec3]) -> bool {
        let _ = points;
        false
    }

    /// Surface area, for shapes that can be area lights. Exact, or `None`.
    fn area(&self) -> Option<f64> {
        None
    }

    /// A point on the surface from `u` in [0,1)^2, distributed with density
    /// [`Shape::pdf_area`] (uniformly, by default), with its outward normal. `None` when the
    /// shape cannot be sampled (the default); then it cannot emit light.
    fn sample_area(&self, u: DVec2) -> Option<AreaSample> {
        let _ = u;
        None
    }

    /// The density with respect to area with which [`Shape::sample_area`] picks `point`, a
    /// point of the surface. The default, `1 / area`, suits uniform sampling; 0 without an area.
    fn pdf_area(&self, point: DVec3) -> f64 {
        let _ = point;
        self.area().map_or(0.0, |area| 1.0 / area)
    }

    /// True when the shape can be an emitter: it can sample points on itself
    /// ([`Shape::sample_area`]) and directions toward itself ([`Shape::sample_toward`]).
    /// Prism refuses an emissive material on a shape that cannot. The default asks
    /// `sample_area` once.
    fn can_emit(&self) -> bool {
        self.sample_area(DVec2::splat(0.5)).is_some()
    }

    /// A direction from `reference` toward the shape, for next-event estimation: the nearest
    /// point of the shape along it and its density with respect to solid angle at
    /// `reference` (object space). `None` when nothing could be sampled (a degenerate sample
    /// seen edge-on, or a shape that cannot emit).
    ///
    /// The default, [`sample_toward_by_area`], samples a point with [`Shape::sample_area`], then follows the ray from
    /// `reference` through it: the nearest crossing is the point returned, and the density
    /// is [`Shape::pdf_toward`] of the direction, which counts every crossing (each of them
    /// could have been the sampled point). Override it with a sampler that spends its
    /// samples on what the reference sees (the sphere samples the cone it subtends), and then
    /// override `pdf_toward` to match.
    fn sample_toward(&self, reference: DVec3, u: DVec2) -> Option<DirectionSample> {
        sample_toward_by_area(self, reference, u)
    }

    /// The density with respect to solid angle at `reference` (object space) with which
    /// [`Shape::sample_toward`] produces `direction` (any non-zero length); 0 for directions
    /// that miss the shape. A direction can cross the surface several times (a closed or
    /// concave shape), and a sampler that picks points anywhere on the surface could have
    /// picked any of those crossings: its density is the sum over all of them.
    ///
    /// The default, [`pdf_toward_by_area`], does exactly that for [`Shape::sample_area`]'s points: the sum over every
    /// crossing ([`for_each_crossing`]) of [`Shape::pdf_area`] converted to solid angle,
    /// `pdf_area * distance^2 / |cos|` ([`math::area_to_solid_angle`]).
    fn pdf_toward(&self, reference: DVec3, direction: DVec3) -> f64 {
        pdf_toward_by_area(self, reference, direction)
    }

    /// The POV-Ray 3.7 SDL of this shape in object space, already mapped to POV-Ray's
    /// left-handed frame with [`crate::pov::vector`] (z negated). `None` when the shape has
    /// no POV-Ray equivalent; the exporter then reports an error naming it.
    fn to_pov(&self) -> Option<String> {
        None
    }

    /// [`Shape::to_pov`] for shapes that read files (a font): `files` writes their paths as
    /// the exported file must name them. The exporter calls this one; the default ignores
    /// `files` and calls `to_pov`.
    fn to_pov_with(&self, files: &dyn crate::pov::FilePaths) -> Option<String> {
        let _ = files;
        self.to_pov()
    }

    /// The shape as canonical Mitsuba 3 shapes in object space (a closed cylinder is a tube
    /// and two disks), for `prism export mitsuba`. `None` when Mitsuba has no equivalent;
    /// the exporter then reports an error naming the shape.
    fn to_mitsuba(&self) -> Option<Vec<crate::mitsuba::MitsubaShape>> {
        None
    }
}

/// [`Shape::sample_toward`] built on [`Shape::sample_area`], the trait's default, for shapes
/// that sample some references another way (the sphere from inside): a point sampled on the
/// surface, replaced by the nearest crossing of the ray from `reference` through it, with
/// the density [`pdf_toward_by_area`] of that direction. `None` when `sample_area` is, or
/// when the density is 0 or infinite (the sample seen edge-on).
pub fn sample_toward_by_area<S: Shape + ?Sized>(shape: &S, reference: DVec3, u: DVec2) -> Option<DirectionSample> {
    let sample = shape.sample_area(u)?;
    let ray = Ray::new(reference, sample.point - reference);
    let mut nearest: Option<Surface> = None;
    let mut pdf = 0.0;
    for_each_crossing(shape, &ray, |_, surface| {
        nearest.get_or_insert(*surface);
        pdf += math::area_to_solid_angle(shape.pdf_area(surface.point), reference, surface.point, surface.normal);
    });
    let nearest = nearest?;
    (pdf > 0.0 && pdf.is_finite()).then_some(DirectionSample {
        point: nearest.point,
        normal: nearest.normal,
        pdf_solid_angle: pdf,
    })
}

/// [`Shape::sample_toward`] for flat shapes (discs, triangles, rectangles), which a ray
/// crosses at most once: the area sample itself is the nearest crossing, so its density
/// converted to solid angle is the direction's, with no ray to follow. `None` when
/// `sample_area` is, or when the sample is seen edge-on.
pub fn sample_toward_flat<S: Shape + ?Sized>(shape: &S, reference: DVec3, u: DVec2) -> Option<DirectionSample> {
    let sample = shape.sample_area(u)?;
    let pdf = math::area_to_solid_angle(sample.pdf_area, reference, sample.point, sample.normal);
    (pdf > 0.0).then_some(DirectionSample { point: sample.point, normal: sample.normal, pdf_solid_angle: pdf })
}

/// [`Shape::pdf_toward`] for points sampled by [`Shape::sample_area`], the trait's default:
/// the sum over every crossing of the ray from `reference` along `direction`
/// ([`for_each_crossing`]) of [`Shape::pdf_area`] there, converted to solid angle with
/// [`math::area_to_solid_angle`].
pub fn pdf_toward_by_area<S: Shape + ?Sized>(shape: &S, reference: DVec3, direction: DVec3) -> f64 {
    let mut pdf = 0.0;
    for_each_crossing(shape, &Ray::new(reference, direction), |_, surface| {
        pdf += math::area_to_solid_angle(shape.pdf_area(surface.point), reference, surface.point, surface.normal);
    });
    pdf
}
