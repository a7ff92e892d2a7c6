//! Stanford PLY import: ASCII, binary little-endian and binary big-endian PLY 1.0, gzip
//! compressed or not (told by the magic bytes, not the name). The `vertex` element gives
//! positions (`x y z`), and when present normals (`nx ny nz`), colours (`red green blue`) and
//! texture coordinates (`u v`, `s t` or `texture_u texture_v`); the `face` element's
//! `vertex_indices` (or `vertex_index`) list gives polygons, triangulated by ear clipping.
//! Other elements and properties are read past.
//!
//! The parser is our own so that every error names where it is: the header line, or for the
//! data the element, the item and the line (ASCII) or byte offset (binary). The header's
//! counts are checked against the bytes that follow before anything is sized by them.

use std::io::Read;
use std::path::Path;
use std::sync::Arc;

use glam::{DAffine3, DVec3, Vec2, Vec3};

use super::triangulate::triangulate;
use super::{ImportError, ImportErrorKind, ImportOptions, Model, ModelNode, ModelPart};
use crate::files::{FileKind, MAX_MESH_BYTES};
use crate::geometry::mesh::{MeshBuilder, MeshError, MeshShape};
use crate::material::Material;
use crate::texture::TextureStore;

/// How the data after the header is encoded.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// Whitespace-separated numbers.
    Ascii,
    /// Binary, least significant byte first.
    BinaryLittleEndian,
    /// Binary, most significant byte first.
    BinaryBigEndian,
}

/// A scalar property type.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Scalar {
    fn parse(name: &str) -> Option<Self> {
        Some(match name {
            "char" | "int8" => Scalar::I8,
            "uchar" | "uint8" => Scalar::U8,
            "short" | "int16" => Scalar::I16,
            "ushort" | "uint16" => Scalar::U16,
            "int" | "int32" => Scalar::I32,
            "uint" | "uint32" => Scalar::U32,
            "float" | "float32" => Scalar::F32,
            "double" | "float64" => Scalar::F64,
            _ => return None,
        })
    }

    fn size(self) -> usize {
        match self {
            Scalar::I8 | Scalar::U8 => 1,
            Scalar::I16 | Scalar::U16 => 2,
            Scalar::I32 | Scalar::U32 | Scalar::F32 => 4,
            Scalar::F64 => 8,
        }
    }

    fn is_integer(self) -> bool {
        !matches!(self, Scalar::F32 | Scalar::F64)
    }

    /// The range of an integer type.
    fn range(self) -> (f64, f64) {
        match self {
            Scalar::I8 => (i8::MIN.into(), i8::MAX.into()),
            Scalar::U8 => (0.0, u8::MAX.into()),
            Scalar::I16 => (i16::MIN.into(), i16::MAX.into()),
            Scalar::U16 => (0.0, u16::MAX.into()),
            Scalar::I32 => (i32::MIN.into(), i32::MAX.into()),
            Scalar::U32 => (0.0, u32::MAX.into()),
            Scalar::F32 | Scalar::F64 => (f64::NEG_INFINITY, f64::INFINITY),
        }
    }

    fn name(self) -> &'static str {
        match self {
            Scalar::I8 => "char",
            Scalar::U8 => "uchar",
            Scalar::I16 => "short",
            Scalar::U16 => "ushort",
            Scalar::I32 => "int",
            Scalar::U32 => "uint",
            Scalar::F32 => "float",
            Scalar::F64 => "double",
        }
    }
}

/// A property of an element: one scalar, or a list (count type, item type).
#[derive(Clone, Debug)]
enum PropertyType {
    Scalar(Scalar),
    List(Scalar, Scalar),
}

#[derive(Clone, Debug)]
struct Property {
    name: String,
    kind: PropertyType,
}

#[derive(Clone, Debug)]
struct Element {
    name: String,
    count: u64,
    properties: Vec<Property>,
    /// The header line that declares it.
    line: usize,
}

impl Element {
    fn property(&self, names: &[&str]) -> Option<usize> {
        names.iter().find_map(|n| self.properties.iter().position(|p| p.name == *n))
    }

    /// The fewest bytes one item can take: binary, every scalar and list count with empty
    /// lists; ASCII, one character and one separator per value.
    fn min_item_bytes(&self, format: Format) -> u64 {
        self.properties
            .iter()
            .map(|p| match (format, &p.kind) {
                (Format::Ascii, _) => 2,
                (_, PropertyType::Scalar(s) | PropertyType::List(s, _)) => s.size() as u64,
            })
            .sum()
    }
}

