#!/usr/bin/env python3
"""Rooms and the host's console (issue 13), with real fts-server and fts-bot processes:
4 rooms x 4 bots play at once and each room's record replays to its live hash; a forged
room code is refused; a spectator sees what a player of the room sees; the console lists,
kicks (the bot is told why) and drains (the server exits 0 when the last room ends)."""
import json, os, re, stat, subprocess, sys, tempfile

from harness import (SERVER, Server, check, finish_bots, main, run_bots, start_bots, wait_for,
                     write_script)


def console(path, *words):
    p = subprocess.run([SERVER, "--console", path, *words], capture_output=True, text=True, timeout=10)
    return p.returncode, (json.loads(p.stdout) if p.stdout.strip() else None), p.stderr


def room_codes(srv):
    return re.findall(r"room_open room=(\d+) code=([A-Z]{5})", srv.text())


def test_four_rooms():
    """4 rooms x 4 bots at once; each room's record replays alone to the hash it closed on."""
    rec = tempfile.mkdtemp(prefix="fts-rooms-")
    sock = os.path.join(rec, "console.sock")
    with Server("--time-scale", "4", "--record-dir", rec, "--console-socket", sock) as srv:
        # The console's close ends every bot (they are told room_closed): their --duration
        # only bounds a run that fails, and must outlast the waits on a loaded machine.
        groups = [start_bots("--connect", srv.address, "--name", g, "--count", "4", "--behavior", "shopper",
                             "--room", "create", "--duration", "90", "--seed", str(i * 10))
                  for i, g in enumerate(["ann", "bob", "cat", "dan"])]
        wait_for(lambda: len(re.findall(r"level_start level=2 room=", srv.text())) >= 4, 90,
                 "level 2 to start in all four rooms")
        rc, rooms, err = console(sock, "rooms")
        check(rc == 0 and len(rooms["rooms"]) == 4, f"console rooms: {rc} {rooms} {err}")
        check(all(r["players"] == 4 for r in rooms["rooms"]), f"not 4 players per room: {rooms}")
        for r in rooms["rooms"]:
            rc, closed, err = console(sock, "close", r["code"])
            check(rc == 0, f"close {r['code']}: {closed} {err}")
        reports = [finish_bots(g, 60) for g in groups]
        for rc, report, err in reports:
            check(len({b["room"] for b in report}) == 1, f"a group split over rooms: {[b['room'] for b in report]}")
            check(all("room_closed" in " ".join(b["errors"]) for b in report), f"bots not told: {report}")
        closed = dict(re.findall(r"room_closed room=(\d+) code=[A-Z]{5} reason=room_closed tick=\d+ state_hash=(\w+)",
                                 srv.text()))
        check(len(closed) == 4, f"room_closed lines: {closed}")
        check(srv.stop() == 0, "the server did not exit 0")
    for room_id, live_hash in closed.items():
        path = os.path.join(rec, f"room-{room_id}")  # a journal that keeps every segment
        p = subprocess.run([SERVER, "--replay", path], capture_output=True, text=True, timeout=120)
        check(p.returncode == 0, f"replay of {path} failed: {p.stderr.strip()}")
        out = json.loads(p.stdout)
        check(out["state_hash"] == live_hash, f"room {room_id}: replayed {out['state_hash']}, live {live_hash}")
        check(out["hashes_checked"] >= 30, f"room {room_id}: only {out['hashes_checked']} hashes checked")
        check(out["format"] == "journal 1", f"room {room_id}: the record read as {out['format']}")
        sim = os.path.join(os.path.dirname(SERVER), "fts-sim")
        p = subprocess.run([sim, "--match", "--inputs", path], capture_output=True, text=True, timeout=120)
        check(p.returncode == 0 and json.loads(p.stdout.strip().splitlines()[-1])["state_hash"] == live_hash,
              f"fts-sim replay of room {room_id}: {p.returncode} {p.stdout[-300:]} {p.stderr[-300:]}")
        # Room state never leaks: a room's record holds one group's players only.
        names = set()
        for seg in sorted(n for n in os.listdir(path) if n.endswith(".jsonl")):
            with open(os.path.join(path, seg)) as f:
                names |= set(re.findall(r'"name":"([a-z]+)\d"', f.read()))
        check(len(names) == 1, f"room {room_id} record holds players of {names}")


