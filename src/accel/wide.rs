//! The 8-wide BVH both levels of Prism's acceleration share: nodes holding their eight
//! children's boxes as structure-of-arrays (tested against a ray at once by the box kernel
//! of [`crate::accel::simd`]), built by collapsing an obvhs binary tree, and traversed depth
//! first, nearest child first. What a leaf is belongs to the user: a packet of triangles in
//! a mesh ([`crate::accel::mesh_bvh`]), one primitive at the top level
//! ([`crate::accel::scene_bvh`]).

use std::mem::MaybeUninit;

use super::simd::{self, BOXES, BoxLanes, BoxRay, Dispatch, Kernels};

/// Children per node.
pub const WIDTH: usize = BOXES;
/// Child slot marker: the child is a leaf (the low bits are the user's leaf reference).
pub const LEAF: u32 = 1 << 31;
/// An unused child slot.
pub const EMPTY: u32 = u32::MAX;

/// A traversal stack entry: a node reference and the distance at which the ray enters it.
pub type StackEntry = MaybeUninit<(u32, f32)>;

/// An 8-wide node: child boxes as structure-of-arrays and child references.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(64))]
pub struct Node {
    /// The children's boxes.
    pub bounds: BoxLanes,
    /// Inner node index, `LEAF | leaf reference`, or `EMPTY`.
    pub child: [u32; WIDTH],
}

impl Node {
    /// A node with no children (empty boxes that no ray enters).
    pub const EMPTY: Node = Node { bounds: BoxLanes::EMPTY, child: [EMPTY; WIDTH] };

    fn set_child(&mut self, slot: usize, child: &obvhs::bvh2::node::Bvh2Node, reference: u32) {
        let (min, max) = (child.aabb().min, child.aabb().max);
        for axis in 0..3 {
            self.bounds.planes[axis][slot] = min[axis];
            self.bounds.planes[axis + 3][slot] = max[axis];
        }
        self.child[slot] = reference;
    }
}

/// Hints the CPU to fetch `child` of a node (an inner node's four cache lines, or the leaf
/// through `leaf`), which the traversal will reach from the stack.
#[inline(always)]
fn prefetch_child<K: Kernels>(kernels: K, nodes: &[Node], child: u32, leaf: &impl LeafVisitor) {
    if child & LEAF == 0 {
        let p: *const Node = nodes.as_ptr().wrapping_add(child as usize);
        kernels.prefetch(p.cast(), std::mem::size_of::<Node>());
    } else if child != EMPTY {
        leaf.prefetch(kernels, child & !LEAF);
    }
}

/// Orders the children of `node` in `mask` (at least two; entry distances in `near`) for
/// a depth-first, nearest-first traversal, prefetching each: returns the nearest and pushes
/// the others onto the stack so that the next nearest is on top. One pass over the mask
/// both prefetches and orders.
#[inline(always)]
#[allow(clippy::too_many_arguments, reason = "inlined into the traversal loop: its state, not an interface")]
fn order_children<K: Kernels>(
    kernels: K,
    nodes: &[Node],
    node: &Node,
    mask: u32,
    near: &[f32; WIDTH],
    stack: &mut [StackEntry],
    sp: &mut usize,
    leaf: &impl LeafVisitor,
) -> u32 {
    let i = mask.trailing_zeros() as usize;
    let mut rest = mask & (mask - 1);
    let j = rest.trailing_zeros() as usize;
    rest &= rest - 1;
    let (a, b) = (node.child[i], node.child[j]);
    prefetch_child(kernels, nodes, a, leaf);
    prefetch_child(kernels, nodes, b, leaf);
    if rest == 0 {
        // The common case: go to the nearer child (the first on a tie), keep the other.
        let (go, keep) = if near[i] <= near[j] { (a, (b, near[j])) } else { (b, (a, near[i])) };
        stack[*sp] = MaybeUninit::new(keep);
        *sp += 1;
        return go;
    }
    // Push every hit child, farthest first, then continue with the nearest: an insertion
    // sort by distance, descending (nearest on top; on a tie the later slot above).
    let base = *sp;
    let mut insert = |entry: (u32, f32), sp: &mut usize| {
        let mut k = *sp;
        // SAFETY: k - 1 < sp, a slot written earlier.
        while k > base && unsafe { stack[k - 1].assume_init() }.1 < entry.1 {
            stack[k] = stack[k - 1];
            k -= 1;
        }
        stack[k] = MaybeUninit::new(entry);
        *sp += 1;
    };
    insert((a, near[i]), sp);
    insert((b, near[j]), sp);
    while rest != 0 {
        let k = rest.trailing_zeros() as usize;
        rest &= rest - 1;
        let child = node.child[k];
        prefetch_child(kernels, nodes, child, leaf);
        insert((child, near[k]), sp);
    }
    *sp -= 1;
    // SAFETY: sp < the number of slots written.
    unsafe { stack[*sp].assume_init() }.0
}

