"""docker/agones/*.yaml checked against the fields Agones requires and against what
fts-server does: UDP game port 7777 matching FTS_PORT, health checking on, exactly the
Counters and Lists the server keeps (seats; rooms, players) with the names its SDK client
uses and the capacities it sets (seats = FTS_MAX_ROOMS x FTS_MAX_PLAYERS, rooms =
min(FTS_MAX_ROOMS, 1000), players = min(seats, 1000)), the autoscaler's Counter policy on a declared
counter of the right Fleet, the two allocations (quick play and create: Allocated with a free
seat and a free room slot first, the fullest first, then Ready; join code X: a rooms
containsValue selector whose placeholder is no room code), a drain grace shorter than Kubernetes' termination grace,
the hand-over to peers (issue 42: its port, secret, journal and the Service of its peers).
The GameServerAllocations are checked field by field against the keys Agones' reference
(examples/gameserverallocation.yaml, GameServerSelector) allows, so a misspelt selector
(which Agones would ignore or refuse) fails here. This is a hand-written check of the
fields we use, not Agones' own OpenAPI schema (no cluster here).
The Counters and Lists (names, kinds, capacities) come from the server's one definition
(server/fleet/fleet_names.hpp), asked of the built fts-server (--print-fleet-names, for the
manifest's FTS_MAX_ROOMS and FTS_MAX_PLAYERS): a name or capacity changed on either side
fails here.
  FTS_BIN_DIR=BUILD_DIR test_agones_manifests.py SOURCE_DIR"""
import json, os, re, subprocess, sys

try:
    import yaml
except ImportError:
    print("SKIP: PyYAML is absent (apt-get install python3-yaml; .ci/deps.sh does)")
    sys.exit(77)

root = sys.argv[1] if len(sys.argv) > 1 else "."
adir = os.path.join(root, "docker", "agones")
problems = []


def need(cond, what):
    if not cond:
        problems.append(what)
    return cond


def load(name):
    with open(os.path.join(adir, name)) as f:
        docs = [d for d in yaml.safe_load_all(f) if d is not None]
    need(len(docs) == 1, f"{name}: one document expected, got {len(docs)}")
    return docs[0]


SERVER = os.path.join(os.environ.get("FTS_BIN_DIR", os.path.join(root, "build")), "server", "fts-server")
if not os.path.exists(SERVER):
    print(f"SKIP: {SERVER} is not built (the names come from it)")
    sys.exit(77)


def server_names(max_rooms=64, max_players=8):
    """The Counters and Lists the server keeps, by what they hold (seats_taken, room_codes,
    player_names): {"kind", "name", "capacity", ...} as the built server prints them."""
    run = subprocess.run([SERVER, "--print-fleet-names", "--max-rooms", str(max_rooms), "--max-players",
                          str(max_players)], capture_output=True, text=True, timeout=60)
    if run.returncode != 0:
        print(f"FAIL - {SERVER} --print-fleet-names: exit {run.returncode}: {run.stderr.strip()}")
        sys.exit(1)
    rows = [json.loads(line) for line in run.stdout.splitlines() if line.strip()]
    return {r["holds"]: r for r in rows}


NAMES = server_names()
need(set(NAMES) == {"seats_taken", "room_codes", "player_names"}, f"the server's fleet table holds {sorted(NAMES)}")
need(NAMES["seats_taken"]["kind"] == "counter" and NAMES["room_codes"]["kind"] == "list" and
     NAMES["player_names"]["kind"] == "list", f"kinds of the server's Counters and Lists: {NAMES}")
SEATS, ROOMS, PLAYERS = (NAMES[h]["name"] for h in ("seats_taken", "room_codes", "player_names"))
LIST_MAX = 1000  # Agones' limit on one List
ROOM_CODE = re.compile(r"^[ABCDEFGHJKMNPQRSTUVWXYZ]{5}$")  # server/app/room_codes.hpp
PHASES = ("lobby", "playing", "shop", "game_over", "draining")  # the sdk-phase label's values


