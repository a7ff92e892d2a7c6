//! POV-Ray 3.7's solid noise (its `noise_generator 2`, "range corrected", the default) and
//! its turbulence, as the noise-based pigment patterns read them.
//!
//! The algorithm is POV-Ray's (`texture.cpp` in 3.7.0, `noise.cpp` and `portablenoise.cpp`
//! later): a lattice of 4096 cells per axis whose corners are hashed through a permutation
//! that POV-Ray's own linear congruential generator shuffles at start-up, each corner
//! contributing a random linear function (four coefficients from a fixed table of 267
//! values) weighted by the smoothstep of the point's position in its cell. The table values
//! and the generator's constants are POV-Ray's, so the noise is the same function.

use glam::DVec3;

/// POV-Ray's `EPSILON`: negative coordinates floor through `(int)(x - (1 - EPSILON))`.
const POV_EPSILON: f64 = 1.0e-10;
/// POV-Ray's lattice offset (`NOISE_MINX`), so negative cells hash like positive ones.
const LATTICE_MIN: i64 = -10000;
/// 2^53: from here on every f64 is a whole number.
const WHOLE_FLOATS: f64 = 9_007_199_254_740_992.0;

/// POV-Ray's `RTable`: 267 random values; entry `2 i + 1` of the working table is half of
/// entry `2 i`.
const RANDOM_VALUES: [f64; 267] = [
    -1.0,
    0.604974,
    -0.937102,
    0.414115,
    0.576226,
    -0.0161593,
    0.432334,
    0.103685,
    0.590539,
    0.0286412,
    0.46981,
    -0.84622,
    -0.0734112,
    -0.304097,
    -0.40206,
    -0.210132,
    -0.919127,
    0.652033,
    -0.83151,
    -0.183948,
    -0.671107,
    0.852476,
    0.043595,
    -0.404532,
    0.75494,
    -0.335653,
    0.618433,
    0.605707,
    0.708583,
    -0.477195,
    0.899474,
    0.490623,
    0.221729,
    -0.400381,
    -0.853727,
    -0.932586,
    0.659113,
    0.961303,
    0.325948,
    -0.750851,
    0.842466,
    0.734401,
    -0.649866,
    0.394491,
    -0.466056,
    -0.434073,
    0.109026,
    0.0847028,
    -0.738857,
    0.241505,
    0.16228,
    -0.71426,
    -0.883665,
    -0.150408,
    -0.90396,
    -0.686549,
    -0.785214,
    0.488548,
    0.0246433,
    0.142473,
    -0.602136,
    0.375845,
    -0.00779736,
    0.498955,
    -0.268147,
    0.856382,
    -0.386007,
    -0.596094,
    -0.867735,
    -0.570977,
    -0.914366,
    0.28896,
    0.672206,
    -0.233783,
    0.94815,
    0.895262,
    0.343252,
    -0.173388,
    -0.767971,
    -0.314748,
    0.824308,
    -0.342092,
    0.721431,
    -0.24004,
    -0.63653,
    0.553277,
    0.376272,
    0.158984,
    -0.452659,
    0.396323,
    -0.420676,
    -0.454154,
    0.122179,
    0.295857,
    0.0664225,
    -0.202075,
    -0.724788,
    0.453513,
    0.224567,
    -0.908812,
    0.176349,
    -0.320516,
    -0.697139,
    0.742702,
    -0.900786,
    0.471489,
    -0.133532,
    0.119127,
    -0.889769,
    -0.23183,
    -0.669673,
    -0.046891,
    -0.803433,
    -0.966735,
    0.475578,
    -0.652644,
    0.0112459,
    -0.730007,
    0.128283,
    0.145647,
    -0.619318,
    0.272023,
    0.392966,
    0.646418,
    -0.0207675,
    -0.315908,
    0.480797,
    0.535668,
    -0.250172,
    -0.83093,
    -0.653773,
    -0.443809,
    0.119982,
    -0.897642,
    0.89453,
    0.165789,
    0.633875,
    -0.886839,
    0.930877,
    -0.537194,
    0.587732,
    0.722011,
    -0.209461,
    -0.0424659,
    -0.814267,
    -0.919432,
    0.280262,
    -0.66302,
    -0.558099,
    -0.537469,
    -0.598779,
    0.929656,
    -0.170794,
    -0.537163,
    0.312581,
    0.959442,
    0.722652,
    0.499931,
    0.175616,
    -0.534874,
    -0.685115,
    0.444999,
    0.17171,
    0.108202,
    -0.768704,
    -0.463828,
    0.254231,
    0.546014,
    0.869474,
    0.875212,
    -0.944427,
    0.130724,
    -0.110185,
    0.312184,
    -0.33138,
    -0.629206,
    0.0606546,
    0.722866,
    -0.0979477,
    0.821561,
    0.0931258,
    -0.972808,
    0.0318151,
    -0.867033,
    -0.387228,
    0.280995,
    -0.218189,
    -0.539178,
    -0.427359,
    -0.602075,
    0.311971,
    0.277974,
    0.773159,
    0.592493,
    -0.0331884,
    -0.630854,
    -0.269947,
    0.339132,
    0.581079,
    0.209461,
    -0.317433,
    -0.284993,
    0.181323,
    0.341634,
    0.804959,
    -0.229572,
    -0.758907,
    -0.336721,
    0.605463,
    -0.991272,
    -0.0188754,
    -0.300191,
    0.368307,
    -0.176135,
    -0.3832,
    -0.749569,
    0.62356,
    -0.573938,
    0.278309,
    -0.971313,
    0.839994,
    -0.830686,
    0.439078,
    0.66128,
    0.694514,
    0.0565042,
    0.54342,
    -0.438804,
    -0.0228428,
    -0.687068,
    0.857267,
    0.301991,
    -0.494255,
    -0.941039,
    0.775509,
    0.410575,
    -0.362081,
    -0.671534,
    -0.348379,
    0.932433,
    0.886442,
    0.868681,
    -0.225666,
    -0.062211,
    -0.0976425,
    -0.641444,
    -0.848112,
    0.724697,
    0.473503,
    0.998749,
    0.174701,
    0.559625,
    -0.029099,
    -0.337392,
    -0.958129,
    -0.659785,
    0.236042,
    -0.246937,
    0.659449,
    -0.027512,
    0.821897,
    -0.226215,
    0.0181735,
    0.500481,
    -0.420127,
    -0.427878,
    0.566186,
];