/// Pushes the children of `node` in `mask` (not empty) but one, which it returns: the order
/// of an any-hit traversal, which need not visit the nearest first.
#[inline(always)]
fn push_children(node: &Node, mut mask: u32, stack: &mut [StackEntry], sp: &mut usize) -> u32 {
    let first = mask.trailing_zeros() as usize;
    mask &= mask - 1;
    while mask != 0 {
        let i = mask.trailing_zeros() as usize;
        mask &= mask - 1;
        // Entered at 0: any-hit traversals never prune.
        stack[*sp] = MaybeUninit::new((node.child[i], 0.0));
        *sp += 1;
    }
    node.child[first]
}

/// Pops the stack down to the first node entered no farther than `t_max`; `None` when the
/// stack runs out.
#[inline(always)]
pub fn pop_within(stack: &[StackEntry], sp: &mut usize, t_max: f32) -> Option<u32> {
    while *sp > 0 {
        *sp -= 1;
        // SAFETY: slots below the stack pointer have been written.
        let (node, distance) = unsafe { stack[*sp].assume_init() };
        if distance <= t_max {
            return Some(node);
        }
    }
    None
}

/// What a traversal does at a leaf.
///
/// A trait with an `#[inline(always)]` method rather than a closure: a closure is a function
/// of its own, compiled without the instruction set [`simd::dispatch`] enables, and when it
/// is too large to inline, the kernels it calls are not inlined either.
pub trait LeafVisitor {
    /// Tests leaf `reference` with `kernels`; may lower `t_max`; returns true to stop the
    /// traversal (an any-hit query that found one).
    fn visit<K: Kernels>(&mut self, kernels: K, reference: u32, t_max: &mut f32) -> bool;

    /// Asks the CPU to fetch leaf `reference` into the cache (a hint; by default nothing).
    #[inline(always)]
    fn prefetch<K: Kernels>(&self, _kernels: K, _reference: u32) {}
}

/// A closure `leaf(reference, &mut t_max) -> stop` as a [`LeafVisitor`] (for leaves that do
/// not use the kernels).
pub struct LeafFn<F>(pub F);

impl<F: FnMut(u32, &mut f32) -> bool> LeafVisitor for LeafFn<F> {
    #[inline(always)]
    fn visit<K: Kernels>(&mut self, _kernels: K, reference: u32, t_max: &mut f32) -> bool {
        (self.0)(reference, t_max)
    }
}

