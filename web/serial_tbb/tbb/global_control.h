// The web build's serial stand-in for oneTBB's global_control: there is one thread to allow.
#pragma once

#include <cstddef>

namespace tbb {

class global_control {
  public:
    enum parameter { max_allowed_parallelism, thread_stack_size };
    global_control(parameter, std::size_t) {}
};

}  // namespace tbb
