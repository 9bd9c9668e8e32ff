#!/usr/bin/env python3
"""Abuse resistance (issue 12) against a real fts-server on loopback.

address_full: 8 scripted sessions from one host (127.0.0.2) get 4 welcomes and 4
              `address_full` refusals, while a real bot from 127.0.0.1 still joins and plays.
command_flood: a scripted session sends 150 datagrams/s of 24 commands each and never
              acknowledges; it is dropped with `overflow`, the server's memory stays flat
              and a real bot plays on.
Scripted sessions speak PROTOCOL.md directly (JSON encoding) from Python sockets."""
import json, os, socket, struct, sys, time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from harness import Failure, Server, check, main, run_bots, start_bots, finish_bots, wait_for  # noqa: E402

FLOOD_HOST = "127.0.0.2"  # another host than the real bots (127.0.0.1)


def header(session=0, seq=0, ack=0, ack_bits=0):
    return b"FTSP" + struct.pack(">HBIHHIH", 2, 0, session, seq, ack, ack_bits, 0)


def parse(data):
    if len(data) < 21 or data[:4] != b"FTSP":
        return None, []
    session = struct.unpack(">I", data[7:11])[0]
    try:
        return session, json.loads(data[21:].decode())
    except ValueError:
        return session, []


def hello(nonce, cookie=""):
    msg = {"t": "hello", "name": f"script{nonce % 100}", "token": "", "cookie": cookie,
           "nonce": f"{nonce:016x}", "pad": ""}
    body = json.dumps([msg]).encode()
    msg["pad"] = "." * max(0, 512 - 21 - len(body))
    return header() + json.dumps([msg]).encode()


class Script:
    """One handshake from its own port; resends its hello every 250 ms like a client."""

    def __init__(self, port, nonce):
        self.sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.sock.bind((FLOOD_HOST, 0))
        self.sock.setblocking(False)
        self.server = ("127.0.0.1", port)
        self.nonce = nonce
        self.cookie = ""
        self.session = 0
        self.error = None
        self.last_hello = 0.0

    def done(self):
        return self.session != 0 or self.error is not None

    def pump(self):
        while True:
            try:
                data = self.sock.recv(2048)
            except BlockingIOError:
                break
            session, msgs = parse(data)
            for m in msgs:
                if m.get("t") == "challenge" and not self.cookie:
                    self.cookie = m["cookie"]
                    self.last_hello = 0.0
                elif m.get("t") == "welcome" and not self.done():
                    self.session = session
                elif m.get("t") == "error" and not self.done():
                    self.error = m["code"]
        if not self.done() and time.monotonic() - self.last_hello >= 0.25:
            self.sock.sendto(hello(self.nonce, self.cookie), self.server)
            self.last_hello = time.monotonic()


def handshake_all(scripts, timeout_s):
    def all_done():
        for s in scripts:
            s.pump()
        return all(s.done() for s in scripts)
    wait_for(all_done, timeout_s, "every scripted handshake to end")


def rss_kb(pid):
    with open(f"/proc/{pid}/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    return 0


def sanitized(pid):
    """AddressSanitizer's quarantine and shadow memory grow with any allocation, so an
    RSS bound only means something for an unsanitized server."""
    with open(f"/proc/{pid}/maps") as f:
        return "libasan" in f.read()


def test_address_full():
    with Server("--max-per-address", "4") as srv:
        scripts = [Script(srv.port, 0xab00 + i) for i in range(8)]
        handshake_all(scripts, 10)
        welcomed = [s for s in scripts if s.session]
        refused = [s.error for s in scripts if s.error]
        print(f"welcomed {len(welcomed)}, refused {refused}")
        check(len(welcomed) == 4, f"4 sessions from one host, got {len(welcomed)}")
        check(refused == ["address_full"] * 4, f"4 address_full refusals, got {refused}")
        # The welcomed scripts keep their sessions alive while a real player joins.
        bot = start_bots("--connect", srv.address, "--name", "real", "--behavior", "hunter", "--duration", "4")
        deadline = time.monotonic() + 4
        seq = 0
        while time.monotonic() < deadline:
            seq += 1
            for s in welcomed:
                s.sock.sendto(header(s.session, seq) + b'[{"t":"input","ack":0,"f":[]}]', s.server)
            time.sleep(0.1)
        rc, report, err = finish_bots(bot, 60)
        check(rc == 0, f"the real bot failed: rc {rc} {err}")
        check(report and report[0].get("snapshots_received", 0) > 0, f"the real bot got no snapshots: {report}")
        print(f"real bot: {report[0]}")


def test_command_flood():
    with Server() as srv:
        real = start_bots("--connect", srv.address, "--name", "real", "--behavior", "shopper", "--duration", "8")
        script = Script(srv.port, 0xf100d)
        handshake_all([script], 10)
        check(script.session != 0, f"the flooder was refused: {script.error}")
        rss_before = rss_kb(srv.proc.pid)
        rid = 0
        seq = 0
        sent = 0
        dropped_with = None
        start = time.monotonic()
        # The flood goes on after the drop: what follows is refused as an unknown session.
        while time.monotonic() - start < 6:
            seq = seq % 65535 + 1
            cmds = []
            for _ in range(24):  # as many as fit in 1200 bytes of JSON
                rid += 1
                cmds.append({"t": "cmd", "rid": rid, "op": "buy", "item": "m"})
            script.sock.sendto(header(script.session, seq) + json.dumps(cmds, separators=(",", ":")).encode(),
                               script.server)
            sent += 1
            try:
                while True:
                    _, msgs = parse(script.sock.recv(2048))
                    for m in msgs:
                        if m.get("t") == "error" and dropped_with is None:
                            dropped_with = m["code"]
            except BlockingIOError:
                pass
            time.sleep(1 / 150)
        elapsed = time.monotonic() - start
        rss_after = rss_kb(srv.proc.pid)
        print(f"flood: {sent} datagrams ({rid} commands) in {elapsed:.2f} s, dropped with {dropped_with}; "
              f"server RSS {rss_before} -> {rss_after} kB")
        check(dropped_with == "overflow", f"the flooder was not dropped with overflow ({dropped_with})")
        if not sanitized(srv.proc.pid):
            check(rss_after - rss_before < 4096, f"server RSS grew by {rss_after - rss_before} kB")
        wait_for(lambda: '"overflow"' in srv.text() or "overflow" in srv.text(), 5, "the overflow in the server log")
        rc, report, err = finish_bots(real, 60)
        check(rc == 0, f"the real bot failed: rc {rc} {err}")
        check(report and report[0].get("snapshots_received", 0) > 0, f"the real bot got no snapshots: {report}")


if __name__ == "__main__":
    sys.exit(main({"address_full": test_address_full, "command_flood": test_command_flood}))