/// Visits the leaves whose boxes the ray enters, nearest boxes first when `NEAREST_FIRST`,
/// pruning boxes beyond the current `t_max`. `leaf.visit(kernels, reference, &mut t_max)`
/// tests one leaf, may lower `t_max`, and returns true to stop the traversal (an any-hit
/// query that found one); `traverse` then returns true.
#[inline(always)]
pub fn traverse<K: Kernels, const NEAREST_FIRST: bool>(
    kernels: K,
    nodes: &[Node],
    r: &BoxRay,
    t_max: f32,
    stack: &mut [StackEntry],
    leaf: &mut impl LeafVisitor,
) -> bool {
    // A copy the optimiser keeps in registers: through the reference, every node reloaded
    // the ray (the stack stores might alias it).
    let r = *r;
    let r = &r;
    let mut t_max = t_max;
    let mut sp = 0usize;
    let mut current = 0u32;
    let mut near = [0f32; WIDTH];
    loop {
        if current & LEAF == 0 {
            let node = &nodes[current as usize];
            let mask = kernels.boxes(&node.bounds, r, t_max, &mut near);
            if mask != 0 {
                if mask & (mask - 1) == 0 {
                    current = node.child[mask.trailing_zeros() as usize];
                } else if NEAREST_FIRST {
                    // All but the nearest wait on the stack: fetching them now hides part
                    // of the cache misses of incoherent rays.
                    current = order_children(kernels, nodes, node, mask, &near, stack, &mut sp, leaf);
                } else {
                    let mut m = mask;
                    while m != 0 {
                        prefetch_child(kernels, nodes, node.child[m.trailing_zeros() as usize], leaf);
                        m &= m - 1;
                    }
                    current = push_children(node, mask, stack, &mut sp);
                }
                continue;
            }
        } else if current == EMPTY {
            // An empty lane is never entered by a ray the slab test can judge, but a ray whose
            // slab distances are NaN (a non-finite origin or direction, or an origin so far
            // away that origin / direction overflows f32) enters every lane: nothing is here.
        } else if leaf.visit(kernels, current & !LEAF, &mut t_max) {
            return true;
        }
        // Pop the next node that is still nearer than the best hit.
        match pop_within(stack, &mut sp, t_max) {
            Some(node) => current = node,
            None => return false,
        }
    }
}

/// [`traverse`] with the fastest kernels the CPU runs.
#[inline(always)]
pub fn traverse_fastest<const NEAREST_FIRST: bool>(
    nodes: &[Node],
    r: &BoxRay,
    t_max: f32,
    stack: &mut [StackEntry],
    leaf: impl FnMut(u32, &mut f32) -> bool,
) -> bool {
    simd::dispatch(Traversal::<_, NEAREST_FIRST> { nodes, ray: r, t_max, stack, leaf })
}

/// The arguments of [`traverse`], for [`simd::dispatch`].
struct Traversal<'a, F, const NEAREST_FIRST: bool> {
    nodes: &'a [Node],
    ray: &'a BoxRay,
    t_max: f32,
    stack: &'a mut [StackEntry],
    leaf: F,
}

impl<F: FnMut(u32, &mut f32) -> bool, const NEAREST_FIRST: bool> Dispatch for Traversal<'_, F, NEAREST_FIRST> {
    type Output = bool;

    #[inline(always)]
    fn run<K: Kernels>(self, kernels: K) -> bool {
        traverse::<K, NEAREST_FIRST>(kernels, self.nodes, self.ray, self.t_max, self.stack, &mut LeafFn(self.leaf))
    }
}

/// Runs `f` with a traversal stack of `size` slots: on the call stack when it fits (the
/// usual case), on the heap for degenerate, very deep trees.
#[inline(always)]
pub fn with_traversal_stack<R>(size: usize, f: impl FnOnce(&mut [StackEntry]) -> R) -> R {
    // Left uninitialised: the traversal writes every slot before reading it.
    let mut local = [const { MaybeUninit::<(u32, f32)>::uninit() }; 160];
    if size <= local.len() { f(&mut local) } else { f(&mut vec![MaybeUninit::uninit(); size]) }
}

/// An 8-wide tree collapsed from a binary one.
#[derive(Clone, Debug)]
pub struct WideTree {
    /// The nodes; the root is node 0.
    pub nodes: Vec<Node>,
    /// Deepest stack a traversal can need.
    pub stack_size: usize,
}

/// What a collapse weighs, in the surface area heuristic's units: the expected cost of a
/// ray reaching a box is the cost of what the box holds times its surface area.
#[derive(Clone, Copy, Debug)]
pub struct CollapseCost {
    /// Cost of testing a wide node's children (one eight-box test).
    pub node: f32,
    /// Cost of testing a leaf of `n` primitives, or `None` when `n` are too many for one
    /// leaf.
    pub leaf: fn(usize) -> Option<f32>,
}

