//! `prism export pov`: a scene as POV-Ray 3.7 scene description language.
//!
//! The file renders in POV-Ray to the image the `classic` integrator renders (see
//! `shared/povray/REPORT.md`): `#version 3.7`, the scene's `assumed_gamma` (1.0 unless it sets one), the camera's `right`, `up`
//! and `direction` written out, every shape through its plugin's [`prism_api::Shape::to_pov`]
//! with its world transform, materials as pigment / finish / interior with every value
//! explicit, lights, ambient light, background, `max_trace_level` and `adc_bailout`.
//!
//! Prism is right-handed and POV-Ray left-handed. Every point, direction and normal is
//! written as `(x, y, -z)` (the map S) and every transform M as S·M·S; the mirror and the
//! change of handedness cancel, so the picture is not mirrored.
//!
//! Antialiasing is a POV-Ray command-line option, not scene language: the options that
//! render the same samples are written in a `// povray-options:` comment line, which
//! `scripts/povray-references.sh` passes to `povray`.

use std::fmt::Write;
use std::path::{Path, PathBuf};

use glam::{DAffine3, DVec3};
use prism_api::pov::{self, FilePaths, number, vector};

use crate::color::Rgb;
use crate::diagnostics::{Diagnostic, SceneError};
use crate::gamma::AssumedGamma;
use crate::geometry::csg::CsgShape;
use crate::material::pov_view::{PovFinish, PovView};
use crate::material::{Finish, Interior, Material, Reflection, SurfaceModel};
use crate::render::camera::CameraFrame;
use crate::render::integrators::classic::lights::pov_equivalent;
use crate::scene::save::relative_path;
use crate::world::Scene;
use crate::world::components::{
    AdaptiveBlur, Antialias, Camera, CsgMaterials, Environment, IntegratorKind, Light, LightKind, MaterialComponent,
    Name, ObjectFlags, Origin, PhotometricLight, Projection, RenderSettings, ShapeComponent, WorldTransform,
};

/// The deepest `max_trace_level` POV-Ray 3.7 accepts.
pub const MAX_TRACE_LEVEL: u32 = 256;

/// The prefix of the comment line that holds the POV-Ray command-line options.
pub const OPTIONS_PREFIX: &str = "// povray-options: ";

/// The scene as POV-Ray 3.7 SDL. `source` names the scene in the header comment; the paths
/// of files shapes read (a text's font) are written relative to `directory`, the folder the
/// file goes to, when given and possible (POV-Ray then finds them run with `+L` that folder,
/// or from it), absolute otherwise. The scene must have been through `resolve_transforms`
/// and `validate`. Every feature that has no exact POV-Ray equivalent is reported, each
/// naming the object, light or setting.
pub fn export(scene: &Scene, source: &str, directory: Option<&Path>) -> Result<String, SceneError> {
    let mut errors = Vec::new();
    let mut out = String::new();
    let options = povray_options(scene, &mut errors);
    let _ = writeln!(out, "// POV-Ray 3.7 scene written by `prism export pov` from {source}; regenerate, do not edit.");
    out.push_str(
        "// Prism is right-handed, POV-Ray left-handed: points, directions and normals are written as\n\
         // (x, y, -z) and transforms as S*M*S with S = diag(1, 1, -1); the image is not mirrored.\n",
    );
    let _ = writeln!(out, "{OPTIONS_PREFIX}{options}");
    out.push_str("#version 3.7;\n\n");
    globals(&mut out, scene, &mut errors);
    camera(&mut out, &scene.camera(), scene.render.samples);
    lights(&mut out, scene);
    let base = directory.map(|d| std::fs::canonicalize(d).or_else(|_| std::path::absolute(d)).unwrap_or(d.into()));
    objects(&mut out, scene, &PovFiles { base }, &mut errors);
    if errors.is_empty() {
        return Ok(out);
    }
    Err(super::in_file_order(errors))
}

/// How the paths of the files shapes read are written: relative to `base` (the exported
/// file's folder) where a relative path exists, absolute otherwise.
struct PovFiles {
    base: Option<PathBuf>,
}

impl FilePaths for PovFiles {
    fn path(&self, file: &Path) -> Option<String> {
        let relative = self.base.as_deref().and_then(|base| relative_path(file, base));
        pov::path_string(relative.as_deref().unwrap_or(file).to_str()?)
    }
}

/// The POV-Ray options in the header line of an exported file, if it has one.
pub fn options_of(pov: &str) -> Option<&str> {
    pov.lines().find_map(|l| l.strip_prefix(OPTIONS_PREFIX))
}

