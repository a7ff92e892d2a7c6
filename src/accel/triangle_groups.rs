//! Mesh BVH leaves as groups of triangles over shared vertices: each distinct vertex of a
//! group is stored once (as structure of arrays) and each triangle names its three by
//! one-byte indices. The neighbouring triangles of a leaf share most of their vertices (a
//! leaf of eight terrain triangles has nine), so a group takes about half the bytes of the
//! same triangles with three vertices each, and the watertight test's shear is applied once
//! per vertex rather than once per corner. A leaf is one or more groups stored one after the
//! other.
//!
//! Layout of a group, in 32-bit words:
//!
//! | words | content |
//! |---|---|
//! | 1 | header: vertex count (bits 0-7), triangle count (8-15), "another group follows" (16) |
//! | 3 × vertices | x of every vertex, then y, then z (f32 bits) |
//! | ⌈3 × triangles / 4⌉ | first-corner index bytes of every triangle, then second, then third |
//! | triangles | the triangle's index in the mesh's triangle list |
//!
//! Vertices are deduplicated by value (bit for bit), so two triangles that share an edge in
//! the mesh read the same numbers for it and the test stays watertight.

use glam::Vec3;

use super::pages::{PageArray, PageBuffer};
use super::triangle::TriangleHit;

/// Most triangles in one group.
pub const GROUP_TRIANGLES: usize = 16;
/// Most distinct vertices in one group (two 8-lane registers per coordinate).
pub const GROUP_VERTICES: usize = 16;
/// Words the kernels may read past the end of a group: an 8-lane load of a group's last
/// coordinates or index bytes reaches up to 8 words beyond them. The buffer ends with this
/// many zero words.
const TAIL_WORDS: usize = 16;
const MORE: u32 = 1 << 16;

/// The number of words of a group of `vertices` and `triangles`.
#[inline(always)]
const fn group_words(vertices: usize, triangles: usize) -> usize {
    1 + 3 * vertices + (3 * triangles).div_ceil(4) + triangles
}

/// The groups of every leaf of a mesh BVH, one after the other; a leaf is named by the word
/// at which its first group starts.
#[derive(Clone, Debug)]
pub struct TriangleGroups {
    words: PageArray<u32>,
}

impl TriangleGroups {
    /// The group starting at word `start` (the start of a leaf, or the end of the group
    /// before it when that one said another follows).
    ///
    /// # Panics
    ///
    /// When the word there cannot be a group's header, or the group it describes would end
    /// past the buffer (never for references made by [`GroupWriter::leaf`]). Any other
    /// wrong start reads a meaningless group, but only from the buffer.
    #[inline(always)]
    pub fn group(&self, start: usize) -> Group<'_> {
        Group::at(&self.words, start)
    }

    /// Words in use (each four bytes).
    pub fn len(&self) -> usize {
        self.words.len()
    }

    /// True when there are no groups.
    pub fn is_empty(&self) -> bool {
        self.words.len() <= TAIL_WORDS
    }

    /// The first word of the buffer, for prefetching a leaf by its reference.
    #[inline(always)]
    pub fn as_ptr(&self) -> *const u32 {
        self.words.as_ptr()
    }

    /// Every group, in storage order.
    pub fn iter(&self) -> impl Iterator<Item = Group<'_>> {
        let mut start = 0;
        std::iter::from_fn(move || {
            (start + TAIL_WORDS < self.words.len()).then(|| {
                let group = self.group(start);
                start = group.end();
                group
            })
        })
    }
}

/// One group of a [`TriangleGroups`], checked when made: its counts are within the limits
/// and its words, with `TAIL_WORDS` after them, lie in the buffer, which is what the SIMD
/// kernels' loads rely on.
#[derive(Clone, Copy, Debug)]
pub struct Group<'a> {
    /// The group's words and at least `TAIL_WORDS` after them.
    words: &'a [u32],
    start: usize,
    vertices: usize,
    triangles: usize,
    more: bool,
}

