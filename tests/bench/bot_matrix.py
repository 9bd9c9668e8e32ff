#!/usr/bin/env python3
"""Predicting bots over a matrix of network cells (issue 28): the program's own figures
beside input_latency.py's outside view. Per cell (RTT x jitter x loss through the seeded
relay, as net_matrix.py builds them: RTT/2 each way, uniform jitter without reordering,
Gilbert-Elliott loss bursts), a fresh fts-server, the relay and one predicting hunter bot
(fts-bot --predict) for --seconds. One CSV row per cell: the bot's level reached,
snapshots lost, RTT, the prediction's corrections (per minute, p50/p99 in ball radii, p99
while nothing touched the ball, snaps), the server's count of frames on time and late, and
bytes each way (the relay's counters). Never passes or fails on time.

Issue 37: --variant NAME=ARGS (repeatable) runs each cell once per variant, back to back
with the same relay seed, the bot given ARGS besides --predict (`own-only=--predict-own-only`
is the prediction before collisions were predicted). Contact corrections: those at a
snapshot that shows another ball within reach of the own ball (predict/prediction.hpp,
PredictionStats): p99 in radii, and snaps (over 2 radii) per minute. --others N adds N
hunter bots (not predicting, straight to the server) in the predicting bot's room (it
creates a private one, they join its code): remote players.

usage: FTS_BIN_DIR=build python3 tests/bench/bot_matrix.py [--out bench-out/bot-matrix]
           [--rtt 0,50,150,300] [--jitter 0,20] [--loss 0,2,10] [--seconds 20] [--burst-len 3]
           [--variant predict=] [--variant own-only=--predict-own-only] [--others 0]
"""
import argparse, csv, json, os, re, signal, subprocess, sys, tempfile, time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
BIN = os.environ.get("FTS_BIN_DIR", "build")
RELAY = os.path.join(ROOT, "tests", "integration", "relay.py")


def numbers(text):
    return [float(x) for x in text.split(",") if x.strip()]


def relay_args(rtt, jitter, loss, burst_len):
    args = ["--delay-ms", f"{rtt / 2:g}", "--jitter-ms", f"{jitter:g}", "--loss", "0", "--dup", "0", "--seed", "1",
            "--no-reorder"]
    if loss > 0:
        share = loss / 100.0
        args += ["--burst-loss", f"{share / (burst_len * (1 - share)):.6g}", "--burst-len", f"{burst_len:g}"]
    return args


