//! Closed scenes with known answers: single-pixel renders whose values POV-Ray 3.7 was
//! measured to produce (shared/povray/REPORT.md, section 7), so each formula of the classic
//! integrator is pinned to the reference renderer.

use std::path::Path;

use prism::render::{RenderOptions, render_frame};

/// Renders `scene` (TOML) as a 1x1 image and returns the pixel.
fn pixel(scene: &str) -> [f64; 3] {
    pixel_with_render("", scene)
}

/// Like [`pixel`], with extra `[render]` keys.
fn pixel_with_render(render_keys: &str, scene: &str) -> [f64; 3] {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("scene.toml");
    let text = format!("[render]\nwidth = 1\nheight = 1\n{render_keys}\n{scene}");
    std::fs::write(&path, text).unwrap();
    let mut loaded = prism::scene::load::load_file(Path::new(&path), &prism::plugins::registry()).unwrap();
    let render_scene = prism::prepare(&mut loaded).unwrap();
    let (film, _) = render_frame(&render_scene, &RenderOptions { threads: Some(1), ..Default::default() }).unwrap();
    film.pixels[0].map(f64::from)
}

fn assert_close(got: [f64; 3], want: [f64; 3], tol: f64) {
    for c in 0..3 {
        assert!((got[c] - want[c]).abs() <= tol, "got {got:?}, want {want:?}");
    }
}

/// A wall at z = 0 facing the seed camera (which looks at it head-on from z = 1).
fn wall(material: &str) -> String {
    format!("[[object]]\nshape = \"plane\"\nnormal = [0, 0, 1]\noffset = 0\nmaterial = {{ {material} }}\n")
}

fn light(x: f64, y: f64, z: f64, extra: &str) -> String {
    format!("[[light]]\nposition = [{x}, {y}, {z}]\n{extra}\n")
}

#[test]
fn ambient_plus_diffuse_head_on() {
    let got = pixel(&(wall("color = [0.5, 0.4, 0.3], ambient = 0.1, diffuse = 0.6") + &light(0.0, 0.0, 10.0, "")));
    assert_close(got, [0.35, 0.28, 0.21], 1e-6);
}

#[test]
fn ambient_light_scales_ambient() {
    let scene = wall("color = [0.5, 0.4, 0.3], ambient = 0.2, diffuse = 0") + "[world]\nambient_light = [0.5, 1, 2]\n";
    assert_close(pixel(&scene), [0.05, 0.08, 0.12], 1e-6);
}

#[test]
fn brilliance_at_sixty_degrees() {
    let (s, c) = (60f64.to_radians().sin(), 60f64.to_radians().cos());
    let scene = wall("color = [0.5, 0.4, 0.3], ambient = 0, diffuse = 0.6, brilliance = 2")
        + &light(10.0 * s, 0.0, 10.0 * c, "");
    assert_close(pixel(&scene), [0.075, 0.06, 0.045], 1e-6);
}

#[test]
fn light_fade_has_the_factor_two() {
    let scene =
        wall("color = 1, ambient = 0, diffuse = 1") + &light(0.0, 0.0, 10.0, "fade_distance = 5\nfade_power = 2");
    assert_close(pixel(&scene), [0.4, 0.4, 0.4], 1e-6);
}

#[test]
fn phong_ten_degrees_off_the_mirror_direction() {
    // The mirror of the view ray is the normal; the light is 10 degrees off it.
    let (s, c) = (10f64.to_radians().sin(), 10f64.to_radians().cos());
    let scene =
        wall("color = 1, ambient = 0, diffuse = 0, phong = 0.8, phong_size = 40") + &light(10.0 * s, 0.0, 10.0 * c, "");
    assert_close(pixel(&scene), [0.43366; 3], 2e-5);
}

#[test]
fn specular_at_twenty_degrees() {
    let (s, c) = (20f64.to_radians().sin(), 20f64.to_radians().cos());
    let scene = wall("color = 1, ambient = 0, diffuse = 0, specular = 0.7, roughness = 0.05")
        + &light(1e4 * s, 0.0, 1e4 * c, "");
    assert_close(pixel(&scene), [0.51538; 3], 2e-5);
}

