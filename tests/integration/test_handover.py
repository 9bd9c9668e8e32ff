#!/usr/bin/env python3
"""Rooms that move (issue 42), with real processes: two fts-servers of one fleet (journals,
one fleet secret; the second takes rooms on --handover-listen) and real bots.

moves: 2 rooms x 3 bots play on the first server, a room of 2 on the second (each server
of a fleet gives ids from its own range: no id meets); mid-level the first's console says
`handover all PEER`: it drains, each room goes to the second at the tick it stood at, the
bots are told (`moved`) and follow with their tokens as the same players; the first exits
0 once its rooms are gone. Every bot plays on at the second (its snapshots pass the tick
of the move), none came back as a new player, and each bot's coins balance against the
ledgers of both servers' logs (the first's events up to the tick its room moved at).

client: the terminal client in tmux (80x24) through a move: told, the same room, coins
and lives on its HUD from the new server, its ball answering the keys there, a clean quit.

faults: a peer whose answer is lost on the way (it took the room, held it unconfirmed
and forgets it after 10 s: no second copy), a peer that is not there, a peer with another secret, a room handed to the
server that runs it (the room twice at one server), a full peer and a peer that dies
mid-hand-over (it takes the room's files and is gone before it answers): each is refused,
the room stays and plays on where it was (its tick goes on), and says why (console, log,
the peer's log for the secret). A request from a server of another version is refused by
the peer, in an answer the sender can authenticate (PROTOCOL.md 14, spoken here by Python's
hashlib and hmac)."""
import hashlib, hmac, json, os, re, shutil, signal, socket, subprocess, sys, tempfile, threading, time

from harness import BIN, HERE, Failure, Server, check, finish_bots, free_port, main, start_bots, wait_for
from test_journal import ledger, add

MANY_LIVES = os.path.join(HERE, "many-lives.json")
CLIENT = os.path.join(BIN, "client", "fts-client")
TICK_HZ = 100
BOTS = 3


def console(sock, request, timeout_s=10):
    with socket.socket(socket.AF_UNIX, socket.SOCK_STREAM) as c:
        c.settimeout(timeout_s)
        c.connect(sock)
        line = request if isinstance(request, str) else json.dumps(request)  # a str: sent as it is
        c.sendall((line + "\n").encode())
        data = b""
        while not data.endswith(b"\n"):
            chunk = c.recv(65536)
            check(chunk, f"the console closed without an answer to {request}")
            data += chunk
    return json.loads(data)


def secret_file(work, name, byte):
    path = os.path.join(work, name)
    with open(path, "wb") as f:
        f.write(bytes([byte]) * 32 + os.urandom(0 if byte else 32))
    os.chmod(path, 0o600)
    return path


def fleet_server(work, name, secret, listen=True, extra=()):
    """A server of the fleet: its journal, console and (listen) its --handover-listen."""
    d = os.path.join(work, name)
    os.makedirs(d)
    sock = os.path.join(d, "console.sock")
    args = ["--config", MANY_LIVES, "--log-level", "debug", "--timeout-ms", "3000", "--journal-dir",
            os.path.join(d, "journal"), "--console-socket", sock, "--fleet-secret", secret, *extra]
    hand = None
    if listen:
        hand = f"127.0.0.1:{free_port()}"
        args += ["--handover-listen", hand]
    srv = Server(*args)
    srv.sock, srv.handover = sock, hand
    return srv


# The channel (PROTOCOL.md 14): the peer's magic and challenge, then frames of a 4-byte
# big-endian length, the JSON, and HMAC-SHA-256(BLAKE2b-256(secret), label | challenge | JSON).
MAGIC, CHALLENGE = b"FTSHOV01", 32
REQUEST, REPLY = b"fts-handover-1 request", b"fts-handover-1 reply"


def channel_key(secret_path):
    with open(secret_path, "rb") as f:
        return hashlib.blake2b(f.read(), digest_size=32).digest()


def channel_mac(key, label, challenge, body):
    return hmac.new(key, label + challenge + body, hashlib.sha256).digest()


