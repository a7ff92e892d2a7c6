//! Render farms: splitting a frame into tiles, merging part files ([`crate::partial`]) into
//! the image one machine would make, and job scripts for schedulers ([`slurm`]).

pub mod merge;
pub mod slurm;

use crate::film::Region;

/// Why a tile cannot be had.
#[derive(Debug, thiserror::Error, PartialEq, Eq)]
pub enum TileError {
    /// `I/N` with I not below N, or N zero.
    #[error("--tile {index}/{count}: the tile index is 0-based and must be below the tile count (0/{count} to {last}/{count})", last = count.saturating_sub(1))]
    Index {
        /// I.
        index: u32,
        /// N.
        count: u32,
    },
    /// More tiles than rows.
    #[error("--tile {index}/{count}: a {height}-row image has at most {height} tiles (one row each)")]
    TooMany {
        /// I.
        index: u32,
        /// N.
        count: u32,
        /// Rows of the frame.
        height: u32,
    },
    /// Not `I/N`.
    #[error("--tile: `{0}` is not I/N (two whole numbers, e.g. 3/16)")]
    Syntax(String),
}

/// Parses `I/N`.
pub fn parse_tile(text: &str) -> Result<(u32, u32), TileError> {
    let syntax = || TileError::Syntax(crate::files::shown(text));
    let (i, n) = text.split_once('/').ok_or_else(syntax)?;
    Ok((i.trim().parse().map_err(|_| syntax())?, n.trim().parse().map_err(|_| syntax())?))
}

/// Tile `index` (0-based, as Slurm's `SLURM_ARRAY_TASK_ID` with `--array=0-(N-1)` and
/// Kubernetes' `JOB_COMPLETION_INDEX`) of `count` tiles of a `width` x `height` frame:
/// full-width bands of rows, band `i` starting at row `floor(i * height / count)` rounded down
/// to a multiple of `align` rows when every band then keeps at least `align` rows (so bands
/// follow the renderer's tiles and POV-Ray's 32-pixel antialiasing blocks, which a band
/// would otherwise render in part twice). The split depends only on these four numbers.
pub fn tile_region(width: u32, height: u32, index: u32, count: u32, align: u32) -> Result<Region, TileError> {
    if count == 0 || index >= count {
        return Err(TileError::Index { index, count });
    }
    if count > height {
        return Err(TileError::TooMany { index, count, height });
    }
    let align = if u64::from(count) * u64::from(align.max(1)) <= u64::from(height) { align.max(1) } else { 1 };
    let start = |i: u32| {
        if i == count {
            return height;
        }
        let row = (u64::from(i) * u64::from(height) / u64::from(count)) as u32;
        row / align * align
    };
    Ok(Region { x0: 0, y0: start(index), x1: width, y1: start(index + 1) })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The tiles of any split cover the frame exactly once, in order, each non-empty.
    #[test]
    fn tiles_partition_the_frame() {
        for (height, align) in [(57, 16), (57, 32), (1000, 32), (7, 16), (64, 32)] {
            for count in 1..=height.min(40) {
                let mut next = 0;
                for i in 0..count {
                    let r = tile_region(100, height, i, count, align).unwrap();
                    assert_eq!((r.x0, r.x1, r.y0), (0, 100, next), "{height}/{count}/{i}");
                    assert!(r.y1 > r.y0, "tile {i}/{count} of {height} rows is empty");
                    next = r.y1;
                }
                assert_eq!(next, height);
            }
        }
        // Aligned when there is room: 4 tiles of 200 rows at 32 start at 0, 32, 96, 128.
        let starts: Vec<u32> = (0..4).map(|i| tile_region(10, 200, i, 4, 32).unwrap().y0).collect();
        assert_eq!(starts, [0, 32, 96, 128]);
    }

    #[test]
    fn bad_tiles_are_refused() {
        assert_eq!(tile_region(10, 10, 5, 4, 16), Err(TileError::Index { index: 5, count: 4 }));
        assert_eq!(tile_region(10, 10, 0, 0, 16), Err(TileError::Index { index: 0, count: 0 }));
        assert!(matches!(tile_region(10, 10, 0, 11, 16), Err(TileError::TooMany { .. })));
        assert_eq!(parse_tile("3/16"), Ok((3, 16)));
        assert!(parse_tile("3").is_err() && parse_tile("-1/4").is_err() && parse_tile("a/b").is_err());
        let message = tile_region(10, 10, 5, 4, 16).unwrap_err().to_string();
        assert!(message.contains("0-based") && message.contains("3/4"), "{message}");
    }
}