/// The vertex and face data of a PLY file.
#[derive(Clone, Debug, Default)]
pub struct PlyData {
    /// The encoding of the data.
    pub format: Option<Format>,
    /// True when the file was gzip-compressed.
    pub gzipped: bool,
    /// Vertex positions (file units).
    pub positions: Vec<Vec3>,
    /// Vertex normals: empty, or one per vertex.
    pub normals: Vec<Vec3>,
    /// Vertex colours scaled to 0..1 (integer channels divided by their type's maximum):
    /// empty, or one per vertex.
    pub colors: Vec<[f32; 3]>,
    /// Texture coordinates as written (v up): empty, or one per vertex.
    pub uvs: Vec<Vec2>,
    /// Polygon corners (vertex indices, all checked against the vertex count), polygon after
    /// polygon.
    pub corners: Vec<u32>,
    /// Where each polygon starts in [`PlyData::corners`] (and one past the last).
    pub polygon_starts: Vec<usize>,
}

impl PlyData {
    /// The polygons as slices of vertex indices.
    pub fn polygons(&self) -> impl Iterator<Item = &[u32]> {
        self.polygon_starts.windows(2).map(|w| &self.corners[w[0]..w[1]])
    }
}

/// Reads a PLY file (`.ply` or `.ply.gz`) through `textures`' file access, reserving its
/// mesh's memory out of the load's budget before building it.
pub fn import(path: &Path, options: &ImportOptions, textures: &mut TextureStore) -> Result<Model, ImportError> {
    let bytes =
        textures.access().read(path, FileKind::Mesh).map_err(|e| ImportError::new(path, ImportErrorKind::File(e)))?;
    let data = parse(&bytes, path)?;
    drop(bytes);
    let triangles: u64 = data.polygons().map(|p| p.len().saturating_sub(2) as u64).sum();
    let estimate = MeshBuilder::estimate_for(data.positions.len() as u64, triangles);
    textures
        .reserve(|| format!("{triangles} triangles with their BVH"), estimate)
        .map_err(|e| ImportError::new(path, ImportErrorKind::OverBudget(e)))?;
    model(&data, options, path)
}

/// Parses PLY bytes (gzip-compressed or not); `name` is the file named in errors.
pub fn parse(bytes: &[u8], name: &Path) -> Result<PlyData, ImportError> {
    let invalid =
        |line: Option<usize>, message: String| ImportError::new(name, ImportErrorKind::Invalid(message)).at_line(line);
    let gzipped = bytes.starts_with(&[0x1f, 0x8b]);
    let inflated;
    let bytes = if gzipped {
        let mut out = Vec::new();
        flate2::read::MultiGzDecoder::new(bytes)
            .take(MAX_MESH_BYTES + 1)
            .read_to_end(&mut out)
            .map_err(|e| invalid(None, format!("gzip data is broken after {} decompressed bytes: {e}", out.len())))?;
        if out.len() as u64 > MAX_MESH_BYTES {
            return Err(invalid(None, format!("decompresses to more than the limit of {MAX_MESH_BYTES} bytes")));
        }
        inflated = out;
        &inflated[..]
    } else {
        bytes
    };
    let header = parse_header(bytes).map_err(|(line, message)| invalid(line, message))?;
    let mut data = PlyData { format: Some(header.format), gzipped, ..PlyData::default() };
    read_body(&header, bytes, &mut data).map_err(|(line, message)| invalid(line, message))?;
    Ok(data)
}

struct Header {
    format: Format,
    elements: Vec<Element>,
    /// Byte offset of the first data byte.
    body: usize,
    /// Lines the header takes (the data's first line is `lines + 1`).
    lines: usize,
}

type Located = (Option<usize>, String);

