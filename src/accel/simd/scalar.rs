//! The kernels as plain loops: what runs without AVX2 (or off x86-64), and the reference the
//! other instruction sets are tested against.

use super::{BOXES, BoxLanes, BoxRay, FAR_SCALE, Kernels};
use crate::accel::triangle::WatertightRay;
use crate::accel::triangle_groups::{Group, GroupHits};

/// The scalar kernels; every CPU runs them.
#[derive(Clone, Copy, Debug, Default)]
pub struct Scalar;

impl Kernels for Scalar {
    #[inline(always)]
    fn boxes(self, boxes: &BoxLanes, ray: &BoxRay, t_max: f32, near: &mut [f32; BOXES]) -> u32 {
        let planes = &boxes.planes;
        let mut mask = 0;
        for (i, entry) in near.iter_mut().enumerate() {
            let mut t0 = 0.0f32;
            let mut t1 = t_max;
            for axis in 0..3 {
                let n = planes[ray.near[axis]][i] * ray.rdir[axis] - ray.org_rdir[axis];
                let f = (planes[ray.far[axis]][i] * ray.rdir[axis] - ray.org_rdir[axis]) * FAR_SCALE;
                t0 = if n > t0 { n } else { t0 };
                t1 = if f < t1 { f } else { t1 };
            }
            *entry = t0;
            if t0 <= t1 {
                mask |= 1 << i;
            }
        }
        mask
    }

    #[inline(always)]
    fn group(self, group: &Group<'_>, ray: &WatertightRay, t_max: f32, hits: &mut GroupHits) -> u32 {
        let mut mask = 0;
        for triangle in 0..group.triangle_count() {
            let [a, b, c] = group.triangle_vertices(triangle);
            if let Some(hit) = ray.intersect(a, b, c, t_max) {
                hits.set(triangle, hit);
                mask |= 1 << triangle;
            }
        }
        mask
    }
}
