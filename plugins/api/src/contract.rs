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
//! against the transform-invariance budget. Rays that hit either way must agree. Each hit's
//! tangent `dpdu` is finite, non-zero, perpendicular to the normal and the same from
//! `surface` and `surface_geometry`, whose point and normals `hit_point` repeats; [`check_dpdu`] checks that it is the derivative of the uv.
//! [`Shape::crossings`] lists the ray's crossings in order within the range, the first being
//! `intersect`'s hit, and for a shape with an inside, `inside` flips across each of them
//! (what CSG relies on), but for a small budget of grazing rays.
//!
//! A shape that can emit ([`Shape::can_emit`]) is checked further, by [`check_area_sampling`]
//! and [`check_sampling_toward`]:
//!
//! * its area samples lie on the surface (a short probe ray along the sampled normal from
//!   just outside meets the surface at the point, with the same normal there), and their
//!   `pdf_area` is [`Shape::pdf_area`];
//! * its area and its area density are right: lines drawn uniformly and isotropically
//!   through its bounding sphere (radius R) cross a surface of area A on average
//!   A / (2 pi R^2) times (Cauchy–Crofton), so 2 pi R^2 times the mean number of crossings
//!   estimates `area()`, and 2 pi R^2 times the mean sum of `pdf_area` over the crossings
//!   estimates the integral of `pdf_area`, which must be 1; both within five standard errors;
//! * its direction sampling matches its density: from reference points far, near, beside
//!   and inside the shape, the directions of [`Shape::sample_toward`] are counted in bins of
//!   equal solid angle over the cone around the shape's bounding sphere (over the whole
//!   sphere of directions from within it), and compared with the counts expected from
//!   [`Shape::pdf_toward`] integrated over each bin (adaptive Gauss–Legendre quadrature) by
//!   Pearson's chi-square test, bins expecting fewer than 5 samples pooled as in Mitsuba's
//!   `ChiSquareTest`, at the significance [`ContractConfig::significance`] Šidák-corrected over
//!   the reference points. Each sample's density equals `pdf_toward` of its direction, its
//!   point is the nearest crossing of that direction, and `pdf_toward` is 0 for directions
//!   that miss the shape and positive for those that hit it.

use std::f64::consts::{PI, TAU};
use std::ops::ControlFlow;

use glam::{DAffine3, DQuat, DVec2, DVec3};

use crate::{Aabb, Ray, Shape, for_each_crossing};

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
    /// Random lines for the Cauchy–Crofton estimate of an emitter's area.
    pub crofton_lines: usize,
    /// Directions drawn with [`Shape::sample_toward`] per reference point for the chi-square test.
    pub direction_samples: usize,
    /// Overall significance of the chi-square tests of one [`check_sampling_toward`] call
    /// (Šidák-corrected over its reference points): the chance that a correct shape fails.
    pub significance: f64,
    /// Largest fraction of [`Shape::sample_toward`] calls that may give no sample. A plain
    /// shape gives one nearly always; Prism's CSG groups sample their members' whole surfaces
    /// and give none where the ray through the point misses the group.
    pub max_unsampled_fraction: f64,
}