fn parse_header(bytes: &[u8]) -> Result<Header, Located> {
    let mut format = None;
    let mut elements: Vec<Element> = Vec::new();
    let mut at = 0;
    let mut line_no = 0;
    loop {
        let Some(len) = bytes[at..].iter().position(|&b| b == b'\n') else {
            let what = if line_no == 0 { "the file is empty or has a single line" } else { "the file ends first" };
            return Err((None, format!("no `end_header` line ({what}; {line_no} header lines read)")));
        };
        line_no += 1;
        let raw = &bytes[at..at + len];
        at += len + 1;
        let raw = raw.strip_suffix(b"\r").unwrap_or(raw);
        let Ok(line) = std::str::from_utf8(raw) else {
            let message = if line_no == 1 {
                "not a PLY file (it does not start with `ply`)"
            } else {
                "the header holds bytes that are not text"
            };
            return Err((Some(line_no), message.into()));
        };
        let words: Vec<&str> = line.split_ascii_whitespace().collect();
        let here = Some(line_no);
        if line_no == 1 {
            if words != ["ply"] {
                return Err((here, "not a PLY file (it does not start with `ply`)".into()));
            }
            continue;
        }
        match words.as_slice() {
            [] => {}
            ["comment" | "obj_info", ..] => {}
            ["format", kind, version] => {
                if format.is_some() {
                    return Err((here, "a second `format` line".into()));
                }
                format = Some(match *kind {
                    "ascii" => Format::Ascii,
                    "binary_little_endian" => Format::BinaryLittleEndian,
                    "binary_big_endian" => Format::BinaryBigEndian,
                    other => {
                        return Err((
                            here,
                            format!(
                                "unknown format `{}` (expected ascii, binary_little_endian or binary_big_endian)",
                                crate::files::shown(other)
                            ),
                        ));
                    }
                });
                if *version != "1.0" {
                    return Err((
                        here,
                        format!("unsupported PLY version `{}` (expected 1.0)", crate::files::shown(version)),
                    ));
                }
            }
            ["format", ..] => return Err((here, "`format` needs a format and a version (`format ascii 1.0`)".into())),
            ["element", name, count] => {
                let count = count.parse::<u64>().map_err(|_| {
                    (
                        here,
                        format!(
                            "element `{}`: the count `{}` is not a whole number",
                            crate::files::shown(name),
                            crate::files::shown(count)
                        ),
                    )
                })?;
                if elements.iter().any(|e| e.name == *name) {
                    return Err((here, format!("element `{}` is declared twice", crate::files::shown(name))));
                }
                elements.push(Element { name: name.to_string(), count, properties: Vec::new(), line: line_no });
            }
            ["element", ..] => return Err((here, "`element` needs a name and a count (`element vertex 8`)".into())),
            ["property", rest @ ..] => {
                let Some(element) = elements.last_mut() else {
                    return Err((here, "a `property` before any `element`".into()));
                };
                let scalar = |word: &str| {
                    Scalar::parse(word).ok_or_else(|| {
                        (
                            here,
                            format!(
                                "element `{}`: unknown property type `{}` (expected char, uchar, short, ushort, int, uint, float, double or int8 ... float64)",
                                element.name,
                                crate::files::shown(word)
                            ),
                        )
                    })
                };
                let (kind, name) = match rest {
                    ["list", count, item, name] => {
                        let count_type = scalar(count)?;
                        let item_type = scalar(item)?;
                        if !count_type.is_integer() {
                            return Err((
                                here,
                                format!(
                                    "element `{}`: list `{name}` has a count of type {} (it must be an integer type)",
                                    element.name,
                                    count_type.name()
                                ),
                            ));
                        }
                        (PropertyType::List(count_type, item_type), *name)
                    }
                    ["list", ..] => {
                        return Err((
                            here,
                            format!(
                                "element `{}`: `property list` needs a count type, an item type and a name",
                                element.name
                            ),
                        ));
                    }
                    [kind, name] => (PropertyType::Scalar(scalar(kind)?), *name),
                    _ => return Err((here, format!("element `{}`: `property` needs a type and a name", element.name))),
                };
                if element.properties.iter().any(|p| p.name == name) {
                    return Err((
                        here,
                        format!(
                            "element `{}`: property `{}` is declared twice",
                            element.name,
                            crate::files::shown(name)
                        ),
                    ));
                }
                element.properties.push(Property { name: name.to_string(), kind });
            }
            ["end_header"] => break,
            [word, ..] => {
                return Err((
                    here,
                    format!(
                        "unknown header line `{}` (expected format, element, property, comment or end_header)",
                        crate::files::shown(word)
                    ),
                ));
            }
        }
    }
    let Some(format) = format else {
        return Err((None, "the header has no `format` line".into()));
    };
    Ok(Header { format, elements, body: at, lines: line_no })
}

