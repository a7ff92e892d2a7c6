//! The `path` integrator against closed-form answers (pbrt-v4's and Mitsuba's habit): a
//! white furnace, a camera inside an emitting, reflecting sphere, direct light from a
//! spherical emitter, no NaN or infinity on the film, and the same image for any thread
//! count.
//!
//! Each test states its tolerance as a number of standard errors of the pixel mean, which
//! the test measures from the image itself.

use std::path::Path;

use prism::film::Film;
use prism::render::{RenderOptions, render_frame};
use prism::scene::load::{Embedded, load_from};

fn render_text(text: &'static str, threads: usize) -> Film {
    let files: &'static [(&'static str, &'static str)] = Box::leak(Box::new([("scene.toml", text)]));
    let embedded: &'static Embedded = Box::leak(Box::new(Embedded(files)));
    let mut scene = load_from(embedded, Path::new("scene.toml"), &prism::plugins::registry()).unwrap();
    let prepared = prism::prepare(&mut scene).unwrap();
    let options = RenderOptions { threads: Some(threads), ..Default::default() };
    render_frame(&prepared, &options).unwrap().0
}

/// Mean and standard error of the mean of one channel over all pixels.
fn mean_and_error(film: &Film, channel: usize) -> (f64, f64) {
    let values: Vec<f64> = film.pixels.iter().map(|p| f64::from(p[channel])).collect();
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let variance = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, (variance / n).sqrt())
}

fn assert_mean(film: &Film, expected: [f64; 3], what: &str) {
    for (c, want) in expected.into_iter().enumerate() {
        let (mean, error) = mean_and_error(film, c);
        // 4 standard errors plus a floor for the float film.
        let tolerance = 4.0 * error + 1e-4 * want.abs();
        assert!(
            (mean - want).abs() <= tolerance,
            "{what}: channel {c} mean {mean} differs from {want} by more than {tolerance} (4 standard errors)"
        );
    }
}

#[test]
fn a_white_diffuse_sphere_in_a_uniform_environment_vanishes() {
    // White furnace: a non-absorbing convex object under a uniform environment returns
    // exactly the environment, at every depth that lets light in and out.
    let film = render_text(
        "[render]\nwidth = 24\nheight = 24\nsamples = 64\nmax_depth = 10\nintegrator = \"path\"\n\
         [world]\nbackground = [0.5, 0.5, 0.5]\n\
         [camera]\nposition = [0, 0, 4]\nvfov = 30\n\
         [[object]]\nshape = \"sphere\"\nradius = 1.0\nmaterial = { bsdf = { type = \"diffuse\" } }\n",
        2,
    );
    assert_mean(&film, [0.5; 3], "furnace");
    // Every pixel, not just the mean: a perfectly white object under white light is exact
    // up to noise in each pixel too, so look for any pixel far off.
    for p in &film.pixels {
        for &c in p {
            assert!((0.0..3.0).contains(&c), "pixel value {c} out of range");
        }
    }
}

#[test]
fn inside_an_emitting_reflecting_sphere_radiance_sums_the_geometric_series() {
    // Le = 0.5 emitted inward (two-sided emission), albedo 0.5: L = Le / (1 - albedo) = 1
    // (pbrt-v4's analytic test).
    let film = render_text(
        "[render]\nwidth = 16\nheight = 16\nsamples = 64\nmax_depth = 200\nrr_depth = 5\nintegrator = \"path\"\n\
         [camera]\nposition = [0, 0, 0]\nlook_at = [0, 0, -1]\nvfov = 60\n\
         [[object]]\nshape = \"sphere\"\nradius = 2.0\n\
         material = { color = 0.5, bsdf = { type = \"diffuse\" }, emission = 0.5, emission_two_sided = true }\n",
        2,
    );
    assert_mean(&film, [1.0; 3], "emitting sphere");
}

