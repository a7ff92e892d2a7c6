//! Wavefront OBJ + MTL import through tobj. tobj parses (negative indices, groups, objects,
//! `usemtl`, MTL files); polygons are triangulated here by ear clipping (tobj's own
//! triangulation is a fan, wrong for concave faces). One part per material: groups and
//! objects that share a material are merged. Errors name the file and, where tobj's error
//! can be traced to one, the line.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use glam::{DAffine3, DVec3, Vec2, Vec3};

use super::triangulate::triangulate;
use super::{ImportError, ImportErrorKind, ImportOptions, Model, ModelNode, ModelPart};
use crate::color::Rgb;
use crate::files::{FileAccess, FileError, FileKind, shown_path};
use crate::geometry::mesh::{MeshBuilder, MeshError, MeshShape, NormalMap, SurfaceMaps};
use crate::limits::MemoryBudget;
use crate::material::{Emission, Material, Mtl, SurfaceModel};
use crate::texture::{ColorSpace, TextureRef, TextureStore};

/// Reads an OBJ file and its MTL files.
pub fn import(path: &Path, options: &ImportOptions, textures: &mut TextureStore) -> Result<Model, ImportError> {
    let access = textures.access().clone();
    let bytes = access.read(path, FileKind::Mesh).map_err(|e| ImportError::new(path, ImportErrorKind::File(e)))?;
    // UTF-16 and binary files have NUL bytes; other stray bytes (Latin-1 names) are kept
    // as replacement characters, as they only ever appear in names and comments.
    if let Some(at) = bytes.iter().position(|&b| b == 0) {
        let line = bytes[..at].iter().filter(|&&b| b == b'\n').count() + 1;
        return Err(ImportError::new(path, ImportErrorKind::NotText).at_line(Some(line)));
    }
    let text = String::from_utf8_lossy(&bytes);
    let text: &str = &text;
    let dir = path.parent().unwrap_or(Path::new("")).to_path_buf();
    let load_options =
        tobj::LoadOptions { single_index: false, triangulate: false, ignore_points: true, ignore_lines: true };
    check_face_indices(text)
        .map_err(|(line, message)| ImportError::new(path, ImportErrorKind::Invalid(message)).at_line(Some(line)))?;
    let mut reader = std::io::BufReader::new(text.as_bytes());
    let mut warnings = Vec::new();
    let mtl_errors = std::cell::RefCell::new(Vec::new());
    let denied = std::cell::RefCell::new(None);
    let (models, materials) = tobj::load_obj_buf(&mut reader, &load_options, |mtl| {
        let result = load_library(&access, &dir, mtl);
        match result {
            Ok(library) => library,
            Err(e) => {
                if let LibraryError::File(f) = &e
                    && f.is_sandbox()
                {
                    denied.borrow_mut().get_or_insert(e.to_string());
                } else {
                    mtl_errors.borrow_mut().push(format!("{e}; using default materials"));
                }
                // One bad library must not drop the others' materials.
                empty_library()
            }
        }
    })
    .map_err(|e| {
        let line = error_line(text, &e);
        ImportError::new(path, ImportErrorKind::Obj(e)).at_line(line)
    })?;
    if let Some(message) = denied.into_inner() {
        return Err(ImportError::new(path, ImportErrorKind::Invalid(message)));
    }
    warnings.extend(mtl_errors.into_inner());
    let materials = materials.unwrap_or_default();

    let mut builders: HashMap<Option<usize>, PartBuilder> = HashMap::new();
    for (model_index, model) in models.iter().enumerate() {
        let mesh = &model.mesh;
        add_model(model_index, mesh, builders.entry(mesh.material_id.filter(|&i| i < materials.len())).or_default())
            .map_err(|message| {
                ImportError::new(path, ImportErrorKind::Invalid(format!("object `{}`: {message}", model.name)))
            })?;
    }
    if builders.values().all(|b| b.builder.triangles.is_empty()) {
        warnings.push("no faces: nothing to render (points and lines are skipped)".into());
    }
    let mut keys: Vec<Option<usize>> = builders.keys().copied().collect();
    keys.sort();
    let mut parts = Vec::new();
    for key in keys {
        let mut part = builders.remove(&key).expect("key from the map");
        if part.builder.triangles.is_empty() {
            continue;
        }
        if part.builder.normals.is_empty()
            && let Some(angle) = options.smooth_angle
        {
            smooth(&mut part, angle);
        }
        let material = key.and_then(|i| materials.get(i));
        let part_name =
            material.map_or_else(|| "faces without a material".into(), |m| format!("material `{}`", m.name));
        let count = part.builder.triangles.len();
        textures
            .reserve(|| format!("{part_name}: {count} triangles with their BVH"), part.builder.estimate_bytes())
            .map_err(|e| ImportError::new(path, ImportErrorKind::OverBudget(e)))?;
        let data = match part.builder.build_within(MemoryBudget::UNLIMITED) {
            Ok(d) => Arc::new(d),
            Err(MeshError::NoTriangles) => {
                warnings.push(format!("{part_name}: only zero-area faces; skipped"));
                continue;
            }
            Err(source) => {
                let line = match source {
                    MeshError::NonFinitePosition { .. } => nonfinite_line(text),
                    _ => None,
                };
                return Err(ImportError::new(path, ImportErrorKind::Mesh { part: part_name, source }).at_line(line));
            }
        };
        let (material, maps, name) = match material {
            Some(m) => {
                let (material, maps) = map_material(m, path, textures, &mut warnings);
                (material, maps, Some(m.name.clone()))
            }
            None => (Material::default(), SurfaceMaps::default(), None),
        };
        parts.push(ModelPart {
            node: 0,
            shape: Arc::new(MeshShape::with_maps(data, maps)),
            material: Arc::new(material),
            material_name: name,
        });
    }
    let nodes = vec![ModelNode { name: None, parent: None, local: DAffine3::IDENTITY }];
    Ok(Model { nodes, parts, warnings, ..Model::default() })
}

