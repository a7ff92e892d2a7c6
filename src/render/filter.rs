//! Pixel reconstruction filters by importance sampling: a sample's offset from the pixel
//! centre is drawn in proportion to |filter| from a table, and carries the weight
//! filter / (pdf * integral of the filter), whose expected value is 1, so a pixel is
//! sum(w L) / N over its N samples: an unbiased estimate, at any sample count, of the
//! filter-weighted mean of the radiance around the centre, the image Mitsuba's splatting
//! converges to. (The ratio sum(w L) / sum(w) is biased by O(1/N) where the radiance varies
//! across the footprint; with a negative-lobed filter at 256 samples, enough for Mitsuba's
//! statistical comparison to see at every edge.) Each sample stays its own pixel's (no
//! splatting into neighbours), so a pixel depends only on its own samples and region renders
//! stay exact.

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
    /// The filter's integral over its square (pixels^2).
    integral: f64,
}

impl PixelFilter {
    /// Half the side of the square outside which the filter is 0, in pixels.
    pub fn radius(&self) -> f64 {
        match *self {
            PixelFilter::Box => 0.5,
            PixelFilter::Gaussian { stddev } => 4.0 * stddev,
            PixelFilter::Mitchell { .. } => 2.0,
        }
    }

    /// The filter's value at offset `x` pixels along one axis (the 2D filter is the product
    /// of the axes', as Mitsuba's).
    pub fn eval_1d(&self, x: f64) -> f64 {
        let x = x.abs();
        match *self {
            PixelFilter::Box => f64::from(u8::from(x <= 0.5)),
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

    /// The integral of the 2D filter over its square, pixels^2: the square of the 1D
    /// integral, by Simpson's rule on 4,096 intervals (exact for the Mitchell cubic, whose
    /// pieces meet at interval ends; to 1e-12 for the Gaussian).
    pub fn integral(&self) -> f64 {
        const INTERVALS: usize = 4096;
        let radius = self.radius();
        let h = 2.0 * radius / INTERVALS as f64;
        let sum: f64 = (0..=INTERVALS)
            .map(|i| {
                let factor = if i == 0 || i == INTERVALS {
                    1.0
                } else if i % 2 == 1 {
                    4.0
                } else {
                    2.0
                };
                factor * self.eval_1d(-radius + i as f64 * h)
            })
            .sum();
        let one_axis = sum * h / 3.0;
        one_axis * one_axis
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
        let integral = filter.integral();
        Some(Self { filter, radius, cells, table: Distribution2D::new(cells, cells, &weights), integral })
    }

    /// The offset from the pixel centre (pixels) that `u` in [0, 1)^2 selects, and its weight
    /// filter / (pdf * integral), of expected value 1 (negative in a negative lobe).
    pub fn sample(&self, u: DVec2) -> (DVec2, f64) {
        let ((column, row), probability, within) = self.table.sample(u);
        let cell = 2.0 * self.radius / self.cells as f64;
        let offset =
            DVec2::new(-self.radius + (column as f64 + within.x) * cell, -self.radius + (row as f64 + within.y) * cell);
        let pdf = probability / (cell * cell);
        (offset, self.filter.eval(offset) / (pdf * self.integral))
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

    /// The weights have expected value 1, so the plain mean of w g estimates the
    /// filter-weighted mean ∫ f g / ∫ f of a test function g without normalising by the
    /// weights' sum (within 5 standard errors); and the integral is the filter's.
    #[test]
    fn weights_estimate_the_filtered_mean() {
        let g = |p: DVec2| 1.0 + p.x + 0.5 * p.y * p.y + (3.0 * p.x).sin();
        for filter in filters() {
            let sampler = FilterSampler::new(filter).unwrap();
            let integral = integrate(filter.radius(), |p| filter.eval(p));
            assert!(
                (filter.integral() / integral - 1.0).abs() < 1e-4,
                "{filter:?}: {} vs {integral}",
                filter.integral()
            );
            let exact = integrate(filter.radius(), |p| filter.eval(p) * g(p)) / integral;
            let mut rng = TestRng::new(5);
            let n = 400_000;
            let (mut sum, mut squares, mut weights) = (0.0, 0.0, 0.0);
            for _ in 0..n {
                let (p, w) = sampler.sample(DVec2::new(rng.uniform(), rng.uniform()));
                sum += w * g(p);
                squares += (w * g(p)).powi(2);
                weights += w;
            }
            let mean = sum / n as f64;
            let error = ((squares / n as f64 - mean * mean) / n as f64).sqrt();
            assert!((mean - exact).abs() < 5.0 * error, "{filter:?}: {mean} vs {exact} (error {error})");
            assert!((weights / n as f64 - 1.0).abs() < 0.01, "{filter:?}: mean weight {}", weights / n as f64);
        }
    }

    /// Mitchell-Netravali filters integrate to 1 for any B and C; the truncated Gaussian's
    /// integral has a closed form.
    #[test]
    fn filter_integrals_are_exact() {
        for filter in [PixelFilter::Mitchell { b: 1.0 / 3.0, c: 1.0 / 3.0 }, PixelFilter::Mitchell { b: 0.0, c: 0.5 }] {
            assert!((filter.integral() - 1.0).abs() < 1e-12, "{filter:?}: {}", filter.integral());
        }
        let stddev: f64 = 0.5;
        let cut = 4.0 * stddev;
        // ∫ exp(-x^2 / 2s^2) over [-4s, 4s] = s sqrt(2 pi) erf(4 / sqrt 2), minus the constant.
        let erf_2_sqrt2 = 0.999_936_657_516_334_2;
        let one_axis = stddev * (2.0 * std::f64::consts::PI).sqrt() * erf_2_sqrt2 - 2.0 * cut * (-8.0f64).exp();
        let gaussian = PixelFilter::Gaussian { stddev };
        assert!((gaussian.integral() / (one_axis * one_axis) - 1.0).abs() < 1e-10, "{}", gaussian.integral());
    }

    #[test]
    fn the_centre_sample_lands_on_the_centre() {
        for filter in filters() {
            let (p, w) = FilterSampler::new(filter).unwrap().sample(DVec2::splat(0.5));
            assert!(p.length() < 1e-9 && w > 0.0, "{filter:?}: {p}");
        }
    }
}
