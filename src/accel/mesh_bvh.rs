//! The bottom level of Prism's two-level BVH: one tree per mesh over its triangles, in f32
//! object space.
//!
//! obvhs builds a binary tree (PLOC, reinsertion, SAH leaf collapse to at most four
//! triangles); it is then collapsed into an 8-wide tree whose nodes hold their children's
//! boxes as structure-of-arrays, so one AVX2 instruction tests a ray against eight boxes,
//! and whose leaves are packets of four triangles tested together with the watertight test
//! of [`super::triangle`] in SSE lanes. Children are visited nearest first. Without AVX2
//! (or off x86-64) the same kernels run as plain loops.

use std::time::Duration;

use glam::{Vec3, Vec3A};
use obvhs::BvhBuildParams;
use obvhs::bvh2::builder::build_bvh2;

use super::triangle::{TriangleHit, WatertightRay};
use crate::accel::wide::{BoxKernel, BoxRay, EMPTY, Node, ScalarBoxes, StackEntry, WideTree, with_traversal_stack};

/// Triangles per leaf packet (and at most per leaf). Four, tested in SSE lanes: leaves of
/// real meshes hold three to four triangles, and wider packets mostly carry padding through
/// the cache.
const PACKET: usize = 4;
/// Four triangles, vertices as structure-of-arrays (`a[axis][lane]`). Unused lanes repeat
/// the last triangle, so they can only report hits that are already reported.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(16))]
struct Packet {
    a: [[f32; PACKET]; 3],
    b: [[f32; PACKET]; 3],
    c: [[f32; PACKET]; 3],
    /// Triangle index (into the mesh's triangle list) of each lane.
    prim: [u32; PACKET],
}

impl Packet {
    /// The packet of `prims` (at most `PACKET` indices into `triangles`).
    fn new(triangles: &[[Vec3; 3]], prims: &[u32]) -> Self {
        let count = prims.len().clamp(1, PACKET);
        let mut p = Packet { a: [[0.0; PACKET]; 3], b: [[0.0; PACKET]; 3], c: [[0.0; PACKET]; 3], prim: [0; PACKET] };
        for lane in 0..PACKET {
            let prim = prims[lane.min(count - 1)];
            let [a, b, c] = triangles[prim as usize];
            for axis in 0..3 {
                p.a[axis][lane] = a[axis];
                p.b[axis][lane] = b[axis];
                p.c[axis][lane] = c[axis];
            }
            p.prim[lane] = prim;
        }
        p
    }
}

