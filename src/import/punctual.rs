//! Cameras and `KHR_lights_punctual` lights of an imported glTF file, used when a mesh object
//! asks for them (`import_camera`, `import_lights`): choosing the camera, and mapping the
//! file's cameras and lights to Prism's [`Camera`] and [`PhotometricLight`], placed by their
//! node's world transform (the node tree of the file under the object's own transform). The
//! mapping, with its units, is documented in `docs/meshes.md`.
//!
//! glTF cameras and spot and directional lights look down their node's local -z with +y up,
//! as Prism's default camera does. Light intensities are photometric, candela for point and
//! spot lights and lux for directional lights, and are kept as the file gives them
//! (`render::lights` converts them to radiometric units).

use std::f64::consts::PI;

use glam::{DAffine3, DVec3};

use super::{CameraProjection, Model, ModelCamera, ModelLight, PunctualKind};
use crate::color::Rgb;
use crate::world::components::{Camera, PhotometricLight, Projection};

/// Which camera of the file `import_camera` asks for.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum CameraChoice {
    /// `true`: the first camera on a node of the imported scene (depth-first node order).
    First,
    /// An index into the file's `cameras` array.
    Index(usize),
    /// The camera with this name, or else the camera on the node with this name.
    Name(String),
}

impl CameraChoice {
    /// The choice written as the value of `import_camera`; `Ok(None)` for `false`.
    pub fn parse(value: &toml::Value) -> Result<Option<Self>, String> {
        match value {
            toml::Value::Boolean(true) => Ok(Some(Self::First)),
            toml::Value::Boolean(false) => Ok(None),
            toml::Value::Integer(i) => match usize::try_from(*i) {
                Ok(i) => Ok(Some(Self::Index(i))),
                Err(_) => Err(format!("camera index {i} is negative")),
            },
            toml::Value::String(s) => Ok(Some(Self::Name(s.clone()))),
            _ => Err("`import_camera` must be true, false, a camera index or a camera name".into()),
        }
    }
}

/// `camera 0 `name` on node `node``: how messages name a camera of `model`.
pub fn describe_camera(model: &Model, camera: &ModelCamera) -> String {
    let mut s = format!("camera {}", camera.index);
    if let Some(name) = &camera.name {
        s.push_str(&format!(" `{name}`"));
    }
    if let Some(name) = model.nodes.get(camera.node).and_then(|n| n.name.as_deref()) {
        s.push_str(&format!(" on node `{name}`"));
    }
    s
}

/// Every camera of `model` with its projection, for messages.
fn list_cameras(model: &Model) -> String {
    let all: Vec<String> = model
        .cameras
        .iter()
        .map(|c| {
            let projection = match c.projection {
                Ok(CameraProjection::Perspective { .. }) => "perspective",
                Ok(CameraProjection::Orthographic { .. }) => "orthographic",
                Err(_) => "invalid",
            };
            format!("{} ({projection})", describe_camera(model, c))
        })
        .collect();
    all.join(", ")
}

/// The names a string `import_camera` can match: camera names, then node names of cameras.
pub fn camera_names(model: &Model) -> Vec<&str> {
    let cameras = model.cameras.iter().filter_map(|c| c.name.as_deref());
    let nodes = model.cameras.iter().filter_map(|c| model.nodes.get(c.node).and_then(|n| n.name.as_deref()));
    let mut names: Vec<&str> = cameras.chain(nodes).collect();
    names.dedup();
    names
}

/// The view of an imported camera that Prism keeps (glTF units: radians, file units).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ImportedView {
    /// A pinhole with this vertical field of view in radians.
    Perspective {
        /// Vertical field of view in radians.
        yfov: f64,
    },
    /// A parallel projection whose viewport is `2 * ymag` file units high (in the camera
    /// node's frame, so the node's world scale applies).
    Orthographic {
        /// Half the viewport's height in the camera node's units.
        ymag: f64,
    },
}

