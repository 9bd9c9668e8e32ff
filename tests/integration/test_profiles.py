#!/usr/bin/env python3
"""Players' profiles (issue 41) with real processes: fts-bot players with identities
against fts-server with --profiles on SQLite and on a real PostgreSQL 15
(tests/support/pg_temp.sh, run as the postgres user where the test is root).

  sqlite_record   a match played and left: the profile, `top`, `profile`, `stats`
  day_later       the same identity a (simulated) day later, under another name: the
                  same profile, two matches, first and last seen a day apart
  day_later_client  the same, with the player's real fts-client (tmux, 80x24): a level
                  joined and quit, and again a day later under another name with the
                  same identity file: one profile, two matches, the waiting screen's rank
  refused_files   a corrupt and a foreign SQLite file refused at start, saying which
  kill_resume     kill -9 mid-match, --resume, the player back and gone: one result
  pg_two_servers  two servers share one PostgreSQL: a record made on one is on the
                  other's `top`, and on the player's fts-client connected to the other
  pg_down_up      PostgreSQL stopped mid-match and started again: the result waits in the
                  spool (stats, /metrics say so) and is written once it is back
  board_forget    a bot plays a match; 10 000 more profiles, the best under hostile names,
                  go into the file; the player's real fts-client (tmux, 80x24) shows the
                  top 10 cleaned and the player's rank on its waiting screen; then
                  `fts-client --forget-me`: a "no" erases nothing, --yes erases the
                  profile (the console's `profile` no longer finds it), the identity file
                  stays
"""
import json, os, shutil, signal, socket, sqlite3, subprocess, sys, tempfile, time

from harness import BIN, HERE, SERVER, Failure, Server, check, finish_bots, main, start_bots, wait_for

PG_TEMP = os.path.join(HERE, "..", "support", "pg_temp.sh")
CLIENT = os.path.join(BIN, "client", "fts-client")
QUICK = ["--reconnect-window-ms", "1000", "--timeout-ms", "2000", "--room-idle-ms", "60000"]


def console(sock, *words):
    out = subprocess.run([SERVER, "--console", sock, *words], capture_output=True, text=True, timeout=20)
    return json.loads(out.stdout) if out.stdout.strip().startswith("{") else {"ok": False, "error": out.stderr}


def profiles_server(work, profiles, *extra, env=None):
    sock = os.path.join(work, f"console-{time.monotonic_ns()}.sock")
    srv = Server("--profiles", profiles, "--console-socket", sock, "--time-scale", "4", *QUICK, *extra,
                 env={"XDG_STATE_HOME": os.path.join(work, "state"), **(env or {})})
    srv.sock = sock
    return srv


def play(srv, identity, name, seconds):
    code, report, err = finish_bots(start_bots("--connect", srv.address, "--identity", identity, "--name", name,
                                               "--duration", str(seconds)), 60)
    check(code == 0, f"fts-bot {name}: {err} {report}")


def profile_of(sock, name):
    reply = wait_for(lambda: (lambda r: r if r.get("ok") and r["profiles"][0]["matches"] >= 1 else None)(
        console(sock, "profile", name)), 20, f"{name}'s profile with a match")
    return reply["profiles"][0]


def sqlite_record():
    work = tempfile.mkdtemp(prefix="fts-prof-")
    db = os.path.join(work, "profiles.sqlite")
    with profiles_server(work, db) as srv:
        play(srv, os.path.join(work, "ann.id"), "ann", 6)
        p = profile_of(srv.sock, "ann")
        check(p["matches"] == 1 and p["best_level"] >= 1 and len(p["fingerprint"]) == 32, f"ann: {p}")
        top = console(srv.sock, "top")
        check(top["ok"] and top["top"][0]["fingerprint"] == p["fingerprint"], f"top: {top}")
        st = console(srv.sock, "stats")["profiles"]
        check(st["connected"] and st["results"] == 1 and st["spooled"] == 0, f"stats: {st}")
        # A guest plays too, and is not recorded.
        code, _, err = finish_bots(start_bots("--connect", srv.address, "--name", "guest", "--duration", "3"), 60)
        check(code == 0, err)
        check(console(srv.sock, "top")["profiles"] == 1, "a guest got a profile")
        srv.stop()
    con = sqlite3.connect(db)
    check(con.execute("SELECT COUNT(*) FROM fts_results").fetchone()[0] == 1, "results in the file")
    shutil.rmtree(work, ignore_errors=True)