#[test]
fn negative_diffuse_phong_and_specular_add_nothing() {
    // POV-Ray 3.7 lights only positive terms (ComputeDiffuseColour returns for diffuse <= 0;
    // ComputeOneDiffuseLight adds phong and specular only when > 0): what is left is the
    // ambient term, 0.1 x colour. Measured with POV-Ray 3.7.0.10 on this scene: 0.05, 0.04, 0.03.
    let (s, c) = (10f64.to_radians().sin(), 10f64.to_radians().cos());
    let scene = wall("color = [0.5, 0.4, 0.3], ambient = 0.1, diffuse = -0.6, phong = -0.8, specular = -0.7")
        + &light(10.0 * s, 0.0, 10.0 * c, "");
    assert_close(pixel(&scene), [0.05, 0.04, 0.03], 1e-6);
    // One negative term leaves the others whole.
    let scene = wall("color = [0.5, 0.4, 0.3], ambient = 0, diffuse = 0.6, phong = -0.8") + &light(0.0, 0.0, 10.0, "");
    assert_close(pixel(&scene), [0.3, 0.24, 0.18], 1e-6);
}

#[test]
fn assumed_gamma_decodes_the_working_space_to_linear_light() {
    // A colour shown as it is (ambient 1, diffuse 0) in POV-Ray 3.7's working spaces: the
    // pixel is the working value decoded to linear light. Measured with POV-Ray 3.7.0.10
    // (half-float EXR): assumed_gamma 2.2 gives (0.2177, 0.04736, 2.44), srgb (0.214,
    // 0.05087, 2.537), and 0.5 (0.707, 0.5, 1.225); 1 leaves the colour as it is.
    let scene = wall("color = [0.5, 0.25, 1.5], ambient = 1, diffuse = 0");
    let relative = |got: [f64; 3], want: [f64; 3]| {
        for c in 0..3 {
            assert!((got[c] / want[c] - 1.0).abs() < 1e-3, "got {got:?}, want {want:?}");
        }
    };
    relative(pixel_with_render("assumed_gamma = 2.2", &scene), [0.2177, 0.04736, 2.44]);
    relative(pixel_with_render("assumed_gamma = \"srgb\"", &scene), [0.214, 0.05087, 2.537]);
    relative(pixel_with_render("assumed_gamma = 0.5", &scene), [0.707, 0.5, 1.225]);
    assert_close(pixel_with_render("assumed_gamma = 1", &scene), [0.5, 0.25, 1.5], 0.0);
    // Within 1 % of 1 POV-Ray uses no curve at all.
    assert_close(pixel_with_render("assumed_gamma = 1.009", &scene), [0.5, 0.25, 1.5], 0.0);
}

#[test]
fn an_infinite_channel_saturates_and_a_nan_channel_is_black() {
    // A negative phong_size 89.99 degrees off the mirror direction: cos^-100 overflows to
    // infinity, and the light's zero green makes 0 x inf = NaN. POV-Ray 3.7.0.10 writes
    // (inf, NaN, inf) to EXR and (255, 0, 255) to PNG: each channel on its own, not a black
    // pixel. Prism keeps files finite: the infinite channels saturate.
    let (s, c) = (89.99f64.to_radians().sin(), 89.99f64.to_radians().cos());
    let scene = wall("color = 1, ambient = 0, diffuse = 0, phong = 0.5, phong_size = -100")
        + &light(10.0 * s, 0.0, 10.0 * c, "color = [1, 0, 0.5]");
    let got = pixel(&scene);
    assert!(got[0] >= 1e30 && got[1] == 0.0 && got[2] >= 1e30, "{got:?}");
}

