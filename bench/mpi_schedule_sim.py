#!/usr/bin/env python3
"""A simulation of luz-mpi's tile scheduler (src/mpi/mpi_tile_share.cpp), for docs/SCALING.md.

It replays the protocol — P tiles per process given out in advance, then requests to rank 0
carrying the finished tiles' bytes, answered one at a time by rank 0's server thread with
guided batches (remaining / 2N, 1 … 64), rank 0's own threads taking tiles without messages —
as a discrete-event simulation over the real per-tile costs of a render (from its `tests`
term, a cost proxy, scaled to its measured single-thread time), and adds the parts that do
not divide: launch, each process's scene build, rank 0's encoding and writing.

    bench/mpi_schedule_sim.py calibrate TESTS.pfm        # tile costs → tiles.json
    bench/mpi_schedule_sim.py machine                    # this machine: 1..4 processes
    bench/mpi_schedule_sim.py cluster                    # 8 … 1000 ranks of 2 cores

Constants (measured on this machine, docs/SCALING.md) are at the top; `cluster` uses a
network's latency and bandwidth instead of shared memory's.
"""
import heapq
import json
import math
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
TILES = os.path.join(HERE, "mpi_tiles.json")

# --- measured on this machine (docs/SCALING.md, bench/mpi_scaling.sh, bench/mpi_pingpong) ---
M = {
    "render_1t_s": 4.0,        # demo:whitted 3200x2400, --threads 1: render seconds (stats)
    "serial_s": 0.9,           # one process: wall − render (start, build, PNG encode, write)
    "launch_s": 0.35,          # mpirun start-up over plain luz (−np 2)
    "launch_per_rank_s": 0.02,  # more per process
    "build_s": 0.0,            # scene build per process (whitted: no mesh, ~0)
    "tile_bytes": 3092,        # bytes per tile received by rank 0 (stats mpi)
    "latency_s": 60e-6,        # one way, request or reply: the polls' back-off dominates
    "per_message_s": 5e-6,     # rank 0's server per message
    "bandwidth_Bps": 6.0e9,    # rank 0's receive bandwidth (shared memory)
    "cores": 2,
}


