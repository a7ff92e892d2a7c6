//! Constructive solid geometry: POV-Ray 3.7's `union`, `merge`, `intersection` and
//! `difference` over any shapes (nested CSG included), each member placed by its own
//! transform and optionally `inverse`.
//!
//! What each operator returns follows POV-Ray's `csg.cpp`: a union keeps every member's
//! crossings (its interior surfaces show through glass); a merge keeps a member's crossing
//! only where it lies inside no other member; an intersection only where it lies inside every
//! other member; a difference `A - B - C` is the intersection of `A` with the inverses of
//! `B` and `C`. Inside tests: a union or merge contains a point that some member contains, an
//! intersection or difference one that every (inverted, for a difference's later members)
//! member contains. `inverse` flips a member's inside test and its normal.
//!
//! POV-Ray inverts a group (for `inverse`, and for each member a difference subtracts) by
//! inverting its members, and a union into the intersection of its inverted members: the same
//! solid, but one that keeps only the crossings outside every other member, as a merge does.
//! So a union inverted once or more, or lying at any depth inside a group that is, loses its
//! interior surfaces (two crossing cylinders drilled out of a box leave no walls where they
//! cross), and [`CsgShape::new`] makes it so.
//!
//! A hit names the member leaf it lies on (for its material and its surface) in the high
//! bits of [`Hit::part`]: leaf `l` with the member's own part `p` is `l << 16 | p`. Leaves
//! are numbered depth first, so a nested group's leaves follow on from its position.
//!
//! An emissive group is sampled as a light through its leaves: a point on some leaf's whole
//! surface (which may lie inside another member, off the group's boundary), then the ray from
//! the reference through it, whose nearest crossing of the group is the point lit. The
//! direction's density counts every leaf crossing along it, each of which could have been
//! the sampled point, so it is right for the directions that reach the group; the others give
//! no sample.

use std::ops::ControlFlow;
use std::sync::{Arc, OnceLock};

use glam::{DAffine3, DMat3, DVec2, DVec3};
use prism_api::{Aabb, DirectionSample, Hit, HitPoint, Ray, Shape, Surface, for_each_crossing, math};

use super::member_tree::MemberTree;

/// How a CSG group combines its members.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CsgOperation {
    /// Everything in any member; interior surfaces are kept.
    Union,
    /// Everything in any member, without the surfaces inside other members.
    Merge,
    /// What lies in every member.
    Intersection,
    /// The first member without the others.
    Difference,
}

impl CsgOperation {
    /// Every operation, in the order of [`CsgOperation::name`].
    pub const ALL: [CsgOperation; 4] =
        [CsgOperation::Union, CsgOperation::Merge, CsgOperation::Intersection, CsgOperation::Difference];

    /// The operation's name, as a scene's `shape` and POV-Ray's keyword.
    pub fn name(self) -> &'static str {
        match self {
            CsgOperation::Union => "union",
            CsgOperation::Merge => "merge",
            CsgOperation::Intersection => "intersection",
            CsgOperation::Difference => "difference",
        }
    }

    /// The operation called `name`.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|op| op.name() == name)
    }

    /// The fewest members the operation accepts.
    pub fn min_members(self) -> usize {
        match self {
            CsgOperation::Difference => 2,
            _ => 1,
        }
    }
}

use crate::accel::primitive::{PART_BITS, leaf_of};
use crate::accel::scene_bvh::SeparableParts;

/// The most leaves (plain shapes, nested groups' included) a group can number in the bits
/// of [`Hit::part`] above [`PART_BITS`].
pub const MAX_LEAVES: u32 = 1 << (32 - PART_BITS);

/// A member of a group: a shape (a plugin shape or another group) placed in the group's
/// space.
#[derive(Clone, Debug)]
pub struct CsgMember {
    /// The member's geometry in its own space.
    pub shape: Arc<dyn Shape>,
    /// Member space to group space.
    pub group_from_member: DAffine3,
    /// `inverse`: inside and outside swapped.
    pub inverse: bool,
    member_from_group: DAffine3,
    normal_to_group: DMat3,
    /// The member's space is the group's (as often inside a group): rays and points pass
    /// as they are.
    identity: bool,
    /// Inside and outside swapped in the group's combination (inverse, or a difference's
    /// subtracted member, or both, which cancel).
    inverted: bool,
    /// Bounds in group space of where the member, as combined, contains points; infinite
    /// when the member is unbounded or inverted.
    bounds: Aabb,
    /// Bounds in group space of the member's surface, inverted or not; infinite when the
    /// member is unbounded.
    surface_bounds: Aabb,
    /// Bounds in group space of the member's own inside ([`Shape::inside_bounds`]), inverted
    /// or not; infinite when that is unbounded (a disc's half-space).
    inside_bounds: Aabb,
    /// How far outside `inside_bounds` a point must lie to be outside the member's own
    /// shape without asking it: a margin for the rounding of the transformed box.
    outside_margin: f64,
    /// Index of the member's first leaf among the group's leaves.
    leaf_base: u32,
    /// Number of leaves (1 for a plain shape).
    leaves: u32,
    /// The shape bounds a solid ([`Shape::has_inside`]); one that does not is inside
    /// nothing, inverted or not.
    solid: bool,
}

impl CsgMember {
    /// `shape` placed by `group_from_member` (invertible), inverted when `inverse`.
    pub fn new(shape: Arc<dyn Shape>, group_from_member: DAffine3, inverse: bool) -> Self {
        let member_from_group = group_from_member.inverse();
        Self {
            shape,
            group_from_member,
            inverse,
            member_from_group,
            normal_to_group: member_from_group.matrix3.transpose(),
            identity: group_from_member == DAffine3::IDENTITY,
            inverted: inverse,
            bounds: Aabb::INFINITE,
            surface_bounds: Aabb::INFINITE,
            inside_bounds: Aabb::INFINITE,
            outside_margin: 0.0,
            leaf_base: 0,
            leaves: 1,
            solid: true,
        }
    }

    fn ray(&self, ray: &Ray) -> Ray {
        if self.identity {
            return *ray;
        }
        Ray::new(
            self.member_from_group.transform_point3(ray.origin),
            self.member_from_group.transform_vector3(ray.direction),
        )
    }

    /// True when the member, as the group combines it, contains the group-space `point`.
    fn contains(&self, point: DVec3) -> bool {
        if !self.solid {
            return false;
        }
        // Well outside its bounds a point is outside the shape: no transform, no test.
        if self.inside_bounds.is_bounded() && !self.inside_bounds.contains(point, self.outside_margin) {
            return self.inverted;
        }
        let point = if self.identity { point } else { self.member_from_group.transform_point3(point) };
        self.shape.inside(point) != self.inverted
    }
}

/// A plain shape at the bottom of a group's nesting that can sample points on itself,
/// placed in the group's space: what the group samples when it is a light.
#[derive(Clone, Debug)]
struct SamplingLeaf {
    shape: Arc<dyn Shape>,
    group_from_leaf: DAffine3,
    leaf_from_group: DAffine3,
    /// Leaf-space normals to group space (the inverse transpose), not normalised.
    normal_to_group: DMat3,
    /// |det| of the linear part: with the normal's stretch, how the transform scales areas.
    determinant: f64,
    /// Probability of sampling this leaf.
    probability: f64,
}