/// Reads the data after the header, element by element, into `data`.
fn read_body(header: &Header, bytes: &[u8], data: &mut PlyData) -> Result<(), Located> {
    let vertex = header
        .elements
        .iter()
        .find(|e| e.name == "vertex")
        .ok_or((None, "no `vertex` element in the header".to_string()))?;
    for axis in ["x", "y", "z"] {
        match vertex.property(&[axis]).map(|i| &vertex.properties[i].kind) {
            Some(PropertyType::Scalar(_)) => {}
            Some(PropertyType::List(..)) => {
                return Err((Some(vertex.line), format!("element `vertex`: property `{axis}` is a list")));
            }
            None => return Err((Some(vertex.line), format!("element `vertex` has no property `{axis}`"))),
        }
    }
    // Counts first: no allocation is sized by a count the remaining bytes cannot hold.
    let available = (bytes.len() - header.body) as u128;
    // The last ASCII value needs no separator after it.
    let slack = u128::from(header.format == Format::Ascii);
    let mut needed: u128 = 0;
    for e in &header.elements {
        needed += u128::from(e.count) * u128::from(e.min_item_bytes(header.format));
        if needed > available + slack {
            return Err((
                Some(e.line),
                format!(
                    "element `{}`: the header promises {} items, but the {available} bytes of data after the header cannot hold them",
                    crate::files::shown(&e.name),
                    e.count
                ),
            ));
        }
    }
    let vertex_count = vertex.count;
    if vertex_count > u64::from(u32::MAX) {
        return Err((
            Some(vertex.line),
            format!("element `vertex`: {vertex_count} vertices is more than Prism indexes"),
        ));
    }
    let mut reader = match header.format {
        Format::Ascii => {
            Reader::Ascii(Ascii { bytes, at: header.body, line: header.lines + 1, token_line: header.lines })
        }
        Format::BinaryLittleEndian => {
            Reader::Binary(Binary { bytes, at: header.body, last: header.body, little: true })
        }
        Format::BinaryBigEndian => Reader::Binary(Binary { bytes, at: header.body, last: header.body, little: false }),
    };
    for element in &header.elements {
        let roles = Roles::of(element);
        let count = element.count as usize;
        if element.name == "vertex" {
            data.positions.reserve_exact(count);
            if roles.normal.is_some() {
                data.normals.reserve_exact(count);
            }
            if roles.color.is_some() {
                data.colors.reserve_exact(count);
            }
            if roles.uv.is_some() {
                data.uvs.reserve_exact(count);
            }
        }
        let mut values = vec![0.0f64; element.properties.len()];
        for item in 0..count {
            for (p, property) in element.properties.iter().enumerate() {
                let context = || {
                    format!(
                        "element `{}` item {item}, property `{}`",
                        crate::files::shown(&element.name),
                        crate::files::shown(&property.name)
                    )
                };
                match property.kind {
                    PropertyType::Scalar(s) => {
                        values[p] = reader.value(s).map_err(|(at, m)| (at, format!("{}: {m}", context())))?
                    }
                    PropertyType::List(count_type, item_type) => {
                        let n = reader
                            .value(count_type)
                            .map_err(|(at, m)| (at, format!("{}: list length: {m}", context())))?;
                        if n < 0.0 {
                            return Err((reader.line(), format!("{}: negative list length {n}", context())));
                        }
                        let n = n as usize;
                        // Each entry takes at least one byte (binary: its size; ASCII: a
                        // digit and a separator), so a length past the end is caught here.
                        if n.saturating_mul(reader.min_entry_bytes(item_type)) > reader.remaining() {
                            return Err(reader.locate(format!(
                                "{}: list of {n} entries runs past the end of the file (truncated?)",
                                context()
                            )));
                        }
                        let is_faces = roles.faces == Some(p);
                        if is_faces && !item_type.is_integer() {
                            return Err((
                                Some(element.line),
                                format!(
                                    "element `face`: `{}` must be an integer list, not {}",
                                    property.name,
                                    item_type.name()
                                ),
                            ));
                        }
                        for k in 0..n {
                            let v = reader
                                .value(item_type)
                                .map_err(|(at, m)| (at, format!("{}: entry {k}: {m}", context())))?;
                            if is_faces {
                                if v < 0.0 || v >= vertex_count as f64 {
                                    return Err(reader.locate(format!(
                                        "{}: vertex index {v}, but there are only {vertex_count} vertices",
                                        context()
                                    )));
                                }
                                data.corners.push(v as u32);
                            }
                        }
                        if is_faces {
                            data.polygon_starts.push(data.corners.len() - n);
                        }
                    }
                }
            }
            if element.name == "vertex" {
                let get = |i: usize| values[i] as f32;
                let [x, y, z] = roles.position;
                data.positions.push(Vec3::new(get(x), get(y), get(z)));
                if let Some([x, y, z]) = roles.normal {
                    data.normals.push(Vec3::new(get(x), get(y), get(z)));
                }
                if let Some(([r, g, b], scale)) = roles.color {
                    data.colors.push([r, g, b].map(|i| (values[i] / scale) as f32));
                }
                if let Some([u, v]) = roles.uv {
                    data.uvs.push(Vec2::new(get(u), get(v)));
                }
            }
        }
    }
    if !data.corners.is_empty() || !data.polygon_starts.is_empty() {
        data.polygon_starts.push(data.corners.len());
    }
    if let Some(extra) = reader.trailing() {
        return Err(extra);
    }
    Ok(())
}

/// Which properties of an element carry which vertex attribute.
#[derive(Default)]
struct Roles {
    position: [usize; 3],
    normal: Option<[usize; 3]>,
    /// The channels and the value that means full intensity.
    color: Option<([usize; 3], f64)>,
    uv: Option<[usize; 2]>,
    /// The list property holding a face's vertex indices.
    faces: Option<usize>,
}

