#!/bin/sh
# CI fragment for the live Mitsuba 3 check of the path integrator (called by .ci/run).
#
# Installs the pinned Mitsuba 3 and Dr.Jit from PyPI when they are missing (the scalar_rgb
# variant needs nothing else), builds Prism in release mode and runs scripts/mitsuba-check.sh
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
python3 -c "import mitsuba; print('Mitsuba', mitsuba.__version__)"
cargo build --release --quiet
bash scripts/mitsuba-check.sh target/release/prism 16 256