impl<'a> Group<'a> {
    #[inline(always)]
    fn at(buffer: &'a [u32], start: usize) -> Self {
        let header = buffer[start];
        let (vertices, triangles) = ((header & 0xff) as usize, (header >> 8 & 0xff) as usize);
        assert!(
            (1..=GROUP_VERTICES).contains(&vertices) && (1..=GROUP_TRIANGLES).contains(&triangles),
            "not a triangle group"
        );
        let end = start + group_words(vertices, triangles);
        Self { words: &buffer[start..end + TAIL_WORDS], start, vertices, triangles, more: header & MORE != 0 }
    }

    /// Distinct vertices (1 to [`GROUP_VERTICES`]).
    #[inline(always)]
    pub fn vertex_count(&self) -> usize {
        self.vertices
    }

    /// Triangles (1 to [`GROUP_TRIANGLES`]).
    #[inline(always)]
    pub fn triangle_count(&self) -> usize {
        self.triangles
    }

    /// True when the leaf has another group after this one.
    #[inline(always)]
    pub fn more(&self) -> bool {
        self.more
    }

    /// The word after this group: where the next one starts.
    #[inline(always)]
    pub fn end(&self) -> usize {
        self.start + group_words(self.vertices, self.triangles)
    }

    /// The coordinates: `3 × vertex_count` floats (x of every vertex, then y, then z),
    /// followed by at least `TAIL_WORDS` readable words.
    #[inline(always)]
    pub fn coordinates(&self) -> *const f32 {
        self.words[1..].as_ptr().cast()
    }

    /// The corner index bytes: `3 × triangle_count` (first corners, then second, then
    /// third), followed by at least `TAIL_WORDS` readable words.
    #[inline(always)]
    pub fn corner_indices(&self) -> *const u8 {
        self.words[1 + 3 * self.vertices..].as_ptr().cast()
    }

    /// The vertices of triangle `triangle` (below [`Self::triangle_count`]), read without
    /// bounds checks: what a hit hands on, on the traversal's path.
    #[inline(always)]
    pub fn triangle_vertices(&self, triangle: usize) -> [Vec3; 3] {
        assert!(triangle < self.triangles);
        let (indices, coordinates, n) = (self.corner_indices(), self.coordinates(), self.vertices);
        [0, 1, 2].map(|k| {
            // SAFETY: the group holds 3 × triangles index bytes and 3 × vertices coordinates
            // (`Group::at` checked that they lie in the buffer), and `v` is kept below
            // `vertices` (`GroupWriter` writes no larger index; the clamp keeps a group read
            // from a wrong start in bounds too).
            unsafe {
                let v = usize::from(*indices.add(k * self.triangles + triangle)).min(n - 1);
                Vec3::new(*coordinates.add(v), *coordinates.add(n + v), *coordinates.add(2 * n + v))
            }
        })
    }

    /// The index in the mesh's triangle list of triangle `triangle`.
    #[inline(always)]
    pub fn prim(&self, triangle: usize) -> u32 {
        self.words[self.end() - self.start - self.triangles + triangle]
    }
}

/// Slots of the table that finds a group's vertices while it is written (four times the
/// most vertices, so that probes are short).
const TABLE_SLOTS: usize = 64;

/// Where the table looks first for the vertex with these bits.
#[inline(always)]
fn table_slot(bits: [u32; 3]) -> usize {
    let hash =
        bits[0].wrapping_mul(0x9e37_79b1) ^ bits[1].wrapping_mul(0x85eb_ca77) ^ bits[2].wrapping_mul(0xc2b2_ae3d);
    (hash >> 26) as usize
}

/// Writes leaves into a [`TriangleGroups`].
pub struct GroupWriter<'a> {
    triangles: &'a [[Vec3; 3]],
    words: PageBuffer<u32>,
}

impl<'a> GroupWriter<'a> {
    /// A writer for leaves over `triangles` (given by their vertices).
    pub fn new(triangles: &'a [[Vec3; 3]]) -> Self {
        // A group of one triangle is the largest per triangle: 1 + 9 + 1 + 1 words.
        let capacity = triangles.len() * group_words(3, 1) + TAIL_WORDS;
        Self { triangles, words: PageBuffer::with_capacity(capacity) }
    }

    /// Asks the CPU for the triangles `prims` ahead of [`Self::leaf`] (they lie in input
    /// order, not the tree's).
    pub fn prefetch(&self, prims: &[u32]) {
        for &prim in prims {
            super::simd::prefetch(self.triangles.as_ptr().wrapping_add(prim as usize));
        }
    }

