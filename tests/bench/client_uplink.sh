#!/usr/bin/env bash
# fts-client's uplink, measured end to end (issue 14): one real fts-client in a private
# tmux server steers with four keys in turn (a w d s, each a 0.13 s tap, one every
# ~40 ms) for about 15 s of level 1; fts-server's 1 s stats records give the bytes and
# datagrams in (one player: all of it is that client's). Prints figures, never fails on
# them. usage: tests/bench/client_uplink.sh [BUILD_DIR]
set -u
build=${1:-build}
command -v tmux >/dev/null || { echo "SKIP: tmux not installed"; exit 77; }
work=$(mktemp -d /tmp/fts-uplink.XXXXXX)
sock="fts-uplink-$$"
tm() { tmux -L "$sock" "$@"; }
port=$((20000 + RANDOM % 20000))
"$build/server/fts-server" --port "$port" --log-format json --stats-interval-ms 1000 --tick-rate 100 \
  >"$work/server.log" 2>&1 &
server=$!
cleanup() { tm kill-server 2>/dev/null; kill "$server" 2>/dev/null; wait 2>/dev/null; rm -rf "$work"; }
trap cleanup EXIT
wait_log() {  # wait_log SECONDS PATTERN
  local deadline=$((SECONDS + $1))
  while ((SECONDS < deadline)); do grep -q "$2" "$work/server.log" && return 0; sleep 0.1; done
  echo "no $2 in the server log within $1 s"; exit 1
}
wait_log 10 '"event":"ready"'
tm new -d -s up -x 120 -y 40 \
  "XDG_STATE_HOME=$work $build/client/fts-client --connect 127.0.0.1:$port --name uplink --quick --new --no-mouse"
wait_log 20 '"event":"connect"'
tm send-keys -t up Enter  # ready: the level starts
wait_log 30 '"event":"level_start"'
start=$(grep -c '"event":"stats"' "$work/server.log")
keys=(a w d s)
for i in $(seq 1 300); do
  tm send-keys -t up "${keys[$((i % 4))]}"
  sleep 0.03
done
tail -n +"$((start + 2))" "$work/server.log" | grep '"event":"stats"' | python3 -c '
import json, sys
rows = [json.loads(l) for l in sys.stdin if json.loads(l)["players"] == 1]
b = sorted(r["bytes_in"] for r in rows); d = sorted(r["datagrams_in"] for r in rows)
print(f"fts-client steering, {len(rows)} s: bytes in per second min {b[0]} median {b[len(b)//2]} max {b[-1]}; "
      f"datagrams in per second min {d[0]} median {d[len(d)//2]} max {d[-1]}")'
