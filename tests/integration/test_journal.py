#!/usr/bin/env python3
"""Crash-safe rooms (issue 15), with real processes: 4 rooms x 4 bots play, the server
is killed with SIGKILL at a random moment and restarted with --resume on the same port;
every room comes back under its code (each journal in DIR/<code>/), every bot reconnects
with its token into its room and finds its player; each bot's coins equal its ledger
(what its enemies and interest earned minus what it spent, counting the crashed server's
events only up to its room's resumed tick); each resumed room's hash equals a straight
replay of its journal (as a --record) up to that tick; the play lost is about the sync
interval (measured from the console's tick just before the kill)."""
import json, os, random, re, shutil, signal, socket, subprocess, sys, tempfile, time

from harness import SERVER, HERE, Failure, Server, check, finish_bots, main, start_bots, wait_for

MANY_LIVES = os.path.join(HERE, "many-lives.json")
SYNC_MS = 100
TICK_HZ = 100
ROOMS = 4
BOTS = 4  # per room
GROUPS = ["ann", "bob", "cat", "dan"][:ROOMS]
BOT_LIMIT_S = 600  # the bots' own limit, a safety net: the test stops them (SIGINT)


def ledger(text, upto=None, seen=None):
    """Per player: coins earned (defeats, interest) and spent, from a server log; only
    events of ticks <= upto[room] when given (the crashed server's events past a room's
    resumed tick never happened for the resumed match), and only until the player's bot
    said goodbye (its report is written then; its last push may still earn later) and,
    with `seen`, of ticks <= seen[player]: the newest snapshot its bot had when it
    stopped (a defeat or purchase the server made after it is not in the bot's coins; an
    event is logged with the tick of the state it is in, the tick of that snapshot)."""
    earned, spent = {}, {}
    gone = set()
    room_tick = r" room=(?P<room>\d+) tick=(?P<tick>\d+)"
    patterns = [(earned, re.compile(r"enemy_defeated enemy=\d+ player=(?P<p>\d+) coins=(?P<c>\d+)" + room_tick)),
                (earned, re.compile(r"interest player=(?P<p>\d+) coins=(?P<c>\d+)" + room_tick)),
                (spent, re.compile(r"purchase player=(?P<p>\d+) item=\w+ ok=true reason=\w* price=(?P<c>\d+) "
                                   r"coins=\d+" + room_tick))]
    for line in text.splitlines():
        bye = re.search(r"disconnect player=(\d+) reason=done", line)
        if bye:
            gone.add(bye.group(1))
        for book, pattern in patterns:
            m = pattern.search(line)
            if m and m["p"] not in gone and (upto is None or int(m["tick"]) <= upto.get(m["room"], -1)) and \
                    (seen is None or int(m["tick"]) <= seen.get(m["p"], -1)):
                book[m["p"]] = book.get(m["p"], 0) + int(m["c"])
    return earned, spent


def add(total, part):
    for k, v in part.items():
        total[k] = total.get(k, 0) + v


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


def rooms_now(sock):
    """The console's rooms (JSON lines on its UNIX socket, spoken here directly: the kill
    follows the answer within a millisecond, so its ticks bound the ticks at the kill)."""
    with socket.socket(socket.AF_UNIX, socket.SOCK_STREAM) as c:
        c.settimeout(10)
        c.connect(sock)
        c.sendall(b'{"cmd":"rooms"}\n')
        data = b""
        while not data.endswith(b"\n"):
            chunk = c.recv(65536)
            check(chunk, "the console closed without an answer")
            data += chunk
    reply = json.loads(data)
    check(reply.get("ok"), f"console rooms: {reply}")
    return reply["rooms"]


def server_args(journal, checkpoint_s, sock):
    return ["--config", MANY_LIVES, "--log-level", "debug", "--timeout-ms", "2000", "--journal-dir", journal,
            "--journal-sync-ms", str(SYNC_MS), "--journal-checkpoint-s", str(checkpoint_s), "--console-socket", sock]


RESUMED = (r"resumed room=(?P<id>\d+) code=(?P<code>[A-Z]{5}) tick=(?P<tick>\d+) level=\d+ .*sessions=(?P<sessions>\d+) "
           r"event_seq=\d+ hash=(?P<hash>[0-9a-f]{16}) ms=[0-9.]+")


def resume_done(srv):
    return wait_for(lambda: re.search(r"resume_done rooms=(\d+) resumed=(\d+) skipped=(\d+) sessions=(\d+) "
                                      r"threads=\d+ ms=([0-9.]+) cpu_ms", srv.text()), 30, "the resume_done line")