/// The camera `choice` picks, as its position in [`Model::cameras`], with its view; an error
/// for a missing or broken camera (a field of view outside (0, pi), a magnification that is
/// not positive and finite).
pub fn select_camera(model: &Model, choice: &CameraChoice) -> Result<(usize, ImportedView), String> {
    if model.cameras.is_empty() {
        return Err("the file has no camera on a node of its default scene".into());
    }
    let node_name = |c: &ModelCamera| model.nodes.get(c.node).and_then(|n| n.name.as_deref());
    let found = match choice {
        CameraChoice::First => Some(0),
        CameraChoice::Index(i) => model.cameras.iter().position(|c| c.index == *i),
        CameraChoice::Name(name) => model
            .cameras
            .iter()
            .position(|c| c.name.as_deref() == Some(name))
            .or_else(|| model.cameras.iter().position(|c| node_name(c) == Some(name))),
    };
    let Some(position) = found else {
        let what = match choice {
            CameraChoice::First => unreachable!("the list is not empty"),
            CameraChoice::Index(i) => format!("camera {i}"),
            CameraChoice::Name(name) => format!("camera named `{name}` (by camera or node name)"),
        };
        return Err(format!(
            "the file has no {what} on a node of its default scene; its cameras: {}",
            list_cameras(model)
        ));
    };
    let camera = &model.cameras[position];
    match camera.projection {
        Ok(CameraProjection::Perspective { yfov, .. }) => {
            if yfov.is_finite() && yfov > 0.0 && yfov < PI {
                Ok((position, ImportedView::Perspective { yfov }))
            } else {
                Err(format!("{}: yfov {yfov} is not between 0 and pi radians", describe_camera(model, camera)))
            }
        }
        Ok(CameraProjection::Orthographic { xmag, ymag }) => {
            // glTF requires both magnifications to be non-zero; a viewport needs them positive.
            if xmag.is_finite() && ymag.is_finite() && xmag > 0.0 && ymag > 0.0 {
                Ok((position, ImportedView::Orthographic { ymag }))
            } else {
                Err(format!(
                    "{}: xmag {xmag} and ymag {ymag} must be positive and finite",
                    describe_camera(model, camera)
                ))
            }
        }
        Err(ref e) => Err(format!("{}: {e}", describe_camera(model, camera))),
    }
}

/// Prism's camera for a glTF camera whose node has the world transform `world_from_camera`:
/// at the node's origin, looking down its -z with its +y up. A perspective view keeps its
/// vertical field of view (radians in the file, degrees in Prism); an orthographic view is
/// `2 * ymag` high in the node's frame, so `view_height` is that times the length the node's
/// world transform gives its +y. `look_at` is one world unit ahead; the lens (`aperture`,
/// `focal_distance`, the `blur_*` keys) comes from `lens`.
pub fn camera_from_node(world_from_camera: DAffine3, view: ImportedView, lens: &Camera) -> Camera {
    let position = world_from_camera.translation;
    let direction = world_from_camera.transform_vector3(DVec3::NEG_Z).normalize_or_zero();
    let world_up = world_from_camera.transform_vector3(DVec3::Y);
    let up = world_up.normalize_or_zero();
    let lens_keys = Camera {
        aperture: lens.aperture,
        focal_distance: lens.focal_distance,
        blur_variance: lens.blur_variance,
        blur_confidence: lens.blur_confidence,
        blur_min_samples: lens.blur_min_samples,
        ..Camera::default()
    };
    let pose = Camera {
        position: position.to_array(),
        look_at: (position + direction).to_array(),
        up: up.to_array(),
        aspect: None,
        ..lens_keys
    };
    match view {
        ImportedView::Perspective { yfov } => Camera { vfov: yfov.to_degrees(), ..pose },
        ImportedView::Orthographic { ymag } => {
            Camera { projection: Projection::Orthographic, view_height: Some(2.0 * ymag * world_up.length()), ..pose }
        }
    }
}

/// `light 2 `name``: how messages name a light of a file.
pub fn describe_light(light: &ModelLight) -> String {
    match &light.name {
        Some(name) => format!("light {} `{name}`", light.index),
        None => format!("light {}", light.index),
    }
}

/// Checks what Prism needs of a file's light: finite, non-negative colour and intensity, and
/// spot cone angles with 0 <= inner <= outer <= pi/2.
pub fn check_light(light: &ModelLight) -> Result<(), String> {
    let what = describe_light(light);
    if !light.color.iter().all(|c| c.is_finite() && *c >= 0.0) {
        return Err(format!("{what}: colour {:?} must be finite and not negative", light.color));
    }
    if !(light.intensity.is_finite() && light.intensity >= 0.0) {
        return Err(format!("{what}: intensity {} must be finite and not negative", light.intensity));
    }
    if let PunctualKind::Spot { inner_cone_angle: inner, outer_cone_angle: outer } = light.kind
        && !(outer > 0.0 && outer <= PI / 2.0 && inner >= 0.0 && inner <= outer)
    {
        return Err(format!(
            "{what}: spot cone angles inner {inner} and outer {outer} need 0 <= inner <= outer <= pi/2 (radians), outer > 0"
        ));
    }
    Ok(())
}

