//! A bounding volume hierarchy over the members of a CSG group, so that a ray or a point
//! meets the few members near it instead of every one. POV-Ray puts a union's members into
//! its scene-wide hierarchy; so does Prism for a union that is an object of the scene
//! (`render::extract::separable`), but inside tests, merges and nested unions go through
//! the group, with this tree of its own.

use glam::DVec3;
use prism_api::{Aabb, Ray};

/// Members per leaf at most.
const LEAF_MEMBERS: usize = 2;

/// Nodes pending in one query at most (see [`Stack`]).
const STACK_CAPACITY: usize = 28;

/// A tree over members' bounds (in the group's space); members without finite bounds are
/// met by every query.
#[derive(Clone, Debug)]
pub struct MemberTree {
    /// Root first; an interior node's children are `first` and `first + 1`.
    nodes: Vec<Node>,
    /// Member indices; each leaf holds a run of them.
    order: Vec<u32>,
    /// The bounds of the members in `order`.
    order_bounds: Vec<Aabb>,
    /// Members every query meets (unbounded, or inverted: they fill all space but a hole).
    everywhere: Vec<u32>,
}

/// Half the surface area of a box: what the chance that a ray meets it is proportional to.
fn half_area(b: &Aabb) -> f64 {
    let d = b.max - b.min;
    d.x * d.y + d.y * d.z + d.z * d.x
}

#[derive(Clone, Copy, Debug)]
struct Node {
    bounds: Aabb,
    /// Leaf: the first of its members in `order`; interior: its first child.
    first: u32,
    /// Members of a leaf; 0 for an interior node.
    count: u32,
}

impl MemberTree {
    /// The tree over members with bounds `bounds` (indexed like the members; infinite for
    /// those met everywhere).
    pub fn new(bounds: &[Aabb]) -> Self {
        let (mut bounded, mut everywhere) = (Vec::new(), Vec::new());
        for (index, b) in bounds.iter().enumerate() {
            if b.is_bounded() && !b.is_empty() {
                bounded.push((index as u32, *b));
            } else {
                everywhere.push(index as u32);
            }
        }
        let mut tree = Self {
            nodes: Vec::new(),
            order: Vec::with_capacity(bounded.len()),
            order_bounds: Vec::with_capacity(bounded.len()),
            everywhere,
        };
        if !bounded.is_empty() {
            tree.nodes.push(Node { bounds: Aabb::EMPTY, first: 0, count: 0 });
            tree.build(0, &mut bounded);
        }
        tree
    }

    /// Fills node `at` with `members`: a leaf when few, else split where the surface area
    /// heuristic is least (the children's areas weighted by their members, over the centres
    /// sorted along each axis), within the middle third so that the tree stays shallow.
    fn build(&mut self, at: usize, members: &mut [(u32, Aabb)]) {
        let bounds = members.iter().fold(Aabb::EMPTY, |b, (_, m)| b.union(*m));
        if members.len() <= LEAF_MEMBERS {
            self.nodes[at] = Node { bounds, first: self.order.len() as u32, count: members.len() as u32 };
            self.order.extend(members.iter().map(|(index, _)| *index));
            self.order_bounds.extend(members.iter().map(|(_, b)| *b));
            return;
        }
        let n = members.len();
        // Members on the low side: each side keeps at least a third.
        let (fewest, most) = (n.div_ceil(3), n - n.div_ceil(3));
        let by_centre = |axis: usize| {
            move |a: &(u32, Aabb), b: &(u32, Aabb)| {
                a.1.center()[axis].total_cmp(&b.1.center()[axis]).then(a.0.cmp(&b.0))
            }
        };
        let (mut best_cost, mut best_axis, mut best_low) = (f64::INFINITY, 0, n / 2);
        let mut high_areas = vec![0.0; n + 1];
        for axis in 0..3 {
            members.sort_unstable_by(by_centre(axis));
            let mut high = Aabb::EMPTY;
            for i in (fewest..n).rev() {
                high = high.union(members[i].1);
                high_areas[i] = half_area(&high);
            }
            let mut low = Aabb::EMPTY;
            for (i, (_, b)) in members[..most].iter().enumerate() {
                low = low.union(*b);
                let count = i + 1;
                if count < fewest {
                    continue;
                }
                let cost = half_area(&low) * count as f64 + high_areas[count] * (n - count) as f64;
                if cost < best_cost {
                    (best_cost, best_axis, best_low) = (cost, axis, count);
                }
            }
        }
        members.sort_unstable_by(by_centre(best_axis));
        let first = self.nodes.len();
        self.nodes[at] = Node { bounds, first: first as u32, count: 0 };
        self.nodes.push(Node { bounds: Aabb::EMPTY, first: 0, count: 0 });
        self.nodes.push(Node { bounds: Aabb::EMPTY, first: 0, count: 0 });
        let (low, high) = members.split_at_mut(best_low);
        self.build(first, low);
        self.build(first + 1, high);
    }

