#!/usr/bin/env bash
# End to end: a real fts-server (and fts-bot, when given), the real fts-client in a tmux
# pane. Sends keys, reads the pane, and checks what a person would see: the ball moves,
# the HUD changes, level 1 is finished, a purchase in the shop makes the coins fall and
# the price rise, q asks and q again quits with the terminal given back, and a restarted
# client takes its player back (its token is kept per server). Every wait polls the pane
# against a deadline; nothing sleeps for a fixed time to "let things happen".
#
# usage: client_tmux.sh FTS_SERVER FTS_CLIENT [FTS_BOT]
set -euo pipefail

SERVER=${1:?usage: client_tmux.sh FTS_SERVER FTS_CLIENT [FTS_BOT]}
CLIENT=${2:?usage: client_tmux.sh FTS_SERVER FTS_CLIENT [FTS_BOT]}
BOT=${3:-}
command -v tmux >/dev/null || { echo "SKIP: tmux not installed"; exit 77; }
if [[ -n "$BOT" && ! -x "$BOT" ]]; then echo "SKIP: $BOT is not built"; exit 77; fi

source "$(dirname "$0")/tmux_lib.sh"
tmux_setup e2e
SESSION=e2e
PANES=("$SESSION")

# The column of the left edge of our ball ('@'), or -1.
# (The legend's "@ name" marker is not a ball: a ball is '@' next to '@' or its mass.)
ball_col() { pane "$SESSION" | awk '{ if (match($0, /@[@0-9]/)) { print RSTART; found = 1; exit } } END { if (!found) print -1 }'; }
# Steering from the screen alone: the key that moves our ball ('@' around its mass label)
# toward the nearest enemy ('#'); rows count double (a cell is twice as tall as wide).
hunt_key() {
  pane "$SESSION" | awk 'NR > 3 {
      line = $0; off = 0
      while (match(line, /[@#]+[0-9]+/)) {
        c = substr(line, RSTART, 1); col = off + RSTART + RLENGTH - 1
        if (c == "@") { mr = NR; mc = col } else { n++; er[n] = NR; ec[n] = col }
        off += RSTART + RLENGTH - 1; line = substr(line, RSTART + RLENGTH)
      }
    }
    END {
      if (!mr || !n) exit
      best = -1
      for (i = 1; i <= n; i++) {
        dx = ec[i] - mc; dy = 2 * (mr - er[i]); d = dx * dx + dy * dy
        if (best < 0 || d < best) { best = d; bx = dx; by = dy }
      }
      if ((bx < 0 ? -bx : bx) >= (by < 0 ? -by : by)) print (bx > 0 ? "d" : "a")
      else print (by > 0 ? "w" : "s")
    }'
}
# A number after "LABEL: " in the HUD line.
hud_number() { pane "$SESSION" | head -n 1 | sed -nE "s/.*$1: ([0-9,]+).*/\1/p" | tr -d ,; }

# A server that gives every player 200 coins at the start, so the shop has something to
# sell, and waits for us in the shop. Port 0: the server picks a free one and logs it.
cat >"$WORK/config.json" <<'EOF'
{"player_coins": 200, "shop_timeout_s": 600}
EOF
start_server "$SERVER" --config "$WORK/config.json"

if [[ -n "$BOT" && -x "$BOT" ]]; then
  "$BOT" --connect "127.0.0.1:$PORT" --name bot1 --behavior shopper --duration 120 >"$WORK/bot.log" 2>&1 &
  BOT_PID=$!
fi

CLIENT_CMD="NO_COLOR=1 XDG_STATE_HOME='$WORK/state' '$CLIENT' --connect 127.0.0.1:$PORT --name e2e --quick; echo CLIENT_EXIT=\$?; sleep 600"
tm new-session -d -s "$SESSION" -x 120 -y 40 "$CLIENT_CMD"

wait_for "$SESSION" 10 '@ e2e '
echo "connected"
tm send-keys -t "$SESSION" Enter  # ready: the match starts
wait_for "$SESSION" 15 '^Level: 1 '
wait_for "$SESSION" 10 '@'
start_col=$(ball_col)
echo "level 1, our ball at column $start_col"

# Thrust right: a held key repeats, so send 'd' every 80 ms until the ball has moved.
deadline=$((SECONDS + 10))
moved=0
while ((SECONDS < deadline)); do
  tm send-keys -t "$SESSION" d
  sleep 0.08
  col=$(ball_col)
  if ((col > start_col + 2)); then moved=1; break; fi
done
((moved)) || fail "the ball did not move right (column $start_col)"
echo "the ball moved to column $col"

# Alone, keep pushing right: the enemy at the centre is knocked off and level 1 is
# complete. With a bot, players spawn elsewhere: let the bot hunt and just watch.
if [[ -z "$BOT_PID" ]]; then
  deadline=$((SECONDS + 60))
  while ((SECONDS < deadline)); do
    if pane "$SESSION" | grep -q 'Level 1 Complete'; then break; fi
    tm send-keys -t "$SESSION" d
    sleep 0.08
  done
else
  deadline=$((SECONDS + 120))
  while ((SECONDS < deadline)); do
    if pane "$SESSION" | grep -q 'Level 1 Complete'; then break; fi
    key=$(hunt_key)
    [[ -n "$key" ]] && tm send-keys -t "$SESSION" "$key"
    sleep 0.08
  done
fi
wait_for "$SESSION" 5 'Press Enter to begin next level\.'
coins=$(hud_number Coins)
echo "level 1 complete with $coins coins"
((coins > 200)) || [[ -n "$BOT_PID" ]] || fail "the HUD shows $coins coins after a defeat (expected more than 200)"

# Buy max speed: coins fall by its price, and its price rises by x1.2.
price=$(pane "$SESSION" | sed -nE "s/.*To increase Max Speed, press 's' \(([0-9,]+) coins\).*/\1/p" | tr -d ,)
[[ -n "$price" ]] || fail "no max speed price in the shop"
((coins >= price)) || fail "not enough coins ($coins) for max speed ($price)"
new_price=$((price * 12 / 10))
# The client ignores purchase keys for a moment after the shop opens (a steering key
# still held must not buy): press until the price changes, once per 1.5 s at most.
deadline=$((SECONDS + 10))
bought=0
while ((SECONDS < deadline)) && ((!bought)); do
  tm send-keys -t "$SESSION" s
  for _ in $(seq 15); do
    if pane "$SESSION" | grep -q "To increase Max Speed, press 's' ($new_price coins)"; then bought=1; break; fi
    sleep 0.1
  done
done
((bought)) || fail "buying max speed did not raise its price to $new_price"
wait_for "$SESSION" 5 "^Level: 1   Coins: $((coins - price)) "
wait_for "$SESSION" 5 'Current Max Speed: 1\.7[89]'
echo "bought max speed: coins $coins -> $((coins - price)), price $price -> $new_price"

# Connection trouble: freeze the server past the client's 10 s time-out. The client says
# so, then resumes with its session token when the server answers again: same coins.
kill -STOP "$SERVER_PID"
wait_for "$SESSION" 5 'connection lost, reconnecting\.\.\.'
echo "the client noticed the silence"
stalled_until=$((SECONDS + 11))
while ((SECONDS < stalled_until)); do sleep 0.5; done  # the frozen server is the point here
kill -CONT "$SERVER_PID"
# Resumed: the warning is gone and the HUD has a ping again (a fresh connection's acks),
# with our coins intact.
deadline=$((SECONDS + 20))
# The level may have moved on meanwhile: an away player does not hold up the shop.
until ! pane "$SESSION" | grep -q 'connection lost' && pane "$SESSION" | grep -qE "^Level: [0-9]+   Coins: $((coins - price))   Lives: [0-9]+   Ping:"; do
  ((SECONDS < deadline)) || fail "no resume within 20 s"
  sleep 0.1
done
grep -q 'reconnect player=' "$WORK/server.log" || fail "the server logged no reconnect"
echo "reconnected with the session token"

# Quit: q asks first, a second q quits; the client exits 0 and leaves the alternate screen.
tm send-keys -t "$SESSION" q
wait_for "$SESSION" 5 'Quit\? Press q again'
tm send-keys -t "$SESSION" q
wait_for "$SESSION" 5 '^CLIENT_EXIT=0'
pane "$SESSION" | grep -qE '^Level: [0-9]+   Coins' && fail "the game screen is still there after quitting"
deadline=$((SECONDS + 5))
until grep -qE 'disconnect player=[0-9]+ reason=quit' "$WORK/server.log"; do
  ((SECONDS < deadline)) || fail "the server did not see the quit"
  sleep 0.1
done
echo "quit: the server saw the bye"

# A restarted client takes its player back with the token it kept: the same coins.
[[ -f "$WORK/state/fear-the-sphere/sessions/127.0.0.1_$PORT" ]] || fail "no session file was kept"
[[ $(stat -c %a "$WORK/state/fear-the-sphere/sessions/127.0.0.1_$PORT") == 600 ]] || fail "the session file is not 0600"
reconnects=$(grep -c 'reconnect player=' "$WORK/server.log" || true)
tm respawn-pane -k -t "$SESSION" "$CLIENT_CMD"
wait_for "$SESSION" 10 "^Level: [0-9]+   Coins: $((coins - price)) "
deadline=$((SECONDS + 5))
until (($(grep -c 'reconnect player=' "$WORK/server.log" || true) > reconnects)); do
  ((SECONDS < deadline)) || fail "the restarted client was not taken back by its token"
  sleep 0.1
done
echo "restarted: the same player, coins $((coins - price))"
tm send-keys -t "$SESSION" q
wait_for "$SESSION" 5 'Quit\? Press q again'
tm send-keys -t "$SESSION" y
wait_for "$SESSION" 5 '^CLIENT_EXIT=0'
echo "PASS"
