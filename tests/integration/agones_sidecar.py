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
Every call is recorded (time, method, path, parsed body, status). It can start late
(start(delay_s)) and fail: the first `fail_first` calls get 500.
Run alone: python3 agones_sidecar.py PORT [--fail-first N] (prints each call)."""
import json, re, sys, threading, time
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer

COUNTER = re.compile(r"^/v1beta1/counters/([a-z0-9-]+)$")
LIST = re.compile(r"^/v1beta1/lists/([a-z0-9-]+)(:addValue|:removeValue)?$")


class Sidecar:
    def __init__(self, port, fail_first=0, counters=None, lists=None, game_port=7777, fleet="fear-the-sphere",
                 name="fts-local"):
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
        self.server = None
        self.thread = None

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
        if self.server:
            self.server.shutdown()
            self.server.server_close()

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
            if c is None:
                return 404, {"error": "counter not declared"}
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
            if lst is None:
                return 404, {"error": "list not declared"}
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
                    status, reply = sidecar.handle(self.command, self.path, body if body is not None else {})
                    sidecar.calls.append({"t": time.monotonic(), "method": self.command, "path": self.path,
                                          "body": body, "status": status})
                data = json.dumps(reply).encode()
                self.send_response(status)
                self.send_header("Content-Type", "application/json")
                self.send_header("Content-Length", str(len(data)))
                self.end_headers()
                self.wfile.write(data)

            do_GET = do_POST = do_PUT = do_PATCH = _serve

            def log_message(self, *args):
                pass

        return Handler


if __name__ == "__main__":
    port = int(sys.argv[1]) if len(sys.argv) > 1 else 9358
    fail = int(sys.argv[sys.argv.index("--fail-first") + 1]) if "--fail-first" in sys.argv else 0
    s = Sidecar(port, fail_first=fail)
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
