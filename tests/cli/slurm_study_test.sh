#!/usr/bin/env bash
# The diagnosis study's Slurm path for real: a one-node Slurm on this machine
# (scripts/slurm_local.sh), the smoke campaign submitted as a job array, then summarised:
#   slurm_study_test.sh SOURCE_DIR DIAGNOSIS_STUDY
# Needs root and Debian's slurmctld, slurmd, slurm-client and munge (scripts/setup.sh installs
# them): without them it fails, it does not skip. The four diagnoses run one after the other (each
# task asks for 2 CPUs), 1 to 4 minutes in all. Only the rows' format is checked: whether each
# verdict is right is the study's question, not this test's.
src=$1
study=$2
# cli_checks.sh: `work`, pass/fail and their counters (it calls its first argument `cli`).
source "$(dirname "$0")/cli_checks.sh" "$study" "$src"
src=$(cd "$src" && pwd)
study=$(cd "$(dirname "$study")" && pwd)/$(basename "$study")
export PATH=$PATH:/usr/sbin
slurm=$work/slurm
# Stop Slurm (and with it any job still queued or running) before the scratch folder goes.
trap 'bash "$src/scripts/slurm_local.sh" stop "$slurm" > /dev/null 2>&1
      kill $(jobs -p) 2>/dev/null; rm -rf "$work"' EXIT
trap 'exit 143' TERM INT

for tool in sbatch sinfo scontrol slurmctld slurmd munged; do
  if ! command -v "$tool" > /dev/null; then
    fail "$tool not found: slurm-wlm is not installed (apt-get install slurmctld slurmd slurm-client munge, or bash scripts/setup.sh deps)"
    echo "$passes passed, $failures failed"
    exit 1
  fi
done
[ -x "$study" ] || { fail "no study binary at $study"; echo "$passes passed, $failures failed"; exit 1; }

# A port pair of its own, so that a real Slurm on a developer's machine (6817) is not in the way.
export SLURM_LOCAL_PORT=${SLURM_LOCAL_PORT:-16817}
if timeout 90 bash "$src/scripts/slurm_local.sh" start "$slurm" > "$work/start.log" 2>&1; then
  pass "slurm_local.sh start: $(tail -1 "$work/start.log")"
else
  fail "slurm_local.sh start: $(cat "$work/start.log")"
  echo "$passes passed, $failures failed"
  exit 1
fi
export SLURM_CONF=$slurm/slurm.conf
export OSCILAB_STUDY=$study

# The job list and the line to submit.
out=$work/study
bash "$src/scripts/diagnosis_power_study.sh" "$out" smoke --slurm > "$work/plan.log" 2>&1
line=$(grep '^sbatch ' "$work/plan.log")
count=$(wc -l < "$out/jobs.txt" 2>/dev/null || echo 0)
expected="sbatch --array=1-4 scripts/diagnosis_campaign.slurm $out/jobs.txt $out/rows"
[ "$count" -eq 4 ] && [ "$line" = "$expected" ] && pass "smoke plan: 4 jobs, $line" ||
  fail "smoke plan: $count jobs, printed: $(cat "$work/plan.log")"

# Submitted as printed, from the checkout (SLURM_SUBMIT_DIR), waiting for the whole array; the
# task logs go to the scratch folder rather than the checkout. The job script bounds each task
# (--time=00:20:00), timeout the whole; in the background so that a TERM reaches the trap.
read -r -a words <<< "$line"
mkdir -p "$work/logs"
started=$SECONDS
(cd "$src" && exec timeout 600 sbatch --wait --output="$work/logs/%x_%A_%a.log" "${words[@]:1}") \
  > "$work/sbatch.log" 2>&1 &
wait $!
status=$?
jobid=$(sed -n 's/^Submitted batch job \([0-9][0-9]*\).*/\1/p' "$work/sbatch.log")
if [ $status -eq 0 ] && [ -n "$jobid" ]; then
  pass "array job $jobid done in $((SECONDS - started)) s (sbatch --wait exit 0)"
else
  fail "sbatch --wait: status $status$([ $status -eq 124 ] && echo ' (timed out after 600 s)'): $(cat "$work/sbatch.log")"
fi

# Every task: its row (21 fields, the case and seed of its line of the job list), its log opened by
# the node's task prolog with SLURM_ARRAY_TASK_ID, its record in the job-completion log.
for n in 1 2 3 4; do
  read -r -a job <<< "$(sed -n "${n}p" "$out/jobs.txt")"
  seed=${job[1]}
  [ "${job[0]}" = power ] && seed=${job[5]}
  row=$out/rows/$n.csv
  if [ -s "$row" ] && [ "$(wc -l < "$row")" -eq 1 ] &&
    awk -F, -v c="${job[0]}" -v s="$seed" 'NF != 21 || ($1 != "control" && $1 != "power") ||
      $1 != c || $6 != s || $10 !~ /^[0-9.]+$/ || $21 !~ /^-?[01]$/ { exit 1 }' "$row"; then
    pass "task $n row: $(cut -d, -f1-10 "$row")"
  else
    fail "task $n row for '${job[*]}': $(cat "$row" 2>/dev/null || echo missing)"
  fi
  log=$work/logs/oscilab-diagnosis_${jobid}_$n.log
  grep -q "^slurm_local: job [0-9]* array task $n of $jobid on localhost" "$log" 2>/dev/null &&
    pass "task $n ran under Slurm: $(head -1 "$log")" ||
    fail "task $n log $log: $(head -3 "$log" 2>/dev/null || echo missing)"
  grep -q "JobState=COMPLETED .*ArrayJobId=$jobid ArrayTaskId=$n .* ExitCode=0:0" "$slurm/log/jobcomp.log" &&
    pass "task $n completed with exit 0 (job-completion log)" ||
    fail "task $n not in the job-completion log as exit 0: $(grep "ArrayTaskId=$n " "$slurm/log/jobcomp.log")"
done
compgen -G "$work/logs/*.log" > /dev/null || fail "no task log in $work/logs"

# The same study command without --slurm summarises and runs nothing again (every row is there).
before=$(cat "$out"/rows/*.csv | md5sum)
if timeout 300 bash "$src/scripts/diagnosis_power_study.sh" "$out" smoke > "$work/summary.log" 2>&1; then
  pass "summary: $(tail -1 "$work/summary.log")"
else
  fail "summary: $(tail -5 "$work/summary.log")"
fi
rows=$(($(wc -l < "$out/results.csv" 2>/dev/null || echo 1) - 1))
[ "$rows" -eq 4 ] && pass "results.csv has 4 rows" || fail "results.csv has $rows rows"
head -1 "$out/results.csv" 2>/dev/null |
  grep -q '^case,effect,scale,.*,embodiment,truth_reduced_chi2,baseline_reaches_truth$' &&
  pass "results.csv header" || fail "results.csv header: $(head -1 "$out/results.csv" 2>/dev/null)"
[ -s "$out/summary.csv" ] && pass "summary.csv written" || fail "no summary.csv"
[ "$(cat "$out"/rows/*.csv | md5sum)" = "$before" ] && pass "the summary ran no task again" ||
  fail "the summary rewrote rows"

bash "$src/scripts/slurm_local.sh" stop "$slurm" > "$work/stop.log" 2>&1 &&
  pass "slurm_local.sh stop" || fail "slurm_local.sh stop: $(cat "$work/stop.log")"

echo "$passes passed, $failures failed"
[ $failures -eq 0 ]
