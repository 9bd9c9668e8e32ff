#!/usr/bin/env bash
# End to end, what a new player hit (issue 26), driven in tmux as a person would:
#  0. Connecting to an address with no server says so and counts down.
#  1. Mouse steering arrives: a few pointer-motion reports (SGR, `\e[<35;COL;ROWM`) at the
#     platform's top row, then nothing. The ball goes there and stops: the footer's
#     "(mouse steering)" goes away by itself and the player keeps all three lives (before,
#     the thrust never ended and the ball coasted off the edge, three lives in ~10 s).
#  2. The idle kick does not end the client: after --idle-timeout-ms without input the
#     client stays, says so, and a key brings the player back with its coins.
# Every wait polls the pane or the server log against a deadline.
#
# usage: client_mouse_idle_tmux.sh FTS_SERVER FTS_CLIENT
set -euo pipefail

SERVER=${1:?usage: client_mouse_idle_tmux.sh FTS_SERVER FTS_CLIENT}
CLIENT=${2:?usage: client_mouse_idle_tmux.sh FTS_SERVER FTS_CLIENT}
command -v tmux >/dev/null || { echo "SKIP: tmux not installed"; exit 77; }

source "$(dirname "$0")/tmux_lib.sh"
tmux_setup mouse
PANES=(ann)

# The server logs falls at debug level; the idle time-out is short so the test is too.
start_server "$SERVER" --log-level debug --idle-timeout-ms 6000

# 0. No server at an address: the client says where it is connecting and counts down
# (before, an empty field for 12 s, then "no answer").
tm new-session -d -s nobody -x 100 -y 30 "TERM=xterm-256color XDG_STATE_HOME='$WORK/state0' '$CLIENT' --connect 127.0.0.1:9 --name zed --no-kitty --quick; echo CLIENT_EXIT=\$?; sleep 600"
PANES=(nobody)
wait_for nobody 3 'connecting to 127\.0\.0\.1:9\.\.\. (9|10) s'
wait_for nobody 5 'connecting to 127\.0\.0\.1:9\.\.\. [5-7] s'
tm kill-session -t nobody
echo "no server: the client says it is connecting and counts down"
PANES=(ann)

cmd="TERM=xterm-256color XDG_STATE_HOME='$WORK/state' '$CLIENT' --connect 127.0.0.1:$PORT --name ann --no-kitty --quick; echo CLIENT_EXIT=\$?; sleep 600"
tm new-session -d -s ann -x 100 -y 30 "$cmd"
wait_for ann 10 'Room [A-Z]{5}'
tm send-keys -t ann Enter
wait_for ann 20 '^Level: 1 '
wait_for ann 10 '@+[0-9]+'

# 1-based screen row of the platform's top border, and the column of ann's ball.
top=$(pane ann | awk '/^\+-+/ { print NR; exit }')
[[ -n "$top" ]] || fail "no platform border on the screen"
col=$(pane ann | awk '{ if (match($0, /@+[0-9]+@*/)) { print RSTART + int(RLENGTH / 2); exit } }')
[[ -n "$col" ]] || fail "ann's ball is not on the screen"
row=$((top + 1))  # the platform's top row: the pointer there is on the platform
echo "platform's top border on row $top; ann's ball in column $col; pointer to row $row"
for _ in 1 2 3; do  # a person moving the mouse up to the edge, then letting go of it
  tm send-keys -t ann -l $'\x1b'"[<35;${col};${row}M"
done
wait_for ann 3 '\(mouse steering\)'
start=$SECONDS
deadline=$((SECONDS + 10))
while ((SECONDS < deadline)) && pane ann | grep -q '(mouse steering)'; do sleep 0.1; done
pane ann | grep -q '(mouse steering)' && fail "mouse steering did not end by itself within 10 s"
echo "mouse steering ended by itself after $((SECONDS - start)) s"
# The ball rests at the top: it is drawn in the platform's first rows and stays there.
ball_row=$(pane ann | awk '{ if (match($0, /@+[0-9]+@*/)) { print NR; exit } }')
[[ -n "$ball_row" ]] && ((ball_row <= top + 3)) || fail "ann's ball is not at the top (row ${ball_row:-none})"
# Several seconds later it has not fallen: no fall in the log, three lives on the HUD.
sleep_until=$((SECONDS + 4))
while ((SECONDS < sleep_until)); do
  grep -q 'player_fell' "$WORK/server.log" && fail "ann's ball fell off the platform"
  sleep 0.2
done
pane ann | head -n 1 | grep -q 'Lives: 3' || fail "ann lost a life: $(pane ann | head -n 1)"
echo "the ball rests at the top edge with three lives"

# 2. Idle: no input for 6 s in a round. The client stays and says what happened.
idle_comes_back ann 15
echo "idle: the client stays and offers to play again"
wait_for ann 10 '^Level: 1 .*Lives: 3'
echo "a key brought ann back into her room"
quit_client ann
echo "PASS"
