#!/usr/bin/env python3
"""The soak matrix (issue 30): 64 shopper bots in 8 private rooms (8 each) against one
fts-server, every datagram of every bot through one impairment relay (relay.py), one
cell per impairment, FTS_SOAK_MINUTES (default 10) minutes each. Per cell it asserts
that no session drops (the server's log: disconnect, reconnect and leave lines while
the bots play; a silence ends in a time-out line --timeout-ms after it began), that
every command is applied exactly once and every coin is accounted for (each bot's
report against the server's log and the room's input record), and reports the
server's RSS, its tick times and skipped ticks (its stats lines), and what the relay
lost, duplicated and reordered (its counters).

usage: FTS_BIN_DIR=build python3 tests/integration/soak_matrix.py [CELL ...|all] [--out CSV] [--minutes M]
                                                                 [--seed S] [--timeout-ms MS] [--rss-log F]
       python3 tests/integration/soak_matrix.py --table CSV...   (the markdown table of CSV rows)
  CELL: clean loss5 loss20 reorder30 dup jitter link_down (default: FTS_SOAK_CELLS, a comma
  list, or all). --out appends one row per cell to CSV. Exit 1 if any cell lost anything.
"""
import argparse, csv, json, os, re, select, shutil, signal, statistics, subprocess, sys, tempfile, time
from datetime import datetime

from harness import BIN, HERE, Failure, Server, check, finish_bots, rss_kib, start_bots, wait_for

ROOMS, BOTS = 8, 8
PLAYERS = ROOMS * BOTS
MANY_LIVES = os.path.join(HERE, "many-lives.json")
# The session time-out, server and bots alike (the welcome carries it to the client).
# The default, 10000 ms, equals the link-down cell's outage: a 10 s silence would be
# dropped at the default, so the matrix runs with 20 s, longer than the outage
# (--timeout-ms 10000 link_down shows the default's drops).
TIMEOUT_MS = 20000
OUTAGE_S = 10
CLEAN = ["--loss", "0", "--dup", "0", "--delay-ms", "0", "--jitter-ms", "0"]
# name: (what the table says, relay flags after CLEAN, a check of the relay's counters
# that the cell impaired what it says: a failure is the rig's, reported as such)
CELLS = {
    "clean": ("none", [], lambda r: r["lost"] == r["dup"] == r["reordered"] == 0),
    "loss5": ("5 % random loss each way", ["--loss", "0.05"], lambda r: 0.04 < r["lost_share"] < 0.06),
    "loss20": ("20 % random loss each way", ["--loss", "0.2"], lambda r: 0.18 < r["lost_share"] < 0.22),
    "reorder30": ("uniform jitter 0-180 ms each way, reordering", ["--jitter-ms", "180"],
                  lambda r: r["reorder_share"] >= 0.2),
    "dup": ("10 % duplicated each way", ["--dup", "0.1"], lambda r: 0.08 < r["dup_share"] < 0.12),
    "jitter": ("half-normal jitter, sigma 20 ms, order kept", ["--jitter-ms", "20", "--jitter-dist", "normal",
                                                                "--no-reorder"],
               lambda r: r["reordered"] == 0 and r["lost"] == 0),
    "link_down": (f"link down {OUTAGE_S} s both ways at mid-run", ["--down-at", "MID", "--down-for", str(OUTAGE_S)],
                  lambda r: r["lost_down"] > 0 and r["lost"] == r["lost_down"]),
}
COLUMNS = ["cell", "impairment", "build", "bots", "minutes", "sessions_dropped", "byes_lost", "ledger_mismatches",
           "purchases", "commands_applied", "commands_sent", "coins_earned", "rss_start_kib", "rss_mid_kib",
           "rss_end_kib", "rss_max_kib", "tick_p50_us", "tick_p99_us", "tick_max_us", "skipped_ticks", "relay_in",
           "relay_out", "relay_lost", "relay_dup", "relay_reordered", "lost_share", "dup_share", "reorder_share",
           "snapshots_lost", "relay_cpu_s", "server_cpu_s", "result"]


def cpu_s(pid):
    with open(f"/proc/{pid}/stat") as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def log_time(line):
    """The wall time (epoch s) of a text log line: [YYYY-mm-dd HH:MM:SS.mmm], local time."""
    return datetime.strptime(line[1:24], "%Y-%m-%d %H:%M:%S.%f").timestamp()


