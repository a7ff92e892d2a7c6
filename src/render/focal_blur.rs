//! POV-Ray 3.7's adaptive focal blur (`blur_samples min, max`, `variance`, `confidence`;
//! `TracePixel::TraceRayWithFocalBlur` and `FocalBlurData` in POV-Ray's `tracepixel.cpp`).
//!
//! A pixel's lens samples are taken in batches whose ends follow POV-Ray's hexagonal lens
//! grids (rings of 7, 6, 6, 4, 4, 4, 4, 2 points, then 4 at a time). After each batch the
//! variance of the mean of every channel, `(S2/n - (S1/n)^2) / n`, is compared with
//! `threshold[n - 1] = variance * chdtri(n, confidence) / chdtri(max - 1, confidence)`; when
//! every channel is below it and at least `min` samples are taken, the pixel stops. It
//! always stops at `max`. `chdtri(df, y)` is Cephes' inverse of the complemented chi-square
//! distribution: the `x` whose upper tail is `y`, i.e. the `1 - confidence` quantile.
//!
//! POV-Ray also tests the transmit channel; Prism's samples carry no transmit (it is 0 for
//! every sample of a POV-Ray render without an alpha channel), so only RGB is tested.

use glam::DVec3;

/// POV-Ray's batch sizes for a blur of at least 37, 19 and 7 samples (`HexGrid4Samples`,
/// `HexGrid3Samples`, `HexGrid2Samples`); every later batch, and every batch of a smaller
/// blur, is 4 samples.
const HEX_GRID_4_BATCHES: [u32; 8] = [7, 6, 6, 4, 4, 4, 4, 2];
const HEX_GRID_3_BATCHES: [u32; 3] = [7, 6, 6];
const HEX_GRID_2_BATCHES: [u32; 1] = [7];
const LATER_BATCH: u32 = 4;

/// Degrees of freedom above which the chi-square quantile is Wilson and Hilferty's
/// approximation (relative error below 1e-5 there) instead of the inverted incomplete gamma.
const WILSON_HILFERTY_DOF: f64 = 1024.0;

/// The samples a pixel has taken at the end of each of its batches, for a blur of `max`
/// samples: increasing, the last one `max`.
pub fn batch_ends(max: u32) -> Vec<u32> {
    let first: &[u32] = if max >= 37 {
        &HEX_GRID_4_BATCHES
    } else if max >= 19 {
        &HEX_GRID_3_BATCHES
    } else if max >= 7 {
        &HEX_GRID_2_BATCHES
    } else {
        &[]
    };
    let mut ends = Vec::new();
    let mut taken = 0u32;
    let mut sizes = first.iter().copied().chain(std::iter::repeat(LATER_BATCH));
    while taken < max {
        taken = taken.saturating_add(sizes.next().unwrap_or(LATER_BATCH)).min(max);
        ends.push(taken);
    }
    ends
}

/// The stopping rule of one render: the batch ends of a blur of `max` samples with the
/// variance threshold at each.
#[derive(Clone, Debug, PartialEq)]
pub struct BlurSchedule {
    variance: f64,
    confidence: f64,
    min_samples: u32,
    max_samples: u32,
    /// (samples taken, threshold on the variance of the mean) at each batch end.
    ends: Vec<(u32, f64)>,
}

impl BlurSchedule {
    /// The schedule of a blur of at most `max_samples` (at least 1) and at least
    /// `min_samples` lens samples per pixel, stopping once the variance of the mean is below
    /// `variance` scaled by POV-Ray's chi-square ratio at `confidence` (in (0, 1)).
    pub fn new(variance: f64, confidence: f64, min_samples: u32, max_samples: u32) -> Self {
        let max_samples = max_samples.max(1);
        // POV-Ray: T1 = variance / chdtri(max - 1, c); threshold[i] = T1 * chdtri(i + 1, c),
        // and all thresholds 0 (never stop early) for a single sample.
        let scale = if max_samples > 1 { variance / chdtri(f64::from(max_samples - 1), confidence) } else { 0.0 };
        let ends = batch_ends(max_samples)
            .into_iter()
            .map(|n| (n, if max_samples > 1 { scale * chdtri(f64::from(n), confidence) } else { 0.0 }))
            .collect();
        Self { variance, confidence, min_samples: min_samples.clamp(1, max_samples), max_samples, ends }
    }

    /// The same rule for a blur of `max_samples` (the minimum kept below it).
    pub fn with_max(&self, max_samples: u32) -> Self {
        Self::new(self.variance, self.confidence, self.min_samples, max_samples)
    }

    /// The most samples a pixel takes.
    pub fn max_samples(&self) -> u32 {
        self.max_samples
    }

    /// A fresh test for one pixel.
    pub fn test(&self) -> BlurTest<'_> {
        BlurTest { schedule: self, sum: DVec3::ZERO, squares: DVec3::ZERO, taken: 0, batch: 0 }
    }
}

