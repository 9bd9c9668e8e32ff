#!/usr/bin/env python3
"""A new player's first ten minutes (issue 26), the server's part, with the real binaries:
the console's announce sends its text from the command line; --record with --record-dir
is refused at startup (exit 2, both flags named) and writes nothing."""
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
    """--record FILE with --record-dir DIR (flags, or a flag and a variable) exits 2 at
    startup with a message naming both flags; neither FILE nor DIR is made."""
    d = tempfile.mkdtemp(prefix="fts-recflags-")
    record, record_dir = os.path.join(d, "room1"), os.path.join(d, "rooms")
    forms = [(["--record", record, "--record-dir", record_dir], {}),
             (["--record-dir", record_dir], {"FTS_RECORD": record}),
             (["--record", record], {"FTS_RECORD_DIR": record_dir})]
    for args, env in forms:
        try:
            p = subprocess.run([SERVER, "--port", "0", *args], capture_output=True, text=True, timeout=5,
                               env={**os.environ, **env})
        except subprocess.TimeoutExpired:
            raise Failure(f"fts-server {' '.join(args)} {env} started instead of refusing the combination")
        check(p.returncode == 2, f"{args} {env}: exit {p.returncode}, want 2; stderr {p.stderr.strip()}")
        check("--record " in p.stderr and "--record-dir" in p.stderr, f"{args} {env}: message {p.stderr.strip()!r}")
        check(not os.path.exists(record) and not os.path.exists(record_dir),
              f"{args} {env}: a refused start wrote {os.listdir(d)}")
    # Each alone still records (room 1 into PATH; every room under DIR), as journals.
    for args, path in ((["--record", record], os.path.join(record, "journal-000001.jsonl")),
                       (["--record-dir", record_dir], os.path.join(record_dir, "room-1", "journal-000001.jsonl"))):
        with Server(*args) as srv:
            finish_bots(start_bots("--connect", srv.address, "--name", "rec", "--behavior", "idle",
                                   "--duration", "1"), 20)
            check(srv.stop() == 0, f"{args}: the server did not exit 0")
        check(os.path.exists(path) and os.path.getsize(path) > 0, f"{args} alone wrote nothing to {path}")


if __name__ == "__main__":
    sys.exit(main({"announce": test_announce, "record_flags": test_record_flags}))
