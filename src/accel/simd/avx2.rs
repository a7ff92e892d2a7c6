//! The kernels in AVX2 lanes (x86-64): eight boxes in one 256-bit register per plane, and a
//! group's vertices and triangles eight to a register.

use std::arch::x86_64::*;
use std::sync::OnceLock;

use super::{BOXES, BoxLanes, BoxRay, Dispatch, FAR_SCALE, Kernels};
use crate::accel::triangle::WatertightRay;
use crate::accel::triangle_groups::{Group, GroupHits};

/// Proof that the CPU runs AVX2, FMA, POPCNT and BMI1: only [`Avx2::detect`] makes one.
#[derive(Clone, Copy, Debug)]
pub struct Avx2 {
    _detected: (),
}

impl Avx2 {
    /// The token, when the CPU has the instructions (checked once per process).
    #[inline]
    pub fn detect() -> Option<Self> {
        static AVAILABLE: OnceLock<bool> = OnceLock::new();
        let available = *AVAILABLE.get_or_init(|| {
            is_x86_feature_detected!("avx2")
                && is_x86_feature_detected!("fma")
                && is_x86_feature_detected!("popcnt")
                && is_x86_feature_detected!("bmi1")
        });
        available.then_some(Avx2 { _detected: () })
    }

    /// Runs `work` with these kernels, compiled with the instructions enabled.
    #[inline(always)]
    pub(super) fn run<D: Dispatch>(self, work: D) -> D::Output {
        // SAFETY: `self` exists only when the CPU has every feature `run_enabled` enables.
        unsafe { run_enabled(self, work) }
    }
}

/// `work` with AVX2 and FMA enabled, so that the kernels it inlines compile to them.
#[target_feature(enable = "avx2,fma,popcnt,bmi1")]
fn run_enabled<D: Dispatch>(avx2: Avx2, work: D) -> D::Output {
    work.run(avx2)
}

impl Kernels for Avx2 {
    #[inline(always)]
    fn prefetch(self, address: *const u8, bytes: usize) {
        super::prefetch_bytes(address, bytes);
    }

    #[inline(always)]
    fn boxes(self, boxes: &BoxLanes, ray: &BoxRay, t_max: f32, near: &mut [f32; BOXES]) -> u32 {
        // SAFETY: `self` proves the CPU has AVX2 and FMA; the loads read rows of a
        // `BoxLanes`, 32 bytes each and 32-byte aligned.
        unsafe {
            let planes = &boxes.planes;
            // Macros, not closures: a closure is a function of its own without AVX, and the
            // intrinsics in it would not be inlined.
            macro_rules! plane {
                ($k:expr, $axis:expr) => {
                    _mm256_fmsub_ps(
                        _mm256_load_ps(planes[$k].as_ptr()),
                        _mm256_set1_ps(ray.rdir[$axis]),
                        _mm256_set1_ps(ray.org_rdir[$axis]),
                    )
                };
            }
            let nx = plane!(ray.near[0], 0);
            let ny = plane!(ray.near[1], 1);
            let nz = plane!(ray.near[2], 2);
            let fx = plane!(ray.far[0], 0);
            let fy = plane!(ray.far[1], 1);
            let fz = plane!(ray.far[2], 2);
            let t0 = _mm256_max_ps(_mm256_max_ps(nx, ny), _mm256_max_ps(nz, _mm256_setzero_ps()));
            // Each far distance scaled on its own (as the scalar kernel does; rounding is
            // monotonic, so the minimum is the same), then a two-level tree of minima: the
            // far side is the longer dependency chain from the node's loads to the mask.
            let scale = _mm256_set1_ps(FAR_SCALE);
            let t1 = _mm256_min_ps(
                _mm256_min_ps(_mm256_mul_ps(fx, scale), _mm256_mul_ps(fy, scale)),
                _mm256_min_ps(_mm256_mul_ps(fz, scale), _mm256_set1_ps(t_max)),
            );
            _mm256_storeu_ps(near.as_mut_ptr(), t0);
            _mm256_movemask_ps(_mm256_cmp_ps::<_CMP_LE_OQ>(t0, t1)) as u32
        }
    }

    #[inline(always)]
    fn group(self, group: &Group<'_>, ray: &WatertightRay, t_max: f32, hits: &mut GroupHits) -> u32 {
        // SAFETY: `self` proves the CPU has AVX2, all that `PermuteBlend` uses.
        unsafe { group_lanes::<PermuteBlend>(group, ray, t_max, hits) }
    }
}