impl SamplingLeaf {
    fn new(shape: Arc<dyn Shape>, group_from_leaf: DAffine3) -> Self {
        let leaf_from_group = group_from_leaf.inverse();
        Self {
            shape,
            group_from_leaf,
            leaf_from_group,
            normal_to_group: leaf_from_group.matrix3.transpose(),
            determinant: group_from_leaf.matrix3.determinant().abs(),
            probability: 0.0,
        }
    }

    /// About the leaf's area in the group's space (exact under rotations and uniform scales),
    /// for choosing between leaves.
    fn area_estimate(&self) -> f64 {
        self.shape.area().unwrap_or(1.0) * self.determinant.powf(2.0 / 3.0)
    }
}

/// A CSG group: a [`Shape`] whose object space is the group's space.
#[derive(Clone, Debug)]
pub struct CsgShape {
    operation: CsgOperation,
    members: Vec<CsgMember>,
    bounds: Aabb,
    leaves: u32,
    /// How it samples itself as a light, made when first asked (most groups never are).
    sampling: OnceLock<LightSampling>,
    /// A union's or merge's members in a tree, when they are many.
    tree: Option<MemberTree>,
    /// A union that keeps its members' crossings inside other members: every union but those
    /// POV-Ray has inverted (see the module's documentation), which keep crossings as a merge.
    interior_surfaces: bool,
    /// `interior_surfaces` here or in a group at any depth below (kept, so that asking it is
    /// not a walk of the whole nesting).
    any_interior_surfaces: bool,
    /// The box POV-Ray bounds the group by (`CSG::Compute_BBox`): a union's or merge's covers
    /// its members' own boxes, inverted ones too (so a union with an inverted member, which
    /// fills all space but a hole, has a finite box); an intersection's is the overlap of its
    /// members' that are not inverted. Only where POV-Ray asks a box instead of the shape
    /// does it matter: which objects a camera ray starts inside.
    container_bounds: Aabb,
}

/// Members from which a union or merge puts its members in a [`MemberTree`].
const TREE_MEMBERS: usize = 8;

/// The leaves a group samples as a light, nested groups' included, each with its
/// probability, and about the area of them the group shows.
#[derive(Clone, Debug, Default)]
struct LightSampling {
    leaves: Vec<SamplingLeaf>,
    shown_area: f64,
}

/// The most leaves a group samples as a light: each light sample and each density looks at
/// every one of them. A larger group lights the scene only through the rays that reach it.
pub const MAX_SAMPLED_LEAVES: u32 = 64;

/// The box both `a` and `b` cover ([`Aabb::EMPTY`] when they do not meet).
fn overlap(a: Aabb, b: Aabb) -> Aabb {
    let (min, max) = (a.min.max(b.min), a.max.min(b.max));
    if min.cmple(max).all() { Aabb { min, max } } else { Aabb::EMPTY }
}

impl CsgShape {
    /// The group `operation` of `members` (at least [`CsgOperation::min_members`]).
    pub fn new(operation: CsgOperation, members: Vec<CsgMember>) -> Self {
        assert!(members.len() >= operation.min_members(), "{} needs more members", operation.name());
        let mut members = members;
        let mut leaves = 0;
        for (i, m) in members.iter_mut().enumerate() {
            let subtracted = operation == CsgOperation::Difference && i > 0;
            m.inverted = m.inverse != subtracted;
            // Inverted twice (`inverse` on a subtracted member), a union is still changed.
            if (m.inverse || subtracted)
                && let Some(group) = CsgShape::of(m.shape.as_ref()).filter(|g| g.has_interior_surfaces())
            {
                m.shape = Arc::new(group.inverted_by_pov_ray());
            }
            m.solid = m.shape.has_inside();
            let own = m.shape.bounds();
            m.surface_bounds = if own.is_bounded() { own.transformed(&m.group_from_member) } else { Aabb::INFINITE };
            let inner = m.shape.inside_bounds();
            m.inside_bounds = if inner.is_bounded() { inner.transformed(&m.group_from_member) } else { Aabb::INFINITE };
            m.outside_margin = 1e-9 * (1.0 + m.inside_bounds.min.abs().max(m.inside_bounds.max.abs()).max_element());
            m.bounds = if m.inverted { Aabb::INFINITE } else { m.inside_bounds };
            m.leaf_base = leaves;
            m.leaves = CsgShape::of(m.shape.as_ref()).map_or(1, |group| group.leaves);
            leaves += m.leaves;
        }
        let bounds = match operation {
            CsgOperation::Union | CsgOperation::Merge => {
                // An inverted member of a union fills all space but a bounded hole.
                members.iter().fold(Aabb::EMPTY, |b, m| b.union(m.bounds))
            }
            CsgOperation::Intersection | CsgOperation::Difference => {
                members.iter().fold(Aabb::INFINITE, |b, m| overlap(b, m.bounds))
            }
        };
        let tree = (matches!(operation, CsgOperation::Union | CsgOperation::Merge) && members.len() >= TREE_MEMBERS)
            .then(|| MemberTree::new(&members.iter().map(|m| m.bounds).collect::<Vec<_>>()));
        let interior_surfaces = operation == CsgOperation::Union;
        let any_interior_surfaces = interior_surfaces
            || members.iter().any(|m| CsgShape::of(m.shape.as_ref()).is_some_and(CsgShape::has_interior_surfaces));
        let container_bounds = container_bounds(operation, &members);
        Self {
            operation,
            members,
            bounds,
            leaves,
            sampling: OnceLock::new(),
            tree,
            interior_surfaces,
            any_interior_surfaces,
            container_bounds,
        }
    }

    /// The box POV-Ray bounds the group by, in the group's space: a point outside it is in
    /// none of POV-Ray's ray containers, whatever the inside test says.
    pub fn container_bounds(&self) -> Aabb {
        self.container_bounds
    }

    /// `shape` as a group, when it is one.
    pub fn of(shape: &dyn Shape) -> Option<&CsgShape> {
        let any: &dyn std::any::Any = shape;
        any.downcast_ref::<CsgShape>()
    }

    /// True when the group or a group inside it keeps interior surfaces.
    fn has_interior_surfaces(&self) -> bool {
        self.any_interior_surfaces
    }

    /// The group's crossings as POV-Ray's inverted form of it keeps them: every union in it,
    /// at any depth, without its interior surfaces. Same solid, same leaves.
    fn inverted_by_pov_ray(&self) -> CsgShape {
        let mut group = self.clone();
        group.interior_surfaces = false;
        group.any_interior_surfaces = false;
        group.sampling = OnceLock::new();
        for m in &mut group.members {
            if let Some(nested) = CsgShape::of(m.shape.as_ref()).filter(|g| g.has_interior_surfaces()) {
                m.shape = Arc::new(nested.inverted_by_pov_ray());
            }
        }
        group
    }

