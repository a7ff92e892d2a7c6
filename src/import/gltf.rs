//! glTF 2.0 import (`.gltf` with external or data-URI buffers, `.glb`) through the gltf
//! crate. The default scene's node tree becomes [`ModelNode`]s; every triangle primitive
//! (indexed or not; strips and fans converted) becomes a [`ModelPart`] with its material
//! mapped to Prism's. Points and lines are skipped with a warning. Cameras and
//! `KHR_lights_punctual` lights on nodes are recorded ([`ModelCamera`], [`ModelLight`]); the
//! scene decides whether to use them (`mesh::cameras_lights`).
//!
//! The crate validates the JSON; this module checks what it does not: buffer views and
//! accessors inside their buffers, index ranges, node cycles, and finite positions. A
//! broken file is an error naming the file, never a panic.

use std::collections::HashMap;
use std::path::Path;
use std::sync::Arc;

use glam::{DAffine3, DMat4, Vec2, Vec3, Vec4};
use gltf::mesh::Mode;

use super::{
    CameraProjection, ImportError, ImportErrorKind, Model, ModelCamera, ModelLight, ModelNode, ModelPart, PunctualKind,
};
use crate::color::Rgb;
use crate::files::{FileAccess, FileError, FileKind};
use crate::geometry::mesh::{AlphaMask, MeshBuilder, MeshData, MeshError, MeshShape, NormalMap, SurfaceMaps};
use crate::limits::{MAX_GLTF_INSTANCES, MemoryBudget};
use crate::material::{AlphaMode, Emission, Finish, MAX_IOR, Material, MetallicRoughness, SurfaceModel};
use crate::texture::{ColorSpace, TextureRef, TextureStore, Wrap};

/// Deepest node nesting accepted (deeper trees are almost certainly broken files).
const MAX_DEPTH: usize = 256;

/// Reads a glTF or GLB file.
pub fn import(path: &Path, textures: &mut TextureStore) -> Result<Model, ImportError> {
    let err = |kind| ImportError::new(path, kind);
    let access = textures.access().clone();
    let bytes = access.read(path, FileKind::Mesh).map_err(|e| err(ImportErrorKind::File(e)))?;
    // The crate's own validation indexes arrays without checking (a POSITION naming a
    // missing accessor panics), so the JSON is checked first, unvalidated.
    let json = if bytes.starts_with(b"glTF") {
        // The crate subtracts the header's size from its length field unchecked (found by
        // fuzzing: a length below 12 overflowed).
        let length = bytes.get(8..12).map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]));
        if !matches!(length, Some(n) if n >= 12) {
            return Err(err(ImportErrorKind::Invalid("the GLB header's length is shorter than the header".into())));
        }
        gltf::Glb::from_slice(&bytes).map_err(|e| err(ImportErrorKind::Gltf(e)))?.json
    } else {
        std::borrow::Cow::Borrowed(&bytes[..])
    };
    let root =
        gltf::json::Root::from_slice(&json).map_err(|e| err(ImportErrorKind::Gltf(gltf::Error::Deserialize(e))))?;
    check_json(&root).map_err(|m| err(ImportErrorKind::Invalid(m)))?;
    drop((root, json));
    let gltf::Gltf { document, blob } = gltf::Gltf::from_slice(&bytes).map_err(|e| err(ImportErrorKind::Gltf(e)))?;
    drop(bytes);
    let base = path.parent().unwrap_or(Path::new(""));
    let buffers = load_buffers(&document, &access, base, blob).map_err(|e| ImportError::new(path, e))?;
    check_views_and_accessors(&document, &buffers).map_err(|m| err(ImportErrorKind::Invalid(m)))?;
    let canonical = access.resolve(path).map_err(|e| err(ImportErrorKind::File(e)))?;

    let scene =
        document.default_scene().or_else(|| document.scenes().next()).ok_or_else(|| err(ImportErrorKind::NoScene))?;
    let mut importer = Importer {
        path,
        document: &document,
        canonical: &canonical,
        buffers: &buffers,
        textures,
        model: Model::default(),
        meshes: HashMap::new(),
        materials: HashMap::new(),
    };
    for root in scene.nodes() {
        importer.node(root, None, &mut Vec::new())?;
    }
    let mut model = importer.model;
    if model.parts.is_empty() {
        model.warnings.push("no triangles in the default scene: nothing to render".into());
    }
    if document.skins().next().is_some() {
        model.warnings.push("skins are ignored: meshes are rendered in their bind pose".into());
    }
    if document.animations().next().is_some() {
        model.warnings.push("animations are ignored".into());
    }
    Ok(model)
}

/// The accessor types, component types and their description that glTF 2.0 (3.7.2.1)
/// allows for a vertex attribute; `None` for application-specific attributes (`_NAME`).
fn attribute_types(
    semantic: &gltf::json::mesh::Semantic,
) -> Option<(&'static [gltf::json::accessor::Type], &'static [gltf::json::accessor::ComponentType], &'static str)> {
    use gltf::json::accessor::{ComponentType as C, Type as T};
    use gltf::json::mesh::Semantic as S;
    Some(match semantic {
        S::Positions => (&[T::Vec3], &[C::F32], "FLOAT VEC3"),
        S::Normals => (&[T::Vec3], &[C::F32], "FLOAT VEC3"),
        S::Tangents => (&[T::Vec4], &[C::F32], "FLOAT VEC4"),
        S::TexCoords(_) => (&[T::Vec2], &[C::F32, C::U8, C::U16], "FLOAT, UNSIGNED_BYTE or UNSIGNED_SHORT VEC2"),
        S::Colors(_) => {
            (&[T::Vec3, T::Vec4], &[C::F32, C::U8, C::U16], "FLOAT, UNSIGNED_BYTE or UNSIGNED_SHORT VEC3 or VEC4")
        }
        S::Joints(_) => (&[T::Vec4], &[C::U8, C::U16], "UNSIGNED_BYTE or UNSIGNED_SHORT VEC4"),
        S::Weights(_) => (&[T::Vec4], &[C::F32, C::U8, C::U16], "FLOAT, UNSIGNED_BYTE or UNSIGNED_SHORT VEC4"),
        #[allow(unreachable_patterns, reason = "`Extras` exists only with the crate's `extras` feature")]
        _ => return None,
    })
}

