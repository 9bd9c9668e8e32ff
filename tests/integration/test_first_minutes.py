#!/usr/bin/env python3
"""A new player's first ten minutes (issue 26), the server's part, with the real binaries:
the console's announce sends its text from the command line; --record with --record-dir
records room 1 into PATH and the other rooms under DIR (issue 38), and a PATH among DIR's
rooms is refused at startup (exit 2, both flags named) and writes nothing."""
import json, os, re, subprocess, sys, tempfile

from harness import SERVER, Failure, Server, check, finish_bots, main, start_bots, wait_for


def console(path, *words):
    p = subprocess.run([SERVER, "--console", path, *words], capture_output=True, text=True, timeout=10)
    return p.returncode, (json.loads(p.stdout) if p.stdout.strip() else None), p.stderr


def test_announce():
    """`fts-server --console PATH announce TEXT...` reaches every connected player with the
    words joined by spaces; announce without text is a usage error that sends nothing."""
    d = tempfile.mkdtemp(prefix="fts-announce-")
    sock = os.path.join(d, "host.sock")
    with Server("--console-socket", sock) as srv:
        bots = start_bots("--connect", srv.address, "--name", "new", "--count", "2", "--behavior", "idle",
                          "--duration", "4")
        wait_for(lambda: len(re.findall(r"connect player=", srv.text())) >= 2, 10, "two players")
        rc, out, err = console(sock, "announce", "server", "restarts", "at", "noon")
        check(rc == 0 and out and out["ok"] is True and out["told"] == 2, f"announce: rc {rc}, {out}, {err.strip()}")
        check(re.search(r'console request=.*"cmd":"announce".*"text":"server restarts at noon"', srv.text()),
              "the server did not log the announce with its text")
        before = srv.text().count("console request=")
        rc, out, err = console(sock, "announce")
        check(rc == 2 and out is None and "announce TEXT" in err, f"announce without text: rc {rc}, {out}, {err}")
        check(srv.text().count("console request=") == before, "a usage error reached the server")
        finish_bots(bots, 20)


def test_record_flags():
    """--record PATH with --record-dir DIR (flags, or a flag and a variable): room 1's
    journal is PATH, room 2's DIR/room-2, and DIR/room-1 is never made. A PATH that is DIR
    or inside it (other than DIR/room-1) exits 2 at startup naming both; nothing is made."""
    d = tempfile.mkdtemp(prefix="fts-recflags-")
    record_dir = os.path.join(d, "rooms")
    for bad in (os.path.join(record_dir, "room-2"), record_dir):
        for args, env in ((["--record", bad, "--record-dir", record_dir], {}),
                          (["--record-dir", record_dir], {"FTS_RECORD": bad})):
            try:
                p = subprocess.run([SERVER, "--port", "0", *args], capture_output=True, text=True, timeout=5,
                                   env={**os.environ, **env})
            except subprocess.TimeoutExpired:
                raise Failure(f"fts-server {' '.join(args)} {env} started with --record inside --record-dir")
            check(p.returncode == 2, f"{args} {env}: exit {p.returncode}, want 2; stderr {p.stderr.strip()}")
            check("--record " in p.stderr and "--record-dir" in p.stderr, f"{args} {env}: message {p.stderr.strip()!r}")
            check(not os.path.exists(record_dir), f"{args} {env}: a refused start wrote {os.listdir(d)}")
    # Together: one seat a match, two bots, two rooms.
    forms = [(["--record", "R", "--record-dir", "D"], {}), (["--record-dir", "D"], {"FTS_RECORD": "R"}),
             (["--record", "R"], {"FTS_RECORD_DIR": "D"})]
    for n, (args, env) in enumerate(forms):
        record, rooms = os.path.join(d, f"room1-{n}"), os.path.join(d, f"rooms-{n}")
        paths = {"R": record, "D": rooms}
        args = [paths.get(a, a) for a in args]
        env = {k: paths[v] for k, v in env.items()}
        with Server("--max-players", "1", *args, env=env) as srv:
            finish_bots(start_bots("--connect", srv.address, "--name", "rec", "--count", "2", "--behavior", "idle",
                                   "--duration", "1"), 20)
            check(srv.stop() == 0, f"{args} {env}: the server did not exit 0")
        for path in (os.path.join(record, "journal-000001.jsonl"), os.path.join(rooms, "room-2", "journal-000001.jsonl")):
            check(os.path.exists(path) and os.path.getsize(path) > 0, f"{args} {env} wrote nothing to {path}")
        check(not os.path.exists(os.path.join(rooms, "room-1")), f"{args} {env}: room 1 recorded twice")
    # Each alone still records (room 1 into PATH; every room under DIR), as journals.
    record, record_dir = os.path.join(d, "room1"), os.path.join(d, "rooms")
    for args, path in ((["--record", record], os.path.join(record, "journal-000001.jsonl")),
                       (["--record-dir", record_dir], os.path.join(record_dir, "room-1", "journal-000001.jsonl"))):
        with Server(*args) as srv:
            finish_bots(start_bots("--connect", srv.address, "--name", "rec", "--behavior", "idle",
                                   "--duration", "1"), 20)
            check(srv.stop() == 0, f"{args}: the server did not exit 0")
        check(os.path.exists(path) and os.path.getsize(path) > 0, f"{args} alone wrote nothing to {path}")


if __name__ == "__main__":
    sys.exit(main({"announce": test_announce, "record_flags": test_record_flags}))