/// Image size and antialiasing as POV-Ray command-line options.
fn povray_options(scene: &Scene, errors: &mut Vec<Diagnostic>) -> String {
    let RenderSettings {
        width,
        height,
        samples,
        max_depth: _,
        rr_depth: _,
        adc_bailout: _,
        seed: _,
        integrator,
        antialias,
        filter,
        exposure: _,
        tone_map: _,
        noise,
        aovs: _,
        assumed_gamma: _,
    } = &scene.render;
    if noise.is_some() {
        errors.push(Diagnostic::new(
            scene.render_key("noise"),
            "POV-Ray has no adaptive sampling to match `noise`: export the scene without it",
        ));
    }
    if !filter.is_box() {
        errors.push(Diagnostic::new(
            scene.render_key("filter"),
            "POV-Ray has no reconstruction filters: export a scene with the default box filter",
        ));
    }
    match integrator {
        IntegratorKind::Classic => {}
        IntegratorKind::Path => errors.push(Diagnostic::new(
            scene.render_key("integrator"),
            "POV-Ray renders the classic integrator's model; export a scene with integrator = \"classic\" \
             (or render `path` scenes against Mitsuba with `prism export mitsuba`)"
                .to_string(),
        )),
    }
    let aa = match *antialias {
        Antialias::Stratified {} => {
            if *samples > 1 && scene.camera().aperture <= 0.0 {
                errors.push(
                    Diagnostic::new(
                        scene.render_key("samples"),
                        format!("{samples} stratified samples per pixel have no POV-Ray equivalent"),
                    )
                    .with_help(
                        "use `antialias = { method = \"pov1\" }` (POV-Ray's +AM1) or `\"pov2\"` for antialiasing \
                         that POV-Ray renders alike, or samples = 1",
                    ),
                );
            }
            "-A".to_string()
        }
        Antialias::Pov1 { threshold, depth } => format!("+A{threshold:?} +AM1 +R{depth} -J"),
        Antialias::Pov2 { threshold, depth } => format!("+A{threshold:?} +AM2 +R{depth} -J"),
    };
    format!("+W{width} +H{height} {aa}")
}

fn rgb(c: Rgb) -> String {
    format!("rgb <{}, {}, {}>", number(c.0.x), number(c.0.y), number(c.0.z))
}

fn globals(out: &mut String, scene: &Scene, errors: &mut Vec<Diagnostic>) {
    // The environment map is the path integrator's; classic, and so POV-Ray, sees the background.
    let Environment { background, ambient_light, environment: _ } = &scene.environment;
    let render = &scene.render;
    if render.max_depth > MAX_TRACE_LEVEL {
        errors.push(Diagnostic::new(
            scene.render_key("max_depth"),
            format!("max_depth {} is deeper than POV-Ray's limit of {MAX_TRACE_LEVEL}", render.max_depth),
        ));
    }
    let _ = write!(
        out,
        "global_settings {{\n  assumed_gamma {}\n  max_trace_level {}\n  adc_bailout {}\n  ambient_light {}\n}}\n\n\
         background {{ {} }}\n\n",
        match render.assumed_gamma {
            AssumedGamma::Power(g) => format!("{g:?}"),
            AssumedGamma::Srgb => "srgb".to_string(),
        },
        render.max_depth,
        number(render.adc_bailout),
        rgb(*ambient_light),
        rgb(*background),
    );
}

fn camera(out: &mut String, camera: &Camera, samples: u32) {
    let Camera { aspect, aperture, projection, .. } = camera;
    let frame = CameraFrame::new(camera);
    // Without an explicit aspect the viewport follows the image, as in Prism.
    let right = match aspect {
        Some(a) => vector(frame.right * frame.height * a),
        None => format!("{} * {} * image_width / image_height", vector(frame.right), number(frame.height)),
    };
    let _ = write!(
        out,
        "camera {{\n  {}\n  location {}\n  direction {}\n  up {}\n  right {right}\n",
        match projection {
            Projection::Perspective => "perspective",
            Projection::Orthographic => "orthographic",
        },
        vector(frame.position),
        vector(frame.direction),
        vector(frame.up * frame.height),
    );
    if *aperture > 0.0 {
        // POV-Ray's lens samples fill a disc of radius aperture / 4 (its sample grid spans
        // [-0.5, 0.5] and is scaled by aperture / 2), Prism's of radius aperture / 2.
        // Variance 0 makes POV-Ray take all blur samples, as Prism does without
        // `blur_variance`; with it, POV-Ray stops each pixel by the same rule as Prism.
        let (counts, variance) = match camera.adaptive_blur() {
            None => (format!("{samples}"), "0".to_string()),
            Some(AdaptiveBlur { variance, confidence, min_samples }) => (
                format!("{min_samples}, {samples}"),
                format!("{}\n  confidence {}", number(variance), number(confidence)),
            ),
        };
        let _ = write!(
            out,
            "  aperture {}\n  blur_samples {counts}\n  focal_point {}\n  variance {variance}\n",
            number(2.0 * aperture),
            vector(frame.position + frame.direction * frame.focal_distance),
        );
    }
    out.push_str("}\n\n");
}

/// Every light, in load order; a light imported from a glTF file as the POV-Ray light source
/// the classic integrator renders it as.
fn lights(out: &mut String, scene: &Scene) {
    let mut lights: Vec<(hecs::Entity, Light)> =
        scene.world.query::<(hecs::Entity, &Light)>().iter().map(|(e, l)| (e, l.clone())).collect();
    let mut imported = scene.world.query::<(hecs::Entity, &PhotometricLight)>();
    lights.extend(imported.iter().map(|(e, l)| (e, pov_equivalent(l))));
    lights.sort_by_key(|(e, _)| e.id());
    for (_, light) in lights {
        light_source(out, &light);
    }
}

