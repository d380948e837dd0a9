// The scene queries' kernels compiled for AVX2 and FMA (geometry/query_isa.h): the portable
// build's own files, included here and compiled with -mavx2 -mfma -ffp-contract=off
// -Dluz=luz_avx2 (CMakeLists.txt), then the entry points of query_isa.h passing luz's types on
// to their luz_avx2 twins, which are the same types by the same source.
#if !defined(__AVX2__) || !defined(__FMA__) || !defined(luz)
#error "compiled by CMakeLists.txt with -mavx2 -mfma -Dluz=luz_avx2"
#endif

#include "geometry/query_all.cpp"
#include "geometry/query_bvh.cpp"
#include "geometry/query_leaf_packet.cpp"
#include "geometry/query_packet.cpp"
#include "geometry/ray_sphere.cpp"
#include "geometry/ray_triangle.cpp"

#undef luz  // from here on, luz is luz
#include "geometry/query_isa.h"

namespace luz::query::avx2 {

namespace {

/// x as its luz_avx2 twin (the same struct, compiled from the same source).
template <class Twin, class T>
Twin& twin(T& x) {
    return reinterpret_cast<Twin&>(x);
}
template <class Twin, class T>
const Twin& twin(const T& x) {
    return reinterpret_cast<const Twin&>(x);
}
template <class Twin, class T>
Twin* twins(T* x) {
    return reinterpret_cast<Twin*>(x);
}
template <class Twin, class T>
const Twin* twins(const T* x) {
    return reinterpret_cast<const Twin*>(x);
}

using Materials2 = std::vector<luz_avx2::Material>;

}  // namespace

bool nearest_hit_bvh(const BuiltScene& scene, const Ray& r, float t_min, float t_max, Hit& hit,
                     IntersectCounters& counters) {
    return luz_avx2::query::nearest_hit_bvh(
        twin<luz_avx2::BuiltScene>(scene), twin<luz_avx2::Ray>(r), t_min, t_max,
        twin<luz_avx2::Hit>(hit), twin<luz_avx2::IntersectCounters>(counters));
}

float transmittance_bvh(const BuiltScene& scene, const std::vector<Material>& materials,
                        const Ray& r, float t_min, float t_max, IntersectCounters& counters,
                        ShadowCache* cache) {
    return luz_avx2::query::transmittance_bvh(
        twin<luz_avx2::BuiltScene>(scene), twin<Materials2>(materials), twin<luz_avx2::Ray>(r),
        t_min, t_max, twin<luz_avx2::IntersectCounters>(counters),
        twins<luz_avx2::ShadowCache>(cache));
}

void nearest_hits_bvh(const BuiltScene& scene, const Ray* rays, int n, float t_min, float t_max,
                      Hit* hits, bool* found, IntersectCounters& counters) {
    luz_avx2::query::nearest_hits_bvh(twin<luz_avx2::BuiltScene>(scene), twins<luz_avx2::Ray>(rays),
                                      n, t_min, t_max, twins<luz_avx2::Hit>(hits), found,
                                      twin<luz_avx2::IntersectCounters>(counters));
}

void transmittances_bvh(const BuiltScene& scene, const std::vector<Material>& materials,
                        const SegmentLanes& s, unsigned active, float* T,
                        IntersectCounters& counters, ShadowCache& cache) {
    luz_avx2::query::transmittances_bvh(
        twin<luz_avx2::BuiltScene>(scene), twin<Materials2>(materials),
        twin<luz_avx2::SegmentLanes>(s), active, T, twin<luz_avx2::IntersectCounters>(counters),
        twin<luz_avx2::ShadowCache>(cache));
}

void transmittances_leaf(const BuiltScene& scene, const std::vector<Material>& materials,
                         uint32_t first, uint32_t count, const SegmentLanes& s, unsigned active,
                         float* T, IntersectCounters& counters) {
    luz_avx2::query::transmittances_leaf(
        twin<luz_avx2::BuiltScene>(scene), twin<Materials2>(materials), first, count,
        twin<luz_avx2::SegmentLanes>(s), active, T, twin<luz_avx2::IntersectCounters>(counters));
}

}  // namespace luz::query::avx2
