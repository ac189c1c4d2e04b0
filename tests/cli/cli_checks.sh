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
# repair_jack_metadata: a JACK metadata database (libjack's Berkeley DB in /dev/shm/jack_db-UID)
# with an empty region file, as a JACK program killed while opening it leaves it (these tests
# kill servers and clients), makes every later JACK client refuse; on a test machine it is
# removed, and the next client makes a new one.
repair_jack_metadata() {
  local db="/dev/shm/jack_db-$(id -u)"
  if [ -n "$(find "$db" -name '__db.*' -empty 2> /dev/null)" ]; then rm -rf "$db"; fi
}
