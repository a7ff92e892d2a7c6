//! The 8-wide BVH both levels of Prism's acceleration share: nodes holding their eight
//! children's boxes as structure-of-arrays (tested against a ray at once by the box kernel
//! of [`crate::accel::simd`]), built by collapsing an obvhs binary tree, and traversed depth
//! first, nearest child first. What a leaf is belongs to the user: groups of triangles in
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

/// Builds obvhs's binary tree over `boxes` (`params` as obvhs takes them), with its Morton
/// curve laid in a cube rather than in the boxes' bounds.
///
/// obvhs sorts the primitives along a Morton curve in the bounds of all boxes, scaled to the
/// unit cube axis by axis, and PLOC then merges neighbours along that curve. In a flat
/// scene's bounds (a terrain, a floor with things on it) the thin axis gets as many bits as
/// the wide ones: the curve splits by height as often as across the ground and strings
/// far-apart primitives together, which the merge's bounded search cannot undo. A point at
/// the far corner of the cube of the bounds' longest side makes the scale the same on every
/// axis; its leaf is taken out of the tree once built (its sibling takes its parent's place,
/// and the boxes above are refitted). On the terrain of `benches/mesh_bvh.rs` the collapsed
/// tree's expected cost fell by 9 %, on the dragon by 1.6 % (docs/meshes.md, seventh round).
///
/// # Panics
///
/// When `params` allow more than one primitive per leaf (the padding could share a leaf).
pub fn build_binary(mut boxes: Vec<obvhs::aabb::Aabb>, params: obvhs::BvhBuildParams) -> obvhs::bvh2::Bvh2 {
    assert_eq!(params.max_prims_per_leaf, 1, "build_binary builds one primitive per leaf");
    let total = boxes.iter().fold(obvhs::aabb::Aabb::INVALID, |all, b| all.union(b));
    let corner = total.min + glam::Vec3A::splat((total.max - total.min).max_element());
    // Bounds too large for a finite cube keep obvhs's own scaling.
    let padded = corner.is_finite() && total.min.is_finite();
    if padded {
        boxes.push(obvhs::aabb::Aabb { min: corner, max: corner });
    }
    let mut bvh2 = obvhs::bvh2::builder::build_bvh2(&boxes, params, &mut std::time::Duration::default());
    if padded {
        let padding = (boxes.len() - 1) as u32;
        let leaf = bvh2
            .nodes
            .iter()
            .position(|n| n.prim_count == 1 && bvh2.primitive_indices[n.first_index as usize] == padding)
            .expect("the padding point has a leaf");
        bvh2.init_parents_if_uninit();
        bvh2.remove_leaf(leaf);
    }
    bvh2
}

/// An 8-wide tree collapsed from a binary one.
#[derive(Clone, Debug)]
pub struct WideTree {
    /// The nodes; the root is node 0.
    pub nodes: Vec<Node>,
    /// Deepest stack a traversal can need.
    pub stack_size: usize,
    /// The expected cost of a ray that enters the root's box, in the collapse's units (its
    /// least cost over the half area of the root's box): a deterministic measure of a tree's
    /// quality, where timings on a shared machine are not.
    pub expected_cost: f32,
}

/// Makes the wide tree's leaves as a collapse chooses them.
pub trait LeafMaker {
    /// The reference of a new leaf holding `primitives` (indices into the binary tree's
    /// primitives).
    fn make(&mut self, primitives: &[u32]) -> u32;

    /// Asks for what [`make`](Self::make) will read of `primitives`, ahead of the call.
    fn prefetch(&self, _primitives: &[u32]) {}
}

impl<F: FnMut(&[u32]) -> u32> LeafMaker for F {
    fn make(&mut self, primitives: &[u32]) -> u32 {
        self(primitives)
    }
}

