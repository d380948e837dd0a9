// The web build's serial stand-in for oneTBB's blocked_range (WebAssembly here has no threads):
// the same interface over [begin, end), never split.
#pragma once

#include <cstddef>

namespace tbb {

template <class T>
class blocked_range {
  public:
    blocked_range(T begin, T end, std::size_t = 1) : begin_(begin), end_(end) {}
    T begin() const { return begin_; }
    T end() const { return end_; }
    std::size_t size() const { return static_cast<std::size_t>(end_ - begin_); }
    bool empty() const { return !(begin_ < end_); }

  private:
    T begin_, end_;
};

}  // namespace tbb
