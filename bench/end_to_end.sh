#!/usr/bin/env bash
# End-to-end benchmark of imunoise (issue 8): simulate 6-channel recordings of the reference
# IMU, then time `imunoise analyze` on them from the binary format and from CSV, plus the
# export and the report. Prints one Markdown table for bench/RESULTS.md.
#
#   bench/end_to_end.sh [CASE...]      CASE = DURATION@RATE_HZ; default 8h@50 8h@400 24h@1000
#
# Per command: wall, CPU (user + sys) and peak RSS (GNU time). Per stage of analyze (its -v
# output): wall time and throughput = float64 bytes of the 6 channels / stage wall time; the
# per-channel stages (deviations, fit, psd, bootstrap) are summed over the channels, i.e.
# thread time, so their rate is per thread. Recordings are cached in $IMUNOISE_BENCH_DIR and
# read once before timing, so figures are page-cache-warm (the disk is not what is measured).
# Environment: IMUNOISE_BIN (default build/release/tools/imunoise, which tools/test builds),
# IMUNOISE_BENCH_DIR (default /tmp/imunoise-bench), IMUNOISE_BENCH_CSV_MAX (largest sample
# count also benchmarked from CSV; default 40000000 — 24 h at 1 kHz as CSV is 11 GB),
# IMUNOISE_BENCH_BOOTSTRAP (default 0: none; N ≥ 2 adds a run with the reference bootstrap of N
# simulated records), IMUNOISE_BENCH_THREADS (default 0 = all cores).
# The binary recording is analysed twice side by side: with the default intervals (the
# variance-distribution draws) and without intervals (--interval-draws 0), and the ratio of
# the two wall times is printed (issue 21: at most 1.5).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BIN="${IMUNOISE_BIN:-$ROOT/build/release/tools/imunoise}"
WORK="${IMUNOISE_BENCH_DIR:-/tmp/imunoise-bench}"
CSV_MAX="${IMUNOISE_BENCH_CSV_MAX:-40000000}"
BOOTSTRAP="${IMUNOISE_BENCH_BOOTSTRAP:-0}"
THREADS="${IMUNOISE_BENCH_THREADS:-0}"
CASES=("$@")
[ ${#CASES[@]} -gt 0 ] || CASES=(8h@50 8h@400 24h@1000)
[ -x "$BIN" ] || { echo "bench: no imunoise binary at $BIN (run tools/test or set IMUNOISE_BIN)" >&2; exit 2; }
command -v /usr/bin/time >/dev/null || { echo "bench: needs GNU time (apt-get install time)" >&2; exit 2; }
mkdir -p "$WORK"

seconds_of() {  # DURATION (e.g. 8h, 30m, 90s) -> seconds
  local d=$1
  case $d in
    *h) echo $((${d%h} * 3600)) ;;
    *m) echo $((${d%m} * 60)) ;;
    *s) echo "${d%s}" ;;
    *) echo "$d" ;;
  esac
}

# timed NAME LOG CMD...: runs CMD, stderr to LOG; sets WALL, CPU, RSS_MB.
timed() {
  local log=$1
  shift
  /usr/bin/time -o "$log.time" -f "%e %U %S %M" "$@" >"$log.out" 2>"$log"
  read -r WALL USER SYS RSS_KB <"$log.time"
  CPU=$(awk -v u="$USER" -v s="$SYS" 'BEGIN { printf "%.1f", u + s }')
  RSS_MB=$(awk -v k="$RSS_KB" 'BEGIN { printf "%.0f", k / 1024 }')
}