    /// True when some member other than `except` contains the group-space `point`.
    fn another_contains(&self, point: DVec3, except: Option<usize>) -> bool {
        let contains = |j: usize| Some(j) != except && self.members[j].contains(point);
        match &self.tree {
            Some(tree) => tree.any_at(point, |j| contains(j as usize)),
            None => (0..self.members.len()).any(contains),
        }
    }

    /// The group's light sampling, made on first use: its leaves that can sample points on
    /// themselves, each chosen in proportion to the area it shows (its area times the
    /// fraction of probe points on it that lie on the group's boundary, with a floor, so that
    /// a leaf whose little boundary the probes missed is still sampled). None for a group of
    /// more than [`MAX_SAMPLED_LEAVES`] leaves.
    fn light_sampling(&self) -> &LightSampling {
        self.sampling.get_or_init(|| {
            if self.leaves > MAX_SAMPLED_LEAVES {
                return LightSampling::default();
            }
            let mut leaves = Vec::new();
            collect_sampling_leaves(&self.members, DAffine3::IDENTITY, &mut leaves);
            // A leaf scaled beyond f64's range has no usable size.
            leaves.retain(|leaf| {
                let area = leaf.area_estimate();
                area.is_finite() && area > 0.0
            });
            let shown: Vec<f64> = leaves.iter().map(|leaf| self.shown_fraction(leaf)).collect();
            let weights: Vec<f64> =
                leaves.iter().zip(&shown).map(|(leaf, fraction)| leaf.area_estimate() * (fraction + 1e-3)).collect();
            let total: f64 = weights.iter().sum();
            if !(total.is_finite() && total > 0.0) {
                return LightSampling::default();
            }
            for (leaf, weight) in leaves.iter_mut().zip(&weights) {
                leaf.probability = weight / total;
            }
            let shown_area = leaves.iter().zip(&shown).map(|(leaf, fraction)| leaf.area_estimate() * fraction).sum();
            LightSampling { leaves, shown_area }
        })
    }

    /// The fraction of 64 points spread over `leaf`'s surface that the group shows: a probe
    /// from just off the point along its normal meets the group there.
    fn shown_fraction(&self, leaf: &SamplingLeaf) -> f64 {
        const SIDE: usize = 8;
        let size = leaf.shape.bounds().transformed(&leaf.group_from_leaf);
        let probe = 1e-6 * (size.max - size.min).max_element();
        let mut shown = 0;
        for i in 0..SIDE * SIDE {
            let u = DVec2::new(((i % SIDE) as f64 + 0.5) / SIDE as f64, ((i / SIDE) as f64 + 0.5) / SIDE as f64);
            let Some(sample) = leaf.shape.sample_area(u) else { continue };
            let point = leaf.group_from_leaf.transform_point3(sample.point);
            let normal = (leaf.normal_to_group * sample.normal).normalize();
            let ray = Ray::new(point + normal * probe, -normal);
            if self.intersect(&ray, 0.0, 2.0 * probe).is_some() {
                shown += 1;
            }
        }
        f64::from(shown) / (SIDE * SIDE) as f64
    }

    /// About the area the group shows of the surfaces it samples as a light (in the group's
    /// space; 0 when none can be sampled): the light's size, for weighing it against other
    /// lights.
    pub fn sampled_area(&self) -> f64 {
        self.light_sampling().shown_area
    }

    /// The density, with respect to solid angle at `reference`, with which the leaves'
    /// sampling produces `direction`: over every leaf crossing along it, the leaf's
    /// probability times its area density there in the group's space.
    fn leaf_direction_pdf(&self, reference: DVec3, direction: DVec3) -> f64 {
        let mut pdf = 0.0;
        for leaf in &self.light_sampling().leaves {
            let ray = Ray::new(
                leaf.leaf_from_group.transform_point3(reference),
                leaf.leaf_from_group.transform_vector3(direction),
            );
            for_each_crossing(leaf.shape.as_ref(), &ray, |_, surface| {
                let normal = leaf.normal_to_group * surface.normal;
                // Nanson: the leaf's area element grows by |det| |M^-T n|.
                let area_scale = leaf.determinant * normal.length();
                let pdf_area = leaf.probability * leaf.shape.pdf_area(surface.point) / area_scale;
                let point = leaf.group_from_leaf.transform_point3(surface.point);
                pdf += math::area_to_solid_angle(pdf_area, reference, point, normal.normalize());
            });
        }
        pdf
    }

    /// How the group combines its members.
    pub fn operation(&self) -> CsgOperation {
        self.operation
    }

    /// The members, in order.
    pub fn members(&self) -> &[CsgMember] {
        &self.members
    }

    /// Number of leaves (plain shapes) in the group, nested groups included.
    pub fn leaves(&self) -> u32 {
        self.leaves
    }

    /// True when the scene's tree may hold the members one by one in place of the group: a
    /// union of two or more members that keeps its interior surfaces, whose members'
    /// surfaces are all bounded. Its nearest hit is the nearest of its members' own (its
    /// [`SeparableParts`]), the lowest member on a tie, so each member can be a leaf of the
    /// scene's tree (as POV-Ray puts a union's members into its bounding hierarchy) and a ray
    /// meets the few near it without a walk of the group's own tree.
    pub fn is_separable(&self) -> bool {
        self.operation == CsgOperation::Union
            && self.interior_surfaces
            && self.members.len() >= 2
            && self.members.iter().all(|m| m.surface_bounds.is_bounded())
    }

    /// True when a crossing of member `index` at group-space `point` lies on the boundary the
    /// group shows.
    fn keeps(&self, index: usize, point: DVec3) -> bool {
        match self.operation {
            CsgOperation::Union if self.interior_surfaces => true,
            CsgOperation::Union | CsgOperation::Merge => !self.another_contains(point, Some(index)),
            CsgOperation::Intersection | CsgOperation::Difference => {
                self.members.iter().enumerate().all(|(j, m)| j == index || m.contains(point))
            }
        }
    }

    /// The member a hit of this group lies on, and the member's own hit.
    fn member_hit(&self, hit: &Hit) -> (&CsgMember, Hit) {
        let leaf = leaf_of(hit);
        let member = self
            .members
            .iter()
            .find(|m| leaf >= m.leaf_base && leaf < m.leaf_base + m.leaves)
            .expect("a group's hit names one of its leaves");
        (member, Hit { part: hit.part - (member.leaf_base << PART_BITS), ..*hit })
    }

    /// Group space from the member's surface; normals flipped for inverted members.
    fn to_group(member: &CsgMember, surface: Surface) -> Surface {
        let HitPoint { point, normal, shading_normal } = Self::point_to_group(member, surface.point_and_normals());
        let dpdu = member.group_from_member.transform_vector3(surface.dpdu);
        // uv units per length: the member's, over how much the transform stretches along dpdu.
        let stretch = dpdu.length() / surface.dpdu.length();
        let uv_density = if stretch > 0.0 && stretch.is_finite() { surface.uv_density / stretch } else { 0.0 };
        Surface { point, normal, shading_normal, uv: surface.uv, uv_density, dpdu }
    }

