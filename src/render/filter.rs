//! Pixel reconstruction filters by importance sampling: a sample's offset from the pixel
//! centre is drawn in proportion to |filter| from a table, and carries the weight
//! filter / pdf, so a pixel is the weighted mean sum(w L) / sum(w). Each sample stays its own
//! pixel's (no splatting into neighbours), so a pixel depends only on its own samples and
//! region renders stay exact. The estimate converges to the same filtered image as
//! Mitsuba's splatting: the filter-weighted mean of the radiance around the centre.

use glam::DVec2;

use crate::texture::distribution::Distribution2D;
use crate::world::components::PixelFilter;

/// Table cells per pixel along each axis.
const CELLS_PER_PIXEL: f64 = 32.0;

/// Draws sample offsets from a non-box filter.
#[derive(Clone, Debug)]
pub struct FilterSampler {
    filter: PixelFilter,
    radius: f64,
    cells: usize,
    table: Distribution2D,
}

impl PixelFilter {
    /// Half the side of the square outside which the filter is 0, in pixels.
    pub fn radius(&self) -> f64 {
        match *self {
            PixelFilter::Box {} => 0.5,
            PixelFilter::Gaussian { stddev } => 4.0 * stddev,
            PixelFilter::Mitchell { .. } => 2.0,
        }
    }

    /// The filter's value at offset `x` pixels along one axis (the 2D filter is the product
    /// of the axes', as Mitsuba's).
    pub fn eval_1d(&self, x: f64) -> f64 {
        let x = x.abs();
        match *self {
            PixelFilter::Box {} => f64::from(u8::from(x <= 0.5)),
            PixelFilter::Gaussian { stddev } => {
                let alpha = -1.0 / (2.0 * stddev * stddev);
                let cut = 4.0 * stddev;
                ((alpha * x * x).exp() - (alpha * cut * cut).exp()).max(0.0)
            }
            PixelFilter::Mitchell { b, c } => {
                let (x2, x3) = (x * x, x * x * x);
                let value = if x < 1.0 {
                    (12.0 - 9.0 * b - 6.0 * c) * x3 + (-18.0 + 12.0 * b + 6.0 * c) * x2 + (6.0 - 2.0 * b)
                } else if x < 2.0 {
                    (-b - 6.0 * c) * x3 + (6.0 * b + 30.0 * c) * x2 + (-12.0 * b - 48.0 * c) * x + (8.0 * b + 24.0 * c)
                } else {
                    0.0
                };
                value / 6.0
            }
        }
    }

    /// The 2D filter at `offset` pixels from the centre.
    pub fn eval(&self, offset: DVec2) -> f64 {
        self.eval_1d(offset.x) * self.eval_1d(offset.y)
    }
}

impl FilterSampler {
    /// The sampler of `filter`; `None` for the box filter, which samples the pixel uniformly.
    pub fn new(filter: PixelFilter) -> Option<Self> {
        if filter.is_box() {
            return None;
        }
        let radius = filter.radius();
        let cells = ((2.0 * radius * CELLS_PER_PIXEL).ceil() as usize).clamp(2, 512);
        let cell = 2.0 * radius / cells as f64;
        let column: Vec<f64> = (0..cells).map(|i| filter.eval_1d(-radius + (i as f64 + 0.5) * cell).abs()).collect();
        let weights: Vec<f64> = column.iter().flat_map(|&fy| column.iter().map(move |&fx| fx * fy)).collect();
        Some(Self { filter, radius, cells, table: Distribution2D::new(cells, cells, &weights) })
    }

    /// The offset from the pixel centre (pixels) that `u` in [0, 1)^2 selects, and its weight
    /// filter / pdf (negative in a negative lobe).
    pub fn sample(&self, u: DVec2) -> (DVec2, f64) {
        let ((column, row), probability, within) = self.table.sample(u);
        let cell = 2.0 * self.radius / self.cells as f64;
        let offset =
            DVec2::new(-self.radius + (column as f64 + within.x) * cell, -self.radius + (row as f64 + within.y) * cell);
        let pdf = probability / (cell * cell);
        (offset, self.filter.eval(offset) / pdf)
    }