fn light_source(out: &mut String, light: &Light) {
    let Light {
        kind,
        position,
        color,
        intensity,
        fade_distance,
        fade_power,
        shadowless,
        point_at,
        radius,
        falloff,
        tightness,
        spot,
        axis1,
        axis2,
        size1,
        size2,
        adaptive,
        jitter,
        circular,
        orient,
        area_illumination,
    } = light;
    let v = |a: &[f64; 3]| vector(DVec3::from_array(*a));
    let _ = writeln!(out, "light_source {{ {}, color {}", v(position), rgb(Rgb(color.0 * *intensity)));
    let spotlight = *kind == LightKind::Spot || (*kind == LightKind::Area && *spot);
    if spotlight {
        let _ = writeln!(
            out,
            "  spotlight point_at {} radius {} falloff {} tightness {}",
            v(point_at),
            number(*radius),
            number(*falloff),
            number(*tightness)
        );
    }
    if *kind == LightKind::Parallel {
        let _ = writeln!(out, "  parallel point_at {}", v(point_at));
    }
    if *kind == LightKind::Area {
        let _ = write!(out, "  area_light {}, {}, {size1}, {size2} adaptive {adaptive}", v(axis1), v(axis2));
        for (flag, word) in [
            (*jitter, "jitter"),
            (*circular || *orient, "circular"),
            (*orient, "orient"),
            (*area_illumination, "area_illumination on"),
        ] {
            if flag {
                let _ = write!(out, " {word}");
            }
        }
        out.push('\n');
    }
    if *fade_distance != 0.0 || *fade_power != 0.0 {
        let _ = writeln!(out, "  fade_distance {} fade_power {}", number(*fade_distance), number(*fade_power));
    }
    if *shadowless {
        out.push_str("  shadowless\n");
    }
    out.push_str("}\n\n");
}

fn objects(out: &mut String, scene: &Scene, files: &PovFiles, errors: &mut Vec<Diagnostic>) {
    let mut query = scene.world.query::<(
        hecs::Entity,
        Option<&ShapeComponent>,
        Option<&WorldTransform>,
        Option<&MaterialComponent>,
        Option<&ObjectFlags>,
        Option<&Origin>,
        Option<&Name>,
    )>();
    let mut entries: Vec<_> = query.iter().collect();
    entries.sort_by_key(|(e, ..)| e.id());
    for (entity, shape, transform, material, flags, origin, name) in entries {
        let Some(origin) = origin else { continue };
        let (shape, material) = match (shape, material) {
            (Some(shape), Some(material)) => (shape, material),
            // Cameras and lights have neither; anything else drawable must not vanish.
            (None, None) => continue,
            _ => {
                errors.push(Diagnostic::new(origin.0.clone(), "this object cannot be exported to POV-Ray"));
                continue;
            }
        };
        let label = name.map_or(String::new(), |n| format!(" \"{}\"", n.0));
        let sdl = match CsgShape::of(shape.geometry.as_ref()) {
            Some(group) => {
                let leaves = scene.world.get::<&CsgMaterials>(entity).ok();
                let leaves = leaves.as_deref().map_or(&[][..], |l| &l.leaves[..]);
                let mut csg =
                    CsgSdl { leaves, group_material: &material.material, files, next_leaf: 0, problems: Vec::new() };
                let sdl = csg.group(group);
                if !csg.problems.is_empty() {
                    for (key, message) in csg.problems {
                        errors.push(Diagnostic::new(origin.0.child(&key), message));
                    }
                    continue;
                }
                sdl
            }
            None => shape.geometry.to_pov_with(files),
        };
        let Some(sdl) = sdl else {
            errors.push(
                Diagnostic::new(
                    origin.0.child("shape"),
                    format!("shape `{}` has no POV-Ray equivalent, so the scene cannot be exported", shape.kind),
                )
                .with_help("its plugin must implement `Shape::to_pov`"),
            );
            continue;
        };
        let Some(body) = sdl.trim_end().strip_suffix('}') else {
            errors.push(Diagnostic::new(
                origin.0.child("shape"),
                format!("shape `{}` wrote POV-Ray code that does not end in `}}`: {sdl}", shape.kind),
            ));
            continue;
        };
        let mut modifiers = String::new();
        let world_from_object = transform.map_or(DAffine3::IDENTITY, |t| t.0);
        if world_from_object != DAffine3::IDENTITY {
            let _ = writeln!(modifiers, "  matrix {}", pov_matrix(&world_from_object));
        }
        if let Err(problems) = texture(&mut modifiers, &material.material, &world_from_object, files) {
            for (key, message) in problems {
                errors.push(Diagnostic::new(origin.0.child(&format!("material.{key}")), message));
            }
            continue;
        }
        if flags.is_some_and(|f| f.no_shadow) {
            modifiers.push_str("  no_shadow\n");
        }
        let _ = writeln!(out, "//{label} {}", shape.kind);
        let _ = write!(out, "{}\n{modifiers}}}\n\n", body.trim_end());
    }
}

/// Writes a CSG group: `union`, `merge`, `intersection` or `difference` around its members,
/// each with its transform, `inverse`, and its texture where its material is not the whole
/// object's (which the object's own texture gives it, as POV-Ray hands a group's texture to
/// the members without one).
struct CsgSdl<'a> {
    /// The material of every leaf, depth first.
    leaves: &'a [MaterialComponent],
    /// The whole object's material.
    group_material: &'a std::sync::Arc<Material>,
    /// How file paths are written.
    files: &'a PovFiles,
    /// The leaf the next plain member is.
    next_leaf: usize,
    /// Key paths and messages of what cannot be written.
    problems: Vec<(String, String)>,
}