def start_relay(server_address, flags, seed):
    relay = subprocess.Popen([sys.executable, os.path.join(HERE, "relay.py"), "--server", server_address,
                              "--seed", str(seed), *flags], stdout=subprocess.PIPE, text=True)
    ready, _, _ = select.select([relay.stdout], [], [], 10)
    line = relay.stdout.readline() if ready else ""
    m = re.search(r"relay ready port=(\d+)", line)
    if not m:
        relay.kill()
        raise Failure(f"the relay did not start: {line!r}")
    return relay, f"127.0.0.1:{m.group(1)}"


def drain_uplink(relay, timeout_s=10):
    """Waits until the relay holds no client datagram (the bots' goodbyes are delivered,
    not cut off by the relay's end): SIGUSR1 makes it print its counters and go on."""
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        relay.send_signal(signal.SIGUSR1)
        ready, _, _ = select.select([relay.stdout], [], [], 1.0)
        line = relay.stdout.readline() if ready else ""
        if line.startswith("{") and json.loads(line)["up"]["pending"] == 0:
            return
    raise Failure(f"the relay still held client datagrams after {timeout_s} s")


def stop_relay(relay):
    """SIGTERM: the relay prints its counters as one JSON line and exits."""
    relay.send_signal(signal.SIGTERM)
    out, _ = relay.communicate(timeout=20)
    lines = [l for l in out.splitlines() if l.startswith("{")]
    check(lines, f"the relay printed no counters: {out!r}")
    c = json.loads(lines[-1])
    both = lambda key: sum(c[d][key] for d in ("up", "down"))
    lost = sum(sum(c[d]["lost"].values()) for d in ("up", "down"))
    n_in, n_out = both("datagrams_in"), both("datagrams_out")
    return {"in": n_in, "out": n_out, "lost": lost, "lost_down": sum(c[d]["lost"]["down"] for d in ("up", "down")),
            "dup": both("duplicated"), "reordered": both("reordered"), "pending": both("pending"),
            "lost_share": lost / max(1, n_in), "dup_share": both("duplicated") / max(1, n_in),
            "reorder_share": both("reordered") / max(1, n_out),
            "per_direction": {d: {k: c[d][k] for k in ("datagrams_in", "datagrams_out", "lost", "duplicated",
                                                       "reordered")} for d in ("up", "down")}}


EVENT = re.compile(r"(?:enemy_defeated enemy=\d+ player=(?P<e>\d+) coins=(?P<ec>\d+)"
                   r"|interest player=(?P<i>\d+) coins=(?P<ic>\d+)"
                   r"|purchase player=(?P<p>\d+) item=\w+ ok=(?P<ok>true|false) reason=\w* price=(?P<pc>\d+) "
                   r"coins=\d+) room=\d+ tick=(?P<tick>\d+)")


def server_book(text):
    """Per player, from the server's log: [(tick, coins change, kind)] with kind earn,
    buy (a purchase applied) or refused (a purchase refused, no coins)."""
    book = {}
    for m in EVENT.finditer(text):
        if m["e"]:
            book.setdefault(m["e"], []).append((int(m["tick"]), int(m["ec"]), "earn"))
        elif m["i"]:
            book.setdefault(m["i"], []).append((int(m["tick"]), int(m["ic"]), "earn"))
        elif m["ok"] == "true":
            book.setdefault(m["p"], []).append((int(m["tick"]), -int(m["pc"]), "buy"))
        else:
            book.setdefault(m["p"], []).append((int(m["tick"]), 0, "refused"))
    return book


def applied_commands(record_dir):
    """Per player: the commands its room's match was given (the input records: one journal
    directory per room, keeping every segment)."""
    applied = {}
    segments = [os.path.join(record_dir, room, seg) for room in sorted(os.listdir(record_dir))
                for seg in sorted(os.listdir(os.path.join(record_dir, room))) if seg.endswith(".jsonl")]
    for path in segments:
        with open(path) as f:
            for line in f:
                if '"cmd"' not in line:
                    continue
                for p in json.loads(line).get("players", []):
                    for cmd in p.get("cmd", []):
                        applied.setdefault(str(p["id"]), []).append(cmd)
    return applied