/// The permutation (doubled to 8192 entries) and the working random table.
struct Tables {
    hash: [u16; 8192],
    random: [f64; 534],
}

/// Built at compile time: the noise reads them without a first-use check on every call.
static TABLES: Tables = tables();

const fn tables() -> Tables {
    let mut hash = [0u16; 8192];
    let mut i = 0;
    while i < 4096 {
        hash[i] = i as u16;
        i += 1;
    }
    // POV-Ray's generator: next = next * 1812433253 + 12345 in a C `int` (wrapping), the
    // index from bits 16..31.
    let mut next: i32 = 0;
    let mut i = 4096;
    while i > 0 {
        i -= 1;
        next = (next as i64 * 1812433253 + 12345) as i32;
        let j = (((next >> 16) & 0x7FFF) % 4096) as usize;
        let swapped = hash[i];
        hash[i] = hash[j];
        hash[j] = swapped;
    }
    let mut i = 0;
    while i < 4096 {
        hash[4096 + i] = hash[i];
        i += 1;
    }
    let mut random = [0.0; 534];
    let mut i = 0;
    while i < RANDOM_VALUES.len() {
        random[2 * i] = RANDOM_VALUES[i];
        random[2 * i + 1] = RANDOM_VALUES[i] * 0.5;
        i += 1;
    }
    Tables { hash, random }
}

