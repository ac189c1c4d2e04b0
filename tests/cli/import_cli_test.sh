#!/usr/bin/env bash
# oscilab-cli info and import: what a file without a sidecar holds and a drafted sidecar; a
# recording imported into another container analyses to the same EDC table; the error paths.
# The readers themselves are tested in depth by daq_recording_tests and the formats' tests.
#   import_cli_test.sh OSCILAB_CLI SOURCE_DIR
source "$(dirname "$0")/cli_checks.sh"
cp "$src/samples/stepped_positive.flac" "$src/samples/stepped_positive.json" "$work/"
pos=$work/stepped_positive.flac

# Import to CSV and to 64-bit WAV: the same stored values, so the same EDC table to the last digit.
for ext in csv wav; do
  if "$cli" import "$pos" --out "$work/imported.$ext" > "$work/import.log" 2>&1; then
    pass "import to .$ext exits 0"
  else
    fail "import to .$ext: $(cat "$work/import.log")"
  fi
  grep -q "2 channels, 134401 samples from FLAC" "$work/import.log" && pass "import says what" ||
    fail "import message: $(cat "$work/import.log")"
  "$cli" analyze "$pos" --edc "$work/edc_flac.csv" > /dev/null 2>&1
  "$cli" analyze "$work/imported.$ext" --edc "$work/edc_$ext.csv" > /dev/null 2>&1
  # The tables name their recording; all else must be equal.
  sed -i "s/stepped_positive\.flac/REC/; s/imported\.$ext/REC/" "$work/edc_flac.csv" "$work/edc_$ext.csv"
  if [ -s "$work/edc_flac.csv" ] && cmp -s "$work/edc_flac.csv" "$work/edc_$ext.csv"; then
    pass "the .$ext import gives the FLAC's EDC table byte for byte"
  else
    fail "EDC table of the .$ext import differs: $(diff "$work/edc_flac.csv" "$work/edc_$ext.csv" | head -4)"
  fi
done

# A sidecar given on the command line instead of beside the file.
mkdir "$work/elsewhere"
cp "$pos" "$work/elsewhere/raw.flac"
if "$cli" import "$work/elsewhere/raw.flac" --sidecar "$work/stepped_positive.json" \
  --out "$work/from_given.wav" > "$work/given.log" 2>&1; then
  pass "import --sidecar"
else
  fail "import --sidecar: $(cat "$work/given.log")"
fi

# info on a file without a sidecar: its signals and a draft; --draft-sidecar writes a valid one.
"$cli" info "$work/elsewhere/raw.flac" > "$work/info.log" 2>&1
rc=$?
[ $rc -eq 0 ] && pass "info without a sidecar exits 0" || fail "info exit $rc: $(cat "$work/info.log")"
grep -q "channel 2: 134401 samples, Signed 24 bit PCM, unit not stated, 512 Hz" "$work/info.log" &&
  pass "info lists the signals" || fail "info signals: $(cat "$work/info.log")"
grep -q "No sidecar" "$work/info.log" && grep -q '"sample_rate_hz": 512.0' "$work/info.log" &&
  pass "info drafts a sidecar with the file's rate" || fail "info draft: $(cat "$work/info.log")"
"$cli" info "$work/elsewhere/raw.flac" --draft-sidecar "$work/elsewhere/raw.json" > /dev/null 2>&1
"$cli" info "$work/elsewhere/raw.flac" > "$work/info2.log" 2>&1 &&
  grep -q "Recording: .*raw.flac" "$work/info2.log" && pass "the drafted sidecar reads" ||
  fail "drafted sidecar: $(cat "$work/info2.log")"

# One file per excitation level, as many labs record: the files make one EDC table, one row
# per file, and fit together like one stepped-sine record.
for f0 in 0.5 1.0 1.5; do
  "$cli" simulate --levels "$f0" --hold 8 --lead-in 1 --seed 3 --out "$work/level_$f0.flac" > /dev/null 2>&1 ||
    fail "simulate level $f0"
done
levels=("$work"/level_0.5.flac "$work"/level_1.0.flac "$work"/level_1.5.flac)
if "$cli" analyze "${levels[@]}" --edc "$work/levels.csv" > "$work/levels.log" 2>&1; then
  rows=$(tail -n +2 "$work/levels.csv" | awk -F, '{ printf "%.1f/%s ", $2, $6 }')
  [ "$rows" = "0.5/level_0.5.flac 1.0/level_1.0.flac 1.5/level_1.5.flac " ] &&
    pass "three level files make one EDC table, a row each" || fail "level rows: $rows"
else
  fail "analyze of level files: $(tail -3 "$work/levels.log")"
fi
# A fixed model-error floor: the sigma budget's harmonic-balance references (a minute under the
# sanitizers) are not what this checks.
if "$cli" fit "${levels[@]}" --evaluations 60 --model-error 0.01 --out "$work/levels_fit.json" > "$work/fit.log" 2>&1 &&
  grep -q '"levels"' "$work/levels_fit.json"; then
  pass "the level files fit together"
else
  fail "fit of level files: $(tail -3 "$work/fit.log")"
fi

# Errors: one line, exit 2, nothing written (expect_error of cli_checks.sh).
expect_error "the draft is not written over a file" "raw.json: exists; the draft is not written over a file" \
  "$cli" info "$work/elsewhere/raw.flac" --draft-sidecar "$work/elsewhere/raw.json"
printf 'just some words\n' > "$work/notes.xyz"
expect_error "an unknown format is named" "notes.xyz: not a format Oscilab reads" \
  "$cli" info "$work/notes.xyz"
expect_error "import into an unknown container" 'unknown container ".xyz"' \
  "$cli" import "$pos" --out "$work/out.xyz"
[ ! -e "$work/out.xyz" ] && [ ! -e "$work/out.json" ] && pass "nothing written on error" ||
  fail "files left after a refused import"
sed 's/"y"/"laser"/' "$work/stepped_positive.json" > "$work/bad.json"
expect_error "import with a sidecar that does not fit the file" \
  "imported.csv" "$cli" import "$work/imported.csv" --sidecar "$work/bad.json" --out "$work/x.wav"
expect_error "import of a missing file" "nope.tdms: file not found" \
  "$cli" import "$work/nope.tdms" --out "$work/y.wav"
expect_error "an analysis setting out of range is named" \
  "analysis setting harmonics = 0: at least 1 harmonic per cycle fit" \
  "$cli" analyze "$pos" --harmonics 0 --edc "$work/h0.csv"
[ ! -e "$work/h0.csv" ] && pass "no EDC table for refused settings" ||
  fail "an EDC table was written for refused settings"

if [ $failures -ne 0 ]; then
  echo "$failures check(s) failed" >&2
  exit 1
fi
echo "all import/info checks passed"