impl WideTree {
    /// Collapses `bvh2` into the wide tree of least expected cost under `cost`: which
    /// binary subtrees become leaves and which descendants each wide node takes as its up
    /// to eight children are chosen together, by dynamic programming over the binary tree
    /// (Ylitie, Karras and Laine, "Efficient incoherent ray traversal on GPUs through
    /// compressed wide BVHs", 2017). A greedy collapse (open the largest child until eight;
    /// every subtree that fits one leaf is one) leaves nodes near the bottom half empty.
    /// A leaf's reference is `make_leaf(primitives)` (the primitive indices under it, in
    /// `bvh2`'s numbering).
    ///
    /// # Panics
    ///
    /// When a binary leaf holds more primitives than `cost.leaf` allows in one leaf (build
    /// `bvh2` with one primitive per leaf).
    pub fn collapse(bvh2: &obvhs::bvh2::Bvh2, cost: CollapseCost, make_leaf: impl FnMut(&[u32]) -> u32) -> Self {
        let plan = Plan::of(bvh2, cost);
        let mut collapse = Collapse { bvh2, plan, make_leaf, nodes: Vec::new(), depth: 1 };
        collapse.nodes.push(Node::EMPTY);
        if collapse.plan.is_leaf(0) {
            // Cheapest as one leaf: a root node holding it.
            let reference = collapse.leaf(0);
            collapse.nodes[0].set_child(0, &bvh2.nodes[0], LEAF | reference);
        } else {
            collapse.fill(0, 0, 1);
        }
        collapse.nodes.shrink_to_fit();
        WideTree { stack_size: collapse.depth * (WIDTH - 1) + 2, nodes: collapse.nodes }
    }
}

/// The least-cost collapse of every binary subtree, as Ylitie et al. tabulate it, with the
/// primitives under every node. For binary node `n` and `i` from 1 to 8, `choice[n][i - 1]`
/// says how the subtree under `n` is best spread over at most `i` child slots of the wide
/// node above it: for `i = 1`, 0 when `n` is a leaf, else the number of its own node's eight
/// slots given to its left child; for `i > 1`, 0 when `i - 1` slots do as well, else the
/// number of the `i` slots given to its left child (the right one has the rest).
struct Plan {
    choice: Vec<[u8; WIDTH]>,
    subtrees: Subtrees,
    /// The least cost of the whole tree.
    #[cfg_attr(not(test), allow(dead_code, reason = "checked by the tests"))]
    cost: f32,
}

/// The primitives under every node of a binary tree.
struct Subtrees {
    /// The primitives in depth-first order, left child first: those under a node are
    /// `prims[start..start + count]`.
    prims: Vec<u32>,
    /// Where each node's primitives begin in `prims`.
    start: Vec<u32>,
    /// How many primitives are under each node.
    count: Vec<u32>,
}

impl Plan {
    /// Marks a stack entry as the end of a node's subtree rather than the node itself.
    const END: u32 = 1 << 31;

