//! Deterministic sampling: every random number is a pure function of
//! (pixel, sample, dimension, seed), so an image is bit-identical for any thread count and
//! any tiling, and tiles rendered on different machines merge seamlessly.

use glam::DVec2;

/// A 64-bit finaliser (the SplitMix64 / Murmur3 mix), a good integer hash.
#[inline]
pub fn mix64(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// Hash of a pixel, sample index, dimension and seed.
#[inline]
pub fn hash4(pixel: u64, sample: u64, dimension: u64, seed: u64) -> u64 {
    hash_dimension(stream_key(pixel, sample, seed), dimension)
}

/// The part of [`hash4`] that does not depend on the dimension.
#[inline]
fn stream_key(pixel: u64, sample: u64, seed: u64) -> u64 {
    let a = mix64(pixel ^ mix64(seed.wrapping_add(0x9E37_79B9_7F4A_7C15)));
    mix64(a ^ sample.wrapping_mul(0xD1B5_4A32_D192_ED03))
}

#[inline]
fn hash_dimension(key: u64, dimension: u64) -> u64 {
    mix64(key ^ dimension.wrapping_mul(0xA24B_AED4_963E_E407))
}

/// Uniform in [0, 1) from a hash.
#[inline]
pub fn to_unit(h: u64) -> f64 {
    (h >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}

/// The random stream of one sample of one pixel, in two kinds of numbers.
///
/// `uniform(d)` is white noise: dimension `d` equals `to_unit(hash4(pixel, sample, d, seed))`
/// (the dimension-free part of the hash is mixed once, when the stream is made, so each
/// number costs one mix).
///
/// `stratified(d)` and `stratified2(d)` are a padded, shuffled and Owen-scrambled Sobol
/// sequence over the pixel's samples (Burley, "Practical Hash-based Owen Scrambling", 2020;
/// pbrt-v4's padded Sobol sampler): each dimension (or pair) of each pixel draws from its own
/// scrambled copy of Sobol's first two dimensions, a (0, 2)-sequence, at a sample index
/// shuffled per dimension by a nested scramble. The shuffle maps every aligned block of 2^k
/// sample indices onto an aligned block of 2^k Sobol points, so the first 2^k samples of a
/// pixel (or any aligned 2^k of them) hold one point in each elementary interval of area
/// 2^-k in every pair of a dimension, a stratification that lowers the variance of smooth
/// integrands well below white noise's, while distinct dimensions stay independent. Each
/// point is uniform over [0, 1)^2 on its own, so estimates stay unbiased, and it is a pure
/// function of (pixel, sample, dimension, seed) like the rest.
#[derive(Clone, Copy, Debug)]
pub struct SampleStream {
    key: u64,
    /// Hash of the pixel and seed, without the sample: the scrambles of a dimension are the
    /// same for all samples of a pixel, as a stratified sequence needs.
    pixel_key: u64,
    /// The sample index within the pixel (its low 32 bits index the Sobol sequence).
    sample: u32,
}

impl SampleStream {
    /// The stream of sample `sample` of pixel `pixel` (any 64-bit pixel key) under `seed`.
    #[inline]
    pub fn new(pixel: u64, sample: u64, seed: u64) -> Self {
        Self {
            key: stream_key(pixel, sample, seed),
            pixel_key: stream_key(pixel, u64::MAX, seed),
            sample: sample as u32,
        }
    }

    /// Uniform in [0, 1) for dimension `d`.
    #[inline]
    pub fn uniform(&self, d: u64) -> f64 {
        to_unit(hash_dimension(self.key, d))
    }

    /// Two uniforms.
    #[inline]
    pub fn uniform2(&self, d: u64) -> DVec2 {
        DVec2::new(self.uniform(d), self.uniform(d + 1))
    }

    /// The Sobol index of this sample in dimension `d`'s shuffle, and the dimension's hash.
    #[inline]
    fn shuffled(&self, d: u64) -> (u32, u64) {
        let hash = hash_dimension(self.pixel_key, d);
        (nested_uniform_scramble(self.sample, hash as u32), hash)
    }

    /// Uniform in [0, 1) for dimension `d`, stratified over the pixel's samples: the scrambled
    /// van der Corput sequence.
    #[inline]
    pub fn stratified(&self, d: u64) -> f64 {
        let (index, hash) = self.shuffled(d);
        // The van der Corput point of `index` has the bits of `index` reversed.
        fraction(owen_scramble_reversed(index, (hash >> 32) as u32))
    }

    /// A point of [0, 1)^2 for dimensions `d` and `d + 1`, stratified over the pixel's
    /// samples as a pair: the scrambled (0, 2)-sequence.
    #[inline]
    pub fn stratified2(&self, d: u64) -> DVec2 {
        let (index, hash) = self.shuffled(d);
        let y_seed = mix64(hash) as u32;
        DVec2::new(
            fraction(owen_scramble_reversed(index, (hash >> 32) as u32)),
            fraction(owen_scramble_reversed(sobol_second(index).reverse_bits(), y_seed)),
        )
    }
}

/// A nested uniform (Owen) scramble of the bits of `x` keyed by `seed`: each output bit is
/// its input bit flipped by a function of the bits above it. Applied to sample indices, it
/// permutes every aligned block of 2^k indices among the aligned blocks of 2^k.
#[inline]
fn nested_uniform_scramble(x: u32, seed: u32) -> u32 {
    owen_scramble_reversed(x.reverse_bits(), seed)
}

/// A 32-bit fraction to [0, 1).
#[inline]
fn fraction(bits: u32) -> f64 {
    f64::from(bits) * FRACTION_SCALE
}

/// Kensler's permutation of `i` in [0, l) keyed by `p` ("Correlated Multi-Jittered
/// Sampling", Pixar 2013).
fn permute(mut i: u32, l: u32, p: u32) -> u32 {
    let mut w = l - 1;
    w |= w >> 1;
    w |= w >> 2;
    w |= w >> 4;
    w |= w >> 8;
    w |= w >> 16;
    loop {
        i ^= p;
        i = i.wrapping_mul(0xe170_893d);
        i ^= p >> 16;
        i ^= (i & w) >> 4;
        i ^= p >> 8;
        i = i.wrapping_mul(0x0929_eb3f);
        i ^= p >> 23;
        i ^= (i & w) >> 1;
        i = i.wrapping_mul(1 | (p >> 27));
        i = i.wrapping_mul(0x6935_fa69);
        i ^= (i & w) >> 11;
        i = i.wrapping_mul(0x74dc_b303);
        i ^= (i & w) >> 2;
        i = i.wrapping_mul(0x9e50_1cc3);
        i ^= (i & w) >> 2;
        i = i.wrapping_mul(0xc860_a3df);
        i &= w;
        i ^= i >> 5;
        if i < l {
            break;
        }
    }
    (i.wrapping_add(p)) % l
}

fn randfloat(i: u32, p: u32) -> f64 {
    let mut i = i;
    i ^= p;
    i ^= i >> 17;
    i ^= i >> 10;
    i = i.wrapping_mul(0xb365_34e5);
    i ^= i >> 12;
    i ^= i >> 21;
    i = i.wrapping_mul(0x93fc_4795);
    i ^= 0xdf6e_307f;
    i ^= i >> 17;
    i = i.wrapping_mul(1 | (p >> 18));
    f64::from(i) * (1.0 / 4_294_967_808.0)
}

/// Sample `s` of `n` correlated multi-jittered samples in [0, 1)^2 for pattern `p`: each
/// sample sits in its own cell of an m x k grid and in its own row and column strata.
///
/// When `n` is not `m * k` the grid has more cells than samples: the samples take a random
/// subset of the cells (the permutation runs over all `m * k`), so that every point of the
/// square is equally likely over patterns. (Permuting over `n` alone would leave the last
/// row's remaining cells empty in every pattern: a biased pixel integral.)
pub fn cmj(s: u32, n: u32, p: u32) -> DVec2 {
    let m = (f64::from(n).sqrt() as u32).max(1);
    let k = n.div_ceil(m);
    let s = permute(s, m * k, p.wrapping_mul(0x51633e2d));
    let sx = permute(s % m, m, p.wrapping_mul(0x68bc21eb));
    let sy = permute(s / m, k, p.wrapping_mul(0x02e5be93));
    place(s, p, (s % m, s / m), (sx, sy), (1.0 / f64::from(m), 1.0 / f64::from(k)))
}

/// The point of permuted sample `s` in cell (col, row) of the m x k grid, at stratum
/// (sx, sy) within it, jittered by hashes of `s` and `p`.
#[inline]
fn place(s: u32, p: u32, (col, row): (u32, u32), (sx, sy): (u32, u32), (inv_m, inv_k): (f64, f64)) -> DVec2 {
    let jx = randfloat(s, p.wrapping_mul(0x967a889b));
    let jy = randfloat(s, p.wrapping_mul(0x368cc8b7));
    DVec2::new(
        ((f64::from(col) + (f64::from(sy) + jx) * inv_k) * inv_m).min(1.0 - f64::EPSILON),
        ((f64::from(row) + (f64::from(sx) + jy) * inv_m) * inv_k).min(1.0 - f64::EPSILON),
    )
}

/// The `n` samples of [`cmj`] for one pattern, with the work shared by all of them done
/// once (the row and column permutations are tabulated): `sample(s)` equals
/// `cmj(s, n, p)` bit for bit, at a fraction of the cost when a pixel takes many samples.
pub struct CmjPattern {
    /// Cells of the m x k grid (at least the sample count).
    cells: u32,
    m: u32,
    p: u32,
    /// 1 / m and 1 / k.
    inverse_sizes: (f64, f64),
    /// `permute(c, m, ..)` for every column c, then `permute(r, k, ..)` for every row r.
    table: PermutationTable,
}

/// The tabulated permutations: inline for up to [`INLINE_TABLE`] entries (over 4,000
/// samples per pixel), so that the common per-pixel patterns never allocate; on the heap
/// beyond (an empty `Vec` does not allocate).
struct PermutationTable {
    inline: [u32; INLINE_TABLE],
    heap: Vec<u32>,
}

const INLINE_TABLE: usize = 128;

impl PermutationTable {
    fn new(len: u32, entry: impl Fn(u32) -> u32) -> Self {
        let mut table = Self { inline: [0; INLINE_TABLE], heap: Vec::new() };
        if len as usize <= INLINE_TABLE {
            for (i, slot) in table.inline[..len as usize].iter_mut().enumerate() {
                *slot = entry(i as u32);
            }
        } else {
            table.heap = (0..len).map(entry).collect();
        }
        table
    }

    #[inline]
    fn get(&self, i: u32) -> u32 {
        if self.heap.is_empty() { self.inline[i as usize] } else { self.heap[i as usize] }
    }
}

impl CmjPattern {
    /// The pattern of `n` samples keyed by `p`.
    pub fn new(n: u32, p: u32) -> Self {
        let m = (f64::from(n).sqrt() as u32).max(1);
        let k = n.div_ceil(m);
        let entry = |i: u32| {
            if i < m {
                permute(i, m, p.wrapping_mul(0x68bc21eb))
            } else {
                permute(i - m, k, p.wrapping_mul(0x02e5be93))
            }
        };
        let table = PermutationTable::new(m + k, entry);
        Self { cells: m * k, m, p, inverse_sizes: (1.0 / f64::from(m), 1.0 / f64::from(k)), table }
    }

    /// Sample `s` (0 <= s < n) in [0, 1)^2.
    pub fn sample(&self, s: u32) -> DVec2 {
        let (m, p) = (self.m, self.p);
        // Over every cell of the grid, as in [`cmj`].
        let s = permute(s, self.cells, p.wrapping_mul(0x51633e2d));
        let (col, row) = (s % m, s / m);
        place(s, p, (col, row), (self.table.get(col), self.table.get(m + row)), self.inverse_sizes)
    }
}

/// Points a render draws all its stratified pixel patterns from: correlated multi-jittered
/// patterns of `samples` points, made once per render for many pattern keys, both in the
/// unit square (pixel offsets) and mapped onto the unit disc (lens positions).
///
/// Making a pattern per pixel (Kensler's permutations, the disc mapping) cost a third of a
/// focal-blur render; a pixel now hashes its key to two of the tabulated patterns, one for
/// its offsets and another for its lens positions, whose independent sample orders pair
/// them at random. The table depends only on the sample count and the seed, so images stay
/// the same for any thread count or tiling. Counts above [`PatternTable::MAX_TABULATED`]
/// (where a pixel's rays outweigh its pattern) make each pixel's own patterns instead.
pub struct PatternTable {
    samples: u32,
    /// Patterns in the table (0 when patterns are made per pixel).
    count: u64,
    /// Pattern i's points in [0, 1)^2 at `i * samples .. (i + 1) * samples`.
    square: Vec<DVec2>,
    /// The same points mapped onto the unit disc.
    disc: Vec<DVec2>,
}

/// The two patterns of one pixel: sample offsets in the pixel and lens positions.
#[allow(
    clippy::large_enum_variant,
    reason = "`Own` is large on purpose: a pixel's patterns live on its stack, not the heap"
)]
pub enum PixelPatterns<'a> {
    /// Slices of a [`PatternTable`].
    Tabulated {
        /// Offsets in [0, 1)^2.
        square: &'a [DVec2],
        /// Lens positions on the unit disc.
        disc: &'a [DVec2],
    },
    /// Patterns made for this pixel alone (very many samples), on the stack: nothing is
    /// allocated per pixel.
    Own {
        /// Offsets.
        square: CmjPattern,
        /// Lens positions (mapped onto the disc per sample).
        lens: CmjPattern,
    },
}

