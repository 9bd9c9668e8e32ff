"""The fleet's cost per tick: two fts-servers side by side (same load, same machine, same
moment), one plain, one with --metrics and --agones against the stand-in sidecar, each
with 4 hunter bots; prints both servers' tick p50/p99 from their last stats record and
the ratio, and each process's CPU time (the fleet's per-tick work runs right after the
measured tick, and its HTTP and exposer threads beside it). Figures, never pass/fail.
  FTS_BIN_DIR=build python3 tests/bench/fleet_overhead.py [SECONDS]"""
import os, socket, sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "integration"))
from harness import Server, finish_bots, start_bots, wait_for  # noqa: E402
from agones_sidecar import Sidecar  # noqa: E402
from bench_procs import cpu_s, last_stats  # noqa: E402


def free_tcp_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


seconds = float(sys.argv[1]) if len(sys.argv) > 1 else 20
sc_port = free_tcp_port()
sc = Sidecar(sc_port)
sc.start()
common = ("--log-format", "json", "--stats-interval-ms", str(int(seconds * 1000 - 2000)))
with Server(*common) as plain, Server(*common, "--metrics", f"127.0.0.1:{free_tcp_port()}",
                                       "--agones", str(sc_port)) as fleet:
    bots = [start_bots("--connect", s.address, "--name", n, "--count", "4", "--behavior", "hunter",
                       "--duration", str(seconds)) for s, n in ((plain, "p"), (fleet, "f"))]
    for b in bots:
        finish_bots(b, seconds + 30)
    a, b = last_stats(plain), last_stats(fleet)
    cpu_a, cpu_b = cpu_s(plain), cpu_s(fleet)
sc.stop()
print(f"plain: tick p50 {a['tick_p50_us']:.1f} us, p99 {a['tick_p99_us']:.1f} us")
print(f"fleet: tick p50 {b['tick_p50_us']:.1f} us, p99 {b['tick_p99_us']:.1f} us")
print(f"CPU time (all threads): plain {cpu_a:.2f} s, fleet {cpu_b:.2f} s, ratio {cpu_b / cpu_a:.2f}")
print(f"ratio fleet/plain: p50 {b['tick_p50_us'] / a['tick_p50_us']:.2f}, p99 {b['tick_p99_us'] / a['tick_p99_us']:.2f}")
