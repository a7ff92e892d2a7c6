//! The blob shape plugin: POV-Ray's metaballs with spherical components.
//!
//! Each component adds the field `strength * (1 - (d / radius)^2)^2` within `radius` of its
//! centre (d is the distance to the centre; the field is 0 farther away). The surface is
//! where the summed field equals `threshold`; the inside is where it is greater. Negative
//! strengths carve dents. This is POV-Ray's `blob { threshold T sphere { c, r, strength s } }`
//! exactly (verified against POV-Ray 3.7.0.10 renders: a single component of strength 1,
//! radius 1 and threshold 0.6 has radius sqrt(1 - sqrt(0.6)), and the threshold defaults to 1).
//!
//! Along a ray the field is a polynomial of degree four in t between consecutive points
//! where the ray enters or leaves a component's sphere, so each such piece is solved
//! exactly ([`prism_api::math::polynomial_roots`]), with the polynomial formed at the start
//! of its piece so that its coefficients stay well scaled.

#![forbid(unsafe_code)]

use std::cell::RefCell;
use std::f64::consts::{PI, TAU};
use std::ops::ControlFlow;
use std::sync::Arc;

use prism_api::math::visit_polynomial_roots;
use prism_api::{Aabb, DVec2, DVec3, Hit, HitPoint, ParamError, Ray, Shape, ShapeParams, Surface, math, pov};
use schemars::JsonSchema;
use serde::Deserialize;

/// Parameters of `shape = "blob"`.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct BlobParams {
    /// Field value on the surface (the field is greater inside); must be greater than 0.
    #[serde(default = "default_threshold")]
    pub threshold: f64,
    /// Spheres `{ center = [x, y, z], radius = r, strength = s }` (defaults origin, 1, 1); one needs s > 0.
    pub components: Vec<BlobComponent>,
}

/// One spherical component of a blob: `components = [{ center = [0, 0, 0], radius = 1, strength = 1 }]`.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct BlobComponent {
    /// Centre of the component in object space.
    #[serde(default)]
    pub center: [f64; 3],
    /// Radius of the component's field (the field is 0 from there on); must be greater than 0.
    #[serde(default = "default_one")]
    pub radius: f64,
    /// Field at the centre; negative values push the surface away. Must be finite.
    #[serde(default = "default_one")]
    pub strength: f64,
}

fn default_threshold() -> f64 {
    1.0
}

fn default_one() -> f64 {
    1.0
}

impl ShapeParams for BlobParams {
    fn build(self) -> Result<Arc<dyn Shape>, ParamError> {
        ParamError::require_positive("threshold", self.threshold)?;
        if self.components.is_empty() {
            return Err(ParamError::new("components", "must list at least one component"));
        }
        let mut components = Vec::with_capacity(self.components.len());
        for (i, c) in self.components.iter().enumerate() {
            ParamError::require_finite(&format!("components[{i}].center"), &c.center)?;
            ParamError::require_positive(&format!("components[{i}].radius"), c.radius)?;
            ParamError::require_finite(&format!("components[{i}].strength"), &[c.strength])?;
            components.push(Component::new(DVec3::from_array(c.center), c.radius, c.strength));
        }
        let positive: f64 = components.iter().map(|c| c.strength.max(0.0)).sum();
        if positive < self.threshold {
            return Err(ParamError::new(
                "threshold",
                format!(
                    "must not exceed the sum of the positive strengths ({positive}), got {}: the blob would be empty",
                    self.threshold
                ),
            ));
        }
        Ok(Arc::new(Blob::new(self.threshold, components)))
    }
}

/// A spherical blob component.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Component {
    /// Centre in object space.
    pub center: DVec3,
    /// Radius of influence (> 0).
    pub radius: f64,
    /// Field at the centre.
    pub strength: f64,
}

impl Component {
    /// A component (values not checked here; [`BlobParams`] validates).
    pub fn new(center: DVec3, radius: f64, strength: f64) -> Self {
        Self { center, radius, strength }
    }

    /// This component's field at `p`.
    pub fn field(&self, p: DVec3) -> f64 {
        let q = 1.0 - p.distance_squared(self.center) / (self.radius * self.radius);
        if q > 0.0 { self.strength * q * q } else { 0.0 }
    }
}

