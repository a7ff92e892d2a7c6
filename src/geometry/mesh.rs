//! Triangle meshes: vertex data ([`MeshBuilder`], [`MeshData`]), the surface maps a mesh
//! material can carry (alpha mask, normal map), and the [`MeshShape`]: an f32 mesh with its
//! own BVH (the bottom level of the two-level BVH) that implements the plugin `Shape` trait.

use std::sync::{Arc, OnceLock};

use glam::{DVec2, DVec3, Vec2, Vec3, Vec4};
use prism_api::math::area_to_solid_angle;
use prism_api::{
    Aabb, AreaSample, DirectionSample, Hit, Ray, Shape, Surface, pdf_toward_by_area, sample_toward_by_area,
    sample_toward_flat,
};

use crate::accel::mesh_bvh::TriangleBvh;
use crate::accel::triangle::{WatertightRay, mesh_hit, plane_t};
use crate::limits::{MemoryBudget, OverBudget};
use crate::texture::TextureRef;

/// Why vertex data cannot become a mesh.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum MeshError {
    /// A position is NaN or infinite.
    #[error("vertex {vertex} has a non-finite position {position:?}")]
    NonFinitePosition {
        /// The vertex.
        vertex: usize,
        /// Its position.
        position: [f32; 3],
    },
    /// An attribute array is neither empty nor one per position.
    #[error("{len} {attribute} for {vertices} vertices")]
    AttributeCount {
        /// `normals`, `texture coordinates` or `tangents`.
        attribute: &'static str,
        /// How many the array holds.
        len: usize,
        /// How many positions there are.
        vertices: usize,
    },
    /// A triangle names a vertex that does not exist.
    #[error("triangle {triangle} uses vertex {corners:?}, but there are only {vertices} vertices")]
    VertexOutOfRange {
        /// The triangle.
        triangle: usize,
        /// Its vertex indices.
        corners: [u32; 3],
        /// How many vertices there are.
        vertices: usize,
    },
    /// Every triangle has zero area (or there were none): nothing to hit.
    #[error("no triangles with a non-zero area")]
    NoTriangles,
    /// The mesh and its BVH would not fit the memory budget (`--max-memory`).
    #[error(transparent)]
    OverBudget(#[from] OverBudget),
}

/// Vertex data of a mesh before its BVH is built.
#[derive(Clone, Debug, Default)]
pub struct MeshBuilder {
    /// Vertex positions.
    pub positions: Vec<Vec3>,
    /// Vertex normals (empty, or one per position).
    pub normals: Vec<Vec3>,
    /// Texture coordinates, glTF convention (v down; empty, or one per position).
    pub uvs: Vec<Vec2>,
    /// Tangents with handedness in w (empty, or one per position).
    pub tangents: Vec<Vec4>,
    /// Triangles as vertex indices.
    pub triangles: Vec<[u32; 3]>,
}

/// Bytes a built mesh and its building cost per vertex at most (position, normal, uv and
/// tangent), the builder's copy included.
const BYTES_PER_VERTEX: u64 = 2 * (12 + 12 + 8 + 16);

/// Bytes a built mesh and its building cost per triangle: the indices, the corner copy and
/// de-duplication set of [`MeshBuilder::build`], the BVH's nodes, references and packed
/// triangles. Measured: `prism render` of a 2 M-triangle, 1 M-vertex OBJ grid peaks at
/// 936 MB resident (the file and the parser's arrays included); this estimates 996 MB.
const BYTES_PER_TRIANGLE: u64 = 450;

impl MeshBuilder {
    /// The memory building this mesh and its BVH takes, in bytes (an upper estimate).
    pub fn estimate_bytes(&self) -> u64 {
        Self::estimate_for(self.positions.len() as u64, self.triangles.len() as u64)
    }

    /// The memory building a mesh of `vertices` and `triangles` takes, in bytes (an upper
    /// estimate), before its builder exists.
    pub fn estimate_for(vertices: u64, triangles: u64) -> u64 {
        vertices.saturating_mul(BYTES_PER_VERTEX).saturating_add(triangles.saturating_mul(BYTES_PER_TRIANGLE))
    }

    /// Checks indices and values: every index in range, every position finite, attribute
    /// arrays empty or as long as the positions. Non-finite normals, uvs or tangents are
    /// dropped (the mesh falls back to flat shading or barycentric uvs), not fatal.
    pub fn validate(&mut self) -> Result<(), MeshError> {
        let n = self.positions.len();
        if let Some(i) = self.positions.iter().position(|p| !p.is_finite()) {
            return Err(MeshError::NonFinitePosition { vertex: i, position: self.positions[i].to_array() });
        }
        for (attribute, len) in [
            ("normals", self.normals.len()),
            ("texture coordinates", self.uvs.len()),
            ("tangents", self.tangents.len()),
        ] {
            if len != 0 && len != n {
                return Err(MeshError::AttributeCount { attribute, len, vertices: n });
            }
        }
        if let Some((t, tri)) = self.triangles.iter().enumerate().find(|(_, t)| t.iter().any(|&i| i as usize >= n)) {
            return Err(MeshError::VertexOutOfRange { triangle: t, corners: *tri, vertices: n });
        }
        if !self.normals.iter().all(|v| v.is_finite()) {
            self.normals.clear();
        }
        if !self.uvs.iter().all(|v| v.is_finite()) {
            self.uvs.clear();
        }
        if !self.tangents.iter().all(|v| v.is_finite()) {
            self.tangents.clear();
        }
        Ok(())
    }

    /// Validates and builds the mesh and its BVH. Triangles with zero area (nothing can hit
    /// them and they have no normal) and repeated triangles are dropped.
    pub fn build(self) -> Result<MeshData, MeshError> {
        self.build_within(MemoryBudget::UNLIMITED)
    }

