// RenderWorker: renders the viewer's scene in a background thread, progressively (1/8, 1/2,
// then full resolution, then with the scene's antialiasing); every new scene cancels the
// render under way and starts again from the coarsest pass.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "luz/luz.h"

namespace luz {

/// One finished refinement pass.
struct RenderFrame {
    Image image;               ///< at the pass's resolution (scaled up for display)
    uint64_t generation = 0;   ///< which submitted scene it shows
    int pass = 0, passes = 0;  ///< pass index (0: coarsest) and how many this scene has
    int divisor = 1;           ///< resolution divisor of the pass (8, 2, 1)
    bool antialiased = false;  ///< the pass with the scene's antialiasing
    double seconds = 0;        ///< render time of the pass
    double first_seconds = 0;  ///< render time of this scene's first (coarsest) pass
    uint64_t rays = 0;         ///< rays (ray pipelines) or shaded samples (zbuffer) of the pass
};

/// The resolution divisors of the passes for an image: 8, 2, 1 (the coarse ones only when
/// the image is large enough), then 1 again with antialiasing when the scene asks for it.
struct PassPlan {
    int divisor;
    bool antialiased;
};
std::vector<PassPlan> plan_passes(const Settings& settings);

/// What the viewer shows: the image, or one of its per-term images (docs/SCENES.md#terms).
struct Showing {
    bool term = false;
    AovKind kind = AovKind::ambient;
};

/// Renders one pass of `scene` with `settings` (their image size and antialiasing changed for
/// the pass on a copy); returns false when cancelled. With a term shown, the pass's image is
/// that term: colour terms as they are, depth, normal and tests as pictures (aov_picture()).
bool render_pass(const Scene& scene, const Settings& settings, const PassPlan& plan, int threads,
                 const std::atomic<bool>* cancel, RenderFrame& out, Showing show = {});

class RenderWorker {
  public:
    explicit RenderWorker(int threads);
    ~RenderWorker();
    RenderWorker(const RenderWorker&) = delete;
    RenderWorker& operator=(const RenderWorker&) = delete;

    /// Cancels the render under way and starts rendering `scene` with `settings` from the
    /// coarsest pass; returns the new generation.
    uint64_t submit(Scene scene, Settings settings, Showing show = {});

    /// Moves the newest finished pass not taken yet into `out`; false when there is none.
    bool take_frame(RenderFrame& out);

    /// True when every pass of the newest scene is finished.
    bool done() const { return done_generation_.load() == generation_.load(); }

    /// How long the last cancelled render took to stop, in seconds (0 if none was cancelled).
    double last_cancel_latency() const { return cancel_latency_.load(); }

    /// How many renders were cancelled so far.
    int cancelled() const { return cancelled_.load(); }

  private:
    void run();

    int threads_;
    mutable std::mutex mutex_;
    std::condition_variable wake_;
    /// The newest scene and settings, not yet picked up.
    struct Job {
        Scene scene;
        Settings settings;
        Showing show;
    };
    std::optional<Job> pending_;
    bool quit_ = false;
    std::atomic<bool> cancel_{false};
    std::atomic<uint64_t> generation_{0}, done_generation_{0};
    std::atomic<int64_t> cancel_requested_ns_{0};
    std::atomic<double> cancel_latency_{0};
    std::atomic<int> cancelled_{0};
    bool has_frame_ = false;
    RenderFrame frame_;
    std::thread thread_;  ///< last: started once every member above is constructed
};

}  // namespace luz
