//! POV-Ray 3.7's `crackle` pattern (Jim McElhiney's, `crackle_pattern` in `pattern.cpp`): the
//! distances from a point to the nearest of a field of pseudo-random points, one per unit
//! cube, combined by `form`; `crackle(p) = 0` is the Voronoi diagram of the points.
//!
//! The points are POV-Ray's own, so the pattern is the same function: the point of cube
//! `(i, j, k)` is the cube's corner plus three consecutive entries, from index `Hash3d(i, j,
//! k)`, of POV-Ray's `PatternRands` table, the first values of a Mersenne Twister (mt19937,
//! its default seed) mapped to [0, 1) by Boost's `uniform_real` (the 32-bit output over 2^32).
//! The nearest points are searched, as POV-Ray does, among the point's own cube and its 80
//! neighbours within a "3D knight move" (offsets of at most 2 with at most one 2).

use std::cell::RefCell;
use std::sync::LazyLock;

use glam::DVec3;

use super::noise::{hash3d, noise};

/// POV-Ray's `EPSILON`: the cube of a point is `floor(x - EPSILON)`.
const POV_EPSILON: f64 = 1.0e-10;

/// How many `PatternRands` entries the cells read: a hash is below 4096, and each cell reads
/// three entries from it.
const RANDS_USED: usize = 4096 + 2;

/// POV-Ray's crackle parameters (`form`, `metric`, `offset`, `solid`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CrackleParams {
    /// Weights of the distances to the nearest, second and third nearest points.
    pub form: DVec3,
    /// The Minkowski metric's exponent (2: Euclidean, 1: Manhattan).
    pub metric: f64,
    /// Added to every distance (as `offset^metric` to the powered sums).
    pub offset: f64,
    /// Constant per cell: the noise at the nearest point instead of the distances.
    pub solid: bool,
}

impl Default for CrackleParams {
    /// POV-Ray's defaults: form <-1, 1, 0>, metric 2, offset 0, not solid.
    fn default() -> Self {
        Self { form: DVec3::new(-1.0, 1.0, 0.0), metric: 2.0, offset: 0.0, solid: false }
    }
}

/// The first `n` outputs of mt19937 with its default seed 5489 (as `std::mt19937` and
/// `boost::mt19937` give them).
fn mt19937(n: usize) -> Vec<u32> {
    const N: usize = 624;
    const M: usize = 397;
    let mut state = [0u32; N];
    state[0] = 5489;
    for i in 1..N {
        state[i] = 1_812_433_253u32.wrapping_mul(state[i - 1] ^ (state[i - 1] >> 30)).wrapping_add(i as u32);
    }
    let mut out = Vec::with_capacity(n);
    let mut index = N;
    while out.len() < n {
        if index == N {
            for i in 0..N {
                let y = (state[i] & 0x8000_0000) | (state[(i + 1) % N] & 0x7FFF_FFFF);
                let mag = if y & 1 == 1 { 0x9908_B0DF } else { 0 };
                state[i] = state[(i + M) % N] ^ (y >> 1) ^ mag;
            }
            index = 0;
        }
        let mut y = state[index];
        index += 1;
        y ^= y >> 11;
        y ^= (y << 7) & 0x9D2C_5680;
        y ^= (y << 15) & 0xEFC6_0000;
        y ^= y >> 18;
        out.push(y);
    }
    out
}

/// POV-Ray's `PatternRands` (`RandomDoubleSequence(0.0, 1.0, 32768)`), the entries cells read.
static PATTERN_RANDS: LazyLock<Vec<f64>> =
    LazyLock::new(|| mt19937(RANDS_USED).into_iter().map(|u| f64::from(u) / 4_294_967_296.0).collect());

/// POV-Ray's `CrackleCubeTable`: the 81 cube offsets searched, in its order (the order
/// decides which of two equally near points a `solid` crackle takes).
static CUBE_OFFSETS: LazyLock<Vec<[i64; 3]>> = LazyLock::new(|| {
    let mut offsets = Vec::with_capacity(81);
    for x in -2..=2 {
        for y in -2..=2 {
            for z in -2..=2 {
                let twos = [x, y, z].iter().filter(|v: &&i64| v.abs() == 2).count();
                if twos <= 1 {
                    offsets.push([x, y, z]);
                }
            }
        }
    }
    offsets
});

/// The largest cube coordinate searched: from 2^53 on every f64 is a whole number, so
/// there are no finer cells to tell apart.
const MAX_CUBE: f64 = 9_007_199_254_740_992.0;