    /// The density of [`FilterSampler::sample`]'s offsets at `offset` (per square pixel).
    pub fn pdf(&self, offset: DVec2) -> f64 {
        let cell = 2.0 * self.radius / self.cells as f64;
        let index = |v: f64| ((v + self.radius) / cell).floor();
        let (column, row) = (index(offset.x), index(offset.y));
        if column < 0.0 || row < 0.0 || column >= self.cells as f64 || row >= self.cells as f64 {
            return 0.0;
        }
        self.table.probability(column as usize, row as usize) / (cell * cell)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_support::chi2::assert_fits;
    use prism_api::contract::TestRng;

    fn filters() -> [PixelFilter; 4] {
        [
            PixelFilter::Gaussian { stddev: 0.5 },
            PixelFilter::Gaussian { stddev: 0.3 },
            PixelFilter::Mitchell { b: 1.0 / 3.0, c: 1.0 / 3.0 },
            PixelFilter::Mitchell { b: 0.0, c: 0.5 },
        ]
    }

    /// Midpoint-rule integral of `f` over the filter's square.
    fn integrate(radius: f64, f: impl Fn(DVec2) -> f64) -> f64 {
        let n = 400;
        let h = 2.0 * radius / n as f64;
        let mut sum = 0.0;
        for j in 0..n {
            for i in 0..n {
                sum += f(DVec2::new(-radius + (i as f64 + 0.5) * h, -radius + (j as f64 + 0.5) * h));
            }
        }
        sum * h * h
    }

    #[test]
    fn mitsuba_values() {
        let g = PixelFilter::Gaussian { stddev: 0.5 };
        assert_eq!(g.radius(), 2.0);
        assert!((g.eval_1d(0.0) - (1.0 - (-8.0f64).exp())).abs() < 1e-15);
        assert_eq!(g.eval_1d(2.0), 0.0);
        let m = PixelFilter::Mitchell { b: 1.0 / 3.0, c: 1.0 / 3.0 };
        // The cubic is C1 at 1, reaches 0 at 2, and its values sum to 1 over integer offsets.
        assert!((m.eval_1d(1.0 - 1e-9) - m.eval_1d(1.0 + 1e-9)).abs() < 1e-7);
        assert!(m.eval_1d(2.0).abs() < 1e-12);
        assert!((m.eval_1d(0.0) + 2.0 * m.eval_1d(1.0) - 1.0).abs() < 1e-12);
        assert!(m.eval_1d(1.5) < 0.0, "a negative lobe");
    }

    /// The offsets follow the table's density: a chi-square test over a coarse grid of bins.
    #[test]
    fn offsets_fit_their_pdf() {
        for filter in filters() {
            let sampler = FilterSampler::new(filter).unwrap();
            let r = filter.radius();
            let bins = 16;
            let bin_of = |p: DVec2| {
                let i = (((p.x + r) / (2.0 * r) * bins as f64) as usize).min(bins - 1);
                let j = (((p.y + r) / (2.0 * r) * bins as f64) as usize).min(bins - 1);
                j * bins + i
            };
            let mut rng = TestRng::new(11);
            let n = 1_000_000;
            let mut observed = vec![0.0; bins * bins];
            for _ in 0..n {
                let (p, w) = sampler.sample(DVec2::new(rng.uniform(), rng.uniform()));
                assert!(p.abs().max_element() <= r && w.is_finite(), "{filter:?}: {p} {w}");
                observed[bin_of(p)] += 1.0;
            }
            // Each table cell's probability, shared among the bins it overlaps.
            let cell = 2.0 * r / sampler.cells as f64;
            let bin = 2.0 * r / bins as f64;
            let overlap = |k: usize, b: usize| {
                let (lo, hi) = (k as f64 * cell, (k + 1) as f64 * cell);
                ((hi.min((b + 1) as f64 * bin) - lo.max(b as f64 * bin)) / cell).max(0.0)
            };
            let mut expected = vec![0.0; bins * bins];
            for row in 0..sampler.cells {
                for column in 0..sampler.cells {
                    let mass = sampler.table.probability(column, row) * n as f64;
                    for j in 0..bins {
                        for i in 0..bins {
                            expected[j * bins + i] += mass * overlap(column, i) * overlap(row, j);
                        }
                    }
                }
            }
            assert_fits(&format!("{filter:?}"), &observed, &expected, 0.01);
        }
    }

    /// Weighted means estimate the filter-weighted mean: E[w g] / E[w] = ∫ f g / ∫ f for a
    /// test function g.
    #[test]
    fn weights_estimate_the_filtered_mean() {
        let g = |p: DVec2| 1.0 + p.x + 0.5 * p.y * p.y + (3.0 * p.x).sin();
        for filter in filters() {
            let sampler = FilterSampler::new(filter).unwrap();
            let exact =
                integrate(filter.radius(), |p| filter.eval(p) * g(p)) / integrate(filter.radius(), |p| filter.eval(p));
            let mut rng = TestRng::new(5);
            let (mut sum, mut weights) = (0.0, 0.0);
            for _ in 0..400_000 {
                let (p, w) = sampler.sample(DVec2::new(rng.uniform(), rng.uniform()));
                sum += w * g(p);
                weights += w;
            }
            assert!((sum / weights - exact).abs() < 5e-3, "{filter:?}: {} vs {exact}", sum / weights);
        }
    }

    #[test]
    fn the_centre_sample_lands_on_the_centre() {
        for filter in filters() {
            let (p, w) = FilterSampler::new(filter).unwrap().sample(DVec2::splat(0.5));
            assert!(p.length() < 1e-9 && w > 0.0, "{filter:?}: {p}");
        }
    }
}
