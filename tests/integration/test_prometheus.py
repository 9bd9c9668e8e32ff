"""fts-server's /metrics scraped by Debian's real Prometheus (package prometheus): its
HTTP API must report fts_players and fts_ticks_total as the server has them. Skips
(exit 77, with a message) when the prometheus binary is absent; .ci/deps.sh installs it."""
import json, os, re, shutil, socket, subprocess, sys, tempfile, time, urllib.parse, urllib.request

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from harness import Failure, Server, check, finish_bots, start_bots, wait_for  # noqa: E402

# Every family the server exports (server/fleet/metrics.cpp).
FAMILIES = ["fts_players", "fts_rooms", "fts_draining", "fts_sessions", "fts_ticks_total", "fts_skipped_ticks_total",
            "fts_datagrams_total", "fts_bytes_total", "fts_drops_total", "fts_purchases_total",
            "fts_tick_duration_seconds_bucket", "fts_tick_duration_seconds_count"]


def free_tcp_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def http_get(url, timeout=2):
    with urllib.request.urlopen(url, timeout=timeout) as r:
        return r.read().decode()


def scrape(port):
    """The server's /metrics as {'name{labels}': value}."""
    out = {}
    for line in http_get(f"http://127.0.0.1:{port}/metrics").splitlines():
        if line and not line.startswith("#"):
            key, value = line.rsplit(" ", 1)
            out[key] = float(value)
    return out


def prom_value(prom_port, query):
    """The instant value of a PromQL query (first series), or None while there is none."""
    try:
        text = http_get(f"http://127.0.0.1:{prom_port}/api/v1/query?" + urllib.parse.urlencode({"query": query}))
    except OSError:
        return None
    data = json.loads(text)
    if data.get("status") != "success" or not data["data"]["result"]:
        return None
    return float(data["data"]["result"][0]["value"][1])


def main():
    prometheus = shutil.which("prometheus")
    if not prometheus:
        print("SKIP: the prometheus binary is absent (apt-get install prometheus; .ci/deps.sh does)")
        return 77
    metrics_port = free_tcp_port()
    prom_port = free_tcp_port()
    work = tempfile.mkdtemp(prefix="fts-prom-")
    config = os.path.join(work, "prometheus.yml")
    with open(config, "w") as f:
        f.write("global:\n  scrape_interval: 1s\n  evaluation_interval: 1s\n"
                "scrape_configs:\n  - job_name: fts\n    scrape_interval: 500ms\n    scrape_timeout: 400ms\n"
                f"    static_configs:\n      - targets: ['127.0.0.1:{metrics_port}']\n")
    prom_log = open(os.path.join(work, "prometheus.log"), "w")
    prom = None
    try:
        with Server("--metrics", f"127.0.0.1:{metrics_port}", "--stats-interval-ms", "500") as srv:
            direct = scrape(metrics_port)
            for family in FAMILIES:
                check(any(k == family or k.startswith(family + "{") for k in direct), f"/metrics lacks {family}")
            check(direct['fts_drops_total{reason="bad_cookie"}'] == 0, "drops by reason start at 0")

            prom = subprocess.Popen([prometheus, f"--config.file={config}", f"--storage.tsdb.path={work}/data",
                                     f"--web.listen-address=127.0.0.1:{prom_port}"], stdout=prom_log, stderr=prom_log)
            wait_for(lambda: prom_value(prom_port, 'up{job="fts"}') == 1, 30, "Prometheus to scrape the server (up == 1)")

            bots = start_bots("--connect", srv.address, "--name", "prom", "--count", "2", "--behavior", "hunter",
                              "--duration", "5")
            wait_for(lambda: prom_value(prom_port, "fts_players") == 2, 20, "fts_players == 2 in Prometheus")
            stats = [l for l in srv.text().splitlines() if " stats " in l]
            check(stats, "no stats line")
            # The server's own account agrees while the bots play.
            check(scrape(metrics_port)["fts_players"] == 2, "the server's /metrics disagrees: fts_players")
            wait_for(lambda: (prom_value(prom_port, 'fts_datagrams_total{direction="in"}') or 0) > 0, 10,
                     "datagrams in counted")

            # fts_ticks_total: what Prometheus stored lies between two direct reads around it.
            before = scrape(metrics_port)["fts_ticks_total"]
            wait_for(lambda: (prom_value(prom_port, "fts_ticks_total") or 0) >= before, 10,
                     "Prometheus to scrape a newer fts_ticks_total")
            stored = prom_value(prom_port, "fts_ticks_total")
            after = scrape(metrics_port)["fts_ticks_total"]
            check(before <= stored <= after, f"fts_ticks_total {stored} not within [{before}, {after}]")
            m = re.findall(r" tick=(\d+)", srv.text())
            check(m and int(m[-1]) <= after + 1, f"the log's tick {m[-1] if m else None} is past the counter {after}")

            finish_bots(bots, 30)
            wait_for(lambda: prom_value(prom_port, "fts_players") == 0, 20, "fts_players == 0 after the bots left")
            check(prom_value(prom_port, "fts_tick_duration_seconds_count") > 0, "no tick durations observed")
            check(srv.stop() == 0, "the server did not exit cleanly")
    except Failure as e:
        print(f"FAIL prometheus: {e}")
        prom_log.flush()
        with open(os.path.join(work, "prometheus.log")) as f:
            print("--- prometheus log (tail) ---\n" + "\n".join(f.read().splitlines()[-10:]))
        return 1
    finally:
        if prom:
            prom.terminate()
            try:
                prom.wait(timeout=10)
            except subprocess.TimeoutExpired:
                prom.kill()
        shutil.rmtree(work, ignore_errors=True)
    print("ok prometheus")
    return 0


if __name__ == "__main__":
    sys.exit(main())
