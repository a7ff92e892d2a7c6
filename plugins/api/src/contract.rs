//! The contract-test kit: properties every [`Shape`] must have, checked with many random
//! rays. A plugin's tests call [`check_shape`] on a few representative parameter sets.
//!
//! Checked for each ray: hits lie inside `t_min < t < t_max`; the surface point equals
//! `ray.at(t)`; normals are unit length; bounded shapes' hits lie inside `bounds()`;
//! `occluded` agrees with `intersect`; shrinking `t_max` below a hit never yields a farther
//! hit; and the hit is invariant (within tolerance) when the ray is expressed through a
//! random rotation, non-uniform scale and translation and mapped back, as Prism does for
//! every transformed primitive; and `misses_hull` never claims to miss a hull holding a
//! segment that hits. A ray whose hit-or-miss answer changes when it is nudged
//! sideways by a billionth of the shape's size grazes a silhouette or an edge (a triangle's
//! edge, a disc's rim): there rounding legitimately decides, so such a ray is not counted
//! against the transform-invariance budget. Rays that hit either way must agree.

use glam::{DAffine3, DQuat, DVec2, DVec3};

use crate::{Aabb, Ray, Shape};

/// How hard [`check_shape_with`] tries.
#[derive(Clone, Copy, Debug)]
pub struct ContractConfig {
    /// Number of random rays.
    pub rays: usize,
    /// Seed of the ray generator.
    pub seed: u64,
    /// Relative tolerance for positions and parameters (scaled by the shape's size).
    pub tolerance: f64,
    /// Fraction of rays allowed to disagree in the transform-invariance test (grazing rays
    /// may legitimately flip between hit and miss).
    pub max_flip_fraction: f64,
}

impl Default for ContractConfig {
    fn default() -> Self {
        Self { rays: 20_000, seed: 0x5EED_CAFE, tolerance: 1e-6, max_flip_fraction: 0.002 }
    }
}

/// Runs the contract with the default configuration; panics with a description of the
/// first violation.
pub fn check_shape(shape: &dyn Shape) {
    check_shape_with(shape, &ContractConfig::default());
}

/// A tiny deterministic generator (SplitMix64), so the kit needs no dependency.
pub struct TestRng(u64);

impl TestRng {
    /// A generator from `seed`.
    pub fn new(seed: u64) -> Self {
        Self(seed)
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1).
    pub fn uniform(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// Uniform in [lo, hi).
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.uniform()
    }

    /// A uniformly distributed unit vector.
    pub fn unit_vector(&mut self) -> DVec3 {
        let z = self.range(-1.0, 1.0);
        let phi = self.range(0.0, std::f64::consts::TAU);
        let r = (1.0 - z * z).max(0.0).sqrt();
        DVec3::new(r * phi.cos(), r * phi.sin(), z)
    }

    /// A point uniformly inside `bounds`.
    pub fn point_in(&mut self, bounds: &Aabb) -> DVec3 {
        DVec3::new(
            self.range(bounds.min.x, bounds.max.x),
            self.range(bounds.min.y, bounds.max.y),
            self.range(bounds.min.z, bounds.max.z),
        )
    }
}

/// The region rays are aimed at: the bounds, or a 4-unit cube for unbounded shapes.
fn target_region(shape: &dyn Shape) -> Aabb {
    let b = shape.bounds();
    if b.is_bounded() { b } else { Aabb::from_corners(DVec3::splat(-2.0), DVec3::splat(2.0)) }
}

/// Rays that start outside, inside and on the edges of the region, aimed at points in it.
fn random_ray(rng: &mut TestRng, region: &Aabb) -> Ray {
    let size = (region.max - region.min).max_element().max(1e-3);
    let target = rng.point_in(region);
    let origin = match rng.next_u64() % 4 {
        // From far outside.
        0 | 1 => region.center() + rng.unit_vector() * size * rng.range(1.5, 4.0),
        // From inside the bounds (inside the shape, often).
        2 => rng.point_in(region),
        // Along an axis through the centre: the rays that break axis-symmetric solvers.
        _ => {
            let axis = [DVec3::X, DVec3::Y, DVec3::Z][(rng.next_u64() % 3) as usize];
            let sign = if rng.uniform() < 0.5 { -1.0 } else { 1.0 };
            return Ray::new(region.center() + axis * sign * size * 2.0, -axis * sign);
        }
    };
    let direction = (target - origin).normalize_or(DVec3::X);
    Ray::new(origin, direction)
}

fn random_transform(rng: &mut TestRng) -> DAffine3 {
    let rotation = DQuat::from_axis_angle(rng.unit_vector(), rng.range(0.0, std::f64::consts::TAU));
    let scale = DVec3::new(rng.range(0.3, 3.0), rng.range(0.3, 3.0), rng.range(0.3, 3.0));
    let translation = DVec3::new(rng.range(-5.0, 5.0), rng.range(-5.0, 5.0), rng.range(-5.0, 5.0));
    DAffine3::from_scale_rotation_translation(scale, rotation, translation)
}

