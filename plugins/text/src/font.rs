//! How POV-Ray 3.7's `truetype.cpp` reads a font's character map and kerning, where it
//! differs from what a font library does:
//!
//! * `ProcessCharMap` under POV-Ray's default `ascii` charset searches the cmap's encoding
//!   records by platform only, Macintosh (1) first, then Windows (3), then Unicode (0); the
//!   first record of a platform whose format it reads (0, 4 or 6) decides alone. Old fonts map
//!   some characters differently in their Macintosh and Unicode tables (POV-Ray's own
//!   `cyrvetic.ttf` maps `-` to different glyphs), and symbol fonts (`povlogo.ttf`) are only
//!   reachable through the Macintosh table.
//! * `ProcessKernTable` reads format 0 subtables of a version 0 `kern` table pair by pair, and
//!   the layout scans each subtable linearly, stopping at the first pair whose left glyph is
//!   beyond the one it looks for: pairs need only be sorted by their left glyph, where a
//!   binary search over (left, right) misses pairs in fonts that sort only by left glyph
//!   (`timrom.ttf`, `cyrvetic.ttf`). Every subtable is read with the first subtable's
//!   coverage bits, as POV-Ray does.

use prism_api::ParamError;
use ttf_parser::cmap::Format;
use ttf_parser::{Face, GlyphId, PlatformId, Tag};

/// The glyph POV-Ray shows for `c`, `None` when the font maps it to no glyph. A character
/// beyond ASCII, which POV-Ray's default charset cannot name, is looked up in the font's
/// Unicode tables.
pub fn glyph_index(face: &Face, c: char) -> Option<GlyphId> {
    if !c.is_ascii() {
        return face.glyph_index(c);
    }
    let cmap = face.tables().cmap?;
    for platform in [PlatformId::Macintosh, PlatformId::Windows, PlatformId::Unicode] {
        let readable = cmap.subtables.into_iter().find(|s| {
            s.platform_id == platform
                && matches!(
                    s.format,
                    Format::ByteEncodingTable(_)
                        | Format::SegmentMappingToDeltaValues(_)
                        | Format::TrimmedTableMapping(_)
                )
        });
        if let Some(table) = readable {
            return table.glyph_index(u32::from(c)).filter(|g| g.0 != 0);
        }
    }
    None
}

/// Coverage bits of a `kern` subtable.
const KERN_HORIZONTAL: u16 = 0x01;
const KERN_MINIMUM: u16 = 0x02;
const KERN_CROSS_STREAM: u16 = 0x04;
const KERN_OVERRIDE: u16 = 0x08;

/// One kerning pair: left and right glyph, value in font units.
#[derive(Clone, Copy, Debug)]
struct Pair {
    left: u16,
    right: u16,
    value: i16,
}

/// A font's kerning as POV-Ray reads it.
#[derive(Debug, Default)]
pub struct Kerning {
    /// The first subtable's coverage bits, which POV-Ray applies to every subtable.
    coverage: u16,
    /// Each subtable's pairs in file order (empty for a format POV-Ray does not read).
    tables: Vec<Vec<Pair>>,
    /// Units per em: the lower clamp of a kerning is minus one em.
    units_per_em: u16,
}

impl Kerning {
    /// The `kern` table of `face` read as `ProcessKernTable` reads it: after the 2-byte
    /// version, a 16-bit subtable count; each subtable's version, length and coverage; a format
    /// 0 subtable's pair count, three search words and pairs. POV-Ray does not skip a
    /// subtable of another format by its length, so the next header is read where its pairs
    /// would start; a read past the table's end is an error, as in POV-Ray ("Cannot read
    /// TrueType font file").
    pub fn read(face: &Face) -> Result<Self, ParamError> {
        let units_per_em = face.units_per_em();
        match face.raw_face().table(Tag::from_bytes(b"kern")) {
            Some(data) => Self::parse(data, units_per_em),
            None => Ok(Self { units_per_em, ..Self::default() }),
        }
    }

    /// [`Kerning::read`] of the `kern` table's bytes.
    fn parse(data: &[u8], units_per_em: u16) -> Result<Self, ParamError> {
        let truncated = || ParamError::new("font", "has a truncated kerning (kern) table");
        let mut at = 2usize;
        let mut word = || -> Result<u16, ParamError> {
            let bytes = data.get(at..at + 2).ok_or_else(truncated)?;
            at += 2;
            Ok(u16::from_be_bytes([bytes[0], bytes[1]]))
        };
        let count = word()?;
        let mut kerning = Self { units_per_em, ..Self::default() };
        for index in 0..count {
            let _version = word()?;
            let _length = word()?;
            let coverage = word()?;
            if index == 0 {
                kerning.coverage = coverage;
            }
            let mut pairs = Vec::new();
            if coverage >> 8 == 0 {
                let n = word()?;
                for _ in 0..3 {
                    word()?;
                }
                // Every pair is read from the table, so the allocation is bounded by its size.
                for _ in 0..n {
                    let (left, right, value) = (word()?, word()?, word()? as i16);
                    pairs.push(Pair { left, right, value });
                }
            }
            kerning.tables.push(pairs);
        }
        Ok(kerning)
    }

