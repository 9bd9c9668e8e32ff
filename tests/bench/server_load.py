#!/usr/bin/env python3
"""Server load: fts-server at 100 Hz with K bots for S seconds; reports tick time p50/p99,
skipped ticks and bytes per client per second from the server's JSON stats records.
Never passes or fails on time.

usage: FTS_BIN_DIR=build python3 tests/bench/server_load.py [--bots 8] [--seconds 60]
"""
import argparse, json, os, sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "integration"))
from harness import Server, finish_bots, start_bots  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bots", type=int, default=8)
    ap.add_argument("--seconds", type=float, default=60)
    ap.add_argument("--behavior", default="shopper")
    a = ap.parse_args()
    with Server("--stats-interval-ms", "10000", "--log-format", "json", "--tick-rate", "100") as srv:
        bots = start_bots("--connect", srv.address, "--name", "load", "--count", str(a.bots), "--behavior", a.behavior,
                          "--duration", str(a.seconds))
        rc, report, err = finish_bots(bots, a.seconds + 60)
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


if __name__ == "__main__":
    main()
