#!/usr/bin/env bash
# The live Mitsuba 3 check of the `path` integrator (called by .ci/run; runs alone too).
#
# Usage: scripts/mitsuba-check.sh PRISM_BIN [K] [SPP] [SCENE.toml ...]
#
# For every equivalence scene in scenes/mitsuba/ (or the ones named): `prism export mitsuba`
# writes its Mitsuba 3 XML afresh in place (git must see no change to the committed
# scenes/mitsuba/NAME.xml and NAME_meshes/),
# Mitsuba renders it with K seeds (scalar_rgb; llvm_ad_rgb for a scene that uses the glTF
# metallic-roughness plugin of scripts/mitsuba_gltf_bsdf.py or a non-box pixel filter, which
# the scalar variants discretise) and Prism renders it with K other
# seeds, both at SPP samples per pixel and the scene's size, and scripts/mitsuba_compare.py
# decides with a per-pixel Welch t-test (Sidak-corrected) and a whole-image bias bound.
# A failure leaves the mean, reference, difference and p-value images in the work folder
# and prints how to look at them. Needs python3 with mitsuba==3.9.1 and libllvm19 (installed
# by scripts/ci-mitsuba.sh).
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
cd "$ROOT"
bin=${1:?usage: $0 PRISM_BIN [K] [SPP] [SCENE.toml ...]}
k=${2:-16}
spp=${3:-32}
shift $(( $# < 3 ? $# : 3 ))
scenes=("$@")
if [ ${#scenes[@]} -eq 0 ]; then
    scenes=(scenes/mitsuba/*.toml)
fi
work=$(mktemp -d "${TMPDIR:-/tmp}/prism-mitsuba.XXXXXX")
failed=()
for scene in "${scenes[@]}"; do
    name=$(basename "$scene" .toml)
    dir="$work/$name"
    mkdir -p "$dir"
    # Written in place (its file references are relative to it), then compared with the
    # committed version by git.
    folder=$(dirname "$scene")
    committed="$folder/$name.xml"
    "$bin" export mitsuba "$scene" -o "$committed"
    if ! git diff --quiet -- "$committed" "$folder/${name}_meshes" ||
        [ -n "$(git ls-files --others --exclude-standard -- "$committed" "$folder/${name}_meshes")" ]; then
        echo "error: $committed is not what the exporter writes now (or is not committed); the fresh" >&2
        echo "export is in the work tree: review it with git diff and commit it" >&2
        git diff -- "$committed" | head -20 >&2 || true
        failed+=("$name")
        continue
    fi
    python3 scripts/mitsuba_render_seeds.py "$committed" --seeds "$k" --spp "$spp" --out "$dir/mitsuba" >/dev/null
    scripts/prism_render_seeds.sh "$bin" "$scene" "$k" "$spp" "$dir/prism" >/dev/null 2>&1
    if python3 scripts/mitsuba_compare.py --name "$name" --out "$dir/compare" \
        --prism "$dir"/prism/prism_*.exr --mitsuba "$dir"/mitsuba/mitsuba_*.exr; then
        :
    else
        echo "the images of $name are in $dir/compare (mean, reference, difference, p-values)" >&2
        failed+=("$name")
    fi
done
if [ ${#failed[@]} -gt 0 ]; then
    echo "FAIL: ${failed[*]} (K=$k, $spp spp each; work folder $work)" >&2
    exit 1
fi
echo "all ${#scenes[@]} Mitsuba equivalence scenes pass (K=$k, $spp spp each)"
rm -rf "$work"