def same_player_a_day_later(srv, first, name):
    """The profile `first` (a match on day one) after a second match a day later under
    `name`: the same profile, two matches, the new name, first and last seen a day apart."""
    p = wait_for(lambda: (lambda r: r if r.get("ok") and r["profiles"][0]["matches"] == 2 else None)(
        console(srv.sock, "profile", first["fingerprint"])), 20, "the second match")["profiles"][0]
    check(p["name"] == name, f"the name is the last one played under: {p}")
    check(p["first_seen"] == first["first_seen"] and p["last_seen"] - p["first_seen"] >= 86400,
          f"first and last seen a day apart: {p}")
    check(console(srv.sock, "top")["profiles"] == 1, "one identity, one profile")


def day_later():
    work = tempfile.mkdtemp(prefix="fts-prof-")
    db = os.path.join(work, "profiles.sqlite")
    ident = os.path.join(work, "ann.id")
    with profiles_server(work, db) as srv:
        play(srv, ident, "ann", 4)
        first = profile_of(srv.sock, "ann")
        srv.stop()
    with profiles_server(work, db, env={"FTS_TEST_CLOCK_OFFSET_S": "86400"}) as srv:
        play(srv, ident, "annie", 4)
        same_player_a_day_later(srv, first, "annie")
        srv.stop()
    shutil.rmtree(work, ignore_errors=True)


def stop_client(tmux, ident):
    """Ends the tmux server and any fts-client of this identity still running: a client
    whose terminal went away was once left behind, spinning on a core for the rest of the
    test command (2026-12-06)."""
    subprocess.run(["pkill", "-KILL", "-f", f"{CLIENT} .*--identity {ident} "], capture_output=True)
    subprocess.run([*tmux, "kill-server"], capture_output=True)


def client_match(srv, work, ident, name):
    """The player's real fts-client (tmux, 80x24, ASCII) joins a match, plays until level 1
    is on its screen and quits (q, then y): a match played and left. Returns the screen
    of the level."""
    if shutil.which("tmux") is None:
        print("tmux is not installed here: skipped")
        sys.exit(77)
    tmux = ["tmux", "-L", f"fts-day-{os.getpid()}-{time.monotonic_ns()}"]
    pane = lambda: subprocess.run([*tmux, "capture-pane", "-p", "-t", "c"], capture_output=True,  # noqa: E731
                                  text=True).stdout
    try:
        env = f"env LANG=C XDG_STATE_HOME={os.path.join(work, 'client-state')} TERM=xterm"
        subprocess.run([*tmux, "new-session", "-d", "-s", "c", "-x", "80", "-y", "24",
                        f"{env} {CLIENT} --connect {srv.address} --identity {ident} --name {name} --quick "
                        "--glyphs ascii; echo CLIENT_EXIT=$?; sleep 30"], check=True)
        wait_for(lambda: "Room " in pane(), 30, f"{name}'s welcome")
        subprocess.run([*tmux, "send-keys", "-t", "c", "Enter"])
        # (At 80x24 the header is the compact one: "Level 1  Coins 0 ...".)
        level = wait_for(lambda: (lambda t: t if t.startswith("Level 1 ") else None)(pane()), 30, f"{name}'s level 1")
        subprocess.run([*tmux, "send-keys", "-t", "c", "Right"])
        subprocess.run([*tmux, "send-keys", "-t", "c", "q"])
        wait_for(lambda: "Quit?" in pane(), 10, "the quit question")
        subprocess.run([*tmux, "send-keys", "-t", "c", "y"])
        wait_for(lambda: "CLIENT_EXIT=0" in pane(), 20, f"{name}'s client to exit")
        return level
    finally:
        stop_client(tmux, ident)


def day_later_client():
    work = tempfile.mkdtemp(prefix="fts-prof-")
    db = os.path.join(work, "profiles.sqlite")
    ident = os.path.join(work, "ann.id")
    with profiles_server(work, db) as srv:
        client_match(srv, work, ident, "ann")
        first = profile_of(srv.sock, "ann")
        srv.stop()
    check(os.path.exists(ident), "the client kept no identity file")
    with profiles_server(work, db, env={"FTS_TEST_CLOCK_OFFSET_S": "86400"}) as srv:
        client_match(srv, work, ident, "annie")
        same_player_a_day_later(srv, first, "annie")
        # Back on its waiting screen, the player sees the one profile as theirs.
        text = client_screen(srv, work, ident, "annie", "You: #1 of 1")
        check("annie" in text, f"the board's name: {text}")
        srv.stop()
    shutil.rmtree(work, ignore_errors=True)