impl Default for ContractConfig {
    fn default() -> Self {
        Self {
            rays: 20_000,
            seed: 0x5EED_CAFE,
            tolerance: 1e-6,
            max_flip_fraction: 0.002,
            crofton_lines: 100_000,
            direction_samples: 32_768,
            significance: 1e-3,
            max_unsampled_fraction: 0.01,
        }
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
    let (mut unchanged_inside, mut has_inside, mut crossed) = (0usize, false, 0usize);
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
        let tangent = surface.dpdu.try_normalize();
        assert!(
            tangent.is_some_and(|t| t.dot(surface.normal).abs() < 1e-6),
            "dpdu {} is not a finite non-zero tangent perpendicular to the normal {} at {} for {ray:?}",
            surface.dpdu,
            surface.normal,
            surface.point
        );
        let geometry = shape.surface_geometry(&ray, &hit);
        assert!(
            (geometry.point, geometry.normal, geometry.shading_normal, geometry.dpdu)
                == (surface.point, surface.normal, surface.shading_normal, surface.dpdu),
            "surface_geometry() {geometry:?} differs from surface() {surface:?} in point, normals or dpdu for {ray:?}"
        );
        let point = shape.hit_point(&ray, &hit);
        assert!(
            point == surface.point_and_normals(),
            "hit_point() {point:?} differs from surface() {surface:?} in point or normals for {ray:?}"
        );

        // A hull holding the segment up to the hit must not be missed.
        let reached = ray.at(hit.t + tol);
        assert!(
            !shape.misses_hull(&[ray.origin, reached]),
            "misses_hull() claims the segment from {} to {reached} misses, but {ray:?} hits at t = {}",
            ray.origin,
            hit.t
        );

        // Every crossing goes in or out of the solid; `crossings` lists them in order, the
        // first being `intersect`'s hit.
        let step = 1e-7 * scale / ray.direction.length();
        let mut previous: Option<f64> = None;
        shape.crossings(&ray, t_min, t_max, &mut |crossing| {
            assert!(
                crossing.t > t_min && crossing.t < t_max && previous.is_none_or(|p| crossing.t >= p),
                "crossings() gave t = {} after {previous:?}, outside ({t_min}, {t_max}) or out of order, for {ray:?}",
                crossing.t
            );
            if previous.is_none() {
                assert_eq!(crossing.t, hit.t, "the first of crossings() is not intersect()'s hit for {ray:?}");
            }
            previous = Some(crossing.t);
            let (before, after) = (shape.inside(ray.at(crossing.t - step)), shape.inside(ray.at(crossing.t + step)));
            has_inside |= before || after;
            crossed += 1;
            if before == after {
                unchanged_inside += 1;
            }
            ControlFlow::Continue(())
        });

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
    let allowed_unchanged = (config.max_flip_fraction * crossed.max(config.rays) as f64).ceil() as usize;
    assert!(
        !has_inside || unchanged_inside <= allowed_unchanged,
        "inside() did not change across {unchanged_inside} of {crossed} surface crossings (allowed {allowed_unchanged})"
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
    }
    if shape.can_emit() {
        check_area_sampling(shape, config);
        let references = reference_points(shape, &mut rng);
        check_sampling_toward(shape, &references, config);
    }
}

/// The sphere around the shape's bounds: centre and radius.
fn bounding_sphere(shape: &dyn Shape) -> (DVec3, f64) {
    let b = shape.bounds();
    (b.center(), 0.5 * (b.max - b.min).length())
}

/// The largest extent of the shape's bounds.
fn shape_size(shape: &dyn Shape) -> f64 {
    let b = shape.bounds();
    (b.max - b.min).max_element()
}

/// How many standard errors the Cauchy–Crofton estimates may be off.
const CROFTON_SIGMAS: f64 = 5.0;

/// Fraction of samples allowed to fail a per-sample check: a sample on a silhouette or an
/// edge meets the shape or misses it by rounding.
const SAMPLE_FAILURE_FRACTION: f64 = 1e-3;

/// Checks a shape's area sampling: samples on the surface with the normal found there, their
/// density [`Shape::pdf_area`], `area()` against a Cauchy–Crofton estimate and the integral
/// of `pdf_area` against 1. Panics with a description of the first violation.
pub fn check_area_sampling(shape: &dyn Shape, config: &ContractConfig) {
    let mut rng = TestRng::new(config.seed ^ 0xA5EA);
    let bounds = shape.bounds();
    assert!(bounds.is_bounded(), "a shape that can emit must be bounded, got {bounds:?}");
    let size = shape_size(shape);
    let tol = config.tolerance * size;

    // Samples lie on the surface: a probe from just outside along the normal meets it there.
    let count = 4096;
    let (mut missing, mut off) = (0usize, Vec::new());
    let probe = 1e-4 * size;
    for _ in 0..count {
        let u = DVec2::new(rng.uniform(), rng.uniform());
        let Some(sample) = shape.sample_area(u) else {
            missing += 1;
            continue;
        };
        assert!((sample.normal.length() - 1.0).abs() < 1e-9, "sampled normal {} not unit", sample.normal);
        assert!(bounds.contains(sample.point, tol), "sampled point {} outside bounds {bounds:?}", sample.point);
        let pdf = shape.pdf_area(sample.point);
        assert!(
            sample.pdf_area.is_finite() && sample.pdf_area > 0.0 && (sample.pdf_area - pdf).abs() <= 1e-9 * pdf,
            "sample_area's pdf_area {} at {} differs from pdf_area() = {pdf}",
            sample.pdf_area,
            sample.point
        );
        let ray = Ray::new(sample.point + sample.normal * probe, -sample.normal);
        let found = shape.intersect(&ray, 0.0, 2.0 * probe).map(|hit| (hit.t, shape.surface_geometry(&ray, &hit)));
        let on_surface = found
            .is_some_and(|(t, surface)| (t - probe).abs() <= tol && surface.normal.dot(sample.normal) >= 1.0 - 1e-6);
        if !on_surface {
            off.push((sample, found));
        }
    }
    assert!(missing <= count / 100, "sample_area() returned None for {missing} of {count} samples");
    let allowed = (SAMPLE_FAILURE_FRACTION * count as f64).ceil() as usize;
    assert!(
        off.len() <= allowed,
        "{} of {count} area samples are not on the surface with their normal (a probe along the normal \
         from {probe} outside did not meet the surface there with that normal); first: {:?}",
        off.len(),
        off.first()
    );

    // Cauchy–Crofton: E[crossings] = area / (2 pi R^2) for isotropic uniform lines.
    let (center, radius) = bounding_sphere(shape);
    let lines = config.crofton_lines.max(1);
    let (mut n1, mut n2, mut p1, mut p2) = (0.0, 0.0, 0.0, 0.0);
    for _ in 0..lines {
        let direction = rng.unit_vector();
        let (a, b) = crate::math::orthonormal_basis(direction);
        let (r, phi) = (radius * rng.uniform().sqrt(), rng.range(0.0, TAU));
        let through = center + a * (r * phi.cos()) + b * (r * phi.sin());
        let ray = Ray::new(through - direction * (2.0 * radius), direction);
        let (mut crossings, mut density) = (0.0, 0.0);
        for_each_crossing(shape, &ray, |_, surface| {
            crossings += 1.0;
            density += shape.pdf_area(surface.point);
        });
        (n1, n2, p1, p2) = (n1 + crossings, n2 + crossings * crossings, p1 + density, p2 + density * density);
    }
    let m = lines as f64;
    let scale = TAU * radius * radius;
    let estimate = |sum: f64, squares: f64| {
        let mean = sum / m;
        let error = ((squares / m - mean * mean).max(0.0) / m).sqrt();
        (scale * mean, scale * error)
    };
    let (area_estimate, area_error) = estimate(n1, n2);
    if let Some(area) = shape.area() {
        assert!(
            (area - area_estimate).abs() <= CROFTON_SIGMAS * area_error + 1e-9 * area,
            "area() = {area}, but {lines} Cauchy-Crofton lines estimate {area_estimate} +- {area_error}"
        );
    }
    let (integral, integral_error) = estimate(p1, p2);
    assert!(
        (integral - 1.0).abs() <= CROFTON_SIGMAS * integral_error + 1e-9,
        "pdf_area integrates to {integral} +- {integral_error} over the surface (estimated by {lines} \
         Cauchy-Crofton lines; the area is {area_estimate} +- {area_error}), not to 1"
    );
}

/// The default reference points for [`check_sampling_toward`]: far from the shape, just
/// outside its bounding sphere, a random point near or within its bounds that is not inside
/// it, and a point inside it when it has an inside.
fn reference_points(shape: &dyn Shape, rng: &mut TestRng) -> Vec<DVec3> {
    let (center, radius) = bounding_sphere(shape);
    let bounds = shape.bounds();
    let pad = DVec3::splat(0.25 * shape_size(shape));
    let padded = Aabb::from_corners(bounds.min - pad, bounds.max + pad);
    let mut references = vec![center + rng.unit_vector() * (4.0 * radius), center + rng.unit_vector() * (1.2 * radius)];
    if let Some(beside) = (0..1000).map(|_| rng.point_in(&padded)).find(|&p| !shape.inside(p)) {
        references.push(beside);
    }
    if let Some(inside) = (0..1000).map(|_| rng.point_in(&bounds)).find(|&p| shape.inside(p)) {
        references.push(inside);
    }
    references
}

/// Bins over the directions from a reference: `Z_BINS` rings of equal solid angle (uniform
/// in the cosine to the axis) times `PHI_BINS` sectors.
const Z_BINS: usize = 16;
const PHI_BINS: usize = 32;

/// Bins expecting fewer samples than this are pooled into one (as in Mitsuba).
const MIN_EXPECTED: f64 = 5.0;

/// Directions from a reference binned over the cone around the bounding sphere.
struct DirectionBins {
    axis: DVec3,
    x: DVec3,
    y: DVec3,
    /// The cosine at the rim of the cone (-1: the whole sphere).
    z_min: f64,
}

impl DirectionBins {
    fn new(reference: DVec3, center: DVec3, radius: f64) -> Self {
        let to_center = center - reference;
        let distance = to_center.length();
        let axis = if distance > 1e-9 * radius { to_center / distance } else { DVec3::Y };
        let (x, y) = crate::math::orthonormal_basis(axis);
        let z_min = if distance > radius * (1.0 + 1e-6) { (1.0 - (radius / distance).powi(2)).sqrt() } else { -1.0 };
        Self { axis, x, y, z_min }
    }

