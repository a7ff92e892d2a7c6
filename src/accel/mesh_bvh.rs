//! The bottom level of Prism's two-level BVH: one tree per mesh over its triangles, in f32
//! object space.
//!
//! obvhs builds a binary tree (PLOC, reinsertion, one triangle per leaf); it is then
//! collapsed into the 8-wide tree shared with the top level (`accel::wide`) of least
//! expected cost, whose leaves hold up to sixteen triangles as groups over shared vertices
//! ([`crate::accel::triangle_groups`]). A ray is tested against a node's eight boxes and a
//! group's triangles eight at a time by the SIMD kernels (`accel::simd`: AVX2 where the CPU
//! has it, plain loops otherwise, with the same hits); children are visited nearest first.

use glam::{Vec3, Vec3A};
use obvhs::BvhBuildParams;
use obvhs::ploc::PlocSearchDistance;

use super::pages::PageArray;
use super::simd::{self, BoxRay, Dispatch, Kernels};
use super::triangle::{TriangleHit, WatertightRay};
use super::triangle_groups::{GroupHits, GroupWriter, TriangleGroups};
use super::wide::{
    CollapseCost, EMPTY, LEAF, LeafMaker, LeafVisitor, Node, StackEntry, WideTree, build_binary, with_traversal_stack,
};

/// A BVH over triangles.
#[derive(Clone)]
pub struct TriangleBvh {
    nodes: PageArray<Node>,
    /// The leaves' triangle groups; a leaf reference is the word at which its first starts.
    groups: TriangleGroups,
    /// Vertices of each triangle, in input order (for refining hits in f64).
    triangles: Vec<[Vec3; 3]>,
    /// Deepest stack a traversal can need.
    stack_size: usize,
    /// The collapse's expected cost of a ray entering the root's box.
    expected_cost: f32,
}

/// The shape of a [`TriangleBvh`].
#[derive(Clone, Copy, Debug)]
pub struct TreeStats {
    /// Wide nodes.
    pub nodes: usize,
    /// Leaves.
    pub leaves: usize,
    /// Triangle groups (a leaf has one or more).
    pub groups: usize,
    /// Mean children per node.
    pub children_per_node: f64,
    /// Mean triangles per group.
    pub triangles_per_group: f64,
    /// Mean distinct vertices per group.
    pub vertices_per_group: f64,
    /// The expected cost of a ray entering the root's box, in the collapse's units (a node
    /// test 1, a leaf 0.1 per started four triangles): lower is better, and unlike a timing
    /// it is the same on every run.
    pub expected_cost: f32,
}

impl std::fmt::Debug for TriangleBvh {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "TriangleBvh({} triangles, {} nodes, {} words of triangle groups)",
            self.triangles.len(),
            self.nodes.len(),
            self.groups.len()
        )
    }
}

/// Most triangles in one leaf.
const LEAF_TRIANGLES: usize = 16;

/// What the collapse weighs: an 8-wide node test costs 1, a leaf 0.1 per started four
/// triangles. A leaf costs far less than a node because its triangles lie side by side and
/// are fetched together, while each node is one more dependent cache miss down the tree.
/// Measured on the terrain and the dragon with incoherent rays when leaves were packets of
/// four triangles with their own vertices (best of three runs each, Mrays/s through the f32
/// API, on the trees of stop 32): packet cost 1 gave 2.73 and 2.88, 0.5 3.17 and 3.26, 0.25
/// 3.40 and 3.69, 0.1 3.33 and 3.50. On the trees built with the Morton cube
/// (`wide::build_binary`), two trees in one process timed in turn (six or eight rounds,
/// median speed-up of each against 0.2): 0.12 gave 1.006 and 1.032 (terrain, two runs) and
/// 1.072 and 1.040 (dragon), 0.1 1.031 and 1.020, 0.08 1.021 and 1.036, 0.05 1.022 and
/// 0.998, 0.3 0.988 and 0.960. With leaves as groups over shared vertices (eight rounds
/// each against this cost): 0.1, 0.15 or 0.2 per started eight triangles, 0.05 per four,
/// 0.05 plus 0.02 per triangle all gave 0.99-1.08, within the rounds' spread.
const LEAF_COST: CollapseCost = CollapseCost {
    node: 1.0,
    leaf: |triangles| (triangles <= LEAF_TRIANGLES).then(|| 0.1 * triangles.div_ceil(4) as f32),
};

