//! The template shape plugin: a capsule (a "pill"), the set of points within `radius` of the
//! segment from (0, -length/2, 0) to (0, length/2, 0) on the y axis.
//!
//! Copy this crate to start a new shape: it has every part `plugins/README.md` describes
//! (a documented parameter struct, validation naming the key, the `Shape` impl, a POV-Ray
//! export and the tests), and each part is marked with a `STEP` comment.

#![forbid(unsafe_code)]

use std::f64::consts::{PI, TAU};
use std::sync::Arc;

use prism_api::math::solve_quadratic;
use prism_api::{Aabb, AreaSample, DVec2, DVec3, Hit, ParamError, Ray, Shape, ShapeParams, Surface, math, pov};
use schemars::JsonSchema;
use serde::Deserialize;

// STEP 1: the parameters. Every field has a doc comment (it becomes the description that
// `prism shapes` prints, through the JSON schema) and a serde default where one makes sense.
// `deny_unknown_fields` turns a misspelt key in a scene into an error instead of a silently
// ignored value.

/// Parameters of `shape = "capsule"`.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CapsuleParams {
    /// Radius of the tube and of the two hemispherical caps; must be greater than 0.
    #[serde(default = "default_radius")]
    pub radius: f64,
    /// Length of the straight part along y (between the caps' centres); at least 0, and 0 is a sphere.
    #[serde(default = "default_length")]
    pub length: f64,
}

fn default_radius() -> f64 {
    0.5
}

fn default_length() -> f64 {
    1.0
}

// STEP 2: validation. `build` is the only way from parameters to a shape, so every check
// lives here, and each error names the key it concerns.

impl ShapeParams for CapsuleParams {
    fn build(self) -> Result<Arc<dyn Shape>, ParamError> {
        ParamError::require_positive("radius", self.radius)?;
        ParamError::require_non_negative("length", self.length)?;
        Ok(Arc::new(Capsule::new(self.radius, self.length)))
    }
}

// STEP 3: the shape, in its own object space. Prism transforms rays into this space, so the
// shape only knows its canonical position (here: centred on the origin, along y).

/// A capsule along the y axis, centred on the origin.
#[derive(Clone, Debug, PartialEq)]
pub struct Capsule {
    /// Radius (> 0).
    pub radius: f64,
    /// Half the distance between the caps' centres (>= 0).
    pub half_length: f64,
}

/// `Hit::part` values.
const SIDE: u32 = 0;
const BOTTOM_CAP: u32 = 1;
const TOP_CAP: u32 = 2;

impl Capsule {
    /// A capsule of `radius` whose cap centres are `length` apart (not checked here;
    /// [`CapsuleParams`] validates).
    pub fn new(radius: f64, length: f64) -> Self {
        Self { radius, half_length: 0.5 * length }
    }

    /// The point of the axis segment closest to `p`.
    fn closest_on_axis(&self, p: DVec3) -> DVec3 {
        DVec3::new(0.0, p.y.clamp(-self.half_length, self.half_length), 0.0)
    }
}

impl Shape for Capsule {
    fn bounds(&self) -> Aabb {
        let extent = DVec3::new(self.radius, self.half_length + self.radius, self.radius);
        Aabb::from_corners(-extent, extent)
    }

    fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit> {
        // Precision: start from the bounds' entry, so that a ray from far away does not
        // carry its large origin into the quadratics' coefficients.
        let (t_enter, _) = self.bounds().ray_interval(ray, t_min, t_max)?;
        let o = ray.at(t_enter);
        let d = ray.direction;
        let (r, h) = (self.radius, self.half_length);
        let mut best: Option<Hit> = None;
        let mut consider = |t: f64, part: u32| {
            let t = t_enter + t;
            if t > t_min && t < t_max && best.is_none_or(|b| t < b.t) {
                best = Some(Hit::on_part(t, part));
            }
        };
        // The tube x^2 + z^2 = r^2, where |y| <= h.
        let a = d.x * d.x + d.z * d.z;
        if a > 0.0
            && let Some((t0, t1)) = solve_quadratic(a, 2.0 * (o.x * d.x + o.z * d.z), o.x * o.x + o.z * o.z - r * r)
        {
            for t in [t0, t1] {
                if (o.y + t * d.y).abs() <= h {
                    consider(t, SIDE);
                }
            }
        }
        // The caps: spheres around (0, -h, 0) and (0, h, 0), each only beyond its end.
        for (part, sign) in [(BOTTOM_CAP, -1.0), (TOP_CAP, 1.0)] {
            let oc = o - DVec3::new(0.0, sign * h, 0.0);
            let dd = d.length_squared();
            if let Some((t0, t1)) = solve_quadratic(dd, 2.0 * oc.dot(d), oc.length_squared() - r * r) {
                for t in [t0, t1] {
                    if sign * (oc.y + t * d.y) >= 0.0 {
                        consider(t, part);
                    }
                }
            }
        }
        best
    }