    /// The plan for `bvh2` under `cost`, made in one depth-first pass: the tree's nodes lie
    /// in no useful order, so each visit is a cache miss. A subtree's costs (the least for
    /// each number of slots) wait on a stack until its parent's are made from them, so they
    /// are still in the cache then.
    fn of(bvh2: &obvhs::bvh2::Bvh2, cost: CollapseCost) -> Self {
        let nodes = &bvh2.nodes;
        assert!(nodes.len() < Self::END as usize, "too many BVH2 nodes");
        let mut subtrees = Subtrees {
            prims: Vec::with_capacity(bvh2.primitive_indices.len()),
            start: vec![0; nodes.len()],
            count: vec![0; nodes.len()],
        };
        let mut choice = vec![[0u8; WIDTH]; nodes.len()];
        // The costs of the finished subtrees whose parents are not: a left child's below its
        // sibling's.
        let mut finished: Vec<[f32; WIDTH]> = Vec::new();
        let mut stack = vec![0u32];
        while let Some(entry) = stack.pop() {
            let index = (entry & !Self::END) as usize;
            let here = subtrees.prims.len() as u32;
            let node = &nodes[index];
            if entry & Self::END != 0 {
                let count = here - subtrees.start[index];
                subtrees.count[index] = count;
                let right = finished.pop().expect("the right child's costs");
                let left = finished.pop().expect("the left child's costs");
                let (costs, choices) = Self::inner(node, count as usize, &left, &right, cost);
                choice[index] = choices;
                finished.push(costs);
                continue;
            }
            subtrees.start[index] = here;
            let first = node.first_index;
            if node.prim_count > 0 {
                let range = first as usize..first as usize + node.prim_count as usize;
                subtrees.prims.extend_from_slice(&bvh2.primitive_indices[range]);
                subtrees.count[index] = node.prim_count;
                let leaf = (cost.leaf)(node.prim_count as usize)
                    .expect("a binary leaf holds more primitives than a wide leaf may");
                finished.push([leaf * half_area(node); WIDTH]);
            } else {
                stack.extend([index as u32 | Self::END, first + 1, first]);
            }
        }
        Plan { choice, subtrees, cost: finished[0][0] }
    }

    /// The least costs of the inner binary node `node` over `count` primitives, for one to
    /// eight slots, and how they are reached, from its children's least costs.
    #[inline]
    fn inner(
        node: &obvhs::bvh2::node::Bvh2Node,
        count: usize,
        left: &[f32; WIDTH],
        right: &[f32; WIDTH],
        cost: CollapseCost,
    ) -> ([f32; WIDTH], [u8; WIDTH]) {
        let area = half_area(node);
        // spread[j - 1]: the least cost of the two children over j slots, and the left's share.
        // A valid share (one slot to the left) stands until a cost beats it, so that costs
        // that overflow or are NaN (boxes near f32's limits) still give a well-formed tree.
        let mut spread = [(f32::INFINITY, 1u8); WIDTH];
        for (j, best) in spread.iter_mut().enumerate().skip(1) {
            for k in 1..=j {
                let c = left[k - 1] + right[j - k];
                if c < best.0 {
                    *best = (c, k as u8);
                }
            }
        }
        let node_cost = cost.node * area + spread[WIDTH - 1].0;
        let (mut best, mut choice) = match (cost.leaf)(count).map(|c| c * area) {
            Some(leaf) if leaf <= node_cost => (leaf, 0),
            _ => (node_cost, spread[WIDTH - 1].1),
        };
        let (mut costs, mut choices) = ([best; WIDTH], [choice; WIDTH]);
        for i in 1..WIDTH {
            choice = 0;
            if spread[i].0 < best {
                (best, choice) = spread[i];
            }
            costs[i] = best;
            choices[i] = choice;
        }
        (costs, choices)
    }

    /// True when binary node `n` becomes a leaf of the wide tree (given one slot).
    fn is_leaf(&self, n: usize) -> bool {
        self.choice[n][0] == 0
    }

    /// Appends the binary nodes that take the (at most) `slots` child slots of binary node
    /// `n` to `out`.
    fn gather(&self, bvh2: &obvhs::bvh2::Bvh2, n: usize, slots: usize, out: &mut Vec<usize>) {
        let mut slots = slots;
        while slots > 1 && self.choice[n][slots - 1] == 0 {
            slots -= 1;
        }
        if slots == 1 {
            out.push(n);
        } else {
            let left = self.choice[n][slots - 1] as usize;
            let first = bvh2.nodes[n].first_index as usize;
            self.gather(bvh2, first, left, out);
            self.gather(bvh2, first + 1, slots - left, out);
        }
    }
}

/// The state of one collapse: the binary tree, the plan, and the wide nodes so far.
struct Collapse<'a, F> {
    bvh2: &'a obvhs::bvh2::Bvh2,
    plan: Plan,
    make_leaf: F,
    nodes: Vec<Node>,
    /// Deepest level filled.
    depth: usize,
}