def read_exactly(conn, n):
    data = b""
    while len(data) < n:
        chunk = conn.recv(n - len(data))
        check(chunk, f"the channel closed after {len(data)} of {n} bytes")
        data += chunk
    return data


def dying_peer():
    """A peer that sends its challenge, takes the first bytes of the room's request and is gone
    (the process died mid-hand-over): its address, and an event set once it has died."""
    listener = socket.create_server(("127.0.0.1", 0))
    died = threading.Event()

    def serve():
        conn, _ = listener.accept()
        with conn:
            conn.sendall(MAGIC + os.urandom(CHALLENGE))
            length = int.from_bytes(read_exactly(conn, 4), "big")
            read_exactly(conn, min(length, 1024))
        listener.close()
        died.set()

    threading.Thread(target=serve, daemon=True).start()
    return f"127.0.0.1:{listener.getsockname()[1]}", died


def answer_cutter(target):
    """A path to the peer `target` that loses the peer's answer: the request goes through,
    then the connection breaks before any of the answer comes back (the peer has taken the
    room; the sender never learns it). Its address."""
    listener = socket.create_server(("127.0.0.1", 0))
    host, port = target.rsplit(":", 1)

    def serve():
        conn, _ = listener.accept()
        listener.close()
        with conn, socket.create_connection((host, int(port))) as up:
            conn.sendall(read_exactly(up, len(MAGIC) + CHALLENGE))
            head = read_exactly(conn, 4)
            up.sendall(head + read_exactly(conn, int.from_bytes(head, "big") + 32))
            read_exactly(up, 4)  # the answer begins: the line breaks here
            for c in (conn, up):
                c.shutdown(socket.SHUT_RDWR)

    threading.Thread(target=serve, daemon=True).start()
    return f"127.0.0.1:{listener.getsockname()[1]}"


def flaky_service(target):
    """A stand-in for the fleet's hand-over Service whose first connection lands on a peer
    that is gone (closed at once); every later one is passed to `target`. Its address and a
    list of the connections it took ("closed" or "passed")."""
    listener = socket.create_server(("127.0.0.1", 0))
    taken = []
    host, port = target.rsplit(":", 1)

    def pipe(a, b):
        try:
            while chunk := a.recv(65536):
                b.sendall(chunk)
        except OSError:
            pass
        for c in (a, b):
            try:
                c.shutdown(socket.SHUT_RDWR)
            except OSError:
                pass

    def serve():
        while True:
            try:
                conn, _ = listener.accept()
            except OSError:
                return
            if not taken:
                taken.append("closed")
                conn.close()
                continue
            taken.append("passed")
            up = socket.create_connection((host, int(port)))
            threading.Thread(target=pipe, args=(conn, up), daemon=True).start()
            threading.Thread(target=pipe, args=(up, conn), daemon=True).start()

    threading.Thread(target=serve, daemon=True).start()
    return f"127.0.0.1:{listener.getsockname()[1]}", taken


def request_of_another_version(peer, key):
    """Asks `peer` to take a room as a server of another version would: its answer, checked
    authentic."""
    host, port = peer.rsplit(":", 1)
    with socket.create_connection((host, int(port)), timeout=10) as conn:
        hello = read_exactly(conn, len(MAGIC) + CHALLENGE)
        check(hello.startswith(MAGIC), f"the peer's hello: {hello[:8]!r}")
        challenge = hello[len(MAGIC):]
        body = json.dumps({"fts_handover": 1, "version": "0.0.1-older",
                           "rooms": [{"room": "OLDER", "tick": 10, "files": []}]}).encode()
        conn.sendall(len(body).to_bytes(4, "big") + body + channel_mac(key, REQUEST, challenge, body))
        length = int.from_bytes(read_exactly(conn, 4), "big")
        answer, mac = read_exactly(conn, length), read_exactly(conn, 32)
        check(hmac.compare_digest(mac, channel_mac(key, REPLY, challenge, answer)), "the peer's answer is not authentic")
        return json.loads(answer)


def rooms_of(srv):
    reply = console(srv.sock, {"cmd": "rooms"})
    check(reply.get("ok"), f"console rooms: {reply}")
    return {r["code"]: r for r in reply["rooms"]}