/// True when `ray` grazes a silhouette or an edge of the shape, where hit-or-miss is decided
/// by rounding: copies of the ray moved sideways by `delta` and `2 delta` miss on one side
/// and hit on the opposite side. Near a cone's apex or a box's edge the nudged rays hit on
/// every side, so solvers that lose such hits to rounding are still caught; a shape that
/// drops hits at random shows no consistent edge and is caught too.
fn grazes_an_edge(shape: &dyn Shape, ray: &Ray, t_min: f64, t_max: f64, delta: f64) -> bool {
    let (a, b) = crate::math::orthonormal_basis(ray.direction.normalize());
    let hits = |offset: DVec3| shape.intersect(&Ray::new(ray.origin + offset, ray.direction), t_min, t_max).is_some();
    [a, -a, b, -b].into_iter().any(|side| {
        !hits(side * delta) && !hits(side * (2.0 * delta)) && hits(-side * delta) && hits(-side * (2.0 * delta))
    })
}

/// Random hulls of four points in `region`: when the shape says it misses one, segments
/// between random points of the hull must not hit it.
fn check_missed_hulls(shape: &dyn Shape, rng: &mut TestRng, region: &Aabb, count: usize, t_min: f64) {
    for _ in 0..count {
        let points: [DVec3; 4] = std::array::from_fn(|_| rng.point_in(region));
        if !shape.misses_hull(&points) {
            continue;
        }
        let mut inside = || {
            let w: [f64; 4] = std::array::from_fn(|_| rng.uniform() + 1e-3);
            let total: f64 = w.iter().sum();
            points.iter().zip(w).map(|(p, w)| *p * (w / total)).sum::<DVec3>()
        };
        for _ in 0..16 {
            let (from, to) = (inside(), inside());
            let ray = Ray::new(from, to - from);
            let hit = shape.intersect(&ray, t_min, 1.0);
            assert!(hit.is_none(), "misses_hull({points:?}) is true, but the segment {from} -> {to} hits: {hit:?}");
        }
    }
}

