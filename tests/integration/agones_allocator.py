"""A matchmaker's allocator over stand-in Agones sidecars (agones_sidecar.py; no Kubernetes
here): allocate() applies a GameServerAllocation of docker/agones/ to the sidecars'
GameServers as Agones does (the selector fields our manifests use, the priorities, the
Counter actions). quick_manifest() and join_manifest(code) are the two allocations the
fleet's front end sends (docs/fleet.md)."""
import json, os, re, urllib.request

from harness import check

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
ALLOCATIONS = os.path.join(ROOT, "docker", "agones")
ROOM_CODE = re.compile(r"^[ABCDEFGHJKMNPQRSTUVWXYZ]{5}$")


def gameserver_view(sc):
    """The GameServer as Agones' allocator sees it: the sidecar's GET /gameserver."""
    with urllib.request.urlopen(f"http://127.0.0.1:{sc.port}/gameserver", timeout=5) as r:
        return json.loads(r.read())


def selects(sel, gs):
    """Whether GameServerSelector `sel` (the fields our manifests use) matches `gs`."""
    labels, status = gs["object_meta"]["labels"], gs["status"]
    if status["state"] != sel.get("gameServerState", "Ready"):
        return False
    if any(labels.get(k) != v for k, v in (sel.get("matchLabels") or {}).items()):
        return False
    for e in sel.get("matchExpressions") or []:
        have, op = labels.get(e["key"]), e["operator"]
        if (op == "In" and have not in e["values"]) or (op == "NotIn" and have in e["values"]) or \
           (op == "Exists" and have is None) or (op == "DoesNotExist" and have is not None):
            return False
    for name, f in (sel.get("counters") or {}).items():
        c = status["counters"][name]
        count, available = int(c["count"]), int(c["capacity"]) - int(c["count"])
        if count < f.get("minCount", 0) or available < f.get("minAvailable", 0):
            return False
        if ("maxCount" in f and count > f["maxCount"]) or ("maxAvailable" in f and available > f["maxAvailable"]):
            return False
    for name, f in (sel.get("lists") or {}).items():
        lst = status["lists"][name]
        available = int(lst["capacity"]) - len(lst["values"])
        if f.get("containsValue", "") and f["containsValue"] not in lst["values"]:
            return False
        if available < f.get("minAvailable", 0) or (f.get("maxAvailable", 0) and available > f["maxAvailable"]):
            return False
    return True


def available(gs, priority):
    if priority["type"] == "Counter":
        c = gs["status"]["counters"][priority["key"]]
        return int(c["capacity"]) - int(c["count"])
    lst = gs["status"]["lists"][priority["key"]]
    return int(lst["capacity"]) - len(lst["values"])


def allocate(manifest_text, sidecars):
    """Applies a GameServerAllocation to the stand-in sidecars as Agones does: the first
    selector that matches any server wins; its matches are ordered by the priorities
    ("Ascending": the least available first; Packed's node packing does not apply, all
    run on one host), the first is Allocated and the Counter actions applied to it.
    Returns {"state", "address", "port", "sidecar"}; state UnAllocated when none matched."""
    import yaml  # checked by the caller
    spec = yaml.safe_load(manifest_text)["spec"]
    views = [(sc, gameserver_view(sc)) for sc in sidecars]
    for sel in spec["selectors"]:
        matched = [(sc, gs) for sc, gs in views if selects(sel, gs)]
        if not matched:
            continue
        order = spec.get("priorities") or []
        matched.sort(key=lambda v: ([available(v[1], p) * (1 if p["order"] == "Ascending" else -1) for p in order],
                                    v[1]["object_meta"]["name"]))
        sc, gs = matched[0]
        with sc.lock:
            sc.state = "Allocated"
            for name, act in (spec.get("counters") or {}).items():
                c = sc.counters[name]
                step = act["amount"] if act["action"] == "Increment" else -act["amount"]
                c["count"] = max(0, min(c["capacity"], c["count"] + step))
        return {"state": "Allocated", "address": gs["status"]["address"], "port": gs["status"]["ports"][0]["port"],
                "sidecar": sc}
    return {"state": "UnAllocated", "address": "", "port": None, "sidecar": None}


def quick_manifest():
    with open(os.path.join(ALLOCATIONS, "allocation-quick.yaml")) as f:
        return f.read()


def join_manifest(typed):
    """allocation-join.yaml with the code in, as README's front end does (checked, then sed)."""
    code = typed.strip().upper()
    check(ROOM_CODE.match(code), f"not a room code: {typed!r}")
    with open(os.path.join(ALLOCATIONS, "allocation-join.yaml")) as f:
        return f.read().replace("ROOMCODE", code)