#[test]
fn a_spherical_lamp_lights_a_diffuse_floor_as_the_formula_says() {
    // A lamp of radius r and radiance L at height h above a floor of albedo a: the floor
    // point straight below sees it within a cone of half-angle asin(r/h), receives
    // E = pi L (r/h)^2 and reflects a E / pi = a L (r/h)^2. The camera looks straight down
    // at that point through a narrow field of view (so the floor under it is nearly that
    // point); max_depth 2 is direct light only. The lamp is behind the camera.
    let film = render_text(
        "[render]\nwidth = 8\nheight = 8\nsamples = 256\nmax_depth = 2\nintegrator = \"path\"\n\
         [camera]\nposition = [0, 1, 0]\nlook_at = [0, 0, 0]\nup = [0, 0, -1]\nvfov = 0.5\n\
         [[object]]\nshape = \"plane\"\nnormal = [0, 1, 0]\noffset = 0.0\n\
         material = { color = 0.8, bsdf = { type = \"diffuse\" } }\n\
         [[object]]\nshape = \"sphere\"\nradius = 0.5\ntransform = { translate = [0, 2, 0] }\n\
         material = { color = 0.0, bsdf = { type = \"diffuse\" }, emission = 3.0 }\n",
        2,
    );
    let expected = 0.8 * 3.0 * (0.5f64 / 2.0).powi(2);
    assert_mean(&film, [expected; 3], "direct light from a sphere");
}

#[test]
fn an_emissive_csg_group_is_sampled_as_a_light() {
    // A small lamp (r = 0.1 at h = 2: one cosine-distributed direction in 400 reaches it) lit
    // as the formula of the test above says, built as CSG groups whose boundary seen from the
    // floor is the lamp's sphere: the sphere inside a larger box (an intersection) and the
    // sphere less a box through its top (a difference, whose hollow the floor does not see).
    // The group is sampled through its members' surfaces; found only by the rays that happen
    // to reach it (as before groups were sampled), the 1024 samples of the image would meet
    // it about 2.6 times.
    let lamp = |shape: &str| -> &'static str {
        Box::leak(
            format!(
                "[render]\nwidth = 8\nheight = 8\nsamples = 16\nmax_depth = 2\nintegrator = \"path\"\n\
                 [camera]\nposition = [0, 1, 0]\nlook_at = [0, 0, 0]\nup = [0, 0, -1]\nvfov = 0.5\n\
                 [[object]]\nshape = \"plane\"\nnormal = [0, 1, 0]\noffset = 0.0\n\
                 material = {{ color = 0.8, bsdf = {{ type = \"diffuse\" }} }}\n\
                 [[object]]\n{shape}\ntransform = {{ translate = [0, 2, 0] }}\n\
                 material = {{ color = 0.0, bsdf = {{ type = \"diffuse\" }}, emission = 3.0 }}\n"
            )
            .into_boxed_str(),
        )
    };
    let sphere = "{ shape = \"sphere\", radius = 0.1 }";
    let expected = 0.8 * 3.0 * (0.1f64 / 2.0).powi(2);
    for (what, shape) in [
        (
            "intersection",
            format!(
                "shape = \"intersection\"\nmembers = [{sphere}, {{ shape = \"box\", min = [-1, -1, -1], max = [1, 1, 1] }}]"
            ),
        ),
        (
            "difference",
            format!(
                "shape = \"difference\"\nmembers = [{sphere}, {{ shape = \"box\", min = [-0.05, 0.06, -0.05], max = [0.05, 1, 0.05] }}]"
            ),
        ),
    ] {
        let film = render_text(lamp(&shape), 2);
        let (mean, error) = mean_and_error(&film, 1);
        assert_mean(&film, [expected; 3], what);
        assert!(error < 0.02 * mean, "{what}: standard error {error} of {mean}: the group is not sampled as a light");
    }
}

/// A sphere under a sun and a dim sky, with the material `normal` given (or none).
fn bumped_sphere(normal: &str) -> Film {
    let text = format!(
        "[render]\nwidth = 48\nheight = 48\nsamples = 16\nintegrator = \"path\"\n\
         [world]\nbackground = 0.1\n\
         [camera]\nposition = [0, 0, 3]\nlook_at = [0, 0, 0]\nvfov = 45\n\
         [[object]]\nshape = \"sphere\"\nradius = 1.0\nmaterial = {{ color = [0.8, 0.8, 0.8] {normal} }}\n\
         [[light]]\nkind = \"parallel\"\nposition = [2, 2, 3]\nintensity = 3.0\n"
    );
    render_text(Box::leak(text.into_boxed_str()), 2)
}

