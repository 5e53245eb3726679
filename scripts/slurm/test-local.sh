#!/usr/bin/env bash
# Runs render-array.sbatch on a one-node Slurm cluster started on this machine, and checks that
# the merged image is byte for byte the image one `raygine render` writes.
#
# Installs Debian's slurm-wlm and munge when missing, starts munged, slurmctld and slurmd with
# their own key, socket, ports, configuration, state and logs in a temporary folder (nothing
# under /etc is touched), submits a 4-shard array and its merge job, waits (at most
# RAYGINE_SLURM_TIMEOUT seconds, default 300), compares, and stops the daemons it started.
# Needs root (apt-get, daemons); otherwise it says why and skips (fails under CI=true).
# The shards run the headless build (`--no-default-features`), as cluster nodes do.
# scripts/check.sh runs it.
set -euo pipefail
cd "$(dirname "$0")/../.."
root="$(pwd)"

skip() {
    if [ "${CI:-}" = true ]; then
        echo "test-local.sh: FAILED: cannot run under CI=true: $*" >&2
        exit 1
    fi
    echo "test-local.sh: skipped: $*"
    exit 0
}
fail() {
    echo "test-local.sh: FAILED: $*" >&2
    exit 1
}

[ "$(id -u)" = 0 ] || skip "not root (it installs slurm-wlm and munge and starts their daemons)"
command -v apt-get >/dev/null 2>&1 || skip "no apt-get (Debian's slurm-wlm and munge are needed)"

missing=""
for p in slurm-wlm munge; do
    dpkg -s "$p" >/dev/null 2>&1 || missing="$missing $p"
done
if [ -n "$missing" ]; then
    echo "test-local.sh: installing$missing"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq
    # shellcheck disable=SC2086
    apt-get install -y -qq --no-install-recommends $missing >/dev/null
fi

export CARGO_INCREMENTAL="${CARGO_INCREMENTAL:-0}"
export CARGO_PROFILE_DEV_DEBUG="${CARGO_PROFILE_DEV_DEBUG:-line-tables-only}"
export CARGO_TERM_COLOR="${CARGO_TERM_COLOR:-never}"
# The headless build, as on cluster nodes; its own target folder keeps the viewer's binary.
headless_target="${CARGO_TARGET_DIR:-$root/target}/headless"
cargo build -q -p raygine --bin raygine --no-default-features --target-dir "$headless_target"
raygine="$headless_target/debug/raygine"
[ -x "$raygine" ] || fail "no raygine binary at $raygine"

started=$SECONDS
tmp="$(mktemp -d /tmp/raygine-slurm.XXXXXX)"
chmod 755 "$tmp"
pids=()
cleanup() {
    local status=$?
    for pidfile in "$tmp/slurmd.pid" "$tmp/slurmctld.pid" "$tmp/munge/munged.pid"; do
        if [ -s "$pidfile" ]; then
            pid="$(cat "$pidfile")"
            kill "$pid" 2>/dev/null || true
            for _ in $(seq 50); do
                kill -0 "$pid" 2>/dev/null || break
                sleep 0.1
            done
        fi
    done
    if [ "$status" != 0 ]; then
        for log in slurmctld.log slurmd.log out/logs/shard-0.out out/logs/merge.out; do
            [ -f "$tmp/$log" ] && { echo "--- $log (last lines)"; tail -n 15 "$tmp/$log"; }
        done
    fi
    rm -rf "$tmp"
}
trap cleanup EXIT

# munge: a fresh key, its own socket (the folder must be world-executable, the key private).
mkdir -m 755 "$tmp/munge"
mkdir -m 700 "$tmp/key"
head -c 1024 /dev/urandom >"$tmp/key/munge.key"
chmod 400 "$tmp/key/munge.key"
socket="$tmp/munge/munge.socket"
munged --key-file="$tmp/key/munge.key" --socket="$socket" --pid-file="$tmp/munge/munged.pid" \
    --log-file="$tmp/munge/munged.log" --seed-file="$tmp/munge/munged.seed" ||
    fail "munged did not start (see $tmp/munge/munged.log)"
