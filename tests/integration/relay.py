#!/usr/bin/env python3
"""A seeded UDP impairment relay between clients and one server, for tests and benchmarks.

usage: relay.py --listen PORT --server HOST:PORT [impairments...] [--seed 1] [--stats FILE]
                [--trace FILE]

Clients send to 127.0.0.1:PORT (0: any free port); each client gets its own socket
towards the server, so the server sees one address per client. "up" is client -> server,
"down" is server -> client. Every impairment flag exists three times: --X sets both
directions, --up-X and --down-X override it for one direction:

  --loss P           random loss, fraction 0..1 of the datagrams arriving
  --burst-loss P     bursty loss (Gilbert-Elliott): P is the chance, per datagram in the
                     good state, of entering the bad state, where everything is lost
  --burst-len N      mean length of a bad state in datagrams (geometric; default 1)
  --dup P            fraction of datagrams sent twice (each copy has its own delay)
  --delay-ms MS      fixed one-way delay; a lower bound of every datagram's delay
  --jitter-ms MS     extra random delay: uniform in [0, MS], or |N(0, MS)| with
  --jitter-dist D    uniform (default) or normal
  --no-reorder       never deliver a datagram of a flow (one client, one direction)
                     before the previous one: jitter then delays, it does not reorder
  --rate-kbps K      bandwidth cap (1000 bits/s, UDP payload bytes only; 0: none): a
                     datagram is sent after the ones before it, size*8/K ms each
  --queue N          datagrams the rate cap holds at most (default 64); one more arriving
                     at a full queue is dropped (drop-tail, counted as lost.queue)

A datagram in the order it meets them: the link-down window, the burst state, random
loss, duplication, the rate queue, then delay + jitter. Without flags the link is clean
(no loss, duplicates, delay or jitter): each flag adds its impairment. (Until issue 37
the defaults were the original relay's --loss 0.2 --dup 0.2 --delay-ms 20 --jitter-ms 60.)

  --down-at S --down-for S   link down: from S seconds after "relay ready" on, for S
                             seconds, every datagram arriving in either direction is
                             dropped (lost.down); those already in flight arrive

Every random draw of a direction comes from its own random.Random (seeded from --seed
and the direction), five draws per datagram whatever happens to it, so the same seed
and the same datagrams give the same drops, duplicates and delays; what depends on
time (the rate queue, the down window) follows the clock.

Prints "relay ready port=N" once listening. On SIGTERM or SIGINT it writes its counters
as one JSON line to stdout (or to --stats FILE) and exits 0; on SIGUSR1 it writes the
same line with "final": false and goes on (a test waits on "pending": 0). Per direction:
  datagrams_in, datagrams_out, bytes_in, bytes_out, lost {random, burst, down, queue},
  duplicated (extra copies sent), reordered (delivered after a later datagram of its
  flow), pending (scheduled, not yet sent), bursts (bad states entered)

--trace FILE writes one line per datagram sent: "DIRECTION INDEX DRAWN_MS LATE_MS", its
index in its flow (0 for a flow's first datagram), the delay the relay drew for it (rate
queue, delay and jitter, from its arrival) and how late the relay sent it after it was
due (the relay's own scheduling: on a loaded machine a starved relay sends late). A test
of the delay model reads what was drawn; what the machine added is reported apart.
"""
import argparse, heapq, json, os, random, select, signal, socket, statistics, sys, time
from collections import deque

DIRECTIONS = ("up", "down")
# name, type, default (both directions), help. Every default is a clean link: a flag
# adds one impairment.
PER_DIRECTION = [
    ("loss", float, 0.0, "random loss fraction"),
    ("burst-loss", float, 0.0, "chance per datagram of entering the bad (all lost) state"),
    ("burst-len", float, 1.0, "mean bad-state length (datagrams)"),
    ("dup", float, 0.0, "duplicate fraction"),
    ("delay-ms", float, 0.0, "fixed one-way delay (ms)"),
    ("jitter-ms", float, 0.0, "extra random delay (ms)"),
    ("jitter-dist", str, "uniform", "uniform or normal"),
    ("rate-kbps", float, 0.0, "bandwidth cap (kbit/s, 0: none)"),
    ("queue", int, 64, "rate cap queue (datagrams)"),
]
NORMAL = statistics.NormalDist()


class Stop(Exception):
    pass