impl CsgSdl<'_> {
    /// The group's SDL, or `None` when a member's shape has no POV-Ray equivalent.
    fn group(&mut self, group: &CsgShape) -> Option<String> {
        let mut out = format!("{} {{\n", group.operation().name());
        for member in group.members() {
            let body = match CsgShape::of(member.shape.as_ref()) {
                Some(nested) => self.group(nested)?,
                None => {
                    let sdl = member.shape.to_pov_with(self.files)?;
                    let leaf = self.leaves.get(self.next_leaf);
                    self.next_leaf += 1;
                    let mut sdl = sdl.trim_end().strip_suffix('}')?.trim_end().to_string();
                    sdl.push('\n');
                    // The member's texture is written before its `matrix`, so POV-Ray moves a
                    // pattern with the member; Prism evaluates it in the group's space, which
                    // the inverse undoes.
                    if let Some(leaf) = leaf.filter(|l| !std::sync::Arc::ptr_eq(&l.material, self.group_material))
                        && let Err(problems) =
                            texture(&mut sdl, &leaf.material, &member.group_from_member.inverse(), self.files)
                    {
                        let at = format!("members.leaf{}", self.next_leaf - 1);
                        self.problems.extend(problems.into_iter().map(|(key, m)| (format!("{at}.material.{key}"), m)));
                    }
                    sdl.push('}');
                    sdl
                }
            };
            let mut body = body.strip_suffix('}')?.trim_end().to_string();
            body.push('\n');
            if member.group_from_member != DAffine3::IDENTITY {
                let _ = writeln!(body, "  matrix {}", pov_matrix(&member.group_from_member));
            }
            if member.inverse {
                body.push_str("  inverse\n");
            }
            body.push('}');
            for line in body.lines() {
                let _ = writeln!(out, "  {line}");
            }
        }
        out.push('}');
        Some(out)
    }
}

/// S·M·S in POV-Ray's `matrix` layout: four rows of three, the rows of the 3x3 part (POV-Ray
/// multiplies row vectors) and then the translation.
pub fn pov_matrix(m: &DAffine3) -> String {
    let s = DVec3::new(1.0, 1.0, -1.0);
    // (S A S) has entries a_ij * s_i * s_j; its column j is POV-Ray's row j.
    let cols = [m.matrix3.x_axis, m.matrix3.y_axis, m.matrix3.z_axis];
    let mut values = Vec::with_capacity(12);
    for (j, col) in cols.iter().enumerate() {
        let c = *col * s * s[j];
        values.extend([c.x, c.y, c.z]);
    }
    let t = m.translation * s;
    values.extend([t.x, t.y, t.z]);
    let text: Vec<String> = values.into_iter().map(number).collect();
    format!("<{}>", text.join(", "))
}

/// The material as `texture { pigment finish }` (one per layer of a layered texture, bottom
/// first) and `interior` (the classic integrator's view of it), or the keys POV-Ray cannot
/// express with messages. A pigment pattern carries
/// the object's transform `world_from_object` itself: the texture is written after the
/// object's `matrix`, which POV-Ray does not apply to textures added later.
fn texture(
    out: &mut String,
    m: &Material,
    world_from_object: &DAffine3,
    files: &dyn FilePaths,
) -> Result<(), Vec<(&'static str, String)>> {
    if let SurfaceModel::Layered(layers) = &m.surface {
        if layers.iter().any(|l| l.finish.texture.is_some()) {
            return Err(vec![("layers", "image textures are not exported to POV-Ray".to_string())]);
        }
        if layers.iter().any(|l| {
            l.finish.pigment.as_ref().is_some_and(|p| unwritable_image_map(&p.spec, files))
                || l.finish.normal.as_ref().is_some_and(|n| unwritable_bump_map(&n.spec, files))
        }) {
            return Err(vec![("layers", UNWRITABLE_IMAGE_MAP.to_string())]);
        }
        // One `texture { }` per layer, bottom first: POV-Ray puts the last on top.
        let view = PovView::new(m);
        let views: Vec<&PovView> = view.layers().collect();
        for (layer, layer_view) in layers.iter().zip(views.into_iter().rev()) {
            let (pigment, normal) = (layer.finish.pigment.as_deref(), layer.finish.normal.as_deref());
            texture_block(out, &layer_view.base, pigment, normal, world_from_object, files);
        }
        interior_sdl(out, &view.base.interior);
        return Ok(());
    }
    let (texture, pbr) = match &m.surface {
        SurfaceModel::Finish(f) => (f.texture.is_some(), false),
        SurfaceModel::MetallicRoughness(p) => (p.finish.texture.is_some(), true),
        SurfaceModel::Mtl(mtl) => (mtl.map_kd.is_some(), false),
        SurfaceModel::Physical(p) => (p.texture.is_some(), false),
        SurfaceModel::Layered(_) => (false, false),
    };
    let (pigment, normal) = match &m.surface {
        SurfaceModel::Finish(f) => (f.pigment.clone(), f.normal.clone()),
        _ => (None, None),
    };
    let patterned = pigment.is_some() && m.emission.radiance == Rgb::BLACK && m.emission.texture.is_none();
    let view = PovView::new(m);
    let mut problems = Vec::new();
    if texture {
        problems.push(("texture", "image textures are not exported to POV-Ray".to_string()));
    }
    if pigment.as_ref().is_some_and(|p| unwritable_image_map(&p.spec, files)) {
        problems.push(("pigment.image_map.file", UNWRITABLE_IMAGE_MAP.to_string()));
    }
    if normal.as_ref().is_some_and(|n| unwritable_bump_map(&n.spec, files)) {
        problems.push(("normal.bump_map.file", UNWRITABLE_IMAGE_MAP.to_string()));
    }
    if pbr {
        problems.push(("pbr", "glTF metallic-roughness materials have no POV-Ray finish equivalent".to_string()));
    } else if view.varies_over_surface() && !texture && !patterned {
        problems.push(("emission", "emitted radiance beside the finish has no POV-Ray equivalent".to_string()));
    }
    if !problems.is_empty() {
        return Err(problems);
    }
    texture_block(out, &view.base, pigment.as_deref(), normal.as_deref(), world_from_object, files);
    interior_sdl(out, &view.base.interior);
    Ok(())
}