/// Why a material library is not used.
#[derive(Debug, thiserror::Error)]
enum LibraryError {
    /// It cannot be read (or the sandbox refuses it).
    #[error("material library: {0}")]
    File(FileError),
    /// A line would make tobj fail or panic.
    #[error("material library `{}`:{line}: {message}", shown_path(.path))]
    Line {
        /// The library.
        path: PathBuf,
        /// 1-based line.
        line: usize,
        /// What is wrong.
        message: &'static str,
    },
    /// tobj rejects the library.
    #[error("material library `{}`: {source}", shown_path(.path))]
    Parse {
        /// The library.
        path: PathBuf,
        /// tobj's error.
        source: tobj::LoadError,
    },
}

/// Reads, checks and parses the MTL file `mtl` (as written after `mtllib`) beside the OBJ.
fn load_library(access: &FileAccess, dir: &Path, mtl: &Path) -> Result<tobj::MTLLoadResult, LibraryError> {
    let written = mtl.to_string_lossy();
    let full = access.join(dir, &written).map_err(LibraryError::File)?;
    let bytes = access.read(&full, FileKind::Mesh).map_err(LibraryError::File)?;
    let text = String::from_utf8_lossy(&bytes);
    check_library(&text).map_err(|(line, message)| LibraryError::Line { path: full.clone(), line, message })?;
    match tobj::load_mtl_buf(&mut std::io::BufReader::new(text.as_bytes())) {
        Ok(library) => Ok(Ok(library)),
        Err(source) => Err(LibraryError::Parse { path: full, source }),
    }
}

/// Lines tobj 4 mishandles: a colour statement (`Ka`, `Kd`, `Ks`, `Ke`) with fewer than
/// three values panics inside the crate, so it is refused here first.
fn check_library(text: &str) -> Result<(), (usize, &'static str)> {
    for (i, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        if matches!(words.next(), Some("Ka" | "Kd" | "Ks" | "Ke")) && words.count() < 3 {
            return Err((i + 1, "a colour statement needs three numbers"));
        }
    }
    Ok(())
}

