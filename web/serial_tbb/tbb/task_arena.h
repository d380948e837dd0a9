// The web build's serial stand-in for oneTBB's task_arena: one thread, the caller's.
#pragma once

namespace tbb {

class task_arena {
  public:
    explicit task_arena(int = 1) {}
    template <class F>
    auto execute(const F& f) const {
        return f();
    }
};

namespace this_task_arena {
inline int max_concurrency() { return 1; }
}  // namespace this_task_arena

}  // namespace tbb
