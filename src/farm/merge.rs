//! `merge`: part files to the film of the whole frame. Regions are assembled (each pixel
//! copied from the one part holding all its samples: the full render's pixels, bit for bit);
//! sample ranges are summed in sample order and divided, as the renderer does, which gives
//! the full render's pixel or the next f32 up or down (f64 addition is not associative: the
//! merge adds each part's sum whole, the renderer adds sample by sample).

use std::fmt::Write as _;

use crate::film::{Film, Region};
use crate::limits::{MemoryBudget, OverBudget};
use crate::partial::{PartInfo, Partial, PixelSums};

/// Why parts do not merge.
#[derive(Debug, thiserror::Error)]
pub enum MergeError {
    /// No parts were given.
    #[error("merge: no parts given")]
    NoParts,
    /// Two parts are of different scenes or settings.
    #[error(
        "{second}: a part of another scene or other settings than {first} ({what} differs); parts merge only when rendered from the same scene with the same settings"
    )]
    Mismatch {
        /// The first part's file.
        first: String,
        /// The mismatching part's file.
        second: String,
        /// The header key that differs.
        what: &'static str,
    },
    /// Two parts hold the same samples of the same pixels.
    #[error("{second}: overlaps {first}: both hold samples {s0}..{s1} of pixels {x0},{y0},{x1},{y1}; give each pixel's samples once", x0 = region.x0, y0 = region.y0, x1 = region.x1, y1 = region.y1)]
    Overlap {
        /// One part's file.
        first: String,
        /// The other part's file.
        second: String,
        /// The pixels both hold.
        region: Region,
        /// First sample both hold.
        s0: u32,
        /// One past the last sample both hold.
        s1: u32,
    },
    /// Some pixels lack samples: the parts to re-run.
    #[error("merge: the parts do not cover the image; missing:\n{missing}")]
    Gaps {
        /// One line per missing tile or region (with its missing samples).
        missing: String,
    },
    /// The merged film would not fit the memory budget.
    #[error(transparent)]
    OverBudget(#[from] OverBudget),
}

/// A part and the name of its file (for messages).
pub struct NamedPart {
    /// The file the part came from, as the user named it.
    pub name: String,
    /// The part.
    pub part: Partial,
}

/// The settings shared by all parts (of the first part).
pub fn shared_info(parts: &[NamedPart]) -> Option<&PartInfo> {
    parts.first().map(|p| &p.part.info)
}

/// Merges `parts` into the film of the whole frame. Refuses parts of different scenes or
/// settings, overlapping parts, and incomplete coverage (listing what is missing: tiles as
/// `--tile I/N` when the parts are tiles, else regions and sample ranges).
pub fn merge(parts: &[NamedPart], budget: MemoryBudget) -> Result<Film, MergeError> {
    let first = parts.first().ok_or(MergeError::NoParts)?;
    let info = &first.part.info;
    for other in &parts[1..] {
        let o = &other.part.info;
        let what = if o.fingerprint != info.fingerprint {
            "the scene fingerprint"
        } else if o.frame != info.frame {
            "the frame size"
        } else if o.total_samples != info.total_samples {
            "the samples per pixel"
        } else if o.sampling != info.sampling {
            "the antialiasing"
        } else if o.exposure != info.exposure || o.tone_map != info.tone_map {
            "the exposure or tone map"
        } else {
            continue;
        };
        return Err(MergeError::Mismatch { first: first.name.clone(), second: other.name.clone(), what });
    }
    check_overlaps(parts)?;
    let (width, height) = info.frame;
    let pixels = u64::from(width) * u64::from(height);
    let any_sums = parts.iter().any(|p| !p.part.info.has_all_samples());
    // The film and the per-pixel sample counts; with sample ranges, the per-pixel sums.
    let per_pixel = 12 + 4 + if any_sums { std::mem::size_of::<PixelSums>() as u64 } else { 0 };
    budget.check(|| format!("merging a {width} x {height} image"), pixels * per_pixel)?;

    let mut film = Film::new(width, height);
    let mut counts = vec![0u32; pixels as usize];
    let mut sums = if any_sums { vec![PixelSums::default(); pixels as usize] } else { Vec::new() };
    let mut order: Vec<&NamedPart> = parts.iter().collect();
    // Ranges are added in sample order, as the renderer adds samples.
    order.sort_by_key(|p| p.part.info.samples.start);
    for named in order {
        let part = &named.part;
        let r = part.info.region;
        let whole = part.info.has_all_samples();
        for y in r.y0..r.y1 {
            for x in r.x0..r.x1 {
                let i = ((y - r.y0) * r.width() + (x - r.x0)) as usize;
                let j = y as usize * width as usize + x as usize;
                counts[j] += part.sample_counts[i];
                if whole {
                    film.pixels[j] = part.radiance[i];
                } else if let Some(part_sums) = &part.sums {
                    sums[j].add(&part_sums[i]);
                }
            }
        }
    }
    report_gaps(parts, &counts, info)?;
    if any_sums {
        for (j, s) in sums.iter().enumerate() {
            // Pixels of whole parts have no sums (a whole part overlaps every range part).
            if s.weight != 0.0 || s.sum != [0.0; 3] {
                film.pixels[j] = s.mean();
            }
        }
        // A pixel whose partial sums are all zero (weights cancelling) is black, as rendered.
    }
    Ok(film)
}

