#!/usr/bin/env python3
"""Faults around a running server (issue 30), with real processes and a real file system.

journal_disk_full: the journal lives on a 4 MiB tmpfs that a filler file then fills
  while four bots play. The server keeps playing (the room's tick goes on, the bots keep
  getting snapshots), logs "journal_failed" once however long the disk stays full, and
  says so on the console (stats: journal.failing) and in /metrics
  (fts_journal_failing_rooms, fts_journal_failures_total). When the filler is removed the
  journal goes on from a new checkpoint ("journal_recovered"), and a server killed with
  SIGKILL after that resumes the room at a tick after the recovery.
journal_read_only: the same, but the room's directory turns read-only (a read-only
  tmpfs is mounted over it: new segments cannot be created) and then writable again.

The tmpfs needs a mount namespace: the test runs itself again under `unshare -m` (as
root) or `unshare -rm` (as a user); where neither works it is skipped (exit 77)."""
import json, os, re, shutil, signal, socket, subprocess, sys, tempfile, time, urllib.request

from harness import SERVER, Failure, Server, check, main, start_bots, wait_for

NS_MARK = "FTS_FAULTS_IN_NAMESPACE"


def in_namespace():
    """Runs this test again in a private mount namespace; returns its exit code, or None
    when already inside one."""
    if os.environ.get(NS_MARK):
        return None
    unshare = shutil.which("unshare")
    if not unshare:
        print("skip: no unshare(1)")
        sys.exit(77)
    for flags in (["-m"], ["-rm"]) if os.geteuid() == 0 else (["-rm"],):
        probe = subprocess.run([unshare, *flags, "--propagation", "private", "true"], capture_output=True)
        if probe.returncode == 0:
            env = {**os.environ, NS_MARK: "1"}
            return subprocess.run([unshare, *flags, "--propagation", "private", sys.executable, *sys.argv],
                                  env=env).returncode
    print("skip: cannot make a mount namespace here")
    sys.exit(77)


def mount_tmpfs(path, size, read_only=False):
    os.makedirs(path, exist_ok=True)
    opts = f"size={size}" + (",ro" if read_only else "")
    subprocess.run(["mount", "-t", "tmpfs", "-o", opts, "tmpfs", path], check=True)


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def console(sock, request):
    with socket.socket(socket.AF_UNIX, socket.SOCK_STREAM) as c:
        c.settimeout(10)
        c.connect(sock)
        c.sendall(json.dumps(request).encode() + b"\n")
        data = b""
        while not data.endswith(b"\n"):
            chunk = c.recv(65536)
            check(chunk, "the console closed without an answer")
            data += chunk
    return json.loads(data)


def metric(port, name):
    body = urllib.request.urlopen(f"http://127.0.0.1:{port}/metrics", timeout=5).read().decode()
    m = re.search(rf"^{name}(?:{{[^}}]*}})? ([0-9.e+-]+)$", body, re.M)
    return float(m.group(1)) if m else None


def room_tick(sock):
    rooms = console(sock, {"cmd": "rooms"})["rooms"]
    check(len(rooms) == 1, f"one room expected: {rooms}")
    return rooms[0]["tick"], rooms[0]["code"]


def fill(path):
    """Writes zeros until the file system is full."""
    with open(path, "wb") as f:
        block = b"\0" * 65536
        try:
            while True:
                f.write(block)
                f.flush()
        except OSError:
            pass


def journal_fault(kind):
    code = in_namespace()
    if code is not None:
        sys.exit(code)
    work = tempfile.mkdtemp(prefix="fts-faults-")
    disk = os.path.join(work, "disk")
    mount_tmpfs(disk, "4m")
    journal = os.path.join(disk, "journal")
    sock = os.path.join(work, "console.sock")
    mport = free_port()
    args = ["--journal-dir", journal, "--journal-checkpoint-s", "1", "--journal-sync-ms", "50",
            "--console-socket", sock, "--metrics", f"127.0.0.1:{mport}", "--log-format", "text"]
    bots = None
    try:
        with Server(*args) as srv:
            bots = start_bots("--connect", srv.address, "--count", "4", "--behavior", "hunter", "--duration", "120",
                              "--name", "disk")
            wait_for(lambda: os.path.isdir(journal) and any(len(d) == 5 for d in os.listdir(journal)), 20,
                     "the room's journal directory")
            tick0, room = wait_for(lambda: room_tick(sock) if room_tick(sock)[0] > 200 else None, 30, "play")
            room_dir = os.path.join(journal, room)
            check(metric(mport, "fts_journal_failing_rooms") == 0, "a failing journal before the fault")

            if kind == "disk_full":
                fill(os.path.join(disk, "filler"))
            else:
                mount_tmpfs(room_dir, "64k", read_only=True)
            wait_for(lambda: "journal_failed" in srv.text(), 20, "journal_failed in the log")
            stats = wait_for(lambda: (lambda s: s if s["journal"]["failing"] == 1 else None)(
                console(sock, {"cmd": "stats"})), 10, "the console's stats saying the journal fails")
            check(stats["journal"]["error"].startswith(room + ": journal:"), f"the console's error: {stats}")
            wait_for(lambda: metric(mport, "fts_journal_failing_rooms") == 1, 10, "fts_journal_failing_rooms 1")
            check(metric(mport, "fts_journal_failures_total") == 1, "fts_journal_failures_total is not 1")
            # It plays on while the journal fails: the tick goes on past several retries.
            t_fail, _ = room_tick(sock)
            wait_for(lambda: room_tick(sock)[0] > t_fail + 300, 20, "the room playing on")
            check(srv.text().count("journal_failed") == 1,
                  f"journal_failed logged {srv.text().count('journal_failed')} times, not once")
            check(srv.proc.poll() is None, "the server exited")

            if kind == "disk_full":
                os.remove(os.path.join(disk, "filler"))
            else:
                subprocess.run(["umount", room_dir], check=True)
            m = wait_for(lambda: re.search(r"journal_recovered durable_tick=(\d+)", srv.text()), 20,
                         "journal_recovered in the log")
            recovered_tick = int(m.group(1))
            check(recovered_tick > t_fail, f"recovered at tick {recovered_tick}, before the failure at {t_fail}")
            wait_for(lambda: metric(mport, "fts_journal_failing_rooms") == 0, 10, "fts_journal_failing_rooms 0")
            check(console(sock, {"cmd": "stats"})["journal"]["failing"] == 0, "the console still says failing")
            # Durable past the recovery: then a crash.
            wait_for(lambda: room_tick(sock)[0] > recovered_tick + 200, 20, "play after the recovery")
            time.sleep(0.2)  # two sync intervals (50 ms each) for the ticks just seen to be durable
            srv.proc.send_signal(signal.SIGKILL)
            srv.proc.wait()

        with Server(*args, "--resume") as again:
            m = wait_for(lambda: re.search(rf"resumed room=\d+ code={room} tick=(\d+)", again.text()), 30,
                         "the room resumed")
            check(int(m.group(1)) > recovered_tick,
                  f"resumed at tick {m.group(1)}, not after the recovery at {recovered_tick}")
            check("resume_skipped" not in again.text(), "a room was skipped at --resume")
            again.stop()
    finally:
        if bots and bots[0].poll() is None:
            bots[0].kill()
            bots[0].wait()
        subprocess.run(["umount", "-l", disk], capture_output=True)
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main({
        "journal_disk_full": lambda: journal_fault("disk_full"),
        "journal_read_only": lambda: journal_fault("read_only"),
    }))
