#!/usr/bin/env python3
"""The sealed framing of PROTOCOL.md 5.7, written from the document alone with PyNaCl
(Debian: python3-nacl): the key exchange, sealing and opening datagrams, the hello's
token box, and a scripted JSON session that speaks the protocol from a Python socket.

`python3 sealed.py` checks the test vectors of PROTOCOL.md 5.7.5 and the `mv` vector of
8.2.1, packed and unpacked from the document's rules (exit status 0: they match the C++
library's)."""
import json, struct, sys

try:
    import nacl.bindings as nb
except ImportError:  # a Python of its own (pyenv, venv) next to Debian's python3-nacl
    sys.path.append("/usr/lib/python3/dist-packages")
    import nacl.bindings as nb
try:
    import msgpack  # Debian: python3-msgpack (only the MessagePack sessions need it)
except ImportError:
    if "/usr/lib/python3/dist-packages" not in sys.path:
        sys.path.append("/usr/lib/python3/dist-packages")
    try:
        import msgpack
    except ImportError:
        msgpack = None

VERSION = 3
HEADER_BYTES = 21
TAG_BYTES = 16
C2S, S2C, HELLO_TOKEN = 1, 2, 3


def header(session=0, seq=0, ack=0, ack_bits=0, delay=0, encoding=0, version=VERSION):
    return b"FTSP" + struct.pack(">HBIHHIH", version, encoding, session, seq, ack, ack_bits, delay)


JSON, MSGPACK = 0, 1  # the header's encoding flags (PROTOCOL.md 2, 3)


def encode(messages, encoding):
    if encoding == MSGPACK:
        return msgpack.packb(messages, use_bin_type=True)
    return json.dumps(messages, separators=(",", ":")).encode()


def decode(body, encoding):
    """The messages of a payload, or None if it does not parse."""
    try:
        if encoding == MSGPACK:
            return msgpack.unpackb(body, raw=False)
        return json.loads(body.decode())
    except Exception:  # ValueError, msgpack's ExtraData / UnpackValueError
        return None


def nonce(direction, sequence):
    return bytes([direction, 0, 0, 0]) + struct.pack(">Q", sequence)


def seal(key, direction, sequence, head, payload):
    return head + nb.crypto_aead_chacha20poly1305_ietf_encrypt(payload, head, nonce(direction, sequence), key)


def open_sealed(key, direction, sequence, datagram):
    """The payload, or None if the tag does not verify."""
    head = datagram[:HEADER_BYTES]
    try:
        return nb.crypto_aead_chacha20poly1305_ietf_decrypt(datagram[HEADER_BYTES:], head,
                                                            nonce(direction, sequence), key)
    except Exception:  # nacl.exceptions.CryptoError
        return None


def client_keys(client_pk, client_sk, server_pk):
    """(rx, tx) of the client."""
    return nb.crypto_kx_client_session_keys(client_pk, client_sk, server_pk)


def token_box(tx, client_pk, token):
    return nb.crypto_aead_chacha20poly1305_ietf_encrypt(token.encode(), client_pk, nonce(HELLO_TOKEN, 0), tx).hex()


def extend(wire, newest):
    candidate = (newest & ~0xFFFF) | wire
    if candidate > newest + 0x8000 and candidate >= 0x10000:
        candidate -= 0x10000
    elif candidate + 0x8000 < newest:
        candidate += 0x10000
    return candidate