/// Face and line indices tobj 4 would turn into wrapped or overflowing arithmetic (a
/// relative index reaching before the first element becomes a huge unsigned one, and tobj
/// doubles and triples indices unchecked): index 0, a negative index past the elements read
/// so far, a positive one larger than the file has bytes. Refused here, with the line. A
/// positive index past the elements that do exist is left to tobj, which ignores normals
/// and texture coordinates a file has none of (real files point at absent normals, even
/// past their own line count).
fn check_face_indices(text: &str) -> Result<(), (usize, String)> {
    const KINDS: [&str; 3] = ["v", "vt", "vn"];
    let bytes = text.len() as u64;
    let mut so_far = [0u64; 3];
    for (i, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        let first = words.next();
        if let Some(kind) = first.and_then(|w| KINDS.iter().position(|k| *k == w)) {
            so_far[kind] += 1;
            continue;
        }
        let Some(word @ ("f" | "l")) = first else { continue };
        for (kind, field) in words.flat_map(|vertex| vertex.split('/').take(3).enumerate()) {
            // Malformed fields are tobj's to report.
            let Ok(index) = field.parse::<i64>() else { continue };
            let name = ["vertex", "texture coordinate", "normal"][kind];
            let problem = if index == 0 {
                format!("`{word}` uses {name} index 0 (OBJ indices count from 1)")
            } else if index < 0 && index.unsigned_abs() > so_far[kind] {
                let before = so_far[kind];
                format!(
                    "`{word}` uses relative {name} index {index}, but only {before} `{}` come before it",
                    KINDS[kind]
                )
            } else if index > 0 && index.unsigned_abs() > bytes {
                format!("`{word}` uses {name} index {index}, more than the file has bytes ({bytes})")
            } else {
                continue;
            };
            return Err((i + 1, problem));
        }
    }
    Ok(())
}

fn empty_library() -> tobj::MTLLoadResult {
    tobj::load_mtl_buf(&mut std::io::BufReader::new(&b""[..]))
}

/// Faces of one material, deduplicated into vertices.
#[derive(Default)]
struct PartBuilder {
    builder: MeshBuilder,
    /// (model, position, texcoord, normal) index -> vertex.
    vertices: HashMap<(usize, u32, u32, u32), u32>,
    /// Identity of each vertex's position (model, position index), for smoothing.
    position_id: Vec<(usize, u32)>,
}