#[test]
fn a_reflection_exponent_of_a_negative_colour_blackens_the_channel() {
    // POV-Ray 3.7.0.10 raises the reflected colour to 1 / exponent with `pow`: the sky's
    // negative green gives NaN, which spreads through the surface's own green (0.4) and the
    // pixel's mean, and is written as 0; red and blue are 0.2 + 0.5 x 0.25^(1/2) and
    // 0.6 + 0.5 x 1 (measured: (0.45, NaN, 1.1) in its EXR), with and without antialiasing.
    let scene = "[camera]\nposition = [0, 0.5, 0.8660254037844386]\nlook_at = [0, 0, 0]\n\
                 [world]\nbackground = [0.25, -0.25, 1]\n\
                 [[object]]\nshape = \"plane\"\nnormal = [0, 1, 0]\nmaterial = { color = [0.2, 0.4, 0.6], \
                 ambient = 1, diffuse = 0, reflection = { max = 0.5, exponent = 2 } }\n";
    for render in ["", "antialias = { method = \"pov1\", threshold = 0.3, depth = 3 }"] {
        assert_close(pixel_with_render(render, scene), [0.45, 0.0, 1.1], 1e-6);
    }
}

#[test]
fn a_shadow_ray_turned_negative_is_not_inside_what_it_crossed() {
    // A sphere between the wall and the light, fading exponentially (exp(-2) over its
    // diameter). POV-Ray notes a shadow ray's crossing (ComputeShadowMedia) only while some
    // channel of the light left is at least 1e-10: a transmit of -0.5 turns the light
    // negative at the near side, so the far side is not taken as leaving the sphere and
    // fades nothing, 0.25 in all; a transmit of 0.5 fades, 0.25 exp(-2). Both measured
    // with POV-Ray 3.7.0.10.
    let sphere = |transmit: f64| {
        format!(
            "[[object]]\nshape = \"sphere\"\nradius = 1\ntransform = {{ translate = [0, 0, 5] }}\n\
             material = {{ color = 1, transmit = {transmit}, fade_distance = 1, fade_power = 1001, \
             fade_color = [0, 0, 0] }}\n"
        )
    };
    for (transmit, want) in [(-0.5, 0.25), (0.5, 0.25 * (-2f64).exp())] {
        let scene = wall("color = 1, ambient = 0, diffuse = 1") + &sphere(transmit) + &light(0.0, 0.0, 10.0, "");
        assert_close(pixel(&scene), [want; 3], 1e-6);
    }
}

#[test]
fn an_area_light_subdivides_where_the_light_arriving_differs() {
    // A 3 x 3 area light (adaptive 0) of colour 0.4 whose corner sample (-1, -1) is seen
    // through a glass box (0.96^2 = 0.9216). POV-Ray subdivides a region when its corners'
    // *light* differs by more than 0.1 summed over the channels: 3 x 0.4 x 0.0784 = 0.094
    // does not, so the shadow is the corners' mean, (0.9216 + 3) / 4, and the wall shows
    // 0.4 x 0.9804 = 0.39216 (POV-Ray 3.7.0.10: 0.392). Comparing the bare visibility
    // (0.235) would subdivide and give 0.39804.
    let scene = wall("color = 1, ambient = 0, diffuse = 1")
        + "[[object]]\nshape = \"box\"\nmin = [-1.0, -1.0, 8.9]\nmax = [-0.8, -0.8, 9.1]\n\
           material = { color = 1, transmit = 0.96 }\n\
           [[light]]\nkind = \"area\"\nposition = [0, 0, 10]\ncolor = 0.4\naxis1 = [2, 0, 0]\n\
           axis2 = [0, 2, 0]\nsize1 = 3\nsize2 = 3\nadaptive = 0\n";
    assert_close(pixel(&scene), [0.4 * (0.9216 + 3.0) / 4.0; 3], 1e-6);
}

/// A floor seen at 60 degrees from its normal, reflecting a white sky.
fn floor_at_sixty_degrees(material: &str) -> String {
    format!(
        "[camera]\nposition = [0, 0.5, 0.8660254037844386]\nlook_at = [0, 0, 0]\n[world]\nbackground = 1\n\
         [[object]]\nshape = \"plane\"\nnormal = [0, 1, 0]\nmaterial = {{ {material} }}\n"
    )
}

#[test]
fn reflection_falloff() {
    let scene = floor_at_sixty_degrees(
        "color = 0, ambient = 0, diffuse = 0, reflection = { min = 0.2, max = 0.8, falloff = 2 }",
    );
    assert_close(pixel(&scene), [0.35; 3], 1e-6);
}

#[test]
fn fresnel_reflection_with_ior() {
    let scene = floor_at_sixty_degrees(
        "color = 0, ambient = 0, diffuse = 0, ior = 1.5, reflection = { min = 0, max = 1, fresnel = true }",
    );
    assert_close(pixel(&scene), [0.08919; 3], 1e-5);
}

