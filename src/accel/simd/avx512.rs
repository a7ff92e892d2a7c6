//! The kernels with AVX-512 (F and VL) beside AVX2 (x86-64): the AVX2 kernels compiled with
//! thirty-two vector registers (the ray's terms stay in registers across a traversal), and
//! a group's corners read from its sixteen sheared vertices by one two-register permute
//! (`vpermt2ps`) instead of two permutes and a blend.

use std::arch::x86_64::*;
use std::sync::OnceLock;

use super::avx2::{CornerGather, group_lanes};
use super::{Avx2, BOXES, BoxLanes, BoxRay, Dispatch, Kernels};
use crate::accel::triangle::WatertightRay;
use crate::accel::triangle_groups::{Group, GroupHits};

/// Proof that the CPU runs AVX-512 F and VL as well as everything [`Avx2`] needs: only
/// [`Avx512::detect`] makes one.
#[derive(Clone, Copy, Debug)]
pub struct Avx512 {
    avx2: Avx2,
}

impl Avx512 {
    /// The token, when the CPU has the instructions (checked once per process).
    #[inline]
    pub fn detect() -> Option<Self> {
        static AVAILABLE: OnceLock<bool> = OnceLock::new();
        let avx2 = Avx2::detect()?;
        let available =
            *AVAILABLE.get_or_init(|| is_x86_feature_detected!("avx512f") && is_x86_feature_detected!("avx512vl"));
        available.then_some(Avx512 { avx2 })
    }

    /// Runs `work` with these kernels, compiled with the instructions enabled.
    #[inline(always)]
    pub(super) fn run<D: Dispatch>(self, work: D) -> D::Output {
        // SAFETY: `self` exists only when the CPU has every feature `run_enabled` enables.
        unsafe { run_enabled(self, work) }
    }
}

/// `work` with AVX2, FMA and AVX-512 F/VL enabled, so that the kernels it inlines compile
/// to them.
#[target_feature(enable = "avx2,fma,popcnt,bmi1,avx512f,avx512vl")]
fn run_enabled<D: Dispatch>(avx512: Avx512, work: D) -> D::Output {
    work.run(avx512)
}

/// AVX-512 VL: one permute across both registers.
struct Permute2;

impl CornerGather for Permute2 {
    #[inline(always)]
    unsafe fn gather(low: __m256, high: __m256, index: __m256i) -> __m256 {
        // SAFETY: the caller's CPU has AVX-512 F and VL.
        unsafe { _mm256_permutex2var_ps(low, index, high) }
    }
}

impl Kernels for Avx512 {
    #[inline(always)]
    fn prefetch(self, address: *const u8, bytes: usize) {
        self.avx2.prefetch(address, bytes);
    }

    #[inline(always)]
    fn boxes(self, boxes: &BoxLanes, ray: &BoxRay, t_max: f32, near: &mut [f32; BOXES]) -> u32 {
        self.avx2.boxes(boxes, ray, t_max, near)
    }

    #[inline(always)]
    fn group(self, group: &Group<'_>, ray: &WatertightRay, t_max: f32, hits: &mut GroupHits) -> u32 {
        // SAFETY: `self` proves the CPU has AVX2 and AVX-512 F/VL, all that `group_lanes`
        // and `Permute2` use.
        unsafe { group_lanes::<Permute2>(group, ray, t_max, hits) }
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec3;
    use prism_api::contract::TestRng;

    use super::*;

    /// The group test returns exactly the scalar test's hits (the AVX2 kernels' test, run
    /// with these kernels).
    #[test]
    fn groups_equal_scalar_bit_for_bit() {
        if let Some(avx512) = Avx512::detect() {
            super::super::avx2::tests::groups_match_scalar(|test| avx512.run(test));
        }
    }

    /// One box test, run by a token's `run`.
    struct BoxTest<'a> {
        boxes: &'a BoxLanes,
        ray: &'a BoxRay,
        t_max: f32,
    }

    impl Dispatch for BoxTest<'_> {
        type Output = (u32, [f32; BOXES]);

        #[inline(always)]
        fn run<K: Kernels>(self, kernels: K) -> Self::Output {
            let mut near = [0f32; BOXES];
            (kernels.boxes(self.boxes, self.ray, self.t_max, &mut near), near)
        }
    }

    /// The box test is the AVX2 one, compiled with AVX-512 enabled: the same entry
    /// distances and masks, bit for bit, each run inside its token's compiled function.
    #[test]
    fn boxes_equal_avx2_bit_for_bit() {
        let Some(avx512) = Avx512::detect() else { return };
        let mut rng = TestRng::new(25);
        for case in 0..20_000 {
            let mut boxes = BoxLanes::EMPTY;
            for lane in 0..BOXES {
                for axis in 0..3 {
                    let (a, b) = (rng.range(-10.0, 10.0) as f32, rng.range(-10.0, 10.0) as f32);
                    boxes.planes[axis][lane] = a.min(b);
                    boxes.planes[axis + 3][lane] = a.max(b);
                }
            }
            let origin = Vec3::from_array([0; 3].map(|_| rng.range(-12.0, 12.0) as f32));
            let direction = Vec3::from_array([0; 3].map(|_| rng.range(-1.0, 1.0) as f32));
            let ray = BoxRay::new(origin, direction);
            let t_max = if case % 2 == 0 { f32::INFINITY } else { rng.range(0.0, 30.0) as f32 };
            let (mask, near_avx2) = avx512.avx2.run(BoxTest { boxes: &boxes, ray: &ray, t_max });
            let (mask_avx512, near_avx512) = avx512.run(BoxTest { boxes: &boxes, ray: &ray, t_max });
            assert_eq!(mask_avx512, mask, "case {case}");
            assert_eq!(near_avx512.map(f32::to_bits), near_avx2.map(f32::to_bits), "case {case}");
        }
    }
}