/// A BVH over triangles.
#[derive(Clone)]
pub struct TriangleBvh {
    nodes: Vec<Node>,
    packets: Vec<Packet>,
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

/// A ray prepared for traversal: the slab test's reciprocal direction and near/far planes
/// per axis, and the watertight test's shear.
struct Prepared {
    wt: WatertightRay,
    boxes: BoxRay,
    /// Origin, permuted to the watertight test's (kx, ky, kz).
    org: [f32; 3],
    perm: [usize; 3],
    shear: [f32; 3],
}

impl Prepared {
    fn new(wt: &WatertightRay) -> Self {
        let o = wt.origin;
        let (perm, shear) = wt.shear();
        Self { wt: *wt, boxes: BoxRay::new(o, wt.direction), org: perm.map(|k| o[k]), perm, shear }
    }
}

impl TriangleBvh {
    /// Builds the tree over `triangles` (given by their vertices). Returns it and the
    /// identity order (triangles keep their indices; kept for the caller's bookkeeping).
    ///
    /// # Panics
    ///
    /// When `triangles` is empty (meshes without triangles are rejected at import).
    pub fn build(triangles: &[[Vec3; 3]]) -> (Self, Vec<u32>) {
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
            packets.push(Packet::new(triangles, prims));
            (packets.len() - 1) as u32
        });
        let out =
            TriangleBvh { nodes: tree.nodes, packets, triangles: triangles.to_vec(), stack_size: tree.stack_size };
        (out, (0..triangles.len() as u32).collect())
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
        let distinct: usize =
            self.packets.iter().map(|p| (0..PACKET).filter(|&l| l == 0 || p.prim[l] != p.prim[l - 1]).count()).sum();
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
        self.nodes.len() * std::mem::size_of::<Node>() + self.packets.len() * std::mem::size_of::<Packet>()
    }

    /// Visits the triangles the ray may hit, nearest boxes first. `accept(triangle, hit)` is
    /// called for each f32 hit below the current bound and returns the new bound (the
    /// accepted distance, which the traversal uses to prune) or `None` to reject the hit.
    #[inline]
    pub fn closest(&self, ray: &WatertightRay, t_max: f32, accept: impl FnMut(usize, TriangleHit) -> Option<f32>) {
        let prepared = Prepared::new(ray);
        with_traversal_stack(self.stack_size, |stack| {
            #[cfg(target_arch = "x86_64")]
            if simd::available() {
                // SAFETY: the CPU has AVX2 and FMA (checked at run time).
                unsafe { simd::closest(self, &prepared, t_max, stack, accept) };
                return;
            }
            traverse::<Scalar, false>(self, &prepared, t_max, stack, &mut AcceptClosest(accept));
        })
    }

    /// True when `accept` takes any f32 hit with `t < t_max`.
    #[inline]
    pub fn any(&self, ray: &WatertightRay, t_max: f32, accept: impl FnMut(usize, TriangleHit) -> bool) -> bool {
        let prepared = Prepared::new(ray);
        with_traversal_stack(self.stack_size, |stack| {
            #[cfg(target_arch = "x86_64")]
            if simd::available() {
                // SAFETY: the CPU has AVX2 and FMA (checked at run time).
                return unsafe { simd::any(self, &prepared, t_max, stack, accept) };
            }
            traverse::<Scalar, true>(self, &prepared, t_max, stack, &mut AcceptAny(accept, false))
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

/// The two SIMD kernels: eight boxes, four triangles.
trait Kernels {
    /// The eight-box test.
    type Boxes: BoxKernel;
    /// Bit mask of the lanes hit with 0 < t < t_max, and per lane t, b1, b2; lanes whose
    /// edge functions rounded to zero are left to the scalar test (their bits are in
    /// `edge`).
    fn triangles(p: &Packet, r: &Prepared, t_max: f32, out: &mut [[f32; PACKET]; 3], edge: &mut u32) -> u32;
}

/// Plain loops (used without AVX2).
struct Scalar;

impl Kernels for Scalar {
    type Boxes = ScalarBoxes;

    #[inline(always)]
    fn triangles(p: &Packet, r: &Prepared, t_max: f32, out: &mut [[f32; PACKET]; 3], edge: &mut u32) -> u32 {
        let mut mask = 0;
        for lane in 0..PACKET {
            let v = |m: &[[f32; PACKET]; 3]| Vec3::new(m[0][lane], m[1][lane], m[2][lane]);
            if let Some(h) = r.wt.intersect(v(&p.a), v(&p.b), v(&p.c), t_max) {
                out[0][lane] = h.t;
                out[1][lane] = h.b1;
                out[2][lane] = h.b2;
                mask |= 1 << lane;
            }
        }
        *edge = 0;
        mask
    }
}

/// The traversal, generic over the kernels and the query.
#[inline(always)]
fn traverse<K: Kernels, const ANY: bool>(
    bvh: &TriangleBvh,
    r: &Prepared,
    t_max: f32,
    stack: &mut [StackEntry],
    acceptor: &mut impl Acceptor,
) -> bool {
    let mut hits = [[0f32; PACKET]; 3];
    crate::accel::wide::traverse::<K::Boxes, true>(&bvh.nodes, &r.boxes, t_max, stack, |leaf, t_max| {
        let packet = &bvh.packets[leaf as usize];
        let mut edge = 0;
        let mut mask = K::triangles(packet, r, *t_max, &mut hits, &mut edge);
        while edge != 0 {
            let lane = edge.trailing_zeros() as usize;
            edge &= edge - 1;
            let v = |m: &[[f32; PACKET]; 3]| Vec3::new(m[0][lane], m[1][lane], m[2][lane]);
            if let Some(h) = r.wt.intersect(v(&packet.a), v(&packet.b), v(&packet.c), *t_max) {
                hits[0][lane] = h.t;
                hits[1][lane] = h.b1;
                hits[2][lane] = h.b2;
                mask |= 1 << lane;
            }
        }
        while mask != 0 {
            let lane = mask.trailing_zeros() as usize;
            mask &= mask - 1;
            let hit = TriangleHit { t: hits[0][lane], b1: hits[1][lane], b2: hits[2][lane] };
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

#[cfg(target_arch = "x86_64")]
mod simd {
    use std::arch::x86_64::*;

    pub use crate::accel::wide::avx2_available as available;

    use super::*;
    use crate::accel::wide::Avx2Boxes;

    struct Avx2;

    impl Kernels for Avx2 {
        type Boxes = Avx2Boxes;

        #[inline(always)]
        fn triangles(p: &Packet, r: &Prepared, t_max: f32, out: &mut [[f32; PACKET]; 3], edge: &mut u32) -> u32 {
            // SAFETY: as for `boxes`; packet arrays are 16-byte aligned.
            unsafe {
                let [kx, ky, kz] = r.perm;
                let (ox, oy, oz) = (_mm_set1_ps(r.org[0]), _mm_set1_ps(r.org[1]), _mm_set1_ps(r.org[2]));
                let (sx, sy, sz) = (_mm_set1_ps(r.shear[0]), _mm_set1_ps(r.shear[1]), _mm_set1_ps(r.shear[2]));
                // The same operations, in the same order, as the scalar test (no fused
                // multiply-adds): shared edges then give exactly opposite edge functions.
                macro_rules! sheared {
                    ($v:expr) => {{
                        let x = _mm_sub_ps(_mm_load_ps($v[kx].as_ptr()), ox);
                        let y = _mm_sub_ps(_mm_load_ps($v[ky].as_ptr()), oy);
                        let z = _mm_sub_ps(_mm_load_ps($v[kz].as_ptr()), oz);
                        (_mm_sub_ps(x, _mm_mul_ps(sx, z)), _mm_sub_ps(y, _mm_mul_ps(sy, z)), z)
                    }};
                }
                let (ax, ay, az) = sheared!(p.a);
                let (bx, by, bz) = sheared!(p.b);
                let (cx, cy, cz) = sheared!(p.c);
                let u = _mm_sub_ps(_mm_mul_ps(cx, by), _mm_mul_ps(cy, bx));
                let v = _mm_sub_ps(_mm_mul_ps(ax, cy), _mm_mul_ps(ay, cx));
                let w = _mm_sub_ps(_mm_mul_ps(bx, ay), _mm_mul_ps(by, ax));
                let zero = _mm_setzero_ps();
                macro_rules! any3 {
                    ($op:ident) => {
                        _mm_or_ps(
                            _mm_or_ps(_mm_cmp_ps::<$op>(u, zero), _mm_cmp_ps::<$op>(v, zero)),
                            _mm_cmp_ps::<$op>(w, zero),
                        )
                    };
                }
                let negative = any3!(_CMP_LT_OQ);
                let positive = any3!(_CMP_GT_OQ);
                let on_edge = any3!(_CMP_EQ_OQ);
                let outside = _mm_and_ps(negative, positive);
                // Lanes with a zero edge function go to the scalar test (which redoes them
                // in f64) unless they are already certainly outside.
                *edge = _mm_movemask_ps(_mm_andnot_ps(outside, on_edge)) as u32;
                let det = _mm_add_ps(_mm_add_ps(u, v), w);
                let t_scaled = _mm_add_ps(
                    _mm_add_ps(_mm_mul_ps(u, _mm_mul_ps(sz, az)), _mm_mul_ps(v, _mm_mul_ps(sz, bz))),
                    _mm_mul_ps(w, _mm_mul_ps(sz, cz)),
                );
                let inv = _mm_div_ps(_mm_set1_ps(1.0), det);
                let t = _mm_mul_ps(t_scaled, inv);
                let in_range =
                    _mm_and_ps(_mm_cmp_ps::<_CMP_GT_OQ>(t, zero), _mm_cmp_ps::<_CMP_LT_OQ>(t, _mm_set1_ps(t_max)));
                let valid = _mm_andnot_ps(
                    _mm_or_ps(outside, on_edge),
                    _mm_and_ps(_mm_cmp_ps::<_CMP_NEQ_OQ>(det, zero), in_range),
                );
                let mask = _mm_movemask_ps(valid) as u32;
                if mask != 0 {
                    _mm_storeu_ps(out[0].as_mut_ptr(), t);
                    _mm_storeu_ps(out[1].as_mut_ptr(), _mm_mul_ps(v, inv));
                    _mm_storeu_ps(out[2].as_mut_ptr(), _mm_mul_ps(w, inv));
                }
                mask
            }
        }
    }

    /// Closest-hit traversal with the AVX2 kernels.
    ///
    /// # Safety
    ///
    /// The CPU must support AVX2 and FMA ([`available`]).
    #[target_feature(enable = "avx2,fma,popcnt,bmi1")]
    pub unsafe fn closest(
        bvh: &TriangleBvh,
        r: &Prepared,
        t_max: f32,
        stack: &mut [StackEntry],
        accept: impl FnMut(usize, TriangleHit) -> Option<f32>,
    ) {
        traverse::<Avx2, false>(bvh, r, t_max, stack, &mut AcceptClosest(accept));
    }

    /// Any-hit traversal with the AVX2 kernels.
    ///
    /// # Safety
    ///
    /// The CPU must support AVX2 and FMA ([`available`]).
    #[target_feature(enable = "avx2,fma,popcnt,bmi1")]
    pub unsafe fn any(
        bvh: &TriangleBvh,
        r: &Prepared,
        t_max: f32,
        stack: &mut [StackEntry],
        accept: impl FnMut(usize, TriangleHit) -> bool,
    ) -> bool {
        traverse::<Avx2, true>(bvh, r, t_max, stack, &mut AcceptAny(accept, false))
    }
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
        let (bvh, _) = TriangleBvh::build(&tris);
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
    fn scalar_and_simd_kernels_agree() {
        let tris = grid(16);
        let (bvh, _) = TriangleBvh::build(&tris);
        let mut rng = TestRng::new(9);
        for _ in 0..2000 {
            let o = Vec3::new(rng.range(-0.5, 1.5) as f32, rng.range(-1.0, 2.0) as f32, rng.range(-0.5, 1.5) as f32);
            let d = Vec3::new(rng.range(-1.0, 1.0) as f32, rng.range(-1.0, 1.0) as f32, rng.range(-1.0, 1.0) as f32);
            let Some(r) = WatertightRay::new(o, d) else { continue };
            let p = Prepared::new(&r);
            let mut stack = vec![std::mem::MaybeUninit::uninit(); bvh.stack_size];
            let mut scalar = None;
            traverse::<Scalar, false>(
                &bvh,
                &p,
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
        let (bvh, _) = TriangleBvh::build(&one);
        let r = WatertightRay::new(Vec3::new(0.2, 0.2, 1.0), Vec3::NEG_Z).unwrap();
        let mut hit = None;
        bvh.closest(&r, f32::INFINITY, |p, h| {
            hit = Some((p, h.t));
            Some(h.t)
        });
        assert_eq!(hit, Some((0, 1.0)));
    }
}
