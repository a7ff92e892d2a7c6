//! The watertight ray-triangle test of Woop, Benthin and Wald (JCGT 2013): the ray is
//! sheared so that it runs along +z from the origin, and the three 2D edge functions of the
//! sheared triangle decide the hit. Edges shared by two triangles are evaluated with exactly
//! the same operations from both sides, so a ray can never slip through the crack between
//! them; an edge function that rounds to zero is redone in f64, as the paper recommends.
//!
//! The test runs in f32 (mesh data is f32). The ray direction need not be unit length: `t`
//! is in units of the direction, as everywhere in Prism. [`WatertightRay::intersect`] is the
//! scalar test; the SIMD kernels (`accel::simd`) test a BVH leaf's triangles
//! (`accel::triangle_groups`) in lanes with exactly its results.

use glam::{DVec3, Vec3};
use prism_api::Hit;

/// A ray prepared for the watertight test: the permutation that makes z the dominant
/// direction axis and the shear that maps the direction to +z.
#[derive(Clone, Copy, Debug)]
pub struct WatertightRay {
    /// Ray origin.
    pub origin: Vec3,
    /// Ray direction (unnormalised).
    pub direction: Vec3,
    /// The axes (kx, ky, kz): kz is the direction's dominant axis.
    axes: [usize; 3],
    /// The shear (sx, sy, sz) that maps the permuted direction to +z.
    shear: [f32; 3],
    /// The origin's coordinates on the axes (kx, ky, kz).
    permuted_origin: [f32; 3],
}

/// Where a ray meets a triangle: the ray parameter and the barycentric weights of the
/// second and third vertices (the first has weight `1 - b1 - b2`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TriangleHit {
    /// Ray parameter (units of the unnormalised direction).
    pub t: f32,
    /// Weight of vertex 1.
    pub b1: f32,
    /// Weight of vertex 2.
    pub b2: f32,
}

impl WatertightRay {
    /// Prepares a ray. Returns `None` for a zero or non-finite direction.
    // Always inlined: as a call, its result went through the stack and stalled on store
    // forwarding in every mesh query.
    #[inline(always)]
    pub fn new(origin: Vec3, direction: Vec3) -> Option<Self> {
        if !direction.is_finite() || !origin.is_finite() || direction == Vec3::ZERO {
            return None;
        }
        let a = direction.abs();
        let kz = if a.x > a.y {
            if a.x > a.z { 0 } else { 2 }
        } else if a.y > a.z {
            1
        } else {
            2
        };
        let mut kx = (kz + 1) % 3;
        let mut ky = (kx + 1) % 3;
        // Keep the winding (and so the sign of the edge functions) when z points backwards.
        if direction[kz] < 0.0 {
            std::mem::swap(&mut kx, &mut ky);
        }
        let sz = 1.0 / direction[kz];
        let axes = [kx, ky, kz];
        Some(Self {
            origin,
            direction,
            axes,
            shear: [direction[kx] * sz, direction[ky] * sz, sz],
            permuted_origin: axes.map(|k| origin[k]),
        })
    }

    /// The axis permutation (kx, ky, kz) of the test.
    #[inline(always)]
    pub(crate) fn axes(&self) -> [usize; 3] {
        self.axes
    }

    /// The shear (sx, sy, sz) of the test.
    #[inline(always)]
    pub(crate) fn shear(&self) -> [f32; 3] {
        self.shear
    }

    /// The origin's coordinates on the axes (kx, ky, kz).
    #[inline(always)]
    pub(crate) fn permuted_origin(&self) -> [f32; 3] {
        self.permuted_origin
    }