/// Runs the contract with `config`; panics with a description of the first violation.
pub fn check_shape_with(shape: &dyn Shape, config: &ContractConfig) {
    let mut rng = TestRng::new(config.seed);
    let region = target_region(shape);
    let scale = (region.max - region.min).max_element().max(1.0);
    let tol = config.tolerance * scale * 10.0;
    let bounds = shape.bounds();
    let mut hits = 0usize;
    let mut flips = 0usize;
    // Crossings where `inside` does not change from just before the hit to just after it,
    // and whether it was ever true (shapes without an inside answer false everywhere).
    let (mut unchanged_inside, mut has_inside) = (0usize, false);
    let t_min = 1e-9;

    for i in 0..config.rays {
        let ray = random_ray(&mut rng, &region);
        let t_max = if i % 7 == 0 { rng.range(0.0, scale * 4.0) } else { f64::INFINITY };
        let hit = shape.intersect(&ray, t_min, t_max);
        let occluded = shape.occluded(&ray, t_min, t_max);
        assert_eq!(
            hit.is_some(),
            occluded,
            "occluded() disagrees with intersect() for {ray:?} in ({t_min}, {t_max}): hit {hit:?}"
        );
        let Some(hit) = hit else { continue };
        hits += 1;
        assert!(
            hit.t > t_min && hit.t < t_max && hit.t.is_finite(),
            "hit t = {} outside ({t_min}, {t_max}) for {ray:?}",
            hit.t
        );
        let surface = shape.surface(&ray, &hit);
        let expected = ray.at(hit.t);
        assert!(
            surface.point.distance(expected) <= tol,
            "surface point {} is not ray.at(t) = {expected} for {ray:?}, hit {hit:?}",
            surface.point
        );
        for (what, n) in [("normal", surface.normal), ("shading normal", surface.shading_normal)] {
            assert!((n.length() - 1.0).abs() < 1e-9, "{what} {n} is not unit length at {} for {ray:?}", surface.point);
        }
        assert!(
            !bounds.is_bounded() || bounds.contains(surface.point, tol),
            "hit {} lies outside bounds {bounds:?} for {ray:?}",
            surface.point
        );
        assert!(surface.uv.is_finite(), "uv {} not finite", surface.uv);
        let geometry = shape.surface_geometry(&ray, &hit);
        assert!(
            (geometry.point, geometry.normal, geometry.shading_normal)
                == (surface.point, surface.normal, surface.shading_normal),
            "surface_geometry() {geometry:?} differs from surface() {surface:?} in point or normals for {ray:?}"
        );

        // A hull holding the segment up to the hit must not be missed.
        let reached = ray.at(hit.t + tol);
        assert!(
            !shape.misses_hull(&[ray.origin, reached]),
            "misses_hull() claims the segment from {} to {reached} misses, but {ray:?} hits at t = {}",
            ray.origin,
            hit.t
        );

        // Crossing the surface goes in or out of the solid.
        let step = 1e-7 * scale / ray.direction.length();
        let (before, after) = (shape.inside(ray.at(hit.t - step)), shape.inside(ray.at(hit.t + step)));
        has_inside |= before || after;
        if before == after {
            unchanged_inside += 1;
        }

        // A shorter segment that ends before the hit must not report anything farther.
        let shorter = hit.t * 0.999;
        if let Some(h) = shape.intersect(&ray, t_min, shorter) {
            assert!(h.t < shorter, "t_max {shorter} not respected: got {} for {ray:?}", h.t);
        }

        // Transform invariance: express the ray in a random world frame and back.
        let world_from_object = random_transform(&mut rng);
        let object_from_world = world_from_object.inverse();
        let world_ray = Ray::new(
            world_from_object.transform_point3(ray.origin),
            world_from_object.transform_vector3(ray.direction),
        );
        let back = Ray::new(
            object_from_world.transform_point3(world_ray.origin),
            object_from_world.transform_vector3(world_ray.direction),
        );
        match shape.intersect(&back, t_min, t_max) {
            Some(h) if (h.t - hit.t).abs() <= tol * (1.0 + hit.t) => {}
            Some(_) => flips += 1,
            None if grazes_an_edge(shape, &ray, t_min, t_max, 1e-9 * scale) => {}
            None => flips += 1,
        }
    }
    check_missed_hulls(shape, &mut rng, &region, config.rays / 8, t_min);
    let allowed = (config.max_flip_fraction * config.rays as f64).ceil() as usize;
    assert!(
        !has_inside || unchanged_inside <= allowed,
        "inside() did not change across {unchanged_inside} of {hits} surface crossings (allowed {allowed})"
    );
    assert!(
        flips <= allowed,
        "{flips} of {} rays changed their hit under a round trip through a random transform (allowed {allowed})",
        config.rays
    );
    assert!(
        hits > config.rays / 50,
        "only {hits} of {} contract rays hit the shape: is intersect() implemented?",
        config.rays
    );

    if let Some(area) = shape.area() {
        assert!(area.is_finite() && area > 0.0, "area {area} must be positive");
        for _ in 0..256 {
            let u = DVec2::new(rng.uniform(), rng.uniform());
            if let Some(sample) = shape.sample_area(u) {
                assert!((sample.normal.length() - 1.0).abs() < 1e-9, "sampled normal not unit");
                assert!(
                    !bounds.is_bounded() || bounds.contains(sample.point, tol),
                    "sampled point {} outside bounds",
                    sample.point
                );
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Hit;

    /// The triangle (0,0,0), (1,0,0), (0,1,0): the kit's rays along z through the centre of
    /// its bounds hit its hypotenuse exactly, where rounding decides hit or miss.
    #[derive(Debug)]
    struct RightTriangle;

    impl Shape for RightTriangle {
        fn bounds(&self) -> Aabb {
            Aabb::from_corners(DVec3::ZERO, DVec3::new(1.0, 1.0, 0.0))
        }
        fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit> {
            if ray.direction.z.abs() <= 1e-12 * ray.direction.length() {
                return None;
            }
            let t = -ray.origin.z / ray.direction.z;
            let p = ray.at(t);
            (t > t_min && t < t_max && p.x >= 0.0 && p.y >= 0.0 && p.x + p.y <= 1.0).then(|| Hit::at(t))
        }
        fn surface(&self, ray: &Ray, hit: &Hit) -> crate::Surface {
            crate::Surface::new(ray.at(hit.t), DVec3::Z, DVec2::ZERO)
        }
    }

    /// A unit sphere that loses or misplaces hits depending on the last bit of the origin.
    #[derive(Debug)]
    struct Flaky {
        far_instead_of_near: bool,
    }

    impl Shape for Flaky {
        fn bounds(&self) -> Aabb {
            Aabb::from_corners(DVec3::splat(-1.0), DVec3::splat(1.0))
        }
        fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit> {
            let d = ray.direction;
            let (t0, t1) = crate::math::solve_quadratic(
                d.length_squared(),
                2.0 * ray.origin.dot(d),
                ray.origin.length_squared() - 1.0,
            )?;
            let odd = ray.origin.x.to_bits() & 1 == 1;
            if odd && !self.far_instead_of_near {
                return None;
            }
            let candidates = if odd { [t1, t1] } else { [t0, t1] };
            candidates.into_iter().find(|&t| t > t_min && t < t_max).map(Hit::at)
        }
        fn surface(&self, ray: &Ray, hit: &Hit) -> crate::Surface {
            let p = ray.at(hit.t);
            crate::Surface::new(p, p.normalize(), DVec2::ZERO)
        }
    }

    #[test]
    fn rays_on_an_edge_may_flip() {
        check_shape(&RightTriangle);
    }

    #[test]
    #[should_panic(expected = "changed their hit")]
    fn hits_that_move_are_caught() {
        check_shape(&Flaky { far_instead_of_near: true });
    }

    #[test]
    #[should_panic(expected = "changed their hit")]
    fn hits_lost_at_random_are_caught() {
        check_shape(&Flaky { far_instead_of_near: false });
    }
}