/// A normal pattern tilts the shading normal under `path` as under `classic`: with a bump
/// size of 0 the image is the smooth one (the same samples, to rounding), with bumps the
/// lit side changes pixel by pixel while its brightness stays about the same, and every
/// pixel stays finite.
#[test]
fn normal_patterns_tilt_the_shading_under_path() {
    let smooth = bumped_sphere("");
    let flat = bumped_sphere(", normal = { pattern = \"bumps\", bump_size = 0.0, scale = 0.2 }");
    let bumpy = bumped_sphere(", normal = { pattern = \"bumps\", bump_size = 1.0, scale = 0.2 }");
    let largest_difference = |a: &Film, b: &Film| {
        a.pixels
            .iter()
            .zip(&b.pixels)
            .map(|(p, q)| (0..3).map(|c| (p[c] - q[c]).abs()).fold(0.0, f32::max))
            .fold(0.0, f32::max)
    };
    assert!(largest_difference(&smooth, &flat) < 1e-4, "bump_size 0 changed the image");
    let changed =
        smooth.pixels.iter().zip(&bumpy.pixels).filter(|(p, q)| p[1] > 0.2 && (p[1] - q[1]).abs() > 0.1 * p[1]).count();
    let lit = smooth.pixels.iter().filter(|p| p[1] > 0.2).count();
    assert!(lit > 300 && changed * 4 > lit, "{changed} of {lit} lit pixels changed by more than 10%");
    let (smooth_mean, _) = mean_and_error(&smooth, 1);
    let (bumpy_mean, _) = mean_and_error(&bumpy, 1);
    assert!((bumpy_mean / smooth_mean - 1.0).abs() < 0.15, "mean {bumpy_mean} against {smooth_mean} when smooth");
    assert!(bumpy.pixels.iter().all(|p| p.iter().all(|c| c.is_finite() && *c >= 0.0)));
}

#[test]
fn no_nan_or_infinity_reaches_the_film() {
    // Grazing geometry, a light inside an object, index-matched and dense glass, a zero
    // roughness conductor, a lamp of enormous radiance touching a surface.
    let film = render_text(
        "[render]\nwidth = 32\nheight = 32\nsamples = 16\nmax_depth = 12\nrr_depth = 2\nintegrator = \"path\"\n\
         [world]\nbackground = [0.2, 0.3, 0.4]\n\
         [camera]\nposition = [0, 0.001, 3]\nlook_at = [0, 0, 0]\nvfov = 70\n\
         [[object]]\nshape = \"plane\"\nnormal = [0, 1, 0]\noffset = 0.0\nmaterial = { bsdf = { type = \"conductor\", metal = \"Au\" } }\n\
         [[object]]\nshape = \"sphere\"\nradius = 0.5\ntransform = { translate = [0, 0.5, 0] }\n\
         material = { bsdf = { type = \"dielectric\", ior = 1.0 } }\n\
         [[object]]\nshape = \"sphere\"\nradius = 0.3\ntransform = { translate = [0.8, 0.3, 0] }\n\
         material = { bsdf = { type = \"dielectric\", ior = 4.0 } }\n\
         [[object]]\nshape = \"sphere\"\nradius = 0.1\ntransform = { translate = [-0.8, 0.1, 0] }\n\
         material = { bsdf = { type = \"diffuse\" }, emission = 1e30 }\n\
         [[light]]\nkind = \"point\"\nposition = [0, 0.5, 0]\nintensity = 10.0\n\
         [[light]]\nkind = \"point\"\nposition = [0, 0, 0]\nintensity = 10.0\n",
        2,
    );
    for p in &film.pixels {
        assert!(p.iter().all(|c| c.is_finite() && *c >= 0.0), "pixel {p:?}");
    }
}

/// Radiance is not negative: a POV-style `emission` with a negative component (a darkening
/// term under classic) emits nothing in that component under path, so the image is the one
/// of the same emission with that component 0, bit for bit, where a point light lights the
/// emitter's reflecting inside (a negative term would darken the light's contribution).
#[test]
fn negative_emission_emits_nothing_under_path() {
    let scene = |emission: &str| -> &'static str {
        Box::leak(
            format!(
                "[render]\nwidth = 8\nheight = 6\nsamples = 8\nintegrator = \"path\"\n\
                 [camera]\nposition = [0, 0, 1]\n\
                 [[light]]\nposition = [0, 1, 0]\ncolor = [1, 0.2, 0.2]\n\
                 [[object]]\nshape = \"sphere\"\nradius = 10.0\n\
                 material = {{ color = [1, 1, 1], diffuse = 0.5, emission = {emission}, emission_two_sided = true }}\n"
            )
            .into_boxed_str(),
        )
    };
    let negative = render_text(scene("[-1.0, 0.5, 0.25]"), 2);
    assert_eq!(negative.pixels, render_text(scene("[0.0, 0.5, 0.25]"), 2).pixels);
    // The emitter's power dwarfs the light's, so few samples pick the light: red in some pixels.
    assert!(negative.pixels.iter().any(|p| p[0] > 0.0), "the light's red reaches the image");
}