/// The random point of unit cube `(x, y, z)` (POV-Ray's `IntPickInCube`), for coordinates
/// within ±2^53.
pub fn cell_point(x: i64, y: i64, z: i64) -> DVec3 {
    // The hash reads the low twelve bits, which the cast to i32 keeps.
    let seed = hash3d(x as i32, y as i32, z as i32);
    let r = &*PATTERN_RANDS;
    DVec3::new(x as f64 + r[seed], y as f64 + r[seed + 1], z as f64 + r[seed + 2])
}

/// The unit cube of `q` as POV-Ray finds it, `floor(q - EPSILON)`, each coordinate clamped
/// to ±2^53 so that the neighbours searched around it cannot overflow (a point that far
/// out, or one made infinite or NaN by extreme turbulence, still reads a cube).
fn cube_of(q: DVec3) -> [i64; 3] {
    // `as` maps NaN to 0.
    q.to_array().map(|v| (v - POV_EPSILON).floor().clamp(-MAX_CUBE, MAX_CUBE) as i64)
}

/// The 81 cell points searched around cube `cube`, in [`CUBE_OFFSETS`]' order.
type CubeCells = [DVec3; 81];

/// How many cubes each thread keeps the cells of: a material may read two cell fields at
/// once (a `facets` normal beside a `crackle` one, patterns of different scales), whose
/// lookups would evict each other from a single entry on every call.
const CACHED_CUBES: usize = 4;

/// The cells of the cubes of recent lookups on one thread, replaced in turn.
struct CubeCache {
    entries: Vec<([i64; 3], Box<CubeCells>)>,
    next: usize,
}

impl CubeCache {
    /// The index of `cube`'s cells, computing them into the oldest entry when absent.
    fn find_or_fill(&mut self, cube: [i64; 3]) -> usize {
        if let Some(i) = self.entries.iter().position(|(at, _)| *at == cube) {
            return i;
        }
        let fill = |cells: &mut CubeCells| {
            for (cell, [dx, dy, dz]) in cells.iter_mut().zip(CUBE_OFFSETS.iter()) {
                *cell = cell_point(cube[0] + dx, cube[1] + dy, cube[2] + dz);
            }
        };
        if self.entries.len() < CACHED_CUBES {
            let mut cells = Box::new([DVec3::ZERO; 81]);
            fill(&mut cells);
            self.entries.push((cube, cells));
            return self.entries.len() - 1;
        }
        let i = self.next;
        self.next = (i + 1) % CACHED_CUBES;
        let (at, cells) = &mut self.entries[i];
        *at = cube;
        fill(cells);
        i
    }
}

thread_local! {
    /// The cells of the cubes recent lookups on this thread fell in (POV-Ray keeps a
    /// per-thread cache of cubes too): neighbouring shading points mostly share a cube, and
    /// the points are a pure function of the cube, so the cache changes no result.
    static RECENT_CUBES: RefCell<CubeCache> = const { RefCell::new(CubeCache { entries: Vec::new(), next: 0 }) };
}

/// Calls `f` with the 81 cell points around `cube`, computing them only when no recent
/// lookup on this thread was in that cube.
fn with_cells<T>(cube: [i64; 3], f: impl FnOnce(&CubeCells) -> T) -> T {
    RECENT_CUBES.with(|cache| {
        let mut cache = cache.borrow_mut();
        let i = cache.find_or_fill(cube);
        f(&cache.entries[i].1)
    })
}

/// How a distance is measured: POV-Ray's three code paths for metric 2, 1 and the others.
#[derive(Clone, Copy)]
enum Metric {
    Square,
    Unity,
    Power(f64),
}

impl Metric {
    /// The powered sum of `d`'s components (the metric's distance to the power `metric`).
    fn sum(self, d: DVec3) -> f64 {
        match self {
            Metric::Square => d.length_squared(),
            Metric::Unity => d.x.abs() + d.y.abs() + d.z.abs(),
            Metric::Power(m) => d.x.abs().powf(m) + d.y.abs().powf(m) + d.z.abs().powf(m),
        }
    }

    /// A powered sum back to a distance.
    fn root(self, sum: f64) -> f64 {
        match self {
            Metric::Square => sum.sqrt(),
            Metric::Unity => sum,
            Metric::Power(m) => sum.powf(1.0 / m),
        }
    }

