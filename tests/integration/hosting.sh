#!/usr/bin/env bash
# An operator's view of fts-server, end to end with real processes on loopback:
#  - starts on a free port (--port 0), the port read from the `ready` log line;
#  - `fts-bot --probe` passes against it, and fails (exit 1, a reason) once it is killed;
#  - starts with the shipped example config, and with FTS_PORT (+ JSON logs) from the
#    environment;
#  - a bad flag, a bad flag value, a bad environment value and a config with an unknown
#    key each exit non-zero with a message naming it, before binding (no `ready`).
# Every wait polls with a deadline; nothing sleeps a fixed time for a result.
#   hosting.sh FTS_SERVER FTS_BOT SOURCE_DIR
set -uo pipefail
server=${1:?usage: hosting.sh FTS_SERVER FTS_BOT SOURCE_DIR}
bot=${2:?}
root=${3:?}
work=$(mktemp -d)
pids=()
cleanup() {
  for p in "${pids[@]}"; do kill "$p" 2>/dev/null; done
  rm -rf "$work"
}
trap cleanup EXIT
failures=0
ok() { echo "ok   - $1"; }
bad() { echo "FAIL - $1"; failures=$((failures + 1)); }

# start_server NAME [env assignments...] -- [flags...]: runs fts-server in the background
# with its log in $work/NAME.log; sets SERVER_PID.
start_server() {
  local name=$1
  shift
  local envs=()
  while (($#)) && [[ $1 != -- ]]; do envs+=("$1"); shift; done
  shift
  env "${envs[@]}" "$server" --bind 127.0.0.1 --stats-interval-ms 200 "$@" >"$work/$name.out" 2>"$work/$name.log" &
  SERVER_PID=$!
  pids+=("$SERVER_PID")
}

# wait_ready NAME: polls the log for the ready record (text or JSON) for up to 10 s;
# sets PORT. Fails early if the server exits.
wait_ready() {
  local name=$1 deadline=$((SECONDS + 10)) line
  PORT=
  while ((SECONDS < deadline)); do
    line=$(grep -m1 -E '(\] ready |"event":"ready")' "$work/$name.log")
    if [[ -n $line ]]; then
      PORT=$(sed -nE 's/.*( port=|"port":)([0-9]+).*/\2/p' <<<"$line")
      [[ -n $PORT ]] && return 0
    fi
    kill -0 "$SERVER_PID" 2>/dev/null || break
    sleep 0.05
  done
  echo "--- $name.log"; cat "$work/$name.log"
  return 1
}

stop_server() {
  kill "$SERVER_PID" 2>/dev/null
  local deadline=$((SECONDS + 5))
  while kill -0 "$SERVER_PID" 2>/dev/null && ((SECONDS < deadline)); do sleep 0.05; done
  kill -9 "$SERVER_PID" 2>/dev/null
  wait "$SERVER_PID" 2>/dev/null
}

probe() {  # probe PORT: sets PROBE_RC, PROBE_ERR, PROBE_S (whole seconds taken)
  local t0=$SECONDS
  "$bot" --probe "127.0.0.1:$1" >"$work/probe.out" 2>"$work/probe.err"
  PROBE_RC=$?
  PROBE_ERR=$(cat "$work/probe.err")
  PROBE_S=$((SECONDS - t0))
}

# 1. A free port, the probe, then a dead port.
start_server free -- --port 0
if wait_ready free; then
  ok "server ready on a free port ($PORT), read from the ready line"
  probe "$PORT"
  if ((PROBE_RC == 0)); then ok "probe passes against the running server"; else bad "probe against the running server exited $PROBE_RC: $PROBE_ERR"; fi
  stop_server
  dead=$PORT
  probe "$dead"
  # The probe gives up after its own 2 s without a snapshot (or at once on an error) and
  # says why. The process's wall time adds start-up and exit (seconds for a sanitized
  # build on a loaded machine), so the wall bound here only catches a hang.
  if ((PROBE_RC == 1)) && [[ -n $PROBE_ERR ]] && ((PROBE_S <= 30)); then
    ok "probe against the dead port exits 1 in ${PROBE_S}s with a reason: $PROBE_ERR"
  else
    bad "probe against the dead port: exit $PROBE_RC after ${PROBE_S}s, stderr: '$PROBE_ERR' (want 1, a reason, <= 30 s)"
  fi
else
  bad "server on --port 0 never logged ready"
fi

# 2. The shipped example config.
start_server config -- --port 0 --config "$root/docker/server-config.example.json"
if wait_ready config; then
  probe "$PORT"
  if ((PROBE_RC == 0)); then ok "server runs the example config (probe passes)"; else bad "example config: probe exited $PROBE_RC: $PROBE_ERR"; fi
else
  bad "server with --config docker/server-config.example.json never logged ready"
fi
stop_server

# 3. Settings from the environment: FTS_PORT and JSON logs, ready and stats records.
want=$(python3 -c 'import socket; s=socket.socket(socket.AF_INET, socket.SOCK_DGRAM); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
start_server env FTS_PORT="$want" FTS_LOG_FORMAT=json FTS_CONFIG="$root/docker/server-config.example.json" --
if wait_ready env && [[ $PORT == "$want" ]]; then
  ok "FTS_PORT=$want from the environment is the bound port"
  probe "$PORT"
  if ((PROBE_RC == 0)); then ok "probe passes against the environment-configured server"; else bad "env server: probe exited $PROBE_RC: $PROBE_ERR"; fi
  deadline=$((SECONDS + 10))
  until grep -q '"event":"stats"' "$work/env.log" || ((SECONDS >= deadline)); do sleep 0.05; done
  if python3 - "$work/env.log" "$want" <<'PY'
import json, sys
records = [json.loads(l) for l in open(sys.argv[1]) if l.strip()]
ready = [r for r in records if r.get("event") == "ready"]
stats = [r for r in records if r.get("event") == "stats"]
assert len(ready) == 1 and ready[0]["port"] == int(sys.argv[2]), ready
assert stats and "players" in stats[0] and "tick" in stats[0], stats[:1]
assert all("ts" in r and "level" in r for r in records)
PY
  then ok "FTS_LOG_FORMAT=json: every line is a JSON record; one ready record, then stats records"
  else bad "JSON log records (see above)"; cat "$work/env.log"; fi
else
  bad "server with FTS_PORT=$want did not log ready on that port (got '$PORT')"
fi
stop_server

# 4. Bad settings: non-zero exit, a message naming the setting, nothing bound.
echo '{"tick_rate_hz": 100, "no_such_setting": 3}' >"$work/bad-config.json"
refuse() {  # refuse DESCRIPTION NAME_IN_MESSAGE [env...] -- [flags...]
  local what=$1 name=$2
  shift 2
  local envs=()
  while (($#)) && [[ $1 != -- ]]; do envs+=("$1"); shift; done
  shift
  timeout 10 env "${envs[@]}" "$server" --port 0 --bind 127.0.0.1 "$@" >"$work/refuse.out" 2>"$work/refuse.err"
  local rc=$? msg
  msg=$(cat "$work/refuse.err")
  if ((rc != 0 && rc != 124)) && grep -qF -- "$name" <<<"$msg" && ! grep -qE 'ready|bind_failed' "$work/refuse.err" "$work/refuse.out"; then
    ok "$what: exit $rc before binding: $msg"
  else
    bad "$what: exit $rc, stderr '$msg' (want non-zero, naming $name, no ready)"
  fi
}
refuse "a bad flag" --no-such-flag -- --no-such-flag 1
refuse "a bad flag value" --tick-rate -- --tick-rate 5
refuse "a bad environment value" FTS_TICK_RATE FTS_TICK_RATE=5 --
refuse "a bad FTS_LOG_FORMAT" FTS_LOG_FORMAT FTS_LOG_FORMAT=xml --
refuse "a bad bind address" --bind -- --bind not-an-address
refuse "a bad FTS_PORT" FTS_PORT FTS_PORT=70000 --
refuse "a config with an unknown key" no_such_setting -- --config "$work/bad-config.json"
refuse "a missing config file" "$work/missing.json" -- --config "$work/missing.json"

if ((failures)); then
  echo "$failures check(s) failed"
  exit 1
fi
echo "all hosting checks passed"
