//! The bottom level of Prism's two-level BVH: one tree per mesh over its triangles, in f32
//! object space.
//!
//! obvhs builds a binary tree (PLOC, reinsertion, one triangle per leaf); it is then
//! collapsed into the 8-wide tree shared with the top level (`accel::wide`), whose leaves
//! are packets of up to four triangles ([`TrianglePacket`]). A ray is tested against a
//! node's eight boxes and a leaf's four triangles at once by the SIMD kernels
//! (`accel::simd`: AVX2 where the CPU has it, plain loops otherwise, with the same hits);
//! children are visited nearest first.

use std::time::Duration;

use glam::{Vec3, Vec3A};
use obvhs::BvhBuildParams;
use obvhs::bvh2::builder::build_bvh2;

use super::simd::{self, BoxRay, Dispatch, Kernels};
use super::triangle::{PACKET, PacketHits, TriangleHit, TrianglePacket, WatertightRay};
use super::wide::{EMPTY, Node, StackEntry, WideTree, with_traversal_stack};

/// A BVH over triangles.
#[derive(Clone)]
pub struct TriangleBvh {
    nodes: Vec<Node>,
    packets: Vec<TrianglePacket>,
    /// Vertices of each triangle, in input order (for refining hits in f64).
    triangles: Vec<[Vec3; 3]>,
    /// Deepest stack a traversal can need.
    stack_size: usize,
}

impl std::fmt::Debug for TriangleBvh {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "TriangleBvh({} triangles, {} nodes, {} packets)",
            self.triangles.len(),
            self.nodes.len(),
            self.packets.len()
        )
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
    /// Builds the tree over `triangles` (given by their vertices). Triangles keep their
    /// indices: the hits name them by their place in `triangles`.
    ///
    /// # Panics
    ///
    /// When `triangles` is empty (meshes without triangles are rejected at import).
    pub fn build(triangles: &[[Vec3; 3]]) -> Self {
        assert!(!triangles.is_empty(), "a mesh BVH needs at least one triangle");
        let boxes: Vec<obvhs::aabb::Aabb> = triangles
            .iter()
            .map(|t| {
                let min = t[0].min(t[1]).min(t[2]);
                let max = t[0].max(t[1]).max(t[2]);
                obvhs::aabb::Aabb { min: Vec3A::from(min), max: Vec3A::from(max) }
            })
            .collect();
        let mut build_time = Duration::default();
        // One triangle per BVH2 leaf: the collapse below forms the leaves.
        let params = BvhBuildParams { max_prims_per_leaf: 1, ..BvhBuildParams::medium_build() };
        let bvh2 = build_bvh2(&boxes, params, &mut build_time);
        let mut packets = Vec::new();
        let tree = WideTree::collapse(&bvh2, PACKET, |prims| {
            packets.push(TrianglePacket::new(triangles, prims));
            (packets.len() - 1) as u32
        });
        TriangleBvh { nodes: tree.nodes, packets, triangles: triangles.to_vec(), stack_size: tree.stack_size }
    }

    /// Number of triangles.
    pub fn len(&self) -> usize {
        self.triangles.len()
    }

    /// True when the tree holds no triangle (never, once built).
    pub fn is_empty(&self) -> bool {
        self.triangles.is_empty()
    }

    /// Vertices of triangle `index`.
    #[inline]
    pub fn triangle(&self, index: usize) -> &[Vec3; 3] {
        &self.triangles[index]
    }

    /// Shape statistics: (nodes, leaf packets, mean children per node, mean distinct
    /// triangles per packet).
    pub fn stats(&self) -> (usize, usize, f64, f64) {
        let children: usize = self.nodes.iter().map(|n| n.child.iter().filter(|&&c| c != EMPTY).count()).sum();
        let distinct: usize = self.packets.iter().map(TrianglePacket::distinct).sum();
        (
            self.nodes.len(),
            self.packets.len(),
            children as f64 / self.nodes.len() as f64,
            distinct as f64 / self.packets.len() as f64,
        )
    }

    /// Bytes used by the nodes and the leaf packets (not the triangle list kept for
    /// shading).
    pub fn memory_bytes(&self) -> usize {
        self.nodes.len() * std::mem::size_of::<Node>() + self.packets.len() * std::mem::size_of::<TrianglePacket>()
    }

    /// Visits the triangles the ray may hit, nearest boxes first. `accept(triangle, hit)` is
    /// called for each f32 hit below the current bound and returns the new bound (the
    /// accepted distance, which the traversal uses to prune) or `None` to reject the hit.
    #[inline]
    pub fn closest(&self, ray: &WatertightRay, t_max: f32, accept: impl FnMut(usize, TriangleHit) -> Option<f32>) {
        let ray = TraversalRay::new(ray);
        with_traversal_stack(self.stack_size, |stack| {
            simd::dispatch(Query::<_, false> { bvh: self, ray: &ray, t_max, stack, acceptor: AcceptClosest(accept) })
        });
    }

    /// True when `accept` takes any f32 hit with `t < t_max`.
    #[inline]
    pub fn any(&self, ray: &WatertightRay, t_max: f32, accept: impl FnMut(usize, TriangleHit) -> bool) -> bool {
        let ray = TraversalRay::new(ray);
        with_traversal_stack(self.stack_size, |stack| {
            simd::dispatch(Query::<_, true> { bvh: self, ray: &ray, t_max, stack, acceptor: AcceptAny(accept, false) })
        })
    }
}