def check_gameserver_spec(where, spec):
    ports = spec.get("ports") or []
    need(ports, f"{where}: spec.ports is empty")
    for p in ports:
        need(p.get("name"), f"{where}: a port without a name")
        need(p.get("protocol") == "UDP", f"{where}: port {p.get('name')} protocol must be UDP, got {p.get('protocol')}")
        need(p.get("containerPort") == 7777, f"{where}: containerPort must be 7777, got {p.get('containerPort')}")
        need(p.get("portPolicy", "Dynamic") in ("Dynamic", "Static", "Passthrough", "None"),
             f"{where}: portPolicy {p.get('portPolicy')}")
    health = spec.get("health") or {}
    need(health and not health.get("disabled", False), f"{where}: health checking must be on")
    for key in ("periodSeconds", "failureThreshold", "initialDelaySeconds"):
        need(isinstance(health.get(key), int) and health.get(key) >= (0 if key == "initialDelaySeconds" else 1),
             f"{where}: health.{key} must be a positive integer")
    # The server pings every 2 s (--agones-health-ms default): well inside a period.
    need(health.get("periodSeconds", 0) * 1000 >= 2 * 2000, f"{where}: health.periodSeconds shorter than two pings")
    pod = (spec.get("template") or {}).get("spec") or {}
    env = {}
    for ct in pod.get("containers") or []:
        env.update({e["name"]: str(e.get("value", "")) for e in ct.get("env") or []})
    max_rooms, max_players = int(env.get("FTS_MAX_ROOMS", "64")), int(env.get("FTS_MAX_PLAYERS", "8"))
    # Exactly the server's Counters and Lists, each with the capacity it sets for these limits.
    want = server_names(max_rooms, max_players).values()
    for kind, key in (("counter", "counters"), ("list", "lists")):
        declared = spec.get(key) or {}
        names = sorted(r["name"] for r in want if r["kind"] == kind)
        need(sorted(declared) == names, f"{where}: {key} must be exactly {names} (fts-server's), got {sorted(declared)}")
        for r in (r for r in want if r["kind"] == kind):
            d = declared.get(r["name"]) or {}
            need(d.get("capacity") == r["capacity"],
                 f"{where}: {r['name']}.capacity must be {r['capacity_rule']} = {r['capacity']} (what fts-server sets for "
                 f"FTS_MAX_ROOMS {max_rooms}, FTS_MAX_PLAYERS {max_players}), got {d.get('capacity')}")
            need(d.get("capacity", 0) <= LIST_MAX or kind == "counter", f"{where}: {r['name']} over Agones' {LIST_MAX}")
            start = ("count", 0) if kind == "counter" else ("values", [])
            need(d.get(start[0], start[1]) == start[1], f"{where}: {r['name']}.{start[0]} must start at {start[1]!r}")
    containers = pod.get("containers") or []
    need(len(containers) == 1, f"{where}: one container expected")
    for ct in containers:
        need(ct.get("image"), f"{where}: container without an image")
        env = {e["name"]: str(e.get("value", "")) for e in ct.get("env") or []}
        need(env.get("FTS_PORT", "7777") == "7777", f"{where}: FTS_PORT must match containerPort 7777")
        need(not env.get("FTS_METRICS", "").endswith(":7777"), f"{where}: /metrics on the game port")
        need("AGONES_SDK_HTTP_PORT" not in env, f"{where}: AGONES_SDK_HTTP_PORT is Agones' to set")
        grace_ms = int(env.get("FTS_DRAIN_GRACE_MS", "25000"))
        need(pod.get("terminationGracePeriodSeconds", 30) * 1000 > grace_ms,
             f"{where}: the drain grace ({grace_ms} ms) must end before Kubernetes' terminationGracePeriodSeconds")


gs = load("gameserver.yaml")
need(gs.get("apiVersion") == "agones.dev/v1" and gs.get("kind") == "GameServer", "gameserver.yaml: kind GameServer")
check_gameserver_spec("gameserver.yaml", gs.get("spec") or {})

fleet = load("fleet.yaml")
need(fleet.get("apiVersion") == "agones.dev/v1" and fleet.get("kind") == "Fleet", "fleet.yaml: kind Fleet")
fleet_name = (fleet.get("metadata") or {}).get("name")
need(fleet_name, "fleet.yaml: metadata.name")
fspec = fleet.get("spec") or {}
need(fspec.get("scheduling", "Packed") in ("Packed", "Distributed"), "fleet.yaml: scheduling Packed or Distributed")
check_gameserver_spec("fleet.yaml template", (fspec.get("template") or {}).get("spec") or {})
need(fspec.get("template", {}).get("spec") == dict(gs["spec"]), "fleet.yaml: template differs from gameserver.yaml's spec")
DECLARED = {"Counter": set((gs["spec"].get("counters") or {})), "List": set((gs["spec"].get("lists") or {}))}
for p in fspec.get("priorities") or []:
    need(p.get("type") in ("Counter", "List") and p.get("order") in ("Ascending", "Descending"),
         f"fleet.yaml: priority {p}")
    need(p.get("key") in DECLARED.get(p.get("type"), ()), f"fleet.yaml: priority on an undeclared {p.get('type')}")