/// Bytes prefetched for a leaf about to be tested. Its size is in its header, which is what
/// is being fetched: ask for the three lines a leaf of eight triangles over nine vertices
/// (168 bytes) reaches.
const LEAF_PREFETCH_BYTES: usize = 192;

/// Makes the collapse's leaves: groups of the triangles, in the order the collapse lists
/// them.
struct LeafGroups<'a>(GroupWriter<'a>);

impl LeafMaker for &mut LeafGroups<'_> {
    fn make(&mut self, prims: &[u32]) -> u32 {
        let start = self.0.leaf(prims);
        u32::try_from(start)
            .ok()
            .filter(|start| start & LEAF == 0)
            .expect("too many triangle groups for a leaf reference")
    }

    fn prefetch(&self, prims: &[u32]) {
        self.0.prefetch(prims);
    }
}

/// A ray prepared for traversal: the watertight test's shear and the slab test's
/// reciprocal direction.
struct TraversalRay {
    triangle: WatertightRay,
    boxes: BoxRay,
}

impl TraversalRay {
    #[inline(always)]
    fn new(ray: &WatertightRay) -> Self {
        Self { triangle: *ray, boxes: BoxRay::new(ray.origin, ray.direction) }
    }
}

impl TriangleBvh {
    /// Builds the tree over `triangles` (given by their vertices), which it keeps (to refine
    /// hits in f64). Triangles keep their indices: the hits name them by their place in
    /// `triangles`.
    ///
    /// # Panics
    ///
    /// When `triangles` is empty (meshes without triangles are rejected at import).
    pub fn build(triangles: Vec<[Vec3; 3]>) -> Self {
        assert!(!triangles.is_empty(), "a mesh BVH needs at least one triangle");
        let boxes: Vec<obvhs::aabb::Aabb> = triangles
            .iter()
            .map(|t| {
                let min = t[0].min(t[1]).min(t[2]);
                let max = t[0].max(t[1]).max(t[2]);
                obvhs::aabb::Aabb { min: Vec3A::from(min), max: Vec3A::from(max) }
            })
            .collect();
        // One triangle per BVH2 leaf: the collapse below forms the leaves. One pass of
        // reinsertion, not obvhs's second pass after its own leaf collapse (which has nothing
        // to collapse at one triangle per leaf): the second pass took a third of the build
        // and did not make traversal measurably faster. PLOC searches two clusters each way
        // for a merge partner (obvhs's `VeryLow`, not `medium_build`'s fourteen) and the pass
        // reinserts 3% of the nodes. On the Morton curve laid in a cube (`build_binary`) a
        // wider search made the terrain's tree worse: the collapsed tree's expected cost
        // (`WideTree::collapse`'s) was 8.964 and 12.567 (terrain and dragon, two and 4%)
        // against 9.096 and 12.588 with six and 3% (under the earlier packet price of 0.2,
        // fourteen and 3% gave 9.822 and 13.514 against six's 9.707 and 13.395), and PLOC's
        // time falls with the search distance. Incoherent rays ran 1-3% faster on the terrain
        // with two and 4% than with six and 3% (two trees timed in turn in one process). With
        // triangle groups the build had grown by their writer, and two and 3% (8.988 and
        // 12.627) builds the terrain in 0.290-0.291 s instead of 0.297-0.304 and the dragon in
        // 0.240-0.258 s instead of 0.291-0.299 (three alternating runs each).
        let params = BvhBuildParams {
            max_prims_per_leaf: 1,
            ploc_search_distance: PlocSearchDistance::VeryLow,
            reinsertion_batch_ratio: 0.03,
            post_collapse_reinsertion_batch_ratio_multiplier: 0.0,
            ..BvhBuildParams::medium_build()
        };
        let bvh2 = build_binary(boxes, params);
        let mut leaves = LeafGroups(GroupWriter::new(&triangles));
        let tree = WideTree::collapse(&bvh2, LEAF_COST, &mut leaves);
        let groups = leaves.0.finish();
        TriangleBvh {
            nodes: PageArray::new(tree.nodes),
            groups,
            triangles,
            stack_size: tree.stack_size,
            expected_cost: tree.expected_cost,
        }
    }

