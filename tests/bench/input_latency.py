#!/usr/bin/env python3
"""Input-to-screen latency of fts-client, measured from outside the program (issue 28).

fts-server (and, if asked, idle bots in the same room) on loopback, fts-client in a
private tmux pane, optionally through tests/integration/relay.py. Once a level is being
played, each trial: wait until the own ball ('@' cells and its mass label, inside the
platform's frame; with
--glyphs braille the dots of the cells in the own colour, read from a capture with
escapes, the mass label on that colour counted as full cells) has
been still for --rest-ms, send an arrow key with `tmux send-keys`, then capture the pane
as fast as tmux answers (≈2 ms a capture here) until the ball's drawn cells change. The
latency is the middle of the capture that first shows the change minus the middle of the
send-keys call (each call's duration is in the CSV). Presses alternate Right and Left,
toward the middle near an edge, so the ball stays where it spawned (level 1: one still
enemy at the centre, nothing else moves).

What the number contains: the key through tmux and the client's input, the link up, the
server's next tick, the link down, the client's render delay (today it draws even its own
ball --interp-delay-ms = 100 ms behind the newest snapshot), its next frame (60 fps), and
the time the ball needs to move far enough to change a cell: from rest at 200 u/s², about
sqrt(2 d / a), with d the smallest distance from a drawn edge of the ball to the next cell
centre (≈ 0.1-0.3 u in a 240x80 pane: 30-55 ms). That last part is physics and the same
for every client; a bigger pane shrinks it. Never passes or fails on time.

usage: FTS_BIN_DIR=build python3 tests/bench/input_latency.py [--trials 20]
           [--variant NAME=CLIENT_ARGS ...] [--client-args "..."]
           [--rtt-ms 0 --jitter-ms 0 --loss 0 --burst-loss-pct 0 --burst-len 3 ...] [--relay]
           [--bots 0] [--csv FILE] [--json FILE]
  --variant NAME=ARGS   a client variant (repeatable): e.g. --variant new= --variant
                        old=--no-predict; each gets a fresh client and room, in the order
                        given, against the same server and relay. --client-args "ARGS" is
                        one variant named "default".
  relay flags           --rtt-ms R (delay R/2 each way), --jitter-ms J (each way),
                        --jitter-dist, --reorder (default: each flow keeps its order),
                        --loss P (random, fraction, each way), --burst-loss-pct X with
                        --burst-len N (Gilbert-Elliott bursts of mean N datagrams giving X %
                        loss each way), --dup P, --relay-seed S, --relay-args "..." (any
                        other relay.py flags). Any of them, or --relay, puts the relay in.
The client runs with TERM=xterm-256color and LANG=C.UTF-8 (so --glyphs auto picks braille:
name the glyphs in each variant). What the client writes to its terminal is piped out of
the pane (tmux pipe-pane) and counted: bytes_per_s over the trials (mostly a ball at
rest), then moving_bytes_per_s over 3 s of taps every 150 ms.
Output: one CSV row per trial (stdout, or --csv), then per variant a line
  summary variant=NAME n=N p50_ms=.. p99_ms=.. mean_ms=.. min_ms=.. max_ms=.. timeouts=..
  ... bytes_per_s=.. moving_bytes_per_s=..
and with --json FILE the summaries and the relay's counters per variant.
"""
import argparse, csv, json, os, re, shlex, shutil, signal, statistics, subprocess, sys, tempfile, time

HERE = os.path.dirname(os.path.abspath(__file__))
RELAY = os.path.join(HERE, "..", "integration", "relay.py")
BIN = os.environ.get("FTS_BIN_DIR", "build")
BORDER = re.compile(r"\+-{3,}\+")
OWN_RUN = re.compile(r"[@0-9]+")


class Failure(Exception):
    pass


