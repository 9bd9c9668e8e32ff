#!/usr/bin/env python3
"""Input-to-screen latency over a matrix of network cells (issue 28): input_latency.py
once per cell (RTT x jitter x loss, through the relay), every client variant in each
cell against the same server and relay. Writes OUT/net_matrix.csv (one row per cell and
variant: p50, p99, n and the relay's counters for that variant), each cell's per-trial
CSV and JSON, and with gnuplot OUT/net_matrix.png: p50 (solid) and p99 (dashed) latency
by RTT per variant, one panel per jitter x loss. Never passes or fails on time.

usage: FTS_BIN_DIR=build python3 tests/bench/net_matrix.py [--out bench-out/net-matrix]
           [--variant NAME=CLIENT_ARGS ...] [--trials 8] [--rtt 0,150] [--jitter 0] [--loss 0]
           [--burst-len 3] [--full] [--bots 0] [-- more input_latency.py flags]
The default is 2 cells (RTT 0 and 150 ms, no jitter, no loss) with one variant, the
client as it is: a few minutes. --full is RTT 0/50/150/300 x jitter 0/20 x loss 0/2/10 %,
24 cells; at the default 8 trials about 40 s per cell and variant. The comparison for
client-side prediction:

  FTS_BIN_DIR=build python3 tests/bench/net_matrix.py --full --trials 20 \\
      --variant predict= --variant no-predict=--no-predict --out bench-out/net-matrix

Per direction, a cell's RTT is a fixed delay of RTT/2, its jitter is uniform 0..J ms
added without reordering, and its loss is Gilbert-Elliott bursts of mean --burst-len
datagrams giving that share of loss (relay.py --burst-loss); seed 1 in every cell.
"""
import argparse, csv, json, os, shutil, subprocess, sys, time

HERE = os.path.dirname(os.path.abspath(__file__))
DRIVER = os.path.join(HERE, "input_latency.py")
COUNTERS = ["datagrams_in", "datagrams_out", "lost.random", "lost.burst", "lost.down", "lost.queue", "duplicated",
            "reordered"]


def numbers(text):
    return [float(x) for x in text.split(",") if x.strip()]


def counter(c, key):
    for k in key.split("."):
        c = c.get(k, {}) if isinstance(c, dict) else {}
    return c if isinstance(c, (int, float)) else ""


