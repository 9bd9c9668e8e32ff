#!/usr/bin/env python3
"""End to end, issue 30: a hostile player's name and chat lines, rendered by another
player's real fts-client, never reach that player's terminal raw.

A real fts-server; a hostile player speaking the protocol from Python (test_abuse.Script
on sealed.py: the sealed handshake, MessagePack so that chat text can carry any bytes);
a real fts-client ("watcher") in a tmux pane whose every output byte is recorded with
`tmux pipe-pane` from before its first write.
  1. The hostile hello name (CSI, OSC, C1 CSI, wide CJK, RLO) is refused: bad_name.
  2. The hostile player joins by quick play under a printable name that looks like
     escapes, "EVIL]0;t[2J"; the watcher joins its room by its code and lists it.
  3. Five chat lines, each waited for on the watcher's pane in its cleaned form: CSI and
     OSC (ESC [ 2 J, ESC ] 0 ; title BEL, ESC ] 52 clipboard), C1 CSI (U+009B) and bare
     C0 (BS, CR, BEL, TAB) and DEL, wide CJK, zero-width (U+200B, U+200D, U+FEFF) and
     bidi controls (U+202E, U+2066-2069), combining marks and invalid UTF-8 (MessagePack
     str with raw bytes: FF FE, an over-long '/', a surrogate), an over-long line (200
     bytes, cut by the server; a 300-byte one is refused: field).
  4. In the same pane after the game: `fts-client --replay` of a record whose version
     string carries OSC, BEL, C1 CSI and RLO; it refuses the record on stderr. This path
     has no server in between: it is what fails if the client writes text raw.
  5. The recorded bytes: printable ASCII, CR, LF, and only the CSI sequences the client
     itself writes (ESC [, parameters 0-9 ; ? < > =, a final byte H J m h l u c: cursor
     position, erase, SGR, the alternate screen / cursor / mouse modes, the kitty
     keyboard flags and the device query, client/ui/screen.cpp, client/term/keys.cpp,
     io.cpp, terminal.cpp). No OSC (ESC ]), no other ESC, no BEL, BS or other C0, no DEL,
     no byte >= 0x80; the cleaned remnants are in the bytes as the pane shows them.
Every wait polls the pane (and pumps the hostile session) against a deadline.

usage: hostile_text_tmux.py FTS_SERVER FTS_CLIENT   (exit 77: no tmux)"""
import json, os, re, shutil, subprocess, sys, tempfile, time

sys.dont_write_bytecode = True  # run from the source tree: no __pycache__ there
HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

HOSTILE_HELLO_NAME = "\x1b[2J\x1b]0;t\x07\u009b\u202e\u65e5\u672c"
NAME = "EVIL]0;t[2J"  # printable ASCII (a name must be): what an escape leaves behind
CJK = "\u65e5\u672c\u8a9e"  # three wide characters
# (text as sent, as the server relays it and the watcher's log shows it)
CHATS = [
    ("L1 \x1b[2J\x1b[H \x1b]0;pwned\x07 \x1b]52;c;aGk=\x07 end", "L1 [2J[H ]0;pwned ]52;c;aGk= end"),
    ("L2 \u009b31m \x08\x08\r\x07 x\x7fy\tz", "L2 ?31m xy z"),
    (f"L3 {CJK} a\u200bb\u200dc\ufeffd \u202eevil\u2066x\u2067\u2068\u2069",
     "L3 ??? a?b?c?d ?evil?x???"),
    (b"L4 e\xcc\x81\xcc\xa7 \xff\xfe\xc0\xaf\xed\xa0\x80 ok", "L4 e?? ???? ok"),
    ("L5 " + CJK * 10 + "W" * 107, "L5 " + "?" * 30 + "W" * 87),  # 200 bytes in, 120 out
]
# What of each cleaned line one row of the log shows in one run of cells: L5 is wrapped
# after "L5" (the rest has no space) and again inside its W's.
RUNS = [[c] for _, c in CHATS[:4]] + [["L5", "?" * 30 + "W" * 40]]
TOO_LONG = "L6 " + "x" * 297  # over the 200 bytes a cmd's text may have: refused whole
RECORD_VERSION = "\x1b]0;pwned\x07\u009b2J\u202e"
CSI_FINALS = "HJmhluc"  # the final bytes of the sequences the client writes
CSI_PARAMS = "0123456789;?<>="