    /// The direction at cosine `z` and angle `phi` around the axis.
    fn direction(&self, z: f64, phi: f64) -> DVec3 {
        let r = (1.0 - z * z).max(0.0).sqrt();
        self.axis * z + self.x * (r * phi.cos()) + self.y * (r * phi.sin())
    }

    /// The (cosine, angle) of a unit direction, or `None` outside the cone.
    fn coordinates(&self, d: DVec3) -> Option<(f64, f64)> {
        let z = d.dot(self.axis);
        (z >= self.z_min - 1e-9).then(|| (z.clamp(self.z_min, 1.0), d.dot(self.y).atan2(d.dot(self.x)).rem_euclid(TAU)))
    }

    fn bin(&self, (z, phi): (f64, f64)) -> usize {
        let iz = (((z - self.z_min) / (1.0 - self.z_min) * Z_BINS as f64) as usize).min(Z_BINS - 1);
        let iphi = ((phi / TAU * PHI_BINS as f64) as usize).min(PHI_BINS - 1);
        iz * PHI_BINS + iphi
    }

    /// The (z0, z1, phi0, phi1) of a bin.
    fn cell(&self, bin: usize) -> [f64; 4] {
        let (iz, iphi) = (bin / PHI_BINS, bin % PHI_BINS);
        let dz = (1.0 - self.z_min) / Z_BINS as f64;
        let dphi = TAU / PHI_BINS as f64;
        [self.z_min + iz as f64 * dz, self.z_min + (iz + 1) as f64 * dz, iphi as f64 * dphi, (iphi + 1) as f64 * dphi]
    }
}

/// The three-point Gauss–Legendre rule on a cell [z0, z1] x [phi0, phi1], with the smallest
/// and largest value of `f` at its nodes.
fn gauss_3x3(f: &mut impl FnMut(f64, f64) -> f64, [z0, z1, p0, p1]: [f64; 4]) -> (f64, f64, f64) {
    let (zm, zh, pm, ph) = (0.5 * (z0 + z1), 0.5 * (z1 - z0), 0.5 * (p0 + p1), 0.5 * (p1 - p0));
    let node = 0.6f64.sqrt();
    let (nodes, weights) = ([-node, 0.0, node], [5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0]);
    let (mut sum, mut min, mut max) = (0.0, f64::INFINITY, f64::NEG_INFINITY);
    for (a, wa) in nodes.iter().zip(weights) {
        for (b, wb) in nodes.iter().zip(weights) {
            let value = f(zm + a * zh, pm + b * ph);
            (min, max) = (min.min(value), max.max(value));
            sum += wa * wb * value;
        }
    }
    (sum * zh * ph, min, max)
}

fn quarters([z0, z1, p0, p1]: [f64; 4]) -> [[f64; 4]; 4] {
    let (zm, pm) = (0.5 * (z0 + z1), 0.5 * (p0 + p1));
    [[z0, zm, p0, pm], [zm, z1, p0, pm], [z0, zm, pm, p1], [zm, z1, pm, p1]]
}

/// A bin whose density varies more than this factor between its nodes is rough: a smooth
/// density varies little across a bin, and a larger spread betrays a band of grazing
/// directions or a singularity that the nodes only touch.
const SMOOTH_RATIO: f64 = 4.0;

/// What the quadrature makes of a bin.
#[derive(Clone, Copy, Debug, PartialEq)]
enum BinIntegral {
    /// The density is 0 at every node.
    Zero,
    /// Positive at every node (corners and the middles of the sides included) and within a
    /// factor [`SMOOTH_RATIO`] there, within that range at the samples, and the rule on the
    /// whole bin agrees with the rule on its quarters to `tolerance`: smooth, and its
    /// integral is this (the quarters' estimate, far more accurate than the agreement for an
    /// analytic integrand).
    Smooth(f64),
    /// A silhouette, an edge or a singularity runs through it: no estimate is trusted.
    Rough,
}

/// Integrates `f` over `cell` with the three-point Gauss–Legendre rule on its quarters, and
/// says whether that can be trusted (see [`BinIntegral`]). `sampled` is the range of the
/// density at the samples that fell in the bin: the samples crowd where the density is
/// high, so one far above (or below) every node betrays a narrow feature between the nodes
/// (a grazing band, a slit seen edge-on), and the bin is rough.
fn integrate_bin(
    f: &mut impl FnMut(f64, f64) -> f64,
    cell: [f64; 4],
    tolerance: f64,
    sampled: (f64, f64),
) -> BinIntegral {
    let (whole, mut min, mut max) = gauss_3x3(f, cell);
    // The corners and the middles of the sides: a silhouette or a hole that only grazes the
    // bin, between the interior nodes, shows there.
    let [z0, z1, p0, p1] = cell;
    for z in [z0, 0.5 * (z0 + z1), z1] {
        for p in [p0, 0.5 * (p0 + p1), p1] {
            let value = f(z, p);
            (min, max) = (min.min(value), max.max(value));
        }
    }
    // Nothing here, or too uneven to be smooth, whatever the quarters say.
    if max == 0.0 {
        return BinIntegral::Zero;
    }
    if !(min > 0.0 && max <= SMOOTH_RATIO * min) {
        return BinIntegral::Rough;
    }
    let mut fine = 0.0;
    for q in quarters(cell) {
        let (value, lo, hi) = gauss_3x3(f, q);
        (fine, min, max) = (fine + value, min.min(lo), max.max(hi));
    }
    if max == 0.0 {
        BinIntegral::Zero
    } else if min > 0.0
        && max <= SMOOTH_RATIO * min
        && (fine - whole).abs() <= tolerance
        && sampled.0 >= 0.5 * min
        && sampled.1 <= 2.0 * max
    {
        BinIntegral::Smooth(fine)
    } else {
        BinIntegral::Rough
    }
}

/// ln Gamma(x) for x > 0 (Lanczos, g = 7, n = 9).
fn ln_gamma(x: f64) -> f64 {
    const C: [f64; 9] = [
        0.999_999_999_999_809_9,
        676.520_368_121_885_1,
        -1_259.139_216_722_402_8,
        771.323_428_777_653_1,
        -176.615_029_162_140_6,
        12.507_343_278_686_905,
        -0.138_571_095_265_720_12,
        9.984_369_578_019_572e-6,
        1.505_632_735_149_311_6e-7,
    ];
    if x < 0.5 {
        return (PI / (PI * x).sin()).ln() - ln_gamma(1.0 - x);
    }
    let x = x - 1.0;
    let t = x + 7.5;
    let sum = C[0] + (1..9).map(|i| C[i] / (x + i as f64)).sum::<f64>();
    0.5 * TAU.ln() + (x + 0.5) * t.ln() - t + sum.ln()
}

/// The p-value of Pearson's chi-square statistic `statistic` with `dof` degrees of freedom:
/// the chance that a correct sampler gives a statistic at least this large, `Q(dof/2,
/// statistic/2)`. Public so that Prism's own sampling tests (environment maps, light
/// selection) share this one implementation.
pub fn chi_square_p_value(statistic: f64, dof: usize) -> f64 {
    gamma_q(0.5 * dof as f64, 0.5 * statistic)
}

/// The regularised upper incomplete gamma function Q(a, x) (series below a + 1, Lentz's
/// continued fraction above).
fn gamma_q(a: f64, x: f64) -> f64 {
    if x <= 0.0 {
        return 1.0;
    }
    let prefix = (a * x.ln() - x - ln_gamma(a)).exp();
    if x < a + 1.0 {
        let (mut term, mut sum, mut n) = (1.0 / a, 1.0 / a, a);
        for _ in 0..100_000 {
            n += 1.0;
            term *= x / n;
            sum += term;
            if term.abs() < sum.abs() * 1e-16 {
                break;
            }
        }
        (1.0 - sum * prefix).max(0.0)
    } else {
        let tiny = 1e-300;
        let mut b = x + 1.0 - a;
        let mut c = 1.0 / tiny;
        let mut d = 1.0 / b;
        let mut h = d;
        for i in 1..100_000 {
            let an = -(i as f64) * (i as f64 - a);
            b += 2.0;
            d = an * d + b;
            if d.abs() < tiny {
                d = tiny;
            }
            c = b + an / c;
            if c.abs() < tiny {
                c = tiny;
            }
            d = 1.0 / d;
            let step = d * c;
            h *= step;
            if (step - 1.0).abs() < 1e-16 {
                break;
            }
        }
        (prefix * h).min(1.0)
    }
}

/// Pearson's chi-square statistic and degrees of freedom for `observed` against `expected`
/// counts over the bins with an expectation, bins expecting fewer than [`MIN_EXPECTED`]
/// pooled into one, plus one more cell: the `rest`, observed and expected, of what those
/// bins hold. `Err` with the observed count when samples fell where nothing is expected.
fn chi_square(observed: &[f64], expected: &[f64], rest: (f64, f64)) -> Result<(f64, usize), f64> {
    let mut order: Vec<usize> = (0..observed.len()).collect();
    order.sort_by(|&a, &b| expected[a].total_cmp(&expected[b]));
    let (mut statistic, mut cells) = (0.0, 0usize);
    let mut cell = |o: f64, e: f64| {
        if e > 0.0 {
            statistic += (o - e) * (o - e) / e;
            cells += 1;
            Ok(())
        } else if o > 0.0 {
            Err(o)
        } else {
            Ok(())
        }
    };
    let (mut pooled_observed, mut pooled_expected) = (0.0, 0.0);
    for &i in &order {
        if expected[i] < MIN_EXPECTED {
            pooled_observed += observed[i];
            pooled_expected += expected[i];
        } else {
            cell(observed[i], expected[i])?;
        }
    }
    // The rest's expectation is a difference, which rounding may leave at 0 or below.
    let floor = 1e-9;
    if rest.1 < MIN_EXPECTED {
        cell(pooled_observed + rest.0, (pooled_expected + rest.1).max(floor))?;
    } else {
        cell(pooled_observed, pooled_expected)?;
        cell(rest.0, rest.1)?;
    }
    Ok((statistic, cells.saturating_sub(1).max(1)))
}

/// Checks [`Shape::sample_toward`] and [`Shape::pdf_toward`] from each of `references`
/// (object-space points off the surface): a chi-square test of the sampled directions
/// against the density, and per sample that its density is `pdf_toward` of its direction
/// and its point the nearest crossing; and that `pdf_toward` is 0 exactly for directions
/// that miss the shape. Panics with a description of the first violation. Plugins add their
/// hard cases with it (the torus's hole, the axis of an open tube); [`check_shape`] calls it
/// with a few references of its own.
pub fn check_sampling_toward(shape: &dyn Shape, references: &[DVec3], config: &ContractConfig) {
    let alpha = 1.0 - (1.0 - config.significance).powf(1.0 / references.len().max(1) as f64);
    // One stream per reference, seeded from the configuration's stream.
    let mut seeds = TestRng::new(config.seed ^ 0xD1EC);
    for &reference in references {
        let mut rng = TestRng::new(seeds.next_u64());
        check_directions_from(shape, reference, config, alpha, &mut rng);
    }
}

fn check_directions_from(shape: &dyn Shape, reference: DVec3, config: &ContractConfig, alpha: f64, rng: &mut TestRng) {
    let (center, radius) = bounding_sphere(shape);
    let size = shape_size(shape);
    let bins = DirectionBins::new(reference, center, radius);
    let n = config.direction_samples.max(1);
    let mut observed = vec![0.0_f64; Z_BINS * PHI_BINS];
    // The smallest and largest density of the samples in each bin.
    let mut sampled_range = vec![(f64::INFINITY, 0.0_f64); Z_BINS * PHI_BINS];
    let (mut none, mut mismatched, mut hidden, mut outside) = (0usize, Vec::new(), Vec::new(), 0usize);
    for i in 0..n {
        let u = DVec2::new(rng.uniform(), rng.uniform());
        let Some(sample) = shape.sample_toward(reference, u) else {
            none += 1;
            continue;
        };
        let to_point = sample.point - reference;
        assert!(
            sample.pdf_solid_angle.is_finite() && sample.pdf_solid_angle > 0.0 && to_point.length() > 0.0,
            "sample_toward({reference}) gave {sample:?}: the density must be positive and finite, the point off the reference"
        );
        assert!((sample.normal.length() - 1.0).abs() < 1e-9, "sample_toward's normal {} is not unit", sample.normal);
        let Some(coordinates) = bins.coordinates(to_point.normalize()) else {
            outside += 1;
            continue;
        };
        let bin = bins.bin(coordinates);
        observed[bin] += 1.0;
        let (lo, hi) = &mut sampled_range[bin];
        (*lo, *hi) = (lo.min(sample.pdf_solid_angle), hi.max(sample.pdf_solid_angle));
        // The per-sample checks cost intersections: every eighth sample is enough.
        if i % 8 != 0 {
            continue;
        }
        let pdf = shape.pdf_toward(reference, to_point);
        if (pdf - sample.pdf_solid_angle).abs() > 1e-6 * sample.pdf_solid_angle {
            mismatched.push((sample, pdf));
        }
        let ray = Ray::new(reference, to_point);
        let nearest = shape.intersect(&ray, 0.0, f64::INFINITY).map(|hit| shape.surface_geometry(&ray, &hit).point);
        if nearest.is_none_or(|p| p.distance(sample.point) > config.tolerance * size) {
            hidden.push((sample, nearest));
        }
    }
    let checked = n.div_ceil(8);
    let allowed = (SAMPLE_FAILURE_FRACTION * checked as f64).ceil() as usize;
    assert!(
        none as f64 <= config.max_unsampled_fraction * n as f64,
        "sample_toward({reference}) returned None for {none} of {n} samples"
    );
    assert!(outside == 0, "{outside} directions sampled from {reference} point outside the shape's bounding sphere");
    assert!(
        mismatched.len() <= allowed,
        "from {reference}, {} of {checked} sampled densities differ from pdf_toward() of their direction; first \
         (sample, pdf_toward): {:?}",
        mismatched.len(),
        mismatched.first()
    );
    assert!(
        hidden.len() <= allowed,
        "from {reference}, {} of {checked} sampled points are not the nearest crossing of their direction; first \
         (sample, nearest): {:?}",
        hidden.len(),
        hidden.first()
    );

    // pdf_toward is 0 for directions that miss, positive for those that hit.
    let mut wrong = Vec::new();
    let probes = 2048;
    for i in 0..probes {
        let direction = if i % 2 == 0 || bins.z_min <= -1.0 {
            rng.unit_vector()
        } else {
            bins.direction(rng.range(bins.z_min, 1.0), rng.range(0.0, TAU))
        };
        let hits = shape.intersect(&Ray::new(reference, direction), 0.0, f64::INFINITY).is_some();
        let pdf = shape.pdf_toward(reference, direction * rng.range(0.1, 10.0));
        if hits != (pdf > 0.0) || !pdf.is_finite() {
            wrong.push((direction, hits, pdf));
        }
    }
    assert!(
        wrong.len() <= (SAMPLE_FAILURE_FRACTION * probes as f64).ceil() as usize,
        "from {reference}, pdf_toward() is not 0 exactly for the directions that miss the shape in {} of {probes} \
         directions; first (direction, hits, pdf_toward): {:?}",
        wrong.len(),
        wrong.first()
    );

    // Expected counts: pdf_toward integrated over each bin where it is smooth. The bins a
    // silhouette, an edge or a curved silhouette's integrable singularity runs through
    // cannot be integrated reliably by a fixed rule; they are pooled into one cell, the rest,
    // whose expectation is what the smooth bins leave of the total: under the hypothesis
    // that the samples follow the normalised density pdf_toward, that is exact.
    let mut f = |z: f64, phi: f64| shape.pdf_toward(reference, bins.direction(z, phi));
    let scale = n as f64;
    let (mut expected, mut rest, mut smooth_bins) = (vec![0.0; observed.len()], (none as f64, scale), 0usize);
    let mut kept = vec![0.0; observed.len()];
    for bin in 0..observed.len() {
        let tolerance = (0.1 * observed[bin].max(1.0).sqrt() / scale).max(0.0);
        match integrate_bin(&mut f, bins.cell(bin), tolerance, sampled_range[bin]) {
            BinIntegral::Smooth(value) => {
                (expected[bin], kept[bin]) = (value * scale, observed[bin]);
                rest.1 -= value * scale;
                smooth_bins += 1;
            }
            BinIntegral::Zero if observed[bin] == 0.0 => {}
            BinIntegral::Zero | BinIntegral::Rough => rest.0 += observed[bin],
        }
    }
    rest.1 = rest.1.max(0.0);
    let (statistic, dof) = match chi_square(&kept, &expected, rest) {
        Ok(result) => result,
        Err(lost) => panic!("from {reference}, {lost} of {n} sampled directions fell where pdf_toward() is 0"),
    };
    let p_value = gamma_q(0.5 * dof as f64, 0.5 * statistic);
    assert!(
        p_value >= alpha,
        "chi-square test of sample_toward() against pdf_toward() from {reference} fails: statistic {statistic:.1} with \
         {dof} degrees of freedom, p = {p_value:.3e} < {alpha:.3e}; {smooth_bins} smooth bins expect {:.1} and hold \
         {:.0} of {n} samples (the rest: {:.1} expected, {:.0} observed){}",
        scale - rest.1,
        scale - rest.0,
        rest.1,
        rest.0,
        worst_bins(&kept, &expected)
    );
}

/// The bins that contribute most to the chi-square statistic, for the failure message.
fn worst_bins(observed: &[f64], expected: &[f64]) -> String {
    let mut bins: Vec<usize> = (0..observed.len()).collect();
    let score = |i: usize| (observed[i] - expected[i]).powi(2) / expected[i].max(1.0);
    bins.sort_by(|&a, &b| score(b).total_cmp(&score(a)));
    let list: Vec<String> = bins
        .iter()
        .take(5)
        .map(|&i| {
            format!(
                "ring {} sector {}: {} observed, {:.1} expected",
                i / PHI_BINS,
                i % PHI_BINS,
                observed[i],
                expected[i]
            )
        })
        .collect();
    format!("; worst bins: {}", list.join("; "))
}

/// Checks that `intersect`'s `t` range is open at both ends on a ray from `origin` along
/// `toward` that enters a closed shape at `t_enter` and leaves it at `t_exit` (both exact):
/// the reversed ray misses, `t_max = t_enter` finds nothing, `t_min = t_enter` finds the exit
/// and `t_min = t_exit` nothing. Returns the exit hit for further checks.
pub fn check_t_range(shape: &dyn Shape, origin: DVec3, toward: DVec3, t_enter: f64, t_exit: f64) -> crate::Hit {
    let away = Ray::new(origin, -toward);
    assert!(shape.intersect(&away, 1e-9, f64::INFINITY).is_none(), "a ray pointing away hit");
    let ray = Ray::new(origin, toward);
    assert!(shape.intersect(&ray, 1e-9, t_enter).is_none(), "t_max is exclusive");
    let exit = shape.intersect(&ray, t_enter, f64::INFINITY).expect("t_min is exclusive: the exit is hit");
    assert!((exit.t - t_exit).abs() <= 1e-12 * t_exit.abs().max(1.0), "exit at t = {}, not {t_exit}", exit.t);
    assert!(shape.intersect(&ray, t_exit, f64::INFINITY).is_none(), "nothing lies beyond the exit");
    exit
}

/// Checks that a shape's own [`Shape::crossings`] lists exactly what the trait's default,
/// [`crate::crossings_by_intersect`], lists (the same `t` and `part`, in the same order), for
/// a shape that overrides it only to find its crossings faster: 40,000 rays from around the
/// bounds, half aimed into them, some along an axis, some starting past the first crossing
/// (a random `t_min`) or stopping early (a finite `t_max`).
pub fn check_crossings_match_intersect(shape: &dyn Shape) {
    fn listed(each: impl FnOnce(&mut dyn FnMut(&crate::Hit) -> ControlFlow<()>)) -> Vec<(f64, u32)> {
        let mut hits = Vec::new();
        each(&mut |hit| {
            hits.push((hit.t, hit.part));
            ControlFlow::Continue(())
        });
        hits
    }
    let mut rng = TestRng::new(0xC055);
    let bounds = shape.bounds();
    let size = bounds.max - bounds.min;
    let around = Aabb { min: bounds.min - size, max: bounds.max + size };
    for i in 0..40_000 {
        let origin = rng.point_in(&around);
        let mut direction = if i % 2 == 0 { rng.point_in(&bounds) - origin } else { rng.unit_vector() };
        if i % 7 == 0 {
            direction = DVec3::X * direction.x.signum();
        }
        let ray = Ray::new(origin, direction * rng.range(0.5, 3.0));
        let t_min = if i % 3 == 0 { rng.range(-1.0, 1.0) } else { 0.0 };
        let t_max = if i % 5 == 0 { rng.range(0.0, 2.0) } else { f64::INFINITY };
        let own = listed(|visit| shape.crossings(&ray, t_min, t_max, visit));
        let default = listed(|visit| crate::crossings_by_intersect(shape, &ray, t_min, t_max, visit));
        assert_eq!(own, default, "crossings() against the default for {ray:?} in ({t_min}, {t_max})");
    }
}

/// Checks that each hit's `dpdu` is the derivative of the uv: for hits whose neighbours (rays
/// moved sideways by a millionth of the shape's size) land on the same part with a
/// well-conditioned change of uv, ∂p/∂u from the finite differences must match `dpdu` to
/// 1e-3 relative, for all but 1% of them (seams, poles and edges). Call it for shapes whose
/// `dpdu` follows their uv (every shape with a real uv parameterisation).
pub fn check_dpdu(shape: &dyn Shape) {
    let mut rng = TestRng::new(0xD9D0);
    let region = target_region(shape);
    let h = 1e-6 * (region.max - region.min).max_element();
    let (mut compared, mut wrong) = (0usize, Vec::new());
    for _ in 0..20_000 {
        let ray = random_ray(&mut rng, &region);
        let Some(hit) = shape.intersect(&ray, 1e-9, f64::INFINITY) else { continue };
        let surface = shape.surface(&ray, &hit);
        let (a, b) = crate::math::orthonormal_basis(ray.direction.normalize());
        let moved = |offset: DVec3| {
            let r = Ray::new(ray.origin + offset, ray.direction);
            shape.intersect(&r, 1e-9, f64::INFINITY).filter(|h| h.part == hit.part).map(|h| shape.surface(&r, &h))
        };
        let (Some(a1), Some(a0), Some(b1), Some(b0)) = (moved(a * h), moved(-a * h), moved(b * h), moved(-b * h))
        else {
            continue;
        };
        let (dpa, dpb, dua, dub) = (a1.point - a0.point, b1.point - b0.point, a1.uv - a0.uv, b1.uv - b0.uv);
        let det = dua.x * dub.y - dub.x * dua.y;
        let seam = dua.abs().max_element() > 0.25 || dub.abs().max_element() > 0.25;
        let conditioned = det.abs() > 1e-3 * dua.length() * dub.length();
        if seam || !conditioned {
            continue;
        }
        let estimate = (dpa * dub.y - dpb * dua.y) / det;
        compared += 1;
        if (estimate - surface.dpdu).length() > 1e-3 * estimate.length().max(surface.dpdu.length()) {
            wrong.push((surface.point, surface.uv, surface.dpdu, estimate));
        }
    }
    assert!(compared >= 100, "only {compared} hits had a usable uv neighbourhood: does the shape have a uv?");
    assert!(
        wrong.len() * 100 <= compared,
        "dpdu is not ∂p/∂u at {} of {compared} hits; first (point, uv, dpdu, finite difference): {:?}",
        wrong.len(),
        wrong.first()
    );
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

    /// A unit sphere sampled by area through the defaults, with deliberate mistakes.
    #[derive(Debug, Default)]
    struct AreaSphere {
        /// `area()` is this many times the true area (1: correct).
        area_factor: f64,
        /// Samples crowd toward +z (z = 1 - 2 u^2) while the density claims uniform.
        skewed: bool,
        /// Both directional functions count only the nearest crossing of a direction (the
        /// classic mistake for closed shapes): they agree with each other, not with the samples.
        nearest_only: bool,
    }

    impl AreaSphere {
        fn correct() -> Self {
            Self { area_factor: 1.0, ..Self::default() }
        }
    }

    impl Shape for AreaSphere {
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
            [t0, t1].into_iter().find(|&t| t > t_min && t < t_max).map(Hit::at)
        }
        fn surface(&self, ray: &Ray, hit: &Hit) -> crate::Surface {
            let n = ray.at(hit.t).normalize();
            crate::Surface::new(n, n, DVec2::ZERO)
        }
        fn inside(&self, point: DVec3) -> bool {
            point.length_squared() < 1.0
        }
        fn area(&self) -> Option<f64> {
            Some(4.0 * PI * self.area_factor)
        }
        fn sample_area(&self, u: DVec2) -> Option<crate::AreaSample> {
            let z = if self.skewed { 1.0 - 2.0 * u.x * u.x } else { 1.0 - 2.0 * u.x };
            let r = (1.0 - z * z).max(0.0).sqrt();
            let n = DVec3::new(r * (TAU * u.y).cos(), r * (TAU * u.y).sin(), z);
            Some(crate::AreaSample { point: n, normal: n, pdf_area: self.pdf_area(n) })
        }
        fn sample_toward(&self, reference: DVec3, u: DVec2) -> Option<crate::DirectionSample> {
            let sample = crate::sample_toward_by_area(self, reference, u)?;
            if !self.nearest_only {
                return Some(sample);
            }
            let pdf = self.pdf_toward(reference, sample.point - reference);
            Some(crate::DirectionSample { pdf_solid_angle: pdf, ..sample })
        }
        fn pdf_toward(&self, reference: DVec3, direction: DVec3) -> f64 {
            if !self.nearest_only {
                return crate::pdf_toward_by_area(self, reference, direction);
            }
            let ray = Ray::new(reference, direction);
            self.intersect(&ray, 0.0, f64::INFINITY).map_or(0.0, |hit| {
                let s = self.surface(&ray, &hit);
                crate::math::area_to_solid_angle(self.pdf_area(s.point), reference, s.point, s.normal)
            })
        }
    }