    /// The hit with triangle (a, b, c) with `0 < t < t_max`, if any. Both faces count.
    #[inline]
    pub fn intersect(&self, a: Vec3, b: Vec3, c: Vec3, t_max: f32) -> Option<TriangleHit> {
        let [kx, ky, kz] = self.axes;
        let [sx, sy, sz] = self.shear;
        let a = a - self.origin;
        let b = b - self.origin;
        let c = c - self.origin;
        let ax = a[kx] - sx * a[kz];
        let ay = a[ky] - sy * a[kz];
        let bx = b[kx] - sx * b[kz];
        let by = b[ky] - sy * b[kz];
        let cx = c[kx] - sx * c[kz];
        let cy = c[ky] - sy * c[kz];
        let mut u = cx * by - cy * bx;
        let mut v = ax * cy - ay * cx;
        let mut w = bx * ay - by * ax;
        if u == 0.0 || v == 0.0 || w == 0.0 {
            // On an edge within f32 rounding: decide in f64 so neighbours agree exactly.
            let (ax, ay, bx, by, cx, cy) =
                (f64::from(ax), f64::from(ay), f64::from(bx), f64::from(by), f64::from(cx), f64::from(cy));
            u = (cx * by - cy * bx) as f32;
            v = (ax * cy - ay * cx) as f32;
            w = (bx * ay - by * ax) as f32;
        }
        if (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0) {
            return None;
        }
        let det = u + v + w;
        if det == 0.0 || !det.is_finite() {
            return None;
        }
        let az = sz * a[kz];
        let bz = sz * b[kz];
        let cz = sz * c[kz];
        let t_scaled = u * az + v * bz + w * cz;
        let inv = 1.0 / det;
        let t = t_scaled * inv;
        if !(t > 0.0 && t < t_max) {
            return None;
        }
        Some(TriangleHit { t, b1: v * inv, b2: w * inv })
    }
}

/// The ray parameter of the plane through triangle (a, b, c), in f64: the f32 test decides
/// *whether* the ray hits, this decides *where* precisely enough that a ray leaving the
/// surface (at a distance of 1e-6 or more) never finds the triangle it starts on. `None`
/// when the ray runs parallel to the plane.
#[inline]
pub fn plane_t(origin: DVec3, direction: DVec3, a: Vec3, b: Vec3, c: Vec3) -> Option<f64> {
    let (a, b, c) = (a.as_dvec3(), b.as_dvec3(), c.as_dvec3());
    let n = (b - a).cross(c - a);
    let denominator = n.dot(direction);
    if denominator == 0.0 || !denominator.is_finite() {
        return None;
    }
    Some(n.dot(a - origin) / denominator)
}

