#!/usr/bin/env bash
# oscilab-cli plant and drive on a real jackd (dummy backend):
#   drive_cli_test.sh OSCILAB_CLI SOURCE_DIR [drive|adaptive]
# `drive`: the plant plays the paper's oscillator on a shaker in real time; `drive` runs a stepped
# sine of two levels through JACK ports, each on target within 10 cycles of its ramp, its events
# logged; a crossed limit ends it with one line naming the limit's option (exit 2); absurd options
# and a missing port are refused in one line.
# `adaptive` (a study, about 4 minutes of real time): the plant plays the paper's model with a
# hidden quadratic damping (c2 = 6 N s^2/m^2) in its positive well, and `adaptive-test --source
# jack:` drives it through JACK: it must name quadratic-damping in less shaker time than the fixed
# grid's one well (26 levels of 10 s).
source "$(dirname "$0")/cli_checks.sh"
repair_jack_metadata
mode=${3:-drive}
server=oscilab-cli-drive-$$
jackd --no-realtime -n "$server" -d dummy -r 48000 -p 256 > "$work/jackd.log" 2>&1 &
jackd_pid=$!
trap 'kill $(jobs -p) 2>/dev/null; wait 2>/dev/null; rm -rf "$work"' EXIT

# The plant, once the server accepts clients (10 s at most).
plant_model=paper
if [ "$mode" = adaptive ]; then
  "$cli" model paper --out "$work/paper.json" > /dev/null
  python3 - "$work/paper.json" "$work/quad.json" << 'PY'
import json, sys
model = json.load(open(sys.argv[1]))
model["terms"].append({"type": "quadratic-damping", "c2_ns2_m2": 6.0})
json.dump(model, open(sys.argv[2], "w"))
PY
  plant_model=$work/quad.json
fi
for _ in $(seq 100); do
  "$cli" plant --jack-server "$server" --model "$plant_model" --duration 900 > "$work/plant.log" 2>&1 &
  plant_pid=$!
  sleep 0.1
  for _ in $(seq 20); do grep -q "plant running" "$work/plant.log" && break; sleep 0.05; done
  grep -q "plant running" "$work/plant.log" && break
  kill $plant_pid 2>/dev/null; wait $plant_pid 2>/dev/null
done
grep -q "plant running at 48000 Hz" "$work/plant.log" && pass "plant runs on jackd" \
  || fail "plant: $(cat "$work/plant.log") $(cat "$work/jackd.log")"

# drive_on SERVER POSITION_PORT FREQ_HZ OPTIONS...: the drive of the plant's ports.
drive_on() {
  local on=$1 position=$2 freq=$3
  shift 3
  "$cli" drive --jack-server "$on" --drive oscilab-plant:drive \
    --acceleration oscilab-plant:acceleration --position "$position" \
    --acceleration-scale 50 --position-scale 0.1 --mass 0.26 --freq "$freq" --ramp 0.5 \
    --gain-guess 63 "$@"
}
drive=(drive_on "$server" oscilab-plant:position 9)

if [ "$mode" = adaptive ]; then
  out=$work/adaptive
  if "$cli" adaptive-test --source jack:oscilab-plant:acceleration,oscilab-plant:position \
      --drive jack:oscilab-plant:drive --jack-server "$server" --acceleration-scale 50 \
      --position-scale 0.1 --wells positive --hold 4 --lead-in 1 --gain-guess 63 \
      --effects quadratic-damping,cubic-damping,quintic-stiffness --out "$out" > "$work/run.log" 2>&1; then
    pass "adaptive-test through JACK ran"
  else
    fail "adaptive-test through JACK: $(tail -3 "$work/run.log")"
  fi
  python3 - "$out" << 'PY' && pass "verdict, shaker time and drive events" || fail "$(tail -5 "$work/run.log")"
import json, sys
out = sys.argv[1]
report = json.load(open(out + "/report.json"))
fixed_s = 2.5 + 26 * 10.0  # the fixed grid's stepped sine in one well, its lead-in included
print("verdict", report["verdict"], "shaker time", report["shaker_time_s"], "s of", fixed_s,
      "levels", report["adaptive_test"]["levels"])