    /// Outside (once near, once far) and inside the sphere.
    fn sphere_references() -> [DVec3; 3] {
        [DVec3::new(0.0, 0.5, 2.0), DVec3::new(5.0, -3.0, 1.0), DVec3::new(0.2, 0.1, -0.3)]
    }

    #[test]
    fn correct_area_sampling_passes() {
        check_shape(&AreaSphere::correct());
        check_sampling_toward(&AreaSphere::correct(), &sphere_references(), &ContractConfig::default());
    }

    #[test]
    #[should_panic(expected = "Cauchy-Crofton")]
    fn twice_the_area_is_caught_by_the_area_estimate() {
        check_area_sampling(&AreaSphere { area_factor: 2.0, ..AreaSphere::default() }, &ContractConfig::default());
    }

    #[test]
    #[should_panic(expected = "chi-square")]
    fn twice_the_area_is_caught_by_the_chi_square_test() {
        let shape = AreaSphere { area_factor: 2.0, ..AreaSphere::default() };
        check_sampling_toward(&shape, &sphere_references(), &ContractConfig::default());
    }

    #[test]
    #[should_panic(expected = "Cauchy-Crofton")]
    fn an_area_off_by_two_percent_is_caught_by_the_area_estimate() {
        check_area_sampling(&AreaSphere { area_factor: 1.02, ..AreaSphere::default() }, &ContractConfig::default());
    }

