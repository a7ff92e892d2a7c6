//! `validate`: checks that need the whole scene (sizes, camera, transforms, lights) and
//! reports every problem with the location it came from.

use glam::DVec3;

use super::components::{
    Antialias, Camera, ImportedCamera, IntegratorKind, Light, LightKind, MaterialComponent, Origin, PhotometricLight,
    PixelFilter, Projection, RenderSettings, WorldTransform,
};
use super::{EntityKeys, Scene};
use crate::diagnostics::{Diagnostic, Location, SceneError, shown_number};
use crate::gamma::AssumedGamma;

/// Largest accepted image side, and pixel count (a 64k x 64k float image is 48 GiB).
pub const MAX_IMAGE_SIDE: u32 = 65_536;
/// Largest accepted number of pixels.
pub const MAX_PIXELS: u64 = 268_435_456;
/// Largest accepted samples per pixel.
pub const MAX_SAMPLES: u32 = 1 << 20;

/// Warnings that depend on the final settings, so they are not among [`Scene::warnings`]: a
/// camera imported from a file made for another aspect ratio than the image's, POV-Ray's
/// adaptive focal blur keys, normal patterns and `assumed_gamma` under `path` (ignored
/// there), negative emission under `path` (emitting nothing there), an environment map
/// under `classic` (ignored there), an `assumed_gamma` below 1 (POV-Ray's "suspicious value"), and a
/// path-traced scene without any light (call it once the settings are final, after
/// command-line overrides).
pub fn warnings(scene: &Scene) -> Vec<Diagnostic> {
    let mut out = Vec::new();
    if let Ok(imported) = scene.world.get::<&ImportedCamera>(scene.camera)
        && let Some(w) = aspect_warning(imported.aspect_ratio, scene.render.width, scene.render.height)
    {
        let location = match scene.world.get::<&Origin>(scene.camera) {
            Ok(origin) => origin.0.clone(),
            Err(_) => scene.render_origin.clone(),
        };
        out.push(Diagnostic::warning(location, format!("{}: {w}", imported.description)));
    }
    let camera = scene.camera();
    let blur_keys = [
        ("blur_variance", camera.blur_variance.is_some()),
        ("blur_confidence", camera.blur_confidence.is_some()),
        ("blur_min_samples", camera.blur_min_samples.is_some()),
    ];
    if scene.render.integrator == IntegratorKind::Path
        && let Some((first, _)) = blur_keys.iter().find(|(_, set)| *set)
    {
        let location = scene.entity_keys(scene.camera, || scene.render_origin.clone()).child(first);
        out.push(
            Diagnostic::warning(
                location,
                format!(
                    "{first} is ignored: POV-Ray's adaptive focal blur belongs to the classic integrator, \
                     and the path integrator takes [render] samples lens samples in every pixel"
                ),
            )
            .with_help("use [render] noise to sample adaptively under path"),
        );
    }
    let gamma_at = || scene.render_key("assumed_gamma");
    if let AssumedGamma::Power(g) = scene.render.assumed_gamma
        && g > 0.0
        && g < 1.0
    {
        // POV-Ray's "suspicious value" warning: gammas are usually given as decoding gammas.
        out.push(Diagnostic::warning(
            gamma_at(),
            format!("assumed_gamma {g} is below 1, which brightens mid-tones; did you mean {}?", 1.0 / g),
        ));
    }
    if scene.render.integrator == IntegratorKind::Path && !scene.render.assumed_gamma.is_linear() {
        out.push(Diagnostic::warning(
            gamma_at(),
            "assumed_gamma belongs to the classic integrator: the path integrator takes the scene's colours, \
             and the image maps read into that working space, as linear values",
        ));
    }
    if scene.render.integrator == IntegratorKind::Classic && scene.environment.environment.is_some() {
        let location = Location::file_only(scene.render_origin.file.clone(), "world.environment");
        out.push(
            Diagnostic::warning(
                location,
                "the environment map is read by the path integrator only: classic ignores it and shows \
                 `background` where rays leave the scene",
            )
            .with_help("render with --integrator path, or give classic a [world] background"),
        );
    }
    if scene.render.integrator == IntegratorKind::Path {
        for (entity, m) in scene.world.query::<(hecs::Entity, &MaterialComponent)>().iter() {
            let e = &m.material.emission;
            if e.radiance.0.min_element() < 0.0 || e.times_color.0.min_element() < 0.0 {
                let location = scene.entity_keys(entity, || scene.render_origin.clone()).child("material.emission");
                out.push(Diagnostic::warning(
                    location,
                    "negative emission darkens under classic, as in POV-Ray; under path radiance cannot be \
                     negative, and the negative components emit nothing",
                ));
            }
        }
    }
    if scene.render.integrator == IntegratorKind::Path && !has_light(scene) {
        out.push(
            Diagnostic::warning(
                scene.render_key("integrator"),
                "the scene has no light: no light source, emitting material or environment, so the path \
                 integrator renders it black",
            )
            .with_help("add a [[light]], a material with `emission`, or a [world] background or environment"),
        );
    }
    out
}