    // STEP 4: the full surface, computed once for the winning hit. Normals point out of the
    // shape and have unit length. The uv (texture coordinates) is added to the geometry
    // below, which Prism asks for alone when nothing is textured: the trigonometry of a
    // longitude is then skipped.
    fn surface(&self, ray: &Ray, hit: &Hit) -> Surface {
        let mut surface = self.surface_geometry(ray, hit);
        let (point, normal) = (surface.point, surface.normal);
        // u: around the y axis, as on the sphere; v: along the whole height, bottom 0, top 1.
        let u = 0.5 + normal.z.atan2(-normal.x) / TAU;
        let v = (point.y + self.half_length + self.radius) / (2.0 * (self.half_length + self.radius));
        surface.uv = DVec2::new(u.rem_euclid(1.0), v.clamp(0.0, 1.0));
        surface
    }

    fn surface_geometry(&self, ray: &Ray, hit: &Hit) -> Surface {
        let p = ray.at(hit.t);
        let axis = match hit.part {
            SIDE => DVec3::new(0.0, p.y, 0.0),
            BOTTOM_CAP => DVec3::new(0.0, -self.half_length, 0.0),
            TOP_CAP => DVec3::new(0.0, self.half_length, 0.0),
            _ => self.closest_on_axis(p),
        };
        let normal = (p - axis).try_normalize().unwrap_or(DVec3::Y);
        // Project onto the surface to remove the rounding of ray.at(t) along the normal.
        // The tangent dpdu is how the point moves as u grows with v held: u turns the normal
        // about the y axis and v fixes the height, so the point circles the axis. The helper
        // gives exactly that, and a unit tangent at the caps' poles, where it vanishes.
        Surface::new(axis + normal * self.radius, normal, DVec2::ZERO)
            .with_dpdu(math::longitude_dpdu(normal * self.radius, normal))
    }

    // Closed shapes say which points are inside: Prism starts camera rays inside the
    // objects that hold the camera (looking out of a glass or water volume).
    fn inside(&self, point: DVec3) -> bool {
        point.distance_squared(self.closest_on_axis(point)) < self.radius * self.radius
    }

    // STEP 5 (optional): area and uniform area sampling make the shape usable as an area
    // light (`can_emit` is then true). Leave them out (the defaults return None) if it cannot
    // be sampled exactly; say so with `fn can_emit(&self) -> bool { false }` and a comment.
    // Direction sampling for next-event estimation (`sample_toward`, `pdf_toward`) then comes
    // for free: the defaults are built on `sample_area` and count every crossing of a
    // direction, as a closed shape needs. Override the pair together only with a better
    // sampler (the sphere samples the cone it subtends); the contract kit checks them with a
    // chi-square test.
    fn area(&self) -> Option<f64> {
        let r = self.radius;
        Some(4.0 * PI * r * r + 2.0 * PI * r * 2.0 * self.half_length)
    }

    fn sample_area(&self, u: DVec2) -> Option<AreaSample> {
        let r = self.radius;
        let tube = 2.0 * PI * r * 2.0 * self.half_length;
        let tube_fraction = tube / self.area()?;
        let phi = TAU * u.y;
        let (point, normal) = if u.x < tube_fraction {
            // On the tube: uniform in height and angle.
            let y = -self.half_length + 2.0 * self.half_length * (u.x / tube_fraction);
            let normal = DVec3::new(phi.cos(), 0.0, phi.sin());
            (DVec3::new(0.0, y, 0.0) + normal * r, normal)
        } else {
            // On the two caps together: a uniform point on a whole sphere, its upper half
            // moved to the top end and its lower half to the bottom end.
            let z = 1.0 - 2.0 * (u.x - tube_fraction) / (1.0 - tube_fraction);
            let ring = (1.0 - z * z).max(0.0).sqrt();
            let normal = DVec3::new(ring * phi.cos(), z, ring * phi.sin());
            (DVec3::new(0.0, self.half_length.copysign(z), 0.0) + normal * r, normal)
        };
        Some(AreaSample { point, normal, pdf_area: 1.0 / self.area()? })
    }

    // STEP 6: the POV-Ray equivalent, for parity scenes. Points go through `pov::vector`,
    // which maps Prism's right-handed frame to POV-Ray's left-handed one.
    fn to_pov(&self) -> Option<String> {
        let r = pov::number(self.radius);
        if self.half_length == 0.0 {
            return Some(format!("sphere {{ {}, {r} }}", pov::vector(DVec3::ZERO)));
        }
        let bottom = pov::vector(DVec3::new(0.0, -self.half_length, 0.0));
        let top = pov::vector(DVec3::new(0.0, self.half_length, 0.0));
        Some(format!(
            "merge {{ cylinder {{ {bottom}, {top}, {r} open }} sphere {{ {bottom}, {r} }} sphere {{ {top}, {r} }} }}"
        ))
    }
}

// STEP 7: the tests. The contract kit checks the properties every shape must have; the
// other tests pin down this shape's own geometry on the rays that break solvers.

#[cfg(test)]
mod tests {
    use super::*;
    use prism_api::contract::{ContractConfig, check_dpdu, check_sampling_toward, check_shape};