fn add_model(model: usize, mesh: &tobj::Mesh, part: &mut PartBuilder) -> Result<(), String> {
    let positions = mesh.positions.len() / 3;
    let normals = mesh.normals.len() / 3;
    let uvs = mesh.texcoords.len() / 2;
    let n = mesh.indices.len();
    let has_normals = !mesh.normal_indices.is_empty() && mesh.normal_indices.len() == n;
    let has_uvs = !mesh.texcoord_indices.is_empty() && mesh.texcoord_indices.len() == n;
    // A part takes normals (or uvs) only when every face it holds has them.
    let first = part.builder.triangles.is_empty();
    if first {
        part.builder.normals.clear();
    }
    let keep_normals = has_normals && (first || !part.builder.normals.is_empty());
    let keep_uvs = has_uvs && (first || !part.builder.uvs.is_empty());
    if !keep_normals && !part.builder.normals.is_empty() {
        part.builder.normals.clear();
    }
    if !keep_uvs && !part.builder.uvs.is_empty() {
        part.builder.uvs.clear();
    }
    let arities: Vec<u32> = if mesh.face_arities.is_empty() { vec![3; n / 3] } else { mesh.face_arities.clone() };
    let mut start = 0usize;
    for arity in arities {
        let arity = arity as usize;
        if start + arity > n {
            return Err("face data shorter than its faces".into());
        }
        let mut corner_vertices = Vec::with_capacity(arity);
        let mut corner_points = Vec::with_capacity(arity);
        for k in start..start + arity {
            let pi = mesh.indices[k];
            if pi as usize >= positions {
                return Err(format!("face uses vertex {} of {positions}", pi + 1));
            }
            let ti = if keep_uvs { mesh.texcoord_indices[k] } else { u32::MAX };
            let ni = if keep_normals { mesh.normal_indices[k] } else { u32::MAX };
            if keep_uvs && ti as usize >= uvs {
                return Err(format!("face uses texture coordinate {} of {uvs}", ti + 1));
            }
            if keep_normals && ni as usize >= normals {
                return Err(format!("face uses normal {} of {normals}", ni + 1));
            }
            let p = Vec3::from_slice(&mesh.positions[3 * pi as usize..3 * pi as usize + 3]);
            let vertex = *part.vertices.entry((model, pi, ti, ni)).or_insert_with(|| {
                let b = &mut part.builder;
                b.positions.push(p);
                if keep_normals {
                    b.normals.push(Vec3::from_slice(&mesh.normals[3 * ni as usize..3 * ni as usize + 3]));
                }
                if keep_uvs {
                    let t = &mesh.texcoords[2 * ti as usize..2 * ti as usize + 2];
                    // OBJ's v counts up from the bottom of the image; Prism's (glTF's) down.
                    b.uvs.push(Vec2::new(t[0], 1.0 - t[1]));
                }
                part.position_id.push((model, pi));
                (b.positions.len() - 1) as u32
            });
            corner_vertices.push(vertex);
            corner_points.push(p.as_dvec3());
        }
        for [a, b, c] in triangulate(&corner_points).map_err(|e| e.to_string())? {
            part.builder.triangles.push([corner_vertices[a], corner_vertices[b], corner_vertices[c]]);
        }
        start += arity;
    }
    // Attribute arrays must cover every vertex or none.
    let count = part.builder.positions.len();
    if part.builder.normals.len() != count {
        part.builder.normals.clear();
    }
    if part.builder.uvs.len() != count {
        part.builder.uvs.clear();
    }
    Ok(())
}

/// Vertex normals for a mesh without any: at each corner, the area-weighted mean of the
/// normals of the faces around the corner's position that meet the corner's face at less
/// than `angle` degrees. Vertices are split where corners get different normals.
fn smooth(part: &mut PartBuilder, angle: f64) {
    smooth_normals(&mut part.builder, &part.position_id, angle);
}

/// [`smooth`] for any mesh: `position_id` gives each vertex's position identity (vertices
/// with the same identity are one point of the surface, split only by their attributes).
pub(super) fn smooth_normals(b: &mut MeshBuilder, position_id: &[(usize, u32)], angle: f64) {
    let cos_limit = angle.to_radians().cos();
    let face_normals: Vec<DVec3> = b
        .triangles
        .iter()
        .map(|t| {
            let [p0, p1, p2] = t.map(|i| b.positions[i as usize].as_dvec3());
            (p1 - p0).cross(p2 - p0)
        })
        .collect();
    let mut around: HashMap<(usize, u32), Vec<usize>> = HashMap::new();
    for (f, t) in b.triangles.iter().enumerate() {
        for &v in t {
            around.entry(position_id[v as usize]).or_default().push(f);
        }
    }
    let mut positions = Vec::new();
    let mut normals = Vec::new();
    let mut uvs = Vec::new();
    let mut split: HashMap<(u32, [i32; 3]), u32> = HashMap::new();
    let mut triangles = Vec::with_capacity(b.triangles.len());
    for (f, t) in b.triangles.iter().enumerate() {
        let nf = face_normals[f].normalize_or_zero();
        let mut out = [0u32; 3];
        for (k, &v) in t.iter().enumerate() {
            let mut sum = DVec3::ZERO;
            for &g in &around[&position_id[v as usize]] {
                let ng = face_normals[g];
                if ng.normalize_or_zero().dot(nf) >= cos_limit - 1e-12 {
                    sum += ng;
                }
            }
            let n = sum.normalize_or(nf).as_vec3();
            let key = (v, (n * 1e5).round().as_ivec3().to_array());
            out[k] = *split.entry(key).or_insert_with(|| {
                positions.push(b.positions[v as usize]);
                normals.push(n);
                if !b.uvs.is_empty() {
                    uvs.push(b.uvs[v as usize]);
                }
                (positions.len() - 1) as u32
            });
        }
        triangles.push(out);
    }
    b.positions = positions;
    b.normals = normals;
    b.uvs = uvs;
    b.triangles = triangles;
}