/// One pixel's running test: the sums POV-Ray keeps (`S1`, `S2`) and the batch it is in.
#[derive(Clone, Debug)]
pub struct BlurTest<'a> {
    schedule: &'a BlurSchedule,
    sum: DVec3,
    squares: DVec3,
    taken: u32,
    batch: usize,
}

impl BlurTest<'_> {
    /// Adds the next sample's colour; true when the pixel is done (after this sample).
    pub fn add(&mut self, colour: DVec3) -> bool {
        self.taken += 1;
        self.sum += colour;
        self.squares += colour * colour;
        let Some(&(end, threshold)) = self.schedule.ends.get(self.batch) else { return true };
        if self.taken < end {
            return false;
        }
        self.batch += 1;
        if self.taken >= self.schedule.max_samples {
            return true;
        }
        let n = f64::from(self.taken);
        let mean = self.sum / n;
        let variance_of_mean = (self.squares / n - mean * mean) / n;
        // POV-Ray's `IsNearZero`: |v| < threshold in every channel (so 0 never stops).
        self.taken >= self.schedule.min_samples && variance_of_mean.abs().max_element() < threshold
    }

    /// Samples added so far.
    pub fn taken(&self) -> u32 {
        self.taken
    }
}

/// Cephes' `chdtri(df, y)`, which POV-Ray's thresholds use: the `x` whose upper chi-square
/// tail with `df` degrees of freedom is `y`.
fn chdtri(df: f64, y: f64) -> f64 {
    chi_square_quantile(1.0 - y, df)
}

/// The `p` quantile of the chi-square distribution with `dof` degrees of freedom: the `x`
/// with `P(dof / 2, x / 2) = p` (regularized lower incomplete gamma), by bisection; above
/// 1024 degrees of freedom Wilson and Hilferty's cube-root normal approximation.
pub fn chi_square_quantile(p: f64, dof: f64) -> f64 {
    if !(p > 0.0 && dof > 0.0) {
        return 0.0;
    }
    if p >= 1.0 {
        return f64::INFINITY;
    }
    if dof > WILSON_HILFERTY_DOF {
        let k = 2.0 / (9.0 * dof);
        let cube = 1.0 - k + normal_quantile(p) * k.sqrt();
        return dof * (cube.max(0.0)).powi(3);
    }
    let a = 0.5 * dof;
    // Bracket: the upper tail at `high` must be below 1 - p; compare tails to keep
    // precision for p near 1.
    let tail = 1.0 - p;
    let (mut low, mut high) = (0.0, dof.max(1.0));
    while upper_gamma(a, 0.5 * high) > tail {
        low = high;
        high *= 2.0;
    }
    for _ in 0..200 {
        let mid = 0.5 * (low + high);
        if mid <= low || mid >= high {
            break;
        }
        if upper_gamma(a, 0.5 * mid) > tail {
            low = mid;
        } else {
            high = mid;
        }
    }
    0.5 * (low + high)
}

/// The regularized upper incomplete gamma function Q(a, x) = 1 - P(a, x): the series of P
/// below x = a + 1, Legendre's continued fraction (modified Lentz) above (Numerical Recipes'
/// `gser` and `gcf`).
fn upper_gamma(a: f64, x: f64) -> f64 {
    if x <= 0.0 {
        return 1.0;
    }
    let log_front = a * x.ln() - x - ln_gamma(a);
    if x < a + 1.0 {
        let (mut term, mut sum, mut n) = (1.0 / a, 1.0 / a, a);
        for _ in 0..10_000 {
            n += 1.0;
            term *= x / n;
            sum += term;
            if term.abs() < sum.abs() * 1e-16 {
                break;
            }
        }
        1.0 - sum * log_front.exp()
    } else {
        const TINY: f64 = 1e-300;
        let mut b = x + 1.0 - a;
        let mut c = 1.0 / TINY;
        let mut d = 1.0 / b;
        let mut h = d;
        for i in 1..10_000 {
            let an = -f64::from(i) * (f64::from(i) - a);
            b += 2.0;
            d = an * d + b;
            if d.abs() < TINY {
                d = TINY;
            }
            c = b + an / c;
            if c.abs() < TINY {
                c = TINY;
            }
            d = 1.0 / d;
            let delta = d * c;
            h *= delta;
            if (delta - 1.0).abs() < 1e-16 {
                break;
            }
        }
        log_front.exp() * h
    }
}