    #[test]
    #[should_panic(expected = "chi-square")]
    fn an_area_off_by_five_percent_is_caught_by_the_chi_square_test() {
        let shape = AreaSphere { area_factor: 1.05, ..AreaSphere::default() };
        check_sampling_toward(&shape, &sphere_references()[..1], &ContractConfig::default());
    }

    #[test]
    #[should_panic(expected = "chi-square")]
    fn counting_only_the_nearest_crossing_is_caught() {
        let shape = AreaSphere { nearest_only: true, ..AreaSphere::correct() };
        check_sampling_toward(&shape, &sphere_references()[..1], &ContractConfig::default());
    }

    #[test]
    #[should_panic(expected = "chi-square")]
    fn samples_that_do_not_follow_the_density_are_caught() {
        let shape = AreaSphere { skewed: true, ..AreaSphere::correct() };
        // The Crofton estimate cannot see it (the claimed density integrates to 1); the
        // directions can.
        check_area_sampling(&shape, &ContractConfig::default());
        check_sampling_toward(&shape, &sphere_references()[..1], &ContractConfig::default());
    }

    #[test]
    fn chi_square_tail_matches_tables() {
        // Upper 5% and 1% points of the chi-square distribution.
        for (dof, x, p) in [(1.0, 3.841_459, 0.05), (10.0, 18.307_038, 0.05), (100.0, 135.806_723, 0.01)] {
            let q = gamma_q(0.5 * dof, 0.5 * x);
            assert!((q - p).abs() < 1e-6 * p.max(1e-3) * 10.0, "dof {dof}: Q = {q}, expected {p}");
        }
        assert!((gamma_q(250.0, 250.0) - 0.491_59).abs() < 1e-4, "{}", gamma_q(250.0, 250.0));
        assert!((ln_gamma(10.0) - 362_880f64.ln()).abs() < 1e-12);
    }

