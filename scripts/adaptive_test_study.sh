#!/usr/bin/env bash
# Fixed campaign against adaptive test on the virtual rig (not run by CI):
#   scripts/adaptive_test_study.sh OSCILAB_CLI OUT [small|weak|full] [-j JOBS]
# Each case is a rig whose truth is the paper's model with one effect of the vocabulary hidden at
# a multiple of the diagnosis campaign's reference strengths (as
# tests/analysis/diagnosis/hidden_effect_campaign.h builds them), or a control (the paper's model
# alone). For each case and seed:
#   fixed:    stepped sines of 26 levels (0.2:0.1:2.7 N, 10 s, 2.5 s lead-in) in both wells, then
#             `diagnose` (525 s of shaker time);
#   adaptive: `adaptive-test` on the same rig and seed, to its stop rule (budget 525 s).
# OUT/results.csv: case,effect,scale,seed,mode,verdict,correct,shaker_time_s,levels,seconds,leader
# (leader: the adaptive loop's leading hypothesis; the fixed campaign's verdict for `fixed`)
# OUT/summary.txt: per mode the median shaker time, wrong verdicts and control false positives.
# small: quadratic and cubic damping at 1x, 1 seed, 1 control. weak: quadratic and cubic damping
# at 0.3x and presliding hysteresis at 1x, 1 seed. full: every effect at 0.3x and 1x, 3 seeds,
# 20 controls (hours on 2 cores).
set -euo pipefail
cli=$(realpath "$1")
out=$2
size=${3:-small}
jobs=1
[ "${4:-}" = "-j" ] && jobs=${5:-1}
mkdir -p "$out/models" "$out/runs"

# The term of each effect at its reference strength (hidden_effect_campaign.h), scaled.
term_json() {
  python3 - "$1" "$2" << 'PY'
import json, sys
effect, s = sys.argv[1], float(sys.argv[2])
terms = {
    "quadratic-damping": {"type": "quadratic-damping", "c2_ns2_m2": 6.0 * s},
    "cubic-damping": {"type": "cubic-damping", "c3_ns3_m3": 60.0 * s},
    "coulomb-friction": {"type": "coulomb-friction", "fc_n": 0.05 * s, "v_eps_m_s": 1e-3},
    "stribeck-friction": {"type": "stribeck-friction", "fs_n": 0.1 * s, "vs_m_s": 5e-3},
    "presliding-hysteresis": {"type": "presliding-hysteresis", "fc_n": 0.06 * s,
                              "sigma0_n_m": 3e3 * s},
    "quintic-stiffness": {"type": "polynomial-stiffness",
                          "coefficients": [0, 0, 0, 0, 0, 1.2e7 * s]},
}
print(json.dumps(terms.get(effect)))
PY
}

"$cli" model paper --out "$out/models/paper.json" > /dev/null
make_model() {  # effect scale -> path
  local effect=$1 scale=$2 path="$out/models/${1}_${2}.json"
  python3 - "$out/models/paper.json" "$path" "$(term_json "$effect" "$scale")" << 'PY'
import json, sys
model = json.load(open(sys.argv[1]))
term = json.loads(sys.argv[3])
if term is not None:
    model["terms"].append(term)
json.dump(model, open(sys.argv[2], "w"))
PY
  echo "$path"
}

cases=()
if [ "$size" = small ]; then
  seeds="1"
  for e in quadratic-damping cubic-damping; do cases+=("$e 1"); done
  cases+=("none 0")
elif [ "$size" = weak ]; then
  seeds="1"
  cases+=("quadratic-damping 0.3" "cubic-damping 0.3" "presliding-hysteresis 1")
else
  seeds="1 2 3"
  for e in quadratic-damping cubic-damping coulomb-friction stribeck-friction presliding-hysteresis quintic-stiffness; do
    cases+=("$e 0.3" "$e 1")
  done
  for c in $(seq 1 20); do cases+=("none 0 $c"); done
fi

