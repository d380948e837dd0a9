// Parallel loops over independent work items (tiles, chunks) with oneTBB, with a fixed
// thread count; results never depend on how the items were scheduled.
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <thread>

namespace luz {

/// The number of threads to use for `requested` (0: all cores).
inline int resolve_threads(int requested) {
    if (requested > 0) return requested;
    const unsigned n = std::thread::hardware_concurrency();
    return n ? static_cast<int>(n) : 1;
}

/// Calls body(i) for every i in [0, count), one item per task, on `threads` threads.
template <class Body>
void parallel_items(int threads, size_t count, Body&& body) {
    tbb::task_arena arena(resolve_threads(threads));
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