class Tmux:
    def __init__(self):
        self.sock = f"fts-lat-{os.getpid()}"  # a private tmux server

    def run(self, *args, check=True):
        p = subprocess.run(["tmux", "-L", self.sock, *args], capture_output=True, text=True)
        if check and p.returncode != 0:
            raise Failure(f"tmux {' '.join(args)}: {p.stderr.strip()}")
        return p.stdout

    def capture(self, target):
        return self.run("capture-pane", "-p", "-e", "-t", target, check=False)

    def kill(self):
        self.run("kill-server", check=False)
        try:  # the server leaves its socket file behind
            os.unlink(os.path.join(os.environ.get("TMUX_TMPDIR", "/tmp"), f"tmux-{os.getuid()}", self.sock))
        except OSError:
            pass


def platform(lines):
    """(top, bottom, left, right) of the platform's frame, inclusive, or None."""
    top = None
    for r, line in enumerate(lines):
        m = BORDER.search(line)
        if m:
            if top is None:
                top, left, right = r, m.start(), m.end() - 1
            elif m.start() == left and m.end() - 1 == right:
                return top, r, left, right
    return None


SGR = re.compile(r"\x1b\[([0-9;]*)m")
BRAILLE0 = 0x2800
# A braille pattern's dot bits by (x, y): U+2800's dots 1-8.
BRAILLE_BITS = {(0, 0): 0x01, (0, 1): 0x02, (0, 2): 0x04, (1, 0): 0x08, (1, 1): 0x10, (1, 2): 0x20, (0, 3): 0x40,
                (1, 3): 0x80}


def styled_grid(text):
    """A pane captured with escapes (capture-pane -e) as rows of (char, fg, bg); colours as
    SGR numbers (30-37, 90-97 for fg; 40-47, 100-107 for bg), None for the default."""
    rows = []
    for line in text.split("\n"):
        row, fg, bg, pos = [], None, None, 0
        for m in SGR.finditer(line + "\x1b[m"):
            row += [(ch, fg, bg) for ch in line[pos:m.start()] if ch != "\x1b"]
            pos = m.end()
            params = [int(p) if p else 0 for p in m.group(1).split(";")] if m.group(1) else [0]
            k = 0
            while k < len(params):
                n = params[k]
                if n == 0:
                    fg = bg = None
                elif 30 <= n <= 37 or 90 <= n <= 97:
                    fg = n
                elif n == 39:
                    fg = None
                elif 40 <= n <= 47 or 100 <= n <= 107:
                    bg = n
                elif n == 49:
                    bg = None
                elif n in (38, 48):  # 256 or true colour: not ours; skip its arguments
                    k += 2 if k + 1 < len(params) and params[k + 1] == 5 else 4
                k += 1
        rows.append(row)
    return rows


def own_colour(grid):
    """The own ball's colour: the fg of the legend's '@' marker ("@ name")."""
    for row in grid:
        for k in range(len(row) - 1):
            if row[k][0] == "@" and row[k + 1][0] == " " and row[k][1] is not None:
                return row[k][1]
    return None


def own_ball(text):
    """The own ball's cells inside the frame and the frame, or (None, None). In ASCII: its
    '@' cells and its mass label (digits next to them); with the label left out, the label
    moving one cell over with the ball's centre would look like a move the other way. In
    braille dots (--glyphs braille; text captured with escapes): the lit dots of the cells
    in the own colour, as (row, col) in cell units, the label's cells (on the own colour)
    counted as full."""
    grid = styled_grid(text) if "\x1b[" in text else None
    if grid is not None:
        text = "\n".join("".join(c for c, _, _ in row) for row in grid)
    lines = text.split("\n")
    if grid is not None and any(BRAILLE0 <= ord(ch) <= BRAILLE0 + 0xFF for ch in text):
        box = platform(lines)
        if box is None:
            return None, None
        top, bottom, left, right = box
        own = own_colour(grid)
        dots = set()
        for r in range(top, bottom + 1):
            for c in range(left, min(right + 1, len(grid[r]))):
                ch, fg, bg = grid[r][c]
                if BRAILLE0 <= ord(ch) <= BRAILLE0 + 0xFF and fg == own:
                    bits = ord(ch) - BRAILLE0
                elif bg is not None and bg == own + 10:
                    bits = 0xFF
                else:
                    continue
                dots.update((r + (y + 0.5) / 4, c + (x + 0.5) / 2) for (x, y), bit in BRAILLE_BITS.items() if bits & bit)
        return (frozenset(dots) or None), box
    box = platform(lines)
    if box is None:
        return None, None
    top, bottom, left, right = box
    cells = set()
    for r in range(top, bottom + 1):
        row = lines[r][left:right + 1]
        for m in OWN_RUN.finditer(row):
            if "@" in m.group(0):
                cells.update((r, c) for c in range(left + m.start(), left + m.end()))
    return (frozenset(cells) or None), box