/// One `texture { pigment normal finish }`: the pattern where given, else the finish's
/// colour with its filter and transmit.
fn texture_block(
    out: &mut String,
    base: &PovFinish,
    pigment: Option<&crate::material::pattern::PigmentField>,
    normal: Option<&crate::material::normal::NormalField>,
    world_from_object: &DAffine3,
    files: &dyn FilePaths,
) {
    let PovFinish {
        finish:
            Finish {
                color,
                filter,
                transmit,
                ambient,
                diffuse,
                brilliance,
                phong,
                phong_size,
                specular,
                roughness,
                metallic,
                reflection,
                conserve_energy,
                texture: _,
                pigment: _,
                normal: _,
            },
        emission,
        interior: _,
    } = base;
    let c = color.0;
    let pigment_sdl = match pigment {
        Some(p) => pigment_pattern(&p.spec, world_from_object, files),
        None => format!(
            "pigment {{ rgbft <{}, {}, {}, {}, {}> }}",
            number(c.x),
            number(c.y),
            number(c.z),
            number(*filter),
            number(*transmit)
        ),
    };
    let normal_sdl = match normal {
        Some(n) => format!("\n    {}", normal_pattern(&n.spec, world_from_object, files)),
        None => String::new(),
    };
    let _ = write!(
        out,
        "  texture {{\n    {pigment_sdl}{normal_sdl}\n    finish {{\n      ambient {} emission {}\n      \
         diffuse {} brilliance {}\n      phong {} phong_size {}\n      specular {} roughness {}\n      metallic {}\n",
        rgb(*ambient),
        rgb(*emission),
        number(*diffuse),
        number(*brilliance),
        number(*phong),
        number(*phong_size),
        number(*specular),
        number(*roughness),
        number(*metallic),
    );
    let Reflection { min, max, falloff, fresnel, metallic: reflection_metallic, exponent } = reflection;
    if reflection.is_reflective() {
        let _ = write!(
            out,
            "      reflection {{ {}, {} falloff {} exponent {} metallic {}",
            rgb(*min),
            rgb(*max),
            number(*falloff),
            number(*exponent),
            number(*reflection_metallic)
        );
        if *fresnel {
            out.push_str(" fresnel on");
        }
        out.push_str(" }\n");
    }
    if *conserve_energy {
        out.push_str("      conserve_energy\n");
    }
    out.push_str("    }\n  }\n");
}

/// The object's `interior { }`.
fn interior_sdl(out: &mut String, interior: &Interior) {
    // Absorption arrives as the exponential fade the classic view made of it.
    let Interior { ior, fade_distance, fade_power, fade_color, absorption: _ } = interior;
    let _ = write!(out, "  interior {{ ior {}", number(*ior));
    if *fade_distance != 0.0 {
        let _ = write!(
            out,
            " fade_distance {} fade_power {} fade_color {}",
            number(*fade_distance),
            number(*fade_power),
            rgb(*fade_color)
        );
    }
    out.push_str(" }\n");
}

/// POV-Ray's `rgbft` form of a pattern colour.
fn rgbft(c: &crate::material::pattern::MapColor) -> String {
    rgbft_of(c.rgbft())
}

/// POV-Ray's `rgbft` form of a colour with filter and transmit.
fn rgbft_of(c: crate::material::pattern::Rgbft) -> String {
    format!(
        "rgbft <{}, {}, {}, {}, {}>",
        number(c.rgb.x),
        number(c.rgb.y),
        number(c.rgb.z),
        number(c.filter),
        number(c.transmit)
    )
}

/// A pigment pattern in POV-Ray SDL: the pattern and its colours, its modifiers, its own
/// transform and then the object's (both mirrored into POV-Ray's frame like every matrix).
fn pigment_pattern(
    p: &crate::material::pattern::Pigment,
    world_from_object: &DAffine3,
    files: &dyn FilePaths,
) -> String {
    format!("pigment {{\n      {}\n    }}", pigment_body(p, world_from_object, files, "\n      "))
}

/// A pigment's body (what POV-Ray reads inside `pigment { }` and in a `pigment_map` entry),
/// each modifier on a new line with `indent`. A `pigment_map` entry gets only its own
/// transform: POV-Ray hands it the point the outer pigment's transform and turbulence made.
fn pigment_body(
    p: &crate::material::pattern::Pigment,
    world_from_object: &DAffine3,
    files: &dyn FilePaths,
    indent: &str,
) -> String {
    use crate::material::pattern::{MapEntry, PigmentMapEntry};
    if let Some(c) = p.plain_color() {
        return format!("color {}", rgbft_of(c));
    }
    let Some(kind) = p.pattern else {
        let mut sdl = String::new();
        if let Some(map) = &p.image_map {
            sdl.push_str(&image_map_sdl(map, image_map_path(map, files).unwrap_or_default()));
        }
        turbulence_sdl(&mut sdl, p.turbulence, p.omega, p.lambda, p.octaves, indent);
        matrices_sdl(&mut sdl, &p.object_from_pattern(), world_from_object, indent);
        return sdl;
    };
    let mut sdl = pattern_arguments(kind, p);
    if !p.colors.is_empty() {
        let colors: Vec<String> = p.colors.iter().map(|c| format!("color {}", rgbft(c))).collect();
        let _ = write!(sdl, " {}", colors.join(", "));
    }
    if !p.pigments.is_empty() {
        // POV-Ray's list form: every item a `pigment { }`, read as a map entry is.
        let inner = format!("{indent}    ");
        let list: Vec<String> = p
            .pigments
            .iter()
            .map(|e| format!("pigment {{{inner}{}{indent}  }}", pigment_body(e, &DAffine3::IDENTITY, files, &inner)))
            .collect();
        let _ = write!(sdl, "{indent}  {}", list.join(&format!(",{indent}  ")));
    }
    brick_sdl(&mut sdl, kind, p);
    pattern_keys_sdl(&mut sdl, p, indent);
    turbulence_sdl(&mut sdl, p.turbulence, p.omega, p.lambda, p.octaves, indent);
    if !p.color_map.is_empty() {
        let _ = write!(sdl, "{indent}color_map {{");
        for MapEntry(value, color) in &p.color_map {
            let _ = write!(sdl, "{indent}  [{} color {}]", number(*value), rgbft(color));
        }
        let _ = write!(sdl, "{indent}}}");
    }
    if !p.pigment_map().is_empty() {
        let _ = write!(sdl, "{indent}pigment_map {{");
        let inner = format!("{indent}    ");
        for PigmentMapEntry(value, entry) in p.pigment_map() {
            let body = pigment_body(entry, &DAffine3::IDENTITY, files, &inner);
            let _ = write!(sdl, "{indent}  [{} {body}]", number(*value));
        }
        let _ = write!(sdl, "{indent}}}");
    }
    wave_sdl(&mut sdl, p, indent);
    matrices_sdl(&mut sdl, &p.object_from_pattern(), world_from_object, indent);
    sdl
}

