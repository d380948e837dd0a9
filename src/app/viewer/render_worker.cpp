// The viewer's background render thread and its progressive passes.
#include "app/viewer/render_worker.h"

#include <chrono>

#include "luz/luz.h"
#include "luz/pictures.h"

namespace luz {

namespace {

int64_t now_ns() {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(
               std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

}  // namespace

std::vector<PassPlan> plan_passes(const Settings& desc) {
    std::vector<PassPlan> plan;
    const int smaller = std::min(desc.image.width, desc.image.height);
    if (smaller >= 64) plan.push_back({8, false});
    if (smaller >= 16) plan.push_back({2, false});
    plan.push_back({1, false});
    if (desc.render.antialias.mode != AaMode::none) plan.push_back({1, true});
    return plan;
}

bool render_pass(const Scene& scene, const Settings& settings, const PassPlan& plan, int threads,
                 const std::atomic<bool>* cancel, RenderFrame& out, Showing show) {
    // The pass's resolution and antialiasing, on a copy of the settings: the scene (shapes,
    // BVH) does not depend on them.
    Settings pass = settings;
    pass.image.width = std::max(1, settings.image.width / plan.divisor);
    pass.image.height = std::max(1, settings.image.height / plan.divisor);
    if (!plan.antialiased) pass.render.antialias.mode = AaMode::none;

    RenderOptions options;
    options.threads = threads;
    options.cancel = cancel;
    if (show.term) options.aovs = {show.kind};
    Frame frame = render(scene, pass, options);
    if (show.term && !frame.aovs.empty()) {
        Aov& a = frame.aovs.front();
        out.image = a.scalar() || a.kind == AovKind::normal ? aov_picture(a) : std::move(a.image);
    } else {
        out.image = std::move(frame.image);
    }
    out.divisor = plan.divisor;
    out.antialiased = plan.antialiased;
    out.seconds = frame.stats.seconds;
    const RenderStats& stats = frame.stats;
    const uint64_t rays =
        stats.rays_primary + stats.rays_shadow + stats.rays_reflection + stats.rays_refraction;
    out.rays = rays > 0 ? rays : stats.samples;
    return frame.complete;
}

RenderWorker::RenderWorker(int threads) : threads_(threads) {
    thread_ = std::thread([this] { run(); });
}

RenderWorker::~RenderWorker() {
    {
        std::lock_guard lock(mutex_);
        quit_ = true;
        cancel_ = true;
    }
    wake_.notify_all();
    thread_.join();
}

uint64_t RenderWorker::submit(Scene scene, Settings settings, Showing show) {
    uint64_t g;
    {
        std::lock_guard lock(mutex_);
        pending_ = Job{std::move(scene), std::move(settings), show};
        g = ++generation_;
        cancel_requested_ns_ = now_ns();
        cancel_ = true;  // the render under way stops at its next tile
    }
    wake_.notify_all();
    return g;
}

bool RenderWorker::take_frame(RenderFrame& out) {
    std::lock_guard lock(mutex_);
    if (!has_frame_) return false;
    out = std::move(frame_);
    has_frame_ = false;
    return true;
}

void RenderWorker::run() {
    std::optional<Job> job;
    uint64_t generation = 0;
    for (;;) {
        {
            std::unique_lock lock(mutex_);
            wake_.wait(lock, [&] { return quit_ || pending_.has_value(); });
            if (quit_) return;
            job = std::move(pending_);
            pending_.reset();
            generation = generation_;
            cancel_ = false;
        }
        const std::vector<PassPlan> plan = plan_passes(job->settings);
        bool finished = true;
        double first_seconds = 0;
        for (size_t i = 0; i < plan.size(); ++i) {
            RenderFrame frame;
            if (!render_pass(job->scene, job->settings, plan[i], threads_, &cancel_, frame,
                             job->show)) {
                cancel_latency_ =
                    static_cast<double>(now_ns() - cancel_requested_ns_.load()) * 1e-9;
                ++cancelled_;
                finished = false;
                break;
            }
            frame.generation = generation;
            if (i == 0) first_seconds = frame.seconds;
            frame.first_seconds = first_seconds;
            frame.pass = static_cast<int>(i);
            frame.passes = static_cast<int>(plan.size());
            std::lock_guard lock(mutex_);
            if (generation != generation_) {  // a newer scene came in as the pass ended
                finished = false;
                break;
            }
            frame_ = std::move(frame);
            has_frame_ = true;
        }
        if (finished) done_generation_ = generation;
    }
}

}  // namespace luz
