#!/usr/bin/env bash
# tools/examples/batch_slurm.sbatch as a real Slurm array job (docs/batch.md, issue 23): starts a
# private single-node Slurm in a temp dir — munged with a fresh key on its own socket, slurmctld
# and slurmd on random localhost ports, proctrack/linuxproc, task/none, no cgroups, no
# accounting — submits the array over three short simulated recordings from the repository root
# as docs/batch.md says, and the `imunoise fleet` step as a job depending on it (afterany); then
# removes one unit and resubmits both: only that unit is redone and fleet runs again. The
# daemons are always stopped (trap; each also runs under `timeout 100`: none survives even a
# SIGKILLed test for long).
#   slurm_array_test.sh IMUNOISE_BINARY SOURCE_DIR
# Exit: 0 pass, 1 fail, 77 skipped (Slurm or munge not installed, or the daemons cannot start
# here: the SKIPPED line quotes their error lines).
set -uo pipefail
BIN="$1"
SRC="$2"
LIFETIME=100 # s, hard limit of every daemon: the test takes ~10 s, ~60 at most; ctest TIMEOUT 150
skip() {
  echo "SKIPPED: $*"
  exit 77
}
for c in slurmctld slurmd sbatch squeue scontrol sinfo scancel munged; do
  command -v "$c" >/dev/null || skip "$c is not installed (tools/install-deps installs slurm-wlm)"
done
# An enclosing Slurm job's variables would steer sbatch and the job (SLURM_JOB_ID, SBATCH_*…).
while read -r v; do unset "$v"; done < <(compgen -e | grep -E '^(SLURM|SBATCH|SALLOC|SRUN)_')
unset IMUNOISE_EXAMPLES_DIR
export IMUNOISE="$BIN"

