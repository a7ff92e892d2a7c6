#!/usr/bin/env bash
# Fuzzing step of CI (docs/security.md, "Fuzzing"): builds the cargo-fuzz targets in fuzz/,
# replays every stored regression input (fuzz/regressions/<target>/) and every seed, then
# fuzzes each target for FUZZ_SECONDS (default 60) from its seed corpus. Any crash, leak,
# timeout (FUZZ_TIMEOUT s per input, default 20) or out-of-memory (2 GiB) fails the step,
# and the input is left in fuzz/artifacts/<target>/ and printed as base64.
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
targets=(${FUZZ_TARGETS:-scene obj gltf image})

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

run() {
    local target=$1
    shift
    if ! cargo "${toolchain[@]}" fuzz run "${sanitizer[@]}" --fuzz-dir fuzz "$target" "$@"; then
        echo "ci-fuzz: target $target FAILED; the input that broke it:" >&2
        for f in fuzz/artifacts/"$target"/*; do
            [ -f "$f" ] && { echo "== $f" >&2; base64 "$f" | head -c 100000 >&2; echo >&2; }
        done
        exit 1
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
    run "$target" "$work/replay-$target" "${replay[@]}" -- -runs=0 -timeout="$timeout" -rss_limit_mb=2048
    echo "ci-fuzz: $target: fuzzing for $seconds s" >&2
    mkdir -p "$work/$target"
    dict=()
    [ -f "fuzz/$target.dict" ] && dict=(-dict="fuzz/$target.dict")
    run "$target" "$work/$target" "fuzz/seeds/$target" -- \
        -max_total_time="$seconds" -timeout="$timeout" -rss_limit_mb=2048 -max_len=131072 \
        -print_final_stats=1 "${dict[@]}"
done
echo "ci-fuzz: all targets passed" >&2