/// True when anything in the scene emits light the path integrator sees.
fn has_light(scene: &Scene) -> bool {
    let positive = |c: crate::color::Rgb, scale: f64| scale > 0.0 && c.0.max_element() > 0.0;
    let env = &scene.environment;
    env.environment.as_ref().is_some_and(|map| map.intensity > 0.0)
        || (env.environment.is_none() && positive(env.background, 1.0))
        || scene.world.query::<&Light>().iter().any(|l| positive(l.color, l.intensity))
        || scene.world.query::<&PhotometricLight>().iter().any(|l| positive(l.color, l.intensity))
        || scene.world.query::<&MaterialComponent>().iter().any(|m| m.material.emission.can_emit())
}

/// Checks the scene; `Ok` means it can be extracted and rendered.
pub fn validate(scene: &Scene) -> Result<(), SceneError> {
    let mut out = Vec::new();
    check_render(scene, &mut out);
    check_camera(scene, &mut out);
    let env = &scene.environment;
    for (key, c) in [("background", env.background), ("ambient_light", env.ambient_light)] {
        if !c.is_finite() {
            let location = Location::file_only(scene.render_origin.file.clone(), format!("world.{key}"));
            out.push(Diagnostic::new(location, format!("`world.{key}` must be finite")));
        }
    }
    for (transform, origin) in scene.world.query::<(&WorldTransform, &Origin)>().iter() {
        let m = transform.0;
        let det = m.matrix3.determinant();
        if !m.matrix3.is_finite() || !m.translation.is_finite() {
            out.push(Diagnostic::new(origin.0.child("transform"), "transform is not finite (NaN or infinity)"));
        } else if det.abs() < 1e-18 {
            out.push(
                Diagnostic::new(origin.0.child("transform"), "transform is singular (it flattens the object)")
                    .with_help("a scale of 0 on some axis, or a matrix without an inverse"),
            );
        }
    }
    for (entity, light) in scene.world.query::<(hecs::Entity, &Light)>().iter() {
        let origin = scene.entity_keys(entity, || scene.render_origin.child("light"));
        check_light(light, &origin, scene.render.integrator, &mut out);
    }
    if out.is_empty() {
        Ok(())
    } else {
        out.sort_by(|a, b| {
            (a.location.file.as_ref(), a.location.line, a.location.column).cmp(&(
                b.location.file.as_ref(),
                b.location.line,
                b.location.column,
            ))
        });
        Err(SceneError { diagnostics: out })
    }
}

