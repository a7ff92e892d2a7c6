//! Helpers shared by the integration tests (each test file includes this module).

#![allow(dead_code, reason = "each test file includes this module and uses only some of its helpers")]

use std::path::PathBuf;
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

/// The repository root.
pub fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The repository's asset folder (`assets/`): the committed assets, and the large ones
/// `scripts/fetch-assets.sh` downloads into `assets/fetched/`.
pub fn assets() -> PathBuf {
    repo().join("assets")
}

/// `assets/fetched/<relative>`, a large asset that `scripts/fetch-assets.sh` downloads, or
/// `None` when it is missing. Under `CI=true` a missing asset fails the test; locally the
/// skip is written straight to the terminal (past the test harness's output capture) so it
/// shows in the test run's output.
pub fn fetched_asset(relative: &str) -> Option<PathBuf> {
    let path = assets().join("fetched").join(relative);
    if path.is_file() {
        return Some(path);
    }
    let message = format!("{} is missing: run scripts/fetch-assets.sh", path.display());
    if std::env::var("CI").is_ok_and(|v| v == "true") {
        panic!("{message} (CI=true: a missing asset is a failure)");
    }
    use std::io::Write;
    let _ = writeln!(std::io::stderr(), "SKIPPED (asset missing): {message}");
    None
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

/// Runs `command`, killing it (and failing the test) if it runs longer than `limit`: a hang
/// is a failure, not a stuck test suite.
pub fn run_within(mut command: Command, limit: Duration) -> Output {
    let mut child = command.stdin(Stdio::null()).stdout(Stdio::piped()).stderr(Stdio::piped()).spawn().unwrap();
    let start = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > limit {
            child.kill().unwrap();
            let out = child.wait_with_output().unwrap();
            panic!("still running after {limit:?}: {}", String::from_utf8_lossy(&out.stderr));
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    child.wait_with_output().unwrap()
}

/// [`run_within`] a minute: what a test's command is given before it counts as hung.
pub fn run(command: Command) -> Output {
    run_within(command, Duration::from_secs(60))
}

/// A finished command's standard error as text.
pub fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}