WORK="$(mktemp -d "${TMPDIR:-/tmp}/imunoise-slurm.XXXXXX")"
chmod 700 "$WORK"
export SLURM_CONF="$WORK/etc/slurm.conf"
PIDS=() # the `timeout` wrappers of munged, slurmctld, slurmd
JOBS=()
all_alive() { # (kill -0 A B… succeeds when any one is alive)
  local p
  for p in "${PIDS[@]}"; do kill -0 "$p" 2>/dev/null || return 1; done
}
stop_daemons() {
  [ ${#PIDS[@]} -gt 0 ] || return 0
  if [ ${#JOBS[@]} -gt 0 ] && all_alive; then
    scancel "${JOBS[@]}" 2>/dev/null
    local until=$((SECONDS + 10))
    while [ $SECONDS -lt $until ] && [ -n "$(squeue -h -o %i 2>/dev/null)" ]; do sleep 0.5; done
    # Steps slurmd could not end: their processes, listed by slurmd itself.
    scontrol listpids 2>/dev/null | awk 'NR > 1 && $1 ~ /^[0-9]+$/ {print $1}' |
      while read -r p; do kill -KILL "$p" 2>/dev/null; done
  fi
  scontrol shutdown >/dev/null 2>&1
  local until=$((SECONDS + 10)) p
  while [ $SECONDS -lt $until ]; do
    local any=0
    for p in "${PIDS[@]:1}"; do kill -0 "$p" 2>/dev/null && any=1; done
    [ $any -eq 0 ] && break
    sleep 0.2
  done
  for p in "${PIDS[@]}"; do kill -TERM "$p" 2>/dev/null; done # timeout passes it on
  sleep 0.5
  for p in "${PIDS[@]}"; do kill -KILL "$p" 2>/dev/null; done
  wait 2>/dev/null
  PIDS=()
}
trap 'stop_daemons; rm -rf "$WORK"' EXIT
trap 'exit 1' INT TERM HUP

# --- the recordings (as tests/examples/batch_examples_test.sh) ---
mkdir -p "$WORK/recs" "$WORK/log" "$WORK/etc" "$WORK/state" "$WORK/spool/localhost" "$WORK/munge"
for i in 1 2 3; do
  "$BIN" simulate "$SRC/configs/reference-imu.yaml" --duration 5min --rate 50 --seed "$i" -q \
    -o "$WORK/recs/unit$i.csv" >/dev/null || { echo "FAIL: simulate"; exit 1; }
done

# --- the cluster ---
port_free() { ! (exec 3<>"/dev/tcp/127.0.0.1/$1") 2>/dev/null; }
user="$(id -un)"
cpus="$(nproc)"
start_cluster() { # writes slurm.conf with two free ports, starts the daemons; 0 when idle
  local port
  while :; do
    port=$((20000 + RANDOM % 40000))
    port_free "$port" && port_free $((port + 1)) && break
  done
  cat >"$SLURM_CONF" <<EOF
# A private single-node cluster for tests/examples/slurm_array_test.sh
ClusterName=imunoisetest
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=$user
SlurmdUser=$user
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$WORK/munge/socket
StateSaveLocation=$WORK/state
SlurmdSpoolDir=$WORK/spool/%n
SlurmctldPidFile=$WORK/slurmctld.pid
SlurmdPidFile=$WORK/slurmd.pid
SlurmctldLogFile=$WORK/log/slurmctld.log
SlurmdLogFile=$WORK/log/slurmd.log
SlurmdParameters=config_overrides
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SwitchType=switch/none
MpiDefault=none
MailProg=/bin/true
SchedulerType=sched/builtin
SchedulerParameters=sched_interval=1,batch_sched_delay=0 # start jobs within ~1 s
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
SlurmctldTimeout=10
SlurmdTimeout=10
InactiveLimit=0
MinJobAge=300
KillWait=5
NodeName=localhost NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=1000 State=UNKNOWN
PartitionName=test Nodes=localhost Default=YES MaxTime=INFINITE State=UP
EOF
  rm -f "$WORK"/log/*.log
  # Foreground daemons (children of this shell), stdin/stdout/stderr off the test's pipes.
  timeout -k 5 "$LIFETIME" munged -F --force --socket="$WORK/munge/socket" \
    --key-file="$WORK/munge/key" --pid-file="$WORK/munge/pid" --seed-file="$WORK/munge/seed" \
    --log-file="$WORK/log/munged.log" </dev/null >"$WORK/log/munged.out" 2>&1 &
  PIDS+=($!)
  local until=$((SECONDS + 5))
  while [ ! -S "$WORK/munge/socket" ] && [ $SECONDS -lt $until ]; do sleep 0.1; done
  timeout -k 5 "$LIFETIME" slurmctld -D -f "$SLURM_CONF" \
    </dev/null >"$WORK/log/slurmctld.out" 2>&1 &
  PIDS+=($!)
  timeout -k 5 "$LIFETIME" slurmd -D -f "$SLURM_CONF" -N localhost \
    </dev/null >"$WORK/log/slurmd.out" 2>&1 &
  PIDS+=($!)
  until=$((SECONDS + 20))
  while [ $SECONDS -lt $until ] && all_alive; do
    [ "$(sinfo -h -N -n localhost -o %T 2>/dev/null)" = idle ] && return 0
    sleep 0.5
  done
  return 1
}
dd if=/dev/urandom of="$WORK/munge/key" bs=1024 count=1 2>/dev/null
chmod 600 "$WORK/munge/key"
t0=$SECONDS
started=0
for _ in 1 2 3; do
  if start_cluster; then
    started=1
    break
  fi
  stop_daemons
  # Another program took a port between the check and the bind: try other ports.
  grep -qs 'Address already in use' "$WORK"/log/slurm*.log "$WORK"/log/slurm*.out || break
done
benign='pmix|MPI:|state file|NOTE: Trying backup' # see docs/batch.md
if [ $started -eq 0 ]; then
  why="$(grep -h -i -E 'fatal|error' "$WORK"/log/*.log "$WORK"/log/*.out 2>/dev/null |
    grep -v -E "$benign" | tail -n 6)"
  skip "a single-node Slurm (munged, slurmctld, slurmd) did not start here within 20 s:" \
    "${why:-no error logged}"
fi
echo "ok: single-node Slurm $(sinfo -V | cut -d' ' -f2) up in $((SECONDS - t0)) s" \
  "($cpus CPUs, munge)"

# --- the array job, as docs/batch.md submits it ---
FAILURES=0
fail() {
  echo "FAIL: $*"
  FAILURES=$((FAILURES + 1))
}
ok() { echo "ok: $*"; }
out="$WORK/out"
log="$WORK/log"
submit() { # the array over the 3 recordings, then fleet after it; sets JID and FJID
  # 1 CPU and 200 MB per task (the script asks 2 CPUs and 4 GB): 2 tasks at once on 2 cores.
  if ! JID="$(cd "$SRC" && sbatch --parsable --array=0-2 --cpus-per-task=1 --mem=200M \
    --output="$log/%A_%a.out" tools/examples/batch_slurm.sbatch "$WORK/recs" "$out" \
    --bootstrap 0 2>"$log/sbatch.err")"; then
    fail "sbatch: $(cat "$log/sbatch.err")"
    return 1
  fi
  JOBS+=("$JID")
  if ! FJID="$(sbatch --parsable --dependency="afterany:$JID" --mem=200M \
    --output="$log/fleet_%j.out" --wrap "\"$BIN\" fleet \"$out\"/*/model.yaml -o \"$out/fleet\"" \
    2>"$log/sbatch.err")"; then
    fail "sbatch fleet: $(cat "$log/sbatch.err")"
    return 1
  fi
  JOBS+=("$FJID")
}
wait_jobs() { # JOBID... : 0 when none is pending or running any more, 1 after 40 s
  local until=$((SECONDS + 40)) ids
  ids="$(IFS=,; echo "$*")"
  while [ $SECONDS -lt $until ]; do
    [ -z "$(squeue -h -j "$ids" -o %i 2>/dev/null)" ] && return 0
    sleep 0.5
  done
  return 1
}
states() { # JobState=… ExitCode=… of each element of job $1
  scontrol -o show job "$1" 2>/dev/null | grep -o -E '(JobState|ExitCode)=[^ ]+' | paste -sd' '
}
fleet_units() {
  tail -n +2 "$out/fleet/fleet.csv" 2>/dev/null | cut -d, -f1 | sort -u | paste -sd' '
}
DONE0="JobState=COMPLETED ExitCode=0:0"
check_fleet() { # $1: what this fleet run is
  if [ "$(states "$FJID")" = "$DONE0" ] && [ "$(fleet_units)" = "unit1 unit2 unit3" ] &&
    [ -s "$out/fleet/fleet.html" ]; then
    ok "$1: fleet.csv holds unit1 unit2 unit3"
  else
    fail "$1 (job $FJID): $(states "$FJID"); units '$(fleet_units)'; $(cat "$log/fleet_$FJID.out")"
  fi
}

t1=$SECONDS
if submit; then
  wait_jobs "$JID" "$FJID" || fail "the jobs did not finish within 40 s: $(squeue -h 2>&1)"
  s="$(states "$JID")"
  if [ "$(grep -o "$DONE0" <<<"$s" | wc -l)" -eq 3 ]; then
    ok "array job $JID: 3 tasks COMPLETED, exit 0, in $((SECONDS - t1)) s"
  else
    fail "array job $JID: $s"
  fi
  for i in 0 1 2; do
    u=$((i + 1))
    grep -qx "done unit$u" "$log/${JID}_$i.out" 2>/dev/null && [ -s "$out/unit$u/model.yaml" ] &&
      [ -s "$out/unit$u/report.html" ] || fail "task $i: $(cat "$log/${JID}_$i.out" 2>&1)"
  done
  check_fleet "the fleet job after the array"
fi

# --- resubmitted after a lost unit: only that unit is redone, fleet runs again ---
if [ $FAILURES -eq 0 ]; then
  rm -rf "$out/unit2"
  before="$(stat -c %Y "$out/unit1/model.yaml")"
  t1=$SECONDS
  if submit; then
    wait_jobs "$JID" "$FJID" || fail "the resubmitted jobs did not finish within 40 s"
    if grep -qx 'skip unit1: .*' "$log/${JID}_0.out" && grep -qx 'done unit2' "$log/${JID}_1.out" &&
      grep -qx 'skip unit3: .*' "$log/${JID}_2.out" &&
      [ "$(stat -c %Y "$out/unit1/model.yaml")" = "$before" ]; then
      ok "resubmitted array $JID redoes only unit2 ($((SECONDS - t1)) s)"
    else
      fail "resubmission: $(cat "$log/${JID}"_*.out 2>&1)"
    fi
    check_fleet "the second fleet job (out/fleet/ present, not taken for a unit)"
  fi
fi

if [ $FAILURES -gt 0 ]; then
  echo "--- slurmctld.log / slurmd.log (errors) ---"
  grep -h -i -E 'error|fatal' "$log"/slurm*.log | grep -v -E "$benign" | tail -n 20
fi
daemons=("${PIDS[@]}")
stop_daemons
for p in "${daemons[@]}"; do
  kill -0 "$p" 2>/dev/null && fail "a daemon (timeout pid $p) survived the shutdown"
done
[ "$FAILURES" -eq 0 ] && { echo "PASSED ($SECONDS s)"; exit 0; }
echo "$FAILURES check(s) failed"
exit 1
