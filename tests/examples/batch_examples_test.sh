#!/usr/bin/env bash
# Test of the batch examples (docs/batch.md, issue 23): three short simulated recordings
# analysed by tools/examples/batch_parallel.sh under GNU parallel into one directory per unit,
# fed to `imunoise fleet`; a second run skips every complete unit; a unit removed and a stale
# .partial left by a killed run are redone alone. Then tools/examples/batch_slurm.sbatch run the
# way Slurm runs an array job — once per SLURM_ARRAY_TASK_ID, by hand (under a real Slurm:
# tests/examples/slurm_array_test.sh) — gives the same three units.
#   batch_examples_test.sh IMUNOISE_BINARY SOURCE_DIR
# Exit: 0 pass, 1 fail, 77 skipped (GNU parallel not installed).
set -uo pipefail
BIN="$1"
SRC="$2"
command -v parallel >/dev/null || { echo "SKIPPED: GNU parallel is not installed (tools/install-deps installs it)"; exit 77; }
WORK="$(mktemp -d "${TMPDIR:-/tmp}/imunoise-batch.XXXXXX")"
trap 'rm -rf "$WORK"' EXIT
FAILURES=0
fail() { echo "FAIL: $*"; FAILURES=$((FAILURES + 1)); }
ok() { echo "ok: $*"; }
export IMUNOISE="$BIN"
mkdir -p "$WORK/recs"
for i in 1 2 3; do
  "$BIN" simulate "$SRC/configs/reference-imu.yaml" --duration 5min --rate 50 --seed "$i" -q \
    -o "$WORK/recs/unit$i.csv" >/dev/null || { echo "FAIL: simulate"; exit 1; }
done
EX="$SRC/tools/examples"

out="$WORK/out"
log="$("$EX/batch_parallel.sh" "$WORK/recs" "$out" -j 2 -- --bootstrap 0 2>&1)" || fail "batch_parallel.sh failed: $log"
for i in 1 2 3; do
  [ -s "$out/unit$i/model.yaml" ] && [ -s "$out/unit$i/report.html" ] || fail "unit$i not analysed"
done
[ "$(grep -c '^done unit' <<<"$log")" -eq 3 ] && ok "GNU parallel analysed 3 units" || fail "expected 3 'done' lines: $log"
[ "$(tail -n +2 "$out/fleet/fleet.csv" | cut -d, -f1 | sort -u | tr '\n' ' ')" = "unit1 unit2 unit3 " ] &&
  ok "fleet.csv holds the 3 units" || fail "fleet.csv units: $(tail -n +2 "$out/fleet/fleet.csv" | cut -d, -f1 | sort -u)"
[ -s "$out/fleet/fleet.html" ] || fail "no fleet.html"

before="$(stat -c %Y "$out/unit1/model.yaml")"
log="$("$EX/batch_parallel.sh" "$WORK/recs" "$out" -j 2 -- --bootstrap 0 2>&1)" || fail "second run failed: $log"
[ "$(grep -c '^skip unit' <<<"$log")" -eq 3 ] && [ "$(stat -c %Y "$out/unit1/model.yaml")" = "$before" ] &&
  ok "second run skips the 3 complete units" || fail "second run did not skip: $log"

rm -rf "$out/unit2"
mkdir -p "$out/unit3.partial"   # a killed run's leftover: not complete, so not unit3
rm -rf "$out/unit3"
log="$("$EX/batch_parallel.sh" "$WORK/recs" "$out" -j 2 -- --bootstrap 0 2>&1)" || fail "resume failed: $log"
grep -q '^skip unit1' <<<"$log" && grep -q '^done unit2' <<<"$log" && grep -q '^done unit3' <<<"$log" &&
  [ ! -e "$out/unit3.partial" ] && [ -s "$out/unit3/model.yaml" ] &&
  ok "resume redoes only the missing units (and replaces a stale .partial)" || fail "resume: $log"

# A recording that cannot be analysed: the others go on, the run reports the failure.
printf 'not,a\nrecording\n' >"$WORK/recs/broken.csv"
if log="$("$EX/batch_parallel.sh" "$WORK/recs" "$out" -j 2 -- --bootstrap 0 2>&1)"; then
  fail "a broken recording did not make the run fail"
else
  grep -q 'FAILED broken' <<<"$log" && [ ! -d "$out/broken" ] && [ -s "$out/fleet/fleet.csv" ] &&
    ok "a broken recording fails alone; the fleet of the others is still written" || fail "broken: $log"
fi
rm -f "$WORK/recs/broken.csv"

slurm="$WORK/slurm"
for task in 0 1 2 3; do   # task 3: beyond the 3 recordings, nothing to do
  SLURM_ARRAY_TASK_ID=$task SLURM_CPUS_PER_TASK=1 IMUNOISE_EXAMPLES_DIR="$EX" \
    bash "$EX/batch_slurm.sbatch" "$WORK/recs" "$slurm" --bootstrap 0 >"$WORK/task$task.log" 2>&1 ||
    fail "array task $task failed: $(cat "$WORK/task$task.log")"
done
[ -s "$slurm/unit1/model.yaml" ] && [ -s "$slurm/unit2/model.yaml" ] && [ -s "$slurm/unit3/model.yaml" ] &&
  grep -q 'nothing to do' "$WORK/task3.log" && ok "the Slurm array script, one run per task id, gives the 3 units" ||
  fail "slurm array units missing"
"$BIN" fleet "$slurm"/unit* -o "$slurm/fleet" -q >/dev/null || fail "fleet on the array's units"
SLURM_ARRAY_TASK_ID= bash "$EX/batch_slurm.sbatch" "$WORK/recs" "$slurm" >/dev/null 2>&1 &&
  fail "the array script ran without a task id" || ok "without SLURM_ARRAY_TASK_ID the array script refuses"

[ "$FAILURES" -eq 0 ] && { echo "PASSED"; exit 0; }
echo "$FAILURES check(s) failed"
exit 1
