//! The bottom level of Prism's two-level BVH: one tree per mesh over its triangles, in f32
//! object space.
//!
//! obvhs builds a binary tree (PLOC, reinsertion, SAH leaf collapse to at most four
//! triangles); it is then collapsed into an 8-wide tree whose nodes hold their children's
//! boxes as structure-of-arrays, so one AVX2 instruction tests a ray against eight boxes,
//! and whose leaves are packets of four triangles tested together with the watertight test
//! of [`super::triangle`] in SSE lanes. Children are visited nearest first. Without AVX2
//! (or off x86-64) the same kernels run as plain loops.

use std::mem::MaybeUninit;
use std::time::Duration;

use glam::{Vec3, Vec3A};
use obvhs::BvhBuildParams;
use obvhs::bvh2::builder::build_bvh2;

use super::triangle::{TriangleHit, WatertightRay};
use crate::accel::wide::{
    BoxKernel, BoxRay, EMPTY, FAR_SCALE, LEAF, Node, ScalarBoxes, StackEntry, WIDTH, WideTree, order_children,
    pop_within, with_traversal_stack,
};

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

impl TriangleBvh {
    /// Closest hits of eight rays traced together (a 4x2 tile of camera rays, say): each
    /// node and leaf is fetched once for all eight, and its boxes and triangles are tested
    /// with the rays in SIMD lanes. `accept(ray, triangle, hit)` works as in
    /// [`TriangleBvh::closest`] for ray `ray`. The results are exactly those of eight
    /// [`TriangleBvh::closest`] calls: rays whose directions do not share a dominant axis
    /// and sign (the watertight test's frame) are traced one by one.
    pub fn closest8(
        &self,
        rays: &[WatertightRay; 8],
        t_max: [f32; 8],
        mut accept: impl FnMut(usize, usize, TriangleHit) -> Option<f32>,
    ) {
        #[cfg(target_arch = "x86_64")]
        if simd::available() && shared_frame(rays) && self.stack_size <= 160 {
            // SAFETY: the CPU has AVX2 and FMA (checked at run time).
            unsafe { simd::closest8(self, rays, t_max, &mut accept) };
            return;
        }
        for (lane, ray) in rays.iter().enumerate() {
            self.closest(ray, t_max[lane], |prim, hit| accept(lane, prim, hit));
        }
    }
}

impl TriangleBvh {
    /// Closest hits of sixteen rays traced together (a 4x4 tile of camera rays): as
    /// [`TriangleBvh::closest8`], with the same exact results. Rays from one origin in one
    /// watertight frame, on a CPU with AVX-512, go down the tree as one packet: each node is
    /// tested once for all sixteen (interval arithmetic over their directions) and each
    /// triangle against all sixteen in one 512-bit register. Other tiles are traced as two
    /// packets of eight.
    pub fn closest16(
        &self,
        rays: &[WatertightRay; 16],
        t_max: [f32; 16],
        mut accept: impl FnMut(usize, usize, TriangleHit) -> Option<f32>,
    ) {
        #[cfg(target_arch = "x86_64")]
        if packet16::available() && shared_frame(rays) && self.stack_size <= 160 {
            // SAFETY: the CPU has AVX-512F, AVX2 and FMA (checked at run time); the rays
            // share their frame.
            if unsafe { packet16::closest16(self, rays, t_max, &mut accept) } {
                return;
            }
        }
        let (low, high) = rays.split_at(8);
        let (low, high): (&[WatertightRay; 8], &[WatertightRay; 8]) =
            (low.try_into().expect("8 rays"), high.try_into().expect("8 rays"));
        let t_low: [f32; 8] = std::array::from_fn(|i| t_max[i]);
        let t_high: [f32; 8] = std::array::from_fn(|i| t_max[i + 8]);
        self.closest8(low, t_low, &mut accept);
        self.closest8(high, t_high, |lane, prim, hit| accept(lane + 8, prim, hit));
    }
}

