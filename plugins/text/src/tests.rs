use std::path::{Path, PathBuf};

use prism_api::contract::{ContractConfig, TestRng, check_shape, check_shape_with};
use prism_api::{LocalFiles, ParamFile};

use super::*;

const FONT: &str = "DejaVuSans.ttf";

fn fonts() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/fonts")
}

fn params(string: &str) -> TextParams {
    TextParams { font: FONT.into(), string: string.into(), thickness: 0.25, offset: vec![0.0, 0.0] }
}

fn build(p: TextParams) -> Result<Arc<dyn Shape>, ParamError> {
    p.build_with_files(&mut LocalFiles(fonts()))
}

fn text(string: &str) -> Arc<dyn Shape> {
    build(params(string)).unwrap()
}

fn face_bytes() -> Vec<u8> {
    std::fs::read(fonts().join(FONT)).unwrap()
}

/// (xMin, xMax, advance, lsb) of `c` in font units, and the units per em.
fn metrics(c: char) -> ([f64; 4], f64) {
    let bytes = face_bytes();
    let face = ttf_parser::Face::parse(&bytes, 0).unwrap();
    let id = face.glyph_index(c).unwrap();
    let b = face.glyph_bounding_box(id).unwrap();
    let m = [
        f64::from(b.x_min),
        f64::from(b.x_max),
        f64::from(face.glyph_hor_advance(id).unwrap()),
        f64::from(face.glyph_hor_side_bearing(id).unwrap()),
    ];
    (m, f64::from(face.units_per_em()))
}

/// The text laid out, without POV-Ray's tilt (see `flat_hit`).
fn flat(string: &str, offset: DVec2) -> Text {
    let glyphs = layout(&face_bytes(), FONT, string, offset).unwrap();
    Text::new(glyphs, 0.25, fonts().join(FONT), string.into(), offset.extend(0.0))
}

/// The nearest hit and its normal in the frame of the laid-out text (before the tilt), where
/// positions are exact.
fn flat_hit(text: &Text, origin: DVec3, direction: DVec3) -> Option<(DVec3, DVec3)> {
    let ray = Ray::new(origin, direction);
    let hit = text.flat_intersect(&ray, 0.0, f64::INFINITY)?;
    let s = text.flat_surface(&ray, &hit);
    Some((s.point, s.normal))
}

#[test]
fn contract_holds() {
    for s in ["O", "AVO", "g&8%"] {
        check_shape(text(s).as_ref());
    }
    let spaced = TextParams { offset: vec![0.1, 0.05, 0.3], thickness: 2.0, ..params("Ra x") };
    check_shape_with(build(spaced).unwrap().as_ref(), &ContractConfig { rays: 5_000, ..ContractConfig::default() });
}

#[test]
fn a_ray_across_the_stem_of_an_l_hits_its_right_edge() {
    // `l` is one rectangle; as the first glyph its left edge is moved to x = 0.
    let ([x_min, x_max, ..], units) = metrics('l');
    let text = flat("l", DVec2::ZERO);
    let (p, n) = flat_hit(&text, DVec3::new(5.0, 0.3, -0.1), DVec3::NEG_X).unwrap();
    assert!((p.x - (x_max - x_min) / units).abs() < 1e-12, "hit at {p}");
    assert!((n - DVec3::X).length() < 1e-12, "normal {n}");
    let (p, n) = flat_hit(&text, DVec3::new(-5.0, 0.3, -0.1), DVec3::X).unwrap();
    assert!(p.x.abs() < 1e-12 && (n + DVec3::X).length() < 1e-12, "hit at {p}, normal {n}");
    // The shape itself is tilted as POV-Ray tilts it: the same hit, turned by 0.001 degrees.
    let shape = self::text("l");
    let ray = Ray::new(DVec3::new(5.0, 0.3, -0.1), DVec3::NEG_X);
    let hit = shape.intersect(&ray, 0.0, f64::INFINITY).unwrap();
    let s = shape.surface(&ray, &hit);
    assert!((s.point.x - (x_max - x_min) / units).abs() < 1e-4 && (s.normal - DVec3::X).length() < 1e-4);
    assert!((s.normal - DVec3::X).length() > 1e-6, "the tilt is there");
}

