#!/usr/bin/env python3
"""Sessions that never lose a player's progress (issue 11), with real processes:
a client killed mid-keypress loses no life, a 15 s stop of the server drops nobody, and
(label soak) 8 bots behind a lossy relay, killed and restarted at random for minutes,
keep every coin they earned."""
import os, random, re, signal, subprocess, sys, time

from harness import (BOT, HERE, Failure, Server, check, finish_bots, main, run_bots, start_bots, wait_for,
                     write_script)

MANY_LIVES = os.path.join(HERE, "many-lives.json")

HOLD_UP = """
timeout 60
wait connected
ready
wait play
move up 1000000
"""


def player_id(srv, name):
    m = wait_for(lambda: re.search(rf"connect player=(\d+) name={name}\b", srv.text()), 10, f"{name} to connect")
    return m.group(1)


def test_killed_mid_keypress():
    """A client killed 50 ms into holding Up: its input expires (150 ms), the ball coasts
    to a stop on the platform, and no life is lost before the server times it out."""
    with Server("--config", MANY_LIVES, "--timeout-ms", "4000", "--log-level", "debug") as srv:
        bot = start_bots("--connect", srv.address, "--name", "crash", "--script", write_script(HOLD_UP))
        pid = player_id(srv, "crash")
        wait_for(lambda: "level_start level=1" in srv.text(), 30, "level 1 to start")
        # The scenario's own timing: the key is held for about 50 ms, then the process dies.
        time.sleep(0.05)
        bot[0].send_signal(signal.SIGKILL)
        bot[0].wait()
        wait_for(lambda: re.search(rf"disconnect player={pid} reason=timeout", srv.text()), 15,
                 "the server to time the killed client out")
        fell = re.findall(rf"player_fell player={pid}\b", srv.text())
        check(not fell, f"the killed client's ball lost {len(fell)} lives while nobody held a key")


def test_server_stall():
    """The server process stopped for 15 s (SIGSTOP): nobody is dropped for it, every
    bot plays on with its own player."""
    with Server("--log-level", "debug") as srv:
        bots = start_bots("--connect", srv.address, "--name", "steady", "--count", "5", "--behavior", "hunter",
                          "--duration", "30")
        wait_for(lambda: len(re.findall(r"connect player=\d+ name=steady", srv.text())) >= 5, 20, "5 bots")
        wait_for(lambda: "level_start level=1" in srv.text(), 30, "level 1 to start")
        srv.proc.send_signal(signal.SIGSTOP)
        time.sleep(15)  # the stall under test
        srv.proc.send_signal(signal.SIGCONT)
        rc, report, err = finish_bots(bots, 90)
        text = srv.text()
        timeouts = re.findall(r"disconnect player=\d+ reason=timeout", text)
        leaves = re.findall(r"leave player=\d+", text)
        check(not timeouts, f"{len(timeouts)} players timed out for the server's own stall")
        check(not leaves, f"players released: {leaves}")
        check(rc == 0, f"bots failed after the stall (exit {rc}): {err.strip()}")
        ids = {b["player_id"] for b in report}
        check(len(ids) == 5, f"bots ended as players {sorted(ids)}")
        check(re.search(r"stall ms=\d+", text), "the server did not log its stall")


def test_host_suspend():
    """The whole machine suspended for 12 s (a laptop's lid: server and clients stop
    together, SIGSTOP to all): nobody is dropped from the match, every bot plays on as its
    own player to the end of its run, its coins what the server's log says it earned
    and spent."""
    with Server("--log-level", "debug") as srv:
        (bots, report) = start_bots("--connect", srv.address, "--name", "lid", "--count", "4", "--behavior",
                                    "shopper", "--duration", "28")
        wait_for(lambda: len(re.findall(r"connect player=\d+ name=lid", srv.text())) >= 4, 20, "4 bots")
        wait_for(lambda: "level_start level=1" in srv.text(), 30, "level 1 to start")
        for p in (srv.proc, bots):
            p.send_signal(signal.SIGSTOP)
        time.sleep(12)  # the suspend under test
        for p in (bots, srv.proc):
            p.send_signal(signal.SIGCONT)
        rc, report, err = finish_bots((bots, report), 90)
        text = srv.text()
        timeouts = re.findall(r"disconnect player=\d+ reason=timeout", text)
        check(not timeouts, f"{len(timeouts)} players timed out for a suspend of the whole host")
        check(not re.findall(r"leave player=\d+", text), "players released after the suspend")
        check(rc == 0, f"bots failed after the suspend (exit {rc}): {err.strip()}")
        check(len({b["player_id"] for b in report}) == 4, "bots came back as other players")
        # A client that stood still past its time-out cannot know the server did too: it
        # comes back at once with its token, as the same player (waiting on a session a
        # server that ran on may have dropped would cost another time-out).
        first = set(re.findall(r"\bconnect player=(\d+) name=lid", text))
        back = set(re.findall(r"reconnect player=(\d+) name=lid", text))
        check(back <= first, f"came back as new players: {back - first}")
        for b in report:
            pid = str(b["player_id"])
            # What the log says up to the bot's own bye: an enemy it pushed may still fall
            # (and pay) after it left, which its report cannot have seen.
            bye = text.find(f"disconnect player={pid} reason=done")
            earned, spent = ledger(text if bye < 0 else text[:bye])
            check(b["coins"] == earned.get(pid, 0) - spent.get(pid, 0),
                  f"{b['name']}: {b['coins']} coins, the log says {earned.get(pid, 0)} - {spent.get(pid, 0)}")
        check(re.search(r"stall ms=\d+", text), "the server did not log its stall")