fn intersect(a: &Region, b: &Region) -> Region {
    Region { x0: a.x0.max(b.x0), y0: a.y0.max(b.y0), x1: a.x1.min(b.x1), y1: a.y1.min(b.y1) }
}

/// Refuses two parts holding the same samples of the same pixels (sweeping parts by first
/// row, so only parts that share rows are compared).
fn check_overlaps(parts: &[NamedPart]) -> Result<(), MergeError> {
    let mut order: Vec<&NamedPart> = parts.iter().collect();
    order.sort_by_key(|p| p.part.info.region.y0);
    for (k, a) in order.iter().enumerate() {
        let (ra, sa) = (&a.part.info.region, &a.part.info.samples);
        for b in &order[k + 1..] {
            let (rb, sb) = (&b.part.info.region, &b.part.info.samples);
            if rb.y0 >= ra.y1 {
                break;
            }
            let both = intersect(ra, rb);
            let (s0, s1) = (sa.start.max(sb.start), sa.end.min(sb.end));
            if both.x0 < both.x1 && both.y0 < both.y1 && s0 < s1 {
                return Err(MergeError::Overlap {
                    first: a.name.clone(),
                    second: b.name.clone(),
                    region: both,
                    s0,
                    s1,
                });
            }
        }
    }
    Ok(())
}

/// Lists what is missing when some pixel has fewer than all its samples: the missing tiles
/// (with the command-line flag that renders each) when every part is a whole tile of one
/// split, else rectangles of pixels with the samples they lack.
fn report_gaps(parts: &[NamedPart], counts: &[u32], info: &PartInfo) -> Result<(), MergeError> {
    let total = info.total_samples;
    if counts.iter().all(|&c| c == total) {
        return Ok(());
    }
    let mut missing = String::new();
    let (width, height) = info.frame;
    let tiles: Option<u32> = info.tile.map(|(_, n)| n).filter(|&n| {
        parts.iter().all(|p| p.part.info.tile.map(|(_, m)| m) == Some(n) && p.part.info.has_all_samples())
    });
    if let Some(n) = tiles {
        let present: std::collections::BTreeSet<u32> =
            parts.iter().filter_map(|p| p.part.info.tile.map(|t| t.0)).collect();
        for i in (0..n).filter(|i| !present.contains(i)) {
            let r = parts
                .iter()
                .find(|p| p.part.info.tile.is_some())
                .map(|_| tile_rows(parts, i, n, width, height))
                .unwrap_or(None);
            let _ = match r {
                Some(r) => writeln!(
                    missing,
                    "  tile {i}/{n} (pixels {},{},{},{}): re-run with --tile {i}/{n}",
                    r.x0, r.y0, r.x1, r.y1
                ),
                None => writeln!(missing, "  tile {i}/{n}: re-run with --tile {i}/{n}"),
            };
        }
        if !missing.is_empty() {
            return Err(MergeError::Gaps { missing });
        }
    }
    for rect in incomplete_rectangles(counts, width, height, total) {
        let covering: Vec<&PartInfo> =
            parts.iter().map(|p| &p.part.info).filter(|i| i.region.contains(rect.x0, rect.y0)).collect();
        let ranges = missing_ranges(&covering, total);
        let ranges: Vec<String> = ranges.iter().map(|r| format!("{}..{}", r.start, r.end)).collect();
        let _ = writeln!(
            missing,
            "  pixels {},{},{},{}: samples {} (re-run with --region {},{},{},{} --sample-range RANGE)",
            rect.x0,
            rect.y0,
            rect.x1,
            rect.y1,
            ranges.join(", "),
            rect.x0,
            rect.y0,
            rect.x1,
            rect.y1
        );
    }
    Err(MergeError::Gaps { missing })
}