/// An attribute's name as glTF writes it (`TEXCOORD_0`).
fn semantic_name(semantic: &gltf::json::mesh::Semantic) -> String {
    use gltf::json::mesh::Semantic as S;
    match semantic {
        S::Positions => "POSITION".into(),
        S::Normals => "NORMAL".into(),
        S::Tangents => "TANGENT".into(),
        S::TexCoords(n) => format!("TEXCOORD_{n}"),
        S::Colors(n) => format!("COLOR_{n}"),
        S::Joints(n) => format!("JOINTS_{n}"),
        S::Weights(n) => format!("WEIGHTS_{n}"),
        #[allow(unreachable_patterns, reason = "`Extras` exists only with the crate's `extras` feature")]
        _ => "an application-specific attribute".into(),
    }
}

/// What the JSON must satisfy before any reader of the crate touches it (the crate panics
/// on some of these): every index names an existing object, images have a source, index
/// accessors are unsigned scalars and every vertex attribute has the accessor type the
/// specification gives it (glTF 2.0, 3.7.2.1).
fn check_json(root: &gltf::json::Root) -> Result<(), String> {
    use gltf::json::accessor::{ComponentType, Type};
    use gltf::json::validation::Checked;
    let views = root.buffer_views.len();
    let accessors = &root.accessors;
    for (i, view) in root.buffer_views.iter().enumerate() {
        if view.buffer.value() >= root.buffers.len() {
            return Err(format!("buffer view {i} names buffer {}, which does not exist", view.buffer.value()));
        }
    }
    for (i, a) in accessors.iter().enumerate() {
        if let Some(v) = a.buffer_view
            && v.value() >= views
        {
            return Err(format!("accessor {i} names buffer view {}, which does not exist", v.value()));
        }
        if !matches!(a.component_type, Checked::Valid(_)) || !matches!(a.type_, Checked::Valid(_)) {
            return Err(format!("accessor {i} has an invalid component type or type"));
        }
        if let Some(sparse) = &a.sparse {
            if sparse.count.0 == 0 || sparse.count.0 > a.count.0 {
                return Err(format!("accessor {i}: sparse count {} is not in 1..={}", sparse.count.0, a.count.0));
            }
            if sparse.indices.buffer_view.value() >= views || sparse.values.buffer_view.value() >= views {
                return Err(format!("accessor {i}: sparse data names a buffer view that does not exist"));
            }
            if !matches!(sparse.indices.component_type, Checked::Valid(_)) {
                return Err(format!("accessor {i}: sparse indices have an invalid component type"));
            }
        }
    }
    let accessor = |i: usize| accessors.get(i).ok_or_else(|| format!("accessor {i} does not exist"));
    for (m, mesh) in root.meshes.iter().enumerate() {
        for (p, primitive) in mesh.primitives.iter().enumerate() {
            let what = format!("mesh {m} primitive {p}");
            for (semantic, index) in &primitive.attributes {
                let a = accessor(index.value()).map_err(|e| format!("{what}: an attribute names {e}"))?;
                let Checked::Valid(semantic) = semantic else { continue };
                // The accessor types the specification allows per attribute (3.7.2.1); the
                // crate's readers assume them (a VEC3 TEXCOORD_0 trips its assertions).
                let Some((types, components, allowed)) = attribute_types(semantic) else { continue };
                let type_ok = matches!(a.type_, Checked::Valid(t) if types.contains(&t));
                let component_ok = matches!(a.component_type, Checked::Valid(c) if components.contains(&c.0));
                if !type_ok || !component_ok {
                    return Err(format!("{what}: {} must be a {allowed} accessor", semantic_name(semantic)));
                }
            }
            if let Some(index) = primitive.indices {
                let a = accessor(index.value()).map_err(|e| format!("{what}: indices name {e}"))?;
                let unsigned = matches!(
                    a.component_type,
                    Checked::Valid(c) if matches!(c.0, ComponentType::U8 | ComponentType::U16 | ComponentType::U32)
                );
                if !unsigned || a.type_ != Checked::Valid(Type::Scalar) {
                    return Err(format!(
                        "{what}: indices must be an UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT SCALAR accessor"
                    ));
                }
            }
        }
    }
    for (i, image) in root.images.iter().enumerate() {
        match (&image.uri, image.buffer_view) {
            (Some(_), None) => {}
            // glTF 2.0, 5.17: `mimeType` is required when `bufferView` is defined (the
            // crate unwraps it; found by fuzzing).
            (None, Some(_)) if image.mime_type.is_none() => {
                return Err(format!(
                    "image {i} has a `bufferView` but no `mimeType`, which the specification requires"
                ));
            }
            (None, Some(v)) if v.value() < views => {}
            (None, Some(v)) => return Err(format!("image {i} names buffer view {}, which does not exist", v.value())),
            _ => return Err(format!("image {i} needs exactly one of `uri` and `bufferView`")),
        }
    }
    for (i, texture) in root.textures.iter().enumerate() {
        if texture.source.value() >= root.images.len() {
            return Err(format!("texture {i} names image {}, which does not exist", texture.source.value()));
        }
    }
    Ok(())
}

