#!/usr/bin/env bash
# The image built and run for real, with podman on a debootstrap base (no registry, no
# Docker engine), as root:
#  1. podman, runc and debootstrap from Debian; podman's own config in a private
#     directory ($FTS_CONTAINER_DIR): runtime runc (crun fails here: "cgroups in hybrid
#     mode not supported"), default ulimits nofile=20000 / nproc=32768 (the default
#     1048576 is refused), storage under that directory;
#  2. debian:bookworm (and :bookworm-slim) imported from `debootstrap --variant=minbase`
#     with the mirror apt already uses (kept between runs; FTS_CONTAINER_CLEAN=1 starts over);
#  3. podman build --pull=never --network=host --format docker (OCI drops HEALTHCHECK);
#  4. podman run with FTS_* variables; waits for the `ready` JSON record; runs the image's
#     HEALTHCHECK; plays two bots from the host against it; checks the user is not root;
#  5. the ssh image (--target ssh) run beside it, FTS_SSH_SERVER naming that server: a
#     player with a fresh key runs `ssh -tt play@127.0.0.1` in tmux, is asked a name,
#     picks quick play and reaches the HUD (issue 37, 9: the image's sshd died at start);
#  6. stops the server (exit 0, `shutdown` logged); prints the image sizes and build time.
# CTest label `container` (not in the default run: ≈3 min). Exits 77 (skip) when not root.
#   bash .ci/container.sh
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
if [[ $(id -u) -ne 0 ]]; then
  echo "container: needs root (podman with runc as root); skipped"
  exit 77
fi
dir=${FTS_CONTAINER_DIR:-/var/tmp/fts-container}
image=fear-the-sphere:latest
name=fts-container-$$
step() { echo "== $*"; }
fail() { echo "FAIL - $*"; exit 1; }

