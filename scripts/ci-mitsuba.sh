#!/bin/sh
# CI fragment for the live Mitsuba 3 check of the path integrator (called by .ci/run).
#
# Installs the pinned Mitsuba 3 and Dr.Jit from PyPI when they are missing, and Debian's
# libllvm19 for the llvm_ad_rgb variant (scenes that use the glTF metallic-roughness plugin of
# scripts/mitsuba_gltf_bsdf.py render in it; the others in scalar_rgb, which needs nothing
# else), builds Prism in release mode and runs scripts/mitsuba-check.sh
# over every scene of scenes/mitsuba/: fresh exports, K = 16 fresh renders on each side, the
# statistical comparison. A Mitsuba that cannot be installed is an error, never a skip.
set -eu
ROOT=$(cd "$(dirname "$0")/.." && pwd)
cd "$ROOT"
MITSUBA=3.9.1
DRJIT=1.5.0
if ! python3 -c "import mitsuba, sys; sys.exit(mitsuba.__version__ != '$MITSUBA')" 2>/dev/null; then
    python3 -m pip install --quiet "mitsuba==$MITSUBA" "drjit==$DRJIT" numpy
fi
if ! ldconfig -p | grep -q 'libLLVM.so.19\|libLLVM-19'; then
    apt-get update -qq && apt-get install -y -qq libllvm19 >/dev/null
fi
python3 -c "import mitsuba; print('Mitsuba', mitsuba.__version__)"
python3 -c "import mitsuba as mi; mi.set_variant('llvm_ad_rgb'); mi.render(mi.load_dict(mi.cornell_box()), spp=1)"
# The glTF plugin's own checks: chi-square of its sampling, eval/pdf consistency, furnace.
python3 scripts/mitsuba_gltf_bsdf.py >/dev/null
cargo build --release --quiet
bash scripts/mitsuba-check.sh target/release/prism 16 256
