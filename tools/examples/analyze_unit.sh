#!/usr/bin/env bash
# Analyse one recording into OUT_DIR/UNIT, resumably: the unit is complete when OUT_DIR/UNIT
# exists, because the analysis writes into OUT_DIR/UNIT.partial and renames it only after
# `imunoise analyze` succeeded (a rename within one directory is atomic). A complete unit is
# skipped; a .partial left by a killed run is removed and redone. Used by batch_parallel.sh
# (GNU parallel) and batch_slurm.sbatch (a Slurm array job); docs/batch.md.
#
#   analyze_unit.sh RECORDING OUT_DIR [analyze flags…]
# IMUNOISE (default: imunoise on PATH) is the binary. UNIT = the recording's name without its
# extension. Exit: 0 done or skipped, else analyze's exit code.
set -euo pipefail
if [ $# -lt 2 ]; then
  echo "usage: $0 RECORDING OUT_DIR [analyze flags...]" >&2
  exit 2
fi
rec="$1"
out="$2"
shift 2
bin="${IMUNOISE:-imunoise}"
name="$(basename "$rec")"
unit="${name%.*}"
final="$out/$unit"
if [ -d "$final" ]; then
  echo "skip $unit: $final is complete"
  exit 0
fi
partial="$final.partial"
rm -rf "$partial"
mkdir -p "$out"
"$bin" analyze "$rec" -o "$partial" -q "$@" >"$partial.log" 2>&1 || {
  rc=$?
  echo "FAILED $unit (exit $rc): see $partial.log" >&2
  exit "$rc"
}
mv "$partial.log" "$partial/analyze.log"
mv "$partial" "$final"
echo "done $unit"
