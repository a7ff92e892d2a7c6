#!/usr/bin/env bash
# Regenerates the gallery: renders every example scene in scenes/ (top level) with each
# integrator that makes sense for it into docs/gallery/, timing each render, and rewrites
# docs/gallery.md with the images, the times and the commands. Sizes and sample counts are
# modest (480 pixels wide) so the whole gallery takes a few minutes on two cores.
#
# Usage: scripts/gallery.sh            (fetches the large assets first if they are missing)
# PRISM=path/to/prism picks a binary; otherwise `cargo build --release` is run.
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
cd "$ROOT"
if [ -z "${PRISM:-}" ]; then
    cargo build --release --quiet
    PRISM=target/release/prism
fi
bash scripts/fetch-assets.sh >/dev/null

# scene integrator width height samples ("-": the scene's own) -- one line per image.
# cornell.toml is path traced (its emitter lights nothing under classic); cornell_classic.toml
# is POV-Ray's version with area spotlights (too dark under physical units for path).
ENTRIES="
room classic 480 270 -
room_path path 480 270 32
snowman classic 480 270 -
snowman_path path 480 270 32
cornell path 480 480 32
cornell_classic classic 480 480 -
gltf_engine classic 480 270 -
gltf_engine path 480 270 16
gltf_clearcoat classic 480 480 -
gltf_clearcoat path 480 480 16
gltf_showcase path 480 270 32
dragons classic 480 270 -
dragons path 480 270 8
string_lights path 480 270 64
"

# Every top-level scene must have an entry: a new scene without one fails here.
for scene in scenes/*.toml; do
    name=$(basename "$scene" .toml)
    echo "$ENTRIES" | grep -q "^$name " || { echo "gallery: $scene has no entry in scripts/gallery.sh" >&2; exit 1; }
done

mkdir -p docs/gallery
rows=""
while read -r scene integrator width height samples; do
    [ -n "$scene" ] || continue
    out="docs/gallery/${scene}_${integrator}.png"
    args="render scenes/$scene.toml --integrator $integrator --width $width --height $height"
    [ "$samples" = "-" ] || args="$args --samples $samples"
    args="$args -o $out"
    start=$(date +%s.%N)
    # shellcheck disable=SC2086
    "$PRISM" $args >/dev/null 2>"$out.log" || { cat "$out.log" >&2; rm -f "$out.log"; exit 1; }
    end=$(date +%s.%N)
    spp=$(sed -n 's/.* at \([0-9]*\) spp.*/\1/p' "$out.log" | tail -n 1)
    rm -f "$out.log"
    seconds=$(echo "$start $end" | awk '{printf "%.1f", $2 - $1}')
    echo "gallery: $out ${width}x$height, $spp spp, $integrator: $seconds s"
    rows="$rows$scene|$integrator|$width|$height|$spp|$seconds|prism $args
"
done <<<"$ENTRIES"

{
    echo "# Gallery"
    echo
    echo "Every example scene in \`scenes/\`, rendered by \`scripts/gallery.sh\` (which writes this"
    echo "page) at 480 pixels wide with the integrators that make sense for it. Times are wall-clock"
    echo "seconds for the whole command (loading, importing meshes and building BVHs included) on"
    echo "the machine that last ran the script, $(nproc) cores shared with other work, so compare"
    echo "them with each other rather than with other machines (load average when the script"
    echo "ended: $(cut -d' ' -f1-3 /proc/loadavg)). \`prism\` is"
    echo "\`cargo run --release --\`; the dragons need \`scripts/fetch-assets.sh\` first."
    current=""
    while IFS='|' read -r scene integrator width height spp seconds command; do
        [ -n "$scene" ] || continue
        if [ "$scene" != "$current" ]; then
            current=$scene
            echo
            echo "## \`scenes/$scene.toml\`"
        fi
        echo
        echo "![$scene under $integrator](gallery/${scene}_${integrator}.png)"
        echo
        echo "\`$integrator\`, ${width}x$height, $spp spp: $seconds s"
        echo
        echo '```sh'
        echo "$command"
        echo '```'
    done <<<"$rows"
} >docs/gallery.md
echo "gallery: wrote docs/gallery.md"
