#!/usr/bin/env bash
# fts-client's uplink, measured end to end (issue 14): one real fts-client in a private
# tmux server steers with four keys in turn (a w d s, each a 0.13 s tap, one every
# ~40 ms) through level 1; fts-server's 1 s stats records give the bytes and datagrams
# in (one player: all of it is that client's). Prints figures, never fails on them.
#   usage: tests/bench/client_uplink.sh [BUILD_DIR]
set -euo pipefail
build=${1:-build}
command -v tmux >/dev/null || { echo "SKIP: tmux not installed"; exit 77; }
source "$(dirname "$0")/../integration/tmux_lib.sh"
tmux_setup uplink
PANES=(up)

# wait_log SECONDS PATTERN: poll the server log against a deadline.
wait_log() {
  local deadline=$((SECONDS + $1))
  while ((SECONDS < deadline)); do
    grep -q "$2" "$WORK/server.log" && return 0
    sleep 0.1
  done
  fail "no $2 in the server log within $1 s"
}

start_server "$build/server/fts-server" --log-format json --stats-interval-ms 1000 --tick-rate 100
tm new -d -s up -x 120 -y 40 \
  "XDG_STATE_HOME=$WORK $build/client/fts-client --connect 127.0.0.1:$PORT --name uplink --quick --new --no-mouse"
wait_log 20 '"event":"connect"'
tm send-keys -t up Enter  # ready: the level starts
wait_log 30 '"event":"level_start"'
start=$(grep -c '"event":"stats"' "$WORK/server.log" || true)
keys=(a w d s)
for i in $(seq 1 300); do
  tm send-keys -t up "${keys[$((i % 4))]}"
  sleep 0.03
done
# The stats records after the level started (the first of them partly before: skipped).
grep '"event":"stats"' "$WORK/server.log" | python3 -c '
import json, sys
rows = [r for r in list(map(json.loads, sys.stdin))[int(sys.argv[1]) + 1:] if r["players"] == 1]
b = sorted(r["bytes_in"] for r in rows)
d = sorted(r["datagrams_in"] for r in rows)
print(f"fts-client steering, {len(rows)} s: bytes in per second min {b[0]} median {b[len(b) // 2]} max {b[-1]}; "
      f"datagrams in per second min {d[0]} median {d[len(d) // 2]} max {d[-1]}")' "$start"
