//! Criterion benchmarks of the hot kernels: shape intersection (per plugin), the top-level
//! BVH's closest-hit and occlusion queries, POV-Ray's solid noise and crackle (what the
//! pattern scenes spend their time in), and a whole small render of the seed room.
//! Run with `cargo bench --bench kernels`; report ratios measured in one run.

use std::hint::black_box;
use std::path::Path;

use criterion::{Criterion, Throughput, criterion_main};
use prism::render::{RenderOptions, render_frame};
use prism_api::contract::TestRng;
use prism_api::{DVec3, Ray};

/// Rays aimed from a sphere of radius 4 at random points in the unit cube.
fn rays(count: usize) -> Vec<Ray> {
    let mut rng = TestRng::new(7);
    (0..count)
        .map(|_| {
            let origin = rng.unit_vector() * 4.0;
            let target = DVec3::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0), rng.range(-1.0, 1.0));
            Ray::new(origin, (target - origin).normalize())
        })
        .collect()
}

fn shape_from(kind: &str, params: &str) -> std::sync::Arc<dyn prism_api::Shape> {
    let registry = prism::plugins::registry();
    let table: toml::Table = toml::from_str(params).unwrap();
    (registry.get(kind).unwrap().build)(table, &mut prism_api::NoFiles).unwrap()
}

fn shapes(c: &mut Criterion) {
    let rays = rays(4096);
    let mut group = c.benchmark_group("intersect");
    group.throughput(Throughput::Elements(rays.len() as u64));
    for (name, kind, params) in [
        ("sphere", "sphere", "radius = 1"),
        ("box", "box", ""),
        ("cone", "cone", "open = false"),
        ("cylinder", "cylinder", ""),
        ("torus", "torus", "major_radius = 0.8\nminor_radius = 0.2"),
        ("superellipsoid", "superellipsoid", "e = 0.5\nn = 0.5"),
        // Exponents in eighths (no powf), and a concave shape (the sampled scan).
        ("superellipsoid_rounded_cube", "superellipsoid", "e = 0.25\nn = 0.25"),
        ("superellipsoid_concave", "superellipsoid", "e = 2.5\nn = 1.5"),
        (
            "blob",
            "blob",
            "components = [{ center = [-0.3, 0, 0], radius = 0.8, strength = 1 }, { center = [0.3, 0, 0], radius = 0.8, strength = 1 }]",
        ),
    ] {
        let shape = shape_from(kind, params);
        group.bench_function(name, |b| {
            b.iter(|| rays.iter().filter(|r| shape.intersect(black_box(r), 1e-6, f64::INFINITY).is_some()).count())
        });
    }
    group.finish();
}

fn room() -> prism::render::extract::RenderScene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/room.toml");
    let mut scene = prism::scene::load::load_file(&path, &prism::plugins::registry()).unwrap();
    scene.render.width = 200;
    scene.render.height = 113;
    prism::prepare(&mut scene).unwrap()
}

fn queries(c: &mut Criterion) {
    let scene = room();
    let camera_rays: Vec<Ray> = (0..4096)
        .map(|i| {
            let (x, y) = ((i % 64) as f64 / 64.0 - 0.5, 0.5 - (i / 64) as f64 / 64.0);
            scene.camera.ray(x, y, glam::DVec2::ZERO)
        })
        .collect();
    let mut group = c.benchmark_group("room_queries");
    group.throughput(Throughput::Elements(camera_rays.len() as u64));
    group.bench_function("closest", |b| {
        b.iter(|| {
            camera_rays
                .iter()
                .filter(|r| scene.accel.closest(&scene.primitives, black_box(r), 1e-6, 1e7, |_| true).is_some())
                .count()
        })
    });
    group.bench_function("occluded", |b| {
        b.iter(|| {
            camera_rays
                .iter()
                .filter(|r| scene.accel.occluded(&scene.primitives, black_box(r), 1e-3, 5.0, |_| true))
                .count()
        })
    });
    group.finish();
}

/// POV-Ray's noise, its vector form (normal perturbations), its turbulence and crackle at
/// random points, per call.
fn patterns(c: &mut Criterion) {
    use prism::material::crackle::{CrackleParams, crackle};
    use prism::material::noise::{Octaves, dnoise, noise, turbulence};
    let mut rng = TestRng::new(5);
    let points: Vec<DVec3> =
        (0..4096).map(|_| DVec3::new(rng.range(-50.0, 50.0), rng.range(-50.0, 50.0), rng.range(-50.0, 50.0))).collect();
    let mut group = c.benchmark_group("patterns");
    group.throughput(Throughput::Elements(points.len() as u64));
    group.bench_function("noise", |b| b.iter(|| points.iter().map(|&p| noise(black_box(p))).sum::<f64>()));
    group.bench_function("dnoise", |b| b.iter(|| points.iter().map(|&p| dnoise(black_box(p))).sum::<DVec3>()));
    let octaves = Octaves::default();
    group.bench_function("turbulence_6_octaves", |b| {
        b.iter(|| points.iter().map(|&p| turbulence(black_box(p), &octaves)).sum::<f64>())
    });
    for (name, metric) in [("crackle_metric_2", 2.0), ("crackle_metric_3", 3.0)] {
        let params = CrackleParams { metric, ..CrackleParams::default() };
        // Neighbouring points, as a surface's shading points are: mostly in one cube.
        group.bench_function(name, |b| {
            b.iter(|| points.iter().map(|&p| crackle(black_box(p * 0.02), &params)).sum::<f64>())
        });
    }
    group.finish();
}

fn whole_render(c: &mut Criterion) {
    let scene = room();
    let mut group = c.benchmark_group("render");
    group.sample_size(20);
    group.throughput(Throughput::Elements(u64::from(scene.settings.width * scene.settings.height)));
    group.bench_function("room_200x113_1thread", |b| {
        b.iter(|| render_frame(&scene, &RenderOptions { threads: Some(1), ..Default::default() }).unwrap())
    });
    group.finish();
}

/// The benchmarks, in a module of their own: `criterion_group!` defines a public function
/// without documentation, which `missing_docs` would report at the crate root.
mod groups {
    use super::{patterns, queries, shapes, whole_render};
    criterion::criterion_group!(benches, shapes, queries, patterns, whole_render);
}
criterion_main!(groups::benches);