fn check_render(scene: &Scene, out: &mut Vec<Diagnostic>) {
    let r = &scene.render;
    let at = |key: &str| scene.render_key(key);
    for (key, v) in [("width", r.width), ("height", r.height)] {
        if v == 0 || v > MAX_IMAGE_SIDE {
            out.push(Diagnostic::new(at(key), format!("image {key} must be between 1 and {MAX_IMAGE_SIDE}, got {v}")));
        }
    }
    let pixels = u64::from(r.width) * u64::from(r.height);
    if pixels > MAX_PIXELS {
        out.push(Diagnostic::new(at("width"), format!("image of {pixels} pixels exceeds the limit of {MAX_PIXELS}")));
    }
    if r.samples == 0 || r.samples > MAX_SAMPLES {
        out.push(Diagnostic::new(
            at("samples"),
            format!("samples must be between 1 and {MAX_SAMPLES}, got {}", r.samples),
        ));
    }
    if let Some(noise) = r.noise {
        if !(noise > 0.0 && noise < 1.0) {
            out.push(Diagnostic::new(at("noise"), format!("noise must be between 0 and 1 (exclusive), got {noise}")));
        } else if !matches!(r.antialias, Antialias::Stratified {}) {
            out.push(Diagnostic::new(
                at("noise"),
                "adaptive sampling (`noise`) works with stratified sampling only, not POV-Ray's antialiasing methods",
            ));
        }
    }
    if let Err(message) = crate::film::Aov::parse_list(r.aovs.iter().map(String::as_str)) {
        out.push(Diagnostic::new(at("aovs"), message));
    }
    if r.max_depth == 0 || r.max_depth > 1000 {
        out.push(Diagnostic::new(
            at("max_depth"),
            format!("max_depth must be between 1 and 1000, got {}", r.max_depth),
        ));
    }
    if r.rr_depth == 0 {
        out.push(Diagnostic::new(at("rr_depth"), "rr_depth must be at least 1, got 0".to_string()));
    }
    if !(r.adc_bailout.is_finite() && (0.0..1.0).contains(&r.adc_bailout)) {
        out.push(Diagnostic::new(
            at("adc_bailout"),
            format!("adc_bailout must be in [0, 1), got {}", shown_number(r.adc_bailout)),
        ));
    }
    if !r.assumed_gamma.is_valid() {
        out.push(Diagnostic::new(
            at("assumed_gamma"),
            format!("assumed_gamma must be a gamma above 0 (1 is linear) or \"srgb\", got {}", r.assumed_gamma),
        ));
    }
    if let Antialias::Pov1 { threshold, depth } | Antialias::Pov2 { threshold, depth } = r.antialias {
        if !(threshold.is_finite() && threshold >= 0.0) {
            out.push(Diagnostic::new(
                at("antialias.threshold"),
                format!("antialias threshold must be 0 or positive, got {threshold}"),
            ));
        }
        if !(1..=9).contains(&depth) {
            out.push(Diagnostic::new(
                at("antialias.depth"),
                format!("antialias depth must be between 1 and 9 (as POV-Ray's +R), got {depth}"),
            ));
        }
    }
    if !r.exposure.is_finite() {
        out.push(Diagnostic::new(at("exposure"), "exposure must be finite"));
    }
    check_filter(r, &at, out);
}

/// A filter's parameters, and that it goes with `stratified` sampling.
fn check_filter(r: &RenderSettings, at: &impl Fn(&str) -> Location, out: &mut Vec<Diagnostic>) {
    match r.filter {
        PixelFilter::Box {} => return,
        PixelFilter::Gaussian { stddev } => {
            if !(stddev.is_finite() && (0.05..=4.0).contains(&stddev)) {
                out.push(Diagnostic::new(
                    at("filter.stddev"),
                    format!("the gaussian filter's stddev must be between 0.05 and 4 pixels, got {stddev}"),
                ));
            }
        }
        PixelFilter::Mitchell { b, c } => {
            for (key, v) in [("filter.B", b), ("filter.C", c)] {
                if !(v.is_finite() && (0.0..=1.0).contains(&v)) {
                    out.push(Diagnostic::new(
                        at(key),
                        format!("Mitchell's {} must be between 0 and 1, got {v}", &key[7..]),
                    ));
                }
            }
        }
    }
    if !matches!(r.antialias, Antialias::Stratified {}) {
        out.push(
            Diagnostic::new(at("filter"), "a reconstruction filter needs stratified sampling")
                .with_help("POV-Ray's antialiasing methods weigh their own samples; remove `filter` or `antialias`"),
        );
    }
}