def run_cell(rtt, jitter, loss, a, work, variant=("predict", [])):
    log = open(os.path.join(work, "server.log"), "w")
    srv = subprocess.Popen([os.path.join(BIN, "server", "fts-server"), "--port", "0", "--bind", "127.0.0.1",
                            "--stats-interval-ms", "1000", "--log-format", "json"], stdout=log, stderr=log)
    try:
        port = None
        for _ in range(200):
            m = re.search(r'"event":"ready".*?"port":(\d+)', open(log.name).read())
            if m:
                port = int(m.group(1))
                break
            time.sleep(0.05)
        relay = subprocess.Popen([sys.executable, RELAY, "--listen", "0", "--server", f"127.0.0.1:{port}",
                                  *relay_args(rtt, jitter, loss, a.burst_len)], stdout=subprocess.PIPE, text=True)
        rport = int(relay.stdout.readline().strip().split("=")[1])
        report = os.path.join(work, "bot.json")
        # With --others the predicting bot makes a private room and the others join its code
        # (from the server's room_open line): they play its match.
        bot = subprocess.Popen([os.path.join(BIN, "client", "fts-bot"), "--connect", f"127.0.0.1:{rport}", "--name", "pred",
                                "--behavior", "hunter", "--predict", *variant[1], "--duration", str(a.seconds),
                                *(["--room", "create"] if a.others > 0 else []), "--report", report],
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        others = None
        if a.others > 0:
            code = None
            for _ in range(200):
                m = re.search(r'"event":"room_open".*?"code":"([A-Z]+)"', open(log.name).read())
                if m:
                    code = m.group(1)
                    break
                time.sleep(0.05)
            others = subprocess.Popen([os.path.join(BIN, "client", "fts-bot"), "--connect", f"127.0.0.1:{port}", "--name", "oth",
                                       "--count", str(a.others), "--behavior", "hunter", "--seed", "7", "--room", code or "quick",
                                       "--duration", str(a.seconds + 2), "--report", os.path.join(work, "others.json")],
                                      stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        bot.wait(timeout=a.seconds + 60)
        same_room = None
        if others is not None:
            try:
                others.wait(timeout=30)  # they end on their own, 2 s after the predicting bot
            except subprocess.TimeoutExpired:
                others.terminate()
                others.wait(timeout=10)
            try:  # the remote players share the predicting bot's room (a quick join: the fullest open one)
                with open(report) as f:
                    room = json.load(f)[0].get("room")
                with open(os.path.join(work, "others.json")) as f:
                    same_room = all(o.get("room") == room for o in json.load(f))
            except (OSError, ValueError, IndexError):
                same_room = False
        relay.send_signal(signal.SIGTERM)
        counters = json.loads(relay.stdout.read().strip().splitlines()[-1] or "{}")
        relay.wait(timeout=10)
        with open(report) as f:
            r = json.load(f)[0]
        stats = [json.loads(l) for l in open(log.name) if '"event":"stats"' in l]
        inputs = stats[-1].get("inputs", {}) if stats else {}
        p = r.get("prediction", {})
        minutes = a.seconds / 60.0
        return {"variant": variant[0], "rtt_ms": rtt, "jitter_ms": jitter, "loss_pct": loss, "ok": r.get("ok"),
                "level": r.get("level"),
                "rtt_p50_ms": round(r.get("rtt_p50_ms", 0), 1), "snapshots_lost": r.get("snapshots_lost"),
                "corrections_per_min": round((p.get("corrections", 0) + p.get("snaps", 0)) / minutes, 1),
                "correction_p50_radii": round(p.get("correction_p50_radii", 0), 4),
                "correction_p99_radii": round(p.get("correction_p99_radii", 0), 4),
                "free_correction_p99_radii": round(p.get("free_correction_p99_radii", 0), 4),
                "contact_corrections": p.get("contact_corrections", 0),
                "contact_correction_p50_radii": round(p.get("contact_correction_p50_radii", 0), 4),
                "contact_correction_p99_radii": round(p.get("contact_correction_p99_radii", 0), 4),
                "snaps_per_min": round(p.get("snaps", 0) / minutes, 2),
                "balls_per_tick": round(p.get("balls_per_tick_stepped", 0), 2),
                "frame_us_p50": round(p.get("frame_us_p50", 0), 1), "frame_us_p99": round(p.get("frame_us_p99", 0), 1),
                "snapshot_us_p50": round(p.get("snapshot_us_p50", 0), 1),
                "snapshot_us_p99": round(p.get("snapshot_us_p99", 0), 1),
                "snaps": p.get("snaps", 0), "frames_on_time": inputs.get("on_time", 0), "frames_late": inputs.get("late", 0),
                "up_bytes_per_s": round(counters.get("up", {}).get("bytes_in", 0) / a.seconds),
                "down_bytes_per_s": round(counters.get("down", {}).get("bytes_in", 0) / a.seconds),
                "bot_rc": bot.returncode, "others_same_room": same_room}
    finally:
        srv.send_signal(signal.SIGINT)
        try:
            srv.wait(timeout=10)
        except subprocess.TimeoutExpired:
            srv.kill()


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", default="bench-out/bot-matrix")
    ap.add_argument("--rtt", default="0,50,150,300")
    ap.add_argument("--jitter", default="0,20")
    ap.add_argument("--loss", default="0,2,10")
    ap.add_argument("--seconds", type=float, default=20)
    ap.add_argument("--burst-len", type=float, default=3)
    ap.add_argument("--variant", action="append", default=[], help="NAME=ARGS (fts-bot flags besides --predict)")
    ap.add_argument("--others", type=int, default=0)
    a = ap.parse_args()
    variants = [(v.split("=", 1)[0], v.split("=", 1)[1].split()) for v in a.variant] or [("predict", [])]
    os.makedirs(a.out, exist_ok=True)
    rows = []
    for rtt in numbers(a.rtt):
        for jitter in numbers(a.jitter):
            for loss in numbers(a.loss):
                for variant in variants:
                    with tempfile.TemporaryDirectory(prefix="fts-botm-") as work:
                        row = run_cell(rtt, jitter, loss, a, work, variant)
                    print(json.dumps(row), flush=True)
                    rows.append(row)
    path = os.path.join(a.out, "bot_matrix.csv")
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    print(f"wrote {path}")


if __name__ == "__main__":
    sys.exit(main())