def refused_files():
    work = tempfile.mkdtemp(prefix="fts-prof-")
    corrupt = os.path.join(work, "corrupt.sqlite")
    with open(corrupt, "wb") as f:
        f.write(b"this is no database, it is a shopping list\n" * 100)
    foreign = os.path.join(work, "foreign.sqlite")
    con = sqlite3.connect(foreign)
    con.execute("CREATE TABLE invoices (id INTEGER, total REAL)")
    con.commit()
    con.close()
    for path, says in [(corrupt, "not a SQLite database"), (foreign, "a SQLite database of something else")]:
        out = subprocess.run([SERVER, "--port", "0", "--profiles", path], capture_output=True, text=True, timeout=20,
                             env={**os.environ, "XDG_STATE_HOME": os.path.join(work, "state")})
        check(out.returncode != 0, f"{path}: started anyway")
        check(says in out.stderr and path in out.stderr, f"{path}: {out.stderr!r}")
    shutil.rmtree(work, ignore_errors=True)


def kill_resume():
    work = tempfile.mkdtemp(prefix="fts-prof-")
    db = os.path.join(work, "profiles.sqlite")
    journal = os.path.join(work, "journal")
    ident = os.path.join(work, "ann.id")
    with profiles_server(work, db, "--journal-dir", journal) as srv:
        port = srv.port
        bot = start_bots("--connect", srv.address, "--identity", ident, "--name", "ann", "--duration", "20")
        wait_for(lambda: "level_start level=1" in srv.text(), 20, "the match's start")
        wait_for(lambda: os.path.exists(journal) and any(
            '"career"' in open(os.path.join(d, f)).read() for d, _, fs in os.walk(journal) for f in fs if
            f.endswith(".jsonl")), 20, "the player's match in the journal")
        srv.proc.kill()
        srv.proc.wait()
        check("match_result" not in srv.text(), "a result before the match ended")
    # (The player is away until its bot notices the silence, 2 s: the window holds it.)
    with profiles_server(work, db, "--journal-dir", journal, "--resume", "--port", str(port),
                         "--reconnect-window-ms", "8000") as srv2:
        code, report, err = finish_bots(bot, 90)
        check(code == 0, f"the bot: {err}")
        check("reconnect player=" in srv2.text(), "the bot took its player back")
        wait_for(lambda: "match_result" in srv2.text(), 30, "the result after the resume")
        p = profile_of(srv2.sock, "ann")
        check(p["matches"] == 1, f"one match: {p}")
        srv2.stop()
        check(srv2.text().count("match_result") == 1, "one result line")
    con = sqlite3.connect(db)
    check(con.execute("SELECT COUNT(*) FROM fts_results").fetchone()[0] == 1, "one result in the file")
    shutil.rmtree(work, ignore_errors=True)


class Pg:
    def __init__(self):
        self.dir = tempfile.mkdtemp(prefix="fts-pgit-")
        with socket.socket() as s:
            s.bind(("127.0.0.1", 0))
            self.port = s.getsockname()[1]
        rc = self.run("start")
        if rc == 77:
            print("PostgreSQL 15 is not installed here: skipped")
            sys.exit(77)
        check(rc == 0, "pg_temp.sh start failed")
        self.url = f"postgresql://fts@127.0.0.1:{self.port}/postgres?connect_timeout=2"

    def run(self, cmd):
        return subprocess.run(["bash", PG_TEMP, cmd, os.path.join(self.dir, "pg"), str(self.port)],
                              env={**os.environ, "FTS_PG_FSYNC": "off"}).returncode

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.run("stop")
        shutil.rmtree(self.dir, ignore_errors=True)


