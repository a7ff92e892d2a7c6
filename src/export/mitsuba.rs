//! `prism export mitsuba`: a scene as Mitsuba 3 XML (`version="3.0.0"`) that renders, with
//! Mitsuba's `path` integrator (`volpath` where interiors absorb: their media are
//! `homogeneous`, see `interior_xml`), the image Prism's `path` integrator renders.
//!
//! Every default is written out: the `path` integrator's `max_depth` and `rr_depth`, a
//! `perspective` (or `thinlens`) sensor with `fov_axis="y"`, an `independent` sampler with
//! the scene's samples and seed, an `hdrfilm` with the scene's filter (sampling its border
//! when the filter is wider than a pixel, as Prism does), and `ext_ior = 1` on every
//! dielectric interface. Materials are written from the path integrator's own reading of
//! them ([`crate::render::integrators::path::scatter`]), lobe by lobe: one lobe is its
//! Mitsuba BSDF (wrapped in `twosided` where Prism scatters alike on both sides), several
//! are a `blendbsdf` tree with the same weights. Meshes become binary PLY files beside the
//! XML. Lights keep their physical units (W/sr, W/m^2, W/(m^2 sr)).
//!
//! Two of Mitsuba 3.9's own ways are written around, found by the random scenes of
//! scripts/mitsuba-differential.py: its `blendbsdf` mis-weights a delta lobe beside a smooth
//! one, so absorbing glass is not padded with a black diffuse lobe; and its `path`
//! integrator drops a sample that only passed through `Null` lobes (a thin dielectric's
//! transmission) before leaving a scene without an environment, so such scenes get a black
//! one (`dark_environment`).
//!
//! glTF metallic-roughness materials become the `gltf_metallic_roughness` BSDF that
//! scripts/mitsuba_gltf_bsdf.py registers with Mitsuba (glTF 2.0 Appendix B written from the
//! specification; Mitsuba's `principled` is a different model), with `bitmap` textures.
//!
//! What Mitsuba cannot express is an error naming the object, material or light: textures
//! other than a diffuse colour image or a glTF material's, textures on a shape whose Mitsuba
//! form has other (u, v) than Prism's (spheres, planes, boxes, discs, cylinder caps: see
//! `MitsubaShape::same_uv`), meshes with normal maps or alpha masks, glTF alpha blending,
//! shapes without a
//! Mitsuba form (torus, blob, superellipsoid, cone, a disc with a hole), spheres and
//! cylinders under non-uniform scales, spot cones with a soft edge (Mitsuba's falls off
//! linearly in angle, Prism's in a smoothstep of the cosine), POV-Ray's antialiasing methods
//! and its adaptive focal blur (`blur_variance`: Mitsuba takes the same samples everywhere).
//! An infinite plane is written as a square of side `MITSUBA_PLANE_SIZE` centred below the
//! scene (under an orthographic camera, 2000 scene radii: Mitsuba places hit points in single
//! precision relative to a shape's size, and such a camera sees no horizon).

use std::collections::HashMap;
use std::fmt::Write;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use glam::{DAffine3, DVec3};
use prism_api::mitsuba::{MitsubaKind, MitsubaShape, TriangleList};

use crate::diagnostics::{Diagnostic, SceneError};
use crate::material::Material;
use crate::render::bsdf::Bsdf;
use crate::render::camera::CameraFrame;
use crate::render::integrators::path::scatter::{Lobe, PathMaterial, SurfacePoint};
use crate::render::lights::{LightSource, RenderLight};
use crate::world::Scene;
use crate::world::components::{
    Antialias, Light, MaterialComponent, Origin, PhotometricLight, PixelFilter, Projection, ShapeComponent,
    WorldTransform,
};

/// A black environment, written where Mitsuba 3.9's `path` integrator would otherwise drop
/// light: it keeps a sample only once the path has scattered off something other than a
/// `Null` lobe (a thin dielectric's transmission, a `null` BSDF) or met an environment
/// emitter, so without one the emission of a thin pane seen straight through it (and what
/// such a pane shows before the path leaves the scene) is lost. Never sampled when
/// `other_emitters` (a sampling weight of 0; Mitsuba refuses one when it is the only
/// emitter).
fn dark_environment(other_emitters: bool) -> String {
    let weight = if other_emitters { "\n    <float name=\"sampling_weight\" value=\"0\"/>" } else { "" };
    format!("  <emitter type=\"constant\">\n    <rgb name=\"radiance\" value=\"0, 0, 0\"/>{weight}\n  </emitter>\n")
}

/// A Mitsuba scene: the XML and the mesh files it refers to.
#[derive(Debug, Default)]
pub struct MitsubaScene {
    /// The scene file's text.
    pub xml: String,
    /// Mesh files to write beside it: (path relative to the XML, binary PLY bytes).
    pub meshes: Vec<(String, Vec<u8>)>,
}

/// Writes `scene` (after `resolve_transforms` and `validate`) as Mitsuba 3 XML, naming mesh
/// files `{mesh_prefix}NNN.ply`; files the scene reads (environment maps) are referred to
/// relative to `xml_dir`, the folder the XML will be written to. `source` names the scene
/// in the header comment.
pub fn export(scene: &Scene, source: &str, mesh_prefix: &str, xml_dir: &Path) -> Result<MitsubaScene, SceneError> {
    let mut errors = Vec::new();
    let mut out = MitsubaScene::default();
    let xml = &mut out.xml;
    let _ = writeln!(
        xml,
        "<!-- Mitsuba 3 scene written by `prism export mitsuba` from {}; regenerate, do not edit. -->",
        escape(source)
    );
    xml.push_str("<scene version=\"3.0.0\">\n");
    let render = &scene.render;
    // Absorbing interiors need the integrator that tracks media.
    let integrator = if scene.world.query::<&MaterialComponent>().iter().any(|m| interior_xml(&m.material).is_some()) {
        "volpath"
    } else {
        "path"
    };
    let _ = writeln!(
        xml,
        "  <integrator type=\"{integrator}\">\n    <integer name=\"max_depth\" value=\"{}\"/>\n    <integer name=\"rr_depth\" value=\"{}\"/>\n    <boolean name=\"hide_emitters\" value=\"false\"/>\n  </integrator>",
        render.max_depth, render.rr_depth
    );
    if !matches!(render.antialias, Antialias::Stratified {}) {
        errors.push(Diagnostic::new(
            scene.render_key("antialias"),
            "POV-Ray's antialiasing methods have no Mitsuba equivalent; use stratified sampling",
        ));
    }
    sensor(xml, scene, &mut errors);
    let background = scene.environment.background.0;
    if let Some(map) = &scene.environment.environment {
        let _ = writeln!(
            xml,
            "  <emitter type=\"envmap\">\n    <string name=\"filename\" value=\"{}\"/>\n    <float name=\"scale\" value=\"{}\"/>\n    <transform name=\"to_world\">\n      <rotate y=\"1\" angle=\"{}\"/>\n    </transform>\n  </emitter>",
            escape(&relative_path(Path::new(&map.file), xml_dir).display().to_string()),
            number(map.intensity),
            number(map.rotate)
        );
    } else if background.max_element() > 0.0 {
        let _ = writeln!(
            xml,
            "  <emitter type=\"constant\">\n    <rgb name=\"radiance\" value=\"{}\"/>\n  </emitter>",
            rgb(background)
        );
    }
    lights(xml, scene, &mut errors);
    objects(&mut out, scene, mesh_prefix, xml_dir, &mut errors);
    let passes_through = out.xml.contains("type=\"thindielectric\"") || out.xml.contains("type=\"null\"");
    if integrator == "volpath" && passes_through {
        errors.push(Diagnostic::new(
            scene.render_key("integrator"),
            "a scene with absorbing interiors needs Mitsuba's `volpath`, whose shadow rays pass through thin \
             dielectrics and alpha-blended surfaces, where Prism's path integrator (and Mitsuba's `path`) \
             stops them: such a scene would render brighter in Mitsuba",
        ));
    }
    let lit_around = scene.environment.environment.is_some() || background.max_element() > 0.0;
    if !lit_around && passes_through {
        out.xml.push_str(&dark_environment(out.xml.contains("<emitter")));
    }
    out.xml.push_str("</scene>\n");
    if errors.is_empty() {
        return Ok(out);
    }
    Err(super::in_file_order(errors))
}

/// `path` relative to the folder `base` (both made absolute first), for file references that
/// survive moving the repository.
fn relative_path(path: &Path, base: &Path) -> PathBuf {
    let absolute = |p: &Path| std::fs::canonicalize(p).unwrap_or_else(|_| p.to_path_buf());
    let (path, base) = (absolute(path), absolute(base));
    let common = path.components().zip(base.components()).take_while(|(a, b)| a == b).count();
    if common == 0 {
        return path;
    }
    let mut out = PathBuf::new();
    for _ in base.components().skip(common) {
        out.push("..");
    }
    out.extend(path.components().skip(common));
    out
}

fn escape(text: &str) -> String {
    text.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;").replace("--", "- -")
}

fn number(x: f64) -> String {
    format!("{x:?}")
}

fn rgb(c: DVec3) -> String {
    format!("{}, {}, {}", number(c.x), number(c.y), number(c.z))
}

