#!/usr/bin/env bash
# Analyse every recording of a directory with GNU parallel, one output directory per unit,
# resumable (a complete unit is skipped), then compare the units with `imunoise fleet`.
# docs/batch.md.
#
#   batch_parallel.sh REC_DIR OUT_DIR [-j JOBS] [--spec SPEC.yaml] [-- analyze flags…]
# Recordings: REC_DIR/*.csv, *.imnb, *.lcmlog, *.bag, *.mcap, *.db3, *.ulg. Writes
# OUT_DIR/UNIT/ (as imunoise analyze) per recording and OUT_DIR/fleet/ (fleet.csv,
# fleet.html). IMUNOISE selects the binary. Run it again after an interruption: only the
# missing units are analysed.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
if [ $# -lt 2 ]; then
  echo "usage: $0 REC_DIR OUT_DIR [-j JOBS] [--spec SPEC.yaml] [-- analyze flags...]" >&2
  exit 2
fi
rec_dir="$1"
out="$2"
shift 2
jobs=1
spec=()
while [ $# -gt 0 ]; do
  case "$1" in
    -j) jobs="$2"; shift 2 ;;
    --spec) spec=(--spec "$2"); shift 2 ;;
    --) shift; break ;;
    *) echo "unknown option $1" >&2; exit 2 ;;
  esac
done
command -v parallel >/dev/null || { echo "GNU parallel is not installed (apt-get install parallel)" >&2; exit 2; }
mkdir -p "$out"
shopt -s nullglob
recs=("$rec_dir"/*.{csv,imnb,lcmlog,bag,mcap,db3,ulg})
[ ${#recs[@]} -gt 0 ] || { echo "no recording in $rec_dir" >&2; exit 2; }
# --halt never: one bad recording does not stop the others; the exit status counts failures.
status=0
parallel --will-cite --halt never -j "$jobs" "$here/analyze_unit.sh" {} "$out" "$@" \
  ::: "${recs[@]}" || status=$?
units=()
for r in "${recs[@]}"; do
  n="$(basename "$r")"
  [ -d "$out/${n%.*}" ] && units+=("$out/${n%.*}")
done
[ ${#units[@]} -gt 0 ] || { echo "no unit was analysed" >&2; exit 1; }
"${IMUNOISE:-imunoise}" fleet "${units[@]}" "${spec[@]}" -o "$out/fleet"
exit "$status"
