#!/usr/bin/env bash
# Fuzzing step of CI (docs/security.md, "Fuzzing"): builds the cargo-fuzz targets in fuzz/,
# replays every stored regression input (fuzz/regressions/<target>/) and every seed, then
# fuzzes each target for FUZZ_SECONDS (default 60) from its seed corpus. A stored input that
# crashes, leaks, times out (FUZZ_TIMEOUT s per input, default 20) or runs out of memory
# (2 GiB) fails the step. A crash that the fresh fuzzing finds is printed as base64 and left
# in fuzz/artifacts/<target>/ as a finding to fix and store in fuzz/regressions/; it fails the
# step only with FUZZ_FAIL_ON_NEW=1 (a random search must not turn CI red at random).
#
# Toolchain: nightly (rustup's `nightly`) with AddressSanitizer. Without a nightly toolchain
# the stable one is used with RUSTC_BOOTSTRAP=1; if AddressSanitizer cannot be built there,
# the targets are built with `--sanitizer none` (libFuzzer still finds panics, hangs and
# runaway allocations). Never skipped: a missing tool is an error.
set -euo pipefail
cd "$(dirname "$0")/.."
export CARGO_TERM_COLOR=never

seconds=${FUZZ_SECONDS:-60}
timeout=${FUZZ_TIMEOUT:-20}
targets=(${FUZZ_TARGETS:-scene obj gltf ply image})

if ! command -v cargo-fuzz >/dev/null; then
    cargo install cargo-fuzz --locked
fi

toolchain=()
if rustup toolchain list 2>/dev/null | grep -q '^nightly'; then
    toolchain=(+nightly)
else
    echo "ci-fuzz: no nightly toolchain; using stable with RUSTC_BOOTSTRAP=1" >&2
    export RUSTC_BOOTSTRAP=1
fi

sanitizer=(--sanitizer address)
if ! cargo "${toolchain[@]}" fuzz build "${sanitizer[@]}" --fuzz-dir fuzz; then
    echo "ci-fuzz: the AddressSanitizer build failed; building with --sanitizer none" >&2
    sanitizer=(--sanitizer none)
    cargo "${toolchain[@]}" fuzz build "${sanitizer[@]}" --fuzz-dir fuzz
fi

findings=0
# run FATAL TARGET ARGS...: FATAL=1 for stored inputs, 0 for fresh fuzzing (see above).
run() {
    local fatal=$1 target=$2
    shift 2
    if ! cargo "${toolchain[@]}" fuzz run "${sanitizer[@]}" --fuzz-dir fuzz "$target" "$@"; then
        echo "ci-fuzz: target $target FAILED; the input that broke it:" >&2
        for f in fuzz/artifacts/"$target"/*; do
            [ -f "$f" ] && { echo "== $f" >&2; base64 "$f" | head -c 100000 >&2; echo >&2; }
        done
        if [ "$fatal" = 1 ] || [ "${FUZZ_FAIL_ON_NEW:-0}" = 1 ]; then
            exit 1
        fi
        findings=$((findings + 1))
        echo "ci-fuzz: FINDING in $target (fresh fuzzing): fix it and add the input to fuzz/regressions/$target/" >&2
    fi
}

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for target in "${targets[@]}"; do
    [ -d "fuzz/seeds/$target" ] || { echo "ci-fuzz: no seeds for $target" >&2; exit 1; }
    echo "ci-fuzz: $target: replaying regressions and seeds" >&2
    replay=("fuzz/seeds/$target")
    [ -d "fuzz/regressions/$target" ] && replay+=("fuzz/regressions/$target")
    mkdir -p "$work/replay-$target"
    run 1 "$target" "$work/replay-$target" "${replay[@]}" -- -runs=0 -timeout="$timeout" -rss_limit_mb=2048
    echo "ci-fuzz: $target: fuzzing for $seconds s" >&2
    mkdir -p "$work/$target"
    dict=()
    [ -f "fuzz/$target.dict" ] && dict=(-dict="fuzz/$target.dict")
    run 0 "$target" "$work/$target" "fuzz/seeds/$target" -- \
        -max_total_time="$seconds" -timeout="$timeout" -rss_limit_mb=2048 -max_len=131072 \
        -print_final_stats=1 "${dict[@]}"
done
if [ "$findings" -gt 0 ]; then
    echo "ci-fuzz: stored inputs all pass; fresh fuzzing has $findings FINDING(S) above to fix" >&2
else
    echo "ci-fuzz: all targets passed" >&2
fi
