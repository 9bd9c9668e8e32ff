"""The journal's cost per tick (issue 15): two fts-servers side by side (same load, same
machine, same moment), one plain, one with --journal-dir (sync every 100 ms, a checkpoint
every 10 s), each with 4 rooms x 4 shopper bots; prints both servers' tick p50/p99 from
their last stats record (the tick of every room together), the ratio, each process's CPU
time (the journal's writer threads included) and the bytes the journal holds at the end.
Figures, never pass/fail.
  FTS_BIN_DIR=build python3 tests/bench/journal_overhead.py [SECONDS]"""
import os, shutil, sys, tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "integration"))
from harness import HERE, Server, finish_bots, start_bots  # noqa: E402
from bench_procs import cpu_s, last_stats  # noqa: E402

seconds = float(sys.argv[1]) if len(sys.argv) > 1 else 30
journal = tempfile.mkdtemp(prefix="fts-journal-overhead-")
common = ("--log-format", "json", "--stats-interval-ms", str(int(seconds * 1000 - 3000)),
          "--config", os.path.join(HERE, "many-lives.json"))
with Server(*common) as plain, Server(*common, "--journal-dir", journal) as journaled:
    bots = [start_bots("--connect", s.address, "--name", f"{tag}{g}", "--count", "4", "--behavior", "shopper",
                       "--room", "create", "--duration", str(seconds), "--seed", str(g))
            for s, tag in ((plain, "p"), (journaled, "j")) for g in range(4)]
    for b in bots:
        finish_bots(b, seconds + 30)
    a, b = last_stats(plain), last_stats(journaled)
    cpu_a, cpu_b = cpu_s(plain), cpu_s(journaled)
    kept = sum(os.path.getsize(os.path.join(d, f)) for d, _, fs in os.walk(journal) for f in fs)
shutil.rmtree(journal, ignore_errors=True)
print(f"plain:     tick p50 {a['tick_p50_us']:.1f} us, p99 {a['tick_p99_us']:.1f} us, max {a['tick_max_us']:.0f} us")
print(f"journaled: tick p50 {b['tick_p50_us']:.1f} us, p99 {b['tick_p99_us']:.1f} us, max {b['tick_max_us']:.0f} us")
print(f"ratio journaled/plain: p50 {b['tick_p50_us'] / a['tick_p50_us']:.2f}, p99 {b['tick_p99_us'] / a['tick_p99_us']:.2f}")
print(f"CPU time (all threads): plain {cpu_a:.2f} s, journaled {cpu_b:.2f} s, ratio {cpu_b / cpu_a:.2f}")
print(f"journal on disk at the end (4 rooms): {kept / 1024:.0f} KB")