/// An MTL texture statement: options (`-bm 0.5`, `-clamp on`, `-o u v`, `-s u v`) and the
/// file name (which may contain spaces).
struct MapStatement {
    file: String,
    bump_multiplier: f64,
    clamp: bool,
    offset: [f64; 2],
    scale: [f64; 2],
}

fn parse_map(statement: &str) -> MapStatement {
    let mut out =
        MapStatement { file: String::new(), bump_multiplier: 1.0, clamp: false, offset: [0.0; 2], scale: [1.0; 2] };
    let tokens: Vec<&str> = statement.split_whitespace().collect();
    let mut i = 0;
    let numbers = |from: usize| tokens[from..].iter().take(3).take_while(|t| t.parse::<f64>().is_ok()).count();
    while i < tokens.len() && tokens[i].starts_with('-') && tokens[i].len() > 1 {
        let option = tokens[i];
        i += 1;
        let n = numbers(i);
        let value = |k: usize| tokens.get(i + k).and_then(|t| t.parse::<f64>().ok());
        match option {
            "-bm" => out.bump_multiplier = value(0).unwrap_or(1.0),
            "-o" => out.offset = [value(0).unwrap_or(0.0), value(1).unwrap_or(0.0)],
            "-s" => out.scale = [value(0).unwrap_or(1.0), value(1).unwrap_or(1.0)],
            "-clamp" => {
                out.clamp = tokens.get(i) == Some(&"on");
                i += 1;
                continue;
            }
            "-blendu" | "-blendv" | "-cc" | "-imfchan" | "-type" | "-texres" => {
                i += 1;
                continue;
            }
            _ => {}
        }
        i += n;
    }
    out.file = tokens[i.min(tokens.len())..].join(" ");
    out
}

fn load_map(
    statement: &str,
    obj: &Path,
    space: ColorSpace,
    textures: &mut TextureStore,
    warnings: &mut Vec<String>,
) -> Option<(TextureRef, MapStatement)> {
    let parsed = parse_map(statement);
    if parsed.file.is_empty() {
        return None;
    }
    let dir = obj.parent().unwrap_or(Path::new(""));
    // Windows exports write backslashes.
    let relative = PathBuf::from(parsed.file.replace('\\', "/"));
    let full = match textures.access().join(dir, &relative.to_string_lossy()) {
        Ok(full) => full,
        Err(e) => {
            warnings.push(format!("{e}; the map is ignored"));
            return None;
        }
    };
    match textures.load_file(&full, space) {
        Ok(texture) => {
            let mut r = TextureRef::new(full.display().to_string());
            r.texture = Some(texture);
            if parsed.clamp {
                r.wrap = [crate::texture::Wrap::Clamp; 2];
            }
            r.offset = parsed.offset;
            r.scale = parsed.scale;
            Some((r, parsed))
        }
        Err(e) => {
            warnings.push(format!("{e}; the map is ignored"));
            None
        }
    }
}

