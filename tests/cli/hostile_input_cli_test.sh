#!/usr/bin/env bash
# oscilab-cli against hostile input:
#   hostile_input_cli_test.sh OSCILAB_CLI SOURCE_DIR
# Whatever a file, an option or a network peer holds, the command ends with exit status 2 and
# one line on stderr naming the problem, and leaves no partial output; a network frame is refused
# alone and the stream goes on.
source "$(dirname "$0")/cli_checks.sh"
pos=$src/samples/stepped_positive.flac

expect_absent() {  # description, paths...
  local what=$1
  shift
  local left=""
  for path in "$@"; do [ -e "$path" ] && left="$left $path"; done
  [ -z "$left" ] && pass "$what" || fail "$what: left$left"
}

# --- JSON nested 100 000 deep under an unknown key of a sidecar: refused, not a stack overflow.
cp "$pos" "$work/bomb.flac"
python3 - "$src/samples/stepped_positive.json" "$work/bomb.json" <<'PY'
import json, sys
sidecar = json.load(open(sys.argv[1]))
text = json.dumps(sidecar)
open(sys.argv[2], "w").write(text[:-1] + ', "junk": ' + "[" * 100000 + "]" * 100000 + "}")
PY
expect_error "info: a depth bomb in a sidecar" "bomb.json: JSON nested deeper than 64 levels" \
  "$cli" info "$work/bomb.flac"
expect_error "analyze: a depth bomb in a sidecar" "bomb.json: JSON nested deeper than 64 levels" \
  "$cli" analyze "$work/bomb.flac" --edc "$work/bomb_edc.csv"
expect_absent "analyze: no EDC table after a refused sidecar" "$work/bomb_edc.csv"
python3 -c "print('{\"mass_kg\": 0.26, \"terms\": [], \"x\": ' + '[' * 100000 + ']' * 100000 + '}')" \
  > "$work/bomb_model.json"
expect_error "hbm: a depth bomb in a model" "bomb_model.json: JSON nested deeper than 64 levels" \
  "$cli" hbm --model "$work/bomb_model.json" --freq 9 --f0 0.1:1 --out "$work/bomb_branch.csv"
expect_absent "hbm: no branch after a refused model" "$work/bomb_branch.csv"

# --- A network sender (the stream protocol, docs/stream-protocol.md) whose frames are given as
# arguments: hello, data:FIRST_SAMPLE:ROWS[:SEQUENCE] (sequence numbers counted on from the last,
# or as given), event:JSON, bomb-hello,
# bomb-event, bye. It connects as soon as the recorder listens.
cat > "$work/send.py" <<'PY'
import json, socket, struct, sys, time
port, sidecar_path = int(sys.argv[1]), sys.argv[2]
sidecar = json.load(open(sidecar_path))
# The excitation's frequency (the live EDC runs), its levels left to the stream's level events.
sidecar["excitation"] = {"type": "stepped-sine", "frequency_hz": 9.0}
deep = "[" * 100000 + "]" * 100000
def frame(kind, payload):
    return b"OSCS" + struct.pack("<BBHI", 1, kind, 0, len(payload)) + payload
out, sequence = b"", 0
for item in sys.argv[3:]:
    if item == "hello":
        out += frame(1, json.dumps({"protocol": "oscilab-stream/1", "stream_id": "s",
                                    "sidecar": sidecar}).encode())
    elif item == "bomb-hello":
        out += frame(1, ('{"protocol": "oscilab-stream/1", "junk": ' + deep + "}").encode())
    elif item == "bomb-event":
        out += frame(3, ('{"t_s": 0, "kind": "mark", "data": {"x": ' + deep + "}}").encode())
    elif item.startswith("event:"):
        out += frame(3, item[6:].encode())
    elif item.startswith("data:"):
        _, first, rows, *given = item.split(":")
        sequence = int(given[0]) if given else sequence
        values = [0.001 * i for i in range(2 * int(rows))]
        out += frame(2, struct.pack("<QQII", sequence, int(first), int(rows), 2) +
                     struct.pack("<%dd" % len(values), *values))
        sequence += 1
    elif item == "bye":
        out += frame(4, b"")
for _ in range(100):
    try:
        connection = socket.create_connection(("127.0.0.1", port))
        break
    except OSError:
        time.sleep(0.1)
