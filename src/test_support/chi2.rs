//! Pearson's chi-square goodness-of-fit test, the one copy every sampling test in this crate
//! uses (the 1D/2D distributions, environment maps; later light selection and BSDFs).
//!
//! [`pearson`] compares observed with expected counts, pooling cells that expect fewer than
//! [`MIN_EXPECTED`] samples (smallest expectations first, as Mitsuba's `ChiSquareTest`
//! does); its p-value is `prism_api::contract::chi_square_p_value`, the same incomplete
//! gamma function the shape contract kit uses. [`sphere_test`] bins unit directions in
//! `cos θ × φ` cells about +y and integrates a solid-angle density over each cell for the
//! expected counts.

use std::f64::consts::{PI, TAU};

use glam::DVec3;

/// Cells expecting fewer samples than this are pooled.
pub(crate) const MIN_EXPECTED: f64 = 5.0;

/// The outcome of a chi-square test.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ChiSquare {
    /// Pearson's statistic.
    pub statistic: f64,
    /// Degrees of freedom: cells after pooling, minus one.
    pub dof: usize,
    /// The chance of a statistic at least this large from a correct sampler.
    pub p_value: f64,
}

/// Pearson's test of `observed` against `expected` counts (same length, same total up to
/// the sampler's error). Cells expecting fewer than [`MIN_EXPECTED`] are pooled in order of
/// their expectation until each pool reaches it; a last pool still short joins the one
/// before it. Samples observed where nothing is expected give a p-value of 0.
pub(crate) fn pearson(observed: &[f64], expected: &[f64]) -> ChiSquare {
    assert_eq!(observed.len(), expected.len());
    if observed.iter().zip(expected).any(|(&o, &e)| e <= 0.0 && o > 0.0) {
        return ChiSquare { statistic: f64::INFINITY, dof: 1, p_value: 0.0 };
    }
    let mut order: Vec<usize> = (0..expected.len()).filter(|&i| expected[i] > 0.0).collect();
    order.sort_by(|&a, &b| expected[a].total_cmp(&expected[b]));
    let mut cells: Vec<(f64, f64)> = Vec::new();
    let mut pool = (0.0, 0.0);
    for &i in &order {
        if expected[i] >= MIN_EXPECTED && pool.1 == 0.0 {
            cells.push((observed[i], expected[i]));
            continue;
        }
        pool.0 += observed[i];
        pool.1 += expected[i];
        if pool.1 >= MIN_EXPECTED {
            cells.push(pool);
            pool = (0.0, 0.0);
        }
    }
    if pool.1 > 0.0 {
        match cells.last_mut() {
            Some(last) => *last = (last.0 + pool.0, last.1 + pool.1),
            None => cells.push(pool),
        }
    }
    let statistic: f64 = cells.iter().map(|&(o, e)| (o - e) * (o - e) / e).sum();
    let dof = cells.len().saturating_sub(1).max(1);
    ChiSquare { statistic, dof, p_value: prism_api::contract::chi_square_p_value(statistic, dof) }
}

/// [`pearson`], printed (visible with `--nocapture`) and asserted to reach `alpha`.
pub(crate) fn assert_fits(what: &str, observed: &[f64], expected: &[f64], alpha: f64) -> ChiSquare {
    let result = pearson(observed, expected);
    eprintln!("chi-square {what}: statistic {:.1}, dof {}, p = {:.4}", result.statistic, result.dof, result.p_value);
    assert!(
        result.p_value >= alpha,
        "chi-square test of {what} fails: statistic {:.1} with {} degrees of freedom, p = {:.3e} < {alpha}",
        result.statistic,
        result.dof,
        result.p_value
    );
    result
}