    /// [`MeshBuilder::build`], after checking [`MeshBuilder::estimate_bytes`] against `budget`.
    pub fn build_within(mut self, budget: MemoryBudget) -> Result<MeshData, MeshError> {
        let triangles = self.triangles.len();
        budget.check(|| format!("{triangles} triangles with their BVH"), self.estimate_bytes())?;
        self.validate()?;
        let positions = &self.positions;
        self.triangles.retain(|t| {
            let [a, b, c] = t.map(|i| positions[i as usize].as_dvec3());
            (b - a).cross(c - a).length_squared() > 0.0
        });
        // Repeated faces (the same three corners in any order) add nothing but work, and
        // many identical boxes make the BVH builder chain them into a very deep tree.
        let mut seen = std::collections::HashSet::with_capacity(self.triangles.len());
        self.triangles.retain(|t| {
            let mut key = t.map(|i| positions[i as usize].to_array().map(f32::to_bits));
            key.sort_unstable();
            seen.insert(key)
        });
        if self.triangles.is_empty() {
            return Err(MeshError::NoTriangles);
        }
        self.triangles.shrink_to_fit();
        let corners: Vec<[Vec3; 3]> = self.triangles.iter().map(|t| t.map(|i| positions[i as usize])).collect();
        let mut bounds = Aabb::EMPTY;
        let mut area = 0.0;
        for t in &corners {
            for p in t {
                bounds = bounds.grow(p.as_dvec3());
            }
            area += 0.5 * (t[1] - t[0]).as_dvec3().cross((t[2] - t[0]).as_dvec3()).length();
        }
        let plane_normal = plane_normal(&corners);
        let bvh = TriangleBvh::build(corners);
        Ok(MeshData {
            positions: self.positions,
            normals: self.normals,
            uvs: self.uvs,
            tangents: self.tangents,
            triangles: self.triangles,
            bvh,
            bounds,
            area,
            plane_normal,
            area_cdf: OnceLock::new(),
            open_edges: OnceLock::new(),
        })
    }
}

/// The unit normal of the plane through every corner of `corners`, if there is one: the
/// largest triangle's normal, when every corner lies within rounding (1e-6 of the largest
/// coordinate, well above f32 positions' 6e-8) of its plane.
fn plane_normal(corners: &[[Vec3; 3]]) -> Option<DVec3> {
    let cross = |t: &[Vec3; 3]| (t[1] - t[0]).as_dvec3().cross((t[2] - t[0]).as_dvec3());
    let largest = corners.iter().max_by(|a, b| cross(a).length_squared().total_cmp(&cross(b).length_squared()))?;
    let normal = cross(largest).try_normalize()?;
    let offset = normal.dot(largest[0].as_dvec3());
    let scale = corners.iter().flatten().fold(0f64, |m, p| m.max(f64::from(p.abs().max_element())));
    let tolerance = 1e-6 * scale;
    corners.iter().flatten().all(|p| (normal.dot(p.as_dvec3()) - offset).abs() <= tolerance).then_some(normal)
}

/// An immutable triangle mesh with its BVH: shared (`Arc`) by every instance.
#[derive(Debug)]
pub struct MeshData {
    positions: Vec<Vec3>,
    normals: Vec<Vec3>,
    uvs: Vec<Vec2>,
    tangents: Vec<Vec4>,
    /// Vertex indices of each triangle (the BVH's hits name them by their index here).
    triangles: Vec<[u32; 3]>,
    bvh: TriangleBvh,
    bounds: Aabb,
    area: f64,
    /// The unit normal of the plane holding every triangle, when the mesh is flat (a quad
    /// light): a ray then crosses it at most once.
    plane_normal: Option<DVec3>,
    /// Cumulative triangle areas, built the first time a point is sampled.
    area_cdf: OnceLock<Vec<f64>>,
    /// How many edges border an odd number of triangles, counted the first time it is asked.
    open_edges: OnceLock<usize>,
}

/// The direction along which a closed mesh's inside test counts crossings, in the mesh's
/// own space, and which `prism export pov` writes as its `inside_vector` (POV-Ray counts
/// along that): along no axis or diagonal, so that it rarely runs along a modelled edge.
pub const INSIDE_VECTOR: DVec3 = DVec3::new(0.2768, 0.3771, 0.8839);

impl MeshData {
    /// How many edges border an odd number of triangles, corners matched by position (a
    /// file's seams, where vertices are repeated for their normals or uvs, are not edges of
    /// the surface). 0 for a closed surface, which bounds a solid.
    pub fn open_edges(&self) -> usize {
        *self.open_edges.get_or_init(|| {
            // Adding 0.0 turns -0.0 into 0.0: one position, one key.
            let key = |p: &Vec3| [p.x + 0.0, p.y + 0.0, p.z + 0.0].map(f32::to_bits);
            let mut ids = std::collections::HashMap::with_capacity(self.positions.len());
            let welded: Vec<u32> = self
                .positions
                .iter()
                .map(|p| {
                    let next = ids.len() as u32;
                    *ids.entry(key(p)).or_insert(next)
                })
                .collect();
            let mut edges = std::collections::HashMap::with_capacity(self.triangles.len() * 3 / 2);
            for t in &self.triangles {
                for (a, b) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
                    let (a, b) = (welded[a as usize], welded[b as usize]);
                    *edges.entry((a.min(b), a.max(b))).or_insert(0u32) += 1;
                }
            }
            edges.values().filter(|&&count| count % 2 == 1).count()
        })
    }

    /// The triangles of `parts`, each placed by its transform, as one mesh (a file's parts as
    /// one CSG member). Vertex normals are kept when every part has them, and so are texture
    /// coordinates; tangents are not (no normal maps on CSG members).
    pub fn merged(parts: &[(Arc<MeshData>, glam::DAffine3)], budget: MemoryBudget) -> Result<Arc<MeshData>, MeshError> {
        if let [(data, placement)] = parts
            && *placement == glam::DAffine3::IDENTITY
        {
            return Ok(data.clone());
        }
        let keep_normals = parts.iter().all(|(d, _)| !d.normals.is_empty());
        let keep_uvs = parts.iter().all(|(d, _)| !d.uvs.is_empty());
        let mut merged = MeshBuilder::default();
        for (data, placement) in parts {
            let first = merged.positions.len() as u32;
            let normal_matrix = placement.matrix3.inverse().transpose();
            merged.positions.extend(data.positions.iter().map(|p| placement.transform_point3(p.as_dvec3()).as_vec3()));
            if keep_normals {
                merged
                    .normals
                    .extend(data.normals.iter().map(|n| (normal_matrix * n.as_dvec3()).normalize_or_zero().as_vec3()));
            }
            if keep_uvs {
                merged.uvs.extend_from_slice(&data.uvs);
            }
            merged.triangles.extend(data.triangles.iter().map(|t| t.map(|i| i + first)));
        }
        merged.build_within(budget).map(Arc::new)
    }

    /// True when the surface is closed ([`MeshData::open_edges`] is 0): then it has an
    /// inside, and can be a CSG member.
    pub fn is_closed(&self) -> bool {
        self.open_edges() == 0
    }

    /// Number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// Number of vertices.
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// Vertex positions.
    pub fn positions(&self) -> &[Vec3] {
        &self.positions
    }

    /// Vertex indices of each triangle.
    pub fn triangles(&self) -> &[[u32; 3]] {
        &self.triangles
    }

    /// True when the mesh has vertex normals (smooth shading).
    pub fn has_normals(&self) -> bool {
        !self.normals.is_empty()
    }

    /// True when the mesh has texture coordinates.
    pub fn has_uvs(&self) -> bool {
        !self.uvs.is_empty()
    }

    /// Bytes of vertex, index and BVH storage.
    pub fn memory_bytes(&self) -> usize {
        self.positions.len() * 12
            + self.normals.len() * 12
            + self.uvs.len() * 8
            + self.tangents.len() * 16
            + self.triangles.len() * 12
            + self.bvh.memory_bytes()
    }

    fn uv(&self, tri: &[u32; 3], b1: f64, b2: f64) -> DVec2 {
        if self.uvs.is_empty() {
            return DVec2::new(b1, b2);
        }
        let [a, b, c] = tri.map(|i| self.uvs[i as usize].as_dvec2());
        a * (1.0 - b1 - b2) + b * b1 + c * b2
    }
}

