#!/usr/bin/env bash
# Old against new on a shared, noisy machine: runs fts-gas-bench from two build
# directories alternately and prints, per engine and build, the median and every run's
# ns per body-step. Figures only; nothing passes or fails.
# usage: tests/bench/gas_ab.sh OLD_BUILD NEW_BUILD ENGINES RUNS [fts-gas-bench arguments]
#   e.g. tests/bench/gas_ab.sh ../old/build build seed,discrete 7 --n 10000 --ticks 300
set -euo pipefail
if [ $# -lt 4 ]; then
  sed -n 2,6p "$0" >&2
  exit 2
fi
old=$1 new=$2 engines=$3 runs=$4
shift 4
args=("$@")
[ ${#args[@]} -gt 0 ] || args=(--n 10000 --ticks 300)
for _ in $(seq "$runs"); do
  for b in "$old" "$new"; do
    "$b/tests/bench/fts-gas-bench" "${args[@]}" --engines "$engines" |
      awk -F'|' -v b="$b" '/^\| [a-z]/ && !/engine/ { gsub(/ /, "", $2); print b, $2, $4 }'
  done
done | python3 -c '
import collections, statistics, sys
runs = collections.defaultdict(list)
for line in sys.stdin:
    build, engine, ns = line.split()
    runs[(engine, build)].append(float(ns))
print("| engine | build | median ns/body-step | runs |")
print("|---|---|---|---|")
for (engine, build), v in sorted(runs.items()):
    print(f"| {engine} | {build} | {statistics.median(v):.1f} | {sorted(v)} |")
'
echo "load: $(cut -d" " -f1-3 /proc/loadavg)"