/// A 4x4 row-major `matrix` value.
fn matrix(m: &DAffine3) -> String {
    let (a, t) = (m.matrix3, m.translation);
    let rows = [
        [a.x_axis.x, a.y_axis.x, a.z_axis.x, t.x],
        [a.x_axis.y, a.y_axis.y, a.z_axis.y, t.y],
        [a.x_axis.z, a.y_axis.z, a.z_axis.z, t.z],
        [0.0, 0.0, 0.0, 1.0],
    ];
    rows.iter().flatten().map(|v| number(*v)).collect::<Vec<_>>().join(" ")
}

fn sensor(xml: &mut String, scene: &Scene, errors: &mut Vec<Diagnostic>) {
    let camera = scene.camera();
    let render = &scene.render;
    let frame = CameraFrame::new(&camera);
    let image_aspect = f64::from(render.width) / f64::from(render.height);
    if let Some(aspect) = camera.aspect
        && (aspect - image_aspect).abs() > 1e-9 * image_aspect
    {
        let origin =
            scene.world.get::<&Origin>(scene.camera).map_or_else(|_| scene.render_origin.clone(), |o| o.0.clone());
        errors.push(Diagnostic::new(
            origin.child("aspect"),
            "Mitsuba's pixels are square: a viewport aspect other than the image's cannot be exported",
        ));
    }
    if camera.blur_variance.is_some_and(|v| v > 0.0) {
        let origin =
            scene.world.get::<&Origin>(scene.camera).map_or_else(|_| scene.render_origin.clone(), |o| o.0.clone());
        errors.push(
            Diagnostic::new(
                origin.child("blur_variance"),
                "POV-Ray's adaptive focal blur has no Mitsuba equivalent: Mitsuba takes the same samples in every pixel",
            )
            .with_help("remove blur_variance (or set it to 0) to export the fixed sample count"),
        );
    }
    let orthographic = camera.projection == Projection::Orthographic;
    let kind = match (orthographic, camera.aperture > 0.0) {
        (true, _) => "orthographic",
        (false, true) => "thinlens",
        (false, false) => "perspective",
    };
    let _ = writeln!(xml, "  <sensor type=\"{kind}\">");
    if !orthographic {
        let _ = writeln!(xml, "    <string name=\"fov_axis\" value=\"y\"/>");
        let _ = writeln!(xml, "    <float name=\"fov\" value=\"{}\"/>", number(camera.vfov));
    }
    let _ = writeln!(
        xml,
        "    <float name=\"near_clip\" value=\"0.0001\"/>\n    <float name=\"far_clip\" value=\"10000000.0\"/>"
    );
    if camera.aperture > 0.0 {
        let _ = writeln!(xml, "    <float name=\"aperture_radius\" value=\"{}\"/>", number(0.5 * camera.aperture));
        let _ = writeln!(xml, "    <float name=\"focus_distance\" value=\"{}\"/>", number(frame.focal_distance));
    }
    let target = frame.position + frame.direction;
    // Mitsuba's orthographic view spans x in [-1, 1] of its frame: scale it to the view's
    // half width (the height follows from the image's aspect).
    let scale = if orthographic {
        let half_width = 0.5 * frame.height * image_aspect;
        format!("\n      <scale x=\"{0}\" y=\"{0}\"/>", number(half_width))
    } else {
        String::new()
    };
    let _ = writeln!(
        xml,
        "    <transform name=\"to_world\">{scale}\n      <lookat origin=\"{}\" target=\"{}\" up=\"{}\"/>\n    </transform>",
        rgb(frame.position),
        rgb(target),
        rgb(frame.up)
    );
    let _ = writeln!(
        xml,
        "    <sampler type=\"independent\">\n      <integer name=\"sample_count\" value=\"{}\"/>\n      <integer name=\"seed\" value=\"{}\"/>\n    </sampler>",
        render.samples, render.seed
    );
    let _ = writeln!(
        xml,
        "    <film type=\"hdrfilm\">\n      <integer name=\"width\" value=\"{}\"/>\n      <integer name=\"height\" value=\"{}\"/>\n      <string name=\"pixel_format\" value=\"rgb\"/>\n      <string name=\"component_format\" value=\"float32\"/>\n{}\n    </film>\n  </sensor>",
        render.width,
        render.height,
        rfilter(render.filter)
    );
}

/// The `rfilter` element of `filter`, every parameter written; a filter wider than the pixel
/// also has the film sample its border (`sample_border`), as Prism draws a pixel's samples
/// around its centre whether or not they fall inside the frame: without it Mitsuba splats
/// an edge pixel from the frame's side only, a different mean wherever the image is not
/// flat at its edges.
fn rfilter(filter: PixelFilter) -> String {
    let element = filter_element(filter);
    if filter.is_box() { element } else { format!("      <boolean name=\"sample_border\" value=\"true\"/>\n{element}") }
}

/// The `rfilter` element of `filter`, every parameter written.
fn filter_element(filter: PixelFilter) -> String {
    match filter {
        PixelFilter::Box {} => "      <rfilter type=\"box\"/>".into(),
        PixelFilter::Gaussian { stddev } => format!(
            "      <rfilter type=\"gaussian\">\n        <float name=\"stddev\" value=\"{}\"/>\n      </rfilter>",
            number(stddev)
        ),
        PixelFilter::Mitchell { b, c } => format!(
            "      <rfilter type=\"mitchell\">\n        <float name=\"B\" value=\"{}\"/>\n        <float name=\"C\" value=\"{}\"/>\n      </rfilter>",
            number(b),
            number(c)
        ),
    }
}

fn lights(xml: &mut String, scene: &Scene, errors: &mut Vec<Diagnostic>) {
    let mut entries: Vec<(hecs::Entity, RenderLight)> = Vec::new();
    for (e, l) in scene.world.query::<(hecs::Entity, &Light)>().iter() {
        if let Some(key) = l.negative_key() {
            let at = scene.entity_keys(e, || scene.render_origin.clone()).child(key);
            errors.push(Diagnostic::new(at, "Mitsuba's emitters cannot be negative (a negative light is POV-Ray's)"));
            continue;
        }
        entries.push((e, RenderLight::from_scene(l)));
    }
    for (e, l) in scene.world.query::<(hecs::Entity, &PhotometricLight)>().iter() {
        entries.push((e, RenderLight::from_photometric(l)));
    }
    entries.sort_by_key(|(e, _)| e.id());
    for (entity, light) in entries {
        let at = |key: &str| scene.entity_keys(entity, || scene.render_origin.clone()).child(key);
        match &light.source {
            LightSource::Point(l) => point(xml, l.position, l.intensity),
            LightSource::Spot(l) => {
                if l.cone.cos_inner - l.cone.cos_outer > 1e-12 {
                    errors.push(Diagnostic::new(
                        at("radius"),
                        "Mitsuba's spot light falls off linearly in angle and Prism's smoothly: only a \
                         hard-edged cone (radius at or beyond the falloff) can be exported",
                    ));
                    continue;
                }
                // The hard edge lies at the radius (see `spot_factor`).
                let angle = l.cone.cos_inner.clamp(-1.0, 1.0).acos().to_degrees();
                let up = prism_api::math::tangent(l.cone.axis);
                let _ = writeln!(
                    xml,
                    "  <emitter type=\"spot\">\n    <rgb name=\"intensity\" value=\"{}\"/>\n    <float name=\"cutoff_angle\" value=\"{}\"/>\n    <float name=\"beam_width\" value=\"{}\"/>\n    <transform name=\"to_world\">\n      <lookat origin=\"{}\" target=\"{}\" up=\"{}\"/>\n    </transform>\n  </emitter>",
                    rgb(l.intensity),
                    number(angle),
                    number(angle),
                    rgb(l.position),
                    rgb(l.position + l.cone.axis),
                    rgb(up)
                );
            }
            LightSource::Directional(l) => {
                let _ = writeln!(
                    xml,
                    "  <emitter type=\"directional\">\n    <vector name=\"direction\" value=\"{}\"/>\n    <rgb name=\"irradiance\" value=\"{}\"/>\n  </emitter>",
                    rgb(l.direction),
                    rgb(l.irradiance)
                );
            }
            LightSource::AreaGrid(l) => {
                if l.cone.is_some() || l.grid.orient || l.grid.circular || l.grid.jitter {
                    errors.push(Diagnostic::new(
                        at("kind"),
                        "only a plain rectangular area light (no spotlight, orient, circular or jitter) \
                         is exported, as its grid of point lights",
                    ));
                    continue;
                }
                // The path integrator's reading: the grid's points share its intensity.
                let (n1, n2) = (l.grid.size1.max(1), l.grid.size2.max(1));
                let share = l.intensity / f64::from(n1 * n2);
                let at = |i: u32, n: u32| if n > 1 { f64::from(i) / f64::from(n - 1) - 0.5 } else { 0.0 };
                for j in 0..n2 {
                    for i in 0..n1 {
                        point(xml, l.centre + l.grid.axis1 * at(i, n1) + l.grid.axis2 * at(j, n2), share);
                    }
                }
            }
        }
    }
}

