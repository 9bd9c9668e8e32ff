"""fts-server against a stand-in Agones sidecar (agones_sidecar.py; no Kubernetes here):
  lifecycle      Ready after binding, labels, Health at the configured period while ticking
                 and none while the process is stopped (SIGSTOP), the rooms Counter and the
                 players List following bots as they come and go, Allocated seen by polling,
                 SIGTERM drains: a new player is refused, Shutdown once the last one leaves,
                 exit 0;
  late_failing   the sidecar starts 5 s late and then answers 500 three times: retried,
                 never fatal, the server plays on meanwhile;
  drain_grace    a player who never leaves: Shutdown when --drain-grace-ms runs out;
  rooms_list     the capacities set from --max-rooms/--max-players; quick and private rooms
                 made by bots: the rooms List holds exactly the open codes (the private one
                 too), the seats Counter the seats taken; a closed room's code goes;
  join_by_code   two servers, two sidecars: allocate() applies docker/agones/allocation-*.yaml
                 to the sidecars' GameServers as Agones would; quick play picks the fullest
                 server with a free seat and room slot, then the other once the first has
                 no slot left; "join code X" picks
                 the server holding X and a bot joins X there; an unknown code is UnAllocated;
  undeclared_counter  a GameServer without the seats Counter (the sidecar answers 500 as Agones
                 does): Ready within a second of the first call, Health at its period, the
                 Lists set; the Counter's failures retried with backoff, counted in /metrics
                 and logged once; declared later, it is set and the recovery logged;
  undeclared_list  without the rooms List: Ready, Health, the Counter and the players List
                 go on, a player is listed; SIGTERM: Shutdown does not wait for the List.
Every wait polls with a deadline."""
import json, os, re, signal, socket, subprocess, sys, time, urllib.request

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from harness import BOT, Failure, Server, check, finish_bots, free_port, main, run_bots, start_bots, wait_for  # noqa: E402
from agones_allocator import allocate, join_manifest, quick_manifest  # noqa: E402
from agones_sidecar import Sidecar  # noqa: E402

HEALTH_MS = 200


def free_tcp_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def records(srv, event):
    out = []
    for line in srv.text().splitlines():
        try:
            r = json.loads(line)
        except ValueError:
            continue
        if r.get("event") == event:
            out.append(r)
    return out


def agones_server(port, *extra):
    # An empty room closes after 1 s (not the default minute), so the rooms Counter
    # follows the bots leaving within the test's deadlines.
    return Server("--agones", str(port), "--agones-health-ms", str(HEALTH_MS), "--log-format", "json",
                  "--stats-interval-ms", "1000", "--room-idle-ms", "1000", *extra)


def players(sc):
    with sc.lock:
        return sorted(sc.lists["players"]["values"])


def seats(sc):
    with sc.lock:
        return sc.counters["seats"]["count"]


def codes(sc):
    with sc.lock:
        return sorted(sc.lists["rooms"]["values"])


def open_codes(srv):
    """The codes of the rooms open now, from the server's own room_open/room_closed records."""
    closed = {r["code"] for r in records(srv, "room_closed")}
    return sorted(r["code"] for r in records(srv, "room_open") if r["code"] not in closed)


def health_times(sc, after=0.0):
    return [c["t"] for c in sc.paths("/health") if c["t"] > after]


