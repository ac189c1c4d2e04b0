#!/usr/bin/env bash
# oscilab-cli export: MATLAB, UFF 58 and EDC MATLAB files from the samples, and the error
# paths. The file contents are checked in depth by daq_export_tests; here the command's wiring:
#   export_cli_test.sh OSCILAB_CLI SOURCE_DIR
source "$(dirname "$0")/cli_checks.sh"
pos=$src/samples/stepped_positive.flac
neg=$src/samples/stepped_negative.flac

# One recording to both formats.
if "$cli" export "$pos" --mat "$work/pos.mat" --uff "$work/pos.uff" > "$work/a.log" 2>&1; then
  pass "export exits 0"
else
  fail "export exits non-zero: $(tail -3 "$work/a.log")"
fi
grep -q "variables t_s, base_acc, y" "$work/a.log" && pass "names the MAT variables" ||
  fail "MAT variables: $(cat "$work/a.log")"
# MAT-file level 5: header text, then version 0x0100 and endian indicator "IM" at bytes 124-127.
head -c 19 "$work/pos.mat" | grep -q "MATLAB 5.0 MAT-file" && pass "MAT header text" ||
  fail "MAT header text: $(head -c 40 "$work/pos.mat")"
[ "$(od -An -tx1 -j124 -N4 "$work/pos.mat" | tr -d ' ')" = "0001494d" ] &&
  pass "MAT version 0x0100, little-endian" || fail "MAT version/endian bytes"
# UFF: dataset 164 then one dataset 58 per channel; lines of at most 80 characters; record 7 of
# each dataset 58 gives the sample count of the recording (262.5 s at 512 Hz, plus t = 0).
[ "$(head -1 "$work/pos.uff")" = "    -1" ] && pass "UFF opens with -1" || fail "UFF first line"
[ "$(grep -c '^    58$' "$work/pos.uff")" -eq 2 ] && pass "two datasets 58" ||
  fail "datasets 58: $(grep -c '^    58$' "$work/pos.uff")"
[ "$(awk 'length($0) > 80' "$work/pos.uff" | wc -l)" -eq 0 ] && pass "UFF lines <= 80" ||
  fail "UFF has lines over 80 characters"
points=$(awk 'BEGIN { n = -1 } $0 == "    58" { n = 0; next } n >= 0 { n++ }
  n == 7 { print substr($0, 11, 10) + 0 }' "$work/pos.uff" | sort -u)
[ "$points" = "134401" ] && pass "UFF record 7: 134401 points" || fail "UFF points: $points"

# Several recordings go to a directory, one file each; the EDC table of both in one MAT-file.
if "$cli" export "$pos" "$neg" --mat "$work/out/" --uff "$work/out/" --edc-mat "$work/edc.mat" \
  > "$work/b.log" 2>&1; then
  pass "export of two recordings exits 0"
else
  fail "export of two recordings: $(tail -3 "$work/b.log")"
fi
for f in stepped_positive.mat stepped_negative.mat stepped_positive.uff stepped_negative.uff; do
  [ -s "$work/out/$f" ] && pass "wrote out/$f" || fail "no out/$f"
done
grep -q "edc.mat (52 EDC levels)" "$work/b.log" && pass "EDC MAT-file of 52 levels" ||
  fail "EDC levels: $(tail -1 "$work/b.log")"

# Bad input: one line naming the problem, exit status 2, no output file.
expect_error() {  # expect_error WHAT PATTERN COMMAND...
  local what=$1 pattern=$2
  shift 2
  local message status
  message=$("$@" 2>&1 >/dev/null)
  status=$?
  if [ $status -eq 2 ] && grep -q -- "$pattern" <<< "$message" && [ "$(wc -l <<< "$message")" -eq 1 ]; then
    pass "$what: $message"
  else
    fail "$what: status $status, message: $message"
  fi
}
expect_error "nothing to write" 'give --mat, --uff or --edc-mat' "$cli" export "$pos"
expect_error "missing recording" 'nope.flac' "$cli" export "$work/nope.flac" --mat "$work/x.mat"
expect_error "wrong MAT extension" '--mat .*x.txt: expected a .mat file' \
  "$cli" export "$pos" --mat "$work/x.txt"
expect_error "wrong UFF extension" 'expected a .uff or .unv file' \
  "$cli" export "$pos" --uff "$work/x.mat"
expect_error "two recordings, one file" '2 recordings need a directory' \
  "$cli" export "$pos" "$neg" --mat "$work/x.mat"
expect_error "same stem twice" 'would both be written to stepped_positive.mat' \
  "$cli" export "$pos" "$pos" --mat "$work/dup/"
expect_error "unwritable MAT" 'nodir/x.mat: cannot write' \
  "$cli" export "$pos" --mat "$work/nodir/x.mat"
expect_error "unwritable UFF" 'nodir/x.uff: cannot write' \
  "$cli" export "$pos" --uff "$work/nodir/x.uff"
expect_error "bad direction" '--uff-direction 9' \
  "$cli" export "$pos" --uff "$work/x.uff" --uff-direction 9
expect_error "bad well" '--well up' "$cli" export "$pos" --edc-mat "$work/x.mat" --well up
expect_error "no EDC levels" 'x.mat: no EDC levels' \
  "$cli" export "$src/samples/random.flac" --edc-mat "$work/x.mat"
for f in x.mat x.txt x.uff dup nodir; do
  [ ! -e "$work/$f" ] && pass "nothing at $f after an error" || fail "$f exists after an error"
done
[ -z "$(find "$work" -name '*.tmp.*')" ] && pass "no temporary files left" ||
  fail "temporary files left: $(find "$work" -name '*.tmp.*')"

[ $failures -eq 0 ]