connection.sendall(out)
connection.shutdown(socket.SHUT_WR)
connection.recv(1)
PY
record_from() {  # name, frames...: records what the sender sends into $work/NAME.wav
  local name=$1
  shift
  local port=$((20000 + RANDOM % 30000))
  timeout 60 "$cli" record --source "net:127.0.0.1:$port" --out "$work/$name.wav" --wait 30 \
    > "$work/$name.log" 2>&1 &
  local recorder=$!
  timeout 60 python3 "$work/send.py" "$port" "$src/samples/stepped_positive.json" "$@"
  wait $recorder
}
if record_from net_bomb bomb-hello hello data:0:512 bomb-event data:512:512 bye; then
  pass "record --source net: depth bombs in HELLO and EVENT frames, exit 0"
else
  fail "record net depth bomb: status $?, $(tail -3 "$work/net_bomb.log")"
fi
[ "$(grep -c '"kind":"malformed-frame".*nested deeper than 64 levels' "$work/net_bomb.events.jsonl")" -eq 2 ] \
  && pass "both bombs logged as malformed frames" \
  || fail "events: $(cut -c1-200 "$work/net_bomb.events.jsonl")"
grep -q '"kind":"source-ended"' "$work/net_bomb.events.jsonl" \
  && pass "the stream went on to its BYE" || fail "no source-ended event"
"$cli" info "$work/net_bomb.wav" > "$work/net_bomb.info" 2>&1 && grep -q "samples: *1024$" "$work/net_bomb.info" \
  && pass "both DATA frames recorded" || fail "net_bomb.wav: $(cat "$work/net_bomb.info")"

# --- Absurd numeric options: refused before anything is allocated or written.
neg=$src/samples/stepped_negative.flac
expect_error "simulate --hold 1e9" "more than the 5e+07 one run holds" \
  "$cli" simulate --hold 1e9 --out "$work/s1.flac"
expect_error "simulate --rate 1e9" "262.5 s at 1e+09 Hz" \
  "$cli" simulate --rate 1e9 --out "$work/s2.flac"
expect_error "simulate --test random --duration 1e9" "random excitation: duration 1e+09 s" \
  "$cli" simulate --test random --duration 1e9 --out "$work/s3.flac"
expect_error "simulate --freq 1e9 (beyond Nyquist)" "excitation frequency 1e+09 Hz is not below the Nyquist" \
  "$cli" simulate --freq 1e9 --out "$work/s4.flac"
expect_error "simulate --band 2:300 at 512 Hz" "band's upper edge 300 Hz is not below the Nyquist" \
  "$cli" simulate --test random --band 2:300 --out "$work/s5.flac"
expect_error "record --source rig --freq 1e9" "is not below the Nyquist frequency" \
  "$cli" record --source rig --freq 1e9 --speed 0 --duration 2 --out "$work/r1.wav"
expect_absent "a refused recording leaves no file" "$work/r1.wav" "$work/r1.json" \
  "$work/r1.events.jsonl" "$work/s4.flac" "$work/s5.flac"
expect_absent "simulate: nothing written" "$work/s1.flac" "$work/s1.json" "$work/s2.flac" \
  "$work/s3.flac"
expect_error "hbm --sweep-time 1e9" "amplitude sweep: 1e+09 s up" \
  "$cli" hbm --sweep-time 1e9 --sweep "$work/sweep.csv" --out "$work/b1.csv"
expect_error "hbm --map-step 0" "bifurcation map: levels: need" \
  "$cli" hbm --map-step 0 --map "$work/map.csv" --out "$work/b2.csv"
expect_error "hbm --samples -1" "samples: -1 must be 0" \
  "$cli" hbm --samples -1 --out "$work/b3.csv"
expect_absent "hbm: no branch, sweep or map CSV" "$work/b1.csv" "$work/sweep.csv" "$work/b2.csv" \
  "$work/map.csv" "$work/b3.csv"
expect_error "fit --evaluations 1e12" "--evaluations: 1000000000000 is more than 10000000" \
  "$cli" fit "$pos" "$neg" --evaluations 1000000000000 --out "$work/f1.json"
expect_error "fit --evaluations 2^66" "--evaluations: .* is more than 10000000" \
  "$cli" fit "$pos" "$neg" --evaluations 73786976294838206464 --out "$work/f2.json"
