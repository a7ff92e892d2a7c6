//! Every input that ever crashed a fuzz target (`fuzz/regressions/<target>/`) and every seed
//! (`fuzz/seeds/<target>/`), replayed through the fuzz targets' own bodies (`fuzz/src/lib.rs`)
//! in the normal test suite: no panic, even one a parser crate's isolation would catch.

#[allow(dead_code, reason = "the fuzz crate's constants are used by the fuzz binaries, not all here")]
#[path = "../fuzz/src/lib.rs"]
mod harness;

mod common;

use std::sync::atomic::{AtomicUsize, Ordering};

/// A fuzz target's body.
type Body = fn(&[u8]);

/// Panics seen by the hook, caught or not.
static PANICS: AtomicUsize = AtomicUsize::new(0);

#[test]
fn stored_fuzz_inputs_replay_without_a_panic() {
    let previous = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        PANICS.fetch_add(1, Ordering::SeqCst);
        previous(info);
    }));
    let targets: [(&str, Body); 5] = [
        ("scene", harness::scene),
        ("obj", harness::obj),
        ("gltf", harness::gltf),
        ("ply", harness::ply),
        ("image", harness::image),
    ];
    let fuzz = common::repo().join("fuzz");
    let mut failures = Vec::new();
    let mut replayed = 0;
    for (target, body) in targets {
        let mut seeds = 0;
        for folder in ["seeds", "regressions"] {
            let Ok(entries) = std::fs::read_dir(fuzz.join(folder).join(target)) else { continue };
            for entry in entries {
                let path = entry.unwrap().path();
                let bytes = std::fs::read(&path).unwrap();
                let before = PANICS.load(Ordering::SeqCst);
                let result = std::panic::catch_unwind(|| body(&bytes));
                if result.is_err() || PANICS.load(Ordering::SeqCst) != before {
                    failures.push(path.display().to_string());
                }
                replayed += 1;
                seeds += usize::from(folder == "seeds");
            }
        }
        assert!(seeds > 0, "no seeds for fuzz target {target}");
    }
    assert!(failures.is_empty(), "{} of {replayed} inputs panicked: {failures:?}", failures.len());
}