/// The bytes of a glTF URI: a `data:` URI decoded, or a relative path (percent-decoded)
/// read through `access`. Other schemes (`file:`, `http:`) are refused.
fn read_uri(uri: &str, access: &FileAccess, base: &Path, kind: FileKind) -> Result<Vec<u8>, ImportErrorKind> {
    if let Some(rest) = uri.strip_prefix("data:") {
        let encoded = rest.split_once(";base64,").map_or(rest, |(_, data)| data);
        return base64::decode(encoded).map_err(|_| ImportErrorKind::Invalid("a data: URI is not valid base64".into()));
    }
    if uri.contains(':') {
        return Err(ImportErrorKind::File(FileError::Uri { uri: uri.to_string() }));
    }
    let decoded = percent_decode(uri).ok_or_else(|| ImportErrorKind::Invalid("a URI has a bad % escape".into()))?;
    let path = access.join(base, &decoded).map_err(ImportErrorKind::File)?;
    access.read(&path, kind).map_err(ImportErrorKind::File)
}

/// `%20` -> ` ` (RFC 3986); `None` when an escape is malformed or the result is not UTF-8.
fn percent_decode(uri: &str) -> Option<String> {
    let bytes = uri.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' {
            let hex = std::str::from_utf8(bytes.get(i + 1..i + 3)?).ok()?;
            out.push(u8::from_str_radix(hex, 16).ok()?);
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    String::from_utf8(out).ok()
}

/// Every buffer's bytes (the GLB blob, data URIs, files beside the glTF), padded to a
/// multiple of four as the crate does, and at least as long as the buffer says.
fn load_buffers(
    document: &gltf::Document,
    access: &FileAccess,
    base: &Path,
    mut blob: Option<Vec<u8>>,
) -> Result<Vec<gltf::buffer::Data>, ImportErrorKind> {
    let mut buffers = Vec::new();
    for buffer in document.buffers() {
        let mut data = match buffer.source() {
            gltf::buffer::Source::Bin => blob.take().ok_or(ImportErrorKind::Gltf(gltf::Error::MissingBlob))?,
            gltf::buffer::Source::Uri(uri) => read_uri(uri, access, base, FileKind::Mesh).map_err(|e| {
                ImportErrorKind::Invalid(format!("cannot load buffers: buffer {}: {e}", buffer.index()))
            })?,
        };
        while data.len() % 4 != 0 {
            data.push(0);
        }
        if data.len() < buffer.length() {
            return Err(ImportErrorKind::Invalid(format!(
                "buffer {} holds {} bytes of the {} it declares",
                buffer.index(),
                data.len(),
                buffer.length()
            )));
        }
        buffers.push(gltf::buffer::Data(data));
    }
    Ok(buffers)
}

/// Decodes image `image` (PNG or JPEG, from a URI or a buffer view) as the crate would,
/// reading files through `access` and checking the decoded size against `budget`.
fn decode_gltf_image(
    image: &gltf::Image,
    access: &FileAccess,
    base: &Path,
    buffers: &[gltf::buffer::Data],
    budget: MemoryBudget,
) -> Result<gltf::image::Data, ImportErrorKind> {
    use image::ImageFormat::{Jpeg, Png};
    let index = image.index() as u32;
    let invalid = |m: String| ImportErrorKind::Invalid(format!("image {index}: {m}"));
    let guess = |bytes: &[u8]| match image::guess_format(bytes) {
        Ok(Png) => Ok(Png),
        Ok(Jpeg) => Ok(Jpeg),
        _ => Err(invalid("not a PNG or JPEG image".into())),
    };
    let by_mime = |mime: Option<&str>, bytes: &[u8]| match mime {
        Some("image/png") => Ok(Png),
        Some("image/jpeg") => Ok(Jpeg),
        _ => guess(bytes),
    };
    let (bytes, format) = match image.source() {
        gltf::image::Source::View { view, mime_type } => {
            let data = &buffers.get(view.buffer().index()).ok_or_else(|| invalid("missing buffer".into()))?.0;
            let end = view.offset().checked_add(view.length()).filter(|&e| e <= data.len());
            let bytes = data[view.offset()..end.ok_or_else(|| invalid("buffer view out of range".into()))?].to_vec();
            let format = by_mime(Some(mime_type), &bytes)?;
            (bytes, format)
        }
        gltf::image::Source::Uri { uri, mime_type } => {
            let bytes = read_uri(uri, access, base, FileKind::Image)?;
            let format = match (uri.strip_prefix("data:"), mime_type) {
                (Some(rest), _) => by_mime(rest.split(';').next(), &bytes)?,
                (None, Some(mime)) => by_mime(Some(mime), &bytes)?,
                (None, None) => match uri.rsplit('.').next() {
                    Some("png") => Png,
                    Some("jpg" | "jpeg") => Jpeg,
                    _ => guess(&bytes)?,
                },
            };
            (bytes, format)
        }
    };
    let name = std::path::PathBuf::from(format!("image {index}.{}", if format == Png { "png" } else { "jpg" }));
    let decoded = crate::texture::decode_image(&name, &bytes, budget).map_err(|e| invalid(e.to_string()))?;
    use gltf::image::Format as F;
    use image::DynamicImage as D;
    let format = match &decoded {
        D::ImageLuma8(_) => F::R8,
        D::ImageLumaA8(_) => F::R8G8,
        D::ImageRgb8(_) => F::R8G8B8,
        D::ImageRgba8(_) => F::R8G8B8A8,
        D::ImageLuma16(_) => F::R16,
        D::ImageLumaA16(_) => F::R16G16,
        D::ImageRgb16(_) => F::R16G16B16,
        D::ImageRgba16(_) => F::R16G16B16A16,
        D::ImageRgb32F(_) => F::R32G32B32FLOAT,
        D::ImageRgba32F(_) => F::R32G32B32A32FLOAT,
        _ => return Err(invalid("unsupported pixel format".into())),
    };
    let (width, height) = (decoded.width(), decoded.height());
    Ok(gltf::image::Data { pixels: decoded.into_bytes(), format, width, height })
}