def centre(cells):
    return (sum(c for _, c in cells) / len(cells), sum(r for r, _ in cells) / len(cells))


def wait_for(predicate, timeout_s, what, poll_s=0.05):
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        v = predicate()
        if v:
            return v
        time.sleep(poll_s)
    raise Failure(f"timed out after {timeout_s} s waiting for {what}")


def percentile(values, q):
    """Linear interpolation between closest ranks (numpy's default)."""
    v = sorted(values)
    if not v:
        return float("nan")
    k = (len(v) - 1) * q
    lo = int(k)
    hi = min(lo + 1, len(v) - 1)
    return v[lo] + (v[hi] - v[lo]) * (k - lo)


class Relay:
    def __init__(self, server_addr, args):
        self.proc = subprocess.Popen([sys.executable, RELAY, "--listen", "0", "--server", server_addr, *args],
                                     stdout=subprocess.PIPE, text=True)
        line = self.proc.stdout.readline()
        m = re.match(r"relay ready port=(\d+)", line)
        if not m:
            raise Failure(f"the relay did not start: {line!r}")
        self.port = int(m.group(1))

    def counters(self, sig=signal.SIGUSR1):
        self.proc.send_signal(sig)
        return json.loads(self.proc.stdout.readline())

    def stop(self):
        if self.proc.poll() is not None:
            return None
        c = self.counters(signal.SIGTERM)
        self.proc.wait(timeout=5)
        return c


def counter_diff(a, b):
    """b - a for the relay's nested counters (numbers only)."""
    if isinstance(b, dict):
        return {k: counter_diff(a.get(k, 0) if isinstance(a, dict) else 0, v) for k, v in b.items()
                if isinstance(v, (dict, int, float)) and not isinstance(v, bool)}
    return b - a


def relay_args(a):
    args = ["--delay-ms", f"{a.rtt_ms / 2:g}", "--jitter-ms", f"{a.jitter_ms:g}", "--jitter-dist", a.jitter_dist,
            "--loss", f"{a.loss:g}", "--dup", f"{a.dup:g}", "--seed", str(a.relay_seed)]
    if a.burst_loss_pct > 0:
        share = a.burst_loss_pct / 100.0  # stationary share of the bad state: p / (p + 1/len)
        args += ["--burst-loss", f"{share / (a.burst_len * (1 - share)):.6g}", "--burst-len", f"{a.burst_len:g}"]
    if not a.reorder:
        args.append("--no-reorder")
    return args + shlex.split(a.relay_args)


