#!/usr/bin/env bash
# CI: render farms on a real Slurm cluster (called by .ci/run; docs/farm.md).
#
# Installs Debian's slurm-wlm and munge when missing, writes a one-node cluster on this
# machine (its real hostname, CPUs and memory as `slurmd -C` reports them; process tracking
# and task plugins that need no cgroups, so it runs in a container), creates a munge key,
# starts munged, slurmctld and slurmd, and for a parity scene (POV-Ray's adaptive
# antialiasing) and a path-traced scene:
#   - submits `prism farm slurm --tiles 4` (a job array of 4 tiles and a merge job after it),
#   - waits (bounded), and checks the merged EXR is byte-identical to a one-process render,
#   - deletes one tile, checks `prism merge` names it, re-submits only that tile
#     (`sbatch --array=I`), merges again and checks the bytes again.
# Prints its wall time and the tiles' summed render time against one render's. Stops the
# daemons it started, whatever happens. Usage: scripts/slurm-check.sh [PRISM_BINARY]
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
START=$(date +%s.%N)
PRISM=${1:-}
if [ -z "$PRISM" ]; then
    (cd "$ROOT" && cargo build --release --quiet --bin prism)
    PRISM="$ROOT/target/release/prism"
fi
PRISM=$(realpath "$PRISM")
TIMEOUT=${SLURM_CHECK_TIMEOUT:-300}

if ! command -v slurmctld >/dev/null 2>&1 || ! command -v munged >/dev/null 2>&1; then
    if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
        apt-get update -qq
        DEBIAN_FRONTEND=noninteractive apt-get install -y -qq slurm-wlm munge >/dev/null
    fi
fi
for tool in slurmctld slurmd munged sbatch squeue; do
    if ! command -v "$tool" >/dev/null 2>&1; then
        echo "error: the Slurm check needs $tool; install Slurm with: apt-get install slurm-wlm munge" >&2
        exit 1
    fi
done
if [ "$(id -u)" != 0 ]; then
    echo "error: the Slurm check starts slurmd, which runs jobs as their users: run it as root (as CI does)" >&2
    exit 1
fi

# Everything lives in one folder on the (shared, here: local) filesystem; the tests' outputs
# too, so the cluster's "shared path" is real.
WORK=$(mktemp -d "${TMPDIR:-/tmp}/prism-slurm.XXXXXX")
chmod 755 "$WORK"
export SLURM_CONF="$WORK/slurm.conf"
PIDS=()
cleanup() {
    status=$?
    for pid in "${PIDS[@]}"; do
        kill "$pid" 2>/dev/null || true
    done
    for pidfile in "$WORK"/slurmctld.pid "$WORK"/slurmd.pid "$WORK"/munged.pid; do
        [ -s "$pidfile" ] && kill "$(cat "$pidfile")" 2>/dev/null || true
    done
    sleep 1
    if [ "$status" != 0 ]; then
        echo "--- slurm check failed; daemon logs:" >&2
        tail -n 20 "$WORK"/*.log >&2 2>/dev/null || true
    fi
    rm -rf "$WORK"
    exit "$status"
}
trap cleanup EXIT INT TERM

# munge: a fresh key, a daemon of our own (its own socket, so a system munged is untouched).
mkdir -p "$WORK/munge"
dd if=/dev/urandom of="$WORK/munge/munge.key" bs=1024 count=1 status=none
chmod 700 "$WORK/munge"
chmod 400 "$WORK/munge/munge.key"
SOCKET="$WORK/munge/munge.socket"
munged --force --key-file="$WORK/munge/munge.key" --socket="$SOCKET" \
    --pid-file="$WORK/munged.pid" --log-file="$WORK/munged.log" --seed-file="$WORK/munge/seed"

# The node as slurmd sees it: NodeName=<hostname> CPUs=... RealMemory=...
NODE=$(slurmd -C | head -n 1)
HOST=$(hostname -s)
cat >"$SLURM_CONF" <<EOF
ClusterName=prism-ci
SlurmctldHost=$HOST(127.0.0.1)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$SOCKET
CredType=cred/munge
MpiDefault=none
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
DependencyParameters=kill_invalid_depend
StateSaveLocation=$WORK/state
SlurmdSpoolDir=$WORK/spool
SlurmctldPidFile=$WORK/slurmctld.pid
SlurmdPidFile=$WORK/slurmd.pid
SlurmctldLogFile=$WORK/slurmctld.log
SlurmdLogFile=$WORK/slurmd.log
SlurmctldPort=${SLURM_CHECK_PORT:-6817}
SlurmdPort=$(( ${SLURM_CHECK_PORT:-6817} + 1 ))
$NODE NodeAddr=127.0.0.1 State=UNKNOWN
PartitionName=ci Nodes=ALL Default=YES MaxTime=INFINITE State=UP
EOF
mkdir -p "$WORK/state" "$WORK/spool"
slurmctld -i
slurmd
for _ in $(seq 60); do
    sinfo -h -o %t 2>/dev/null | grep -qE '^(idle|mix|alloc)' && break
    sleep 1
done
sinfo -h -o %t | grep -qE '^(idle|mix|alloc)' || { echo "error: the Slurm node did not come up" >&2; exit 1; }
echo "slurm: $(sinfo --version) cluster up on $HOST: $NODE"

# Waits until every job of `ids` has left the queue (bounded).
wait_jobs() {
    local deadline=$(( $(date +%s) + TIMEOUT ))
    while [ -n "$(squeue -h -j "$1" 2>/dev/null)" ]; do
        if [ "$(date +%s)" -gt "$deadline" ]; then
            echo "error: jobs $1 still queued after ${TIMEOUT}s:" >&2
            squeue -j "$1" >&2 || true
            exit 1
        fi
        sleep 1
    done
}

# Sum of the "in X s" render times of the tile logs.
tile_seconds() {
    cat "$1"/tile-*.log | sed -n 's/.* in \([0-9.]*\) s -> .*/\1/p' | awk '{s += $1} END {printf "%.3f", s}'
}