    /// Number of triangles.
    pub fn len(&self) -> usize {
        self.triangles.len()
    }

    /// True when the tree holds no triangle (never, once built).
    pub fn is_empty(&self) -> bool {
        self.triangles.is_empty()
    }

    /// Vertices of every triangle, in input order.
    pub fn triangles(&self) -> &[[Vec3; 3]] {
        &self.triangles
    }

    /// Vertices of triangle `index`.
    #[inline]
    pub fn triangle(&self, index: usize) -> &[Vec3; 3] {
        &self.triangles[index]
    }

    /// The tree's shape and expected cost.
    pub fn stats(&self) -> TreeStats {
        let children: usize = self.nodes.iter().map(|n| n.child.iter().filter(|&&c| c != EMPTY).count()).sum();
        let leaves = self.nodes.iter().flat_map(|n| n.child).filter(|&c| c != EMPTY && c & LEAF != 0).count();
        let (mut groups, mut triangles, mut vertices) = (0, 0, 0);
        for group in self.groups.iter() {
            groups += 1;
            triangles += group.triangle_count();
            vertices += group.vertex_count();
        }
        TreeStats {
            nodes: self.nodes.len(),
            leaves,
            groups,
            children_per_node: children as f64 / self.nodes.len() as f64,
            triangles_per_group: triangles as f64 / groups as f64,
            vertices_per_group: vertices as f64 / groups as f64,
            expected_cost: self.expected_cost,
        }
    }

    /// Bytes used by the nodes and the leaves' triangle groups (not the triangle list kept
    /// for shading).
    pub fn memory_bytes(&self) -> usize {
        self.nodes.len() * std::mem::size_of::<Node>() + 4 * self.groups.len()
    }

    /// Visits the triangles the ray may hit, nearest boxes first. `accept(triangle, hit,
    /// vertices)` is called for each f32 hit below the current bound (with the triangle's
    /// vertices, read from the leaf just tested rather than from [`Self::triangle`], which
    /// would be a cache miss) and returns the new bound (the accepted distance, which the
    /// traversal uses to prune) or `None` to reject the hit.
    #[inline]
    pub fn closest(
        &self,
        ray: &WatertightRay,
        t_max: f32,
        accept: impl FnMut(usize, TriangleHit, [Vec3; 3]) -> Option<f32>,
    ) {
        with_traversal_stack(self.stack_size, |stack| {
            simd::dispatch(Query::<_, false> { bvh: self, ray, t_max, stack, acceptor: AcceptClosest(accept) })
        });
    }

    /// True when `accept(triangle, hit, vertices)` takes any f32 hit with `t < t_max`.
    #[inline]
    pub fn any(
        &self,
        ray: &WatertightRay,
        t_max: f32,
        accept: impl FnMut(usize, TriangleHit, [Vec3; 3]) -> bool,
    ) -> bool {
        with_traversal_stack(self.stack_size, |stack| {
            simd::dispatch(Query::<_, true> { bvh: self, ray, t_max, stack, acceptor: AcceptAny(accept, false) })
        })
    }
}

/// What the traversal does with a candidate hit.
trait Acceptor {
    /// Offers a hit on the triangle with these vertices; returns the new bound on t if it
    /// was taken.
    fn offer(&mut self, prim: usize, hit: TriangleHit, vertices: [Vec3; 3]) -> Option<f32>;
    /// True when traversal can stop (any-hit queries).
    fn done(&self) -> bool;
}

struct AcceptClosest<F>(F);

impl<F: FnMut(usize, TriangleHit, [Vec3; 3]) -> Option<f32>> Acceptor for AcceptClosest<F> {
    #[inline(always)]
    fn offer(&mut self, prim: usize, hit: TriangleHit, vertices: [Vec3; 3]) -> Option<f32> {
        (self.0)(prim, hit, vertices)
    }

    #[inline(always)]
    fn done(&self) -> bool {
        false
    }
}