#[test]
fn the_tilt_is_pov_rays_rotate_of_a_thousandth_degree() {
    // POV-Ray's rotate <0.001, 0.001, 0.001> of (1, 0, 0) in its frame, mirrored in z.
    let r = 0.001_f64.to_radians();
    let (x, y, z) = (1.0_f64, 0.0_f64, 0.0_f64);
    let (y, z) = (y * r.cos() - z * r.sin(), y * r.sin() + z * r.cos());
    let (x, z) = (x * r.cos() + z * r.sin(), -x * r.sin() + z * r.cos());
    let (x, y) = (x * r.cos() - y * r.sin(), x * r.sin() + y * r.cos());
    let expected = DVec3::new(x, y, -z);
    assert!((pov_tilt() * DVec3::X - expected).length() < 1e-15);
    assert!((pov_tilt().determinant() - 1.0).abs() < 1e-12);
}

#[test]
fn a_ray_through_the_hole_of_an_o_misses() {
    let text = flat("O", DVec2::ZERO);
    let b = text.flat_bounds;
    let centre = b.center();
    assert!(flat_hit(&text, DVec3::new(centre.x, centre.y, 5.0), DVec3::NEG_Z).is_none());
    assert!(!text.inside(DVec3::new(centre.x, centre.y, -0.1)));
    // The ring itself, just inside its left edge, is hit on the front face.
    let (p, n) = flat_hit(&text, DVec3::new(b.min.x + 0.02, centre.y, 5.0), DVec3::NEG_Z).unwrap();
    assert!(p.z.abs() < 1e-12 && n == DVec3::Z, "hit at {p}, normal {n}");
}

#[test]
fn caps_face_out_and_sides_are_horizontal() {
    let text = flat("H", DVec2::ZERO);
    let b = text.flat_bounds;
    let stem = DVec3::new(b.min.x + 0.03, 0.3, 0.0);
    let (p, n) = flat_hit(&text, stem + DVec3::Z, DVec3::new(0.0, 0.0, -2.0)).unwrap();
    assert!(p.z == 0.0 && n == DVec3::Z);
    let (p, n) = flat_hit(&text, stem - 3.0 * DVec3::Z, DVec3::Z).unwrap();
    assert!(p.z == -0.25 && n == DVec3::NEG_Z);
    // From inside the solid the ray leaves through the back.
    let (p, _) = flat_hit(&text, stem - 0.1 * DVec3::Z, DVec3::NEG_Z).unwrap();
    assert!((p.z + 0.25).abs() < 1e-12);
    let (_, n) = flat_hit(&text, DVec3::new(-1.0, 0.3, -0.1), DVec3::new(1.0, 0.01, 0.02)).unwrap();
    assert!(n.z == 0.0 && (n + DVec3::X).length() < 1e-9, "side normal {n}");
    let shape = self::text("H");
    assert!(shape.inside(stem - 0.1 * DVec3::Z) && !shape.inside(stem + 0.1 * DVec3::Z));
}

#[test]
fn bounds_hold_every_hit() {
    let shape = text("Prism & POV");
    let b = shape.bounds();
    let mut rng = TestRng::new(7);
    let mut hits = 0;
    for _ in 0..20_000 {
        let target = rng.point_in(&b);
        let from = target + 4.0 * DVec3::new(rng.uniform() - 0.5, rng.uniform() - 0.5, rng.uniform() - 0.5);
        let ray = Ray::new(from, target - from);
        if let Some(hit) = shape.intersect(&ray, 0.0, f64::INFINITY) {
            hits += 1;
            assert!(b.contains(shape.surface(&ray, &hit).point, 1e-9));
        }
    }
    assert!(hits > 1000);
}