fn check_camera(scene: &Scene, out: &mut Vec<Diagnostic>) {
    let camera = scene.camera();
    let origin = scene.entity_keys(scene.camera, || Location::file_only("", "camera"));
    let position = DVec3::from_array(camera.position);
    let look_at = DVec3::from_array(camera.look_at);
    let up = DVec3::from_array(camera.up);
    for (key, v) in [("position", position), ("look_at", look_at), ("up", up)] {
        if !v.is_finite() {
            out.push(Diagnostic::new(origin.child(key), format!("camera {key} must be finite")));
            return;
        }
    }
    let forward = look_at - position;
    if forward.length() < 1e-12 {
        out.push(Diagnostic::new(origin.child("look_at"), "camera look_at is the camera position"));
    } else if up.length() < 1e-12 || forward.normalize().cross(up.normalize()).length() < 1e-9 {
        out.push(
            Diagnostic::new(origin.child("up"), "camera up is zero or parallel to the viewing direction")
                .with_help("choose an up vector that is not along look_at - position"),
        );
    }
    if !(camera.vfov.is_finite() && camera.vfov > 0.0 && camera.vfov < 180.0) {
        out.push(Diagnostic::new(
            origin.child("vfov"),
            format!("vfov must be greater than 0 and less than 180 degrees, got {}", shown_number(camera.vfov)),
        ));
    }
    if let Some(a) = camera.aspect
        && !(a.is_finite() && a > 0.0)
    {
        out.push(Diagnostic::new(origin.child("aspect"), format!("aspect must be positive, got {a}")));
    }
    if !(camera.aperture.is_finite() && camera.aperture >= 0.0) {
        out.push(Diagnostic::new(origin.child("aperture"), "aperture must be 0 or positive"));
    }
    if let Some(f) = camera.focal_distance
        && !(f.is_finite() && f > 0.0)
    {
        out.push(Diagnostic::new(origin.child("focal_distance"), "focal_distance must be positive"));
    }
    check_adaptive_blur(&camera, &scene.render, &origin, out);
    match camera.projection {
        Projection::Perspective => {
            if camera.view_height.is_some() {
                out.push(
                    Diagnostic::new(origin.child("view_height"), "view_height belongs to an orthographic camera")
                        .with_help("set projection = \"orthographic\", or frame the view with vfov"),
                );
            }
        }
        Projection::Orthographic => {
            if camera.aperture > 0.0 {
                out.push(Diagnostic::new(
                    origin.child("aperture"),
                    "an orthographic camera has no lens: depth of field needs projection = \"perspective\"",
                ));
            }
            if let Some(h) = camera.view_height
                && !(h.is_finite() && h > 0.0)
            {
                out.push(Diagnostic::new(
                    origin.child("view_height"),
                    format!("view_height must be positive, got {h}"),
                ));
            }
        }
    }
}

use crate::limits::{MAX_COEFFICIENT, MAX_COLOR_COMPONENT};

/// POV-Ray's adaptive focal blur keys: in range, and only where they apply (a lens, the
/// classic integrator, `blur_variance` for the other two, not beside `noise`).
fn check_adaptive_blur(camera: &Camera, render: &RenderSettings, origin: &EntityKeys<'_>, out: &mut Vec<Diagnostic>) {
    let set: Vec<&str> = [
        ("blur_variance", camera.blur_variance.is_some()),
        ("blur_confidence", camera.blur_confidence.is_some()),
        ("blur_min_samples", camera.blur_min_samples.is_some()),
    ]
    .into_iter()
    .filter_map(|(key, is_set)| is_set.then_some(key))
    .collect();
    let Some(&first) = set.first() else { return };
    if let Some(v) = camera.blur_variance
        && !(0.0..=1.0).contains(&v)
    {
        out.push(Diagnostic::new(
            origin.child("blur_variance"),
            format!("blur_variance must be between 0 and 1 (POV-Ray's range), got {}", shown_number(v)),
        ));
    }
    if let Some(c) = camera.blur_confidence
        && !(c > 0.0 && c < 1.0)
    {
        out.push(Diagnostic::new(
            origin.child("blur_confidence"),
            format!("blur_confidence must be between 0 and 1 (exclusive), got {c}"),
        ));
    }
    if let Some(m) = camera.blur_min_samples
        && !(1..=render.samples.max(1)).contains(&m)
    {
        out.push(
            Diagnostic::new(
                origin.child("blur_min_samples"),
                format!("blur_min_samples must be between 1 and [render] samples ({}), got {m}", render.samples),
            )
            .with_help("[render] samples is the most lens samples a pixel takes (POV-Ray's blur_samples maximum)"),
        );
    }
    if camera.aperture <= 0.0 {
        out.push(
            Diagnostic::new(
                origin.child(first),
                format!("{first} applies to focal blur, but the camera has no aperture"),
            )
            .with_help("set aperture > 0, or remove the blur_* keys"),
        );
        return;
    }
    // Under `path` the keys are ignored with a warning ([`warnings`]), so that every scene
    // renders under both integrators.
    if render.integrator != IntegratorKind::Classic {
        return;
    }
    if !camera.blur_variance.is_some_and(|v| v > 0.0) {
        for key in set.iter().filter(|k| **k != "blur_variance") {
            out.push(
                Diagnostic::new(origin.child(key), format!("{key} has no effect without blur_variance > 0"))
                    .with_help("set blur_variance (POV-Ray's variance, e.g. 0.0001) to make the focal blur adaptive"),
            );
        }
    } else if render.noise.is_some() {
        out.push(
            Diagnostic::new(
                origin.child("blur_variance"),
                "blur_variance and [render] noise are two rules for when a pixel stops sampling; use one",
            )
            .with_help("remove [render] noise to stop lens samples as POV-Ray does, or blur_variance for Prism's adaptive sampling"),
        );
    }
}

