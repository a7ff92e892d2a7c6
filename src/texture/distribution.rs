//! Tabulated discrete distributions for importance sampling: [`Distribution1D`] picks an
//! index with probability proportional to its weight (a cumulative table, searched from a
//! guide table), [`Distribution2D`] a cell of a grid (a marginal over the rows, then the row's
//! conditional). Both hand back the uniform sample remapped to `[0, 1)` within the chosen
//! entry, so the caller can place a continuous point inside it with the same random number.
//! The environment map samples its cells with them; light selection can use them too.

use glam::DVec2;

/// A distribution over `0..len` proportional to finite, non-negative weights. When every
/// weight is 0, every index is equally likely (so that sampling stays defined); then
/// [`Distribution1D::total`] is 0 and the caller decides what that means.
#[derive(Clone, Debug)]
pub struct Distribution1D {
    /// `entries[i]` is the sum of the weights before `i` and the weight of `i`, side by side
    /// so that the search's last reads bring in the weight too; `len + 1` entries, the last
    /// one the total and a weight of 0.
    entries: Vec<Entry>,
    /// `guide[b]`, for each of `len` equal slices of `[0, 1)` and the end: the last index `i`
    /// with `entries[i].before <= b / len * total`, where the search for a `u` in slice `b`
    /// starts (a guide table: a few entries to search instead of a binary search's chain of
    /// dependent loads over the whole table).
    guide: Vec<u32>,
}

#[derive(Clone, Copy, Debug)]
struct Entry {
    /// The sum of the weights before this entry.
    before: f64,
    weight: f64,
}

impl Distribution1D {
    /// The distribution of `weights`; panics when it is empty or a weight is negative or
    /// not finite (callers validate their data first).
    pub fn new(weights: Vec<f64>) -> Self {
        assert!(!weights.is_empty(), "a distribution needs at least one entry");
        assert!(weights.iter().all(|w| w.is_finite() && *w >= 0.0), "weights must be finite and non-negative");
        let mut entries = Vec::with_capacity(weights.len() + 1);
        let mut sum = 0.0;
        for &weight in &weights {
            entries.push(Entry { before: sum, weight });
            sum += weight;
        }
        entries.push(Entry { before: sum, weight: 0.0 });
        assert!(sum.is_finite(), "the weights' sum overflows");
        let slices = weights.len();
        let guide = (0..=slices)
            .map(|b| (last_at_most(&entries, b as f64 / slices as f64 * sum) as u32).min(slices as u32 - 1))
            .collect();
        Self { entries, guide }
    }

    /// Number of entries.
    pub fn len(&self) -> usize {
        self.entries.len() - 1
    }

    /// Always false: a distribution has at least one entry.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The sum of the weights.
    pub fn total(&self) -> f64 {
        self.entries[self.len()].before
    }

    /// The weight of entry `i`, as given.
    pub fn weight(&self, i: usize) -> f64 {
        self.entries[..self.len()][i].weight
    }

    /// The probability of entry `i`: its weight over the total (`1 / len` when all are 0).
    pub fn probability(&self, i: usize) -> f64 {
        let total = self.total();
        if total > 0.0 { self.weight(i) / total } else { 1.0 / self.len() as f64 }
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
        // The last i with a sum before it <= target: entries of weight 0 have the same sum
        // before them as the next and are stepped over; rounding at the very top can still
        // land on one (trailing zeros), so step back to the last entry with weight.
        let mut i = self.last_at_most(u, target).min(n - 1);
        while self.entries[i].weight == 0.0 && i > 0 {
            i -= 1;
        }
        while self.entries[i].weight == 0.0 {
            i += 1;
        }
        let Entry { before, weight } = self.entries[i];
        let remapped = ((target - before) / weight).clamp(0.0, ONE_BELOW);
        (i, weight / total, remapped)
    }

    /// [`last_at_most`] of `target = u * total`, searched between the guide's entries for
    /// `u`'s slice and the next. The slice's bounds are checked against `target` itself, so
    /// rounding in the slice's choice can only send the search to the whole table, never
    /// change its answer.
    fn last_at_most(&self, u: f64, target: f64) -> usize {
        let slices = self.len();
        let slice = ((u * slices as f64) as usize).min(slices - 1);
        let low = self.guide[slice] as usize;
        let high = (self.guide[slice + 1] as usize + 2).min(self.entries.len());
        if self.entries[low].before <= target && (high == self.entries.len() || self.entries[high].before > target) {
            low + self.entries[low + 1..high].partition_point(|e| e.before <= target)
        } else {
            last_at_most(&self.entries, target)
        }
    }
}

/// The last index `i` of `entries` with `entries[i].before <= target` (0 when there is
/// none), the sums not decreasing.
fn last_at_most(entries: &[Entry], target: f64) -> usize {
    entries.partition_point(|e| e.before <= target).max(1) - 1
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

    /// The guided search answers exactly as a binary search over the whole table, for tables
    /// with runs of zeros, spikes, tiny and huge weights, at random `u` and at the slices'
    /// edges (where rounding decides the slice).
    #[test]
    fn guided_search_is_the_whole_search() {
        let mut rng = TestRng::new(21);
        let mut tables = vec![vec![1.0], vec![0.0, 5.0], vec![3.0, 0.0, 0.0, 0.0, 1e-300, 0.0, 7.0, 0.0]];
        for len in [2, 3, 17, 256, 1000] {
            tables.push((0..len).map(|_| rng.uniform()).collect());
            tables.push(
                (0..len)
                    .map(|k| match k % 5 {
                        0 => 0.0,
                        1 => 1e6 * rng.uniform(),
                        2 => 1e-9 * rng.uniform(),
                        _ => rng.uniform(),
                    })
                    .collect(),
            );
            let mut spike = vec![1e-12; len];
            spike[len / 3] = 1e12;
            tables.push(spike);
        }
        for weights in tables {
            let d = Distribution1D::new(weights);
            let (n, total) = (d.len(), d.total());
            let edges = (0..=n).flat_map(|b| {
                let x = b as f64 / n as f64;
                [x, x.next_down().max(0.0), x.next_up().min(1.0)]
            });
            for u in (0..20_000).map(|_| rng.uniform()).chain(edges) {
                let target = u * total;
                assert_eq!(d.last_at_most(u, target), last_at_most(&d.entries, target), "u = {u}, {n} entries");
            }
        }
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
