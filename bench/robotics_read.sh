#!/usr/bin/env bash
# Read throughput of the robotics-log readers (issue 22): a ROS 1 bag, MCAP (none, zstd) and a
# PX4 ULog of one IMU topic, DURATION at RATE_HZ, each read by `imunoise check` (the reader, the
# Recording and the sampling report every command gets). Prints one Markdown table for
# bench/RESULTS.md.
#
#   bench/robotics_read.sh [DURATION_S [RATE_HZ]]      default 28800 s (8 h) at 400 Hz
#
# The files are written by the formats' own writers (bench/robotics_logs/: Debian's
# python3-rosbag for the bag; @mcap/core with @foxglove/rosmsg2-serialization for MCAP; our
# ULog writer, the same layout as tests/fixtures/write_ulog_fixtures.mjs), cached in
# $IMUNOISE_BENCH_DIR (8 h at 400 Hz: 4.4 GB bag, 4.3 + 0.9 GB MCAP, 0.6 GB ULog; writing them
# takes ~10 min), and read once before timing (page-cache warm). Per file: wall, peak RSS (GNU
# time), file MB/s = file bytes / wall, and RSS / decoded columns, the columns being what the
# reader yields: time + 6 channels as float64 = 56 bytes per sample. The same samples as .imnb
# (imunoise convert) are read too, for comparison.
# Needs the npm packages of tests/fixtures (tools/test installs them into
# build/release/tests/fixtures/node_modules).
# Environment: IMUNOISE_BIN (default build/release/tools/imunoise), IMUNOISE_BENCH_DIR (default
# /tmp/imunoise-bench), IMUNOISE_NODE_MODULES (default build/release/tests/fixtures).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BIN="${IMUNOISE_BIN:-$ROOT/build/release/tools/imunoise}"
WORK="${IMUNOISE_BENCH_DIR:-/tmp/imunoise-bench}"
NODE_DIR="${IMUNOISE_NODE_MODULES:-$ROOT/build/release/tests/fixtures}"
SECONDS_REC=${1:-28800}
RATE_HZ=${2:-400}
[ -x "$BIN" ] || { echo "bench: no imunoise binary at $BIN (run tools/test or set IMUNOISE_BIN)" >&2; exit 2; }
[ -d "$NODE_DIR/node_modules/@mcap/core" ] ||
  { echo "bench: no npm packages in $NODE_DIR/node_modules (run tools/test first)" >&2; exit 2; }
command -v /usr/bin/time >/dev/null || { echo "bench: needs GNU time (apt-get install time)" >&2; exit 2; }
dir="$WORK/robotics_${SECONDS_REC}s_${RATE_HZ}hz"
mkdir -p "$dir"

if [ ! -f "$dir/imu_none.bag" ]; then
  /usr/bin/python3 "$ROOT/bench/robotics_logs/write_bench_bag.py" "$SECONDS_REC" "$RATE_HZ" none \
    "$dir/imu_none.bag.tmp"
  mv "$dir/imu_none.bag.tmp" "$dir/imu_none.bag"
fi
if [ ! -f "$dir/imu.ulg" ] || [ ! -f "$dir/imu_zstd.mcap" ]; then
  # An ES module resolves its imports from its own folder.
  cp "$ROOT/bench/robotics_logs/write_bench_logs.mjs" "$NODE_DIR/"
  node "$NODE_DIR/write_bench_logs.mjs" "$SECONDS_REC" "$RATE_HZ" "$dir"
fi
[ -f "$dir/imu.imnb" ] || "$BIN" convert "$dir/imu.ulg" -o "$dir/imu.imnb" --quiet

samples=$(awk -v s="$SECONDS_REC" -v r="$RATE_HZ" 'BEGIN { printf "%d", s * r + 0.5 }')
columns_mib=$(awk -v n="$samples" 'BEGIN { printf "%.0f", n * 56 / 1048576 }')
echo "machine: $(nproc) cores,$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2); $("$BIN" --version 2>/dev/null | head -1)"
echo "$samples samples; decoded columns (time + 6 × float64) $columns_mib MiB"
echo
echo "| file | size MB | wall s | file MB/s | peak RSS MiB | RSS / columns |"
echo "|---|---|---|---|---|---|"
for f in imu_none.bag imu_none.mcap imu_zstd.mcap imu.ulg imu.imnb; do
  path="$dir/$f"
  cat "$path" >/dev/null
  /usr/bin/time -o "$dir/time.txt" -f "%e %M" "$BIN" check "$path" >"$dir/check.out" 2>&1 ||
    { echo "bench: imunoise check $path failed:" >&2; cat "$dir/check.out" >&2; exit 1; }
  read -r wall rss_kb <"$dir/time.txt"
  bytes=$(stat -L -c %s "$path")
  awk -v f="$f" -v b="$bytes" -v w="$wall" -v r="$rss_kb" -v c="$columns_mib" 'BEGIN {
    printf "| %s | %.0f | %.2f | %.0f | %.0f | %.2f |\n", f, b / 1e6, w, (w > 0 ? b / w / 1e6 : 0),
      r / 1024, r / 1024 / c }'
done