    /// A member's surface point and normals in the group's space (an inverted member's
    /// normals turned around).
    fn point_to_group(member: &CsgMember, surface: HitPoint) -> HitPoint {
        let sign = if member.inverted { -1.0 } else { 1.0 };
        HitPoint {
            point: member.group_from_member.transform_point3(surface.point),
            normal: (member.normal_to_group * surface.normal).normalize() * sign,
            shading_normal: (member.normal_to_group * surface.shading_normal).normalize() * sign,
        }
    }

    /// The part of `(t_min, t_max)` where `ray` (its direction's reciprocal `inverse`) can
    /// cross member `index`'s surface: within the surface's bounds (an inverted member's
    /// too), widened a little (the interval is rounded, the member's own test is exact).
    /// `None` when it cannot.
    fn member_range(&self, index: usize, ray: &Ray, inverse: DVec3, t_min: f64, t_max: f64) -> Option<(f64, f64)> {
        let bounds = &self.members[index].surface_bounds;
        if !bounds.is_bounded() {
            return Some((t_min, t_max));
        }
        let (near, far) = bounds.ray_interval_inverse(ray.origin, inverse, t_min, t_max)?;
        Some(((near - 1e-9 * (1.0 + near.abs())).max(t_min), (far * (1.0 + 1e-9) + 1e-9).min(t_max)))
    }

    /// Calls `visit` with every kept crossing of member `index` in `(t_min, t_max)`, nearest
    /// first, until it breaks; the hits carry the group's leaf numbering. `inverse` is the
    /// reciprocal of the ray's direction.
    fn member_crossings(
        &self,
        index: usize,
        ray: &Ray,
        inverse: DVec3,
        t_min: f64,
        t_max: f64,
        visit: &mut dyn FnMut(&Hit) -> ControlFlow<()>,
    ) {
        let Some((t_min, t_max)) = self.member_range(index, ray, inverse, t_min, t_max) else { return };
        let member = &self.members[index];
        let member_ray = member.ray(ray);
        member.shape.crossings(&member_ray, t_min, t_max, &mut |hit| {
            if self.keeps(index, ray.at(hit.t)) {
                visit(&Hit { part: hit.part + (member.leaf_base << PART_BITS), ..*hit })
            } else {
                ControlFlow::Continue(())
            }
        });
    }

    /// The nearest kept crossing of member `index` in `(t_min, t_max)`: for a union, which
    /// keeps every crossing, the member's own nearest hit (no list of its crossings).
    fn member_nearest(&self, index: usize, ray: &Ray, inverse: DVec3, t_min: f64, t_max: f64) -> Option<Hit> {
        if self.interior_surfaces {
            let (t_min, t_max) = self.member_range(index, ray, inverse, t_min, t_max)?;
            let member = &self.members[index];
            let hit = member.shape.intersect(&member.ray(ray), t_min, t_max)?;
            return Some(Hit { part: hit.part + (member.leaf_base << PART_BITS), ..hit });
        }
        let mut nearest = None;
        self.member_crossings(index, ray, inverse, t_min, t_max, &mut |hit| {
            nearest = Some(*hit);
            ControlFlow::Break(())
        });
        nearest
    }
}

/// [`CsgShape::container_bounds`] of a group of `members` combined by `operation`.
fn container_bounds(operation: CsgOperation, members: &[CsgMember]) -> Aabb {
    let own = |m: &CsgMember| {
        let bounds = CsgShape::of(m.shape.as_ref()).map_or_else(|| m.shape.bounds(), CsgShape::container_bounds);
        if bounds.is_bounded() { bounds.transformed(&m.group_from_member) } else { Aabb::INFINITE }
    };
    match operation {
        CsgOperation::Union | CsgOperation::Merge => members.iter().fold(Aabb::EMPTY, |b, m| b.union(own(m))),
        CsgOperation::Intersection | CsgOperation::Difference => {
            members.iter().filter(|m| !m.inverted).fold(Aabb::INFINITE, |b, m| overlap(b, own(m)))
        }
    }
}

/// Appends to `out` the leaves below `members` (placed in some group's space by
/// `group_from_members`) that can sample points on themselves, nested groups' included.
fn collect_sampling_leaves(members: &[CsgMember], group_from_members: DAffine3, out: &mut Vec<SamplingLeaf>) {
    for m in members {
        let group_from_member = group_from_members * m.group_from_member;
        match CsgShape::of(m.shape.as_ref()) {
            Some(group) => collect_sampling_leaves(&group.members, group_from_member, out),
            None if m.shape.bounds().is_bounded() && m.shape.can_emit() => {
                out.push(SamplingLeaf::new(m.shape.clone(), group_from_member));
            }
            None => {}
        }
    }
}

/// A union's members as parts of the scene's tree (asked only of groups that
/// [`CsgShape::is_separable`]): a part's hit is the member's nearest, numbered among the
/// group's leaves, with the member's surface bounds clipping the ray as in the group's own
/// walk.
impl SeparableParts for CsgShape {
    fn part_count(&self) -> usize {
        self.members.len()
    }

    fn part_bounds(&self, index: usize) -> Aabb {
        self.members[index].surface_bounds
    }

    fn part_intersect(&self, index: usize, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit> {
        self.member_nearest(index, ray, DVec3::ONE / ray.direction, t_min, t_max)
    }
}

impl Shape for CsgShape {
    fn bounds(&self) -> Aabb {
        self.bounds
    }

    fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit> {
        let inverse = DVec3::ONE / ray.direction;
        if let Some(tree) = &self.tree {
            // Members in the tree's order; on a tie in t the first member wins, as below.
            let mut nearest: Option<(Hit, u32)> = None;
            // The limit is t_max, then just past the nearest hit so far (ties are searched).
            tree.visit_ray(ray, t_min, t_max, |index, limit| {
                if let Some(hit) = self.member_nearest(index as usize, ray, inverse, t_min, limit)
                    && nearest.is_none_or(|(best, at)| hit.t < best.t || (hit.t == best.t && index < at))
                {
                    nearest = Some((hit, index));
                }
                nearest.map_or(limit, |(hit, _)| hit.t.next_up())
            });
            return nearest.map(|(hit, _)| hit);
        }
        let mut nearest: Option<Hit> = None;
        for index in 0..self.members.len() {
            let limit = nearest.map_or(t_max, |h| h.t);
            if let Some(hit) = self.member_nearest(index, ray, inverse, t_min, limit) {
                nearest = Some(hit);
            }
        }
        nearest
    }

    fn surface(&self, ray: &Ray, hit: &Hit) -> Surface {
        let (member, member_hit) = self.member_hit(hit);
        Self::to_group(member, member.shape.surface(&member.ray(ray), &member_hit))
    }

    fn surface_geometry(&self, ray: &Ray, hit: &Hit) -> Surface {
        let (member, member_hit) = self.member_hit(hit);
        Self::to_group(member, member.shape.surface_geometry(&member.ray(ray), &member_hit))
    }

    fn hit_point(&self, ray: &Ray, hit: &Hit) -> HitPoint {
        let (member, member_hit) = self.member_hit(hit);
        Self::point_to_group(member, member.shape.hit_point(&member.ray(ray), &member_hit))
    }

