#!/usr/bin/env bash
# End-to-end benchmark of `imunoise analyze` (issue 3): simulate a 6-channel recording with
# the reference IMU model, then time the analysis (wall, CPU, peak RSS via GNU time).
#   bench/analyze_bench.sh [DURATION] [RATE_HZ] [BOOTSTRAP]     defaults: 8h 400 0
# Needs a Release build in build/release (tools/test or tools/demo makes one). Figures go to
# stdout; record them in bench/RESULTS.md with the machine description.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BIN="${IMUNOISE_BIN:-$ROOT/build/release/tools/imunoise}"
DURATION="${1:-8h}"
RATE="${2:-400}"
BOOTSTRAP="${3:-0}"
WORK="${IMUNOISE_BENCH_DIR:-$(mktemp -d)}"
REC="$WORK/rec_${DURATION}_${RATE}hz.csv"
if [ ! -f "$REC" ]; then
  /usr/bin/time -f "simulate: %e s wall, %U s user, %M KiB peak RSS" \
    "$BIN" simulate "$ROOT/configs/reference-imu.yaml" --duration "$DURATION" --rate "$RATE" \
    --seed 1 -o "$REC"
fi
echo "recording: $REC ($(du -h "$REC" | cut -f1), $(nproc) cores: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2))"
/usr/bin/time -f "analyze (bootstrap $BOOTSTRAP): %e s wall, %U s user, %S s sys, %M KiB peak RSS" \
  "$BIN" analyze "$REC" -o "$WORK/out" --bootstrap "$BOOTSTRAP" --quiet > "$WORK/summary.txt"
echo "outputs in $WORK/out"
