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

impl WideTree {
    /// Collapses `bvh2`: each node takes the eight most promising descendants of a binary
    /// node (repeatedly opening the one with the largest surface area). A subtree with at
    /// most `leaf_size` primitives becomes a leaf, whose reference is
    /// `make_leaf(primitives)` (the primitive indices under it, in `bvh2`'s numbering). A
    /// binary leaf holding more than `leaf_size` primitives stays one leaf: build `bvh2`
    /// with at most `leaf_size` per leaf to rule that out.
    pub fn collapse(bvh2: &obvhs::bvh2::Bvh2, leaf_size: usize, make_leaf: impl FnMut(&[u32]) -> u32) -> Self {
        // About one wide node per eight leaves of `leaf_size`.
        let estimate = bvh2.primitive_indices.len() / (WIDTH * leaf_size.max(1)) * 2 + 1;
        let mut collapse = Collapse {
            bvh2,
            subtrees: Subtrees::of(bvh2),
            leaf_size,
            make_leaf,
            nodes: Vec::with_capacity(estimate),
            depth: 1,
        };
        collapse.nodes.push(Node::EMPTY);
        if !collapse.openable(0) {
            // Small enough for one leaf: a root node holding it.
            let reference = collapse.leaf(0);
            collapse.nodes[0].set_child(0, &bvh2.nodes[0], LEAF | reference);
        } else {
            collapse.fill(0, 0, 1);
        }
        collapse.nodes.shrink_to_fit();
        WideTree { stack_size: collapse.depth * (WIDTH - 1) + 2, nodes: collapse.nodes }
    }
}

/// The state of one collapse: the binary tree, the leaf policy, and the wide nodes so far.
struct Collapse<'a, F> {
    bvh2: &'a obvhs::bvh2::Bvh2,
    subtrees: Subtrees,
    leaf_size: usize,
    make_leaf: F,
    nodes: Vec<Node>,
    /// Deepest level filled.
    depth: usize,
}

impl<F: FnMut(&[u32]) -> u32> Collapse<'_, F> {
    /// True when binary node `index` is an inner node over more than `leaf_size` primitives
    /// (a binary leaf is never opened: its `first_index` points at primitives).
    fn openable(&self, index: usize) -> bool {
        self.bvh2.nodes[index].prim_count == 0 && self.subtrees.count[index] as usize > self.leaf_size
    }

    /// Makes the leaf of the primitives under binary node `index`.
    fn leaf(&mut self, index: usize) -> u32 {
        let start = self.subtrees.start[index] as usize;
        let end = start + self.subtrees.count[index] as usize;
        (self.make_leaf)(&self.subtrees.prims[start..end])
    }

    /// Fills wide node `index` from the binary inner node `bvh2_index`, at `level`.
    fn fill(&mut self, bvh2_index: usize, index: usize, level: usize) {
        self.depth = self.depth.max(level);
        let nodes = &self.bvh2.nodes;
        let first = nodes[bvh2_index].first_index as usize;
        // (binary node, openable)
        let mut children = [(0usize, false); WIDTH];
        children[0] = (first, self.openable(first));
        children[1] = (first + 1, self.openable(first + 1));
        let mut len = 2;
        while len < WIDTH {
            // Open the largest child; subtrees small enough for one leaf stay whole.
            let open = children[..len]
                .iter()
                .enumerate()
                .filter(|&(_, &(_, openable))| openable)
                .max_by(|a, b| half_area(&nodes[a.1.0]).total_cmp(&half_area(&nodes[b.1.0])))
                .map(|(i, _)| i);
            let Some(i) = open else { break };
            let c = children[i].0;
            // As `Vec::swap_remove` then two pushes.
            children[i] = children[len - 1];
            let f = nodes[c].first_index as usize;
            children[len - 1] = (f, self.openable(f));
            children[len] = (f + 1, self.openable(f + 1));
            len += 1;
        }
        for (slot, &(c, openable)) in children[..len].iter().enumerate() {
            let child = &nodes[c];
            if openable {
                let inner = self.nodes.len();
                self.nodes.push(Node::EMPTY);
                self.nodes[index].set_child(slot, child, inner as u32);
                self.fill(c, inner, level + 1);
            } else {
                let reference = self.leaf(c);
                self.nodes[index].set_child(slot, child, LEAF | reference);
            }
        }
    }
}

/// The primitives under every node of a binary tree, found in one depth-first pass (the
/// tree's nodes lie in no useful order, so each visit is a cache miss: one pass, not one
/// count per node and one walk per leaf).
struct Subtrees {
    /// The primitives in depth-first order, left child first: those under a node are
    /// `prims[start..start + count]`.
    prims: Vec<u32>,
    /// Where each node's primitives begin in `prims`.
    start: Vec<u32>,
    /// How many primitives are under each node.
    count: Vec<u32>,
}

impl Subtrees {
    /// Marks a stack entry as the end of a node's subtree rather than the node itself.
    const END: u32 = 1 << 31;

    fn of(bvh2: &obvhs::bvh2::Bvh2) -> Self {
        let nodes = &bvh2.nodes;
        assert!(nodes.len() < Self::END as usize, "too many BVH2 nodes");
        let mut subtrees = Subtrees {
            prims: Vec::with_capacity(bvh2.primitive_indices.len()),
            start: vec![0; nodes.len()],
            count: vec![0; nodes.len()],
        };
        let mut stack = vec![0u32];
        while let Some(entry) = stack.pop() {
            let index = (entry & !Self::END) as usize;
            let here = subtrees.prims.len() as u32;
            if entry & Self::END != 0 {
                subtrees.count[index] = here - subtrees.start[index];
                continue;
            }
            subtrees.start[index] = here;
            let node = &nodes[index];
            let first = node.first_index;
            if node.prim_count > 0 {
                let range = first as usize..first as usize + node.prim_count as usize;
                subtrees.prims.extend_from_slice(&bvh2.primitive_indices[range]);
                subtrees.count[index] = node.prim_count;
            } else {
                stack.extend([index as u32 | Self::END, first + 1, first]);
            }
        }
        subtrees
    }
}

fn half_area(n: &obvhs::bvh2::node::Bvh2Node) -> f32 {
    let d = n.aabb().max - n.aabb().min;
    d.x * d.y + d.y * d.z + d.z * d.x
}