/// `brick`'s size and mortar, always written (POV-Ray's defaults are Prism's).
fn brick_sdl(sdl: &mut String, kind: crate::material::pattern::PatternKind, p: &crate::material::pattern::Pigment) {
    use crate::material::pattern::{DEFAULT_BRICK_SIZE, DEFAULT_MORTAR, PatternKind};
    if kind == PatternKind::Brick {
        let size = p.brick_size.unwrap_or(DEFAULT_BRICK_SIZE);
        // Brick sizes are lengths along POV-Ray's own axes: not mirrored.
        let _ = write!(
            sdl,
            " brick_size <{}, {}, {}> mortar {}",
            number(size[0]),
            number(size[1]),
            number(size[2]),
            number(p.mortar.unwrap_or(DEFAULT_MORTAR))
        );
    }
}

/// A pattern's keyword with the arguments that follow it (`gradient`'s vector, the spirals'
/// arms).
fn pattern_arguments(kind: crate::material::pattern::PatternKind, p: &crate::material::pattern::Pigment) -> String {
    use crate::material::pattern::PatternKind;
    match kind {
        PatternKind::Gradient => format!("gradient {}", vector(DVec3::from_array(p.vector.unwrap_or([0.0, 1.0, 0.0])))),
        PatternKind::Spiral1 | PatternKind::Spiral2 => format!("{kind} {}", p.arms.unwrap_or(0)),
        kind => kind.to_string(),
    }
}

/// `crackle`'s and `quilted`'s own keys, as written.
fn pattern_keys_sdl(sdl: &mut String, p: &crate::material::pattern::Pigment, indent: &str) {
    if let Some(f) = p.form {
        // Weights of distances, not a direction: not mirrored.
        let _ = write!(sdl, "{indent}form <{}, {}, {}>", number(f[0]), number(f[1]), number(f[2]));
    }
    if let Some(m) = p.metric {
        let _ = write!(sdl, " metric {}", number(m));
    }
    if let Some(o) = p.offset {
        let _ = write!(sdl, " offset {}", number(o));
    }
    if p.solid == Some(true) {
        sdl.push_str(" solid");
    }
    for (keyword, value) in [("control0", p.control0), ("control1", p.control1)] {
        if let Some(v) = value {
            let _ = write!(sdl, " {keyword} {}", number(v));
        }
    }
}

/// A pattern's `frequency`, `phase` and wave type, when written.
fn wave_sdl(sdl: &mut String, p: &crate::material::pattern::Pigment, indent: &str) {
    if let Some(f) = p.frequency {
        let _ = write!(sdl, "{indent}frequency {}", number(f));
    }
    if let Some(phase) = p.phase {
        let _ = write!(sdl, "{indent}phase {}", number(phase));
    }
    if let Some(wave) = p.wave {
        let _ = write!(sdl, "{indent}{}", wave_keyword(wave));
    }
}

/// POV-Ray's keyword for a wave type.
fn wave_keyword(wave: crate::material::pattern::Wave) -> &'static str {
    use crate::material::pattern::Wave;
    match wave {
        Wave::Ramp => "ramp_wave",
        Wave::Sine => "sine_wave",
        Wave::Triangle => "triangle_wave",
        Wave::Scallop => "scallop_wave",
        Wave::Cubic => "cubic_wave",
    }
}

/// The line break and indent of a texture's pattern modifiers.
const INDENT: &str = "\n      ";

/// The message for an image map whose file POV-Ray's strings cannot name.
const UNWRITABLE_IMAGE_MAP: &str =
    "an image map's file name with quotes, backslashes or control characters cannot be written as a POV-Ray string";

/// An image map's file as a POV-Ray string literal, written as every file a scene reads is
/// (relative to the exported file's folder, else absolute); `None` when the path cannot be
/// written.
fn image_map_path(map: &crate::material::image_map::ImageMap, files: &dyn FilePaths) -> Option<String> {
    match &map.path {
        Some(path) => files.path(path),
        None => pov::path_string(&map.file),
    }
}