# Rooms that move (issue 42): every FTS_* variable is one of fts-server's (its flag
# reference, generated from the option table); the hand-over listens on a named TCP
# containerPort with the secret and the journal where the container mounts volumes; the
# Service that FTS_HANDOVER_TO names selects the fleet's pods on that port; the secret is
# copied to the server's own mode-0600 file by an init container (Secret files are root's).
with open(os.path.join(root, "docs", "flags", "fts-server.md")) as f:
    KNOWN_ENV = set(re.findall(r"\bFTS_[A-Z0-9_]+", f.read()))
tspec = ((fspec.get("template") or {}).get("spec") or {}).get("template", {}).get("spec", {})
for ct in tspec.get("containers") or []:
    env = {e["name"]: str(e.get("value", "")) for e in ct.get("env") or []}
    for name in env:
        need(not name.startswith("FTS_") or name in KNOWN_ENV, f"fleet.yaml: {name} is no fts-server setting")
    listen = env.get("FTS_HANDOVER_LISTEN", "")
    if not need(listen and env.get("FTS_HANDOVER_TO"), "fleet.yaml: FTS_HANDOVER_LISTEN and FTS_HANDOVER_TO"):
        continue
    need(env.get("FTS_FLEET_SECRET") and env.get("FTS_JOURNAL_DIR"),
         "fleet.yaml: the hand-over needs FTS_FLEET_SECRET and FTS_JOURNAL_DIR")
    need(env.get("FTS_RESUME") == "1", "fleet.yaml: FTS_RESUME=1 (a restarted container refuses its journals without)")
    mounts = {m["mountPath"]: m["name"] for m in ct.get("volumeMounts") or []}
    for var in ("FTS_FLEET_SECRET", "FTS_JOURNAL_DIR"):
        need(any(env.get(var, "").startswith(path.rstrip("/") + "/") or env.get(var) == path for path in mounts),
             f"fleet.yaml: {var} {env.get(var)} is on no mounted volume")
    port = int(listen.rsplit(":", 1)[1])
    named = {p.get("name"): p for p in ct.get("ports") or []}
    need(any(p.get("containerPort") == port and p.get("protocol") == "TCP" for p in named.values()),
         f"fleet.yaml: no TCP containerPort {port} for FTS_HANDOVER_LISTEN")
    svc = load("handover-service.yaml")
    need(svc.get("apiVersion") == "v1" and svc.get("kind") == "Service", "handover-service.yaml: kind Service")
    host, to_port = env["FTS_HANDOVER_TO"].rsplit(":", 1)
    need((svc.get("metadata") or {}).get("name") == host, f"handover-service.yaml: its name must be {host!r}")
    labels = ((fspec.get("template") or {}).get("metadata") or {}).get("labels") or {}
    selector = (svc.get("spec") or {}).get("selector") or {}
    need(selector and all(labels.get(k) == v for k, v in selector.items()),
         f"handover-service.yaml: selector {selector} must select the fleet's pods {labels}")
    sports = (svc.get("spec") or {}).get("ports") or []
    need(any(str(p.get("port")) == to_port and (named.get(p.get("targetPort")) or {}).get("containerPort") == port
             for p in sports), f"handover-service.yaml: port {to_port} must target the hand-over port {port}")
    secret_dir = os.path.dirname(env["FTS_FLEET_SECRET"])
    copies = [c for c in tspec.get("initContainers") or []
              if env["FTS_FLEET_SECRET"] in (c.get("command") or []) and "0600" in (c.get("command") or [])]
    need(copies and mounts.get(secret_dir), "fleet.yaml: an init container copies the secret to a mode-0600 file")

fas = load("fleetautoscaler.yaml")
need(fas.get("apiVersion") == "autoscaling.agones.dev/v1" and fas.get("kind") == "FleetAutoscaler",
     "fleetautoscaler.yaml: kind FleetAutoscaler")