/// MTL as written (documented in `docs/meshes.md`): Kd, Ks, Ns, Ni, d (or 1 - Tr), illum and
/// map_Kd into [`Mtl`], Ke into the emission; map_Bump / bump -> height bump, norm ->
/// tangent-space normal map. A material with non-finite values falls back to the default.
fn map_material(
    m: &tobj::Material,
    obj: &Path,
    textures: &mut TextureStore,
    warnings: &mut Vec<String>,
) -> (Material, SurfaceMaps) {
    let rgb = |c: [f32; 3]| Rgb::new(f64::from(c[0]), f64::from(c[1]), f64::from(c[2]));
    let mut maps = SurfaceMaps::default();
    let map_kd = m
        .diffuse_texture
        .as_ref()
        .and_then(|map| load_map(map, obj, ColorSpace::Srgb, textures, warnings))
        .map(|(t, _)| t);
    let d = m
        .dissolve
        .map(f64::from)
        .or_else(|| m.unknown_param.get("Tr").and_then(|t| t.trim().parse::<f64>().ok()).map(|tr| 1.0 - tr));
    let mtl = Mtl {
        kd: m.diffuse.map(rgb),
        ks: m.specular.map(rgb),
        ns: m.shininess.map(f64::from),
        ni: m.optical_density.map(f64::from),
        d,
        illum: m.illumination_model,
        map_kd,
    };
    let emission = Emission { radiance: m.emissive.map(rgb).unwrap_or(Rgb::BLACK), ..Emission::default() };
    let material = Material { surface: SurfaceModel::Mtl(mtl), emission, ..Material::default() };
    let normal = m.unknown_param.get("norm").map(|s| (s.as_str(), false));
    let bump = m.normal_texture.as_deref().map(|s| (s, true));
    if let Some((statement, height)) = normal.or(bump)
        && let Some((t, parsed)) = load_map(statement, obj, ColorSpace::Linear, textures, warnings)
    {
        maps.normal_map =
            Some(NormalMap { texture: t, scale: if height { parsed.bump_multiplier } else { 1.0 }, height });
    }
    if material.check().is_err() {
        warnings.push(format!("material `{}` has out-of-range values; using defaults", m.name));
        return (Material::default(), maps);
    }
    (material, maps)
}

/// A sentence for a tobj error.
pub(super) fn describe(e: &tobj::LoadError) -> String {
    use tobj::LoadError as E;
    match e {
        E::PositionParseError => "cannot parse a vertex position (`v x y z`)".into(),
        E::NormalParseError => "cannot parse a vertex normal (`vn x y z`)".into(),
        E::TexcoordParseError => "cannot parse a texture coordinate (`vt u v`)".into(),
        E::FaceParseError => "cannot parse a face (`f v/vt/vn ...`)".into(),
        E::FaceVertexOutOfBounds => "a face refers to a vertex that does not exist".into(),
        E::FaceTexCoordOutOfBounds => "a face refers to a texture coordinate that does not exist".into(),
        E::FaceNormalOutOfBounds => "a face refers to a normal that does not exist".into(),
        E::MaterialParseError => "cannot parse a material statement (`usemtl` or `mtllib` without a name?)".into(),
        other => other.to_string(),
    }
}

/// The line tobj most likely stopped at: the first line of the kind its error names that
/// does not parse (tobj itself reports no line numbers).
fn error_line(text: &str, e: &tobj::LoadError) -> Option<usize> {
    use tobj::LoadError as E;
    let floats_ok = |rest: &[&str], min: usize, max: usize| {
        (min..=max).contains(&rest.len()) && rest.iter().all(|t| t.parse::<f32>().is_ok())
    };
    let (mut v, mut vt, mut vn) = (0i64, 0i64, 0i64);
    for (i, line) in text.lines().enumerate() {
        let tokens: Vec<&str> = line.split_whitespace().collect();
        let Some((&head, rest)) = tokens.split_first() else { continue };
        let bad = match (head, e) {
            ("v", E::PositionParseError) => !floats_ok(rest, 3, 7),
            ("vn", E::NormalParseError) => !floats_ok(rest, 3, 3),
            ("vt", E::TexcoordParseError) => !floats_ok(rest, 1, 3),
            ("usemtl" | "mtllib", E::MaterialParseError) => rest.is_empty(),
            (
                "f",
                E::FaceParseError | E::FaceVertexOutOfBounds | E::FaceTexCoordOutOfBounds | E::FaceNormalOutOfBounds,
            ) => {
                rest.len() < 3
                    || rest.iter().any(|corner| {
                        let mut fields = corner.split('/');
                        let check = |field: Option<&str>, count: i64, required: bool| match field {
                            None | Some("") => required,
                            Some(s) => match s.parse::<i64>() {
                                Ok(i) if i > 0 => i > count,
                                Ok(i) if i < 0 => count + i < 0,
                                _ => true,
                            },
                        };
                        check(fields.next(), v, true)
                            || check(fields.next(), vt, false)
                            || check(fields.next(), vn, false)
                    })
            }
            _ => false,
        };
        if bad {
            return Some(i + 1);
        }
        match head {
            "v" => v += 1,
            "vt" => vt += 1,
            "vn" => vn += 1,
            _ => {}
        }
    }
    None
}

