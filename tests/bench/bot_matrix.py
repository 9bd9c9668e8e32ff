#!/usr/bin/env python3
"""Predicting bots over a matrix of network cells (issue 28): the program's own figures
beside input_latency.py's outside view. Per cell (RTT x jitter x loss through the seeded
relay, as net_matrix.py builds them: RTT/2 each way, uniform jitter without reordering,
Gilbert-Elliott loss bursts), a fresh fts-server, the relay and one predicting hunter bot
(fts-bot --predict) for --seconds. One CSV row per cell: the bot's level reached,
snapshots lost, RTT, the prediction's corrections (per minute, p50/p99 in ball radii, p99
while nothing touched the ball, snaps), the server's count of frames on time and late, and
bytes each way (the relay's counters). Never passes or fails on time.

usage: FTS_BIN_DIR=build python3 tests/bench/bot_matrix.py [--out bench-out/bot-matrix]
           [--rtt 0,50,150,300] [--jitter 0,20] [--loss 0,2,10] [--seconds 20] [--burst-len 3]
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


def run_cell(rtt, jitter, loss, a, work):
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
        bot = subprocess.run([os.path.join(BIN, "client", "fts-bot"), "--connect", f"127.0.0.1:{rport}", "--name", "pred",
                              "--behavior", "hunter", "--predict", "--duration", str(a.seconds), "--report", report],
                             capture_output=True, text=True, timeout=a.seconds + 60)
        relay.send_signal(signal.SIGTERM)
        counters = json.loads(relay.stdout.read().strip().splitlines()[-1] or "{}")
        relay.wait(timeout=10)
        with open(report) as f:
            r = json.load(f)[0]
        stats = [json.loads(l) for l in open(log.name) if '"event":"stats"' in l]
        inputs = stats[-1].get("inputs", {}) if stats else {}
        p = r.get("prediction", {})
        minutes = a.seconds / 60.0
        return {"rtt_ms": rtt, "jitter_ms": jitter, "loss_pct": loss, "ok": r.get("ok"), "level": r.get("level"),
                "rtt_p50_ms": round(r.get("rtt_p50_ms", 0), 1), "snapshots_lost": r.get("snapshots_lost"),
                "corrections_per_min": round((p.get("corrections", 0) + p.get("snaps", 0)) / minutes, 1),
                "correction_p50_radii": round(p.get("correction_p50_radii", 0), 4),
                "correction_p99_radii": round(p.get("correction_p99_radii", 0), 4),
                "free_correction_p99_radii": round(p.get("free_correction_p99_radii", 0), 4),
                "snaps": p.get("snaps", 0), "frames_on_time": inputs.get("on_time", 0), "frames_late": inputs.get("late", 0),
                "up_bytes_per_s": round(counters.get("up", {}).get("bytes_in", 0) / a.seconds),
                "down_bytes_per_s": round(counters.get("down", {}).get("bytes_in", 0) / a.seconds),
                "bot_rc": bot.returncode}
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
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    rows = []
    for rtt in numbers(a.rtt):
        for jitter in numbers(a.jitter):
            for loss in numbers(a.loss):
                with tempfile.TemporaryDirectory(prefix="fts-botm-") as work:
                    row = run_cell(rtt, jitter, loss, a, work)
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