expect_error "fit --threads -1" "--threads: -1 must be 0 (all cores) to 1024" \
  "$cli" fit "$pos" "$neg" --threads -1 --out "$work/f3.json"
expect_error "fit --max-harmonics 5" "--max-harmonics: 5 must be in 15 … 63" \
  "$cli" fit "$pos" "$neg" --max-harmonics 5 --out "$work/f4.json"
expect_error "diagnose --threads -1" "--threads: -1 must be 0 (all cores) to 1024" \
  "$cli" diagnose "$pos" "$neg" --threads -1 --out "$work/diag"
expect_absent "fit, diagnose: nothing written" "$work/f1.json" "$work/f2.json" "$work/f3.json" \
  "$work/f4.json" "$work/diag"
expect_error "diagnose: a missing recording" "missing.flac: file not found" \
  "$cli" diagnose "$work/missing.flac" --out "$work/diag_bad"
expect_absent "diagnose: no folder made for a recording it cannot read" "$work/diag_bad"
expect_error "record --wait -1" "--wait: -1 s must be >= 0" \
  "$cli" record --source "net:127.0.0.1:$((20000 + RANDOM % 30000))" --wait -1 --out "$work/w.wav"
expect_absent "record --wait -1: nothing written" "$work/w.wav" "$work/w.json"
expect_error "record --source usb:3: an unknown kind, not a missing file" \
  "--source usb:3: unknown source kind \"usb:\"" "$cli" record --source usb:3 --out "$work/u.wav"
expect_absent "record --source usb:3: nothing written" "$work/u.wav" "$work/u.json"
# Options the parser refuses (unknown, not a number, missing) are bad input like any other.
expect_error "fit --evaluations abc" "oscilab-cli: .*--evaluations.*abc" \
  "$cli" fit "$pos" --evaluations abc --out "$work/p1.json"
expect_error "fit --no-such-option" "oscilab-cli: .*--no-such-option" \
  "$cli" fit "$pos" --no-such-option --out "$work/p2.json"
expect_error "record without --out" "oscilab-cli: .*--out.*required" "$cli" record --source rig
expect_absent "refused options: nothing written" "$work/p1.json" "$work/p2.json"
"$cli" --help > /dev/null 2>&1 && pass "--help still exits 0" || fail "--help: exit $?"

# A sender whose HELLO is refused (a rate no sidecar can have) is named with the reason when the
# wait ends, not taken for no sender at all; nothing is left.
python3 - "$src/samples/stepped_positive.json" "$work/fast_hello.json" <<'PY'
import json, sys
sidecar = json.load(open(sys.argv[1]))
sidecar["sample_rate_hz"] = 1e9
json.dump(sidecar, open(sys.argv[2], "w"))
PY
port=$((20000 + RANDOM % 30000))
timeout 60 python3 "$work/send.py" "$port" "$work/fast_hello.json" hello data:0:512 bye &
expect_error "record: a refused HELLO named when the wait ends" \
  "no usable sender within 2 s; the last was refused: .*sample_rate_hz: 1000000000.0 Hz is outside" \
  timeout 60 "$cli" record --source "net:127.0.0.1:$port" --wait 2 --out "$work/fast.wav"
wait
expect_absent "record: a refused HELLO leaves no file" "$work/fast.wav" "$work/fast.json" \
  "$work/fast.events.jsonl"

# At 4096 Hz a gap of 2^20 + 1024 samples (256 s) is past the receiver's bound in samples, which
# it runs through one by one: refused at once (it had held the recorder up for minutes).
python3 - "$src/samples/stepped_positive.json" "$work/khz_hello.json" <<'PY'
import json, sys
sidecar = json.load(open(sys.argv[1]))
sidecar["sample_rate_hz"] = 4096.0
json.dump(sidecar, open(sys.argv[2], "w"))
PY
port=$((20000 + RANDOM % 30000))
timeout 60 "$cli" record --source "net:127.0.0.1:$port" --wait 30 --out "$work/khz.wav" \
  > "$work/khz.log" 2>&1 &
recorder=$!
timeout 60 python3 "$work/send.py" "$port" "$work/khz_hello.json" hello data:0:512 \
  data:1049600:512 data:512:512 bye