impl PixelPatterns<'_> {
    /// Offset of sample `s` in [0, 1)^2.
    #[inline]
    pub fn offset(&self, s: u32) -> DVec2 {
        match self {
            PixelPatterns::Tabulated { square, .. } => square[s as usize],
            PixelPatterns::Own { square, .. } => square.sample(s),
        }
    }

    /// Lens position of sample `s` on the unit disc.
    #[inline]
    pub fn lens(&self, s: u32) -> DVec2 {
        match self {
            PixelPatterns::Tabulated { disc, .. } => disc[s as usize],
            PixelPatterns::Own { lens, .. } => concentric_disc(lens.sample(s)),
        }
    }
}

impl PatternTable {
    /// Sample counts up to this are tabulated.
    pub const MAX_TABULATED: u32 = 1024;
    /// Points in a table: at least 32 patterns at the largest tabulated count, thousands at
    /// the usual ones, and 1 MiB of memory.
    const POINTS: u32 = 1 << 15;

    /// The table for `samples` per pixel under `seed`.
    pub fn new(samples: u32, seed: u64) -> Self {
        let samples = samples.max(1);
        let count = if samples <= Self::MAX_TABULATED { Self::POINTS / samples } else { 0 };
        let mut square = vec![DVec2::ZERO; (count * samples) as usize];
        let fill = |(i, points): (usize, &mut [DVec2])| {
            let pattern = CmjPattern::new(samples, Self::key(i as u64, seed));
            for (s, point) in points.iter_mut().enumerate() {
                *point = pattern.sample(s as u32);
            }
        };
        use rayon::prelude::*;
        square.par_chunks_mut(samples as usize).enumerate().for_each(fill);
        let disc = square.par_iter().map(|&u| concentric_disc(u)).collect();
        Self { samples, count: u64::from(count), square, disc }
    }