# One case, one seed, both modes: a CSV line each.
run_case() {
  local effect=$1 scale=$2 seed=$3 model=$4 dir=$5
  mkdir -p "$dir"
  local start end
  start=$(date +%s.%N)
  "$cli" simulate --model "$model" --well positive --seed "$seed" --out "$dir/pos.flac" > /dev/null
  "$cli" simulate --model "$model" --well negative --seed "$((seed + 100))" --out "$dir/neg.flac" > /dev/null
  "$cli" diagnose "$dir/pos.flac" "$dir/neg.flac" --no-png --seed "$seed" --out "$dir/fixed" \
    > "$dir/fixed.log" 2>&1 || true
  end=$(date +%s.%N)
  python3 - "$dir/fixed/report.json" "$effect" "$scale" "$seed" fixed "$start" "$end" << 'PY'
import json, sys
path, effect, scale, seed, mode, start, end = sys.argv[1:]
seconds = float(end) - float(start)
try:
    r = json.load(open(path)); verdict = r["verdict"]
    levels = sum(1 for l in r["baseline"]["maps"]["levels"])
except Exception:
    verdict, levels = "failed", 0
print(f"{effect}_{scale},{effect},{scale},{seed},{mode},{verdict},{int(verdict == effect)},525.0,{levels},{float(seconds):.1f},{verdict}")
PY
  start=$(date +%s.%N)
  "$cli" adaptive-test --source rig --rig-model "$model" --seed "$seed" --budget 525 \
    --out "$dir/adaptive" > "$dir/adaptive.log" 2>&1 || true
  end=$(date +%s.%N)
  python3 - "$dir/adaptive/report.json" "$effect" "$scale" "$seed" adaptive "$start" "$end" << 'PY'
import json, sys
path, effect, scale, seed, mode, start, end = sys.argv[1:]
seconds = float(end) - float(start)
try:
    r = json.load(open(path)); verdict = r["verdict"]
    shaker = r["shaker_time_s"]; levels = r["adaptive_test"]["levels"]
    leader = r["adaptive_test"]["leader"]
except Exception:
    verdict, shaker, levels, leader = "failed", float("nan"), 0, "failed"
print(f"{effect}_{scale},{effect},{scale},{seed},{mode},{verdict},{int(verdict == effect)},{shaker},{levels},{float(seconds):.1f},{leader}")
PY
}
export -f run_case
export cli

joblist=$out/jobs.txt
: > "$joblist"
for c in "${cases[@]}"; do
  read -r effect scale control <<< "$c"
  model=$(make_model "$effect" "$scale")
  for seed in $seeds; do
    s=$seed
    [ -n "${control:-}" ] && s=$((control * 10 + seed))
    echo "run_case $effect $scale $s $model $out/runs/${effect}_${scale}_$s" >> "$joblist"
  done
done
echo "case,effect,scale,seed,mode,verdict,correct,shaker_time_s,levels,seconds,leader" > "$out/results.csv"
if [ "$jobs" -gt 1 ] && command -v parallel > /dev/null; then
  parallel -j "$jobs" < "$joblist" >> "$out/results.csv"
else
  while read -r line; do eval "$line" >> "$out/results.csv"; done < "$joblist"
fi

python3 - "$out/results.csv" > "$out/summary.txt" << 'PY'
import csv, statistics, sys
rows = list(csv.DictReader(open(sys.argv[1])))
for mode in ("fixed", "adaptive"):
    r = [x for x in rows if x["mode"] == mode]
    effects = [x for x in r if x["effect"] != "none"]
    controls = [x for x in r if x["effect"] == "none"]
    times = [float(x["shaker_time_s"]) for x in r if x["shaker_time_s"] != "nan"]
    print(f"{mode}: {len(r)} runs, median shaker time {statistics.median(times) if times else float('nan'):.1f} s, "
          f"wrong verdicts {sum(1 for x in effects if x['correct'] == '0')}/{len(effects)}, "
          f"control false positives {sum(1 for x in controls if x['verdict'] != 'none')}/{len(controls)}, "
          f"wrong leaders {sum(1 for x in r if x['leader'] != x['effect'])}/{len(r)}")
PY
cat "$out/summary.txt"
