#!/usr/bin/env python3
"""The speed/accuracy trade, measured: sweeps model x tick rate x sub-steps over the
shipped scenes with fts-sim and writes CSV, a Markdown table and a cost-vs-error plot.

usage: tests/bench/trade_sweep.py [--fts-sim build/server/fts-sim] [--out bench-out]
                                  [--seconds 2] [--quick]

Each run simulates the same physical time (--seconds), so tick rates are comparable.
Columns:
  ns_per_body_step, us_per_tick  cost (wall clock of the steps only; noisy machine:
                                 compare ratios within one run)
  energy_drift                   max over ticks of |E - E0| / E0 (walled scenes)
  max_penetration                largest overlap after any tick (u)
  collisions, missed             ball-ball impulses; missed = continuous's count at the
                                 same tick rate minus this run's (never below 0)
  wall_pressure                  wall impulse / (perimeter x time) (walled scenes)
  pos_error                      RMS final-position error (u) against continuous at
                                 400 Hz, on the few-ball scenes only
It never passes or fails on time.
"""
import argparse, csv, json, math, os, subprocess, sys, tempfile

RATES = [25, 50, 100, 200, 400]
CONFIGS = [("seed", 1), ("discrete", 1), ("discrete", 2), ("discrete", 4), ("discrete", 8), ("continuous", 1)]
SCENES = {  # name: (walls, few-ball reference for position error)
    "gas-1000": (True, False),
    "gas-10000": (True, False),
    "rocket": (True, True),
    "game-like": (False, True),
}
ARENAS = {}


def run(sim, scene, model, substeps, hz, seconds, dump=None):
    steps = max(1, int(round(seconds * hz)))
    cmd = [sim, f"tests/scenes/{scene}.json", "--model", model, "--substeps", str(substeps),
           "--tick-rate", str(hz), "--steps", str(steps), "--check-every", "1" if "gas" not in scene else "10"]
    if dump:
        cmd += ["--dump-state", dump]
    out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    return json.loads(out), steps


def positions(path):
    with open(path) as f:
        return {b["id"]: (b["x"], b["y"]) for b in json.load(f)}


def rms_error(a, b):
    common = sorted(set(a) & set(b))
    if not common:
        return float("nan")
    err = sum((a[i][0] - b[i][0]) ** 2 + (a[i][1] - b[i][1]) ** 2 for i in common) / len(common)
    return math.sqrt(err)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--fts-sim", default="build/server/fts-sim")
    ap.add_argument("--out", default="bench-out")
    ap.add_argument("--seconds", type=float, default=2.0)
    ap.add_argument("--quick", action="store_true", help="100 Hz only, gas-1000 and game-like")
    ap.add_argument("--from-csv", help="skip the runs: redraw the table and plot from a trade.csv")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    rates = [100] if args.quick else RATES
    scenes = {k: v for k, v in SCENES.items() if not args.quick or k in ("gas-1000", "game-like")}
    for name in scenes:
        with open(f"tests/scenes/{name}.json") as f:
            ARENAS[name] = json.load(f)["arena"]
    rows = []
    tmp = tempfile.mkdtemp()
    if args.from_csv:
        with open(args.from_csv) as f:
            for r in csv.DictReader(f):
                r["substeps"], r["tick_rate"] = int(r["substeps"]), int(r["tick_rate"])
                for k in ("ns_per_body_step", "us_per_tick"):
                    r[k] = float(r[k])
                rows.append(r)
        scenes = {k: v for k, v in scenes.items() if any(r["scene"] == k for r in rows)}
    for scene, (walls, few) in ([] if args.from_csv else scenes.items()):
        ref = None
        if few:
            ref_path = os.path.join(tmp, f"{scene}-ref.json")
            run(args.fts_sim, scene, "continuous", 1, 400, args.seconds, ref_path)
            ref = positions(ref_path)
        for hz in rates:
            cont_collisions = None
            results = []
            for model, k in reversed(CONFIGS):  # continuous first: it is the reference count
                dump = os.path.join(tmp, f"{scene}-{model}-{k}-{hz}.json") if few else None
                r, steps = run(args.fts_sim, scene, model, k, hz, args.seconds, dump)
                if model == "continuous":
                    cont_collisions = r["collisions"]
                a = ARENAS[scene]
                perimeter = 2 * (a["width"] + a["height"])
                results.append({
                    "scene": scene, "model": model, "substeps": k, "tick_rate": hz, "steps": steps,
                    "bodies": r["bodies_start"],
                    "ns_per_body_step": r["ns_per_body_step"],
                    "us_per_tick": r["wall_seconds"] * 1e6 / steps,
                    "energy_drift": r["energy_drift_max_rel"] if walls else "",
                    "max_penetration": r["max_penetration"],
                    "collisions": r["collisions"],
                    "missed": max(0, cont_collisions - r["collisions"]),
                    "wall_pressure": r["wall_impulse"] / (perimeter * args.seconds) if walls else "",
                    "escaped": r["escaped"],
                    "pos_error": rms_error(positions(dump), ref) if few else "",
                })
                print(f"{scene:10} {model:10} K={k} {hz:4} Hz  {results[-1]['ns_per_body_step']:9.1f} ns/body-step",
                      file=sys.stderr)
            rows += reversed(results)
    fields = list(rows[0].keys())
    with open(os.path.join(args.out, "trade.csv") if not args.from_csv else os.devnull, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields)
        w.writeheader()
        w.writerows(rows)

    def fmt(v):
        if isinstance(v, float):
            return f"{v:.3g}"
        return str(v)
    with open(os.path.join(args.out, "trade.md"), "w") as f:
        f.write("| " + " | ".join(fields) + " |\n|" + "---|" * len(fields) + "\n")
        for r in rows:
            f.write("| " + " | ".join(fmt(r[k]) for k in fields) + " |\n")

    # Cost against error: one series per model configuration, its points the tick rates
    # (25 .. 400 Hz, cost rising with the rate). Error: RMS position error against
    # continuous@400Hz on few-ball scenes, max penetration on the gases (0 drawn at 1e-12).
    plot = os.path.join(args.out, "trade.png")
    script = ["set terminal png size 1400,1000", f"set output '{plot}'", "set multiplot layout 2,2",
              "set logscale xy", "set xlabel 'ns per body-step'", "set key bottom left font ',9'",
              "set format y '%.0e'"]
    for scene, (walls, few) in scenes.items():
        series = []
        for model, k in CONFIGS:
            dat = os.path.join(args.out, f"plot-{scene}-{model}-{k}.dat")
            with open(dat, "w") as f:
                for r in rows:
                    if r["scene"] == scene and r["model"] == model and r["substeps"] == k:
                        err = r["pos_error"] if few else r["max_penetration"]
                        f.write(f"{r['tick_rate']} {r['ns_per_body_step']} {max(float(err), 1e-12)}\n")
            series.append(f"'{dat}' using 2:3 with linespoints pt 7 title '{model} K={k}'")
        ylabel = "RMS position error vs continuous 400 Hz (u)" if few else "max penetration (u)"
        script += [f"set title '{scene} (points: 25, 50, 100, 200, 400 Hz)'", f"set ylabel \"{ylabel}\"",
                   "plot " + ", ".join(series)]
    script.append("unset multiplot")
    try:
        subprocess.run(["gnuplot"], input="\n".join(script), text=True, check=True, capture_output=True)
    except (OSError, subprocess.CalledProcessError) as e:
        print(f"gnuplot failed: {e}", file=sys.stderr)
    print(f"wrote {args.out}/trade.csv, trade.md, trade.png", file=sys.stderr)


if __name__ == "__main__":
    main()
