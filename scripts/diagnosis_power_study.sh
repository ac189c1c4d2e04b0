#!/usr/bin/env bash
# Detection-power study of the model-gap diagnosis (docs/diagnosis.md): blind diagnoses of
# virtual-rig campaigns of the paper's model with one hidden effect at strengths from below its
# detection threshold to 10x above, at 8, 9 and 10 Hz and sensor noise x1 and x3, and controls
# (the paper's model with its friction parameters moved by up to +-30 %). Long (hours on 2
# cores): a study, not a test. Writes OUT/results.csv (one row per diagnosis, appended as they
# finish, so an interrupted run keeps what it did) and OUT/summary.csv.
#
#   bash scripts/diagnosis_power_study.sh OUT [quick|full]
#
# quick: 2 seeds at 9 Hz, noise x1, scales 0.003 ... 10; 1 seed at 8 Hz, 10 Hz and noise x3
#        for scales 0.3 and 1; 20 control seeds.   full: 5 seeds everywhere, 9 scales.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:?usage: diagnosis_power_study.sh OUT [quick|full]}
mode=${2:-quick}
study=./build/tests/diagnosis_study
[ -x "$study" ] || cmake --build build --target diagnosis_study
mkdir -p "$out"
results=$out/results.csv
[ -s "$results" ] || echo "case,effect,scale,freq_hz,noise_scale,seed,verdict,correct,status,seconds,baseline_reduced_chi2,noise_reduced_chi2,steps,accepted" > "$results"

effects=(presliding-hysteresis quadratic-damping cubic-damping stribeck-friction coulomb-friction
         quadratic-stiffness cubic-stiffness quintic-stiffness)
if [ "$mode" = full ]; then
  scales=(0.001 0.003 0.01 0.03 0.1 0.3 1 3 10); seeds=5; side_scales=(0.1 0.3 1 3); side_seeds=5; controls=40
else
  scales=(0.003 0.01 0.03 0.1 0.3 1 10); seeds=2; side_scales=(0.3 1); side_seeds=1; controls=20
fi

done_already() {  # case effect scale freq noise seed
  grep -q "^$1,$2,$3,$4,$5,$6," "$results"
}
run() {  # mode args... ; appends the result row
  "$study" "$@" | tail -n 1 >> "$results"
}

for seed in $(seq 1 "$controls"); do
  done_already control none 0 9 1 "$seed" || run control "$seed" 9 1
done
for effect in "${effects[@]}"; do
  for scale in "${scales[@]}"; do
    for seed in $(seq 1 "$seeds"); do
      done_already power "$effect" "$scale" 9 1 "$seed" || run power "$effect" "$scale" 9 1 "$seed"
    done
  done
  for scale in "${side_scales[@]}"; do
    for seed in $(seq 1 "$side_seeds"); do
      for spec in "8 1" "10 1" "9 3"; do
        set -- $spec
        done_already power "$effect" "$scale" "$1" "$2" "$seed" ||
          run power "$effect" "$scale" "$1" "$2" "$seed"
      done
    done
  done
done

# Summary: hit rate per effect, scale and condition; false-positive rate of the controls.
awk -F, 'NR > 1 {
  key = $2 "," $3 "," $4 "," $5; n[key]++; hit[key] += $8; t[key] += $10
} END {
  print "effect,scale,freq_hz,noise_scale,runs,named_correctly,hit_rate,mean_seconds"
  for (k in n) printf "%s,%d,%d,%.2f,%.1f\n", k, n[k], hit[k], hit[k] / n[k], t[k] / n[k]
}' "$results" | sort -t, -k1,1 -k3,3n -k4,4n -k2,2g > "$out/summary.csv"
echo "study: $(($(wc -l < "$results") - 1)) diagnoses in $results; summary in $out/summary.csv"
if /usr/bin/python3 -c "import matplotlib" 2>/dev/null; then
  /usr/bin/python3 scripts/diagnosis_power_plot.py "$results" "$out/detection_power.png"
  echo "study: curves in $out/detection_power.png"
else
  echo "study: no matplotlib (apt-get install python3-matplotlib) -- no curves drawn"
fi