/// What the traversal does with a candidate hit.
trait Acceptor {
    /// Offers a hit; returns the new bound on t if it was taken.
    fn offer(&mut self, prim: usize, hit: TriangleHit) -> Option<f32>;
    /// True when traversal can stop (any-hit queries).
    fn done(&self) -> bool;
}

struct AcceptClosest<F>(F);

impl<F: FnMut(usize, TriangleHit) -> Option<f32>> Acceptor for AcceptClosest<F> {
    #[inline(always)]
    fn offer(&mut self, prim: usize, hit: TriangleHit) -> Option<f32> {
        (self.0)(prim, hit)
    }

    #[inline(always)]
    fn done(&self) -> bool {
        false
    }
}

struct AcceptAny<F>(F, bool);

impl<F: FnMut(usize, TriangleHit) -> bool> Acceptor for AcceptAny<F> {
    #[inline(always)]
    fn offer(&mut self, prim: usize, hit: TriangleHit) -> Option<f32> {
        if (self.0)(prim, hit) {
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
    ray: &'a TraversalRay,
    t_max: f32,
    stack: &'a mut [StackEntry],
    acceptor: A,
}

impl<A: Acceptor, const ANY: bool> Dispatch for Query<'_, A, ANY> {
    type Output = bool;

    #[inline(always)]
    fn run<K: Kernels>(mut self, kernels: K) -> bool {
        traverse::<K, ANY>(kernels, self.bvh, self.ray, self.t_max, self.stack, &mut self.acceptor)
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
    let mut hits = PacketHits::default();
    super::wide::traverse::<K, true>(kernels, &bvh.nodes, &ray.boxes, t_max, stack, |leaf, t_max| {
        let packet = &bvh.packets[leaf as usize];
        let mut mask = kernels.triangles(packet, &ray.triangle, *t_max, &mut hits);
        while mask != 0 {
            let lane = mask.trailing_zeros() as usize;
            mask &= mask - 1;
            let hit = hits.get(lane);
            if hit.t < *t_max
                && let Some(bound) = acceptor.offer(packet.prim[lane] as usize, hit)
            {
                if ANY && acceptor.done() {
                    return true;
                }
                *t_max = t_max.min(bound);
            }
        }
        false
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use prism_api::contract::TestRng;

    /// A bumpy grid of triangles.
    fn grid(n: usize) -> Vec<[Vec3; 3]> {
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
        let bvh = TriangleBvh::build(&tris);
        let mut rng = TestRng::new(3);
        for i in 0..4000 {
            // From above the grid to below it, inside its footprint: the ray must cross it.
            let o = Vec3::new(rng.range(0.05, 0.95) as f32, rng.range(0.3, 2.0) as f32, rng.range(0.05, 0.95) as f32);
            let target = Vec3::new(rng.range(0.05, 0.95) as f32, -0.2, rng.range(0.05, 0.95) as f32);
            let r = WatertightRay::new(o, (target - o) * rng.range(0.2, 3.0) as f32).unwrap();
            let mut got: Option<(usize, f32)> = None;
            bvh.closest(&r, f32::INFINITY, |prim, h| {
                if got.is_none_or(|g| h.t < g.1) {
                    got = Some((prim, h.t));
                }
                Some(h.t)
            });
            let expected = brute(&tris, &r);
            // Every ray aimed into the grid from above hits it (no cracks).
            assert!(got.is_some(), "ray {i} slipped through");
            assert_eq!(got.map(|g| g.1), expected.map(|e| e.1), "ray {i}");
            let any = bvh.any(&r, f32::INFINITY, |_, _| true);
            assert!(any);
            let short = bvh.any(&r, got.unwrap().1 * 0.999, |_, _| true);
            assert!(!short || brute(&tris, &r).is_some_and(|e| e.1 < got.unwrap().1 * 0.999));
        }
    }

    #[test]
    fn scalar_and_fastest_traversals_agree() {
        let tris = grid(16);
        let bvh = TriangleBvh::build(&tris);
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
                &mut AcceptClosest(|prim: usize, h: TriangleHit| {
                    scalar = Some((prim, h.t));
                    Some(h.t)
                }),
            );
            let mut fast = None;
            bvh.closest(&r, f32::INFINITY, |prim, h| {
                fast = Some((prim, h.t));
                Some(h.t)
            });
            assert_eq!(scalar.map(|s| s.1), fast.map(|f| f.1));
        }
    }

    #[test]
    fn tiny_meshes_build() {
        let one = vec![[Vec3::ZERO, Vec3::X, Vec3::Y]];
        let bvh = TriangleBvh::build(&one);
        let r = WatertightRay::new(Vec3::new(0.2, 0.2, 1.0), Vec3::NEG_Z).unwrap();
        let mut hit = None;
        bvh.closest(&r, f32::INFINITY, |p, h| {
            hit = Some((p, h.t));
            Some(h.t)
        });
        assert_eq!(hit, Some((0, 1.0)));
    }
}
