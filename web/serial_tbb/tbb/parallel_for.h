// The web build's serial stand-in for oneTBB's parallel_for: the body runs on the calling
// thread, items in order (luz's results never depend on the order of parallel items).
#pragma once

#include "tbb/blocked_range.h"

namespace tbb {

struct simple_partitioner {};

template <class Range, class Body>
void parallel_for(const Range& range, const Body& body) {
    body(range);
}

template <class Range, class Body>
void parallel_for(const Range& range, const Body& body, const simple_partitioner&) {
    body(range);
}

template <class Index, class Function>
void parallel_for(Index first, Index last, const Function& f) {
    for (Index i = first; i < last; ++i) f(i);
}

}  // namespace tbb