def parse_args(argv=None):
    ap = argparse.ArgumentParser(description="Seeded UDP impairment relay (see the module docstring).",
                                 allow_abbrev=False)
    ap.add_argument("--listen", type=int, default=0)
    ap.add_argument("--server", required=True)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--stats", help="write the counters here instead of stdout")
    ap.add_argument("--trace", help="write one line per datagram sent here (see above)")
    ap.add_argument("--down-at", type=float, default=None, help="link down from S s after ready")
    ap.add_argument("--down-for", type=float, default=0.0, help="for S s")
    for name, typ, default, text in PER_DIRECTION:
        ap.add_argument(f"--{name}", type=typ, default=default, help=f"{text}, both directions")
        for d in DIRECTIONS:
            ap.add_argument(f"--{d}-{name}", type=typ, default=None, help=f"{text}, {d} only")
    ap.add_argument("--no-reorder", action="store_true", help="keep each flow's order, both directions")
    for d in DIRECTIONS:
        ap.add_argument(f"--{d}-no-reorder", action="store_true", help=f"keep each flow's order, {d} only")
    a = ap.parse_args(argv)
    links = {}
    for d in DIRECTIONS:
        cfg = {}
        for name, _, _, _ in PER_DIRECTION:
            key = name.replace("-", "_")
            own = getattr(a, f"{d}_{key}")
            cfg[key] = getattr(a, key) if own is None else own
        cfg["no_reorder"] = a.no_reorder or getattr(a, f"{d}_no_reorder")
        for key in ("loss", "burst_loss", "dup"):
            if not 0.0 <= cfg[key] <= 1.0:
                ap.error(f"--{d}-{key.replace('_', '-')}: a fraction 0..1, got {cfg[key]}")
        if cfg["burst_len"] < 1.0:
            ap.error(f"--{d}-burst-len: at least 1 datagram, got {cfg['burst_len']}")
        if cfg["jitter_dist"] not in ("uniform", "normal"):
            ap.error(f"--{d}-jitter-dist: uniform or normal, got {cfg['jitter_dist']!r}")
        for key in ("delay_ms", "jitter_ms", "rate_kbps"):
            if cfg[key] < 0:
                ap.error(f"--{d}-{key.replace('_', '-')}: not negative, got {cfg[key]}")
        if cfg["queue"] < 1:
            ap.error(f"--{d}-queue: at least 1 datagram, got {cfg['queue']}")
        links[d] = cfg
    return a, links


class Link:
    """One direction: its settings, its random generator, its state and its counters."""

    def __init__(self, name, cfg, seed):
        self.name = name
        self.cfg = cfg
        self.rng = random.Random(f"{seed}/{name}")
        self.bad = False                  # Gilbert-Elliott state
        self.tx = deque()                 # finish times of datagrams in the rate queue (s)
        self.last_due = {}                # flow -> due time of its last scheduled datagram
        self.arrived = {}                 # flow -> datagrams of it seen so far
        self.sent_max = {}                # flow -> highest arrival index delivered
        self.c = {"datagrams_in": 0, "datagrams_out": 0, "bytes_in": 0, "bytes_out": 0,
                  "lost": {"random": 0, "burst": 0, "down": 0, "queue": 0},
                  "duplicated": 0, "reordered": 0, "pending": 0, "bursts": 0}

    def extra_delay_s(self, u):
        j = self.cfg["jitter_ms"]
        if j <= 0:
            return 0.0
        if self.cfg["jitter_dist"] == "uniform":
            return u * j / 1000.0
        # |N(0, j)| from one uniform draw: the inverse CDF of the half-normal.
        return j * NORMAL.inv_cdf(0.5 + 0.5 * min(u, 1.0 - 1e-12)) / 1000.0

    def admit(self, size, now, link_down):
        """The copies of an arriving datagram to schedule: a list of due times (s)."""
        cfg, c = self.cfg, self.c
        # Five draws per datagram, always, so one datagram's fate never shifts the next's.
        u_state, u_loss, u_dup, u_j1, u_j2 = (self.rng.random() for _ in range(5))
        c["datagrams_in"] += 1
        c["bytes_in"] += size
        if self.bad:
            if u_state < 1.0 / cfg["burst_len"]:
                self.bad = False
        elif cfg["burst_loss"] > 0 and u_state < cfg["burst_loss"]:
            self.bad = True
            c["bursts"] += 1
        if link_down:
            c["lost"]["down"] += 1
            return []
        if self.bad:
            c["lost"]["burst"] += 1
            return []
        if u_loss < cfg["loss"]:
            c["lost"]["random"] += 1
            return []
        copies = [u_j1, u_j2] if u_dup < cfg["dup"] else [u_j1]
        due = []
        for u in copies:
            ready = now
            if cfg["rate_kbps"] > 0:
                while self.tx and self.tx[0] <= now:
                    self.tx.popleft()
                if len(self.tx) >= cfg["queue"]:
                    c["lost"]["queue"] += 1
                    continue
                start = max(now, self.tx[-1]) if self.tx else now
                ready = start + size * 8 / (cfg["rate_kbps"] * 1000.0)
                self.tx.append(ready)
            due.append(ready + cfg["delay_ms"] / 1000.0 + self.extra_delay_s(u))
        if len(due) == 2:
            c["duplicated"] += 1
        return due


