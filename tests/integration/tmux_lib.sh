# Shared by the tmux end-to-end scripts (sourced, not run): a private tmux server, a work
# directory removed on exit, pane reads, deadline waits and a real fts-server on a free port.
#
#   source tmux_lib.sh; tmux_setup NAME        WORK, SOCK, tm, cleanup trap
#   PANES=(a b)                                panes printed when a check fails
#   pane PANE / wait_for PANE SECONDS REGEX    read a pane / poll it against a deadline
#   start_server SERVER ARGS...                SERVER_PID and PORT (the port it logged)
#   quit_client PANE                           q, y: the client exits 0
#   idle_comes_back PANE SECONDS               the idle kick keeps the client; a key is back
# A failed check calls fail, which prints the panes and the server log's tail and exits 1.

tmux_setup() {
  # The panes' clients draw the field in ASCII ('@', 'O', '#', which these tests read):
  # under a UTF-8 locale --glyphs auto would draw braille dots.
  export LANG=C
  unset LC_ALL LC_CTYPE
  WORK=$(mktemp -d "/tmp/fts-$1.XXXXXX")
  SOCK="fts-$1-$$"  # a private tmux server: never touches the user's sessions
  SERVER_PID=""
  BOT_PID=""
  PANES=()
  trap tmux_cleanup EXIT
}
tm() { tmux -L "$SOCK" "$@"; }

tmux_cleanup() {
  tm kill-server 2>/dev/null || true
  [[ -n "$BOT_PID" ]] && kill "$BOT_PID" 2>/dev/null || true
  [[ -n "$SERVER_PID" ]] && kill "$SERVER_PID" 2>/dev/null || true
  wait 2>/dev/null || true
  rm -rf "$WORK"
}

fail() {
  echo "FAIL: $*" >&2
  local p
  for p in "${PANES[@]}"; do
    echo "--- pane $p ---" >&2
    tm capture-pane -p -t "$p" >&2 2>/dev/null || true
  done
  echo "--- server log (tail) ---" >&2
  tail -n 20 "$WORK/server.log" >&2 || true
  exit 1
}

pane() { tm capture-pane -p -t "$1"; }

# wait_for PANE SECONDS REGEX: poll the pane until a line matches. SECONDS is what an idle
# machine needs; the deadline is FTS_WAIT_SCALE (default 3) times that, so that a loaded
# machine (a sanitized client beside other tests, a CPU hog) passes too: the wait ends at
# the match, so a longer deadline costs nothing when the test passes.
wait_for() {
  local deadline=$((SECONDS + $2 * ${FTS_WAIT_SCALE:-3}))
  while ((SECONDS < deadline)); do
    if pane "$1" | grep -qE -- "$3"; then return 0; fi
    sleep 0.1
  done
  fail "no '$3' on $1's screen within $2 s"
}

# start_server SERVER ARGS...: on port 0 (the server picks a free one and logs it), log in
# $WORK/server.log; sets SERVER_PID and PORT.
start_server() {
  local server=$1
  shift
  "$server" --port 0 --bind 127.0.0.1 --log-level info "$@" >"$WORK/server.log" 2>&1 &
  SERVER_PID=$!
  PORT=""
  local deadline=$((SECONDS + 10))
  while ((SECONDS < deadline)) && [[ -z "$PORT" ]]; do
    PORT=$(sed -nE 's/.*ready .*port=([0-9]+).*/\1/p; s/.*"event":"ready".*"port":([0-9]+).*/\1/p' \
      "$WORK/server.log" | head -n 1 || true)
    [[ -z "$PORT" ]] && sleep 0.1
  done
  [[ -n "$PORT" ]] || fail "the server did not log its port"
  echo "server on port $PORT"
}

# quit_client PANE: q asks, y quits, and the client exits with status 0.
quit_client() {
  tm send-keys -t "$1" q
  wait_for "$1" 5 'Quit\?'
  tm send-keys -t "$1" y
  wait_for "$1" 5 '^CLIENT_EXIT=0'
}

# idle_comes_back PANE SECONDS: within SECONDS the server drops the idle player (its log
# says reason=idle) and the client stays, offering to play again; a key takes the player
# back (issue 26: the idle kick used to end the client).
idle_comes_back() {
  wait_for "$1" "$2" 'press a key to play again'
  pane "$1" | grep -q '^CLIENT_EXIT=' && fail "the client exited on the idle kick"
  grep -q 'reason=idle' "$WORK/server.log" || fail "the server did not log the idle drop"
  tm send-keys -t "$1" Enter
  wait_for "$1" 10 'Reconnected: welcome back'
}
