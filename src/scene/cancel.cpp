// The calling thread's cancel flag (scene/cancel.h).
#include "scene/cancel.h"

namespace luz {
namespace {
thread_local const std::atomic<bool>* t_flag = nullptr;
}  // namespace

CancelScope::CancelScope(const std::atomic<bool>* flag) : previous_(t_flag) { t_flag = flag; }

CancelScope::~CancelScope() { t_flag = previous_; }

const std::atomic<bool>* cancel_flag() { return t_flag; }

void check_cancel() {
    if (cancel_requested(t_flag)) throw Cancelled{};
}

}  // namespace luz
