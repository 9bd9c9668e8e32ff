"""What the server-process benchmarks read from a running fts-server (tests/bench/*.py):
its CPU time and its last stats record (--log-format json)."""
import json, os


def cpu_s(srv):
    """User + system CPU time of the server process so far (all its threads), seconds."""
    with open(f"/proc/{srv.proc.pid}/stat") as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def last_stats(srv):
    recs = [json.loads(l) for l in srv.text().splitlines() if '"event":"stats"' in l]
    return recs[-1]