def pg_two_servers():
    with Pg() as pg:
        work = tempfile.mkdtemp(prefix="fts-prof-")
        with profiles_server(work, pg.url) as a, profiles_server(work, pg.url) as b:
            play(a, os.path.join(work, "ann.id"), "ann", 5)
            p = profile_of(a.sock, "ann")
            top = wait_for(lambda: (lambda r: r if r.get("ok") and r["top"] else None)(console(b.sock, "top")), 20,
                           "the other server's top")
            check(top["top"][0]["fingerprint"] == p["fingerprint"] and "postgresql" in top["where"], f"top: {top}")
            # The player's own client on the other server shows the fleet's board.
            if shutil.which("tmux") is not None:
                text = client_screen(b, work, os.path.join(work, "ann.id"), "ann", "You: #1 of 1,")
                check(" 1. ann " in text, text)
                print("the other server's waiting screen shows ann first: #1 of 1")
            a.stop()
            b.stop()
        shutil.rmtree(work, ignore_errors=True)


def pg_down_up():
    with Pg() as pg:
        work = tempfile.mkdtemp(prefix="fts-prof-")
        with profiles_server(work, pg.url) as srv:
            bot = start_bots("--connect", srv.address, "--identity", os.path.join(work, "ann.id"), "--name", "ann",
                             "--duration", "8")
            wait_for(lambda: "level_start level=1" in srv.text(), 20, "the match's start")
            check(pg.run("stop") == 0, "pg stop")
            code, _, err = finish_bots(bot, 60)
            check(code == 0, f"the game went on without the database: {err}")
            st = wait_for(lambda: (lambda s: s if s["spooled"] >= 1 and not s["connected"] else None)(
                console(srv.sock, "stats")["profiles"]), 30, "the result spooled, the database down")
            check(st["results"] == 0 and st["error"], f"stats: {st}")
            check(pg.run("start") == 0, "pg start")
            st = wait_for(lambda: (lambda s: s if s["results"] == 1 and s["spooled"] == 0 else None)(
                console(srv.sock, "stats")["profiles"]), 30, "the result written once the database is back")
            check(profile_of(srv.sock, "ann")["matches"] == 1, "one match")
            srv.stop()
        shutil.rmtree(work, ignore_errors=True)


# Names a shared database could hold that no hello lets in, and what a board row makes
# of them (the server cleans them; the client again).
HOSTILE = [("\x1b[2J\x1b]0;pwned\x07", "[2J]0;pwned"), ("\u65e5\u672c\u8a9e-long-name-here", "???-long-name-he"),
           ("", "?"), ("\u009b31m\x7f", "?31m")]


def add_profiles(db, n):
    """n profiles with a match each, the first ones at level 1000 under hostile names."""
    con = sqlite3.connect(db)
    rows = []
    for i in range(n):
        name, level = (HOSTILE[i][0], 1000 - i) if i < len(HOSTILE) else (f"p{i}", i % 37)
        rows.append((f"{i + 1:032x}", name, 1000, 1000, 1, level, i, i, 0, 0, 1000))
    con.executemany("INSERT INTO fts_profiles (fingerprint, name, first_seen, last_seen, matches, best_level,"
                    " best_level_coins, most_coins, knocks, lives_lost, play_ms) VALUES (?,?,?,?,?,?,?,?,?,?,?)", rows)
    con.commit()
    con.close()


def rank_in(db, fp):
    con = sqlite3.connect(db)
    level, coins = con.execute("SELECT best_level, best_level_coins FROM fts_profiles WHERE fingerprint = ?",
                               (fp,)).fetchone()
    ahead = con.execute("SELECT COUNT(*) FROM fts_profiles WHERE matches > 0 AND (best_level > ? OR (best_level = ?"
                        " AND best_level_coins > ?) OR (best_level = ? AND best_level_coins = ? AND fingerprint < ?))",
                        (level, level, coins, level, coins, fp)).fetchone()[0]
    total = con.execute("SELECT COUNT(*) FROM fts_profiles WHERE matches > 0").fetchone()[0]
    con.close()
    return ahead + 1, total


def forget(srv, ident, *extra, stdin=""):
    return subprocess.run([CLIENT, "--connect", srv.address, "--identity", ident, "--forget-me", *extra],
                          input=stdin, capture_output=True, text=True, timeout=30)


