#!/bin/sh
# Render the POV-Ray references of the example scenes (scenes/povray-examples/NAME.toml).
#
# usage: scripts/povray-example-references.sh [OUTDIR] [NAME...]
#
# Unlike scenes/parity, where Prism's exporter writes the .pov files, these scenes are POV-Ray's
# own sample scenes: POV-Ray renders the committed original NAME.pov, unchanged, to
# OUTDIR/NAME.exr (linear, half-float OpenEXR) with the options of the "# povray-options:"
# line in NAME.toml (size, antialiasing, always -J). OUTDIR defaults to scenes/povray-examples,
# i.e. the committed references; give a fresh directory to check against a live POV-Ray
# instead (tests/parity.rs reads PRISM_PARITY_REFS/povray-examples).
#
# Environment: THREADS   POV-Ray render threads (default 2; the results do not depend on it)
set -eu
ROOT=$(cd "$(dirname "$0")/.." && pwd)
SCENES=$ROOT/scenes/povray-examples
OUT=${1:-$SCENES}
[ $# -gt 0 ] && shift
THREADS=${THREADS:-2}

if ! command -v povray >/dev/null 2>&1; then
    echo "error: povray (POV-Ray 3.7) is not installed, so the references cannot be rendered." >&2
    echo "       install it with: apt-get update && apt-get install -y povray" >&2
    exit 1
fi
mkdir -p "$OUT"
OUT=$(cd "$OUT" && pwd)

if [ $# -gt 0 ]; then
    NAMES=$*
else
    NAMES=$(cd "$SCENES" && ls ./*.toml | sed 's|^\./||; s|\.toml$||')
fi
for name in $NAMES; do
    scene=$SCENES/$name.toml
    options=$(sed -n 's|^# povray-options: ||p' "$scene")
    if [ -z "$options" ]; then
        echo "error: $scene has no '# povray-options:' line" >&2
        exit 1
    fi
    log=$OUT/$name.povray.log
    # Run from the scene directory so that includes beside the original are found.
    # -D: no preview window; +FE: OpenEXR output.
    # shellcheck disable=SC2086 # the options are words
    if ! (cd "$SCENES" && povray "$name.pov" $options -D +WT"$THREADS" +FE +O"$OUT/$name.exr") >"$log" 2>&1; then
        echo "error: povray failed on $SCENES/$name.pov ($options), see $log:" >&2
        tail -20 "$log" >&2
        exit 1
    fi
    rm -f "$log"
    echo "$name: $options -> $OUT/$name.exr"
done
