use glam::{DAffine3, DVec3};

/// An axis-aligned bounding box. Components may be infinite for unbounded shapes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    /// The smallest corner.
    pub min: DVec3,
    /// The largest corner.
    pub max: DVec3,
}

impl Aabb {
    /// The box that contains nothing; `union` with it is the identity.
    pub const EMPTY: Aabb = Aabb { min: DVec3::INFINITY, max: DVec3::NEG_INFINITY };
    /// The box that contains everything (an unbounded shape such as an infinite plane).
    pub const INFINITE: Aabb = Aabb { min: DVec3::NEG_INFINITY, max: DVec3::INFINITY };

    /// The box with corners `a` and `b` (in any order).
    pub fn from_corners(a: DVec3, b: DVec3) -> Self {
        Self { min: a.min(b), max: a.max(b) }
    }

    /// The smallest box that holds all `points`.
    pub fn from_points(points: impl IntoIterator<Item = DVec3>) -> Self {
        points.into_iter().fold(Self::EMPTY, |b, p| b.grow(p))
    }

    /// This box grown to hold `p`.
    pub fn grow(self, p: DVec3) -> Self {
        Self { min: self.min.min(p), max: self.max.max(p) }
    }

    /// The smallest box holding both.
    pub fn union(self, other: Aabb) -> Self {
        Self { min: self.min.min(other.min), max: self.max.max(other.max) }
    }

    /// True when every component is finite (the shape can go into a BVH).
    pub fn is_bounded(&self) -> bool {
        self.min.is_finite() && self.max.is_finite()
    }

    /// True when the box holds no point.
    pub fn is_empty(&self) -> bool {
        self.min.x > self.max.x || self.min.y > self.max.y || self.min.z > self.max.z
    }

    /// Centre of the box.
    pub fn center(&self) -> DVec3 {
        0.5 * (self.min + self.max)
    }

    /// True when `p` lies inside the box grown by `eps` on every side.
    pub fn contains(&self, p: DVec3, eps: f64) -> bool {
        p.cmpge(self.min - DVec3::splat(eps)).all() && p.cmple(self.max + DVec3::splat(eps)).all()
    }

    /// The box around this box after `transform`; infinite boxes stay infinite.
    pub fn transformed(&self, transform: &DAffine3) -> Self {
        if !self.is_bounded() {
            return Self::INFINITE;
        }
        // Arvo's method: each output axis is the sum of the extreme contributions.
        let mut min = transform.translation;
        let mut max = transform.translation;
        let m = transform.matrix3;
        for col in 0..3 {
            let axis = m.col(col);
            let a = axis * self.min[col];
            let b = axis * self.max[col];
            min += a.min(b);
            max += a.max(b);
        }
        Self { min, max }
    }

    /// The parametric interval in which `ray` is inside the box, if any, clipped to [t_min, t_max]
    /// (`None` when either limit is NaN).
    pub fn ray_interval(&self, ray: &crate::Ray, t_min: f64, t_max: f64) -> Option<(f64, f64)> {
        self.ray_interval_inverse(ray.origin, DVec3::ONE / ray.direction, t_min, t_max)
    }

