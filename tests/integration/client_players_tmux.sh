#!/usr/bin/env bash
# End to end, several players: a real fts-server, two real fts-clients (ann and bob) in
# tmux panes and an fts-bot, in one match. Checks what players see of each other: each
# sees the other's name in the legend, in the same colour on both screens; a chat line
# typed by ann arrives on bob's screen with her name; ann steers with the mouse (SGR
# reports typed into the pane) and her ball moves toward the pointer; a pane shrunk
# below 60x20 shows the warning; and `fts-client --replay` of the server's record ends on
# the level and coins ann saw live. Every wait polls a pane against a deadline.
#
# usage: client_players_tmux.sh FTS_SERVER FTS_CLIENT FTS_BOT
set -euo pipefail

SERVER=${1:?usage: client_players_tmux.sh FTS_SERVER FTS_CLIENT FTS_BOT}
CLIENT=${2:?usage: client_players_tmux.sh FTS_SERVER FTS_CLIENT FTS_BOT}
BOT=${3:?usage: client_players_tmux.sh FTS_SERVER FTS_CLIENT FTS_BOT}
command -v tmux >/dev/null || { echo "SKIP: tmux not installed"; exit 77; }
[[ -x "$BOT" ]] || { echo "SKIP: $BOT is not built"; exit 77; }

source "$(dirname "$0")/tmux_lib.sh"
tmux_setup players
PANES=(ann bob replay)

# The SGR colour (30-37, 90-97) the pane draws NAME in (the legend's "@ name" or "O name"
# entry or the label on the field, whichever comes first).
colour_of() {
  tm capture-pane -e -p -t "$1" | grep -aoE "("$'\x1b'"\\[[0-9;]*m)+([@O] )?$2[^a-z0-9_]" | head -n 1 |
    grep -oE '[[;](3[0-7]|9[0-7])[;m]' | tail -n 1 | tr -d '[;m'
}
# "ROW COL" of the centre of ann's ball ('@' next to '@' or its mass), 1-based, or "".
ball_at() {
  pane ann | awk '{ if (match($0, /@+[0-9]+@*/)) { print NR, RSTART + int(RLENGTH / 2); exit } }'
}

cat >"$WORK/config.json" <<'JSON'
{"shop_timeout_s": 600}
JSON
start_server "$SERVER" --config "$WORK/config.json" --record "$WORK/match.record"

for name in ann bob; do
  cmd="TERM=xterm-256color XDG_STATE_HOME='$WORK/state-$name' '$CLIENT' --connect 127.0.0.1:$PORT --name $name --no-kitty --quick; echo CLIENT_EXIT=\$?; sleep 600"
  tm new-session -d -s "$name" -x 120 -y 40 "$cmd"
done
# Names: each sees the other (and the bot) in the legend. The bot joins once both are in
# their room, by its code: a bot alone in a room readies at once and would start a match
# of its own before the two clients arrive on a loaded machine.
wait_for ann 10 'O bob '
wait_for bob 10 'O ann '
code=$(pane ann | grep -oE 'Room [A-Z]{5}' | head -n 1 | cut -d' ' -f2)
[[ -n "$code" ]] || fail "no room code on ann's screen"
"$BOT" --connect "127.0.0.1:$PORT" --name bot1 --room "$code" --behavior wander --duration 120 >"$WORK/bot.log" 2>&1 &
BOT_PID=$!
wait_for ann 10 'O bot1 '
echo "each sees the other's name"
# Colours: the same player is drawn in the same colour on both screens.
for who in ann bob; do
  a=$(colour_of ann "$who")
  b=$(colour_of bob "$who")
  [[ -n "$a" && "$a" == "$b" ]] || fail "$who is colour '$a' on ann's screen and '$b' on bob's"
done
[[ $(colour_of ann ann) != $(colour_of ann bob) ]] || fail "ann and bob have the same colour"
echo "colours agree: ann $(colour_of ann ann), bob $(colour_of ann bob)"

# Chat: ann types a line; bob's log shows it with her name.
tm send-keys -t ann t
wait_for ann 5 'Say: _'
tm send-keys -t ann -l 'hello bob'
wait_for ann 5 'Say: hello bob_'
tm send-keys -t ann Enter
wait_for bob 5 'ann: hello bob'
wait_for ann 5 'ann: hello bob'
echo "the chat line arrived"

# Play: both ready; the level starts.
tm send-keys -t ann Enter
tm send-keys -t bob Enter
wait_for ann 20 '^Level: 1 '
wait_for ann 10 '@+[0-9]+'
read -r row col <<<"$(ball_at)"
[[ -n "$row" ]] || fail "ann's ball is not on the screen"
echo "level 1: ann's ball at row $row, column $col"
# Mouse: the pointer 30 columns to the left of the ball (or near the platform's left
# edge), on its row (SGR any-motion report, 1-based); the ball must move left.
# (On the platform: a pointer off it ends mouse steering, issue 26.)
left=$(pane ann | awk -v r="$row" 'NR == r { print index($0, "|"); exit }')
target=$((col - 30 > left + 1 ? col - 30 : left + 2))
deadline=$((SECONDS + 10))
moved=0
while ((SECONDS < deadline)); do
  tm send-keys -t ann -l $'\x1b'"[<35;${target};${row}M"
  sleep 0.1
  read -r _ now_col <<<"$(ball_at)"
  if [[ -n "$now_col" ]] && ((now_col < col - 2)); then moved=1; break; fi
done
((moved)) || fail "ann's ball did not move toward the pointer (column $col, pointer $target)"
echo "the mouse steered ann's ball from column $col to $now_col"
# Pointer on the ball again: still.
read -r row col <<<"$(ball_at)"
tm send-keys -t ann -l $'\x1b'"[<35;${col};${row}M"

# A small terminal: the warning instead of the field.
tm resize-window -t bob -x 50 -y 15
wait_for bob 5 'terminal too small: 50x15, need at least 60x20'
tm resize-window -t bob -x 120 -y 40
wait_for bob 5 '^Level: '
echo "the small pane showed the warning"

# The replay: note what ann sees last, quit both clients, stop the server (its record
# is complete) and play the record back to its end.
live=$(pane ann | head -n 1 | sed -nE 's/^Level: ([0-9]+)   Coins: ([0-9,]+) .*/\1 \2/p' | tr -d ,)
[[ -n "$live" ]] || fail "no HUD on ann's screen"
read -r live_level live_coins <<<"$live"
for name in ann bob; do quit_client "$name"; done
kill -TERM "$SERVER_PID"
wait "$SERVER_PID" 2>/dev/null || true
SERVER_PID=""
tm new-session -d -s replay -x 120 -y 40 "TERM=xterm-256color '$CLIENT' --replay '$WORK/match.record'; echo CLIENT_EXIT=\$?; sleep 600"
wait_for replay 10 'Replay: tick'
tm send-keys -t replay e
wait_for replay 30 '\(end\)'
wait_for replay 5 "^Level: $live_level "
coins=$(pane replay | grep -oE '[@O] ann +[0-9,]+c' | head -n 1 | sed -E 's/.* ([0-9,]+)c/\1/' | tr -d ,)
[[ "$coins" == "$live_coins" ]] || fail "the replay ends with ann at $coins coins, live she had $live_coins"
pane replay | grep -q 'differs from this build' && fail "the replay's hashes differ from the record's"
echo "the replay ends on level $live_level with ann at $coins coins, as live"
tm send-keys -t replay q
wait_for replay 5 '^CLIENT_EXIT=0'
echo "PASS"
