#!/usr/bin/env bash
# Issue 37's renderer matrix: --glyphs ascii against --glyphs braille in one run of
# tests/bench/input_latency.py per cell, 80x24 and 120x40, 0/150/300 ms RTT through the relay.
# usage (repository root): FTS_BIN_DIR=build-asan bash tests/bench/results/2026-12-04-glyphs/matrix.sh OUT_DIR
set -euo pipefail
out=${1:?OUT_DIR}
mkdir -p "$out"
for size in 80x24 120x40; do
  for rtt in 0 150 300; do
    w=${size%x*}; h=${size#*x}
    FTS_BIN_DIR=${FTS_BIN_DIR:-build-asan} timeout 400 python3 tests/bench/input_latency.py --trials 12 --rest-ms 600 \
      --width "$w" --height "$h" --relay --rtt-ms "$rtt" --variant "ascii=--glyphs ascii" \
      --variant "braille=--glyphs braille" --csv "$out/$size-$rtt.csv" --json "$out/$size-$rtt.json" 2> "$out/$size-$rtt.log"
  done
done
