#!/usr/bin/env bash
# End to end, issue 26's closing test, "a new player's first ten minutes", driven in tmux
# as a person would: a new player joins a bot room that is at level 5 or later, steers
# with keys and the mouse, chats, buys in the shop, goes idle, comes back, and reaches
# the next level with coins of their own.
#  1. A real fts-server (nine lives a player: see the config) and three private rooms of
#     two shopper bots each; the first room whose server log says level 5 (or later) has
#     started is the one joined.
#  2. fts-client --join CODE --name newbie: the HUD shows the late joiner's coins (the
#     median of the room's players' value: Coins > 0) and "Protected" once its ball is on
#     the platform (a newcomer during a level is protected).
#  3. An arrow key moves the ball (and ends the protection: the player has thrust); the
#     mouse (SGR motion reports at a point inside the platform) steers it there; a chat
#     line shows in the log; while the level lasts the mouse keeps it busy; in the shop
#     the cheapest item it can afford is bought (the result line, the coins fall by the
#     price) and Enter is ready; with no input for --idle-timeout-ms the server drops it,
#     the client stays ("press a key to play again"), a key brings it back ("Reconnected:
#     welcome back") with its coins, at a level higher than the one it joined at.
# Every wait polls the pane or the server log against a deadline.
#
# Speed: the server runs at --time-scale 4 (every duration in the config below is game
# time: a quarter of it passes in real time) and caps each level at one enemy
# (enemies_cap, a config key), so bots get to level 5 in seconds rather than minutes; the
# protection lasts 12 s of game time (3 s on the clock) so the pane can be read in time.
#
# usage: new_player_tmux.sh FTS_SERVER FTS_CLIENT FTS_BOT
set -euo pipefail

SERVER=${1:?usage: new_player_tmux.sh FTS_SERVER FTS_CLIENT FTS_BOT}
CLIENT=${2:?usage: new_player_tmux.sh FTS_SERVER FTS_CLIENT FTS_BOT}
BOT=${3:?usage: new_player_tmux.sh FTS_SERVER FTS_CLIENT FTS_BOT}
command -v tmux >/dev/null || { echo "SKIP: tmux not installed"; exit 77; }
[[ -x "$BOT" ]] || { echo "SKIP: $BOT is not built"; exit 77; }

source "$(dirname "$0")/tmux_lib.sh"
tmux_setup newbie
PANES=(newbie)
BOT_PIDS=()
cleanup_all() {
  local p
  for p in "${BOT_PIDS[@]}"; do kill "$p" 2>/dev/null || true; done
  tmux_cleanup
}
trap cleanup_all EXIT
started=$SECONDS

# "ROW COL" of the centre of newbie's ball ('@' next to '@' or its mass), 1-based, or "".
ball_at() { pane newbie | awk '{ if (match($0, /@+[0-9]+@*/)) { print NR, RSTART + int(RLENGTH / 2); exit } }'; }
# A number after "LABEL: " in the HUD line (or "LABEL ": the HUD drops the colons when
# the line is too long for the terminal).
hud_number() { pane newbie | head -n 1 | sed -nE "s/^Level:? .*$1:? ([0-9,]+).*/\1/p" | tr -d ,; }
hud_level() { pane newbie | head -n 1 | sed -nE 's/^Level:? ([0-9]+) .*/\1/p'; }
# wait_log SECONDS REGEX: poll the server log until a line matches.
wait_log() {
  local deadline=$((SECONDS + $1))
  until grep -qE -- "$2" "$WORK/server.log"; do
    ((SECONDS < deadline)) || fail "no '$2' in the server log within $1 s"
    sleep 0.1
  done
}

# Nine lives, not the rules' three: on a loaded machine (the test command compiles beside
# it) the newbie lost all three to the room's heavy bots before any shop twice in 2026-12-07's
# cold runs, and an out player never sees the shop this test buys in.
cat >"$WORK/config.json" <<'JSON'
{"enemies_cap": 1, "lobby_timeout_s": 4, "shop_timeout_s": 24, "spawn_protection_s": 12, "player_lives": 9}
JSON
start_server "$SERVER" --time-scale 4 --idle-timeout-ms 5000 --max-per-address 16 --config "$WORK/config.json"

# 1. Three rooms of two shopper bots (hunt, buy, ready at once): the first to level 5 wins.
for name in alfa bravo delta; do
  "$BOT" --connect "127.0.0.1:$PORT" --name "$name" --count 2 --behavior shopper --room create \
    --duration 240 >"$WORK/bot-$name.log" 2>&1 &
  BOT_PIDS+=($!)
done
deadline=$((SECONDS + 90))
room=""
while [[ -z "$room" ]]; do
  ((SECONDS < deadline)) || fail "no bot room reached level 5 within 90 s"
  room=$(sed -nE 's/.*level_start level=([0-9]+) room=([0-9]+).*/\1 \2/p' "$WORK/server.log" |
    awk '$1 >= 5 { print $2; exit }')
  [[ -z "$room" ]] && sleep 0.1