/// Tile `i` of `n`, split as the parts were (their alignment is that of the renderer's
/// tiles or of POV-Ray's blocks; both splits are tried and the one consistent with the
/// present tiles is used).
fn tile_rows(parts: &[NamedPart], i: u32, n: u32, width: u32, height: u32) -> Option<Region> {
    [crate::render::TILE_SIZE, crate::render::antialias::BLOCK_SIZE].into_iter().find_map(|align| {
        let consistent = parts.iter().all(|p| match p.part.info.tile {
            Some((k, _)) => super::tile_region(width, height, k, n, align).ok() == Some(p.part.info.region),
            None => true,
        });
        if consistent { super::tile_region(width, height, i, n, align).ok() } else { None }
    })
}

/// The sample ranges of `0..total` no part in `covering` holds.
fn missing_ranges(covering: &[&PartInfo], total: u32) -> Vec<std::ops::Range<u32>> {
    let mut held: Vec<std::ops::Range<u32>> = covering.iter().map(|i| i.samples.clone()).collect();
    held.sort_by_key(|r| r.start);
    let mut missing = Vec::new();
    let mut next = 0;
    for r in held {
        if r.start > next {
            missing.push(next..r.start);
        }
        next = next.max(r.end);
    }
    if next < total {
        missing.push(next..total);
    }
    missing
}

