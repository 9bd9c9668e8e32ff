#!/usr/bin/env python3
"""Server load: fts-server at 100 Hz with R rooms of B bots each for S seconds; reports
tick time p50/p99, skipped ticks, the server's CPU per client and bytes per client per
second from the server's JSON stats records and /proc. Never passes or fails on time.

usage: FTS_BIN_DIR=build python3 tests/bench/server_load.py [--rooms 1] [--bots 8] [--seconds 60] [--check]
  --rooms R: R fts-bot processes, each putting its B bots in one room of its own
  (--room create); R = 1 without --rooms-create keeps the one-room quick-play run.
  --pin: the server on CPU 0 alone, this script and the bots on the other CPUs (so
  that the bots' CPU does not count against the server's tick).
  --check: exit 1 unless the run worked (every bot process exits 0, every client got
  snapshots, the server reported a full house); never on time. --max-skipped N also
  fails a run with more than N skipped ticks (for a quiet machine: it depends on load).
"""
import argparse, json, os, sys, time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "integration"))
from harness import Server, finish_bots, rss_kib, start_bots  # noqa: E402


def cpu_s(pid):
    """utime + stime of a process, in seconds (/proc/PID/stat fields 14 and 15)."""
    with open(f"/proc/{pid}/stat") as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--rooms", type=int, default=1)
    ap.add_argument("--bots", type=int, default=8, help="bots per room")
    ap.add_argument("--seconds", type=float, default=60)
    ap.add_argument("--behavior", default="shopper")
    ap.add_argument("--check", action="store_true")
    ap.add_argument("--pin", action="store_true")
    ap.add_argument("--max-skipped", type=int, default=None)
    ap.add_argument("--threads", type=int, default=1, help="the server's --threads (issue 29)")
    a = ap.parse_args()
    load0 = os.getloadavg()
    cpus = sorted(os.sched_getaffinity(0))
    if a.pin:
        if len(cpus) < 2:
            print("--pin needs at least 2 CPUs")
            return 2
        os.sched_setaffinity(0, set(cpus[1:]))  # the bots inherit this
    clients = a.rooms * a.bots
    with Server("--stats-interval-ms", "10000", "--log-format", "json", "--tick-rate", "100",
                "--max-rooms", str(max(64, a.rooms)), "--max-per-address", str(min(1024, clients + 8)),
                # Every bot is on 127.0.0.1: one host for the per-host room cap (5bc01f0).
                "--max-rooms-per-host", str(min(1024, max(4, a.rooms))), "--threads", str(a.threads)) as srv:
        if a.pin:
            os.sched_setaffinity(srv.proc.pid, {cpus[0]})
        rss0 = rss_kib(srv.proc.pid)  # bound, no room yet
        room = ["--room", "create"] if a.rooms > 1 else []
        groups = [start_bots("--connect", srv.address, "--name", f"r{r}b", "--count", str(a.bots), "--behavior",
                             a.behavior, "--duration", str(a.seconds), "--seed", str(1 + r * a.bots), *room)
                  for r in range(a.rooms)]
        t0, c0 = time.monotonic(), cpu_s(srv.proc.pid)
        # The server's memory with every bot playing: sampled halfway, the largest kept.
        rss_full = 0
        while time.monotonic() < t0 + a.seconds / 2:
            time.sleep(min(1.0, max(0.0, t0 + a.seconds / 2 - time.monotonic())))
            rss_full = max(rss_full, rss_kib(srv.proc.pid))
        results = [finish_bots(g, a.seconds + 120) for g in groups]
        t1, c1 = time.monotonic(), cpu_s(srv.proc.pid)
        srv.stop()
        stats = [json.loads(l) for l in srv.text().splitlines() if '"event":"stats"' in l]
    report = [b for _, rep, _ in results for b in rep]
    full = [s for s in stats if s["players"] == clients]
    print(f"{a.rooms} rooms x {a.bots} bots = {clients} clients, {a.seconds:.0f} s at 100 Hz, server --threads {a.threads}"
          + (f"; server pinned to CPU {cpus[0]}, bots on {cpus[1:]}" if a.pin else ""))
    print(f"| interval | players | rooms | tick p50 (µs) | tick p99 (µs) | tick max (µs) | skipped (total) | bytes out/client/s | bytes in/client/s |")
    print("|---|---|---|---|---|---|---|---|---|")
    for i, s in enumerate(full):
        print(f"| {i + 1} | {s['players']} | {s.get('rooms', 1)} | {s['tick_p50_us']:.1f} | {s['tick_p99_us']:.1f} | "
              f"{s['tick_max_us']:.0f} | {s['ticks_skipped_total']} | {s['bytes_out'] / s['players'] / 10:.0f} | "
              f"{s['bytes_in'] / s['players'] / 10:.0f} |")
    lost = sum(b["snapshots_lost"] for b in report)
    got = sum(b["snapshots_received"] for b in report)
    levels = max((b["level"] for b in report), default=0)
    rcs = sorted({rc for rc, _, _ in results})
    wall = t1 - t0
    print(f"\nserver CPU {c1 - c0:.1f} s over {wall:.1f} s wall = {100 * (c1 - c0) / wall:.1f}% of a core; "
          f"per client {1e6 * (c1 - c0) / wall / clients:.0f} µs CPU per second ({100 * (c1 - c0) / wall / clients:.2f}% of a core)")
    skipped = stats[-1]['ticks_skipped_total'] if stats else None
    print(f"server RSS {rss0} KiB with no room, {rss_full} KiB with {clients} clients in {a.rooms} rooms: "
          f"{(rss_full - rss0) / clients:.0f} KiB per client ({(rss_full - rss0) / max(1, a.rooms):.0f} KiB per room of {a.bots})")
    print(f"bots exit {rcs}; snapshots received {got}, lost {lost}; highest level {levels}; "
          f"skipped ticks {skipped if skipped is not None else '?'}")
    print(f"load average before {load0[0]:.1f}, after {os.getloadavg()[0]:.1f} (1 min; {os.cpu_count()} cores)")
    if not a.check:
        return 0
    problems = []
    if rcs != [0]:
        problems.append(f"bot processes exited {rcs}")
    starved = [b.get("name", "?") for b in report if b["snapshots_received"] == 0]
    if len(report) != clients or starved:
        problems.append(f"{len(report)} of {clients} bots reported, {len(starved)} got no snapshot")
    if not full:
        problems.append(f"the server never reported {clients} players")
    if a.max_skipped is not None and (skipped is None or skipped > a.max_skipped):
        problems.append(f"{skipped} skipped ticks (at most {a.max_skipped})")
    for p in problems:
        print("FAIL:", p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
