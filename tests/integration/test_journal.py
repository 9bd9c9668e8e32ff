#!/usr/bin/env python3
"""Crash-safe rooms (issue 15), with real processes: bots play, the server is killed
with SIGKILL at a random moment and restarted with --resume on the same port; every bot
reconnects with its token and finds its player; each bot's coins equal its ledger (what
its enemies and interest earned minus what it spent, counting the crashed server's
events only up to the resumed tick); the resumed state's hash equals a straight replay
of the journal (as a --record) up to that tick; the play lost is about the sync interval."""
import json, os, random, re, shutil, signal, subprocess, sys, tempfile, time

from harness import SERVER, HERE, Failure, Server, check, finish_bots, main, start_bots, wait_for

MANY_LIVES = os.path.join(HERE, "many-lives.json")
SYNC_MS = 100
TICK_HZ = 100
BOTS = 4


def ledger(text, upto_tick=None):
    """Per player: coins earned (defeats, interest) and spent, from a server log; only
    events of ticks <= upto_tick when given (the crashed server's events past the resumed
    tick never happened for the resumed match)."""
    earned, spent = {}, {}

    def keep(m):
        return upto_tick is None or int(m.group("tick")) <= upto_tick

    for m in re.finditer(r"enemy_defeated enemy=\d+ player=(?P<p>\d+) coins=(?P<c>\d+)(?: room=\d+)? tick=(?P<tick>\d+)", text):
        if keep(m):
            earned[m["p"]] = earned.get(m["p"], 0) + int(m["c"])
    for m in re.finditer(r"interest player=(?P<p>\d+) coins=(?P<c>\d+)(?: room=\d+)? tick=(?P<tick>\d+)", text):
        if keep(m):
            earned[m["p"]] = earned.get(m["p"], 0) + int(m["c"])
    for m in re.finditer(r"purchase player=(?P<p>\d+) item=\w+ ok=true reason=\w* price=(?P<c>\d+) coins=\d+ "
                         r"(?:room=\d+ )?tick=(?P<tick>\d+)", text):
        if keep(m):
            spent[m["p"]] = spent.get(m["p"], 0) + int(m["c"])
    return earned, spent


def add(total, part):
    for k, v in part.items():
        total[k] = total.get(k, 0) + v


def max_event_tick(text):
    ticks = [int(t) for t in re.findall(r"(?:enemy_defeated|interest|purchase) .*tick=(\d+)", text)]
    return max(ticks) if ticks else 0


def journal_as_record(segment_path, upto_tick, final_hash):
    """A --record made of the first segment (which starts at tick 0), cut at upto_tick,
    ending with the resumed state's hash: `fts-server --replay` then checks every
    journaled hash and the resumed one by a straight replay."""
    lines = open(segment_path).read().split("\n")
    head = json.loads(lines[0])
    cp = json.loads(lines[1])
    check(cp["tick"] == 0, f"the first segment starts at tick {cp['tick']}, not 0")
    out = [json.dumps({"fts_record": 1, "version": head["version"], "seed": head["seed"], "config": head["config"]})]
    for line in lines[2:-1]:  # the last element is "" or a torn line
        j = json.loads(line)
        if "session" in j or "released" in j:
            continue
        if "hash" in j:
            if j["tick"] <= upto_tick:
                out.append(json.dumps({"tick": j["tick"], "hash": j["hash"]}))
            continue
        if j["tick"] < upto_tick:
            out.append(line)
    out.append(json.dumps({"tick": upto_tick, "hash": final_hash}))
    fd, path = tempfile.mkstemp(prefix="fts-journal-record-", suffix=".jsonl")
    with os.fdopen(fd, "w") as f:
        f.write("\n".join(out) + "\n")
    return path


def server_args(journal, checkpoint_s):
    return ["--config", MANY_LIVES, "--log-level", "debug", "--timeout-ms", "2000", "--journal-dir", journal,
            "--journal-sync-ms", str(SYNC_MS), "--journal-checkpoint-s", str(checkpoint_s)]


def resumed_line(srv):
    return wait_for(lambda: re.search(r"resumed room=main tick=(\d+) level=(\d+) .*sessions=(\d+) event_seq=\d+ "
                                      r"hash=([0-9a-f]{16}) ms=([0-9.]+)", srv.text()), 30, "the resumed line")