    /// A table that makes each pixel's patterns when asked, for renders that take one
    /// sample per pixel and position (nothing to tabulate).
    pub fn untabulated(samples: u32) -> Self {
        Self { samples: samples.max(1), count: 0, square: Vec::new(), disc: Vec::new() }
    }

    /// The CMJ pattern key of table entry `i`.
    fn key(i: u64, seed: u64) -> u32 {
        hash4(i, 0, u64::MAX - 1, seed) as u32
    }

    /// The patterns of the pixel (or image position) with hash `key`.
    #[inline]
    pub fn for_key(&self, key: u64) -> PixelPatterns<'_> {
        if self.count == 0 {
            return PixelPatterns::Own {
                square: CmjPattern::new(self.samples, key as u32),
                lens: CmjPattern::new(self.samples, (key >> 32) as u32),
            };
        }
        let n = self.samples as usize;
        let i = (key % self.count) as usize;
        // A different pattern for the lens: the same one would pair each offset with the lens
        // position of the same stratum.
        let j = ((key >> 32) % (self.count - 1)) as usize;
        let j = if j >= i { j + 1 } else { j };
        PixelPatterns::Tabulated { square: &self.square[i * n..(i + 1) * n], disc: &self.disc[j * n..(j + 1) * n] }
    }
}

