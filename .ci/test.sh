#!/usr/bin/env bash
# Sets everything up and passes every test: the README's test command, and CI's.
# 1. dependencies; 2. a warnings-as-errors build and its unit tests; 3. a warnings-as-
# errors AddressSanitizer + UBSan build and every test (unit, integration, e2e, hosting);
# 4. a short libFuzzer run of the wire decoder.
# Slow soak and load runs are labelled "soak" and left out: run them with
#   ctest --test-dir build -L soak
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
bash .ci/deps.sh
jobs=${FTS_JOBS:-$(nproc)}

# The optimized build: the programs, the benchmarks and the simulation's tests (physics,
# extremes, match rules and golden hashes: determinism must hold at -O2 as shipped). The
# other test areas and the process-level tests (integration, e2e, hosting) build and run
# once, in the sanitized build below, where they also check the server, bots and client
# for memory errors and UB. (Compiling the other 53 test files twice cost an estimated
# four CPU-minutes per run.)
plain_tests="fts_physics_tests fts_extreme_tests fts_match_tests"
# The shipped server and the benchmarks at -O2 with -Werror; fts-client, fts-bot and
# fts-sim are built (-Werror, -O1) and run by every process-level test in the sanitized
# build, and at -O2 by `bash .ci/play.sh` and the image (about a minute of 2 cores saved).
FTS_TARGETS="fts-server bench $plain_tests" bash .ci/build.sh build -DFTS_WERROR=ON
ctest --test-dir build -L "^(${plain_tests// /|})\$" -LE soak -j "$jobs" --output-on-failure --timeout 600

bash .ci/build.sh build-asan -DFTS_WERROR=ON -DFTS_SANITIZE=ON
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --test-dir build-asan -LE 'soak|container' -j "$jobs" --output-on-failure --timeout 900

if [[ -f .ci/fuzz.sh ]]; then
  FUZZ_JOBS="$jobs" bash .ci/fuzz.sh
fi
echo "all tests passed"
