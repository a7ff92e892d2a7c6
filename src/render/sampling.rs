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
    let a = mix64(pixel ^ mix64(seed.wrapping_add(0x9E37_79B9_7F4A_7C15)));
    let b = mix64(a ^ sample.wrapping_mul(0xD1B5_4A32_D192_ED03));
    mix64(b ^ dimension.wrapping_mul(0xA24B_AED4_963E_E407))
}

/// Uniform in [0, 1) from a hash.
#[inline]
pub fn to_unit(h: u64) -> f64 {
    (h >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}

/// The random stream of one sample of one pixel: dimension `d` is `uniform(d)`.
#[derive(Clone, Copy, Debug)]
pub struct SampleStream {
    /// Linear pixel index (y * width + x).
    pub pixel: u64,
    /// Sample index within the pixel.
    pub sample: u64,
    /// Scene seed.
    pub seed: u64,
}

impl SampleStream {
    /// Uniform in [0, 1) for dimension `d`.
    #[inline]
    pub fn uniform(&self, d: u64) -> f64 {
        to_unit(hash4(self.pixel, self.sample, d, self.seed))
    }

    /// Two uniforms.
    #[inline]
    pub fn uniform2(&self, d: u64) -> DVec2 {
        DVec2::new(self.uniform(d), self.uniform(d + 1))
    }
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
pub fn cmj(s: u32, n: u32, p: u32) -> DVec2 {
    let m = (f64::from(n).sqrt() as u32).max(1);
    let k = n.div_ceil(m);
    let s = permute(s, n, p.wrapping_mul(0x51633e2d));
    let sx = permute(s % m, m, p.wrapping_mul(0x68bc21eb));
    let sy = permute(s / m, k, p.wrapping_mul(0x02e5be93));
    let jx = randfloat(s, p.wrapping_mul(0x967a889b));
    let jy = randfloat(s, p.wrapping_mul(0x368cc8b7));
    DVec2::new(
        ((f64::from(s % m) + (f64::from(sy) + jx) / f64::from(k)) / f64::from(m)).min(1.0 - f64::EPSILON),
        ((f64::from(s / m) + (f64::from(sx) + jy) / f64::from(m)) / f64::from(k)).min(1.0 - f64::EPSILON),
    )
}

/// The `n` samples of [`cmj`] for one pattern, with the work shared by all of them done
/// once (the row and column permutations are tabulated): `sample(s)` equals
/// `cmj(s, n, p)` bit for bit, at a fraction of the cost when a pixel takes many samples.
pub struct CmjPattern {
    n: u32,
    m: u32,
    k: u32,
    p: u32,
    /// `permute(c, m, ..)` for every column c.
    columns: Vec<u32>,
    /// `permute(r, k, ..)` for every row r.
    rows: Vec<u32>,
}

impl CmjPattern {
    /// The pattern of `n` samples keyed by `p`.
    pub fn new(n: u32, p: u32) -> Self {
        let m = (f64::from(n).sqrt() as u32).max(1);
        let k = n.div_ceil(m);
        let columns = (0..m).map(|c| permute(c, m, p.wrapping_mul(0x68bc21eb))).collect();
        let rows = (0..k).map(|r| permute(r, k, p.wrapping_mul(0x02e5be93))).collect();
        Self { n, m, k, p, columns, rows }
    }

    /// Sample `s` (0 <= s < n) in [0, 1)^2.
    pub fn sample(&self, s: u32) -> DVec2 {
        let (m, k, p) = (self.m, self.k, self.p);
        let s = permute(s, self.n, p.wrapping_mul(0x51633e2d));
        let (col, row) = (s % m, s / m);
        let sx = self.columns[col as usize];
        let sy = self.rows[row as usize];
        let jx = randfloat(s, p.wrapping_mul(0x967a889b));
        let jy = randfloat(s, p.wrapping_mul(0x368cc8b7));
        DVec2::new(
            ((f64::from(col) + (f64::from(sy) + jx) / f64::from(k)) / f64::from(m)).min(1.0 - f64::EPSILON),
            ((f64::from(row) + (f64::from(sx) + jy) / f64::from(m)) / f64::from(k)).min(1.0 - f64::EPSILON),
        )
    }
}

/// A uniformly distributed point on the unit disc (concentric mapping, which keeps strata).
pub fn concentric_disc(u: DVec2) -> DVec2 {
    let a = 2.0 * u - DVec2::ONE;
    if a.x == 0.0 && a.y == 0.0 {
        return DVec2::ZERO;
    }
    let (r, theta) = if a.x.abs() > a.y.abs() {
        (a.x, std::f64::consts::FRAC_PI_4 * (a.y / a.x))
    } else {
        (a.y, std::f64::consts::FRAC_PI_2 - std::f64::consts::FRAC_PI_4 * (a.x / a.y))
    };
    DVec2::new(r * theta.cos(), r * theta.sin())
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
        for (n, p) in [(1u32, 7u32), (4, 99), (7, 1234), (16, 0xdead_beef), (30, 5)] {
            let pattern = CmjPattern::new(n, p);
            for s in 0..n {
                assert_eq!(pattern.sample(s), cmj(s, n, p), "n = {n}, s = {s}");
            }
        }
    }

    #[test]
    fn cmj_mean_is_centred() {
        let n = 64;
        let mean = (0..n).map(|s| cmj(s, n, 99)).fold(DVec2::ZERO, |a, b| a + b) / f64::from(n);
        assert!((mean - DVec2::splat(0.5)).length() < 0.02, "{mean}");
    }

    #[test]
    fn hashes_are_uniform_enough() {
        let n = 100_000;
        let mean: f64 = (0..n).map(|i| to_unit(hash4(i, 0, 0, 7))).sum::<f64>() / n as f64;
        assert!((mean - 0.5).abs() < 0.005, "{mean}");
    }

    #[test]
    fn disc_points_are_inside() {
        for i in 0..100 {
            let p = concentric_disc(DVec2::new(to_unit(hash4(i, 1, 0, 0)), to_unit(hash4(i, 1, 1, 0))));
            assert!(p.length() <= 1.0 + 1e-12);
        }
    }
}