/// The first `v` line with a non-finite coordinate.
fn nonfinite_line(text: &str) -> Option<usize> {
    text.lines()
        .position(|line| {
            let mut t = line.split_whitespace();
            t.next() == Some("v") && t.take(3).any(|x| x.parse::<f32>().is_ok_and(|f| !f.is_finite()))
        })
        .map(|i| i + 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
        let p = dir.join(name);
        std::fs::write(&p, text).unwrap();
        p
    }

    #[test]
    fn negative_indices_quads_and_materials() {
        let dir = tempfile::tempdir().unwrap();
        write(
            dir.path(),
            "m.mtl",
            "newmtl red\nKd 1 0 0\nKs 0.5 0.5 0.5\nNs 100\nnewmtl glass\nKd 1 1 1\nd 0.2\nNi 1.5\n",
        );
        let p = write(
            dir.path(),
            "q.obj",
            "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nusemtl red\nf -4 -3 -2 -1\ng other\nusemtl glass\nf 1 2 3\n",
        );
        let model = import(&p, &ImportOptions::default(), &mut TextureStore::new()).unwrap();
        assert_eq!(model.parts.len(), 2);
        let red = model.parts.iter().find(|p| p.material_name.as_deref() == Some("red")).unwrap();
        assert_eq!(red.shape.data().triangle_count(), 2);
        let SurfaceModel::Mtl(mtl) = &red.material.surface else { panic!("an MTL surface") };
        assert_eq!((mtl.kd, mtl.ks, mtl.ns), (Some(Rgb::new(1.0, 0.0, 0.0)), Some(Rgb::grey(0.5)), Some(100.0)));
        let glass = model.parts.iter().find(|p| p.material_name.as_deref() == Some("glass")).unwrap();
        let SurfaceModel::Mtl(mtl) = &glass.material.surface else { panic!("an MTL surface") };
        assert!((mtl.d.unwrap() - 0.2).abs() < 1e-6 && (mtl.ni.unwrap() - 1.5).abs() < 1e-6);
    }

    /// Indices tobj would wrap or overflow on (found by fuzzing: `f 1/-10` after one `vt`
    /// panicked inside tobj in an overflow-checked build) are errors naming the line.
    #[test]
    fn out_of_range_face_indices_are_refused_with_their_line() {
        let dir = tempfile::tempdir().unwrap();
        let cases = [
            (
                "vt 0 0\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/-1 2/-10 3\n",
                5,
                "relative texture coordinate index -10, but only 1 `vt`",
            ),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", 4, "vertex index 0"),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4\n", 4, "relative vertex index -4, but only 3 `v`"),
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//4611686018427387904\n",
                5,
                "normal index 4611686018427387904, more than the file has bytes (68)",
            ),
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -9223372036854775808\n",
                4,
                "relative vertex index -9223372036854775808, but only 3",
            ),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 99\n", 4, "vertex index 99, more than the file has bytes (31)"),
        ];
        for (n, (text, line, expected)) in cases.into_iter().enumerate() {
            let p = write(dir.path(), &format!("bad{n}.obj"), text);
            let e = import(&p, &ImportOptions::default(), &mut TextureStore::new()).unwrap_err().to_string();
            assert!(e.contains(expected) && e.contains(&format!(":{line}")), "{text:?}: {e}");
        }
        // Relative indices within range, and a vertex defined after the face that uses it
        // (tobj resolves faces at the end of their object), stay valid.
        let p = write(dir.path(), "good.obj", "v 0 0 0\nv 1 0 0\nvt 0 0\nf -2/-1 -1/-1 3/1\nv 0 1 0\n");
        assert_eq!(import(&p, &ImportOptions::default(), &mut TextureStore::new()).unwrap().parts.len(), 1);
    }

    #[test]
    fn concave_face_and_smoothing() {
        let dir = tempfile::tempdir().unwrap();
        let p = write(dir.path(), "l.obj", "v 0 0 0\nv 2 0 0\nv 2 1 0\nv 1 1 0\nv 1 2 0\nv 0 2 0\nf 1 2 3 4 5 6\n");
        let model = import(&p, &ImportOptions::default(), &mut TextureStore::new()).unwrap();
        let shape = &model.parts[0].shape;
        assert_eq!(shape.data().triangle_count(), 4);
        // The notch (1.5, 1.5) is empty; a fan from vertex 1 would have covered it.
        use prism_api::Shape;
        let down = DVec3::new(0.0, 0.0, -1.0);
        assert!(shape.intersect(&prism_api::Ray::new(DVec3::new(1.5, 1.5, 1.0), down), 1e-9, f64::INFINITY).is_none());
        assert!(shape.intersect(&prism_api::Ray::new(DVec3::new(0.5, 1.5, 1.0), down), 1e-9, f64::INFINITY).is_some());

        // A ridge: two faces at 90 degrees; smoothing at 100 degrees blends them, at 30 not.
        let ridge =
            write(dir.path(), "r.obj", "v 0 0 0\nv 1 0 0\nv 1 1 1\nv 0 1 1\nv 1 2 0\nv 0 2 0\nf 1 2 3 4\nf 4 3 5 6\n");
        let flat = import(&ridge, &ImportOptions { smooth_angle: Some(30.0) }, &mut TextureStore::new()).unwrap();
        assert_eq!(flat.parts[0].shape.data().vertex_count(), 8, "split at the crease");
        let smooth = import(&ridge, &ImportOptions { smooth_angle: Some(100.0) }, &mut TextureStore::new()).unwrap();
        assert_eq!(smooth.parts[0].shape.data().vertex_count(), 6);
    }

    #[test]
    fn errors_name_the_line() {
        let dir = tempfile::tempdir().unwrap();
        let p = write(dir.path(), "b.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 9\n");
        let e = import(&p, &ImportOptions::default(), &mut TextureStore::new()).unwrap_err();
        assert_eq!(e.line, Some(5), "{e}");
        let p = write(dir.path(), "c.obj", "v 0 0 0\nv 1 x 0\n");
        let e = import(&p, &ImportOptions::default(), &mut TextureStore::new()).unwrap_err();
        assert_eq!(e.line, Some(2), "{e}");
        let p = write(dir.path(), "d.obj", "v 0 0 0\nv 1 0 0\n");
        let m = import(&p, &ImportOptions::default(), &mut TextureStore::new()).unwrap();
        assert!(m.parts.is_empty() && m.warnings[0].contains("no faces"), "{m:?}");
        std::fs::write(dir.path().join("u.obj"), [0xfe, 0xff, 0, b'v']).unwrap();
        let e = import(&dir.path().join("u.obj"), &ImportOptions::default(), &mut TextureStore::new()).unwrap_err();
        assert!(matches!(e.kind, ImportErrorKind::NotText), "{e}");
        // Latin-1 in a material name is not an error.
        std::fs::write(dir.path().join("l.obj"), b"v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl Terraind\xe6k\nf 1 2 3\n")
            .unwrap();
        assert_eq!(
            import(&dir.path().join("l.obj"), &ImportOptions::default(), &mut TextureStore::new()).unwrap().parts.len(),
            1
        );
    }

    #[test]
    fn map_statement_options() {
        let m = parse_map("-bm 0.3 -clamp on -s 2 2 1 tex ture.png");
        assert_eq!((m.bump_multiplier, m.clamp, m.scale, m.file.as_str()), (0.3, true, [2.0, 2.0], "tex ture.png"));
        assert_eq!(parse_map("a.png").file, "a.png");
    }
}