/// What a mesh part's own (file) material does to its geometry: cut-outs and bumps. These
/// belong to the shape rather than to [`Material`](crate::material::Material) because the alpha test runs during
/// traversal and the normal map changes the shading normal the shape reports.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SurfaceMaps {
    /// glTF alpha mode MASK: triangles are skipped where alpha < cutoff.
    pub alpha_mask: Option<AlphaMask>,
    /// A tangent-space normal map (glTF convention: +y up in the image's green channel).
    pub normal_map: Option<NormalMap>,
}

/// An alpha cut-out: alpha = factor * texture alpha, hit where alpha >= cutoff.
#[derive(Clone, Debug, PartialEq)]
pub struct AlphaMask {
    /// The base colour texture whose alpha is tested (`None`: the factor alone decides).
    pub texture: Option<TextureRef>,
    /// The base colour factor's alpha.
    pub factor: f32,
    /// glTF alphaCutoff.
    pub cutoff: f32,
}

/// A tangent-space normal map, or a height (bump) map.
#[derive(Clone, Debug, PartialEq)]
pub struct NormalMap {
    /// The (linear) texture.
    pub texture: TextureRef,
    /// Normal maps: glTF normalTexture.scale, multiplying the map's x and y. Height maps: the
    /// height of a texel value of 1 in object-space units (MTL `-bm`).
    pub scale: f64,
    /// True for a height map (MTL `map_Bump`): the normal tilts along the height's gradient.
    pub height: bool,
}

/// A triangle mesh in object space: shared mesh data plus the maps of the part's material.
#[derive(Clone, Debug)]
pub struct MeshShape {
    data: Arc<MeshData>,
    maps: Option<Arc<SurfaceMaps>>,
}

/// Bending keeps reflected view directions at least this far (as a cosine) above the
/// geometric surface.
const TERMINATOR_MARGIN: f64 = 0.01;

impl MeshShape {
    /// A shape over `data` with no surface maps.
    pub fn new(data: Arc<MeshData>) -> Self {
        Self { data, maps: None }
    }

    /// A shape over `data` with the given maps (`None` when they are empty).
    pub fn with_maps(data: Arc<MeshData>, maps: SurfaceMaps) -> Self {
        let maps = (maps != SurfaceMaps::default()).then(|| Arc::new(maps));
        Self { data, maps }
    }

    /// The shared mesh data.
    pub fn data(&self) -> &Arc<MeshData> {
        &self.data
    }

    /// The triangles' vertices in object space, indexed like the hits' `part`, when the
    /// triangles alone decide every hit (no alpha mask): then the scene BVH may hold them
    /// itself and report [`crate::accel::triangle::mesh_hit`]s, as [`Shape::intersect`] does.
    pub fn flattenable_triangles(&self) -> Option<&[[Vec3; 3]]> {
        let masked = self.maps.as_ref().is_some_and(|m| m.alpha_mask.is_some());
        (!masked).then(|| self.data.bvh.triangles())
    }

    /// The alpha test of triangle slot `slot` at barycentrics (b1, b2): true when solid.
    #[inline]
    fn solid(&self, slot: usize, b1: f32, b2: f32) -> bool {
        let Some(mask) = self.maps.as_ref().and_then(|m| m.alpha_mask.as_ref()) else { return true };
        let alpha = match &mask.texture {
            Some(t) => {
                let uv = self.data.uv(&self.data.triangles[slot], f64::from(b1), f64::from(b2));
                match &t.texture {
                    Some(image) => image.nearest(t.transform_uv(uv), t.wrap).w,
                    None => 1.0,
                }
            }
            None => 1.0,
        };
        alpha * mask.factor >= mask.cutoff
    }

    // Always inlined: called, it wrote the ray to memory that the caller then read back in
    // wider loads, a store-forwarding stall of about a tenth of a primary ray's time.
    #[inline(always)]
    fn prepare(ray: &Ray) -> Option<WatertightRay> {
        WatertightRay::new(ray.origin.as_vec3(), ray.direction.as_vec3())
    }

