#!/usr/bin/env python3
"""Two fts-host-bench binaries (old and new trees) under callgrind's cache simulator: the
host's work counted, not timed, so the comparison holds on a shared, noisy machine where
wall-clock pairs differ by 20-40 % (server_ab.py). Counts only inside GameHost::tick and
GameHost::receive (the clients' simulation in the same process is left out): instructions
(Ir), first-level data misses (D1mr + D1mw), last-level misses (LLm, with a 2 MiB last
level: a host's rooms do not fit a core's cache) and callgrind's cycle estimate,
Ir + 10 x L1 misses + 100 x LL misses. The handshakes (key exchanges) are counted too,
the same in both. Prints a table and B / A; never passes or fails.

usage: python3 tests/bench/callgrind_ab.py --a OLD/tests/bench/fts-host-bench
       --b build-opt/tests/bench/fts-host-bench [--clients 256] [--ticks 400]
(needs valgrind; one cell takes about a minute at 256 clients and 400 ticks)
"""
import argparse, os, re, subprocess, tempfile

EVENTS = ["Ir", "Dr", "Dw", "I1mr", "D1mr", "D1mw", "ILmr", "DLmr", "DLmw"]


def counts(binary, clients, ticks):
    out = tempfile.NamedTemporaryFile(prefix="fts-cg-", suffix=".out", delete=False).name
    subprocess.run(["valgrind", "--tool=callgrind", "--cache-sim=yes", "--LL=2097152,16,64",
                    f"--callgrind-out-file={out}",
                    "--toggle-collect=fts::server::GameHost::tick(*",
                    "--toggle-collect=fts::server::GameHost::receive(*",
                    binary, "--clients", str(clients), "--threads", "1", "--phase", "out",
                    "--ticks", str(ticks)], check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with open(out) as f:
        text = f.read()
    os.unlink(out)
    events = re.search(r"^events: (.*)$", text, re.M).group(1).split()
    totals = [int(v) for v in re.search(r"^totals: (.*)$", text, re.M).group(1).split()]
    c = dict(zip(events, totals))
    l1 = c["I1mr"] + c["D1mr"] + c["D1mw"]
    ll = c["ILmr"] + c["DLmr"] + c["DLmw"]
    return {"Ir": c["Ir"], "D1m": c["D1mr"] + c["D1mw"], "LLm": ll, "cycles": c["Ir"] + 10 * l1 + 100 * ll}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--a", required=True, help="the old tree's fts-host-bench")
    ap.add_argument("--b", required=True, help="the new tree's fts-host-bench")
    ap.add_argument("--clients", type=int, default=256)
    ap.add_argument("--ticks", type=int, default=400)
    args = ap.parse_args()
    a = counts(args.a, args.clients, args.ticks)
    b = counts(args.b, args.clients, args.ticks)
    print(f"{args.clients} clients, {args.ticks} timed ticks (and 100 to warm up), GameHost::tick + receive")
    print("| count | A | B | B / A |")
    print("|---|---|---|---|")
    for k in ["Ir", "D1m", "LLm", "cycles"]:
        print(f"| {k} | {a[k]:,} | {b[k]:,} | {b[k] / a[k]:.3f} |")


if __name__ == "__main__":
    main()
