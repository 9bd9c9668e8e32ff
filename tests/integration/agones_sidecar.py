"""A stand-in for the Agones SDK sidecar's REST gateway (no Kubernetes here), serving the
endpoints fts-server uses as agones.dev documents them ("REST Game Server Client API"):
  POST /ready /health /shutdown /allocate            body {}
  PUT  /metadata/label /metadata/annotation          body {"key": K, "value": V}
  GET  /gameserver                                   {"object_meta": ..., "status": {"state": ...}}
  GET/PATCH /v1beta1/counters/NAME                   body {"count": "N", "capacity": "C"}, either or
                                                     both (int64 as strings); count outside
                                                     [0, capacity]: 400 (Agones: OUT_OF_RANGE)
  GET/PATCH /v1beta1/lists/NAME                      body {"capacity": "C", "values": [...]}: only
                                                     the fields given change (the gateway's field
                                                     mask); capacity 0..1000; values past the
                                                     capacity are cut off, as Agones does
  POST /v1beta1/lists/NAME:addValue / :removeValue   body {"value": V}; a full List: 400, a
                                                     value already there: 409, one not there: 404
A Counter or List the GameServer does not declare (Sidecar(undeclared={"seats"}), or
--undeclared NAME alone) is answered as Agones' SDK server answers it: its handler returns a
plain error ("counter not found: seats", "list not found: rooms"; pkg/sdkserver/
sdkserver.go), which gRPC reports as code 2 (Unknown) and the REST gateway as HTTP 500
with {"code": 2, "message": ..., "details": []}. declare(name) adds it later (recovery).
Every call is recorded (time, method, path, parsed body, status). It can start late
(start(delay_s)), stop and start again (a sidecar that goes away mid-run), and fail: the
first `fail_first` calls get 500. set_fault(kind) makes every call from then on fail so
(recorded with status = the kind, not applied), until set_fault(None):
  "error"     HTTP 500 with a JSON error body
  "slow"      the answer after `delay_s` (default 3 s: past the server's 2 s read timeout)
  "garbage"   bytes that are not HTTP (NUL, invalid UTF-8), then the connection closes
  "bad_json"  200 with a body that is not JSON (NUL, invalid UTF-8)
  "wrong_types" 200 with JSON of the wrong shape ({"status": {"state": 5}, ...})
  "lying"     200 with a Content-Length longer than the body, then the connection closes
  "trickle"   a status line, then a header byte every `delay_s` (default 0.5 s), never done
  "huge"      200 with a Content-Length of 1 TB, the body streamed as fast as it is read
Run alone: python3 agones_sidecar.py PORT [--fail-first N] [--fault KIND] [--undeclared NAME]...
(prints each call)."""
import json, os, re, sys, threading, time
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer

COUNTER = re.compile(r"^/v1beta1/counters/([a-z0-9-]+)$")
LIST = re.compile(r"^/v1beta1/lists/([a-z0-9-]+)(:addValue|:removeValue)?$")