    /// The bound the f32 traversal prunes by: `t_max` widened by the f32 test's error (the
    /// origin rounded to f32 moves t by about |origin| / |direction| times 2^-24, the
    /// arithmetic by a few ulps of t). A surface exactly at `t_max`, as where a CSG group
    /// clips a member's search to the member's bounds, would otherwise be lost when its f32
    /// t lands above the f64 one; hits beyond `t_max` are still refused in f64.
    #[inline(always)]
    fn f32_bound(ray: &Ray, t_max: f64) -> f32 {
        if t_max >= f64::from(f32::MAX) {
            return f32::INFINITY;
        }
        let reach = ray.origin.abs().max_element() / ray.direction.abs().max_element();
        let slack = 4e-6 * (t_max.abs() + reach);
        if slack.is_finite() { next_up((t_max + slack) as f32) } else { f32::INFINITY }
    }

    /// The shading normal: interpolated vertex normals, then the normal map. Not bent for
    /// the view: the `path` integrator applies the terminator fix
    /// ([`shading_normal_for_view`]); `classic` shades with this normal, as POV-Ray shades a
    /// smooth triangle with its interpolated one.
    fn shading_normal(&self, tri: &[u32; 3], b: (f64, f64), ng: DVec3, uv: DVec2) -> DVec3 {
        let d = &self.data;
        let normal_map = self.maps.as_ref().and_then(|m| m.normal_map.as_ref());
        if d.normals.is_empty() && normal_map.is_none() {
            return ng;
        }
        let (b1, b2) = b;
        let b0 = 1.0 - b1 - b2;
        let mut ns = if d.normals.is_empty() {
            ng
        } else {
            let [n0, n1, n2] = tri.map(|i| d.normals[i as usize].as_dvec3());
            let n = n0 * b0 + n1 * b1 + n2 * b2;
            let n = n.normalize_or_zero();
            if n == DVec3::ZERO { ng } else { n }
        };
        // Vertex normals that disagree with the winding (mirrored exports) follow the winding.
        if ns.dot(ng) < 0.0 {
            ns = -ns;
        }
        if let Some(map) = normal_map
            && let Some(perturbed) = self.normal_mapped(map, tri, b, ns, uv)
        {
            ns = perturbed;
        }
        ns
    }

    fn normal_mapped(&self, map: &NormalMap, tri: &[u32; 3], b: (f64, f64), n: DVec3, uv: DVec2) -> Option<DVec3> {
        let d = &self.data;
        if d.uvs.is_empty() {
            return None;
        }
        let (b1, b2) = b;
        let (tangent, sign) = if d.tangents.is_empty() {
            // No TANGENT: the triangle's own dp/du (per-triangle, not MikkTSpace).
            let [p0, p1, p2] = tri.map(|i| d.positions[i as usize].as_dvec3());
            let [t0, t1, t2] = tri.map(|i| d.uvs[i as usize].as_dvec2());
            let (e1, e2) = (p1 - p0, p2 - p0);
            let (d1, d2) = (t1 - t0, t2 - t0);
            let det = d1.x * d2.y - d1.y * d2.x;
            if det == 0.0 {
                return None;
            }
            let dpdu = (e1 * d2.y - e2 * d1.y) / det;
            let dpdv = (e2 * d1.x - e1 * d2.x) / det;
            // Images count v downward, so the bitangent (image up) is -dp/dv.
            let sign = if n.cross(dpdu).dot(-dpdv) < 0.0 { -1.0 } else { 1.0 };
            (dpdu, sign)
        } else {
            let [a, bb, c] = tri.map(|i| d.tangents[i as usize].as_dvec4());
            let t = a * (1.0 - b1 - b2) + bb * b1 + c * b2;
            (t.truncate(), if a.w < 0.0 { -1.0 } else { 1.0 })
        };
        // Gram-Schmidt against the (interpolated) normal.
        let t = (tangent - n * n.dot(tangent)).normalize_or_zero();
        if t == DVec3::ZERO {
            return None;
        }
        let bitangent = n.cross(t) * sign;
        if map.height {
            return Some(self.bumped(map, uv, n, tri));
        }
        let texel = map.texture.sample(uv, 0.0);
        let x = (f64::from(texel.x) * 2.0 - 1.0) * map.scale;
        let y = (f64::from(texel.y) * 2.0 - 1.0) * map.scale;
        let z = f64::from(texel.z) * 2.0 - 1.0;
        let mapped = (t * x + bitangent * y + n * z).normalize_or_zero();
        (mapped != DVec3::ZERO).then_some(mapped)
    }

    /// Bump mapping from a height map: the surface is displaced along `n` by scale * height,
    /// and the normal is that of the displaced surface (finite differences one texel apart).
    fn bumped(&self, map: &NormalMap, uv: DVec2, n: DVec3, tri: &[u32; 3]) -> DVec3 {
        let d = &self.data;
        let Some(image) = &map.texture.texture else { return n };
        let [p0, p1, p2] = tri.map(|i| d.positions[i as usize].as_dvec3());
        let [t0, t1, t2] = tri.map(|i| d.uvs[i as usize].as_dvec2());
        let (e1, e2, d1, d2) = (p1 - p0, p2 - p0, t1 - t0, t2 - t0);
        let det = d1.x * d2.y - d1.y * d2.x;
        if det == 0.0 {
            return n;
        }
        let dpdu = (e1 * d2.y - e2 * d1.y) / det;
        let dpdv = (e2 * d1.x - e1 * d2.x) / det;
        let (du, dv) = (1.0 / image.width() as f64, 1.0 / image.height() as f64);
        let h = |o: DVec2| f64::from(map.texture.sample(uv + o, 0.0).x) * map.scale;
        let dhdu = (h(DVec2::new(du, 0.0)) - h(DVec2::new(-du, 0.0))) / (2.0 * du);
        let dhdv = (h(DVec2::new(0.0, dv)) - h(DVec2::new(0.0, -dv))) / (2.0 * dv);
        let bumped = (dpdu + n * dhdu).cross(dpdv + n * dhdv).normalize_or_zero();
        if bumped == DVec3::ZERO {
            n
        } else if bumped.dot(n) < 0.0 {
            -bumped
        } else {
            bumped
        }
    }

