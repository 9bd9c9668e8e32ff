"""Scripted sessions for the abuse tests (test_abuse.py, hostile_text_tmux.py): a client
that speaks PROTOCOL.md itself from a Python socket (sealed.Handshake: JSON or MessagePack,
sealed with PyNaCl), so that a test can send what no real client would; and what such a
test reads of the server's process."""
import socket, time

from harness import wait_for
import sealed

FLOOD_HOST = "127.0.0.2"  # another host than the real bots (127.0.0.1)


class Script:
    """One handshake from its own port (sealed.Handshake, PROTOCOL.md 5 and 5.7); resends
    its hello every 250 ms like a client. Once welcomed, `session` seals what it sends."""

    def __init__(self, port, nonce, bind=FLOOD_HOST, **hello):
        self.sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.sock.bind((bind, 0))
        self.sock.setblocking(False)
        self.server = ("127.0.0.1", port)
        self.hs = sealed.Handshake(f"script{nonce % 100}", nonce, **hello)
        self.last_hello = 0.0

    @property
    def session(self):
        return self.hs.session

    @property
    def error(self):
        return self.hs.error

    def done(self):
        return self.session is not None or self.error is not None

    def pump(self):
        while True:
            try:
                data = self.sock.recv(2048)
            except BlockingIOError:
                break
            if self.hs.receive(data):
                self.last_hello = 0.0
        if not self.done() and time.monotonic() - self.last_hello >= 0.25:
            self.sock.sendto(self.hs.hello(), self.server)
            self.last_hello = time.monotonic()

    def received(self):
        """The messages of every sealed datagram waiting (those that open)."""
        out = []
        while True:
            try:
                data = self.sock.recv(2048)
            except BlockingIOError:
                return out
            out.extend(self.session.open(data) or [])


def handshake_all(scripts, timeout_s):
    def all_done():
        for s in scripts:
            s.pump()
        return all(s.done() for s in scripts)
    wait_for(all_done, timeout_s, "every scripted handshake to end")


def sanitized(pid):
    """AddressSanitizer's quarantine and shadow memory grow with any allocation, so an
    RSS bound only means something for an unsanitized server."""
    with open(f"/proc/{pid}/maps") as f:
        return "libasan" in f.read()


def answers(script, want, timeout_s, chats=None):
    """Pumps the script's session (heartbeats carry its acks) until results for every
    rid in `want` arrived; returns {cmd rid: result}. Chat lines go to `chats`."""
    got = {}
    last = [0.0]

    def done():
        for m in script.received():
            if m.get("t") == "result":
                got.setdefault(m["cmd"], m)
            elif m.get("t") == "chat" and chats is not None and m["rid"] not in [c["rid"] for c in chats]:
                chats.append(m)
        if time.monotonic() - last[0] > 0.05:
            script.sock.sendto(script.session.datagram([{"t": "input", "ack": 0, "f": []}]), script.server)
            last[0] = time.monotonic()
        return all(r in got for r in want)
    wait_for(done, timeout_s, f"results for commands {sorted(set(want) - set(got))}")
    return got
