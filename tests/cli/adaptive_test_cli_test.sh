#!/usr/bin/env bash
# oscilab-cli adaptive-test on the virtual rig:
#   adaptive_test_cli_test.sh OSCILAB_CLI SOURCE_DIR errors|run [EFFECTS]
# `errors`: bad options are refused with one line and exit 2, before any shaker time is spent.
# `run`: a rig whose truth is the paper's model with quadratic damping at the diagnosis
# campaign's reference strength (c2 = 6 N s^2/m^2) hidden in it. The test must name
# quadratic-damping and decide with less shaker time than the fixed grid (2 wells x 26 levels x
# 10 s); every decision is one JSON line. EFFECTS (comma-separated) narrows the candidates weighed:
# with three rivals (another damping law, a stiffness term) about a minute of CPU; with the whole
# vocabulary (no EFFECTS) about four minutes, every hypothesis's global search on the pilot.
source "$(dirname "$0")/cli_checks.sh"
repair_jack_metadata
mode=${3:-errors}
effects=()
[ -n "${4:-}" ] && effects=(--effects "$4")

"$cli" model paper --out "$work/paper.json" > /dev/null
python3 - "$work/paper.json" "$work/quad.json" << 'PY'
import json, sys
model = json.load(open(sys.argv[1]))
model["terms"].append({"type": "quadratic-damping", "c2_ns2_m2": 6.0})
model["name"] = "paper + quadratic damping"
json.dump(model, open(sys.argv[2], "w"))
PY

if [ "$mode" = errors ]; then
  expect_error "no rig model" "--rig-model: required" "$cli" adaptive-test --out "$work/e1"
  expect_error "an unknown source" "^oscilab-cli: --source usb:3: rig (the virtual rig) or jack:" \
    "$cli" adaptive-test --source usb:3 --rig-model "$work/quad.json" --out "$work/e2"
  expect_error "a JACK source without a drive" "^oscilab-cli: --drive: required with --source jack:" \
    "$cli" adaptive-test --source jack:a,b --out "$work/e9"
  expect_error "a JACK source of one port" "^oscilab-cli: --source jack:a: give jack:ACCELERATION_PORT,POSITION_PORT" \
    "$cli" adaptive-test --source jack:a --drive jack:p --out "$work/e10"
  expect_error "a JACK source without scales" "^oscilab-cli: --acceleration-scale, --position-scale: required" \
    "$cli" adaptive-test --source jack:a,b --drive jack:p --out "$work/e11"
  expect_error "a JACK source in both wells" "^oscilab-cli: --wells both: a real rig cannot move the mass" \
    "$cli" adaptive-test --source jack:a,b --drive jack:p --acceleration-scale 50 \
    --position-scale 0.1 --out "$work/e12"
  expect_error "a JACK source and a rig model" "^oscilab-cli: --rig-model: only with --source rig" \
    "$cli" adaptive-test --source jack:a,b --drive jack:p --acceleration-scale 50 \
    --position-scale 0.1 --wells positive --rig-model "$work/quad.json" --out "$work/e13"
  expect_error "a JACK server that does not run" "^oscilab-cli: JACK server \"oscilab-none-$$\" is not running" \
    "$cli" adaptive-test --source jack:a,b --drive jack:p --acceleration-scale 50 \
    --position-scale 0.1 --wells positive --jack-server "oscilab-none-$$" --out "$work/e14"
  expect_error "a drive for the rig" "^oscilab-cli: --drive: only with --source jack:" \
    "$cli" adaptive-test --rig-model "$work/quad.json" --drive jack:p --out "$work/e15"
  expect_error "an f0 range upside down" "--f0: need 0 < A <= B" \
    "$cli" adaptive-test --rig-model "$work/quad.json" --f0 2.7:0.2 --out "$work/e3"
  expect_error "a leader weight above 1" "--leader-weight" \
    "$cli" adaptive-test --rig-model "$work/quad.json" --leader-weight 2 --out "$work/e4"
  expect_error "an unknown effect" 'unknown effect "drag"' \
    "$cli" adaptive-test --rig-model "$work/quad.json" --effects quadratic-damping,drag \
    --out "$work/e5"
  expect_error "a negative budget" "oscilab-cli: --budget: must be a positive number of s" \
    "$cli" adaptive-test --rig-model "$work/quad.json" --budget -5 --out "$work/e6"
  expect_error "a frequency step of 0" "oscilab-cli: --freq-step: must be a positive number of Hz" \
    "$cli" adaptive-test --rig-model "$work/quad.json" --freq-step 0 --out "$work/e8"
  expect_error "a missing rig model file" "nothing.json" \
    "$cli" adaptive-test --rig-model "$work/nothing.json" --out "$work/e7"
  [ ! -e "$work/e3" ] && [ ! -e "$work/e5" ] && [ ! -e "$work/e8" ] && [ ! -e "$work/e14" ] &&
    pass "nothing written for refused options" ||
    fail "a refused run left a folder"
else
  out=$work/adaptive
  if "$cli" adaptive-test --source rig --rig-model "$work/quad.json" --out "$out" "${effects[@]}" \
    > "$work/run.log" 2>&1; then
    pass "adaptive-test ran"
  else
    fail "adaptive-test failed: $(tail -3 "$work/run.log")"
  fi
  python3 - "$out" << 'PY' && pass "verdict, shaker time and decision log" || fail "$(tail -5 "$work/run.log")"
import json, sys
out = sys.argv[1]
report = json.load(open(out + "/report.json"))
fixed_s = 2 * (2.5 + 26 * 10.0)  # the fixed campaign's stepped sines, lead-ins included
print("verdict", report["verdict"], "shaker time", report["shaker_time_s"], "s of", fixed_s,
      "levels", report["adaptive_test"]["levels"])
assert report["verdict"] == "quadratic-damping", report["verdict"]
assert report["shaker_time_s"] < fixed_s, report["shaker_time_s"]
assert report["adaptive_test"]["decided"], report["adaptive_test"]["stop_reason"]
assert report["adaptive_test"]["leader"] == "quadratic-damping"
lines = [json.loads(l) for l in open(out + "/decisions.jsonl")]
assert lines and lines[-1]["stop"] and not any(l["stop"] for l in lines[:-1])
for l in lines:
    for key in ("time_s", "shaker_time_s", "weights", "reason"):
        assert key in l, key
    assert abs(sum(l["weights"].values()) - 1.0) < 1e-9
for l in lines[:-1]:
    assert l["proposal"]["admissible"] and l["scores"], l
    assert " sigma in " in l["reason"], l["reason"]
PY
  n=$(ls "$out"/recordings/*.wav | wc -l)
  [ "$n" -ge 3 ] && pass "$n recordings" || fail "only $n recordings"
fi

[ $failures -eq 0 ] || { echo "$failures failure(s)" >&2; exit 1; }
echo "all passed"