fn point(xml: &mut String, position: DVec3, intensity: DVec3) {
    let _ = writeln!(
        xml,
        "  <emitter type=\"point\">\n    <point name=\"position\" value=\"{}\"/>\n    <rgb name=\"intensity\" value=\"{}\"/>\n  </emitter>",
        rgb(position),
        rgb(intensity)
    );
}

/// True when `m` scales every direction by the same factor (a rotation, a mirror and a
/// uniform scale), as Mitsuba's spheres and cylinders need.
fn is_similarity(m: &glam::DMat3) -> bool {
    let (a, b, c) = (m.x_axis, m.y_axis, m.z_axis);
    let s = a.length();
    let close = |x: f64, y: f64| (x - y).abs() <= 1e-9 * s * s;
    close(b.length_squared(), s * s)
        && close(c.length_squared(), s * s)
        && close(a.dot(b), 0.0)
        && close(a.dot(c), 0.0)
        && close(b.dot(c), 0.0)
}

/// Under an orthographic camera, the half side of the square standing in for an infinite
/// plane, over the radius of the scene's bounds and the camera.
const ORTHOGRAPHIC_PLANE_REACH: f64 = 2000.0;

/// The square that stands in for an infinite plane (`world_from_square`, the plugin's square
/// of side `MITSUBA_PLANE_SIZE`), centred below the scene. Mitsuba's single-precision
/// rectangles place hit points with an error in proportion to their size (a square 10^5
/// wide puts them millimetres off), while a perspective camera near the plane sees sky below
/// the horizon of a square too small: a square of 100 scene radii showed a quarter of a
/// pixel of it, 2000 radii still a fiftieth, enough for the per-pixel test. So a perspective
/// view keeps the plugin's size; an orthographic one, which sees no horizon but resolves
/// contacts finely, gets [`ORTHOGRAPHIC_PLANE_REACH`] radii. (Framing a small square with
/// large strips made Mitsuba render a diffuse scene under a constant sky 1.5 % brighter.)
fn fit_plane(world_from_square: &DAffine3, extent: &prism_api::Aabb, orthographic: bool) -> DAffine3 {
    let m = world_from_square.matrix3;
    let normal = m.z_axis.normalize();
    let centre = 0.5 * (extent.min + extent.max);
    let radius = (0.5 * (extent.max - extent.min).length()).max(1.0);
    let far = m.x_axis.length();
    let half = if orthographic { (ORTHOGRAPHIC_PLANE_REACH * radius).min(far) } else { far };
    let foot = centre - normal * normal.dot(centre - world_from_square.translation);
    DAffine3::from_mat3_translation(
        glam::DMat3::from_cols(m.x_axis.normalize() * half, m.y_axis.normalize() * half, m.z_axis),
        foot,
    )
}

fn objects(out: &mut MitsubaScene, scene: &Scene, mesh_prefix: &str, xml_dir: &Path, errors: &mut Vec<Diagnostic>) {
    let mut query =
        scene
            .world
            .query::<(hecs::Entity, &ShapeComponent, Option<&WorldTransform>, &MaterialComponent, Option<&Origin>)>();
    let mut entries: Vec<_> = query.iter().collect();
    entries.sort_by_key(|(e, ..)| e.id());
    let extent = entries.iter().fold(
        prism_api::Aabb::from_corners(scene.camera().position.into(), scene.camera().position.into()),
        |extent, (_, shape, transform, ..)| {
            let bounds = shape.geometry.bounds().transformed(&transform.map_or(DAffine3::IDENTITY, |t| t.0));
            if bounds.is_bounded() { extent.union(bounds) } else { extent }
        },
    );
    let orthographic = scene.camera().projection == Projection::Orthographic;
    let mut meshes =
        MeshFiles::counted(entries.iter().map(|(_, shape, _, material, _)| (&shape.geometry, &material.material)));
    for (_, shape, transform, material, origin) in entries {
        let at = |key: &str| origin.map_or_else(|| scene.render_origin.clone(), |o| o.0.child(key));
        let Some(parts) = shape.geometry.to_mitsuba() else {
            if shape.kind == crate::import::spawn::MESH_SHAPE {
                errors.push(Diagnostic::new(
                    at("file"),
                    "a mesh whose file material has a normal map or an alpha mask (MASK) has no Mitsuba 3 \
                     equivalent; replace the material (`material` or `material_map`) to export it",
                ));
                continue;
            }
            errors.push(
                Diagnostic::new(at("shape"), format!("shape `{}` has no Mitsuba 3 equivalent", shape.kind))
                    .with_help("its plugin must implement `Shape::to_mitsuba`"),
            );
            continue;
        };
        if material.material.emission.two_sided && material.material.emission.can_emit() {
            errors.push(Diagnostic::new(
                at("material.emission_two_sided"),
                "Mitsuba's area emitters shine from one side only (a flipped copy of the shape would hide the first)",
            ));
            continue;
        }
        let world_from_object = transform.map_or(DAffine3::IDENTITY, |t| t.0);
        if material.material.is_textured()
            && let Some(part) = parts.iter().find(|part| !same_uv(part, &world_from_object))
        {
            errors.push(Diagnostic::new(
                at("material.texture"),
                format!(
                    "Mitsuba's {} has other texture coordinates than Prism's `{}`, so its image would land \
                     elsewhere: textures are exported on rectangles, triangles, meshes and open cylinders",
                    mitsuba_type(&part.kind),
                    shape.kind
                ),
            ));
            continue;
        }
        let (bsdf, emission) = match bsdf_xml(&material.material, xml_dir, out, mesh_prefix)
            .map(|bsdf| bsdf + &interior_xml(&material.material).unwrap_or_default())
            .and_then(|bsdf| Ok((bsdf, emitter_xml(&material.material)?)))
        {
            Ok(xml) => xml,
            Err((key, message)) => {
                errors.push(Diagnostic::new(at(&format!("material.{key}")), message));
                continue;
            }
        };
        let infinite = !shape.geometry.bounds().is_bounded();
        for part in parts {
            let mut world_from_shape = world_from_object * part.object_from_shape;
            if infinite && part.kind == MitsubaKind::Rectangle {
                world_from_shape = fit_plane(&world_from_shape, &extent, orthographic);
            }
            let needs_similarity = matches!(part.kind, MitsubaKind::Sphere | MitsubaKind::Cylinder { .. });
            if needs_similarity && !is_similarity(&world_from_shape.matrix3) {
                errors.push(Diagnostic::new(
                    at("transform"),
                    format!(
                        "Mitsuba's {} cannot be scaled unevenly",
                        if part.kind == MitsubaKind::Sphere { "sphere" } else { "cylinder" }
                    ),
                ));
                continue;
            }
            let shape = ShapeXml { part: &part, world_from_shape: &world_from_shape, material: &material.material };
            shape_xml(out, &mut meshes, &shape, &bsdf, emission.as_deref(), mesh_prefix);
        }
    }
}

/// The shape's absorbing interior as a Mitsuba `homogeneous` medium that absorbs and does not
/// scatter (`sigma_t` times `scale` the absorption per scene unit, albedo 0), when the path integrator sees
/// one ([`PathMaterial::encloses_medium`]). Mitsuba gives a shape's inside this medium and
/// its outside none: an object inside another absorbing one would need the outer medium as
/// its `exterior`, which the export does not write (Prism tracks nested interiors itself).
fn interior_xml(material: &Material) -> Option<String> {
    let path_material = PathMaterial::new(material);
    let absorption = path_material.absorption();
    let strongest = absorption.max_element();
    // Mitsuba reads an RGB `sigma_t` as a reflectance (0..1): the largest channel goes to `scale`.
    (path_material.encloses_medium() && strongest > 0.0).then(|| {
        format!(
            "    <medium type=\"homogeneous\" name=\"interior\">\n      <rgb name=\"sigma_t\" value=\"{}\"/>\n      <float name=\"scale\" value=\"{}\"/>\n      <rgb name=\"albedo\" value=\"0, 0, 0\"/>\n    </medium>\n",
            rgb(absorption / strongest),
            number(strongest)
        )
    })
}

/// The PLY files of an export: one per distinct triangle list, however many objects use it,
/// and the Mitsuba shape groups that objects sharing a list and a material are instances of.
struct MeshFiles {
    /// The materials each triangle list (by the hash of its PLY bytes) is used with, and how
    /// many parts use each pair.
    uses: HashMap<u64, Vec<(Arc<Material>, usize)>>,
    /// The file written for each list: hash -> index into `MitsubaScene::meshes`.
    files: HashMap<u64, usize>,
    /// The shape group of each (list, BSDF): its id.
    groups: HashMap<(u64, String), String>,
}