check_scene() {
    local name=$1 scene=$2 size=$3
    shift 3
    local out="$WORK/$name"
    mkdir -p "$out"
    # One process, for reference.
    local t0 t1
    t0=$(date +%s.%N)
    "$PRISM" render "$scene" $size --threads 1 --exr "$out/one.exr" 2>"$out/one.log"
    t1=$(date +%s.%N)
    local one
    one=$(sed -n 's/.* in \([0-9.]*\) s: .*/\1/p' "$out/one.log")
    # The farm: 4 tiles and the merge.
    local submitted array
    submitted=$("$PRISM" farm slurm "$scene" $size --tiles 4 --out "$out")
    echo "$name: $submitted"
    array=$(echo "$submitted" | sed -n 's/^submitted job array \([0-9]*\) .* merge job \([0-9]*\) .*/\1,\2/p')
    [ -n "$array" ] || { echo "error: no job ids in: $submitted" >&2; exit 1; }
    local s0 s1
    s0=$(date +%s.%N)
    wait_jobs "$array"
    s1=$(date +%s.%N)
    [ -f "$out/$name.exr" ] || { echo "error: $name: the merge job wrote no image" >&2; cat "$out"/*.log >&2; exit 1; }
    cmp "$out/one.exr" "$out/$name.exr"
    [ -f "$out/$name.png" ]
    echo "$name: merged EXR of 4 Slurm tiles is byte-identical to one process's render"
    echo "$name: one render $one s; 4 tiles $(tile_seconds "$out") s of render time in all; queue to merged $(awk "BEGIN {printf \"%.1f\", $s1 - $s0}") s"

    # A lost tile: merge names it, only it is re-run.
    rm "$out/tile-2.exr" "$out/$name.exr"
    if "$PRISM" merge -o "$out/$name.exr" "$out"/tile-*.exr 2>"$out/gap.txt"; then
        echo "error: $name: merge succeeded without tile 2" >&2
        exit 1
    fi
    grep -q "tile 2/4" "$out/gap.txt" || { echo "error: merge did not name tile 2/4:" >&2; cat "$out/gap.txt" >&2; exit 1; }
    [ ! -e "$out/$name.exr" ] || { echo "error: a failed merge wrote an image" >&2; exit 1; }
    echo "$name: merge without tile 2 says: $(tr '\n' ' ' <"$out/gap.txt")"
    local again
    again=$(sbatch --parsable --array=2 "$out/render.sbatch")
    wait_jobs "${again%%;*}"
    "$PRISM" merge -o "$out/$name.exr" "$out"/tile-*.exr
    cmp "$out/one.exr" "$out/$name.exr"
    echo "$name: re-ran tile 2 alone (job $again); merged again, byte-identical"
}

check_scene snowman_pov2 "$ROOT/scenes/parity/snowman_pov2.toml" "--width 160 --height 90"
check_scene snowman_path "$ROOT/scenes/snowman_path.toml" "--width 96 --height 54 --samples 16"

END=$(date +%s.%N)
echo "slurm check: passed in $(awk "BEGIN {printf \"%.1f\", $END - $START}") s (wall, including installs and cluster start-up)"
