// The viewer's background render thread and its progressive passes.
#include "app/viewer/render_worker.h"

#include <chrono>

#include "render/render.h"

namespace luz {

namespace {

int64_t now_ns() {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(
               std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

}  // namespace

std::vector<PassPlan> plan_passes(const SceneDesc& desc) {
    std::vector<PassPlan> plan;
    const int smaller = std::min(desc.image.width, desc.image.height);
    if (smaller >= 64) plan.push_back({8, false});
    if (smaller >= 16) plan.push_back({2, false});
    plan.push_back({1, false});
    if (desc.render.antialias.mode != AaMode::none) plan.push_back({1, true});
    return plan;
}

bool render_pass(Scene& scene, const PassPlan& plan, int threads, const std::atomic<bool>* cancel,
                 RenderFrame& out) {
    // The pass's resolution and antialiasing, on the scene's own description (restored below):
    // the shapes and the BVH do not depend on them.
    ImageDesc& image = scene.desc.image;
    AntialiasDesc& aa = scene.desc.render.antialias;
    const ImageDesc image_kept = image;
    const AntialiasDesc aa_kept = aa;
    image.width = std::max(1, image.width / plan.divisor);
    image.height = std::max(1, image.height / plan.divisor);
    if (!plan.antialiased) aa.mode = AaMode::none;

    RenderControl control;
    control.threads = threads;
    control.cancel = cancel;
    RenderStats stats;
    out.image = render(scene, control, stats);
    image = image_kept;
    aa = aa_kept;
    out.divisor = plan.divisor;
    out.antialiased = plan.antialiased;
    out.seconds = stats.seconds;
    const uint64_t rays =
        stats.rays_primary + stats.rays_shadow + stats.rays_reflection + stats.rays_refraction;
    out.rays = rays > 0 ? rays : stats.samples;
    return !(cancel && cancel->load());
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

uint64_t RenderWorker::submit(std::shared_ptr<Scene> scene) {
    uint64_t g;
    {
        std::lock_guard lock(mutex_);
        pending_ = std::move(scene);
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
    std::shared_ptr<Scene> scene;
    uint64_t generation = 0;
    for (;;) {
        {
            std::unique_lock lock(mutex_);
            wake_.wait(lock, [&] { return quit_ || pending_; });
            if (quit_) return;
            scene = std::move(pending_);
            pending_.reset();
            generation = generation_;
            cancel_ = false;
        }
        const std::vector<PassPlan> plan = plan_passes(scene->desc);
        bool finished = true;
        double first_seconds = 0;
        for (size_t i = 0; i < plan.size(); ++i) {
            RenderFrame frame;
            if (!render_pass(*scene, plan[i], threads_, &cancel_, frame)) {
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