    fn pill() -> Capsule {
        Capsule::new(0.5, 1.0)
    }

    fn first_hit(c: &Capsule, origin: DVec3, dir: DVec3) -> Option<DVec3> {
        let ray = Ray::new(origin, dir);
        c.intersect(&ray, 1e-9, f64::INFINITY).map(|h| c.surface(&ray, &h).point)
    }

    /// Distance from `p` to the surface.
    fn distance(c: &Capsule, p: DVec3) -> f64 {
        (p - c.closest_on_axis(p)).length() - c.radius
    }

    #[test]
    fn contract_holds() {
        check_shape(&pill());
        check_shape(&Capsule::new(1.0, 0.0));
        check_shape(&Capsule::new(0.05, 4.0));
        // The tangent follows the uv, and direction sampling holds from the hard places too:
        // the axis beyond a cap, and the middle of the tube.
        check_dpdu(&pill());
        check_sampling_toward(&pill(), &[DVec3::new(0.0, 3.0, 0.0), DVec3::ZERO], &ContractConfig::default());
    }

    #[test]
    fn side_caps_and_inside() {
        let c = pill();
        let p = first_hit(&c, DVec3::new(5.0, 0.2, 0.0), -DVec3::X).unwrap();
        assert!((p - DVec3::new(0.5, 0.2, 0.0)).length() < 1e-12);
        // Along the axis: the top of the cap.
        let p = first_hit(&c, DVec3::new(0.0, 9.0, 0.0), -DVec3::Y).unwrap();
        assert!((p.y - 1.0).abs() < 1e-12);
        // From the centre (inside) towards the bottom: the exit, normal outward.
        let ray = Ray::new(DVec3::ZERO, -DVec3::Y * 2.0);
        let hit = c.intersect(&ray, 1e-9, f64::INFINITY).unwrap();
        assert!((hit.t - 0.5).abs() < 1e-12);
        assert!((c.surface(&ray, &hit).normal + DVec3::Y).length() < 1e-12);
    }

    #[test]
    fn grazing_tangent_and_distant_rays() {
        let c = pill();
        assert!(first_hit(&c, DVec3::new(0.5 + 1e-9, 0.0, 5.0), -DVec3::Z).is_none());
        let p = first_hit(&c, DVec3::new(0.5 - 1e-9, 0.0, 5.0), -DVec3::Z).unwrap();
        assert!(distance(&c, p).abs() < 1e-12);
        // Parallel to the axis, on the tube's wall: touches only the caps' rims or misses.
        if let Some(p) = first_hit(&c, DVec3::new(0.5, 5.0, 0.0), -DVec3::Y) {
            assert!(distance(&c, p).abs() < 1e-9);
        }
        let far = DVec3::new(0.1, 0.3, 1e7);
        let p = first_hit(&c, far, -DVec3::Z).unwrap();
        assert!(distance(&c, p).abs() < 1e-9 && p.z > 0.0);
    }

    #[test]
    fn area_samples_lie_on_the_surface() {
        let c = pill();
        let mut rng = prism_api::contract::TestRng::new(1);
        for _ in 0..1000 {
            let s = c.sample_area(DVec2::new(rng.uniform(), rng.uniform())).unwrap();
            assert!(distance(&c, s.point).abs() < 1e-12);
            assert!((s.normal.length() - 1.0).abs() < 1e-12);
        }
    }

    #[test]
    fn parameters_are_validated() {
        assert!(CapsuleParams { radius: 1.0, length: 0.0 }.build().is_ok());
        assert_eq!(CapsuleParams { radius: 0.0, length: 1.0 }.build().unwrap_err().key, "radius");
        assert_eq!(CapsuleParams { radius: 1.0, length: -1.0 }.build().unwrap_err().key, "length");
    }

    #[test]
    fn parameters_deserialise_with_defaults_and_deny_unknown_keys() {
        use serde::de::IntoDeserializer;
        use serde::de::value::{Error, MapDeserializer};
        let parse = |entries: Vec<(&'static str, f64)>| {
            let map: MapDeserializer<'_, _, Error> = MapDeserializer::new(entries.into_iter());
            CapsuleParams::deserialize(map.into_deserializer())
        };
        let defaults = parse(vec![]).unwrap();
        assert_eq!((defaults.radius, defaults.length), (0.5, 1.0));
        assert!(parse(vec![("height", 2.0)]).unwrap_err().to_string().contains("unknown"));
    }

    #[test]
    fn exports_to_pov() {
        assert_eq!(
            pill().to_pov().unwrap(),
            "merge { cylinder { <0.0, -0.5, -0.0>, <0.0, 0.5, -0.0>, 0.5 open } \
             sphere { <0.0, -0.5, -0.0>, 0.5 } sphere { <0.0, 0.5, -0.0>, 0.5 } }"
        );
        assert_eq!(Capsule::new(2.0, 0.0).to_pov().unwrap(), "sphere { <0.0, 0.0, -0.0>, 2.0 }");
    }
}