    /// The surface at a hit; its uv and uv density only `with_uv` (the shading normal reads
    /// the uv of a normal map either way).
    fn surface_at(&self, ray: &Ray, hit: &Hit, with_uv: bool) -> Surface {
        let d = &self.data;
        let slot = (hit.part as usize).min(d.triangles.len() - 1);
        let tri = d.triangles[slot];
        let [p0, p1, p2] = tri.map(|i| d.positions[i as usize].as_dvec3());
        let cross = (p1 - p0).cross(p2 - p0);
        let ng = cross.normalize_or(DVec3::Z);
        let (b1, b2) = (hit.scratch.x, hit.scratch.y);
        let normal_mapped = self.maps.as_ref().is_some_and(|m| m.normal_map.is_some());
        let uv = if with_uv || normal_mapped { d.uv(&tri, b1, b2) } else { DVec2::ZERO };
        let uv_density = if !with_uv || d.uvs.is_empty() {
            0.0
        } else {
            let [t0, t1, t2] = tri.map(|i| d.uvs[i as usize].as_dvec2());
            let (e1, e2) = (t1 - t0, t2 - t0);
            let uv_area = (e1.x * e2.y - e1.y * e2.x).abs();
            (uv_area / cross.length()).sqrt()
        };
        let shading_normal = self.shading_normal(&tri, (b1, b2), ng, uv);
        Surface { point: ray.at(hit.t), normal: ng, shading_normal, uv, uv_density, dpdu: prism_api::math::tangent(ng) }
    }

    fn area_cdf(&self) -> &[f64] {
        self.data.area_cdf.get_or_init(|| {
            let mut sum = 0.0;
            self.data
                .triangles
                .iter()
                .map(|t| {
                    let [a, b, c] = t.map(|i| self.data.positions[i as usize].as_dvec3());
                    sum += 0.5 * (b - a).cross(c - a).length();
                    sum
                })
                .collect()
        })
    }
}

/// The next f32 above a non-negative finite `x` (`f32::next_up`, which needs Rust 1.86).
#[inline]
fn next_up(x: f32) -> f32 {
    if x.is_finite() && x >= 0.0 { f32::from_bits(x.to_bits() + 1) } else { x }
}

/// The shading-normal terminator fix (Keller et al., "The Iray light transport simulation
/// and rendering system", 2017, A.3): where an interpolated or mapped normal `ns` would
/// mirror the view direction to below the geometric surface (a black band or a flipped
/// highlight at silhouettes of coarse meshes), it is replaced by the normal that mirrors the
/// view to just above the surface, halfway between the view and that direction. The normal
/// stays on the same side of the surface as the geometric normal `ng` (both are returned on
/// the side of `ng`, not of the viewer).
pub fn shading_normal_for_view(ns: DVec3, ng: DVec3, direction: DVec3) -> DVec3 {
    let v = -direction.normalize_or_zero();
    let side = if v.dot(ng) >= 0.0 { 1.0 } else { -1.0 };
    let (ng_v, ns_v) = (ng * side, ns * side);
    let r = 2.0 * v.dot(ns_v) * ns_v - v;
    let height = r.dot(ng_v);
    if height >= TERMINATOR_MARGIN || v.dot(ng_v) <= 0.0 {
        return ns;
    }
    // Lift the reflection to the margin above the tangent plane, then take the half vector.
    let tangential = (r - ng_v * height).normalize_or_zero();
    let lifted = tangential * (1.0 - TERMINATOR_MARGIN * TERMINATOR_MARGIN).sqrt() + ng_v * TERMINATOR_MARGIN;
    let bent = (v + lifted).normalize_or_zero();
    if bent == DVec3::ZERO { ng } else { bent * side }
}

impl Shape for MeshShape {
    fn bounds(&self) -> Aabb {
        self.data.bounds
    }

    fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit> {
        let wray = Self::prepare(ray)?;
        let mut best: Option<Hit> = None;
        let mut best_t = t_max;
        let bvh = &self.data.bvh;
        bvh.closest(&wray, Self::f32_bound(ray, t_max), |slot, h, [a, b, c]| {
            let t = plane_t(ray.origin, ray.direction, a, b, c).unwrap_or(f64::from(h.t));
            if t <= t_min || t >= best_t || !self.solid(slot, h.b1, h.b2) {
                return None;
            }
            best_t = t;
            best = Some(mesh_hit(t, slot as u32, h));
            // Round up so the f32 traversal never prunes a box holding an equally near hit.
            Some(next_up(t as f32))
        });
        best
    }

    /// Only a closed mesh bounds a solid; an open one is inside nothing, in CSG too.
    fn has_inside(&self) -> bool {
        self.data.is_closed()
    }

    /// A closed mesh's inside: the points from which a ray along [`INSIDE_VECTOR`] crosses
    /// the surface an odd number of times (POV-Ray's test with that `inside_vector`; the
    /// watertight triangle test counts a crossing through a shared edge once). An open mesh
    /// has no inside.
    fn inside(&self, point: DVec3) -> bool {
        if !self.data.is_closed() {
            return false;
        }
        // The traversal runs in f32 from a start a little behind the point, so that rounding
        // the point cannot skip a triangle just ahead of it; the f64 plane distance from the
        // point itself then decides which crossings lie ahead.
        let bounds = self.data.bounds;
        let behind = 1e-5 * (1.0 + bounds.min.abs().max(bounds.max.abs()).max_element().max(point.abs().max_element()));
        let start = point - INSIDE_VECTOR * behind;
        let Some(wray) = WatertightRay::new(start.as_vec3(), INSIDE_VECTOR.as_vec3()) else { return false };
        let mut crossings = 0u32;
        self.data.bvh.any(&wray, f32::INFINITY, |_, h, [a, b, c]| {
            if plane_t(point, INSIDE_VECTOR, a, b, c).unwrap_or(f64::from(h.t)) > 0.0 {
                crossings += 1;
            }
            false
        });
        crossings % 2 == 1
    }