/// Sobol's direction numbers of the first four dimensions (Joe and Kuo's primitive
/// polynomials and initial numbers), one 32-bit column per bit of the sample index: the
/// first dimension is the van der Corput sequence, the second makes the pair a
/// (0, 2)-sequence.
const SOBOL_DIRECTIONS: [[u32; 32]; 4] = sobol_directions();

/// [`SOBOL_DIRECTIONS`] with their bits reversed: the form the Owen scramble works on.
const SOBOL_DIRECTIONS_REVERSED: [[u32; 32]; 4] = reversed(SOBOL_DIRECTIONS);

const fn reversed(directions: [[u32; 32]; 4]) -> [[u32; 32]; 4] {
    let mut out = directions;
    let mut d = 0;
    while d < 4 {
        let mut k = 0;
        while k < 32 {
            out[d][k] = directions[d][k].reverse_bits();
            k += 1;
        }
        d += 1;
    }
    out
}

const fn sobol_directions() -> [[u32; 32]; 4] {
    // (degree s, coefficients a, initial numbers m) of dimensions 2, 3 and 4.
    const POLYNOMIALS: [(usize, u32, [u32; 3]); 3] = [(1, 0, [1, 0, 0]), (2, 1, [1, 3, 0]), (3, 1, [1, 3, 1])];
    let mut directions = [[0u32; 32]; 4];
    let mut k = 0;
    while k < 32 {
        directions[0][k] = 1 << (31 - k);
        k += 1;
    }
    let mut d = 0;
    while d < 3 {
        let (s, a, m) = POLYNOMIALS[d];
        let v = &mut directions[d + 1];
        let mut k = 0;
        while k < 32 {
            v[k] = if k < s {
                m[k] << (31 - k)
            } else {
                let mut value = v[k - s] ^ (v[k - s] >> s);
                let mut j = 1;
                while j < s {
                    if (a >> (s - 1 - j)) & 1 == 1 {
                        value ^= v[k - j];
                    }
                    j += 1;
                }
                value
            };
            k += 1;
        }
        d += 1;
    }
    directions
}

/// Coordinate `dimension` (0..4) of point `index` of the Sobol sequence, as 32 bits of a
/// fraction.
fn sobol(index: u32, dimension: usize) -> u32 {
    let columns = &SOBOL_DIRECTIONS[dimension];
    let mut bits = index;
    let mut value = 0;
    let mut column = 0;
    while bits != 0 {
        if bits & 1 == 1 {
            value ^= columns[column];
        }
        bits >>= 1;
        column += 1;
    }
    value
}

/// [`sobol`]`(index, 1)` from four table lookups, one per byte of the index: the sequence
/// is linear over GF(2), so each byte's share is a fixed XOR of its direction numbers.
#[inline]
fn sobol_second(index: u32) -> u32 {
    let [b0, b1, b2, b3] = index.to_le_bytes();
    SOBOL_SECOND_BYTES[0][b0 as usize]
        ^ SOBOL_SECOND_BYTES[1][b1 as usize]
        ^ SOBOL_SECOND_BYTES[2][b2 as usize]
        ^ SOBOL_SECOND_BYTES[3][b3 as usize]
}

/// `SOBOL_SECOND_BYTES[k][b]`: Sobol's second coordinate of the index `b << 8k`.
const SOBOL_SECOND_BYTES: [[u32; 256]; 4] = sobol_second_bytes();

const fn sobol_second_bytes() -> [[u32; 256]; 4] {
    let mut table = [[0u32; 256]; 4];
    let mut k = 0;
    while k < 4 {
        let mut b = 0;
        while b < 256 {
            let mut value = 0;
            let mut bit = 0;
            while bit < 8 {
                if (b >> bit) & 1 == 1 {
                    value ^= SOBOL_DIRECTIONS[1][8 * k + bit];
                }
                bit += 1;
            }
            table[k][b] = value;
            b += 1;
        }
        k += 1;
    }
    table
}

/// An Owen (nested uniform) scramble, keyed by `seed`, of a 32-bit fraction given with its
/// bits reversed; returns the scrambled fraction (bits in order). By hashing (Burley,
/// "Practical Hash-based Owen Scrambling", 2020): on the reversed bits, adding the seed and
/// XOR-ing with even multiples only carries low bits into higher ones, so each output bit of
/// the fraction depends on the bits above it alone, as a nested scramble's flips do. A
/// scrambled net is still a net, and each scrambled point is uniform.
fn owen_scramble_reversed(reversed_fraction: u32, seed: u32) -> u32 {
    let mut x = reversed_fraction.wrapping_add(seed);
    x ^= x.wrapping_mul(0x6c50_b47c);
    x ^= x.wrapping_mul(0xb82f_1e52);
    x ^= x.wrapping_mul(0xc7af_e638);
    x ^= x.wrapping_mul(0x8d22_f6e6);
    x.reverse_bits()
}