def terminal_problems(data):
    """What in `data` is more than printable ASCII, CR, LF and the client's own CSI
    sequences: a list of (offset, what), empty if nothing."""
    out = []
    i = 0
    while i < len(data):
        c = data[i]
        if 0x20 <= c < 0x7F or c in (0x0D, 0x0A):
            i += 1
            continue
        if c != 0x1B:
            out.append((i, f"byte 0x{c:02x}"))
            i += 1
            continue
        if data[i + 1:i + 2] != b"[":
            out.append((i, f"ESC followed by {data[i + 1:i + 2]!r}"))
            i += 1
            continue
        j = i + 2
        while j < len(data) and chr(data[j]) in CSI_PARAMS:
            j += 1
        if j >= len(data) or chr(data[j]) not in CSI_FINALS:
            out.append((i, f"CSI {data[i:j + 1]!r} with a final byte the client never writes"))
        i = j + 1
    return out


class Pane:
    def __init__(self, sock, name):
        self.sock, self.name = sock, name

    def tm(self, *args):
        return subprocess.run(["tmux", "-L", self.sock, *args], capture_output=True, text=True).stdout

    def text(self):
        return self.tm("capture-pane", "-p", "-t", self.name)


def main():
    # The watcher draws its field in ASCII (a UTF-8 locale would give braille dots, bytes
    # >= 0x80 of the client's own): what is checked here is the text others sent.
    os.environ["LANG"] = "C"
    for var in ("LC_ALL", "LC_CTYPE"):
        os.environ.pop(var, None)
    if len(sys.argv) != 3:
        print(__doc__.splitlines()[-1])
        return 2
    if shutil.which("tmux") is None:
        print("SKIP: tmux not installed")
        return 77
    import harness
    import sealed
    from harness import Failure, Server, check, wait_for
    from scripted import Script, answers
    harness.SERVER = os.path.abspath(sys.argv[1])
    client = os.path.abspath(sys.argv[2])
    started = time.monotonic()
    work = tempfile.mkdtemp(prefix="fts-hostile-")
    pane = Pane(f"fts-hostile-{os.getpid()}", "watcher")
    try:
        with Server() as srv:
            # 1. The hostile hello name: refused, saying why.
            bad = Script(srv.port, 0x30e0, encoding=sealed.MSGPACK)
            bad.hs.name = HOSTILE_HELLO_NAME
            wait_for(lambda: bad.pump() or bad.done(), 10, "an answer to the hostile hello name")
            check(bad.error == "bad_name", f"the hostile hello name got {bad.error!r}, session {bad.session}")
            print("the hostile hello name is refused: bad_name")

            # 2. The hostile player under a printable name, by quick play; its room's code.
            evil = Script(srv.port, 0x30e1, encoding=sealed.MSGPACK)
            evil.hs.name = NAME
            wait_for(lambda: evil.pump() or evil.done(), 10, "the hostile player's welcome")
            check(evil.session is not None, f"the hostile player was refused: {evil.error}")
            code = evil.hs.welcome.get("room", "")
            check(re.fullmatch(r"[A-Z]{5}", code) is not None, f"no room code in the welcome: {evil.hs.welcome}")
            relayed = []
            pump = lambda: answers(evil, [], 5, relayed)  # noqa: E731 (heartbeats carry its acks)

            def wait_pane(needle, seconds, what):
                def seen():  # in the pane's text, its rows joined (a log line wraps)
                    pump()
                    return needle in " ".join(pane.text().split())
                wait_for(seen, seconds, f"{what} ({needle!r}) on the watcher's pane")

            # The watcher: starts once pipe-pane records (GO), so every byte it writes is
            # in out.bin; after the game, the replay of the hostile record.
            record = os.path.join(work, "hostile.record")
            with open(record, "w") as f:
                f.write('{"fts_record":999,"version":%s,"seed":1,"config":{}}\n'
                        % json.dumps(RECORD_VERSION))
            go, out = os.path.join(work, "GO"), os.path.join(work, "out.bin")
            cmd = (f"while [ ! -e '{go}' ]; do sleep 0.02; done; TERM=xterm-256color XDG_STATE_HOME='{work}/state' "
                   f"'{client}' --connect 127.0.0.1:{srv.port} --name watcher --no-kitty --join {code}; "
                   f"echo CLIENT_EXIT=$?; '{client}' --replay '{record}'; echo REPLAY_EXIT=$?; sleep 600")
            pane.tm("new-session", "-d", "-s", "watcher", "-x", "120", "-y", "40", cmd)
            pane.tm("pipe-pane", "-o", "-t", "watcher", f"cat >> '{out}'")
            open(go, "w").close()
            wait_pane(f"Room {code}", 10, "the room code in the HUD")
            wait_pane(f"O {NAME} ", 10, "the hostile player in the legend")
            print(f"the watcher is in room {code} with {NAME}")

            # 3. The chat lines, one at a time, each seen in its cleaned form.
            def say(rid, text):
                msg = {"t": "cmd", "rid": rid, "op": "chat", "text": text}
                evil.session.seq = evil.session.seq % 65535 + 1
                seq = evil.session.seq
                # MessagePack with use_bin_type=False: bytes go as str (raw), any bytes
                # (sealed.encode would make them bin, which a text field refuses).
                body = sealed.msgpack.packb([msg], use_bin_type=False)
                head = sealed.header(evil.session.id, seq, encoding=sealed.MSGPACK)
                evil.sock.sendto(sealed.seal(evil.session.tx, sealed.C2S, seq, head, body), evil.server)
                return answers(evil, [rid], 5, relayed)[rid]

            for rid, (text, clean) in enumerate(CHATS, start=1):
                got = say(rid, text)
                check(got["ok"] and got["code"] == "ok", f"chat line {rid} answered {got}")
                wait_pane(f"{NAME}: {clean[:50]}", 5, f"chat line {rid}, cleaned")
            got = say(len(CHATS) + 1, TOO_LONG)
            check(got["code"] == "field", f"a {len(TOO_LONG)}-byte chat line answered {got}")
            texts = [c["text"] for c in relayed]
            check(texts == [c for _, c in CHATS], f"the server relayed {texts}")
            screen = pane.text()
            print("the watcher's screen at the last line:\n" + "\n".join(l.rstrip() for l in screen.splitlines()[:2] + screen.splitlines()[-4:]))

            # 4. The game ends (q asks, y quits); the hostile record is refused.
            pane.tm("send-keys", "-t", "watcher", "q")
            wait_pane("Quit?", 5, "the quit question")
            pane.tm("send-keys", "-t", "watcher", "y")
            wait_pane("CLIENT_EXIT=0", 10, "the client's exit")
            wait_pane("REPLAY_EXIT=1", 10, "the replay's refusal of the record")
            wait_for(lambda: b"REPLAY_EXIT=" in open(out, "rb").read(), 5, "the last bytes in the recording")
            refusal = [l for l in pane.text().splitlines() if "hostile.record:" in l]
            print("the replay says: " + " ".join(refusal))

        # 5. Every byte the watcher's terminal received.
        data = open(out, "rb").read()
        check(data.startswith(b"\x1b[?1049h"), f"the recording does not start with the client's first write: {data[:40]!r}")
        problems = terminal_problems(data)
        kinds = {"OSC (ESC ])": data.count(b"\x1b]"), "bytes >= 0x80": sum(b >= 0x80 for b in data),
                 "BEL": data.count(b"\x07"), "BS": data.count(b"\x08"), "DEL": data.count(b"\x7f"),
                 "ESC not followed by [": len(re.findall(rb"\x1b(?!\[)", data))}
        for offset, what in problems[:10]:
            print(f"  at byte {offset}: {what}: ...{data[max(0, offset - 20):offset + 20]!r}...")
        check(not problems and not any(kinds.values()),
              f"{len(problems)} unsafe places in the {len(data)} recorded bytes: {kinds}")
        sequences = sorted(set(re.findall(rb"\x1b\[[0-9;?<>=]*([A-Za-z])", data)))
        print(f"{len(data)} bytes recorded: printable ASCII, CR, LF and CSI sequences ending in "
              f"{b''.join(sequences).decode()}; none of {kinds}")
        # The remnants are in the bytes as drawn: the name (in the log, its colour up to the
        # colon), each line's text in runs of cells, the record's version cleaned.
        for needle in [f"{NAME}:", "]0;pwned?2J?"] + [run for runs in RUNS for run in runs]:
            check(needle.encode() in data, f"{needle!r} is not in the recorded bytes")
        print(f"PASS in {time.monotonic() - started:.1f} s")
        return 0
    except Failure as e:
        print(f"FAIL: {e}")
        print("--- the watcher's pane ---\n" + pane.text())
        return 1
    finally:
        pane.tm("kill-server")
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
