// `--stats FILE`: RenderStats to JSON.
#include "api/stats_json.h"

#include <sys/resource.h>

#include "luz/memory.h"  // peak_resident_bytes()

namespace luz {

const char* pipeline_name(Pipeline p) {
    switch (p) {
        case Pipeline::zbuffer:
            return "zbuffer";
        case Pipeline::raycast:
            return "raycast";
        case Pipeline::raytrace:
            return "raytrace";
    }
    return "?";
}

static const char* model_name(Model m) { return m == Model::lambert ? "lambert" : "phong"; }

static const char* aa_name(AaMode m) {
    switch (m) {
        case AaMode::none:
            return "none";
        case AaMode::grid:
            return "grid";
        case AaMode::adaptive:
            return "adaptive";
    }
    return "?";
}

uint64_t peak_resident_bytes() {
    rusage usage{};
    if (getrusage(RUSAGE_SELF, &usage) != 0) return 0;
    return static_cast<uint64_t>(usage.ru_maxrss) * 1024;  // Linux reports KiB
}

nlohmann::json stats_to_json(const RenderStats& s, const SceneDesc& desc) {
    using nlohmann::json;
    nlohmann::json out = json{
        {"scene", desc.source},
        {"seconds", s.seconds},
        {"width", s.width},
        {"height", s.height},
        {"threads", s.threads},
        {"pipeline", pipeline_name(desc.render.pipeline)},
        {"model", model_name(desc.render.model)},
        {"antialias", aa_name(desc.render.antialias.mode)},
        {"rays", json{{"primary", s.rays_primary},
                      {"shadow", s.rays_shadow},
                      {"reflection", s.rays_reflection},
                      {"refraction", s.rays_refraction}}},
        {"intersection_tests", json{{"primitive", s.tests_primitive}, {"bounds", s.tests_bounds}}},
        {"pixels_refined", s.pixels_refined},
        {"samples", s.samples},
        {"triangles", s.triangles},
        {"bvh_nodes", s.bvh_nodes},
        {"accel", desc.geometry.accel == Accel::bvh ? "bvh" : "none"},
        {"bvh_build_seconds", s.bvh_build_seconds},
        {"bvh_bytes", s.bvh_bytes},
        {"intersection_time",
         json{
             {"share", s.sampled_seconds > 0 ? json(s.intersect_sampled_seconds / s.sampled_seconds)
                                             : json(nullptr)},
             {"sampled_seconds", s.sampled_seconds},
             {"intersection_seconds", s.intersect_sampled_seconds},
             {"method",
              "timers around every nearest-hit and shadow-ray query of every 256th primary "
              "sample, and around those whole samples; share = query time / sample time "
              "(null: no rays traced)"}}},
        {"peak_memory_bytes", s.peak_memory_bytes},
    };
    if (s.region[2] > 0) {  // --region: the rectangle, as given (width and height are its size)
        out["region"] = json::array({s.region[0], s.region[1], s.region[2], s.region[3]});
    }
    if (s.processes > 0) {  // mpirun: how the work was shared
        out["processes"] = s.processes;
        out["primary_rays_by_process"] = s.primary_rays_by_process;
        out["mpi"] = json{{"messages_received_and_sent", s.mpi_messages},
                          {"tiles_received", s.mpi_tiles_received},
                          {"tile_bytes_received", s.mpi_tile_bytes_received},
                          {"broadcast_bytes", s.mpi_broadcast_bytes}};
    }
    return out;
}

std::string stats_json(const RenderStats& stats, const SceneDesc& desc) {
    return stats_to_json(stats, desc).dump(2) + "\n";
}

}  // namespace luz