/// What a collapse weighs, in the surface area heuristic's units: the expected cost of a
/// ray reaching a box is the cost of what the box holds times its surface area.
#[derive(Clone, Copy, Debug)]
pub struct CollapseCost {
    /// Cost of testing a wide node's children (one eight-box test).
    pub node: f32,
    /// Cost of testing a leaf of `n` primitives, or `None` when `n` are too many for one
    /// leaf (then for every larger `n` too; at most 256).
    pub leaf: fn(usize) -> Option<f32>,
}

impl WideTree {
    /// Collapses `bvh2` into the wide tree of least expected cost under `cost`: which
    /// binary subtrees become leaves and which descendants each wide node takes as its up
    /// to eight children are chosen together, by dynamic programming over the binary tree
    /// (Ylitie, Karras and Laine, "Efficient incoherent ray traversal on GPUs through
    /// compressed wide BVHs", 2017). A greedy collapse (open the largest child until eight;
    /// every subtree that fits one leaf is one) leaves nodes near the bottom half empty.
    /// A leaf's reference is `leaves.make(primitives)` (the primitive indices under it, in
    /// `bvh2`'s numbering).
    ///
    /// # Panics
    ///
    /// When a binary leaf holds more primitives than `cost.leaf` allows in one leaf (build
    /// `bvh2` with one primitive per leaf).
    pub fn collapse(bvh2: &obvhs::bvh2::Bvh2, cost: CollapseCost, leaves: impl LeafMaker) -> Self {
        let plan = Plan::of(bvh2, cost);
        let mut collapse = Collapse { bvh2, plan, leaves, nodes: Vec::new(), depth: 1 };
        collapse.nodes.push(Node::EMPTY);
        if collapse.plan.is_leaf(0) {
            // Cheapest as one leaf: a root node holding it.
            let reference = collapse.leaf(0);
            collapse.nodes[0].set_child(0, &bvh2.nodes[0], LEAF | reference);
        } else {
            collapse.fill(0, 0, 1);
        }
        collapse.nodes.shrink_to_fit();
        let root_area = half_area(&bvh2.nodes[0]);
        let expected_cost = if root_area > 0.0 { collapse.plan.cost / root_area } else { collapse.plan.cost };
        WideTree { stack_size: collapse.depth * (WIDTH - 1) + 2, nodes: collapse.nodes, expected_cost }
    }
}

/// A leaf's cost for each primitive count it may hold (`CollapseCost::leaf` tabulated: the
/// plan asks once per binary node).
struct LeafCosts(Vec<f32>);

impl LeafCosts {
    /// Most primitives one leaf may hold under any cost (more are never asked about).
    const MOST: usize = 256;

    fn of(cost: CollapseCost) -> Self {
        Self((0..=Self::MOST).map_while(|n| if n == 0 { Some(0.0) } else { (cost.leaf)(n) }).collect())
    }

    /// The cost of a leaf of `count` primitives, `None` when they are too many.
    #[inline]
    fn get(&self, count: usize) -> Option<f32> {
        self.0.get(count).copied()
    }
}

/// The least-cost collapse of every binary subtree, as Ylitie et al. tabulate it, with the
/// primitives under every node.
///
/// The binary tree's nodes lie in no useful order (reinsertion moves them), so a
/// depth-first walk over them waits for one cache miss per node, each address known only
/// once the parent is read. The plan instead lists the nodes level by level, where the
/// next nodes' addresses are known ahead and their misses overlap, and copies what it needs
/// of each node into that list; every later pass reads the list in order. Nodes are named
/// by their *position* in it: a node's children are side by side, after it.
///
/// For the node at position `p` and `i` from 1 to 8, `choice[p][i - 1]` says how its
/// subtree is best spread over at most `i` child slots of the wide node above it: for
/// `i = 1`, 0 when the node is a leaf, else the number of its own node's eight slots given
/// to its left child; for `i > 1`, 0 when `i - 1` slots do as well, else the number of the
/// `i` slots given to its left child (the right one has the rest).
struct Plan {
    /// The binary node at each position.
    order: Vec<u32>,
    /// What the plan needs of the node at each position.
    listed: Vec<Listed>,
    choice: Vec<[u8; WIDTH]>,
    /// The primitives in depth-first order, left child first: those under the node at
    /// position `p` are `prims[start[p]..start[p] + count[p]]`.
    prims: Vec<u32>,
    /// Where the primitives under each position begin in `prims`.
    start: Vec<u32>,
    /// How many primitives are under each position.
    count: Vec<u32>,
    /// The least cost of the whole tree.
    cost: f32,
}

