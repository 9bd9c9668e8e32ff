#!/usr/bin/env python3
"""The latency driver's parts (input_latency.py): what it reads from a pane, the relay
flags it derives, its percentiles; and one short run end to end (a real server, relay
and client in tmux) that must produce numbers. Asserts nothing about time.

usage: test_input_latency.py parse|smoke   (smoke needs FTS_BIN_DIR and tmux)
"""
import argparse, json, os, random, shutil, subprocess, sys, tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "..", "integration"))
import input_latency as il  # noqa: E402
from harness import check, main  # noqa: E402

PANE = """Level: 1   Coins: 0   Lives: 3   Ping: 0 ms   Loss: 0.0%   Room EANEG
                          Players
                          @ lat        0c 3L
+-----------------------+  1s Level 1 started.
|.......................|
|....lat................|
|...@@@@@.......#####...|
|...@@40@......###30##..|
|...@@@@@.......#####...|
|........O12O...........|
+-----------------------+  @@ not a ball
Move: arrows/WASD/hjkl/mouse"""


def test_parse():
    cells, box = il.own_ball(PANE)
    check(box == (3, 10, 0, 24), f"the frame is {box}")
    check(cells is not None and len(cells) == 15, f"{len(cells or ())} cells of the own ball: {sorted(cells or ())}")
    check(all(3 <= r <= 10 and 0 <= c <= 24 for r, c in cells), "an '@' outside the frame was taken")
    col, row = il.centre(cells)
    check(col == 6.0 and row == 7.0, f"centre {col}, {row}")
    moved, _ = il.own_ball(PANE.replace("|...@@@@@.......", "|....@@@@@......", 1))
    check(moved != cells and il.centre(moved)[0] > col, "a cell to the right is not seen as a move right")
    # One column left, its label with it: a move left (only '@' cells would say right).
    left, _ = il.own_ball(PANE.replace("|...@@40@", "|..@@40@.", 1))
    check(left != cells and il.centre(left)[0] < col, f"the label's shift reads as {il.centre(left)[0] - col:+.2f}")
    gone, box2 = il.own_ball(PANE.replace("@@@@@", ".....").replace("@@40@", "..40."))
    check(gone is None and box2 == box, "no ball on the platform must read as none")
    check(il.own_ball("Connecting...\n")[0] is None, "a pane without the platform has no ball")
    # Braille dots (--glyphs braille), captured with escapes: the dots in the own colour
    # (the legend's '@'), the label on the own colour as full cells; red dots are another ball.
    y, red, lbl, off = "\x1b[1;33m", "\x1b[1;31m", "\x1b[0;1;30;43m", "\x1b[0m"

    def fine(row):
        return "\n".join(["Level: 1   Coins: 0", f"{y}@{off} lat", "+--------+", f"|{row}{off}|", "+--------+"])
    dots, fbox = il.own_ball(fine(f"{y}\u28ff{lbl}12{y}\u2847{off}  {red}\u28ff{off} "))
    check(fbox == (2, 4, 0, 9), f"the frame is {fbox}")
    check(dots is not None and len(dots) == 8 + 16 + 4, f"{len(dots or ())} own dots")
    right, _ = il.own_ball(fine(f" {y}\u28ff{lbl}12{y}\u2847{off} {red}\u28ff{off} "))
    check(right != dots and il.centre(right)[0] > il.centre(dots)[0], "a move right in dots")
    nudged, _ = il.own_ball(fine(f"{y}\u28fe{lbl}12{y}\u2847{off}  {red}\u28ff{off} "))
    check(nudged != dots, "one dot fewer is a change")
    v = [float(x) for x in range(1, 101)]
    check(il.percentile(v, 0.5) == 50.5 and abs(il.percentile(v, 0.99) - 99.01) < 1e-9, "percentiles")
    check(il.percentile([7.0], 0.99) == 7.0, "one value is every percentile")
    # --burst-loss-pct X with --burst-len N: the relay's bad state holds X % of the datagrams.
    for pct, n in ((2, 3), (10, 3), (10, 5)):
        a = argparse.Namespace(rtt_ms=150, jitter_ms=20, jitter_dist="uniform", loss=0, dup=0, relay_seed=1,
                               burst_loss_pct=pct, burst_len=n, reorder=False, relay_args="--rate-kbps 500")
        args = il.relay_args(a)
        p = float(args[args.index("--burst-loss") + 1])
        share = p / (p + 1 / n)
        check(abs(share - pct / 100) < 1e-5, f"{pct} % in bursts of {n}: p={p} gives {share:.4%}")
        check(args[args.index("--delay-ms") + 1] == "75" and "--no-reorder" in args and args[-2:] == ["--rate-kbps",
              "500"], f"relay args {args}")
        # and the relay's own Gilbert-Elliott chain with that p loses about that share
        rng, bad, lost = random.Random(pct * 10 + n), False, 0
        for _ in range(200000):
            u = rng.random()
            bad = (u >= 1 / n) if bad else (u < p)
            lost += bad
        check(abs(lost / 200000 - pct / 100) < 0.1 * pct / 100, f"{pct} %: the chain lost {lost / 2000:.2f} %")
    c = il.counter_diff({"up": {"datagrams_in": 5, "lost": {"burst": 1}}, "final": False, "seed": 1},
                        {"up": {"datagrams_in": 9, "lost": {"burst": 4}}, "final": False, "seed": 1})
    check(c == {"up": {"datagrams_in": 4, "lost": {"burst": 3}}, "seed": 0}, f"counter diff {c}")


def test_smoke():
    """Two trials through the relay (50 ms RTT): the driver finds the ball, sees it move
    both ways and reports n = 2 with the relay's counters; a variant whose client refuses
    its flags is reported as an error, not as numbers."""
    if not shutil.which("tmux"):
        print("SKIP: tmux not installed")
        sys.exit(77)
    out = tempfile.mkdtemp(prefix="fts-latency-test-")
    try:
        js = os.path.join(out, "run.json")
        p = subprocess.run([sys.executable, os.path.join(HERE, "input_latency.py"), "--trials", "2", "--rtt-ms", "50",
                            "--trial-timeout-s", "20",
                            "--variant", "plain=", "--variant", "bad=--no-such-flag", "--csv",
                            os.path.join(out, "run.csv"), "--json", js], capture_output=True, text=True, timeout=120)
        print(p.stderr)
        check(p.returncode == 1, f"exit {p.returncode} with a variant that cannot start (expected 1)")
        with open(js) as f:
            r = json.load(f)
        plain, bad = r["variants"]
        check(plain["n"] >= 1, f"plain: {plain}")
        check(plain["p50_ms"] > 0 and plain["relay"]["up"]["datagrams_out"] > 0 and
              plain["relay"]["down"]["datagrams_out"] > 0, f"plain: {plain}")
        check("error" in bad and "no-such-flag" in bad["error"], f"bad: {bad}")
        with open(os.path.join(out, "run.csv")) as f:
            rows = f.read().splitlines()
        check(rows[0].startswith("variant,trial,key,latency_ms") and len(rows) == 3, f"csv: {rows}")
        check({r.split(",")[2] for r in rows[1:]} == {"Left", "Right"}, f"keys: {rows}")
    finally:
        shutil.rmtree(out, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main({"parse": test_parse, "smoke": test_smoke}))
