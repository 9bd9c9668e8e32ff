#!/usr/bin/env bash
# Sets everything up and runs the main job: a local fts-server with a few bots, and the
# terminal client on it when this is an interactive terminal (otherwise it says how to
# join and keeps the server running until Ctrl-C). On a terminal the player makes a
# private room and the bots join it, so the match waits in the lobby for the player's
# Enter (the bots are ready at once) and level 1 is played from its start; without one,
# the bots make the room and the line printed joins it. Friends join with --join CODE
# (the code is in the HUD).
#   FTS_PORT (default 7777)   FTS_BOTS (default 3)   FTS_NAME (default: $USER or "player")
#   FTS_PLAY_BIN=DIR: use the programs already built in DIR (no install, no build; tests)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
bin=${FTS_PLAY_BIN:-build}
if [[ -z ${FTS_PLAY_BIN:-} ]]; then
bash .ci/deps.sh
bash .ci/build.sh build
fi
port=${FTS_PORT:-7777}
nbots=${FTS_BOTS:-3}
name=${FTS_NAME:-${USER:-player}}
log=${FTS_PLAY_LOG:-$bin/server.log}
pids=()
cleanup() { for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done; wait 2>/dev/null || true; }
trap cleanup EXIT INT TERM HUP

# Every local client (the bots and you) comes from 127.0.0.1: lift the per-address cap.
per_address=$((nbots + 4 > 64 ? 64 : nbots + 4))
"$bin/server/fts-server" --port "$port" --max-per-address "$per_address" >"$log" 2>&1 &
pids+=($!)
for _ in $(seq 1 100); do  # up to 10 s for the ready line
  grep -q " ready " "$log" && break
  kill -0 "${pids[0]}" 2>/dev/null || { cat "$log"; exit 1; }
  sleep 0.1
done
grep " ready " "$log"
if [[ $port == 0 ]]; then port=$(sed -n 's/.* ready .*port=\([0-9]*\).*/\1/p' "$log" | head -n 1); fi
interactive=0
[[ -t 0 && -t 1 && -x $bin/client/fts-client ]] && interactive=1
# The room's code from the server's log: the first room opened.
room_code() {
  local code=""
  for _ in $(seq 1 "$1"); do  # tenths of a second
    code=$(sed -n 's/.* room_open .*code=\([A-Z]\{5\}\).*/\1/p' "$log" | head -n 1)
    [[ -n "$code" ]] && break
    sleep 0.1
  done
  echo "$code"
}
bots() {  # bots ROOM (a code, or create): runs them
  exec "$bin/client/fts-bot" --connect "127.0.0.1:$port" --name bot --count "$nbots" --behavior shopper \
    --room "$1" --report "${log%/*}/bots.json" >/dev/null 2>"${log%/*}/bots.log"
}
room=(--create)
code=""
if ((nbots > 0 && !interactive)); then
  (bots create) &
  pids+=($!)
  code=$(room_code 100)  # up to 10 s for the bots' room
  [[ -n "$code" ]] && room=(--join "$code")
elif ((nbots > 0)); then
  # The player's client makes the room; the bots join it once it is open (up to 60 s).
  (code=$(room_code 600); [[ -n "$code" ]] && bots "$code") &
  pids+=($!)
fi
echo "fts-server is on UDP port $port with $nbots bots (log: $log)${code:+ in room $code}."
if ((interactive)); then
  echo "Your client makes a room and the bots join it; friends join it with --join and the"
  echo "code in your HUD:  $bin/client/fts-client --connect 127.0.0.1:$port --name YOURNAME --join CODE"
else
  echo "Join from any terminal:  $bin/client/fts-client --connect 127.0.0.1:$port --name YOURNAME ${room[*]}"
fi
# Over ssh (README, "Playing over ssh"), once this host's sshd has the game account.
ssh_conf=/etc/ssh/sshd_config.d/fts-play.conf
if [[ -x /usr/sbin/sshd && -f $ssh_conf ]]; then
  ssh_user=$(awk '$1 == "Match" && $2 == "User" { print $3; exit }' "$ssh_conf")
  ssh_port=$(/usr/sbin/sshd -T 2>/dev/null | awk '$1 == "port" { print $2; exit }' || true)
  grep -q -- "--connect 127.0.0.1:$port " "$ssh_conf" || echo "(the ssh account plays on the server named in $ssh_conf)"
  echo "Or with nothing installed:  ssh -t -p ${ssh_port:-22} $ssh_user@$(hostname -f 2>/dev/null || hostname)"
elif [[ -x /usr/sbin/sshd ]]; then
  echo "To let players join with ssh alone: bash docker/ssh/fts-ssh-setup --open install (README, \"Playing over ssh\")"
fi
if ((interactive)); then
  "$bin/client/fts-client" --connect "127.0.0.1:$port" --name "${name:0:16}" "${room[@]}"
else
  echo "Press Ctrl-C to stop."
  wait "${pids[0]}"
fi