/// POV-Ray's `Hash3d`: the lattice hash of an integer cell, each coordinate taken modulo
/// 4096 (its low twelve bits, as a two's complement `& 0xfff`), in 0..4096.
pub fn hash3d(x: i32, y: i32, z: i32) -> usize {
    let h = &TABLES.hash;
    h[h[h[(x & 0xFFF) as usize] as usize ^ (y & 0xFFF) as usize] as usize ^ (z & 0xFFF) as usize] as usize
}

/// A coordinate's lattice cell (hash index) and its offset in the cell, as POV-Ray takes
/// them.
fn cell(v: f64) -> (usize, f64) {
    if v.is_nan() || v.abs() >= WHOLE_FLOATS {
        // Every f64 this large is a whole number (and beyond 2^63 the integer cast would
        // saturate): the cell is the value modulo the lattice, the offset 0, as below. A
        // point made infinite or NaN by extreme turbulence reads cell 0.
        let whole = if v.is_finite() { v.rem_euclid(4096.0) as i64 } else { 0 };
        return (((whole - LATTICE_MIN) & 0xFFF) as usize, 0.0);
    }
    let whole = if v >= 0.0 { v as i64 } else { (v - (1.0 - POV_EPSILON)) as i64 };
    (((whole - LATTICE_MIN) & 0xFFF) as usize, v - whole as f64)
}

fn scurve(a: f64) -> f64 {
    a * a * (3.0 - 2.0 * a)
}

/// The eight corners of the cell of `p`: per corner its random-table index and its weight
/// and offset from the point. Inlined into each noise, so that the corners never go through
/// memory; the four hashes of the cell's (x, y) edges are shared by the corners above them.
#[inline(always)]
fn corners(t: &Tables, p: DVec3) -> [(usize, f64, DVec3); 8] {
    let (ix, fx) = cell(p.x);
    let (iy, fy) = cell(p.y);
    let (iz, fz) = cell(p.z);
    let (sx, sy, sz) = (scurve(fx), scurve(fy), scurve(fz));
    let (wx, wy, wz) = ([1.0 - sx, sx], [1.0 - sy, sy], [1.0 - sz, sz]);
    let (ox, oy, oz) = ([fx, fx - 1.0], [fy, fy - 1.0], [fz, fz - 1.0]);
    // Cells are below 4096 and so are the table's values: every index is below 8192.
    let hash = |i: usize| t.hash[i & 0x1FFF] as usize;
    let column = [hash(ix), hash(ix + 1)];
    let edge = |dx: usize, dy: usize| hash(column[dx] ^ (iy + dy));
    let edges = [edge(0, 0), edge(1, 0), edge(0, 1), edge(1, 1)];
    std::array::from_fn(|k| {
        let (dx, dy, dz) = (k & 1, (k >> 1) & 1, k >> 2);
        let m = (hash(edges[k & 3] ^ (iz + dz)) & 0xFF) * 2;
        (m, wx[dx] * wy[dy] * wz[dz], DVec3::new(ox[dx], oy[dy], oz[dz]))
    })
}

/// One corner's random linear function at `offset`, from table index `m` (even, at most
/// 510) plus `shift` (0, 8 or 16: [`dnoise`]'s three components).
#[inline(always)]
fn linear(r: &[f64; 534], m: usize, shift: usize, o: DVec3) -> f64 {
    // `m` is at most 510 already; the mask tells the compiler, which drops a bounds check
    // per read (the largest index is 511 + 16 + 6 = 533).
    let m = (m & 0x1FF) + shift;
    r[m + 1] + r[m + 2] * o.x + r[m + 4] * o.y + r[m + 6] * o.z
}

/// POV-Ray's measured range of the raw noise sum, [-1.05242, 0.988997], mapped onto [0, 1].
fn noise_of_sum(sum: f64) -> f64 {
    ((sum + 1.05242) * 0.48985582).clamp(0.0, 1.0)
}