impl<F: FnMut(&[u32]) -> u32> Collapse<'_, F> {
    /// Makes the leaf of the primitives under binary node `index`.
    fn leaf(&mut self, index: usize) -> u32 {
        let subtrees = &self.plan.subtrees;
        let start = subtrees.start[index] as usize;
        let end = start + subtrees.count[index] as usize;
        (self.make_leaf)(&subtrees.prims[start..end])
    }

    /// Fills wide node `index` from the binary inner node `bvh2_index`, at `level`.
    fn fill(&mut self, bvh2_index: usize, index: usize, level: usize) {
        self.depth = self.depth.max(level);
        let nodes = &self.bvh2.nodes;
        let first = nodes[bvh2_index].first_index as usize;
        let left = self.plan.choice[bvh2_index][0] as usize;
        let mut children = Vec::with_capacity(WIDTH);
        self.plan.gather(self.bvh2, first, left, &mut children);
        self.plan.gather(self.bvh2, first + 1, WIDTH - left, &mut children);
        for (slot, &c) in children.iter().enumerate() {
            if self.plan.is_leaf(c) {
                let reference = self.leaf(c);
                self.nodes[index].set_child(slot, &nodes[c], LEAF | reference);
            } else {
                let inner = self.nodes.len();
                self.nodes.push(Node::EMPTY);
                self.nodes[index].set_child(slot, &nodes[c], inner as u32);
                self.fill(c, inner, level + 1);
            }
        }
    }
}

fn half_area(n: &obvhs::bvh2::node::Bvh2Node) -> f32 {
    let d = n.aabb().max - n.aabb().min;
    d.x * d.y + d.y * d.z + d.z * d.x
}

#[cfg(test)]
mod tests {
    use glam::Vec3A;
    use obvhs::BvhBuildParams;
    use obvhs::aabb::Aabb;
    use obvhs::bvh2::builder::build_bvh2;
    use prism_api::contract::TestRng;

    use super::*;

    /// `count` small random boxes in the unit cube, and the binary tree over them.
    fn binary_tree(count: usize, seed: u64) -> obvhs::bvh2::Bvh2 {
        let mut rng = TestRng::new(seed);
        let boxes: Vec<Aabb> = (0..count)
            .map(|_| {
                let min = Vec3A::new(rng.uniform() as f32, rng.uniform() as f32, rng.uniform() as f32);
                let size = Vec3A::new(rng.uniform() as f32, rng.uniform() as f32, rng.uniform() as f32) * 0.05;
                Aabb { min, max: min + size }
            })
            .collect();
        let params = BvhBuildParams { max_prims_per_leaf: 1, ..BvhBuildParams::medium_build() };
        build_bvh2(&boxes, params, &mut std::time::Duration::default())
    }

    const PACKETS: CollapseCost = CollapseCost { node: 1.0, leaf: |n| (n <= 16).then(|| 0.4 * n.div_ceil(4) as f32) };

    /// The wide tree, the primitives of each leaf (by reference), and the tree's cost under
    /// `cost` recomputed from its nodes' boxes.
    fn collapse_and_price(bvh2: &obvhs::bvh2::Bvh2, cost: CollapseCost) -> (WideTree, Vec<Vec<u32>>, f32) {
        let mut leaves = Vec::new();
        let tree = WideTree::collapse(bvh2, cost, |prims| {
            leaves.push(prims.to_vec());
            leaves.len() as u32 - 1
        });
        let area = |b: &BoxLanes, slot: usize| {
            let d = [0, 1, 2].map(|axis| b.planes[axis + 3][slot] - b.planes[axis][slot]);
            d[0] * d[1] + d[1] * d[2] + d[2] * d[0]
        };
        let mut total =
            if tree.nodes.len() > 1 || leaves.len() > 1 { cost.node * half_area(&bvh2.nodes[0]) } else { 0.0 };
        for node in &tree.nodes {
            for (slot, &child) in node.child.iter().enumerate().filter(|&(_, &c)| c != EMPTY) {
                total += area(&node.bounds, slot)
                    * if child & LEAF != 0 {
                        (cost.leaf)(leaves[(child & !LEAF) as usize].len()).expect("leaf within the limit")
                    } else {
                        cost.node
                    };
            }
        }
        (tree, leaves, total)
    }