class Session:
    """One fts-client in a tmux session, in a room of its own."""

    def __init__(self, tmux, name, client, port, extra, work, size):
        self.tmux, self.name = tmux, name
        state = os.path.join(work, f"state-{name}")
        cmd = (f"TERM=xterm-256color LANG=C.UTF-8 XDG_STATE_HOME={shlex.quote(state)} {shlex.quote(client)} "
               f"--connect 127.0.0.1:{port} --name lat --no-kitty --create {extra}; "
               f"echo CLIENT_EXIT=$?; sleep 600")
        tmux.run("new-session", "-d", "-s", name, "-x", str(size[0]), "-y", str(size[1]), cmd)

    def pane(self):
        """The pane with its colours (escape sequences)."""
        return self.tmux.capture(self.name)

    def text(self):
        """The pane as plain text."""
        return SGR.sub("", self.pane())

    def exited(self, text):
        m = re.search(r"CLIENT_EXIT=(\d+)", text)
        return m and m.group(1)

    def start_level(self):
        def connected():
            t = self.text()
            if self.exited(t):
                raise Failure(f"the client exited ({self.exited(t)}):\n{t.strip()}")
            return "@ lat" in t
        wait_for(connected, 15, "the client to join its room")
        self.tmux.run("send-keys", "-t", self.name, "Enter")  # ready: the match starts
        wait_for(lambda: re.search(r"^Level:? \d+ ", self.text(), re.M) and own_ball(self.pane())[0], 20,
                 "a level with the own ball on screen")
        m = re.search(r"Room ([A-Z0-9]{4,})", self.text())
        return m.group(1) if m else None

    def kill(self):
        self.tmux.run("kill-session", "-t", self.name, check=False)


def at_rest(session, rest_s, timeout_s):
    """The ball's cells once they have not changed for rest_s (None on a timeout)."""
    deadline = time.monotonic() + timeout_s
    last, since = None, time.monotonic()
    while time.monotonic() < deadline:
        cells, box = own_ball(session.pane())
        now = time.monotonic()
        if cells != last:
            last, since = cells, now
        elif cells and now - since >= rest_s:
            return cells, box
        time.sleep(0.01)
    return None, None


def trial(session, key, before, timeout_s):
    """Sends key; returns (latency_ms, send_ms, polls, moved_col, moved_row) or None on a timeout."""
    t0 = time.monotonic()
    session.tmux.run("send-keys", "-t", session.name, key)
    t1 = time.monotonic()
    polls = 0
    while True:
        s = time.monotonic()
        text = session.pane()
        e = time.monotonic()
        polls += 1
        cells, _ = own_ball(text)
        if cells and cells != before:
            (c0, r0), (c1, r1) = centre(before), centre(cells)
            return ((s + e) / 2 - (t0 + t1) / 2) * 1000, (t1 - t0) * 1000, polls, c1 - c0, r1 - r0, (e - t1) * 1000 / polls
        if e - t1 > timeout_s:
            return None, (t1 - t0) * 1000, polls, 0, 0, (e - t1) * 1000 / polls