/// How a group kernel reads each lane's corner from the sixteen sheared vertices held in
/// two registers (the low and the high eight), by the lane's index.
pub(super) trait CornerGather {
    /// The value at lane `index & 15` of (low, high), lane by lane.
    ///
    /// # Safety
    ///
    /// The CPU must have the instructions the implementation uses.
    unsafe fn gather(low: __m256, high: __m256, index: __m256i) -> __m256;
}

/// AVX2: both halves permuted, then blended on the index's bit 3.
pub(super) struct PermuteBlend;

impl CornerGather for PermuteBlend {
    #[inline(always)]
    unsafe fn gather(low: __m256, high: __m256, index: __m256i) -> __m256 {
        // SAFETY: the caller's CPU has AVX2.
        unsafe {
            let from_low = _mm256_permutevar8x32_ps(low, index);
            let from_high = _mm256_permutevar8x32_ps(high, index);
            _mm256_blendv_ps(from_low, from_high, _mm256_castsi256_ps(_mm256_slli_epi32::<28>(index)))
        }
    }
}

/// The group test of [`Kernels::group`] with AVX2 lanes and corners read by `G`.
///
/// # Safety
///
/// The CPU must have AVX2 and what `G` uses.
#[inline(always)]
pub(super) unsafe fn group_lanes<G: CornerGather>(
    group: &Group<'_>,
    ray: &WatertightRay,
    t_max: f32,
    hits: &mut GroupHits,
) -> u32 {
    let (vertices, triangles) = (group.vertex_count(), group.triangle_count());
    let coordinates = group.coordinates();
    let corner_indices = group.corner_indices();
    let mut mask = 0u32;
    let mut edge = 0u32;
    // SAFETY: the caller's CPU has AVX2 and what `G` uses; `Group` guarantees its counts
    // (at most 16 vertices and 16 triangles) and that the words after its coordinates and
    // index bytes are readable for at least 16 words, which covers every 8-lane load below.
    unsafe {
        let [kx, ky, kz] = ray.axes();
        let org = ray.permuted_origin();
        let shear = ray.shear();
        let (ox, oy, oz) = (_mm256_set1_ps(org[0]), _mm256_set1_ps(org[1]), _mm256_set1_ps(org[2]));
        let (sx, sy, sz) = (_mm256_set1_ps(shear[0]), _mm256_set1_ps(shear[1]), _mm256_set1_ps(shear[2]));
        // Each vertex sheared once, with the scalar test's operations in its order (no
        // fused multiply-adds): corners that are the same vertex get the same numbers.
        macro_rules! sheared {
            ($first:expr) => {{
                let x = _mm256_sub_ps(_mm256_loadu_ps(coordinates.add(kx * vertices + $first)), ox);
                let y = _mm256_sub_ps(_mm256_loadu_ps(coordinates.add(ky * vertices + $first)), oy);
                let z = _mm256_sub_ps(_mm256_loadu_ps(coordinates.add(kz * vertices + $first)), oz);
                (_mm256_sub_ps(x, _mm256_mul_ps(sx, z)), _mm256_sub_ps(y, _mm256_mul_ps(sy, z)), _mm256_mul_ps(sz, z))
            }};
        }
        // Both halves always (the loads past a group of eight vertices or fewer read
        // words that no index names): a branch on the count would be mispredicted.
        let low = sheared!(0);
        let high = sheared!(8);
        // A corner's value: the lane its index names, from the low or the high eight.
        let zero = _mm256_setzero_ps();
        let mut first = 0;
        while first < triangles {
            let lanes = (1u32 << (triangles - first).min(8)) - 1;
            macro_rules! corner {
                ($k:expr) => {{
                    let index = _mm256_cvtepu8_epi32(_mm_loadl_epi64(
                        corner_indices.add($k * triangles + first).cast::<__m128i>(),
                    ));
                    (G::gather(low.0, high.0, index), G::gather(low.1, high.1, index), G::gather(low.2, high.2, index))
                }};
            }
            let (ax, ay, az) = corner!(0);
            let (bx, by, bz) = corner!(1);
            let (cx, cy, cz) = corner!(2);
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
            let negative = any3!(_CMP_LT_OQ);
            let positive = any3!(_CMP_GT_OQ);
            let on_edge = any3!(_CMP_EQ_OQ);
            let outside = _mm256_and_ps(negative, positive);
            let inside = !(_mm256_movemask_ps(outside) as u32) & lanes;
            if inside != 0 {
                edge |= (_mm256_movemask_ps(on_edge) as u32 & inside) << first;
                let det = _mm256_add_ps(_mm256_add_ps(u, v), w);
                // az, bz, cz are already scaled by sz (the scalar test's `sz * a[kz]`).
                let t_scaled =
                    _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(u, az), _mm256_mul_ps(v, bz)), _mm256_mul_ps(w, cz));
                let inv = _mm256_div_ps(_mm256_set1_ps(1.0), det);
                let t = _mm256_mul_ps(t_scaled, inv);
                let in_range = _mm256_and_ps(
                    _mm256_cmp_ps::<_CMP_GT_OQ>(t, zero),
                    _mm256_cmp_ps::<_CMP_LT_OQ>(t, _mm256_set1_ps(t_max)),
                );
                let valid = _mm256_andnot_ps(
                    _mm256_or_ps(outside, on_edge),
                    _mm256_and_ps(_mm256_cmp_ps::<_CMP_NEQ_OQ>(det, zero), in_range),
                );
                let found = _mm256_movemask_ps(valid) as u32 & lanes;
                if found != 0 {
                    _mm256_storeu_ps(hits.t.as_mut_ptr().add(first), t);
                    _mm256_storeu_ps(hits.b1.as_mut_ptr().add(first), _mm256_mul_ps(v, inv));
                    _mm256_storeu_ps(hits.b2.as_mut_ptr().add(first), _mm256_mul_ps(w, inv));
                    mask |= found << first;
                }
            }
            first += 8;
        }
    }
    // Triangles with a zero edge function are left to the scalar test (which redoes
    // them in f64) unless they are already certainly outside.
    while edge != 0 {
        let triangle = edge.trailing_zeros() as usize;
        edge &= edge - 1;
        let [a, b, c] = group.triangle_vertices(triangle);
        if let Some(hit) = ray.intersect(a, b, c, t_max) {
            hits.set(triangle, hit);
            mask |= 1 << triangle;
        }
    }
    mask
}

