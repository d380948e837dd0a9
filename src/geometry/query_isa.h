// The scene queries' kernels a second time, compiled for AVX2 and FMA (isa/query_avx2.cpp), for a
// portable build on a CPU that has them: chosen once per process by scene_query.cpp, unless
// LUZ_ISA=baseline asks for the portable ones. The same arithmetic lane by lane (no contraction,
// IEEE everywhere; only the BVH's padded slab test fuses, and it hits a superset of the boxes),
// so the same hits and transmittances bit for bit; the work counters may differ.
//
// The kernels' file is query_bvh.cpp, query_packet.cpp and query_leaf_packet.cpp (with the rare
// double paths of ray_sphere.cpp and ray_triangle.cpp) compiled with namespace luz renamed
// luz_avx2: none of their inline functions can stand in for the portable ones at link time. Only
// the entry points below are shared, declared on luz's types, whose layout does not depend on
// the instruction set (no lane type is stored in a BuiltScene).
#pragma once

#include <cstdint>
#include <vector>

namespace luz {

struct BuiltScene;
struct Ray;
struct Hit;
struct IntersectCounters;
struct Material;
struct SegmentLanes;
struct ShadowCache;

namespace query::avx2 {

/// Whether this build has the AVX2 kernels and they run here: the CPU has AVX2 and FMA and the
/// environment's LUZ_ISA is not "baseline" (decided once, at the first call).
bool active();

// query_parts.h's strategies of the same names.
bool nearest_hit_bvh(const BuiltScene& scene, const Ray& r, float t_min, float t_max, Hit& hit,
                     IntersectCounters& counters);
float transmittance_bvh(const BuiltScene& scene, const std::vector<Material>& materials,
                        const Ray& r, float t_min, float t_max, IntersectCounters& counters,
                        ShadowCache* cache);
void nearest_hits_bvh(const BuiltScene& scene, const Ray* rays, int n, float t_min, float t_max,
                      Hit* hits, bool* found, IntersectCounters& counters);
void transmittances_bvh(const BuiltScene& scene, const std::vector<Material>& materials,
                        const SegmentLanes& s, unsigned active, float* T,
                        IntersectCounters& counters, ShadowCache& cache);
void transmittances_leaf(const BuiltScene& scene, const std::vector<Material>& materials,
                         uint32_t first, uint32_t count, const SegmentLanes& s, unsigned active,
                         float* T, IntersectCounters& counters);

}  // namespace query::avx2

}  // namespace luz