/// The world's light for a file's light (checked by [`check_light`]) whose node has the world
/// transform `world_from_light`: at the node's origin, shining down its -z, with the file's
/// colour and photometric intensity. `object_scale` is the mesh object's world scale (the cube
/// root of its transform's determinant): file units (metres) times it are world units, so the
/// inverse-square falloff is measured in file units. The node's own scale changes neither the
/// intensity nor the cone (glTF's rule).
pub fn light_from_node(light: &ModelLight, world_from_light: DAffine3, object_scale: f64) -> PhotometricLight {
    let [r, g, b] = light.color;
    PhotometricLight {
        kind: light.kind,
        position: world_from_light.translation,
        direction: world_from_light.transform_vector3(DVec3::NEG_Z).normalize_or(DVec3::NEG_Z),
        color: Rgb::new(r, g, b),
        intensity: light.intensity,
        world_units_per_metre: object_scale,
    }
}

/// The uniform scale of an affine map: the cube root of its determinant's magnitude.
pub fn uniform_scale(m: &DAffine3) -> f64 {
    m.matrix3.determinant().abs().cbrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::import::ModelNode;
    use glam::DQuat;

    fn light(kind: PunctualKind) -> ModelLight {
        ModelLight { node: 0, index: 0, name: None, kind, color: [1.0, 0.5, 0.25], intensity: 10.0, range: None }
    }

    #[test]
    fn lights_keep_the_files_photometric_values() {
        let m = DAffine3::from_translation(DVec3::new(1.0, 2.0, 3.0));
        let l = light_from_node(&light(PunctualKind::Point), m, 2.5);
        assert_eq!(l.kind, PunctualKind::Point);
        assert_eq!(l.position, DVec3::new(1.0, 2.0, 3.0));
        assert_eq!(l.color, Rgb::new(1.0, 0.5, 0.25));
        assert_eq!((l.intensity, l.world_units_per_metre), (10.0, 2.5));
    }

    #[test]
    fn spot_and_directional_lights_shine_down_their_nodes_minus_z() {
        let kind = PunctualKind::Spot { inner_cone_angle: 0.2, outer_cone_angle: 0.4 };
        // Turned 90 degrees about +y and scaled: -z becomes -x, still of unit length.
        let m = DAffine3::from_scale_rotation_translation(
            DVec3::splat(3.0),
            DQuat::from_rotation_y(PI / 2.0),
            DVec3::new(0.0, 5.0, 0.0),
        );
        let l = light_from_node(&light(kind), m, 1.0);
        assert_eq!(l.kind, kind);
        assert!((l.direction - DVec3::NEG_X).length() < 1e-12, "{}", l.direction);
        assert_eq!(l.position, DVec3::new(0.0, 5.0, 0.0));
        let sun = light_from_node(&light(PunctualKind::Directional), DAffine3::from_rotation_x(-PI / 2.0), 2.0);
        assert!((sun.direction - DVec3::NEG_Y).length() < 1e-12, "{}", sun.direction);
        assert_eq!(sun.intensity, 10.0);
    }

    #[test]
    fn bad_lights_are_refused() {
        let mut l = light(PunctualKind::Spot { inner_cone_angle: 0.5, outer_cone_angle: 0.4 });
        assert!(check_light(&l).unwrap_err().contains("cone"));
        l.kind = PunctualKind::Spot { inner_cone_angle: 0.0, outer_cone_angle: 2.0 };
        assert!(check_light(&l).is_err());
        l.kind = PunctualKind::Point;
        assert!(check_light(&l).is_ok());
        l.intensity = -1.0;
        assert!(check_light(&l).unwrap_err().contains("intensity"));
        l.intensity = 1.0;
        l.color[1] = f64::INFINITY;
        assert!(check_light(&l).unwrap_err().contains("colour"));
    }

    fn model_with_cameras() -> Model {
        let node = |name: &str| ModelNode { name: Some(name.into()), parent: None, local: DAffine3::IDENTITY };
        let perspective = Ok(CameraProjection::Perspective { yfov: 0.7, aspect_ratio: Some(1.0) });
        Model {
            nodes: vec![node("ortho node"), node("eye")],
            cameras: vec![
                ModelCamera {
                    node: 0,
                    index: 1,
                    name: Some("top".into()),
                    projection: Ok(CameraProjection::Orthographic { xmag: 1.0, ymag: 1.0 }),
                },
                ModelCamera { node: 1, index: 0, name: None, projection: perspective },
            ],
            ..Model::default()
        }
    }

    #[test]
    fn cameras_are_chosen_by_order_index_or_name() {
        let model = model_with_cameras();
        let first = select_camera(&model, &CameraChoice::First).unwrap();
        assert_eq!(first, (0, ImportedView::Orthographic { ymag: 1.0 }));
        assert_eq!(select_camera(&model, &CameraChoice::Index(0)).unwrap().1, ImportedView::Perspective { yfov: 0.7 });
        assert_eq!(select_camera(&model, &CameraChoice::Name("eye".into())).unwrap().0, 1);
        assert_eq!(select_camera(&model, &CameraChoice::Name("top".into())).unwrap().0, 0);
        assert!(select_camera(&model, &CameraChoice::Index(7)).unwrap_err().contains("no camera 7"));
        assert!(select_camera(&Model::default(), &CameraChoice::First).unwrap_err().contains("no camera"));
        assert_eq!(camera_names(&model), vec!["top", "ortho node", "eye"]);
        assert_eq!(CameraChoice::parse(&toml::Value::Integer(2)), Ok(Some(CameraChoice::Index(2))));
        assert_eq!(CameraChoice::parse(&toml::Value::Boolean(false)), Ok(None));
        assert!(CameraChoice::parse(&toml::Value::Integer(-1)).is_err());
        assert!(CameraChoice::parse(&toml::Value::Float(1.5)).is_err());
    }

    #[test]
    fn cameras_look_down_minus_z_with_y_up() {
        let m = DAffine3::from_rotation_translation(DQuat::from_rotation_y(PI / 2.0), DVec3::new(1.0, 2.0, 3.0));
        let lens = Camera {
            aperture: 0.5,
            focal_distance: Some(4.0),
            blur_variance: Some(1e-3),
            blur_confidence: Some(0.8),
            blur_min_samples: Some(7),
            ..Camera::default()
        };
        let c = camera_from_node(m, ImportedView::Perspective { yfov: 0.5 }, &lens);
        assert_eq!(c.position, [1.0, 2.0, 3.0]);
        let view = DVec3::from_array(c.look_at) - DVec3::from_array(c.position);
        assert!((view - DVec3::NEG_X).length() < 1e-12, "{view}");
        assert!((DVec3::from_array(c.up) - DVec3::Y).length() < 1e-12);
        assert!((c.vfov - 0.5f64.to_degrees()).abs() < 1e-12);
        assert_eq!((c.aperture, c.focal_distance, c.aspect), (0.5, Some(4.0), None));
        assert_eq!((c.blur_variance, c.blur_confidence, c.blur_min_samples), (Some(1e-3), Some(0.8), Some(7)));
        assert_eq!((c.projection, c.view_height), (Projection::Perspective, None));
    }

    #[test]
    fn orthographic_cameras_keep_their_magnification_in_world_units() {
        let m = DAffine3::from_scale_rotation_translation(
            DVec3::splat(3.0),
            DQuat::from_rotation_x(-PI / 2.0),
            DVec3::new(0.0, 10.0, 0.0),
        );
        let c = camera_from_node(m, ImportedView::Orthographic { ymag: 2.0 }, &Camera::default());
        assert_eq!(c.projection, Projection::Orthographic);
        assert!((c.view_height.unwrap() - 12.0).abs() < 1e-12, "{:?}", c.view_height);
        let view = DVec3::from_array(c.look_at) - DVec3::from_array(c.position);
        assert!((view - DVec3::NEG_Y).length() < 1e-12, "{view}");
        let mut model = model_with_cameras();
        model.cameras[0].projection = Ok(CameraProjection::Orthographic { xmag: 1.0, ymag: 0.0 });
        let zero = select_camera(&model, &CameraChoice::First).unwrap_err();
        assert!(zero.contains("ymag 0") && zero.contains("positive"), "{zero}");
    }
}