    /// The kerning between glyphs `left` and `right`, (along the line, across it) in font
    /// units, as POV-Ray's layout sums, overrides and clamps it: values are 16-bit (`FWord`)
    /// sums, and neither goes below its minimum (-1 em unless a minimum subtable sets one).
    pub fn between(&self, left: GlyphId, right: GlyphId) -> (i16, i16) {
        let (mut x, mut y) = (0i16, 0i16);
        let lowest = (self.units_per_em as i16).wrapping_neg();
        let (mut min_x, mut min_y) = (lowest, lowest);
        let coverage = self.coverage;
        if coverage & KERN_HORIZONTAL != 0 {
            for table in &self.tables {
                for pair in table {
                    if pair.left == left.0 && pair.right == right.0 {
                        let v = pair.value;
                        match (coverage & KERN_MINIMUM != 0, coverage & KERN_CROSS_STREAM != 0) {
                            (true, true) => min_y = v,
                            (true, false) => min_x = v,
                            (false, true) if v == i16::MIN => y = 0,
                            (false, true) if coverage & KERN_OVERRIDE != 0 => y = v,
                            (false, true) => y = y.wrapping_add(v),
                            (false, false) if coverage & KERN_OVERRIDE != 0 => x = v,
                            (false, false) => x = x.wrapping_add(v),
                        }
                        break;
                    }
                    if pair.left > left.0 {
                        break;
                    }
                }
            }
        }
        (x.max(min_x), y.max(min_y))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A `kern` table with one format 0 subtable of `coverage` and `pairs`.
    fn kern_table(coverage: u16, pairs: &[(u16, u16, i16)]) -> Vec<u8> {
        let mut t = Vec::new();
        for w in [0u16, 1, 0, (14 + 6 * pairs.len()) as u16, coverage, pairs.len() as u16, 0, 0, 0] {
            t.extend(w.to_be_bytes());
        }
        for &(l, r, v) in pairs {
            t.extend(l.to_be_bytes());
            t.extend(r.to_be_bytes());
            t.extend(v.to_be_bytes());
        }
        t
    }

    fn kerning(coverage: u16, pairs: &[(u16, u16, i16)]) -> Kerning {
        let tables = vec![pairs.iter().map(|&(left, right, value)| Pair { left, right, value }).collect()];
        Kerning { coverage, tables, units_per_em: 1000 }
    }

    #[test]
    fn pairs_sorted_only_by_left_glyph_are_found() {
        // Right glyphs out of order within left glyph 5, as in timrom.ttf: a binary search
        // over (left, right) misses (5, 3).
        let k = kerning(KERN_HORIZONTAL, &[(2, 9, -10), (5, 40, -20), (5, 3, -30), (5, 7, -40), (8, 1, -50)]);
        assert_eq!(k.between(GlyphId(5), GlyphId(3)), (-30, 0));
        assert_eq!(k.between(GlyphId(5), GlyphId(7)), (-40, 0));
        assert_eq!(k.between(GlyphId(8), GlyphId(1)), (-50, 0));
        assert_eq!(k.between(GlyphId(5), GlyphId(1)), (0, 0));
    }

    #[test]
    fn the_scan_stops_at_a_larger_left_glyph() {
        // Pairs out of order by left glyph: POV-Ray stops at (9, _) and never sees (4, 2).
        let k = kerning(KERN_HORIZONTAL, &[(9, 1, -10), (4, 2, -20)]);
        assert_eq!(k.between(GlyphId(4), GlyphId(2)), (0, 0));
    }

    #[test]
    fn kerning_is_clamped_at_minus_one_em_and_by_minimum_tables() {
        let k = kerning(KERN_HORIZONTAL, &[(1, 2, -3000)]);
        assert_eq!(k.between(GlyphId(1), GlyphId(2)), (-1000, 0));
        let minimum = kerning(KERN_HORIZONTAL | KERN_MINIMUM, &[(1, 2, -300)]);
        assert_eq!(minimum.between(GlyphId(1), GlyphId(2)), (0, 0), "a minimum table only clamps");
        let cross = kerning(KERN_HORIZONTAL | KERN_CROSS_STREAM, &[(1, 2, 120)]);
        assert_eq!(cross.between(GlyphId(1), GlyphId(2)), (0, 120));
        let vertical = kerning(0, &[(1, 2, -300)]);
        assert_eq!(vertical.between(GlyphId(1), GlyphId(2)), (0, 0), "vertical tables are skipped");
    }

    #[test]
    fn every_subtable_reads_the_first_ones_coverage() {
        let mut k = kerning(KERN_HORIZONTAL, &[(1, 2, -10)]);
        k.tables.push(vec![Pair { left: 1, right: 2, value: -15 }]);
        assert_eq!(k.between(GlyphId(1), GlyphId(2)), (-25, 0), "sums across subtables");
        k.coverage = KERN_HORIZONTAL | KERN_OVERRIDE;
        assert_eq!(k.between(GlyphId(1), GlyphId(2)), (-15, 0), "the last override wins");
    }

    #[test]
    fn tables_are_read_as_pov_ray_reads_them() {
        let table = kern_table(KERN_HORIZONTAL, &[(1, 2, -10), (3, 4, -20)]);
        let k = Kerning::parse(&table, 1000).unwrap();
        assert_eq!(k.between(GlyphId(3), GlyphId(4)), (-20, 0));
        // A read past the end is an error, however little is missing.
        assert!(Kerning::parse(&table[..table.len() - 1], 1000).is_err());
        // Another format's subtable is not skipped: its first words are read as the next header.
        let mut other = kern_table(KERN_HORIZONTAL | 0x0200, &[]);
        other[2..4].copy_from_slice(&2u16.to_be_bytes());
        other.extend([0, 0, 0, 14, 0, 1, 0, 0]);
        let k = Kerning::parse(&other, 1000).unwrap();
        assert_eq!(k.tables.len(), 2);
        assert!(k.tables.iter().all(Vec::is_empty));
        let font = std::fs::read(concat!(env!("CARGO_MANIFEST_DIR"), "/../../assets/fonts/DejaVuSans.ttf")).unwrap();
        let read = Kerning::read(&Face::parse(&font, 0).unwrap()).unwrap();
        assert!(!read.tables.is_empty() && read.coverage & KERN_HORIZONTAL != 0, "DejaVu Sans has a kern table");
    }
}