impl MeshFiles {
    /// Counts the (triangle list, material) pairs of the scene's objects: a pass before
    /// writing, so that a pair used once is written as a plain shape and one used more often
    /// as a shape group and its instances.
    fn counted<'a>(objects: impl Iterator<Item = (&'a Arc<dyn prism_api::Shape>, &'a Arc<Material>)>) -> Self {
        let mut uses: HashMap<u64, Vec<(Arc<Material>, usize)>> = HashMap::new();
        for (geometry, material) in objects {
            for part in geometry.to_mitsuba().into_iter().flatten() {
                if let MitsubaKind::Triangles(triangles) = &part.kind {
                    let pairs = uses.entry(hash_bytes(&ply(triangles))).or_default();
                    match pairs.iter_mut().find(|(m, _)| **m == **material) {
                        Some((_, count)) => *count += 1,
                        None => pairs.push((material.clone(), 1)),
                    }
                }
            }
        }
        Self { uses, files: HashMap::new(), groups: HashMap::new() }
    }

    /// True when more than one part carries the list with hash `hash` and `material`.
    fn repeats(&self, hash: u64, material: &Material) -> bool {
        self.uses.get(&hash).is_some_and(|pairs| pairs.iter().any(|(m, count)| **m == *material && *count > 1))
    }

    /// The file name of `bytes` (hash `hash`), written on first use; a list whose hash
    /// collides with another's gets its own file.
    fn file(&mut self, out: &mut MitsubaScene, hash: u64, bytes: Vec<u8>, mesh_prefix: &str) -> String {
        if let Some(&index) = self.files.get(&hash)
            && out.meshes[index].1 == bytes
        {
            return out.meshes[index].0.clone();
        }
        let count = out.meshes.iter().filter(|(n, _)| n.ends_with(".ply")).count();
        let name = format!("{mesh_prefix}{count:03}.ply");
        self.files.entry(hash).or_insert(out.meshes.len());
        out.meshes.push((name.clone(), bytes));
        name
    }
}

/// One Mitsuba shape to write: a part of an object, placed, with the object's material.
struct ShapeXml<'a> {
    part: &'a MitsubaShape,
    world_from_shape: &'a DAffine3,
    material: &'a Material,
}

fn hash_bytes(bytes: &[u8]) -> u64 {
    use std::hash::{Hash, Hasher};
    let mut hasher = std::collections::hash_map::DefaultHasher::new();
    bytes.hash(&mut hasher);
    hasher.finish()
}

fn shape_xml(
    out: &mut MitsubaScene,
    meshes: &mut MeshFiles,
    shape: &ShapeXml,
    bsdf: &str,
    emission: Option<&str>,
    mesh_prefix: &str,
) {
    let part = shape.part;
    // Mitsuba 3.9's cylinder mis-samples its area under a mirroring to_world (a mirrored
    // emissive tube lit the floor 8 % too dark; `flip_normals` makes it worse), and the tube
    // is its own mirror image across the plane x = 0 of its frame: that mirror is taken out.
    let unmirrored;
    let world_from_shape = if is_mirrored_cylinder(&part.kind, shape.world_from_shape) {
        unmirrored = *shape.world_from_shape * DAffine3::from_scale(DVec3::new(-1.0, 1.0, 1.0));
        &unmirrored
    } else {
        shape.world_from_shape
    };
    let kind = mitsuba_type(&part.kind);
    let mut mesh_file = None;
    if let MitsubaKind::Triangles(triangles) = &part.kind {
        let bytes = ply(triangles);
        let hash = hash_bytes(&bytes);
        let name = meshes.file(out, hash, bytes, mesh_prefix);
        let ply_lines = format!(
            "    <string name=\"filename\" value=\"{}\"/>\n    <boolean name=\"face_normals\" value=\"{}\"/>\n",
            escape(&name),
            triangles.normals.is_empty()
        );
        // A list several objects share with one material becomes a shape group and an
        // instance per object (Mitsuba then holds the triangles once); emitters cannot be
        // instances.
        if emission.is_none() && meshes.repeats(hash, shape.material) {
            let key = (hash, bsdf.to_string());
            let id = match meshes.groups.get(&key) {
                Some(id) => id.clone(),
                None => {
                    let id = format!("mesh_group_{}", meshes.groups.len());
                    let _ = write!(
                        out.xml,
                        "  <shape type=\"shapegroup\" id=\"{id}\">\n  <shape type=\"ply\">\n{ply_lines}{bsdf}  </shape>\n  </shape>\n"
                    );
                    meshes.groups.insert(key, id.clone());
                    id
                }
            };
            let _ = writeln!(
                out.xml,
                "  <shape type=\"instance\">\n    <ref id=\"{id}\"/>\n    <transform name=\"to_world\">\n      <matrix value=\"{}\"/>\n    </transform>\n  </shape>",
                matrix(world_from_shape)
            );
            return;
        }
        mesh_file = Some(ply_lines);
    }
    let xml = &mut out.xml;
    let _ = writeln!(xml, "  <shape type=\"{kind}\">");
    if let Some(lines) = mesh_file {
        xml.push_str(&lines);
    }
    if flips_normals(&part.kind, world_from_shape) {
        xml.push_str("    <boolean name=\"flip_normals\" value=\"true\"/>\n");
    }
    if let MitsubaKind::Cylinder { radius, length } = part.kind {
        let _ = writeln!(
            xml,
            "    <point name=\"p0\" value=\"0, 0, 0\"/>\n    <point name=\"p1\" value=\"0, 0, {}\"/>\n    <float name=\"radius\" value=\"{}\"/>",
            number(length),
            number(radius)
        );
    }
    let _ = writeln!(
        xml,
        "    <transform name=\"to_world\">\n      <matrix value=\"{}\"/>\n    </transform>",
        matrix(world_from_shape)
    );
    xml.push_str(bsdf);
    if let Some(emission) = emission {
        xml.push_str(emission);
    }
    xml.push_str("  </shape>\n");
}

/// The Mitsuba plugin that writes a part of kind `kind`.
fn mitsuba_type(kind: &MitsubaKind) -> &'static str {
    match kind {
        MitsubaKind::Sphere => "sphere",
        MitsubaKind::Rectangle => "rectangle",
        MitsubaKind::Disk => "disk",
        MitsubaKind::Cube => "cube",
        MitsubaKind::Cylinder { .. } => "cylinder",
        MitsubaKind::Triangles(_) => "ply",
    }
}

/// True when Mitsuba's (u, v) on `part`, placed by `world_from_object`, is the shape's own:
/// the part says so, and it is not a cylinder written unmirrored (see [`shape_xml`]), whose
/// angle then runs the other way.
fn same_uv(part: &MitsubaShape, world_from_object: &DAffine3) -> bool {
    part.same_uv && !is_mirrored_cylinder(&part.kind, &(*world_from_object * part.object_from_shape))
}

/// A cylinder placed by a mirroring `world_from_shape`, which [`shape_xml`] writes unmirrored.
fn is_mirrored_cylinder(kind: &MitsubaKind, world_from_shape: &DAffine3) -> bool {
    matches!(kind, MitsubaKind::Cylinder { .. }) && world_from_shape.matrix3.determinant() < 0.0
}

/// True when Mitsuba turns the shape's normal inward (or to its back) under a mirroring
/// `world_from_shape` (negative determinant), where Prism's normal, carried by the inverse
/// transpose, keeps its side: the shape is then written with `flip_normals`, which undoes it.
/// Mitsuba's sphere reads a mirror as a negative radius and flips its normals, and a mesh
/// with face normals takes them from the world-space winding, which a mirror reverses (meshes
/// with vertex normals shade and emit by those, which Mitsuba transforms as Prism does; its
/// rectangle, disk, cube and cylinder keep their side too).
fn flips_normals(kind: &MitsubaKind, world_from_shape: &DAffine3) -> bool {
    let mirrored = world_from_shape.matrix3.determinant() < 0.0;
    mirrored
        && match kind {
            MitsubaKind::Sphere => true,
            MitsubaKind::Triangles(triangles) => triangles.normals.is_empty(),
            _ => false,
        }
}

/// Binary little-endian PLY of `triangles`: positions, normals and uvs when present, and faces.
fn ply(t: &TriangleList) -> Vec<u8> {
    let normals = t.normals.len() == t.positions.len() && !t.normals.is_empty();
    let uvs = t.uvs.len() == t.positions.len() && !t.uvs.is_empty();
    let mut header = format!("ply\nformat binary_little_endian 1.0\nelement vertex {}\n", t.positions.len());
    header.push_str("property float x\nproperty float y\nproperty float z\n");
    if normals {
        header.push_str("property float nx\nproperty float ny\nproperty float nz\n");
    }
    if uvs {
        // Mitsuba's PLY u, v are taken as they are, and its bitmaps put v = 0 at the image's
        // top row, as Prism does.
        header.push_str("property float u\nproperty float v\n");
    }
    let _ = write!(header, "element face {}\nproperty list uchar int vertex_indices\nend_header\n", t.triangles.len());
    let mut bytes = header.into_bytes();
    for (i, p) in t.positions.iter().enumerate() {
        for v in p {
            bytes.extend_from_slice(&v.to_le_bytes());
        }
        if normals {
            for v in t.normals[i] {
                bytes.extend_from_slice(&v.to_le_bytes());
            }
        }
        if uvs {
            for v in t.uvs[i] {
                bytes.extend_from_slice(&v.to_le_bytes());
            }
        }
    }
    for tri in &t.triangles {
        bytes.push(3);
        for i in tri {
            bytes.extend_from_slice(&(*i as i32).to_le_bytes());
        }
    }
    bytes
}

