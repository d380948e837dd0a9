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
    "render_1t_s": 1.52,       # demo:whitted 3200x2400, --threads 1: render seconds (stats)
    "serial_s": 0.07,          # one process: wall − render (start, PNG encode, write)
    "launch_s": 0.43,          # mpirun -np 2 start-up and MPI_Init over plain luz
    "launch_per_rank_s": 0.01,  # more per process
    "build_s": 0.0,            # scene build per process (whitted: no mesh, ~0)
    "tile_bytes": 3160,        # bytes per tile received by rank 0 (stats "mpi")
    "latency_s": 0.2e-6,       # one way (bench/mpi_pingpong: 0.33 µs round trip)
    "per_message_s": 2e-6,     # rank 0 per message (probe, receive, reply)
    "bandwidth_Bps": 12e9,     # rank 0's receive bandwidth (bench/mpi_pingpong)
    "cores": 2,
}


MAX_BATCH, LOW_WATER = 256, 8  # src/mpi/mpi_tile_share.h


def guided(left, n):
    return max(1, min(MAX_BATCH, left // (2 * n)))


def preassigned(count, n):
    return max(1, min(8, count // (4 * n)))


def simulate_pass(costs, n, threads, latency, per_message, bandwidth, speed, tile_bytes,
                  poll=50e-6):
    """Seconds of one pass over `costs` (seconds per tile at full speed, in image order) on n
    processes of `threads` threads each running at `speed` (1: a core each). Rank 0 answers
    requests between two of its tiles, and every `poll` seconds once its own are done."""
    count = len(costs)
    p = preassigned(count, n)
    queue = [list(range(r * p, min(count, (r + 1) * p))) for r in range(n)]
    next_free = min(count, n * p)
    pending = [0] * n        # finished tiles not yet sent
    out = [False] * n        # a request is out
    last_batch = [0] * n
    exhausted = [False] * n
    idle = [[] for _ in range(n)]  # threads waiting for a reply
    inbox = []               # (arrival, rank, bytes, final)
    busy0 = [0.0] * threads  # when each of rank 0's threads is free
    events = [(0.0, 0, r, t) for r in range(n) for t in range(threads)]  # (time, kind, r, t)
    heapq.heapify(events)    # kind 0: a thread is free; 1: a reply reaches rank r
    replies = {}
    finals_at = 0.0
    end = 0.0

    def answer(now):
        """Rank 0 takes in what has arrived by `now`; returns the time it spent."""
        nonlocal next_free, finals_at
        spent = 0.0
        inbox.sort()
        while inbox and inbox[0][0] <= now:
            arrival, r, nbytes, final = inbox.pop(0)
            spent += per_message + nbytes / bandwidth
            if final:
                finals_at = max(finals_at, now + spent)
                continue
            left = count - next_free
            b = guided(left, n) if left > 0 else 0
            replies[r] = list(range(next_free, min(count, next_free + b)))
            next_free += len(replies[r])
            heapq.heappush(events, (now + spent + latency, 1, r, -1))
        return spent

    def request(r, now, final=False):
        out[r] = not final
        inbox.append((now + latency + pending[r] * tile_bytes / bandwidth, r,
                      pending[r] * tile_bytes, final))
        pending[r] = 0

    while events:
        now, kind, r, t = heapq.heappop(events)
        if kind == 1:
            items = replies.pop(r)
            out[r] = False
            last_batch[r] = len(items)
            exhausted[r] = not items
            queue[r] += items
            for th in idle[r]:
                heapq.heappush(events, (now, 0, r, th))
            idle[r] = []
            if exhausted[r] and not queue[r]:
                request(r, now, final=True)  # its last tiles
            continue
        if r == 0:
            now += answer(now)
            if not queue[0] and next_free < count:
                queue[0].append(next_free)
                next_free += 1
            if queue[0]:
                i = queue[0].pop(0)
                done = now + costs[i] / speed
                end = max(end, done)
                heapq.heappush(events, (done, 0, 0, t))
            continue
        if queue[r]:
            i = queue[r].pop(0)
            if len(queue[r]) <= max(LOW_WATER, last_batch[r] // 2) and not out[r] and not exhausted[r]:
                request(r, now)
            done = now + costs[i] / speed
            pending[r] += 1
            end = max(end, done)
            heapq.heappush(events, (done, 0, r, t))
            continue
        if exhausted[r]:
            continue
        idle[r].append(t)
        if not out[r]:
            request(r, now)
        # rank 0 answers at its next tile boundary, or after a poll when it has no tiles left
        if not any(queue[0]) and next_free >= count:
            heapq.heappush(events, (now + latency + poll, 0, 0, 0))
    # the last tiles: rank 0 polls until every final has come in
    while inbox:
        now = max(end, min(a for a, *_ in inbox)) + poll / 2
        answer(now)
    return max(end, finals_at)


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
    jobs = {  # name: (compute over whitted 3200x2400 without antialiasing, tiles over it)
        "whitted 3200x2400": (1.0, 1),
        "poster 7680x4320, 256 samples per pixel": (4.32 * 256, 4),
    }
    base_costs = load_costs(M["render_1t_s"])
    for job, (scale, reps) in jobs.items():
        costs = [c * scale / reps for c in base_costs for _ in range(reps)]
        net1 = networks["InfiniBand"]
        one_pass = simulate_pass(costs, 1, 2, net1["latency_s"], net1["per_message_s"],
                                 net1["bandwidth_Bps"], 1.0, M["tile_bytes"])
        serial = M["serial_s"] * reps
        one = one_pass + serial
        print(f"\n{job}: {len(costs)} tiles; one machine, 2 threads: {one:.2f} s "
              f"(tile pass {one_pass:.2f} s)")
        print(f"{'ranks':>6s} " + " ".join(
            f"{k + ' wall s':>16s} {'speed-up':>8s} {'pass only':>9s}" for k in networks))
        for n in [8, 16, 64, 256, 1000]:
            row = f"{n:6d} "
            for net in networks.values():
                t_pass = simulate_pass(costs, n, 2, net["latency_s"], net["per_message_s"],
                                       net["bandwidth_Bps"], 1.0, M["tile_bytes"])
                launch = M["launch_s"] + 0.002 * n  # assumed: launch grows with the ranks
                w = launch + M["build_s"] + serial + t_pass
                row += f"{w:16.2f} {one / w:8.1f} {one_pass / t_pass:9.1f} "
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