munge -n -S "$socket" | unmunge -S "$socket" >/dev/null || fail "munge cannot decode its own credential"

# Two free TCP ports for slurmctld and slurmd.
port_free() { ! (exec 3<>"/dev/tcp/127.0.0.1/$1") 2>/dev/null; }
ports=()
for p in $(seq 16817 16917); do
    port_free "$p" && ports+=("$p")
    [ "${#ports[@]}" = 2 ] && break
done
[ "${#ports[@]}" = 2 ] || fail "no free TCP ports between 16817 and 16917"

host="$(hostname -s)"
mem_mib=$(($(awk '/MemTotal/ {print $2}' /proc/meminfo) / 1024 * 9 / 10))
mkdir -p "$tmp/spool" "$tmp/state"
export SLURM_CONF="$tmp/slurm.conf"
cat >"$SLURM_CONF" <<CONF
ClusterName=raygine-test
SlurmctldHost=$host
SlurmctldPort=${ports[0]}
SlurmdPort=${ports[1]}
AuthType=auth/munge
AuthInfo=socket=$socket
CredType=cred/munge
SlurmUser=root
SlurmdUser=root
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=none
ReturnToService=2
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SlurmctldPidFile=$tmp/slurmctld.pid
SlurmdPidFile=$tmp/slurmd.pid
SlurmdSpoolDir=$tmp/spool
StateSaveLocation=$tmp/state
SlurmctldLogFile=$tmp/slurmctld.log
SlurmdLogFile=$tmp/slurmd.log
NodeName=$host CPUs=$(nproc) RealMemory=$mem_mib State=UNKNOWN
PartitionName=debug Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF

slurmctld -f "$SLURM_CONF" || fail "slurmctld did not start"
slurmd -f "$SLURM_CONF" || fail "slurmd did not start"
for _ in $(seq 100); do
    state="$(sinfo -h -n "$host" -o %t 2>/dev/null || true)"
    [ "$state" = idle ] && break
    sleep 0.2
done
[ "$state" = idle ] || fail "the node did not come up (sinfo says '${state:-nothing}')"
echo "test-local.sh: one-node cluster up on $host (ports ${ports[*]}) in $((SECONDS - started)) s"

# The render: small and quick, global illumination, 4 shards of 8 samples.
render=(--gi path --samples 8 -W 96 -H 64)
submitted=$SECONDS
out="$(RAYGINE="$raygine" scripts/slurm/render-array.sbatch submit "$tmp/out" 4 "${render[@]}" -- --tone-map reinhard)"
echo "$out"
merge_id="$(echo "$out" | sed -n 's/.*merge \([0-9]*\).*/\1/p' | head -n 1)"
[ -n "$merge_id" ] || fail "could not read the merge job's id from: $out"

timeout="${RAYGINE_SLURM_TIMEOUT:-300}"
while true; do
    job_state="$(scontrol show job "$merge_id" 2>/dev/null | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p')"
    case "$job_state" in
    COMPLETED) break ;;
    FAILED | CANCELLED | TIMEOUT | NODE_FAIL | OUT_OF_MEMORY | "")
        squeue || true
        fail "the merge job $merge_id ended as '${job_state:-unknown}'"
        ;;
    esac
    if [ $((SECONDS - submitted)) -ge "$timeout" ]; then
        squeue || true
        fail "timed out after $timeout s waiting for the Slurm jobs (merge job $merge_id is $job_state; RAYGINE_SLURM_TIMEOUT sets the limit)"
    fi
    sleep 1
done
echo "test-local.sh: 4 shards and the merge ran in $((SECONDS - submitted)) s"

"$raygine" render "${render[@]}" --tone-map reinhard -R "$tmp/single.png" --exr "$tmp/single.exr" >/dev/null
cmp "$tmp/out/image.png" "$tmp/single.png" || fail "the merged PNG differs from a single render's"
cmp "$tmp/out/image.exr" "$tmp/single.exr" || fail "the merged EXR differs from a single render's"
echo "test-local.sh: the merged PNG and EXR equal a single render's, byte for byte ($((SECONDS - started)) s in all)"