type Problem = (&'static str, String);

/// The `<bsdf>` of a material, indented for a shape; image files are referred to relative to
/// `xml_dir`.
fn bsdf_xml(
    material: &crate::material::Material,
    xml_dir: &Path,
    out: &mut MitsubaScene,
    mesh_prefix: &str,
) -> Result<String, Problem> {
    if let crate::material::SurfaceModel::MetallicRoughness(m) = &material.surface {
        return metallic_roughness_xml(material, m, xml_dir, out, mesh_prefix).map(|bsdf| format!("    {bsdf}\n"));
    }
    if let crate::material::SurfaceModel::Layered(_) = &material.surface {
        return Err(("layers", "layered textures are not exported to Mitsuba".into()));
    }
    if let crate::material::SurfaceModel::Finish(f) = &material.surface
        && f.pigment.is_some()
    {
        return Err(("pigment", "pigment patterns and image maps are not exported to Mitsuba".into()));
    }
    if let crate::material::SurfaceModel::Finish(f) = &material.surface
        && f.normal.is_some()
    {
        return Err(("normal", "normal patterns are not exported to Mitsuba".into()));
    }
    if material.is_textured() {
        return textured_diffuse_xml(material, xml_dir).map(|bsdf| format!("    {bsdf}\n"));
    }
    let shaded =
        PathMaterial::new(material).shade(&SurfacePoint { uv: glam::DVec2::ZERO, object_point: glam::DVec3::ZERO });
    let lobes: Vec<(DVec3, &Lobe)> = shaded.scatter.lobes().collect();
    if lobes.is_empty() {
        return Ok(
            "    <bsdf type=\"diffuse\">\n      <rgb name=\"reflectance\" value=\"0, 0, 0\"/>\n    </bsdf>\n".into()
        );
    }
    // A lone lobe of weight below 1 (a mirror with `diffuse = 0`, say) is that lobe with the
    // weight as its tint: padding it with a black diffuse in a blendbsdf would be the same
    // BSDF on paper, but Mitsuba 3.9's blendbsdf mis-weights a delta lobe mixed with a smooth
    // one (see docs/scene-format.md), and rendered such a mirror 27 % too dark.
    if let [(weight, lobe)] = lobes.as_slice()
        && !matches!(lobe, Lobe::PassThrough)
        && let Ok(xml) = lobe_xml(lobe, *weight)
    {
        return Ok(format!("    {xml}\n"));
    }
    // A sum of weighted lobes as nested blends: lobe i's grey weight s_i (the largest
    // channel) goes into the blend, the rest of its colour into the lobe's own tint.
    let scales: Vec<f64> = lobes.iter().map(|(weight, _)| weight.max_element()).collect();
    let total: f64 = scales.iter().sum();
    if total > 1.0 + 1e-9 {
        return Err((
            "reflection",
            format!("the lobes' weights sum to {total} > 1, which Mitsuba's blendbsdf cannot hold"),
        ));
    }
    // Weights summing below 1 (glass that absorbs part of the light) are the blend of the
    // lobes in proportion, each tinted by the sum, where every lobe takes a tint: a black
    // diffuse padding the blend would be the same on paper, but is a smooth lobe beside
    // delta ones, which Mitsuba 3.9's blendbsdf mis-weights (as above).
    let absorbs = total < 1.0 - 1e-12;
    let tintable = |lobe: &Lobe| match lobe {
        Lobe::Mirror => true,
        Lobe::PassThrough => false,
        Lobe::Bsdf { bsdf, .. } => !matches!(bsdf, Bsdf::Plastic { .. }),
    };
    let renormalise = absorbs && total > 0.0 && lobes.iter().all(|(_, lobe)| tintable(lobe));
    // Renormalised, each lobe's share of the blend is divided by the sum and its tint
    // multiplied by it.
    let sum = if renormalise { total } else { 1.0 };
    let mut parts = Vec::new();
    for ((weight, lobe), scale) in lobes.iter().zip(&scales) {
        parts.push((scale / sum, lobe_xml(lobe, *weight / scale * sum)?));
    }
    if absorbs && !renormalise {
        parts.push((1.0 - total, "<bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"0, 0, 0\"/></bsdf>".into()));
    }
    Ok(format!("    {}\n", blend(&parts)))
}

/// The Mitsuba plugin of glTF metallic-roughness, registered by scripts/mitsuba_gltf_bsdf.py.
const GLTF_PLUGIN: &str = "gltf_metallic_roughness";

/// A glTF metallic-roughness material as the `gltf_metallic_roughness` BSDF of
/// scripts/mitsuba_gltf_bsdf.py (the specification's Appendix B, written from its text), as
/// Prism's path integrator reads it: the base colour factor times an sRGB texture, the
/// metallic and roughness factors times a linear texture's blue and green channels, the ior,
/// specular, thin-walled transmission and clear coat factors, both sides alike. Textures are bilinear
/// at full resolution with their wrap modes; an image inside a glTF file is written beside
/// the meshes as a PNG of the texels Prism samples. Errors name what the plugin does not
/// hold: alpha blending below full coverage, textured emission, the extensions' textures,
/// texture transforms (KHR_texture_transform), different wraps along u and v.
fn metallic_roughness_xml(
    material: &crate::material::Material,
    m: &crate::material::MetallicRoughness,
    xml_dir: &Path,
    out: &mut MitsubaScene,
    mesh_prefix: &str,
) -> Result<String, Problem> {
    use crate::material::AlphaMode;
    if material.emission.texture.is_some() {
        return Err(("pbr.emissive_texture", "textured emission is not exported to Mitsuba".into()));
    }
    if m.alpha_mode == AlphaMode::Blend && m.alpha < 1.0 {
        return Err((
            "pbr",
            format!("alpha blending (BLEND, alpha {}) is not exported to Mitsuba; use OPAQUE", m.alpha),
        ));
    }
    let extension_textures = [
        ("glossiness_texture (KHR_materials_pbrSpecularGlossiness)", &m.glossiness_texture),
        ("pbr.specular_texture", &m.specular_texture),
        ("pbr.specular_color_texture", &m.specular_color_texture),
        ("pbr.transmission_texture", &m.transmission_texture),
        ("pbr.clearcoat_texture", &m.clearcoat_texture),
        ("pbr.clearcoat_roughness_texture", &m.clearcoat_roughness_texture),
    ];
    if let Some((key, _)) = extension_textures.iter().find(|(_, t)| t.is_some()) {
        return Err((key, "the extensions' textures are not exported to Mitsuba (their factors are)".into()));
    }
    let mut xml = format!(
        "<bsdf type=\"{GLTF_PLUGIN}\"><rgb name=\"base_color_factor\" value=\"{}\"/><float name=\"metallic\" value=\"{}\"/><float name=\"roughness\" value=\"{}\"/><float name=\"ior\" value=\"{}\"/>",
        rgb(m.finish.color.0),
        number(m.metallic),
        number(m.roughness),
        number(m.ior)
    );
    if m.specular != 1.0 {
        xml.push_str(&format!("<float name=\"specular\" value=\"{}\"/>", number(m.specular)));
    }
    if m.specular_color != crate::color::Rgb::WHITE {
        xml.push_str(&format!("<rgb name=\"specular_color\" value=\"{}\"/>", rgb(m.specular_color.0)));
    }
    for (name, value) in
        [("transmission", m.transmission), ("clearcoat", m.clearcoat), ("clearcoat_roughness", m.clearcoat_roughness)]
    {
        if value != 0.0 {
            xml.push_str(&format!("<float name=\"{name}\" value=\"{}\"/>", number(value)));
        }
    }
    if let Some(texture) = &m.finish.texture {
        xml.push_str(&bitmap_xml("base_color_texture", "texture", texture, false, xml_dir, out, mesh_prefix)?);
    }
    if let Some(texture) = &m.metallic_roughness_texture {
        xml.push_str(&bitmap_xml(
            "metallic_roughness_texture",
            "pbr.metallic_roughness_texture",
            texture,
            true,
            xml_dir,
            out,
            mesh_prefix,
        )?);
    }
    xml.push_str("</bsdf>");
    Ok(xml)
}

/// A `bitmap` texture named `name` (bilinear, `raw` for linear data, sRGB decoded
/// otherwise) of `texture`, whose errors name `key`. An image file is referred to relative
/// to `xml_dir`; an image inside a glTF file becomes a PNG file beside the meshes (one per
/// distinct image).
fn bitmap_xml(
    name: &str,
    key: &'static str,
    texture: &crate::texture::TextureRef,
    raw: bool,
    xml_dir: &Path,
    out: &mut MitsubaScene,
    mesh_prefix: &str,
) -> Result<String, Problem> {
    use crate::texture::Wrap;
    if texture.offset != [0.0; 2] || texture.scale != [1.0; 2] || texture.rotation != 0.0 {
        return Err((key, "a texture's offset, scale or rotation is not exported to Mitsuba".into()));
    }
    let wrap = match texture.wrap {
        [Wrap::Repeat, Wrap::Repeat] => "repeat",
        [Wrap::Clamp, Wrap::Clamp] => "clamp",
        [Wrap::Mirror, Wrap::Mirror] => "mirror",
        _ => return Err((key, "Mitsuba's bitmap has one wrap mode for both axes".into())),
    };
    let file = match (texture.image, &texture.texture) {
        (None, _) => relative_path(Path::new(&texture.file), xml_dir).display().to_string(),
        (Some(_), Some(decoded)) => {
            let png = decoded.rgb_png().map_err(|e| (key, format!("cannot encode the image as PNG: {e}")))?;
            match out.meshes.iter().find(|(n, bytes)| n.ends_with(".png") && *bytes == png) {
                Some((existing, _)) => existing.clone(),
                None => {
                    let images = out.meshes.iter().filter(|(n, _)| n.ends_with(".png")).count();
                    let file = format!("{mesh_prefix}image{images:03}.png");
                    out.meshes.push((file.clone(), png));
                    file
                }
            }
        }
        (Some(_), None) => return Err((key, "the image inside the glTF file was not loaded".into())),
    };
    Ok(format!(
        "<texture type=\"bitmap\" name=\"{name}\"><string name=\"filename\" value=\"{}\"/><string name=\"filter_type\" value=\"bilinear\"/><string name=\"wrap_mode\" value=\"{wrap}\"/><boolean name=\"raw\" value=\"{raw}\"/></texture>",
        escape(&file)
    ))
}

/// A diffuse `bsdf` material whose colour is an image file: Mitsuba's `diffuse` with a
/// `bitmap` reflectance (sRGB decoded to linear, bilinear, the same wrap), as Prism's `path`
/// integrator reads it (full resolution, bilinear, texel centres at half-integers, v down
/// from the image's top row, as Mitsuba's bitmap). Other textured materials are errors
/// naming the key: Mitsuba 3 has no texture product for a colour times an image, nor uv
/// transforms that match KHR_texture_transform's order without a matrix.
fn textured_diffuse_xml(material: &crate::material::Material, xml_dir: &Path) -> Result<String, Problem> {
    use crate::material::{Scattering, SurfaceModel};
    use crate::texture::Wrap;
    if material.emission.texture.is_some() {
        return Err(("emission_texture", "textured emission is not exported to Mitsuba".into()));
    }
    let SurfaceModel::Physical(physical) = &material.surface else {
        return Err(("texture", "only a diffuse `bsdf` material's colour texture is exported to Mitsuba".into()));
    };
    let (Scattering::Diffuse, Some(texture)) = (&physical.scattering, &physical.texture) else {
        return Err(("texture", "only a diffuse `bsdf` material's colour texture is exported to Mitsuba".into()));
    };
    if physical.color.0 != DVec3::ONE {
        return Err((
            "color",
            "a textured colour is exported only as the image itself (`color` 1): Mitsuba 3 has no product of a colour and a bitmap".into(),
        ));
    }
    if texture.image.is_some() {
        return Err(("texture", "an image inside a glTF file is not exported to Mitsuba".into()));
    }
    if texture.offset != [0.0; 2] || texture.scale != [1.0; 2] || texture.rotation != 0.0 {
        return Err(("texture", "a texture's offset, scale or rotation is not exported to Mitsuba".into()));
    }
    let wrap = match texture.wrap {
        [Wrap::Repeat, Wrap::Repeat] => "repeat",
        [Wrap::Clamp, Wrap::Clamp] => "clamp",
        [Wrap::Mirror, Wrap::Mirror] => "mirror",
        _ => return Err(("texture.wrap", "Mitsuba's bitmap has one wrap mode for both axes".into())),
    };
    let file = relative_path(Path::new(&texture.file), xml_dir).display().to_string();
    // Diffuse reflection scatters alike on both sides under Prism's path integrator.
    Ok(format!(
        "<bsdf type=\"twosided\"><bsdf type=\"diffuse\"><texture type=\"bitmap\" name=\"reflectance\"><string name=\"filename\" value=\"{}\"/><string name=\"filter_type\" value=\"bilinear\"/><string name=\"wrap_mode\" value=\"{wrap}\"/><boolean name=\"raw\" value=\"false\"/></texture></bsdf></bsdf>",
        escape(&file)
    ))
}

/// `parts` (weights summing to 1) as a `blendbsdf` tree.
fn blend(parts: &[(f64, String)]) -> String {
    match parts {
        [] => String::new(),
        [(_, only)] => only.clone(),
        [(w, first), rest @ ..] => {
            let rest_total: f64 = rest.iter().map(|(s, _)| s).sum();
            let total = w + rest_total;
            let normalised: Vec<(f64, String)> = rest.iter().map(|(s, x)| (s / rest_total, x.clone())).collect();
            // blendbsdf is (1 - weight) * first + weight * second.
            format!(
                "<bsdf type=\"blendbsdf\"><float name=\"weight\" value=\"{}\"/>{first}{}</bsdf>",
                number(rest_total / total),
                blend(&normalised)
            )
        }
    }
}

fn lobe_xml(lobe: &Lobe, tint: DVec3) -> Result<String, Problem> {
    let twosided = |inner: String| format!("<bsdf type=\"twosided\">{inner}</bsdf>");
    Ok(match lobe {
        Lobe::Mirror => twosided(format!(
            "<bsdf type=\"conductor\"><string name=\"material\" value=\"none\"/><rgb name=\"specular_reflectance\" value=\"{}\"/></bsdf>",
            rgb(tint)
        )),
        Lobe::PassThrough => "<bsdf type=\"null\"/>".into(),
        Lobe::Bsdf { bsdf, two_sided } => {
            let inner = bsdf_model_xml(bsdf, tint)?;
            // A thin slab is the same from both sides already, and Mitsuba's twosided refuses
            // transmitting BSDFs.
            let symmetric = matches!(bsdf, Bsdf::ThinDielectric { .. } | Bsdf::Dielectric { .. });
            if *two_sided && !symmetric { twosided(inner) } else { inner }
        }
    })
}

fn ggx(alpha: f64) -> String {
    format!(
        "<string name=\"distribution\" value=\"ggx\"/><float name=\"alpha\" value=\"{}\"/><boolean name=\"sample_visible\" value=\"true\"/>",
        number(alpha)
    )
}

fn bsdf_model_xml(bsdf: &Bsdf, tint: DVec3) -> Result<String, Problem> {
    Ok(match bsdf {
        Bsdf::Diffuse { reflectance } => {
            format!("<bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"{}\"/></bsdf>", rgb(*reflectance * tint))
        }
        Bsdf::Conductor { eta, k, alpha, tint: own } => {
            let kind = if *alpha > 0.0 { "roughconductor" } else { "conductor" };
            let rough = if *alpha > 0.0 { ggx(*alpha) } else { String::new() };
            format!(
                "<bsdf type=\"{kind}\">{rough}<rgb name=\"eta\" value=\"{}\"/><rgb name=\"k\" value=\"{}\"/><rgb name=\"specular_reflectance\" value=\"{}\"/></bsdf>",
                rgb(*eta),
                rgb(*k),
                rgb(*own * tint)
            )
        }
        Bsdf::Dielectric { eta, alpha, reflect_tint, transmit_tint } => {
            let kind = if *alpha > 0.0 { "roughdielectric" } else { "dielectric" };
            let rough = if *alpha > 0.0 { ggx(*alpha) } else { String::new() };
            format!(
                "<bsdf type=\"{kind}\">{rough}<float name=\"int_ior\" value=\"{}\"/><float name=\"ext_ior\" value=\"1.0\"/><rgb name=\"specular_reflectance\" value=\"{}\"/><rgb name=\"specular_transmittance\" value=\"{}\"/></bsdf>",
                number(*eta),
                rgb(*reflect_tint * tint),
                rgb(*transmit_tint * tint)
            )
        }
        Bsdf::ThinDielectric { eta, reflect_tint, transmit_tint } => format!(
            "<bsdf type=\"thindielectric\"><float name=\"int_ior\" value=\"{}\"/><float name=\"ext_ior\" value=\"1.0\"/><rgb name=\"specular_reflectance\" value=\"{}\"/><rgb name=\"specular_transmittance\" value=\"{}\"/></bsdf>",
            number(*eta),
            rgb(*reflect_tint * tint),
            rgb(*transmit_tint * tint)
        ),
        Bsdf::Plastic { diffuse, eta, alpha } => {
            if tint != DVec3::ONE {
                return Err(("bsdf", "a tinted plastic lobe has no Mitsuba equivalent".into()));
            }
            let kind = if *alpha > 0.0 { "roughplastic" } else { "plastic" };
            let rough = if *alpha > 0.0 {
                format!(
                    "<string name=\"distribution\" value=\"ggx\"/><float name=\"alpha\" value=\"{}\"/>",
                    number(*alpha)
                )
            } else {
                String::new()
            };
            format!(
                "<bsdf type=\"{kind}\">{rough}<rgb name=\"diffuse_reflectance\" value=\"{}\"/><float name=\"int_ior\" value=\"{}\"/><float name=\"ext_ior\" value=\"1.0\"/><boolean name=\"nonlinear\" value=\"false\"/></bsdf>",
                rgb(*diffuse),
                number(*eta)
            )
        }
        Bsdf::MetallicRoughness(_) => {
            return Err(("pbr", "glTF metallic-roughness is exported only as a whole material".into()));
        }
    })
}

/// The `<emitter type="area">` of an emissive material, if it emits.
fn emitter_xml(material: &crate::material::Material) -> Result<Option<String>, Problem> {
    let path = PathMaterial::new(material);
    if !path.can_emit() {
        return Ok(None);
    }
    let radiance = path.emitted(&SurfacePoint { uv: glam::DVec2::ZERO, object_point: glam::DVec3::ZERO });
    if radiance.max_element() <= 0.0 {
        return Ok(None);
    }
    Ok(Some(format!(
        "    <emitter type=\"area\">\n      <rgb name=\"radiance\" value=\"{}\"/>\n    </emitter>\n",
        rgb(radiance)
    )))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::load::{Embedded, load_from};

    fn export_text(text: &'static str) -> Result<MitsubaScene, SceneError> {
        let files: &'static [(&'static str, &'static str)] = Box::leak(Box::new([("s.toml", text)]));
        let embedded: &'static Embedded = Box::leak(Box::new(Embedded(files)));
        let mut scene = load_from(embedded, std::path::Path::new("s.toml"), &crate::plugins::registry()).unwrap();
        crate::world::transforms::resolve_transforms(&mut scene).unwrap();
        crate::world::validate::validate(&scene).unwrap();
        export(&scene, "s.toml", "s_meshes/", Path::new("."))
    }

    #[test]
    fn every_default_is_written() {
        let out = export_text(
            "[render]\nwidth = 64\nheight = 48\nsamples = 16\nmax_depth = 7\nintegrator = \"path\"\n\
             [[object]]\nshape = \"sphere\"\nradius = 0.5\nmaterial = { bsdf = { type = \"conductor\", metal = \"Au\", alpha = 0.2 } }\n",
        )
        .unwrap();
        for needle in [
            "<scene version=\"3.0.0\">",
            "name=\"max_depth\" value=\"7\"",
            "name=\"rr_depth\" value=\"5\"",
            "name=\"fov_axis\" value=\"y\"",
            "<sampler type=\"independent\">",
            "<rfilter type=\"box\"/>",
            "type=\"roughconductor\"",
            "name=\"distribution\" value=\"ggx\"",
            "<bsdf type=\"twosided\">",
        ] {
            assert!(out.xml.contains(needle), "missing {needle} in\n{}", out.xml);
        }
    }

    #[test]
    fn what_mitsuba_cannot_express_is_an_error_naming_it() {
        let error = export_text("[[object]]\nshape = \"torus\"\nmajor_radius = 1.0\nminor_radius = 0.2\n").unwrap_err();
        assert!(error.to_string().contains("torus"), "{error}");
        let error = export_text(
            "[[light]]\nkind = \"spot\"\nposition = [0, 1, 0]\npoint_at = [0, 0, 0]\nradius = 10\nfalloff = 20\n",
        )
        .unwrap_err();
        assert!(error.to_string().contains("radius"), "{error}");
    }

    #[test]
    fn a_pov_finish_becomes_a_blend_with_the_same_weights() {
        let out =
            export_text("[[object]]\nshape = \"sphere\"\nmaterial = { color = [0.8, 0.4, 0.2], reflection = 0.25 }\n")
                .unwrap();
        assert!(out.xml.contains("type=\"blendbsdf\""), "{}", out.xml);
        assert!(out.xml.contains("name=\"material\" value=\"none\""), "{}", out.xml);
    }

    /// A mirror alone is one conductor tinted by its reflectivity: no blendbsdf padded with a
    /// black diffuse, which Mitsuba 3.9 renders too dark (the blend mis-weights a delta lobe
    /// mixed with a smooth one).
    #[test]
    fn a_lone_lobe_is_written_with_its_weight_as_tint_not_blended_with_black() {
        let out = export_text(
            "[[object]]\nshape = \"sphere\"\nmaterial = { color = [0.3, 0.6, 0.3], reflection = [0.5, 0.2, 0.1], diffuse = 0 }\n",
        )
        .unwrap();
        assert!(!out.xml.contains("blendbsdf"), "{}", out.xml);
        assert!(out.xml.contains("name=\"specular_reflectance\" value=\"0.5, 0.2, 0.1\""), "{}", out.xml);
    }

    /// An absorbing interior is a `homogeneous` medium inside the shape that absorbs what the
    /// path integrator absorbs (sigma_t = absorption, albedo 0), rendered by `volpath`; a scene
    /// without one keeps `path`, and an interior behind no refracting surface is not written.
    /// Beside a thin dielectric the export is an error: `volpath`'s shadow rays pass through it.
    #[test]
    fn absorbing_interiors_are_media_under_volpath() {
        let glass = export_text(
            "[[object]]\nshape = \"sphere\"\nmaterial = { bsdf = { type = \"dielectric\" }, \
             attenuation_color = [0.5, 1.0, 1.0], attenuation_distance = 2.0 }\n",
        )
        .unwrap();
        let sigma = std::f64::consts::LN_2 / 2.0;
        assert!(glass.xml.contains("<integrator type=\"volpath\">"), "{}", glass.xml);
        assert!(glass.xml.contains("<medium type=\"homogeneous\" name=\"interior\">"), "{}", glass.xml);
        assert!(glass.xml.contains("name=\"sigma_t\" value=\"1.0, 0.0, 0.0\""), "{}", glass.xml);
        assert!(glass.xml.contains(&format!("name=\"scale\" value=\"{}\"", number(sigma))), "{}", glass.xml);
        let beside_a_pane = export_text(
            "[[object]]\nshape = \"sphere\"\nmaterial = { bsdf = { type = \"dielectric\" }, \
             attenuation_color = 0.5, attenuation_distance = 2.0 }\n\
             [[object]]\nshape = \"rectangle\"\nmaterial = { bsdf = { type = \"thin_dielectric\" } }\n",
        );
        let error = beside_a_pane.unwrap_err().to_string();
        assert!(error.contains("volpath") && error.contains("thin"), "{error}");
        let sheet = export_text(
            "[[object]]\nshape = \"sphere\"\nmaterial = { bsdf = { type = \"thin_dielectric\" }, \
             attenuation_color = 0.5, attenuation_distance = 2.0 }\n",
        )
        .unwrap();
        assert!(sheet.xml.contains("<integrator type=\"path\">") && !sheet.xml.contains("<medium"), "{}", sheet.xml);
    }

    /// Under a mirroring transform Mitsuba turns a sphere's normals inward (a negative radius)
    /// and takes a flat mesh's from its reversed winding: `flip_normals` restores Prism's side,
    /// which matters for one-sided emitters and dielectrics. Unmirrored shapes, and a mirrored
    /// disc (Mitsuba's keeps its side), are written without it.
    #[test]
    fn mirrored_spheres_and_flat_meshes_flip_their_normals_back() {
        let object = |shape: &str, scale: &str| {
            format!(
                "[[object]]\n{shape}\ntransform = {{ scale = {scale} }}\nmaterial = {{ bsdf = {{ type = \"dielectric\" }} }}\n"
            )
        };
        let shapes = [
            ("shape = \"sphere\"", true),
            ("shape = \"triangle\"\nvertices = [[0, 0, 0], [1, 0, 0], [0, 1, 0]]", true),
            ("shape = \"disc\"", false),
        ];
        for (shape, flips) in shapes {
            for (scale, mirrored) in
                [("[-1, 1, 1]", true), ("[2, 2, -2]", true), ("[-1, -1, -1]", true), ("[2, 2, 2]", false)]
            {
                let text: &'static str = Box::leak(object(shape, scale).into_boxed_str());
                let out = export_text(text).unwrap();
                assert_eq!(
                    out.xml.contains("name=\"flip_normals\" value=\"true\""),
                    flips && mirrored,
                    "{shape} {scale}: {}",
                    out.xml
                );
            }
        }
    }

    /// A mirrored cylinder is written unmirrored (it is its own mirror image across x = 0 of
    /// its frame): Mitsuba's cylinder samples its area wrongly under a mirroring to_world.
    #[test]
    fn a_mirrored_cylinder_is_written_without_the_mirror() {
        let out = export_text(
            "[[object]]\nshape = \"cylinder\"\nbase = [0, 0, 0]\ntop = [0, 1, 0]\nradius = 0.2\nopen = true\n\
             transform = { scale = [-1, 1, 1] }\nmaterial = { color = 0, bsdf = { type = \"diffuse\" }, emission = 1 }\n",
        )
        .unwrap();
        let start = out.xml.find("<shape type=\"cylinder\">").expect("a cylinder");
        let values = out.xml[start..].split("<matrix value=\"").nth(1).unwrap().split('"').next().unwrap();
        let m: Vec<f64> = values.split(' ').map(|v| v.parse().unwrap()).collect();
        let det = m[0] * (m[5] * m[10] - m[6] * m[9]) - m[1] * (m[4] * m[10] - m[6] * m[8])
            + m[2] * (m[4] * m[9] - m[5] * m[8]);
        assert!(det > 0.0, "{values}");
        // The same tube: its axis (the frame's z) still runs from the base up.
        assert_eq!((m[2], m[6], m[10]), (0.0, 1.0, 0.0), "{values}");
    }

    #[test]
    fn meshes_become_ply_files() {
        let out =
            export_text("[[object]]\nshape = \"triangle\"\nvertices = [[0, 0, 0], [1, 0, 0], [0, 1, 0]]\n").unwrap();
        assert_eq!(out.meshes.len(), 1);
        let (name, bytes) = &out.meshes[0];
        assert_eq!(name, "s_meshes/000.ply");
        assert!(bytes.starts_with(b"ply\nformat binary_little_endian 1.0\nelement vertex 3\n"));
        assert!(out.xml.contains("s_meshes/000.ply"));
    }

    /// Objects that share a triangle list share its PLY file; those that also share a
    /// material become instances of one shape group, the others stay plain shapes.
    #[test]
    fn shared_meshes_are_written_once_and_instanced_per_material() {
        let triangle = |material: &str, x: i32| {
            format!(
                "[[object]]\nshape = \"triangle\"\nvertices = [[0, 0, 0], [1, 0, 0], [0, 1, 0]]\nmaterial = \"{material}\"\ntransform = {{ translate = [{x}, 0, 0] }}\n"
            )
        };
        let text = format!(
            "[materials.a]\ncolor = 0.5\nbsdf = {{ type = \"diffuse\" }}\n[materials.b]\ncolor = 0.25\nbsdf = {{ type = \"diffuse\" }}\n{}{}{}",
            triangle("a", 0),
            triangle("a", 2),
            triangle("b", 4)
        );
        let out = export_text(Box::leak(text.into_boxed_str())).unwrap();
        assert_eq!(out.meshes.len(), 1, "one PLY for the three objects");
        assert_eq!(out.xml.matches("<shape type=\"shapegroup\" id=\"mesh_group_0\">").count(), 1, "{}", out.xml);
        assert_eq!(out.xml.matches("<ref id=\"mesh_group_0\"/>").count(), 2, "{}", out.xml);
        assert_eq!(out.xml.matches("s_meshes/000.ply").count(), 2, "the group's shape and the plain one");
        assert!(!out.xml.contains("mesh_group_1"), "material b is used once: a plain shape");
    }

    #[test]
    fn mesh_uvs_follow_each_vertex_in_the_ply() {
        let t = TriangleList {
            positions: vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
            normals: Vec::new(),
            uvs: vec![[0.0, 0.0], [1.0, 0.0], [0.0, 0.25]],
            triangles: vec![[0, 1, 2]],
        };
        let bytes = ply(&t);
        let header_end = bytes.windows(11).position(|w| w == b"end_header\n").unwrap() + 11;
        let header = std::str::from_utf8(&bytes[..header_end]).unwrap();
        assert!(header.contains("property float z\nproperty float u\nproperty float v\n"), "{header}");
        // Vertex 2: x, y, z, u, v as little-endian f32.
        let vertex = &bytes[header_end + 2 * 20..header_end + 3 * 20];
        let v = f32::from_le_bytes(vertex[16..20].try_into().unwrap());
        assert_eq!(v, 0.25);
    }

    #[test]
    fn a_pbr_material_is_the_gltf_plugin() {
        let out = export_text(
            "[[object]]\nshape = \"sphere\"\nmaterial = { color = [0.9, 0.5, 0.1], pbr = { metallic = 0.75, roughness = 0.3 } }\n",
        )
        .unwrap();
        assert!(out.xml.contains("<bsdf type=\"gltf_metallic_roughness\">"), "{}", out.xml);
        assert!(out.xml.contains("<float name=\"metallic\" value=\"0.75\"/>"), "{}", out.xml);
        assert!(!out.xml.contains("twosided"), "the plugin is two-sided itself: {}", out.xml);
    }

    #[test]
    fn absorbing_delta_lobes_are_blended_in_proportion_without_a_black_lobe() {
        // A finish of mirror 0.2 and glass 0.5 (transmit) reflects 0.2 * (1 - 0.5) = 0.1 and
        // transmits 0.5: the blend holds them as 1/6 and 5/6, each tinted by their sum 0.6.
        let out = export_text(
            "[[object]]\nshape = \"sphere\"\nmaterial = { diffuse = 0.0, transmit = 0.5, ior = 1.3, reflection = 0.2 }\n",
        )
        .unwrap();
        assert!(!out.xml.contains("type=\"diffuse\""), "{}", out.xml);
        let blend = out.xml.find("<float name=\"weight\" value=\"").unwrap() + 28;
        let weight: f64 = out.xml[blend..].split('"').next().unwrap().parse().unwrap();
        assert!((weight - 5.0 / 6.0).abs() < 1e-9, "{weight}: {}", out.xml);
        assert!(out.xml.contains("name=\"specular_reflectance\" value=\"0.6, 0.6, 0.6\""), "{}", out.xml);
        assert!(out.xml.contains("name=\"specular_transmittance\" value=\"0.6, 0.6, 0.6\""), "{}", out.xml);
    }

    #[test]
    fn thin_panes_in_the_dark_get_a_dark_environment() {
        let pane = "[[object]]\nshape = \"rectangle\"\nmaterial = { color = 0.8, bsdf = { type = \"thin_dielectric\" }, emission = [1, 1, 1] }\n";
        let lamp = "[[light]]\nposition = [0, 2, 0]\n";
        let dark = |text: &str| {
            let xml = export_text(Box::leak(text.to_string().into_boxed_str())).unwrap().xml;
            let at = xml
                .find("<emitter type=\"constant\">")
                .map(|i| xml[i..].split("</emitter>").next().unwrap().to_string());
            (at, xml)
        };
        let (environment, xml) = dark(&format!("{pane}{lamp}"));
        let environment = environment.unwrap_or_else(|| panic!("no environment in\n{xml}"));
        assert!(environment.contains("value=\"0, 0, 0\""), "{environment}");
        assert!(environment.contains("name=\"sampling_weight\" value=\"0\""), "{environment}");
        // The only emitter but the pane's own area light: sampled (Mitsuba refuses a total
        // weight of 0), which costs nothing.
        let (alone, _) = dark(&format!("[world]\nbackground = 0\n{}", pane.replace(", emission = [1, 1, 1]", "")));
        assert!(alone.is_some_and(|e| !e.contains("sampling_weight")));
        // A lit background is an environment already; opaque scenes need none.
        let (lit, _) = dark(&format!("[world]\nbackground = 0.5\n{pane}"));
        assert!(lit.is_some_and(|e| e.contains("value=\"0.5, 0.5, 0.5\"")));
        let (opaque, _) = dark(&format!("[[object]]\nshape = \"sphere\"\n{lamp}"));
        assert!(opaque.is_none());
    }

    #[test]
    fn wide_filters_sample_the_film_border() {
        let out =
            export_text("[render]\nintegrator = \"path\"\nfilter = { type = \"gaussian\", stddev = 0.5 }\n").unwrap();
        assert!(out.xml.contains("<boolean name=\"sample_border\" value=\"true\"/>"), "{}", out.xml);
        let out = export_text("[render]\nintegrator = \"path\"\n").unwrap();
        assert!(!out.xml.contains("sample_border"), "{}", out.xml);
    }

    #[test]
    fn textures_are_refused_where_mitsubas_uv_is_not_the_shapes() {
        let image = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/textures/tiles16.png");
        let textured = |shape: &str| {
            let text = format!(
                "[[object]]\n{shape}\nmaterial = {{ color = 1.0, texture = \"{image}\", bsdf = {{ type = \"diffuse\" }} }}\n"
            );
            export_text(Box::leak(text.into_boxed_str()))
        };
        for (shape, mitsuba) in [
            ("shape = \"sphere\"", "sphere"),
            ("shape = \"plane\"", "rectangle"),
            ("shape = \"disc\"", "disk"),
            ("shape = \"box\"", "cube"),
            ("shape = \"cylinder\"", "disk"),
            ("shape = \"cylinder\"\nopen = true\ntransform = { scale = [-1, 1, 1] }", "cylinder"),
        ] {
            let error = textured(shape).unwrap_err().to_string();
            assert!(error.contains(&format!("Mitsuba's {mitsuba} has other texture coordinates")), "{shape}: {error}");
            assert!(error.contains("material.texture"), "{error}");
        }
        for shape in ["shape = \"rectangle\"", "shape = \"cylinder\"\nopen = true"] {
            let out = textured(shape).unwrap_or_else(|e| panic!("{shape}: {e}"));
            assert!(out.xml.contains("<texture type=\"bitmap\""), "{shape}: {}", out.xml);
        }
    }

    #[test]
    fn a_spot_whose_radius_passes_its_falloff_has_its_hard_edge_at_the_radius() {
        let out = export_text(
            "[render]\nintegrator = \"path\"\n[[light]]\nkind = \"spot\"\nposition = [0, 1, 0]\npoint_at = [0, 0, 0]\nradius = 50\nfalloff = 20\n",
        )
        .unwrap();
        assert!(out.xml.contains("<float name=\"cutoff_angle\" value=\"50.0\"/>"), "{}", out.xml);
        assert!(out.xml.contains("<float name=\"beam_width\" value=\"50.0\"/>"), "{}", out.xml);
    }
}