def ledger(text):
    """Per player: coins from enemies and interest, and coins spent, from the server log."""
    earned, spent = {}, {}
    for m in re.finditer(r"enemy_defeated enemy=\d+ player=(\d+) coins=(\d+)", text):
        earned[m.group(1)] = earned.get(m.group(1), 0) + int(m.group(2))
    for m in re.finditer(r"interest player=(\d+) coins=(\d+)", text):
        earned[m.group(1)] = earned.get(m.group(1), 0) + int(m.group(2))
    for m in re.finditer(r"purchase player=(\d+) item=\w+ ok=true reason=\w* price=(\d+)", text):
        spent[m.group(1)] = spent.get(m.group(1), 0) + int(m.group(2))
    return earned, spent


def test_soak_churn():
    """10 minutes: 8 shopper bots behind a relay with 25 % loss, 25 % duplicates and
    10-70 ms delay; bots are killed and restarted at random with their tokens. At the end
    every bot's coins equal what its enemies and interest earned minus what it spent."""
    minutes = float(os.environ.get("FTS_SOAK_MINUTES", "10"))
    rng = random.Random(11)
    with Server("--config", MANY_LIVES, "--log-level", "debug", "--reconnect-window-ms", "60000") as srv:
        relay = subprocess.Popen([sys.executable, os.path.join(HERE, "relay.py"), "--server", srv.address,
                                  "--loss", "0.25", "--dup", "0.25", "--delay-ms", "10", "--jitter-ms", "60",
                                  "--seed", "5"], stdout=subprocess.PIPE, text=True)
        try:
            m = re.search(r"port=(\d+)", relay.stdout.readline())
            check(m, "relay did not start")
            target = f"127.0.0.1:{m.group(1)}"
            tokens = [write_script("") for _ in range(8)]
            for t in tokens:
                os.unlink(t)

            def launch(i, seconds):
                return start_bots("--connect", target, "--name", f"soak{i}", "--behavior", "shopper",
                                  "--token-file", tokens[i], "--duration", str(seconds), "--seed", str(i + 1))

            end = time.monotonic() + minutes * 60
            bots = [launch(i, minutes * 60 + 30) for i in range(8)]
            kills = 0
            while time.monotonic() < end - 20:
                time.sleep(rng.uniform(5, 20))  # churn at random moments (the load under test)
                i = rng.randrange(8)
                bots[i][0].send_signal(signal.SIGKILL)
                bots[i][0].wait()
                kills += 1
                bots[i] = launch(i, max(30, end - time.monotonic() + 10))
            reports = [finish_bots(b, minutes * 60 + 120) for b in bots]
        finally:
            relay.kill()
            relay.wait()
        srv.stop()
        text = srv.text()
        earned, spent = ledger(text)
        start = 0
        for rc, report, err in reports:
            check(report, f"a bot wrote no report: {err.strip()}")
            b = report[0]
            pid = str(b["player_id"])
            expected = start + earned.get(pid, 0) - spent.get(pid, 0)
            check(b["coins"] == expected,
                  f"{b['name']} (player {pid}): {b['coins']} coins, the ledger says {expected} "
                  f"(earned {earned.get(pid, 0)}, spent {spent.get(pid, 0)})")
        check(kills >= 10, f"only {kills} restarts")
        print(f"soak: {kills} restarts, ledger per player: earned {earned}, spent {spent}")


if __name__ == "__main__":
    sys.exit(main({"killed_mid_keypress": test_killed_mid_keypress, "server_stall": test_server_stall, "host_suspend": test_host_suspend,
                   "soak_churn": test_soak_churn}))