    fn occluded(&self, ray: &Ray, t_min: f64, t_max: f64) -> bool {
        let Some(wray) = Self::prepare(ray) else { return false };
        let bvh = &self.data.bvh;
        bvh.any(&wray, Self::f32_bound(ray, t_max), |slot, h, [a, b, c]| {
            let t = plane_t(ray.origin, ray.direction, a, b, c).unwrap_or(f64::from(h.t));
            t > t_min && t < t_max && self.solid(slot, h.b1, h.b2)
        })
    }

    fn surface(&self, ray: &Ray, hit: &Hit) -> Surface {
        self.surface_at(ray, hit, true)
    }

    fn surface_geometry(&self, ray: &Ray, hit: &Hit) -> Surface {
        self.surface_at(ray, hit, false)
    }

    fn area(&self) -> Option<f64> {
        Some(self.data.area)
    }

    fn sample_area(&self, u: DVec2) -> Option<AreaSample> {
        let cdf = self.area_cdf();
        let total = *cdf.last()?;
        let target = u.x * total;
        let slot = cdf.partition_point(|&c| c <= target).min(cdf.len() - 1);
        let below = if slot == 0 { 0.0 } else { cdf[slot - 1] };
        let width = cdf[slot] - below;
        // Reuse the fraction of u.x inside the chosen triangle as a fresh number.
        let ux = if width > 0.0 { ((target - below) / width).clamp(0.0, 1.0) } else { 0.5 };
        let [a, b, c] = self.data.triangles[slot].map(|i| self.data.positions[i as usize].as_dvec3());
        let su = ux.sqrt();
        let point = a * (1.0 - su) + b * (su * (1.0 - u.y)) + c * (su * u.y);
        let normal = (b - a).cross(c - a).normalize_or(DVec3::Z);
        // The density `pdf_area` and `pdf_toward` report, from the same total.
        Some(AreaSample { point, normal, pdf_area: 1.0 / self.data.area })
    }

    fn sample_toward(&self, reference: DVec3, u: DVec2) -> Option<DirectionSample> {
        if self.data.plane_normal.is_some() {
            sample_toward_flat(self, reference, u)
        } else {
            sample_toward_by_area(self, reference, u)
        }
    }

    fn pdf_toward(&self, reference: DVec3, direction: DVec3) -> f64 {
        let Some(normal) = self.data.plane_normal else { return pdf_toward_by_area(self, reference, direction) };
        // One crossing at most: the density of the point it hits.
        let ray = Ray::new(reference, direction);
        self.intersect(&ray, 0.0, f64::INFINITY)
            .map_or(0.0, |hit| area_to_solid_angle(1.0 / self.data.area, reference, ray.at(hit.t), normal))
    }

    fn to_mitsuba(&self) -> Option<Vec<prism_api::mitsuba::MitsubaShape>> {
        use prism_api::mitsuba::{MitsubaKind, MitsubaShape, TriangleList};
        if self.maps.is_some() {
            // Alpha masks and normal maps have no Mitsuba mesh equivalent.
            return None;
        }
        let d = &self.data;
        let triangles = TriangleList {
            positions: d.positions.iter().map(|p| p.to_array()).collect(),
            normals: d.normals.iter().map(|n| n.to_array()).collect(),
            uvs: d.uvs.iter().map(|t| t.to_array()).collect(),
            triangles: d.triangles.clone(),
        };
        Some(vec![MitsubaShape::new(MitsubaKind::Triangles(triangles), prism_api::DAffine3::IDENTITY)])
    }

    fn to_pov(&self) -> Option<String> {
        use prism_api::pov::vector;
        let d = &self.data;
        let mut s = String::from("mesh2 {\n");
        push_pov_list(&mut s, "vertex_vectors", d.positions.iter().map(|p| vector(p.as_dvec3())));
        if !d.normals.is_empty() {
            push_pov_list(&mut s, "normal_vectors", d.normals.iter().map(|n| vector(n.as_dvec3())));
        }
        if !d.uvs.is_empty() {
            // POV-Ray's v counts up from the bottom of an image map.
            push_pov_list(&mut s, "uv_vectors", d.uvs.iter().map(|t| format!("<{:?}, {:?}>", t.x, 1.0 - t.y)));
        }
        push_pov_list(&mut s, "face_indices", d.triangles.iter().map(|t| format!("<{}, {}, {}>", t[0], t[1], t[2])));
        if d.is_closed() {
            // A solid in POV-Ray too, counted along the same direction as Prism's test.
            s.push_str(&format!("  inside_vector {}\n", vector(INSIDE_VECTOR)));
        }
        s.push('}');
        Some(s)
    }
}

