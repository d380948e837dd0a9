// Animations in the API: load with every frame checked, frames on demand, --frames, frame
// file names, and the statistics of a sequence (include/luz/animation.h).
#include "luz/animation.h"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <filesystem>

#include "api/stats_json.h"
#include "render/parallel.h"  // start_workers()
#include "render/stats.h"     // add_counters()
#include "scene/scene_loader.h"

namespace luz {

struct Animation::Meshes {
    MeshCache cache;
};

Animation Animation::load(const std::string& source, const std::vector<Override>& overrides) {
    start_workers();  // the threads that will build the BVH and render start meanwhile
    Animation a;
    a.text_ = read_scene_text(source);
    a.overrides_ = overrides;
    a.meshes_ = std::make_shared<Animation::Meshes>();
    a.first_ =
        parse_scene(a.text_.text, a.text_.label, a.text_.base_dir, overrides, &a.meshes_->cache);
    return a;
}

SceneDesc Animation::frame(int f) const {
    if (f == 0) return first_;
    SceneDesc d =
        parse_scene_frame(text_.text, text_.label, text_.base_dir, overrides_, f, &meshes_->cache);
    return d;
}

namespace {

/// The whole decimal number `s`, or -1.
long long whole_number(std::string_view s) {
    long long v = -1;
    if (s.empty() || s.size() > 9) return -1;
    const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
    if (r.ec != std::errc() || r.ptr != s.data() + s.size() || v < 0) return -1;
    return v;
}

}  // namespace

FrameRange parse_frames(const std::string& text, const Animation& animation,
                        const std::string& option) {
    const std::string label = option + " " + text;
    if (!animation.animated()) {
        throw SceneError(
            label + ": " + animation.first().source +
            " has no animation (add an \"animation\" key, docs/SCENES.md#scene-files)");
    }
    const int n = animation.frames();
    const std::string frames = "the scene has frames 0 to " + std::to_string(n - 1);
    if (text == "all") return {0, n};
    const std::size_t colon = text.find(':');
    const long long a = colon == std::string::npos ? -1 : whole_number(text.substr(0, colon));
    const long long b = colon == std::string::npos ? -1 : whole_number(text.substr(colon + 1));
    if (a < 0 || b < 0) {
        throw SceneError(label +
                         ": expected A:B (frames A to B-1) or all, e.g. 0:" + std::to_string(n));
    }
    if (a >= b) throw SceneError(label + ": empty range: B must be greater than A");
    if (b > n)
        throw SceneError(label + ": past the last frame: " + frames + ", so B ≤ " +
                         std::to_string(n));
    return {int(a), int(b)};
}

std::string frame_path(const std::string& path, int f) {
    const std::filesystem::path p(path);
    char digits[16];
    std::snprintf(digits, sizeof digits, "%04d", f);
    std::filesystem::path out = p.parent_path() / p.stem();
    out += std::string(".") + digits + p.extension().string();
    return out.string();
}

std::string animation_stats_json(const std::vector<RenderStats>& stats,
                                 const std::vector<int>& numbers, const SceneDesc& desc) {
    RenderStats total = stats.front();
    for (std::size_t i = 1; i < stats.size(); ++i) {
        const RenderStats& s = stats[i];
        add_counters(total, s);
        total.seconds += s.seconds;
        total.bvh_build_seconds += s.bvh_build_seconds;
        total.sampled_seconds += s.sampled_seconds;
        total.intersect_sampled_seconds += s.intersect_sampled_seconds;
        total.bvh_nodes = std::max(total.bvh_nodes, s.bvh_nodes);
        total.bvh_bytes = std::max(total.bvh_bytes, s.bvh_bytes);
        total.peak_memory_bytes = std::max(total.peak_memory_bytes, s.peak_memory_bytes);
        for (std::size_t r = 0;
             r < s.primary_rays_by_process.size() && r < total.primary_rays_by_process.size(); ++r)
            total.primary_rays_by_process[r] += s.primary_rays_by_process[r];
        total.mpi_messages += s.mpi_messages;
        total.mpi_tiles_received += s.mpi_tiles_received;
        total.mpi_tile_bytes_received += s.mpi_tile_bytes_received;
        total.mpi_broadcast_bytes += s.mpi_broadcast_bytes;
    }
    nlohmann::json out = stats_to_json(total, desc);
    nlohmann::json frames = nlohmann::json::array();
    for (std::size_t i = 0; i < stats.size(); ++i) {
        nlohmann::json f = stats_to_json(stats[i], desc);
        f.erase("scene");
        frames.push_back(nlohmann::json{{"frame", numbers[i]}});
        frames.back().update(f);
    }
    out["frame_range"] = nlohmann::json::array({numbers.front(), numbers.back() + 1});
    out["fps"] = desc.animation.fps;
    out["frames"] = std::move(frames);
    return out.dump(2) + "\n";
}

}  // namespace luz