def test_moves():
    work = tempfile.mkdtemp(prefix="fts-handover-")
    secret = secret_file(work, "fleet.secret", 7)
    groups, home = [], None
    with fleet_server(work, "a", secret, listen=False) as a, fleet_server(work, "b", secret) as b:
        # The peer plays a room of its own: the rooms that come keep their players' ids, which
        # its own players do not have (each server of a fleet gives ids from its own range).
        home = start_bots("--connect", b.address, "--name", "cat", "--count", "2", "--room", "create",
                          "--duration", "600")
        groups = [start_bots("--connect", a.address, "--name", g, "--count", str(BOTS), "--behavior", "shopper",
                             "--room", "create", "--duration", "600", "--seed", str(i + 1))
                  for i, g in enumerate(["ann", "bob"])]
        wait_for(lambda: len(re.findall(r"\bconnect player=\d+ name=[a-z]+\d", a.text())) >= 2 * BOTS, 20, "the bots")
        wait_for(lambda: len(re.findall(r"level_start level=1 room=", a.text())) >= 2, 30, "level 1 in both rooms")
        wait_for(lambda: re.search(r"enemy_defeated enemy=\d+ player=[1-9]", a.text()), 60, "a bot to earn coins")
        first_ids = dict(re.findall(r"\bconnect player=(\d+) name=([a-z]+\d)", a.text()))
        codes = dict(re.findall(r"room_open room=(\d+) code=([A-Z]{5})", a.text()))
        check(len(codes) == 2, f"rooms opened: {codes}")
        watched = codes[min(codes, key=int)]
        watcher = start_bots("--connect", a.address, "--name", "eve", "--spectate", watched, "--duration", "600")
        groups.append(watcher)
        wait_for(lambda: re.search(r"\bconnect spectator=\d+ name=eve ", a.text()), 20, "the spectator")
        wait_for(lambda: len(re.findall(r"\bconnect player=\d+ name=cat\d", b.text())) >= 2, 20, "the peer's own bots")
        home_ids = set(re.findall(r"\bconnect player=(\d+) name=cat\d", b.text()))
        check(not home_ids & set(first_ids), f"the two servers gave the same ids: {home_ids & set(first_ids)}")

        started = time.monotonic()
        reply = console(a.sock, {"cmd": "handover", "room": "all", "peer": b.handover})
        check(reply.get("ok") and reply.get("draining"), f"handover all: {reply}")
        check(sorted(r["room"] for r in reply["rooms"]) == sorted(codes.values()), f"rooms handed over: {reply}")
        told = {c: BOTS + (c == watched) for c in codes.values()}  # the spectator is told too
        check(all(r["ok"] and r["to"] == b.address and r["clients_told"] == told[r["room"]] for r in reply["rooms"]),
              f"a room did not go to {b.address} with its clients told ({told}): {reply}")
        moved = {m["code"]: int(m["tick"]) for m in re.finditer(r"room_moved room=\d+ code=(?P<code>[A-Z]{5}) "
                                                               r"to=\S+ tick=(?P<tick>\d+)", a.text())}
        adopted = {m["code"]: int(m["tick"]) for m in re.finditer(r"room_adopted code=(?P<code>[A-Z]{5}) "
                                                                 r"tick=(?P<tick>\d+)", b.text())}
        check(moved == adopted and len(moved) == 2, f"moved at {moved}, resumed at {adopted}: not the same ticks")
        # Each confirmed (PROTOCOL.md 14, step 4; by the first server, or by a bot that came
        # before the confirmation was read): none is held there. The sender answers its
        # console once the confirmation is written; the peer reads it in its own time.
        def confirmed():
            return set(re.findall(r"adopt_confirmed code=([A-Z]{5}) by=(?:sender|client)", b.text()))
        wait_for(lambda: confirmed() == set(moved), 10, f"both rooms confirmed at the peer (moved: {set(moved)})")
        check(a.proc.wait(timeout=10) == 0, "the first server did not exit 0 once its rooms had gone")
        wait_for(lambda: len(re.findall(r"\breconnect player=\d+ name=[a-z]+\d", b.text())) >= 2 * BOTS, 20,
                 "every bot on the second server")
        followed_s = time.monotonic() - started
        check(not re.search(r"\bconnect player=\d+ name=(ann|bob)", b.text().replace("reconnect", "")),
              "a bot came to the second server as a new player")
        # Play on there, then each bot says goodbye.
        wait_for(lambda: all(r["tick"] >= moved[c] + 3 * TICK_HZ for c, r in rooms_of(b).items() if c in moved),
                 30, "3 s of play on the second server")
        for proc, _ in groups + [home]:
            proc.send_signal(signal.SIGINT)
        reports = [finish_bots(g, 60) for g in groups]
        home_rc, home_report, home_err = finish_bots(home, 60)
        groups, home = [], None
        check(home_rc == 0 and len(home_report) == 2, f"the peer's own bots failed (exit {home_rc}): {home_err.strip()}")
        check(b.stop() == 0, "the second server did not exit 0 on SIGINT")
        rc, spectated, err = reports.pop()  # the spectator's
        check(rc == 0 and len(spectated) == 1, f"the spectator failed (exit {rc}): {err.strip()}")
        eve = spectated[0]
        check(eve.get("spectator") and eve["moves"] == 1 and eve["room"] == watched,
              f"the spectator did not follow room {watched} as a spectator: {eve}")
        check(max((int(t) for t in eve["snapshot_digests"]), default=-1) > moved[watched],
              "the spectator saw nothing of the room on the second server")
        upto = {rid: moved[code] for rid, code in codes.items()}
        seen = {str(x["player_id"]): max((int(t) for t in x["snapshot_digests"]), default=-1)
                for _, report, _ in reports for x in report}
        earned, spent = {}, {}
        for text, limit, sight in [(a.text(), upto, None), (b.text(), None, seen)]:
            e, s = ledger(text, limit, sight)
            add(earned, e)
            add(spent, s)
        for rc, report, err in reports:
            check(rc == 0, f"bots failed (exit {rc}): {err.strip()}")
            check(len(report) == BOTS, f"{len(report)} bot reports")
            for x in report:
                pid = str(x["player_id"])
                check(first_ids.get(pid) == x["name"], f"{x['name']} ended as player {pid}, started as another")
                check(x["moves"] == 1 and x["moved_to"] == b.address, f"{x['name']}: moves {x['moves']}")
                check(x["room"] in moved, f"{x['name']} ended in room {x['room']}")
                newest = max((int(t) for t in x["snapshot_digests"]), default=-1)
                check(newest > moved[x["room"]], f"{x['name']}'s newest snapshot is of tick {newest}, before the move")
                expected = earned.get(pid, 0) - spent.get(pid, 0)
                check(x["coins"] == expected, f"{x['name']} (player {pid}): {x['coins']} coins, the ledgers say "
                                              f"{expected} (earned {earned.get(pid, 0)}, spent {spent.get(pid, 0)})")
        check(sum(earned.values()) > 0, "nobody earned anything: the test proved nothing")
        ms = [r["ms"] for r in reply["rooms"]]
        print(f"handover: 2 rooms x {BOTS} bots, hand-over {max(ms):.1f} ms (console), every bot on the new server "
              f"{followed_s * 1000:.0f} ms after the command; earned {sum(earned.values())}")
    for proc, _ in groups + ([home] if home else []):
        proc.kill()


