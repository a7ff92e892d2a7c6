//! Test support shared by every BSDF's tests: a deterministic RNG, Mitsuba-style chi-square
//! goodness-of-fit of `sample` against `pdf`, eval/pdf/sample consistency, Monte Carlo
//! albedo and reciprocity checks.
//!
//! The chi-square test follows Mitsuba's `chi2.py`: the sphere is cut into 20 (cos θ) × 40
//! (φ) cells, each cell's expected count is N ∫cell pdf (Simpson's rule on a sub-grid),
//! cells expecting fewer than 5 samples are pooled, Pearson's statistic is compared to the
//! chi-square distribution, and the test fails when the p-value is below the Šidák-corrected
//! significance of 1% over all the chi-square tests in the suite. Delta samples, and those
//! `sample` rejects, fall in one extra cell whose expected count is what the cells leave.

use std::collections::HashMap;
use std::f64::consts::{PI, TAU};

use glam::{DVec2, DVec3};

use super::Bsdf;
use crate::render::sampling::{mix64, to_unit};
use crate::test_support::chi2::{ChiSquare, pearson};

/// Cosines of the incident directions every test uses.
pub const COS_WO: [f64; 3] = [0.9, 0.5, 0.1];
/// Roughnesses every rough lobe is tested with.
pub const ALPHAS: [f64; 3] = [0.05, 0.3, 0.8];

/// Samples per chi-square test.
const SAMPLES: usize = 200_000;
const THETA_BINS: usize = 20;
const PHI_BINS: usize = 40;
/// Simpson sub-intervals per cell side (even).
const SUBDIV: usize = 4;
/// Upper bound of the chi-square tests in the suite, for the Šidák correction.
const TESTS: f64 = 120.0;
/// Family-wise significance level.
const SIGNIFICANCE: f64 = 0.01;

/// SplitMix64 through the crate's `mix64`.
pub struct Rng(u64);

impl Rng {
    /// A stream from a seed.
    pub fn new(seed: u64) -> Self {
        Rng(mix64(seed ^ 0x5EED))
    }

    /// Uniform in [0, 1).
    pub fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        to_unit(mix64(self.0))
    }

    /// Two uniforms in [0, 1).
    pub fn next2(&mut self) -> DVec2 {
        DVec2::new(self.next(), self.next())
    }
}

/// A unit direction with the given cosine to the normal (negative: below), at an azimuth
/// off the bin edges.
pub fn wo_at(cos: f64) -> DVec3 {
    let sin = (1.0 - cos * cos).max(0.0).sqrt();
    let phi: f64 = 0.37;
    DVec3::new(sin * phi.cos(), sin * phi.sin(), cos)
}

fn direction(cos: f64, phi: f64) -> DVec3 {
    let sin = (1.0 - cos * cos).max(0.0).sqrt();
    DVec3::new(sin * phi.cos(), sin * phi.sin(), cos)
}

fn cell_of(v: DVec3) -> usize {
    let t = (((v.z + 1.0) * 0.5 * THETA_BINS as f64) as usize).min(THETA_BINS - 1);
    let phi = v.y.atan2(v.x).rem_euclid(TAU);
    let p = ((phi / TAU * PHI_BINS as f64) as usize).min(PHI_BINS - 1);
    t * PHI_BINS + p
}

/// ∫ pdf over one cell: adaptive 2D Simpson in (cos θ, φ), each rectangle split in four
/// until the split changes the estimate by less than 1e-6 + 1e-4 of it (a fraction of a
/// sample at N = 200k), which resolves the narrow lobes of alpha 0.05 at grazing angles.
fn integrate_cell(bsdf: &Bsdf, wo: DVec3, t: usize, p: usize) -> f64 {
    let (c0, dc) = (-1.0 + 2.0 * t as f64 / THETA_BINS as f64, 2.0 / THETA_BINS as f64);
    let (p0, dp) = (TAU * p as f64 / PHI_BINS as f64, TAU / PHI_BINS as f64);
    let whole = simpson(bsdf, wo, c0, dc, p0, dp);
    adaptive(bsdf, wo, (c0, dc, p0, dp), whole, 0)
}

