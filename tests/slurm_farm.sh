#!/bin/bash
# A single-node Slurm cluster on localhost (Debian slurm-wlm), started and stopped here, runs
# scripts/slurm/render_sequence.sbatch as a 4-task job array; the frames must equal one local render of
# the whole range, byte for byte. Exit 77 (skipped) with a message where Slurm is not installed or
# does not start. Usage: slurm_farm.sh BRUME_EXE SOURCE_DIR
set -uo pipefail
brume=$1 src=$2
skip() { echo "SKIPPED: $*"; exit 77; }
for tool in slurmctld slurmd sbatch sinfo scontrol; do
  command -v "$tool" >/dev/null || PATH=$PATH:/usr/sbin command -v "$tool" >/dev/null || skip "$tool not found (apt-get install slurm-wlm)"
done
export PATH=$PATH:/usr/sbin
work=$(mktemp -d /tmp/brume_slurm_XXXXXX)
pids=()
cleanup() {
  for p in "${pids[@]}"; do kill "$p" 2>/dev/null; done
  for p in "${pids[@]}"; do wait "$p" 2>/dev/null; done
  rm -rf "$work"
}
trap cleanup EXIT
user=$(id -un)
host=$(hostname -s)
# Ports from the process id, so test runs of other build folders on this machine do not collide.
base=$(( 20000 + ($$ % 2000) * 2 ))
cpus=$(nproc)
mkdir -p "$work"/{state,spool,frames,whole,logs}
cat >"$work/slurm.conf" <<CONF
ClusterName=brumetest
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$base
SlurmdPort=$(( base + 1 ))
SlurmUser=$user
SlurmdUser=$user
AuthType=auth/none
CredType=cred/none
MpiDefault=none
ProctrackType=proctrack/pgid
TaskPlugin=task/none
SwitchType=switch/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/logs/slurmctld.log
SlurmdLogFile=$work/logs/slurmd.log
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
JobAcctGatherType=jobacct_gather/none
SchedulerType=sched/builtin
InactiveLimit=0
KillWait=5
MinJobAge=60
NodeName=brumenode NodeHostname=$host NodeAddr=127.0.0.1 CPUs=$cpus State=UNKNOWN
PartitionName=brume Nodes=brumenode Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$work/slurm.conf
slurmctld -D -i >"$work/logs/ctld.out" 2>&1 & pids+=($!)
slurmd -D -N brumenode >"$work/logs/d.out" 2>&1 & pids+=($!)
started=0
for _ in $(seq 1 100); do
  if [[ "$(sinfo -h -n brumenode -o %T 2>/dev/null)" == idle* ]]; then started=1; break; fi
  sleep 0.2
done
if (( ! started )); then
  tail -n 5 "$work"/logs/*.log "$work"/logs/*.out 2>/dev/null
  skip "slurmctld/slurmd did not start within 20 s (the logs are above)"
fi
echo "slurm up after $SECONDS s"

cat >"$work/scene.json" <<'SCENE'
{"brume_scene": 1,
 "camera": {"position": [0, 1, 4], "target": [0, 1, 0]},
 "render": {"width": 32, "height": 20, "quality": "low"},
 "temporal": {"enabled": true, "history_weight": 0.5},
 "volumes": [{"type": "box", "transform": {"translation": [0, 1, 0], "scale": [3, 2, 3]},
              "keys": {"medium.scattering": [{"time": 0, "value": [0.1, 0.1, 0.1]}, {"time": 0.5, "value": [0.6, 0.4, 0.2]}]}}],
 "lights": [{"type": "point", "position": [0.5, 2, 0.5], "intensity": 30}]}
SCENE
cd "$work" || exit 1
BRUME=$brume sbatch --wait --array=0-3 --cpus-per-task=1 --output="$work/logs/task-%a.out" \
  "$src/scripts/slurm/render_sequence.sbatch" "$work/scene.json" 0 11 "$work/frames/f_####.exr" --cpu
rc=$?
cat "$work"/logs/task-*.out
if (( rc != 0 )); then echo "FAILED: the job array exited $rc"; tail -n 20 "$work"/logs/*.log; exit 1; fi
"$brume" render "$work/scene.json" --cpu --sequence 0-11 -o "$work/whole/f_####.exr" >/dev/null || { echo "FAILED: local render"; exit 1; }
fail=0
for f in $(seq -f %04g 0 11); do
  if ! cmp -s "$work/frames/f_$f.exr" "$work/whole/f_$f.exr"; then echo "FAILED: frame $f from the farm differs from the local render (or is missing)"; fail=1; fi
done
(( fail )) && exit 1
echo "PASSED: 4 array tasks rendered frames 0-11, equal to one local render ($SECONDS s)"
