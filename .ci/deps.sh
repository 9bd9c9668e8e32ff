#!/usr/bin/env bash
# Installs the build and test dependencies from Debian 12's packages (idempotent).
set -euo pipefail
packages=(build-essential cmake ninja-build ccache pkg-config
          libboost-dev nlohmann-json3-dev libspdlog-dev catch2 libsodium-dev libcli11-dev
          clang libclang-rt-14-dev tmux gnuplot-nox python3
          prometheus-cpp-dev libcpp-httplib-dev prometheus python3-yaml)
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