#[cfg(test)]
pub(super) mod tests {
    use glam::Vec3;
    use prism_api::contract::TestRng;

    use super::*;
    use crate::accel::simd::Scalar;

    /// A multiple of `step` with up to `bits` significant bits.
    fn grid(rng: &mut TestRng, bits: u32, step: f32) -> f32 {
        (rng.range(-1.0, 1.0) * f64::from(1u32 << bits)).round() as f32 * step
    }

    /// Eight random boxes (some empty) and a ray; `coordinate` draws each value.
    fn boxes_case(rng: &mut TestRng, case: usize, coordinate: impl Fn(&mut TestRng) -> f32) -> BoxLanes {
        let mut boxes = BoxLanes::EMPTY;
        for lane in 0..BOXES {
            if case.is_multiple_of(5) && lane.is_multiple_of(3) {
                continue;
            }
            for axis in 0..3 {
                let (a, b) = (coordinate(rng), coordinate(rng));
                boxes.planes[axis][lane] = a.min(b);
                boxes.planes[axis + 3][lane] = a.max(b);
            }
        }
        boxes
    }

    /// A slab-test ray with the given origin and reciprocal direction.
    fn box_ray(origin: Vec3, rdir: Vec3) -> BoxRay {
        let mut ray = BoxRay::new(origin, rdir.recip());
        ray.rdir = rdir.to_array();
        ray.org_rdir = (origin * rdir).to_array();
        ray
    }

    fn t_max_of(rng: &mut TestRng, case: usize) -> f32 {
        match case % 4 {
            0 => f32::INFINITY,
            1 => 0.0,
            _ => rng.range(0.0, 64.0) as f32,
        }
    }