def test_forged_room():
    """A join or spectate of a room code that does not exist is refused, and nothing else happens."""
    with Server() as srv:
        script = write_script("expect room refused no_such_room\n")
        rc, report, err = run_bots("--connect", srv.address, "--name", "forger", "--room", "QQQQQ", "--script", script,
                                   timeout_s=20)
        check(rc == 0 and report[0].get("refused") == "no_such_room", f"forged join: {rc} {report} {err}")
        rc, report, err = run_bots("--connect", srv.address, "--name", "peeker", "--spectate", "QQQQQ",
                                   "--duration", "3", timeout_s=20)
        check(rc == 1 and "no_such_room" in " ".join(report[0]["errors"]), f"forged spectate: {rc} {report}")
        check("room_open" not in srv.text(), "a refused join opened a room")
        # A real room's code, and a player in it: a bot in another room cannot reach it.
        owner = start_bots("--connect", srv.address, "--name", "own", "--room", "create", "--behavior", "idle",
                           "--duration", "4")
        code = wait_for(lambda: room_codes(srv), 10, "the room")[0][1]
        script = write_script(f"expect room {code}\n")
        rc, report, err = run_bots("--connect", srv.address, "--name", "guest", "--room", code, "--script", script,
                                   timeout_s=20)
        check(rc == 0 and report[0]["room"] == code, f"join by code: {rc} {report} {err}")
        finish_bots(owner, 20)


def test_spectator():
    """A spectator gets the same snapshots (balls, players) as a player of the room, and has no ball."""
    with Server("--time-scale", "2") as srv:
        players = start_bots("--connect", srv.address, "--name", "play", "--count", "2", "--room", "create",
                             "--behavior", "hunter", "--duration", "8")
        code = wait_for(lambda: room_codes(srv), 10, "the room")[0][1]
        wait_for(lambda: "level_start level=1" in srv.text(), 30, "the level to start")
        rc, watcher, err = run_bots("--connect", srv.address, "--name", "watch", "--spectate", code,
                                    "--duration", "4", timeout_s=30)
        rc2, report, err2 = finish_bots(players, 30)
        check(rc == 0 and watcher[0]["spectator"] is True and watcher[0]["room"] == code, f"spectator: {watcher} {err}")
        seen = watcher[0]["snapshot_digests"]
        theirs = report[0]["snapshot_digests"]
        common = sorted(set(seen) & set(theirs), key=int)
        check(len(common) >= 10, f"only {len(common)} common snapshot ticks")
        differ = [t for t in common if seen[t] != theirs[t]]
        check(not differ, f"spectator and player saw different states at ticks {differ[:5]}")
        check(re.search(r"connect spectator=\d+ name=watch", srv.text()), "no spectator connect line")


def test_console():
    """The console socket is 0600; rooms and players list; kick tells the bot why; drain exits 0."""
    d = tempfile.mkdtemp(prefix="fts-console-")
    sock = os.path.join(d, "host.sock")
    with Server("--console-socket", sock, "--room-idle-ms", "300") as srv:
        check(stat.S_IMODE(os.stat(sock).st_mode) == 0o600, f"socket mode {oct(os.stat(sock).st_mode)}")
        bots = start_bots("--connect", srv.address, "--name", "kk", "--count", "2", "--room", "create",
                          "--behavior", "idle", "--duration", "6")
        wait_for(lambda: len(re.findall(r"connect player=", srv.text())) >= 2, 10, "two players")
        rc, rooms, err = console(sock, "rooms")
        check(rc == 0 and len(rooms["rooms"]) == 1 and rooms["rooms"][0]["players"] == 2, f"rooms: {rooms} {err}")
        rc, players, err = console(sock, "players", rooms["rooms"][0]["code"])
        check(rc == 0 and len(players["players"]) == 2, f"players: {players}")
        victim = players["players"][0]["player"]
        rc, out, err = console(sock, "kick", str(victim), "too", "loud")
        check(rc == 0 and out["kicked"] == victim, f"kick: {out} {err}")
        rc, out, err = console(sock, "kick", "999")
        check(rc == 1 and "no player" in out["error"], f"kick of nobody: {out}")
        rc, out, err = console(sock, "fly")
        check(rc == 1 and "unknown command" in out["error"], f"unknown command: {out}")
        rc, out, err = console(sock, "stats")
        check(rc == 0 and out["rooms"] == 1, f"stats: {out}")
        rc, out, err = console(sock, "drain")
        check(rc == 0 and out["draining"] is True, f"drain: {out}")
        rc, report, err = finish_bots(bots, 30)
        kicked = [b for b in report if b["player_id"] == victim]
        check(kicked and "kicked by the host: too loud" in " ".join(kicked[0]["errors"]),
              f"the kicked bot was not told why: {report}")
        # The other bot leaves at the end of its run; the room empties, closes, the server exits 0.
        code = srv.proc.wait(timeout=20)
        check(code == 0, f"drained server exited {code}")
        check(re.search(r"console request=.*kick", srv.text()), "commands are not logged")
        check("drained" in srv.text(), "no drained line")
        check(not os.path.exists(sock), "the socket file is left behind")


if __name__ == "__main__":
    sys.exit(main({"four_rooms": test_four_rooms, "forged_room": test_forged_room, "spectator": test_spectator,
                   "console": test_console}))