class Session:
    """One client's side of a JSON session after the handshake: seals what it sends
    (its own sequence), opens what the server sends (no replay window: a test script)."""

    def __init__(self, session_id, rx, tx, encoding=JSON):
        self.id, self.rx, self.tx, self.encoding = session_id, rx, tx, encoding
        self.seq = 0
        self.newest = 0
        self.seen = set()  # extended sequences opened (for the header's ack and ack bits)

    def datagram(self, messages, seq=None):
        if seq is None:
            self.seq = self.seq % 65535 + 1
            seq = self.seq
        body = encode(messages, self.encoding)
        # Acknowledges what arrived (PROTOCOL.md 2, 6), so reliable results stop coming again.
        ack = self.newest & 0xFFFF
        bits = 0
        for i in range(32):
            if self.newest - 1 - i in self.seen:
                bits |= 1 << i
        return seal(self.tx, C2S, seq, header(self.id, seq, ack=ack, ack_bits=bits, encoding=self.encoding), body)

    def open(self, data):
        """The messages of a datagram of this session, or None."""
        if len(data) < HEADER_BYTES + TAG_BYTES or struct.unpack(">I", data[7:11])[0] != self.id:
            return None
        seq = extend(struct.unpack(">H", data[11:13])[0], self.newest)
        body = open_sealed(self.rx, S2C, seq, data)
        if body is None:
            return None
        self.newest = max(self.newest, seq)
        self.seen.add(seq)
        if len(self.seen) > 256:
            self.seen = {x for x in self.seen if x > self.newest - 64}
        return decode(body, self.encoding)


class Handshake:
    """The client side of the handshake (PROTOCOL.md 5): hellos with this attempt's key,
    the challenge's key, the sealed welcome."""

    def __init__(self, name, nonce_value, token="", encoding=JSON, join="", room=""):
        self.pk, self.sk = nb.crypto_kx_keypair()
        self.name, self.nonce, self.token = name, nonce_value, token
        self.encoding, self.join, self.room = encoding, join, room
        self.cookie = ""
        self.rx = self.tx = None
        self.session = None  # a Session once welcomed
        self.welcome = None
        self.error = None

    def hello(self):
        box = token_box(self.tx, self.pk, self.token) if self.token and self.tx else ""
        msg = {"t": "hello", "name": self.name, "token": box, "cookie": self.cookie,
               "nonce": f"{self.nonce:016x}", "key": self.pk.hex(), "pad": ""}
        if self.join:
            msg["join"], msg["room"] = self.join, self.room
        # 512 bytes at least (5.1); a longer pad may need a longer MessagePack length prefix.
        while HEADER_BYTES + len(encode([msg], self.encoding)) < 512:
            msg["pad"] += "." * (512 - HEADER_BYTES - len(encode([msg], self.encoding)))
        return header(encoding=self.encoding) + encode([msg], self.encoding)

    def receive(self, data):
        """Feeds one datagram; returns True when the hello should be sent again now."""
        if len(data) < HEADER_BYTES or data[:4] != b"FTSP":
            return False
        session = struct.unpack(">I", data[7:11])[0]
        if session == 0:
            msgs = decode(data[HEADER_BYTES:], data[6] & 3)
            for m in msgs or []:
                if m.get("t") == "challenge" and not self.cookie:
                    self.cookie = m["cookie"]
                    self.rx, self.tx = client_keys(self.pk, self.sk, bytes.fromhex(m["key"]))
                    return True
                if m.get("t") == "error" and self.error is None and self.session is None:
                    self.error = m["code"]
            return False
        if self.session is None and self.rx is not None:
            s = Session(session, self.rx, self.tx, self.encoding)
            msgs = s.open(data)
            for m in msgs or []:
                if m.get("t") == "welcome":
                    self.session, self.welcome = s, m
        return False


# ---- the packed motion entries of a snap's "mv" (PROTOCOL.md 8.2) -----------------------

def zigzag(v):
    return 2 * v if v >= 0 else -2 * v - 1


def unzigzag(u):
    return u // 2 if u % 2 == 0 else -(u + 1) // 2