/// The shape hit on triangle `slot` of a mesh at the refined distance `t`, with the f32
/// test's barycentrics: the one form both the mesh shape's own BVH and the scene BVH's
/// flattened triangles report, and which the mesh shape's `surface` reads back.
#[inline]
pub fn mesh_hit(t: f64, slot: u32, hit: TriangleHit) -> Hit {
    Hit { t, part: slot, scratch: DVec3::new(f64::from(hit.b1), f64::from(hit.b2), 0.0) }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ray(o: [f32; 3], d: [f32; 3]) -> WatertightRay {
        WatertightRay::new(Vec3::from(o), Vec3::from(d)).unwrap()
    }

    const A: Vec3 = Vec3::new(0.0, 0.0, 0.0);
    const B: Vec3 = Vec3::new(1.0, 0.0, 0.0);
    const C: Vec3 = Vec3::new(0.0, 1.0, 0.0);

    #[test]
    fn hits_inside_with_barycentrics() {
        let h = ray([0.25, 0.5, 2.0], [0.0, 0.0, -1.0]).intersect(A, B, C, f32::INFINITY).unwrap();
        assert!((h.t - 2.0).abs() < 1e-6);
        assert!((h.b1 - 0.25).abs() < 1e-6 && (h.b2 - 0.5).abs() < 1e-6);
        // From behind: both faces count.
        let h = ray([0.25, 0.5, -2.0], [0.0, 0.0, 1.0]).intersect(A, B, C, f32::INFINITY).unwrap();
        assert!((h.b1 - 0.25).abs() < 1e-6 && (h.b2 - 0.5).abs() < 1e-6);
    }

    #[test]
    fn unnormalised_direction_scales_t() {
        let h = ray([0.25, 0.25, 4.0], [0.0, 0.0, -2.0]).intersect(A, B, C, f32::INFINITY).unwrap();
        assert!((h.t - 2.0).abs() < 1e-6);
    }

    #[test]
    fn misses_outside_behind_and_beyond_t_max() {
        assert!(ray([0.8, 0.8, 1.0], [0.0, 0.0, -1.0]).intersect(A, B, C, f32::INFINITY).is_none());
        assert!(ray([0.2, 0.2, 1.0], [0.0, 0.0, 1.0]).intersect(A, B, C, f32::INFINITY).is_none(), "behind");
        assert!(ray([0.2, 0.2, 1.0], [0.0, 0.0, -1.0]).intersect(A, B, C, 0.999).is_none(), "t_max");
        // Parallel to the plane.
        assert!(ray([0.2, 0.2, 0.0], [1.0, 0.0, 0.0]).intersect(A, B, C, f32::INFINITY).is_none());
        // Degenerate triangle.
        assert!(ray([0.2, 0.0, 1.0], [0.0, 0.0, -1.0]).intersect(A, B, B * 2.0, f32::INFINITY).is_none());
        assert!(WatertightRay::new(Vec3::ZERO, Vec3::ZERO).is_none());
    }

    #[test]
    fn shared_edge_is_watertight() {
        // Two triangles sharing the diagonal of the unit square; rays exactly on and near
        // the diagonal hit at least one of them, whatever the direction's dominant axis.
        let d = Vec3::new(1.0, 1.0, 0.0);
        let mut rng = prism_api::contract::TestRng::new(7);
        for i in 0..20_000 {
            let s = rng.uniform() as f32;
            let p = Vec3::new(s, s, 0.0) + if i % 2 == 0 { Vec3::ZERO } else { Vec3::new(1e-7, -1e-7, 0.0) };
            let dir = Vec3::new(rng.range(-0.3, 0.3) as f32, rng.range(-0.3, 0.3) as f32, -1.0);
            let origin = p - dir * 3.0;
            let r = ray(origin.into(), dir.into());
            let first = r.intersect(A, B, d, f32::INFINITY);
            let second = r.intersect(A, d, C, f32::INFINITY);
            assert!(first.is_some() || second.is_some(), "ray {i} through {p} slipped through the shared edge");
        }
    }

    #[test]
    fn vertex_hit_exactly() {
        // A ray straight through a vertex hits (the edge functions are 0, not negative).
        let h = ray([1.0, 0.0, 1.0], [0.0, 0.0, -1.0]).intersect(A, B, C, f32::INFINITY).unwrap();
        assert!((h.b1 - 1.0).abs() < 1e-6 && h.b2.abs() < 1e-6);
    }

    #[test]
    fn every_dominant_axis() {
        for (o, d) in [([0.2, 0.2, 1.0], [0.0, 0.0, -1.0]), ([0.2, 0.2, 1.0], [-0.1, 0.05, -0.5])] {
            for perm in 0..3 {
                let p = |v: [f32; 3]| Vec3::new(v[perm % 3], v[(perm + 1) % 3], v[(perm + 2) % 3]);
                let r = WatertightRay::new(p(o), p(d)).unwrap();
                let h = r.intersect(p(A.into()), p(B.into()), p(C.into()), f32::INFINITY);
                assert!(h.is_some(), "perm {perm}");
            }
        }
    }

    #[test]
    fn plane_t_is_precise() {
        let t = plane_t(DVec3::new(0.3, 0.3, 1e-3), DVec3::new(0.0, 0.0, -1.0), A, B, C).unwrap();
        assert!((t - 1e-3).abs() < 1e-15);
        assert!(plane_t(DVec3::ZERO, DVec3::X, A, B, C).is_none());
    }
}
