#!/bin/sh
# Renders every scene in scenes/ (parity scenes included) to EXR with 1 and 2 threads and
# compares the files byte for byte with a baseline folder made the same way by an older
# build. Used to check that a refactor leaves every image unchanged.
#
#   scripts/byte-identity.sh record BIN DIR    render with BIN into DIR (the baseline)
#   scripts/byte-identity.sh check  BIN DIR    render with BIN and compare with DIR
#
# Scenes render at their own size; PRISM_IDENTITY_SIZE=WxH overrides it to save time.
set -eu
mode=$1 bin=$2 dir=$3
ROOT=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$dir"
work=$(mktemp -d "${TMPDIR:-/tmp}/prism-identity.XXXXXX")
trap 'rm -rf "$work"' EXIT
size=""
if [ -n "${PRISM_IDENTITY_SIZE:-}" ]; then
    size="--width ${PRISM_IDENTITY_SIZE%x*} --height ${PRISM_IDENTITY_SIZE#*x}"
fi
fail=0
for scene in "$ROOT"/scenes/*.toml "$ROOT"/scenes/parity/*.toml; do
    name=$(basename "$(dirname "$scene")")_$(basename "$scene" .toml)
    for threads in 1 2; do
        out="$work/$name.t$threads.exr"
        # shellcheck disable=SC2086
        "$bin" render "$scene" --exr "$out" --threads "$threads" $size >/dev/null 2>"$work/err" || {
            echo "FAIL $name (threads $threads): render failed"; cat "$work/err"; fail=1; continue; }
        if [ "$mode" = record ]; then
            mv "$out" "$dir/"
        elif cmp -s "$out" "$dir/$name.t$threads.exr"; then
            echo "same $name (threads $threads)"
        else
            echo "DIFF $name (threads $threads)"; fail=1
        fi
    done
done
exit $fail
