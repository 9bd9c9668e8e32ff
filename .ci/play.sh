#!/usr/bin/env bash
# Sets everything up and runs the main job: a local fts-server with a few bots, and the
# terminal client on it when this is an interactive terminal (otherwise it says how to
# join and keeps the server running until Ctrl-C). The bots make a private room and the
# player joins it (its code is in the HUD: friends join with --join CODE).
#   FTS_PORT (default 7777)   FTS_BOTS (default 3)   FTS_NAME (default: $USER or "player")
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
bash .ci/deps.sh
bash .ci/build.sh build
port=${FTS_PORT:-7777}
nbots=${FTS_BOTS:-3}
name=${FTS_NAME:-${USER:-player}}
log=build/server.log
pids=()
cleanup() { for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done; wait 2>/dev/null || true; }
trap cleanup EXIT INT TERM

# Every local client (the bots and you) comes from 127.0.0.1: lift the per-address cap.
per_address=$((nbots + 4 > 64 ? 64 : nbots + 4))
./build/server/fts-server --port "$port" --max-per-address "$per_address" >"$log" 2>&1 &
pids+=($!)
for _ in $(seq 1 100); do  # up to 10 s for the ready line
  grep -q " ready " "$log" && break
  kill -0 "${pids[0]}" 2>/dev/null || { cat "$log"; exit 1; }
  sleep 0.1
done
grep " ready " "$log"
room=()
if ((nbots > 0)); then
  ./build/client/fts-bot --connect "127.0.0.1:$port" --name bot --count "$nbots" --behavior shopper \
    --room create --report build/bots.json >/dev/null 2>build/bots.log &
  pids+=($!)
  code=""
  for _ in $(seq 1 100); do  # up to 10 s for the bots' room
    code=$(sed -n 's/.* room_open .*code=\([A-Z]\{5\}\).*/\1/p' "$log" | head -n 1)
    [[ -n "$code" ]] && break
    sleep 0.1
  done
  [[ -n "$code" ]] && room=(--join "$code")
fi
((${#room[@]})) || room=(--create)
echo "fts-server is on UDP port $port with $nbots bots (log: $log)${code:+ in room $code}."
echo "Join from any terminal:  ./build/client/fts-client --connect 127.0.0.1:$port --name YOURNAME ${room[*]}"
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
if [[ -t 0 && -t 1 && -x build/client/fts-client ]]; then
  ./build/client/fts-client --connect "127.0.0.1:$port" --name "${name:0:16}" "${room[@]}"
else
  echo "Press Ctrl-C to stop."
  wait "${pids[0]}"
fi
