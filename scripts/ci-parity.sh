#!/bin/sh
# CI fragment for the live POV-Ray parity check (called by .ci/run).
#
# Installs Debian's POV-Ray 3.7 when it is missing, re-renders every parity reference into a
# fresh directory with scripts/povray-references.sh (our exporter writes the .pov files,
# povray renders them) and the references of POV-Ray's own sample scenes into its
# povray-examples/ with scripts/povray-example-references.sh (povray renders the committed
# originals), checks that the exporter still writes the committed .pov files, and runs
# tests/parity.rs against the fresh images as well as the committed ones (PRISM_PARITY_REFS).
# A missing POV-Ray that cannot be installed is an error, never a skip.
set -eu
ROOT=$(cd "$(dirname "$0")/.." && pwd)
cd "$ROOT"

# povray-includes (colors.inc, finish.inc, ...) is only recommended by povray; the sample
# scenes in scenes/povray-examples include it.
if ! command -v povray >/dev/null 2>&1 || [ ! -e /usr/share/povray-3.7/include/colors.inc ]; then
    if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
        apt-get update -qq &&
            DEBIAN_FRONTEND=noninteractive apt-get install -y -qq povray povray-includes >/dev/null
    fi
fi
if ! command -v povray >/dev/null 2>&1; then
    echo "error: the live parity check needs POV-Ray 3.7; install it with: apt-get install povray" >&2
    exit 1
fi
povray --version 2>&1 | grep -m1 "^POV-Ray" || true

FRESH=$(mktemp -d "${TMPDIR:-/tmp}/prism-parity-refs.XXXXXX")
scripts/povray-references.sh "$FRESH"
scripts/povray-example-references.sh "$FRESH/povray-examples"

# The committed .pov files name the files they read (fonts, image maps) relative to their own
# folder, so each is compared with an export written into that folder.
PRISM_BIN=${PRISM:-${CARGO_TARGET_DIR:-$ROOT/target}/release/prism}
stale=0
for pov in "$FRESH"/*.pov; do
    name=$(basename "$pov" .pov)
    check=$(mktemp "$ROOT/scenes/parity/.$name.XXXXXX.pov")
    "$PRISM_BIN" export pov "scenes/parity/$name.toml" -o "$check"
    if ! cmp -s "$check" "scenes/parity/$name.pov"; then
        echo "error: scenes/parity/$name.pov is not what the exporter writes now:" >&2
        diff -u "scenes/parity/$name.pov" "$check" | head -40 >&2 || true
        stale=1
    fi
    rm -f "$check"
done
if [ "$stale" = 1 ]; then
    echo "regenerate the committed files with: scripts/povray-references.sh" >&2
    exit 1
fi

PRISM_PARITY_REFS="$FRESH" cargo test --test parity -- --nocapture