#[test]
fn an_emitting_glass_sphere_does_not_light_itself() {
    // Radiance 1 over black: a convex emitter cannot light itself, and its inside (which shows
    // the emitting front of no surface) adds nothing, so the sphere is exactly 1 wherever it is
    // seen. Light sampled from just above the surface once found the sphere's own outside below
    // it through the rough transmission lobe: 1.0226.
    let film = render_text(
        "[render]\nwidth = 8\nheight = 8\nsamples = 64\nmax_depth = 12\nintegrator = \"path\"\n\
         [camera]\nposition = [0, 0, 4]\nvfov = 4\n\
         [[object]]\nshape = \"sphere\"\nradius = 1.0\n\
         material = { bsdf = { type = \"dielectric\", ior = 1.5, alpha = 0.3 }, emission = 1.0 }\n",
        2,
    );
    assert_mean(&film, [1.0; 3], "emitting rough glass");
}

/// A diffuse floor of albedo 0.5 under a uniform environment of radiance 1, seen straight
/// down by an orthographic camera, and lit from straight above by `lights` parallel lights
/// that sum to an irradiance of 1 W/m^2.
fn floor_under_sky_and_parallel_lights(lights: usize) -> Film {
    let mut text = String::from(
        "[render]\nwidth = 16\nheight = 16\nsamples = 4\nintegrator = \"path\"\nmax_depth = 2\n\
         [camera]\nprojection = \"orthographic\"\nposition = [0, 2, 0]\nlook_at = [0, 0, 0]\n\
         up = [0, 0, -1]\nview_height = 2\n\
         [world]\nbackground = 1.0\n\
         [[object]]\nshape = \"plane\"\nnormal = [0, 1, 0]\nmaterial = { color = 0.5, bsdf = { type = \"diffuse\" } }\n",
    );
    for _ in 0..lights {
        text +=
            &format!("[[light]]\nkind = \"parallel\"\nposition = [0, 10, 0]\nintensity = {}\n", 1.0 / lights as f64);
    }
    render_text(Box::leak(text.into_boxed_str()), 2)
}

#[test]
fn point_spot_and_parallel_lights_are_sampled_at_every_bounce() {
    // L = albedo (E / pi + L_sky): 0.5 / pi + 0.5.
    let expected = 0.5 / std::f64::consts::PI + 0.5;
    let film = floor_under_sky_and_parallel_lights(1);
    assert_mean(&film, [expected; 3], "one parallel light and the sky");
    // The light's share is the same in every sample, so only the sky's estimate is noisy.
    // Chosen by power against the sky instead (7 % of the samples), the light left the
    // pixels' standard deviation at 37 % of their mean at 4 samples; sampled always, 6 %.
    let (mean, error) = mean_and_error(&film, 0);
    let spread = error * (film.pixels.len() as f64).sqrt() / mean;
    assert!(spread < 0.15, "pixels spread by {spread} of their mean: the light is not sampled at every bounce");
    // Beyond the limit the lights are chosen among, still without bias.
    let many =
        floor_under_sky_and_parallel_lights(prism::render::integrators::path::light_sampler::EVERY_SOURCE_LIMIT + 1);
    assert_mean(&many, [expected; 3], "many parallel lights and the sky");
}