def test_faults():
    work = tempfile.mkdtemp(prefix="fts-handover-")
    secret = secret_file(work, "fleet.secret", 7)
    other = secret_file(work, "other.secret", 9)
    bots = None
    with fleet_server(work, "a", secret) as a, fleet_server(work, "stranger", other) as stranger, \
            fleet_server(work, "full", secret, extra=("--max-rooms", "1")) as full, \
            fleet_server(work, "taker", secret) as taker:
        bots = start_bots("--connect", a.address, "--name", "ann", "--count", "2", "--behavior", "shopper",
                          "--room", "create", "--duration", "600")
        wait_for(lambda: re.search(r"level_start level=1 room=", a.text()), 30, "level 1")
        code = re.search(r"room_open room=\d+ code=([A-Z]{5})", a.text()).group(1)
        # The full peer holds a room of its own.
        filler = start_bots("--connect", full.address, "--name", "cat", "--room", "create", "--duration", "600")
        wait_for(lambda: re.search(r"room_open room=\d+ code=", full.text()), 20, "the full peer's room")
        cases = [
            # First: the peer takes the room and holds it for 10 s while the others run.
            ("a peer whose answer is lost", answer_cutter(taker.handover), "closed the connection before answering"),
            ("an absent peer", f"127.0.0.1:{free_port()}", "cannot reach the peer"),
            ("another secret", stranger.handover, "another fleet secret"),
            ("the room's own server", a.handover, f"room {code} is open here already"),
            ("a full peer", full.handover, "full: this server has --max-rooms rooms"),
            ("a peer that dies mid-hand-over", None, "closed the connection before answering"),
        ]
        died = None
        for what, peer, says in cases:
            if peer is None:
                peer, died = dying_peer()
            before = rooms_of(a)[code]["tick"]
            reply = console(a.sock, {"cmd": "handover", "room": code, "peer": peer})
            check(not reply.get("ok") and says in reply.get("error", "") and "plays on here" in reply["error"],
                  f"{what}: {reply}")
            wait_for(lambda: rooms_of(a)[code]["tick"] >= before + TICK_HZ, 10, f"room {code} to play on ({what})")
            check(re.search(rf"handover_refused room=\d+ code={code} reason=.*{re.escape(says)}", a.text()),
                  f"{what}: no handover_refused line")
        check(re.search(r"handover_denied from=127\.0\.0\.1:\d+ reason=not authenticated", stranger.text()),
              "the stranger did not log the unauthenticated request")
        check(died.is_set(), "the dying peer never took the request")
        # The peer whose answer was lost took the room, held it unconfirmed and forgets it: no
        # second copy lives on there, and its journal goes (no restart brings it back).
        check(re.search(rf"room_adopted code={code}", taker.text()), "the taker never took the room")
        check(re.search(r"handover_unconfirmed from=127\.0\.0\.1:\d+ rooms=1 reason=the sender closed", taker.text()),
              "the taker did not log the room it holds unconfirmed")
        wait_for(lambda: re.search(rf"adopt_forgotten room=\d+ code={code}", taker.text()), 30,
                 f"the taker to forget room {code}")
        check(code not in rooms_of(taker), f"the taker still runs room {code}")
        wait_for(lambda: not os.path.exists(os.path.join(work, "taker", "journal", code)), 10,
                 f"the taker's journal of room {code} to go")
        check(rooms_of(stranger) == {} and list(rooms_of(full)) != [code], "a refusing peer took the room")
        # Another version: the peer says so, authentically, and takes nothing.
        other_version = request_of_another_version(full.handover, channel_key(secret))
        check(other_version.get("ok") is False and "another version" in other_version.get("error", "")
              and "0.0.1-older" in other_version["error"], f"another version: {other_version}")
        check(re.search(r"handover_denied from=127\.0\.0\.1:\d+ reason=another version", full.text()),
              "the peer did not log the other version's request")
        check("OLDER" not in rooms_of(full), "the peer took a room of another version")
        check(not re.search(r"room_moved|disconnect player=\d+ reason=moved", a.text()), "a refused room moved")
        check(not re.search(r"\breconnect player=", a.text()), "a bot had to reconnect")
        bad = console(a.sock, {"cmd": "handover", "room": "NOPE1", "peer": full.handover})
        check(not bad.get("ok") and "no room NOPE1" in bad.get("error", ""), f"an unknown room: {bad}")
        bad = console(a.sock, {"cmd": "handover", "room": code, "peer": "nowhere"})
        check(not bad.get("ok") and "HOST:PORT" in bad.get("error", ""), f"a peer that is no address: {bad}")
        # A key given twice is refused by the console's strict reading, deferred or not.
        bad = console(a.sock, f'{{"cmd":"handover","room":"{code}","peer":"{full.handover}","room":"{code}"}}')
        check(not bad.get("ok") and "appears twice" in bad.get("error", ""), f"a key given twice: {bad}")
        for p in (bots, filler):
            p[0].send_signal(signal.SIGINT)
            finish_bots(p, 30)
        bots = None
        print(f"handover faults: {len(cases)} refusals, room {code} played on at its server after each; "
              "another version refused by the peer")
    if bots:
        bots[0].kill()


