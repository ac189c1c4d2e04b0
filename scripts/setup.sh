#!/usr/bin/env bash
# Oscilab set-up for a fresh Debian 12 machine (as root, or a user with sudo).
#
#   bash scripts/setup.sh run    install, build the app, the CLI and the Python module (installed into
#                                the system's Python: `python3 -c "import oscilab"`), start the app on
#                                the bundled sample (headless: print the analysis of it instead)
#   bash scripts/setup.sh test   install, build and run every test: clang-format check, release
#                                build with -Werror (GUI offscreen, Python, the `slow` end-to-end
#                                tests, benchmarks printed), the headless unit and CLI tests under
#                                ASan + UBSan, and the live chain's tests under ThreadSanitizer
#   bash scripts/setup.sh deps   only install the Debian packages
#   bash scripts/setup.sh build  only configure and build (release, ./build)
#
# Every dependency is a Debian 12 package; nothing is downloaded from anywhere else.
set -euo pipefail
cd "$(dirname "$0")/.."

PACKAGES=(
  build-essential cmake ninja-build pkg-config git
  libeigen3-dev libfftw3-dev libsndfile1-dev libboost-dev
  jackd2 libjack-jackd2-dev libsoxr-dev
  nlohmann-json3-dev libcli11-dev
  libpagmo-dev libnlopt-cxx-dev libmatio-dev libhdf5-dev libcairo2-dev parallel
  python3-numpy python3-scipy python3-h5py python3-pytest python3-dev pybind11-dev
  python3-setuptools python3-wheel python3-pip python3-venv
  libgtest-dev libgmock-dev libbenchmark-dev
  qt6-base-dev qt6-svg-dev libqcustomplot-dev libqcustomplot2.1-qt6
  xvfb xauth clang-format clang-tidy
  slurmctld slurmd slurm-client munge
)
DEFAULT_SAMPLE=samples/stepped_positive.flac
JOBS=$(nproc 2>/dev/null || echo 2)

as_root() {
  if [ "$(id -u)" -eq 0 ]; then "$@"; else sudo "$@"; fi
}

deps() {
  local missing=()
  for p in "${PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  if [ ${#missing[@]} -eq 0 ]; then
    echo "setup: all ${#PACKAGES[@]} Debian packages present"
    return
  fi
  echo "setup: installing ${missing[*]}"
  as_root apt-get update
  as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends "${missing[@]}"
}

build() {  # build DIR [cmake options...]: everything, tests included
  local dir=$1
  shift
  cmake -S . -B "$dir" -G Ninja "$@"
  cmake --build "$dir" -j "$JOBS"
}

python_module() {  # builds the Python module and installs it into the system's Python
  if [ ! -d build/python ]; then
    echo "setup: the Python module is not configured (needs python3-dev and pybind11-dev)"
    return
  fi
  cmake --build build -j "$JOBS" --target oscilab_python
  as_root cmake --install build --component python
  local python
  python=$(sed -n 's/^Python3_EXECUTABLE:FILEPATH=//p' build/CMakeCache.txt)
  (cd / && "$python" -c "import oscilab; print('setup: Python module oscilab', oscilab.__version__, 'for', '$python')")
  if [ "$(command -v python3)" != "$python" ] && ! (cd / && python3 -c "import oscilab" 2>/dev/null); then
    echo "setup: note: python3 on PATH ($(command -v python3)) is not $python, the Python with NumPy"
    echo "setup: the module was built for; use $python (or configure with -DPython3_EXECUTABLE=...)"
  fi
}

run_main() {  # only what the main job needs: the app, the CLI, the optimiser and Python modules
  cmake -S . -B build -G Ninja -DOSCILAB_UNITY_BUILD=ON
  cmake --build build -j "$JOBS" --target oscilab oscilab-cli oscilab_cmaes
  python_module
  if [ -n "${DISPLAY:-}${WAYLAND_DISPLAY:-}" ]; then
    echo "setup: starting the Oscilab desktop app on $DEFAULT_SAMPLE"
    exec ./build/app/oscilab "$DEFAULT_SAMPLE"
  fi
  echo "setup: no display (DISPLAY and WAYLAND_DISPLAY are unset), so the desktop app cannot open;"
  echo "setup: running the headless analysis of the same sample instead:"
  echo
  ./build/app/oscilab-cli info "$DEFAULT_SAMPLE"
  echo
  local out
  out=$(mktemp -d)
  ./build/app/oscilab-cli analyze "$DEFAULT_SAMPLE" --edc "$out/edc.csv" --summary "$out/summary.json"
  echo
  echo "setup: EDC table and summary written to $out/"
}