/// True when some image map of the pigment (its `pigment_map` entries' included) has a file
/// POV-Ray's strings cannot name.
fn unwritable_image_map(p: &crate::material::pattern::Pigment, files: &dyn FilePaths) -> bool {
    p.image_maps().into_iter().any(|map| image_map_path(map, files).is_none())
}

/// True when some bump map of the normal (its `normal_map` entries' included) has a file
/// POV-Ray's strings cannot name.
fn unwritable_bump_map(n: &crate::material::normal::Normal, files: &dyn FilePaths) -> bool {
    n.bump_maps().into_iter().any(|map| image_map_path(map, files).is_none())
}

/// An image map in POV-Ray SDL: `file` (a POV-Ray string literal) and POV-Ray's numbers.
fn image_map_sdl(map: &crate::material::image_map::ImageMap, file: String) -> String {
    let mut sdl = format!("image_map {{ {}", image_options_sdl(map, file));
    if let Some(f) = map.filter_all {
        let _ = write!(sdl, " filter all {}", number(f));
    }
    if let Some(t) = map.transmit_all {
        let _ = write!(sdl, " transmit all {}", number(t));
    }
    sdl.push_str(" }");
    sdl
}

/// An image file with its mapping: `png FILE map_type N`, then `interpolate N`, `once`,
/// `repeat` and `offset` when written.
fn image_options_sdl(map: &crate::material::image_map::ImageMap, file: String) -> String {
    use crate::material::image_map::Interpolate;
    let mut sdl = format!("png {file} map_type {}", map.map_type.pov_number());
    if map.interpolate != Interpolate::None {
        let _ = write!(sdl, " interpolate {}", map.interpolate.pov_number());
    }
    if map.once {
        sdl.push_str(" once");
    }
    if let Some([u, v]) = map.repeat {
        let _ = write!(sdl, " repeat <{}, {}>", number(u), number(v));
    }
    if let Some([u, v]) = map.offset {
        let _ = write!(sdl, " offset <{}, {}>", number(u), number(v));
    }
    sdl
}

/// A normal pattern in POV-Ray SDL: the pattern with its bump size, its modifiers, its own
/// transform and then the object's.
fn normal_pattern(n: &crate::material::normal::Normal, world_from_object: &DAffine3, files: &dyn FilePaths) -> String {
    format!("normal {{{INDENT}{}\n    }}", normal_body(n, world_from_object, files, INDENT))
}

/// A normal's body (what POV-Ray reads inside `normal { }`, in a `normal_map` entry and in a
/// discrete pattern's list), each modifier on a new line with `indent`, and `no_bump_scale`
/// when set. A map or list entry gets only its own transform: POV-Ray hands it the point
/// and normal the outer normal's transform and turbulence made.
fn normal_body(
    n: &crate::material::normal::Normal,
    world_from_object: &DAffine3,
    files: &dyn FilePaths,
    indent: &str,
) -> String {
    let mut sdl = normal_pattern_body(n, world_from_object, files, indent);
    if n.no_bump_scale == Some(true) {
        let _ = write!(sdl, "{indent}no_bump_scale");
    }
    sdl
}

/// [`normal_body`] without `no_bump_scale`.
fn normal_pattern_body(
    n: &crate::material::normal::Normal,
    world_from_object: &DAffine3,
    files: &dyn FilePaths,
    indent: &str,
) -> String {
    use crate::material::normal::{DEFAULT_BUMP_SIZE, NormalKind, SlopeMapEntry};
    let bump_size = number(n.bump_size.unwrap_or(DEFAULT_BUMP_SIZE));
    if let Some(kind) = n.pattern.pigment_pattern() {
        let p = n.as_pigment().expect("a pigment pattern");
        let mut sdl = pattern_arguments(kind, &p);
        if let Some(list) = &n.normals {
            // POV-Ray's list form: every item a `normal { }`, read as a map entry is.
            let inner = format!("{indent}    ");
            let items: Vec<String> = list
                .iter()
                .map(|e| format!("normal {{{inner}{}{indent}  }}", normal_body(e, &DAffine3::IDENTITY, files, &inner)))
                .collect();
            let _ = write!(sdl, "{indent}  {}", items.join(&format!(",{indent}  ")));
        }
        brick_sdl(&mut sdl, kind, &p);
        if n.normal_map.is_none() && n.normals.is_none() {
            // `bump_size` as a keyword: a negative amount right after a vector or the arms
            // would be read as part of their expression.
            let _ = write!(sdl, " bump_size {bump_size}");
        }
        if let Some(a) = n.accuracy {
            let _ = write!(sdl, " accuracy {}", number(a));
        }
        pattern_keys_sdl(&mut sdl, &p, indent);
        turbulence_sdl(&mut sdl, p.turbulence, p.omega, p.lambda, p.octaves, indent);
        if let Some(map) = &n.slope_map {
            let _ = write!(sdl, "{indent}slope_map {{");
            for SlopeMapEntry(value, [height, slope]) in map {
                let _ = write!(sdl, "{indent}  [{} <{}, {}>]", number(*value), number(*height), number(*slope));
            }
            let _ = write!(sdl, "{indent}}}");
        }
        normal_map_sdl(&mut sdl, n, files, indent);
        wave_sdl(&mut sdl, &p, indent);
        matrices_sdl(&mut sdl, &n.object_from_pattern(), world_from_object, indent);
        return sdl;
    }
    if n.pattern == NormalKind::Average {
        // No bump size: POV-Ray's `average` takes none.
        let mut sdl = String::from("average");
        turbulence_sdl(&mut sdl, n.turbulence, n.omega, n.lambda, n.octaves, indent);
        normal_map_sdl(&mut sdl, n, files, indent);
        matrices_sdl(&mut sdl, &n.object_from_pattern(), world_from_object, indent);
        return sdl;
    }
    if let Some(map) = &n.bump_map {
        // No `gamma`: POV-Ray reads a bump map's samples as stored, as Prism does.
        let file = image_map_path(map, files).unwrap_or_default();
        let use_index = if map.use_index { " use_index" } else { "" };
        let mut sdl = format!("bump_map {{ {}{use_index} bump_size {bump_size} }}", image_options_sdl(map, file));
        turbulence_sdl(&mut sdl, n.turbulence, n.omega, n.lambda, n.octaves, indent);
        matrices_sdl(&mut sdl, &n.object_from_pattern(), world_from_object, indent);
        return sdl;
    }
    // With a normal map the pattern's value picks the entries and its amount does not apply.
    let mut sdl = match n.normal_map {
        Some(_) => n.pattern.to_string(),
        None => format!("{} {bump_size}", n.pattern),
    };
    for (keyword, value) in [
        ("control0", n.control0),
        ("control1", n.control1),
        ("size", n.size),
        ("coords", n.coords),
        ("metric", n.metric),
    ] {
        if let Some(v) = value {
            let _ = write!(sdl, " {keyword} {}", number(v));
        }
    }
    turbulence_sdl(&mut sdl, n.turbulence, n.omega, n.lambda, n.octaves, indent);
    if let Some(f) = n.frequency {
        let _ = write!(sdl, "{indent}frequency {}", number(f));
    }
    if let Some(phase) = n.phase {
        let _ = write!(sdl, "{indent}phase {}", number(phase));
    }
    if let Some(wave) = n.wave {
        let _ = write!(sdl, "{indent}{}", wave_keyword(wave));
    }
    normal_map_sdl(&mut sdl, n, files, indent);
    matrices_sdl(&mut sdl, &n.object_from_pattern(), world_from_object, indent);
    sdl
}