aspec = fas.get("spec") or {}
need(aspec.get("fleetName") == fleet_name, f"fleetautoscaler.yaml: fleetName must be {fleet_name!r}")
policy = aspec.get("policy") or {}
need(policy.get("type") == "Counter", "fleetautoscaler.yaml: a Counter policy")
pc = policy.get("counter") or {}
need(pc.get("key") == SEATS, f"fleetautoscaler.yaml: counter key must be {SEATS!r}")
buf, lo, hi = pc.get("bufferSize"), pc.get("minCapacity"), pc.get("maxCapacity")
need(isinstance(buf, int) and buf >= 1, "fleetautoscaler.yaml: bufferSize >= 1")
need(isinstance(hi, int) and isinstance(lo, int) and buf is not None and buf <= lo <= hi,
     "fleetautoscaler.yaml: bufferSize <= minCapacity <= maxCapacity")

# The keys a GameServerAllocation may carry (Agones' reference); anything else is a typo.
ALLOC_SPEC = {"selectors", "scheduling", "priorities", "counters", "lists", "metadata", "multiClusterSetting"}
SELECTOR = {"matchLabels", "matchExpressions", "gameServerState", "players", "counters", "lists"}
SELECTOR_COUNTER = {"minCount", "maxCount", "minAvailable", "maxAvailable"}
SELECTOR_LIST = {"containsValue", "minAvailable", "maxAvailable"}
COUNTER_ACTION = {"action", "amount", "capacity"}
LIST_ACTION = {"addValues", "deleteValues", "capacity"}


def keys_in(where, obj, allowed):
    if not need(isinstance(obj, dict), f"{where}: a mapping expected, got {obj!r}"):
        return {}
    extra = set(obj) - allowed
    need(not extra, f"{where}: unknown field(s) {sorted(extra)} (allowed: {sorted(allowed)})")
    return obj


def check_allocation(name):
    alloc = load(name)
    need(alloc.get("apiVersion") == "allocation.agones.dev/v1" and alloc.get("kind") == "GameServerAllocation",
         f"{name}: kind GameServerAllocation")
    spec = keys_in(f"{name} spec", alloc.get("spec") or {}, ALLOC_SPEC)
    need(spec.get("scheduling", "Packed") in ("Packed", "Distributed"), f"{name}: scheduling {spec.get('scheduling')}")
    for p in spec.get("priorities") or []:
        keys_in(f"{name} priority", p, {"type", "key", "order"})
        need(p.get("type") in ("Counter", "List") and p.get("order") in ("Ascending", "Descending"), f"{name}: priority {p}")
        need(p.get("key") in DECLARED.get(p.get("type"), ()), f"{name}: priority on an undeclared {p.get('type')} {p.get('key')!r}")
    sel = spec.get("selectors") or []
    need(sel, f"{name}: no selectors")
    for i, s in enumerate(sel):
        where = f"{name} selector {i}"
        keys_in(where, s, SELECTOR)
        need(s.get("gameServerState", "Ready") in ("Ready", "Allocated"), f"{where}: gameServerState {s.get('gameServerState')}")
        labels = s.get("matchLabels") or {}
        need(labels.get("agones.dev/fleet") == fleet_name, f"{where}: not on fleet {fleet_name!r}")
        phase_values = [v for k, v in labels.items() if k == "agones.dev/sdk-phase"]
        for k in labels:
            if k.startswith("agones.dev/sdk-"):
                # Labels the server sets itself (agones_sync.cpp): phase and version.
                need(k in ("agones.dev/sdk-phase", "agones.dev/sdk-version"), f"{where}: {k} is not set by fts-server")
        for e in s.get("matchExpressions") or []:
            keys_in(f"{where} matchExpression", e, {"key", "operator", "values"})
            need(e.get("operator") in ("In", "NotIn", "Exists", "DoesNotExist"), f"{where}: operator {e.get('operator')}")
            if e.get("key") == "agones.dev/sdk-phase":
                phase_values += list(e.get("values") or [])
        for v in phase_values:
            need(v in PHASES, f"{where}: phase {v!r} is never set by fts-server")
        for cname, c in (s.get("counters") or {}).items():
            need(cname in DECLARED["Counter"], f"{where}: counter {cname!r} not declared")
            for k, v in keys_in(f"{where} counter {cname}", c, SELECTOR_COUNTER).items():
                need(isinstance(v, int) and v >= 0, f"{where}: {cname}.{k} must be an integer >= 0")
        for lname, l in (s.get("lists") or {}).items():
            need(lname in DECLARED["List"], f"{where}: list {lname!r} not declared")
            keys_in(f"{where} list {lname}", l, SELECTOR_LIST)
            need(isinstance(l.get("containsValue", ""), str), f"{where}: {lname}.containsValue must be a string")
    for cname, a in (spec.get("counters") or {}).items():
        need(cname in DECLARED["Counter"], f"{name}: counter action on undeclared {cname!r}")
        keys_in(f"{name} counter action {cname}", a, COUNTER_ACTION)
        need(a.get("action") in ("Increment", "Decrement") and isinstance(a.get("amount"), int) and a["amount"] >= 1,
             f"{name}: counter action {a}")
    for lname, a in (spec.get("lists") or {}).items():
        need(lname in DECLARED["List"], f"{name}: list action on undeclared {lname!r}")
        keys_in(f"{name} list action {lname}", a, LIST_ACTION)
    return spec, sel