def hud(text):
    """The HUD's first line, wide ("Level: 1   Coins: 0   Lives: 50 ... Room ABCDE") or
    compact ("L1 0c 50L ... Room ABCDE"): (level, coins, lives, room), or None."""
    first = text.splitlines()[0] if text else ""
    level = re.search(r"^(?:Level:? |L)(\d+)\b", first)
    coins = re.search(r"Coins:? ([0-9,]+)|\b([0-9,]+)c\b", first)
    lives = re.search(r"Lives:? (\d+)|\b(\d+)L\b", first)
    room = re.search(r"Room ([A-Z]{5})", first)
    if not (level and coins and lives and room):
        return None
    return (int(level[1]), int((coins[1] or coins[2]).replace(",", "")), int(lives[1] or lives[2]), room[1])


def ball_col(text):
    """The column of the player's own ball ("@1@" in ASCII) on the screen, or None."""
    for line in text.splitlines()[2:]:
        m = re.search(r"@+[0-9]+@*", line)
        if m:
            return (m.start() + m.end()) // 2
    return None


def test_client():
    """The real terminal client in tmux (80x24) plays through a hand-over: its log says the
    room moved, its HUD shows the same room, coins and lives from the new server, the
    player's ball still answers the arrow keys there, and q, y quits cleanly."""
    if shutil.which("tmux") is None:
        print("tmux is not installed here: skipped")
        sys.exit(77)
    work = tempfile.mkdtemp(prefix="fts-handover-")
    secret = secret_file(work, "fleet.secret", 7)
    tmux = ["tmux", "-L", f"fts-handover-{os.getpid()}"]
    pane = lambda: subprocess.run([*tmux, "capture-pane", "-p", "-t", "c"], capture_output=True,  # noqa: E731
                                  text=True).stdout
    keys = lambda *k: subprocess.run([*tmux, "send-keys", "-t", "c", *k])  # noqa: E731
    try:
        with fleet_server(work, "a", secret, listen=False) as a, fleet_server(work, "b", secret) as b:
            env = f"env LANG=C XDG_STATE_HOME={os.path.join(work, 'client-state')} TERM=xterm"
            subprocess.run([*tmux, "new-session", "-d", "-s", "c", "-x", "80", "-y", "24",
                            f"{env} {CLIENT} --connect {a.address} --guest --name zoe --quick --glyphs ascii; "
                            "echo CLIENT_EXIT=$?; sleep 30"], check=True)
            wait_for(lambda: "Room " in pane(), 30, "the client's welcome")
            keys("Enter")
            before = wait_for(lambda: (lambda h: h if h and h[0] >= 1 else None)(hud(pane())), 30, "level 1 on the HUD")
            player = re.search(r"\bconnect player=(\d+) name=zoe ", a.text())[1]
            reply = console(a.sock, {"cmd": "handover", "room": "all", "peer": b.handover})
            check(reply.get("ok") and reply["rooms"][0]["clients_told"] == 1, f"handover all: {reply}")
            wait_for(lambda: "Room moved to another server" in pane(), 10, "the client to say the room moved")
            wait_for(lambda: re.search(rf"\breconnect player={player} name=zoe ", b.text()), 10,
                     "the client on the second server as the same player")
            after = wait_for(lambda: (lambda h: h if h and h[3] == before[3] and h[0] >= before[0] else None)(
                hud(pane())), 10, f"the HUD of room {before[3]} at level {before[0]} or later")
            check(after[2] == before[2] and after[1] >= before[1],
                  f"lives or coins changed with the move: before {before}, after {after}")
            # The ball answers the keys on the new server: its inputs arrive there.
            start = wait_for(lambda: ball_col(pane()), 10, "zoe's ball on the screen")

            def moved_right():
                keys("Right")
                col = ball_col(pane())
                return col if col and col >= start + 3 else None
            wait_for(moved_right, 10, f"zoe's ball to go right of column {start} on the new server")
            check(a.proc.wait(timeout=10) == 0, "the first server did not exit 0 once its room had gone")
            keys("q")
            wait_for(lambda: "Quit?" in pane(), 10, "the quit question")
            keys("y")
            wait_for(lambda: "CLIENT_EXIT=0" in pane(), 20, "the client to exit")
            wait_for(lambda: re.search(rf"disconnect player={player} reason=quit", b.text()), 10,
                     "the quit at the second server")
            print(f"handover client: room {before[3]} moved with zoe (level {before[0]}, {before[1]} coins, "
                  f"{before[2]} lives); on the new server {after}")
    finally:
        subprocess.run([*tmux, "kill-server"], capture_output=True)