    /// On boxes and rays whose products `plane * rdir` are exact in f32 (planes of 12
    /// significant bits, reciprocal directions of 8), AVX2's fused slab distances equal the
    /// scalar kernel's two roundings, so the two kernels agree bit for bit.
    #[test]
    fn boxes_equal_scalar_bit_for_bit_on_exact_products() {
        // Without AVX2 there is nothing to compare.
        let Some(avx2) = Avx2::detect() else { return };
        let mut rng = TestRng::new(21);
        let mut entered = 0;
        for case in 0..20_000 {
            let boxes = boxes_case(&mut rng, case, |rng| grid(rng, 12, 1.0 / 256.0));
            let origin = Vec3::from_array([0; 3].map(|_| grid(&mut rng, 12, 1.0 / 256.0)));
            let rdir = Vec3::from_array([0; 3].map(|_| {
                let m = grid(&mut rng, 8, 1.0 / 8.0);
                if m == 0.0 { 1.0 / 8.0 } else { m }
            }));
            let ray = box_ray(origin, rdir);
            let t_max = t_max_of(&mut rng, case);
            let (mut near_scalar, mut near_avx2) = ([0f32; BOXES], [0f32; BOXES]);
            let mask = Scalar.boxes(&boxes, &ray, t_max, &mut near_scalar);
            assert_eq!(avx2.boxes(&boxes, &ray, t_max, &mut near_avx2), mask, "case {case}");
            assert_eq!(near_avx2.map(f32::to_bits), near_scalar.map(f32::to_bits), "case {case}");
            entered += mask.count_ones();
        }
        assert!(entered > 5_000, "the rays enter many boxes ({entered})");
    }

    /// On arbitrary boxes and rays the fused and unfused slab distances differ by rounding
    /// only: entry distances agree to a few units in the last place of the terms, and the
    /// kernels enter the same boxes except where entry and exit are that close.
    #[test]
    fn boxes_agree_with_scalar_within_rounding() {
        let Some(avx2) = Avx2::detect() else { return };
        let mut rng = TestRng::new(22);
        for case in 0..20_000 {
            let boxes = boxes_case(&mut rng, case, |rng| rng.range(-10.0, 10.0) as f32);
            let origin = Vec3::from_array([0; 3].map(|_| rng.range(-12.0, 12.0) as f32));
            let direction = Vec3::from_array([0; 3].map(|_| rng.range(-1.0, 1.0) as f32));
            let ray = BoxRay::new(origin, direction);
            let t_max = t_max_of(&mut rng, case);
            let (mut near_scalar, mut near_avx2) = ([0f32; BOXES], [0f32; BOXES]);
            let mask_scalar = Scalar.boxes(&boxes, &ray, t_max, &mut near_scalar);
            let mask_avx2 = avx2.boxes(&boxes, &ray, t_max, &mut near_avx2);
            for lane in 0..BOXES {
                // The size of the terms of each slab distance bounds their rounding.
                let scale = (0..6)
                    .map(|k| (boxes.planes[k][lane] * ray.rdir[k % 3]).abs() + ray.org_rdir[k % 3].abs())
                    .fold(0.0f32, f32::max);
                let tolerance = 4.0 * f32::EPSILON * scale;
                let (a, b) = (near_scalar[lane], near_avx2[lane]);
                assert!(a == b || (a - b).abs() <= tolerance, "case {case} lane {lane}: {a} vs {b}");
                if (mask_scalar ^ mask_avx2) & (1 << lane) != 0 {
                    // Recompute the exit distance as the scalar kernel does.
                    let exit = (0..3)
                        .map(|axis| {
                            (boxes.planes[ray.far[axis]][lane] * ray.rdir[axis] - ray.org_rdir[axis]) * FAR_SCALE
                        })
                        .fold(t_max, f32::min);
                    assert!((exit - a).abs() <= 2.0 * tolerance, "case {case} lane {lane}: masks differ");
                }
            }
        }
    }

    /// A ray at `triangles`: on `integer` cases, where vertices lie on a coarse grid, along
    /// an axis or a grid diagonal through a grid point, so that edge functions are often
    /// exactly zero (rays through edges and vertices, which the kernel hands to the scalar
    /// test); otherwise from a random point towards a point inside one of the triangles.
    fn ray_case(rng: &mut TestRng, integer: bool, triangles: &[[Vec3; 3]]) -> WatertightRay {
        let origin = Vec3::from_array([0; 3].map(|_| rng.range(-2.0, 2.0) as f32));
        let [a, b, c] = triangles[rng.next_u64() as usize % triangles.len()];
        let ray = if integer {
            let target = Vec3::from_array([0; 3].map(|_| (rng.range(-3.0, 3.0)).round() as f32));
            let axis = rng.next_u64() as usize % 3;
            let mut d = Vec3::ZERO;
            d[axis] = if rng.uniform() < 0.5 { 1.0 } else { -1.0 };
            if rng.uniform() < 0.3 {
                d[(axis + 1) % 3] = 1.0;
            }
            WatertightRay::new(target - d * 4.0, d)
        } else {
            let (u, v) = (rng.uniform() as f32, rng.uniform() as f32);
            let (u, v) = if u + v > 1.0 { (1.0 - u, 1.0 - v) } else { (u, v) };
            WatertightRay::new(origin, a + (b - a) * u + (c - a) * v - origin)
        };
        ray.unwrap_or_else(|| WatertightRay::new(origin, Vec3::X).expect("a ray"))
    }

