//! Helpers shared by the integration tests (each test file includes this module).

#![allow(dead_code, reason = "each test file includes this module and uses only some of its helpers")]

use std::path::PathBuf;
use std::process::Output;

/// The repository root.
pub fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The shared asset folder (`$PRISM_ASSETS`, then `../shared/assets`), or `None` with a
/// `SKIPPED` message when it is not there.
pub fn shared_assets() -> Option<PathBuf> {
    let candidates: Vec<PathBuf> = std::env::var_os("PRISM_ASSETS")
        .map(PathBuf::from)
        .into_iter()
        .chain([repo().join("../shared/assets")])
        .collect();
    let found = candidates.iter().find(|p| p.join("obj").is_dir() || p.join("gltf").is_dir()).cloned();
    if found.is_none() {
        eprintln!(
            "SKIPPED: shared mesh assets not found (looked in {}); set PRISM_ASSETS to run the asset tests",
            candidates.iter().map(|p| p.display().to_string()).collect::<Vec<_>>().join(", ")
        );
    }
    found
}

/// What is wrong with a CLI run that should have failed cleanly: a zero exit, a panic or
/// signal, or a message missing one of `expect`.
pub fn failed_run_problems(run: &Output, expect: &[&str]) -> Vec<String> {
    let stderr = String::from_utf8_lossy(&run.stderr);
    let mut problems = Vec::new();
    if run.status.success() {
        problems.push("exited 0".to_string());
    }
    if run.status.code().is_none() || stderr.contains("panicked") {
        problems.push("panicked or was killed".to_string());
    }
    for e in expect {
        if !stderr.contains(e) {
            problems.push(format!("message lacks `{e}`"));
        }
    }
    problems
}
