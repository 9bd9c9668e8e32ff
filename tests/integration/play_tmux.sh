#!/usr/bin/env bash
# The main job as a new player meets it (issue 37, point 1): `bash .ci/play.sh` in a
# terminal starts a server, three shopper bots and the client. The bots used to make the
# room and ready at once, so level 1 was under way (or over) before the player's client
# got in; now the player's client makes the room, the bots join it, and the lobby waits
# for the player's Enter. Checked from the pane and the server's log: the lobby shows the
# room, the bots are in it, no level has started; Enter starts level 1 with the player in
# the room; q, y ends the client and play.sh stops its server and bots.
# usage: play_tmux.sh BUILD_DIR SOURCE_DIR   (the programs already built in BUILD_DIR)
set -euo pipefail
BIN=${1:?usage: play_tmux.sh BUILD_DIR SOURCE_DIR}
ROOT=${2:?usage: play_tmux.sh BUILD_DIR SOURCE_DIR}
command -v tmux >/dev/null || { echo "SKIP: tmux not installed"; exit 77; }

source "$(dirname "$0")/tmux_lib.sh"
tmux_setup play
PANES=(me)
log=$WORK/server.log

# wait_log SECONDS REGEX: poll the server's log (play.sh writes it) against a deadline.
wait_log() {
  local deadline=$((SECONDS + $1 * ${FTS_WAIT_SCALE:-3}))
  while ((SECONDS < deadline)); do
    grep -qE -- "$2" "$log" 2>/dev/null && return 0
    sleep 0.1
  done
  fail "no '$2' in the server's log within $1 s"
}

tm new-session -d -s me -x 100 -y 30 "cd '$ROOT' && TERM=xterm-256color XDG_STATE_HOME='$WORK/state' \
  FTS_PLAY_BIN='$BIN' FTS_PLAY_LOG='$log' FTS_PORT=0 FTS_BOTS=3 FTS_NAME=newbie bash .ci/play.sh; \
  echo PLAY_EXIT=\$?; sleep 600"
wait_for me 20 'Room [A-Z]{5}'
wait_log 20 'connect .*name=newbie'
room=$(sed -nE 's/.* connect .*name=newbie.* room=([0-9]+).*/\1/p' "$log" | head -n 1)
[[ -n "$room" ]] || fail "newbie's connect line names no room"
# The three bots join the player's room (a connect line each, in that room).
deadline=$((SECONDS + 20 * ${FTS_WAIT_SCALE:-3}))
until (($(grep -cE " connect .*name=bot.* room=$room( |$)" "$log") >= 3)); do
  ((SECONDS < deadline)) || fail "the bots did not join room $room"
  sleep 0.1
done
echo "the player made room $room and three bots joined it"
if grep -q 'level_start' "$log"; then fail "a level started before the player was ready"; fi
tm send-keys -t me Enter
wait_for me 20 '^Level: 1 '
wait_log 10 "level_start level=1 room=$room"
first_start=$(grep -n 'level_start' "$log" | head -n 1 | cut -d: -f1)
joined=$(grep -n 'connect .*name=newbie' "$log" | head -n 1 | cut -d: -f1)
((joined < first_start)) || fail "level 1 started (log line $first_start) before the player joined (line $joined)"
echo "level 1 started with the player in it"
tm send-keys -t me q
wait_for me 5 'Quit\?'
tm send-keys -t me y
wait_for me 10 '^PLAY_EXIT=0'
echo "play.sh ended with the client"