    /// The group test returns exactly the scalar test's hits, triangle by triangle and bit
    /// for bit: groups of one to sixteen triangles over one to sixteen shared vertices,
    /// on rays through edges and vertices too.
    #[test]
    fn groups_equal_scalar_bit_for_bit() {
        if let Some(avx2) = Avx2::detect() {
            groups_match_scalar(|test| avx2.run(test));
        }
    }

    /// One group test, run by a token's `run` (inside the function compiled with its
    /// instructions, as the traversal runs it).
    pub(in crate::accel::simd) struct GroupTest<'a> {
        group: &'a Group<'a>,
        ray: &'a WatertightRay,
        t_max: f32,
    }

    impl Dispatch for GroupTest<'_> {
        type Output = (u32, GroupHits);

        #[inline(always)]
        fn run<K: Kernels>(self, kernels: K) -> Self::Output {
            let mut hits = GroupHits::default();
            let mask = kernels.group(self.group, self.ray, self.t_max, &mut hits);
            (mask, hits)
        }
    }

    /// [`groups_equal_scalar_bit_for_bit`] for the kernels that `run` runs a test with.
    pub(in crate::accel::simd) fn groups_match_scalar(run: impl Fn(GroupTest<'_>) -> (u32, GroupHits)) {
        use crate::accel::triangle_groups::{GroupHits, GroupWriter};
        let mut rng = TestRng::new(24);
        let (mut hits_total, mut on_edges, mut wide_groups) = (0, 0, 0);
        for case in 0..20_000 {
            let integer = case % 2 == 0;
            let point = |rng: &mut TestRng| {
                if integer {
                    Vec3::from_array([0; 3].map(|_| (rng.range(-3.0, 3.0)).round() as f32))
                } else {
                    Vec3::from_array([0; 3].map(|_| rng.range(-1.0, 1.0) as f32))
                }
            };
            // Triangles over a small pool of points, so that they share vertices and edges.
            let pool: Vec<Vec3> = (0..3 + case % 20).map(|_| point(&mut rng)).collect();
            let count = 1 + case % 24;
            let triangles: Vec<[Vec3; 3]> =
                (0..count).map(|_| [0; 3].map(|_| pool[rng.next_u64() as usize % pool.len()])).collect();
            let ray = ray_case(&mut rng, integer, &triangles);
            let t_max = if case % 3 == 0 { rng.range(0.5, 8.0) as f32 } else { f32::INFINITY };
            let mut writer = GroupWriter::new(&triangles);
            let mut start = writer.leaf(&(0..count as u32).collect::<Vec<u32>>());
            let groups = writer.finish();
            loop {
                let group = groups.group(start);
                wide_groups += usize::from(group.vertex_count() > 8 && group.triangle_count() > 8);
                let mut scalar = GroupHits::default();
                let mask = Scalar.group(&group, &ray, t_max, &mut scalar);
                let (simd_mask, simd) = run(GroupTest { group: &group, ray: &ray, t_max });
                assert_eq!(simd_mask, mask, "case {case}");
                for k in (0..group.triangle_count()).filter(|k| mask & (1 << k) != 0) {
                    let (a, b) = (scalar.get(k), simd.get(k));
                    assert_eq!([a.t, a.b1, a.b2].map(f32::to_bits), [b.t, b.b1, b.b2].map(f32::to_bits), "case {case}");
                    hits_total += 1;
                    on_edges += usize::from(a.b1 == 0.0 || a.b2 == 0.0 || a.b1 + a.b2 == 1.0);
                }
                if !group.more() {
                    break;
                }
                start = group.end();
            }
        }
        assert!(
            hits_total > 5_000 && on_edges > 500 && wide_groups > 1_000,
            "{hits_total} hits, {on_edges} on edges, {wide_groups} wide"
        );
    }
}