wait $recorder && grep -q '"malformed-frame".*first_sample 1049600 is 256 s past .* 1048576 samples' \
  "$work/khz.events.jsonl" && "$cli" info "$work/khz.wav" 2>&1 | grep -q "samples: *1024$" \
  && pass "record at 4096 Hz: a gap of more than 2^20 samples refused, the stream kept" \
  || fail "record khz: $(tail -2 "$work/khz.log"; grep malformed "$work/khz.events.jsonl")"

# --- Absurd network fields: each frame refused alone (one malformed-frame event), the stream
# goes on, the clock never jumps, nothing beyond Nyquist reaches the analysis or the sidecar.
level() { echo "event:{\"t_s\": 1.0, \"kind\": \"level\", \"data\": $1}"; }
if record_from net_fields hello data:0:512 \
    "$(level '{"f0_n": 0.5, "frequency_hz": 1e9}')" \
    "$(level '{"f0_n": 0.5, "frequency_hz": 300}')" \
    "$(level '{"f0_n": "x", "frequency_hz": 9}')" \
    "$(level '{"f0_n": 0.5, "frequency_hz": 9, "steady_from_s": 1e300}')" \
    "$(level '{"f0_n": 0.5, "frequency_hz": 9, "steady_from_s": 2.5, "steady_to_s": 1.5}')" \
    "$(level '{"f0_n": 0.5, "frequency_hz": 9}')" \
    data:512:512 data:9223372036854775808:512 data:1024:512 bye; then
  pass "record --source net: absurd level events and a DATA clock jump, exit 0 (no hang)"
else
  fail "record net fields: status $?, $(tail -3 "$work/net_fields.log")"
fi
events=$work/net_fields.events.jsonl
for text in "frequency_hz 1e+09 is not in (0, 256) Hz" "frequency_hz 300 is not in (0, 256) Hz" \
    "f0_n is not a number" "steady_from_s 1e+300 is not a stream time" \
    "the steady window \[2.5, 1.5) s ends before it starts" \
    "DATA frame refused: first_sample 9223372036854775808 is 1.8e+16 s past"; do
  grep -q "\"malformed-frame\".*$text" "$events" && pass "refused: $text" \
    || fail "not refused: $text: $(cut -c1-160 "$events")"
done
grep -q '"kind":"source-ended","t_s":3.0' "$events" \
  && pass "the stream clock ends at 3 s: the jump never moved it" \
  || fail "clock: $(grep source-ended "$events")"
python3 - "$work/net_fields.json" <<'PY' && pass "the sidecar holds the one valid level" || fail "sidecar levels"
import json, sys
excitation = json.load(open(sys.argv[1]))["excitation"]
assert excitation["frequency_hz"] == 9.0, excitation
assert [level["f0_n"] for level in excitation["levels"]] == [0.5], excitation
PY
"$cli" info "$work/net_fields.wav" 2>&1 | grep -q "samples: *1536$" \
  && pass "the three valid DATA frames recorded" || fail "net_fields.wav samples"

# A DATA sequence far ahead (2^63, and 2^64 - 1 where the next one would wrap): each frame
# refused with one event, no hang, no blocks counted lost, the stream and its clock go on.
if record_from net_sequence hello data:0:512 data:512:512:9223372036854775808 \
    data:512:512:18446744073709551615 data:512:512:1 bye; then
  pass "record --source net: DATA sequences 2^63 and 2^64-1, exit 0 (no hang)"
else
  fail "record net sequence: status $?, $(tail -3 "$work/net_sequence.log")"
fi
events=$work/net_sequence.events.jsonl
for text in "sequence 9223372036854775808 is 9223372036854775807 blocks past the next expected 1" \
    "sequence 18446744073709551615 is"; do
  grep -q "\"malformed-frame\".*DATA frame refused: $text" "$events" && pass "refused: $text" \
    || fail "not refused: $text: $(cut -c1-160 "$events")"
done
grep -q '"kind":"\(gap\|late\|duplicate\)"' "$events" && fail "a refused sequence counted: $(grep -m1 '"kind":"\(gap\|late\|duplicate\)"' "$events")" \
  || pass "no gap, late or duplicate block from a refused sequence"
