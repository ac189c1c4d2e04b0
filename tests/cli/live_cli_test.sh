#!/usr/bin/env bash
# oscilab-cli record and stream from the command line:
#   live_cli_test.sh OSCILAB_CLI SOURCE_DIR
# A sample streamed over TCP and recorded on the other side must analyse exactly as the sample
# itself (lossless); the rig records unattended; SIGTERM ends a recording cleanly; bad input
# ends with one line and exit status 2.
source "$(dirname "$0")/cli_checks.sh"
repair_jack_metadata
pos=$src/samples/stepped_positive.flac

# The rig, unattended, as fast as possible: a stepped sine of three levels, recorded.
if "$cli" record --source rig --levels 0.5:0.5:1.5 --hold 6 --lead-in 1 --speed 0 \
    --duration 20 --out "$work/rig.wav" --edc "$work/rig_edc.csv" \
    --status-log "$work/rig_status.csv" --status-every 0.01 > "$work/rig.log" 2>&1; then
  pass "record --source rig exits 0"
else
  fail "record --source rig: $(tail -3 "$work/rig.log")"
fi
[ -f "$work/rig.json" ] && [ -f "$work/rig.events.jsonl" ] && pass "sidecar and event log written" \
  || fail "sidecar or event log missing"
grep -q "3 level(s)" "$work/rig.log" && pass "three live levels" || fail "live levels: $(grep EDC "$work/rig.log")"
# The status log: its header, a row at least at the start and one at the end; stream time and
# samples never go back; the last row holds the final counts the run printed.
status=$work/rig_status.csv
head -1 "$status" | grep -q "^wall_s,stream_s,samples,gaps,.*,edc_latency_s,edc_latency_median_s,edc_latency_max_s$" \
  && pass "status log: header" || fail "status log header: $(head -1 "$status")"
rows=$(($(wc -l < "$status") - 1))
[ "$rows" -ge 2 ] && pass "status log: $rows rows" || fail "status log: $rows rows"
awk -F, 'NR > 2 && ($2 < s || $3 < n) { bad = 1 } NR > 1 { s = $2; n = $3 } END { exit bad }' "$status" \
  && pass "status log: stream time and samples never go back" || fail "status log goes back: $(cat "$status")"
recorded=$(sed -n 's/^recorded .*: \([0-9]*\) samples.*/\1/p' "$work/rig.log")
last_samples=$(tail -1 "$status" | cut -d, -f3)
[ -n "$recorded" ] && [ "$last_samples" -ge "$recorded" ] \
  && pass "status log: the last row counts every recorded sample ($last_samples)" \
  || fail "status log: last row $last_samples samples, recorded $recorded"
live_cycles=$(sed -n 's/^live EDC: .*level(s), \([0-9]*\) cycle(s).*/\1/p' "$work/rig.log")
[ "$(tail -1 "$status" | cut -d, -f14)" = "$live_cycles" ] \
  && pass "status log: the last row's cycles are the live EDC's ($live_cycles)" \
  || fail "status log cycles: $(tail -1 "$status" | cut -d, -f14) against $live_cycles"
"$cli" analyze "$work/rig.wav" --edc "$work/rig_offline.csv" > /dev/null 2>&1
if [ "$(cut -d, -f3 "$work/rig_edc.csv" | tail -n +2)" = "$(cut -d, -f3 "$work/rig_offline.csv" | tail -n +2)" ]; then
  pass "live EDC = offline EDC of the recording"
else
  fail "live and offline EDC differ: $(paste -d' ' "$work/rig_edc.csv" "$work/rig_offline.csv")"
fi

# A sample streamed to a listening recorder, as fast as it takes it: lossless end to end.
port=$((20000 + RANDOM % 30000))
"$cli" record --source "net:127.0.0.1:$port" --out "$work/net.wav" --wait 30 \
  > "$work/net.log" 2>&1 &
recorder=$!
for _ in $(seq 50); do
  "$cli" stream "$pos" --to "127.0.0.1:$port" --speed 0 > "$work/stream.log" 2>&1 && break
  sleep 0.2
done
if wait $recorder; then pass "record --source net exits 0"; else fail "record net: $(tail -3 "$work/net.log")"; fi
grep -q "streamed 2101 block(s)" "$work/stream.log" && pass "stream sends every block" \
  || fail "stream: $(cat "$work/stream.log")"