#[test]
fn glyphs_are_placed_by_advance_kerning_and_offset() {
    let ([a_min, _, a_adv, a_lsb], units) = metrics('A');
    let ([v_min, v_max, _, v_lsb], _) = metrics('V');
    let bytes = face_bytes();
    let face = ttf_parser::Face::parse(&bytes, 0).unwrap();
    let (a, v) = (face.glyph_index('A').unwrap(), face.glyph_index('V').unwrap());
    let kern = face.tables().kern.unwrap().subtables.into_iter().find_map(|s| s.glyphs_kerning(a, v)).unwrap();
    assert!(kern < 0, "DejaVu Sans kerns A-V");
    let shape = flat("AV", DVec2::ZERO);
    let expected_v = (a_adv - a_lsb + v_lsb - v_min + f64::from(kern) + v_max) / units;
    assert!((shape.flat_bounds.max.x - expected_v).abs() < 1e-12, "{} vs {expected_v}", shape.flat_bounds.max.x);
    assert!(a_min == a_lsb);
    let offset = flat("AV", DVec2::new(0.5, 0.25));
    assert!((offset.flat_bounds.max.x - expected_v - 0.5).abs() < 1e-12);
    assert!((offset.flat_bounds.max.y - shape.flat_bounds.max.y - 0.25).abs() < 1e-12);
}

#[test]
fn empty_strings_and_spaces_have_nothing_to_hit() {
    for s in ["", "   "] {
        let shape = text(s);
        assert!(shape.intersect(&Ray::new(DVec3::Z, DVec3::NEG_Z), 0.0, f64::INFINITY).is_none());
        assert!(shape.bounds().is_bounded());
    }
}

#[test]
fn parameters_are_validated() {
    let key = |p: TextParams| build(p).err().map(|e| e.key);
    for thickness in [0.0, -1.0, f64::NAN, f64::INFINITY, 1e9] {
        assert_eq!(key(TextParams { thickness, ..params("a") }), Some("thickness".into()));
    }
    for offset in [vec![0.0], vec![0.0; 4], vec![f64::NAN, 0.0], vec![1e9, 0.0]] {
        assert_eq!(key(TextParams { offset, ..params("a") }), Some("offset".into()));
    }
    assert_eq!(key(params(&"a".repeat(MAX_CHARS + 1))), Some("string".into()));
    let missing = build(params("a\u{10FFFF}")).err().unwrap();
    assert_eq!(missing.key, "string");
    assert!(missing.message.contains("U+10FFFF"), "{}", missing.message);
    assert_eq!(key(TextParams { font: "no-such.ttf".into(), ..params("a") }), Some("font".into()));
    assert!(params("a").build().is_err(), "text needs a file reader");
}

struct Bytes(Vec<u8>);

impl FileReader for Bytes {
    fn read(&mut self, _: &str, _: &str) -> Result<ParamFile, ParamError> {
        Ok(ParamFile { path: "font.ttf".into(), bytes: self.0.clone() })
    }
}

#[test]
fn corrupt_fonts_are_refused_without_panic() {
    let good = face_bytes();
    let mut rng = TestRng::new(3);
    let mut cases = vec![Vec::new(), b"not a font at all".to_vec(), good[..good.len() / 3].to_vec()];
    for _ in 0..40 {
        let mut bytes = good.clone();
        for _ in 0..64 {
            let i = (rng.uniform() * bytes.len() as f64) as usize;
            bytes[i] = (rng.uniform() * 256.0) as u8;
        }
        cases.push(bytes);
    }
    for bytes in cases {
        // Either an error naming the font or the string, or a shape that intersects.
        match params("Prism").build_with_files(&mut Bytes(bytes)) {
            Ok(shape) => {
                let _ = shape.intersect(&Ray::new(DVec3::new(0.3, 0.3, 5.0), DVec3::NEG_Z), 0.0, f64::INFINITY);
            }
            Err(e) => assert!(e.key == "font" || e.key == "string", "{e}"),
        }
    }
}

#[test]
fn parameters_deserialise_with_defaults_and_deny_unknown_keys() {
    use serde::de::IntoDeserializer;
    use serde::de::value::{Error, MapDeserializer};
    let map: MapDeserializer<'_, _, Error> =
        MapDeserializer::new(vec![("font", "f.ttf"), ("string", "Hi")].into_iter());
    let p = TextParams::deserialize(map.into_deserializer()).unwrap();
    assert_eq!((p.thickness, p.offset), (1.0, vec![0.0, 0.0]));
    let map: MapDeserializer<'_, _, Error> =
        MapDeserializer::new(vec![("font", "f.ttf"), ("string", "Hi"), ("size", "2")].into_iter());
    assert!(TextParams::deserialize(map.into_deserializer()).is_err());
}