/// Rectangles covering the pixels with fewer than `total` samples: runs of equal count in
/// each row, joined with identical runs of the rows below.
fn incomplete_rectangles(counts: &[u32], width: u32, height: u32, total: u32) -> Vec<Region> {
    let mut open: Vec<(Region, u32)> = Vec::new();
    let mut done = Vec::new();
    for y in 0..height {
        let row = &counts[(y * width) as usize..((y + 1) * width) as usize];
        let mut runs = Vec::new();
        let mut x = 0;
        while x < width {
            let c = row[x as usize];
            let start = x;
            while x < width && row[x as usize] == c {
                x += 1;
            }
            if c < total {
                runs.push((start, x, c));
            }
        }
        let mut next_open = Vec::new();
        for (x0, x1, c) in runs {
            match open.iter().position(|(r, oc)| r.x0 == x0 && r.x1 == x1 && *oc == c && r.y1 == y) {
                Some(k) => {
                    let (mut r, _) = open.swap_remove(k);
                    r.y1 = y + 1;
                    next_open.push((r, c));
                }
                None => next_open.push((Region { x0, y0: y, x1, y1: y + 1 }, c)),
            }
        }
        done.extend(open.drain(..).map(|(r, _)| r));
        open = next_open;
    }
    done.extend(open.into_iter().map(|(r, _)| r));
    done.sort_by_key(|r| (r.y0, r.x0));
    done
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::partial::{Fingerprint, Sampling};
    use crate::world::components::ToneMap;

    fn info(region: Region, samples: std::ops::Range<u32>, tile: Option<(u32, u32)>) -> PartInfo {
        PartInfo {
            fingerprint: Fingerprint::of_text("scene"),
            frame: (6, 4),
            region,
            samples,
            total_samples: 4,
            tile,
            sampling: Sampling::Stratified,
            exposure: 0.0,
            tone_map: ToneMap::Clamp,
            scene: None,
        }
    }

    /// A part whose pixel (x, y) sample s is worth x + 10 y + 100 s, weight 1.
    fn part(name: &str, region: Region, samples: std::ops::Range<u32>, tile: Option<(u32, u32)>) -> NamedPart {
        let info = info(region, samples.clone(), tile);
        let mut sums = Vec::new();
        for y in region.y0..region.y1 {
            for x in region.x0..region.x1 {
                let s: f64 = samples.clone().map(|s| f64::from(x + 10 * y + 100 * s)).sum();
                sums.push(PixelSums { sum: [s, 0.0, 0.25 * samples.len() as f64], weight: samples.len() as f64 });
            }
        }
        let radiance = sums.iter().map(PixelSums::mean).collect();
        let whole = info.has_all_samples();
        let n = region.pixel_count();
        let part = Partial {
            info,
            radiance,
            sample_counts: vec![samples.len() as u32; n],
            sums: (!whole).then_some(sums),
            layers: Vec::new(),
        };
        NamedPart { name: name.into(), part }
    }

    fn rows(y0: u32, y1: u32) -> Region {
        Region { x0: 0, y0, x1: 6, y1 }
    }

    #[test]
    fn regions_and_sample_ranges_merge_to_the_mean() {
        let parts = vec![
            part("a", rows(0, 2), 0..4, None),
            part("b", rows(2, 4), 2..4, None),
            part("c", rows(2, 4), 0..2, None),
        ];
        let film = merge(&parts, MemoryBudget::default()).unwrap();
        for y in 0..4 {
            for x in 0..6 {
                let mean = f64::from(x + 10 * y) + 150.0;
                assert_eq!(film.get(x, y), [mean as f32, 0.0, 0.25], "({x}, {y})");
            }
        }
    }

    #[test]
    fn gaps_name_the_missing_tiles_or_samples() {
        let tiles = vec![part("t0", rows(0, 1), 0..4, Some((0, 3))), part("t2", rows(2, 4), 0..4, Some((2, 3)))];
        let error = merge(&tiles, MemoryBudget::default()).unwrap_err().to_string();
        assert!(error.contains("tile 1/3 (pixels 0,1,6,2): re-run with --tile 1/3"), "{error}");
        assert!(!error.contains("tile 0/3") && !error.contains("tile 2/3"), "{error}");

        let ranges = vec![part("a", rows(0, 4), 0..1, None), part("b", rows(0, 2), 3..4, None)];
        let error = merge(&ranges, MemoryBudget::default()).unwrap_err().to_string();
        assert!(error.contains("pixels 0,0,6,2: samples 1..3"), "{error}");
        assert!(error.contains("pixels 0,2,6,4: samples 1..4"), "{error}");
    }

    #[test]
    fn overlaps_and_mismatches_are_refused() {
        let parts = vec![part("a", rows(0, 3), 0..4, None), part("b", rows(2, 4), 3..4, None)];
        let error = merge(&parts, MemoryBudget::default()).unwrap_err().to_string();
        assert!(error.contains("b: overlaps a: both hold samples 3..4 of pixels 0,2,6,3"), "{error}");

        let mut other = part("other", rows(2, 4), 0..4, None);
        other.part.info.fingerprint = Fingerprint::of_text("another scene");
        let parts = vec![part("a", rows(0, 2), 0..4, None), other];
        let error = merge(&parts, MemoryBudget::default()).unwrap_err().to_string();
        assert!(error.starts_with("other: a part of another scene") && error.contains("fingerprint"), "{error}");
        assert!(matches!(merge(&[], MemoryBudget::default()), Err(MergeError::NoParts)));
    }
}
