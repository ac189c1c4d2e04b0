#!/usr/bin/env bash
# Detection-power study of the model-gap diagnosis (docs/diagnosis.md): blind diagnoses of
# virtual-rig campaigns, each run as a lab runs it (the stiffness identified from the records):
# the paper's model with one hidden effect at strengths from below its detection threshold to 10x
# above (at 8, 9 and 10 Hz and sensor noise x1 and x3), the friction's own presliding regime at
# presliding lengths from 0.3 um to 1 mm, an effect outside the vocabulary (a one-sided damper),
# and controls: the paper's model with its six friction parameters moved by up to +-30 %, at a
# frequency from 8 to 10.5 Hz, sensor noise x1 to x3 and 17 to 26 levels per well, all drawn
# from the control's seed. A study, not a test: hours on 2 cores.
#
#   bash scripts/diagnosis_power_study.sh OUT [quick|full|smoke] [-j JOBS]
#   bash scripts/diagnosis_power_study.sh OUT [quick|full|smoke] --slurm   (prints the sbatch line)
#   bash scripts/diagnosis_power_study.sh OUT [quick|full|smoke] --summarise (what is there so far)
#
# The diagnoses are independent: the script writes OUT/jobs.txt (one diagnosis per line, the
# arguments of tests/study/diagnosis_study.cpp) and runs it with GNU parallel (JOBS at a time,
# default: the number of cores, each diagnosis on its own threads), or, with --slurm, leaves it
# to a Slurm job array (scripts/diagnosis_campaign.slurm, one diagnosis per task) and prints the
# commands to submit it and to summarise when it is done. Rows go to OUT/rows/N.csv as each
# diagnosis finishes, so an interrupted run keeps what it did and a rerun does the rest;
# OUT/results.csv joins them and OUT/summary.csv counts them.
#
# quick: 2 seeds at 9 Hz, noise x1, scales 0.003 ... 10; 1 seed at 8 Hz, 10 Hz and noise x3 for
#        scales 0.3 and 1; presliding regime 0.3 ... 1000 um, 2 seeds; the one-sided damper at
#        0.1, 0.3, 1 and 3; 100 controls; every effect at 1x and the presliding regime at 1, 3 and
#        30 um on top of friction moved as a control's (2 seeds: the start is not the truth's).
#        full: 5 seeds everywhere, 9 scales, 200 controls.
# smoke: 3 controls and one presliding-regime diagnosis (what CI runs through Slurm).
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:?usage: diagnosis_power_study.sh OUT [quick|full|smoke] [-j JOBS | --slurm]}
mode=${2:-quick}
shift $(($# >= 2 ? 2 : 1))
jobs=$(nproc 2>/dev/null || echo 2)
slurm=0
summarise_only=0
while [ $# -gt 0 ]; do
  case $1 in
    -j) jobs=$2; shift 2 ;;
    --slurm) slurm=1; shift ;;
    --summarise) summarise_only=1; shift ;;
    *) echo "diagnosis_power_study.sh: unknown option $1" >&2; exit 2 ;;
  esac
done
study=${OSCILAB_STUDY:-./build/tests/diagnosis_study}
[ -x "$study" ] || cmake --build build --target diagnosis_study
mkdir -p "$out/rows"

effects=(presliding-hysteresis quadratic-damping cubic-damping stribeck-friction coulomb-friction
         quadratic-stiffness cubic-stiffness quintic-stiffness)
regime_lengths_um=(0.3 1 3 10 30 100 300 1000)
damper_scales=(0.1 0.3 1 3)
moved_lengths_um=(1 3 30)
moved_seeds=2
case $mode in
  full) scales=(0.001 0.003 0.01 0.03 0.1 0.3 1 3 10); seeds=5; side_scales=(0.1 0.3 1 3)
        side_seeds=5; controls=200; moved_seeds=5 ;;
  quick) scales=(0.003 0.01 0.03 0.1 0.3 1 10); seeds=2; side_scales=(0.3 1); side_seeds=1
         controls=100 ;;
  smoke) scales=(); seeds=0; side_scales=(); side_seeds=0; controls=3; regime_lengths_um=(30)
         damper_scales=(); moved_seeds=0 ;;
  *) echo "diagnosis_power_study.sh: mode must be quick, full or smoke" >&2; exit 2 ;;
esac

