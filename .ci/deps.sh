#!/usr/bin/env bash
# Installs the build and test dependencies from Debian 12's packages (idempotent).
#   bash .ci/deps.sh           everything: build, tests, benchmarks, fuzzing, Prometheus
#   bash .ci/deps.sh --image   only what building fts-server and fts-bot needs (the image's
#                              build stage: no clang, tmux, gnuplot, Catch2 or prometheus)
set -euo pipefail
image=(build-essential cmake ninja-build pkg-config
       libboost-dev nlohmann-json3-dev libspdlog-dev libsodium-dev libcli11-dev
       prometheus-cpp-dev libcpp-httplib-dev libsoci-dev libsqlite3-dev libpq-dev)
packages=("${image[@]}" ccache lld catch2 clang libclang-rt-14-dev tmux gnuplot-nox python3
          prometheus python3-yaml python3-nacl python3-msgpack libbenchmark-dev
          openssh-server openssh-client stress-ng postgresql)
if [[ ${1:-} == --image ]]; then
  packages=("${image[@]}")
elif [[ -n ${1:-} ]]; then
  echo "usage: bash .ci/deps.sh [--image]" >&2
  exit 2
fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  sudo_cmd=()
  [[ $(id -u) -eq 0 ]] || sudo_cmd=(sudo)
  "${sudo_cmd[@]}" apt-get update
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y --no-install-recommends "${missing[@]}"
fi
