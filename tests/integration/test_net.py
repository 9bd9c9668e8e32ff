#!/usr/bin/env python3
"""Playing over a real network (issue 28): a real fts-server behind the seeded impairment
relay at 150 ms round trip (75 ms each way), 20 ms jitter and 2 % loss.

bot_150ms_tuned: the same bot for 20 s against a host with friction 0.95 per frame in
              --config (issue 36): it predicts with the welcome's physics, so its corrections
              while nothing touches its ball are as small as on a default host
              (bot_150ms_default, not in CTest, prints a default host's figures).
bot_150ms:    a predicting fts-bot (hunter) plays through the relay: it clears level 1,
              its prediction's corrections while nothing touches its ball stay under half
              a ball radius at the 99th percentile, and most of its frames reach the server
              before the tick they name (the server's stats line counts them).
client_150ms: the real fts-client in tmux through the relay, steered with arrow keys, with
              --stats-file; predicting, its own ball's drawn motion answers a key within
              two frames, corrections stay small and no remote-ball stall lasts over 100 ms;
              with --no-predict (the same link) the answer waits for the server.
Every wait polls with a deadline."""
import json, os, shutil, signal, subprocess, sys, tempfile, time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from harness import BIN, Failure, Server, check, finish_bots, main, start_bots, wait_for  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
CLIENT = os.path.join(BIN, "client", "fts-client")
LINK_JITTER_MS = 20
LINK = ["--delay-ms", "75", "--jitter-ms", str(LINK_JITTER_MS), "--loss", "0.02", "--dup", "0"]


class Relay:
    def __init__(self, server_port, seed=28):
        self.proc = subprocess.Popen([sys.executable, os.path.join(HERE, "relay.py"), "--listen", "0", "--server",
                                      f"127.0.0.1:{server_port}", "--seed", str(seed), *LINK],
                                     stdout=subprocess.PIPE, text=True)
        line = self.proc.stdout.readline()
        check(line.startswith("relay ready port="), f"the relay did not start: {line!r}")
        self.port = int(line.strip().split("=")[1])
        self.address = f"127.0.0.1:{self.port}"

    def close(self):
        self.proc.terminate()
        try:
            self.proc.wait(timeout=5)
        except subprocess.TimeoutExpired:
            self.proc.kill()


def stats_lines(srv):
    return [json.loads(l) for l in srv.text().splitlines() if '"event":"stats"' in l]


def predicting_hunter(seconds, *server_args):
    """A predicting fts-bot hunter through the relay for `seconds` (it stops by itself);
    returns its report's prediction figures."""
    with Server("--stats-interval-ms", "500", "--log-format", "json", *server_args) as srv:
        relay = Relay(srv.port)
        try:
            bot = start_bots("--connect", relay.address, "--name", "pred", "--behavior", "hunter", "--predict",
                             "--duration", str(seconds))
            rc, report, err = finish_bots(bot, seconds + 60)
        finally:
            relay.close()
    check(rc == 0 and report and report[0]["ok"], f"the bot failed: rc {rc} {report} {err}")
    pred = report[0].get("prediction")
    check(pred is not None, "no prediction figures in the report")
    return pred


# A host of issue 36: friction 0.95 per frame instead of 0.991 (docker/server-config.example.json
# invites such a change). Before the welcome carried the physics, a client predicted the
# default friction: its free corrections were p50 0.096, p99 0.41 radii (default host:
# 0.0027 and 0.084). The median is the check: a client on the wrong physics is off in
# every correction. The p99 also holds inputs that reached the server late on a busy
# machine (0.27 radii with the physics right, beside a CPU hog, 2026-12-06): reported.
TUNED = {"friction_per_frame": 0.95}
FREE_P50_MAX_RADII = 0.03


def test_bot_150ms_tuned():
    work = tempfile.mkdtemp(prefix="fts-net-")
    try:
        config = os.path.join(work, "tuned.json")
        with open(config, "w") as f:
            json.dump(TUNED, f)
        pred = predicting_hunter(20, "--config", config)
    finally:
        shutil.rmtree(work, ignore_errors=True)
    print(f"tuned host {TUNED}: prediction {pred}")
    check(pred["free_corrections"] >= 20, f"too few corrections to measure: {pred}")
    check(pred["free_correction_p50_radii"] <= FREE_P50_MAX_RADII,
          f"a tuned host's free corrections p50 {pred['free_correction_p50_radii']} radii (p99 "
          f"{pred['free_correction_p99_radii']}): over {FREE_P50_MAX_RADII} (a default host's run "
          "meets it): does the client predict with the host's physics?")


