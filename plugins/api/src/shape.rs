use std::fmt::Debug;

use glam::{DVec2, DVec3};

use crate::{Aabb, Ray};

/// The cheap result of [`Shape::intersect`]: the ray parameter plus scratch values the
/// shape may keep to finish the job in [`Shape::surface`] (which part was hit, barycentrics...).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Hit {
    /// Ray parameter of the hit.
    pub t: f64,
    /// Which part of the shape was hit (for example 0 = side, 1 = base cap, 2 = top cap).
    pub part: u32,
    /// Free scratch space for the shape.
    pub scratch: DVec3,
}

impl Hit {
    /// A hit at `t` on part 0 with no scratch data.
    pub fn at(t: f64) -> Self {
        Self { t, ..Self::default() }
    }

    /// A hit at `t` on `part`.
    pub fn on_part(t: f64, part: u32) -> Self {
        Self { t, part, scratch: DVec3::ZERO }
    }
}

/// Geometry at a hit, in object space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Surface {
    /// The hit point.
    pub point: DVec3,
    /// Unit geometric normal, pointing out of the shape (for open surfaces: the shape's own
    /// front side). The integrators flip it toward the viewer; they never rely on its sign
    /// for shading, only for entering and leaving interiors.
    pub normal: DVec3,
    /// Unit shading normal (interpolated on meshes); equal to `normal` on analytic shapes.
    pub shading_normal: DVec3,
    /// Surface parameterisation for texturing, each component in [0, 1] where defined.
    pub uv: DVec2,
    /// How fast `uv` changes along the surface: uv units per unit of object-space length
    /// (the square root of the uv-to-surface area ratio; meshes know it per triangle). Texture
    /// filtering turns a ray's footprint into texels with it; 0 when unknown.
    pub uv_density: f64,
}

impl Surface {
    /// A surface point whose shading normal is its geometric normal.
    pub fn new(point: DVec3, normal: DVec3, uv: DVec2) -> Self {
        Self { point, normal, shading_normal: normal, uv, uv_density: 0.0 }
    }
}

/// A point sampled uniformly on a shape's surface (object space).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AreaSample {
    /// The sampled point.
    pub point: DVec3,
    /// Unit outward normal there.
    pub normal: DVec3,
    /// Probability density with respect to area (1 / area for uniform sampling).
    pub pdf_area: f64,
}

/// A shape in its own object space. Prism transforms rays into this space; `t` is shared
/// between spaces because the direction is not renormalised.
pub trait Shape: Send + Sync + Debug + 'static {
    /// Object-space bounds; [`Aabb::INFINITE`] for unbounded shapes.
    fn bounds(&self) -> Aabb;

    /// The nearest hit with `t_min < t < t_max`, if any. Keep it cheap: the full surface
    /// is computed once, for the winning hit, by [`Shape::surface`].
    fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit>;

    /// The surface at a hit this shape returned for this ray.
    fn surface(&self, ray: &Ray, hit: &Hit) -> Surface;

    /// The surface at a hit without its texture coordinates: `point`, `normal` and
    /// `shading_normal` exactly as [`Shape::surface`] gives them, while `uv` and
    /// `uv_density` may be left 0. Prism calls it for untextured materials, which is most
    /// hits; override it when the uv costs trigonometry (longitudes, latitudes), and let
    /// `surface` add the uv to it so the two cannot drift apart. The default is `surface`.
    fn surface_geometry(&self, ray: &Ray, hit: &Hit) -> Surface {
        self.surface(ray, hit)
    }

    /// True when `point` (object space) lies inside the solid. Prism asks it once per render
    /// for the camera position, as POV-Ray does: a camera inside a glass or water object sees
    /// through that interior first (its rays leave the object rather than enter it). The
    /// default, false, suits surfaces without an inside (discs, triangles, meshes); closed
    /// shapes should answer it.
    fn inside(&self, point: DVec3) -> bool {
        let _ = point;
        false
    }

    /// True when anything lies on the ray with `t_min < t < t_max` (shadow rays).
    fn occluded(&self, ray: &Ray, t_min: f64, t_max: f64) -> bool {
        self.intersect(ray, t_min, t_max).is_some()
    }

    /// True when the shape certainly does not meet the convex hull of `points` (object
    /// space). Prism asks unbounded shapes this to skip them for a whole bundle of rays (the
    /// shadow rays from a point to an area light); bounded shapes are culled by their
    /// bounds instead. The default, false, is always correct; a `true` must be certain,
    /// with a margin for rounding.
    fn misses_hull(&self, points: &[DVec3]) -> bool {
        let _ = points;
        false
    }

    /// Surface area, for shapes that can be area lights.
    fn area(&self) -> Option<f64> {
        None
    }

    /// A uniformly distributed point on the surface from `u` in [0,1)^2.
    fn sample_area(&self, u: DVec2) -> Option<AreaSample> {
        let _ = u;
        None
    }

    /// The POV-Ray 3.7 SDL of this shape in object space, already mapped to POV-Ray's
    /// left-handed frame with [`crate::pov::vector`] (z negated). `None` when the shape has
    /// no POV-Ray equivalent; the exporter then reports an error naming it.
    fn to_pov(&self) -> Option<String> {
        None
    }
}