class Bits:
    """Most significant bit first; Exp-Golomb codes of order k."""

    def __init__(self, data=b""):
        self.bits = [(byte >> (7 - i)) & 1 for byte in data for i in range(8)]
        self.pos = 0

    def put(self, value, n):
        self.bits += [(value >> (n - 1 - i)) & 1 for i in range(n)]

    def put_golomb(self, n, k):
        m = n + (1 << k)
        self.put(0, m.bit_length() - k - 1)
        self.put(m, m.bit_length())

    def take(self, n):
        if self.pos + n > len(self.bits):
            raise ValueError("the bin ends inside a code")
        v = 0
        for b in self.bits[self.pos:self.pos + n]:
            v = v << 1 | b
        self.pos += n
        return v

    def take_golomb(self, k):
        zeros = 0
        while self.take(1) == 0:
            zeros += 1
        return ((1 << (zeros + k)) | self.take(zeros + k)) - (1 << k)

    def padded(self):
        """The bits written, zero-padded to a byte."""
        bits = self.bits + [0] * (-len(self.bits) % 8)
        return bytes(int("".join(map(str, bits[i:i + 8])), 2) for i in range(0, len(bits), 8))


def mv_pack(rows, orders):
    """The bin of motion rows [id, ex, ey, dvx, dvy] (increasing ids) with these orders."""
    w = Bits()
    w.put_golomb(len(rows), 3)
    for k in orders:
        w.put(k, 6)
    prev = 0
    for row in rows:
        codes = [row[0] - prev - 1] + [zigzag(v) for v in row[1:]]  # the id gap as it is
        assert codes[0] >= 0, "ids in increasing order"
        prev = row[0]
        for code, k in zip(codes, orders):
            w.put_golomb(code, k)
    return w.padded()


def mv_unpack(data):
    """(rows, orders) of a bin; ValueError if it is not one."""
    r = Bits(data)
    count = r.take_golomb(3)
    orders = [r.take(6) for _ in range(5)]
    rows, prev = [], 0
    for _ in range(count):
        codes = [r.take_golomb(k) for k in orders]
        prev = prev + 1 + codes[0]
        rows.append([prev] + [unzigzag(c) for c in codes[1:]])
    if len(r.bits) - r.pos >= 8 or any(r.bits[r.pos:]):
        raise ValueError("not zero padding")
    return rows, orders


def motion_vector(path=None):
    """The rows, orders and bin of PROTOCOL.md 8.2.1, read from the document."""
    import os
    path = path or os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "protocol", "PROTOCOL.md")
    out, inside = {}, False
    for line in open(path, encoding="utf-8"):
        if line.startswith("#### 8.2.1"):
            inside = True
        elif inside and line.startswith("#"):
            break
        words = line.split()
        if inside and words and words[0] in ("rows", "orders", "bin"):
            out[words[0]] = words[1:]
    rows = [json.loads(r) for r in out["rows"]]
    return rows, [int(k) for k in out["orders"]], bytes.fromhex(out["bin"][0])


def check_motion_vector():
    rows, orders, data = motion_vector()
    ok = True
    if mv_pack(rows, orders) != data:
        print(f"mv vector: packed {mv_pack(rows, orders).hex()}, PROTOCOL.md 8.2.1 says {data.hex()}")
        ok = False
    if mv_unpack(data) != (rows, orders):
        print(f"mv vector: unpacked {mv_unpack(data)}, PROTOCOL.md 8.2.1 says {(rows, orders)}")
        ok = False
    return ok


