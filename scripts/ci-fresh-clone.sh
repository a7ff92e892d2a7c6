#!/usr/bin/env bash
# CI fragment (called by .ci/run): a fresh clone renders every example. Clones the repository
# into a temporary folder with nothing beside it (no ../shared), runs the README's render
# command there, fetches the large assets from the registries (no local cache: the clone has
# none beside it), and renders every scene under scenes/ at 64x36 with one sample, under
# each integrator. A scene that needs a file outside the repository fails here.
#
# The clone builds in its own folder; CARGO_TARGET_DIR, when set, is reused so that the
# dependencies compiled by the earlier CI steps are not compiled again (the clone's own crates
# still are). The cargo registry cache (~/.cargo) is shared as usual.
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
git clone --quiet "$ROOT" "$TMP/prism"
cd "$TMP/prism"
[ ! -e ../shared ] || { echo "fresh-clone: $TMP/shared exists" >&2; exit 1; }

echo "fresh-clone: the README's render command"
command=$(sed -n 's/^\(cargo run --release\) *#.*/\1/p' README.md | head -n 1)
[ -n "$command" ] || { echo "fresh-clone: README.md has no \`cargo run --release\` line" >&2; exit 1; }
$command --quiet
[ -s prism.png ] || { echo "fresh-clone: \`$command\` wrote no prism.png" >&2; exit 1; }

echo "fresh-clone: scripts/fetch-assets.sh"
PRISM_ASSET_CACHE=/nonexistent bash scripts/fetch-assets.sh

PRISM=${CARGO_TARGET_DIR:-target}/release/prism
mkdir -p "$TMP/out"
failed=0
count=0
while IFS= read -r scene; do
    count=$((count + 1))
    name=$(echo "$scene" | tr '/' '_')
    # Every scene renders under both integrators (issue: "every scene in scenes/ renders
    # under both"), whichever one it names.
    for integrator in classic path; do
        if ! "$PRISM" render "$scene" --width 64 --height 36 --samples 1 --integrator "$integrator" \
            -o "$TMP/out/${name%.toml}-$integrator.png" >/dev/null 2>"$TMP/err"; then
            echo "fresh-clone: $scene does not render under $integrator in a fresh clone:" >&2
            cat "$TMP/err" >&2
            failed=1
        fi
    done
done < <(find scenes -name '*.toml' | sort)
[ "$failed" = 0 ] || exit 1
echo "fresh-clone: the README's command and all $count scenes, under both integrators, render in a fresh clone"