def guided(left, n):
    return max(1, min(64, left // (2 * n)))


def preassigned(count, n):
    return max(1, min(8, count // (4 * n)))


def simulate_pass(costs, n, threads, latency, per_message, bandwidth, speed, tile_bytes):
    """Seconds of one pass over `costs` (seconds per tile at full speed) on n processes of
    `threads` threads each running at `speed` (1: a core each)."""
    count = len(costs)
    p = preassigned(count, n)
    queues = [list(range(r * p, min(count, (r + 1) * p))) for r in range(n)]
    for q in queues:
        q.reverse()
    next_free = min(count, n * p)
    pending = [0] * n          # finished tiles not yet sent, per rank
    requesting = [False] * n   # a request is out
    waiting = [[] for _ in range(n)]
    exhausted = [False] * n
    server_free = 0.0
    events = []  # (time, kind, rank, thread)
    for r in range(n):
        for t in range(threads):
            heapq.heappush(events, (0.0, 0, r, t))  # 0: thread free
    end = 0.0
    finals = 0

    def serve(arrival, nbytes):
        nonlocal server_free
        start = max(arrival, server_free)
        server_free = start + per_message + nbytes / bandwidth
        return server_free

    while events:
        time, kind, r, t = heapq.heappop(events)
        if kind == 1:  # a reply reached rank r
            left = count - next_free
            b = guided(left, n) if left > 0 else 0
            items = list(range(next_free, min(count, next_free + b)))
            next_free += len(items)
            requesting[r] = False
            if not items:
                exhausted[r] = True
                # final: what is pending goes to rank 0 when the rank's threads are done
            queues[r] = items[::-1] + queues[r]
            for th in waiting[r]:
                heapq.heappush(events, (time, 0, r, th))
            waiting[r] = []
            continue
        # a thread of rank r is free at `time`
        if queues[r]:
            i = queues[r].pop()
            heapq.heappush(events, (time + costs[i] / speed, 0, r, t))
            pending[r] += 1
            end = max(end, time + costs[i] / speed)
            continue
        if r == 0:
            if next_free < count:
                i = next_free
                next_free += 1
                heapq.heappush(events, (time + costs[i] / speed, 0, r, t))
                end = max(end, time + costs[i] / speed)
            continue
        if exhausted[r]:
            continue
        waiting[r].append(t)
        if not requesting[r]:
            requesting[r] = True
            nbytes = pending[r] * tile_bytes
            pending[r] = 0
            done = serve(time + latency, nbytes)
            heapq.heappush(events, (done + latency, 1, r, -1))
    # finals: each rank's last tiles reach rank 0
    for r in range(1, n):
        if pending[r]:
            end = max(end, serve(end + latency, pending[r] * tile_bytes))
    return max(end, server_free)


def load_costs(total_seconds):
    d = json.load(open(TILES))
    w = np.array(d["weights"], dtype=float)
    return list(w / w.sum() * total_seconds)


def wall(costs, n, threads, net, speed, serial, launch, build):
    return (launch + build + serial +
            simulate_pass(costs, n, threads, net["latency_s"], net["per_message_s"],
                          net["bandwidth_Bps"], speed, M["tile_bytes"]))


def machine():
    costs = load_costs(M["render_1t_s"])
    print(f"{'run':28s} {'simulated_s':>11s}")
    for n, threads in [(1, 2), (2, 1), (1, 1), (3, 1), (4, 1), (2, 2)]:
        speed = min(1.0, M["cores"] / (n * threads))
        launch = 0.0 if (n, threads) in [(1, 2), (1, 1)] else M["launch_s"] + M["launch_per_rank_s"] * (n - 2)
        w = wall(costs, n, threads, M, speed, M["serial_s"], launch, M["build_s"])
        print(f"{n} x {threads} thread(s){'':14s} {w:11.2f}")


def cluster():
    networks = {
        "10GbE": {"latency_s": 25e-6, "per_message_s": 5e-6, "bandwidth_Bps": 1.1e9},
        "InfiniBand": {"latency_s": 2e-6, "per_message_s": 2e-6, "bandwidth_Bps": 11e9},
    }
    jobs = {  # name: (scale of compute over whitted 3200x2400 none, tiles scale)
        "whitted 3200x2400": (1.0, 1),
        "poster 7680x4320, 256 spp": (4.32 * 256 * 1.0, 4.32),
    }
    base_costs = load_costs(M["render_1t_s"])
    for job, (scale, tiles_scale) in jobs.items():
        reps = int(round(tiles_scale))
        costs = [c * scale / reps for c in base_costs for _ in range(reps)]
        one = wall(costs, 1, 2, networks["InfiniBand"], 1.0, M["serial_s"] * tiles_scale, 0, 0)
        print(f"\n{job}: one machine (2 threads) {one:.1f} s")
        print(f"{'ranks':>6s} " + " ".join(f"{k + ' s':>14s} {'speed-up':>8s}" for k in networks))
        for n in [8, 16, 64, 256, 1000]:
            row = f"{n:6d} "
            for net in networks.values():
                launch = M["launch_s"] + 0.002 * n  # launch grows with the ranks (tree spawn)
                w = wall(costs, n, 2, net, 1.0, M["serial_s"] * tiles_scale, launch, M["build_s"])
                row += f"{w:14.2f} {one / w:8.1f} "
            print(row)


def calibrate(pfm):
    with open(pfm, "rb") as f:
        kind = f.readline().strip()
        w, h = map(int, f.readline().split())
        scale = float(f.readline())
        data = np.frombuffer(f.read(), dtype="<f4" if scale < 0 else ">f4")
    img = data.reshape(h, w, 3 if kind == b"PF" else 1)[::-1, :, 0]
    T = 16
    weights = []
    for ty in range(0, h, T):
        for tx in range(0, w, T):
            tile = img[ty:ty + T, tx:tx + T]
            weights.append(float(tile.sum() + 20.0 * tile.size))  # tests + a per-pixel constant
    json.dump({"source": os.path.basename(pfm), "tile": T, "weights": weights}, open(TILES, "w"))
    print(f"{len(weights)} tiles → {TILES}")


if __name__ == "__main__":
    cmd = sys.argv[1] if len(sys.argv) > 1 else "machine"
    if cmd == "calibrate":
        calibrate(sys.argv[2])
    elif cmd == "machine":
        machine()
    else:
        cluster()