impl Roles {
    fn of(element: &Element) -> Self {
        let scalar = |names: &[&str]| {
            element.property(names).filter(|&i| matches!(element.properties[i].kind, PropertyType::Scalar(_)))
        };
        let mut roles = Roles::default();
        if element.name == "vertex" {
            roles.position = [scalar(&["x"]), scalar(&["y"]), scalar(&["z"])].map(|i| i.expect("checked before"));
            if let (Some(x), Some(y), Some(z)) = (scalar(&["nx"]), scalar(&["ny"]), scalar(&["nz"])) {
                roles.normal = Some([x, y, z]);
            }
            if let (Some(r), Some(g), Some(b)) = (
                scalar(&["red", "r", "diffuse_red"]),
                scalar(&["green", "g", "diffuse_green"]),
                scalar(&["blue", "b", "diffuse_blue"]),
            ) {
                let full = match element.properties[r].kind {
                    PropertyType::Scalar(s) if s.is_integer() => s.range().1,
                    _ => 1.0,
                };
                roles.color = Some(([r, g, b], full));
            }
            let pairs: [[&str; 2]; 3] = [["u", "v"], ["s", "t"], ["texture_u", "texture_v"]];
            roles.uv = pairs.iter().find_map(|[u, v]| Some([scalar(&[u])?, scalar(&[v])?]));
        }
        if element.name == "face" {
            roles.faces = element
                .property(&["vertex_indices", "vertex_index"])
                .filter(|&i| matches!(element.properties[i].kind, PropertyType::List(..)));
        }
        roles
    }
}

enum Reader<'a> {
    Ascii(Ascii<'a>),
    Binary(Binary<'a>),
}

struct Ascii<'a> {
    bytes: &'a [u8],
    at: usize,
    /// 1-based line of `at`.
    line: usize,
    /// 1-based line of the last token read (where the file ends, when it ends early).
    token_line: usize,
}

struct Binary<'a> {
    bytes: &'a [u8],
    at: usize,
    /// Offset of the last value read.
    last: usize,
    little: bool,
}

impl Reader<'_> {
    /// Where the reader is, for errors: the line (ASCII) or `None` (binary: the byte offset
    /// goes into the message).
    fn line(&self) -> Option<usize> {
        match self {
            Reader::Ascii(a) => Some(a.line),
            Reader::Binary(_) => None,
        }
    }

    fn remaining(&self) -> usize {
        match self {
            Reader::Ascii(a) => a.bytes.len() - a.at,
            Reader::Binary(b) => b.bytes.len() - b.at,
        }
    }

    /// The fewest bytes a list entry takes: its size (binary) or one digit (ASCII).
    fn min_entry_bytes(&self, s: Scalar) -> usize {
        match self {
            Reader::Ascii(_) => 1,
            Reader::Binary(_) => s.size(),
        }
    }

    /// `message` at the last value read: its line (ASCII) or byte offset (binary).
    fn locate(&self, message: String) -> Located {
        match self {
            Reader::Ascii(a) => (Some(a.token_line), message),
            Reader::Binary(b) => (None, format!("byte offset {}: {message}", b.last)),
        }
    }

    /// The next value of type `s`, range-checked for integer types.
    fn value(&mut self, s: Scalar) -> Result<f64, Located> {
        match self {
            Reader::Ascii(a) => a.value(s),
            Reader::Binary(b) => b.value(s),
        }
    }

    /// An error when anything but whitespace follows the last element.
    fn trailing(&mut self) -> Option<Located> {
        match self {
            Reader::Ascii(a) => {
                a.skip_space();
                (a.at < a.bytes.len())
                    .then(|| (Some(a.line), "data after the last element (the header's counts are too small)".into()))
            }
            Reader::Binary(b) => (b.at < b.bytes.len()).then(|| {
                (
                    None,
                    format!(
                        "byte offset {}: {} bytes after the last element (the header's counts or types do not match the data)",
                        b.at,
                        b.bytes.len() - b.at
                    ),
                )
            }),
        }
    }
}

impl Ascii<'_> {
    fn skip_space(&mut self) {
        while let Some(&c) = self.bytes.get(self.at) {
            if c == b'\n' {
                self.line += 1;
            } else if !c.is_ascii_whitespace() {
                break;
            }
            self.at += 1;
        }
    }

    fn value(&mut self, s: Scalar) -> Result<f64, Located> {
        self.skip_space();
        let start = self.at;
        while self.at < self.bytes.len() && !self.bytes[self.at].is_ascii_whitespace() {
            self.at += 1;
        }
        if start == self.at {
            return Err((
                Some(self.token_line),
                "the file ends here (truncated, or the header's counts are too large)".into(),
            ));
        }
        self.token_line = self.line;
        let token = std::str::from_utf8(&self.bytes[start..self.at])
            .map_err(|_| (Some(self.line), "bytes that are not text in ASCII data".to_string()))?;
        let shown = crate::files::shown(token);
        if s.is_integer() {
            let v = token
                .parse::<i64>()
                .map_err(|_| (Some(self.line), format!("`{shown}` is not an integer ({})", s.name())))?;
            let (lo, hi) = s.range();
            if (v as f64) < lo || (v as f64) > hi {
                return Err((Some(self.line), format!("{v} is out of range for {}", s.name())));
            }
            Ok(v as f64)
        } else {
            token.parse::<f64>().map_err(|_| (Some(self.line), format!("`{shown}` is not a number ({})", s.name())))
        }
    }
}