def measure_default():
    """The tuned case's run on a default host: its figures, which the bounds above hold
    with room (not in CTest: bot_150ms covers the default host)."""
    pred = predicting_hunter(20)
    print(f"default host: prediction {pred}")


def test_bot_150ms():
    with Server("--stats-interval-ms", "500", "--log-format", "json") as srv:
        relay = Relay(srv.port)
        try:
            bot = start_bots("--connect", relay.address, "--name", "pred", "--behavior", "hunter", "--predict",
                             "--duration", "60")
            wait_for(lambda: '"level_complete"' in srv.text(), 60, "the predicting bot to clear level 1")
            bot[0].send_signal(signal.SIGINT)  # done: a clean stop writes the report
            rc, report, err = finish_bots(bot, 30)
        finally:
            relay.close()
        check(rc == 0 and report and report[0]["ok"], f"the bot failed: rc {rc} {report} {err}")
        pred = report[0].get("prediction")
        print(f"bot: level {report[0]['level']}, rtt p50 {report[0]['rtt_p50_ms']} ms, prediction {pred}")
        check(pred is not None, "no prediction figures in the report")
        check(pred["free_correction_p99_radii"] <= 0.5,
              f"corrections while nothing touched the ball: p99 {pred['free_correction_p99_radii']} radii")
        inputs = stats_lines(srv)[-1].get("inputs", {})
        print(f"server: input frames {inputs}")
        timed = inputs.get("on_time", 0) + inputs.get("late", 0)
        check(timed > 50, f"too few frames named a tick: {inputs}")
        check(inputs["on_time"] >= 0.8 * timed, f"most frames should arrive before their tick: {inputs}")


def tmux(sock, *args):
    return subprocess.run(["tmux", "-L", sock, *args], capture_output=True, text=True).stdout


def read_stats(path):
    """The client's --stats-file figures so far ({} before the first write)."""
    try:
        with open(path) as f:
            return json.loads(f.read())
    except (OSError, ValueError):
        return {}


def client_run(relay, work, name, extra):
    """Plays a level-1 round in tmux through the relay, steering with arrow keys; returns
    the client's --stats-file figures."""
    sock = f"fts-net-{os.getpid()}-{name}"
    stats = os.path.join(work, f"{name}.json")
    cmd = (f"TERM=xterm-256color XDG_STATE_HOME='{work}/state-{name}' '{CLIENT}' --connect {relay.address} "
           f"--name {name} --no-kitty --quick --stats-file '{stats}' {extra}; echo CLIENT_EXIT=$?; sleep 600")
    tmux(sock, "new-session", "-d", "-s", name, "-x", "100", "-y", "30", cmd)
    try:
        pane = lambda: tmux(sock, "capture-pane", "-p", "-t", name)  # noqa: E731
        wait_for(lambda: "Room " in pane(), 15, f"{name}'s welcome")
        tmux(sock, "send-keys", "-t", name, "Enter")
        wait_for(lambda: pane().startswith("Level: 1 ") and "@" in pane(), 30, f"{name}'s level 1")
        # Taps and holds: each arrow key a new thrust the client answers, and 0.8 s after
        # each for the answer through the relay (about 0.3 s without prediction). On a loaded
        # machine tmux delivers keys late and some answers are not measurable (a ball at a
        # wall, a fall), so the keys go on until the stats file (written every second) counts
        # six answers, or for 40 s; the checks want four of each run.
        # A new key starts a new measurement, so an answer slower than the pause is cut off:
        # without prediction it is the round trip and the remote balls' delay, about 0.4 s
        # here. (That delay once grew to 1.8 s in a minute on a busy machine: the jitter
        # estimate took a server skipping ticks for a late link; client/net/jitter_buffer.cpp.)
        keys = ["Right", "Up", "Left", "Down"]
        pause = 0.8
        deadline = time.monotonic() + 40
        sent = 0
        while time.monotonic() < deadline and (sent < 4 or read_stats(stats).get("responses", 0) < 6):
            for _ in range(3):
                tmux(sock, "send-keys", "-t", name, keys[sent % 4])
                time.sleep(0.08)
            sent += 1
            time.sleep(pause)
        tmux(sock, "send-keys", "-t", name, "q")
        wait_for(lambda: "Quit?" in pane(), 5, "the quit question")
        tmux(sock, "send-keys", "-t", name, "y")
        wait_for(lambda: "CLIENT_EXIT=0" in pane(), 10, f"{name} to exit")
        return wait_for(lambda: read_stats(stats), 5, "the stats file")
    finally:
        tmux(sock, "kill-server")