assert report["verdict"] == "quadratic-damping", report["verdict"]
assert report["adaptive_test"]["leader"] == "quadratic-damping"
assert report["shaker_time_s"] < fixed_s, report["shaker_time_s"]
events = [json.loads(l) for l in open(out + "/drive_events.jsonl")]
on = [e for e in events if e["state"] == "on_target"]
assert len(on) >= report["adaptive_test"]["levels"], (len(on), report["adaptive_test"]["levels"])
assert not any(e["state"] == "aborted" for e in events)
PY
  kill $plant_pid 2>/dev/null; wait $plant_pid 2>/dev/null
  kill $jackd_pid 2>/dev/null; wait $jackd_pid 2>/dev/null
  echo "$passes passed, $failures failed"
  [ "$failures" -eq 0 ]
  exit
fi
if "${drive[@]}" --levels 0.5,1.5 --hold 0.5 --events "$work/drive.jsonl" > "$work/drive.log" 2>&1; then
  pass "drive exits 0"
else
  fail "drive: $(cat "$work/drive.log")"
fi
[ "$(grep -c "on target after" "$work/drive.log")" -eq 2 ] && pass "two levels on target" \
  || fail "levels on target: $(cat "$work/drive.log")"
grep -q "ramped down and stopped" "$work/drive.log" && pass "ramped down" || fail "no ramp down"
# The event log: one JSON object per line, on target within 10 cycles, idle at the end.
python3 - "$work/drive.jsonl" <<'PY' && pass "event log: on target within 10 cycles, idle last" || fail "event log: $(cat "$work/drive.jsonl")"
import json, sys
lines = [json.loads(l) for l in open(sys.argv[1])]
on = [l for l in lines if l["state"] == "on_target"]
assert len(on) >= 2, on
assert all(1 <= l["cycles"] <= 10 for l in on), on
assert all(abs(l["measured_m_s2"] / l["target_m_s2"] - 1) <= 0.01 for l in on), on
assert lines[0]["state"] == "ramping" and lines[-1]["state"] == "idle", lines
assert all(l["event"] == "drive" for l in lines)
PY

# A limit crossed: exit 2, one line naming the option, the drive at zero (the next run starts).
expect_error "--max-acceleration aborts" "^oscilab-cli: --max-acceleration: the table acceleration reached" \
  "${drive[@]}" --levels 2.0 --hold 0.5 --max-acceleration 5
expect_error "--max-drive aborts" "^oscilab-cli: --max-drive: the level needs a drive of" \
  "${drive[@]}" --levels 2.7 --hold 0.5 --max-drive 0.05
# Absurd options and missing ports.
expect_error "a missing port" "^oscilab-cli: port \"oscilab-plant:nothing\" does not exist" \
  drive_on "$server" oscilab-plant:nothing 9 --levels 1
expect_error "a level above the rate's eighth" "^oscilab-cli: --levels 1.000000: drive level: the frequency" \
  drive_on "$server" oscilab-plant:position 1e9 --levels 1
expect_error "no such server" "^oscilab-cli: JACK server \"oscilab-none-$$\" is not running" \
  drive_on "oscilab-none-$$" oscilab-plant:position 9 --levels 1
expect_error "plant: no such server" "^oscilab-cli: --jack-server: JACK server" \
  "$cli" plant --jack-server "oscilab-none-$$"
"${drive[@]}" --levels 1 --max-drive 2 > "$work/parse.out" 2> "$work/parse.log"
[ $? -ne 0 ] && grep -q "max-drive" "$work/parse.log" && pass "--max-drive 2 refused by the parser" \
  || fail "--max-drive 2: $(cat "$work/parse.log")"

kill $plant_pid 2>/dev/null; wait $plant_pid 2>/dev/null
kill $jackd_pid 2>/dev/null; wait $jackd_pid 2>/dev/null
echo "$passes passed, $failures failed"
[ "$failures" -eq 0 ]