grep -q '"kind":"source-ended","t_s":2.0' "$events" && "$cli" info "$work/net_sequence.wav" 2>&1 \
  | grep -q "samples: *1024$" && pass "both valid DATA frames recorded, the clock at 2 s" \
  || fail "net_sequence: $(grep source-ended "$events")"

# --- Degenerate data said, not scored: a dead or constant channel, swapped roles, a steady
# window shorter than a cycle, levels past the record's end. Each level gets a flag and the
# report a note; a record none of whose levels measures anything is refused with one line.
"$cli" import "$pos" --out "$work/deg.csv" > /dev/null
python3 - "$work" <<'PY'
import copy, csv, json, sys
work = sys.argv[1]
rows = list(csv.reader(open(work + "/deg.csv")))
sidecar = json.load(open(work + "/deg.json"))
def write(name, column=None, value=None, edit=None):
    with open("%s/%s.csv" % (work, name), "w") as out:
        for i, row in enumerate(rows):
            if i > 0 and column is not None:
                row = row[:column] + [value] + row[column + 1:]
            out.write(",".join(row) + "\n")
    side = copy.deepcopy(sidecar)
    if edit:
        edit(side)
    json.dump(side, open("%s/%s.json" % (work, name), "w"))
def swap(side):
    side["channels"][0]["role"], side["channels"][1]["role"] = "mass", "base"
def short(side):
    side["excitation"]["levels"][0]["end_s"] = side["excitation"]["levels"][0]["start_s"] + 0.001
def beyond(side):
    for level in side["excitation"]["levels"]:
        level["start_s"] += 1000
        level["end_s"] += 1000
def scale(side):
    side["channels"][1]["scale"] = 1e300
