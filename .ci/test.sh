#!/usr/bin/env bash
# Sets everything up and passes every test: the README's test command, and CI's.
# 1. dependencies; 2. an optimized warnings-as-errors build of the simulation's tests, run;
# 3. a warnings-as-errors AddressSanitizer + UBSan build of everything (the programs, every
# test, the benchmarks) and every test (unit, integration, e2e, hosting, and every fuzz
# target on its seed corpus: the wire, configs, scenes, journals, console).
# Slow soak and load runs are labelled "soak" and left out, as the libFuzzer mutation runs
# (clang: label fuzz, about 4 CPU-minutes) and the container build; run them with
#   ctest --test-dir build-asan -L soak      (or -L fuzz, -L container)
# docs/testing.md says what runs where, and how to run one area or the suite beside a CPU hog.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
bash .ci/deps.sh
jobs=${FTS_JOBS:-$(nproc)}
start=$SECONDS
stage() { echo "== $1 (at $((SECONDS - start)) s)"; }

# The optimized build: the simulation's tests (physics, extremes, match rules and golden
# hashes: determinism must hold at -O2 as shipped). Everything else builds once, in the
# sanitized build below, where every process-level test also checks the server, bots and
# client for memory errors and UB; the shipped programs are built at -O2 by
# `bash .ci/play.sh` and the image.
stage "optimized build"
plain_tests="fts_physics_tests fts_extreme_tests fts_match_tests"
FTS_TARGETS="$plain_tests" bash .ci/build.sh build -DFTS_WERROR=ON
# Each test area runs whole, in one process (label unit_area; every case is also a CTest
# entry of its own, labelled by its area, for running one).
ctest --test-dir build -L '^unit_area$' -R "^(${plain_tests// /|})\$" -j "$jobs" --output-on-failure --timeout 600

# The sanitized build in two steps, without the match rules' test area (run optimized
# above; tests/CMakeLists.txt says why). The programs first (fts_programs: fts-server,
# fts-client, fts-bot, fts-sim); then the process tests (labels integration, e2e, hosting,
# layout, bench: real processes that mostly wait on game time and sockets, about one core
# between them) start in the background while the test areas and the benchmarks compile,
# and the unit areas (label unit_area: each area's cases in one process) and the fuzz
# targets' seeds (label fts_fuzz_replay) run once they are built.
stage "sanitized build: the programs"
export FTS_TARGETS=fts_programs
bash .ci/build.sh build-asan -DFTS_WERROR=ON -DFTS_SANITIZE=ON -DFTS_SANITIZED_MATCH_TESTS=OFF
unset FTS_TARGETS
export ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
stage "process tests (in the background) and the rest of the sanitized build"
# One per core: these mostly wait on game time, but each is a sanitized server with its
# clients, and four at once on two cores made the timing-sensitive ones fail (a mouse
# drag late, a resumed player's coins, ticks skipped: 2026-12-06). They still end before
# the build does. The few that need the machine to themselves say RUN_SERIAL
# (tests/CMakeLists.txt). A test area not built yet shows as <area>_NOT_BUILT (Catch2's
# placeholder): excluded here, run below.
ctest --test-dir build-asan -LE '^(soak|container|fuzz|unit_area|fts_.*)$' -E '_NOT_BUILT' -j "$jobs" \
  --output-on-failure --timeout 900 >build-asan/process-tests.log 2>&1 &
process_tests=$!
trap 'kill "$process_tests" 2>/dev/null || true' EXIT
# The compile at nice 10 (a tenth of a test's weight): a process test that wakes gets its
# core at once, as on an idle machine, and the compile takes every cycle the tests leave.
nice -n 10 bash .ci/build.sh build-asan -DFTS_WERROR=ON -DFTS_SANITIZE=ON -DFTS_SANITIZED_MATCH_TESTS=OFF
stage "unit tests (sanitized)"
# At nice 19: the process tests still running (the RUN_SERIAL ones last) measure
# what a player feels through a relay, and get their core at once.
nice -n 19 ctest --test-dir build-asan -L '^(unit_area|fts_fuzz_replay)$' -j "$((jobs * 2))" --output-on-failure --timeout 900
stage "process tests (waiting for them)"
if ! wait "$process_tests"; then
  cat build-asan/process-tests.log
  echo "process tests failed (build-asan/process-tests.log)"
  exit 1
fi
grep -E "tests passed|Total Test time" build-asan/process-tests.log

trap - EXIT
stage "done"
echo "all tests passed"