    #[test]
    fn collapse_holds_every_primitive_once_at_the_planned_cost() {
        for (count, seed) in [(1, 1), (2, 2), (9, 3), (100, 4), (5000, 5)] {
            let bvh2 = binary_tree(count, seed);
            let planned = Plan::of(&bvh2, PACKETS).cost;
            let (tree, leaves, built) = collapse_and_price(&bvh2, PACKETS);
            let mut prims: Vec<u32> = leaves.concat();
            prims.sort_unstable();
            assert_eq!(prims, (0..count as u32).collect::<Vec<_>>(), "{count} primitives");
            assert!(leaves.iter().all(|l| !l.is_empty() && l.len() <= 16));
            let referenced: usize =
                tree.nodes.iter().flat_map(|n| n.child).filter(|&c| c != EMPTY && c & LEAF != 0).count();
            assert_eq!(referenced, leaves.len(), "every leaf hangs in the tree once");
            if count > 1 {
                assert!((built - planned).abs() <= 1e-4 * planned, "{count}: built {built}, planned {planned}");
            }
        }
    }

    #[test]
    fn collapse_fills_the_nodes_it_makes() {
        // A greedy collapse that made every subtree of up to sixteen primitives one leaf
        // left the lowest nodes about half empty.
        let (tree, ..) = collapse_and_price(&binary_tree(20_000, 7), PACKETS);
        let children = tree.nodes.iter().flat_map(|n| n.child).filter(|&c| c != EMPTY).count();
        let mean = children as f64 / tree.nodes.len() as f64;
        assert!(mean > 7.0, "{mean} children per node");
    }

    #[test]
    fn boxes_at_the_limits_of_f32_still_make_a_well_formed_tree() {
        // Areas overflow to infinity (and to NaN where a side is zero): no leaf may then
        // exceed the limit, and every primitive must still be in the tree once.
        let boxes: Vec<Aabb> = (0..300)
            .map(|i| {
                let x = if i % 2 == 0 { -3e38 } else { 3e38 } * (i as f32 / 300.0);
                let min = Vec3A::new(x, -3e38, if i % 3 == 0 { 0.0 } else { -3e38 });
                Aabb { min, max: Vec3A::new(x + 1.0, 3e38, if i % 3 == 0 { 0.0 } else { 3e38 }) }
            })
            .collect();
        let params = BvhBuildParams { max_prims_per_leaf: 1, ..BvhBuildParams::medium_build() };
        let bvh2 = build_bvh2(&boxes, params, &mut std::time::Duration::default());
        let mut leaves: Vec<Vec<u32>> = Vec::new();
        WideTree::collapse(&bvh2, PACKETS, |prims| {
            leaves.push(prims.to_vec());
            leaves.len() as u32 - 1
        });
        assert!(leaves.iter().all(|l| !l.is_empty() && l.len() <= 16));
        let mut prims = leaves.concat();
        prims.sort_unstable();
        assert_eq!(prims, (0..300).collect::<Vec<u32>>());
    }

    #[test]
    fn costlier_leaves_make_smaller_leaves() {
        let bvh2 = binary_tree(5000, 9);
        let mean_leaf = |cost| {
            let (_, leaves, _) = collapse_and_price(&bvh2, cost);
            5000.0 / leaves.len() as f64
        };
        let cheap = mean_leaf(CollapseCost { node: 1.0, leaf: |n| (n <= 16).then(|| 0.1 * n.div_ceil(4) as f32) });
        let dear = mean_leaf(CollapseCost { node: 1.0, leaf: |n| (n <= 16).then_some(4.0 * n as f32) });
        assert!(cheap > 2.0 * dear, "{cheap} against {dear} primitives per leaf");
    }
}