/// True when the rays share the watertight test's frame: the same dominant axis and sign of
/// the direction (the axis permutation of [`WatertightRay::shear`]).
fn shared_frame(rays: &[WatertightRay]) -> bool {
    let first = rays[0].shear().0;
    let negative = rays[0].direction[first[2]] < 0.0;
    rays.iter().all(|r| {
        let (perm, _) = r.shear();
        perm == first && (r.direction[perm[2]] < 0.0) == negative
    })
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

/// One triangle's candidate hits for the rays of a packet, by lane, and the rays' bounds.
struct PacketHits<'a> {
    t: &'a mut [f32],
    b1: &'a mut [f32],
    b2: &'a mut [f32],
    bounds: &'a mut [f32],
}

impl PacketHits<'_> {
    /// Offers the hits in `mask` to `accept`: lanes in `edge` (an edge function rounded to
    /// zero) are first redone with the scalar test, and a hit nearer than its ray's bound
    /// that `accept` takes tightens that bound.
    #[inline(always)]
    fn offer(
        self,
        rays: &[WatertightRay],
        [a, b, c]: [Vec3; 3],
        prim: usize,
        mut mask: u32,
        mut edge: u32,
        accept: &mut impl FnMut(usize, usize, TriangleHit) -> Option<f32>,
    ) {
        while edge != 0 {
            let ray = edge.trailing_zeros() as usize;
            edge &= edge - 1;
            if let Some(h) = rays[ray].intersect(a, b, c, self.bounds[ray]) {
                self.t[ray] = h.t;
                self.b1[ray] = h.b1;
                self.b2[ray] = h.b2;
                mask |= 1 << ray;
            }
        }
        while mask != 0 {
            let ray = mask.trailing_zeros() as usize;
            mask &= mask - 1;
            let hit = TriangleHit { t: self.t[ray], b1: self.b1[ray], b2: self.b2[ray] };
            if hit.t < self.bounds[ray]
                && let Some(bound) = accept(ray, prim, hit)
            {
                self.bounds[ray] = self.bounds[ray].min(bound);
            }
        }
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

    pub use super::packet::closest8;

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

#[cfg(target_arch = "x86_64")]
mod packet {
    use std::arch::x86_64::*;

    use super::*;

    /// Eight rays in SIMD lanes.
    struct Rays8 {
        rdir: [__m256; 3],
        org_rdir: [__m256; 3],
        /// Origins permuted to the shared watertight frame.
        org: [__m256; 3],
        shear: [__m256; 3],
        perm: [usize; 3],
    }

    /// The largest of eight lanes.
    #[inline(always)]
    unsafe fn horizontal_max(v: __m256) -> f32 {
        // SAFETY: register operations only; the caller has AVX.
        unsafe {
            let m = _mm256_max_ps(v, _mm256_permute2f128_ps::<1>(v, v));
            let m = _mm_max_ps(
                _mm256_castps256_ps128(m),
                _mm_movehl_ps(_mm256_castps256_ps128(m), _mm256_castps256_ps128(m)),
            );
            _mm_cvtss_f32(_mm_max_ss(m, _mm_shuffle_ps::<1>(m, m)))
        }
    }

    /// The smallest of eight lanes.
    #[inline(always)]
    unsafe fn horizontal_min(v: __m256) -> f32 {
        // SAFETY: register operations only; the caller has AVX.
        unsafe {
            let m = _mm256_min_ps(v, _mm256_permute2f128_ps::<1>(v, v));
            let m = _mm_min_ps(
                _mm256_castps256_ps128(m),
                _mm_movehl_ps(_mm256_castps256_ps128(m), _mm256_castps256_ps128(m)),
            );
            _mm_cvtss_f32(_mm_min_ss(m, _mm_shuffle_ps::<1>(m, m)))
        }
    }

    /// Each child box against each ray; a child is entered when any ray enters it, at the
    /// nearest entry distance among those rays.
    #[inline(always)]
    unsafe fn boxes_per_ray(node: &Node, r: &Rays8, t_max: __m256, near: &mut [f32; WIDTH]) -> u32 {
        // SAFETY: register operations and reads of the node's arrays; the caller has AVX2+FMA.
        unsafe {
            let mut mask = 0;
            for slot in 0..WIDTH {
                // Children fill the slots from the first one.
                if node.child[slot] == EMPTY {
                    break;
                }
                let b = &node.bounds;
                let mut t0 = _mm256_setzero_ps();
                let mut t1 = t_max;
                for axis in 0..3 {
                    let lo = _mm256_set1_ps(b[axis][slot]);
                    let hi = _mm256_set1_ps(b[axis + 3][slot]);
                    let ta = _mm256_fmsub_ps(lo, r.rdir[axis], r.org_rdir[axis]);
                    let tb = _mm256_fmsub_ps(hi, r.rdir[axis], r.org_rdir[axis]);
                    t0 = _mm256_max_ps(t0, _mm256_min_ps(ta, tb));
                    t1 = _mm256_min_ps(t1, _mm256_mul_ps(_mm256_max_ps(ta, tb), _mm256_set1_ps(FAR_SCALE)));
                }
                let hit = _mm256_cmp_ps::<_CMP_LE_OQ>(t0, t1);
                if _mm256_movemask_ps(hit) != 0 {
                    near[slot] = horizontal_min(_mm256_blendv_ps(_mm256_set1_ps(f32::INFINITY), t0, hit));
                    mask |= 1 << slot;
                }
            }
            mask
        }
    }

    /// The rays of a packet with one origin and the same direction signs, bounded by
    /// intervals of their reciprocal directions: one test of eight boxes then serves all
    /// eight rays (interval arithmetic on the slab test).
    pub(super) struct Frustum {
        /// The shared origin, broadcast.
        org: [__m256; 3],
        /// Smallest and largest reciprocal direction per axis, broadcast.
        rdir_lo: [__m256; 3],
        rdir_hi: [__m256; 3],
        near: [usize; 3],
        far: [usize; 3],
    }

    impl Frustum {
        /// `None` when the rays do not share their origin and direction signs.
        #[inline(always)]
        pub(super) unsafe fn new(prepared: &[Prepared], rays: &[WatertightRay]) -> Option<Self> {
            let origin = rays[0].origin;
            let shared = prepared
                .iter()
                .zip(rays)
                .all(|(p, ray)| ray.origin == origin && p.boxes.near == prepared[0].boxes.near);
            if !shared {
                return None;
            }
            let lo = [0, 1, 2].map(|k| prepared.iter().map(|p| p.boxes.rdir[k]).fold(f32::INFINITY, f32::min));
            let hi = [0, 1, 2].map(|k| prepared.iter().map(|p| p.boxes.rdir[k]).fold(f32::NEG_INFINITY, f32::max));
            // SAFETY: broadcasts only; the caller has AVX.
            unsafe {
                Some(Self {
                    org: [0, 1, 2].map(|k| _mm256_set1_ps(origin[k])),
                    rdir_lo: lo.map(|v| _mm256_set1_ps(v)),
                    rdir_hi: hi.map(|v| _mm256_set1_ps(v)),
                    near: prepared[0].boxes.near,
                    far: prepared[0].boxes.far,
                })
            }
        }

        /// Children some ray of the packet may enter before `t_max`, and a lower bound of
        /// their entry distances. Each ray's slab distances are `(plane - origin) * rdir`,
        /// rounded; rounding is monotonic, so the products with the interval's ends bound
        /// every ray's, and the test keeps every box a ray's own conservative test would.
        #[inline(always)]
        pub(super) unsafe fn boxes(&self, node: &Node, t_max: f32, near: &mut [f32; WIDTH]) -> u32 {
            // SAFETY: aligned loads of the node's 32-byte aligned arrays; the caller has AVX.
            unsafe {
                let b = &node.bounds;
                let mut t0 = _mm256_setzero_ps();
                let mut t1 = _mm256_set1_ps(t_max);
                for axis in 0..3 {
                    let dn = _mm256_sub_ps(_mm256_load_ps(b[self.near[axis]].as_ptr()), self.org[axis]);
                    let df = _mm256_sub_ps(_mm256_load_ps(b[self.far[axis]].as_ptr()), self.org[axis]);
                    let entry =
                        _mm256_min_ps(_mm256_mul_ps(dn, self.rdir_lo[axis]), _mm256_mul_ps(dn, self.rdir_hi[axis]));
                    let exit =
                        _mm256_max_ps(_mm256_mul_ps(df, self.rdir_lo[axis]), _mm256_mul_ps(df, self.rdir_hi[axis]));
                    t0 = _mm256_max_ps(t0, entry);
                    t1 = _mm256_min_ps(t1, _mm256_mul_ps(exit, _mm256_set1_ps(FAR_SCALE)));
                }
                _mm256_storeu_ps(near.as_mut_ptr(), t0);
                _mm256_movemask_ps(_mm256_cmp_ps::<_CMP_LE_OQ>(t0, t1)) as u32
            }
        }
    }

    /// See [`TriangleBvh::closest8`].
    ///
    /// # Safety
    ///
    /// The CPU must support AVX2 and FMA, all eight rays must share the watertight frame
    /// (`shear().0` and the sign of the dominant direction component), and the tree's stack
    /// size must be at most 160.
    #[target_feature(enable = "avx2,fma,popcnt,bmi1")]
    pub unsafe fn closest8(
        bvh: &TriangleBvh,
        rays: &[WatertightRay; 8],
        t_max: [f32; 8],
        accept: &mut impl FnMut(usize, usize, TriangleHit) -> Option<f32>,
    ) {
        // SAFETY: the caller guarantees AVX2 and FMA; every load and store is of a local or
        // node array of the accessed length.
        unsafe {
            let prepared: [Prepared; 8] = std::array::from_fn(|i| Prepared::new(&rays[i]));
            // A macro, not a closure: intrinsics inside a closure would not be inlined.
            macro_rules! lanes {
                ($($field:ident).+, $k:expr) => {{
                    let v: [f32; 8] = std::array::from_fn(|i| prepared[i].$($field).+[$k]);
                    _mm256_loadu_ps(v.as_ptr())
                }};
            }
            // The slab test orders each lane's planes with min/max, so the rays may differ in
            // the signs of their other two direction components.
            let r = Rays8 {
                rdir: [lanes!(boxes.rdir, 0), lanes!(boxes.rdir, 1), lanes!(boxes.rdir, 2)],
                org_rdir: [lanes!(boxes.org_rdir, 0), lanes!(boxes.org_rdir, 1), lanes!(boxes.org_rdir, 2)],
                org: [lanes!(org, 0), lanes!(org, 1), lanes!(org, 2)],
                shear: [lanes!(shear, 0), lanes!(shear, 1), lanes!(shear, 2)],
                perm: prepared[0].perm,
            };
            let frustum = Frustum::new(&prepared, rays);
            let mut t_max_v = _mm256_loadu_ps(t_max.as_ptr());
            let mut stack = [const { MaybeUninit::<(u32, f32)>::uninit() }; 160];
            let mut sp = 0usize;
            let mut current = 0u32;
            let zero = _mm256_setzero_ps();
            loop {
                if current & LEAF == 0 {
                    let node = &bvh.nodes[current as usize];
                    let farthest = horizontal_max(t_max_v);
                    let mut near = [0f32; WIDTH];
                    let mask = match &frustum {
                        Some(f) => f.boxes(node, farthest, &mut near),
                        None => boxes_per_ray(node, &r, t_max_v, &mut near),
                    };
                    if let Some(next) = order_children(node, mask, &near, &mut stack, &mut sp) {
                        current = next;
                        continue;
                    }
                } else {
                    let packet = &bvh.packets[(current & !LEAF) as usize];
                    let [kx, ky, kz] = r.perm;
                    for lane in 0..PACKET {
                        if lane > 0 && packet.prim[lane] == packet.prim[lane - 1] {
                            break;
                        }
                        // One triangle against eight rays: the scalar test's operations per lane.
                        macro_rules! sheared {
                            ($v:expr) => {{
                                let x = _mm256_sub_ps(_mm256_set1_ps($v[kx][lane]), r.org[0]);
                                let y = _mm256_sub_ps(_mm256_set1_ps($v[ky][lane]), r.org[1]);
                                let z = _mm256_sub_ps(_mm256_set1_ps($v[kz][lane]), r.org[2]);
                                (
                                    _mm256_sub_ps(x, _mm256_mul_ps(r.shear[0], z)),
                                    _mm256_sub_ps(y, _mm256_mul_ps(r.shear[1], z)),
                                    z,
                                )
                            }};
                        }
                        let (ax, ay, az) = sheared!(packet.a);
                        let (bx, by, bz) = sheared!(packet.b);
                        let (cx, cy, cz) = sheared!(packet.c);
                        let u = _mm256_sub_ps(_mm256_mul_ps(cx, by), _mm256_mul_ps(cy, bx));
                        let v = _mm256_sub_ps(_mm256_mul_ps(ax, cy), _mm256_mul_ps(ay, cx));
                        let w = _mm256_sub_ps(_mm256_mul_ps(bx, ay), _mm256_mul_ps(by, ax));
                        macro_rules! any3 {
                            ($op:ident) => {
                                _mm256_or_ps(
                                    _mm256_or_ps(_mm256_cmp_ps::<$op>(u, zero), _mm256_cmp_ps::<$op>(v, zero)),
                                    _mm256_cmp_ps::<$op>(w, zero),
                                )
                            };
                        }
                        let outside = _mm256_and_ps(any3!(_CMP_LT_OQ), any3!(_CMP_GT_OQ));
                        // Most triangles of a leaf miss every ray: skip the division then.
                        if _mm256_movemask_ps(outside) == 0xff {
                            continue;
                        }
                        let on_edge = any3!(_CMP_EQ_OQ);
                        let det = _mm256_add_ps(_mm256_add_ps(u, v), w);
                        let sz = r.shear[2];
                        let t_scaled = _mm256_add_ps(
                            _mm256_add_ps(
                                _mm256_mul_ps(u, _mm256_mul_ps(sz, az)),
                                _mm256_mul_ps(v, _mm256_mul_ps(sz, bz)),
                            ),
                            _mm256_mul_ps(w, _mm256_mul_ps(sz, cz)),
                        );
                        let inv = _mm256_div_ps(_mm256_set1_ps(1.0), det);
                        let t = _mm256_mul_ps(t_scaled, inv);
                        let valid = _mm256_andnot_ps(
                            _mm256_or_ps(outside, on_edge),
                            _mm256_and_ps(
                                _mm256_cmp_ps::<_CMP_NEQ_OQ>(det, zero),
                                _mm256_and_ps(
                                    _mm256_cmp_ps::<_CMP_GT_OQ>(t, zero),
                                    _mm256_cmp_ps::<_CMP_LT_OQ>(t, t_max_v),
                                ),
                            ),
                        );
                        let mask = _mm256_movemask_ps(valid) as u32;
                        let edge = _mm256_movemask_ps(_mm256_andnot_ps(outside, on_edge)) as u32;
                        if mask == 0 && edge == 0 {
                            continue;
                        }
                        let mut ts = [0f32; 8];
                        let mut b1 = [0f32; 8];
                        let mut b2 = [0f32; 8];
                        _mm256_storeu_ps(ts.as_mut_ptr(), t);
                        _mm256_storeu_ps(b1.as_mut_ptr(), _mm256_mul_ps(v, inv));
                        _mm256_storeu_ps(b2.as_mut_ptr(), _mm256_mul_ps(w, inv));
                        let mut bounds = [0f32; 8];
                        _mm256_storeu_ps(bounds.as_mut_ptr(), t_max_v);
                        let vertex = |m: &[[f32; PACKET]; 3]| Vec3::new(m[0][lane], m[1][lane], m[2][lane]);
                        let triangle = [vertex(&packet.a), vertex(&packet.b), vertex(&packet.c)];
                        let hits = PacketHits { t: &mut ts, b1: &mut b1, b2: &mut b2, bounds: &mut bounds };
                        hits.offer(rays, triangle, packet.prim[lane] as usize, mask, edge, accept);
                        t_max_v = _mm256_loadu_ps(bounds.as_ptr());
                    }
                }
                // Pop the next node some ray may still reach before its best hit.
                match pop_within(&stack, &mut sp, horizontal_max(t_max_v)) {
                    Some(node) => current = node,
                    None => return,
                }
            }
        }
    }
}

#[cfg(target_arch = "x86_64")]
mod packet16 {
    use std::arch::x86_64::*;
    use std::sync::OnceLock;

    use super::packet::Frustum;
    use super::*;

    /// True when the CPU runs the AVX-512 packet kernel.
    pub fn available() -> bool {
        static AVAILABLE: OnceLock<bool> = OnceLock::new();
        *AVAILABLE.get_or_init(|| super::simd::available() && is_x86_feature_detected!("avx512f"))
    }

    /// See [`TriangleBvh::closest16`]. Returns false, having traced nothing, when the rays
    /// do not share their origin and direction signs.
    ///
    /// # Safety
    ///
    /// The CPU must support AVX-512F, AVX2 and FMA ([`available`]); the rays must share the
    /// watertight frame, and the tree's stack size must be at most 160.
    #[target_feature(enable = "avx512f,avx2,fma,popcnt,bmi1")]
    pub unsafe fn closest16(
        bvh: &TriangleBvh,
        rays: &[WatertightRay; 16],
        t_max: [f32; 16],
        accept: &mut impl FnMut(usize, usize, TriangleHit) -> Option<f32>,
    ) -> bool {
        let prepared: [Prepared; 16] = std::array::from_fn(|i| Prepared::new(&rays[i]));
        // SAFETY: the caller guarantees the CPU features; loads and stores are of local or
        // node arrays of the accessed length.
        unsafe {
            let Some(frustum) = Frustum::new(&prepared, rays) else { return false };
            let origin = rays[0].origin;
            let [kx, ky, kz] = prepared[0].perm;
            let shear: [__m512; 3] = [0, 1, 2].map(|k| {
                let v: [f32; 16] = std::array::from_fn(|i| prepared[i].shear[k]);
                _mm512_loadu_ps(v.as_ptr())
            });
            let mut bounds = t_max;
            let mut t_max_v = _mm512_loadu_ps(bounds.as_ptr());
            let mut stack = [const { MaybeUninit::<(u32, f32)>::uninit() }; 160];
            let mut sp = 0usize;
            let mut current = 0u32;
            let zero = _mm512_setzero_ps();
            loop {
                if current & LEAF == 0 {
                    let node = &bvh.nodes[current as usize];
                    let mut near = [0f32; WIDTH];
                    let mask = frustum.boxes(node, _mm512_reduce_max_ps(t_max_v), &mut near);
                    if let Some(next) = order_children(node, mask, &near, &mut stack, &mut sp) {
                        current = next;
                        continue;
                    }
                } else {
                    let packet = &bvh.packets[(current & !LEAF) as usize];
                    for lane in 0..PACKET {
                        if lane > 0 && packet.prim[lane] == packet.prim[lane - 1] {
                            break;
                        }
                        // One triangle against sixteen rays, with the scalar test's operations
                        // (the origin is shared, so the vertices' offsets are too).
                        let vertex = |m: &[[f32; PACKET]; 3]| Vec3::new(m[0][lane], m[1][lane], m[2][lane]);
                        let (a, b, c) = (vertex(&packet.a), vertex(&packet.b), vertex(&packet.c));
                        macro_rules! sheared {
                            ($v:expr) => {{
                                let d = $v - origin;
                                let z = _mm512_set1_ps(d[kz]);
                                (
                                    _mm512_sub_ps(_mm512_set1_ps(d[kx]), _mm512_mul_ps(shear[0], z)),
                                    _mm512_sub_ps(_mm512_set1_ps(d[ky]), _mm512_mul_ps(shear[1], z)),
                                    z,
                                )
                            }};
                        }
                        let (ax, ay, az) = sheared!(a);
                        let (bx, by, bz) = sheared!(b);
                        let (cx, cy, cz) = sheared!(c);
                        let u = _mm512_sub_ps(_mm512_mul_ps(cx, by), _mm512_mul_ps(cy, bx));
                        let v = _mm512_sub_ps(_mm512_mul_ps(ax, cy), _mm512_mul_ps(ay, cx));
                        let w = _mm512_sub_ps(_mm512_mul_ps(bx, ay), _mm512_mul_ps(by, ax));
                        macro_rules! any3 {
                            ($op:ident) => {
                                _mm512_cmp_ps_mask::<$op>(u, zero)
                                    | _mm512_cmp_ps_mask::<$op>(v, zero)
                                    | _mm512_cmp_ps_mask::<$op>(w, zero)
                            };
                        }
                        let outside = any3!(_CMP_LT_OQ) & any3!(_CMP_GT_OQ);
                        let on_edge = any3!(_CMP_EQ_OQ);
                        // Most triangles of a leaf miss every ray: skip the division then.
                        if outside == u16::MAX {
                            continue;
                        }
                        let det = _mm512_add_ps(_mm512_add_ps(u, v), w);
                        let sz = shear[2];
                        let t_scaled = _mm512_add_ps(
                            _mm512_add_ps(
                                _mm512_mul_ps(u, _mm512_mul_ps(sz, az)),
                                _mm512_mul_ps(v, _mm512_mul_ps(sz, bz)),
                            ),
                            _mm512_mul_ps(w, _mm512_mul_ps(sz, cz)),
                        );
                        let inv = _mm512_div_ps(_mm512_set1_ps(1.0), det);
                        let t = _mm512_mul_ps(t_scaled, inv);
                        let valid = !(outside | on_edge)
                            & _mm512_cmp_ps_mask::<_CMP_NEQ_OQ>(det, zero)
                            & _mm512_cmp_ps_mask::<_CMP_GT_OQ>(t, zero)
                            & _mm512_cmp_ps_mask::<_CMP_LT_OQ>(t, t_max_v);
                        let mask = u32::from(valid);
                        // Lanes with a zero edge function go to the scalar test (f64 there).
                        let edge = u32::from(!outside & on_edge);
                        if mask == 0 && edge == 0 {
                            continue;
                        }
                        let mut ts = [0f32; 16];
                        let mut b1 = [0f32; 16];
                        let mut b2 = [0f32; 16];
                        _mm512_storeu_ps(ts.as_mut_ptr(), t);
                        _mm512_storeu_ps(b1.as_mut_ptr(), _mm512_mul_ps(v, inv));
                        _mm512_storeu_ps(b2.as_mut_ptr(), _mm512_mul_ps(w, inv));
                        let hits = PacketHits { t: &mut ts, b1: &mut b1, b2: &mut b2, bounds: &mut bounds };
                        hits.offer(rays, [a, b, c], packet.prim[lane] as usize, mask, edge, accept);
                        t_max_v = _mm512_loadu_ps(bounds.as_ptr());
                    }
                }
                // Pop the next node some ray may still reach before its best hit.
                match pop_within(&stack, &mut sp, _mm512_reduce_max_ps(t_max_v)) {
                    Some(node) => current = node,
                    None => return true,
                }
            }
        }
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
            let mut stack = vec![MaybeUninit::uninit(); bvh.stack_size];
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
    fn packets_match_single_rays() {
        let tris = grid(30);
        let (bvh, _) = TriangleBvh::build(&tris);
        let mut rng = TestRng::new(5);
        for _ in 0..500 {
            let eye = Vec3::new(rng.range(-0.5, 1.5) as f32, rng.range(0.2, 1.5) as f32, rng.range(-0.5, 1.5) as f32);
            let centre = Vec3::new(rng.uniform() as f32, 0.0, rng.uniform() as f32);
            // A 4x2 tile, sometimes spread so wide that the rays change frames.
            let spread = if rng.uniform() < 0.2 { 2.0 } else { 0.01 };
            let rays: [WatertightRay; 8] = std::array::from_fn(|i| {
                let offset = Vec3::new((i % 4) as f32, 0.0, (i / 4) as f32) * spread;
                WatertightRay::new(eye, centre + offset - eye).unwrap()
            });
            let mut packet = [None; 8];
            bvh.closest8(&rays, [f32::INFINITY; 8], |lane, prim, h| {
                if packet[lane].is_none_or(|(_, t): (usize, f32)| h.t < t) {
                    packet[lane] = Some((prim, h.t));
                }
                Some(h.t)
            });
            for (lane, ray) in rays.iter().enumerate() {
                let mut single = None;
                bvh.closest(ray, f32::INFINITY, |prim, h| {
                    if single.is_none_or(|(_, t): (usize, f32)| h.t < t) {
                        single = Some((prim, h.t));
                    }
                    Some(h.t)
                });
                assert_eq!(packet[lane].map(|p| p.1), single.map(|s| s.1), "lane {lane}");
            }
        }
    }

    #[test]
    fn sixteen_ray_packets_match_single_rays() {
        let tris = grid(30);
        let (bvh, _) = TriangleBvh::build(&tris);
        let mut rng = TestRng::new(11);
        for case in 0..500 {
            let eye = Vec3::new(rng.range(-0.5, 1.5) as f32, rng.range(0.2, 1.5) as f32, rng.range(-0.5, 1.5) as f32);
            let centre = Vec3::new(rng.uniform() as f32, 0.0, rng.uniform() as f32);
            // A 4x4 tile from one eye (the frustum path), sometimes spread so wide that the
            // rays change frames or direction signs, sometimes from jittered eyes (as with a
            // lens), which takes the per-ray path.
            let spread = if rng.uniform() < 0.2 { 2.0 } else { 0.01 };
            let jitter = if case % 5 == 0 { 1e-3 } else { 0.0 };
            let rays: [WatertightRay; 16] = std::array::from_fn(|i| {
                let offset = Vec3::new((i % 4) as f32, 0.0, (i / 4) as f32) * spread;
                let origin = eye + Vec3::splat(jitter * i as f32);
                WatertightRay::new(origin, centre + offset - origin).unwrap()
            });
            // Some rays start with a bound already (as shadow-less reuse would).
            let t_max: [f32; 16] = std::array::from_fn(|i| if i % 7 == 3 { 0.5 } else { f32::INFINITY });
            let mut packet = [None; 16];
            bvh.closest16(&rays, t_max, |lane, prim, h| {
                if packet[lane].is_none_or(|(_, t): (usize, f32)| h.t < t) {
                    packet[lane] = Some((prim, h.t));
                }
                Some(h.t)
            });
            for (lane, ray) in rays.iter().enumerate() {
                let mut single = None;
                bvh.closest(ray, t_max[lane], |prim, h| {
                    if single.is_none_or(|(_, t): (usize, f32)| h.t < t) {
                        single = Some((prim, h.t));
                    }
                    Some(h.t)
                });
                assert_eq!(packet[lane].map(|p| p.1), single.map(|s| s.1), "case {case} lane {lane}");
            }
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