/// Appends one of `mesh2`'s lists: `  NAME { COUNT,` then one item per line.
fn push_pov_list(s: &mut String, name: &str, items: impl ExactSizeIterator<Item = String>) {
    s.push_str(&format!("  {name} {{ {}", items.len()));
    for item in items {
        s.push_str(",\n    ");
        s.push_str(&item);
    }
    s.push_str("\n  }\n");
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// A unit square in z = 0 from two triangles, with normals tilted outward and uvs.
    pub(crate) fn square() -> MeshData {
        MeshBuilder {
            positions: vec![
                Vec3::new(0.0, 0.0, 0.0),
                Vec3::new(1.0, 0.0, 0.0),
                Vec3::new(1.0, 1.0, 0.0),
                Vec3::new(0.0, 1.0, 0.0),
            ],
            normals: vec![
                Vec3::new(-1.0, -1.0, 2.0).normalize(),
                Vec3::new(1.0, -1.0, 2.0).normalize(),
                Vec3::new(1.0, 1.0, 2.0).normalize(),
                Vec3::new(-1.0, 1.0, 2.0).normalize(),
            ],
            uvs: vec![Vec2::new(0.0, 1.0), Vec2::new(1.0, 1.0), Vec2::new(1.0, 0.0), Vec2::new(0.0, 0.0)],
            tangents: vec![],
            triangles: vec![[0, 1, 2], [0, 2, 3]],
        }
        .build()
        .unwrap()
    }

    #[test]
    fn hits_and_interpolates() {
        let shape = MeshShape::new(Arc::new(square()));
        let ray = Ray::new(DVec3::new(0.5, 0.5, 2.0), DVec3::new(0.0, 0.0, -1.0));
        let hit = shape.intersect(&ray, 1e-9, f64::INFINITY).unwrap();
        assert!((hit.t - 2.0).abs() < 1e-12);
        let s = shape.surface(&ray, &hit);
        assert!((s.normal - DVec3::Z).length() < 1e-12);
        // At the centre the four tilted normals average to +z.
        assert!((s.shading_normal - DVec3::Z).length() < 1e-6, "{}", s.shading_normal);
        assert!((s.uv - DVec2::new(0.5, 0.5)).length() < 1e-6);
        assert!((s.uv_density - 1.0).abs() < 1e-9);
        // Near a corner the normal leans outward.
        let ray = Ray::new(DVec3::new(0.99, 0.99, 2.0), DVec3::new(0.0, 0.0, -1.0));
        let s = shape.surface(&ray, &shape.intersect(&ray, 1e-9, f64::INFINITY).unwrap());
        assert!(
            s.shading_normal.x > 0.3 && s.shading_normal.y > 0.3 && (s.shading_normal.length() - 1.0).abs() < 1e-12
        );
    }

    #[test]
    fn self_intersection_is_rejected_at_tiny_t_min() {
        let shape = MeshShape::new(Arc::new(square()));
        // Far from the origin, f32 rounding is large, but the f64 plane distance is exact.
        let ray = Ray::new(DVec3::new(0.3, 0.6, 0.0), DVec3::new(0.3, 0.1, 1.0));
        assert!(shape.intersect(&ray, 1e-6, f64::INFINITY).is_none());
        assert!(!shape.occluded(&ray, 1e-6, f64::INFINITY));
    }

    #[test]
    fn terminator_bend_keeps_reflection_above_surface() {
        let ng = DVec3::Z;
        // Shading normal tilted 60 degrees; a grazing view from the other side.
        let ns = DVec3::new(-(60f64.to_radians().sin()), 0.0, 60f64.to_radians().cos());
        let d = DVec3::new(1.0, 0.0, -0.2).normalize();
        let bent = shading_normal_for_view(ns, ng, d);
        let v = -d;
        let r = 2.0 * v.dot(bent) * bent - v;
        assert!(r.dot(ng) >= TERMINATOR_MARGIN - 1e-9, "reflection {r} below the surface");
        assert!((bent.length() - 1.0).abs() < 1e-12 && bent.dot(ng) > 0.0);
        // A harmless normal is left alone.
        assert_eq!(shading_normal_for_view(ng, ng, DVec3::new(0.1, 0.0, -1.0)), ng);
        // From below, the result stays on the geometric normal's side.
        let below = shading_normal_for_view(ns, ng, DVec3::new(1.0, 0.0, 0.2).normalize());
        assert!(below.dot(ng) > 0.0);
    }

    #[test]
    fn mesh_meets_the_shape_contract() {
        let shape = MeshShape::new(Arc::new(square()));
        prism_api::contract::check_shape(&shape);
        // A closed mesh, with an inside: its crossings must flip it.
        let cube = MeshShape::new(Arc::new(tilted_cube()));
        assert!(cube.data().is_closed());
        prism_api::contract::check_shape(&cube);
    }

    /// A unit cube about the origin (side 1), each face with its own four vertices, as files
    /// repeat them at seams.
    pub(crate) fn axis_cube() -> MeshData {
        cube(|p| 0.5 * p)
    }

    /// A cube of side 2 about the origin, turned off the axes (so that the contract kit's
    /// rays along the axes cross faces rather than graze edges), faces as [`axis_cube`]'s.
    pub(crate) fn tilted_cube() -> MeshData {
        let turn = glam::DQuat::from_euler(glam::EulerRot::XYZ, 0.35, 0.5, 0.2);
        cube(|p| turn * p)
    }

    /// The cube [-1, 1]^3 with its corners moved by `place`, four vertices per face, wound
    /// counter-clockwise seen from outside.
    fn cube(place: impl Fn(DVec3) -> DVec3) -> MeshData {
        let mut builder = MeshBuilder::default();
        for axis in 0..3 {
            for sign in [-1.0, 1.0] {
                let mut normal = DVec3::ZERO;
                normal[axis] = sign;
                let u = DVec3::new(normal.z.abs(), normal.x.abs(), normal.y.abs());
                // u x v = normal.
                let v = normal.cross(u);
                let first = builder.positions.len() as u32;
                for (a, b) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
                    builder.positions.push(place(normal + u * a + v * b).as_vec3());
                }
                builder.triangles.push([first, first + 1, first + 2]);
                builder.triangles.push([first, first + 2, first + 3]);
            }
        }
        builder.build().unwrap()
    }

    #[test]
    fn closed_meshes_have_an_inside_and_open_ones_none() {
        let cube = MeshShape::new(Arc::new(tilted_cube()));
        assert_eq!(cube.data().open_edges(), 0);
        let turn = glam::DQuat::from_euler(glam::EulerRot::XYZ, 0.35, 0.5, 0.2);
        let mut rng = prism_api::contract::TestRng::new(11);
        for _ in 0..2000 {
            let local = DVec3::new(rng.range(-1.5, 1.5), rng.range(-1.5, 1.5), rng.range(-1.5, 1.5));
            let expected = local.abs().max_element() < 1.0;
            if (local.abs().max_element() - 1.0).abs() > 1e-6 {
                assert_eq!(cube.inside(turn * local), expected, "at {local} in the cube's frame");
            }
        }
        // Points within 1e-9 of a face: the f32 traversal must not lose the face just ahead.
        for _ in 0..200 {
            let ray = Ray::new(DVec3::ZERO, rng.unit_vector());
            let t = cube.intersect(&ray, 0.0, f64::INFINITY).expect("a ray from the centre leaves the cube").t;
            assert!(cube.inside(ray.at(t - 1e-9)) && !cube.inside(ray.at(t + 1e-9)), "across {}", ray.at(t));
        }
        // The square is open: four edges border one triangle each, and nothing is inside it.
        let square = MeshShape::new(Arc::new(square()));
        assert_eq!(square.data().open_edges(), 4);
        assert!(!square.inside(DVec3::new(0.5, 0.5, 0.0)));
    }

    #[test]
    fn merged_parts_keep_every_triangle_where_placed() {
        let square = Arc::new(square());
        let lifted = glam::DAffine3::from_translation(DVec3::new(0.0, 0.0, 2.0));
        let merged = MeshData::merged(
            &[(square.clone(), glam::DAffine3::IDENTITY), (square.clone(), lifted)],
            MemoryBudget::UNLIMITED,
        )
        .unwrap();
        assert_eq!(merged.triangle_count(), 4);
        assert_eq!(merged.bounds.max.z, 2.0);
        assert_eq!(merged.normals.len(), 8);
        // One part in place is shared, not copied.
        let alone = MeshData::merged(&[(square.clone(), glam::DAffine3::IDENTITY)], MemoryBudget::UNLIMITED).unwrap();
        assert!(Arc::ptr_eq(&alone, &square));
    }

    #[test]
    fn validation_rejects_bad_data() {
        let mut bad =
            MeshBuilder { positions: vec![Vec3::ZERO; 3], triangles: vec![[0, 1, 3]], ..MeshBuilder::default() };
        assert_eq!(
            bad.validate().unwrap_err(),
            MeshError::VertexOutOfRange { triangle: 0, corners: [0, 1, 3], vertices: 3 }
        );
        let mut nan = MeshBuilder { positions: vec![Vec3::new(f32::NAN, 0.0, 0.0)], ..MeshBuilder::default() };
        assert!(matches!(nan.validate().unwrap_err(), MeshError::NonFinitePosition { vertex: 0, .. }));
        let flat = MeshBuilder {
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::X * 2.0],
            triangles: vec![[0, 1, 2]],
            ..MeshBuilder::default()
        };
        assert_eq!(flat.build().unwrap_err(), MeshError::NoTriangles);
    }

    #[test]
    fn alpha_mask_cuts_out() {
        let data = Arc::new(square());
        let mut mask = crate::texture::TextureRef::new("mask");
        // Left half transparent, right half opaque.
        mask.texture = Some(Arc::new(crate::texture::Texture::from_rgba8(
            2,
            1,
            vec![[255, 255, 255, 0], [255, 255, 255, 255]],
            crate::texture::ColorSpace::Linear,
        )));
        let maps = SurfaceMaps {
            alpha_mask: Some(AlphaMask { texture: Some(mask), factor: 1.0, cutoff: 0.5 }),
            normal_map: None,
        };
        let shape = MeshShape::with_maps(data, maps);
        let down = DVec3::new(0.0, 0.0, -1.0);
        assert!(shape.intersect(&Ray::new(DVec3::new(0.25, 0.5, 1.0), down), 1e-9, f64::INFINITY).is_none());
        assert!(shape.intersect(&Ray::new(DVec3::new(0.75, 0.5, 1.0), down), 1e-9, f64::INFINITY).is_some());
        assert!(!shape.occluded(&Ray::new(DVec3::new(0.25, 0.5, 1.0), down), 1e-9, f64::INFINITY));
    }

    /// A flat mesh (a quad light, here tilted so that f32 rounding leaves its corners off
    /// the exact plane) samples directions as a flat shape, with the densities the general
    /// crossing-by-crossing sum gives; a closed or bent mesh is not flat.
    #[test]
    fn flat_meshes_sample_directions_as_flat_shapes() {
        let (u, v) = (DVec3::new(0.8, 0.36, -0.48), DVec3::new(0.0, 0.8, 0.6));
        let corner = |a: f64, b: f64| (DVec3::new(1.0, 2.0, 3.0) + u * a + v * b).as_vec3();
        let quad = MeshBuilder {
            positions: vec![corner(0.0, 0.0), corner(2.0, 0.0), corner(2.0, 1.5), corner(0.0, 1.5)],
            triangles: vec![[0, 1, 2], [0, 2, 3]],
            ..MeshBuilder::default()
        }
        .build()
        .unwrap();
        let normal = quad.plane_normal.expect("flat");
        assert!(normal.dot(u.cross(v)).abs() > 1.0 - 1e-6);
        let shape = MeshShape::new(Arc::new(quad));
        for (i, reference) in [DVec3::new(0.0, 0.0, 10.0), DVec3::new(3.0, -2.0, -4.0)].into_iter().enumerate() {
            for k in 0..50 {
                let sample_u = DVec2::new(f64::from(k) / 50.0 + 0.01, f64::from(k * 7 % 50) / 50.0 + 0.01);
                let sample = shape.sample_toward(reference, sample_u).expect("visible");
                let direction = sample.point - reference;
                let general = pdf_toward_by_area(&shape, reference, direction);
                for pdf in [sample.pdf_solid_angle, shape.pdf_toward(reference, direction)] {
                    assert!((pdf / general - 1.0).abs() < 1e-6, "reference {i}, sample {k}: {pdf} vs {general}");
                }
            }
            assert_eq!(shape.pdf_toward(reference, DVec3::new(0.0, 0.0, 1.0) - reference * 2.0), 0.0);
        }
        let bent = MeshBuilder {
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.01), Vec3::Y],
            triangles: vec![[0, 1, 2], [0, 2, 3]],
            ..MeshBuilder::default()
        }
        .build()
        .unwrap();
        assert!(bent.plane_normal.is_none() && square().plane_normal.is_some());
    }

    #[test]
    fn area_sampling_stays_on_the_mesh() {
        let shape = MeshShape::new(Arc::new(square()));
        assert!((shape.area().unwrap() - 1.0).abs() < 1e-12);
        for u in [DVec2::new(0.1, 0.9), DVec2::new(0.99, 0.01), DVec2::new(0.5, 0.5)] {
            let s = shape.sample_area(u).unwrap();
            assert!(
                s.point.z.abs() < 1e-12 && s.point.x >= 0.0 && s.point.x <= 1.0 && s.point.y >= 0.0 && s.point.y <= 1.0
            );
        }
    }
}
