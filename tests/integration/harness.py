"""Helpers for the integration tests: real processes on loopback, free ports, and
waits with deadlines (poll for an event, never sleep and hope)."""
import json, os, re, shutil, signal, socket, subprocess, sys, tempfile, time
from datetime import datetime, timezone

BIN = os.environ.get("FTS_BIN_DIR", "build")
SERVER = os.path.join(BIN, "server", "fts-server")
BOT = os.path.join(BIN, "client", "fts-bot")
HERE = os.path.dirname(os.path.abspath(__file__))


class Failure(Exception):
    pass


def check(cond, message):
    if not cond:
        raise Failure(message)


def wait_for(predicate, timeout_s, what):
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        value = predicate()
        if value:
            return value
        time.sleep(0.02)
    raise Failure(f"timed out after {timeout_s} s waiting for {what}")


class Server:
    """fts-server on a free port; its log (stderr) goes to a file we can poll."""

    def __init__(self, *args, env=None):
        self.dir = tempfile.mkdtemp(prefix="fts-it-")
        self.log_path = os.path.join(self.dir, "server.log")
        self.log = open(self.log_path, "w")
        # Every test process runs on 127.0.0.1: one host for the server's per-address cap,
        # so it is lifted here (a test that means the cap gives its own, the last wins).
        self.proc = subprocess.Popen([SERVER, "--port", "0", "--max-per-address", "16", *args],
                                     stdout=self.log, stderr=self.log,
                                     env={**os.environ, **(env or {})})
        m = wait_for(lambda: re.search(r'ready .*port=(\d+)|"event":"ready".*"port":(\d+)', self.text()), 10,
                     "the server's ready line")
        self.port = int(m.group(1) or m.group(2))
        self.address = f"127.0.0.1:{self.port}"

    def text(self):
        with open(self.log_path) as f:
            return f.read()

    def stop(self, sig=signal.SIGINT, timeout_s=10):
        if self.proc.poll() is None:
            self.proc.send_signal(sig)
        try:
            return self.proc.wait(timeout=timeout_s)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            raise Failure("the server did not exit after SIGINT")

    def __enter__(self):
        return self

    def __exit__(self, exc_type, exc, tb):
        if self.proc.poll() is None:
            self.proc.kill()
            self.proc.wait()
        if exc_type is not None:  # a failing test shows what the server saw
            print("--- server log (tail) ---")
            print("\n".join(self.text().splitlines()[-25:]))


def free_port():
    """A TCP port that is free on 127.0.0.1 now."""
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def records(srv, event):
    """The server's records of one event (--log-format json), each with "t": its "ts" in
    seconds since the epoch (time.time()'s clock)."""
    out = []
    for line in srv.text().splitlines():
        try:
            r = json.loads(line)
        except ValueError:  # not a record, or the one being written
            continue
        if isinstance(r, dict) and r.get("event") == event:
            r["t"] = datetime.strptime(r["ts"], "%Y-%m-%dT%H:%M:%S.%fZ").replace(tzinfo=timezone.utc).timestamp()
            out.append(r)
    return out


def rss_kib(pid):
    """The resident set of a process now, KiB (/proc/PID/status VmRSS)."""
    with open(f"/proc/{pid}/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    return 0


def start_bots(*args):
    """Starts fts-bot with a report file; returns (process, report path)."""
    fd, report = tempfile.mkstemp(prefix="fts-bot-", suffix=".json")
    os.close(fd)
    proc = subprocess.Popen([BOT, *args, "--report", report], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    return proc, report


def finish_bots(started, timeout_s):
    proc, report = started
    try:
        out, err = proc.communicate(timeout=timeout_s)
    except subprocess.TimeoutExpired:
        proc.kill()
        out, err = proc.communicate()
        raise Failure(f"fts-bot did not finish within {timeout_s} s: {err}")
    with open(report) as f:
        text = f.read()
    data = json.loads(text) if text.strip() else []
    return proc.returncode, data, err


def run_bots(*args, timeout_s=120):
    return finish_bots(start_bots(*args), timeout_s)


def write_script(text):
    fd, path = tempfile.mkstemp(prefix="fts-script-", suffix=".txt")
    with os.fdopen(fd, "w") as f:
        f.write(text)
    return path


def main(tests):
    """Runs the test named by argv[1] (one CTest entry per test)."""
    name = sys.argv[1] if len(sys.argv) > 1 else ""
    if name not in tests:
        print(f"unknown test {name!r}; known: {', '.join(tests)}")
        return 2
    # Every temporary directory of the case (tempfile's) inside one of its own: removed when
    # the case passes, kept (and named) when it fails, for its logs.
    own = tempfile.mkdtemp(prefix=f"fts-test-{name}-")
    os.chmod(own, 0o711)  # others may pass through (PostgreSQL's own user, to its data directory)
    tempfile.tempdir = own
    keep = True
    try:
        tests[name]()
        keep = False
    except Failure as e:
        print(f"FAIL {name}: {e} (its files: {own})")
        return 1
    except SystemExit as e:  # a skip (77) leaves nothing worth keeping
        keep = e.code not in (None, 0, 77)
        raise
    finally:
        tempfile.tempdir = None
        if not keep:
            shutil.rmtree(own, ignore_errors=True)
    print(f"ok {name}")
    return 0