struct AcceptAny<F>(F, bool);

impl<F: FnMut(usize, TriangleHit, [Vec3; 3]) -> bool> Acceptor for AcceptAny<F> {
    #[inline(always)]
    fn offer(&mut self, prim: usize, hit: TriangleHit, vertices: [Vec3; 3]) -> Option<f32> {
        if (self.0)(prim, hit, vertices) {
            self.1 = true;
            Some(0.0)
        } else {
            None
        }
    }

    #[inline(always)]
    fn done(&self) -> bool {
        self.1
    }
}

/// One query (closest hit, or any hit when `ANY`), for [`simd::dispatch`].
struct Query<'a, A, const ANY: bool> {
    bvh: &'a TriangleBvh,
    ray: &'a WatertightRay,
    t_max: f32,
    stack: &'a mut [StackEntry],
    acceptor: A,
}

impl<A: Acceptor, const ANY: bool> Dispatch for Query<'_, A, ANY> {
    type Output = bool;

    #[inline(always)]
    fn run<K: Kernels>(mut self, kernels: K) -> bool {
        // Prepared here, with the kernels' instructions and straight into registers.
        let ray = TraversalRay::new(self.ray);
        traverse::<K, ANY>(kernels, self.bvh, &ray, self.t_max, self.stack, &mut self.acceptor)
    }
}

/// The leaves of a mesh BVH: groups of triangles, whose hits go to the acceptor.
struct GroupLeaves<'a, A, const ANY: bool> {
    groups: &'a TriangleGroups,
    /// A copy of the ray, kept in registers.
    ray: WatertightRay,
    hits: GroupHits,
    acceptor: &'a mut A,
}

impl<A: Acceptor, const ANY: bool> LeafVisitor for GroupLeaves<'_, A, ANY> {
    #[inline(always)]
    fn prefetch<K: Kernels>(&self, kernels: K, leaf: u32) {
        kernels.prefetch(self.groups.as_ptr().wrapping_add(leaf as usize).cast(), LEAF_PREFETCH_BYTES);
    }

    #[inline(always)]
    fn visit<K: Kernels>(&mut self, kernels: K, leaf: u32, t_max: &mut f32) -> bool {
        let mut start = leaf as usize;
        loop {
            let group = self.groups.group(start);
            let mut mask = kernels.group(&group, &self.ray, *t_max, &mut self.hits);
            while mask != 0 {
                let lane = mask.trailing_zeros() as usize;
                mask &= mask - 1;
                let hit = self.hits.get(lane);
                if hit.t < *t_max
                    && let Some(bound) =
                        self.acceptor.offer(group.prim(lane) as usize, hit, group.triangle_vertices(lane))
                {
                    if ANY && self.acceptor.done() {
                        return true;
                    }
                    *t_max = t_max.min(bound);
                }
            }
            if !group.more() {
                return false;
            }
            start = group.end();
        }
    }
}