#[test]
fn a_csg_member_with_its_own_material_is_a_medium_of_its_own() {
    // A union of a clear sphere (the group's material) and a box whose own material is
    // Fresnel glass (ior 1.5), its top face through the sphere's centre, seen at 60 degrees
    // through the sphere. POV-Ray gives the member its own interior, so the ray inside the
    // sphere enters the glass: 0.08919 (measured: 0.0892). Taking the member for the group's
    // interior would have the ray leave glass and reflect totally (1).
    let scene = "[camera]\nposition = [0, 0.5, 0.8660254037844386]\nlook_at = [0, 0, 0]\n[world]\nbackground = 1\n\
                 [[object]]\nshape = \"union\"\nmembers = [{ shape = \"sphere\", radius = 0.5 }, { shape = \"box\", \
                 min = [-3, -1, -3], max = [3, 0, 3], material = { color = 0, ambient = 0, diffuse = 0, ior = 1.5, \
                 reflection = { min = 0, max = 1, fresnel = true } } }]\n\
                 material = { color = 1, transmit = 1, ambient = 0, diffuse = 0 }\n";
    assert_close(pixel(scene), [0.08919; 3], 1e-5);
}

#[test]
fn fresnel_needs_an_ior() {
    let scene = floor_at_sixty_degrees(
        "color = 0, ambient = 0, diffuse = 0, reflection = { min = 0, max = 1, fresnel = true }",
    );
    assert_close(pixel(&scene), [0.0; 3], 1e-12);
}

#[test]
fn area_light_uses_hierarchical_weights() {
    // A 3x3 grid above the wall; a bar blocks exactly the right column of shadow rays.
    // POV-Ray weighs columns (1, 2, 1) / 4, so the visibility is 0.75, not 2/3.
    let scene = wall("color = 1, ambient = 0, diffuse = 1")
        + &light(0.0, 0.0, 10.0, "kind = \"area\"\naxis1 = [2, 0, 0]\naxis2 = [0, 2, 0]\nsize1 = 3\nsize2 = 3")
        + "[[object]]\nshape = \"box\"\nmin = [0.3, -1, 4.9]\nmax = [0.7, 1, 5.1]\n";
    assert_close(pixel(&scene), [0.75; 3], 1e-6);
}

#[test]
fn stopped_rays_are_black_not_background() {
    // Two facing mirrors: ambient 0.1, reflection 0.5, max_depth 5 -> sum_{k<5} 0.1 * 0.5^k.
    let scene = "[world]\nbackground = 1\n[camera]\nposition = [0, 0, 0]\nlook_at = [0, 0, -1]\n\
        [[object]]\nshape = \"plane\"\nnormal = [0, 0, 1]\noffset = -1\nmaterial = { color = 1, ambient = 0.1, diffuse = 0, reflection = 0.5 }\n\
        [[object]]\nshape = \"plane\"\nnormal = [0, 0, -1]\noffset = -1\nmaterial = { color = 1, ambient = 0.1, diffuse = 0, reflection = 0.5 }\n";
    let want: f64 = (0..5).map(|k| 0.1 * 0.5f64.powi(k)).sum();
    assert_close(pixel_with_render("max_depth = 5", scene), [want; 3], 1e-6);
}

#[test]
fn transparent_sphere_filters_its_shadow_at_each_crossing() {
    // A transmit-0.5 sphere between the wall and the light lets 0.25 through.
    let scene = wall("color = 1, ambient = 0, diffuse = 1")
        + &light(0.0, 0.0, 10.0, "")
        + "[[object]]\nshape = \"sphere\"\nradius = 0.5\ntransform = { translate = [0, 0, 5] }\nmaterial = { color = 1, transmit = 0.5 }\n";
    assert_close(pixel(&scene), [0.25; 3], 1e-6);
}