fn check_light(light: &Light, origin: &EntityKeys<'_>, integrator: IntegratorKind, out: &mut Vec<Diagnostic>) {
    let vectors =
        [("position", light.position), ("point_at", light.point_at), ("axis1", light.axis1), ("axis2", light.axis2)];
    for (key, v) in vectors {
        if !DVec3::from_array(v).is_finite() {
            out.push(Diagnostic::new(origin.child(key), format!("`{key}` must be finite")));
        }
    }
    let numbers = [
        ("intensity", light.intensity),
        ("fade_distance", light.fade_distance),
        ("fade_power", light.fade_power),
        ("radius", light.radius),
        ("falloff", light.falloff),
        ("tightness", light.tightness),
    ];
    for (key, v) in numbers {
        if !v.is_finite() {
            out.push(Diagnostic::new(origin.child(key), format!("`{key}` must be finite, got {v}")));
        } else if v.abs() > MAX_COEFFICIENT {
            out.push(Diagnostic::new(
                origin.child(key),
                format!(
                    "`{key}` must lie within ±{MAX_COEFFICIENT:e} (products would overflow), got {}",
                    shown_number(v)
                ),
            ));
        }
    }
    if !light.color.is_finite() {
        out.push(Diagnostic::new(origin.child("color"), "`color` must be finite"));
    } else if light.color.0.abs().max_element() > MAX_COLOR_COMPONENT {
        out.push(Diagnostic::new(
            origin.child("color"),
            format!("`color` components must lie within ±{MAX_COLOR_COMPONENT:e} (products would overflow)"),
        ));
    }
    let power = light.color.0 * light.intensity;
    if integrator == IntegratorKind::Path
        && power.is_finite()
        && let Some(key) = light.negative_key()
    {
        // POV-Ray's negative lights subtract light; a physical emitter cannot.
        out.push(
            Diagnostic::new(
                origin.child(key),
                format!(
                    "the path integrator reads `color * intensity` as emitted power, which cannot be negative; \
                     got {:?}",
                    power.to_array()
                ),
            )
            .with_help("a negative light subtracts light only under the classic integrator, as in POV-Ray"),
        );
    }
    let position = DVec3::from_array(light.position);
    let point_at = DVec3::from_array(light.point_at);
    let aims = light.kind == LightKind::Spot || light.kind == LightKind::Parallel || light.spot;
    if aims && (point_at - position).length() < 1e-12 {
        out.push(
            Diagnostic::new(origin.child("point_at"), "point_at equals position, so the light has no direction")
                .with_help("set point_at to where the light shines"),
        );
    }
    if light.kind == LightKind::Area {
        for (key, n) in [("size1", light.size1), ("size2", light.size2)] {
            if n == 0 || n > 1024 {
                out.push(Diagnostic::new(origin.child(key), format!("`{key}` must be between 1 and 1024, got {n}")));
            }
        }
        // POV-Ray makes an oriented area light circular.
        if (light.circular || light.orient) && (light.size1 < 2 || light.size2 < 2) {
            out.push(Diagnostic::new(
                origin.child(if light.circular { "circular" } else { "orient" }),
                "a circular (or oriented) area light needs size1 and size2 of at least 2",
            ));
        }
    }
}

/// The warning for a file camera made for another aspect ratio than the image's, if any.
pub fn aspect_warning(aspect_ratio: Option<f64>, width: u32, height: u32) -> Option<String> {
    let file = aspect_ratio?;
    let image = f64::from(width) / f64::from(height.max(1));
    ((file - image).abs() > 1e-3 * image).then(|| {
        format!(
            "the camera's aspectRatio {file} differs from the image's {width}x{height} ({image:.4}); the vertical field of view is kept"
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn aspect_warning_only_for_a_different_aspect() {
        assert!(aspect_warning(Some(1.0), 64, 36).unwrap().contains("aspectRatio 1"));
        assert!(aspect_warning(Some(16.0 / 9.0), 1920, 1080).is_none());
        assert!(aspect_warning(None, 64, 36).is_none());
    }
}
