#!/usr/bin/env python3
"""Server load: fts-server at 100 Hz with N bots (spread over several fts-bot processes)
for S seconds; reports tick time p50/p99, skipped ticks, bytes per client per second each
way (the server's JSON stats records) and the server's CPU time per client (from
/proc). Never passes or fails on time.

usage: FTS_BIN_DIR=build python3 tests/bench/server_load.py [--bots 8] [--procs 1] [--seconds 60]
       [--server-arg=--rooms ...]   (N > 64 needs rooms: issue 13)
"""
import argparse, json, os, sys, time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "integration"))
from harness import Server, finish_bots, start_bots  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bots", type=int, default=8)
    ap.add_argument("--seconds", type=float, default=60)
    ap.add_argument("--behavior", default="shopper")
    ap.add_argument("--procs", type=int, default=1, help="fts-bot processes the bots are spread over")
    ap.add_argument("--server-arg", action="append", default=[], help="extra fts-server argument (repeatable)")
    a = ap.parse_args()
    server_args = ["--stats-interval-ms", "10000", "--log-format", "json", "--tick-rate", "100",
                   "--max-players", str(min(a.bots, 64)), "--max-per-address", str(a.bots), *a.server_arg]
    with Server(*server_args) as srv:
        cpu0, t0 = cpu_seconds(srv.proc.pid), time.monotonic()
        per = [a.bots // a.procs + (1 if i < a.bots % a.procs else 0) for i in range(a.procs)]
        started = [start_bots("--connect", srv.address, "--name", f"load{i}", "--count", str(n), "--behavior",
                              a.behavior, "--duration", str(a.seconds)) for i, n in enumerate(per) if n]
        rc, report = 0, []
        for bots in started:
            code, rep, err = finish_bots(bots, a.seconds + 60)
            rc = rc or code
            report += rep if isinstance(rep, list) else [rep]
        cpu1, t1 = cpu_seconds(srv.proc.pid), time.monotonic()
        srv.stop()
        stats = [json.loads(l) for l in srv.text().splitlines() if '"event":"stats"' in l]
    full = [s for s in stats if s["players"] == a.bots]
    print(f"| interval | players | tick p50 (µs) | tick p99 (µs) | tick max (µs) | skipped (total) | bytes out/client/s | bytes in/client/s |")
    print("|---|---|---|---|---|---|---|---|")
    for i, s in enumerate(full):
        print(f"| {i + 1} | {s['players']} | {s['tick_p50_us']:.1f} | {s['tick_p99_us']:.1f} | {s['tick_max_us']:.0f} | "
              f"{s['ticks_skipped_total']} | {s['bytes_out'] / s['players'] / 10:.0f} | {s['bytes_in'] / s['players'] / 10:.0f} |")
    lost = sum(b["snapshots_lost"] for b in report)
    got = sum(b["snapshots_received"] for b in report)
    levels = max((b["level"] for b in report), default=0)
    print(f"\nbots exit {rc}; snapshots received {got}, lost {lost}; highest level {levels}; "
          f"skipped ticks {stats[-1]['ticks_skipped_total'] if stats else '?'}")
    busy = (cpu1 - cpu0) / (t1 - t0)
    print(f"server CPU {100 * busy:.1f} % of one core over {t1 - t0:.0f} s: {100 * busy / a.bots:.2f} % per client")


def cpu_seconds(pid):
    """User + system CPU seconds of a process so far (Linux /proc)."""
    with open(f"/proc/{pid}/stat") as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


if __name__ == "__main__":
    main()