#[test]
fn a_negative_transmit_passes_light_negated() {
    // POV-Ray traces on wherever the filter's grey level is not 0, negative too (a bicubic
    // image map overshoots at alpha edges): opacity 1.2 gives ambient 0.6, and the background
    // seen through the wall adds -0.2 of itself (POV-Ray renders [0.4, 0.5, 0.55]).
    let scene =
        wall("color = 0.5, transmit = -0.2, ambient = 1, diffuse = 0") + "[world]\nbackground = [1, 0.5, 0.25]\n";
    assert_close(pixel(&scene), [0.4, 0.5, 0.55], 1e-6);
    // A shadow ray crossing a disc of transmit -0.3 carries -0.3 of the light on: ambient
    // 0.05 plus diffuse 0.3 * -0.3 (POV-Ray renders [-0.04, -0.032, -0.024]).
    let scene = wall("color = [0.5, 0.4, 0.3], ambient = 0.1, diffuse = 0.6")
        + &light(0.0, 0.0, 10.0, "")
        + "[[object]]\nshape = \"disc\"\ncenter = [0, 0, 5]\nnormal = [0, 0, 1]\nradius = 0.5\nmaterial = { color = 1, transmit = -0.3 }\n";
    assert_close(pixel(&scene), [-0.04, -0.032, -0.024], 1e-6);
}

#[test]
fn a_camera_starts_inside_only_the_groups_whose_pov_ray_box_holds_it() {
    // A union of a slab and an inverted sphere holds all space but the sphere, the camera
    // too; POV-Ray's box for it covers the slab and the sphere only, so the camera ray starts
    // outside, enters the slab at z = -2 and fades over its 0.2 units alone: 1 / (1 + 0.2)
    // (POV-Ray renders 0.8335 in half floats). Counted inside, it faded over 3 units.
    let scene = "[world]\nbackground = [1, 1, 1]\n[[object]]\nshape = \"union\"\nmembers = [\n\
        { shape = \"sphere\", radius = 0.3, transform = { translate = [0, 3, -3] }, inverse = true },\n\
        { shape = \"box\", min = [-1, -1, -2.2], max = [1, 1, -2] },\n]\n\
        material = { color = 1, transmit = 1, ambient = 0, diffuse = 0, fade_distance = 1, fade_power = 1 }\n";
    assert_close(pixel(scene), [1.0 / 1.2; 3], 1e-6);
}

/// A clear sheet (transmit 1, index 1) at z = 0 in front of the seed camera, a red wall `gap`
/// behind it, and a blue background.
fn sheet_before_wall(gap: f64) -> String {
    format!(
        "[world]\nbackground = [0, 0, 1]\n\
         [[object]]\nshape = \"plane\"\nnormal = [0, 0, 1]\noffset = 0\n\
         material = {{ color = 1, ambient = 0, diffuse = 0, transmit = 1 }}\n\
         [[object]]\nshape = \"plane\"\nnormal = [0, 0, 1]\noffset = {}\n\
         material = {{ color = [1, 0, 0], ambient = 1, diffuse = 0 }}\n",
        -gap
    )
}

#[test]
fn rays_ignore_hits_within_min_isect_depth_of_their_origin() {
    // POV-Ray's MIN_ISECT_DEPTH: the ray continuing through the sheet ignores a wall closer
    // than 1e-4 (world units) and sees the background; a wall beyond it is seen.
    assert_close(pixel(&sheet_before_wall(5e-5)), [0.0, 0.0, 1.0], 1e-9);
    assert_close(pixel(&sheet_before_wall(2e-4)), [1.0, 0.0, 0.0], 1e-9);
}

#[test]
fn a_spot_whose_radius_exceeds_its_falloff_has_a_hard_edge_at_radius() {
    // The wall's centre pixel lies 25 or 40 degrees off the axis of a spot with radius 30,
    // falloff 20: POV-Ray lights it fully at 25 and not at all at 40.
    let lit = |degrees: f64| {
        let x = 10.0 * degrees.to_radians().tan();
        let spot = format!("kind = \"spot\"\npoint_at = [{x}, 0, 0]\nradius = 30\nfalloff = 20");
        pixel(&(wall("color = 1, ambient = 0, diffuse = 1") + &light(0.0, 0.0, 10.0, &spot)))
    };
    assert_close(lit(25.0), [1.0; 3], 1e-9);
    assert_close(lit(40.0), [0.0; 3], 1e-9);
}