/// POV-Ray's blob with spherical components.
#[derive(Clone, Debug, PartialEq)]
pub struct Blob {
    /// Field value of the surface (> 0).
    pub threshold: f64,
    /// The components.
    pub components: Vec<Component>,
    bounds: Aabb,
}

thread_local! {
    /// Each thread's scratch lists for [`Blob::nearest_root`] (component spans, piece
    /// breaks), kept between rays instead of allocated for each.
    static SCRATCH: RefCell<(Vec<Span>, Vec<f64>)> = const { RefCell::new((Vec::new(), Vec::new())) };
}

/// Where a ray is inside one component's sphere, in distance along the unit direction.
#[derive(Clone, Copy, Debug)]
struct Span {
    enter: f64,
    exit: f64,
    component: usize,
}

/// True when the quartic with `coefficients` (constant first) certainly has no root in
/// `[lo, hi]`: on that interval in Bernstein form, all its coefficients have one sign and
/// clear the rounding of their computation (the polynomial lies within their hull). False
/// means nothing: the roots are then searched.
fn certainly_no_root(coefficients: &[f64; 5], lo: f64, hi: f64) -> bool {
    let h = hi - lo;
    // Power coefficients of q(x) = p(lo + h x), and the same sums over absolute values to
    // bound the rounding (a Taylor shift by lo, then a scaling by h).
    let (mut q, mut q_abs) = (*coefficients, coefficients.map(f64::abs));
    for i in 0..4 {
        for j in (i..4).rev() {
            q[j] += lo * q[j + 1];
            q_abs[j] += lo.abs() * q_abs[j + 1];
        }
    }
    let mut scale = 1.0;
    for (c, a) in q.iter_mut().zip(q_abs.iter_mut()) {
        *c *= scale;
        *a *= scale;
        scale *= h;
    }
    // Bernstein coefficients b_j = sum over i <= j of C(j, i) / C(4, i) q_i.
    const WEIGHTS: [[f64; 5]; 5] = [
        [1.0, 0.0, 0.0, 0.0, 0.0],
        [1.0, 0.25, 0.0, 0.0, 0.0],
        [1.0, 0.5, 1.0 / 6.0, 0.0, 0.0],
        [1.0, 0.75, 0.5, 0.25, 0.0],
        [1.0, 1.0, 1.0, 1.0, 1.0],
    ];
    let (mut positive, mut negative) = (true, true);
    for weights in &WEIGHTS {
        let (b, bound) = weights
            .iter()
            .zip(q.iter().zip(&q_abs))
            .fold((0.0, 0.0), |(b, bound), (w, (c, a))| (b + w * c, bound + w * a));
        let slack = 1e-12 * bound;
        positive &= b > slack;
        negative &= b < -slack;
    }
    (positive || negative) && q.iter().all(|c| c.is_finite())
}

impl Blob {
    /// A blob; its bounds are the union of the spheres of the components with positive
    /// strength (outside them the field is at most 0, below any threshold).
    pub fn new(threshold: f64, components: Vec<Component>) -> Self {
        let bounds = components
            .iter()
            .filter(|c| c.strength > 0.0)
            .fold(Aabb::EMPTY, |b, c| b.union(Aabb::from_corners(c.center - c.radius, c.center + c.radius)));
        Self { threshold, components, bounds }
    }

    /// The summed field at `p`.
    pub fn field(&self, p: DVec3) -> f64 {
        self.components.iter().map(|c| c.field(p)).sum()
    }

    /// The gradient of the summed field at `p` (points inwards, towards higher field).
    fn gradient(&self, p: DVec3) -> DVec3 {
        self.components
            .iter()
            .map(|c| {
                let r2 = c.radius * c.radius;
                let offset = p - c.center;
                let q = 1.0 - offset.length_squared() / r2;
                if q > 0.0 { offset * (-4.0 * c.strength * q / r2) } else { DVec3::ZERO }
            })
            .sum()
    }
}