/// A binary node as the plan lists it.
#[derive(Clone, Copy)]
struct Listed {
    /// Half the surface area of its box.
    half_area: f32,
    /// Primitives in it when it is a leaf, 0 when it is an inner node.
    prim_count: u32,
    /// The position of its first child (inner node), or its first primitive's place in the
    /// binary tree's primitive indices (leaf).
    first: u32,
}

impl Plan {
    /// How many positions ahead of the one in hand the listing asks for the node.
    const LOOKAHEAD: usize = 16;

    /// The plan for `bvh2` under `cost`.
    fn of(bvh2: &obvhs::bvh2::Bvh2, cost: CollapseCost) -> Self {
        let leaf_cost = LeafCosts::of(cost);
        let (order, listed, levels) = Self::list(bvh2);
        // The costs are made from the deepest level up; `below` holds the level under the
        // one in hand, indexed by position from that level's start.
        let mut choice = vec![[0u8; WIDTH]; order.len()];
        let mut count = vec![0u32; order.len()];
        let mut below: Vec<[f32; WIDTH]> = Vec::new();
        let mut here: Vec<[f32; WIDTH]> = Vec::new();
        for level in levels.windows(3).rev() {
            let (begin, end, next) = (level[0], level[1], level[2]);
            debug_assert!(below.len() == next - end);
            here.clear();
            for position in begin..end {
                let node = listed[position];
                if node.prim_count > 0 {
                    count[position] = node.prim_count;
                    let leaf = leaf_cost
                        .get(node.prim_count as usize)
                        .expect("a binary leaf holds more primitives than a wide leaf may");
                    here.push([leaf * node.half_area; WIDTH]);
                } else {
                    let first = node.first as usize;
                    let under = count[first] + count[first + 1];
                    count[position] = under;
                    let (left, right) = (&below[first - end], &below[first + 1 - end]);
                    let (costs, choices) =
                        Self::inner(node.half_area, leaf_cost.get(under as usize), left, right, cost.node);
                    choice[position] = choices;
                    here.push(costs);
                }
            }
            std::mem::swap(&mut below, &mut here);
        }
        // Each subtree's primitives follow its left sibling's: where each begins, from the
        // root down; then the primitives of each leaf in their place.
        let mut start = vec![0u32; order.len()];
        let mut prims = vec![0u32; count[0] as usize];
        for (position, node) in listed.iter().enumerate() {
            // A leaf's primitives and their place lie anywhere: ask ahead (a place not yet
            // known is asked for at 0, harmlessly).
            if let Some(ahead) = listed.get(position + Self::LOOKAHEAD).filter(|n| n.prim_count > 0) {
                simd::prefetch(bvh2.primitive_indices.as_ptr().wrapping_add(ahead.first as usize));
                simd::prefetch(prims.as_ptr().wrapping_add(start[position + Self::LOOKAHEAD] as usize));
            }
            let at = start[position] as usize;
            if node.prim_count == 0 {
                let first = node.first as usize;
                start[first] = at as u32;
                start[first + 1] = at as u32 + count[first];
            } else {
                let from = node.first as usize..(node.first + node.prim_count) as usize;
                prims[at..at + from.len()].copy_from_slice(&bvh2.primitive_indices[from]);
            }
        }
        Plan { order, listed, choice, prims, start, count, cost: below[0][0] }
    }

