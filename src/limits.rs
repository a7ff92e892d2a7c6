//! `limits`: the caps on what one scene may ask for, and the memory budget that large
//! allocations (the film and its layers, decoded textures, meshes with their BVHs, imported
//! instances) are estimated against before they are made. `docs/security.md` lists them all.

/// Most render threads (`--threads`); more is an error.
pub const MAX_THREADS: usize = 256;

/// Most instances (node placements) one glTF file's node graph may expand to: a graph whose
/// nodes name the same children repeatedly grows exponentially.
pub const MAX_GLTF_INSTANCES: usize = 1_000_000;

/// Most distinct scene files (the scene and its includes) one load reads.
pub const MAX_SCENE_FILES: usize = 10_000;

/// Longest side of a texture, in texels.
pub const MAX_TEXTURE_SIDE: u32 = 32_768;

/// Largest magnitude of a colour component (material colours, light colours, emission;
/// emission may be enormous for tiny lamps): beyond it, products overflow even `f64`
/// (a colour of -1e308 rendered NaN). A product that still overflows the film's `f32` is
/// caught by the film's last line of defence.
pub const MAX_COLOR_COMPONENT: f64 = 1e30;

/// Largest magnitude of a scalar material or light coefficient (intensities, fades, finish
/// values).
pub const MAX_COEFFICIENT: f64 = 1e9;

/// Largest index of refraction (real materials stay below 5; 1e17 broke the renderer).
pub const MAX_IOR: f64 = 100.0;

/// The default memory budget when the machine's memory is known: this fraction of it.
pub const DEFAULT_MEMORY_FRACTION: f64 = 0.75;

/// The default memory budget when the machine's memory is unknown: 4 GiB.
pub const FALLBACK_MEMORY_BUDGET: u64 = 4 << 30;

/// Bytes of film per pixel and per channel of output (beauty and layers are `f32`; the
/// encoders make one more copy of each channel, and 8-bit formats one byte more).
const FILM_BYTES_PER_CHANNEL: u64 = 8;

/// Bytes one imported entity (a mesh file's node, or one placement of a mesh part) costs
/// from loading to rendering, about: the entity and its components, its world transform,
/// its render primitive and its share of the scene BVH.
pub const BYTES_PER_INSTANCE: u64 = 1024;

/// Bytes of memory parsing takes per byte of scene TOML, at most: measured on the worst
/// case, deeply nested inline tables (a 55 MB file of nested `normal_map`s peaked at 9.8 GB
/// while parsed, checked and indexed for error locations); flat scenes take about 80.
pub const PARSED_BYTES_PER_SCENE_BYTE: u64 = 200;

/// Scene TOML parsed whatever the memory budget (at most 200 MiB while parsed, less than
/// any render needs), so that small budgets meant for meshes still load small scenes.
pub const UNBUDGETED_SCENE_BYTES: u64 = 1 << 20;

/// An estimate over the memory budget.
#[derive(Debug, Clone, thiserror::Error, PartialEq, Eq)]
#[error("{what} needs about {}{}, over the memory budget of {} (--max-memory)", size(*.estimate), spent_before(*.spent), size(*.budget))]
pub struct OverBudget {
    /// What would be allocated (`a 16384 x 16384 film`, `texture `wood.png``).
    pub what: String,
    /// Its estimated size in bytes.
    pub estimate: u64,
    /// The budget in bytes.
    pub budget: u64,
    /// Bytes already taken out of the same budget by what was loaded before (meshes and
    /// images of one load share one budget; 0 for a single allocation's check).
    pub spent: u64,
}

fn spent_before(spent: u64) -> String {
    if spent == 0 {
        String::new()
    } else {
        format!(" on top of {} for the meshes and images loaded before it", size(spent))
    }
}

/// A size in bytes as a message shows it: whole MiB from 1 MiB up (rounded up, as the
/// estimates are), else KiB or bytes, so that a tiny budget does not read as 1 MiB.
fn size(bytes: u64) -> String {
    if bytes >= 1 << 20 {
        format!("{} MiB", bytes.div_ceil(1 << 20))
    } else if bytes >= 1 << 10 {
        format!("{} KiB", bytes.div_ceil(1 << 10))
    } else if bytes == 1 {
        "1 byte".into()
    } else {
        format!("{bytes} bytes")
    }
}