def test_lifecycle():
    port = free_tcp_port()
    sc = Sidecar(port)
    sc.start()
    try:
        with agones_server(port) as srv:
            wait_for(lambda: sc.paths("/ready"), 10, "POST /ready")
            wait_for(lambda: sc.labels.get("version") and sc.labels.get("phase") == "lobby", 5,
                     "the version and phase labels")
            check(seats(sc) == 0 and codes(sc) == [] and players(sc) == [],
                  "an empty server has no seats taken, no rooms and no players")

            # Health at the configured period, from the tick loop.
            t0 = time.monotonic()
            wait_for(lambda: len(health_times(sc, t0)) >= 8, 10, "8 health pings")
            ts = health_times(sc, t0)
            gaps = sorted(b - a for a, b in zip(ts, ts[1:]))
            median = gaps[len(gaps) // 2]
            check(0.15 <= median <= 0.4, f"health every {HEALTH_MS} ms expected, median gap {median:.3f} s")

            # A stopped process (a stuck loop) sends no health; it resumes after.
            os.kill(srv.proc.pid, signal.SIGSTOP)
            t_stop = time.monotonic()
            time.sleep(1.5)  # the length of the stall under test, not a wait for a result
            t_cont = time.monotonic()
            os.kill(srv.proc.pid, signal.SIGCONT)
            during = [t for t in health_times(sc, t_stop + 0.3) if t < t_cont]
            check(not during, f"{len(during)} health pings while the server was stopped")
            wait_for(lambda: health_times(sc, t_cont), 5, "health after SIGCONT")

            # Counters and Lists follow the players.
            bots = start_bots("--connect", srv.address, "--name", "ag", "--count", "2", "--behavior", "hunter",
                              "--duration", "4")
            wait_for(lambda: players(sc) == ["ag1", "ag2"] and seats(sc) == 2 and len(codes(sc)) == 1, 10,
                     "players [ag1, ag2], 2 seats and one room code in the sidecar")
            finish_bots(bots, 30)
            wait_for(lambda: players(sc) == [] and seats(sc) == 0 and codes(sc) == [], 10,
                     "no players, seats or codes after the bots left")

            # Allocated (by a GameServerAllocation) is learnt by polling GET /gameserver.
            sc.set_state("Allocated")
            wait_for(lambda: any(r.get("state") == "Allocated" for r in records(srv, "agones_state")), 10,
                     "the agones_state Allocated record")

            # SIGTERM drains: nobody new, Shutdown when the last player leaves, exit 0.
            stay = start_bots("--connect", srv.address, "--name", "dr", "--behavior", "hunter", "--duration", "5")
            wait_for(lambda: players(sc) == ["dr"], 10, "the draining test's player in the list")
            srv.proc.send_signal(signal.SIGTERM)
            wait_for(lambda: records(srv, "drain"), 5, "the drain record")
            wait_for(lambda: sc.labels.get("phase") == "draining", 5, "the phase label draining")
            late = start_bots("--connect", srv.address, "--name", "late", "--behavior", "hunter", "--duration", "3")
            rc_late, _, err_late = finish_bots(late, 30)
            check(rc_late != 0, "a player joining a draining server was accepted")
            check(any(r.get("reason") == "draining" for r in records(srv, "join_refused")),
                  "no join_refused record with reason draining")
            check(not sc.paths("/shutdown"), "Shutdown before the last player left")
            finish_bots(stay, 30)
            rc = srv.proc.wait(timeout=15)
            check(rc == 0, f"exit status {rc} after the drain")
            shutdowns = sc.paths("/shutdown")
            check(len(shutdowns) == 1, f"one POST /shutdown expected, got {len(shutdowns)}")
            check(seats(sc) == 0 and codes(sc) == [] and players(sc) == [], "counts not back to 0 before Shutdown")
            over = records(srv, "drain_over")
            check(over and over[0].get("timed_out") is False, f"drain_over should not have timed out: {over}")
            bad = [c for c in sc.snapshot() if c["status"] >= 400]
            check(not bad, f"calls the sidecar refused: {bad}")
    finally:
        sc.stop()


def test_late_failing():
    port = free_tcp_port()
    sc = Sidecar(port, fail_first=3)
    t0 = time.monotonic()
    sc.start(delay_s=5)
    try:
        with agones_server(port) as srv:
            wait_for(lambda: records(srv, "agones_retry"), 5, "an agones_retry record while the sidecar is away")
            # The game goes on meanwhile: a probe gets a snapshot.
            probe = subprocess.run([BOT, "--probe", srv.address], capture_output=True, text=True, timeout=10)
            check(probe.returncode == 0, f"probe failed while the sidecar was away: {probe.stderr}")
            wait_for(lambda: sc.paths("/ready"), 20, "POST /ready once the sidecar is up")
            check(time.monotonic() - t0 >= 5, "ready before the sidecar started?")
            failed = [c for c in sc.snapshot() if c["status"] == 500]
            check(len(failed) == 3, f"3 injected 500s expected, got {len(failed)}")
            wait_for(lambda: len(health_times(sc)) >= 3, 10, "health pings after the failures")
            check(srv.proc.poll() is None, "the server exited")
            check(srv.stop() == 0, "the server did not exit cleanly")
    finally:
        sc.stop()


def test_drain_grace():
    port = free_tcp_port()
    sc = Sidecar(port)
    sc.start()
    try:
        with agones_server(port, "--drain-grace-ms", "1500") as srv:
            wait_for(lambda: sc.paths("/ready"), 10, "POST /ready")
            stay = start_bots("--connect", srv.address, "--name", "stay", "--behavior", "hunter", "--duration", "60")
            wait_for(lambda: players(sc) == ["stay"], 10, "the player in the list")
            t_term = time.monotonic()
            srv.proc.send_signal(signal.SIGTERM)
            rc = srv.proc.wait(timeout=15)
            took = time.monotonic() - t_term
            check(rc == 0, f"exit status {rc}")
            check(took >= 1.4, f"stopped after {took:.2f} s, before the 1.5 s grace")
            check(sc.paths("/shutdown"), "no POST /shutdown")
            over = records(srv, "drain_over")
            check(over and over[0].get("timed_out") is True, f"drain_over should have timed out: {over}")
            stay[0].kill()
            stay[0].wait()
    finally:
        sc.stop()


def test_rooms_list():
    port = free_tcp_port()
    sc = Sidecar(port)
    sc.start()
    try:
        with agones_server(port, "--max-rooms", "4", "--max-players", "3") as srv:
            wait_for(lambda: sc.paths("/ready"), 10, "POST /ready")
            # The server's own limits, not the declared ones (seats 10, rooms 3).
            with sc.lock:
                caps = (sc.counters["seats"]["capacity"], sc.lists["rooms"]["capacity"], sc.lists["players"]["capacity"])
            check(caps == (12, 4, 12), f"capacities seats/rooms/players {caps}, want 4 x 3 = 12, 4, 12")
            ready_at = sc.paths("/ready")[0]["t"]
            check(all(c["t"] < ready_at for c in sc.snapshot() if c["method"] == "PATCH" and "capacity" in (c["body"] or {})),
                  "a capacity was set after Ready")

            quick = start_bots("--connect", srv.address, "--name", "qa", "--count", "2", "--room", "quick",
                               "--behavior", "hunter", "--duration", "15")
            private = start_bots("--connect", srv.address, "--name", "pb", "--count", "2", "--room", "create",
                                 "--behavior", "hunter", "--duration", "3")
            wait_for(lambda: len(open_codes(srv)) == 2 and codes(sc) == open_codes(srv) and seats(sc) == 4, 15,
                     "both rooms' codes in the rooms List and 4 seats taken")
            opened = {r["code"]: r["private"] for r in records(srv, "room_open")}
            check(sorted(opened.values()) == [False, True], f"one public and one private room expected: {opened}")
            private_code = next(c for c, p in opened.items() if p)

            # The private room empties (its bots' 3 s end) and closes after --room-idle-ms:
            # its code leaves the List, its seats the Counter.
            rc, report, err = finish_bots(private, 30)
            check(rc == 0 and {b["room"] for b in report} == {private_code}, f"private bots: {rc} {report} {err}")
            wait_for(lambda: any(r["code"] == private_code for r in records(srv, "room_closed")), 10,
                     "the private room's room_closed record")
            wait_for(lambda: codes(sc) == open_codes(srv) and private_code not in codes(sc) and seats(sc) == 2, 10,
                     "the closed room's code out of the List, 2 seats taken")
            finish_bots(quick, 30)
            wait_for(lambda: codes(sc) == [] and seats(sc) == 0, 10, "no codes and no seats once every room closed")
            bad = [c for c in sc.snapshot() if c["status"] >= 400]
            check(not bad, f"calls the sidecar refused: {bad}")
            # Removals before additions: the List never held more than its capacity.
            check(max(len(v) for v in list_history(sc, "rooms")) <= 4, "the rooms List went over its capacity")
    finally:
        sc.stop()


def list_history(sc, name):
    """The List's values after each of the server's calls to it (replayed from the record)."""
    values, out = [], []
    for c in sc.snapshot():
        if c["status"] == 200 and c["path"].startswith(f"/v1beta1/lists/{name}:"):
            (values.append if c["path"].endswith(":addValue") else values.remove)(c["body"]["value"])
            out.append(list(values))
    return out or [[]]


def test_join_by_code():
    try:
        import yaml  # noqa: F401
    except ImportError:
        print("SKIP: PyYAML is absent (apt-get install python3-yaml; .ci/deps.sh does)")
        sys.exit(77)
    ports = [free_tcp_port(), free_tcp_port()]
    sidecars = [Sidecar(p, name=n) for p, n in zip(ports, ("fts-a", "fts-b"))]
    for sc in sidecars:
        sc.start()
    stay = []
    try:
        with agones_server(ports[0], "--max-rooms", "4", "--max-players", "3") as a, \
             agones_server(ports[1], "--max-rooms", "2", "--max-players", "3") as b:
            sa, sb = sidecars
            sa.game_port, sb.game_port = a.port, b.port
            wait_for(lambda: sa.paths("/ready") and sb.paths("/ready"), 10, "both servers Ready")
            # Server a: one private room of one player; server b: one public room of two.
            stay.append(start_bots("--connect", a.address, "--name", "host", "--room", "create",
                                   "--behavior", "hunter", "--duration", "40"))
            stay.append(start_bots("--connect", b.address, "--name", "qb", "--count", "2", "--room", "quick",
                                   "--behavior", "hunter", "--duration", "40"))
            wait_for(lambda: len(codes(sa)) == 1 and seats(sa) == 1 and len(codes(sb)) == 1 and seats(sb) == 2, 15,
                     "one code and 1 seat on a, one code and 2 seats on b")
            private_code, public_code = codes(sa)[0], codes(sb)[0]
            for sc in sidecars:  # the players above were sent there by earlier allocations
                sc.set_state("Allocated")

            # Join code X: the server holding X, whatever its seats; a bot joins X there.
            got = allocate(join_manifest(private_code.lower()), sidecars)
            check(got["state"] == "Allocated" and got["sidecar"] is sa and got["port"] == a.port,
                  f"join {private_code}: {got}, want server a (port {a.port})")
            rc, report, err = run_bots("--connect", f"{got['address']}:{got['port']}", "--name", "friend",
                                       "--room", private_code, "--behavior", "hunter", "--duration", "2", timeout_s=30)
            check(rc == 0 and report and report[0]["room"] == private_code,
                  f"the friend did not play in {private_code}: {rc} {report} {err}")
            got = allocate(join_manifest(public_code), sidecars)
            check(got["sidecar"] is sb, f"join {public_code}: {got}, want server b")
            unknown = next(c for c in ("KXQPT", "MNPQR", "ZZZZZ") if c not in (private_code, public_code))
            got = allocate(join_manifest(unknown), sidecars)
            check(got["state"] == "UnAllocated" and got["sidecar"] is None, f"join of unknown {unknown}: {got}")

            # Quick play: the fullest server with a free seat and a free room slot (b: 4 of
            # 6 seats free, 1 of 2 slots; a: 11 of 12, 3 of 4), which takes the seat. b's
            # room is being played, so qq gets b's second room; then b has no slot left: a.
            got = allocate(quick_manifest(), sidecars)
            check(got["sidecar"] is sb, f"quick play: {got}, want the fullest server b")
            check(seats(sb) == 3, f"the allocation's Increment: b's seats {seats(sb)}, want 3")
            stay.append(start_bots("--connect", f"{got['address']}:{got['port']}", "--name", "qq", "--room", "quick",
                                   "--behavior", "hunter", "--duration", "40"))
            wait_for(lambda: "qq" in players(sb) and seats(sb) == 3 and len(codes(sb)) == 2, 10,
                     "qq seated on b, in b's second room")
            got = allocate(quick_manifest(), sidecars)
            check(got["sidecar"] is sa, f"quick play with b's room slots taken: {got}, want server a")
            rc, report, err = run_bots("--connect", f"{got['address']}:{got['port']}", "--name", "qa", "--room", "quick",
                                       "--behavior", "hunter", "--duration", "2", timeout_s=30)
            check(rc == 0 and report and report[0]["room"] not in (private_code, ""),
                  f"quick play on a must open a public room, not join the private one: {rc} {report} {err}")
    finally:
        for p, _ in stay:
            p.kill()
            p.wait()
        for sc in sidecars:
            sc.stop()


# ---- Counters and Lists the GameServer does not declare -----------------------------

UPDATE_FAILURES = re.compile(r'^fts_agones_update_failures_total\{([^}]*)\} ([0-9.e+-]+)$', re.M)


def update_failures(metrics_port):
    """fts_agones_update_failures_total by (kind, name), from the server's /metrics."""
    with urllib.request.urlopen(f"http://127.0.0.1:{metrics_port}/metrics", timeout=5) as r:
        body = r.read().decode()
    out = {}
    for labels, value in UPDATE_FAILURES.findall(body):
        kv = dict(re.findall(r'(\w+)="([^"]*)"', labels))
        out[(kv.get("kind"), kv.get("name"))] = float(value)
    return out


def refused(sc, path):
    return [c for c in sc.snapshot() if c["path"] == path and c["status"] == 500]


def ready_soon_and_healthy(sc, srv):
    """Ready within a second of the server's first call, then Health at its period."""
    wait_for(lambda: sc.paths("/ready"), 10, "POST /ready although a Counter or List is undeclared")
    first = sc.snapshot()[0]["t"]
    ready = sc.paths("/ready")[0]["t"]
    check(ready - first < 1.0, f"Ready {ready - first:.2f} s after the first call, want < 1 s")
    t0 = time.monotonic()
    wait_for(lambda: len(health_times(sc, t0)) >= 8, 10, "8 health pings")
    ts = health_times(sc, t0)
    gaps = sorted(b - a for a, b in zip(ts, ts[1:]))
    check(0.15 <= gaps[len(gaps) // 2] <= 0.4, f"health every {HEALTH_MS} ms expected, gaps {gaps}")


def test_undeclared_counter():
    port, mport = free_tcp_port(), free_port()
    sc = Sidecar(port, undeclared={"seats"})
    sc.start()
    try:
        with agones_server(port, "--metrics", f"127.0.0.1:{mport}") as srv:
            ready_soon_and_healthy(sc, srv)
            with sc.lock:
                caps = (sc.lists["rooms"]["capacity"], sc.lists["players"]["capacity"])
            check(caps == (64, 512), f"the Lists' capacities {caps}, want 64 and 512 beside the failing Counter")
            # Retried with backoff (100 ms doubling), counted, logged once for the spell.
            wait_for(lambda: len(refused(sc, "/v1beta1/counters/seats")) >= 4, 10, "4 tries of the seats Counter")
            wait_for(lambda: update_failures(mport).get(("counter", "seats"), 0) >= 4, 5,
                     "fts_agones_update_failures_total{kind=counter,name=seats} >= 4")
            fails = update_failures(mport)
            check(fails.get(("list", "rooms")) == 0 and fails.get(("list", "players")) == 0, f"list failures {fails}")
            tries = refused(sc, "/v1beta1/counters/seats")
            gaps = [b["t"] - a["t"] for a, b in zip(tries, tries[1:])]
            # Each wait at least the doubled one before it (100, 200, 400 ms: a late thread only adds).
            check(all(g >= 0.09 * 2 ** i for i, g in enumerate(gaps[:3])), f"no backoff between tries: {gaps}")
            failing = records(srv, "agones_update_failing")
            check(len(failing) == 1 and failing[0].get("name") == "seats" and failing[0].get("kind") == "counter",
                  f"one agones_update_failing record for the seats spell expected: {failing}")
            check(not records(srv, "agones_retry"), "the undeclared Counter held the other calls (agones_retry)")

            # Declared: the next try (within the 5 s backoff cap) sets it, the spell ends.
            sc.declare("seats")
            wait_for(lambda: sc.counters["seats"]["capacity"] == 512, 10, "the seats capacity set once declared")
            wait_for(lambda: records(srv, "agones_update_recovered"), 5, "the agones_update_recovered record")
            rec = records(srv, "agones_update_recovered")
            n = len(refused(sc, "/v1beta1/counters/seats"))
            check(len(rec) == 1 and rec[0].get("name") == "seats" and rec[0].get("failures") == n,
                  f"one agones_update_recovered with the spell's {n} failures: {rec}")
            wait_for(lambda: update_failures(mport).get(("counter", "seats")) == n, 5, f"the metric at {n}")
            check(len(records(srv, "agones_update_failing")) == 1, "a second agones_update_failing in one spell")
            check(srv.proc.poll() is None and srv.stop() == 0, "the server did not exit cleanly")
    finally:
        sc.stop()


def test_undeclared_list():
    port, mport = free_tcp_port(), free_port()
    sc = Sidecar(port, undeclared={"rooms"})
    sc.start()
    try:
        with agones_server(port, "--metrics", f"127.0.0.1:{mport}") as srv:
            ready_soon_and_healthy(sc, srv)
            check(seats(sc) == 0 and sc.counters["seats"]["capacity"] == 512, "the seats Counter not set")
            # A player: the players List and the seats Counter follow, the rooms List fails.
            bot = start_bots("--connect", srv.address, "--name", "ul", "--behavior", "hunter", "--duration", "3")
            wait_for(lambda: players(sc) == ["ul"] and seats(sc) == 1, 10, "the player listed, one seat taken")
            wait_for(lambda: update_failures(mport).get(("list", "rooms"), 0) >= 2, 10, "the rooms List's failures")
            failing = records(srv, "agones_update_failing")
            check(len(failing) == 1 and failing[0].get("name") == "rooms", f"one agones_update_failing: {failing}")
            finish_bots(bot, 30)
            wait_for(lambda: players(sc) == [] and seats(sc) == 0, 10, "the player gone from the List and Counter")
            # A drain with no player left: Shutdown, although the rooms List is still owed.
            srv.proc.send_signal(signal.SIGTERM)
            rc = srv.proc.wait(timeout=15)
            check(rc == 0, f"exit status {rc} after the drain")
            check(len(sc.paths("/shutdown")) == 1, "no POST /shutdown while the rooms List was failing")
    finally:
        sc.stop()


if __name__ == "__main__":
    sys.exit(main({"lifecycle": test_lifecycle, "late_failing": test_late_failing, "drain_grace": test_drain_grace,
                   "rooms_list": test_rooms_list, "join_by_code": test_join_by_code,
                   "undeclared_counter": test_undeclared_counter, "undeclared_list": test_undeclared_list}))