def plot(out, rows, variants, jitters, losses):
    if not shutil.which("gnuplot"):
        print("gnuplot not found: no plot (apt-get install gnuplot-nox)", file=sys.stderr)
        return None
    panels = []
    for j in jitters:
        for loss in losses:
            series = []
            for v in variants:
                pts = sorted((r["rtt_ms"], r["p50_ms"], r["p99_ms"]) for r in rows
                             if r["variant"] == v and r["jitter_ms"] == j and r["loss_pct"] == loss and r["n"])
                if not pts:
                    continue
                dat = os.path.join(out, f"plot-{v}-j{j:g}-l{loss:g}.dat")
                with open(dat, "w") as f:
                    f.writelines(f"{x:g} {p50:.2f} {p99:.2f}\n" for x, p50, p99 in pts)
                series.append((v, dat))
            panels.append((j, loss, series))
    cols = len(losses)
    script = [f"set terminal pngcairo size {max(640, 480 * cols)},{max(420, 360 * len(jitters))} font ',10'",
              f"set output '{os.path.join(out, 'net_matrix.png')}'",
              f"set multiplot layout {len(jitters)},{cols} title 'fts-client input-to-screen latency (tmux)'",
              "set xlabel 'RTT (ms)'", "set ylabel 'latency (ms)'", "set grid", "set key top left",
              "set yrange [0:*]"]
    for j, loss, series in panels:
        script.append(f"set title 'jitter {j:g} ms, loss {loss:g} %'")
        if not series:
            script.append("plot NaN notitle")
            continue
        parts = []
        for i, (v, dat) in enumerate(series):
            parts.append(f"'{dat}' using 1:2 with linespoints lt {i + 1} dt 1 pt 7 ps 0.7 title '{v} p50'")
            parts.append(f"'{dat}' using 1:3 with linespoints lt {i + 1} dt 2 pt 6 ps 0.7 title '{v} p99'")
        script.append("plot " + ", ".join(parts))
    script.append("unset multiplot")
    p = subprocess.run(["gnuplot"], input="\n".join(script) + "\n", text=True, capture_output=True)
    if p.returncode != 0:
        print(f"gnuplot failed: {p.stderr.strip()}", file=sys.stderr)
        return None
    return os.path.join(out, "net_matrix.png")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0], allow_abbrev=False)
    ap.add_argument("--out", default=os.path.join("bench-out", "net-matrix"))
    ap.add_argument("--variant", action="append", default=[], help="NAME=CLIENT_ARGS (repeatable)")
    ap.add_argument("--trials", type=int, default=8)
    ap.add_argument("--rtt", default="0,150", help="RTTs in ms, comma-separated")
    ap.add_argument("--jitter", default="0", help="jitter per direction in ms")
    ap.add_argument("--loss", default="0", help="loss per direction in %% (bursts)")
    ap.add_argument("--burst-len", type=float, default=3)
    ap.add_argument("--full", action="store_true", help="RTT 0,50,150,300 x jitter 0,20 x loss 0,2,10")
    ap.add_argument("--bots", type=int, default=0)
    a, rest = ap.parse_known_args()
    if rest[:1] == ["--"]:
        rest = rest[1:]
    if a.full:
        a.rtt, a.jitter, a.loss = "0,50,150,300", "0,20", "0,2,10"
    rtts, jitters, losses = numbers(a.rtt), numbers(a.jitter), numbers(a.loss)
    variants = a.variant or ["current="]
    names = [v.partition("=")[0] for v in variants]
    os.makedirs(a.out, exist_ok=True)
    rows = []
    header = ["cell", "rtt_ms", "jitter_ms", "loss_pct", "variant", "client_args", "p50_ms", "p99_ms", "mean_ms", "n",
              "timeouts", "wrong_direction"] + [f"{d}_{k.replace('.', '_')}" for d in ("up", "down") for k in COUNTERS]
    table = os.path.join(a.out, "net_matrix.csv")
    cells = [(r, j, l) for l in losses for j in jitters for r in rtts]
    t_start = time.monotonic()
    with open(table, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(header)
        for k, (rtt, jit, loss) in enumerate(cells):
            cell = f"rtt{rtt:g}-j{jit:g}-l{loss:g}"
            cmd = [sys.executable, DRIVER, "--relay", "--rtt-ms", f"{rtt:g}", "--jitter-ms", f"{jit:g}",
                   "--burst-loss-pct", f"{loss:g}", "--burst-len", f"{a.burst_len:g}", "--trials", str(a.trials),
                   "--bots", str(a.bots), "--csv", os.path.join(a.out, f"{cell}.csv"),
                   "--json", os.path.join(a.out, f"{cell}.json"), *rest]
            for v in variants:
                cmd += ["--variant", v]
            print(f"[{k + 1}/{len(cells)}] {cell} ({time.monotonic() - t_start:.0f} s)", file=sys.stderr, flush=True)
            p = subprocess.run(cmd, stdout=subprocess.DEVNULL)
            try:
                with open(os.path.join(a.out, f"{cell}.json")) as jf:
                    result = json.load(jf)["variants"]
            except (OSError, ValueError, KeyError):
                print(f"{cell}: the driver wrote no results (exit {p.returncode})", file=sys.stderr)
                continue
            for s in result:
                row = {"cell": cell, "rtt_ms": rtt, "jitter_ms": jit, "loss_pct": loss, "variant": s["variant"],
                       "client_args": s.get("client_args", ""), "n": s.get("n", 0)}
                for key in ("p50_ms", "p99_ms", "mean_ms"):
                    row[key] = s.get(key, float("nan"))
                rows.append(row)
                relay = s.get("relay", {})
                w.writerow([cell, f"{rtt:g}", f"{jit:g}", f"{loss:g}", s["variant"], row["client_args"],
                            f"{row['p50_ms']:.1f}", f"{row['p99_ms']:.1f}", f"{row['mean_ms']:.1f}", row["n"],
                            s.get("timeouts", ""), s.get("wrong_direction", "")]
                           + [counter(relay.get(d, {}), c) for d in ("up", "down") for c in COUNTERS])
                f.flush()
                print(f"  {s['variant']}: p50 {row['p50_ms']:.1f} ms, p99 {row['p99_ms']:.1f} ms, n {row['n']}"
                      + (f" ({s['error'][:200]})" if "error" in s else ""), file=sys.stderr, flush=True)
    png = plot(a.out, rows, names, jitters, losses)
    print(f"wrote {table}" + (f" and {png}" if png else ""), file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
