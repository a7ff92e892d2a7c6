//! `watch`: noticing that files changed, by polling their modification times (`prism
//! watch`). Polling needs no platform API and no dependency, and a scene's handful of files
//! costs a few `stat` calls a poll.

use std::path::PathBuf;
use std::time::{Duration, SystemTime};

/// What a file looked like: its modification time and size, or `None` when it cannot be
/// read (missing, or not allowed).
type Stamp = Option<(SystemTime, u64)>;

fn stamp(path: &std::path::Path) -> Stamp {
    let metadata = std::fs::metadata(path).ok()?;
    Some((metadata.modified().ok()?, metadata.len()))
}

/// The stamps of a set of files at one moment.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FileStamps {
    paths: Vec<PathBuf>,
    stamps: Vec<Stamp>,
}

impl FileStamps {
    /// The files' stamps now (a missing file's stamp is that it is missing, so its
    /// appearing is a change).
    pub fn of(paths: &[PathBuf]) -> Self {
        Self { paths: paths.to_vec(), stamps: paths.iter().map(|p| stamp(p)).collect() }
    }

    /// The same files' stamps now.
    pub fn again(&self) -> Self {
        Self::of(&self.paths)
    }

    /// The files whose stamps differ between `self` and `later`.
    pub fn changed(&self, later: &Self) -> Vec<PathBuf> {
        self.paths
            .iter()
            .zip(self.stamps.iter().zip(&later.stamps))
            .filter(|(_, (a, b))| a != b)
            .map(|(p, _)| p.clone())
            .collect()
    }

    /// Blocks until a file changes, looking every `poll`, then until no file has changed for
    /// `settle` (an editor's save can be several writes; rendering a half-written file would
    /// report an error the user never made). Returns the stamps it settled on.
    pub fn wait_for_change(&self, poll: Duration, settle: Duration) -> Self {
        let mut seen = loop {
            std::thread::sleep(poll);
            let now = self.again();
            if now != *self {
                break now;
            }
        };
        let mut quiet = Duration::ZERO;
        while quiet < settle {
            std::thread::sleep(poll);
            let now = self.again();
            if now == seen {
                quiet += poll;
            } else {
                (seen, quiet) = (now, Duration::ZERO);
            }
        }
        seen
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn edits_appearances_and_removals_are_changes() {
        let dir = tempfile::tempdir().unwrap();
        let (a, b) = (dir.path().join("a.toml"), dir.path().join("b.toml"));
        std::fs::write(&a, "x = 1\n").unwrap();
        let before = FileStamps::of(&[a.clone(), b.clone()]);
        assert!(before.changed(&before.again()).is_empty());
        // A longer file differs even within one tick of the clock.
        std::fs::write(&a, "x = 12\n").unwrap();
        assert_eq!(before.changed(&before.again()), vec![a.clone()]);
        std::fs::write(&b, "").unwrap();
        assert_eq!(before.changed(&before.again()), vec![a.clone(), b.clone()]);
        std::fs::remove_file(&a).unwrap();
        let after = before.again();
        assert_eq!(after.changed(&FileStamps::of(&[a.clone(), b])), Vec::<PathBuf>::new());
        assert!(after.stamps[0].is_none());
    }

    #[test]
    fn waiting_returns_after_a_burst_of_writes_has_settled() {
        let dir = tempfile::tempdir().unwrap();
        let a = dir.path().join("a.toml");
        std::fs::write(&a, "x = 1\n").unwrap();
        let before = FileStamps::of(std::slice::from_ref(&a));
        let writer = {
            let (a, temp) = (a.clone(), dir.path().join("a.toml.tmp"));
            std::thread::spawn(move || {
                for n in 0..5 {
                    std::thread::sleep(Duration::from_millis(20));
                    // Each save whole, by rename (as many editors save): a truncated file
                    // seen mid-write would be a state of its own, and on a loaded machine
                    // the writer can stall there for longer than the settling time.
                    std::fs::write(&temp, "y".repeat(10 + n)).unwrap();
                    std::fs::rename(&temp, &a).unwrap();
                }
            })
        };
        let start = std::time::Instant::now();
        let settle = Duration::from_millis(300);
        let settled = before.wait_for_change(Duration::from_millis(10), settle);
        writer.join().unwrap();
        // It waited for the last save (about 100 ms in) and the quiet time after it.
        assert!(start.elapsed() >= settle, "{:?}", start.elapsed());
        assert_eq!(settled, before.again());
        assert_eq!(std::fs::read_to_string(&a).unwrap().len(), 14);
    }
}