def audit_bot(b, book, applied):
    """The exactly-once checks of one bot: a list of what did not add up (empty: all did)."""
    pid, problems = str(b["player_id"]), []
    last_tick = max(map(int, b["snapshot_digests"]), default=-1)  # its last snapshot (stale ones are refused)
    seen = [e for e in book.get(pid, []) if e[0] <= last_tick]
    ledger = sum(c for _, c, _ in seen)
    buys = sum(1 for _, _, k in seen if k == "buy")
    if b["coins"] != ledger:
        problems.append(f"coins {b['coins']}, the server's log says {ledger} by tick {last_tick}")
    if b["coins"] != b["coins_earned_by_events"] - b["coins_spent_by_events"]:
        problems.append(f"coins {b['coins']}, its own events say {b['coins_earned_by_events']} - "
                        f"{b['coins_spent_by_events']}")
    if b["purchase_events"] != buys:
        problems.append(f"{b['purchase_events']} purchase events seen, the server applied {buys} by tick {last_tick}")
    every = book.get(pid, [])
    ok_all = sum(1 for _, _, k in every if k == "buy")
    refused_all = sum(1 for _, _, k in every if k == "refused")
    cmds = applied.get(pid, [])
    # A command still unanswered at the end may or may not have been applied: one, at most.
    slack = 1 if b["command_pending"] else 0
    if not b["commands_sent"] - slack <= len(cmds) <= b["commands_sent"]:
        problems.append(f"{b['commands_sent']} commands sent (pending {b['command_pending']}), "
                        f"{len(cmds)} applied: {cmds}")
    if b["commands_answered"] != b["commands_sent"] - slack:
        problems.append(f"{b['commands_sent']} commands sent, {b['commands_answered']} answered")
    buy_cmds = sum(1 for c in cmds if c.startswith("buy"))
    if buy_cmds != ok_all + refused_all:
        problems.append(f"{buy_cmds} buy commands applied, the log has {ok_all} purchases + {refused_all} refusals")
    if not (ok_all - slack <= b["purchases"] <= ok_all and
            refused_all - slack <= b["purchases_refused"] <= refused_all):
        problems.append(f"results: {b['purchases']} ok, {b['purchases_refused']} refused; the server: {ok_all} ok, "
                        f"{refused_all} refused")
    if len(b["bought"]) != b["purchases"]:
        problems.append(f"bought {b['bought']} but {b['purchases']} purchases")
    return problems


def session_drops(text, players, end_wall):
    """Drops while the bots played, as (player, log line): a disconnect other than the
    bot's goodbye, a reconnect or a release before the bots' end; a time-out line after
    it whose silence began before the end (the line comes TIMEOUT_MS after the last
    datagram). A time-out of a silence that began at the end is a lost goodbye (its
    three datagrams all lost), counted apart."""
    drops, byes_lost = [], 0
    for line in text.splitlines():
        m = re.search(r"\] \[\w+\] (disconnect|reconnect|leave) player=(\d+)(?: reason=(\w+))?", line)
        if not m or m[2] not in players or m[3] == "done":
            continue
        t = log_time(line)
        began = t - TIMEOUT_MS / 1000 if m[3] == "timeout" else t
        if began < end_wall - 1.0:
            drops.append((m[2], line.strip()))
        elif m[1] == "disconnect" and m[3] == "timeout":
            byes_lost += 1
    return drops, byes_lost


STATS = re.compile(r"stats players=(?P<players>\d+) .*tick_p50_us=(?P<p50>[0-9.]+) tick_p99_us=(?P<p99>[0-9.]+) "
                   r"tick_max_us=(?P<max>[0-9.]+) ticks_skipped_total=(?P<skipped>\d+)")


def tick_stats(text):
    """Tick p50 (median of the intervals'), p99 and max (the worst interval's) over the
    stats intervals with every bot in; skipped ticks over the whole run."""
    recs = [m.groupdict() for m in STATS.finditer(text)]
    full = [r for r in recs if int(r["players"]) == PLAYERS] or recs
    if not full:
        return None, None, None, None
    return (round(statistics.median(float(r["p50"]) for r in full), 1), round(max(float(r["p99"]) for r in full), 1),
            round(max(float(r["max"]) for r in full)), int(recs[-1]["skipped"]))