# A socket's receive buffer: 4 MiB (the kernel caps it at net.core.rmem_max). With the
# default ~200 KiB a relay starved of CPU (a loaded machine) lost datagrams in the kernel
# before it could read them: loss that no flag asked for, and a count the tests could
# never reach.
RCVBUF_BYTES = 1 << 22


def relay_socket():
    s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    s.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, RCVBUF_BYTES)
    return s


def main():
    a, cfgs = parse_args()
    host, port = a.server.rsplit(":", 1)
    server = (host, int(port))
    links = {d: Link(d, cfgs[d], a.seed) for d in DIRECTIONS}
    front = relay_socket()
    front.bind(("127.0.0.1", a.listen))
    uplinks = {}   # client address -> socket towards the server
    owner = {}     # uplink socket -> client address
    queue = []     # (due, seq, direction, flow, arrival index, socket, payload, destination, arrival)
    trace = open(a.trace, "w", buffering=1 << 16) if a.trace else None
    seq = 0
    t0 = time.monotonic()  # the down window counts from here (just before "ready")

    sending = [None]  # the direction of a datagram taken off the queue and not yet sent

    def write_stats(final):
        # A signal can land between the queue's pop and the send: that one is pending too.
        for d in DIRECTIONS:
            links[d].c["pending"] = sum(1 for q in queue if q[2] == d) + (sending[0] == d)
        line = json.dumps({"final": final, "seed": a.seed, "elapsed_s": round(time.monotonic() - t0, 3),
                           **{d: links[d].c for d in DIRECTIONS}})
        if a.stats:
            with open(a.stats, "a") as f:
                f.write(line + "\n")
        else:
            print(line, flush=True)

    def on_stop(signum, frame):
        raise Stop()

    def on_dump(signum, frame):
        write_stats(False)

    signal.signal(signal.SIGTERM, on_stop)
    signal.signal(signal.SIGINT, on_stop)
    signal.signal(signal.SIGUSR1, on_dump)

    def arrive(direction, flow, sock, data, dest, now):
        nonlocal seq
        link = links[direction]
        down = a.down_at is not None and a.down_at <= now - t0 < a.down_at + a.down_for
        index = link.arrived.get(flow, 0)
        link.arrived[flow] = index + 1
        for due in link.admit(len(data), now, down):
            if link.cfg["no_reorder"]:
                due = max(due, link.last_due.get(flow, due))
                link.last_due[flow] = due
            seq += 1
            heapq.heappush(queue, (due, seq, direction, flow, index, sock, data, dest, now))

    print(f"relay ready port={front.getsockname()[1]}", flush=True)
    try:
        while True:
            timeout = max(0.0, queue[0][0] - time.monotonic()) if queue else 0.05
            ready, _, _ = select.select([front] + list(owner), [], [], timeout)
            for s in ready:
                try:
                    data, addr = s.recvfrom(65535)
                except OSError:
                    continue
                now = time.monotonic()
                if s is front:
                    up = uplinks.get(addr)
                    if up is None:
                        up = relay_socket()
                        up.bind(("127.0.0.1", 0))
                        uplinks[addr] = up
                        owner[up] = addr
                    arrive("up", addr, up, data, server, now)
                else:
                    arrive("down", owner[s], front, data, owner[s], now)
            now = time.monotonic()
            while queue and queue[0][0] <= now:
                sending[0] = queue[0][2]
                due, _, direction, flow, index, sock, data, dest, arrived = heapq.heappop(queue)
                link = links[direction]
                if index < link.sent_max.get(flow, -1):
                    link.c["reordered"] += 1
                link.sent_max[flow] = max(index, link.sent_max.get(flow, -1))
                try:
                    sock.sendto(data, dest)
                    link.c["datagrams_out"] += 1
                    link.c["bytes_out"] += len(data)
                except OSError:
                    pass
                if trace:
                    trace.write(f"{direction} {index} {(due - arrived) * 1e3:.6f} "
                                f"{(time.monotonic() - due) * 1e3:.6f}\n")
                sending[0] = None
    except Stop:
        pass
    if trace:
        trace.close()
    write_stats(True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
