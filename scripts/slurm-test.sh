#!/usr/bin/env bash
# A real Slurm on localhost: runs a small study through `asperity slurm --submit` (a job array of
# shards on a shared cache, then a collect job with --dependency=afterok) and checks that the
# tables equal those of a single-process run.
#
# Installs Debian's slurm-wlm and munge when missing (root or sudo), starts munged, slurmctld and
# slurmd with a minimal configuration under a temporary folder (own ports and munge socket: it
# does not touch a system Slurm), and stops every daemon it started on exit.
# When CI is set, any failure to install or start Slurm is an error; otherwise it is reported
# and the script exits 0 (nothing tested).
#
# Usage: scripts/slurm-test.sh            (from the repository root; ~1 min after the build)
# Env:   SLURM_TEST_TIMEOUT (seconds to wait for the jobs, default 300), KEEP=1 keeps the folder.
set -euo pipefail
cd "$(dirname "$0")/.."

TIMEOUT=${SLURM_TEST_TIMEOUT:-300}
WORK=$(mktemp -d /tmp/asperity-slurm.XXXXXX)
PIDS=()

log() { echo "slurm-test: $*" >&2; }

cleanup() {
    local rc=$?
    for pid in "${PIDS[@]}"; do
        kill "$pid" 2>/dev/null || true
    done
    for pid in "${PIDS[@]}"; do
        wait "$pid" 2>/dev/null || true
    done
    if [[ $rc -ne 0 ]]; then
        for f in "$WORK"/*.log "$WORK"/jobs/logs/*; do
            [[ -f $f ]] && { echo "---- $f" >&2; tail -n 30 "$f" >&2; }
        done
    fi
    if [[ ${KEEP:-0} == 1 ]]; then log "kept $WORK"; else rm -rf "$WORK"; fi
    exit "$rc"
}
trap cleanup EXIT

# Slurm cannot be set up: an error under CI, a loud notice otherwise.
unavailable() {
    if [[ -n ${CI:-} ]]; then
        log "FAILED: $* (CI is set: Slurm must work here)"
        exit 1
    fi
    log "NOT RUN: $* (set CI=1 to make this an error)"
    exit 0
}

if ! command -v slurmctld >/dev/null || ! command -v munged >/dev/null; then
    SUDO=""
    [[ $(id -u) -ne 0 ]] && SUDO="sudo -n"
    log "installing slurm-wlm and munge"
    $SUDO apt-get update -qq >"$WORK/apt.log" 2>&1 &&
        DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends \
            slurm-wlm munge >>"$WORK/apt.log" 2>&1 ||
        unavailable "cannot install slurm-wlm and munge (see $WORK/apt.log)"
fi
export PATH="$PATH:/usr/sbin:/sbin"

log "building asperity"
cargo test --no-run --quiet  # the binary `cargo test` built: same features, no rebuild
# A private copy: a concurrent build cannot replace the binary under the running jobs.
cp "${CARGO_TARGET_DIR:-target}/debug/asperity" "$WORK/asperity"
BIN="$WORK/asperity"

# munge, on a private socket.
dd if=/dev/urandom of="$WORK/munge.key" bs=1024 count=1 status=none
chmod 400 "$WORK/munge.key"
chmod 700 "$WORK"
munged --foreground --force --key-file="$WORK/munge.key" --socket="$WORK/munge.sock" \
    --pid-file="$WORK/munged.pid" --log-file="$WORK/munged.log" --seed-file="$WORK/munge.seed" >"$WORK/munged.out" 2>&1 &
PIDS+=($!)

HOST=$(hostname -s)
CPUS=$(nproc)
PORT=$((20000 + RANDOM % 20000))
mkdir -p "$WORK/state" "$WORK/spool"
cat >"$WORK/slurm.conf" <<EOF
ClusterName=asperity-test
SlurmctldHost=$HOST(127.0.0.1)
SlurmctldPort=$PORT
SlurmdPort=$((PORT + 1))
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$WORK/munge.sock
SlurmUser=$(id -un)
StateSaveLocation=$WORK/state
SlurmdSpoolDir=$WORK/spool
SlurmctldPidFile=$WORK/slurmctld.pid
SlurmdPidFile=$WORK/slurmd.pid
SlurmctldLogFile=$WORK/slurmctld.log
SlurmdLogFile=$WORK/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MaxArraySize=1001
NodeName=$HOST NodeAddr=127.0.0.1 CPUs=$CPUS State=UNKNOWN
PartitionName=debug Nodes=$HOST Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF="$WORK/slurm.conf"

for _ in $(seq 50); do [[ -S $WORK/munge.sock ]] && break; sleep 0.1; done
[[ -S $WORK/munge.sock ]] || unavailable "munged did not start"

slurmctld -D -i -f "$SLURM_CONF" >"$WORK/slurmctld.out" 2>&1 &
PIDS+=($!)
slurmd -D -N "$HOST" -f "$SLURM_CONF" >"$WORK/slurmd.out" 2>&1 &
PIDS+=($!)

log "waiting for the node to become idle"
state=""
for _ in $(seq 60); do
    state=$(sinfo -h -N -o %T 2>/dev/null | head -n1 || true)
    [[ $state == idle* ]] && break
    sleep 1
done
[[ $state == idle* ]] || unavailable "slurmctld/slurmd did not start (node state '${state:-none}')"

# A small study: 6 contacts of 64² synthetic surfaces.
cat >"$WORK/study.yaml" <<'EOF'
study: slurm-test
parameters:
  product:
    seed: {range: [1, 6]}
nodes:
  lower:
    surface:
      synthetic: {grid: [64, 64], size: [0.25 mm, 0.25 mm], sq: 1 um, hurst: 0.8,
                  correlation_length: 40 um, seed: "${seed}"}
  upper:
    surface:
      synthetic: {grid: [64, 64], size: [0.25 mm, 0.25 mm], sq: 0.5 um, hurst: 0.7,
                  correlation_length: 40 um, seed: 1000}
  pair:
    contact:
      lower: lower
      upper: upper
      lower_material: {youngs_modulus: 210 GPa, poisson_ratio: 0.3}
      upper_material: {youngs_modulus: 210 GPa, poisson_ratio: 0.3}
      flow_pressure: 4 GPa
      nominal_pressures: [5 MPa, 20 MPa]
EOF

log "submitting"
submitted=$("$BIN" slurm "$WORK/study.yaml" --cache "$WORK/cache" --out "$WORK/out-slurm" \
    --dir "$WORK/jobs" --array-size 3 --throttle 2 --time 00:10:00 --submit)
echo "$submitted"
fail() { log "FAILED: $*"; exit 1; }
ids=$(sed -n 's/^submitted array job \([0-9]*\) and collect job \([0-9]*\)$/\1 \2/p' <<<"$submitted")
read -r array_id collect_id <<<"$ids" || true
[[ -n ${array_id:-} && -n ${collect_id:-} ]] || fail "no job ids in the output"
grep -q -- "--array=0-2%2" "$WORK/jobs/shards.sbatch" || fail "array line missing in shards.sbatch"

log "waiting for jobs $array_id (array) and $collect_id (collect), at most ${TIMEOUT} s"
deadline=$((SECONDS + TIMEOUT))
while [[ -n $(squeue -h -j "$array_id,$collect_id" 2>/dev/null) ]]; do
    if ((SECONDS > deadline)); then
        squeue >&2 || true
        scancel "$array_id" "$collect_id" 2>/dev/null || true
        log "FAILED: jobs still queued after ${TIMEOUT} s"
        exit 1
    fi
    sleep 1
done

shopt -s nullglob
shard_logs=("$WORK"/jobs/logs/shard-*.out)
collect_logs=("$WORK"/jobs/logs/collect-*.out)
((${#shard_logs[@]} == 3)) || fail "expected 3 shard logs, found ${#shard_logs[@]}"
((${#collect_logs[@]} == 1)) || fail "the collect job did not run (a shard failed?)"
grep -q "no tables written" "${shard_logs[@]}" || fail "shard logs lack their summary"
grep -q "slurm-test: 0 computed, 13 reused from cache" "${collect_logs[0]}" ||
    fail "the collect job recomputed nodes: $(cat "${collect_logs[0]}")"

log "single-process reference run"
"$BIN" run "$WORK/study.yaml" --cache "$WORK/cache-single" --out "$WORK/out-single" --quiet >/dev/null
ASPERITY_TABLES_A="$WORK/out-slurm" ASPERITY_TABLES_B="$WORK/out-single" \
    cargo test --quiet --test engine -- --ignored --exact table_equality::same_tables_in_two_folders
log "OK: Slurm job array + collect job gave the single-process tables"
