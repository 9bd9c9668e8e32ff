#!/usr/bin/env python3
"""A seeded UDP impairment relay: loss, duplicates, reordering (random delay) and delay,
in both directions, between clients and one server. For integration tests only.

usage: relay.py --listen PORT --server HOST:PORT [--loss 0.2] [--dup 0.2]
                [--delay-ms 20] [--jitter-ms 60] [--seed 1]
Prints "relay ready port=N" on stdout once listening (PORT 0: any free port).
"""
import argparse, heapq, random, select, socket, sys, time


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--listen", type=int, default=0)
    ap.add_argument("--server", required=True)
    ap.add_argument("--loss", type=float, default=0.2)
    ap.add_argument("--dup", type=float, default=0.2)
    ap.add_argument("--delay-ms", type=float, default=20)
    ap.add_argument("--jitter-ms", type=float, default=60)
    ap.add_argument("--seed", type=int, default=1)
    a = ap.parse_args()
    host, port = a.server.rsplit(":", 1)
    server = (host, int(port))
    rng = random.Random(a.seed)
    front = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    front.bind(("127.0.0.1", a.listen))
    print(f"relay ready port={front.getsockname()[1]}", flush=True)
    uplinks = {}   # client address -> socket towards the server
    owner = {}     # uplink socket -> client address
    queue = []     # (due, seq, socket, payload, destination)
    seq = 0

    def schedule(sock, data, dest):
        nonlocal seq
        if rng.random() < a.loss:
            return
        copies = 2 if rng.random() < a.dup else 1
        for _ in range(copies):
            due = time.monotonic() + (a.delay_ms + rng.random() * a.jitter_ms) / 1000.0
            seq += 1
            heapq.heappush(queue, (due, seq, sock, data, dest))

    while True:
        timeout = max(0.0, queue[0][0] - time.monotonic()) if queue else 0.05
        ready, _, _ = select.select([front] + list(owner), [], [], timeout)
        for s in ready:
            data, addr = s.recvfrom(4096)
            if s is front:
                up = uplinks.get(addr)
                if up is None:
                    up = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
                    up.bind(("127.0.0.1", 0))
                    uplinks[addr] = up
                    owner[up] = addr
                schedule(up, data, server)
            else:
                schedule(front, data, owner[s])
        now = time.monotonic()
        while queue and queue[0][0] <= now:
            _, _, sock, data, dest = heapq.heappop(queue)
            try:
                sock.sendto(data, dest)
            except OSError:
                pass


if __name__ == "__main__":
    try:
        main()
    except KeyboardInterrupt:
        sys.exit(0)