# The job list: one diagnosis per line.
{
  for seed in $(seq 1 "$controls"); do
    # Frequency 8 ... 10.5 Hz, noise x1 ... x3 and 17 or 26 levels, drawn from the seed.
    awk -v s="$seed" 'BEGIN { srand(s * 7919); f = 8 + 2.5 * rand(); n = 1 + 2 * rand();
      printf "control %d %.2f %.2f %d\n", s, f, n, (rand() < 0.5 ? 17 : 26) }'
  done
  for effect in "${effects[@]}"; do
    for scale in "${scales[@]}"; do
      for seed in $(seq 1 "$seeds"); do echo "power $effect $scale 9 1 $seed"; done
    done
    for scale in "${side_scales[@]}"; do
      for seed in $(seq 1 "$side_seeds"); do
        for spec in "8 1" "10 1" "9 3"; do echo "power $effect $scale $spec $seed"; done
      done
    done
  done
  for length in "${regime_lengths_um[@]}"; do
    for seed in $(seq 1 "$((seeds > 0 ? seeds : 1))"); do
      echo "power presliding-regime $length 9 1 $seed"
    done
  done
  for scale in "${damper_scales[@]}"; do echo "power one-sided-damper $scale 9 1 1"; done
  # Effects on top of friction moved as a control's (the start is not the truth's friction).
  for seed in $(seq 1 "$moved_seeds"); do
    for effect in "${effects[@]}"; do echo "moved $effect 1 9 1 $seed"; done
    for length in "${moved_lengths_um[@]}"; do echo "moved presliding-regime $length 9 1 $seed"; done
  done
} > "$out/jobs.txt"
count=$(wc -l < "$out/jobs.txt")

if [ "$slurm" = 1 ]; then
  echo "sbatch --array=1-$count scripts/diagnosis_campaign.slurm $out/jobs.txt $out/rows"
  echo "then: bash scripts/diagnosis_power_study.sh $out $mode   (summarises; runs what is missing)"
  exit 0
fi

# GNU parallel, JOBS at a time; a job whose row exists is skipped (a rerun finishes a study).
export study out
run_one() {  # N ARGS...
  local n=$1
  shift
  [ -s "$out/rows/$n.csv" ] && return 0
  "$study" "$@" | tail -n 1 > "$out/rows/$n.csv.part" && mv "$out/rows/$n.csv.part" "$out/rows/$n.csv"
}
export -f run_one
threads=$(( $(nproc 2>/dev/null || echo 2) / jobs ))
if [ "$summarise_only" = 0 ]; then
  nl -ba -w1 -s' ' "$out/jobs.txt" |
    OMP_NUM_THREADS=$((threads > 0 ? threads : 1)) \
    parallel -j "$jobs" --colsep ' ' --joblog "$out/joblog.tsv" run_one {}
fi

# Results and summary: hit rate per effect, scale and condition; false-positive rate of the
# controls; how often the gap was said open; for the controls, how often the settled baseline
# reached the χ² of the true parameters (within 2 √(2ν)).
{
  "$study" header
  for f in "$out"/rows/*.csv; do [ -s "$f" ] && cat "$f"; done
} > "$out/results.csv"
awk -F, 'NR > 1 {
  cond = ($1 == "control") ? "control,any,any" : $3 "," $4 "," $5
  key = ($1 == "moved" ? "moved " $2 : $2) "," cond; n[key]++; hit[key] += $8; t[key] += $10; gap_open[key] += (1 - $17)
  if ($10 > tmax[key]) tmax[key] = $10
  inc[key] += ($9 == "incomplete")
  if ($21 != "" && $21 >= 0) { compared[key]++; reached[key] += $21 }
} END {
  print "effect,scale,freq_hz,noise_scale,runs,correct,rate,gap_open,incomplete,mean_seconds," \
        "max_seconds,baseline_compared,baseline_reached_truth"
  for (k in n) printf "%s,%d,%d,%.3f,%d,%d,%.1f,%.1f,%d,%d\n", k, n[k], hit[k], hit[k] / n[k],
    gap_open[k], inc[k], t[k] / n[k], tmax[k], compared[k], reached[k]
}' "$out/results.csv" | sort -t, -k1,1 -k3,3 -k4,4 -k2,2g > "$out/summary.csv"
echo "study: $(($(wc -l < "$out/results.csv") - 1)) of $count diagnoses in $out/results.csv; summary in $out/summary.csv"
if /usr/bin/python3 -c "import matplotlib" 2>/dev/null && [ "$mode" != smoke ]; then
  /usr/bin/python3 scripts/diagnosis_power_plot.py "$out/results.csv" "$out/detection_power.png" ||
    echo "study: the curves could not be drawn"
fi
