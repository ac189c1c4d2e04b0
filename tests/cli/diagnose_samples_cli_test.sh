#!/usr/bin/env bash
# oscilab-cli diagnose on the bundled presliding samples, with its default budgets:
#   diagnose_samples_cli_test.sh OSCILAB_CLI SOURCE_DIR
# A whole diagnosis (baseline fit, every candidate effect, refits) takes about 20 s of CPU in a
# release build and minutes under the sanitizers, so this runs in the `slow` suite (release only);
# fit_cli_test.sh covers diagnose's options and error paths with small budgets.
source "$(dirname "$0")/cli_checks.sh"

# The hidden presliding hysteresis of the samples is named, with the evidence that supported it.
if "$cli" diagnose "$src/samples/presliding_positive.flac" "$src/samples/presliding_negative.flac" \
  --no-png --out "$work/diag_p" > "$work/diag_p.log" 2>&1 &&
  grep -q '"verdict": "presliding-hysteresis"' "$work/diag_p/report.json" &&
  grep -q '"verdict_supported_by"' "$work/diag_p/report.json" &&
  grep -q '"sigma_budget"' "$work/diag_p/report.json"; then
  pass "diagnose names the samples' presliding hysteresis"
else
  fail "diagnose presliding samples: $(tail -3 "$work/diag_p.log")"
fi

[ $failures -eq 0 ]