# stage LOG NAME: seconds of stage NAME in analyze -v output (0 when absent).
stage() {
  awk -v name="$2" '
    /wall time:|summed over the channels:/ {
      n = split($0, parts, /[:,(]/)
      for (i = 1; i <= n; ++i) {
        f = parts[i]; gsub(/^ +| +$/, "", f)
        if (index(f, name " ") == 1 && f ~ / s$/) { split(f, w, " "); print w[2]; exit }
      }
    }' "$1" | awk 'END { print (NR ? $0 : 0) }'
}

rate() {  # BYTES SECONDS -> "X MB/s" (decimal MB)
  awk -v b="$1" -v s="$2" 'BEGIN { if (s > 0) printf "%.0f MB/s", b / s / 1e6; else print "—" }'
}

echo "machine: $(nproc) cores,$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2), $(awk '/MemTotal/ { printf "%.0f GB", $2 / 1048576 }' /proc/meminfo) RAM; $("$BIN" --version 2>/dev/null | head -1)"
echo
echo "| case | command | wall s | CPU s | peak RSS MiB | RSS / data | stages (wall s, throughput of the float64 data) |"
echo "|---|---|---|---|---|---|---|"
for c in "${CASES[@]}"; do
  duration=${c%@*}
  rate_hz=${c#*@}
  samples=$(($(seconds_of "$duration") * rate_hz))
  data_bytes=$((samples * 6 * 8))
  data_mb=$(awk -v b="$data_bytes" 'BEGIN { printf "%.0f", b / 1048576 }')
  base="$WORK/rec_${duration}_${rate_hz}hz"
  if [ ! -f "$base.imnb" ]; then
    timed "$base.simulate.log" "$BIN" simulate "$ROOT/configs/reference-imu.yaml" \
      --duration "$duration" --rate "$rate_hz" --seed 1 -o "$base.imnb" --quiet
    echo "| $c | simulate → binary | $WALL | $CPU | $RSS_MB | | $(rate "$data_bytes" "$WALL") |"
  fi
  inputs=("$base.imnb")
  if [ "$samples" -le "$CSV_MAX" ]; then
    if [ ! -f "$base.csv" ]; then
      timed "$base.convert.log" "$BIN" convert "$base.imnb" -o "$base.csv" --quiet
      echo "| $c | convert binary → CSV | $WALL | $CPU | $RSS_MB | | $(rate "$data_bytes" "$WALL") |"
    fi
    inputs+=("$base.csv")
  fi
  # analyze_run INPUT LABEL OUT FLAGS...: one timed analyze -v, its table row; sets WALL.
  analyze_run() {
    local input=$1 label=$2 out=$3
    shift 3
    local kind=${input##*.}
    rm -rf "$out"
    timed "$out.log" "$BIN" analyze "$input" -o "$out" --threads "$THREADS" -v "$@"
    local file_bytes read_s stages v s ratio
    file_bytes=$(stat -L -c %s "$input")
    read_s=$(stage "$out.log" read)
    stages="read $read_s ($(rate "$file_bytes" "$read_s") of $kind file)"
    for s in deviations PSD fit bootstrap intervals; do
      v=$(stage "$out.log" "$s")
      [ "$v" = 0 ] || stages+=", $s $v ($(rate "$data_bytes" "$v") per thread)"
    done
    for s in outputs report; do
      stages+=", $s $(stage "$out.log" "$s")"
    done
    ratio=$(awk -v r="$RSS_MB" -v d="$data_mb" 'BEGIN { printf "%.2f", r / d }')
    echo "| $c ($samples samples × 6, $data_mb MiB) | analyze $kind, $label | $WALL | $CPU | $RSS_MB | $ratio | $stages |"
  }
  for input in "${inputs[@]}"; do
    kind=${input##*.}
    cat "$input" >/dev/null  # page cache warm
    out="$WORK/out_${duration}_${rate_hz}hz_$kind"
    if [ "$kind" = imnb ]; then
      analyze_run "$input" "no intervals (--interval-draws 0)" "${out}_no_intervals" \
        --interval-draws 0
      wall_none=$WALL
      analyze_run "$input" "default intervals" "$out"
      echo "| $c | default / no intervals, wall | $(awk -v a="$WALL" -v b="$wall_none" 'BEGIN { printf "%.2f", a / b }') | | | | |"
      if [ "$BOOTSTRAP" -ge 2 ]; then
        analyze_run "$input" "bootstrap $BOOTSTRAP" "${out}_bootstrap" --bootstrap "$BOOTSTRAP"
      fi
    else
      analyze_run "$input" "default intervals" "$out"
    fi
  done
  out="$WORK/out_${duration}_${rate_hz}hz_imnb"
  timed "$out.export.log" "$BIN" export "$out/model.yaml" --to all -o "$out/exports" --quiet
  echo "| $c | export --to all | $WALL | $CPU | $RSS_MB | | |"
  timed "$out.report.log" "$BIN" report "$out" --quiet
  echo "| $c | report | $WALL | $CPU | $RSS_MB | | |"
done
