#!/usr/bin/env bash
# Sets everything up and runs the main job. For now (before the server lands): fts-sim
# on the shipped game-like scene and on a headless 4-player match, printing reports.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
bash .ci/deps.sh
bash .ci/build.sh build
echo "== fts-sim tests/scenes/game-like.json"
./build/server/fts-sim tests/scenes/game-like.json
if ./build/server/fts-sim --help | grep -q -- --match; then
  echo "== fts-sim --match --players 4 --levels 5 --seed 7"
  ./build/server/fts-sim --match --players 4 --levels 5 --seed 7
fi