def not_draining(s):
    return any(e.get("key") == "agones.dev/sdk-phase" and e.get("operator") == "NotIn" and "draining" in (e.get("values") or [])
               for e in s.get("matchExpressions") or [])


# Quick play: an Allocated server with a free seat and room slot first, the fullest first; then Ready.
spec, sel = check_allocation("allocation-quick.yaml")
need(len(sel) >= 2, "allocation-quick.yaml: two selectors (Allocated with a free seat, then Ready)")
if len(sel) >= 2:
    need(sel[0].get("gameServerState") == "Allocated", "allocation-quick.yaml: the first selector prefers Allocated")
    need(sel[-1].get("gameServerState", "Ready") == "Ready", "allocation-quick.yaml: the last selector takes Ready")
for i, s in enumerate(sel):
    need(((s.get("counters") or {}).get(SEATS) or {}).get("minAvailable", 0) >= 1,
         f"allocation-quick.yaml: selector {i} needs {SEATS}.minAvailable >= 1 (a free seat)")
    need(((s.get("lists") or {}).get(ROOMS) or {}).get("minAvailable", 0) >= 1,
         f"allocation-quick.yaml: selector {i} needs {ROOMS}.minAvailable >= 1 (a free room slot)")
    need(not_draining(s), f"allocation-quick.yaml: selector {i} must leave draining servers out")
need(spec.get("scheduling", "Packed") == "Packed", "allocation-quick.yaml: Packed scheduling")
need({"type": "Counter", "key": SEATS, "order": "Ascending"} in (spec.get("priorities") or []),
     f"allocation-quick.yaml: priority Counter {SEATS} Ascending (the fewest free seats first)")
act = (spec.get("counters") or {}).get(SEATS) or {}
need(act.get("action") == "Increment" and act.get("amount", 0) == 1, f"allocation-quick.yaml: Increment {SEATS} by 1")

# Join code X: every selector finds the code in the rooms List; the placeholder is no code.
spec, sel = check_allocation("allocation-join.yaml")
need(len(sel) >= 2 and sel[0].get("gameServerState") == "Allocated",
     "allocation-join.yaml: Allocated first (where rooms live), then Ready")
for i, s in enumerate(sel):
    held = ((s.get("lists") or {}).get(ROOMS) or {}).get("containsValue")
    need(held == "ROOMCODE", f"allocation-join.yaml: selector {i} needs {ROOMS}.containsValue ROOMCODE, got {held!r}")
    need(not s.get("counters"), f"allocation-join.yaml: selector {i}: a code join needs no free seat (spectators)")
    need(not_draining(s), f"allocation-join.yaml: selector {i} must leave draining servers out")
need(not ROOM_CODE.match("ROOMCODE"), "allocation-join.yaml: the placeholder must never be a real room code")
need(not spec.get("counters") and not spec.get("lists"), "allocation-join.yaml: a code join changes no Counter or List")
with open(os.path.join(adir, "allocation-join.yaml")) as f:
    need(f.read().count("ROOMCODE") >= len(sel), "allocation-join.yaml: ROOMCODE in every selector")
stale = os.path.join(adir, "allocation.yaml")
need(not os.path.exists(stale), "allocation.yaml: replaced by allocation-quick.yaml and allocation-join.yaml")

if problems:
    for p in problems:
        print("FAIL -", p)
    sys.exit(1)
print("ok - docker/agones manifests")