/// 2^-32: a 32-bit fraction to [0, 1).
const FRACTION_SCALE: f64 = 1.0 / 4_294_967_296.0;

/// The pixel offsets and lens positions of one pixel under adaptive sampling: an
/// Owen-scrambled Sobol sequence, whose every prefix is well stratified. The offsets are
/// dimensions 1 and 2, a (0, 2)-sequence: its first 2^k points (and every aligned block of
/// 2^k) have exactly one point in each elementary interval of area 2^-k, so a pixel that
/// stops after any number of samples holds a stratified pattern of that many points, not a
/// scattered subset of a larger one. Lens positions are dimensions 3 and 4, mapped onto the
/// disc. Each dimension has its own scramble, keyed by the pixel.
///
/// Points are taken in Gray-code order (point i is Sobol point `i ^ (i >> 1)`), which
/// permutes each aligned block of 2^k points among itself, so the prefixes are the same sets;
/// stepping to the next point then flips one direction number per dimension.
#[derive(Clone, Copy, Debug)]
pub struct ProgressivePattern {
    seeds: [u32; 4],
    /// The point the pattern stands at, and its unscrambled coordinates with their bits
    /// reversed.
    index: u32,
    sobol_reversed: [u32; 4],
}

impl ProgressivePattern {
    /// The pattern of the pixel (or image position) with hash `key`, at point 0.
    pub fn new(key: u64) -> Self {
        let seed = |d: u64| mix64(key ^ mix64(d + 1)) as u32;
        Self { seeds: [seed(0), seed(1), seed(2), seed(3)], index: 0, sobol_reversed: [0; 4] }
    }

    /// Moves to point `index`: one XOR per dimension from the point before it, computed
    /// afresh from any other.
    #[inline]
    pub fn seek(&mut self, index: u32) {
        if index == self.index {
            return;
        }
        if index == self.index.wrapping_add(1) {
            let column = index.trailing_zeros() as usize;
            for (d, value) in self.sobol_reversed.iter_mut().enumerate() {
                *value ^= SOBOL_DIRECTIONS_REVERSED[d][column];
            }
        } else {
            let gray = index ^ (index >> 1);
            self.sobol_reversed = [0, 1, 2, 3].map(|d| sobol(gray, d).reverse_bits());
        }
        self.index = index;
    }

    #[inline]
    fn coordinate(&self, dimension: usize) -> f64 {
        fraction(owen_scramble_reversed(self.sobol_reversed[dimension], self.seeds[dimension]))
    }

    /// The offset of the current point in [0, 1)^2.
    #[inline]
    pub fn offset(&self) -> DVec2 {
        DVec2::new(self.coordinate(0), self.coordinate(1))
    }

    /// The lens position of the current point on the unit disc.
    #[inline]
    pub fn lens(&self) -> DVec2 {
        concentric_disc(DVec2::new(self.coordinate(2), self.coordinate(3)))
    }
}

/// A uniformly distributed point on the unit disc (concentric mapping, which keeps strata).
pub fn concentric_disc(u: DVec2) -> DVec2 {
    let a = 2.0 * u - DVec2::ONE;
    if a.x == 0.0 && a.y == 0.0 {
        return DVec2::ZERO;
    }
    if a.x.abs() > a.y.abs() {
        let (sin, cos) = sin_cos_eighth_turn(std::f64::consts::FRAC_PI_4 * (a.y / a.x));
        DVec2::new(a.x * cos, a.x * sin)
    } else {
        // The angle is pi/2 - phi: cosine and sine swap.
        let (sin, cos) = sin_cos_eighth_turn(std::f64::consts::FRAC_PI_4 * (a.x / a.y));
        DVec2::new(a.y * sin, a.y * cos)
    }
}

/// `(sin x, cos x)` for |x| <= pi/4 from their Taylor series to x^17 and x^18, whose first
/// omitted terms are below 1e-19 there: as accurate as libm's, without its range reduction.
/// Both polynomials in x^2 are evaluated by Estrin's scheme (pairs, then pairs of pairs), a
/// dependency chain half as long as nesting them (lens sampling calls this per camera ray).
fn sin_cos_eighth_turn(x: f64) -> (f64, f64) {
    let z = x * x;
    let z2 = z * z;
    let z4 = z2 * z2;
    let z8 = z4 * z4;
    let [s0, s1, s2, s3, s4, s5, s6, s7, s8] = SINE_TERMS;
    let sin_low = (s0 + s1 * z) + z2 * (s2 + s3 * z);
    let sin_high = (s4 + s5 * z) + z2 * (s6 + s7 * z);
    let sin = (sin_low + z4 * sin_high) + z8 * s8;
    let [c0, c1, c2, c3, c4, c5, c6, c7, c8, c9] = COSINE_TERMS;
    let cos_low = (c0 + c1 * z) + z2 * (c2 + c3 * z);
    let cos_high = (c4 + c5 * z) + z2 * (c6 + c7 * z);
    let cos = (cos_low + z4 * cos_high) + z8 * (c8 + c9 * z);
    (x * sin, cos)
}