done
code=$(sed -nE "s/.*room_open room=$room code=([A-Z]+).*/\1/p" "$WORK/server.log" | head -n 1)
[[ -n "$code" ]] || fail "no code for room $room in the server log"
echo "room $room ($code) reached level 5 after $((SECONDS - started)) s"

# 2. The new player joins that room.
cmd="TERM=xterm-256color XDG_STATE_HOME='$WORK/state' '$CLIENT' --connect 127.0.0.1:$PORT --name newbie --no-kitty --join $code; echo CLIENT_EXIT=\$?; sleep 600"
tm new-session -d -s newbie -x 100 -y 30 "$cmd"
wait_for newbie 10 "^Level:? [0-9]+ +Coins:? [0-9,]+ .*Room $code"
wait_log 5 "connect player=[0-9]+ name=newbie room=$room"
me=$(sed -nE "s/.*connect player=([0-9]+) name=newbie room=$room.*/\1/p" "$WORK/server.log" | head -n 1)
joined=$(hud_level)
coins=$(hud_number Coins)
((coins > 0)) || fail "the late joiner has $coins coins (the room's median value expected)"
echo "newbie joined $code at level $joined with $coins coins"
wait_for newbie 10 '@+[0-9]+'
wait_for newbie 5 '^Level:? .*Protected:? [0-9]+s'
echo "its ball is on the platform, protected"

# The platform: its top and bottom border rows and left and right border columns.
read -r top bottom left right <<<"$(pane newbie | awk '
  match($0, /\+----------+\+/) { if (!t) { t = NR; l = RSTART; r = RSTART + RLENGTH - 1 } b = NR }
  END { print t, b, l, r }')"
[[ -n "$right" ]] && ((bottom > top + 4)) || fail "no platform border on the screen"
echo "platform: rows $top-$bottom, columns $left-$right"

# A level can end at any moment (the bots hunt its one enemy): each step on the field
# below returns 1 when the shop opens under it; play_step then visits the shop (buys
# once, then Enter: ready) and runs the step again in the next level.
in_shop() { pane newbie | grep -q 'Press Enter to begin next level\.'; }
bought=0
shop_visit() {
  local coins key price deadline result
  coins=$(hud_number Coins)
  if ((!bought)); then
    # The cheapest item newbie can afford (and still keep some coins).
    read -r key price <<<"$(pane newbie | sed -nE "s/.*press '([msarlxb])' \(([0-9,]+) coins\).*/\1 \2/p" |
      tr -d , | sort -k2 -n | head -n 1)"
    [[ -n "$price" ]] || fail "no prices in the shop"
    ((price < coins)) || fail "newbie cannot afford anything: $coins coins, the cheapest ('$key') costs $price"
    # The client ignores purchase keys for a moment after the shop opens (a steering key
    # still held must not buy): press until the result shows, once per 1.5 s at most.
    deadline=$((SECONDS + 10))
    while ((SECONDS < deadline)) && ((!bought)); do
      tm send-keys -t newbie "$key"
      for _ in $(seq 15); do
        result=$(pane newbie | grep -oE '(Bought|You bought) [a-z][^.]*' | head -n 1 || true)
        if [[ -n "$result" ]]; then bought=1; break; fi
        sleep 0.1
      done
    done
    ((bought)) || fail "pressing '$key' ($price coins) in the shop bought nothing"
    wait_for newbie 5 "^Level:? [0-9]+ +Coins:? $((coins - price)) "
    wait_log 5 "purchase player=$me item=[a-z]+ ok=true .*coins=$((coins - price)) room=$room"
    echo "shop: bought '$key' for $price coins ("$result"), $((coins - price)) left"
  fi
  tm send-keys -t newbie Enter  # ready: the next level starts (the bots are ready)
  deadline=$((SECONDS + 15))
  while in_shop; do
    ((SECONDS < deadline)) || fail "the shop did not end on Enter within 15 s"
    sleep 0.1
  done
  echo "level $(hud_level) started"
}
play_step() { until "$@"; do shop_visit; done; }
# field: wait until newbie's ball is drawn; 1 if the shop opens first.
field() {
  local deadline=$((SECONDS + 15))
  until [[ -n "$(ball_at)" ]]; do
    in_shop && return 1
    ((SECONDS < deadline)) || fail "newbie's ball is not on the screen"
    sleep 0.1
  done
}

# 3a. Keys: the ball spawns in the left third; a right arrow moves it right. A thrust
# ends the protection.
step_keys() {
  local row col now_col deadline
  field || return 1
  read -r row col <<<"$(ball_at)"
  deadline=$((SECONDS + 10))
  while ((SECONDS < deadline)); do
    in_shop && return 1
    tm send-keys -t newbie Right
    sleep 0.1
    read -r _ now_col <<<"$(ball_at)"
    if [[ -n "$now_col" ]] && ((now_col > col + 2)); then
      echo "the right arrow moved the ball from column $col to $now_col"
      deadline=$((SECONDS + 5))
      while pane newbie | head -n 1 | grep -q 'Protected'; do
        ((SECONDS < deadline)) || fail "the protection did not end when newbie thrust"
        sleep 0.1
      done
      return 0
    fi
  done
  fail "the right arrow did not move newbie's ball (column $col)"
}
play_step step_keys