/// Small lamps over a floor at (x, z) each, rendered from above (an orthographic view 24 x 3
/// about the origin, 96 x 12 pixels, 4 samples): each pixel against the formula averaged over
/// its square; the ratios' mean and spread.
fn lamps_over_a_floor(lamps: &[(f64, f64)]) -> (f64, f64) {
    let (albedo, radiance, radius, height) = (0.5, 100.0, 0.1, 0.6);
    let mut text = String::from(
        "[render]\nwidth = 96\nheight = 12\nsamples = 4\nintegrator = \"path\"\nmax_depth = 2\n\
         [camera]\nprojection = \"orthographic\"\nposition = [0, 0.3, 0]\nlook_at = [0, 0, 0]\n\
         up = [0, 0, -1]\nview_height = 3\n\
         [[object]]\nshape = \"plane\"\nnormal = [0, 1, 0]\nmaterial = { color = 0.5, bsdf = { type = \"diffuse\" } }\n",
    );
    for (x, z) in lamps {
        text += &format!(
            "[[object]]\nshape = \"sphere\"\nradius = {radius}\ntransform = {{ translate = [{x}, {height}, {z}] }}\n\
             material = {{ color = 0.0, bsdf = {{ type = \"diffuse\" }}, emission = {radiance} }}\n"
        );
    }
    let film = render_text(Box::leak(text.into_boxed_str()), 2);
    // A sphere of radius r and radiance L whose centre is at distance D, seen at angle theta
    // from the normal, gives E = pi L (r / D)^2 cos theta; the floor reflects albedo E / pi.
    // The view is symmetric in x and z about the origin, as the lamps are, so its
    // orientation does not matter; each pixel is averaged over 8 x 8 points of its square.
    let at = |x: f64, z: f64| -> f64 {
        lamps
            .iter()
            .map(|(lamp_x, lamp_z)| {
                let d = ((x - lamp_x).powi(2) + (z - lamp_z).powi(2) + height * height).sqrt();
                albedo * radiance * (radius / d).powi(2) * height / d
            })
            .sum()
    };
    let (width, rows) = (96usize, 12usize);
    let pixel = 24.0 / width as f64;
    let mut ratios = Vec::new();
    for j in 0..rows {
        for i in 0..width {
            let mut expected = 0.0;
            for (a, b) in (0..64).map(|k| (k % 8, k / 8)) {
                let x = -12.0 + pixel * (i as f64 + (f64::from(a) + 0.5) / 8.0);
                let z = -1.5 + pixel * (j as f64 + (f64::from(b) + 0.5) / 8.0);
                expected += at(x, z) / 64.0;
            }
            ratios.push(f64::from(film.pixels[j * width + i][1]) / expected);
        }
    }
    let n = ratios.len() as f64;
    let mean = ratios.iter().sum::<f64>() / n;
    let spread = (ratios.iter().map(|r| (r - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt();
    assert!((mean - 1.0).abs() <= 4.0 * spread / n.sqrt() + 1e-3, "pixels average {mean} of the formula");
    (mean, spread)
}

/// Eight small lamps in a row over a floor: each floor point is lit mostly by the lamp
/// above it. Chosen in proportion to what each can give the point, the lamps light every
/// pixel as the formula says with little noise; chosen by power alone (an eighth of the
/// samples to each lamp everywhere), the pixels spread by 80 % of it at 4 samples (now 3 %).
#[test]
fn lamps_are_chosen_by_what_they_give_the_point() {
    let lamps: Vec<(f64, f64)> = (0..8).map(|i| (-10.5 + 3.0 * f64::from(i), 0.0)).collect();
    let (_, spread) = lamps_over_a_floor(&lamps);
    assert!(spread < 0.08, "pixels spread by {spread} of the formula: the lamps are not chosen by where they light");
}

/// The same with 120 lamps, 8 x 15 on a grid 3 apart (the view sees a row of them): more
/// than the choice weighs one by one, so it walks a tree of them, and the pixels spread by
/// 33 % of the formula at 4 samples. Chosen by power alone (a 120th of the samples to each
/// lamp everywhere), they spread by 280 %.
#[test]
fn many_lamps_are_chosen_through_a_tree_by_what_they_give_the_point() {
    let lamps: Vec<(f64, f64)> =
        (0..120).map(|i| (-10.5 + 3.0 * f64::from(i % 8), -21.0 + 3.0 * f64::from(i / 8))).collect();
    assert!(lamps.len() > prism::render::integrators::path::light_sampler::SPATIAL_LIMIT);
    let (_, spread) = lamps_over_a_floor(&lamps);
    assert!(spread < 0.7, "pixels spread by {spread} of the formula: the lamps are not chosen by where they light");
}

#[test]
fn the_image_is_the_same_for_any_thread_count() {
    const SCENE: &str = "[render]\nwidth = 40\nheight = 30\nsamples = 4\nmax_depth = 6\nintegrator = \"path\"\n\
         [world]\nbackground = [0.3, 0.3, 0.3]\n\
         [[object]]\nshape = \"sphere\"\nradius = 0.4\ntransform = { translate = [0, 0, -2] }\n\
         material = { bsdf = { type = \"plastic\", alpha = 0.2 }, color = [0.8, 0.2, 0.1] }\n\
         [[object]]\nshape = \"plane\"\nnormal = [0, 1, 0]\noffset = -0.4\nmaterial = { bsdf = { type = \"diffuse\" } }\n\
         [[light]]\nkind = \"spot\"\nposition = [1, 2, -1]\npoint_at = [0, 0, -2]\nintensity = 5.0\n";
    let one = render_text(SCENE, 1);
    let two = render_text(SCENE, 2);
    assert_eq!(one.pixels, two.pixels);
}

#[test]
fn bad_physical_materials_are_errors_naming_the_key() {
    let cases = [
        ("material = { bsdf = { type = \"dielectric\", eta = 1.5 } }", "eta"),
        ("material = { bsdf = { type = \"conductor\", metal = \"Au\", alpha = 2.0 } }", "alpha"),
        ("material = { bsdf = { type = \"dielectric\", ior = 50.0 } }", "ior"),
        ("material = { bsdf = { type = \"conductor\", metal = \"Unobtainium\" } }", "metal"),
        ("material = { bsdf = { type = \"diffuse\" }, phong = 0.5 }", "phong"),
        ("material = { bsdf = { type = \"diffuse\" }, emission = [-1, 0, 0] }", "emission"),
        ("material = { attenuation_color = [1.5, 0, 0], attenuation_distance = 1 }", "attenuation_color"),
        ("material = { attenuation_color = [0.5, 0.5, 0.5] }", "attenuation_color"),
        ("material = { attenuation_distance = 0 }", "attenuation_distance"),
        ("material = { attenuation_distance = -2 }", "attenuation_distance"),
        ("material = { attenuation_distance = nan }", "attenuation_distance"),
        ("material = { attenuation_color = 0.5, attenuation_distance = 1e-300 }", "attenuation_distance"),
        ("material = { attenuation_distance = 1, fade_distance = 2 }", "attenuation_distance"),
        ("material = { attenuation_distance = 1, layers = [{ attenuation_distance = 1 }] }", "attenuation_distance"),
    ];
    for (material, key) in cases {
        let text: &'static str = Box::leak(format!("[[object]]\nshape = \"sphere\"\n{material}\n").into_boxed_str());
        let files: &'static [(&'static str, &'static str)] = Box::leak(Box::new([("scene.toml", text)]));
        let embedded: &'static Embedded = Box::leak(Box::new(Embedded(files)));
        let error = match load_from(embedded, Path::new("scene.toml"), &prism::plugins::registry()) {
            Ok(mut scene) => prism::prepare(&mut scene).err().map(|e| e.to_string()).unwrap_or_default(),
            Err(e) => e.to_string(),
        };
        assert!(error.contains("scene.toml:3") && error.contains(key), "{material}: {error}");
    }
}

/// An orthographic camera sees an object the same size at any distance: an emissive square
/// of side 1 under a view 2 high covers a quarter of the image, wherever the camera stands.
#[test]
fn an_orthographic_camera_keeps_sizes_at_any_distance() {
    let lit_fraction =
        |film: &Film| film.pixels.iter().filter(|p| p[0] > 0.5).count() as f64 / film.pixels.len() as f64;
    let near = render_text(
        "[render]\nwidth = 64\nheight = 64\nintegrator = \"path\"\n\
         [camera]\nprojection = \"orthographic\"\nposition = [0, 0, 2]\nview_height = 2.0\n\
         [[object]]\nshape = \"rectangle\"\ntransform = { scale = 0.5 }\nmaterial = { emission = 1.0, bsdf = { type = \"diffuse\" } }\n",
        2,
    );
    let far = render_text(
        "[render]\nwidth = 64\nheight = 64\nintegrator = \"path\"\n\
         [camera]\nprojection = \"orthographic\"\nposition = [0, 0, 200]\nview_height = 2.0\n\
         [[object]]\nshape = \"rectangle\"\ntransform = { scale = 0.5 }\nmaterial = { emission = 1.0, bsdf = { type = \"diffuse\" } }\n",
        2,
    );
    assert_eq!(lit_fraction(&near), 0.25, "a 32 x 32 pixel square");
    assert_eq!(near.pixels, far.pixels, "distance does not change an orthographic image");
}

/// Filtered pixels are weighted means: under a uniform environment every pixel is exactly
/// the environment, for every filter (the weights of Mitchell's negative lobes included).
#[test]
fn filters_keep_a_uniform_image_uniform() {
    for filter in ["{ type = \"gaussian\" }", "{ type = \"gaussian\", stddev = 0.3 }", "{ type = \"mitchell\" }"] {
        let text = format!(
            "[render]\nwidth = 16\nheight = 12\nsamples = 16\nintegrator = \"path\"\nfilter = {filter}\n\
             [world]\nbackground = [0.25, 0.5, 1.0]\n"
        );
        let film = render_text(Box::leak(text.into_boxed_str()), 2);
        for p in &film.pixels {
            for (c, want) in [0.25f32, 0.5, 1.0].into_iter().enumerate() {
                assert!((p[c] - want).abs() <= 1e-6 * want, "{filter}: {p:?}");
            }
        }
    }
}

/// A Gaussian filter weighs radiance beyond the pixel as its density says; the box filter
/// keeps an edge on a pixel boundary sharp.
#[test]
fn a_gaussian_filter_reaches_beyond_the_pixel() {
    let edge = |filter: &str| {
        let text = format!(
            "[render]\nwidth = 16\nheight = 4\nsamples = 256\nintegrator = \"path\"\nfilter = {filter}\n\
             [camera]\nprojection = \"orthographic\"\nposition = [0, 0, 2]\nview_height = 4.0\n\
             [[object]]\nshape = \"rectangle\"\ntransform = {{ scale = [8, 8, 1], translate = [8, 0, 0] }}\n\
             material = {{ emission = 1.0, bsdf = {{ type = \"diffuse\" }} }}\n"
        );
        let film = render_text(Box::leak(text.into_boxed_str()), 1);
        (0..16).map(|x| film.get(x, 1)[0]).collect::<Vec<f32>>()
    };
    // The lit half starts at x = 0, the boundary between pixels 7 and 8.
    let sharp = edge("{ type = \"box\" }");
    assert_eq!(&sharp[..8], &[0.0; 8]);
    assert_eq!(&sharp[8..], &[1.0; 8]);
    // Pixel 7's centre lies half a pixel (one stddev) from the edge: P(z > 1) = 0.159 of
    // the Gaussian's weight is beyond it (its 4-stddev window changes that by under 1e-3).
    let soft = edge("{ type = \"gaussian\" }");
    assert!((soft[7] - 0.159).abs() < 0.03 && (soft[8] - 0.841).abs() < 0.03, "{soft:?}");
    assert!(soft[6] < 0.01 && soft[9] > 0.99, "three stddevs away: {soft:?}");
    assert_eq!(soft[0], 0.0, "beyond the radius of 2 pixels");
    assert_eq!(soft[15], 1.0);
}

/// Slabs of index 1 (no refraction, no reflection: every ray crosses each face once, straight)
/// seen through an orthographic camera in front of a uniform sky, `inner` between the faces of
/// an absorbing slab two units thick.
fn through_slabs(outer_material: &str, inner: Option<&str>) -> Film {
    let mut text = format!(
        "[render]\nwidth = 8\nheight = 8\nsamples = 4\nmax_depth = 8\nintegrator = \"path\"\n\
         [world]\nbackground = 1.0\n\
         [camera]\nprojection = \"orthographic\"\nposition = [0, 0, 5]\nview_height = 2\n\
         [[object]]\nshape = \"box\"\nmin = [-2, -2, -1]\nmax = [2, 2, 1]\nmaterial = {outer_material}\n"
    );
    if let Some(inner) = inner {
        text +=
            &format!("[[object]]\nshape = \"box\"\nmin = [-3, -3, -0.25]\nmax = [3, 3, 0.25]\nmaterial = {inner}\n");
    }
    render_text(Box::leak(text.into_boxed_str()), 2)
}

fn assert_every_pixel(film: &Film, expected: [f64; 3], what: &str) {
    for p in &film.pixels {
        for (c, want) in expected.into_iter().enumerate() {
            assert!((f64::from(p[c]) - want).abs() < 1e-5, "{what}: pixel {p:?} against {expected:?}");
        }
    }
}

#[test]
fn absorbing_interiors_attenuate_by_beer_lambert() {
    // White light keeps (0.5, 0.25, 1) per unit of the interior: over two units, the square.
    let absorbing = "{ bsdf = { type = \"dielectric\", ior = 1.0 }, attenuation_color = [0.5, 0.25, 1.0], \
                     attenuation_distance = 1.0 }";
    assert_every_pixel(&through_slabs(absorbing, None), [0.25, 0.0625, 1.0], "one slab");
    // A clear slab inside the absorbing one: the path leaves it back into the absorbing
    // interior, which absorbs along 1.5 units.
    let clear = "{ bsdf = { type = \"dielectric\", ior = 1.0 } }";
    let expected = [0.5f64.powf(1.5), 0.25f64.powf(1.5), 1.0];
    assert_every_pixel(&through_slabs(absorbing, Some(clear)), expected, "a clear slab inside");
    // A thin sheet has no inside: crossing it leaves the path in the absorbing interior.
    let sheet = "{ bsdf = { type = \"thin_dielectric\", ior = 1.0 } }";
    assert_every_pixel(&through_slabs(absorbing, Some(sheet)), [0.25, 0.0625, 1.0], "a thin sheet inside");
    // POV-Ray's exponential fade is the same absorption: exp(-(1 - fade_color) d / fade_distance).
    let faded = "{ filter = 1.0, ior = 1.0, fade_distance = 2.0, fade_power = 1001, fade_color = [0.0, 0.5, 1.0] }";
    let expected = [(-1.0f64).exp(), (-0.5f64).exp(), 1.0];
    assert_every_pixel(&through_slabs(faded, None), expected, "POV-Ray's exponential fade");
}

#[test]
fn a_camera_inside_an_absorbing_sphere_sees_through_its_radius() {
    // From the centre every ray crosses one radius of the interior, then the sky.
    let film = render_text(
        "[render]\nwidth = 8\nheight = 8\nsamples = 4\nmax_depth = 4\nintegrator = \"path\"\n\
         [world]\nbackground = 1.0\n\
         [camera]\nposition = [0, 0, 0]\nlook_at = [0, 0, -1]\nvfov = 90\n\
         [[object]]\nshape = \"sphere\"\nradius = 2.0\n\
         material = { bsdf = { type = \"dielectric\", ior = 1.0 }, attenuation_color = [0.5, 0.25, 1.0], attenuation_distance = 1.0 }\n",
        2,
    );
    assert_every_pixel(&film, [0.25, 0.0625, 1.0], "a camera at the centre");
}

#[test]
fn light_sampled_inside_an_absorbing_interior_is_attenuated_on_its_way() {
    // A floor and a point lamp 0.5 above it, both inside an absorbing box (index 1) seen from
    // above (the box's top face is the first segment's end, the floor the second's): direct
    // light only, L = albedo / pi * I cos / r^2 * T(r) * T(1), T(s) = c^s with
    // the camera ray's unit of the interior above the floor. The image's mean against the
    // formula's mean over the view (midpoint quadrature).
    let film = render_text(
        "[render]\nwidth = 32\nheight = 32\nsamples = 4\nmax_depth = 3\nintegrator = \"path\"\n\
         [camera]\nprojection = \"orthographic\"\nposition = [0, 3, 0]\nlook_at = [0, 0, 0]\nup = [0, 0, -1]\nview_height = 2\n\
         [[object]]\nshape = \"box\"\nmin = [-3, -1, -3]\nmax = [3, 1, 3]\n\
         material = { bsdf = { type = \"dielectric\", ior = 1.0 }, attenuation_color = [0.5, 1.0, 0.25], attenuation_distance = 1.0 }\n\
         [[object]]\nshape = \"plane\"\nnormal = [0, 1, 0]\nmaterial = { color = 0.5, bsdf = { type = \"diffuse\" } }\n\
         [[light]]\nkind = \"point\"\nposition = [0, 0.5, 0]\nintensity = 2.0\n",
        2,
    );
    let (height, intensity, albedo) = (0.5f64, 2.0f64, 0.5f64);
    let kept = [0.5f64, 1.0, 0.25];
    let n = 400;
    let mut expected = [0.0f64; 3];
    for i in 0..n {
        for j in 0..n {
            let x = -1.0 + 2.0 * (i as f64 + 0.5) / n as f64;
            let z = -1.0 + 2.0 * (j as f64 + 0.5) / n as f64;
            let r = (x * x + z * z + height * height).sqrt();
            let irradiance = intensity * height / (r * r * r);
            for c in 0..3 {
                expected[c] += albedo / std::f64::consts::PI * irradiance * kept[c].powf(r) * kept[c];
            }
        }
    }
    let expected = expected.map(|e| e / (n * n) as f64);
    for (c, want) in expected.into_iter().enumerate() {
        let (mean, _) = mean_and_error(&film, c);
        assert!((mean - want).abs() < 0.01 * want, "channel {c}: mean {mean} against {want}");
    }
}