format_check() {  # CI fails on a format diff (.clang-format)
  local files
  mapfile -t files < <(git ls-files '*.cpp' '*.h' 2>/dev/null || find analysis daq ui app tests -name '*.cpp' -o -name '*.h')
  if ! clang-format --dry-run --Werror "${files[@]}"; then
    echo "setup: clang-format found a diff: run clang-format -i on the files above" >&2
    return 1
  fi
  echo "setup: clang-format: ${#files[@]} files formatted"
}

phase_started=$SECONDS
phase() {  # phase NAME: the time the step before it took, so CI logs say where the minutes go
  echo "setup: --- $1 (previous step: $((SECONDS - phase_started)) s, total: $SECONDS s)"
  phase_started=$SECONDS
}

run_tests() {
  phase "format check"
  format_check
  phase "release build"
  # Every test runs once. The headless unit tests (GoogleTest without Qt, the oscilab-cli scripts)
  # run in the sanitizer build below, so the release tree leaves them out
  # (OSCILAB_HEADLESS_UNIT_TESTS=OFF) and keeps what only it can run: the GUI tests, the Python
  # module's, the `slow` end-to-end runs (a diagnosis, a fit, an adaptive test: release only) and
  # the benchmarks, once each (their medians for notes come from runs of their own).
  # The core libraries compile as a unity build (batches of 8 units) in each of the three trees.
  build build -DOSCILAB_WERROR=ON -DOSCILAB_HEADLESS_UNIT_TESTS=OFF -DOSCILAB_BENCHMARK_REPETITIONS=1 \
    -DOSCILAB_UNITY_BUILD=ON
  phase "release tests"
  # `study`: suites that are studies more than checks (minutes each), run with `ctest -L study`.
  ctest --test-dir build --output-on-failure -j "$JOBS" -LE "benchmark|study"
  phase "benchmarks"
  # Benchmarks verbose, so their figures are printed (each line prefixed by its test's number),
  # two at a time but the real-time JACK one (RUN_SERIAL): in CI they run once each to show that
  # they run, and their medians for notes come from runs of their own on an idle machine.
  ctest --test-dir build --output-on-failure -L benchmark -V -j "$JOBS" | grep -E "^[0-9]+: (BM_|Benchmark )|tests passed|tests failed|Failed|rror"
  phase "ASan + UBSan build"
  # Sanitizer build: the headless tests under AddressSanitizer + UndefinedBehaviorSanitizer,
  # at -O1 with light debug info (faster to build than -O2 -g; stack traces keep file and line).
  # The Qt GUI tests run in the release build above: a second, sanitized Qt build does not fit
  # the CI budget (20 minutes on 2 cores).
  # Benchmarks are neither built nor registered there: their timings would mean nothing. Suites
  # labelled `slow` (whole diagnoses, fits, an adaptive test) ran in the release build and are
  # not built or repeated at -O1; `study` suites are not built either.
  build build-asan -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g1" \
    -DOSCILAB_SANITIZE=ON -DOSCILAB_WERROR=ON -DOSCILAB_BUILD_GUI=OFF -DOSCILAB_UNITY_BUILD=ON
  phase "ASan + UBSan tests"
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 \
  LSAN_OPTIONS=suppressions=$PWD/tests/lsan.supp \
  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    ctest --test-dir build-asan --output-on-failure -j "$JOBS" -LE "slow|study"
  # ThreadSanitizer on the live chain (source threads, the block queue, the acquisition thread and
  # its readers, the recorder): only that test binary is built. ASLR off (setarch -R) because
  # GCC 12's ThreadSanitizer refuses the memory layout of kernels with high mmap randomisation.
  phase "TSan build"
  cmake -S . -B build-tsan -G Ninja -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g1" \
    -DOSCILAB_SANITIZE_THREAD=ON -DOSCILAB_WERROR=ON -DOSCILAB_BUILD_GUI=OFF -DOSCILAB_UNITY_BUILD=ON
  cmake --build build-tsan -j "$JOBS" --target daq_live_tests
  phase "TSan tests"
  TSAN_OPTIONS=halt_on_error=1:second_deadlock_stack=1 \
    setarch "$(uname -m)" -R build-tsan/tests/daq_live_tests
  phase "done"
}

case "${1:-run}" in
  deps) deps ;;
  build) deps; build build ;;
  run) deps; run_main ;;
  test) deps; run_tests ;;
  *) echo "usage: bash scripts/setup.sh run|test|deps|build" >&2; exit 2 ;;
esac
