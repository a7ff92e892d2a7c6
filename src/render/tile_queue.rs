//! How the render threads share out the frame's tiles.
//!
//! Each worker owns one contiguous run of tiles and takes them front to back; a worker whose
//! run is empty takes single tiles from the back of the run with the most tiles left. No
//! worker idles while another still has tiles queued (rayon's splitting of a tile range runs
//! long stretches as one piece that cannot be stolen: where cost varies across the frame,
//! one core idled for a third of a render), and the workers stay apart in the frame until
//! the end (threads on neighbouring tiles contend for the film's rows and the border
//! samples the tiles share: a few per cent of a simple scene's time).

use std::ops::Range;
use std::sync::{Mutex, MutexGuard, PoisonError};

/// Tiles `0..count` shared out among a fixed number of workers.
pub struct TileQueue {
    /// Per worker, the tiles still queued in its run. A tile takes milliseconds to render,
    /// a lock nanoseconds: the locks are as good as free.
    runs: Vec<Mutex<Range<u64>>>,
}

impl TileQueue {
    /// Tiles `0..count` in `workers` runs of (nearly) equal length, in order (at least one
    /// run, so every tile is queued even for zero workers).
    pub fn new(count: u64, workers: usize) -> Self {
        let workers = u64::try_from(workers.max(1)).unwrap_or(u64::MAX).min(count.max(1));
        // count * i / workers without overflow: count = q * workers + r.
        let (q, r) = (count / workers, count % workers);
        let bound = |i: u64| q * i + r * i / workers;
        let runs = (0..workers).map(|i| Mutex::new(bound(i)..bound(i + 1))).collect();
        Self { runs }
    }

    /// The next tile for `worker` (any index; those beyond the runs only take from others),
    /// or `None` once every tile has been taken. Every tile is handed out exactly once.
    pub fn take(&self, worker: usize) -> Option<u64> {
        if let Some(own) = self.runs.get(worker)
            && let Some(tile) = Self::lock(own).next()
        {
            return Some(tile);
        }
        loop {
            // The run with the most tiles left.
            let victim = self.runs.iter().max_by_key(|run| Self::left(run))?;
            if let Some(tile) = Self::lock(victim).next_back() {
                return Some(tile);
            }
            // Emptied meanwhile; runs only shrink, so once all are empty the queue is.
            if self.runs.iter().all(|run| Self::left(run) == 0) {
                return None;
            }
        }
    }

    fn lock(run: &Mutex<Range<u64>>) -> MutexGuard<'_, Range<u64>> {
        run.lock().unwrap_or_else(PoisonError::into_inner)
    }

    /// How many tiles `run` has left.
    fn left(run: &Mutex<Range<u64>>) -> u64 {
        let run = Self::lock(run);
        run.end.saturating_sub(run.start)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_worker_takes_every_tile_in_order() {
        let queue = TileQueue::new(5, 1);
        let taken: Vec<u64> = std::iter::from_fn(|| queue.take(0)).collect();
        assert_eq!(taken, [0, 1, 2, 3, 4]);
    }

    #[test]
    fn workers_start_on_their_own_runs_and_then_take_from_the_longest_back() {
        let queue = TileQueue::new(10, 2);
        // Runs 0..5 and 5..10.
        assert_eq!(queue.take(0), Some(0));
        assert_eq!(queue.take(1), Some(5));
        for expected in 6..10 {
            assert_eq!(queue.take(1), Some(expected));
        }
        // Worker 1's run is empty: it takes from the back of worker 0's (1..5 left).
        assert_eq!(queue.take(1), Some(4));
        assert_eq!(queue.take(0), Some(1));
        assert_eq!(queue.take(1), Some(3));
        assert_eq!(queue.take(0), Some(2));
        assert_eq!(queue.take(0), None);
        assert_eq!(queue.take(1), None);
    }

    #[test]
    fn more_workers_than_tiles_and_no_tiles() {
        let queue = TileQueue::new(2, 8);
        let mut taken: Vec<u64> = (0..8).filter_map(|w| queue.take(w)).collect();
        taken.sort_unstable();
        assert_eq!(taken, [0, 1]);
        assert_eq!(TileQueue::new(0, 2).take(0), None);
        assert_eq!(TileQueue::new(3, 0).take(0), Some(0));
    }

    #[test]
    fn concurrent_workers_take_every_tile_exactly_once() {
        const TILES: u64 = 20_000;
        for workers in [2, 3, 7] {
            let queue = TileQueue::new(TILES, workers);
            let mut taken: Vec<u64> = std::thread::scope(|scope| {
                let handles: Vec<_> = (0..workers)
                    .map(|w| {
                        let queue = &queue;
                        // Uneven work: some workers stop to "render" longer, so the others
                        // run dry and take from their runs.
                        scope.spawn(move || {
                            let mut mine = Vec::new();
                            while let Some(tile) = queue.take(w) {
                                if w == 0 && tile % 64 == 0 {
                                    std::thread::yield_now();
                                }
                                mine.push(tile);
                            }
                            mine
                        })
                    })
                    .collect();
                handles.into_iter().flat_map(|h| h.join().expect("worker")).collect()
            });
            taken.sort_unstable();
            assert_eq!(taken, (0..TILES).collect::<Vec<_>>(), "{workers} workers");
        }
    }
}