/// The raw sum of the corners' weighted linear functions, in corner order.
#[inline(always)]
fn noise_sum(t: &Tables, p: DVec3) -> f64 {
    corners(t, p).iter().map(|&(m, w, o)| w * linear(&t.random, m, 0, o)).sum()
}

/// The vector sum of the corners' weighted linear-function triples, in corner order.
#[inline(always)]
fn dnoise_sum(t: &Tables, p: DVec3) -> DVec3 {
    corners(t, p)
        .iter()
        .map(|&(m, w, o)| {
            w * DVec3::new(linear(&t.random, m, 0, o), linear(&t.random, m, 8, o), linear(&t.random, m, 16, o))
        })
        .sum()
}

/// POV-Ray's `Noise` with noise generator 2: about uniform over [0, 1], clamped to it.
pub fn noise(p: DVec3) -> f64 {
    noise_of_sum(noise_sum(&TABLES, p))
}

/// [`noise`] at two points, the same values: the two evaluations are independent chains of
/// table reads and sums, which one function body lets the processor overlap (octave loops
/// are made of such pairs).
pub fn noise_pair(a: DVec3, b: DVec3) -> [f64; 2] {
    let t = &TABLES;
    [noise_of_sum(noise_sum(t, a)), noise_of_sum(noise_sum(t, b))]
}

/// POV-Ray's `DNoise`: a vector of three noises (consecutive table entries), not clamped.
pub fn dnoise(p: DVec3) -> DVec3 {
    dnoise_sum(&TABLES, p)
}

/// [`dnoise`] at two points, the same values (see [`noise_pair`]).
pub fn dnoise_pair(a: DVec3, b: DVec3) -> [DVec3; 2] {
    let t = &TABLES;
    [dnoise_sum(t, a), dnoise_sum(t, b)]
}

/// Turbulence parameters: POV-Ray's `octaves`, `omega` and `lambda` (the latter two stored
/// in single precision, as POV-Ray does).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Octaves {
    /// Number of noise octaves summed (1 to 10).
    pub octaves: u32,
    /// Amplitude factor from one octave to the next.
    pub omega: f64,
    /// Frequency factor from one octave to the next.
    pub lambda: f64,
}

impl Default for Octaves {
    /// POV-Ray's defaults: 6 octaves, omega 0.5, lambda 2.
    fn default() -> Self {
        Self { octaves: 6, omega: 0.5, lambda: 2.0 }
    }
}

impl Octaves {
    /// `octaves` octaves, each of twice the frequency and half the amplitude of the one
    /// before (granite's six and wrinkles' ten).
    pub const fn halving(octaves: u32) -> Self {
        Self { octaves, omega: 0.5, lambda: 2.0 }
    }

    /// Every octave's (frequency, amplitude), from the first's (1, 1): evaluated in pairs
    /// (see [`noise_pair`]), summed in this order.
    fn all(&self) -> impl Iterator<Item = (f64, f64)> {
        std::iter::once((1.0, 1.0)).chain(self.higher())
    }

    /// Each octave's (frequency, amplitude) after the first (which is (1, 1)).
    fn higher(&self) -> impl Iterator<Item = (f64, f64)> {
        let (lambda, omega) = (f64::from(self.lambda as f32), f64::from(self.omega as f32));
        (2..=self.octaves).scan((lambda, omega), move |(l, o), i| {
            let here = (*l, *o);
            if i < self.octaves {
                *l *= lambda;
                *o *= omega;
            }
            Some(here)
        })
    }
}

/// POV-Ray's scalar `Turbulence` (generator 2): the first octave mapped and clamped to
/// [0, 1], the others added unclamped.
pub fn turbulence(p: DVec3, o: &Octaves) -> f64 {
    let mut value = None;
    for_each_octave(p, o, noise, noise_pair, |w, n| {
        value = Some(match value {
            None => (2.0 * n - 0.5).clamp(0.0, 1.0),
            Some(v) => v + w * (2.0 * n - 0.5),
        });
    });
    value.unwrap_or_default()
}