def client_screen(srv, work, ident, name, needle):
    """The player's real fts-client (tmux, 80x24, ASCII) until `needle` is on its screen
    (its waiting screen: the leaderboard); the screen's text. Quits it."""
    if shutil.which("tmux") is None:
        print("tmux is not installed here: skipped")
        sys.exit(77)
    tmux = ["tmux", "-L", f"fts-board-{os.getpid()}-{time.monotonic_ns()}"]
    try:
        env = f"env LANG=C XDG_STATE_HOME={os.path.join(work, 'client-state')} TERM=xterm"
        subprocess.run([*tmux, "new-session", "-d", "-s", "c", "-x", "80", "-y", "24",
                        f"{env} {CLIENT} --connect {srv.address} --identity {ident} --name {name} --quick "
                        "--glyphs ascii; echo CLIENT_EXIT=$?; sleep 30"], check=True)
        pane = lambda: subprocess.run([*tmux, "capture-pane", "-p", "-t", "c"], capture_output=True,  # noqa: E731
                                      text=True).stdout
        text = wait_for(lambda: (lambda t: t if needle in t else None)(pane()), 30, f"{needle!r} on the client's screen")
        subprocess.run([*tmux, "send-keys", "-t", "c", "q"])
        subprocess.run([*tmux, "send-keys", "-t", "c", "q"])
        wait_for(lambda: "CLIENT_EXIT=" in pane(), 20, f"{name}'s client to exit")
        return text
    finally:
        stop_client(tmux, ident)


def board_forget():
    if shutil.which("tmux") is None:
        print("tmux is not installed here: skipped")
        sys.exit(77)
    work = tempfile.mkdtemp(prefix="fts-prof-")
    db = os.path.join(work, "profiles.sqlite")
    ident = os.path.join(work, "ann.id")
    with profiles_server(work, db) as srv:
        play(srv, ident, "ann", 6)
        fp = profile_of(srv.sock, "ann")["fingerprint"]
        srv.stop()
    add_profiles(db, 10000)
    rank, total = rank_in(db, fp)
    check(total == 10001, f"{total} ranked")
    with profiles_server(work, db) as srv:
        you = f"You: #{rank:,} of {total:,}"
        text = client_screen(srv, work, ident, "ann", you)
        check("Best levels on this server (10,001 players)" in text, text)
        for r in range(1, 11):
            check(f"{r:>2}. " in text, f"row {r}: {text}")
        for _, shown in HOSTILE:
            check(f". {shown}" in text, f"{shown!r}: {text}")
        check("\x1b" not in text and "\x07" not in text, "escapes on the screen")
        print(f"the client shows rank {rank:,} of {total:,} and the top 10")
        # --forget-me asks first: anything but yes erases nothing.
        out = forget(srv, ident, stdin="no\n")
        check(out.returncode == 1 and "Nothing was erased" in out.stdout and "Type yes" in out.stdout,
              f"a no: {out.returncode} {out.stdout!r} {out.stderr!r}")
        check(console(srv.sock, "profile", fp).get("ok"), "the profile went after a no")
        out = forget(srv, ident, "--yes")
        check(out.returncode == 0 and "erased" in out.stdout and "is kept" in out.stdout,
              f"--yes: {out.returncode} {out.stdout!r} {out.stderr!r}")
        reply = console(srv.sock, "profile", fp)
        check(not reply.get("ok") and "no profile" in reply.get("error", ""), f"profile after --forget-me: {reply}")
        check(os.path.exists(ident), "the identity file is kept")
        check("profile_forget" in srv.text(), "the erasure is logged")
        # A guest has nothing to forget; a missing identity file neither (none is made).
        out = subprocess.run([CLIENT, "--connect", srv.address, "--guest", "--forget-me"], capture_output=True,
                             text=True, timeout=30)
        check(out.returncode == 2, f"--guest --forget-me: {out.returncode} {out.stderr!r}")
        missing = os.path.join(work, "nobody.id")
        out = forget(srv, missing, "--yes")
        check(out.returncode == 1 and not os.path.exists(missing), f"no identity: {out.stderr!r}")
        srv.stop()
    con = sqlite3.connect(db)
    check(con.execute("SELECT COUNT(*) FROM fts_results WHERE fingerprint = ?", (fp,)).fetchone()[0] == 0,
          "the player's results are gone")
    check(con.execute("SELECT COUNT(*) FROM fts_profiles").fetchone()[0] == 10000, "the others' profiles stay")
    con.close()
    shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main({"sqlite_record": sqlite_record, "day_later": day_later,
                   "day_later_client": day_later_client, "refused_files": refused_files,
                   "kill_resume": kill_resume, "pg_two_servers": pg_two_servers, "pg_down_up": pg_down_up,
                   "board_forget": board_forget}))
