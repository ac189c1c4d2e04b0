#!/usr/bin/env bash
# Peak memory and time of the offline analysis against the record's length: virtual-rig stepped
# sines of 10 min, 1 h, 6 h and 24 h (26 levels of the paper's grid, 24-bit FLAC), each analysed
# in a child process as `oscilab-cli analyze` does (streamed from the file) and, as the
# reference beside it, read whole into memory with everything kept (as `fit`, `diagnose`, the app
# and Python hold a record). Prints the benchmark's table: peak resident set (MB), the signal's
# size as doubles (MB), their ratio and the analysis's wall time. Making the 24 h record takes
# the rig about 4 minutes and 5 GB; the whole study about 10 minutes on 2 cores.
#
#   bash scripts/memory_study.sh [BUILD]      (BUILD default: build)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
exec "$build/tests/analyze_memory_benchmark" --benchmark_counters_tabular=true