def run_variant(a, tmux, work, port, name, extra, out, summaries):
    session = Session(tmux, f"v-{len(summaries)}", os.path.join(BIN, "client", "fts-client"), port, extra, work,
                      (a.width, a.height))
    bots = None
    try:
        room = session.start_level()
        _, (top, bottom, left, right) = own_ball(session.pane())
        print(f"# {name}: pane {a.width}x{a.height}, platform {right - left - 1}x{bottom - top - 1} cells "
              f"({500 / (right - left - 1):.2f} u a column at the default 500 u width)", file=sys.stderr, flush=True)
        if a.bots:
            if not room:
                raise Failure("no room code on the client's screen for the bots")
            bots = subprocess.Popen([os.path.join(BIN, "client", "fts-bot"), "--connect", f"127.0.0.1:{a.server_port}",
                                     "--name", "b", "--count", str(a.bots), "--behavior", a.bot_behavior,
                                     "--duration", "3600", "--room", room, "--report", os.devnull],
                                    stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            wait_for(lambda: session.text().count(" b1 ") >= 1, 15, "the bots in the room")
        # What the client writes to its terminal (the frames' bytes, as an ssh link would
        # carry them): the pane's output piped to a file, counted over the trials.
        out_path = os.path.join(work, f"out-{session.name}")
        tmux.run("pipe-pane", "-o", "-t", session.name, f"cat >> {shlex.quote(out_path)}")
        wait_for(lambda: os.path.exists(out_path), 5, "the pane's output file")
        b0, t0 = os.path.getsize(out_path), time.monotonic()
        lat, timeouts, skipped, wrong = [], 0, 0, 0
        go_right = True
        for i in range(a.trials):
            before, box = at_rest(session, a.rest_ms / 1000, a.rest_timeout_s)
            if before is None:
                skipped += 1
                if skipped > a.trials:
                    raise Failure("the own ball never came to rest")
                continue
            top, bottom, left, right = box
            col, _ = centre(before)
            if col < left + 0.1 * (right - left):
                go_right = True
            elif col > right - 0.1 * (right - left):
                go_right = False
            key = "Right" if go_right else "Left"
            go_right = not go_right
            ms, send_ms, polls, dcol, drow, poll_ms = trial(session, key, before, a.trial_timeout_s)
            if ms is None:
                status = "timeout"
                timeouts += 1
            elif (dcol > 0) != (key == "Right") or dcol == 0:
                status = "wrong_direction"  # something else moved the ball (a bot, a correction)
                wrong += 1
            else:
                status = "ok"
                lat.append(ms)
            out.writerow([name, i, key, "" if ms is None else f"{ms:.1f}", f"{send_ms:.1f}", polls, f"{poll_ms:.2f}",
                          f"{dcol:+.2f}", f"{drow:+.2f}", status])
            if a.csv:
                out_file.flush()
        bytes_per_s = (os.path.getsize(out_path) - b0) / (time.monotonic() - t0)
        # Then the ball kept moving: a tap every 150 ms for 3 s, right then left.
        b1, t1 = os.path.getsize(out_path), time.monotonic()
        k = 0
        while time.monotonic() - t1 < 3:
            session.tmux.run("send-keys", "-t", session.name, "Right" if (k // 10) % 2 == 0 else "Left")
            k += 1
            time.sleep(0.15)
        moving_bytes_per_s = (os.path.getsize(out_path) - b1) / (time.monotonic() - t1)
        s = {"variant": name, "client_args": extra, "bytes_per_s": bytes_per_s, "moving_bytes_per_s": moving_bytes_per_s,
             "n": len(lat), "p50_ms": percentile(lat, 0.5),
             "p99_ms": percentile(lat, 0.99), "mean_ms": statistics.mean(lat) if lat else float("nan"),
             "min_ms": min(lat, default=float("nan")), "max_ms": max(lat, default=float("nan")),
             "timeouts": timeouts, "wrong_direction": wrong, "not_at_rest": skipped}
        summaries.append(s)
        print(f"summary variant={name} n={s['n']} p50_ms={s['p50_ms']:.1f} p99_ms={s['p99_ms']:.1f} "
              f"mean_ms={s['mean_ms']:.1f} min_ms={s['min_ms']:.1f} max_ms={s['max_ms']:.1f} "
              f"timeouts={timeouts} wrong_direction={wrong} not_at_rest={skipped} bytes_per_s={bytes_per_s:.0f} "
              f"moving_bytes_per_s={moving_bytes_per_s:.0f}", file=sys.stderr, flush=True)
        return s
    finally:
        if bots:
            bots.terminate()
            bots.wait()
        session.kill()


out_file = None


def main():
    global out_file
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0], allow_abbrev=False)
    ap.add_argument("--trials", type=int, default=20)
    ap.add_argument("--variant", action="append", default=[], help="NAME=CLIENT_ARGS (repeatable)")
    ap.add_argument("--client-args", default=None, help="one variant named 'default'")
    ap.add_argument("--server-args", default="", help="extra fts-server flags")
    ap.add_argument("--bots", type=int, default=0, help="fts-bots in the client's room")
    ap.add_argument("--bot-behavior", default="idle")
    ap.add_argument("--width", type=int, default=240)
    ap.add_argument("--height", type=int, default=80)
    ap.add_argument("--rest-ms", type=float, default=1000, help="the ball still this long before a press")
    ap.add_argument("--rest-timeout-s", type=float, default=15)
    ap.add_argument("--trial-timeout-s", type=float, default=3)
    ap.add_argument("--relay", action="store_true")
    ap.add_argument("--rtt-ms", type=float, default=0)
    ap.add_argument("--jitter-ms", type=float, default=0)
    ap.add_argument("--jitter-dist", default="uniform")
    ap.add_argument("--reorder", action="store_true")
    ap.add_argument("--loss", type=float, default=0)
    ap.add_argument("--burst-loss-pct", type=float, default=0)
    ap.add_argument("--burst-len", type=float, default=3)
    ap.add_argument("--dup", type=float, default=0)
    ap.add_argument("--relay-seed", type=int, default=1)
    ap.add_argument("--relay-args", default="")
    ap.add_argument("--csv", help="per-trial rows here (default stdout)")
    ap.add_argument("--json", help="summaries and relay counters here")
    a = ap.parse_args()
    variants = []
    for v in a.variant:
        name, _, args = v.partition("=")
        variants.append((name, args))
    if a.client_args is not None or not variants:
        variants.insert(0, ("default", a.client_args or ""))
    use_relay = a.relay or a.rtt_ms or a.jitter_ms or a.loss or a.burst_loss_pct or a.dup or a.relay_args
    out_file = open(a.csv, "w", newline="") if a.csv else sys.stdout
    out = csv.writer(out_file)
    out.writerow(["variant", "trial", "key", "latency_ms", "send_ms", "polls", "poll_ms", "dcol", "drow", "status"])
    work = tempfile.mkdtemp(prefix="fts-latency-")
    tmux = Tmux()
    server = relay = None
    summaries, relay_counters = [], {}
    try:
        log = open(os.path.join(work, "server.log"), "w")
        server = subprocess.Popen([os.path.join(BIN, "server", "fts-server"), "--port", "0", "--bind", "127.0.0.1",
                                   "--max-per-address", "64", *shlex.split(a.server_args)], stdout=log, stderr=log)
        m = wait_for(lambda: re.search(r"ready .*port=(\d+)", open(log.name).read()), 10, "the server's ready line")
        a.server_port = int(m.group(1))
        port = a.server_port
        rargs = relay_args(a) if use_relay else []
        if use_relay:
            relay = Relay(f"127.0.0.1:{a.server_port}", rargs)
            port = relay.port
        load = os.getloadavg()
        print(f"# {time.strftime('%Y-%m-%d %H:%M')} load {load[0]:.1f} relay: {' '.join(rargs) or 'none'}",
              file=sys.stderr, flush=True)
        for name, extra in variants:
            c0 = relay.counters() if relay else None
            try:
                run_variant(a, tmux, work, port, name, extra, out, summaries)
            except Failure as e:
                print(f"variant {name}: {e}", file=sys.stderr, flush=True)
                summaries.append({"variant": name, "client_args": extra, "n": 0, "error": str(e)[:2000]})
            if relay:
                relay_counters[name] = counter_diff(c0, relay.counters())
                summaries[-1]["relay"] = relay_counters[name]
    finally:
        tmux.kill()
        if relay:
            relay.stop()
        if server:
            server.send_signal(signal.SIGINT)
            try:
                server.wait(timeout=10)
            except subprocess.TimeoutExpired:
                server.kill()
        if a.csv:
            out_file.close()
        shutil.rmtree(work, ignore_errors=True)
    if a.json:
        with open(a.json, "w") as f:
            json.dump({"relay_args": rargs, "load": list(load), "trials": a.trials, "pane": [a.width, a.height],
                       "variants": summaries}, f, indent=1)
    return 1 if any("error" in s for s in summaries) else 0


if __name__ == "__main__":
    sys.exit(main())