    /// The nodes reachable from the root, level by level, a node's children side by side
    /// (the binary node at each position, and what the plan needs of it); and where each
    /// level begins (with the end of the list last, twice: the level below the deepest is
    /// empty).
    fn list(bvh2: &obvhs::bvh2::Bvh2) -> (Vec<u32>, Vec<Listed>, Vec<usize>) {
        let nodes = &bvh2.nodes;
        assert!(nodes.len() < u32::MAX as usize, "too many BVH2 nodes");
        let mut order = Vec::with_capacity(nodes.len());
        let mut listed = Vec::with_capacity(nodes.len());
        order.push(0u32);
        let mut levels = vec![0];
        while levels[levels.len() - 1] < order.len() {
            let (begin, end) = (levels[levels.len() - 1], order.len());
            levels.push(end);
            for position in begin..end {
                if let Some(&ahead) = order.get(position + Self::LOOKAHEAD) {
                    simd::prefetch(nodes.as_ptr().wrapping_add(ahead as usize));
                }
                let node = &nodes[order[position] as usize];
                let first = if node.prim_count == 0 {
                    order.extend([node.first_index, node.first_index + 1]);
                    order.len() as u32 - 2
                } else {
                    node.first_index
                };
                listed.push(Listed { half_area: half_area(node), prim_count: node.prim_count, first });
            }
        }
        levels.push(order.len());
        (order, listed, levels)
    }

    /// The least costs of an inner binary node (of half surface area `area`) for one to
    /// eight slots, and how they are reached, from its children's least costs, the cost of
    /// all its primitives as one leaf (`None` when they are too many) and a node's cost.
    #[inline]
    fn inner(
        area: f32,
        leaf: Option<f32>,
        left: &[f32; WIDTH],
        right: &[f32; WIDTH],
        node: f32,
    ) -> ([f32; WIDTH], [u8; WIDTH]) {
        // spread_cost[j - 1]: the least cost of the two children over j slots; spread_left[j - 1]
        // the left's share. A valid share (one slot to the left) stands until a cost beats
        // it, so that costs that overflow or are NaN (boxes near f32's limits) still give a
        // well-formed tree. For each share of the left, all slot counts at once, without
        // branches (the comparisons are unpredictable): the right's costs shifted by the
        // share, infinite where the right would get no slot.
        // The shares are kept as 32-bit integers, so that their selects use the same lane
        // masks as the costs' and vectorise.
        let mut spread_cost = [f32::INFINITY; WIDTH];
        let mut spread_left = [1i32; WIDTH];
        let mut padded = [f32::INFINITY; 2 * WIDTH];
        padded[WIDTH..].copy_from_slice(right);
        for share in 1..WIDTH {
            let right_shifted = &padded[WIDTH - share..2 * WIDTH - share];
            for j in 0..WIDTH {
                let c = left[share - 1] + right_shifted[j];
                let better = c < spread_cost[j];
                spread_cost[j] = if better { c } else { spread_cost[j] };
                spread_left[j] = if better { share as i32 } else { spread_left[j] };
            }
        }
        let spread_left = spread_left.map(|share| share as u8);
        let node_cost = node * area + spread_cost[WIDTH - 1];
        let (mut best, choice) = match leaf.map(|c| c * area) {
            Some(leaf) if leaf <= node_cost => (leaf, 0),
            _ => (node_cost, spread_left[WIDTH - 1]),
        };
        let (mut costs, mut choices) = ([best; WIDTH], [choice; WIDTH]);
        for i in 1..WIDTH {
            let better = spread_cost[i] < best;
            best = if better { spread_cost[i] } else { best };
            costs[i] = best;
            choices[i] = if better { spread_left[i] } else { 0 };
        }
        (costs, choices)
    }

    /// The primitives under the node at position `p`.
    fn prims_under(&self, p: usize) -> &[u32] {
        let start = self.start[p] as usize;
        &self.prims[start..start + self.count[p] as usize]
    }