    /// Writes a leaf of the triangles `prims` (at least one) and returns the word at which
    /// it starts. Triangles are taken in order into groups of at most
    /// [`GROUP_TRIANGLES`] triangles and [`GROUP_VERTICES`] distinct vertices.
    pub fn leaf(&mut self, prims: &[u32]) -> usize {
        assert!(!prims.is_empty(), "a leaf holds at least one triangle");
        let start = self.words.len();
        let mut rest = prims;
        while !rest.is_empty() {
            // The distinct vertices so far, as their bits (equal bits: the same vertex),
            // found through a small open-addressing table of their indices plus one.
            let mut pool = [[0u32; 3]; GROUP_VERTICES];
            let mut table = [0u8; TABLE_SLOTS];
            let mut vertices = 0;
            // Corner k's vertex index of triangle t, at byte k * taken + t once taken is known.
            let mut corners = [[0u8; GROUP_TRIANGLES]; 3];
            let mut taken = 0;
            for &prim in rest.iter().take(GROUP_TRIANGLES) {
                // Spelled out: `array::map` here compiled to calls that went through the stack.
                let bits = |v: Vec3| [v.x.to_bits(), v.y.to_bits(), v.z.to_bits()];
                let [a, b, c] = self.triangles[prim as usize];
                let triangle = [bits(a), bits(b), bits(c)];
                let mut grown = vertices;
                let mut corner = [0u8; 3];
                for (k, &v) in triangle.iter().enumerate() {
                    let mut slot = table_slot(v);
                    corner[k] = loop {
                        match table[slot] {
                            0 => {
                                // New: stored while there is room (a triangle that does not fit
                                // ends the group, and what it stored is not written).
                                if grown < GROUP_VERTICES {
                                    pool[grown] = v;
                                    table[slot] = grown as u8 + 1;
                                }
                                grown += 1;
                                break (grown - 1) as u8;
                            }
                            entry if pool[usize::from(entry - 1)] == v => break entry - 1,
                            _ => slot = (slot + 1) % TABLE_SLOTS,
                        }
                    };
                }
                if grown > GROUP_VERTICES {
                    break;
                }
                vertices = grown;
                for k in 0..3 {
                    corners[k][taken] = corner[k];
                }
                taken += 1;
            }
            let (group, after) = rest.split_at(taken);
            rest = after;
            let mut words = [0u32; group_words(GROUP_VERTICES, GROUP_TRIANGLES)];
            words[0] = vertices as u32 | (taken as u32) << 8 | if rest.is_empty() { 0 } else { MORE };
            for axis in 0..3 {
                for (word, v) in words[1 + axis * vertices..1 + (axis + 1) * vertices].iter_mut().zip(&pool) {
                    *word = v[axis];
                }
            }
            let indices = 1 + 3 * vertices;
            for (n, &byte) in corners.iter().flat_map(|c| &c[..taken]).enumerate() {
                words[indices + n / 4] |= u32::from(byte) << (8 * (n % 4));
            }
            let prims = indices + (3 * taken).div_ceil(4);
            words[prims..prims + taken].copy_from_slice(group);
            self.words.extend_from_slice(&words[..prims + taken]);
        }
        start
    }

    /// The finished groups.
    pub fn finish(mut self) -> TriangleGroups {
        self.words.extend_from_slice(&[0; TAIL_WORDS]);
        TriangleGroups { words: self.words.finish() }
    }
}

/// The hits of one ray with a group's triangles, as structure of arrays.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct GroupHits {
    /// Ray parameter of each triangle's hit.
    pub t: [f32; GROUP_TRIANGLES],
    /// Weight of vertex 1 of each triangle's hit.
    pub b1: [f32; GROUP_TRIANGLES],
    /// Weight of vertex 2 of each triangle's hit.
    pub b2: [f32; GROUP_TRIANGLES],
}

impl GroupHits {
    /// The hit of triangle `triangle`.
    #[inline(always)]
    pub fn get(&self, triangle: usize) -> TriangleHit {
        TriangleHit { t: self.t[triangle], b1: self.b1[triangle], b2: self.b2[triangle] }
    }

