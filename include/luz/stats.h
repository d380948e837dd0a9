// RenderStats: what a render counted and measured, written by `--stats FILE` (docs/CLI.md).
#pragma once

#include <cstdint>
#include <vector>

namespace luz {

struct RenderStats {
    double seconds = 0;  ///< render time, from scene build to image in memory
    int width = 0, height = 0, threads = 0;
    uint64_t rays_primary = 0, rays_shadow = 0, rays_reflection = 0, rays_refraction = 0;
    uint64_t tests_primitive = 0, tests_bounds = 0;  ///< intersection tests
    uint64_t pixels_refined = 0;                     ///< adaptive antialiasing
    uint64_t samples = 0;                            ///< colour evaluations
    uint64_t triangles = 0;                          ///< zbuffer: rasterized; raytrace: in meshes
    uint64_t bvh_nodes = 0;
    double bvh_build_seconds = 0;  ///< building the BVH (part of the scene build)
    uint64_t bvh_bytes = 0;        ///< nodes and primitives (in leaf order)
    /// The share of ray-tracing time spent in intersection, measured on a sample: timers around
    /// the scene queries of 1 primary sample in 256 (the reference, render/whitted.h) or of the
    /// batches holding one (render/batch_tracer.h), and around those whole samples or batches.
    /// Share = intersect_sampled_seconds / sampled_seconds.
    double intersect_sampled_seconds = 0, sampled_seconds = 0;
    uint64_t peak_memory_bytes = 0;
    /// --region X0,Y0,X1,Y1 (docs/CLI.md): the rectangle rendered; all 0 for the whole image.
    int region[4] = {0, 0, 0, 0};
    /// Under mpirun (docs/DISTRIBUTED.md): the number of processes (0: not shared) and the primary
    /// rays each one traced, by rank; they add up to rays_primary.
    int processes = 0;
    std::vector<uint64_t> primary_rays_by_process;
    /// Under mpirun, what rank 0 received: messages, tiles and their bytes, and the bytes it
    /// broadcast (adaptive's corners) — the costs docs/SCALING.md's model starts from.
    uint64_t mpi_messages = 0, mpi_tiles_received = 0, mpi_tile_bytes_received = 0,
             mpi_broadcast_bytes = 0;
};

}  // namespace luz