impl Blob {
    /// The nearest root of the field in range along `ray` (direction of length `length`),
    /// from the bounds' entry `t_enter` over `span` (unit-direction length): the pieces
    /// between component boundaries in order, each a quartic. `spans` and `breaks` are
    /// scratch space.
    fn nearest_root(
        &self,
        ray: &Ray,
        (t_min, t_max): (f64, f64),
        (t_enter, span, length): (f64, f64, f64),
        spans: &mut Vec<Span>,
        breaks: &mut Vec<f64>,
    ) -> Option<Hit> {
        let dir = ray.direction / length;
        let o = ray.at(t_enter);
        spans.clear();
        breaks.clear();
        breaks.extend([0.0, span]);
        for (component, c) in self.components.iter().enumerate() {
            if c.strength == 0.0 {
                continue;
            }
            // Closest approach form of the sphere intersection (precise for grazing rays).
            let oc = o - c.center;
            let b = oc.dot(dir);
            let closest = oc - b * dir;
            let disc = c.radius * c.radius - closest.length_squared();
            if disc <= 0.0 {
                continue;
            }
            let half = disc.sqrt();
            let (enter, exit) = (-b - half, -b + half);
            if exit <= 0.0 || enter >= span {
                continue;
            }
            spans.push(Span { enter, exit, component });
            for u in [enter, exit] {
                if u > 0.0 && u < span {
                    breaks.push(u);
                }
            }
        }
        breaks.sort_by(f64::total_cmp);
        breaks.dedup();

        let margin = 1e-9 * span;
        for piece in breaks.windows(2) {
            let (s0, s1) = (piece[0], piece[1]);
            if s1 <= s0 {
                continue;
            }
            let mid = 0.5 * (s0 + s1);
            // The field as a quartic in w = u - s0, summed over the spheres covering the piece.
            let start = o + s0 * dir;
            let mut coefficients = [0.0; 5];
            let mut positive = false;
            for s in spans.iter().filter(|s| s.enter < mid && s.exit > mid) {
                let c = &self.components[s.component];
                positive |= c.strength > 0.0;
                let inv_r2 = 1.0 / (c.radius * c.radius);
                let v = start - c.center;
                // q(w) = 1 - |v + w dir|^2 / r^2 = a0 + a1 w + a2 w^2; the field is strength q^2.
                let a0 = 1.0 - v.length_squared() * inv_r2;
                let a1 = -2.0 * v.dot(dir) * inv_r2;
                let a2 = -inv_r2;
                let k = c.strength;
                coefficients[0] += k * a0 * a0;
                coefficients[1] += k * 2.0 * a0 * a1;
                coefficients[2] += k * (a1 * a1 + 2.0 * a0 * a2);
                coefficients[3] += k * 2.0 * a1 * a2;
                coefficients[4] += k * a2 * a2;
            }
            if !positive {
                continue;
            }
            coefficients[0] -= self.threshold;
            // The field and its slope are continuous across sphere boundaries, so a root on a
            // breakpoint is searched slightly beyond both ends of the piece: rounding cannot
            // then hide it between two pieces.
            if certainly_no_root(&coefficients, -margin, s1 - s0 + margin) {
                continue;
            }
            // Roots in ascending order until one lies in the range; farther ones are never
            // searched for.
            let mut nearest = None;
            let _ = visit_polynomial_roots(&coefficients, -margin, s1 - s0 + margin, &mut |w| {
                let t = t_enter + (s0 + w) / length;
                if t > t_min && t < t_max {
                    nearest = Some(Hit::at(t));
                    return ControlFlow::Break(());
                }
                ControlFlow::Continue(())
            });
            if nearest.is_some() {
                return nearest;
            }
        }
        None
    }
}

impl Shape for Blob {
    fn bounds(&self) -> Aabb {
        self.bounds
    }

    fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit> {
        let (t_enter, t_exit) = self.bounds.ray_interval(ray, t_min, t_max)?;
        let length = ray.direction.length();
        if !(length > 0.0 && length.is_finite() && t_enter.is_finite() && t_exit.is_finite()) {
            return None;
        }
        // Work from the bounds' entry along the unit direction: u = (t - t_enter) * length.
        let span = (t_exit - t_enter) * length;
        SCRATCH.with_borrow_mut(|(spans, breaks)| {
            self.nearest_root(ray, (t_min, t_max), (t_enter, span, length), spans, breaks)
        })
    }

    fn inside(&self, point: DVec3) -> bool {
        self.field(point) > self.threshold
    }