    /// A bound on the largest component of a difference whose powered sum is below `sum`:
    /// a point farther than it along any axis is no nearer than `sum`, so the search skips
    /// it without its powers. `None` where the check would cost what it saves (metrics 1
    /// and 2) or where the bound's margin falls below the powers' rounding (metrics below
    /// 1/100). The margin of a millionth keeps the skip exact: `max^m` then exceeds `sum` by
    /// far more than `powf`'s rounding, and the sum of the three powers is at least each.
    fn cutoff(self, sum: f64) -> Option<f64> {
        match self {
            Metric::Power(m) if m >= 0.01 => Some(sum.powf(1.0 / m) * (1.0 + 1e-6)),
            _ => None,
        }
    }

    /// `offset` as a powered sum.
    fn power(self, offset: f64) -> f64 {
        match self {
            Metric::Square => offset * offset,
            Metric::Unity => offset,
            Metric::Power(m) => offset.powf(m),
        }
    }
}

/// POV-Ray's crackle at pattern point `q` (POV-Ray's frame), in [0, 1].
pub fn crackle(q: DVec3, params: &CrackleParams) -> f64 {
    let metric = if params.metric == 2.0 {
        Metric::Square
    } else if params.metric == 1.0 {
        Metric::Unity
    } else {
        Metric::Power(params.metric)
    };
    with_cells(cube_of(q), |cells| crackle_in(q, cells, metric, params))
}

/// [`crackle`] with the cells around `q`'s cube given.
fn crackle_in(q: DVec3, cells: &CubeCells, metric: Metric, params: &CrackleParams) -> f64 {
    let point = |i: usize| cells[i];
    // The three smallest sums, ordered, and the index of the nearest point, exactly as
    // POV-Ray sorts the first three and then walks the rest.
    let (mut s1, mut s2, mut s3) = (metric.sum(point(0) - q), metric.sum(point(1) - q), metric.sum(point(2) - q));
    let mut nearest = 0;
    if s2 < s1 {
        std::mem::swap(&mut s1, &mut s2);
        nearest = 1;
    }
    if s3 < s1 {
        std::mem::swap(&mut s1, &mut s3);
        nearest = 2;
    }
    if s3 < s2 {
        std::mem::swap(&mut s2, &mut s3);
    }
    let mut cutoff = metric.cutoff(s3);
    for i in 3..cells.len() {
        let d = point(i) - q;
        if cutoff.is_some_and(|c| d.abs().max_element() > c) {
            continue;
        }
        let sum = metric.sum(d);
        if sum < s1 {
            s3 = s2;
            s2 = s1;
            s1 = sum;
            nearest = i;
        } else if sum < s2 {
            s3 = s2;
            s2 = sum;
        } else if sum < s3 {
            s3 = sum;
        } else {
            continue;
        }
        cutoff = metric.cutoff(s3);
    }
    if params.offset != 0.0 {
        let o = metric.power(params.offset);
        s1 += o;
        s2 += o;
        s3 += o;
    }
    let value = if params.solid {
        noise(point(nearest))
    } else {
        let f = params.form;
        f.x * metric.root(s1) + f.y * metric.root(s2) + f.z * metric.root(s3)
    };
    value.clamp(0.0, 1.0)
}