/// POV-Ray's vector `DTurbulence`: a sum of `dnoise` octaves.
pub fn dturbulence(p: DVec3, o: &Octaves) -> DVec3 {
    let mut value = None;
    for_each_octave(p, o, dnoise, dnoise_pair, |w, n| {
        value = Some(match value {
            None => n,
            Some(v) => v + w * n,
        });
    });
    value.unwrap_or_default()
}

/// Every octave's noise at `p` (`single`, or `pair` for two octaves at once), to `add` with
/// the octave's amplitude, in order from the first. Every octave sum goes through here, so
/// that each evaluates its octaves in pairs.
pub(super) fn for_each_octave<T>(
    p: DVec3,
    o: &Octaves,
    single: impl Fn(DVec3) -> T,
    pair: impl Fn(DVec3, DVec3) -> [T; 2],
    mut add: impl FnMut(f64, T),
) {
    let mut octaves = o.all();
    while let Some((la, wa)) = octaves.next() {
        match octaves.next() {
            Some((lb, wb)) => {
                let [na, nb] = pair(p * la, p * lb);
                add(wa, na);
                add(wb, nb);
            }
            None => add(wa, single(p * la)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn far_and_non_finite_points_read_a_cell_without_overflow() {
        // From 2^53 to 2^63 the modulo agrees with POV-Ray's integer formula.
        for v in [9_007_199_254_740_992.0, 9_007_199_254_740_992.0 * 3.0 + 4096.0 * 5.0, -1.5e17, 9.0e18] {
            let whole = v as i64;
            assert_eq!(cell(v), (((whole - LATTICE_MIN) & 0xFFF) as usize, 0.0), "{v}");
        }
        // Beyond i64 (turbulence of 1e300, or a lambda whose powers overflow) the noise and
        // its gradient stay finite.
        for v in [9.3e18, -9.3e18, 1e300, f64::INFINITY, f64::NEG_INFINITY, f64::NAN] {
            let p = DVec3::new(v, 0.5, -v);
            assert!((0.0..=1.0).contains(&noise(p)), "{v}");
            assert!(dnoise(p).is_finite(), "{v}");
        }
        let extreme = Octaves { octaves: 10, omega: 0.5, lambda: 1e300 };
        assert!(turbulence(DVec3::splat(0.3), &extreme).is_finite());
        assert!(dturbulence(DVec3::splat(0.3), &extreme).is_finite());
    }

    #[test]
    fn the_permutation_is_povrays_shuffle() {
        let t = &TABLES;
        // The generator's first steps by hand: next = 12345 (>> 16 = 0: hash[4095] <-> hash[0]),
        // then 12345 * 1812433253 + 12345 wraps to 2003875766 (>> 16 = 30576, % 4096 = 1904).
        // The ends of the finished table, from a separate emulation of POV-Ray's C loop
        // (Python, 32-bit wrapping arithmetic).
        assert_eq!(t.hash[..8], [2291, 2574, 3654, 1557, 1196, 3388, 2637, 1820]);
        assert_eq!(t.hash[4090..4096], [3061, 753, 3734, 3267, 3816, 3088]);
        let mut sorted = t.hash[..4096].to_vec();
        sorted.sort_unstable();
        assert_eq!(sorted, (0..4096).collect::<Vec<u16>>(), "a permutation");
        assert_eq!(t.hash[4096..], t.hash[..4096], "doubled");
        assert_eq!((t.random[0], t.random[1], t.random[2], t.random[3]), (-1.0, -0.5, 0.604974, 0.302487));
    }

    #[test]
    fn noise_at_lattice_points_is_the_corner_constant() {
        // At a lattice point only one corner has weight, and its offset is 0: the value is
        // the table's half entry r[m + 1], mapped by the range correction.
        let t = &TABLES;
        for p in [DVec3::ZERO, DVec3::new(3.0, -2.0, 7.0)] {
            let (ix, _) = cell(p.x);
            let (iy, _) = cell(p.y);
            let (iz, _) = cell(p.z);
            let h = t.hash[t.hash[ix] as usize ^ iy] as usize;
            let m = (t.hash[h ^ iz] as usize & 0xFF) * 2;
            let expected = ((t.random[m + 1] + 1.05242) * 0.48985582).clamp(0.0, 1.0);
            assert!((noise(p) - expected).abs() < 1e-15, "{p}");
        }
    }

    #[test]
    fn noise_is_continuous_bounded_and_spread() {
        let mut values = Vec::new();
        for i in 0..2000 {
            let p = DVec3::new(i as f64 * 0.137, (i % 37) as f64 * 0.291 - 5.0, (i % 11) as f64 * 0.77 - 3.0);
            let v = noise(p);
            assert!((0.0..=1.0).contains(&v));
            assert!((noise(p + DVec3::splat(1e-7)) - v).abs() < 1e-5, "continuous at {p}");
            values.push(v);
        }
        let mean = values.iter().sum::<f64>() / values.len() as f64;
        let spread = values.iter().cloned().fold(0.0, f64::max) - values.iter().cloned().fold(1.0, f64::min);
        assert!((0.3..0.7).contains(&mean) && spread > 0.5, "mean {mean}, spread {spread}");
    }

    /// Pairs are the single evaluations bit for bit, and the paired octave sums are POV-Ray's
    /// loops (one octave at a time, in order) for every octave count and odd factors.
    #[test]
    fn paired_octaves_are_the_sequential_sums() {
        let mut rng = prism_api::contract::TestRng::new(5);
        for _ in 0..2000 {
            let mut point = || DVec3::new(rng.range(-50.0, 50.0), rng.range(-50.0, 50.0), rng.range(-50.0, 50.0));
            let (a, b) = (point(), point());
            assert_eq!(noise_pair(a, b).map(f64::to_bits), [noise(a), noise(b)].map(f64::to_bits));
            let [da, db] = dnoise_pair(a, b);
            assert_eq!([da, db], [dnoise(a), dnoise(b)]);
            for octaves in 1..=10 {
                let o = Octaves { octaves, omega: rng.range(0.1, 0.9), lambda: rng.range(1.0, 3.0) };
                let mut scalar = (2.0 * noise(a) - 0.5).clamp(0.0, 1.0);
                let mut vector = dnoise(a);
                for (l, w) in o.higher() {
                    scalar += w * (2.0 * noise(a * l) - 0.5);
                    vector += w * dnoise(a * l);
                }
                assert_eq!(turbulence(a, &o).to_bits(), scalar.to_bits(), "{octaves} octaves");
                assert_eq!(dturbulence(a, &o).to_array().map(f64::to_bits), vector.to_array().map(f64::to_bits));
            }
        }
    }

    #[test]
    fn turbulence_is_deterministic_and_one_octave_is_the_clamped_noise() {
        let p = DVec3::new(0.3, 1.7, -2.2);
        let o = Octaves::default();
        assert_eq!(turbulence(p, &o).to_bits(), turbulence(p, &o).to_bits());
        assert_eq!(dturbulence(p, &o), dturbulence(p, &o));
        let one = Octaves { octaves: 1, ..o };
        assert_eq!(turbulence(p, &one), (2.0 * noise(p) - 0.5).clamp(0.0, 1.0));
        assert_eq!(dturbulence(p, &one), dnoise(p));
        // Two octaves add omega times the noise at lambda times the point.
        let two = Octaves { octaves: 2, omega: 0.25, lambda: 3.0 };
        let expected = (2.0 * noise(p) - 0.5).clamp(0.0, 1.0) + 0.25 * (2.0 * noise(p * 3.0) - 0.5);
        assert_eq!(turbulence(p, &two), expected);
    }
}
