#!/usr/bin/env bash
# Builds the libFuzzer targets (one per decoder of outside bytes: the wire, a match
# config, a scene, a room's journal, the console's lines; tests/fuzz/) with clang in their
# own build dir, and runs each on its seed corpus (tests/fuzz/corpus/NAME/) for a while.
# Exits non-zero if the build fails or a fuzzer finds a crash, a broken property, a
# sanitizer report or a leak (the input is saved as build-fuzz/findings/NAME/crash-*).
#   .ci/fuzz.sh [SECONDS] [NAME...]
# SECONDS is the decoder's time (default 20); the others get a third of it each
# (min 5 s). The test command runs it with the default (about 50 s of fuzzing);
# `ctest --test-dir build -L soak -R fuzz` runs it with 600 (the decoder 10 minutes, the
# others 200 s each). FUZZ_BUILD_DIR overrides the build dir, FUZZ_JOBS the jobs;
# FUZZ_BUILD_ONLY=1 builds and stops (the test command builds beside its tests);
# FUZZ_RUN_ONLY=1 runs what is built (the test command runs two fuzzers at once).
# FUZZ_OPT is the optimization of the libraries and targets: -O1 by default (as the
# sanitized build); the test command builds at -O0, which compiles in about 55 % of the
# CPU (protocol's first unity batch: 14 s against 25 s) and runs far fewer inputs a
# second (the decoder 570 against 3 900): a smoke run takes every seed and a few thousand
# mutations; depth comes from the soak run (600 s at -O1).
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
seconds="${1:-20}"
shift || true
names=("$@")
((${#names[@]})) || names=(decode config scene journal console)
build="${FUZZ_BUILD_DIR:-$here/build-fuzz}"
jobs="${FUZZ_JOBS:-1}"

if [[ ${FUZZ_RUN_ONLY:-0} != 1 ]]; then
  export CCACHE_SLOPPINESS=${CCACHE_SLOPPINESS:-pch_defines,time_macros}
  export CCACHE_DEPEND=${CCACHE_DEPEND:-1}  # as .ci/build.sh: no preprocessor run on a miss
  cmake -S "$here" -B "$build" -G Ninja \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="${FUZZ_OPT:--O1} -g1 -DNDEBUG" \
    -DCMAKE_CXX_COMPILER=clang++ \
    -DCMAKE_CXX_FLAGS="-fsanitize=fuzzer-no-link,address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined" \
    -DFTS_FUZZ=ON -DFTS_BUILD_TESTS=OFF >/dev/null
  targets=()
  for n in "${names[@]}"; do targets+=(--target "fts_fuzz_$n"); done
  cmake --build "$build" -j"$jobs" "${targets[@]}"
fi
[[ ${FUZZ_BUILD_ONLY:-0} == 1 ]] && exit 0

for n in "${names[@]}"; do
  t=$seconds
  len=4096
  [[ $n == decode ]] && len=1300   # a datagram's most
  [[ $n == journal ]] && len=16384  # a header and a checkpoint are 2-3 KiB each
  [[ $n == decode ]] || t=$(((seconds / 3) > 5 ? seconds / 3 : 5))
  # The seeds stay as they are in the tree; what the fuzzer finds goes to the build dir.
  work="$build/corpus/$n"
  findings="$build/findings/$n"
  mkdir -p "$work" "$findings"
  echo "fuzz: $n for ${t}s"
  (cd "$findings" &&
    UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
      "$build/tests/fuzz/fts_fuzz_$n" -max_total_time="$t" -max_len="$len" -print_final_stats=1 \
      "$work" "$here/tests/fuzz/corpus/$n")
done