/// ln Γ(x) for x > 0 (Lanczos, g = 7, nine coefficients; relative error about 1e-15).
fn ln_gamma(x: f64) -> f64 {
    const COEFFICIENTS: [f64; 9] = [
        0.999_999_999_999_809_9,
        676.520_368_121_885_1,
        -1_259.139_216_722_402_8,
        771.323_428_777_653_1,
        -176.615_029_162_140_6,
        12.507_343_278_686_905,
        -0.138_571_095_265_720_12,
        9.984_369_578_019_572e-6,
        1.505_632_735_149_311_6e-7,
    ];
    if x < 0.5 {
        // Reflection: Γ(x) Γ(1 - x) = π / sin(πx).
        let pi = std::f64::consts::PI;
        return (pi / (pi * x).sin()).ln() - ln_gamma(1.0 - x);
    }
    let x = x - 1.0;
    let mut sum = COEFFICIENTS[0];
    for (i, c) in COEFFICIENTS.iter().enumerate().skip(1) {
        sum += c / (x + i as f64);
    }
    let t = x + 7.5;
    0.5 * (2.0 * std::f64::consts::PI).ln() + (x + 0.5) * t.ln() - t + sum.ln()
}

/// The standard normal quantile (Acklam's rational approximation, relative error 1.2e-9).
fn normal_quantile(p: f64) -> f64 {
    const A: [f64; 6] = [
        -3.969_683_028_665_376e1,
        2.209_460_984_245_205e2,
        -2.759_285_104_469_687e2,
        1.383_577_518_672_69e2,
        -3.066_479_806_614_716e1,
        2.506_628_277_459_239,
    ];
    const B: [f64; 5] = [
        -5.447_609_879_822_406e1,
        1.615_858_368_580_409e2,
        -1.556_989_798_598_866e2,
        6.680_131_188_771_972e1,
        -1.328_068_155_288_572e1,
    ];
    const C: [f64; 6] = [
        -7.784_894_002_430_293e-3,
        -3.223_964_580_411_365e-1,
        -2.400_758_277_161_838,
        -2.549_732_539_343_734,
        4.374_664_141_464_968,
        2.938_163_982_698_783,
    ];
    const D: [f64; 4] =
        [7.784_695_709_041_462e-3, 3.224_671_290_700_398e-1, 2.445_134_137_142_996, 3.754_408_661_907_416];
    const LOW: f64 = 0.024_25;
    let tail = |q: f64| {
        let q = (-2.0 * q.ln()).sqrt();
        (((((C[0] * q + C[1]) * q + C[2]) * q + C[3]) * q + C[4]) * q + C[5])
            / ((((D[0] * q + D[1]) * q + D[2]) * q + D[3]) * q + 1.0)
    };
    if p < LOW {
        tail(p)
    } else if p > 1.0 - LOW {
        -tail(1.0 - p)
    } else {
        let q = p - 0.5;
        let r = q * q;
        (((((A[0] * r + A[1]) * r + A[2]) * r + A[3]) * r + A[4]) * r + A[5]) * q
            / (((((B[0] * r + B[1]) * r + B[2]) * r + B[3]) * r + B[4]) * r + 1.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn batches_follow_povray_hexagonal_rings() {
        assert_eq!(batch_ends(1), [1]);
        assert_eq!(batch_ends(6), [4, 6]);
        assert_eq!(batch_ends(7), [7]);
        assert_eq!(batch_ends(16), [7, 11, 15, 16]);
        assert_eq!(batch_ends(19), [7, 13, 19]);
        assert_eq!(batch_ends(25), [7, 13, 19, 23, 25]);
        assert_eq!(batch_ends(37), [7, 13, 19, 23, 27, 31, 35, 37]);
        assert_eq!(batch_ends(45), [7, 13, 19, 23, 27, 31, 35, 37, 41, 45]);
        let ends = batch_ends(64);
        assert_eq!(ends[..9], [7, 13, 19, 23, 27, 31, 35, 37, 41]);
        assert_eq!(ends[ends.len() - 2..], [61, 64]);
    }

    #[test]
    fn chi_square_quantiles_match_tables() {
        for (p, dof, x) in [
            (0.9, 1.0, 2.705_543),
            (0.9, 10.0, 15.987_18),
            (0.9, 100.0, 118.498_0),
            (0.1, 1.0, 0.015_790_8),
            (0.1, 10.0, 4.865_182),
            (0.1, 100.0, 82.358_1),
            (0.5, 2.0, 2.0 * std::f64::consts::LN_2),
            (0.95, 5.0, 11.070_50),
        ] {
            let got = chi_square_quantile(p, dof);
            assert!((got - x).abs() < 1e-5 * x.max(1.0), "p {p}, {dof} dof: {got}, table {x}");
        }
        // POV-Ray's chdtri(df, confidence) is the upper tail: the 1 - confidence quantile.
        assert!((chdtri(10.0, 0.9) - 4.865_182).abs() < 1e-5);
    }

    #[test]
    fn wilson_hilferty_agrees_with_the_exact_quantile_where_it_takes_over() {
        for p in [0.1, 0.5, 0.9] {
            let approximate = chi_square_quantile(p, 1025.0);
            let a = 0.5 * 1025.0;
            // The exact quantile's tail at the approximation is p's to within 1e-4.
            let tail = upper_gamma(a, 0.5 * approximate);
            assert!((tail - (1.0 - p)).abs() < 1e-4, "p {p}: tail {tail}");
            let below = chi_square_quantile(p, 1024.0);
            assert!((approximate - below - 1.0).abs() < 0.05, "p {p}: {below} then {approximate}");
        }
    }

    #[test]
    fn thresholds_are_povrays() {
        let schedule = BlurSchedule::new(1e-4, 0.9, 1, 64);
        let scale = 1e-4 / chdtri(63.0, 0.9);
        for &(n, threshold) in &schedule.ends {
            assert!((threshold - scale * chdtri(f64::from(n), 0.9)).abs() < 1e-18);
        }
        assert_eq!(schedule.ends.last().map(|e| e.0), Some(64));
        // The threshold at max - 1 samples would be the variance itself.
        assert!((scale * chdtri(63.0, 0.9) - 1e-4).abs() < 1e-18);
    }

    fn samples_taken(schedule: &BlurSchedule, colour: impl Fn(u32) -> DVec3) -> u32 {
        let mut test = schedule.test();
        let mut i = 0;
        while !test.add(colour(i)) {
            i += 1;
        }
        test.taken()
    }

    #[test]
    fn a_constant_pixel_stops_after_its_first_batch() {
        let schedule = BlurSchedule::new(1e-4, 0.9, 1, 64);
        assert_eq!(samples_taken(&schedule, |_| DVec3::new(0.3, 0.5, 0.7)), 7);
        // Never before the minimum: the first batch end at or after 20 samples.
        let schedule = BlurSchedule::new(1e-4, 0.9, 20, 64);
        assert_eq!(samples_taken(&schedule, |_| DVec3::splat(0.5)), 23);
    }

    #[test]
    fn a_noisy_pixel_runs_to_the_maximum() {
        let schedule = BlurSchedule::new(1e-4, 0.9, 7, 64);
        let noisy = |i: u32| if i.is_multiple_of(2) { DVec3::ZERO } else { DVec3::new(0.0, 1.0, 0.0) };
        assert_eq!(samples_taken(&schedule, noisy), 64);
        // Variance 0 is POV-Ray's fixed count.
        let fixed = BlurSchedule::new(0.0, 0.9, 1, 64);
        assert_eq!(samples_taken(&fixed, |_| DVec3::splat(0.5)), 64);
    }

    #[test]
    fn a_little_noise_stops_in_between() {
        let schedule = BlurSchedule::new(1e-4, 0.9, 1, 64);
        // Samples 0.5 +- 0.03: the variance of the mean, about 9e-4 / n, falls below the
        // threshold (about 2e-6 (n - 1.3 sqrt(2n))) near 30 samples.
        let taken = samples_taken(&schedule, |i| DVec3::splat(0.5 + if i.is_multiple_of(2) { 0.03 } else { -0.03 }));
        assert!(taken > 7 && taken < 64, "{taken}");
    }

    #[test]
    fn a_blurred_edge_takes_more_samples_than_a_flat_region() {
        use crate::render::integrators::classic::Classic;
        use crate::scene::load::{Embedded, load_from};
        // A sphere far in front of the sharp plane: its silhouette is blurred over several
        // pixels; the background around it is one flat colour.
        const SCENE: &str = "[render]\nwidth = 40\nheight = 24\nsamples = 64\n\
            [camera]\nposition = [0.0, 0.0, 4.0]\nvfov = 40.0\naperture = 0.4\nfocal_distance = 10.0\n\
            blur_variance = 0.0001\nblur_min_samples = 7\n\
            [world]\nbackground = [0.5, 0.6, 0.8]\n\
            [[object]]\nshape = \"sphere\"\nradius = 1.0\nmaterial = { color = [1.0, 0.5, 0.2] }\n\
            [[light]]\nposition = [2.0, 3.0, 4.0]\n";
        const FILES: Embedded = Embedded(&[("s.toml", SCENE)]);
        let mut scene = load_from(&FILES, std::path::Path::new("s.toml"), &crate::plugins::registry()).unwrap();
        let scene = crate::prepare(&mut scene).unwrap();
        let integrator = Classic::new(&scene);
        let taken = |x: u32, y: u32| crate::render::render_pixel_samples(&scene, &integrator, x, y, 0..64).2.samples;
        for corner in [(0, 0), (39, 0), (0, 23), (39, 23)] {
            assert_eq!(taken(corner.0, corner.1), 7, "flat background at {corner:?}");
        }
        let edge = (0..40).map(|x| taken(x, 12)).max().unwrap();
        assert!(edge > 20, "the row through the blurred silhouette takes at most {edge} samples");
    }
}
