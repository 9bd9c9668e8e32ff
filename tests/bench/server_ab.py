#!/usr/bin/env python3
"""Two fts-server binaries in turn under the same bot load, for a ratio measured in one run
(the machine is shared: runs minutes apart differ by 20-40 %, so only pairs run back to
back are compared). Each round runs A, then B: the server alone on CPU 0 at 100 Hz, N
fts-bot shoppers on the other CPUs in rooms of 8, --warm seconds once started, then
--seconds measured: the server's CPU per client (utime + stime, /proc), its context
switches per second (every thread's, /proc/PID/task/*/status), and its last full stats
record's tick p50. Prints a row per run, B ÷ A per round and the median. Never passes or
fails on time.

usage: FTS_BIN_DIR=build-opt python3 tests/bench/server_ab.py --a OLD/server/fts-server
       --b build-opt/server/fts-server [--clients 256] [--rounds 4] [--warm 12] [--seconds 15]
With --profile OUT (and --b only): one run of B under the same load, its measured window
recorded by perf instead (perf record -p SERVER --call-graph dwarf,16384 -F 499 -o OUT);
read it with perf report -i OUT.
(the bots: FTS_BIN_DIR's fts-bot)
(an old tree's server: git worktree add /tmp/old COMMIT && FTS_TARGETS=fts-server
 bash .ci/build.sh /tmp/old/build -DFTS_WERROR=ON)
"""
import argparse, glob, json, os, statistics, subprocess, sys, tempfile, time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "integration"))
from harness import finish_bots, start_bots, wait_for  # noqa: E402
from server_load import cpu_s  # noqa: E402


def context_switches(pid):
    total = 0
    for status in glob.glob(f"/proc/{pid}/task/*/status"):
        with open(status) as f:
            for line in f:
                if line.startswith(("voluntary_ctxt_switches", "nonvoluntary_ctxt_switches")):
                    total += int(line.split()[1])
    return total


def run(binary, n, a, cpus, profile=None):
    log = tempfile.NamedTemporaryFile(prefix="fts-ab-", suffix=".log", delete=False)
    srv = subprocess.Popen([binary, "--port", "0", "--tick-rate", "100", "--log-format", "json",
                            "--stats-interval-ms", "1000", "--max-rooms", str(max(64, n // 8)),
                            "--max-per-address", str(n + 8), "--max-rooms-per-host", "1024"],
                           stdout=log, stderr=log)
    text = lambda: open(log.name).read()  # noqa: E731
    try:
        os.sched_setaffinity(srv.pid, {cpus[0]})
        ready = wait_for(lambda: next((json.loads(l) for l in text().splitlines() if '"event":"ready"' in l), None),
                         10, "the server's ready line")
        groups = [start_bots("--connect", f"127.0.0.1:{ready['port']}", "--name", f"r{r}b", "--count", "8",
                             "--behavior", "shopper", "--duration", str(a.warm + a.seconds + 10),
                             "--seed", str(1 + 8 * r), "--room", "create") for r in range(n // 8)]
        for p, _ in groups:
            os.sched_setaffinity(p.pid, set(cpus[1:]))
        time.sleep(a.warm)  # the measured window's start: a workload, not a wait for an event
        c0, s0, t0 = cpu_s(srv.pid), context_switches(srv.pid), time.monotonic()
        if profile:
            subprocess.run(["perf", "record", "-o", profile, "-p", str(srv.pid), "--call-graph", "dwarf,16384",
                            "-F", "499", "--", "sleep", str(a.seconds)], check=True,
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        else:
            time.sleep(a.seconds)
        c1, s1, t1 = cpu_s(srv.pid), context_switches(srv.pid), time.monotonic()
        stats = [json.loads(l) for l in text().splitlines() if '"event":"stats"' in l]
        full = [s for s in stats if s["players"] == n]
        for p, _ in groups:
            p.terminate()
        for g in groups:
            try:
                finish_bots(g, 30)
            except Exception:  # noqa: BLE001 - a bot stopped early changes no figure of the server's
                pass
        return {"us_per_client": 1e6 * (c1 - c0) / (t1 - t0) / n, "switches_s": (s1 - s0) / (t1 - t0),
                "tick_p50_us": full[-1]["tick_p50_us"] if full else float("nan"), "full": bool(full)}
    finally:
        srv.terminate()
        srv.wait()
        os.unlink(log.name)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--a", help="fts-server A (the old)")
    ap.add_argument("--b", required=True, help="fts-server B (the new)")
    ap.add_argument("--clients", type=int, default=256)
    ap.add_argument("--rounds", type=int, default=4)
    ap.add_argument("--warm", type=float, default=12)
    ap.add_argument("--seconds", type=float, default=15)
    ap.add_argument("--profile", help="record B's measured window with perf into this file (no A)")
    a = ap.parse_args()
    if not a.profile and not a.a:
        ap.error("--a is needed unless --profile is given")
    cpus = sorted(os.sched_getaffinity(0))
    if len(cpus) < 2:
        print("needs at least 2 CPUs (the server alone on the first)")
        return 2
    os.sched_setaffinity(0, set(cpus[1:]))
    if a.profile:
        g = run(a.b, a.clients, a, cpus, profile=a.profile)
        print(f"{a.clients} clients, {a.b}: {g['us_per_client']:.0f} µs CPU/s per client while recorded "
              f"(perf's own cost included); perf report -i {a.profile}")
        return 0
    print(f"{a.clients} clients, A = {a.a}, B = {a.b}; server on CPU {cpus[0]}, bots on {cpus[1:]}")
    print("| round | run | µs CPU/s per client | context switches/s | tick p50 (µs) | all in |")
    print("|---|---|---|---|---|---|")
    ratios = []
    for r in range(a.rounds):
        got = {}
        for name, binary in (("A", a.a), ("B", a.b)):
            got[name] = run(binary, a.clients, a, cpus)
            g = got[name]
            print(f"| {r + 1} | {name} | {g['us_per_client']:.0f} | {g['switches_s']:.0f} | {g['tick_p50_us']:.0f} | "
                  f"{'yes' if g['full'] else 'no'} |", flush=True)
        ratios.append(got["B"]["us_per_client"] / got["A"]["us_per_client"])
    print(f"\nB ÷ A, CPU per client, by round: {', '.join(f'{x:.2f}' for x in ratios)}; "
          f"median {statistics.median(ratios):.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