/// (-1)^k / (2k + 1)! for k = 0..=8: sin x = x (sum of these times x^2k).
const SINE_TERMS: [f64; 9] = taylor_terms(1);
/// (-1)^k / (2k)! for k = 0..=9: cos x = sum of these times x^2k.
const COSINE_TERMS: [f64; 10] = taylor_terms(0);

/// (-1)^k / (2k + shift)! for k = 0..N.
const fn taylor_terms<const N: usize>(shift: u64) -> [f64; N] {
    let mut terms = [0.0; N];
    let mut k = 0;
    while k < N {
        let mut factorial = 1u64;
        let mut i = 2;
        while i <= 2 * k as u64 + shift {
            factorial *= i;
            i += 1;
        }
        let magnitude = 1.0 / factorial as f64;
        terms[k] = if k % 2 == 0 { magnitude } else { -magnitude };
        k += 1;
    }
    terms
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cmj_is_stratified_in_rows_and_columns() {
        for n in [4u32, 9, 16, 7, 12] {
            let pts: Vec<DVec2> = (0..n).map(|s| cmj(s, n, 1234)).collect();
            assert!(pts.iter().all(|p| (0.0..1.0).contains(&p.x) && (0.0..1.0).contains(&p.y)));
            // 1-D projections: exactly one sample per 1/n stratum.
            let mut xs: Vec<u32> = pts.iter().map(|p| (p.x * f64::from(n)) as u32).collect();
            xs.sort_unstable();
            if n == 4 || n == 9 || n == 16 {
                assert_eq!(xs, (0..n).collect::<Vec<_>>(), "x strata for n = {n}");
            }
        }
    }

    #[test]
    fn tabulated_pattern_equals_cmj() {
        for (n, p) in [(1u32, 7u32), (4, 99), (7, 1234), (16, 0xdead_beef), (30, 5), (5000, 3)] {
            let pattern = CmjPattern::new(n, p);
            for s in 0..n {
                assert_eq!(pattern.sample(s), cmj(s, n, p), "n = {n}, s = {s}");
            }
        }
    }

    /// Every pixel's offsets are a stratified pattern in the square and its lens positions
    /// another pattern's points on the disc, for tabulated and per-pixel counts alike.
    #[test]
    fn pixel_patterns_are_stratified_and_distinct() {
        for n in [4u32, 9, 16, PatternTable::MAX_TABULATED + 1] {
            let table = PatternTable::new(n, 42);
            let m = f64::from(n).sqrt() as u32;
            for pixel in 0..200u64 {
                let patterns = table.for_key(hash4(pixel, 0, u64::MAX, 42));
                let offsets: Vec<DVec2> = (0..n).map(|s| patterns.offset(s)).collect();
                let lens: Vec<DVec2> = (0..n).map(|s| patterns.lens(s)).collect();
                assert!(offsets.iter().all(|p| (0.0..1.0).contains(&p.x) && (0.0..1.0).contains(&p.y)));
                assert!(lens.iter().all(|p| p.length() <= 1.0 + 1e-12));
                let mut columns: Vec<u32> = offsets.iter().map(|p| (p.x * f64::from(n)) as u32).collect();
                columns.sort_unstable();
                if m * m == n {
                    assert_eq!(columns, (0..n).collect::<Vec<_>>(), "n = {n}, pixel {pixel}");
                }
                let lens_as_offsets = (0..n).all(|s| concentric_disc(patterns.offset(s)) == patterns.lens(s));
                assert!(!lens_as_offsets, "the lens pattern must not be the offset pattern (n = {n})");
            }
        }
    }

    #[test]
    fn pattern_table_is_a_function_of_count_and_seed() {
        let (a, b, c) = (PatternTable::new(9, 1), PatternTable::new(9, 1), PatternTable::new(9, 2));
        assert_eq!(a.square, b.square);
        assert_eq!(a.disc, b.disc);
        assert_ne!(a.square, c.square);
        // Each entry is the CMJ pattern of its key.
        let pattern = CmjPattern::new(9, PatternTable::key(5, 1));
        assert!((0..9).all(|s| a.square[5 * 9 + s as usize] == pattern.sample(s)));
    }

    /// Over patterns, a sample is equally likely anywhere in the square, for any count: the
    /// top-right corner (where a partly filled last grid row ends) gets its share.
    #[test]
    fn cmj_covers_the_square_uniformly_for_any_count() {
        for n in [7u32, 12, 30, 128] {
            let patterns = 4000u32;
            let inside = (0..patterns)
                .flat_map(|p| (0..n).map(move |s| cmj(s, n, p.wrapping_mul(2_654_435_761))))
                .filter(|u| u.x >= 0.75 && u.y >= 0.75)
                .count() as f64;
            let total = f64::from(patterns * n);
            let expected = total / 16.0;
            // Stratification only lowers the variance below the binomial one.
            let sigma = (total * (1.0 / 16.0) * (15.0 / 16.0)).sqrt();
            assert!(
                (inside - expected).abs() < 5.0 * sigma,
                "n = {n}: {inside} samples in the corner, expected {expected}"
            );
        }
    }

    #[test]
    fn cmj_mean_is_centred() {
        let n = 64;
        let mean = (0..n).map(|s| cmj(s, n, 99)).fold(DVec2::ZERO, |a, b| a + b) / f64::from(n);
        assert!((mean - DVec2::splat(0.5)).length() < 0.02, "{mean}");
    }

    /// Sobol's first dimensions as their defining recurrences give them: the van der Corput
    /// sequence, and the second dimension's known first points.
    #[test]
    fn sobol_dimensions_are_the_known_sequences() {
        for i in 0..1000u32 {
            assert_eq!(sobol(i, 0), i.reverse_bits());
        }
        // Dimension 2 (direction numbers 1/2, 3/4, 5/8): 0, 1/2, 3/4, 1/4, 5/8, 1/8, 3/8, 7/8.
        let eighths: Vec<u32> = (0..8).map(|i| sobol(i, 1) >> 29).collect();
        assert_eq!(eighths, [0, 4, 6, 2, 5, 1, 3, 7]);
        // Dimension 3 (1/2, 3/4, 3/8 from m = 1, 3 and x^2 + x + 1): 0, 1/2, 3/4, 1/4, 3/8,
        // 7/8, 5/8, 1/8.
        let eighths: Vec<u32> = (0..8).map(|i| sobol(i, 2) >> 29).collect();
        assert_eq!(eighths, [0, 4, 6, 2, 3, 7, 5, 1]);
    }

    /// Every power-of-two prefix of a pixel's offsets, and every aligned block, is a
    /// (0, k, 2)-net: one point in each elementary interval of area 2^-k, whatever the
    /// scramble.
    #[test]
    fn progressive_offsets_are_nets_at_every_power_of_two() {
        for pixel in 0..20u64 {
            let mut pattern = ProgressivePattern::new(hash4(pixel, 0, u64::MAX, 9));
            for k in 0..=10u32 {
                let n = 1u32 << k;
                for start in [0, n, 3 * n] {
                    let points: Vec<DVec2> = (start..start + n)
                        .map(|i| {
                            pattern.seek(i);
                            pattern.offset()
                        })
                        .collect();
                    assert!(points.iter().all(|p| (0.0..1.0).contains(&p.x) && (0.0..1.0).contains(&p.y)));
                    assert!(is_net(&points), "pixel {pixel}, 2^{k} points from {start}");
                }
            }
        }
    }

    /// Over pixels, each sample of the progressive pattern is uniform in the square and on the
    /// disc (chi-square over a grid of cells), and offsets and lens positions are independent.
    #[test]
    fn progressive_samples_are_uniform_over_pixels() {
        use crate::test_support::chi2::assert_fits;
        let cells = 8usize;
        let pixels = 20_000u64;
        for index in [0u32, 1, 5, 31, 200] {
            let mut offsets = vec![0f64; cells * cells];
            let mut joint = vec![0f64; cells * cells];
            for pixel in 0..pixels {
                let mut pattern = ProgressivePattern::new(hash4(pixel, 0, u64::MAX, 3));
                pattern.seek(index);
                let (o, l) = (pattern.offset(), pattern.lens());
                offsets[(o.x * cells as f64) as usize * cells + (o.y * cells as f64) as usize] += 1.0;
                // The lens point's angle sector against the offset's x: independent if uniform.
                let sector = ((l.y.atan2(l.x) / std::f64::consts::TAU + 0.5) * cells as f64) as usize % cells;
                joint[(o.x * cells as f64) as usize * cells + sector] += 1.0;
            }
            let expected = vec![pixels as f64 / (cells * cells) as f64; cells * cells];
            assert_fits(&format!("sample {index}'s offset"), &offsets, &expected, 1e-4);
            assert_fits(&format!("sample {index}'s offset x and lens angle"), &joint, &expected, 1e-4);
        }
    }

    /// Stepping point by point gives the same points as seeking each one afresh.
    #[test]
    fn progressive_steps_equal_fresh_points() {
        let key = hash4(77, 0, u64::MAX, 5);
        let mut stepped = ProgressivePattern::new(key);
        for i in 0..5000u32 {
            stepped.seek(i);
            let mut fresh = ProgressivePattern::new(key);
            fresh.seek(i);
            if i > 0 {
                // From point 0, `seek` to a point other than 1 recomputes it.
                assert_eq!(fresh.sobol_reversed, stepped.sobol_reversed, "point {i}");
            }
            assert_eq!((stepped.offset(), stepped.lens()), (fresh.offset(), fresh.lens()), "point {i}");
        }
    }

    /// Whether `points` hold exactly one point in each elementary interval of area
    /// 1 / points.len() (a power of two): a (0, k, 2)-net.
    fn is_net(points: &[DVec2]) -> bool {
        let n = points.len() as u32;
        let k = n.trailing_zeros();
        (0..=k).all(|columns_log| {
            let (columns, rows) = (1u32 << columns_log, 1u32 << (k - columns_log));
            let mut cells = vec![0u32; n as usize];
            for p in points {
                let cell = (p.x * f64::from(columns)) as u32 * rows + (p.y * f64::from(rows)) as u32;
                cells[cell as usize] += 1;
            }
            cells.iter().all(|&c| c == 1)
        })
    }

    /// In every dimension pair of every pixel, the first 2^k samples and every aligned block
    /// of 2^k are a (0, k, 2)-net, and in every single dimension they fill the 2^k strata of
    /// [0, 1) once each.
    #[test]
    fn stratified_streams_are_nets_at_every_power_of_two() {
        for pixel in 0..12u64 {
            for d in [0u64, 5, 13, 1000] {
                for k in 0..=9u32 {
                    let n = 1u64 << k;
                    for start in [0, n, 5 * n] {
                        let streams: Vec<SampleStream> =
                            (start..start + n).map(|s| SampleStream::new(pixel, s, 3)).collect();
                        let pairs: Vec<DVec2> = streams.iter().map(|s| s.stratified2(d)).collect();
                        assert!(pairs.iter().all(|p| (0.0..1.0).contains(&p.x) && (0.0..1.0).contains(&p.y)));
                        assert!(is_net(&pairs), "pixel {pixel}, dimension {d}, 2^{k} samples from {start}");
                        let mut strata = vec![0u32; n as usize];
                        for s in &streams {
                            strata[(s.stratified(d) * n as f64) as usize] += 1;
                        }
                        assert!(strata.iter().all(|&c| c == 1), "pixel {pixel}, dimension {d}, 2^{k} from {start}");
                    }
                }
            }
        }
    }

    /// Distinct dimensions of a pixel are independent: over 4,096 samples of one pixel, pairs
    /// of stratified numbers from two dimensions (and a number against a pair's coordinate)
    /// fill a grid as independent uniforms would. Scrambling without the per-dimension shuffle
    /// would fail: every dimension would share its first bits' strata.
    #[test]
    fn stratified_dimensions_are_independent() {
        use crate::test_support::chi2::assert_fits;
        let cells = 8usize;
        let samples = 4096u64;
        for pixel in [0u64, 17, 999] {
            let mut ones = vec![0f64; cells * cells];
            let mut pairs = vec![0f64; cells * cells];
            for s in 0..samples {
                let stream = SampleStream::new(pixel, s, 11);
                let cell = |u: f64| (u * cells as f64) as usize;
                ones[cell(stream.stratified(4)) * cells + cell(stream.stratified(7))] += 1.0;
                pairs[cell(stream.stratified2(8).y) * cells + cell(stream.stratified2(12).x)] += 1.0;
            }
            let expected = vec![samples as f64 / (cells * cells) as f64; cells * cells];
            assert_fits(&format!("pixel {pixel}, dimensions 4 and 7"), &ones, &expected, 1e-4);
            assert_fits(&format!("pixel {pixel}, pairs 8 and 12"), &pairs, &expected, 1e-4);
        }
    }

    /// Over pixels, each sample's stratified numbers are uniform (chi-square over a grid).
    #[test]
    fn stratified_samples_are_uniform_over_pixels() {
        use crate::test_support::chi2::assert_fits;
        let cells = 8usize;
        let pixels = 20_000u64;
        for sample in [0u64, 1, 6, 255] {
            let mut pairs = vec![0f64; cells * cells];
            let mut ones = vec![0f64; cells];
            for pixel in 0..pixels {
                let stream = SampleStream::new(pixel, sample, 5);
                let p = stream.stratified2(20);
                pairs[(p.x * cells as f64) as usize * cells + (p.y * cells as f64) as usize] += 1.0;
                ones[(stream.stratified(21) * cells as f64) as usize] += 1.0;
            }
            assert_fits(&format!("sample {sample}'s pair"), &pairs, &[pixels as f64 / 64.0; 64], 1e-4);
            assert_fits(&format!("sample {sample}'s number"), &ones, &[pixels as f64 / 8.0; 8], 1e-4);
        }
    }

    #[test]
    fn second_sobol_dimension_from_bytes_equals_the_sum_over_bits() {
        for i in (0..100_000u32).chain([u32::MAX, 0x8000_0000, 0x1234_5678]) {
            let index = i.wrapping_mul(0x9E37_79B9);
            assert_eq!(sobol_second(index), sobol(index, 1), "{index:#x}");
        }
    }

    #[test]
    fn streams_equal_the_full_hash() {
        for (pixel, sample, seed) in [(0, 0, 0), (12345, 7, 99), (u64::MAX, 3, 1 << 40)] {
            let stream = SampleStream::new(pixel, sample, seed);
            for d in [0, 1, 5, 1000, u64::MAX] {
                assert_eq!(stream.uniform(d), to_unit(hash4(pixel, sample, d, seed)));
            }
        }
    }

    #[test]
    fn hashes_are_uniform_enough() {
        let n = 100_000;
        let mean: f64 = (0..n).map(|i| to_unit(hash4(i, 0, 0, 7))).sum::<f64>() / n as f64;
        assert!((mean - 0.5).abs() < 0.005, "{mean}");
    }

    #[test]
    fn eighth_turn_sine_and_cosine_match_libm() {
        for i in -1000..=1000 {
            let x = f64::from(i) / 1000.0 * std::f64::consts::FRAC_PI_4;
            let (sin, cos) = sin_cos_eighth_turn(x);
            assert!((sin - x.sin()).abs() <= 2.0 * f64::EPSILON, "sin {x}");
            assert!((cos - x.cos()).abs() <= 2.0 * f64::EPSILON, "cos {x}");
        }
    }

    #[test]
    fn disc_points_are_inside() {
        for i in 0..100 {
            let p = concentric_disc(DVec2::new(to_unit(hash4(i, 1, 0, 0)), to_unit(hash4(i, 1, 1, 0))));
            assert!(p.length() <= 1.0 + 1e-12);
        }
    }
}
