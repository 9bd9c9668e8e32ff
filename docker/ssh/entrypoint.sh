#!/usr/bin/env bash
# The ssh image's entry point (Dockerfile stage "ssh", compose service "ssh"): host keys
# made once into the volume /etc/ssh/host-keys (a restarted container keeps its identity,
# so players' known_hosts stay valid), the game account "play" set up by fts-ssh-setup
# (open to any key), then sshd in the foreground on port 2222 (FTS_SSH_PORT), logging to
# stderr.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
keys=/etc/ssh/host-keys
install -d -m 700 "$keys"
for type in ed25519 rsa; do
  [[ -f $keys/ssh_host_${type}_key ]] || ssh-keygen -q -t "$type" -N '' -f "$keys/ssh_host_${type}_key"
done
# The host keys through a drop-in of sshd_config, so that every sshd that reads the
# config (fts-ssh-setup's `sshd -t` check included) finds them: the image has none in
# /etc/ssh, and passing them only on sshd's command line left that check with "no
# hostkeys available", which ended the container at its first start (issue 37, 9).
install -d -m 755 /etc/ssh/sshd_config.d
printf 'HostKey %s\n' "$keys/ssh_host_ed25519_key" "$keys/ssh_host_rsa_key" \
  >/etc/ssh/sshd_config.d/00-fts-host-keys.conf
# sshd's privilege separation directory before anything runs sshd: fts-ssh-setup's
# `sshd -t` refuses to check the config without it ("Missing privilege separation
# directory: /run/sshd"), which ended the container at its first start (found by
# .ci/container.sh's ssh step, 2026-12-06).
install -d -m 755 /run/sshd
empty=()
[[ -n ${FTS_SSH_EMPTY_PASSWORD:-} ]] && empty=(--empty-password)
bash "$here/fts-ssh-setup" --connect "${FTS_SSH_SERVER:-server:7777}" --open "${empty[@]}" \
  --max-sessions "${FTS_SSH_MAX_SESSIONS:-8}" --max-per-key "${FTS_SSH_MAX_PER_KEY:-2}" \
  --idle-exit-s "${FTS_SSH_IDLE_EXIT_S:-600}" install
exec /usr/sbin/sshd -D -e -p "${FTS_SSH_PORT:-2222}"