class Sidecar:
    def __init__(self, port, fail_first=0, counters=None, lists=None, game_port=7777, fleet="fear-the-sphere",
                 name="fts-local", undeclared=()):
        self.port = port
        self.name = name            # metadata.name of the GameServer
        self.game_port = game_port  # status.ports[0].port: where players connect
        self.fleet = fleet          # the agones.dev/fleet label Agones puts on a Fleet's servers
        self.fail_first = fail_first
        self.lock = threading.Lock()
        self.calls = []  # dicts: t, method, path, body, status
        self.state = "Scheduled"
        self.labels = {}
        self.annotations = {}
        # As the GameServer's spec declares them (docker/agones/gameserver.yaml), with
        # capacities unlike the server's so that a test sees the server set its own.
        self.counters = counters or {"seats": {"count": 0, "capacity": 10}}
        self.lists = lists or {"rooms": {"capacity": 3, "values": []}, "players": {"capacity": 100, "values": []}}
        # Left out of the spec, as in a GameServer manifest that does not declare them.
        self.undeclared = {}
        for gone in undeclared:
            where = self.counters if gone in self.counters else self.lists
            assert gone in where, gone
            self.undeclared[gone] = (where, where.pop(gone))
        self.server = None
        self.thread = None
        self.fault = None     # see set_fault
        self.delay_s = 0.0
        self.faulted = 0      # calls answered with a fault so far

    # ---- control ------------------------------------------------------------------------
    def start(self, delay_s=0.0):
        """Serves from now, or from delay_s seconds on (a sidecar that starts late)."""
        def run():
            if delay_s:
                time.sleep(delay_s)  # simulates the late sidecar itself, not a test wait
            self.server = ThreadingHTTPServer(("127.0.0.1", self.port), self._handler())
            self.server.daemon_threads = True
            # A client that hangs up mid-answer (a server exiting) is not the test's concern.
            self.server.handle_error = lambda request, address: None
            self.server.serve_forever(poll_interval=0.05)
        self.thread = threading.Thread(target=run, daemon=True)
        self.thread.start()

    def stop(self):
        """Stops listening (a connection refused from now on); start() again serves on."""
        if self.server:
            self.server.shutdown()
            self.server.server_close()
            self.server = None

    FAULTS = {"error": 0, "slow": 3.0, "garbage": 0, "bad_json": 0, "wrong_types": 0, "lying": 0, "trickle": 0.5,
              "huge": 0}

    def set_fault(self, kind, delay_s=None):
        """Every call from now on fails as `kind` (FAULTS); None: answers as the gateway does."""
        assert kind is None or kind in self.FAULTS, kind
        with self.lock:
            self.fault = kind
            self.delay_s = self.FAULTS.get(kind, 0) if delay_s is None else delay_s

    def faulted_calls(self):
        with self.lock:
            return self.faulted

    def declare(self, name):
        """Declares a Counter or List left out by undeclared= (with its declared count/values)."""
        with self.lock:
            where, spec = self.undeclared.pop(name)
            where[name] = spec

    def set_state(self, state):
        with self.lock:
            self.state = state

    def snapshot(self):
        with self.lock:
            return list(self.calls)

    def paths(self, path):
        return [c for c in self.snapshot() if c["path"] == path and c["status"] == 200]

    # ---- the gateway --------------------------------------------------------------------
    def gameserver(self):
        return {"object_meta": {"name": self.name, "namespace": "default",
                                "labels": {"agones.dev/fleet": self.fleet,
                                           **{"agones.dev/sdk-" + k: v for k, v in self.labels.items()}},
                                "annotations": {"agones.dev/sdk-" + k: v for k, v in self.annotations.items()}},
                "status": {"state": self.state, "address": "127.0.0.1",
                           "ports": [{"name": "default", "port": self.game_port}],
                           "counters": {k: {"count": str(v["count"]), "capacity": str(v["capacity"])}
                                        for k, v in self.counters.items()},
                           "lists": {k: {"capacity": str(v["capacity"]), "values": list(v["values"])}
                                     for k, v in self.lists.items()}}}

    def handle(self, method, path, body):
        """Returns (status, response object); runs under the lock."""
        if self.fail_first > 0:
            self.fail_first -= 1
            return 500, {"error": "injected failure"}
        if method == "POST" and path in ("/ready", "/allocate", "/shutdown", "/health"):
            if body != {}:
                return 400, {"error": "body must be {}"}
            self.state = {"/ready": "Ready", "/allocate": "Allocated", "/shutdown": "Shutdown"}.get(path, self.state)
            return 200, {}
        if method == "PUT" and path in ("/metadata/label", "/metadata/annotation"):
            if set(body) != {"key", "value"}:
                return 400, {"error": "want key and value"}
            (self.labels if path.endswith("label") else self.annotations)[body["key"]] = body["value"]
            return 200, {}
        if method == "GET" and path == "/gameserver":
            return 200, self.gameserver()
        m = COUNTER.match(path)
        if m:
            c = self.counters.get(m.group(1))
            if c is None:  # what Agones answers (see the top of this file)
                return 500, {"code": 2, "message": f"counter not found: {m.group(1)}", "details": []}
            if method == "PATCH":
                fields = {k: body.get(k) for k in ("count", "capacity") if k in body}
                if not fields or set(body) - {"count", "capacity"}:
                    return 400, {"error": "want count and/or capacity"}
                if not all(isinstance(v, str) and v.isdigit() for v in fields.values()):
                    return 400, {"error": "count and capacity must be int64 strings"}
                count = int(fields.get("count", c["count"]))
                capacity = int(fields.get("capacity", c["capacity"]))
                if count > capacity:
                    return 400, {"error": "out of range: count over capacity"}
                c["count"], c["capacity"] = count, capacity
            return 200, {"name": m.group(1), "count": str(c["count"]), "capacity": str(c["capacity"])}
        m = LIST.match(path)
        if m:
            lst = self.lists.get(m.group(1))
            if lst is None:  # UpdateList says "not found. NAME List not found", the others this
                return 500, {"code": 2, "message": f"list not found: {m.group(1)}", "details": []}
            if method == "PATCH" and not m.group(2):
                if not body or set(body) - {"capacity", "values"}:
                    return 400, {"error": "want capacity and/or values"}
                if "capacity" in body:
                    cap = body["capacity"]
                    if not isinstance(cap, str) or not cap.isdigit() or int(cap) > 1000:
                        return 400, {"error": "out of range: capacity must be within [0,1000]"}
                    lst["capacity"] = int(cap)
                if "values" in body:
                    if not isinstance(body["values"], list) or not all(isinstance(v, str) for v in body["values"]):
                        return 400, {"error": "values must be strings"}
                    lst["values"] = list(dict.fromkeys(body["values"]))
                del lst["values"][lst["capacity"]:]
            elif method == "POST" and m.group(2):
                value = body.get("value")
                if not isinstance(value, str):
                    return 400, {"error": "value must be a string"}
                if m.group(2) == ":addValue":
                    if value in lst["values"]:
                        return 409, {"error": "already exists"}
                    if len(lst["values"]) >= lst["capacity"]:
                        return 400, {"error": "list full"}
                    lst["values"].append(value)
                else:
                    if value not in lst["values"]:
                        return 404, {"error": "not found"}
                    lst["values"].remove(value)
            return 200, {"name": m.group(1), "capacity": str(lst["capacity"]), "values": list(lst["values"])}
        return 404, {"error": "no such endpoint"}

    def _handler(self):
        sidecar = self

        class Handler(BaseHTTPRequestHandler):
            protocol_version = "HTTP/1.1"

            def _serve(self):
                length = int(self.headers.get("Content-Length") or 0)
                raw = self.rfile.read(length) if length else b""
                try:
                    body = json.loads(raw) if raw else None
                except ValueError:
                    body = "<not json>"
                with sidecar.lock:
                    fault, delay = sidecar.fault, sidecar.delay_s
                    if fault:
                        sidecar.faulted += 1
                        sidecar.calls.append({"t": time.monotonic(), "method": self.command, "path": self.path,
                                              "body": body, "status": fault})
                if fault:
                    return self._fault(fault, delay)
                with sidecar.lock:
                    status, reply = sidecar.handle(self.command, self.path, body if body is not None else {})
                    sidecar.calls.append({"t": time.monotonic(), "method": self.command, "path": self.path,
                                          "body": body, "status": status})
                data = json.dumps(reply).encode()
                self.send_response(status)
                self.send_header("Content-Type", "application/json")
                self.send_header("Content-Length", str(len(data)))
                self.end_headers()
                self.wfile.write(data)

            def _fault(self, fault, delay):
                self.close_connection = True
                if fault == "slow":
                    time.sleep(delay)  # the fault itself: an answer this late
                    fault = "error"
                if fault == "garbage":
                    self.wfile.write(b"\x00\xff\xfe garbage \xc3\x28 not http\r\n\r\n" + os.urandom(64))
                elif fault == "error":
                    data = b'{"error": "injected failure"}'
                    self.wfile.write(b"HTTP/1.1 500 Internal Server Error\r\nContent-Type: application/json\r\n"
                                     b"Content-Length: %d\r\n\r\n%s" % (len(data), data))
                elif fault in ("bad_json", "wrong_types", "lying"):
                    data = {"bad_json": b'{"status": {"state": [\x00\xff',
                            "wrong_types": b'{"status": {"state": 5, "ports": "x"}, "object_meta": [], "count": {}}',
                            "lying": b'{"status": {"sta'}[fault]
                    length = len(data) + (1000 if fault == "lying" else 0)
                    self.wfile.write(b"HTTP/1.1 200 OK\r\nContent-Type: application/json\r\n"
                                     b"Content-Length: %d\r\n\r\n%s" % (length, data))
                elif fault == "trickle":
                    self.wfile.write(b"HTTP/1.1 200 OK\r\n")
                    while sidecar.fault == "trickle":  # one byte of an endless header at a time
                        self.wfile.write(b"X")
                        self.wfile.flush()
                        time.sleep(delay)
                elif fault == "huge":
                    self.wfile.write(b"HTTP/1.1 200 OK\r\nContent-Type: application/json\r\n"
                                     b"Content-Length: 1000000000000\r\n\r\n")
                    chunk = b"[" * 65536
                    while sidecar.fault == "huge":
                        self.wfile.write(chunk)

            do_GET = do_POST = do_PUT = do_PATCH = _serve

            def log_message(self, *args):
                pass

        return Handler


if __name__ == "__main__":
    port = int(sys.argv[1]) if len(sys.argv) > 1 else 9358
    fail = int(sys.argv[sys.argv.index("--fail-first") + 1]) if "--fail-first" in sys.argv else 0
    gone = [sys.argv[i + 1] for i, a in enumerate(sys.argv) if a == "--undeclared"]
    s = Sidecar(port, fail_first=fail, undeclared=gone)
    if "--fault" in sys.argv:
        s.set_fault(sys.argv[sys.argv.index("--fault") + 1])
    s.start()
    seen = 0
    try:
        while True:
            time.sleep(0.2)
            calls = s.snapshot()
            for c in calls[seen:]:
                print(c["status"], c["method"], c["path"], json.dumps(c["body"]), flush=True)
            seen = len(calls)
    except KeyboardInterrupt:
        s.stop()