impl Binary<'_> {
    fn value(&mut self, s: Scalar) -> Result<f64, Located> {
        let n = s.size();
        let Some(raw) = self.bytes.get(self.at..self.at + n) else {
            return Err((
                None,
                format!(
                    "byte offset {}: the file ends here ({} bytes left, a {} needs {n}; truncated, or the header's counts are too large)",
                    self.at,
                    self.bytes.len() - self.at,
                    s.name()
                ),
            ));
        };
        self.last = self.at;
        self.at += n;
        let mut b = [0u8; 8];
        b[..n].copy_from_slice(raw);
        if !self.little {
            b[..n].reverse();
        }
        Ok(match s {
            Scalar::I8 => f64::from(b[0] as i8),
            Scalar::U8 => f64::from(b[0]),
            Scalar::I16 => f64::from(i16::from_le_bytes([b[0], b[1]])),
            Scalar::U16 => f64::from(u16::from_le_bytes([b[0], b[1]])),
            Scalar::I32 => f64::from(i32::from_le_bytes([b[0], b[1], b[2], b[3]])),
            Scalar::U32 => f64::from(u32::from_le_bytes([b[0], b[1], b[2], b[3]])),
            Scalar::F32 => f64::from(f32::from_le_bytes([b[0], b[1], b[2], b[3]])),
            Scalar::F64 => f64::from_le_bytes(b),
        })
    }
}