/// A normal's `normal_map { [v ENTRY] ... }`, when it has one: each entry's body with its own
/// transform only.
fn normal_map_sdl(sdl: &mut String, n: &crate::material::normal::Normal, files: &dyn FilePaths, indent: &str) {
    use crate::material::normal::NormalMapEntry;
    let Some(map) = &n.normal_map else { return };
    let _ = write!(sdl, "{indent}normal_map {{");
    let inner = format!("{indent}    ");
    for NormalMapEntry(value, entry) in map {
        let body = normal_body(entry, &DAffine3::IDENTITY, files, &inner);
        let _ = write!(sdl, "{indent}  [{} {body}]", number(*value));
    }
    let _ = write!(sdl, "{indent}}}");
}

/// A pattern's `turbulence` with its octaves, when it has one.
fn turbulence_sdl(
    sdl: &mut String,
    turbulence: Option<crate::material::pattern::TurbulenceAmount>,
    omega: Option<f64>,
    lambda: Option<f64>,
    octaves: Option<u32>,
    indent: &str,
) {
    if let Some(t) = turbulence {
        // Amounts per axis of the pattern's own (POV-Ray's) frame: not mirrored.
        let t = t.vector();
        let _ = write!(sdl, "{indent}turbulence <{}, {}, {}>", number(t.x), number(t.y), number(t.z));
    }
    for (keyword, value) in [("omega", omega), ("lambda", lambda)] {
        if let Some(v) = value {
            let _ = write!(sdl, " {keyword} {}", number(v));
        }
    }
    if let Some(n) = octaves {
        let _ = write!(sdl, " octaves {n}");
    }
}

/// A pattern's own transform, then the object's (mirrored like every matrix).
fn matrices_sdl(sdl: &mut String, own: &DAffine3, world_from_object: &DAffine3, indent: &str) {
    if *own != DAffine3::IDENTITY {
        let _ = write!(sdl, "{indent}matrix {}", pov_matrix(own));
    }
    if *world_from_object != DAffine3::IDENTITY {
        let _ = write!(sdl, "{indent}matrix {}", pov_matrix(world_from_object));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DMat3;

    #[test]
    fn matrix_is_mirrored_conjugate_in_row_layout() {
        // Rotate 90 degrees about y (+x -> -z) and translate by (1, 2, 3).
        let m = DAffine3 {
            matrix3: DMat3::from_rotation_y(std::f64::consts::FRAC_PI_2),
            translation: DVec3::new(1.0, 2.0, 3.0),
        };
        let text = pov_matrix(&m);
        let numbers: Vec<f64> =
            text.trim_matches(|c| c == '<' || c == '>').split(", ").map(|v| v.parse().unwrap()).collect();
        // POV-Ray maps a row vector p to p * M; S(m(p)) must equal that for S(p).
        let p = DVec3::new(0.3, -0.7, 1.1);
        let s = DVec3::new(1.0, 1.0, -1.0);
        let q = p * s;
        let pov = DVec3::new(
            q.x * numbers[0] + q.y * numbers[3] + q.z * numbers[6] + numbers[9],
            q.x * numbers[1] + q.y * numbers[4] + q.z * numbers[7] + numbers[10],
            q.x * numbers[2] + q.y * numbers[5] + q.z * numbers[8] + numbers[11],
        );
        assert!((pov - m.transform_point3(p) * s).length() < 1e-12, "{pov}");
    }

    #[test]
    fn options_line_round_trips() {
        let text = format!("// header\n{OPTIONS_PREFIX}+W320 +H180 -A\n#version 3.7;\n");
        assert_eq!(options_of(&text), Some("+W320 +H180 -A"));
    }
}
