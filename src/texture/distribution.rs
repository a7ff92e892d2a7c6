//! Tabulated discrete distributions for importance sampling: [`Distribution1D`] picks an
//! index with probability proportional to its weight (a cumulative table and a binary
//! search), [`Distribution2D`] a cell of a grid (a marginal over the rows, then the row's
//! conditional). Both hand back the uniform sample remapped to `[0, 1)` within the chosen
//! entry, so the caller can place a continuous point inside it with the same random number.
//! The environment map samples its cells with them; light selection can use them too.

use glam::DVec2;

/// A distribution over `0..len` proportional to finite, non-negative weights. When every
/// weight is 0, every index is equally likely (so that sampling stays defined); then
/// [`Distribution1D::total`] is 0 and the caller decides what that means.
#[derive(Clone, Debug)]
pub struct Distribution1D {
    weights: Vec<f64>,
    /// `prefix[i]` is the sum of the weights before `i`; `len + 1` entries.
    prefix: Vec<f64>,
}

impl Distribution1D {
    /// The distribution of `weights`; panics when it is empty or a weight is negative or
    /// not finite (callers validate their data first).
    pub fn new(weights: Vec<f64>) -> Self {
        assert!(!weights.is_empty(), "a distribution needs at least one entry");
        assert!(weights.iter().all(|w| w.is_finite() && *w >= 0.0), "weights must be finite and non-negative");
        let mut prefix = Vec::with_capacity(weights.len() + 1);
        let mut sum = 0.0;
        prefix.push(0.0);
        for &w in &weights {
            sum += w;
            prefix.push(sum);
        }
        assert!(sum.is_finite(), "the weights' sum overflows");
        Self { weights, prefix }
    }

    /// Number of entries.
    pub fn len(&self) -> usize {
        self.weights.len()
    }

    /// Always false: a distribution has at least one entry.
    pub fn is_empty(&self) -> bool {
        self.weights.is_empty()
    }

    /// The sum of the weights.
    pub fn total(&self) -> f64 {
        self.prefix[self.weights.len()]
    }

    /// The weight of entry `i`, as given.
    pub fn weight(&self, i: usize) -> f64 {
        self.weights[i]
    }

    /// The probability of entry `i`: its weight over the total (`1 / len` when all are 0).
    pub fn probability(&self, i: usize) -> f64 {
        let total = self.total();
        if total > 0.0 { self.weights[i] / total } else { 1.0 / self.len() as f64 }
    }

    /// The entry `u` in `[0, 1)` selects (never one of probability 0), its probability, and
    /// `u` remapped to `[0, 1)` within that entry's share.
    pub fn sample(&self, u: f64) -> (usize, f64, f64) {
        let n = self.len();
        let total = self.total();
        let u = u.clamp(0.0, 1.0);
        if total <= 0.0 {
            let x = u * n as f64;
            let i = (x as usize).min(n - 1);
            return (i, 1.0 / n as f64, (x - i as f64).clamp(0.0, ONE_BELOW));
        }
        let target = u * total;
        // The last i with prefix[i] <= target: entries of weight 0 have prefix[i] ==
        // prefix[i + 1] and are stepped over; rounding at the very top can still land on one
        // (trailing zeros), so step back to the last entry with weight.
        let mut i = (self.prefix.partition_point(|&p| p <= target).max(1) - 1).min(n - 1);
        while self.weights[i] == 0.0 && i > 0 {
            i -= 1;
        }
        while self.weights[i] == 0.0 {
            i += 1;
        }
        let remapped = ((target - self.prefix[i]) / self.weights[i]).clamp(0.0, ONE_BELOW);
        (i, self.weights[i] / total, remapped)
    }
}

/// The largest `f64` below 1.
const ONE_BELOW: f64 = 1.0 - f64::EPSILON / 2.0;

/// A distribution over the cells of a `width × height` grid proportional to their weights:
/// a [`Distribution1D`] over the rows' sums, then one per row.
#[derive(Clone, Debug)]
pub struct Distribution2D {
    rows: Distribution1D,
    columns: Vec<Distribution1D>,
}

impl Distribution2D {
    /// The distribution of `weights`, row-major (`weights[row * width + column]`); panics
    /// when the grid is empty, the length is not `width * height`, or a weight is negative
    /// or not finite.
    pub fn new(width: usize, height: usize, weights: &[f64]) -> Self {
        assert!(width > 0 && height > 0 && weights.len() == width * height, "weights must fill the grid");
        let columns: Vec<Distribution1D> =
            weights.chunks_exact(width).map(|row| Distribution1D::new(row.to_vec())).collect();
        let rows = Distribution1D::new(columns.iter().map(Distribution1D::total).collect());
        Self { rows, columns }
    }

