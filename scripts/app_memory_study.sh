#!/usr/bin/env bash
# Peak memory and time of the app opening a record against the record's length: virtual-rig
# stepped sines of 10 min, 1 h, 6 h and 24 h (26 levels of the paper's grid, the hold stretched,
# W64 as `oscilab-cli record` writes them), each opened by `oscilab REC --screenshot` under the
# offscreen platform, which opens the record, draws it, runs the review's analysis and takes the
# picture once it ended. Prints the peak resident set (MB, from /usr/bin/time) and the wall time.
# Making the 24 h record takes the rig about 7 minutes on 2 cores and 0.7 GB of disk.
#
#   bash scripts/app_memory_study.sh [BUILD] [MINUTES...]   (defaults: build, 10 60 360 1440)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
shift || true
lengths=("$@")
[ ${#lengths[@]} -gt 0 ] || lengths=(10 60 360 1440)
dir=${OSCILAB_STUDY_DIR:-$(mktemp -d)}
printf '%8s %12s %12s %10s\n' "minutes" "samples/ch" "peak_rss_MB" "wall_s"
for minutes in "${lengths[@]}"; do
  record="$dir/stepped_${minutes}min.w64"
  if [ ! -f "$record" ]; then
    duration=$((minutes * 60))
    hold=$(awk -v d="$duration" 'BEGIN { printf "%.3f", (d - 2.5) / 26 }')
    "$build/app/oscilab-cli" record --source rig --levels 0.2:0.1:2.7 --hold "$hold" --speed 0 \
      --duration "$duration" --out "$record" > /dev/null
  fi
  start=$(date +%s.%N)
  /usr/bin/time -f '%M' -o "$dir/rss.txt" env QT_QPA_PLATFORM=offscreen \
    "$build/app/oscilab" --screenshot "$dir/shot_${minutes}.png" "$record" > /dev/null 2>&1
  end=$(date +%s.%N)
  samples=$((minutes * 60 * 512))
  awk -v m="$minutes" -v n="$samples" -v kb="$(tail -1 "$dir/rss.txt")" -v s="$start" -v e="$end" \
    'BEGIN { printf "%8d %12d %12.1f %10.1f\n", m, n, kb / 1024, e - s }'
done