/// The [`Model`] of parsed PLY data: one node, one part with the default material.
pub fn model(data: &PlyData, options: &ImportOptions, name: &Path) -> Result<Model, ImportError> {
    let mut warnings = Vec::new();
    let mut builder = MeshBuilder {
        positions: data.positions.clone(),
        normals: data.normals.clone(),
        // PLY's v points up, the mesh's (glTF's) down.
        uvs: data.uvs.iter().map(|t| Vec2::new(t.x, 1.0 - t.y)).collect(),
        ..MeshBuilder::default()
    };
    let mut short = 0usize;
    for (face, polygon) in data.polygons().enumerate() {
        match polygon.len() {
            0..=2 => short += 1,
            3 => builder.triangles.push([polygon[0], polygon[1], polygon[2]]),
            _ => {
                let points: Vec<DVec3> = polygon.iter().map(|&i| data.positions[i as usize].as_dvec3()).collect();
                let triangles = triangulate(&points).map_err(|e| {
                    ImportError::new(name, ImportErrorKind::Invalid(format!("element `face` {face}: {e}")))
                })?;
                builder.triangles.extend(triangles.into_iter().map(|t| t.map(|k| polygon[k])));
            }
        }
    }
    if short > 0 {
        warnings.push(format!("{short} faces with fewer than 3 vertices skipped"));
    }
    if !data.colors.is_empty() {
        warnings.push(
            "vertex colours are not rendered (meshes carry no per-vertex colour); the material's colour is used".into(),
        );
    }
    if builder.triangles.is_empty() {
        warnings.push("no faces: nothing to render (a point cloud)".into());
        let nodes = vec![ModelNode { name: None, parent: None, local: DAffine3::IDENTITY }];
        return Ok(Model { nodes, warnings, ..Model::default() });
    }
    if builder.normals.is_empty()
        && let Some(angle) = options.smooth_angle
    {
        let ids: Vec<(usize, u32)> = (0..builder.positions.len() as u32).map(|i| (0, i)).collect();
        super::obj::smooth_normals(&mut builder, &ids, angle);
    }
    let mut parts = Vec::new();
    match builder.build() {
        Ok(mesh) => parts.push(ModelPart {
            node: 0,
            shape: Arc::new(MeshShape::new(Arc::new(mesh))),
            material: Arc::new(Material::default()),
            material_name: None,
        }),
        Err(MeshError::NoTriangles) => warnings.push("only zero-area faces: nothing to render".into()),
        Err(source) => {
            return Err(ImportError::new(name, ImportErrorKind::Mesh { part: "element `vertex`".into(), source }));
        }
    }
    let nodes = vec![ModelNode { name: None, parent: None, local: DAffine3::IDENTITY }];
    Ok(Model { nodes, parts, warnings, ..Model::default() })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse_str(text: &str) -> Result<PlyData, String> {
        parse(text.as_bytes(), Path::new("t.ply")).map_err(|e| e.to_string())
    }

    const QUAD: &str = "ply\nformat ascii 1.0\ncomment a unit square\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nproperty float u\nproperty float v\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0 255 0 0 0 0\n1 0 0 0 255 0 1 0\n1 1 0 0 0 255 1 1\n0 1 0 255 255 255 0 1\n4 0 1 2 3\n";

    /// The same square as binary PLY with normals, in either byte order.
    fn binary_quad(little: bool) -> Vec<u8> {
        let order = if little { "binary_little_endian" } else { "binary_big_endian" };
        let mut bytes = format!(
            "ply\r\nformat {order} 1.0\r\nelement vertex 4\r\nproperty double x\r\nproperty double y\r\nproperty double z\r\nproperty float nx\r\nproperty float ny\r\nproperty float nz\r\nelement face 2\r\nproperty list uchar uint vertex_indices\r\nproperty int flags\r\nend_header\r\n"
        )
        .into_bytes();
        let f64b = |v: f64| if little { v.to_le_bytes().to_vec() } else { v.to_be_bytes().to_vec() };
        let f32b = |v: f32| if little { v.to_le_bytes().to_vec() } else { v.to_be_bytes().to_vec() };
        let u32b = |v: u32| if little { v.to_le_bytes().to_vec() } else { v.to_be_bytes().to_vec() };
        for [x, y] in [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]] {
            for v in [x, y, 0.0] {
                bytes.extend(f64b(v));
            }
            for v in [0.0, 0.0, 1.0] {
                bytes.extend(f32b(v));
            }
        }
        for tri in [[0, 1, 2], [0, 2, 3]] {
            bytes.push(3);
            for i in tri {
                bytes.extend(u32b(i));
            }
            bytes.extend(u32b(7));
        }
        bytes
    }

    fn gzip(bytes: &[u8]) -> Vec<u8> {
        use std::io::Write;
        let mut e = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::fast());
        e.write_all(bytes).unwrap();
        e.finish().unwrap()
    }

    #[test]
    fn ascii_with_colours_and_uvs() {
        let d = parse_str(QUAD).unwrap();
        assert_eq!(d.format, Some(Format::Ascii));
        assert_eq!(d.positions.len(), 4);
        assert_eq!(d.positions[2], Vec3::new(1.0, 1.0, 0.0));
        assert_eq!(d.colors[1], [0.0, 1.0, 0.0]);
        assert_eq!(d.uvs[2], Vec2::new(1.0, 1.0));
        assert!(d.normals.is_empty());
        assert_eq!(d.polygons().collect::<Vec<_>>(), vec![&[0u32, 1, 2, 3][..]]);
        let m = model(&d, &ImportOptions::default(), Path::new("t.ply")).unwrap();
        assert_eq!(m.triangle_count(), 2);
        assert!(m.warnings.iter().any(|w| w.contains("colours")), "{:?}", m.warnings);
    }

    #[test]
    fn binary_both_byte_orders_and_gzip_agree() {
        let little = parse(&binary_quad(true), Path::new("l.ply")).unwrap();
        let big = parse(&binary_quad(false), Path::new("b.ply")).unwrap();
        let zipped = parse(&gzip(&binary_quad(false)), Path::new("b.ply.gz")).unwrap();
        assert_eq!(little.format, Some(Format::BinaryLittleEndian));
        assert_eq!(big.format, Some(Format::BinaryBigEndian));
        assert!(zipped.gzipped && !big.gzipped);
        for d in [&big, &zipped] {
            assert_eq!(d.positions, little.positions);
            assert_eq!(d.normals, little.normals);
            assert_eq!(d.corners, little.corners);
        }
        assert_eq!(little.positions[3], Vec3::new(0.0, 1.0, 0.0));
        assert_eq!(little.normals[0], Vec3::Z);
        assert_eq!(little.corners, vec![0, 1, 2, 0, 2, 3]);
        let ascii_gz = parse(&gzip(QUAD.as_bytes()), Path::new("q.ply.gz")).unwrap();
        assert_eq!(ascii_gz.positions, parse_str(QUAD).unwrap().positions);
    }

    #[test]
    fn smoothing_applies_only_without_normals() {
        let d = parse_str(QUAD).unwrap();
        let smooth = model(&d, &ImportOptions { smooth_angle: Some(60.0) }, Path::new("t.ply")).unwrap();
        assert!(smooth.parts[0].shape.data().has_normals());
        let flat = model(&d, &ImportOptions::default(), Path::new("t.ply")).unwrap();
        assert!(!flat.parts[0].shape.data().has_normals());
    }

    /// Each broken file's error names the file, the place and the problem.
    #[test]
    fn broken_headers_and_data_are_located_errors() {
        let header = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
        let good_body = "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
        assert!(parse_str(&format!("{header}{good_body}")).is_ok());
        // Without the last newline, and with CRLF line ends, the file is still whole.
        assert!(parse_str(&format!("{header}{}", good_body.trim_end())).is_ok());
        assert!(parse_str(&format!("{header}{good_body}").replace('\n', "\r\n")).is_ok());
        let cases: Vec<(String, &[&str])> = vec![
            ("PLY\nformat ascii 1.0\nend_header\n".into(), &["t.ply:1", "not a PLY file"]),
            ("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n".into(), &["t.ply", "no `end_header`"]),
            (header.replace("ascii", "utf8"), &["t.ply:2", "unknown format `utf8`"]),
            (
                format!("{}{good_body}", header.replace("float y", "float3 y")),
                &["t.ply:5", "unknown property type `float3`"],
            ),
            (
                format!("{}{good_body}", header.replace("list uchar int", "list float int")),
                &["t.ply:8", "integer type"],
            ),
            (
                format!("{}{good_body}", header.replace("list uchar int", "list uchar float")),
                &["t.ply:7", "integer list"],
            ),
            (
                format!("{}{good_body}", header.replace("vertex 3", "vertex 3000000")),
                &["t.ply:3", "`vertex`", "3000000 items"],
            ),
            (
                format!("{}{good_body}", header.replace("vertex 3", "vertex 4")),
                &["t.ply:13", "`face` item 0", "list of 2 entries runs past the end"],
            ),
            (
                format!("{}{good_body}", header.replace("vertex 3", "vertex 2")),
                &["t.ply:12", "data after the last element"],
            ),
            (
                format!("{header}0 0 0\n1 0 0\n0 1 0\n3 0 1 9\n"),
                &["t.ply:13", "`face` item 0", "vertex index 9", "only 3 vertices"],
            ),
            (format!("{header}0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n"), &["t.ply:13", "vertex index -1"]),
            (format!("{header}0 0 0\n1 0 0\n0 1 0\n3 0 1\n"), &["t.ply:13", "`face` item 0", "ends here"]),
            (
                format!("{header}0 0 0\n1 zero 0\n0 1 0\n3 0 1 2\n"),
                &["t.ply:11", "`vertex` item 1, property `y`", "`zero` is not a number"],
            ),
            (format!("{header}0 0 0\n1 0 0\n0 1 0\n300 0 1 2\n"), &["t.ply:13", "300 is out of range for uchar"]),
            (format!("{header}{good_body}3 0 1 2\n"), &["t.ply:14", "data after the last element"]),
            (
                format!(
                    "{}{good_body}",
                    header.replace("element vertex 3\nproperty float x\nproperty float y\nproperty float z\n", "")
                ),
                &["t.ply", "no `vertex` element"],
            ),
            (format!("{}{good_body}", header.replace("property float z\n", "")), &["t.ply:3", "no property `z`"]),
            (
                format!("{}{good_body}", header.replace("end_header", "end_headr")),
                &["t.ply:9", "unknown header line `end_headr`"],
            ),
            ("ply\nelement vertex 0\nend_header\n".into(), &["t.ply", "no `format` line"]),
        ];
        for (text, expect) in cases {
            let error = match parse_str(&text) {
                Ok(_) => panic!("parsed:\n{text}"),
                Err(e) => e,
            };
            for e in expect {
                assert!(error.contains(e), "`{e}` not in `{error}` for:\n{text}");
            }
        }
    }

    #[test]
    fn broken_binary_data_names_the_byte_offset() {
        let good = binary_quad(true);
        let truncated = &good[..good.len() - 3];
        let error = parse(truncated, Path::new("b.ply")).unwrap_err().to_string();
        assert!(error.contains("b.ply") && error.contains("`face` item 1") && error.contains("byte offset"), "{error}");
        let mut bad_index = binary_quad(true);
        let at = bad_index.len() - 8;
        bad_index[at..at + 4].copy_from_slice(&99u32.to_le_bytes());
        let error = parse(&bad_index, Path::new("b.ply")).unwrap_err().to_string();
        assert!(error.contains(&format!("byte offset {at}")) && error.contains("vertex index 99"), "{error}");
        let mut long = binary_quad(true);
        long.extend([0u8; 5]);
        let error = parse(&long, Path::new("b.ply")).unwrap_err().to_string();
        assert!(error.contains("5 bytes after the last element"), "{error}");
        // A list length that runs past the end is refused before anything is read.
        let mut huge = binary_quad(true);
        let first_face = huge.len() - 2 * (1 + 12 + 4);
        huge[first_face] = 255;
        let error = parse(&huge, Path::new("b.ply")).unwrap_err().to_string();
        assert!(error.contains("list of 255 entries runs past the end"), "{error}");
        let error = parse(&gzip(&good)[..20], Path::new("b.ply.gz")).unwrap_err().to_string();
        assert!(error.contains("b.ply.gz") && error.contains("gzip"), "{error}");
    }

    #[test]
    fn huge_counts_are_refused_before_allocation() {
        let text = "ply\nformat binary_little_endian 1.0\nelement vertex 18446744073709551615\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
        let error = parse_str(text).unwrap_err();
        assert!(error.contains("t.ply:3") && error.contains("cannot hold them"), "{error}");
    }
}