    #[test]
    fn bins_are_integrated_where_smooth_and_pooled_where_not() {
        // A smooth bump is integrated accurately; a step (a silhouette) or a jump inside the
        // bin is rough; nothing at all is zero.
        let mut bump = |z: f64, p: f64| (-(z * z + p * p) / 4.0).exp();
        // (integral of exp(-z^2 / 4) over [0, 1])^2 = (sqrt(pi) erf(1 / 2))^2.
        let exact = PI * 0.520_499_877_813_046_5f64.powi(2);
        match integrate_bin(&mut bump, [0.0, 1.0, 0.0, 1.0], 1e-4, (0.7, 0.9)) {
            BinIntegral::Smooth(value) => assert!((value - exact).abs() < 1e-7, "{value} vs {exact}"),
            other => panic!("{other:?}"),
        }
        let mut step = |z: f64, p: f64| if z * z + p * p < 0.09 { 1.0 } else { 0.0 };
        assert_eq!(integrate_bin(&mut step, [-0.5, 0.5, -0.5, 0.5], 1.0, NO_SAMPLES), BinIntegral::Rough);
        let mut jump = |z: f64, _: f64| if z < 0.3 { 1.0 } else { 2.0 };
        assert_eq!(integrate_bin(&mut jump, [0.0, 1.0, 0.0, 1.0], 1e-3, NO_SAMPLES), BinIntegral::Rough);
        // A narrow spike between the nodes, which a sample found.
        let mut spike = |z: f64, _: f64| 1.0 + 1e3 * (-((z - 0.4) / 1e-3).powi(2)).exp();
        assert!(matches!(integrate_bin(&mut spike, [0.0, 1.0, 0.0, 1.0], 1e-3, NO_SAMPLES), BinIntegral::Smooth(_)));
        assert_eq!(integrate_bin(&mut spike, [0.0, 1.0, 0.0, 1.0], 1e-3, (1.0, 900.0)), BinIntegral::Rough);
        assert_eq!(integrate_bin(&mut |_, _| 0.0, [0.0, 1.0, 0.0, 1.0], 1e-3, NO_SAMPLES), BinIntegral::Zero);
    }

    const NO_SAMPLES: (f64, f64) = (f64::INFINITY, 0.0);

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