"$cli" analyze "$pos" --edc "$work/orig.csv" > /dev/null 2>&1
"$cli" analyze "$work/net.wav" --edc "$work/net.csv" > /dev/null 2>&1
if cmp -s <(cut -d, -f1-5 "$work/orig.csv") <(cut -d, -f1-5 "$work/net.csv"); then
  pass "the streamed recording analyses exactly as the sample (26 levels)"
else
  fail "streamed EDC differs: $(diff <(cut -d, -f1-5 "$work/orig.csv") <(cut -d, -f1-5 "$work/net.csv") | head -4)"
fi

# SIGTERM ends a real-time recording cleanly, with what was recorded so far.
"$cli" record --source rig --out "$work/term.wav" > "$work/term.log" 2>&1 &
recorder=$!
for _ in $(seq 100); do [ -s "$work/term.wav" ] && break; sleep 0.1; done
sleep 1
kill -TERM $recorder
if wait $recorder; then pass "SIGTERM: exit 0"; else fail "SIGTERM: $(tail -2 "$work/term.log")"; fi
grep -q "stopped by a signal" "$work/term.log" && pass "SIGTERM: says so" || fail "SIGTERM log: $(cat "$work/term.log")"
"$cli" info "$work/term.wav" > /dev/null 2>&1 && pass "SIGTERM: the recording opens" || fail "SIGTERM recording unreadable"

# Bad input: one line naming the problem, exit status 2, nothing left behind.
expect_error "a FLAC live recording is refused" ".wav, .w64 or .rf64" \
  "$cli" record --source rig --duration 1 --speed 0 --out "$work/x.flac"
expect_error "a missing replay file is named" "missing.wav" \
  "$cli" record --source file:"$work/missing.wav" --out "$work/y.wav"
expect_error "a bad port is named" "99999" \
  "$cli" record --source net:127.0.0.1:99999 --out "$work/y.wav"
expect_error "nobody listening" "connect to 127.0.0.1:1" \
  "$cli" stream "$pos" --to 127.0.0.1:1
expect_error "no sender within --wait" "no sender connected within" \
  "$cli" record --source "net:127.0.0.1:$((port + 1))" --wait 0.5 --out "$work/z.wav"
expect_error "a JACK source needs its calibration" "give the calibration with --sidecar" \
  "$cli" record --source jack:system:capture_1,system:capture_2 --out "$work/j.wav"
echo '{"sample_rate_hz": 512, "channels": [
  {"name": "b", "role": "base", "quantity": "acceleration", "unit": "V", "scale": 9.80665},
  {"name": "y", "role": "mass", "quantity": "displacement", "unit": "V", "scale": 0.1}]}' \
  > "$work/cal.json"
expect_error "no JACK server of that name" "JACK server \"oscilab-cli-test-none\" is not running" \
  "$cli" record --source jack:system:capture_1,system:capture_2 --jack-server oscilab-cli-test-none \
  --sidecar "$work/cal.json" --out "$work/j.wav"
expect_error "stream does not take a JACK source" "jack: is for record" \
  "$cli" stream jack:system:capture_1,system:capture_2 --to 127.0.0.1:1
[ ! -e "$work/x.flac" ] && pass "nothing written for the refused FLAC" || fail "x.flac written"
expect_error "--status-every 0 is refused" "--status-every: 0 s must be 0.01 to 86400" \
  "$cli" record --source rig --duration 1 --speed 0 --out "$work/s0.wav" \
  --status-log "$work/s0.csv" --status-every 0
expect_error "a status log that cannot be written is named" "--status-log: $work/nowhere/s.csv: cannot write" \
  "$cli" record --source rig --duration 1 --speed 0 --out "$work/s1.wav" --status-log "$work/nowhere/s.csv"
expect_error "the status log over the recording is refused" "is the recording" \
  "$cli" record --source rig --duration 1 --speed 0 --out "$work/s2.wav" --status-log "$work/s2.wav"
expect_error "no sender within --wait leaves no status log" "no sender connected within" \
  "$cli" record --source "net:127.0.0.1:$((port + 2))" --wait 0.5 --out "$work/s3.wav" \
  --status-log "$work/s3.csv"
ls "$work" | grep -q "^s[0-3]\." && fail "refused status-log runs left: $(ls "$work" | grep "^s[0-3]\.")" \
  || pass "refused status-log runs leave no file"

echo "$passes passed, $failures failed"
[ $failures -eq 0 ]