fn adaptive(bsdf: &Bsdf, wo: DVec3, (c0, dc, p0, dp): (f64, f64, f64, f64), whole: f64, depth: u32) -> f64 {
    let (hc, hp) = (dc / 2.0, dp / 2.0);
    let quads = [(c0, p0), (c0 + hc, p0), (c0, p0 + hp), (c0 + hc, p0 + hp)];
    let parts = quads.map(|(c, p)| simpson(bsdf, wo, c, hc, p, hp));
    let split: f64 = parts.iter().sum();
    if depth >= 7 || (split - whole).abs() <= 1e-6 + 1e-4 * split.abs() {
        return split;
    }
    quads.iter().zip(parts).map(|(&(c, p), part)| adaptive(bsdf, wo, (c, hc, p, hp), part, depth + 1)).sum()
}

/// Simpson's rule with SUBDIV x SUBDIV intervals on one rectangle of (cos θ, φ).
fn simpson(bsdf: &Bsdf, wo: DVec3, c0: f64, dc: f64, p0: f64, dp: f64) -> f64 {
    let weight = |i: usize| {
        if i == 0 || i == SUBDIV {
            1.0
        } else if i % 2 == 1 {
            4.0
        } else {
            2.0
        }
    };
    let mut sum = 0.0;
    for i in 0..=SUBDIV {
        let cos = c0 + dc * i as f64 / SUBDIV as f64;
        for j in 0..=SUBDIV {
            let phi = p0 + dp * j as f64 / SUBDIV as f64;
            sum += weight(i) * weight(j) * bsdf.pdf(wo, direction(cos, phi));
        }
    }
    sum * (dc / SUBDIV as f64 / 3.0) * (dp / SUBDIV as f64 / 3.0)
}

fn relative(a: f64, b: f64) -> f64 {
    (a - b).abs() / a.abs().max(b.abs()).max(1e-300)
}

/// The chi-square test of `bsdf.sample` against `bsdf.pdf` for one `wo`, plus per sample:
/// `pdf(wo, wi) == sample.pdf` and `weight == eval / pdf` (relative 1e-6) for non-delta
/// samples, finite values, unit directions; and the delta samples' fraction against the sum
/// of the delta lobes' selection probabilities (binomial, 5 sigma). Returns the p-value.
pub fn check(bsdf: &Bsdf, wo: DVec3, label: &str) -> f64 {
    let mut rng = Rng::new(mix64(wo.z.to_bits()) ^ label.len() as u64);
    let mut observed = vec![0.0; THETA_BINS * PHI_BINS];
    let mut delta_count = 0usize;
    // Delta lobes are deterministic given wo: one probability per distinct direction.
    let mut delta_lobes: HashMap<[i64; 3], f64> = HashMap::new();
    for _ in 0..SAMPLES {
        let Some(s) = bsdf.sample(wo, rng.next(), rng.next2()) else { continue };
        assert!(s.weight.is_finite() && s.pdf.is_finite() && s.pdf > 0.0, "{label}: {s:?}");
        assert!((s.wi.length() - 1.0).abs() < 1e-9, "{label}: wi not unit {s:?}");
        if s.delta {
            delta_count += 1;
            let key = (s.wi * 1e9).round().as_i64vec3().to_array();
            delta_lobes.entry(key).or_insert(s.pdf);
            continue;
        }
        let pdf = bsdf.pdf(wo, s.wi);
        assert!(relative(pdf, s.pdf) < 1e-6, "{label}: pdf {pdf} vs sample {s:?}");
        let expected = bsdf.eval(wo, s.wi) / pdf;
        let scale = expected.abs().max_element().max(s.weight.abs().max_element()).max(1e-300);
        assert!((expected - s.weight).abs().max_element() / scale < 1e-6, "{label}: eval/pdf {expected} vs {s:?}");
        observed[cell_of(s.wi)] += 1.0;
    }

    let n = SAMPLES as f64;
    let p_delta: f64 = delta_lobes.values().sum();
    let sigma = (n * p_delta * (1.0 - p_delta)).max(0.0).sqrt();
    assert!(
        (delta_count as f64 - n * p_delta).abs() <= 5.0 * sigma + 1.0,
        "{label}: {delta_count} delta samples, expected {}",
        n * p_delta
    );

    let mut cells = Vec::with_capacity(observed.len() + 1);
    let (mut sum_o, mut sum_e) = (0.0, 0.0);
    for t in 0..THETA_BINS {
        for p in 0..PHI_BINS {
            let e = n * integrate_cell(bsdf, wo, t, p);
            let o = observed[t * PHI_BINS + p];
            sum_o += o;
            sum_e += e;
            cells.push((o, e));
        }
    }
    // Delta and rejected samples: what the cells leave.
    cells.push((n - sum_o, (n - sum_e).max(0.0)));
    let (observed, expected): (Vec<f64>, Vec<f64>) = cells.into_iter().unzip();
    let ChiSquare { statistic, dof, p_value } = pearson(&observed, &expected);
    let threshold = 1.0 - (1.0 - SIGNIFICANCE).powf(1.0 / TESTS);
    eprintln!("chi2 {label}, cos wo {:.2}: statistic {statistic:.1}, dof {dof}, p {p_value:.4}", wo.z);
    assert!(
        p_value >= threshold,
        "{label}, wo {wo}: chi-square p-value {p_value} < {threshold} (statistic {statistic}, dof {dof})"
    );
    p_value
}