/// POV-Ray's `facets` search: the cell point nearest to `tv` among the same 81 cubes, the
/// first of equals winning. Its metric 1 sums the components without their absolute values,
/// as POV-Ray's `facets` does.
pub fn nearest_facet_point(tv: DVec3, metric: f64) -> DVec3 {
    let sum = |d: DVec3| {
        if metric == 2.0 {
            d.length_squared()
        } else if metric == 1.0 {
            d.x + d.y + d.z
        } else {
            d.x.abs().powf(metric) + d.y.abs().powf(metric) + d.z.abs().powf(metric)
        }
    };
    let power = (metric != 2.0 && metric != 1.0).then_some(Metric::Power(metric));
    with_cells(cube_of(tv), |cells| {
        let mut best = DVec3::ZERO;
        let mut best_sum = f64::INFINITY;
        let mut cutoff = None;
        for (i, &p) in cells.iter().enumerate() {
            let d = p - tv;
            if cutoff.is_some_and(|c| d.abs().max_element() > c) {
                continue;
            }
            let s = sum(d);
            if i == 0 || s < best_sum {
                best = p;
                best_sum = s;
                cutoff = power.and_then(|m| m.cutoff(best_sum));
            }
        }
        best
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mersenne_twister_matches_the_standard() {
        // C++11 [rand.predef]: the 10000th output of a default-constructed mt19937.
        assert_eq!(mt19937(10_000)[9_999], 4_123_659_995);
        assert_eq!(mt19937(1)[0], 3_499_211_612);
        assert_eq!(PATTERN_RANDS[0], 3_499_211_612.0 / 4_294_967_296.0);
    }

    #[test]
    fn far_and_non_finite_points_search_a_cube_without_overflow() {
        // Past the i32 range (a plane seen far away through a small pattern scale), at the
        // f64 limit and beyond it.
        for v in [3.0e9, -3.0e9, 2.0f64.powi(60), 1e300, f64::INFINITY, f64::NEG_INFINITY, f64::NAN] {
            let q = DVec3::new(v, 0.25, -v);
            let value = crackle(q, &CrackleParams::default());
            assert!(value.is_nan() || (0.0..=1.0).contains(&value), "{v}: {value}");
            let _ = nearest_facet_point(q, 2.0);
        }
        // Within it the cells are still the point's own.
        let q = DVec3::new(3.0e9 + 0.5, 0.5, 0.5);
        assert_eq!(cube_of(q), [3_000_000_000, 0, 0]);
        assert!(crackle(q, &CrackleParams::default()).is_finite());
    }

    #[test]
    fn cube_table_is_povrays_81_cells_in_order() {
        assert_eq!(CUBE_OFFSETS.len(), 81);
        // x = -2 allows only y, z in -1..=1: the first entry is (-2, -1, -1).
        assert_eq!(CUBE_OFFSETS[0], [-2, -1, -1]);
        assert_eq!(CUBE_OFFSETS[80], [2, 1, 1]);
        assert!(CUBE_OFFSETS.contains(&[0, 0, -2]) && !CUBE_OFFSETS.contains(&[0, 2, -2]));
    }

    #[test]
    fn cell_points_lie_in_their_cube_and_wrap_every_4096() {
        for (x, y, z) in [(0, 0, 0), (-1, 3, -7), (4095, -4096, 17)] {
            let p = cell_point(x, y, z);
            let corner = DVec3::new(x as f64, y as f64, z as f64);
            assert!((p - corner).min_element() >= 0.0 && (p - corner).max_element() < 1.0, "{p}");
            // The hash reads coordinates modulo 4096.
            assert_eq!(cell_point(x + 4096, y, z) - DVec3::new(4096.0, 0.0, 0.0), p);
        }
        let r = &*PATTERN_RANDS;
        let h = hash3d(-1, 2, 3);
        assert_eq!(cell_point(-1, 2, 3), DVec3::new(-1.0 + r[h], 2.0 + r[h + 1], 3.0 + r[h + 2]));
    }

    /// The cell points POV-Ray searches around `q` (its cube and the 80 knight-move
    /// neighbours) with their powered sums, nearest first: the answer by sorting.
    fn sorted_sums(q: DVec3, metric: Metric) -> Vec<(f64, DVec3)> {
        let c = (q - DVec3::splat(POV_EPSILON)).floor();
        let mut all: Vec<(f64, DVec3)> = CUBE_OFFSETS
            .iter()
            .map(|[x, y, z]| {
                let p = cell_point(c.x as i64 + x, c.y as i64 + y, c.z as i64 + z);
                (metric.sum(p - q), p)
            })
            .collect();
        all.sort_by(|a, b| a.0.total_cmp(&b.0));
        all
    }

    const POINTS: [DVec3; 4] = [
        DVec3::new(0.31, -1.27, 2.45),
        DVec3::new(-3.5, 0.25, 0.125),
        DVec3::new(10.2, 4.4, -7.9),
        DVec3::new(0.0, 0.0, 0.0),
    ];

    #[test]
    fn default_form_is_second_minus_first_euclidean_distance() {
        for q in POINTS {
            let s = sorted_sums(q, Metric::Square);
            let expected = (s[1].0.sqrt() - s[0].0.sqrt()).clamp(0.0, 1.0);
            assert!((crackle(q, &CrackleParams::default()) - expected).abs() < 1e-15, "{q}");
        }
    }

    #[test]
    fn metrics_one_two_and_three_with_form_and_offset() {
        for q in POINTS {
            // Metric 1: Manhattan distances, used unrooted; form picks the third.
            let s = sorted_sums(q, Metric::Unity);
            let p = CrackleParams { form: DVec3::new(0.0, 0.0, 0.5), metric: 1.0, offset: 0.1, solid: false };
            let expected = (0.5 * (s[2].0 + 0.1)).clamp(0.0, 1.0);
            assert!((crackle(q, &p) - expected).abs() < 1e-14, "metric 1 at {q}");
            // Metric 3: cube roots of the sums of cubes, the offset added as its cube.
            let s = sorted_sums(q, Metric::Power(3.0));
            let p = CrackleParams { form: DVec3::new(1.0, 0.0, 0.0), metric: 3.0, offset: 0.2, solid: false };
            let expected = (s[0].0 + 0.008).powf(1.0 / 3.0).clamp(0.0, 1.0);
            assert!((crackle(q, &p) - expected).abs() < 1e-14, "metric 3 at {q}");
            // Metric 2 with an offset: sqrt(d^2 + offset^2).
            let s = sorted_sums(q, Metric::Square);
            let p = CrackleParams { form: DVec3::new(0.5, 0.0, 0.0), offset: 0.3, ..CrackleParams::default() };
            let expected = (0.5 * (s[0].0 + 0.09).sqrt()).clamp(0.0, 1.0);
            assert!((crackle(q, &p) - expected).abs() < 1e-14, "offset at {q}");
        }
    }

    /// Skipping the cells whose largest component is beyond the third distance changes
    /// nothing: on random points, for metrics with and without the skip, every form and
    /// `solid` give exactly what sorting all 81 powered sums gives.
    #[test]
    fn the_pruned_search_equals_sorting_every_cell() {
        let mut rng = prism_api::contract::TestRng::new(41);
        for metric in [0.005, 0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 7.0, 100.0] {
            let kind = if metric == 2.0 {
                Metric::Square
            } else if metric == 1.0 {
                Metric::Unity
            } else {
                Metric::Power(metric)
            };
            for _ in 0..300 {
                let q = DVec3::new(rng.range(-20.0, 20.0), rng.range(-20.0, 20.0), rng.range(-20.0, 20.0));
                let s = sorted_sums(q, kind);
                let form = DVec3::new(0.7, -0.4, 0.3);
                let p = CrackleParams { form, metric, offset: 0.0, solid: false };
                let expected = (form.x * kind.root(s[0].0) + form.y * kind.root(s[1].0) + form.z * kind.root(s[2].0))
                    .clamp(0.0, 1.0);
                assert_eq!(crackle(q, &p).to_bits(), expected.to_bits(), "metric {metric} at {q}");
                let solid = CrackleParams { solid: true, ..p };
                assert_eq!(crackle(q, &solid).to_bits(), noise(s[0].1).to_bits(), "solid, metric {metric} at {q}");
                if metric != 1.0 {
                    assert_eq!(nearest_facet_point(q, metric), s[0].1, "facets, metric {metric} at {q}");
                }
            }
        }
    }

    #[test]
    fn crackle_is_zero_on_the_voronoi_boundary_and_positive_inside() {
        // Halfway between a cell point and its nearest neighbour the default form is 0;
        // at the cell point itself it is the distance to the neighbour (clamped).
        let a = cell_point(0, 0, 0);
        let s = sorted_sums(a, Metric::Square);
        let b = s[1].1;
        let mid = (a + b) * 0.5;
        assert!(crackle(mid, &CrackleParams::default()) < 1e-9);
        assert!((crackle(a, &CrackleParams::default()) - s[1].0.sqrt().min(1.0)).abs() < 1e-15);
    }

    #[test]
    fn facets_take_the_nearest_cell_point() {
        for q in POINTS {
            let s = sorted_sums(q, Metric::Square);
            assert_eq!(nearest_facet_point(q, 2.0), s[0].1, "{q}");
            let s = sorted_sums(q, Metric::Power(3.0));
            assert_eq!(nearest_facet_point(q, 3.0), s[0].1, "{q}");
        }
        // Metric 1 without absolute values: the smallest signed sum, a point below and
        // behind rather than the nearest.
        let q = DVec3::new(0.5, 0.5, 0.5);
        let c = (q - DVec3::splat(POV_EPSILON)).floor();
        let signed = CUBE_OFFSETS
            .iter()
            .map(|[x, y, z]| cell_point(c.x as i64 + x, c.y as i64 + y, c.z as i64 + z))
            .min_by(|a, b| (a.x + a.y + a.z).total_cmp(&(b.x + b.y + b.z)))
            .unwrap();
        assert_eq!(nearest_facet_point(q, 1.0), signed);
    }

    #[test]
    fn solid_crackle_is_constant_per_cell_and_the_noise_at_its_point() {
        let solid = CrackleParams { solid: true, ..CrackleParams::default() };
        let a = cell_point(2, -1, 5);
        let value = noise(a);
        // Points close to the cell point share its nearest point.
        for d in [DVec3::new(0.01, 0.0, 0.0), DVec3::new(-0.02, 0.015, 0.01), DVec3::ZERO] {
            assert_eq!(crackle(a + d, &solid), value);
        }
        // Across a boundary the value is another cell's.
        let s = sorted_sums(a, Metric::Square);
        assert_eq!(crackle(s[1].1, &solid), noise(s[1].1));
    }
}