def play_and_crash(kills, seed, checkpoint_s, replay_check):
    rng = random.Random(seed)
    journal = tempfile.mkdtemp(prefix="fts-journal-")
    runs = []  # (server log text, resumed tick of the next run)
    try:
        srv = Server(*server_args(journal, checkpoint_s))
        port = srv.port
        duration = 12 + kills * 14
        bots = start_bots("--connect", srv.address, "--name", "jr", "--count", str(BOTS), "--behavior", "shopper",
                          "--duration", str(duration), "--seed", str(seed))
        wait_for(lambda: len(re.findall(r"\bconnect player=\d+ name=jr", srv.text())) >= BOTS, 20, "the bots")
        wait_for(lambda: "level_start level=1" in srv.text(), 30, "level 1 to start")
        first_ids = dict(re.findall(r"\bconnect player=(\d+) name=(jr\d+)", srv.text()))
        resumes = []
        for k in range(kills):
            # Something to lose: a bot has earned coins on this server, then a random moment.
            wait_for(lambda: re.search(r"enemy_defeated enemy=\d+ player=[1-9]", srv.text()), 60,
                     "a bot to defeat an enemy")
            time.sleep(rng.uniform(0.5, 4.0))  # the random kill moment (the event under test)
            srv.proc.send_signal(signal.SIGKILL)
            srv.proc.wait()
            before = srv.text()
            first_segment = os.path.join(journal, "main", "journal-000001.jsonl")
            saved = None
            if replay_check and k == 0:
                saved = tempfile.mktemp(prefix="fts-journal-seg1-")
                shutil.copy(first_segment, saved)
            srv.log.close()
            srv = Server(*server_args(journal, checkpoint_s), "--port", str(port), "--resume")
            m = resumed_line(srv)
            tick, sessions, state_hash, ms = int(m.group(1)), int(m.group(3)), m.group(4), float(m.group(5))
            check(sessions == BOTS, f"resumed {sessions} sessions, not {BOTS}")
            check("resume_damage" not in srv.text() or "torn" in srv.text(),
                  f"resume found damage other than a torn tail: {srv.text()}")
            lost_ticks = max_event_tick(before) - tick
            resumes.append({"tick": tick, "ms": ms, "lost_ticks_at_least": lost_ticks})
            check(lost_ticks * 1000 / TICK_HZ <= 5 * SYNC_MS,
                  f"the crashed server logged events {lost_ticks} ticks after the resumed tick {tick}")
            runs.append((before, tick))
            if saved:
                record = journal_as_record(saved, tick, state_hash)
                p = subprocess.run([SERVER, "--replay", record], capture_output=True, text=True, timeout=120)
                check(p.returncode == 0, f"straight replay of the journal differs from the resumed state: "
                                         f"{p.stderr.strip()}")
                out = json.loads(p.stdout)
                check(out["ticks"] == tick, f"replayed to tick {out['ticks']}, resumed at {tick}")
                os.unlink(record)
                os.unlink(saved)
            wait_for(lambda: len(re.findall(r"\breconnect player=\d+ name=jr", srv.text())) >= BOTS, 40,
                     "every bot to reconnect with its token")
            check(not re.search(r"\bconnect player=\d+ name=jr", srv.text().replace("reconnect", "")),
                  "a bot came back as a new player")
        rc, report, err = finish_bots(bots, duration + 90)
        check(srv.stop() == 0, "the resumed server did not exit 0 on SIGINT")
        runs.append((srv.text(), None))
        check(rc == 0, f"bots failed (exit {rc}): {err.strip()}")
        earned, spent = {}, {}
        for text, upto in runs:
            e, s = ledger(text, upto)
            add(earned, e)
            add(spent, s)
        check(len(report) == BOTS, f"{len(report)} bot reports")
        for b in report:
            pid = str(b["player_id"])
            check(first_ids.get(pid) == b["name"], f"{b['name']} ended as player {pid}, started as another")
            expected = earned.get(pid, 0) - spent.get(pid, 0)
            check(b["coins"] == expected, f"{b['name']} (player {pid}): {b['coins']} coins, the ledger says "
                                          f"{expected} (earned {earned.get(pid, 0)}, spent {spent.get(pid, 0)})")
        check(sum(earned.values()) > 0, "nobody earned anything: the test proved nothing")
        print(f"journal: {kills} kills, resumes {resumes}, earned {earned}, spent {spent}")
    finally:
        try:
            if srv.proc.poll() is None:
                srv.proc.kill()
                srv.proc.wait()
        except NameError:
            pass
        shutil.rmtree(journal, ignore_errors=True)


def test_kill_resume():
    """One kill at a random moment; the resumed state checked against a straight replay."""
    play_and_crash(kills=1, seed=int(os.environ.get("FTS_JOURNAL_SEED", "1")), checkpoint_s=3600, replay_check=True)


def test_soak_kill_resume():
    """The test 5 times with random kill moments; every other round kills twice, with
    checkpoints every 3 s (segments written, compacted and resumed from)."""
    base = int(os.environ.get("FTS_JOURNAL_SEED", str(int(time.time()))))
    for rep in range(5):
        print(f"round {rep + 1}: seed {base + rep}", flush=True)
        even = rep % 2 == 0
        play_and_crash(kills=1 if even else 2, seed=base + rep, checkpoint_s=3600 if even else 3, replay_check=even)


if __name__ == "__main__":
    sys.exit(main({"kill_resume": test_kill_resume, "soak_kill_resume": test_soak_kill_resume}))