    fn inside(&self, point: DVec3) -> bool {
        match self.operation {
            CsgOperation::Union | CsgOperation::Merge => self.another_contains(point, None),
            CsgOperation::Intersection | CsgOperation::Difference => self.members.iter().all(|m| m.contains(point)),
        }
    }

    /// A point sampled on a leaf's surface, by area (the leaves chosen by the area of them
    /// the group shows), and the nearest crossing of the group along the ray from `reference`
    /// through it; `None` when that ray misses the group (the point lay off its boundary).
    fn sample_toward(&self, reference: DVec3, u: DVec2) -> Option<DirectionSample> {
        // The leaf whose share of [0, 1) holds u.x, and u.x's place within that share.
        let leaves = &self.light_sampling().leaves;
        let mut rest = u.x;
        let mut leaf = leaves.last()?;
        for candidate in leaves {
            if rest < candidate.probability {
                leaf = candidate;
                break;
            }
            rest -= candidate.probability;
        }
        let reuse = (rest / leaf.probability).clamp(0.0, 1.0 - f64::EPSILON);
        let sample = leaf.shape.sample_area(DVec2::new(reuse, u.y))?;
        let ray = Ray::new(reference, leaf.group_from_leaf.transform_point3(sample.point) - reference);
        let hit = self.intersect(&ray, 0.0, f64::INFINITY)?;
        let surface = self.surface_geometry(&ray, &hit);
        let pdf = self.leaf_direction_pdf(reference, ray.direction);
        (pdf > 0.0 && pdf.is_finite()).then_some(DirectionSample {
            point: surface.point,
            normal: surface.normal,
            pdf_solid_angle: pdf,
        })
    }

    /// [`CsgShape::sample_toward`]'s density: 0 for a direction that misses the group,
    /// else the leaves' density of it.
    fn pdf_toward(&self, reference: DVec3, direction: DVec3) -> f64 {
        if self.light_sampling().leaves.is_empty()
            || self.intersect(&Ray::new(reference, direction), 0.0, f64::INFINITY).is_none()
        {
            return 0.0;
        }
        self.leaf_direction_pdf(reference, direction)
    }