write("zero_base", 1, "0")
write("const_base", 1, "80")  # counts: the accelerometer's bias alone
write("const_mass", 2, "236663")
write("swapped", edit=swap)
write("short", edit=short)
write("beyond", edit=beyond)
write("scale", edit=scale)
PY
for case in "zero_base:base-constant: the base channel shows no motion above its noise" \
    "const_base:base-constant" \
    "const_mass:mass-constant: the mass channel shows no motion above its noise" \
    "swapped:negative-edc: .* roles (or a channel's sign) are likely swapped" \
    "beyond:beyond-record: the sidecar's steady window reaches past the end"; do
  name=${case%%:*}
  text=${case#*:}
  flag=${text%%:*}
  expect_error "analyze: $name refused" "$name.csv: no usable level: 26 of 26 levels flagged $text" \
    "$cli" analyze "$work/$name.csv" --edc "$work/${name}_edc.csv"
  [ "$(grep -c "[ ;]$flag\$" "$work/err.out")" -eq 26 ] \
    && grep -q "^note: 26 of 26 levels flagged $flag" "$work/err.out" \
    && pass "analyze: $name: each level flagged $flag in the report, with a note" \
    || fail "analyze $name report: $(head -4 "$work/err.out")"
  expect_absent "analyze: $name: no EDC table" "$work/${name}_edc.csv"
done
expect_error "fit: a record with a dead base channel" "zero_base.csv: no usable level: 26 of 26" \
  "$cli" fit "$work/zero_base.csv" "$neg" --evaluations 20 --out "$work/deg_fit.json"
expect_error "diagnose: a record with swapped roles" "swapped.csv: no usable level: 26 of 26" \
  "$cli" diagnose "$work/swapped.csv" "$neg" --out "$work/deg_diag"
expect_error "export --edc-mat: a record with a constant mass channel" \
  "const_mass.csv: no usable level: 26 of 26" \
  "$cli" export "$work/const_mass.csv" --edc-mat "$work/deg.mat"
expect_absent "fit, diagnose, export: nothing written for a degenerate record" \
  "$work/deg_fit.json" "$work/deg_diag" "$work/deg.mat"
# The same record replayed live: the live table flags each level and the report notes it.
"$cli" record --source "file:$work/zero_base.csv" --speed 0 --out "$work/live_dead.wav" \
  --edc "$work/live_dead_edc.csv" > "$work/live_dead.out" 2>&1
[ "$(grep -c ',base-constant$' "$work/live_dead_edc.csv")" -eq 26 ] \
  && grep -q "^note: 26 of 26 levels flagged base-constant" "$work/live_dead.out" \
  && pass "record --edc: a dead base channel's live levels flagged base-constant, with a note" \
  || fail "record --edc dead base: $(tail -2 "$work/live_dead.out")"
expect_error "analyze: a scale of 1e300" \
  "scale.json: channels\[1\].scale: 1e+300 is outside the magnitudes a calibration can have" \
  "$cli" analyze "$work/scale.csv" --edc "$work/scale_edc.csv"
expect_absent "analyze: no EDC table after an absurd scale" "$work/scale_edc.csv"
if "$cli" analyze "$work/short.csv" --edc "$work/short_edc.csv" > "$work/short.out" 2>&1 \
    && [ "$(wc -l < "$work/short_edc.csv")" -eq 27 ] \
    && sed -n 2p "$work/short_edc.csv" | grep -q ",3.001000,0,0,0,few-cycles;short-window$" \
    && [ "$(grep -c ',1,$' "$work/short_edc.csv")" -eq 25 ] \
    && grep -q "^note: 1 of 26 levels flagged short-window" "$work/short.out"; then
  pass "analyze: a 1 ms steady window is a row flagged short-window, not usable, with a note"
else
  fail "analyze short window: $(head -2 "$work/short_edc.csv"; head -3 "$work/short.out")"
fi

# --- The live status line is for a person at a terminal: with stderr a file (a log, a service),
# a good recording leaves it empty, and the final counts go to stdout with the rest.
"$cli" record --source rig --speed 0 --duration 3 --out "$work/quiet.wav" > "$work/quiet.out" \
  2> "$work/quiet.err"
status=$?
[ $status -eq 0 ] && [ ! -s "$work/quiet.err" ] && grep -q "samples 1536 .* levels 0$" "$work/quiet.out" \
  && pass "record: no status line on a stderr that is not a terminal" \
  || fail "record status: exit $status, stderr $(head -c 200 "$work/quiet.err")"

# --- A recording cut short (a power cut before its header caught up, a copy stopped short): the
# readers refuse it naming the repair, and recover keeps every whole sample before the cut.
cp "$work/quiet.wav" "$work/cut.wav"
cp "$work/quiet.json" "$work/cut.json"
truncate -s $(($(stat -c %s "$work/cut.wav") - 16 * 100 - 5)) "$work/cut.wav"  # 2 channels
expect_error "info: a recording cut short" "cut.wav: truncated: .*(oscilab-cli recover" \
  "$cli" info "$work/cut.wav"
"$cli" recover "$work/cut.wav" > "$work/recover.out" 2>&1 \
  && grep -q "recovered 1435 samples per channel" "$work/recover.out" \
  && "$cli" info "$work/cut.wav" 2>&1 | grep -q "samples: *1435$" \
  && pass "recover: the cut recording opens with the 1435 whole samples before the cut" \
  || fail "recover: $(cat "$work/recover.out")"
"$cli" recover "$work/quiet.wav" 2>&1 | grep -q "whole (1536 samples per channel); nothing to" \
  && pass "recover: a whole recording is left as it is" || fail "recover of a whole recording"
expect_error "recover: not even a header" "header.wav: not a sound file" \
  bash -c "head -c 40 '$work/quiet.wav' > '$work/header.wav' && cp '$work/quiet.json' \
    '$work/header.json' && '$cli' recover '$work/header.wav'"

# --- Outputs never over inputs, and all or nothing.
# A fixed model-error floor: the sigma budget is not what this checks (half a minute under ASan).
"$cli" fit "$pos" "$neg" --evaluations 20 --threads 1 --model-error 0.01 --out "$work/fit1.json" > /dev/null 2>&1
cp "$work/fit1.json" "$work/fit1.before"
expect_error "merge: --out one of its inputs" "--out: $work/fit1.json is an input of this command" \
  "$cli" merge "$work/fit1.json" --out "$work/fit1.json"
expect_error "merge: --out one of its inputs by another path" "is an input of this command" \
  "$cli" merge "$work/fit1.json" --out "$work/nowhere/../fit1.json"
cmp -s "$work/fit1.json" "$work/fit1.before" && pass "merge: the input FIT JSON is intact" \
  || fail "merge overwrote its input"
cp "$pos" "$work/run.flac"
cp "$src/samples/stepped_positive.json" "$work/run.json"
expect_error "analyze: --summary over the recording's sidecar" "--summary: $work/run.json is an input" \
  "$cli" analyze "$work/run.flac" --summary "$work/run.json"
expect_error "fit: --out over a recording" "--out: $work/run.flac is an input" \
  "$cli" fit "$work/run.flac" "$neg" --out "$work/run.flac"
cmp -s "$work/run.json" "$src/samples/stepped_positive.json" && cmp -s "$work/run.flac" "$pos" \
  && pass "analyze, fit: recording and sidecar intact" || fail "an input was overwritten"
ls "$work" | grep -q "\.tmp\." && fail "temporaries left: $(ls "$work" | grep tmp)" || pass "no temporary left"

# A full disk: a small file system made for the test (root only; skipped elsewhere).
small=$work/small
mkdir -p "$small"
if mount -t tmpfs -o size=256k tmpfs "$small" 2> /dev/null; then
  trap 'umount "$small" 2> /dev/null; kill $(jobs -p) 2> /dev/null; rm -rf "$work"' EXIT
  cat /dev/zero > "$small/fill" 2> /dev/null  # until the file system is full
  expect_error "record on a disk already full" "x0.wav: cannot write: .*No space left on device" \
    "$cli" record --source rig --speed 0 --duration 5 --out "$small/x0.wav"
  [ "$(ls "$small")" = "fill" ] && pass "record on a disk already full: no empty WAV left" \
    || fail "left: $(ls -l "$small")"
  expect_error "analyze on a full disk" "No space left on device" \
    "$cli" analyze "$pos" --edc "$small/e.csv" --cycles "$small/c.csv"
  expect_absent "analyze on a full disk: neither table nor temporary left" "$small/e.csv" "$small/c.csv"
  [ "$(ls "$small")" = "fill" ] && pass "full disk: nothing but the filler" || fail "left: $(ls "$small")"
  expect_error "merge on a full disk" "No space left on device" \
    "$cli" merge "$work/fit1.json" "$work/fit1.json" "$work/fit1.json" --out "$small/m.csv"
  [ "$(ls "$small")" = "fill" ] && pass "merge on a full disk: nothing left" || fail "left: $(ls "$small")"
  expect_error "hbm on a full disk" "b.csv: write failed: No space left on device" \
    "$cli" hbm --out "$small/b.csv"
  expect_error "model on a full disk" "write failed: No space left on device" \
    "$cli" model paper --out "$small/m.json" --summary "$small/ms.json"
  [ "$(ls "$small")" = "fill" ] && pass "hbm, model on a full disk: nothing left" \
    || fail "left: $(ls "$small")"
  rm -f "$small/fill"
  # Room for the recording (6 kB) but not for its truth (280 kB): none of the four files stays.
  expect_error "simulate --truth on a full disk" "s.truth.csv: write failed: No space left" \
    "$cli" simulate --levels 0.5:0.1:0.5 --hold 2 --truth --out "$small/s.flac"
  [ -z "$(ls "$small")" ] && pass "simulate --truth on a full disk: nothing left" \
    || fail "left: $(ls "$small")"
  # The recorder filling the disk: it stops cleanly, says so once, and leaves a recording whose
  # header matches what was written, so that it opens.
  expect_error "record on a full disk" "x.wav: write failed: .*No space left on device" \
    "$cli" record --source rig --speed 0 --duration 600 --out "$small/x.wav"
  "$cli" info "$small/x.wav" > "$work/full_info.txt" 2>&1 && grep -q "samples: *[1-9]" "$work/full_info.txt" \
    && pass "record on a full disk: the recording opens with what was written" \
    || fail "record on a full disk: $(head -2 "$work/full_info.txt")"
  grep -q '"kind":"error".*recording stopped: .*No space left on device' "$small/x.events.jsonl" \
    && pass "record on a full disk: the error is in the event log" \
    || fail "event log: $(cut -c1-120 "$small/x.events.jsonl")"
  ls "$small" | grep -q "\.tmp\." && fail "temporaries left: $(ls "$small")" \
    || pass "record on a full disk: no temporary left"
else
  echo "skipped: the full-disk checks (mounting a small tmpfs needs root)"
fi

echo "$passes passed, $failures failed"
[ $failures -eq 0 ]
