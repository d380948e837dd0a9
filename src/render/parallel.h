// Parallel loops over independent work items (tiles, chunks) with oneTBB, with a fixed
// thread count; results never depend on how the items were scheduled.
#pragma once

#include <sched.h>
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <thread>

namespace luz {

/// The number of threads to use for `requested` (0: all the cores this process may run on —
/// its CPU affinity, which taskset, a container's cpuset or mpirun's binding may narrow).
inline int resolve_threads(int requested) {
    if (requested > 0) return requested;
#if defined(__EMSCRIPTEN__) && !defined(__EMSCRIPTEN_PTHREADS__)
    return 1;  // WebAssembly without threads (the web page): web/serial_tbb runs the items
#else
    cpu_set_t set;
    if (sched_getaffinity(0, sizeof set, &set) == 0 && CPU_COUNT(&set) > 0) return CPU_COUNT(&set);
    const unsigned n = std::thread::hardware_concurrency();
    return n ? static_cast<int>(n) : 1;
#endif
}

/// Starts oneTBB's worker threads now and returns at once. They otherwise start at the first
/// parallel loop, which waits for them: a scene's BVH build took 1-3 ms longer on the SPD
/// scenes for it (balls: 3.4 -> 2.1 ms). Called as a scene begins to load, they start while
/// it is read.
inline void start_workers() {
#if !defined(__EMSCRIPTEN__) || defined(__EMSCRIPTEN_PTHREADS__)
    tbb::this_task_arena::enqueue([] {});
#endif
}

/// Calls body(i) for every i in [0, count), one item per task, on `threads` threads.
template <class Body>
void parallel_items(int threads, size_t count, Body&& body) {
    const int n = resolve_threads(threads);
    // Allow more threads than cores when asked for (results do not depend on it).
    const tbb::global_control allow(
        tbb::global_control::max_allowed_parallelism,
        std::max<size_t>(static_cast<size_t>(n), std::thread::hardware_concurrency()));
    tbb::task_arena arena(n);
    arena.execute([&] {
        tbb::parallel_for(
            tbb::blocked_range<size_t>(0, count, 1),
            [&](const tbb::blocked_range<size_t>& r) {
                for (size_t i = r.begin(); i != r.end(); ++i) body(i);
            },
            tbb::simple_partitioner());
    });
}

}  // namespace luz
