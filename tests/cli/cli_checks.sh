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