/// Buffer views inside their buffers and accessors inside their views: the crate's reader
/// slices without checking some of these, and silently stops early on others.
fn check_views_and_accessors(document: &gltf::Document, buffers: &[gltf::buffer::Data]) -> Result<(), String> {
    let view_len = |view: &gltf::buffer::View| -> Result<usize, String> {
        let buffer = buffers.get(view.buffer().index()).ok_or("a buffer view names a missing buffer")?;
        let end = view.offset().checked_add(view.length()).ok_or("buffer view size overflows")?;
        if end > buffer.len() {
            return Err(format!(
                "buffer view {} (bytes {}..{end}) runs past the end of buffer {} ({} bytes)",
                view.index(),
                view.offset(),
                view.buffer().index(),
                buffer.len()
            ));
        }
        Ok(view.length())
    };
    for view in document.views() {
        view_len(&view)?;
    }
    for accessor in document.accessors() {
        let count = accessor.count();
        if count == 0 {
            return Err(format!("accessor {} has no elements", accessor.index()));
        }
        let size = accessor.size();
        if let Some(view) = accessor.view() {
            let stride = view.stride().unwrap_or(size);
            if stride < size {
                return Err(format!(
                    "accessor {}: stride {stride} is smaller than its element ({size} bytes)",
                    accessor.index()
                ));
            }
            let end = (count - 1)
                .checked_mul(stride)
                .and_then(|x| x.checked_add(size))
                .and_then(|x| x.checked_add(accessor.offset()))
                .ok_or_else(|| format!("accessor {} size overflows", accessor.index()))?;
            if end > view_len(&view)? {
                return Err(format!(
                    "accessor {} needs {end} bytes of buffer view {}, which has {}",
                    accessor.index(),
                    view.index(),
                    view.length()
                ));
            }
        }
        if let Some(sparse) = accessor.sparse() {
            let n = sparse.count();
            let indices = sparse.indices();
            let values = sparse.values();
            let overflow = || format!("accessor {}: sparse size overflows", accessor.index());
            let index_end = n
                .checked_mul(indices.index_type().size())
                .and_then(|x| x.checked_add(indices.offset()))
                .ok_or_else(overflow)?;
            let value_end = n.checked_mul(size).and_then(|x| x.checked_add(values.offset())).ok_or_else(overflow)?;
            if n == 0 || index_end > view_len(&indices.view())? || value_end > view_len(&values.view())? {
                return Err(format!("accessor {}: sparse data runs past its buffer view", accessor.index()));
            }
            // Indices strictly increasing and inside the accessor (3.6.2.3).
            let view = indices.view();
            let data = &buffers[view.buffer().index()].0[view.offset() + indices.offset()..];
            let width = indices.index_type().size();
            let mut last: Option<u64> = None;
            for k in 0..n {
                let b = &data[k * width..(k + 1) * width];
                let i = match width {
                    1 => u64::from(b[0]),
                    2 => u64::from(u16::from_le_bytes([b[0], b[1]])),
                    _ => u64::from(u32::from_le_bytes([b[0], b[1], b[2], b[3]])),
                };
                if i >= count as u64 || last.is_some_and(|l| i <= l) {
                    return Err(format!(
                        "accessor {}: sparse index {k} is {i}; indices must increase and stay below {count}",
                        accessor.index()
                    ));
                }
                last = Some(i);
            }
        }
    }
    Ok(())
}

struct Importer<'a> {
    path: &'a Path,
    document: &'a gltf::Document,
    canonical: &'a Path,
    buffers: &'a [gltf::buffer::Data],
    textures: &'a mut TextureStore,
    model: Model,
    /// (mesh, primitive) -> geometry (a mesh used by several nodes is built once).
    meshes: HashMap<(usize, usize), Option<Arc<MeshData>>>,
    /// material index (None = default) -> mapped material and maps.
    materials: HashMap<Option<usize>, (Arc<Material>, SurfaceMaps, Option<String>)>,
}