step "packages"
need=()
for p in podman runc debootstrap; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || need+=("$p")
done
if ((${#need[@]})); then
  apt-get update
  DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends "${need[@]}"
fi

if [[ ${FTS_CONTAINER_CLEAN:-0} == 1 && -d $dir ]]; then
  step "clean: removing $dir"
  podman --root "$dir/storage" --runroot "$dir/run" system reset -f >/dev/null 2>&1 || true
  rm -rf "$dir"
fi
mkdir -p "$dir"
cat >"$dir/containers.conf" <<CONF
[containers]
default_ulimits = ["nofile=20000:20000", "nproc=32768:32768"]
[engine]
runtime = "runc"
cgroup_manager = "cgroupfs"
events_logger = "file"
CONF
cat >"$dir/storage.conf" <<CONF
[storage]
driver = "overlay"
graphroot = "$dir/storage"
runroot = "$dir/run"
CONF
export CONTAINERS_CONF=$dir/containers.conf CONTAINERS_STORAGE_CONF=$dir/storage.conf

cleanup() {
  podman rm -f "$name" >/dev/null 2>&1 || true
  [[ -n ${bots_pid:-} ]] && kill "$bots_pid" 2>/dev/null || true
}
trap cleanup EXIT

step "base image debian:bookworm"
if ! podman image exists debian:bookworm; then
  mirror=$(sed -nE 's/^URIs: *(http[^ ]*\/debian)\/?$/\1/p' /etc/apt/sources.list.d/*.sources 2>/dev/null | head -1)
  [[ -n $mirror ]] || mirror=$(sed -nE 's/^deb +(http[^ ]*\/debian)\/? +bookworm .*/\1/p' /etc/apt/sources.list 2>/dev/null | head -1)
  [[ -n $mirror ]] || mirror=http://deb.debian.org/debian
  rootfs=$dir/rootfs
  rm -rf "$rootfs"
  debootstrap --variant=minbase bookworm "$rootfs" "$mirror" >"$dir/debootstrap.log" 2>&1 ||
    { tail -20 "$dir/debootstrap.log"; fail "debootstrap from $mirror"; }
  # The mirror apt uses here, for apt-get inside the image too; no downloaded packages
  # or package lists left behind (debootstrap keeps them: ~80 MB).
  echo "deb $mirror bookworm main" >"$rootfs/etc/apt/sources.list"
  rm -rf "$rootfs"/var/cache/apt/archives/*.deb "$rootfs"/var/cache/apt/*.bin "$rootfs"/var/lib/apt/lists/*
  tar -C "$rootfs" -c . | podman import - debian:bookworm >/dev/null
  # -slim, like Docker Hub's: without documentation, manual pages and translations.
  tar -C "$rootfs" --exclude=./usr/share/doc --exclude=./usr/share/man --exclude=./usr/share/info \
    --exclude=./usr/share/locale -c . | podman import - debian:bookworm-slim >/dev/null
  rm -rf "$rootfs"
fi
podman image exists debian:bookworm-slim || podman tag debian:bookworm debian:bookworm-slim

step "build $image"
t0=$SECONDS
podman build --pull=never --network=host --format docker -f docker/Dockerfile -t "$image" . ||
  fail "podman build"
build_s=$((SECONDS - t0))
[[ $(podman image inspect --format '{{.Config.Healthcheck.Test}}' "$image") == *"fts-bot --probe"* ]] ||
  fail "the image has no HEALTHCHECK (built without --format docker?)"

step "run"
port=$(python3 -c 'import socket; s=socket.socket(socket.AF_INET, socket.SOCK_DGRAM); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
podman run -d --name "$name" --network=host -e FTS_PORT="$port" -e FTS_BIND=127.0.0.1 \
  -e FTS_MAX_PER_ADDRESS=8 -e FTS_STATS_INTERVAL_MS=1000 "$image" >/dev/null
deadline=$((SECONDS + 20))
until podman logs "$name" 2>&1 | grep -q '"event":"ready"'; do
  ((SECONDS < deadline)) || { podman logs "$name" 2>&1 | tail; fail "no ready record within 20 s"; }
  sleep 0.2
done
podman logs "$name" 2>&1 | grep -m1 '"event":"ready"'

step "HEALTHCHECK"
podman healthcheck run "$name" || fail "the image's HEALTHCHECK failed against the running server"
echo "healthy"

step "user"
uid=$(podman exec "$name" id -u)
[[ $uid != 0 ]] || fail "the server runs as root"
echo "uid $uid ($(podman exec "$name" id -un))"

step "two bots from the host"
bot=${FTS_BOT:-$root/build/client/fts-bot}
report=$dir/bots.json
if [[ -x $bot ]]; then
  "$bot" --connect "127.0.0.1:$port" --name host --count 2 --behavior hunter --duration 5 --report "$report" ||
    fail "fts-bot exit status $?"
else  # no host build: the image's own fts-bot, on the host network
  podman run --rm --network=host --entrypoint fts-bot "$image" --connect "127.0.0.1:$port" --name host \
    --count 2 --behavior hunter --duration 5 --report - >"$report" || fail "fts-bot (image) failed"
fi
python3 - "$report" <<'PY' || fail "the bots' report"
import json, sys
bots = json.load(open(sys.argv[1]))
assert len(bots) == 2, f"2 bots expected, got {len(bots)}"
for b in bots:
    assert b["snapshots_received"] > 20, f"{b['name']}: {b['snapshots_received']} snapshots"
print("bots:", ", ".join(f"{b['name']} {b['snapshots_received']} snapshots" for b in bots))
PY

step "ssh image: a player through it"
ssh_image=fear-the-sphere-ssh:latest
podman build --pull=never --network=host --format docker -f docker/Dockerfile --target ssh -t "$ssh_image" . ||
  fail "podman build --target ssh"
for p in tmux openssh-client; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" ||
    DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends "$p" >/dev/null
done
ssh_port=$(python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
podman run -d --name "$name-ssh" --network=host -e FTS_SSH_SERVER="127.0.0.1:$port" -e FTS_SSH_PORT="$ssh_port" \
  "$ssh_image" >/dev/null
deadline=$((SECONDS + 20))
until podman logs "$name-ssh" 2>&1 | grep -q "Server listening on .* port $ssh_port"; do
  [[ $(podman inspect --format '{{.State.Running}}' "$name-ssh") == true ]] ||
    { podman logs "$name-ssh" 2>&1 | tail; fail "the ssh container ended at start"; }
  ((SECONDS < deadline)) || { podman logs "$name-ssh" 2>&1 | tail; fail "sshd not listening within 20 s"; }
  sleep 0.2
done
keydir=$(mktemp -d)
ssh-keygen -q -t ed25519 -N '' -C '' -f "$keydir/key"
tsock=fts-container-$$
cleanup_ssh() { tmux -L "$tsock" kill-server 2>/dev/null || true; podman rm -f "$name-ssh" >/dev/null 2>&1 || true; rm -rf "$keydir"; }
trap 'cleanup_ssh; cleanup' EXIT
tmux -L "$tsock" new-session -d -s player -x 80 -y 24 \
  "LANG=C ssh -tt -i $keydir/key -o StrictHostKeyChecking=no -o UserKnownHostsFile=/dev/null -p $ssh_port play@127.0.0.1"
wait_pane() {  # wait_pane SECONDS REGEX
  local deadline=$((SECONDS + $1))
  until tmux -L "$tsock" capture-pane -p -t player | grep -qE -- "$2"; do
    ((SECONDS < deadline)) || { tmux -L "$tsock" capture-pane -p -t player; podman logs "$name-ssh" 2>&1 | tail;
                                fail "no '$2' on the ssh player's screen within $1 s"; }
    sleep 0.2
  done
}
wait_pane 30 'Your name'
tmux -L "$tsock" send-keys -t player "ann" Enter
wait_pane 15 'pick a room'
tmux -L "$tsock" send-keys -t player 2 Enter
wait_pane 20 '^Level:? [0-9]+ +Coins:? '
echo "ssh: a player through the image reached the HUD"
cleanup_ssh
ssh_size=$(podman image inspect --format '{{.Size}}' "$ssh_image")

step "stop"
podman stop -t 10 "$name" >/dev/null
code=$(podman inspect --format '{{.State.ExitCode}}' "$name")
[[ $code == 0 ]] || fail "exit status $code after SIGTERM"
podman logs "$name" 2>&1 | grep -q '"event":"shutdown"' || fail "no shutdown record"
echo "exit 0, shutdown logged"

size=$(podman image inspect --format '{{.Size}}' "$image")
echo "image $image: $((size / 1000000)) MB ($size bytes); build ${build_s} s"
echo "image $ssh_image: $((ssh_size / 1000000)) MB ($ssh_size bytes)"
echo "container: all checks passed"
