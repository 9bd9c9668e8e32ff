"""fts-server against a stand-in Agones sidecar (agones_sidecar.py; no Kubernetes here):
  lifecycle      Ready after binding, labels, Health at the configured period while ticking
                 and none while the process is stopped (SIGSTOP), the rooms Counter and the
                 players List following bots as they come and go, Allocated seen by polling,
                 SIGTERM drains: a new player is refused, Shutdown once the last one leaves,
                 exit 0;
  late_failing   the sidecar starts 5 s late and then answers 500 three times: retried,
                 never fatal, the server plays on meanwhile;
  drain_grace    a player who never leaves: Shutdown when --drain-grace-ms runs out.
Every wait polls with a deadline."""
import json, os, signal, socket, subprocess, sys, time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from harness import BOT, Failure, Server, check, finish_bots, main, start_bots, wait_for  # noqa: E402
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


if __name__ == "__main__":
    sys.exit(main({"lifecycle": test_lifecycle, "late_failing": test_late_failing, "drain_grace": test_drain_grace}))