    /// The sum of all weights.
    pub fn total(&self) -> f64 {
        self.rows.total()
    }

    /// The probability of the cell at `column`, `row`.
    pub fn probability(&self, column: usize, row: usize) -> f64 {
        self.rows.probability(row) * self.columns[row].probability(column)
    }

    /// The cell `u` in `[0, 1)^2` selects, `(column, row)`, its probability, and `u`
    /// remapped to `[0, 1)^2` within the cell (x from the column's choice, y from the row's).
    pub fn sample(&self, u: DVec2) -> ((usize, usize), f64, DVec2) {
        let (row, p_row, v) = self.rows.sample(u.y);
        let (column, p_column, w) = self.columns[row].sample(u.x);
        ((column, row), p_row * p_column, DVec2::new(w, v))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_support::chi2::assert_fits;
    use prism_api::contract::TestRng;

    #[test]
    fn one_dimension_fits_its_weights_and_remaps_uniformly() {
        // Zeros at both ends and inside: never chosen.
        let weights = vec![0.0, 1.0, 3.0, 0.0, 0.0, 0.5, 2.0, 0.0];
        let d = Distribution1D::new(weights.clone());
        assert_eq!(d.total(), 6.5);
        let quarters = 4;
        let n = 100_000;
        let mut observed = vec![0.0; weights.len() * quarters];
        let mut rng = TestRng::new(11);
        for _ in 0..n {
            let (i, p, r) = d.sample(rng.uniform());
            assert!(weights[i] > 0.0, "entry {i} of weight 0 chosen");
            assert_eq!(p, d.probability(i));
            assert!((0.0..1.0).contains(&r));
            observed[i * quarters + (r * quarters as f64) as usize] += 1.0;
        }
        let expected: Vec<f64> =
            (0..observed.len()).map(|k| n as f64 * d.probability(k / quarters) / quarters as f64).collect();
        assert_fits("Distribution1D (entries x remapped quarters)", &observed, &expected, 0.01);
    }

    #[test]
    fn extremes_of_u_pick_entries_with_weight() {
        let d = Distribution1D::new(vec![0.0, 0.0, 2.0, 0.0, 1.0, 0.0, 0.0]);
        assert_eq!(d.sample(0.0).0, 2);
        assert_eq!(d.sample(ONE_BELOW).0, 4);
        assert_eq!(d.sample(1.0).0, 4);
        assert_eq!(d.sample(2.0 / 3.0).0, 4, "the boundary belongs to the next entry with weight");
        let zero = Distribution1D::new(vec![0.0; 4]);
        assert_eq!(zero.total(), 0.0);
        let (i, p, r) = zero.sample(0.6);
        assert_eq!((i, p), (2, 0.25));
        assert!((r - 0.4).abs() < 1e-12);
        assert_eq!(zero.probability(3), 0.25);
    }

    #[test]
    fn two_dimensions_fit_their_weights() {
        let (w, h) = (8, 5);
        let mut weights: Vec<f64> = (0..w * h).map(|k| ((k * 7) % 5) as f64).collect();
        weights[3 * w + 6] = 40.0; // a spike
        weights[w..2 * w].fill(0.0); // an empty row
        let d = Distribution2D::new(w, h, &weights);
        let total: f64 = weights.iter().sum();
        assert!((d.total() - total).abs() < 1e-12);
        let n = 200_000;
        let mut observed = vec![0.0; w * h * 4];
        let mut rng = TestRng::new(12);
        for _ in 0..n {
            let ((x, y), p, r) = d.sample(DVec2::new(rng.uniform(), rng.uniform()));
            assert!(weights[y * w + x] > 0.0);
            assert!((p - weights[y * w + x] / total).abs() < 1e-15);
            assert!((p - d.probability(x, y)).abs() < 1e-15);
            let quadrant = usize::from(r.x >= 0.5) + 2 * usize::from(r.y >= 0.5);
            observed[(y * w + x) * 4 + quadrant] += 1.0;
        }
        let expected: Vec<f64> = (0..observed.len()).map(|k| n as f64 * weights[k / 4] / total / 4.0).collect();
        assert_fits("Distribution2D (cells x remapped quadrants)", &observed, &expected, 0.01);
    }
}