    fn surface(&self, ray: &Ray, hit: &Hit) -> Surface {
        let mut surface = self.surface_geometry(ray, hit);
        // No natural parameterisation: longitude/latitude of the direction from the centre of
        // the bounds, as on the sphere.
        let d = (surface.point - self.bounds.center()).normalize_or(DVec3::Y);
        let u = 0.5 + d.z.atan2(-d.x) / TAU;
        let v = 0.5 + d.y.clamp(-1.0, 1.0).asin() / PI;
        surface.uv = DVec2::new(u.rem_euclid(1.0), v);
        surface
    }

    fn surface_geometry(&self, ray: &Ray, hit: &Hit) -> Surface {
        let HitPoint { point, normal, .. } = self.hit_point(ray, hit);
        Surface::new(point, normal, DVec2::ZERO).with_dpdu(math::longitude_dpdu(point - self.bounds.center(), normal))
    }

    fn hit_point(&self, ray: &Ray, hit: &Hit) -> HitPoint {
        let point = ray.at(hit.t);
        let normal = (-self.gradient(point)).try_normalize().unwrap_or_else(|| (-ray.direction).normalize_or(DVec3::Y));
        HitPoint::new(point, normal)
    }

    /// No: a blob's surface is an iso-surface of a sum of fields with neither a closed-form
    /// area nor a parameterisation to sample uniformly, so it cannot be an area light.
    fn can_emit(&self) -> bool {
        false
    }

