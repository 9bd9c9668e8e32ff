"""docker/agones/*.yaml checked against the fields Agones requires and against what
fts-server does: UDP game port 7777 matching FTS_PORT, health checking on, the "rooms"
Counter and "players" List declared with the names the server's SDK client uses, the
autoscaler's Counter policy on a declared counter of the right Fleet, the allocation's
high-density selectors (Allocated with a free room first, then Ready), a drain grace
shorter than Kubernetes' termination grace.
  test_agones_manifests.py SOURCE_DIR"""
import os, re, sys

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


def server_names():
    """The Counter and List names the server's SDK client uses (server/fleet/agones_sync.hpp)."""
    with open(os.path.join(root, "server", "fleet", "agones_sync.hpp")) as f:
        text = f.read()
    counter = re.search(r'kRoomsCounter = "([^"]+)"', text).group(1)
    lst = re.search(r'kPlayersList = "([^"]+)"', text).group(1)
    return counter, lst


COUNTER, LIST = server_names()


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
    counters = spec.get("counters") or {}
    need(COUNTER in counters, f"{where}: counter {COUNTER!r} not declared")
    c = counters.get(COUNTER) or {}
    need(isinstance(c.get("capacity"), int) and c["capacity"] >= 1, f"{where}: {COUNTER}.capacity must be >= 1")
    need(c.get("count", 0) == 0, f"{where}: {COUNTER}.count must start at 0")
    lists = spec.get("lists") or {}
    need(LIST in lists, f"{where}: list {LIST!r} not declared")
    lcap = (lists.get(LIST) or {}).get("capacity")
    need(isinstance(lcap, int) and 1 <= lcap <= 1000, f"{where}: {LIST}.capacity must be 1..1000 (Agones' limit)")
    pod = (spec.get("template") or {}).get("spec") or {}
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
for p in fspec.get("priorities") or []:
    need(p.get("type") in ("Counter", "List") and p.get("order") in ("Ascending", "Descending"),
         f"fleet.yaml: priority {p}")

fas = load("fleetautoscaler.yaml")
need(fas.get("apiVersion") == "autoscaling.agones.dev/v1" and fas.get("kind") == "FleetAutoscaler",
     "fleetautoscaler.yaml: kind FleetAutoscaler")
aspec = fas.get("spec") or {}
need(aspec.get("fleetName") == fleet_name, f"fleetautoscaler.yaml: fleetName must be {fleet_name!r}")
policy = aspec.get("policy") or {}
need(policy.get("type") == "Counter", "fleetautoscaler.yaml: a Counter policy")
pc = policy.get("counter") or {}
need(pc.get("key") == COUNTER, f"fleetautoscaler.yaml: counter key must be {COUNTER!r}")
buf, lo, hi = pc.get("bufferSize"), pc.get("minCapacity"), pc.get("maxCapacity")
need(isinstance(buf, int) and buf >= 1, "fleetautoscaler.yaml: bufferSize >= 1")
need(isinstance(hi, int) and isinstance(lo, int) and buf is not None and buf <= lo <= hi,
     "fleetautoscaler.yaml: bufferSize <= minCapacity <= maxCapacity")

alloc = load("allocation.yaml")
need(alloc.get("apiVersion") == "allocation.agones.dev/v1" and alloc.get("kind") == "GameServerAllocation",
     "allocation.yaml: kind GameServerAllocation")
sel = (alloc.get("spec") or {}).get("selectors") or []
need(len(sel) >= 2, "allocation.yaml: two selectors (Allocated with a free room, then Ready)")
if len(sel) >= 2:
    need(sel[0].get("gameServerState") == "Allocated", "allocation.yaml: the first selector prefers Allocated")
    need(sel[-1].get("gameServerState", "Ready") == "Ready", "allocation.yaml: the last selector takes Ready")
    need(((sel[0].get("counters") or {}).get(COUNTER) or {}).get("minAvailable", 0) >= 1,
         f"allocation.yaml: the Allocated selector needs {COUNTER}.minAvailable >= 1")
for s in sel:
    labels = s.get("matchLabels") or {}
    need(labels.get("agones.dev/fleet") == fleet_name, f"allocation.yaml: selector not on fleet {fleet_name!r}")
    for k, v in labels.items():
        if k.startswith("agones.dev/sdk-"):
            # Labels the server sets itself (agones_sync.cpp): phase and version.
            need(k in ("agones.dev/sdk-phase", "agones.dev/sdk-version"), f"allocation.yaml: {k} is not set by fts-server")
            if k == "agones.dev/sdk-phase":
                need(v in ("lobby", "playing", "shop", "game_over"), f"allocation.yaml: phase {v!r} never set")
act = ((alloc.get("spec") or {}).get("counters") or {}).get(COUNTER) or {}
need(act.get("action") == "Increment" and act.get("amount", 0) >= 1, f"allocation.yaml: Increment {COUNTER} on allocation")

if problems:
    for p in problems:
        print("FAIL -", p)
    sys.exit(1)
print("ok - docker/agones manifests")