def check_vectors():
    cpk, csk = nb.crypto_kx_seed_keypair(bytes(range(0x00, 0x20)))
    spk, ssk = nb.crypto_kx_seed_keypair(bytes(range(0x20, 0x40)))
    c_rx, c_tx = client_keys(cpk, csk, spk)
    s_rx, s_tx = nb.crypto_kx_server_session_keys(spk, ssk, cpk)
    ping = b'[{"t":"ping"}]'
    got = {
        "client pk": cpk.hex(), "server pk": spk.hex(), "client tx": c_tx.hex(), "server tx": s_tx.hex(),
        "1": seal(s_tx, S2C, 1, header(0x0a0b0c0d, 1), ping).hex(),
        "2": seal(c_tx, C2S, 0x10001, header(0x0a0b0c0d, 1, ack=1, delay=3), ping).hex(),
        "3": token_box(c_tx, cpk, "0123456789abcdef0123456789abcdef"),
    }
    want = {
        "client pk": "0e0216223f147143d32615a91189c288c1728cba3cc5f9f621b1026e03d83129",
        "server pk": "99f4674ecc87c0b8e712f192b8f49e7442a9376b4875967ababa28471019a93e",
        "client tx": "17821f6861b0f9ac897981c01cca46b711a0afd09010d3694895333903865af2",
        "server tx": "59f8af2a2061b2e35fd1cbfb708efd27a85c9924e6b83932e8a67c901a9998cb",
        "1": "465453500003000a0b0c0d00010000000000000000"
             "378ed4db2dd054b6230e0b5b0019219b7b2634477f9810a703b3097dc27e",
        "2": "465453500003000a0b0c0d00010001000000000003"
             "d825f86b42d7c4dd77d7739e15609d8f5dc6b8bf3595670d96db32e9a099",
        "3": "42d9e71714d2ea27a1fe7f940c6e93cadc1412190673465631a36f0a08cb0312"
             "bd367ef0d6350cb38c2507db15a2f231",
    }
    assert c_tx == s_rx and c_rx == s_tx
    ok_identity = check_identity_vector(cpk, spk, c_tx, s_rx)
    assert open_sealed(c_rx, S2C, 1, bytes.fromhex(want["1"])) == ping
    bad = [k for k in want if got[k] != want[k]]
    for k in bad:
        print(f"vector {k}: got {got[k]}, PROTOCOL.md says {want[k]}")
    return not bad and ok_identity


def check_identity_vector(cpk, spk, c_tx, s_rx):
    """PROTOCOL.md 5.8.3: the hello's identity proof, from the document alone."""
    import hashlib
    ipk, isk = nb.crypto_sign_seed_keypair(bytes(range(0x40, 0x60)))
    cookie = bytes.fromhex("00000000000030390123456789abcdef0123456789abcdef")
    transcript = b"fts-identity-1\x00" + cookie + cpk + spk
    signature = nb.crypto_sign(transcript, isk)[:64]
    box = nb.crypto_aead_chacha20poly1305_ietf_encrypt(ipk + signature, cpk, nonce(4, 0), c_tx)
    got = {"identity pk": ipk.hex(), "fingerprint": hashlib.blake2b(ipk, digest_size=16).hexdigest(),
           "signature": signature.hex(), "id": box.hex()}
    want = {"identity pk": "2543b92ff1095511476adc8369db6ddc933665a11978dda1404ee1066ca9559d",
            "fingerprint": "0e934e02183f97e0cd83ad10d6c4be5a",
            "signature": "1fc9b5e73f7afd32820670dbfee9135b7864d80a141c8702c1157fbfedd5c08b"
                         "d38b1fab5261680729684de4943e0c480ee66b4164ff07b169a3146f2f4b360a",
            "id": "e16a2caac55b7fd0dd8d4663428a1bd1487aa62783cc4ee7e8b50f19c0d3214b"
                  "2eeaef8066502552311a4e7e2168d3d45867ebdb211b8b4a29bb199575318aa7"
                  "47550b255c8ca20bed3fcc5e8c117ac2d9f026a45bc6a8f7019138cec0239ef1"
                  "839d24d543f5947eac7038417dd2d817"}
    opened = nb.crypto_aead_chacha20poly1305_ietf_decrypt(bytes.fromhex(want["id"]), cpk, nonce(4, 0), s_rx)
    nb.crypto_sign_open(opened[32:] + transcript, opened[:32])  # raises if it does not verify
    bad = [k for k in want if got[k] != want[k]]
    for k in bad:
        print(f"identity vector {k}: got {got[k]}, PROTOCOL.md says {want[k]}")
    return not bad


if __name__ == "__main__":
    ok = check_vectors()
    print("sealed framing test vectors:", "ok" if ok else "MISMATCH")
    mv_ok = check_motion_vector()
    print("mv test vector (8.2.1):", "ok" if mv_ok else "MISMATCH")
    sys.exit(0 if ok and mv_ok else 1)
