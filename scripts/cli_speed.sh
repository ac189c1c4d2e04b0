#!/usr/bin/env bash
# Whole-process speed of the headless CLI: `oscilab-cli analyze` on the two bundled stepped-sine
# records, as a script or a cluster job runs it. Runs each command RUNS times (default 21, after
# one warm-up) and prints medians:
#   start-up       `oscilab-cli --version`, the whole process (loading, parsing, exit)
#   read/analysis/output   the split `analyze --timing` prints (steady clock, inside the process)
#   whole process  `analyze`, fork to exit, and the signal's duration over it (x real time)
# Wall times come from bash's EPOCHREALTIME (no extra process per measurement).
#
#   bash scripts/cli_speed.sh [RUNS] [CLI]      (CLI default: build/app/oscilab-cli)
set -euo pipefail
cd "$(dirname "$0")/.."
runs=${1:-21}
cli=${2:-build/app/oscilab-cli}
records=(samples/stepped_positive.flac samples/stepped_negative.flac)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

now_us() { local t=${EPOCHREALTIME/./}; echo "$((10#$t))"; }
median() { sort -g | awk '{v[NR]=$1} END {print (NR % 2) ? v[(NR+1)/2] : (v[NR/2]+v[NR/2+1])/2}'; }

echo "libraries loaded by $cli: $(ldd "$cli" | wc -l) ($(ldd "$cli" | grep -ci 'libqt') of them Qt)"
"$cli" --version > /dev/null
"$cli" analyze "${records[@]}" --edc "$tmp/edc.csv" > /dev/null
: > "$tmp/startup" ; : > "$tmp/whole" ; : > "$tmp/split"
for ((i = 0; i < runs; ++i)); do
  t0=$(now_us); "$cli" --version > /dev/null; t1=$(now_us)
  echo "$(( t1 - t0 ))" >> "$tmp/startup"
  t0=$(now_us); "$cli" analyze "${records[@]}" --edc "$tmp/edc.csv" --timing > "$tmp/out"; t1=$(now_us)
  echo "$(( t1 - t0 ))" >> "$tmp/whole"
  grep '^timing:' "$tmp/out" | sed -E 's/timing: read ([0-9.]+) ms, analysis ([0-9.]+) ms, output ([0-9.]+) ms.* for ([0-9.]+) s of signal.*/\1 \2 \3 \4/' >> "$tmp/split"
done
startup_ms=$(median < "$tmp/startup" | awk '{printf "%.2f", $1 / 1000}')
whole_ms=$(median < "$tmp/whole" | awk '{printf "%.2f", $1 / 1000}')
read_ms=$(cut -d' ' -f1 "$tmp/split" | median)
analysis_ms=$(cut -d' ' -f2 "$tmp/split" | median)
output_ms=$(cut -d' ' -f3 "$tmp/split" | median)
signal_s=$(head -1 "$tmp/split" | cut -d' ' -f4)
echo "medians of $runs runs, ${records[*]} ($signal_s s of signal):"
echo "  start-up (--version, whole process)  $startup_ms ms"
echo "  read                                 $read_ms ms"
echo "  analysis                             $analysis_ms ms"
echo "  output                               $output_ms ms"
echo "  analyze, whole process               $whole_ms ms"
awk -v s="$signal_s" -v w="$whole_ms" 'BEGIN {printf "  real-time factor, whole process      %.0fx\n", 1000 * s / w}'