/// A discrete choice tested against the probabilities it claims: `draws` calls of `choose`,
/// each returning the index chosen and the probability it reports, which must equal
/// `probabilities[index]` to the bit (what MIS computes apart); then [`assert_fits`] of the
/// counts at `alpha`, with more than `min_dof` degrees of freedom left after pooling.
pub(crate) fn assert_choice_fits(
    what: &str,
    probabilities: &[f64],
    draws: u32,
    min_dof: usize,
    mut choose: impl FnMut() -> (usize, f64),
) -> ChiSquare {
    let mut observed = vec![0.0; probabilities.len()];
    for _ in 0..draws {
        let (index, probability) = choose();
        assert_eq!(probability, probabilities[index], "{what}: the probability reported is the one asked for");
        observed[index] += 1.0;
    }
    let expected: Vec<f64> = probabilities.iter().map(|p| p * f64::from(draws)).collect();
    let result = assert_fits(what, &observed, &expected, 1e-4);
    assert!(result.dof > min_dof, "{what}: too few cells to mean anything ({})", result.dof);
    result
}

/// The `cos θ × φ` cell of unit direction `d`: `cos θ = d.y` in `cos_bins` equal steps from
/// -1 to 1, `φ = atan2(d.z, d.x)` in `phi_bins` equal steps over `[0, 2π)`. Every cell
/// has the same solid angle, `4π / (cos_bins · phi_bins)`.
pub(crate) fn sphere_cell(d: DVec3, cos_bins: usize, phi_bins: usize) -> usize {
    let c = (((d.y + 1.0) * 0.5 * cos_bins as f64) as usize).min(cos_bins - 1);
    let p = ((d.z.atan2(d.x).rem_euclid(TAU) / TAU * phi_bins as f64) as usize).min(phi_bins - 1);
    c * phi_bins + p
}

/// The direction at `cos θ = z`, azimuth `φ` of [`sphere_cell`]'s frame.
fn direction(z: f64, phi: f64) -> DVec3 {
    let r = (1.0 - z * z).max(0.0).sqrt();
    DVec3::new(r * phi.cos(), z, r * phi.sin())
}

/// The integral of `pdf` (solid-angle density) over each of [`sphere_cell`]'s cells, times
/// `samples`: the counts a sampler of that density should put there. The midpoint rule on an
/// 8 × 8 grid in `(cos θ, φ)` (uniform in solid angle); a cell whose 64 values differ is
/// integrated again on a 128 × 128 grid, so a discontinuity (a texel's edge) inside a cell
/// costs at most a 256th of its content.
pub(crate) fn sphere_expected(pdf: &impl Fn(DVec3) -> f64, cos_bins: usize, phi_bins: usize, samples: f64) -> Vec<f64> {
    let (dz, dphi) = (2.0 / cos_bins as f64, TAU / phi_bins as f64);
    let integrate = |c: usize, p: usize, n: usize| -> (f64, bool) {
        let (mut sum, mut lo, mut hi) = (0.0, f64::INFINITY, f64::NEG_INFINITY);
        for i in 0..n {
            let z = -1.0 + dz * (c as f64 + (i as f64 + 0.5) / n as f64);
            for j in 0..n {
                let phi = dphi * (p as f64 + (j as f64 + 0.5) / n as f64);
                let v = pdf(direction(z, phi));
                sum += v;
                lo = lo.min(v);
                hi = hi.max(v);
            }
        }
        (sum * dz * dphi / (n * n) as f64, hi > lo)
    };
    let mut expected = Vec::with_capacity(cos_bins * phi_bins);
    for c in 0..cos_bins {
        for p in 0..phi_bins {
            let (coarse, varies) = integrate(c, p, 8);
            expected.push(samples * if varies { integrate(c, p, 128).0 } else { coarse });
        }
    }
    expected
}

