//! The kernels in AVX2 lanes (x86-64): eight boxes in one 256-bit register per plane, four
//! triangles in 128-bit lanes.

use std::arch::x86_64::*;
use std::sync::OnceLock;

use super::{BOXES, BoxLanes, BoxRay, Dispatch, FAR_SCALE, Kernels};
use crate::accel::triangle::{PacketHits, TrianglePacket, WatertightRay};

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
    fn triangles(self, packet: &TrianglePacket, ray: &WatertightRay, t_max: f32, hits: &mut PacketHits) -> u32 {
        // SAFETY: `self` proves the CPU has AVX; the loads read rows of a `TrianglePacket`,
        // 16 bytes each and 16-byte aligned, and the stores write `PacketHits` rows of four.
        let (mut mask, mut edge) = unsafe {
            let [kx, ky, kz] = ray.axes();
            let org = ray.permuted_origin();
            let shear = ray.shear();
            let (ox, oy, oz) = (_mm_set1_ps(org[0]), _mm_set1_ps(org[1]), _mm_set1_ps(org[2]));
            let (sx, sy, sz) = (_mm_set1_ps(shear[0]), _mm_set1_ps(shear[1]), _mm_set1_ps(shear[2]));
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
            let (ax, ay, az) = sheared!(packet.a);
            let (bx, by, bz) = sheared!(packet.b);
            let (cx, cy, cz) = sheared!(packet.c);
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
            // Most packets a ray reaches lie beside it: stop before the division.
            if _mm_movemask_ps(outside) == 0b1111 {
                return 0;
            }
            // Lanes with a zero edge function are left to the scalar test (which redoes them
            // in f64) unless they are already certainly outside.
            let edge = _mm_movemask_ps(_mm_andnot_ps(outside, on_edge)) as u32;
            let det = _mm_add_ps(_mm_add_ps(u, v), w);
            let t_scaled = _mm_add_ps(
                _mm_add_ps(_mm_mul_ps(u, _mm_mul_ps(sz, az)), _mm_mul_ps(v, _mm_mul_ps(sz, bz))),
                _mm_mul_ps(w, _mm_mul_ps(sz, cz)),
            );
            let inv = _mm_div_ps(_mm_set1_ps(1.0), det);
            let t = _mm_mul_ps(t_scaled, inv);
            let in_range =
                _mm_and_ps(_mm_cmp_ps::<_CMP_GT_OQ>(t, zero), _mm_cmp_ps::<_CMP_LT_OQ>(t, _mm_set1_ps(t_max)));
            let valid =
                _mm_andnot_ps(_mm_or_ps(outside, on_edge), _mm_and_ps(_mm_cmp_ps::<_CMP_NEQ_OQ>(det, zero), in_range));
            let mask = _mm_movemask_ps(valid) as u32;
            if mask != 0 {
                _mm_storeu_ps(hits.t.as_mut_ptr(), t);
                _mm_storeu_ps(hits.b1.as_mut_ptr(), _mm_mul_ps(v, inv));
                _mm_storeu_ps(hits.b2.as_mut_ptr(), _mm_mul_ps(w, inv));
            }
            (mask, edge)
        };
        while edge != 0 {
            let lane = edge.trailing_zeros() as usize;
            edge &= edge - 1;
            let [a, b, c] = packet.vertices(lane);
            if let Some(hit) = ray.intersect(a, b, c, t_max) {
                hits.set(lane, hit);
                mask |= 1 << lane;
            }
        }
        mask
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec3;
    use prism_api::contract::TestRng;

    use super::*;
    use crate::accel::simd::Scalar;
    use crate::accel::triangle::PACKET;

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

    /// A random packet of four triangles; on `integer` cases vertices lie on a coarse grid
    /// and rays run along grid lines, so edge functions are often exactly zero (rays through
    /// edges and vertices, which the kernel hands to the scalar test).
    fn triangles_case(rng: &mut TestRng, integer: bool) -> ([[Vec3; 3]; PACKET], WatertightRay) {
        let point = |rng: &mut TestRng| {
            if integer {
                Vec3::from_array([0; 3].map(|_| (rng.range(-3.0, 3.0)).round() as f32))
            } else {
                Vec3::from_array([0; 3].map(|_| rng.range(-1.0, 1.0) as f32))
            }
        };
        let mut triangles = [[Vec3::ZERO; 3]; PACKET];
        for lane in 0..PACKET {
            triangles[lane] = [point(rng), point(rng), point(rng)];
            // Neighbours share an edge now and then, and a triangle is degenerate now and then.
            if lane > 0 && rng.uniform() < 0.3 {
                triangles[lane][0] = triangles[lane - 1][1];
                triangles[lane][1] = triangles[lane - 1][0];
            }
            if rng.uniform() < 0.05 {
                triangles[lane][2] = triangles[lane][1];
            }
        }
        let origin = point(rng) * 2.0;
        let target = if integer { point(rng) } else { triangles[rng.next_u64() as usize % PACKET][0] * 0.9 };
        let direction = if integer {
            // Along an axis or a grid diagonal, in either sense.
            let axis = rng.next_u64() as usize % 3;
            let mut d = Vec3::ZERO;
            d[axis] = if rng.uniform() < 0.5 { 1.0 } else { -1.0 };
            if rng.uniform() < 0.3 {
                d[(axis + 1) % 3] = 1.0;
            }
            d
        } else {
            target - origin
        };
        let ray = WatertightRay::new(if integer { target - direction * 4.0 } else { origin }, direction)
            .unwrap_or_else(|| WatertightRay::new(origin, Vec3::X).expect("a ray"));
        (triangles, ray)
    }

    /// The packet test returns exactly the scalar test's hits, lane by lane and bit for bit,
    /// including lanes on edges and vertices.
    #[test]
    fn triangles_equal_scalar_bit_for_bit() {
        let Some(avx2) = Avx2::detect() else { return };
        let mut rng = TestRng::new(23);
        let (mut hits_total, mut on_edges) = (0, 0);
        for case in 0..40_000 {
            let (triangles, ray) = triangles_case(&mut rng, case % 2 == 0);
            let prims: Vec<u32> = (0..(1 + case % PACKET) as u32).collect();
            let packet = TrianglePacket::new(&triangles, &prims);
            let t_max = if case % 3 == 0 { rng.range(0.5, 8.0) as f32 } else { f32::INFINITY };
            let (mut scalar, mut simd) = (PacketHits::default(), PacketHits::default());
            let mask = Scalar.triangles(&packet, &ray, t_max, &mut scalar);
            assert_eq!(avx2.triangles(&packet, &ray, t_max, &mut simd), mask, "case {case}");
            for lane in (0..PACKET).filter(|lane| mask & (1 << lane) != 0) {
                let (a, b) = (scalar.get(lane), simd.get(lane));
                assert_eq!([a.t, a.b1, a.b2].map(f32::to_bits), [b.t, b.b1, b.b2].map(f32::to_bits), "case {case}");
                hits_total += 1;
                on_edges += usize::from(a.b1 == 0.0 || a.b2 == 0.0 || a.b1 + a.b2 == 1.0);
            }
        }
        assert!(hits_total > 5_000 && on_edges > 500, "{hits_total} hits, {on_edges} on edges");
    }
}