def run_cell(name, minutes, seed, rss_log=None):
    what, flags, rig_ok = CELLS[name]
    seconds = max(30.0, minutes * 60)
    flags = [str(round(seconds / 2, 1)) if f == "MID" else f for f in CLEAN + flags]
    record_dir = tempfile.mkdtemp(prefix="fts-soak-record-")
    row = {"cell": name, "impairment": what, "build": os.path.basename(os.path.normpath(BIN)), "bots": PLAYERS,
           "minutes": round(seconds / 60, 2)}
    problems = []
    print(f"== {name}: {what}; {PLAYERS} bots in {ROOMS} rooms, {seconds:.0f} s, relay {' '.join(flags)}", flush=True)
    with Server("--config", MANY_LIVES, "--log-level", "debug", "--timeout-ms", str(TIMEOUT_MS),
                "--max-per-address", str(PLAYERS + 16), "--max-rooms", "64", "--stats-interval-ms", "10000",
                "--record-dir", record_dir) as srv:
        relay, target = start_relay(srv.address, flags, seed)
        try:
            groups = [start_bots("--connect", target, "--name", f"r{r}b", "--count", str(BOTS), "--behavior",
                                 "shopper", "--room", "create", "--duration", str(seconds),
                                 "--seed", str(seed * 100 + r * BOTS + 1)) for r in range(ROOMS)]
            wait_for(lambda: len(re.findall(r"\] \[info\] connect player=\d+ name=r\db\d", srv.text())) >= PLAYERS, 60,
                     f"{PLAYERS} bots to connect")
            wait_for(lambda: len(set(re.findall(r"level_start level=1 room=(\d+)", srv.text()))) >= ROOMS, 60,
                     "level 1 in every room")
            rss = [rss_kib(srv.proc.pid)]
            row["rss_start_kib"] = rss[0]
            deadline = time.monotonic() + seconds + 120
            # Until the first bot process ends (its duration is over): the server's memory each second.
            while all(g[0].poll() is None for g in groups):
                check(srv.proc.poll() is None, f"the server exited ({srv.proc.returncode}) mid-run")
                check(relay.poll() is None, "the relay exited mid-run")
                check(time.monotonic() < deadline, "the bots did not end within their duration + 120 s")
                rss.append(rss_kib(srv.proc.pid))
                time.sleep(1)
            end_wall = time.time()
            # (one sample a second: the middle one splits warm-up growth from a steady rise)
            row["rss_mid_kib"], row["rss_end_kib"], row["rss_max_kib"] = rss[len(rss) // 2], rss[-1], max(rss)
            if rss_log:
                with open(rss_log, "a") as f:
                    f.writelines(f"{name},{i},{k}\n" for i, k in enumerate(rss))
            reports = [finish_bots(g, 120) for g in groups]
            drain_uplink(relay)
            row["relay_cpu_s"] = round(cpu_s(relay.pid), 1)
        finally:
            counters = stop_relay(relay) if relay.poll() is None else None
        check(counters, "the relay ended before its counters were read")
        bots = [b for _, rep, _ in reports for b in rep]
        players = {str(b["player_id"]) for b in bots}
        # Every session ends in the log: the goodbye, or (all three goodbye datagrams lost) the time-out.
        wait_for(lambda: players <= set(re.findall(r"disconnect player=(\d+)", srv.text())), TIMEOUT_MS / 1000 + 20,
                 "every session to end (goodbye or time-out)")
        row["server_cpu_s"] = round(cpu_s(srv.proc.pid), 1)
        check(srv.stop() == 0, "the server did not exit 0 on SIGINT")
        text = srv.text()
    for rc, rep, err in reports:
        if rc != 0:
            problems.append(f"a bot process exited {rc}: {err.strip()[-300:]}")
    bad = [f"{b['name']}: {b['errors']}" for b in bots if not b["ok"]]
    problems += [f"bot failed: {x}" for x in bad]
    if len(bots) != PLAYERS or len(players) != PLAYERS:
        problems.append(f"{len(bots)} reports, {len(players)} distinct players (expected {PLAYERS})")
    rooms = {}
    for b in bots:
        rooms.setdefault(b["room"], set()).add(b["name"][:2])
    if len(rooms) != ROOMS or any(len(v) != 1 for v in rooms.values()):
        problems.append(f"rooms: {rooms}")
    drops, byes_lost = session_drops(text, players, end_wall)
    problems += [f"session dropped: {line}" for _, line in drops[:10]]
    if len(drops) > 10:
        problems.append(f"... {len(drops)} drop lines in all")
    book, applied = server_book(text), applied_commands(record_dir)
    mismatched = 0
    for b in bots:
        found = audit_bot(b, book, applied)
        mismatched += bool(found)
        problems += [f"{b['name']} (player {b['player_id']}): {p}" for p in found]
    shutil.rmtree(record_dir)
    purchases = sum(1 for p in players for e in book.get(p, []) if e[2] == "buy")
    earned = sum(e[1] for p in players for e in book.get(p, []) if e[2] == "earn")
    if purchases == 0 or earned == 0:
        problems.append(f"nothing to check: {purchases} purchases, {earned} coins earned")
    p50, p99, tmax, skipped = tick_stats(text)
    row.update({"sessions_dropped": len({p for p, _ in drops}), "byes_lost": byes_lost, "ledger_mismatches": mismatched,
                "purchases": purchases, "commands_applied": sum(len(applied.get(p, [])) for p in players),
                "commands_sent": sum(b["commands_sent"] for b in bots), "coins_earned": earned,
                "tick_p50_us": p50, "tick_p99_us": p99, "tick_max_us": tmax, "skipped_ticks": skipped,
                "relay_in": counters["in"], "relay_out": counters["out"], "relay_lost": counters["lost"],
                "relay_dup": counters["dup"], "relay_reordered": counters["reordered"],
                "lost_share": round(counters["lost_share"], 4), "dup_share": round(counters["dup_share"], 4),
                "reorder_share": round(counters["reorder_share"], 4),
                "snapshots_lost": sum(b["snapshots_lost"] for b in bots)})
    if not rig_ok(counters):
        problems.append(f"the relay did not impair as the cell says: {counters}")
    row["result"] = "ok" if not problems else "FAIL"
    print(f"   relay per direction: {json.dumps(counters['per_direction'])}", flush=True)
    return row, problems


def table(rows):
    head = ("| cell | impairment | bots | min | sessions dropped | ledger mismatches | purchases | commands "
            "(applied/sent) | RSS start→mid→end (max) MiB | tick p50/p99 µs | skipped ticks | relay lost / dup / "
            "reordered (share) | result |")
    out = [head, "|" + "---|" * head.count(" | ") + "---|"]
    mib = lambda k: f"{int(k) / 1024:.1f}" if k not in (None, "") else "–"
    for r in rows:
        out.append(f"| {r['cell']} | {r['impairment']} | {r['bots']} | {float(r['minutes']):g} | "
                   f"{r['sessions_dropped']} | {r['ledger_mismatches']} | {r['purchases']} | "
                   f"{r['commands_applied']}/{r['commands_sent']} | "
                   f"{mib(r['rss_start_kib'])}→{mib(r.get('rss_mid_kib'))}→{mib(r['rss_end_kib'])} "
                   f"({mib(r['rss_max_kib'])}) | "
                   f"{r['tick_p50_us']}/{r['tick_p99_us']} | {r['skipped_ticks']} | {r['relay_lost']} / "
                   f"{r['relay_dup']} / {r['relay_reordered']} ({100 * float(r['lost_share']):.1f} % / "
                   f"{100 * float(r['dup_share']):.1f} % / {100 * float(r['reorder_share']):.1f} %) | {r['result']} |")
    return "\n".join(out)


def main():
    global TIMEOUT_MS
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("cells", nargs="*")
    ap.add_argument("--out", help="append one CSV row per cell")
    ap.add_argument("--minutes", type=float, default=float(os.environ.get("FTS_SOAK_MINUTES", "10")))
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--timeout-ms", type=int, default=TIMEOUT_MS, help="the server's --timeout-ms")
    ap.add_argument("--rss-log", help="append the server's RSS each second (cell,second,KiB) to this file")
    ap.add_argument("--table", nargs="+", metavar="CSV", help="print the table of these CSV files' rows, run nothing")
    a = ap.parse_args()
    if a.table:
        print(table([r for path in a.table for r in csv.DictReader(open(path))]))
        return 0
    TIMEOUT_MS = a.timeout_ms
    cells = a.cells or [c for c in os.environ.get("FTS_SOAK_CELLS", "all").split(",") if c]
    if cells == ["all"]:
        cells = list(CELLS)
    unknown = [c for c in cells if c not in CELLS]
    if unknown:
        print(f"unknown cell(s) {unknown}; known: {', '.join(CELLS)}")
        return 2
    rows, failed = [], []
    for name in cells:
        t0 = time.monotonic()
        try:
            row, problems = run_cell(name, a.minutes, a.seed, a.rss_log)
        except Failure as e:
            print(f"FAIL {name}: {e}", flush=True)
            failed.append(name)
            continue
        rows.append(row)
        for p in problems:
            print(f"   FAIL {name}: {p}")
        if problems:
            failed.append(name)
        print(f"   {name}: {row['result']} in {time.monotonic() - t0:.0f} s", flush=True)
        if a.out:
            new = not os.path.exists(a.out) or os.path.getsize(a.out) == 0
            with open(a.out, "a", newline="") as f:
                w = csv.DictWriter(f, fieldnames=COLUMNS)
                if new:
                    w.writeheader()
                w.writerow(row)
    print(f"\nbuild {BIN}, {os.cpu_count()} CPUs, load average {os.getloadavg()[0]:.1f} (1 min) at the end\n")
    print(table(rows))
    if failed:
        print(f"\nFAIL: {', '.join(failed)}")
        return 1
    print(f"\nok: {', '.join(cells)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