def damage_journals(journal, code):
    """Tears the last line of room `code`'s newest segment and adds a room directory with
    nothing usable in it: the resume must go on with both reported."""
    room = os.path.join(journal, code)
    newest = os.path.join(room, sorted(f for f in os.listdir(room) if f.startswith("journal-"))[-1])
    os.truncate(newest, os.path.getsize(newest) - 3)
    os.makedirs(os.path.join(journal, "ZZZZZ"))
    with open(os.path.join(journal, "ZZZZZ", "journal-000001.jsonl"), "w") as f:
        f.write('{"fts_journal":1\n')


def play_and_crash(kills, seed, checkpoint_s, replay_check, play_after_s=5, damage=False):
    """The bots play until told to stop (SIGINT: each says goodbye and writes its report),
    play_after_s seconds of game time after the last resume: a bot that stopped by a
    clock of its own could stop while the server was down, or before the resumed match's
    first snapshot, and report what the killed server last said (a purchase the resumed
    match never had)."""
    rng = random.Random(seed)
    journal = tempfile.mkdtemp(prefix="fts-journal-")
    sock = os.path.join(journal, "console.sock")
    runs = []  # (server log text, {room id: resumed tick} of the next run)
    srv = None
    try:
        srv = Server(*server_args(journal, checkpoint_s, sock))
        port = srv.port
        groups = [start_bots("--connect", srv.address, "--name", g, "--count", str(BOTS), "--behavior", "shopper",
                             "--room", "create", "--duration", str(BOT_LIMIT_S), "--seed", str(seed * 10 + i))
                  for i, g in enumerate(GROUPS)]
        wait_for(lambda: len(re.findall(r"\bconnect player=\d+ name=[a-z]+\d", srv.text())) >= ROOMS * BOTS, 20,
                 "the bots")
        wait_for(lambda: len(re.findall(r"level_start level=1 room=", srv.text())) >= ROOMS, 30, "level 1 in every room")
        first_ids = dict(re.findall(r"\bconnect player=(\d+) name=([a-z]+\d)", srv.text()))
        codes = dict(re.findall(r"room_open room=(\d+) code=([A-Z]{5})", srv.text()))
        check(len(codes) == ROOMS, f"rooms opened: {codes}")
        check(sorted(os.listdir(journal)) == sorted([*codes.values(), "console.sock", "lock"]),
              f"journal directory: {os.listdir(journal)}")
        resumes = []
        for k in range(kills):
            # Something to lose: a bot has earned coins on this server, then a random moment.
            wait_for(lambda: re.search(r"enemy_defeated enemy=\d+ player=[1-9]", srv.text()), 60,
                     "a bot to defeat an enemy")
            time.sleep(rng.uniform(0.5, 4.0))  # the random kill moment (the event under test)
            live = {str(r["id"]): r["tick"] for r in rooms_now(sock)}
            srv.proc.send_signal(signal.SIGKILL)
            srv.proc.wait()
            before = srv.text()
            saved = {}
            if replay_check and k == 0:
                for rid, code in codes.items():
                    saved[rid] = tempfile.mktemp(prefix="fts-journal-seg1-")
                    shutil.copy(os.path.join(journal, code, "journal-000001.jsonl"), saved[rid])
            torn = codes[min(codes, key=int)] if damage and k == 0 else None
            if torn:
                damage_journals(journal, torn)
            srv.log.close()
            srv = Server(*server_args(journal, checkpoint_s, sock), "--port", str(port), "--resume")
            done = resume_done(srv)
            extra = 1 if damage else 0  # the directory with nothing usable stays (reported each time)
            check(done.groups()[:4] == (str(ROOMS + extra), str(ROOMS), str(extra), str(ROOMS * BOTS)),
                  f"resume_done: {done.group(0)}")
            if torn:
                check(re.search(r"resume_skipped code=ZZZZZ reason=no usable journal segment", srv.text()),
                      "the room with nothing usable was not reported")
                check(re.search(rf"resume_damage code={torn} damage=journal-\d+\.jsonl: line \d+: torn", srv.text()),
                      f"the torn tail of room {torn} was not reported")
            resumed = {m["id"]: m for m in re.finditer(RESUMED, srv.text())}
            check({rid: m["code"] for rid, m in resumed.items()} == codes,
                  f"resumed rooms {[(k, m['code']) for k, m in resumed.items()]}, had {codes}")
            check(all(int(m["sessions"]) == BOTS for m in resumed.values()), "a room resumed without its 4 sessions")
            check("resume_damage" not in srv.text() or "torn" in srv.text(),
                  f"resume found damage other than a torn tail: {srv.text()}")
            upto = {rid: int(m["tick"]) for rid, m in resumed.items()}
            lost_ms = {rid: (live[rid] - upto[rid]) * 1000 / TICK_HZ for rid in upto}
            resumes.append({"ms": float(done.group(5)), "lost_ms_at_least": lost_ms})
            check(all(ms <= 2 * SYNC_MS for ms in lost_ms.values()),
                  f"lost more than the sync interval ({SYNC_MS} ms) plus a write: {lost_ms}")
            runs.append((before, upto))
            for rid, path in saved.items():
                record = journal_as_record(path, upto[rid], resumed[rid]["hash"])
                p = subprocess.run([SERVER, "--replay", record], capture_output=True, text=True, timeout=120)
                check(p.returncode == 0, f"room {rid}: straight replay of the journal differs from the resumed "
                                         f"state: {p.stderr.strip()}")
                check(json.loads(p.stdout)["ticks"] == upto[rid], f"room {rid}: replayed to another tick")
                os.unlink(record)
                os.unlink(path)
            wait_for(lambda: len(re.findall(r"\breconnect player=\d+ name=[a-z]+\d", srv.text())) >= ROOMS * BOTS, 40,
                     "every bot to reconnect with its token")
            check(not re.search(r"\bconnect player=\d+ name=", srv.text().replace("reconnect", "")),
                  "a bot came back as a new player")
        # Some play on the resumed server, then each bot says goodbye.
        resumed_at = upto  # the last resume's tick per room
        wait_for(lambda: all(r["tick"] >= resumed_at[str(r["id"])] + play_after_s * TICK_HZ for r in rooms_now(sock)),
                 60, f"{play_after_s} s of play in every resumed room")
        for proc, _ in groups:
            proc.send_signal(signal.SIGINT)
        reports = [finish_bots(g, 60) for g in groups]
        check(srv.stop() == 0, "the resumed server did not exit 0 on SIGINT")
        runs.append((srv.text(), None))
        earned, spent = {}, {}
        # The newest tick each bot saw: what its coins say.
        seen = {str(b["player_id"]): max((int(t) for t in b["snapshot_digests"]), default=-1)
                for _, report, _ in reports for b in report}
        for text, upto in runs:
            e, s = ledger(text, upto, seen if upto is None else None)
            add(earned, e)
            add(spent, s)
        for rc, report, err in reports:
            check(rc == 0, f"bots failed (exit {rc}): {err.strip()}")
            check(len(report) == BOTS, f"{len(report)} bot reports")
            check(len({b["room"] for b in report}) == 1, f"a group split over rooms: {[b['room'] for b in report]}")
            for b in report:
                pid = str(b["player_id"])
                check(first_ids.get(pid) == b["name"], f"{b['name']} ended as player {pid}, started as another")
                rid = next(r for r, c in codes.items() if c == b["room"])
                seen = max((int(t) for t in b["snapshot_digests"]), default=-1)
                check(seen > resumed_at[rid], f"{b['name']}'s newest snapshot is of tick {seen}: nothing from the "
                                              f"resumed match (from tick {resumed_at[rid]}; state {b['state']}, "
                                              f"{b['snapshots_received']} snapshots)")
                expected = earned.get(pid, 0) - spent.get(pid, 0)
                check(b["coins"] == expected, f"{b['name']} (player {pid}): {b['coins']} coins, the ledger says "
                                              f"{expected} (earned {earned.get(pid, 0)}, spent {spent.get(pid, 0)})")
        check(sum(earned.values()) > 0, "nobody earned anything: the test proved nothing")
        print(f"journal: {kills} kills, resumes {resumes}, earned {sum(earned.values())}, "
              f"spent {sum(spent.values())}")
    finally:
        if srv and srv.proc.poll() is None:
            srv.proc.kill()
            srv.proc.wait()
        shutil.rmtree(journal, ignore_errors=True)


def test_kill_resume():
    """4 rooms x 4 bots, one kill at a random moment; each room checked against a straight
    replay; one room's journal torn at its tail and a fifth room with nothing usable."""
    play_and_crash(kills=1, seed=int(os.environ.get("FTS_JOURNAL_SEED", "1")), checkpoint_s=3600, replay_check=True,
                   damage=True)


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