    /// Calls `visit` with each member whose bounds the ray meets in `(t_min, limit)`, nearer
    /// boxes first; `visit` returns the new limit (the nearest hit found so far), which
    /// prunes what is left. Members met everywhere come first.
    pub fn visit_ray(&self, ray: &Ray, t_min: f64, limit: f64, mut visit: impl FnMut(u32, f64) -> f64) {
        let mut limit = limit;
        for &index in &self.everywhere {
            limit = visit(index, limit);
        }
        if self.nodes.is_empty() {
            return;
        }
        let inverse = DVec3::ONE / ray.direction;
        let entry = |at: usize, limit: f64| {
            self.nodes[at].bounds.ray_interval_inverse(ray.origin, inverse, t_min, limit).map(|(t, _)| t)
        };
        // Each node's box is tested once, when its parent is opened; popped, a node is
        // skipped when a hit found since lies before its entry.
        let mut stack = Stack::new();
        match entry(0, limit) {
            Some(t) => stack.push((0, t)),
            None => return,
        }
        while let Some((at, t_entry)) = stack.pop() {
            if t_entry > limit {
                continue;
            }
            let node = self.nodes[at];
            if node.count > 0 {
                for &index in &self.order[node.first as usize..(node.first + node.count) as usize] {
                    limit = visit(index, limit);
                }
                continue;
            }
            let (a, b) = (node.first as usize, node.first as usize + 1);
            // The nearer child is popped first.
            match (entry(a, limit), entry(b, limit)) {
                (Some(ta), Some(tb)) if ta <= tb => {
                    stack.push((b, tb));
                    stack.push((a, ta));
                }
                (Some(ta), Some(tb)) => {
                    stack.push((a, ta));
                    stack.push((b, tb));
                }
                (Some(ta), None) => stack.push((a, ta)),
                (None, Some(tb)) => stack.push((b, tb)),
                (None, None) => {}
            }
        }
    }

    /// True when `test` holds for some member whose bounds hold `point` (members met
    /// everywhere included), asking no more members once one holds.
    pub fn any_at(&self, point: DVec3, mut test: impl FnMut(u32) -> bool) -> bool {
        if self.everywhere.iter().any(|&index| test(index)) {
            return true;
        }
        if self.nodes.is_empty() {
            return false;
        }
        let mut stack = Stack::new();
        stack.push(0usize);
        while let Some(at) = stack.pop() {
            let node = self.nodes[at];
            if !node.bounds.contains(point, 0.0) {
                continue;
            }
            if node.count > 0 {
                let run = node.first as usize..(node.first + node.count) as usize;
                let mut members = self.order[run.clone()].iter().zip(&self.order_bounds[run]);
                if members.any(|(&index, bounds)| bounds.contains(point, 0.0) && test(index)) {
                    return true;
                }
            } else {
                stack.push(node.first as usize);
                stack.push(node.first as usize + 1);
            }
        }
        false
    }
}

/// The nodes still to visit, on the stack frame: each level of the tree leaves at most one
/// node behind, and a tree over at most 2^16 members whose splits keep a third on each side
/// is at most 26 levels deep. Small, because it is filled with defaults on every query.
struct Stack<T: Copy + Default> {
    items: [T; STACK_CAPACITY],
    len: usize,
}

impl<T: Copy + Default> Stack<T> {
    fn new() -> Self {
        Self { items: [T::default(); STACK_CAPACITY], len: 0 }
    }

    fn push(&mut self, item: T) {
        self.items[self.len] = item;
        self.len += 1;
    }

    fn pop(&mut self) -> Option<T> {
        self.len = self.len.checked_sub(1)?;
        Some(self.items[self.len])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Nested boxes growing as the cube of their index (the centres all tie) make every
    /// split as uneven as allowed (the heuristic's best is three quarters low, at any scale):
    /// the deepest tree of the largest group must still fit the stack, and a ray through
    /// them all meets every box.
    #[test]
    fn the_most_uneven_splits_fit_the_query_stack() {
        let count = crate::geometry::csg::MAX_LEAVES as usize;
        let bounds: Vec<Aabb> = (0..count)
            .map(|i| {
                let half = (1.0 + i as f64).powi(3);
                Aabb::from_corners(DVec3::splat(-half), DVec3::splat(half))
            })
            .collect();
        let tree = MemberTree::new(&bounds);
        let depth = |at: usize| {
            let mut stack = vec![(at, 0usize)];
            let mut deepest = 0;
            while let Some((at, level)) = stack.pop() {
                deepest = deepest.max(level);
                let node = tree.nodes[at];
                if node.count == 0 {
                    stack.push((node.first as usize, level + 1));
                    stack.push((node.first as usize + 1, level + 1));
                }
            }
            deepest
        };
        let levels = depth(0);
        assert!((24..STACK_CAPACITY).contains(&levels), "{levels} levels");
        let mut met = 0;
        tree.visit_ray(&Ray::new(DVec3::ZERO, DVec3::X), 0.0, f64::INFINITY, |_, limit| {
            met += 1;
            limit
        });
        assert_eq!(met, count);
        assert!(tree.any_at(DVec3::splat((count as f64).powi(3) - 0.5), |index| index as usize == count - 1));
    }

    /// The largest group (2^16 members) builds the deepest tree; its queries must fit the
    /// fixed stack and meet exactly the members they should.
    #[test]
    fn the_largest_group_fits_the_query_stack() {
        let count = crate::geometry::csg::MAX_LEAVES as usize;
        // Unit boxes along x, two apart: none touches another and no two centres tie.
        let bounds: Vec<Aabb> = (0..count)
            .map(|i| {
                let x = 2.0 * i as f64;
                Aabb::from_corners(DVec3::new(x, 0.0, 0.0), DVec3::new(x + 1.0, 1.0, 1.0))
            })
            .collect();
        let tree = MemberTree::new(&bounds);
        let ray = Ray::new(DVec3::new(-1.0, 0.5, 0.5), DVec3::X);
        let mut met = Vec::new();
        tree.visit_ray(&ray, 0.0, f64::INFINITY, |index, limit| {
            met.push(index);
            limit
        });
        assert_eq!(met, (0..count as u32).collect::<Vec<_>>(), "every box, nearest first");
        for i in [0, 1, count / 2, count - 1] {
            let inside = DVec3::new(2.0 * i as f64 + 0.5, 0.5, 0.5);
            assert!(tree.any_at(inside, |index| index as usize == i));
            assert!(!tree.any_at(inside + DVec3::X, |_| true), "between boxes");
        }
    }
}