    fn crossings(&self, ray: &Ray, t_min: f64, t_max: f64, visit: &mut dyn FnMut(&Hit) -> ControlFlow<()>) {
        // Every member's kept crossings, merged in t order.
        let inverse = DVec3::ONE / ray.direction;
        let mut all = Vec::new();
        let mut collect = |index: usize| {
            self.member_crossings(index, ray, inverse, t_min, t_max, &mut |hit| {
                all.push(*hit);
                ControlFlow::Continue(())
            });
        };
        match &self.tree {
            Some(tree) => tree.visit_ray(ray, t_min, t_max, |index, limit| {
                collect(index as usize);
                limit
            }),
            None => (0..self.members.len()).for_each(&mut collect),
        }
        // Equal t in member order (leaves are numbered in member order).
        all.sort_by(|a, b| a.t.total_cmp(&b.t).then(a.part.cmp(&b.part)));
        for hit in &all {
            if visit(hit).is_break() {
                return;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use prism_sphere::Sphere;

    fn sphere(center: DVec3, radius: f64) -> Arc<dyn Shape> {
        Arc::new(Sphere { center, radius })
    }

    fn member(shape: Arc<dyn Shape>) -> CsgMember {
        CsgMember::new(shape, DAffine3::IDENTITY, false)
    }

    /// Two unit spheres at x = -0.5 and x = +0.5.
    fn pair(operation: CsgOperation) -> CsgShape {
        CsgShape::new(operation, vec![member(sphere(DVec3::X * -0.5, 1.0)), member(sphere(DVec3::X * 0.5, 1.0))])
    }

    /// Every crossing t of a ray along +x from x = -5.
    fn crossings_along_x(shape: &dyn Shape) -> Vec<f64> {
        let ray = Ray::new(DVec3::X * -5.0, DVec3::X);
        let mut ts = Vec::new();
        shape.crossings(&ray, 1e-9, f64::INFINITY, &mut |hit| {
            ts.push(hit.t);
            ControlFlow::Continue(())
        });
        ts
    }

    fn assert_ts(found: &[f64], expected: &[f64]) {
        assert_eq!(found.len(), expected.len(), "{found:?} vs {expected:?}");
        for (f, e) in found.iter().zip(expected) {
            assert!((f - e).abs() < 1e-9, "{found:?} vs {expected:?}");
        }
    }

    /// Along the x axis the spheres span [-1.5, 0.5] and [-0.5, 1.5]; from x = -5 the ray
    /// meets their surfaces at t = 3.5, 4.5, 5.5, 6.5.
    #[test]
    fn each_operator_keeps_povrays_crossings() {
        assert_ts(&crossings_along_x(&pair(CsgOperation::Union)), &[3.5, 4.5, 5.5, 6.5]);
        assert_ts(&crossings_along_x(&pair(CsgOperation::Merge)), &[3.5, 6.5]);
        assert_ts(&crossings_along_x(&pair(CsgOperation::Intersection)), &[4.5, 5.5]);
        assert_ts(&crossings_along_x(&pair(CsgOperation::Difference)), &[3.5, 4.5]);
    }

    /// POV-Ray inverts a union into the intersection of its inverted members, which keeps no
    /// interior surfaces: subtracted or `inverse`, at any depth of the inverted member, twice
    /// inverted too, a union keeps the crossings a merge keeps (the union's own inside and the
    /// group's leaves unchanged); a union not inverted keeps all four.
    #[test]
    fn inverted_unions_lose_their_interior_surfaces() {
        let big = || member(sphere(DVec3::ZERO, 4.0));
        let group = |shape: CsgShape, inverse: bool| CsgMember::new(Arc::new(shape), DAffine3::IDENTITY, inverse);
        // From x = -5 the big sphere is crossed at t = 1 and 9.
        let subtracted = CsgShape::new(CsgOperation::Difference, vec![big(), group(pair(CsgOperation::Union), false)]);
        assert_ts(&crossings_along_x(&subtracted), &[1.0, 3.5, 6.5, 9.0]);
        let hit = subtracted.intersect(&Ray::new(DVec3::X * -0.5, DVec3::X), 1e-9, f64::INFINITY).unwrap();
        assert!((hit.t - 2.0).abs() < 1e-12, "from inside the hollow, the wall at x = 1.5: {}", hit.t);
        let inverse = CsgShape::new(CsgOperation::Intersection, vec![big(), group(pair(CsgOperation::Union), true)]);
        assert_ts(&crossings_along_x(&inverse), &[1.0, 3.5, 6.5, 9.0]);
        // Nested in the subtracted member, under an intersection, and inverted twice.
        let nested = CsgShape::new(
            CsgOperation::Intersection,
            vec![member(sphere(DVec3::ZERO, 3.0)), group(pair(CsgOperation::Union), false)],
        );
        let deep = CsgShape::new(CsgOperation::Difference, vec![big(), group(nested, false)]);
        assert_ts(&crossings_along_x(&deep), &[1.0, 3.5, 6.5, 9.0]);
        let twice = CsgShape::new(CsgOperation::Difference, vec![big(), group(pair(CsgOperation::Union), true)]);
        assert_ts(&crossings_along_x(&twice), &[3.5, 6.5]);
        assert_eq!(twice.leaves(), 3);
        // Not inverted: the union inside an intersection keeps its interior surfaces.
        let kept = CsgShape::new(CsgOperation::Intersection, vec![big(), group(pair(CsgOperation::Union), false)]);
        assert_ts(&crossings_along_x(&kept), &[3.5, 4.5, 5.5, 6.5]);
        assert_eq!(kept.members()[1].shape.bounds(), pair(CsgOperation::Union).bounds());
        assert!(twice.inside(DVec3::X * 0.2) && !twice.inside(DVec3::X * 2.0));
    }

    /// POV-Ray's box of a union counts an inverted member by its own box; an intersection's
    /// leaves inverted members out, and a subtracted `inverse` member (inverted twice) in.
    #[test]
    fn container_bounds_follow_pov_rays_boxes() {
        let inverted_sphere = CsgMember::new(sphere(DVec3::X * 3.0, 1.0), DAffine3::IDENTITY, true);
        let union = CsgShape::new(CsgOperation::Union, vec![member(sphere(DVec3::ZERO, 1.0)), inverted_sphere.clone()]);
        assert!(!union.bounds().is_bounded(), "the solid fills all space but a hole");
        let expected = Aabb { min: DVec3::new(-1.0, -1.0, -1.0), max: DVec3::new(4.0, 1.0, 1.0) };
        assert_eq!(union.container_bounds(), expected);
        let intersection =
            CsgShape::new(CsgOperation::Intersection, vec![member(sphere(DVec3::ZERO, 1.0)), inverted_sphere]);
        assert_eq!(intersection.container_bounds(), Aabb { min: DVec3::splat(-1.0), max: DVec3::splat(1.0) });
        let twice = CsgShape::new(
            CsgOperation::Difference,
            vec![member(sphere(DVec3::ZERO, 1.0)), CsgMember::new(sphere(DVec3::X, 1.0), DAffine3::IDENTITY, true)],
        );
        assert_eq!(twice.container_bounds(), Aabb { min: DVec3::new(0.0, -1.0, -1.0), max: DVec3::splat(1.0) });
        let nested = CsgShape::new(
            CsgOperation::Union,
            vec![CsgMember::new(Arc::new(union), DAffine3::from_translation(DVec3::Y), false)],
        );
        assert_eq!(nested.container_bounds(), Aabb { min: expected.min + DVec3::Y, max: expected.max + DVec3::Y });
    }

    #[test]
    fn a_ray_through_a_difference_hits_the_hollow() {
        let difference = pair(CsgOperation::Difference);
        let ray = Ray::new(DVec3::X * -5.0, DVec3::X);
        let hit = difference.intersect(&ray, 1e-9, f64::INFINITY).unwrap();
        assert!((hit.t - 3.5).abs() < 1e-12);
        assert_eq!(leaf_of(&hit), 0);
        // Beyond the first surface the next one is the subtracted sphere's: its normal, out of
        // the remaining solid, points into the hollow (+x), against the sphere's own.
        let second = difference.intersect(&ray, hit.t + 1e-6, f64::INFINITY).unwrap();
        assert!((second.t - 4.5).abs() < 1e-12);
        assert_eq!(leaf_of(&second), 1);
        let surface = difference.surface(&ray, &second);
        assert!((surface.point - DVec3::X * -0.5).length() < 1e-12);
        assert!((surface.normal - DVec3::X).length() < 1e-12, "{}", surface.normal);
        // A ray starting in the hollow sees nothing in front of it along +x.
        assert!(difference.intersect(&Ray::new(DVec3::ZERO, DVec3::X), 1e-9, f64::INFINITY).is_none());
    }

    #[test]
    fn inside_tests_follow_each_operator() {
        let (left, both, right, neither) = (DVec3::X * -1.2, DVec3::ZERO, DVec3::X * 1.2, DVec3::Y * 3.0);
        let cases = [
            (CsgOperation::Union, [true, true, true, false]),
            (CsgOperation::Merge, [true, true, true, false]),
            (CsgOperation::Intersection, [false, true, false, false]),
            (CsgOperation::Difference, [true, false, false, false]),
        ];
        for (operation, expected) in cases {
            let group = pair(operation);
            let found = [left, both, right, neither].map(|p| group.inside(p));
            assert_eq!(found, expected, "{operation:?}");
        }
    }

    #[test]
    fn inverse_flips_inside_and_normal() {
        let inverted = CsgShape::new(
            CsgOperation::Union,
            vec![CsgMember::new(sphere(DVec3::ZERO, 1.0), DAffine3::IDENTITY, true)],
        );
        assert!(!inverted.inside(DVec3::ZERO));
        assert!(inverted.inside(DVec3::X * 2.0));
        assert!(!inverted.bounds().is_bounded());
        let ray = Ray::new(DVec3::X * -5.0, DVec3::X);
        let hit = inverted.intersect(&ray, 1e-9, f64::INFINITY).unwrap();
        assert!((inverted.surface(&ray, &hit).normal - DVec3::X).length() < 1e-12);
        // An intersection with an inverted member is a difference.
        let cut = CsgShape::new(
            CsgOperation::Intersection,
            vec![
                member(sphere(DVec3::X * -0.5, 1.0)),
                CsgMember::new(sphere(DVec3::X * 0.5, 1.0), DAffine3::IDENTITY, true),
            ],
        );
        assert_ts(&crossings_along_x(&cut), &crossings_along_x(&pair(CsgOperation::Difference)));
        // Subtracting an inverted member keeps what lies inside it.
        let kept = CsgShape::new(
            CsgOperation::Difference,
            vec![
                member(sphere(DVec3::X * -0.5, 1.0)),
                CsgMember::new(sphere(DVec3::X * 0.5, 1.0), DAffine3::IDENTITY, true),
            ],
        );
        assert_ts(&crossings_along_x(&kept), &crossings_along_x(&pair(CsgOperation::Intersection)));
    }

    #[test]
    fn nested_groups_with_transforms_number_their_leaves() {
        // (lens of the pair, moved +10 along x) unioned with a small sphere at the origin.
        let lens: Arc<dyn Shape> = Arc::new(pair(CsgOperation::Intersection));
        let group = CsgShape::new(
            CsgOperation::Union,
            vec![
                member(sphere(DVec3::ZERO, 0.25)),
                CsgMember::new(lens, DAffine3::from_translation(DVec3::X * 10.0), false),
            ],
        );
        assert_eq!(group.leaves(), 3);
        assert!(group.inside(DVec3::X * 10.0) && !group.inside(DVec3::X * 10.6) && group.inside(DVec3::ZERO));
        let ray = Ray::new(DVec3::X * -5.0, DVec3::X);
        assert_ts(&crossings_along_x(&group), &[4.75, 5.25, 14.5, 15.5]);
        // The lens's near face is its second sphere's (leaf 1 + 1), its far face its first's.
        let near = group.intersect(&ray, 6.0, f64::INFINITY).unwrap();
        assert_eq!(leaf_of(&near), 2);
        let surface = group.surface(&ray, &near);
        assert!((surface.point - DVec3::X * 9.5).length() < 1e-12);
        assert!((surface.normal - DVec3::NEG_X).length() < 1e-12);
        let far = group.intersect(&ray, near.t + 1e-6, f64::INFINITY).unwrap();
        assert_eq!(leaf_of(&far), 1);
        // Bounds: the union of the small sphere's and the lens's (the overlap of its spheres).
        let b = group.bounds();
        assert!((b.min - DVec3::splat(-1.0).with_x(-0.25)).length() < 1e-9, "{b:?}");
        assert!((b.max - DVec3::new(10.5, 1.0, 1.0)).length() < 1e-9, "{b:?}");
    }

    #[test]
    fn bounds_of_intersections_and_differences_are_tight() {
        let lens = pair(CsgOperation::Intersection).bounds();
        assert!(
            (lens.min - DVec3::new(-0.5, -1.0, -1.0)).length() < 1e-9
                && (lens.max - DVec3::new(0.5, 1.0, 1.0)).length() < 1e-9
        );
        let cut = pair(CsgOperation::Difference).bounds();
        assert!(
            (cut.min - DVec3::new(-1.5, -1.0, -1.0)).length() < 1e-9
                && (cut.max - DVec3::new(0.5, 1.0, 1.0)).length() < 1e-9
        );
    }

    /// Unequal spheres at x = -0.5 and x = 0.4, whose surfaces meet in the plane x = 0.15:
    /// away from the centre of any group's bounds, through which the contract shoots rays
    /// along the axes (on the circle where two surfaces meet, rounding decides what is kept).
    fn unequal_pair(operation: CsgOperation) -> CsgShape {
        CsgShape::new(operation, vec![member(sphere(DVec3::X * -0.5, 1.0)), member(sphere(DVec3::X * 0.4, 0.8))])
    }

    /// The contract, inside flips at every crossing included. A union of overlapping members
    /// keeps surfaces inside the solid (POV-Ray's interior surfaces), where inside does not
    /// flip, so its members here are apart; the other operations show only the boundary.
    #[test]
    fn csg_groups_keep_the_shape_contract() {
        for operation in [CsgOperation::Merge, CsgOperation::Intersection, CsgOperation::Difference] {
            prism_api::contract::check_shape(&unequal_pair(operation));
        }
        let apart = CsgShape::new(
            CsgOperation::Union,
            vec![
                member(sphere(DVec3::X * -1.5, 1.0)),
                CsgMember::new(sphere(DVec3::ZERO, 0.5), DAffine3::from_translation(DVec3::X * 1.5), false),
            ],
        );
        prism_api::contract::check_shape(&apart);
        let nested = CsgShape::new(
            CsgOperation::Difference,
            vec![
                member(Arc::new(pair(CsgOperation::Merge))),
                CsgMember::new(
                    Arc::new(pair(CsgOperation::Intersection)),
                    DAffine3::from_scale(DVec3::splat(0.5)),
                    false,
                ),
            ],
        );
        prism_api::contract::check_shape(&nested);
    }

    /// A shape without an inside (a rectangle, an open mesh) is inside nothing even where the
    /// group inverts it, as POV-Ray's `Inside` of a polygon answers before the inversion: a
    /// sphere minus a rectangle through its centre keeps none of the sphere, only the part of
    /// the rectangle within it.
    #[test]
    fn members_without_an_inside_are_inside_nothing_even_inverted() {
        let sheet: Arc<dyn Shape> = Arc::new(prism_rectangle::Rectangle::new(4.0, 4.0));
        let group = CsgShape::new(CsgOperation::Difference, vec![member(sphere(DVec3::ZERO, 1.0)), member(sheet)]);
        for p in [DVec3::ZERO, DVec3::new(0.3, 0.2, 0.5), DVec3::new(0.0, 0.0, -0.9), DVec3::splat(3.0)] {
            assert!(!group.inside(p), "{p}");
        }
        // Down the z axis: the sphere's surface at z = 1 is not kept, the sheet's at 0 is.
        let ray = Ray::new(DVec3::new(0.0, 0.0, 3.0), -DVec3::Z);
        let mut ts = Vec::new();
        group.crossings(&ray, 1e-9, f64::INFINITY, &mut |hit| {
            ts.push(hit.t);
            ControlFlow::Continue(())
        });
        assert_ts(&ts, &[3.0]);
        // Beside the sphere the sheet lies outside it: nothing.
        let beside = Ray::new(DVec3::new(1.5, 0.0, 3.0), -DVec3::Z);
        assert!(group.intersect(&beside, 0.0, f64::INFINITY).is_none());
    }

    /// A mesh member finds the crossings at the very end of its bounds, where the group
    /// clips its search: rays through a see-through merge of a cube mesh and a sphere inside
    /// it cross the same surfaces, at the same distances, as through the analytic box's.
    #[test]
    fn mesh_members_keep_crossings_on_their_bounds() {
        use crate::geometry::mesh::{MeshShape, tests::axis_cube};
        let scale = DAffine3::from_scale(DVec3::splat(0.8));
        let merge = |cube: Arc<dyn Shape>| {
            CsgShape::new(
                CsgOperation::Merge,
                vec![CsgMember::new(cube, scale, false), member(sphere(DVec3::ZERO, 0.37))],
            )
        };
        let mesh = merge(Arc::new(MeshShape::new(Arc::new(axis_cube()))));
        let analytic = merge(Arc::new(prism_box::BoxShape { min: DVec3::splat(-0.5), max: DVec3::splat(0.5) }));
        let mut rng = prism_api::contract::TestRng::new(1);
        for _ in 0..2000 {
            let target = DVec3::new(rng.range(-0.4, 0.4), rng.range(-0.4, 0.4), rng.range(-0.4, 0.4));
            let ray = Ray::new(DVec3::new(0.9, 1.4, 3.5), target - DVec3::new(0.9, 1.4, 3.5));
            // Each hit, then the next beyond it, as a ray through a transparent surface goes on.
            let walk = |group: &CsgShape| {
                let (mut ts, mut from) = (Vec::new(), 1e-9);
                while let Some(hit) = group.intersect(&ray, from, f64::INFINITY).filter(|_| ts.len() < 8) {
                    ts.push(hit.t);
                    from = hit.t + 1e-4;
                }
                ts
            };
            let (found, expected) = (walk(&mesh), walk(&analytic));
            assert_eq!(found.len(), expected.len(), "{found:?} against {expected:?} along {ray:?}");
            assert!(found.iter().zip(&expected).all(|(a, b)| (a - b).abs() < 1e-6), "{found:?} against {expected:?}");
        }
    }

    /// A closed mesh is a member like any solid: a cube mesh minus a sphere, and its
    /// intersection with one, keep the contract and answer as the same groups of analytic
    /// shapes would (the mesh's cube is turned off the axes, so the box is turned too).
    #[test]
    fn closed_meshes_are_members() {
        use crate::geometry::mesh::{MeshShape, tests::tilted_cube};
        let cube: Arc<dyn Shape> = Arc::new(MeshShape::new(Arc::new(tilted_cube())));
        for operation in [CsgOperation::Difference, CsgOperation::Intersection, CsgOperation::Merge] {
            let group = CsgShape::new(operation, vec![member(cube.clone()), member(sphere(DVec3::X, 0.8))]);
            prism_api::contract::check_shape(&group);
            let turn = glam::DQuat::from_euler(glam::EulerRot::XYZ, 0.35, 0.5, 0.2);
            let inside_box = |p: DVec3| (turn.inverse() * p).abs().max_element() < 1.0;
            let mut rng = prism_api::contract::TestRng::new(operation as u64);
            for _ in 0..2000 {
                let p = DVec3::new(rng.range(-2.0, 2.0), rng.range(-2.0, 2.0), rng.range(-2.0, 2.0));
                let in_sphere = (p - DVec3::X).length() < 0.8;
                let expected = match operation {
                    CsgOperation::Difference => inside_box(p) && !in_sphere,
                    CsgOperation::Intersection => inside_box(p) && in_sphere,
                    _ => inside_box(p) || in_sphere,
                };
                // Away from the surfaces (the mesh's corners are rounded to f32).
                let near_box = ((turn.inverse() * p).abs().max_element() - 1.0).abs() < 1e-5;
                if !near_box && ((p - DVec3::X).length() - 0.8).abs() > 1e-9 {
                    assert_eq!(group.inside(p), expected, "{} at {p}", operation.name());
                }
            }
        }
    }

    /// Asserts that two groups give the same nearest hits, crossings and inside tests for
    /// 4000 random rays and points in `region`.
    fn assert_same_answers(a: &CsgShape, b: &CsgShape, region: &Aabb, rng: &mut prism_api::contract::TestRng) {
        let operation = a.operation;
        for _ in 0..4000 {
            let ray = Ray::new(rng.point_in(region), rng.unit_vector());
            let hit = |g: &CsgShape| g.intersect(&ray, 1e-9, f64::INFINITY).map(|h| (h.t, h.part));
            assert_eq!(hit(a), hit(b), "{operation:?} {ray:?}");
            let all = |g: &CsgShape| {
                let mut ts = Vec::new();
                g.crossings(&ray, 1e-9, f64::INFINITY, &mut |h| {
                    ts.push((h.t, h.part));
                    ControlFlow::Continue(())
                });
                ts
            };
            assert_eq!(all(a), all(b), "{operation:?} {ray:?}");
            let p = rng.point_in(region);
            assert_eq!(a.inside(p), b.inside(p), "{operation:?} {p}");
        }
    }

    /// A union or merge of many members finds its hits through a tree of them: the same hits,
    /// crossings and inside tests as the plain loop over every member, ties included
    /// (members that share surfaces).
    #[test]
    fn many_members_answer_through_their_tree_as_through_all() {
        use prism_api::contract::TestRng;
        let mut rng = TestRng::new(11);
        for operation in [CsgOperation::Union, CsgOperation::Merge] {
            let mut members: Vec<CsgMember> = (0..24)
                .map(|i| {
                    let centre = DVec3::new((i % 6) as f64 * 0.7, (i / 6) as f64 * 0.7, rng.range(-0.2, 0.2));
                    member(sphere(centre, rng.range(0.2, 0.6)))
                })
                .collect();
            // A repeated member (ties in t) and an inverted one (met everywhere).
            members.push(members[3].clone());
            members.push(CsgMember::new(sphere(DVec3::new(1.0, 1.0, 0.0), 5.0), DAffine3::IDENTITY, true));
            let tree = CsgShape::new(operation, members);
            assert!(tree.tree.is_some());
            let plain = CsgShape { tree: None, ..tree.clone() };
            let region = Aabb { min: DVec3::splat(-1.5), max: DVec3::new(5.0, 3.5, 1.5) };
            assert_same_answers(&tree, &plain, &region, &mut rng);
        }
    }

    /// A difference with many holes tests a subtracted member's surface only where the ray
    /// meets its bounds, and answers inside tests for points well outside a member's bounds
    /// without asking it: the same hits, crossings and inside tests as without bounds.
    #[test]
    fn members_bounds_spare_tests_without_changing_answers() {
        use prism_api::contract::TestRng;
        let mut rng = TestRng::new(5);
        let mut members = vec![member(sphere(DVec3::ZERO, 2.0))];
        for i in 0..30 {
            let centre = DVec3::new(rng.range(-2.0, 2.0), rng.range(-2.0, 2.0), rng.range(-2.0, 2.0));
            let placed = DAffine3::from_scale_rotation_translation(
                DVec3::new(1.0, 0.6, 1.4),
                glam::DQuat::from_rotation_y(0.3 * i as f64),
                centre,
            );
            members.push(CsgMember::new(sphere(DVec3::ZERO, rng.range(0.1, 0.5)), placed, i % 5 == 0));
        }
        for operation in [CsgOperation::Difference, CsgOperation::Intersection, CsgOperation::Merge] {
            let bounded = CsgShape::new(operation, members.clone());
            let mut unbounded = bounded.clone();
            for m in &mut unbounded.members {
                m.surface_bounds = Aabb::INFINITE;
                m.inside_bounds = Aabb::INFINITE;
            }
            assert!(bounded.members[1..].iter().all(|m| m.surface_bounds.is_bounded() && m.inside_bounds.is_bounded()));
            let region = Aabb { min: DVec3::splat(-3.0), max: DVec3::splat(3.0) };
            assert_same_answers(&bounded, &unbounded, &region, &mut rng);
        }
    }

    /// An emissive group's directions follow their density from references outside it, in
    /// a difference's hollow and inside a solid, through members placed by rotations and
    /// non-uniform scales and through nested groups; the points are the nearest crossings
    /// and the density is 0 exactly where a direction misses.
    #[test]
    fn groups_sample_directions_toward_them_with_their_density() {
        use prism_api::contract::{ContractConfig, check_sampling_toward};
        let config = ContractConfig { max_unsampled_fraction: 0.9, direction_samples: 16_384, ..Default::default() };
        let squashed = DAffine3::from_scale_rotation_translation(
            DVec3::new(1.2, 0.5, 0.8),
            glam::DQuat::from_rotation_z(0.6),
            DVec3::new(0.3, 0.2, 0.0),
        );
        let nested = CsgShape::new(
            CsgOperation::Union,
            vec![
                member(Arc::new(unequal_pair(CsgOperation::Difference))),
                CsgMember::new(Arc::new(pair(CsgOperation::Intersection)), squashed, false),
            ],
        );
        let groups = [
            pair(CsgOperation::Union),
            unequal_pair(CsgOperation::Merge),
            unequal_pair(CsgOperation::Intersection),
            unequal_pair(CsgOperation::Difference),
            nested,
        ];
        let references = [DVec3::new(0.3, 2.6, -1.1), DVec3::new(-3.5, 0.2, 0.4), DVec3::new(0.45, 0.05, 0.0)];
        for (group, leaves) in groups.iter().zip([2, 2, 2, 2, 4]) {
            assert_eq!(group.light_sampling().leaves.len(), leaves);
            check_sampling_toward(group, &references, &config);
        }
    }
}
