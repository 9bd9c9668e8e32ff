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

bash .ci/build.sh build -DFTS_WERROR=ON
# The process-level tests (integration, e2e, hosting) run once, in the sanitized build
# below, where they also check the server, bots and client for memory errors and UB.
ctest --test-dir build -LE 'soak|integration|e2e|hosting|container' -j "$jobs" --output-on-failure --timeout 600

bash .ci/build.sh build-asan -DFTS_WERROR=ON -DFTS_SANITIZE=ON
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --test-dir build-asan -LE 'soak|container' -j "$jobs" --output-on-failure --timeout 900

if [[ -f .ci/fuzz.sh ]]; then
  FUZZ_JOBS="$jobs" bash .ci/fuzz.sh
fi
echo "all tests passed"