/// The traversal with the kernels `K`; true when an any-hit query (`ANY`) found its hit.
#[inline(always)]
fn traverse<K: Kernels, const ANY: bool>(
    kernels: K,
    bvh: &TriangleBvh,
    ray: &TraversalRay,
    t_max: f32,
    stack: &mut [StackEntry],
    acceptor: &mut impl Acceptor,
) -> bool {
    let mut leaves =
        GroupLeaves::<_, ANY> { groups: &bvh.groups, ray: ray.triangle, hits: GroupHits::default(), acceptor };
    super::wide::traverse::<K, true>(kernels, &bvh.nodes, &ray.boxes, t_max, stack, &mut leaves)
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use prism_api::contract::TestRng;

    /// A bumpy grid of triangles: two per cell of an `n` by `n` grid over the unit square.
    pub(in crate::accel) fn grid(n: usize) -> Vec<[Vec3; 3]> {
        let p = |i: usize, j: usize| {
            let (x, z) = (i as f32 / n as f32, j as f32 / n as f32);
            Vec3::new(x, 0.1 * (7.0 * x).sin() * (5.0 * z).cos(), z)
        };
        let mut out = Vec::new();
        for i in 0..n {
            for j in 0..n {
                out.push([p(i, j), p(i, j + 1), p(i + 1, j)]);
                out.push([p(i + 1, j), p(i, j + 1), p(i + 1, j + 1)]);
            }
        }
        out
    }

    fn brute(tris: &[[Vec3; 3]], r: &WatertightRay) -> Option<(usize, f32)> {
        let mut best: Option<(usize, f32)> = None;
        for (i, t) in tris.iter().enumerate() {
            if let Some(h) = r.intersect(t[0], t[1], t[2], best.map_or(f32::INFINITY, |b| b.1)) {
                best = Some((i, h.t));
            }
        }
        best
    }

    #[test]
    fn matches_brute_force_and_is_watertight() {
        let tris = grid(40);
        let bvh = TriangleBvh::build(tris.clone());
        let mut rng = TestRng::new(3);
        for i in 0..4000 {
            // From above the grid to below it, inside its footprint: the ray must cross it.
            let o = Vec3::new(rng.range(0.05, 0.95) as f32, rng.range(0.3, 2.0) as f32, rng.range(0.05, 0.95) as f32);
            let target = Vec3::new(rng.range(0.05, 0.95) as f32, -0.2, rng.range(0.05, 0.95) as f32);
            let r = WatertightRay::new(o, (target - o) * rng.range(0.2, 3.0) as f32).unwrap();
            let mut got: Option<(usize, f32)> = None;
            bvh.closest(&r, f32::INFINITY, |prim, h, _| {
                if got.is_none_or(|g| h.t < g.1) {
                    got = Some((prim, h.t));
                }
                Some(h.t)
            });
            let expected = brute(&tris, &r);
            // Every ray aimed into the grid from above hits it (no cracks).
            assert!(got.is_some(), "ray {i} slipped through");
            assert_eq!(got.map(|g| g.1), expected.map(|e| e.1), "ray {i}");
            let any = bvh.any(&r, f32::INFINITY, |_, _, _| true);
            assert!(any);
            let short = bvh.any(&r, got.unwrap().1 * 0.999, |_, _, _| true);
            assert!(!short || brute(&tris, &r).is_some_and(|e| e.1 < got.unwrap().1 * 0.999));
        }
    }

    #[test]
    fn scalar_and_fastest_traversals_agree() {
        let tris = grid(16);
        let bvh = TriangleBvh::build(tris.clone());
        let mut rng = TestRng::new(9);
        for _ in 0..2000 {
            let o = Vec3::new(rng.range(-0.5, 1.5) as f32, rng.range(-1.0, 2.0) as f32, rng.range(-0.5, 1.5) as f32);
            let d = Vec3::new(rng.range(-1.0, 1.0) as f32, rng.range(-1.0, 1.0) as f32, rng.range(-1.0, 1.0) as f32);
            let Some(r) = WatertightRay::new(o, d) else { continue };
            let ray = TraversalRay::new(&r);
            let mut stack = vec![std::mem::MaybeUninit::uninit(); bvh.stack_size];
            let mut scalar = None;
            traverse::<_, false>(
                simd::Scalar,
                &bvh,
                &ray,
                f32::INFINITY,
                &mut stack,
                &mut AcceptClosest(|prim: usize, h: TriangleHit, _: [Vec3; 3]| {
                    scalar = Some((prim, h.t));
                    Some(h.t)
                }),
            );
            let mut fast = None;
            bvh.closest(&r, f32::INFINITY, |prim, h, _| {
                fast = Some((prim, h.t));
                Some(h.t)
            });
            assert_eq!(scalar.map(|s| s.1), fast.map(|f| f.1));
        }
    }

    #[test]
    fn tiny_meshes_build() {
        let one = vec![[Vec3::ZERO, Vec3::X, Vec3::Y]];
        let bvh = TriangleBvh::build(one.clone());
        let r = WatertightRay::new(Vec3::new(0.2, 0.2, 1.0), Vec3::NEG_Z).unwrap();
        let mut hit = None;
        bvh.closest(&r, f32::INFINITY, |p, h, _| {
            hit = Some((p, h.t));
            Some(h.t)
        });
        assert_eq!(hit, Some((0, 1.0)));
    }
}