/// Mean and standard error of the sample weight (rejected samples count 0): the directional
/// albedo, scattered power per unit incident power in radiance terms.
pub fn directional_albedo(bsdf: &Bsdf, wo: DVec3, n: usize, rng: &mut Rng) -> (DVec3, DVec3) {
    let (mut sum, mut sum2) = (DVec3::ZERO, DVec3::ZERO);
    for _ in 0..n {
        if let Some(s) = bsdf.sample(wo, rng.next(), rng.next2()) {
            sum += s.weight;
            sum2 += s.weight * s.weight;
        }
    }
    let mean = sum / n as f64;
    let var = (sum2 / n as f64 - mean * mean).max(DVec3::ZERO);
    (mean, (var / n as f64).powf(0.5))
}

/// The directional albedo from `eval` alone, with uniformly distributed directions.
pub fn uniform_albedo(bsdf: &Bsdf, wo: DVec3, n: usize, rng: &mut Rng) -> (DVec3, DVec3) {
    let (mut sum, mut sum2) = (DVec3::ZERO, DVec3::ZERO);
    for _ in 0..n {
        let u = rng.next2();
        let v = direction(1.0 - 2.0 * u.x, TAU * u.y);
        let f = bsdf.eval(wo, v) * (4.0 * PI);
        sum += f;
        sum2 += f * f;
    }
    let mean = sum / n as f64;
    let var = (sum2 / n as f64 - mean * mean).max(DVec3::ZERO);
    (mean, (var / n as f64).powf(0.5))
}

/// eval(wo, wi) / |cos wi| == eval(wi, wo) / |cos wo| over random pairs of directions above
/// the surface (relative 1e-9).
pub fn check_reciprocity(bsdf: &Bsdf) {
    let mut rng = Rng::new(41);
    for _ in 0..10_000 {
        let (a, b) = (rng.next2(), rng.next2());
        let wo = direction(a.x.max(1e-3), TAU * a.y);
        let wi = direction(b.x.max(1e-3), TAU * b.y);
        let f1 = bsdf.eval(wo, wi) / wi.z;
        let f2 = bsdf.eval(wi, wo) / wo.z;
        let scale = f1.abs().max_element().max(f2.abs().max_element()).max(1e-300);
        assert!((f1 - f2).abs().max_element() / scale < 1e-9, "{bsdf:?}: wo {wo} wi {wi}: {f1} vs {f2}");
    }
}
