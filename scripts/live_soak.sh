#!/usr/bin/env bash
# A day-long live acquisition, freewheeled: `oscilab-cli record` on the virtual rig at the
# speed the chain takes (--speed 0, about 140x real time on 2 cores), a stepped sine of the
# paper's 26 levels with the hold stretched to the run's length, recorded to a float64 W64 file
# with the live EDC. Prints the process's resident memory against the stream time every
# INTERVAL seconds of wall time (the stream time from the recording's size), then the live EDC's
# summary (levels, cycles, latency) and, from the run's status log (--status-log, a row a second
# of wall time), the live EDC's latency per hour of stream: the median of the rows' rolling
# median (last 10 000 cycles), the largest last-cycle latency seen, the fullest queue and the
# blocks lost to a full queue. The resident set should stay flat: the history ring, the live
# EDC's kept cycles and the queues are bounded; only the levels and the event log grow. The
# latency should not grow from the first hour to the last.
#
#   bash scripts/live_soak.sh [STREAM_SECONDS] [INTERVAL] [CLI]
#   (defaults: 86400 s of stream, every 30 s, build/app/oscilab-cli; a day takes ~10 minutes
#    and 6 GB of disk in a temporary directory, removed at the end)
set -euo pipefail
cd "$(dirname "$0")/.."
duration=${1:-86400}
interval=${2:-30}
cli=${3:-build/app/oscilab-cli}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
hold=$(awk -v d="$duration" 'BEGIN { printf "%.3f", (d - 2.5) / 26 }')
"$cli" record --source rig --levels 0.2:0.1:2.7 --hold "$hold" --speed 0 \
  --duration "$duration" --out "$tmp/soak.w64" --status-log "$tmp/status.csv" --status-every 1 \
  > "$tmp/out.txt" 2> "$tmp/err.txt" &
pid=$!
start=$SECONDS
printf '%8s %10s %10s %10s\n' "wall_s" "stream_h" "rss_MB" "peak_MB"
while kill -0 "$pid" 2> /dev/null; do
  rss=$(awk '/^VmRSS/ { print $2 }' "/proc/$pid/status" 2> /dev/null || echo 0)
  hwm=$(awk '/^VmHWM/ { print $2 }' "/proc/$pid/status" 2> /dev/null || echo 0)
  bytes=$(stat -c %s "$tmp/soak.w64" 2> /dev/null || echo 0)
  # Two float64 channels at 512 Hz (base, mass); the header is a few hundred bytes.
  printf '%8d %10.3f %10.1f %10.1f\n' "$((SECONDS - start))" \
    "$(awk -v b="$bytes" 'BEGIN { print b / (2 * 8 * 512) / 3600 }')" \
    "$(awk -v k="${rss:-0}" 'BEGIN { print k / 1024 }')" "$(awk -v k="${hwm:-0}" 'BEGIN { print k / 1024 }')"
  sleep "$interval"
done
wait "$pid"
grep -E "^(recorded|live EDC)" "$tmp/out.txt"
cat "$tmp/err.txt"
echo
printf '%8s %6s %14s %12s %10s %10s\n' "stream_h" "rows" "median_ms" "max_ms" "queue_max" "overflow"
# Columns of the status log: 2 stream_s, 11 overflowed_blocks, 12 queue_fill, 17 edc_latency_s,
# 18 edc_latency_median_s (docs/contracts.md).
tail -n +2 "$tmp/status.csv" | awk -F, '
  { h = int($2 / 3600); n[h]++; med[h, n[h]] = $18
    if ($17 > mx[h]) mx[h] = $17
    if ($12 > q[h]) q[h] = $12
    of[h] = $11; if (h > last) last = h }
  END {
    for (h = 0; h <= last; h++) {
      if (!n[h]) continue
      # the median of the hour'"'"'s rows (insertion sort: a few thousand rows an hour at most)
      for (i = 1; i <= n[h]; i++) v[i] = med[h, i]
      for (i = 2; i <= n[h]; i++) { x = v[i]; j = i - 1; while (j > 0 && v[j] > x) { v[j + 1] = v[j]; j-- } v[j + 1] = x }
      m = (n[h] % 2) ? v[(n[h] + 1) / 2] : (v[n[h] / 2] + v[n[h] / 2 + 1]) / 2
      printf "%8d %6d %14.1f %12.1f %10d %10d\n", h, n[h], 1e3 * m, 1e3 * mx[h], q[h], of[h]
    }
  }' 
