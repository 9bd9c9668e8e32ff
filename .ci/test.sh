#!/usr/bin/env bash
# Sets everything up and passes every test: the README's test command, and CI's.
# 1. dependencies; 2. a warnings-as-errors build and its unit tests; 3. a warnings-as-
# errors AddressSanitizer + UBSan build and every test (unit, integration, e2e, hosting);
# 4. a short run of each libFuzzer target (the wire, configs, scenes, journals, console).
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
# The libFuzzer targets' clang build (about 4 CPU-minutes) runs beside the sanitized
# tests at the lowest priority: it takes the cycles the one-at-a-time process tests leave
# idle, and almost none from a test that wants them (nice 19 weighs 1/70 of a test).
mkdir -p build-fuzz
nice -n 19 env FUZZ_BUILD_ONLY=1 FUZZ_JOBS="$jobs" bash .ci/fuzz.sh >build-fuzz/build.log 2>&1 &
fuzz_build=$!
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --test-dir build-asan -LE 'soak|container' -j "$jobs" --output-on-failure --timeout 900 ||
  { kill "$fuzz_build" 2>/dev/null; exit 1; }
wait "$fuzz_build" || { cat build-fuzz/build.log; echo "the fuzzers' build failed"; exit 1; }

# 4. Each fuzzer on its corpus: the wire decoder 20 s, the others 6 s each.
FUZZ_JOBS="$jobs" bash .ci/fuzz.sh
echo "all tests passed"
