#!/usr/bin/env bash
# Render one Prism scene K times with the `path` integrator and different
# seeds, for scripts/mitsuba_compare.py.
#
# Usage: scripts/prism_render_seeds.sh PRISM_BIN SCENE.toml K SPP DIR [EXTRA PRISM ARGS...]
#
# Writes DIR/prism_<k>.exr (linear float32 R,G,B) and DIR/prism_<k>.png for
# k = 0 .. K-1, seed 1000+k (Prism hashes pixel, sample and seed into its
# random streams, so distinct seeds give independent images). Extra
# arguments, e.g. `--width 128 --height 128` or `--threads 2`, go to
# `prism render` unchanged. Renders run one after another (each uses all
# cores); the time of each is printed. Stops at the first failing render.
set -euo pipefail
if [ $# -lt 5 ]; then
    echo "usage: $0 PRISM_BIN SCENE.toml K SPP DIR [EXTRA PRISM ARGS...]" >&2
    exit 2
fi
bin=$1 scene=$2 k_count=$3 spp=$4 dir=$5
shift 5
mkdir -p "$dir"
for ((k = 0; k < k_count; k++)); do
    start=$(date +%s.%N)
    "$bin" render "$scene" --integrator path --samples "$spp" --seed $((1000 + k)) \
        --exr "$dir/prism_$k.exr" -o "$dir/prism_$k.png" "$@" >/dev/null
    end=$(date +%s.%N)
    printf 'seed %d: %.2f s -> %s\n' $((1000 + k)) "$(echo "$end - $start" | bc)" "$dir/prism_$k.exr"
done