impl Importer<'_> {
    /// A broken-structure error about this file.
    fn err(&self, message: String) -> ImportError {
        ImportError::new(self.path, ImportErrorKind::Invalid(message))
    }

    fn node(&mut self, node: gltf::Node, parent: Option<usize>, stack: &mut Vec<usize>) -> Result<(), ImportError> {
        if stack.contains(&node.index()) {
            let chain: Vec<String> =
                stack.iter().chain(std::iter::once(&node.index())).map(|i| i.to_string()).collect();
            return Err(self.err(format!("the node tree has a cycle: nodes {}", chain.join(" -> "))));
        }
        if stack.len() >= MAX_DEPTH {
            return Err(self.err(format!("the node tree is deeper than {MAX_DEPTH} levels")));
        }
        let columns = node.transform().matrix();
        let m = DMat4::from_cols_array_2d(&columns.map(|c| c.map(f64::from)));
        let local = DAffine3::from_mat4(m);
        if !local.matrix3.is_finite() || !local.translation.is_finite() {
            return Err(self.err(format!("node {} has a non-finite transform", node.index())));
        }
        if local.matrix3.determinant().abs() < 1e-18 {
            // Scale 0 is how glTF files hide things: drop the subtree.
            self.model.warnings.push(format!(
                "node {} has a singular transform (scale 0); it and its children are skipped",
                node.index()
            ));
            return Ok(());
        }
        let index = self.model.nodes.len();
        if index >= MAX_GLTF_INSTANCES {
            return Err(self.err(format!(
                "the node graph expands to more than {MAX_GLTF_INSTANCES} node instances (nodes reused as \
                 children are counted each time)"
            )));
        }
        self.model.nodes.push(ModelNode { name: node.name().map(str::to_string), parent, local });
        if let Some(mesh) = node.mesh() {
            for primitive in mesh.primitives() {
                self.primitive(index, &mesh, &primitive)?;
            }
        }
        if let Some(camera) = node.camera() {
            let projection = self.projection(camera.index());
            self.model.cameras.push(ModelCamera {
                node: index,
                index: camera.index(),
                name: camera.name().map(str::to_string),
                projection,
            });
        }
        if let Some(light) = node.light() {
            let kind = match light.kind() {
                gltf::khr_lights_punctual::Kind::Point => PunctualKind::Point,
                gltf::khr_lights_punctual::Kind::Directional => PunctualKind::Directional,
                gltf::khr_lights_punctual::Kind::Spot { inner_cone_angle, outer_cone_angle } => PunctualKind::Spot {
                    inner_cone_angle: f64::from(inner_cone_angle),
                    outer_cone_angle: f64::from(outer_cone_angle),
                },
            };
            self.model.lights.push(ModelLight {
                node: index,
                index: light.index(),
                name: light.name().map(str::to_string),
                kind,
                color: light.color().map(f64::from),
                intensity: f64::from(light.intensity()),
                range: light.range().map(f64::from),
            });
        }
        stack.push(node.index());
        for child in node.children() {
            self.node(child, Some(index), stack)?;
        }
        stack.pop();
        Ok(())
    }

    /// Camera `index`'s projection, read from the JSON (the crate's accessor panics when the
    /// `type` and the parameters disagree).
    fn projection(&self, index: usize) -> Result<CameraProjection, String> {
        use gltf::json::camera::Type;
        use gltf::json::validation::Checked;
        let camera = self.document.as_json().cameras.get(index).ok_or("the camera does not exist")?;
        match (&camera.type_, &camera.perspective, &camera.orthographic) {
            (Checked::Valid(Type::Perspective), Some(p), _) => Ok(CameraProjection::Perspective {
                yfov: f64::from(p.yfov),
                aspect_ratio: p.aspect_ratio.map(f64::from),
            }),
            (Checked::Valid(Type::Orthographic), _, Some(o)) => {
                Ok(CameraProjection::Orthographic { xmag: f64::from(o.xmag), ymag: f64::from(o.ymag) })
            }
            (Checked::Valid(Type::Perspective), None, _) => Err("type `perspective` without `perspective`".into()),
            (Checked::Valid(Type::Orthographic), _, None) => Err("type `orthographic` without `orthographic`".into()),
            (Checked::Invalid, _, _) => Err("unknown camera type".into()),
        }
    }

    fn primitive(&mut self, node: usize, mesh: &gltf::Mesh, primitive: &gltf::Primitive) -> Result<(), ImportError> {
        let key = (mesh.index(), primitive.index());
        let data = match self.meshes.get(&key) {
            Some(d) => d.clone(),
            None => {
                let d = self.geometry(mesh, primitive)?;
                self.meshes.insert(key, d.clone());
                d
            }
        };
        let Some(data) = data else { return Ok(()) };
        if self.model.parts.len() >= MAX_GLTF_INSTANCES {
            return Err(self.err(format!("the node graph places more than {MAX_GLTF_INSTANCES} mesh primitives")));
        }
        let material_key = primitive.material().index();
        if !self.materials.contains_key(&material_key) {
            let mapped = self.material(&primitive.material())?;
            self.materials.insert(material_key, mapped);
        }
        let (material, maps, name) = self.materials[&material_key].clone();
        self.model.parts.push(ModelPart {
            node,
            shape: Arc::new(MeshShape::with_maps(data, maps)),
            material,
            material_name: name,
        });
        Ok(())
    }

    /// The triangles of a primitive; `None` (with a warning) for points, lines and
    /// primitives without positions.
    fn geometry(
        &mut self,
        mesh: &gltf::Mesh,
        primitive: &gltf::Primitive,
    ) -> Result<Option<Arc<MeshData>>, ImportError> {
        let what = format!("mesh {} primitive {}", mesh.index(), primitive.index());
        let mode = primitive.mode();
        if !matches!(mode, Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan) {
            self.model.warnings.push(format!("{what}: {mode:?} primitives are not rendered; skipped"));
            return Ok(None);
        }
        let buffers = self.buffers;
        let reader = primitive.reader(|b| buffers.get(b.index()).map(|d| &d.0[..]));
        let Some(positions) = reader.read_positions() else {
            self.model.warnings.push(format!("{what}: no POSITION attribute; skipped"));
            return Ok(None);
        };
        let positions: Vec<Vec3> = positions.map(Vec3::from).collect();
        let n = positions.len();
        let count_of = |semantic: &gltf::Semantic| primitive.get(semantic).map(|a| a.count());
        if let Some(expected) = count_of(&gltf::Semantic::Positions)
            && expected != n
        {
            return Err(self.err(format!("{what}: POSITION has {n} readable values of {expected}")));
        }
        let attribute = |semantic: gltf::Semantic, len: usize| -> Result<bool, ImportError> {
            match count_of(&semantic) {
                Some(c) if c != n => Err(self.err(format!("{what}: {semantic:?} has {c} values for {n} positions"))),
                Some(_) if len != n => Err(self.err(format!("{what}: {semantic:?} could not be read"))),
                Some(_) => Ok(true),
                None => Ok(false),
            }
        };
        let normals: Vec<Vec3> = reader.read_normals().map(|it| it.map(Vec3::from).collect()).unwrap_or_default();
        let normals = if attribute(gltf::Semantic::Normals, normals.len())? { normals } else { Vec::new() };
        let uvs: Vec<Vec2> =
            reader.read_tex_coords(0).map(|it| it.into_f32().map(Vec2::from).collect()).unwrap_or_default();
        let uvs = if attribute(gltf::Semantic::TexCoords(0), uvs.len())? { uvs } else { Vec::new() };
        let tangents: Vec<Vec4> = reader.read_tangents().map(|it| it.map(Vec4::from).collect()).unwrap_or_default();
        let tangents = if attribute(gltf::Semantic::Tangents, tangents.len())? { tangents } else { Vec::new() };

        let indices: Vec<u32> = match reader.read_indices() {
            Some(it) => {
                let indices: Vec<u32> = it.into_u32().collect();
                if let Some(expected) = primitive.indices().map(|a| a.count())
                    && indices.len() != expected
                {
                    return Err(
                        self.err(format!("{what}: indices could not be read ({} of {expected})", indices.len()))
                    );
                }
                if let Some((k, &i)) = indices.iter().enumerate().find(|&(_, &i)| i as usize >= n) {
                    return Err(self.err(format!("{what}: index {k} is {i}, but there are only {n} vertices")));
                }
                indices
            }
            None => (0..n as u32).collect(),
        };
        let triangles = assemble(mode, &indices);
        if let Some(i) = positions.iter().position(|p| !p.is_finite()) {
            return Err(self.err(format!("{what}: vertex {i} has a non-finite position {:?}", positions[i].to_array())));
        }
        if triangles.is_empty() {
            self.model.warnings.push(format!("{what}: no triangles; skipped"));
            return Ok(None);
        }
        let builder = MeshBuilder { positions, normals, uvs, tangents, triangles };
        let count = builder.triangles.len();
        self.textures
            .reserve(|| format!("{what}: {count} triangles with their BVH"), builder.estimate_bytes())
            .map_err(|e| ImportError::new(self.path, ImportErrorKind::OverBudget(e)))?;
        match builder.build_within(MemoryBudget::UNLIMITED) {
            Ok(d) => Ok(Some(Arc::new(d))),
            Err(e @ MeshError::NoTriangles) => {
                self.model.warnings.push(format!("{what}: {e}; skipped"));
                Ok(None)
            }
            Err(source) => Err(ImportError::new(self.path, ImportErrorKind::Mesh { part: what, source })),
        }
    }

    /// The texture a material's texture info names, if it names one.
    fn texture_info(
        &mut self,
        info: Option<gltf::texture::Info>,
        space: ColorSpace,
    ) -> Result<Option<TextureRef>, ImportError> {
        info.map(|info| self.texture(info.texture(), info.tex_coord(), info.texture_transform(), space)).transpose()
    }

    fn texture(
        &mut self,
        texture: gltf::Texture,
        tex_coord: u32,
        transform: Option<gltf::texture::TextureTransform>,
        space: ColorSpace,
    ) -> Result<TextureRef, ImportError> {
        if tex_coord != 0 {
            self.model
                .warnings
                .push(format!("texture {} uses TEXCOORD_{tex_coord}; TEXCOORD_0 is used instead", texture.index()));
        }
        let image = texture.source();
        let index = image.index() as u32;
        let (path, buffers) = (self.path, self.buffers);
        let base = path.parent().unwrap_or(Path::new(""));
        let (access, budget) = (self.textures.access().clone(), self.textures.budget());
        let loaded = self.textures.load_embedded(self.canonical, index, space, || {
            let data = decode_gltf_image(&image, &access, base, buffers, budget)?;
            rgba8(&data).ok_or(ImportErrorKind::PixelFormat { index, format: data.format })
        });
        let loaded = loaded.map_err(|kind| ImportError::new(path, kind))?;
        let sampler = texture.sampler();
        let wrap = |m: gltf::texture::WrappingMode| match m {
            gltf::texture::WrappingMode::ClampToEdge => Wrap::Clamp,
            gltf::texture::WrappingMode::MirroredRepeat => Wrap::Mirror,
            gltf::texture::WrappingMode::Repeat => Wrap::Repeat,
        };
        let mut r = TextureRef::new(self.canonical.display().to_string());
        r.image = Some(index);
        r.wrap = [wrap(sampler.wrap_s()), wrap(sampler.wrap_t())];
        if let Some(t) = transform {
            r.offset = t.offset().map(f64::from);
            r.scale = t.scale().map(f64::from);
            r.rotation = f64::from(t.rotation()).to_degrees();
        }
        r.texture = Some(loaded);
        Ok(r)
    }

    /// glTF metallic-roughness as written (see `docs/meshes.md`), factors clamped to glTF's
    /// 0..1; the emission is `emissiveFactor` times `KHR_materials_emissive_strength`. A
    /// `KHR_materials_pbrSpecularGlossiness` material is converted as `KHR_materials_specular`
    /// describes: its diffuse as the base colour, metallic 0, roughness 1 - glossiness, and
    /// its specular colour as the F0 of a dielectric of ior 0 (a Fresnel rising from the
    /// colour to 1).
    fn material(&mut self, m: &gltf::Material) -> Result<(Arc<Material>, SurfaceMaps, Option<String>), ImportError> {
        let pbr = m.pbr_metallic_roughness();
        let specular_glossiness = m.pbr_specular_glossiness();
        let (base_factor, base_texture) = match &specular_glossiness {
            Some(sg) => (sg.diffuse_factor(), sg.diffuse_texture()),
            None => (pbr.base_color_factor(), pbr.base_color_texture()),
        };
        let [r, g, b, alpha] = base_factor.map(f64::from);
        let mut finish = Finish { color: Rgb::new(r, g, b), ..Finish::default() };
        let mut maps = SurfaceMaps::default();
        finish.texture = self.texture_info(base_texture.clone(), ColorSpace::Srgb)?;
        let mut params = MetallicRoughness {
            metallic_roughness_texture: None,
            alpha_mode: AlphaMode::Opaque,
            alpha,
            ..MetallicRoughness::core(
                finish,
                f64::from(pbr.metallic_factor()).clamp(0.0, 1.0),
                f64::from(pbr.roughness_factor()).clamp(0.0, 1.0),
            )
        };
        params.metallic_roughness_texture = self.texture_info(pbr.metallic_roughness_texture(), ColorSpace::Linear)?;
        self.material_extensions(m, &mut params)?;
        if let Some(sg) = specular_glossiness {
            let [r, g, b] = sg.specular_factor().map(|c| f64::from(c).max(0.0));
            params.metallic = 0.0;
            params.metallic_roughness_texture = None;
            params.roughness = (1.0 - f64::from(sg.glossiness_factor())).clamp(0.0, 1.0);
            (params.ior, params.specular, params.specular_color) = (0.0, 1.0, Rgb::new(r, g, b));
            let info = sg.specular_glossiness_texture();
            params.specular_color_texture = self.texture_info(info.clone(), ColorSpace::Srgb)?;
            params.glossiness_texture = self.texture_info(info, ColorSpace::Linear)?;
        }
        let strength = f64::from(m.emissive_strength().unwrap_or(1.0));
        let [er, eg, eb] = m.emissive_factor().map(|c| f64::from(c) * strength);
        let mut emission = Emission { radiance: Rgb::new(er, eg, eb), ..Emission::default() };
        emission.texture = self.texture_info(m.emissive_texture(), ColorSpace::Srgb)?;
        if let Some(normal) = m.normal_texture() {
            let t = self.texture(normal.texture(), normal.tex_coord(), None, ColorSpace::Linear)?;
            maps.normal_map = Some(NormalMap { texture: t, scale: f64::from(normal.scale()), height: false });
        }
        match m.alpha_mode() {
            gltf::material::AlphaMode::Opaque => {}
            gltf::material::AlphaMode::Mask => {
                params.alpha_mode = AlphaMode::Mask { cutoff: f64::from(m.alpha_cutoff().unwrap_or(0.5)) };
                let texture = self.texture_info(base_texture.clone(), ColorSpace::Linear)?;
                maps.alpha_mask =
                    Some(AlphaMask { texture, factor: alpha as f32, cutoff: m.alpha_cutoff().unwrap_or(0.5) });
            }
            gltf::material::AlphaMode::Blend => {
                params.alpha_mode = AlphaMode::Blend;
                if base_texture.is_some() {
                    self.model.warnings.push(format!(
                        "material {}: alpha BLEND uses the factor's alpha only, not the texture's",
                        m.index().map_or("default".into(), |i| i.to_string())
                    ));
                }
            }
        }
        let material =
            Material { surface: SurfaceModel::MetallicRoughness(Box::new(params)), emission, ..Material::default() };
        if let Err((key, message)) = material.check() {
            let material = m.index().map_or("default".into(), |i| i.to_string());
            return Err(ImportError::new(self.path, ImportErrorKind::Material { material, key, message }));
        }
        Ok((Arc::new(material), maps, m.name().map(str::to_string)))
    }

    /// `KHR_materials_ior`, `KHR_materials_specular`, `KHR_materials_transmission` and
    /// `KHR_materials_clearcoat` (read from the extension's JSON: the crate has no type for
    /// it) into `params`; factors clamped to 0..1 as the core's are (the specular colour only
    /// to at least 0: it may exceed 1). Not read, with a warning: `KHR_materials_volume` (the
    /// transmission stays thin-walled), the clear coat's normal texture and transforms of
    /// the clear coat's textures.
    fn material_extensions(&mut self, m: &gltf::Material, params: &mut MetallicRoughness) -> Result<(), ImportError> {
        let name = || m.index().map_or("default".into(), |i| i.to_string());
        if let Some(ior) = m.ior().map(f64::from) {
            // The extension allows 0 and anything from 1 up; Prism's dielectrics stop at
            // MAX_IOR, and a file is not refused for what it may say.
            params.ior = if ior == 0.0 || (1.0..=MAX_IOR).contains(&ior) {
                ior
            } else {
                let used = if ior > MAX_IOR { MAX_IOR } else { 1.5 };
                self.model.warnings.push(format!(
                    "material {}: KHR_materials_ior {ior} is outside 0 or 1..{MAX_IOR}; {used} is used",
                    name()
                ));
                used
            };
        }
        if let Some(s) = m.specular() {
            params.specular = f64::from(s.specular_factor()).clamp(0.0, 1.0);
            let [r, g, b] = s.specular_color_factor().map(|c| f64::from(c).max(0.0));
            params.specular_color = Rgb::new(r, g, b);
            params.specular_texture = self.texture_info(s.specular_texture(), ColorSpace::Linear)?;
            params.specular_color_texture = self.texture_info(s.specular_color_texture(), ColorSpace::Srgb)?;
        }
        if let Some(t) = m.transmission() {
            params.transmission = f64::from(t.transmission_factor()).clamp(0.0, 1.0);
            params.transmission_texture = self.texture_info(t.transmission_texture(), ColorSpace::Linear)?;
        }
        if m.volume().is_some_and(|v| v.thickness_factor() > 0.0) {
            self.model.warnings.push(format!(
                "material {}: KHR_materials_volume is not read: its transmission is thin-walled (no refraction, no attenuation)",
                name()
            ));
        }
        let Some(coat) = m.extension_value("KHR_materials_clearcoat") else { return Ok(()) };
        let factor = |key: &str, default: f64| coat.get(key).and_then(gltf::json::Value::as_f64).unwrap_or(default);
        params.clearcoat = factor("clearcoatFactor", 0.0).clamp(0.0, 1.0);
        params.clearcoat_roughness = factor("clearcoatRoughnessFactor", 0.0).clamp(0.0, 1.0);
        let slots = [
            ("clearcoatTexture", "KHR_materials_clearcoat.clearcoatTexture", &mut params.clearcoat_texture),
            (
                "clearcoatRoughnessTexture",
                "KHR_materials_clearcoat.clearcoatRoughnessTexture",
                &mut params.clearcoat_roughness_texture,
            ),
        ];
        for (key, error_key, slot) in slots {
            let Some(info) = coat.get(key) else { continue };
            let texture = info
                .get("index")
                .and_then(gltf::json::Value::as_u64)
                .and_then(|i| self.document.textures().nth(usize::try_from(i).ok()?))
                .ok_or_else(|| {
                    let message = format!("names no texture of the file: {}", shown_json(info));
                    ImportError::new(self.path, ImportErrorKind::Material { material: name(), key: error_key, message })
                })?;
            if info.get("extensions").is_some() {
                self.model.warnings.push(format!(
                    "material {}: the extensions of KHR_materials_clearcoat's {key} (a texture transform) are not read",
                    name()
                ));
            }
            let tex_coord = info.get("texCoord").and_then(gltf::json::Value::as_u64).unwrap_or(0);
            *slot =
                Some(self.texture(texture, u32::try_from(tex_coord).unwrap_or(u32::MAX), None, ColorSpace::Linear)?);
        }
        if coat.get("clearcoatNormalTexture").is_some() {
            self.model
                .warnings
                .push(format!("material {}: KHR_materials_clearcoat's normal texture is not read", name()));
        }
        Ok(())
    }
}