# 3b. Mouse: the pointer at a point inside the platform, the farther from the ball of the
# centre and the point halfway between it and the left edge; the ball goes there.
mid_row=$(((top + bottom) / 2))
points=("$(((left + right) / 2))" "$(((3 * left + right) / 4))")
point_far() {
  local c
  read -r _ c <<<"$(ball_at)"
  c=${c:-0}
  local a=${points[0]} b=${points[1]}
  if (((a > c ? a - c : c - a) >= (b > c ? b - c : c - b))); then echo "$a"; else echo "$b"; fi
}
# Lives on the HUD's first line ("2L" compact, "Lives: 2" wide); empty if not shown.
lives() { pane newbie | head -n 1 | sed -nE 's/.*Lives:? ([0-9]+).*/\1/p; t; s/.* ([0-9]+)L .*/\1/p' || true; }
# A ball knocked off by an enemy while it steers (level 6 has chasers) is a new ball, which
# ends the steering: the step is tried once more with the respawned ball.
step_mouse() {
  local try rc before
  for try in 1 2; do
    before=$(lives)
    step_mouse_once && return 0
    rc=$?
    ((rc == 1)) && return 1
    ((rc == 2 && try == 1)) || break
    echo "newbie was knocked off during the mouse step (lives $before -> $(lives)): once more"
  done
  fail "the mouse did not bring the ball from column $mouse_col to column $mouse_target, row $mid_row"
}
step_mouse_once() {  # 0 steered; 1 the shop opened; 2 the ball fell; 3 it did not arrive
  local row col now_col target gap start_gap deadline before
  before=$(lives)
  field || return 1
  target=$(point_far)
  read -r row col <<<"$(ball_at)"
  for _ in 1 2 3; do tm send-keys -t newbie -l $'\x1b'"[<35;${target};${mid_row}M"; sleep 0.05; done
  start_gap=$((target > col ? target - col : col - target))
  deadline=$((SECONDS + 10))
  while ((SECONDS < deadline)); do
    in_shop && return 1
    read -r row now_col <<<"$(ball_at)"
    if [[ -n "$now_col" ]]; then
      gap=$((target > now_col ? target - now_col : now_col - target))
      if ((gap * 3 <= start_gap && row >= mid_row - 3 && row <= mid_row + 3)); then
        echo "the mouse steered the ball from column $col to $now_col (pointer at column $target, row $mid_row)"
        return 0
      fi
    fi
    sleep 0.1
  done
  mouse_col=$col mouse_target=$target
  local now
  now=$(lives)
  [[ -n "$before" && -n "$now" ]] && ((now < before)) && return 2
  return 3
}
play_step step_mouse

# 3c. Chat: t opens the line, Enter sends it; the log shows it with the name.
tm send-keys -t newbie t
wait_for newbie 5 'Say: _'
tm send-keys -t newbie -l 'hi, new here'
wait_for newbie 5 'Say: hi, new here_'
tm send-keys -t newbie Enter
wait_for newbie 5 'newbie: hi, new here'
echo "the chat line shows in the log"

# 3d. The shop, unless it has been visited: play on until the level is complete, the
# pointer moving between the two points every 1-2 s (input: newbie is not idle).
if ((!bought)); then
  deadline=$((SECONDS + 60))
  next_move=0
  until in_shop; do
    ((SECONDS < deadline)) || fail "the level was not complete within 60 s"
    [[ "$(lives)" == 0 ]] && fail "newbie lost every life before a shop (out: no shop to buy in)"
    if ((SECONDS >= next_move)); then
      tm send-keys -t newbie -l $'\x1b'"[<35;$(point_far);${mid_row}M"
      next_move=$((SECONDS + 1))
    fi
    sleep 0.1
  done
  shop_visit
fi
grep -qE "disconnect player=$me reason=idle" "$WORK/server.log" && fail "newbie was dropped as idle while playing"
field || fail "the shop opened again before newbie could go idle"

# 3e. Idle: no input now. The server drops newbie after 5 s of a round without input (a
# shop, where nobody can act, does not count: a level under 5 s only delays it); the
# client stays and says a key brings it back.
coins=$(hud_number Coins)
idle_from=$SECONDS
idle_comes_back newbie 60
grep -qE "disconnect player=$me reason=idle" "$WORK/server.log" || fail "the server did not log newbie's idle drop"
echo "idle: dropped after $((SECONDS - idle_from)) s without input; the client stays"
echo "a key brought newbie back"

# Finally: the room's level is past the one newbie joined at, and newbie has coins.
deadline=$((SECONDS + 10))
while :; do
  level=$(hud_level)
  now=$(hud_number Coins)
  [[ -n "$level" && -n "$now" ]] && ((level > joined && now > 0)) && break
  ((SECONDS < deadline)) || fail "back: level ${level:-?} (joined at $joined), ${now:-?} coins"
  sleep 0.1
done
((now >= coins)) || fail "newbie came back with $now coins, had $coins"
echo "newbie is at level $level (joined at $joined) with $now coins of their own"

quit_client newbie
echo "PASS in $((SECONDS - started)) s"