    /// Stores `hit` for triangle `triangle`.
    #[inline(always)]
    pub fn set(&mut self, triangle: usize, hit: TriangleHit) {
        self.t[triangle] = hit.t;
        self.b1[triangle] = hit.b1;
        self.b2[triangle] = hit.b2;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::mesh_bvh::tests::grid;

    /// The groups of the leaf starting at `start`.
    fn leaf_groups(groups: &TriangleGroups, start: usize) -> Vec<Group<'_>> {
        let mut out = vec![groups.group(start)];
        while out.last().unwrap().more() {
            let next = out.last().unwrap().end();
            out.push(groups.group(next));
        }
        out
    }

    #[test]
    fn a_leaf_reads_back_its_triangles_in_order_with_shared_vertices_stored_once() {
        let triangles = grid(2);
        let mut writer = GroupWriter::new(&triangles);
        let prims = [0, 1, 2, 3, 4, 5, 6, 7];
        let start = writer.leaf(&prims);
        let groups = writer.finish();
        let read = leaf_groups(&groups, start);
        assert_eq!(read.len(), 1);
        // A 2 by 2 grid has nine vertices.
        assert_eq!((read[0].vertex_count(), read[0].triangle_count()), (9, 8));
        for (k, &prim) in prims.iter().enumerate() {
            assert_eq!(read[0].prim(k), prim);
            assert_eq!(read[0].triangle_vertices(k), triangles[prim as usize]);
        }
        assert_eq!(groups.iter().count(), 1);
    }

    #[test]
    fn leaves_split_into_groups_at_sixteen_vertices_or_sixteen_triangles() {
        // Sixteen triangles without a shared vertex: five to a group (15 vertices).
        let soup: Vec<[Vec3; 3]> = (0..16)
            .map(|k| {
                let o = Vec3::splat(k as f32 * 10.0);
                [o, o + Vec3::X, o + Vec3::Y]
            })
            .collect();
        let mut writer = GroupWriter::new(&soup);
        let first = writer.leaf(&(0..16).collect::<Vec<u32>>());
        let second = writer.leaf(&[3, 9]);
        let groups = writer.finish();
        let read = leaf_groups(&groups, first);
        assert_eq!(read.iter().map(Group::triangle_count).collect::<Vec<_>>(), [5, 5, 5, 1]);
        assert_eq!(read.iter().map(Group::vertex_count).collect::<Vec<_>>(), [15, 15, 15, 3]);
        let prims: Vec<u32> = read.iter().flat_map(|g| (0..g.triangle_count()).map(|k| g.prim(k))).collect();
        assert_eq!(prims, (0..16).collect::<Vec<u32>>());
        for g in &read {
            for k in 0..g.triangle_count() {
                assert_eq!(g.triangle_vertices(k), soup[g.prim(k) as usize]);
            }
        }
        assert_eq!(read.last().unwrap().end(), second);
        let read = leaf_groups(&groups, second);
        assert_eq!((read.len(), read[0].prim(0), read[0].prim(1)), (1, 3, 9));
        // A 4 by 4 grid's 32 triangles: at most sixteen to a group.
        let triangles = grid(4);
        let mut writer = GroupWriter::new(&triangles);
        let start = writer.leaf(&(0..32).collect::<Vec<u32>>());
        let groups = writer.finish();
        let read = leaf_groups(&groups, start);
        assert!(read.iter().all(|g| g.triangle_count() <= GROUP_TRIANGLES && g.vertex_count() <= GROUP_VERTICES));
        assert_eq!(read.iter().map(Group::triangle_count).sum::<usize>(), 32);
    }

    #[test]
    fn vertices_are_shared_by_value_not_by_sign_of_zero() {
        // 0.0 and -0.0 compare equal but are different numbers: both are kept, so that each
        // triangle reads back exactly the vertices it was given.
        let triangles = vec![[Vec3::ZERO, Vec3::X, Vec3::Y], [Vec3::new(-0.0, 0.0, 0.0), Vec3::X, Vec3::Y]];
        let mut writer = GroupWriter::new(&triangles);
        let start = writer.leaf(&[0, 1]);
        let groups = writer.finish();
        let group = groups.group(start);
        assert_eq!(group.vertex_count(), 4);
        assert_eq!(group.triangle_vertices(1)[0].x.to_bits(), (-0.0f32).to_bits());
    }
}