def test_drain_agones():
    """Under Agones (stand-in sidecars, tests/integration/agones_sidecar.py), SIGTERM drains a
    server started with --handover-to SERVICE: its room goes to the peer, the room's code
    leaves this GameServer's rooms List for the peer's (allocation by code finds the new
    home), the bots follow, and the drained server tells Agones Shutdown and exits 0. The
    Service's first connection lands on a peer that is gone: the room is tried again a
    second later and goes."""
    from agones_sidecar import Sidecar
    from test_agones import codes
    work = tempfile.mkdtemp(prefix="fts-handover-")
    secret = secret_file(work, "fleet.secret", 7)
    sidecars = {name: Sidecar(free_port()) for name in ("a", "b")}
    for sc in sidecars.values():
        sc.start()
    bots = None
    try:
        agones = {name: ("--agones", str(sc.port), "--agones-health-ms", "200") for name, sc in sidecars.items()}
        with fleet_server(work, "b", secret, extra=agones["b"]) as b:
            service, taken = flaky_service(b.handover)
            with fleet_server(work, "a", secret, listen=False, extra=(*agones["a"], "--handover-to", service)) as a:
                wait_for(lambda: all(sc.paths("/ready") for sc in sidecars.values()), 10, "both GameServers Ready")
                bots = start_bots("--connect", a.address, "--name", "ann", "--count", "2", "--behavior", "shopper",
                                  "--room", "create", "--duration", "600")
                wait_for(lambda: re.search(r"level_start level=1 room=", a.text()), 30, "level 1")
                code = re.search(r"room_open room=\d+ code=([A-Z]{5})", a.text()).group(1)
                wait_for(lambda: codes(sidecars["a"]) == [code], 10, "the room's code in the first's rooms List")
                a.proc.send_signal(signal.SIGTERM)
                wait_for(lambda: re.search(rf"room_adopted code={code} ", b.text()), 20, "the room on the peer")
                wait_for(lambda: codes(sidecars["b"]) == [code] and codes(sidecars["a"]) == [], 10,
                         "the code moved from the first's rooms List to the peer's")
                wait_for(lambda: len(re.findall(r"\breconnect player=\d+ name=ann\d", b.text())) >= 2, 20,
                         "the bots on the peer")
                check(a.proc.wait(timeout=20) == 0, "the drained server did not exit 0")
                check(sidecars["a"].paths("/shutdown"), "the drained server did not tell Agones Shutdown")
                check(not sidecars["b"].paths("/shutdown"), "the peer was shut down")
                check(re.search(r"drain_handover rooms=1 moved=0 ok=false", a.text()) and
                      re.search(rf"drain_handover_retry room={code} attempt=2 ok=true", a.text()),
                      "the room was not tried again after the gone peer")
                check(taken[:2] == ["closed", "passed"], f"the Service's connections: {taken}")
                bots[0].send_signal(signal.SIGINT)
                rc, report, err = finish_bots(bots, 60)
                bots = None
                check(rc == 0 and len(report) == 2, f"bots failed (exit {rc}): {err.strip()}")
                check(all(x["moves"] == 1 and x["moved_to"] == b.address for x in report), f"bots: {report}")
                print(f"handover drain under Agones: room {code} and its code moved to the peer on SIGTERM")
    finally:
        if bots:
            bots[0].kill()
        for sc in sidecars.values():
            sc.stop()


if __name__ == "__main__":
    sys.exit(main({"moves": test_moves, "faults": test_faults, "client": test_client,
                   "drain_agones": test_drain_agones}))
