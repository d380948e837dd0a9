// The web build's serial stand-in for oneTBB's parallel_invoke: the functions in order.
#pragma once

namespace tbb {

template <class... Functions>
void parallel_invoke(const Functions&... f) {
    (f(), ...);
}

}  // namespace tbb