    /// [`Aabb::ray_interval`] for a ray from `origin` given by the reciprocal of its
    /// direction (`1 / d` per axis), computed once for the many boxes one ray meets: the same
    /// result.
    #[inline]
    pub fn ray_interval_inverse(&self, origin: DVec3, inverse: DVec3, t_min: f64, t_max: f64) -> Option<(f64, f64)> {
        // The slabs' entries and exits per axis, without branches (which axis order or a
        // miss ends the test is a coin flip per ray). A NaN (0 * inf: the ray runs inside a
        // slab's plane) sets no constraint: `max` and `min` return the other operand.
        let a = (self.min - origin) * inverse;
        let b = (self.max - origin) * inverse;
        let swap = a.cmpgt(b);
        let near = DVec3::select(swap, b, a);
        let far = DVec3::select(swap, a, b);
        // `later`/`earlier` keep the first operand when the second is NaN: one instruction
        // each, where `f64::max`/`min` also test the first for NaN (t_min and t_max are not).
        let later = |t: f64, candidate: f64| if candidate > t { candidate } else { t };
        let earlier = |t: f64, candidate: f64| if candidate < t { candidate } else { t };
        let t0 = later(later(later(t_min, near.x), near.y), near.z);
        let t1 = earlier(earlier(earlier(t_max, far.x), far.y), far.z);
        // t0 only grows and t1 only shrinks axis by axis: crossed at the end means crossed.
        (t0 <= t1).then_some((t0, t1))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn transformed_box_holds_transformed_corners() {
        let b = Aabb::from_corners(DVec3::new(-1.0, -2.0, -3.0), DVec3::new(1.0, 2.0, 3.0));
        let m = DAffine3::from_scale_rotation_translation(
            DVec3::new(2.0, 1.0, 0.5),
            glam::DQuat::from_euler(glam::EulerRot::XYZ, 0.3, 0.7, -1.1),
            DVec3::new(5.0, -1.0, 2.0),
        );
        let t = b.transformed(&m);
        for i in 0..8 {
            let c = DVec3::new(
                if i & 1 == 0 { b.min.x } else { b.max.x },
                if i & 2 == 0 { b.min.y } else { b.max.y },
                if i & 4 == 0 { b.min.z } else { b.max.z },
            );
            assert!(t.contains(m.transform_point3(c), 1e-12));
        }
    }

    #[test]
    fn infinite_stays_infinite() {
        assert!(!Aabb::INFINITE.transformed(&DAffine3::IDENTITY).is_bounded());
        assert!(Aabb::EMPTY.is_empty());
    }

    #[test]
    fn ray_interval_of_unit_box() {
        let b = Aabb::from_corners(DVec3::splat(-1.0), DVec3::splat(1.0));
        let r = crate::Ray::new(DVec3::new(0.0, 0.0, 5.0), DVec3::new(0.0, 0.0, -1.0));
        assert_eq!(b.ray_interval(&r, 0.0, f64::INFINITY), Some((4.0, 6.0)));
        let miss = crate::Ray::new(DVec3::new(2.0, 0.0, 5.0), DVec3::new(0.0, 0.0, -1.0));
        assert_eq!(b.ray_interval(&miss, 0.0, f64::INFINITY), None);
    }

    /// The interval slab by slab, stopping at the first miss: the definition the branchless
    /// version must reproduce bit for bit.
    fn slab_by_slab(b: &Aabb, origin: DVec3, inverse: DVec3, t_min: f64, t_max: f64) -> Option<(f64, f64)> {
        let (mut t0, mut t1) = (t_min, t_max);
        for axis in 0..3 {
            let mut near = (b.min[axis] - origin[axis]) * inverse[axis];
            let mut far = (b.max[axis] - origin[axis]) * inverse[axis];
            if near > far {
                std::mem::swap(&mut near, &mut far);
            }
            if !near.is_nan() {
                t0 = t0.max(near);
            }
            if !far.is_nan() {
                t1 = t1.min(far);
            }
            if t0 > t1 {
                return None;
            }
        }
        Some((t0, t1))
    }

    #[test]
    fn ray_interval_matches_the_slab_by_slab_definition() {
        let mut rng = crate::contract::TestRng::new(0x2545_f491_4f6c_dd1d);
        let mut next = || rng.next_u64();
        let b = Aabb::from_corners(DVec3::new(-1.0, -2.0, 0.5), DVec3::new(1.5, 2.0, 3.0));
        // Coordinates that often lie exactly on a slab's plane, and directions that are
        // often exactly +0, -0 or parallel to an axis (NaN and infinite slab distances).
        let coordinate = |r: u64| match r % 6 {
            0 => -1.0,
            1 => 2.0,
            2 => 0.5,
            _ => (r >> 8) as f64 / (1u64 << 56) as f64 * 8.0 - 4.0,
        };
        let component = |r: u64| match r % 5 {
            0 => 0.0,
            1 => -0.0,
            _ => (r >> 8) as f64 / (1u64 << 56) as f64 * 2.0 - 1.0,
        };
        let bits = |v: Option<(f64, f64)>| v.map(|(a, b)| (a.to_bits(), b.to_bits()));
        let mut hits = 0;
        for _ in 0..200_000 {
            let origin = DVec3::new(coordinate(next()), coordinate(next()), coordinate(next()));
            let inverse = DVec3::ONE / DVec3::new(component(next()), component(next()), component(next()));
            let (t_min, t_max) = if next() % 2 == 0 { (0.0, f64::INFINITY) } else { (0.25, 3.0) };
            let expected = slab_by_slab(&b, origin, inverse, t_min, t_max);
            hits += usize::from(expected.is_some());
            assert_eq!(
                bits(b.ray_interval_inverse(origin, inverse, t_min, t_max)),
                bits(expected),
                "origin {origin}, inverse {inverse}, ({t_min}, {t_max})"
            );
        }
        assert!(hits > 10_000, "the rays must meet the box often: {hits}");
    }
}
