#!/usr/bin/env bash
# A campaign of EDC fits on one workstation: one `oscilab-cli fit` per line of a job list, run
# side by side by GNU parallel, then joined into one table by `oscilab-cli merge`.
#
#   scripts/fit_parallel.sh [-j JOBS] JOBLIST OUTDIR [fit options ...]
#
# JOBLIST: one fit per line, the recordings of that fit separated by spaces (shell quoting for
# names with spaces); blank lines and lines starting with # are skipped. Every fit gets the same
# fit options (e.g. --method cmaes --bootstrap 30) and writes OUTDIR/fit_N.json and
# OUTDIR/fit_N.log, N being its line number among the jobs; OUTDIR/fits.csv joins them, and
# OUTDIR/joblog.tsv is GNU parallel's record of each job (exit status, run time). Each fit runs
# on one thread, so JOBS fits (default: the number of cores) keep JOBS cores busy.
#
# Example (the bundled samples, fitted separately and together, 3 seeds each):
#   printf '%s\n' "samples/stepped_positive.flac" "samples/stepped_negative.flac" \
#     "samples/stepped_positive.flac samples/stepped_negative.flac" > jobs.txt
#   for s in 1 2 3; do scripts/fit_parallel.sh jobs.txt fits/seed$s --seed $s; done
set -euo pipefail

jobs=$(nproc 2>/dev/null || echo 2)
if [ "${1:-}" = "-j" ]; then
  jobs=$2
  shift 2
fi
if [ $# -lt 2 ]; then
  echo "usage: scripts/fit_parallel.sh [-j JOBS] JOBLIST OUTDIR [fit options ...]" >&2
  exit 2
fi
list=$1
out=$2
shift 2
cli=${OSCILAB_CLI:-$(cd "$(dirname "$0")/.." && pwd)/build/app/oscilab-cli}
command -v parallel >/dev/null || { echo "fit_parallel.sh: GNU parallel is not installed (apt-get install parallel)" >&2; exit 2; }
[ -x "$cli" ] || { echo "fit_parallel.sh: $cli: not built (set OSCILAB_CLI or run scripts/setup.sh build)" >&2; exit 2; }
[ -r "$list" ] || { echo "fit_parallel.sh: $list: cannot read the job list" >&2; exit 2; }
mkdir -p "$out"

# The job list without comments and blank lines; {#} numbers the jobs, {=uq=} passes a line's
# recordings unquoted so that the shell splits them into arguments.
grep -v -E '^[[:space:]]*(#|$)' "$list" |
  parallel --will-cite -j "$jobs" --halt soon,fail=1 --joblog "$out/joblog.tsv" \
    "$(printf '%q' "$cli")" fit '{=uq=}' --threads 1 --out "$(printf '%q' "$out")/fit_{#}.json" \
    "$(printf '%q ' "$@")" '>' "$(printf '%q' "$out")/fit_{#}.log" '2>&1'

"$cli" merge "$out"/fit_*.json --out "$out/fits.csv"
