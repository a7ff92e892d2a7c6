#!/bin/sh
# Regenerate the POV-Ray references of the parity scenes (scenes/parity/*.toml).
#
# usage: scripts/povray-references.sh [OUTDIR] [NAME...]
#
# For each scene NAME.toml it exports OUTDIR/NAME.pov with Prism's own exporter and renders
# OUTDIR/NAME.exr (linear, half-float OpenEXR) with POV-Ray 3.7, using the size and
# antialiasing options the exporter wrote in the file's "// povray-options:" line (always
# without jitter). OUTDIR defaults to scenes/parity, i.e. the committed references; give a
# fresh directory to check against a live POV-Ray instead (tests/parity.rs reads it from
# PRISM_PARITY_REFS).
#
# Environment: PRISM     the prism binary (default: built here with cargo build --release)
#              THREADS   POV-Ray render threads (default 2; results do not depend on it
#                        except for jittered area lights, which are compared statistically)
set -eu
ROOT=$(cd "$(dirname "$0")/.." && pwd)
OUT=${1:-$ROOT/scenes/parity}
[ $# -gt 0 ] && shift
THREADS=${THREADS:-2}

if ! command -v povray >/dev/null 2>&1; then
    echo "error: povray (POV-Ray 3.7) is not installed, so the references cannot be rendered." >&2
    echo "       install it with: apt-get update && apt-get install -y povray" >&2
    exit 1
fi
if [ -z "${PRISM:-}" ]; then
    (cd "$ROOT" && cargo build --release --quiet --bin prism)
    PRISM=${CARGO_TARGET_DIR:-$ROOT/target}/release/prism
fi
mkdir -p "$OUT"

if [ $# -gt 0 ]; then
    NAMES=$*
else
    NAMES=$(cd "$ROOT/scenes/parity" && ls ./*.toml | sed 's|^\./||; s|\.toml$||')
fi
for name in $NAMES; do
    scene=$ROOT/scenes/parity/$name.toml
    pov=$OUT/$name.pov
    "$PRISM" export pov "$scene" -o "$pov"
    options=$(sed -n 's|^// povray-options: ||p' "$pov")
    log=$OUT/$name.povray.log
    # -D: no preview window; -V: no verbose statistics; +FE: OpenEXR output; +L: the .pov's
    # folder, which the paths of files it reads (a text's font, image map PNGs) are relative to.
    # shellcheck disable=SC2086 # the options are words
    if ! povray "$pov" $options -D +WT"$THREADS" +FE +L"$OUT" +O"$OUT/$name.exr" >"$log" 2>&1; then
        echo "error: povray failed on $pov ($options), see $log:" >&2
        tail -20 "$log" >&2
        exit 1
    fi
    rm -f "$log"
    echo "$name: $options -> $OUT/$name.exr"
done
