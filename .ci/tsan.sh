#!/usr/bin/env bash
# The ThreadSanitizer run (issues 29, 39): every test that starts threads, in a TSan
# build: the server's, journal's, fleet's (the Agones client's watchdog) and profiles'
# (the writer thread) unit tests, and the process tests whose servers step rooms on 2
# threads, talk to a stand-in Agones sidecar, serve /metrics and the console to hostile
# clients, or write profiles. Not in the default test
# command (a third full build would not fit its 20 minutes); run it after changing
# anything the tick's parallel phases touch (server/app/game_host.*, room.*,
# worker_pool.*, protocol/src/server.cpp):
#   bash .ci/tsan.sh
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
jobs=${FTS_JOBS:-$(nproc)}
FTS_TARGETS="fts-server fts-sim fts-bot fts-client fts_server_tests fts_journal_tests fts_fleet_tests fts_profiles_tests" \
  bash .ci/build.sh build-tsan -DFTS_WERROR=ON -DFTS_TSAN=ON
# .ci/tsan.supp: races inside Debian libraries (each one explained there).
export TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1 suppressions=$root/.ci/tsan.supp"
build-tsan/tests/fts_server_tests
build-tsan/tests/fts_journal_tests
build-tsan/tests/fts_fleet_tests
build-tsan/tests/fts_profiles_tests
FTS_THREADS=2 ctest --test-dir build-tsan \
  -R '^(rooms\.|integration\.(levels|exactly_once|reconnect|garbage)|journal\.kill_resume$|agones\.|hostile\.|profiles\.(sqlite_record|kill_resume|pg_down_up)$)' \
  -j "$jobs" --output-on-failure --timeout 900
echo "tsan: clean"