/// A JSON value for a message: at most 80 characters.
fn shown_json(value: &gltf::json::Value) -> String {
    let text = value.to_string();
    if text.chars().count() <= 80 { text } else { format!("{}...", text.chars().take(77).collect::<String>()) }
}

/// Triangles from a triangle list, strip or fan (glTF 2.0 section 3.7.2.1 winding rules).
pub fn assemble(mode: Mode, indices: &[u32]) -> Vec<[u32; 3]> {
    match mode {
        Mode::Triangles => indices.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect(),
        Mode::TriangleStrip => (0..indices.len().saturating_sub(2))
            .map(|i| {
                if i % 2 == 0 {
                    [indices[i], indices[i + 1], indices[i + 2]]
                } else {
                    [indices[i + 1], indices[i], indices[i + 2]]
                }
            })
            .collect(),
        Mode::TriangleFan => {
            (1..indices.len().saturating_sub(1)).map(|i| [indices[i], indices[i + 1], indices[0]]).collect()
        }
        _ => Vec::new(),
    }
}

/// Decoded glTF image data as RGBA8 texels.
fn rgba8(data: &gltf::image::Data) -> Option<(usize, usize, Vec<[u8; 4]>)> {
    use gltf::image::Format as F;
    let (w, h) = (data.width as usize, data.height as usize);
    let p = &data.pixels;
    let u16_at = |i: usize| (u16::from_le_bytes([p[2 * i], p[2 * i + 1]]) >> 8) as u8;
    let f32_at = |i: usize| {
        let v = f32::from_le_bytes([p[4 * i], p[4 * i + 1], p[4 * i + 2], p[4 * i + 3]]);
        (v.clamp(0.0, 1.0) * 255.0 + 0.5) as u8
    };
    let (channels, get): (usize, &dyn Fn(usize) -> u8) = match data.format {
        F::R8 => (1, &|i| p[i]),
        F::R8G8 => (2, &|i| p[i]),
        F::R8G8B8 => (3, &|i| p[i]),
        F::R8G8B8A8 => (4, &|i| p[i]),
        F::R16 => (1, &u16_at),
        F::R16G16 => (2, &u16_at),
        F::R16G16B16 => (3, &u16_at),
        F::R16G16B16A16 => (4, &u16_at),
        F::R32G32B32FLOAT => (3, &f32_at),
        F::R32G32B32A32FLOAT => (4, &f32_at),
    };
    let bytes_per = match data.format {
        F::R8 | F::R8G8 | F::R8G8B8 | F::R8G8B8A8 => 1,
        F::R16 | F::R16G16 | F::R16G16B16 | F::R16G16B16A16 => 2,
        _ => 4,
    };
    if w == 0 || h == 0 || p.len() < w * h * channels * bytes_per {
        return None;
    }
    let texels = (0..w * h)
        .map(|t| {
            let c = |k: usize| get(t * channels + k);
            match channels {
                1 => [c(0), c(0), c(0), 255],
                2 => [c(0), c(0), c(0), c(1)],
                3 => [c(0), c(1), c(2), 255],
                _ => [c(0), c(1), c(2), c(3)],
            }
        })
        .collect();
    Some((w, h, texels))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strips_and_fans_keep_winding() {
        assert_eq!(assemble(Mode::TriangleStrip, &[0, 1, 2, 3]), vec![[0, 1, 2], [2, 1, 3]]);
        assert_eq!(assemble(Mode::TriangleFan, &[0, 1, 2, 3]), vec![[1, 2, 0], [2, 3, 0]]);
        assert_eq!(assemble(Mode::Triangles, &[0, 1, 2, 3]), vec![[0, 1, 2]]);
        assert!(assemble(Mode::TriangleStrip, &[0, 1]).is_empty());
        assert!(assemble(Mode::Lines, &[0, 1, 2]).is_empty());
    }
}