struct Relative;

impl pov::FilePaths for Relative {
    fn path(&self, _: &Path) -> Option<String> {
        pov::string("../fonts/DejaVuSans.ttf")
    }
}

#[test]
fn exports_to_pov() {
    let shape = build(TextParams { thickness: 0.5, offset: vec![0.1, 0.0, 0.2], ..params("a\"b\\é") }).unwrap();
    assert_eq!(
        shape.to_pov_with(&Relative).unwrap(),
        r#"text { ttf "../fonts/DejaVuSans.ttf" "a\"b\\\u00E9" 0.5, <0.1, 0.0, -0.2> }"#
    );
    assert!(shape.to_pov().unwrap().contains("DejaVuSans.ttf\""));
}

/// POV-Ray's own fonts (Debian's povray-includes), which CI installs: `None` where they are
/// missing outside CI.
fn povray_font(name: &str) -> Option<Vec<u8>> {
    let path = Path::new("/usr/share/povray-3.7/include").join(name);
    match std::fs::read(&path) {
        Ok(bytes) => Some(bytes),
        Err(e) if std::env::var_os("CI").is_some_and(|v| v == "true") => panic!("{}: {e}", path.display()),
        Err(_) => None,
    }
}

/// The x of the second glyph's left edge in `string` laid out in `bytes`.
fn second_glyph_left(bytes: &[u8], string: &str) -> f64 {
    let glyphs = layout(bytes, "font", string, DVec2::ZERO).unwrap();
    glyphs[1].min.x
}

#[test]
fn povray_fonts_kern_pairs_sorted_only_by_left_glyph() {
    // timrom.ttf sorts its kern pairs by left glyph only: F-o (-28 units) lies where a binary
    // search over (left, right) does not look. POV-Ray's linear scan finds it.
    let Some(bytes) = povray_font("timrom.ttf") else { return };
    let face = ttf_parser::Face::parse(&bytes, 0).unwrap();
    let (f, o) = (face.glyph_index('F').unwrap(), face.glyph_index('o').unwrap());
    let missed = face.tables().kern.unwrap().subtables.into_iter().find_map(|s| s.glyphs_kerning(f, o));
    assert_eq!(missed, None, "the binary search misses the pair");
    let units = f64::from(face.units_per_em());
    let kerned = second_glyph_left(&bytes, "Fo");
    let reference = {
        let advance = f64::from(face.glyph_hor_advance(f).unwrap());
        let lsb = f64::from(face.glyph_hor_side_bearing(f).unwrap());
        let o_lsb = f64::from(face.glyph_hor_side_bearing(o).unwrap());
        // The glyph's left edge sits at the pen plus its left side bearing.
        (advance - lsb + o_lsb) / units
    };
    assert!((kerned - (reference - 28.0 / units)).abs() < 1e-9, "{kerned} vs {}", reference - 28.0 / units);
}

#[test]
fn povray_fonts_map_characters_through_the_macintosh_table_first() {
    // cyrvetic.ttf maps '-' to glyph 14 in its Macintosh table and to glyph 100 in its
    // Unicode one; POV-Ray's default charset reads the Macintosh table.
    if let Some(bytes) = povray_font("cyrvetic.ttf") {
        let face = ttf_parser::Face::parse(&bytes, 0).unwrap();
        assert_eq!(font::glyph_index(&face, '-'), Some(ttf_parser::GlyphId(14)));
        assert_eq!(face.glyph_index('-'), Some(ttf_parser::GlyphId(100)));
    }
    // povlogo.ttf has its logo only in the Macintosh table ('P'; the Windows table is a
    // symbol one at U+F050).
    if let Some(bytes) = povray_font("povlogo.ttf") {
        let face = ttf_parser::Face::parse(&bytes, 0).unwrap();
        assert_eq!(font::glyph_index(&face, 'P'), Some(ttf_parser::GlyphId(4)));
        assert!(layout(&bytes, "povlogo.ttf", "P", DVec2::ZERO).is_ok_and(|g| g.len() == 1));
        assert!(layout(&bytes, "povlogo.ttf", "Q", DVec2::ZERO).is_err(), "no glyph for Q");
    }
}