/// A memory budget in bytes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MemoryBudget(pub u64);

impl Default for MemoryBudget {
    /// [`DEFAULT_MEMORY_FRACTION`] of the machine's memory (`MemTotal` of `/proc/meminfo`),
    /// or [`FALLBACK_MEMORY_BUDGET`] where that is unknown.
    fn default() -> Self {
        match physical_memory() {
            Some(total) => Self((total as f64 * DEFAULT_MEMORY_FRACTION) as u64),
            None => Self(FALLBACK_MEMORY_BUDGET),
        }
    }
}

impl MemoryBudget {
    /// No limit (tests, library callers that budget themselves).
    pub const UNLIMITED: Self = Self(u64::MAX);

    /// Ok when `estimate` bytes fit the budget.
    pub fn check(self, what: impl FnOnce() -> String, estimate: u64) -> Result<(), OverBudget> {
        if estimate > self.0 { Err(OverBudget { what: what(), estimate, budget: self.0, spent: 0 }) } else { Ok(()) }
    }

    /// The estimated bytes of a `width` × `height` film with `channels` channels in all
    /// (3 for beauty plus each layer's).
    pub fn film_estimate(width: u32, height: u32, channels: u32) -> u64 {
        u64::from(width)
            .saturating_mul(u64::from(height))
            .saturating_mul(u64::from(channels) * FILM_BYTES_PER_CHANNEL + 4)
    }
}

/// The machine's memory in bytes (Linux: `MemTotal` in `/proc/meminfo`).
pub fn physical_memory() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    parse_meminfo(&text)
}

fn parse_meminfo(text: &str) -> Option<u64> {
    let line = text.lines().find(|l| l.starts_with("MemTotal:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    kib.checked_mul(1024)
}

/// Parses a `--max-memory` value: bytes, or a number with a `K`, `M`, `G` or `T` suffix
/// (binary: `512M` is 512 MiB).
pub fn parse_size(text: &str) -> Result<u64, String> {
    let t = text.trim();
    let (digits, shift) = match t.chars().last().map(|c| c.to_ascii_uppercase()) {
        Some('K') => (&t[..t.len() - 1], 10),
        Some('M') => (&t[..t.len() - 1], 20),
        Some('G') => (&t[..t.len() - 1], 30),
        Some('T') => (&t[..t.len() - 1], 40),
        _ => (t, 0),
    };
    let n: u64 = digits.parse().map_err(|_| "expected a size such as 2048M or 8G".to_string())?;
    if n == 0 {
        return Err("must be more than 0".into());
    }
    n.checked_mul(1 << shift).ok_or_else(|| "too large".to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_parse_with_binary_suffixes() {
        assert_eq!(parse_size("512M"), Ok(512 << 20));
        assert_eq!(parse_size("8g"), Ok(8 << 30));
        assert_eq!(parse_size("1000"), Ok(1000));
        assert!(parse_size("0").is_err());
        assert!(parse_size("-1G").is_err());
        assert!(parse_size("99999999999T").is_err());
    }

    #[test]
    fn meminfo_total_is_read() {
        assert_eq!(parse_meminfo("MemTotal:       16314660 kB\nMemFree: 1 kB\n"), Some(16_314_660 * 1024));
        assert_eq!(parse_meminfo("nothing"), None);
    }

    #[test]
    fn the_budget_names_what_is_over_it() {
        let e = MemoryBudget(1 << 20).check(|| "a 16384 x 16383 film".into(), 3 << 30).unwrap_err();
        assert_eq!(
            e.to_string(),
            "a 16384 x 16383 film needs about 3072 MiB, over the memory budget of 1 MiB (--max-memory)"
        );
        assert!(MemoryBudget::UNLIMITED.check(String::new, u64::MAX).is_ok());
        let e = MemoryBudget(1).check(|| "a 64 x 48 film".into(), 80_000).unwrap_err();
        assert_eq!(e.to_string(), "a 64 x 48 film needs about 79 KiB, over the memory budget of 1 byte (--max-memory)");
    }
}