    /// True when the node at position `p` becomes a leaf of the wide tree (given one slot).
    fn is_leaf(&self, p: usize) -> bool {
        self.choice[p][0] == 0
    }

    /// Appends the positions of the nodes that take the (at most) `slots` child slots of
    /// the node at position `p` to `out`.
    fn gather(&self, p: usize, slots: usize, out: &mut Vec<usize>) {
        let mut slots = slots;
        while slots > 1 && self.choice[p][slots - 1] == 0 {
            slots -= 1;
        }
        if slots == 1 {
            out.push(p);
        } else {
            let left = self.choice[p][slots - 1] as usize;
            let first = self.listed[p].first as usize;
            self.gather(first, left, out);
            self.gather(first + 1, slots - left, out);
        }
    }
}

/// The state of one collapse: the binary tree, the plan, and the wide nodes so far.
struct Collapse<'a, F> {
    bvh2: &'a obvhs::bvh2::Bvh2,
    plan: Plan,
    leaves: F,
    nodes: Vec<Node>,
    /// Deepest level filled.
    depth: usize,
}

impl<F: LeafMaker> Collapse<'_, F> {
    /// Makes the leaf of the primitives under the node at position `p`.
    fn leaf(&mut self, p: usize) -> u32 {
        self.leaves.make(self.plan.prims_under(p))
    }

    /// The binary node at position `p`.
    fn binary(&self, p: usize) -> &obvhs::bvh2::node::Bvh2Node {
        &self.bvh2.nodes[self.plan.order[p] as usize]
    }

    /// Fills wide node `index` from the binary inner node at position `p`, at `level`.
    fn fill(&mut self, p: usize, index: usize, level: usize) {
        self.depth = self.depth.max(level);
        let first = self.plan.listed[p].first as usize;
        let left = self.plan.choice[p][0] as usize;
        let mut children = Vec::with_capacity(WIDTH);
        self.plan.gather(first, left, &mut children);
        self.plan.gather(first + 1, WIDTH - left, &mut children);
        // The children's binary nodes (for their boxes) and the leaves' primitives lie
        // anywhere: ask for all at once, so that their cache misses overlap.
        for &c in &children {
            simd::prefetch(self.bvh2.nodes.as_ptr().wrapping_add(self.plan.order[c] as usize));
            if self.plan.is_leaf(c) {
                self.leaves.prefetch(self.plan.prims_under(c));
            }
        }
        for (slot, &c) in children.iter().enumerate() {
            if self.plan.is_leaf(c) {
                let reference = self.leaf(c);
                let child = *self.binary(c);
                self.nodes[index].set_child(slot, &child, LEAF | reference);
            } else {
                let inner = self.nodes.len();
                self.nodes.push(Node::EMPTY);
                let child = *self.binary(c);
                self.nodes[index].set_child(slot, &child, inner as u32);
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
        let tree = WideTree::collapse(bvh2, cost, |prims: &[u32]| {
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

    /// The boxes of a wavy height field's triangles, `cells` by `cells` quads over 3.2 by 2
    /// units and 0.3 high: a flat scene, like the terrain of `benches/mesh_bvh.rs`.
    fn height_field(cells: usize) -> Vec<Aabb> {
        let point = |i: usize, j: usize| {
            let (x, z) = (i as f32 / cells as f32 * 3.2 - 1.6, j as f32 / cells as f32 * 2.0 - 1.0);
            Vec3A::new(x, 0.15 * (3.0 * x).sin() * (4.0 * z).cos(), z)
        };
        let mut boxes = Vec::new();
        for j in 0..cells {
            for i in 0..cells {
                let [a, b, c, d] = [point(i, j), point(i + 1, j), point(i, j + 1), point(i + 1, j + 1)];
                boxes.push(Aabb { min: a.min(b).min(c), max: a.max(b).max(c) });
                boxes.push(Aabb { min: b.min(c).min(d), max: b.max(c).max(d) });
            }
        }
        boxes
    }

    #[test]
    fn binary_build_takes_its_padding_point_out_and_refits() {
        let params = BvhBuildParams { max_prims_per_leaf: 1, ..BvhBuildParams::medium_build() };
        let mut rng = TestRng::new(7);
        let random = |count: usize, rng: &mut TestRng| -> Vec<Aabb> {
            (0..count)
                .map(|_| {
                    let min = Vec3A::new(rng.uniform() as f32, rng.uniform() as f32 * 0.1, rng.uniform() as f32);
                    Aabb { min, max: min + Vec3A::splat(0.01) }
                })
                .collect()
        };
        for boxes in
            [random(1, &mut rng), random(2, &mut rng), random(3, &mut rng), random(500, &mut rng), height_field(40)]
        {
            let bvh2 = build_binary(boxes.clone(), params);
            // Walk the tree from the root: every input primitive in one leaf, no other, and
            // every inner box the union of its children's.
            let mut seen = vec![0; boxes.len()];
            let mut stack = vec![0usize];
            while let Some(index) = stack.pop() {
                let node = &bvh2.nodes[index];
                if node.prim_count > 0 {
                    for &prim in &bvh2.primitive_indices[node.first_index as usize..][..node.prim_count as usize] {
                        seen[prim as usize] += 1;
                        assert_eq!(node.aabb(), &boxes[prim as usize], "a leaf's box is its primitive's");
                    }
                } else {
                    let (left, right) = (node.first_index as usize, node.first_index as usize + 1);
                    assert_eq!(node.aabb(), &bvh2.nodes[left].aabb().union(bvh2.nodes[right].aabb()), "refitted");
                    stack.extend([left, right]);
                }
            }
            assert!(seen.iter().all(|&n| n == 1), "{} primitives, each once: {seen:?}", boxes.len());
            let all = boxes.iter().fold(Aabb::INVALID, |all, b| all.union(b));
            assert_eq!(bvh2.nodes[0].aabb(), &all, "the root's box holds the primitives and no more");
        }
    }

    /// On a flat scene the Morton curve laid in a cube gives the collapsed tree a lower
    /// expected cost than obvhs's curve in the scene's own bounds.
    #[test]
    fn a_cubic_morton_space_makes_a_flat_scene_cheaper() {
        let params = BvhBuildParams { max_prims_per_leaf: 1, ..BvhBuildParams::medium_build() };
        let boxes = height_field(120);
        let plain = build_bvh2(&boxes, params, &mut std::time::Duration::default());
        let cubic = build_binary(boxes, params);
        let (plain, cubic) = (Plan::of(&plain, PACKETS).cost, Plan::of(&cubic, PACKETS).cost);
        assert!(cubic < 0.97 * plain, "cubic {cubic}, plain {plain}");
    }

    #[test]
    fn collapse_holds_every_primitive_once_at_the_planned_cost() {
        for (count, seed) in [(1, 1), (2, 2), (9, 3), (100, 4), (5000, 5)] {
            let bvh2 = binary_tree(count, seed);
            if count >= 5000 {
                // Reinsertion has moved nodes: the plan must not rely on children lying after
                // their parents.
                let out_of_order =
                    bvh2.nodes.iter().enumerate().any(|(i, n)| n.prim_count == 0 && (n.first_index as usize) < i);
                assert!(out_of_order, "{count}: the test wants a tree whose nodes are out of order");
            }
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
                // The reported expected cost is the built tree's, per unit of root area.
                let reported = tree.expected_cost * half_area(&bvh2.nodes[0]);
                assert!((built - reported).abs() <= 1e-4 * built, "{count}: built {built}, reported {reported}");
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
        WideTree::collapse(&bvh2, PACKETS, |prims: &[u32]| {
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
