# What the command-line tests share, sourced by each with its arguments (OSCILAB_CLI SOURCE_DIR):
# `cli` and `src`, a scratch folder `work` removed at exit (with any background job the test
# left), and pass/fail that count the checks (`passes`, `failures`).
set -uo pipefail
cli=$1
src=$2
work=$(mktemp -d)
trap 'kill $(jobs -p) 2>/dev/null; rm -rf "$work"' EXIT
failures=0
passes=0
pass() { echo "ok: $1"; passes=$((passes + 1)); }
fail() { echo "FAILED: $1" >&2; failures=$((failures + 1)); }
# expect_error WHAT PATTERN COMMAND...: the command exits 2 with exactly one line on stderr that
# matches PATTERN (grep); its output is left in $work/err.out and $work/err.log.
expect_error() {
  local what=$1 text=$2
  shift 2
  "$@" > "$work/err.out" 2> "$work/err.log"
  local status=$?
  if [ $status -eq 2 ] && grep -q -- "$text" "$work/err.log" && [ "$(wc -l < "$work/err.log")" -eq 1 ]; then
    pass "$what"
  else
    fail "$what: status $status, $(head -c 300 "$work/err.log")"
  fi
}
