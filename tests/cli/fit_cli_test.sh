#!/usr/bin/env bash
# oscilab-cli fit and merge from the command line, and the campaign scripts:
#   fit_cli_test.sh OSCILAB_CLI SOURCE_DIR
# Small GA budgets keep it fast; the numbers themselves are checked by the GoogleTest suites.
source "$(dirname "$0")/cli_checks.sh"
pos=$src/samples/stepped_positive.flac
neg=$src/samples/stepped_negative.flac
small=(--method ga --population 6 --generations 1 --seed 4)

# A fit on both samples writes the contract's keys; GA evaluations = 6 + 1 × (6 − 1 elite).
if "$cli" fit "$pos" "$neg" "${small[@]}" --out "$work/a.json" > "$work/a.log" 2>&1; then
  pass "fit exits 0"
else
  fail "fit exits non-zero: $(tail -3 "$work/a.log")"
fi
for key in '"parameters"' '"fd_zminus_n"' '"fd_zero_n"' '"fd_zplus_n"' '"ks"' '"c_ns_m"' \
  '"vt_m_s"' '"cost_j"' '"mean_deviation_pct"' '"positive"' '"negative"' '"evaluations": 11' \
  '"seconds"' '"standard_errors"' '"friction_coefficients"' '"method"'; do
  grep -q -- "$key" "$work/a.json" && pass "FIT JSON has $key" || fail "FIT JSON lacks $key"
done
grep -q "52 levels" "$work/a.log" && pass "fit reports 52 levels" || fail "fit level count: $(head -2 "$work/a.log")"

# Same seed, same result (cost and parameters); the seconds may differ.
"$cli" fit "$pos" "$neg" "${small[@]}" --out "$work/b.json" > /dev/null 2>&1
if diff <(grep -v '"seconds"' "$work/a.json") <(grep -v '"seconds"' "$work/b.json") > /dev/null; then
  pass "same seed, same FIT JSON"
else
  fail "same seed gave a different FIT JSON"
fi

# Bad input: one line naming the problem, exit status 2, no output file.
expect_error() {  # expect_error WHAT PATTERN COMMAND...
  local what=$1 pattern=$2
  shift 2
  local message status
  message=$("$@" 2>&1 >/dev/null)
  status=$?
  if [ $status -eq 2 ] && grep -q -- "$pattern" <<< "$message"; then
    pass "$what: $message"
  else
    fail "$what: status $status, message: $message"
  fi
}
expect_error "unknown method" 'simplex' "$cli" fit "$pos" --method simplex --out "$work/x.json"
expect_error "missing recording" 'nope.flac' "$cli" fit "$work/nope.flac" --out "$work/x.json"
expect_error "unknown model form" 'model-form' "$cli" fit "$pos" --model-form cubic --out "$work/x.json"
expect_error "mutation out of range" 'mutation' "$cli" fit "$pos" --mutation 1.5 --out "$work/x.json"
[ ! -e "$work/x.json" ] && pass "no FIT JSON after an error" || fail "a FIT JSON was written after an error"
# Sidecar values of the right form but no sense, and an excitation frequency that leaves no whole
# cycles: one line naming the field and why, never a hang or an internal error.
cp "$pos" "$work/nyquist.flac"
sed 's/"frequency_hz": 9.0/"frequency_hz": 300.0/' "$src/samples/stepped_positive.json" > "$work/nyquist.json"
expect_error "sidecar frequency above Nyquist" \
  'nyquist.json: excitation.frequency_hz: 300 Hz is not below the Nyquist frequency' \
  "$cli" analyze "$work/nyquist.flac" --edc "$work/x.csv"
cp "$pos" "$work/heavy.flac"
sed 's/"mass_kg": 0.26/"mass_kg": 1e308/' "$src/samples/stepped_positive.json" > "$work/heavy.json"
expect_error "absurd mass" 'heavy.json: mass_kg: 1e+308 kg is outside the range' \
  "$cli" analyze "$work/heavy.flac" --edc "$work/x.csv"
expect_error "--freq above Nyquist" '(--freq): 1e+09 Hz is not below the Nyquist' \
  "$cli" analyze "$pos" --edc "$work/x.csv" --freq 1e9
expect_error "--freq without two cycles" '(--freq): 1e-09 Hz: the record.s 262.502 s hold fewer' \
  "$cli" fit "$pos" --freq 1e-9 --out "$work/x.json"
message=$("$cli" analyze "$pos" --edc "$work/x.csv" --freq -3 2>&1 >/dev/null)
status=$?
if [ $status -ne 0 ] && grep -q -- '--freq: -3 is not a positive number' <<< "$message"; then
  pass "negative --freq refused: $(head -1 <<< "$message")"
else
  fail "negative --freq: status $status, message: $message"
fi
[ ! -e "$work/x.csv" ] && pass "no EDC table after an error" || fail "an EDC table was written after an error"
echo '{"cost_j": 1}' > "$work/not_a_fit.json"
expect_error "merge of a non-FIT JSON" 'not_a_fit.json: parameters' "$cli" merge "$work/not_a_fit.json" --out "$work/m.csv"
echo 'not json' > "$work/garbage.json"
expect_error "merge of garbage" 'garbage.json' "$cli" merge "$work/garbage.json" --out "$work/m.csv"