/// Bins `directions` with [`sphere_cell`] and tests them against `pdf` with [`assert_fits`];
/// also checks that `pdf` integrates to 1 over the sphere (within 1e-3).
pub(crate) fn sphere_test(
    what: &str,
    directions: &[DVec3],
    pdf: &impl Fn(DVec3) -> f64,
    cos_bins: usize,
    phi_bins: usize,
    alpha: f64,
) -> ChiSquare {
    let n = directions.len() as f64;
    let expected = sphere_expected(pdf, cos_bins, phi_bins, n);
    let total: f64 = expected.iter().sum::<f64>() / n;
    assert!((total - 1.0).abs() < 1e-3, "{what}: the density integrates to {total} over the sphere, not 1");
    let mut observed = vec![0.0; cos_bins * phi_bins];
    for &d in directions {
        observed[sphere_cell(d, cos_bins, phi_bins)] += 1.0;
    }
    assert_fits(what, &observed, &expected, alpha)
}

#[cfg(test)]
mod tests {
    use super::*;
    use prism_api::contract::TestRng;

    #[test]
    fn perfect_fit_and_gross_misfit() {
        let expected = vec![100.0; 10];
        assert!(pearson(&expected, &expected).p_value > 0.999);
        let mut skewed = expected.clone();
        skewed[0] = 200.0;
        skewed[1] = 0.0;
        assert!(pearson(&skewed, &expected).p_value < 1e-10);
        assert_eq!(pearson(&[1.0, 0.0], &[0.0, 1.0]).p_value, 0.0, "samples where nothing is expected");
    }

    #[test]
    fn small_cells_are_pooled() {
        let expected = [1.0, 1.0, 1.0, 1.0, 1.0, 50.0, 50.0];
        let observed = [0.0, 2.0, 1.0, 1.0, 1.0, 50.0, 50.0];
        let result = pearson(&observed, &expected);
        assert_eq!(result.dof, 2, "five small cells make one");
        assert!(result.statistic.abs() < 1e-12);
    }

    #[test]
    fn uniform_sphere_directions_fit_the_uniform_density() {
        let mut rng = TestRng::new(7);
        let directions: Vec<DVec3> = (0..50_000).map(|_| rng.unit_vector()).collect();
        sphere_test("uniform directions", &directions, &|_| 1.0 / (4.0 * PI), 10, 20, 0.01);
        // Directions only in the upper hemisphere do not.
        let upper: Vec<DVec3> = directions.iter().map(|d| DVec3::new(d.x, d.y.abs(), d.z)).collect();
        assert!(pearson_of(&upper, 10, 20) < 1e-10);
    }

    /// The chi-square CDF against known quantiles.
    #[test]
    fn chi2_quantiles() {
        // (statistic, dof, upper-tail p)
        for (x, k, p) in
            [(3.841459, 1, 0.05), (18.307038, 10, 0.05), (6.634897, 1, 0.01), (124.342113, 100, 0.05), (0.0, 5, 1.0)]
        {
            let got = prism_api::contract::chi_square_p_value(x, k);
            assert!((got - p).abs() < 1e-6, "chi2({x}, {k}) = {got}, want {p}");
        }
    }

    /// A sampler that disagrees with its pdf by 20 % in a tenth of the cells fails; one within
    /// its noise passes.
    #[test]
    fn pearson_rejects_a_wrong_distribution() {
        let expected = vec![1000.0_f64; 100];
        let mut rng = TestRng::new(1);
        let fair: Vec<f64> = expected.iter().map(|&e| e + (rng.uniform() - 0.5) * 2.0 * e.sqrt() * 1.7).collect();
        assert!(pearson(&fair, &expected).p_value > 0.01);
        let skewed: Vec<f64> =
            expected.iter().enumerate().map(|(i, &e)| if i < 10 { e * 1.2 } else { e * (1.0 - 0.2 / 9.0) }).collect();
        assert!(pearson(&skewed, &expected).p_value < 1e-6);
    }

    fn pearson_of(directions: &[DVec3], cos_bins: usize, phi_bins: usize) -> f64 {
        let expected = sphere_expected(&|_| 1.0 / (4.0 * PI), cos_bins, phi_bins, directions.len() as f64);
        let mut observed = vec![0.0; cos_bins * phi_bins];
        for &d in directions {
            observed[sphere_cell(d, cos_bins, phi_bins)] += 1.0;
        }
        pearson(&observed, &expected).p_value
    }
}
