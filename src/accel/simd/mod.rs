//! The SIMD kernels of both BVH levels, each written once per instruction set: the test of
//! one ray against eight boxes (a wide node's children) and against a group of up to sixteen
//! triangles over shared vertices (a mesh leaf, `accel::triangle_groups`).
//!
//! An instruction set is a zero-sized token type that implements [`Kernels`]: [`Scalar`]
//! (plain loops, always available, the reference the others are tested against) and, on
//! x86-64, [`Avx2`] and [`Avx512`] (the AVX2 kernels with AVX-512's thirty-two registers and
//! two-register permutes), whose only constructors are the run-time CPU checks. A safe
//! kernel taking one is therefore sound by construction: holding it proves the CPU has the
//! instructions. [`dispatch`] runs work generic over the kernels with the fastest set the
//! CPU has, inside a function compiled for that set so that the kernels inline into it.

#[cfg(target_arch = "x86_64")]
mod avx2;
#[cfg(target_arch = "x86_64")]
mod avx512;
mod scalar;

#[cfg(target_arch = "x86_64")]
pub use avx2::Avx2;
#[cfg(target_arch = "x86_64")]
pub use avx512::Avx512;
use glam::{Vec3, Vec3A};
pub use scalar::Scalar;

use super::triangle::WatertightRay;
use super::triangle_groups::{Group, GroupHits};

/// Hints the CPU to fetch every cache line of `*item`, which is about to be read.
#[inline(always)]
pub fn prefetch<T>(item: *const T) {
    prefetch_bytes(item.cast(), std::mem::size_of::<T>());
}

/// Hints the CPU to fetch every cache line holding a byte of `address..address + bytes`
/// (a hint that never faults, whatever the address). The SSE prefetch is part of every
/// x86-64, so this needs no kernel token; elsewhere nothing is done.
#[inline(always)]
pub fn prefetch_bytes(address: *const u8, bytes: usize) {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_MM_HINT_T0, _mm_prefetch};
        let offset = address as usize & 63;
        let lines = (offset + bytes.max(1)).div_ceil(64);
        let first = address.cast::<i8>().wrapping_sub(offset);
        for line in 0..lines {
            // SAFETY: a prefetch never faults and changes no state a program can observe.
            unsafe { _mm_prefetch::<_MM_HINT_T0>(first.wrapping_add(64 * line)) };
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = (address, bytes);
}

/// Boxes tested together: the children of one wide node.
pub const BOXES: usize = 8;

/// Ize's conservative slab test: far distances grow by 2 gamma(3) so rounding never loses a
/// box.
pub const FAR_SCALE: f32 = 1.0 + 2.0 * (3.0 * f32::EPSILON * 0.5) / (1.0 - 3.0 * f32::EPSILON * 0.5);

/// Eight boxes as structure of arrays, aligned for 256-bit loads.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C, align(32))]
pub struct BoxLanes {
    /// min x, min y, min z, max x, max y, max z, each for the eight boxes.
    pub planes: [[f32; BOXES]; 6],
}

impl BoxLanes {
    /// Eight empty boxes (inverted bounds), which no ray enters.
    pub const EMPTY: BoxLanes = BoxLanes {
        planes: [
            [f32::INFINITY; BOXES],
            [f32::INFINITY; BOXES],
            [f32::INFINITY; BOXES],
            [f32::NEG_INFINITY; BOXES],
            [f32::NEG_INFINITY; BOXES],
            [f32::NEG_INFINITY; BOXES],
        ],
    };
}

/// A ray prepared for the slab test: reciprocal direction, origin times it, and which
/// bound is the near plane on each axis.
#[derive(Clone, Copy, Debug)]
pub struct BoxRay {
    /// Reciprocal direction.
    pub rdir: [f32; 3],
    /// Origin times the reciprocal direction.
    pub org_rdir: [f32; 3],
    /// Index into [`BoxLanes::planes`] of the near plane on each axis.
    pub near: [usize; 3],
    /// Index of the far plane on each axis (`near` + 3 mod 6).
    pub far: [usize; 3],
}

impl BoxRay {
    /// Prepares the ray `origin + t direction`.
    #[inline]
    pub fn new(origin: Vec3, direction: Vec3) -> Self {
        let d = Vec3A::from(direction);
        // Zero components become tiny ones (as Embree does): infinite reciprocals would turn
        // the slab test's products into NaN.
        let tiny = Vec3A::splat(1e-18);
        let rdir = Vec3A::select(d.abs().cmplt(tiny), tiny.copysign(d), d).recip();
        let org_rdir = Vec3A::from(origin) * rdir;
        let negative = rdir.is_negative_bitmask();
        let near_of = |axis: usize| if negative & (1 << axis) == 0 { axis } else { axis + 3 };
        let far_of = |axis: usize| if negative & (1 << axis) == 0 { axis + 3 } else { axis };
        Self {
            rdir: rdir.to_array(),
            org_rdir: org_rdir.to_array(),
            near: [near_of(0), near_of(1), near_of(2)],
            far: [far_of(0), far_of(1), far_of(2)],
        }
    }
}

/// One instruction set's kernels. Implemented by tokens that prove the CPU runs them, so
/// every method is safe to call.
pub trait Kernels: Copy {
    /// Bit mask of the boxes the ray enters at `0 <= t <= t_max`, and their entry distances
    /// in `near` (written for every box). Far distances are scaled by [`FAR_SCALE`].
    fn boxes(self, boxes: &BoxLanes, ray: &BoxRay, t_max: f32, near: &mut [f32; BOXES]) -> u32;

    /// Bit mask of the group's triangles that [`WatertightRay::intersect`] hits with
    /// `0 < t < t_max`, and those hits in `hits` (the entries of other triangles may be
    /// overwritten with meaningless values). Every implementation returns exactly the
    /// scalar test's hits, bit for bit.
    fn group(self, group: &Group<'_>, ray: &WatertightRay, t_max: f32, hits: &mut GroupHits) -> u32;

    /// Hints the CPU to bring the `bytes` at `address` into the cache (any address is
    /// allowed: a prefetch never faults). By default nothing.
    #[inline(always)]
    fn prefetch(self, _address: *const u8, _bytes: usize) {}
}

/// Work generic over the kernels, run by [`dispatch`].
pub trait Dispatch {
    /// What the work returns.
    type Output;

    /// Does the work with `kernels`. Mark implementations `#[inline(always)]`: [`dispatch`]
    /// compiles them inside a function with the instruction set enabled only if they inline.
    fn run<K: Kernels>(self, kernels: K) -> Self::Output;
}

/// The name of the instruction set `dispatch` runs with on this CPU.
pub fn instruction_set() -> &'static str {
    #[cfg(target_arch = "x86_64")]
    if Avx512::detect().is_some() {
        return "AVX-512 F/VL + AVX2 + FMA";
    }
    #[cfg(target_arch = "x86_64")]
    if Avx2::detect().is_some() {
        return "AVX2 + FMA";
    }
    "scalar"
}

/// Runs `work` with the fastest kernels the CPU has: AVX-512 (F and VL) with AVX2 where the
/// CPU has both, AVX2 where it has that, else the scalar ones.
#[inline(always)]
pub fn dispatch<D: Dispatch>(work: D) -> D::Output {
    #[cfg(target_arch = "x86_64")]
    if let Some(avx512) = Avx512::detect() {
        return avx512.run(work);
    }
    #[cfg(target_arch = "x86_64")]
    if let Some(avx2) = Avx2::detect() {
        return avx2.run(work);
    }
    work.run(Scalar)
}