    fn to_pov(&self) -> Option<String> {
        let mut sdl = format!("blob {{\n  threshold {}\n", pov::number(self.threshold));
        for c in &self.components {
            sdl += &format!(
                "  sphere {{ {}, {}, strength {} }}\n",
                pov::vector(c.center),
                pov::number(c.radius),
                pov::number(c.strength)
            );
        }
        sdl.push('}');
        Some(sdl)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use prism_api::contract::{TestRng, check_dpdu, check_shape};
    use prism_api::math::polynomial_roots;

    #[test]
    fn a_piece_is_skipped_only_when_it_has_no_root() {
        // Random quartics, and quartics with a root placed near an end of the interval.
        let mut rng = TestRng::new(3);
        let (mut skipped, mut total) = (0, 0);
        for i in 0..200_000 {
            let (lo, hi) = (rng.range(-0.1, 0.0), rng.range(0.01, 3.0));
            let coefficients = if i % 2 == 0 {
                [0.0; 5].map(|_| rng.range(-2.0, 2.0))
            } else {
                // (w - r) times a random cubic, r just inside or outside [lo, hi].
                let r = if i % 4 == 1 { hi + rng.range(-1e-9, 1e-9) } else { lo + rng.range(-1e-9, 1e-9) };
                let c = [0.0; 4].map(|_| rng.range(-2.0, 2.0));
                [-r * c[0], c[0] - r * c[1], c[1] - r * c[2], c[2] - r * c[3], c[3]]
            };
            total += 1;
            if certainly_no_root(&coefficients, lo, hi) {
                skipped += 1;
                let roots = polynomial_roots(&coefficients, lo, hi);
                assert!(
                    roots.as_slice().is_empty(),
                    "{coefficients:?} on [{lo}, {hi}] has roots {:?}",
                    roots.as_slice()
                );
            }
        }
        assert!(skipped > total / 4, "only {skipped} of {total} pieces skipped");
    }

    fn single(threshold: f64) -> Blob {
        Blob::new(threshold, vec![Component::new(DVec3::ZERO, 1.0, 1.0)])
    }

    /// POV-Ray's documentation example: three components in a ring.
    fn trio() -> Blob {
        Blob::new(
            0.6,
            vec![
                Component::new(DVec3::new(0.75, 0.0, 0.0), 1.0, 1.0),
                Component::new(DVec3::new(-0.375, 0.64952, 0.0), 1.0, 1.0),
                Component::new(DVec3::new(-0.375, -0.64952, 0.0), 1.0, 1.0),
            ],
        )
    }

    /// Two lobes and a negative component denting their waist.
    fn dented() -> Blob {
        Blob::new(
            0.5,
            vec![
                Component::new(DVec3::new(-0.6, 0.0, 0.0), 1.0, 1.0),
                Component::new(DVec3::new(0.6, 0.0, 0.0), 1.2, 1.5),
                Component::new(DVec3::new(0.0, 0.5, 0.0), 0.6, -1.0),
            ],
        )
    }

    fn hit_point(b: &Blob, origin: DVec3, dir: DVec3) -> Option<DVec3> {
        let ray = Ray::new(origin, dir);
        b.intersect(&ray, 1e-9, f64::INFINITY).map(|h| ray.at(h.t))
    }

    #[test]
    fn contract_holds() {
        check_shape(&single(0.6));
        check_shape(&trio());
        check_shape(&dented());
        check_dpdu(&trio());
        assert!(!trio().can_emit());
    }

    #[test]
    fn single_component_is_a_sphere_of_the_predicted_radius() {
        // (1 - d^2)^2 = T  =>  d = sqrt(1 - sqrt(T)); POV-Ray renders the same radius.
        for threshold in [0.6, 0.1, 0.99] {
            let b = single(threshold);
            let radius = (1.0 - threshold.sqrt()).sqrt();
            let p = hit_point(&b, DVec3::new(0.0, 0.0, 5.0), -DVec3::Z).unwrap();
            assert!((p.z - radius).abs() < 1e-12, "{threshold}: {p}");
            let ray = Ray::new(DVec3::new(0.0, 0.0, 5.0), -DVec3::Z);
            let h = b.intersect(&ray, 1e-9, f64::INFINITY).unwrap();
            assert!((b.surface(&ray, &h).normal - DVec3::Z).length() < 1e-12);
            // From the centre (inside), along an axis: the exit, with the normal still outward.
            let ray = Ray::new(DVec3::ZERO, DVec3::Y * 3.0);
            let h = b.intersect(&ray, 1e-9, f64::INFINITY).unwrap();
            assert!((h.t * 3.0 - radius).abs() < 1e-12);
            assert!((b.surface(&ray, &h).normal - DVec3::Y).length() < 1e-12);
        }
    }

    #[test]
    fn grazing_and_tangent_rays() {
        let b = single(0.6);
        let radius = (1.0 - 0.6f64.sqrt()).sqrt();
        assert!(hit_point(&b, DVec3::new(radius + 1e-9, 0.0, 5.0), -DVec3::Z).is_none());
        let p = hit_point(&b, DVec3::new(radius - 1e-9, 0.0, 5.0), -DVec3::Z).unwrap();
        assert!((b.field(p) - 0.6).abs() < 1e-12, "{p}");
        // Grazing the waist between two lobes of the trio, from far away.
        let b = trio();
        let mut rng = TestRng::new(1);
        for _ in 0..2000 {
            let origin = rng.unit_vector() * 50.0;
            let target = rng.point_in(&b.bounds());
            if let Some(p) = hit_point(&b, origin, target - origin) {
                assert!((b.field(p) - 0.6).abs() < 1e-9, "{p}: {}", b.field(p));
            }
        }
    }

    #[test]
    fn negative_component_dents_and_rays_pass_through_the_dent() {
        let b = dented();
        // Straight down onto the negative component's centre: the dent lowers the surface.
        let p = hit_point(&b, DVec3::new(0.0, 5.0, 0.0), -DVec3::Y).unwrap();
        let undented = Blob::new(0.5, b.components[..2].to_vec());
        let q = hit_point(&undented, DVec3::new(0.0, 5.0, 0.0), -DVec3::Y).unwrap();
        assert!(p.y < q.y - 0.05, "dent {p} vs {q}");
        assert!((b.field(p) - 0.5).abs() < 1e-12);
    }

    #[test]
    fn walls_along_a_line_through_all_components() {
        // Separate components along x: every wall is found in order.
        let b = Blob::new(
            0.5,
            vec![
                Component::new(DVec3::new(-3.0, 0.0, 0.0), 1.0, 1.0),
                Component::new(DVec3::new(3.0, 0.0, 0.0), 1.0, 1.0),
            ],
        );
        let ray = Ray::new(DVec3::new(-10.0, 0.0, 0.0), DVec3::X);
        let mut walls = vec![];
        let mut t_min = 1e-9;
        while let Some(h) = b.intersect(&ray, t_min, f64::INFINITY) {
            walls.push(ray.at(h.t).x);
            t_min = h.t + 1e-9;
        }
        let r = (1.0 - 0.5f64.sqrt()).sqrt();
        let expected = [-3.0 - r, -3.0 + r, 3.0 - r, 3.0 + r];
        assert_eq!(walls.len(), 4, "{walls:?}");
        for (w, e) in walls.iter().zip(expected) {
            assert!((w - e).abs() < 1e-12, "{w} vs {e}");
        }
    }

    #[test]
    fn distant_origins_and_unnormalised_directions() {
        let b = trio();
        for distance in [1e3, 1e6] {
            let origin = DVec3::new(0.1, 0.2, distance);
            let p = hit_point(&b, origin, -DVec3::Z * 0.01).unwrap();
            assert!((b.field(p) - 0.6).abs() < 1e-15 * distance + 1e-9, "{p}");
        }
    }

    #[test]
    fn random_hits_lie_on_the_surface_with_finite_uvs() {
        let mut rng = TestRng::new(3);
        for b in [trio(), dented()] {
            let mut hits = 0;
            for _ in 0..5000 {
                let origin = rng.unit_vector() * rng.range(0.0, 6.0);
                let target = rng.point_in(&b.bounds());
                let ray = Ray::new(origin, (target - origin) * rng.range(0.1, 10.0));
                if let Some(h) = b.intersect(&ray, 1e-9, f64::INFINITY) {
                    hits += 1;
                    let s = b.surface(&ray, &h);
                    assert!((b.field(s.point) - b.threshold).abs() < 1e-9);
                    assert!(s.uv.is_finite());
                }
            }
            assert!(hits > 500);
        }
    }

    #[test]
    fn parameters_are_validated() {
        let comp = |center: [f64; 3], radius: f64, strength: f64| BlobComponent { center, radius, strength };
        let ok = BlobParams { threshold: 0.6, components: vec![comp([0.0; 3], 1.0, 1.0)] };
        assert!(ok.build().is_ok());
        let err = |p: BlobParams| p.build().unwrap_err().key;
        assert_eq!(err(BlobParams { threshold: 0.0, components: vec![comp([0.0; 3], 1.0, 1.0)] }), "threshold");
        assert_eq!(err(BlobParams { threshold: 1.0, components: vec![] }), "components");
        assert_eq!(
            err(BlobParams { threshold: 0.5, components: vec![comp([0.0; 3], 1.0, 1.0), comp([0.0; 3], -1.0, 1.0)] }),
            "components[1].radius"
        );
        assert_eq!(
            err(BlobParams { threshold: 0.5, components: vec![comp([f64::NAN, 0.0, 0.0], 1.0, 1.0)] }),
            "components[0].center"
        );
        assert_eq!(
            err(BlobParams { threshold: 0.5, components: vec![comp([0.0; 3], 1.0, f64::INFINITY)] }),
            "components[0].strength"
        );
        // Only negative components, or a threshold above every positive strength: empty.
        assert_eq!(err(BlobParams { threshold: 0.5, components: vec![comp([0.0; 3], 1.0, -1.0)] }), "threshold");
        assert_eq!(err(BlobParams { threshold: 2.5, components: vec![comp([0.0; 3], 1.0, 2.0)] }), "threshold");
    }

    #[test]
    fn parameters_deserialise_with_defaults_and_deny_unknown_keys() {
        use serde::de::IntoDeserializer;
        use serde::de::value::{Error, MapDeserializer};
        let component = |entries: Vec<(&'static str, f64)>| {
            let map: MapDeserializer<'_, _, Error> = MapDeserializer::new(entries.into_iter());
            BlobComponent::deserialize(map.into_deserializer())
        };
        let c = component(vec![("strength", -2.0)]).unwrap();
        assert_eq!((c.center, c.radius, c.strength), ([0.0; 3], 1.0, -2.0));
        assert!(component(vec![("radus", 1.0)]).unwrap_err().to_string().contains("unknown"));
    }

    #[test]
    fn exports_to_pov_with_z_mirrored() {
        let b = Blob::new(
            0.6,
            vec![
                Component::new(DVec3::new(1.0, 2.0, 3.0), 1.5, 1.0),
                Component::new(DVec3::new(0.0, 0.5, -1.0), 0.5, -2.0),
            ],
        );
        assert_eq!(
            b.to_pov().unwrap(),
            "blob {\n  threshold 0.6\n  sphere { <1.0, 2.0, -3.0>, 1.5, strength 1.0 }\n  sphere { <0.0, 0.5, 1.0>, 0.5, strength -2.0 }\n}"
        );
    }
}