# The GNU parallel path on the samples: two fits side by side, then one table.
printf '%s\n' "# one fit per line" "$pos" "" "$pos $neg" > "$work/jobs.txt"
if OSCILAB_CLI=$cli bash "$src/scripts/fit_parallel.sh" -j 2 "$work/jobs.txt" "$work/fits" \
  "${small[@]}" > "$work/parallel.log" 2>&1; then
  pass "fit_parallel.sh exits 0"
else
  fail "fit_parallel.sh: $(tail -5 "$work/parallel.log")"
fi
rows=$(($(wc -l < "$work/fits/fits.csv") - 1))
[ "$rows" -eq 2 ] && pass "merged table has 2 fits" || fail "merged table has $rows rows"
head -1 "$work/fits/fits.csv" | grep -q '^fit,records,method,cost_j,mean_deviation_pct_positive' &&
  pass "merged table header" || fail "merged table header: $(head -1 "$work/fits/fits.csv")"
grep -q "stepped_negative.flac" "$work/fits/fits.csv" && pass "table names the records" ||
  fail "table lacks the record names"

# The Slurm array script, run as task 2 outside Slurm (same job list).
if SLURM_ARRAY_TASK_ID=2 SLURM_CPUS_PER_TASK=1 OSCILAB_CLI=$cli \
  bash "$src/scripts/fit_campaign.slurm" "$work/jobs.txt" "$work/slurm" "${small[@]}" \
  > "$work/slurm.log" 2>&1 && grep -q '"evaluations": 11' "$work/slurm/fit_2.json"; then
  pass "fit_campaign.slurm task 2"
else
  fail "fit_campaign.slurm: $(tail -3 "$work/slurm.log")"
fi

# diagnose on the samples (the paper's model itself): the baseline explains them, verdict none.
# No wall-clock bound (--max-seconds 0): what it finds, not how fast; under the sanitizers on a
# loaded machine the default 120 s cut the baseline short (reduced chi2 3.3e5, incomplete).
if "$cli" diagnose "$pos" "$neg" --baseline-evaluations 300 --max-seconds 0 --no-png --out "$work/diag" \
  > "$work/diag.log" 2>&1; then
  pass "diagnose exits 0"
else
  fail "diagnose: $(tail -3 "$work/diag.log")"
fi
for key in '"baseline"' '"cost_j"' '"steps"' '"verdict": "none"' '"final_model"' '"verdict_reason"'; do
  grep -q -- "$key" "$work/diag/report.json" && pass "report has $key" || fail "report lacks $key"
done
[ -s "$work/diag/levels.csv" ] && pass "diagnose levels table" || fail "no levels.csv"
# The time bound: stopped long before the baseline fit ends, the report is still written, marked
# incomplete, with the reason.
if "$cli" diagnose "$pos" "$neg" --max-seconds 0.001 --no-png --out "$work/diag_cut" \
  > "$work/diag_cut.log" 2>&1 && grep -q '"status": "incomplete"' "$work/diag_cut/report.json" &&
  grep -q 'INCOMPLETE' "$work/diag_cut.log"; then
  pass "diagnose --max-seconds writes an incomplete report"
else
  fail "diagnose --max-seconds: $(tail -3 "$work/diag_cut.log")"
fi
# The stiffness identified (the default): the report's baseline holds K(z)'s coefficients, and
# the report says whether the gap is explained.
for key in '"stiffness_c3_n_m3"' '"gap_explained": true' '"gap"'; do
  grep -q -- "$key" "$work/diag/report.json" && pass "report has $key" || fail "report lacks $key"
done
grep -q "gap explained" "$work/diag.log" && pass "diagnose says the gap is explained" ||
  fail "diagnose does not say whether the gap is explained: $(tail -3 "$work/diag.log")"
expect_error "diagnose unknown stiffness" 'stiffness' "$cli" diagnose "$pos" "$neg" --stiffness slice --out "$work/d5"
expect_error "fit unknown stiffness" 'stiffness' "$cli" fit "$pos" "$neg" --stiffness slice --out "$work/f5.json"
[ -e "$work/f5.json" ] && fail "fit wrote an output on a bad --stiffness" || pass "no FIT JSON on a bad --stiffness"

# The lab's model from its random record: its mass and the slice's K(z), the friction of --model.
if "$cli" analyze "$src/samples/random.flac" --model-out "$work/lab.json" > "$work/lab.log" 2>&1 &&
  grep -q '"polynomial-stiffness"' "$work/lab.json" && grep -q '"position-dependent-friction"' "$work/lab.json" &&
  "$cli" model "$work/lab.json" > /dev/null 2>&1; then
  pass "analyze --model-out writes a model the CLI reads back"
else
  fail "analyze --model-out: $(tail -3 "$work/lab.log")"
fi
expect_error "analyze --model-out with an unknown model" 'nope.json' "$cli" analyze "$src/samples/random.flac" --model-out "$work/lab2.json" --model "$work/nope.json"
[ -e "$work/lab2.json" ] && fail "analyze wrote a model on a bad --model" || pass "no model written on a bad --model"
expect_error "diagnose negative time bound" 'max-seconds' "$cli" diagnose "$pos" "$neg" --max-seconds -1 --out "$work/d4"
expect_error "diagnose unknown form" 'model-form' "$cli" diagnose "$pos" --model-form cubic --out "$work/d2"
expect_error "diagnose without mass" 'nope.flac' "$cli" diagnose "$work/nope.flac" --out "$work/d3"

[ $failures -eq 0 ]
