#!/usr/bin/env bash
# CI test of deploy/slurm/cache_build.sbatch on a real Slurm: brings up a single-node
# cluster on localhost (munged, slurmctld, slurmd from Debian's slurm-wlm and munge, all in
# a private folder with their own ports and munge socket, nothing of the machine's touched),
# submits the array job over 9 presets in 4 shards, waits for it, and compares the shared
# cache with a serial `forest cache build` of the same presets, byte for byte.
# Usage: slurm_cache_test.sh FOREST SOURCE_DIR. Needs root (slurmd and munged run as root
# here) or password-less sudo; exit 77 (ctest: skipped) without either or without Slurm.
set -euo pipefail
forest=$1
src=$2
for tool in munged slurmctld slurmd sbatch sinfo; do
  command -v "$tool" >/dev/null || { echo "slurm_cache_test: $tool missing (scripts/install-deps.sh --test installs it)"; exit 77; }
done
as_root=""
if [[ $(id -u) -ne 0 ]]; then
  sudo -n true 2>/dev/null || { echo "slurm_cache_test: needs root or password-less sudo"; exit 77; }
  as_root="sudo -n --preserve-env=SLURM_CONF"
fi

tmp=$(mktemp -d /tmp/forest-slurm.XXXXXX)
chmod 755 "$tmp"
cleanup() {
  for pid_file in "$tmp"/slurmd.pid "$tmp"/slurmctld.pid "$tmp"/munged.pid; do
    [[ -f "$pid_file" ]] && $as_root kill "$(cat "$pid_file")" 2>/dev/null || true
  done
  sleep 1
  $as_root rm -rf "$tmp"
}
trap cleanup EXIT
fail() {
  echo "slurm_cache_test: $*"
  for log in "$tmp"/*.log; do [[ -f "$log" ]] && { echo "--- $log"; tail -20 "$log"; }; done
  exit 1
}

# Ports no other test or daemon on the machine uses: derived from this process.
base=$(( 20000 + ($$ % 20000) ))
presets=(conifer visual_hull_cone magnetic_3d silhouettes_round larix_decidua broadleaf plantons_broadleaf fig2_1 mig_j)
args=()
for p in "${presets[@]}"; do args+=("$src/scenes/species/$p.toml"); done
args+=(--views 1 --resolution 32 --no-impostor)

# munge: a private key and socket.
mkdir -p "$tmp/munge"
dd if=/dev/urandom of="$tmp/munge/munge.key" bs=1024 count=1 status=none
chmod 700 "$tmp/munge"
chmod 400 "$tmp/munge/munge.key"
$as_root chown -R root:root "$tmp/munge"
$as_root munged --force --socket="$tmp/munge/munge.sock" --key-file="$tmp/munge/munge.key" \
  --pid-file="$tmp/munged.pid" --log-file="$tmp/munged.log" --seed-file="$tmp/munge/seed" || fail "munged did not start"

# Slurm: one node, localhost, the node's real size (slurmd -C).
node=$(slurmd -C | head -1 | sed 's/^NodeName=[^ ]*/NodeName=localhost/; s/ UpTime=.*//')
mkdir -p "$tmp/state" "$tmp/spool"
cat > "$tmp/slurm.conf" <<CONF
ClusterName=forestci
SlurmctldHost=localhost
SlurmctldPort=$base
SlurmdPort=$(( base + 1 ))
AuthType=auth/munge
AuthInfo=socket=$tmp/munge/munge.sock
CredType=cred/munge
SlurmUser=root
SlurmdUser=root
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MpiDefault=none
StateSaveLocation=$tmp/state
SlurmdSpoolDir=$tmp/spool
SlurmctldPidFile=$tmp/slurmctld.pid
SlurmdPidFile=$tmp/slurmd.pid
SlurmctldLogFile=$tmp/slurmctld.log
SlurmdLogFile=$tmp/slurmd.log
$node State=UNKNOWN
PartitionName=ci Nodes=localhost Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$tmp/slurm.conf
$as_root slurmctld -f "$SLURM_CONF" || fail "slurmctld did not start"
$as_root slurmd -f "$SLURM_CONF" || fail "slurmd did not start"
for _ in $(seq 60); do
  state=$(sinfo -h -N -o %t 2>/dev/null || true)
  [[ "$state" == idle* ]] && break
  sleep 1
done
[[ "$state" == idle* ]] || fail "the node did not come up (state '$state')"

# The serial reference, then the array job into the shared folder.
"$forest" cache build "${args[@]}" --cache "$tmp/serial" >"$tmp/serial.out" || fail "serial build failed"
start=$(date +%s)
$as_root env SLURM_CONF="$SLURM_CONF" FOREST="$forest" FOREST_CACHE="$tmp/shared" \
  VK_DRIVER_FILES="${VK_DRIVER_FILES:-}" LP_NUM_THREADS=1 \
  sbatch --wait --array=0-3 --cpus-per-task=1 --chdir="$tmp" --output="$tmp/task-%a.log" \
  "$src/deploy/slurm/cache_build.sbatch" "${args[@]}" >"$tmp/sbatch.out" || fail "the array job failed"
echo "slurm_cache_test: array job of 4 shards done in $(( $(date +%s) - start )) s"
for k in 0 1 2 3; do
  grep -q "shard $k/4" "$tmp/task-$k.log" || fail "task $k did not run shard $k/4"
done
# Together the shards made every entry, each once, byte-identical to the serial run.
$as_root chown -R "$(id -u):$(id -g)" "$tmp/shared"
diff -r "$tmp/serial" "$tmp/shared" || fail "the shared cache differs from the serial one"
n=$(ls "$tmp/shared" | wc -l)
[[ $n -eq $(( 2 * ${#presets[@]} )) ]] || fail "$n files in the shared cache, expected $(( 2 * ${#presets[@]} ))"
grep -h "cache build:" "$tmp"/task-*.log
echo "slurm_cache_test: ${#presets[@]} presets in 4 shards, shared cache identical to the serial one"