def test_client_150ms():
    if shutil.which("tmux") is None:
        print("SKIP: tmux not installed")
        sys.exit(77)
    work = tempfile.mkdtemp(prefix="fts-net-")
    with Server() as srv:
        relay = Relay(srv.port)
        try:
            new = client_run(relay, work, "ann", "")
            old = client_run(relay, work, "bob", "--no-predict")
        finally:
            relay.close()
    print(f"predicting: {new}")
    print(f"--no-predict: {old}")
    check(new["predict"] and not old["predict"], "the runs did not predict as asked")
    check(new["responses"] >= 4 and old["responses"] >= 4, f"too few key responses: {new['responses']}, {old['responses']}")
    # The link's jitter is 20 ms; a loaded machine adds what its server's schedule slips
    # in the jitter buffer's 3 s window (client/net/jitter_buffer.cpp), never seconds.
    check(new["jitter_ms"] < 500 and old["jitter_ms"] < 500,
          f"the jitter estimate ran away: {new['jitter_ms']} ms, {old['jitter_ms']} ms")
    check(new["response_p50_ms"] <= 2 * 1000 / 60 + 5,
          f"predicting, the own ball answered a key in {new['response_p50_ms']} ms (p50), not within two frames")
    # From snapshots the answer needs at least the 75 ms way up and a snapshot back.
    check(old["response_p50_ms"] >= 60,
          f"without prediction the answer took only {old['response_p50_ms']} ms: is the relay delaying?")
    check(old["response_p50_ms"] - new["response_p50_ms"] >= 40, "prediction answered no sooner than snapshots")
    check(new["free_correction_p99_radii"] <= 0.5, f"corrections p99 {new['free_correction_p99_radii']} radii")
    # A stall is the client's to answer for while snapshots keep coming as the relay sends
    # them: at most 190 ms apart (95 ms one way, two lost in a row), and no later than the
    # link's jitter makes them. A longer gap is the server or the machine stopping (a loaded
    # machine: the suite beside a CPU hog), and no delay sized from the link bridges it.
    # Shorter hiccups of a starved server, relay or client make arrivals late beyond the
    # link: the buffer's delay grows by a quarter of the time passing, so arrivals 33 ms
    # later than it had seen stalled the balls for 134 ms (CI, 2026-12-07: the last
    # lateness estimate 89 ms on a link of 20 ms jitter). The estimate's highest value in
    # the run tells: within the link's jitter, a frame of the client's loop (it reads its
    # socket once a frame) and a margin, the stalls are judged. Idle, with the suite beside
    # it or beside `stress-ng --cpu 2`, that highest value was 30-36 ms here.
    late_limit = LINK_JITTER_MS + 17 + 15
    if new["longest_snapshot_gap_ms"] > 200:
        print(f"stalls not judged: snapshots stopped for {new['longest_snapshot_gap_ms']} ms (a busy machine)")
    elif new["jitter_max_ms"] > late_limit:
        print(f"stalls not judged: arrivals up to {new['jitter_max_ms']} ms late (p95), past the link's "
              f"{LINK_JITTER_MS} ms of jitter, a frame and a margin (a busy machine); stalls over 100 ms: "
              f"{new['stalls_over_100ms']}")
    else:
        print(f"stalls judged: arrivals at most {new['jitter_max_ms']} ms late (p95)")
        check(new["stalls_over_100ms"] == 0, f"{new['stalls_over_100ms']} remote-ball stalls over 100 ms")
    check(new["rtt_ms"] >= 120, f"the round trip {new['rtt_ms']} ms is not the relay's")


if __name__ == "__main__":
    sys.exit(main({"bot_150ms": test_bot_150ms, "bot_150ms_tuned": test_bot_150ms_tuned,
                   "client_150ms": test_client_150ms, "bot_150ms_default": measure_default}))
