// Benchmark: luz's scene query against Embree 3 on a whole scene's own rays (the SPD scenes,
// issue 39): camera rays through pixel centres, then the reflected, refracted and shadow rays
// the ray tree spawns from their hits (spawn_ray, bounce, to every light in front), collected
// once, then timed through nearest_hit()/transmittance() and rtcIntersect1/rtcOccluded1, the two
// passes alternating (--reps pairs): rates from each one's best pass, the ratio the median of
// the pairs' ratios, over all rays and for the nearest-hit and the shadow rays apart.
// Embree holds mesh triangles as triangles and every other bounded shape as user geometry whose
// callbacks run luz's own exact test (the structures compared, not the primitive tests). A shadow
// ray asks both the same question, the transmittance along it (SPEC's vis_j): an opaque surface
// ends it, a transparent one multiplies its transparency and lets it go on — in Embree an
// occlusion filter that rejects such hits (triangles) and an occlusion callback that counts a
// transparent shape's crossings (user geometry), as a renderer on Embree would do it.
// --robust: Embree's watertight triangle test (RTC_SCENE_FLAG_ROBUST), as luz's always is.
#include <embree3/rtcore.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "geometry/scene.h"
#include "geometry/scene_query.h"
#include "geometry/shapes.h"
#include "render/recursion.h"
#include "scene/camera.h"
#include "scene/scene_loader.h"

namespace {

using namespace luz;
constexpr float kInf = std::numeric_limits<float>::infinity();

struct Segment {
    Ray ray;
    float t_max;
};
/// The rays of one scene by kind, as the renderer spawns them.
struct SceneRays {
    std::vector<Ray> camera, reflected, refracted;
    std::vector<Segment> shadow;
};

SceneRays collect_rays(const SceneDesc& d, const BuiltScene& scene, int size) {
    SceneRays out;
    const Camera cam = Camera::from(d.camera, size, size);
    IntersectCounters counters;
    struct Pending {
        Ray ray;
        int depth;
    };
    std::vector<Pending> stack;
    for (int y = 0; y < size; ++y) {
        for (int x = 0; x < size; ++x) {
            stack.push_back({cam.ray(x + 0.5f, y + 0.5f), 1});
            out.camera.push_back(stack.back().ray);
            while (!stack.empty()) {
                const Pending p = stack.back();
                stack.pop_back();
                Hit hit;
                if (!nearest_hit(scene, p.ray, 0.0f, kInf, hit, counters)) continue;
                const Shape& s = scene.shapes[hit.shape];
                const int mi = s.mesh ? s.mesh->materials[hit.part] : s.material;
                const Material& m = d.materials[mi];
                const SurfacePoint sp = surface_at(s, p.ray, hit);
                for (const Light& l : d.lights) {
                    const Vec3 L = l.position - sp.P;
                    if (dot(sp.N, L) <= 0) continue;  // no shadow ray from the unlit side
                    out.shadow.push_back({spawn_ray(sp.P, sp.Ng, L), 1.0f});
                }
                if (p.depth > d.render.max_depth) continue;
                const Vec3 D = normalize(p.ray.direction);
                const Bounce b = bounce(D, sp, m);
                if (m.reflection > 0) {
                    out.reflected.push_back(spawn_ray(sp.P, sp.Ng, b.reflected));
                    stack.push_back({out.reflected.back(), p.depth + 1});
                }
                if (m.transparency > 0) {
                    out.refracted.push_back(spawn_ray(sp.P, sp.Ng, b.refracted));
                    stack.push_back({out.refracted.back(), p.depth + 1});
                }
            }
        }
    }
    return out;
}

// ---- Embree: triangles, and luz's shapes as user geometry --------------------------------------

const BuiltScene* g_scene = nullptr;
const Materials* g_materials = nullptr;
std::vector<uint32_t> g_user_shapes;  // user primitive → shape
float g_transmittance = 1.0f;         // of the shadow ray being traced (one thread)
// The transparent triangles it has crossed: Embree's spatial splits (build quality high) put a
// triangle in several leaves, and its filter may see one crossing more than once.
std::vector<std::pair<const void*, unsigned>> g_crossed;

/// Transparency of a material (0: opaque).
float transparency_of(int material) { return (*g_materials)[material].transparency; }

void user_bounds(const RTCBoundsFunctionArguments* a) {
    const Bounds3& b = g_scene->bounds[g_user_shapes[a->primID]];
    *a->bounds_o = {b.lo.x, b.lo.y, b.lo.z, 0, b.hi.x, b.hi.y, b.hi.z, 0};
}
bool user_hit(const RTCRay& ray, unsigned prim, Hit& h) {
    const Ray r{{ray.org_x, ray.org_y, ray.org_z}, {ray.dir_x, ray.dir_y, ray.dir_z}};
    return intersect(g_scene->shapes[g_user_shapes[prim]], r, ray.tnear, ray.tfar, h);
}
void user_intersect(const RTCIntersectFunctionNArguments* a) {
    if (!a->valid[0]) return;
    RTCRayHit* rh = reinterpret_cast<RTCRayHit*>(a->rayhit);
    Hit h;
    if (!user_hit(rh->ray, a->primID, h)) return;
    rh->ray.tfar = h.t;
    rh->hit.primID = a->primID;
    rh->hit.geomID = a->geomID;
}
void user_occluded(const RTCOccludedFunctionNArguments* a) {
    if (!a->valid[0]) return;
    RTCRay* ray = reinterpret_cast<RTCRay*>(a->ray);
    const Shape& s = g_scene->shapes[g_user_shapes[a->primID]];
    const float T = transparency_of(s.material);
    if (T <= 0) {  // opaque: any hit ends the ray
        Hit h;
        if (user_hit(*ray, a->primID, h)) ray->tfar = -kInf;
        return;
    }
    const Ray r{{ray->org_x, ray->org_y, ray->org_z}, {ray->dir_x, ray->dir_y, ray->dir_z}};
    uint64_t tests = 0;
    const uint32_t n = count_crossings(s, r, ray->tnear, ray->tfar, false, tests);
    for (uint32_t k = 0; k < n; ++k) g_transmittance *= T;
}
/// Occlusion filter of a mesh with transparent triangles: their hits multiply the
/// transmittance and are rejected (the ray goes on); an opaque one's hit stands.
void transparent_triangles(const RTCFilterFunctionNArguments* a) {
    if (a->valid[0] == 0) return;
    const Shape& s = *static_cast<const Shape*>(a->geometryUserPtr);
    const unsigned tri = RTCHitN_primID(a->hit, a->N, 0);
    const float T = transparency_of(s.mesh->materials[tri]);
    if (T <= 0) return;
    a->valid[0] = 0;
    for (const auto& c : g_crossed)
        if (c.first == &s && c.second == tri) return;  // seen from another leaf
    g_crossed.emplace_back(&s, tri);
    g_transmittance *= T;
}

RTCScene embree_scene(RTCDevice device, const BuiltScene& scene, bool robust) {
    RTCScene es = rtcNewScene(device);
    rtcSetSceneFlags(es, robust ? RTC_SCENE_FLAG_ROBUST : RTC_SCENE_FLAG_NONE);
    g_scene = &scene;
    g_user_shapes.clear();
    for (size_t i = 0; i < scene.shapes.size(); ++i) {
        const Shape& s = scene.shapes[i];
        if (!s.bounded) continue;  // planes: tested apart, as luz does
        if (!s.mesh) {
            g_user_shapes.push_back(static_cast<uint32_t>(i));
            continue;
        }
        const size_t n = s.mesh->triangle_count();
        RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* v = static_cast<float*>(
            rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 12, 3 * n));
        auto* idx = static_cast<unsigned*>(
            rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 12, n));
        for (size_t t = 0; t < n; ++t) {
            Vec3 p[3];
            s.mesh->vertices(t, p[0], p[1], p[2]);
            for (int c = 0; c < 3; ++c) {
                for (int a = 0; a < 3; ++a) v[9 * t + 3 * c + a] = p[c][a];
                idx[3 * t + c] = static_cast<unsigned>(3 * t + c);
            }
        }
        bool transparent = false;
        for (size_t t = 0; t < n; ++t) transparent |= transparency_of(s.mesh->materials[t]) > 0;
        if (transparent) {
            rtcSetGeometryUserData(g, const_cast<Shape*>(&s));
            rtcSetGeometryOccludedFilterFunction(g, transparent_triangles);
        }
        rtcCommitGeometry(g);
        rtcAttachGeometry(es, g);
        rtcReleaseGeometry(g);
    }
    if (!g_user_shapes.empty()) {
        RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
        rtcSetGeometryUserPrimitiveCount(g, static_cast<unsigned>(g_user_shapes.size()));
        rtcSetGeometryBoundsFunction(g, user_bounds, nullptr);
        rtcSetGeometryIntersectFunction(g, user_intersect);
        rtcSetGeometryOccludedFunction(g, user_occluded);
        rtcCommitGeometry(g);
        rtcAttachGeometry(es, g);
        rtcReleaseGeometry(g);
    }
    rtcSetSceneBuildQuality(es, RTC_BUILD_QUALITY_HIGH);
    rtcCommitScene(es);
    return es;
}

RTCRayHit embree_ray(const Ray& r, float t_max) {
    RTCRayHit rh{};
    rh.ray = {r.origin.x,
              r.origin.y,
              r.origin.z,
              0.0f,
              r.direction.x,
              r.direction.y,
              r.direction.z,
              0.0f,
              t_max,
              0xFFFFFFFFu,
              0,
              0};
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    return rh;
}

/// The transmittance of segment s by Embree: 0 if rtcOccluded1 finds an opaque hit, else the
/// product the transparent ones' callbacks leave.
float embree_transmittance(RTCScene es, RTCIntersectContext& ctx, const Segment& s) {
    g_transmittance = 1.0f;
    g_crossed.clear();
    RTCRay ray = embree_ray(s.ray, s.t_max).ray;
    rtcOccluded1(es, &ctx, &ray);
    return ray.tfar < 0 ? 0.0f : g_transmittance;
}

double seconds_of(const auto& f) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

int main(int argc, char** argv) {
    int size = 256, reps = 3;
    bool robust = false;  // Embree's watertight triangle test (RTC_SCENE_FLAG_ROBUST), as luz's
    std::vector<std::string> files;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--size" && i + 1 < argc) {
            size = std::atoi(argv[++i]);
        } else if (a == "--reps" && i + 1 < argc) {
            reps = std::atoi(argv[++i]);
        } else if (a == "--robust") {
            robust = true;
        } else if (a == "-h" || a == "--help") {
            std::printf("usage: spd_vs_embree [--size N] [--reps N] [--robust] SCENE…\n");
            return 0;
        } else {
            files.push_back(a);
        }
    }
    RTCDevice device = rtcNewDevice("threads=1");
    std::printf(
        "| scene | rays (camera / reflected / refracted / shadow) | luz Mrays/s | Embree "
        "Mrays/s | luz / Embree | nearest / shadow | hits differing | shadow transmittances "
        "differing |\n|---|---|---|---|---|---|---|---|\n");
    for (const std::string& file : files) {
        SceneDesc d = load_scene(file);
        d.render.pipeline = Pipeline::raytrace;
        const BuiltScene scene = build_scene(d);
        const SceneRays rays = collect_rays(d, scene, size);
        g_materials = &d.materials;
        RTCScene es = embree_scene(device, scene, robust);
        std::vector<Ray> nearest = rays.camera;
        nearest.insert(nearest.end(), rays.reflected.begin(), rays.reflected.end());
        nearest.insert(nearest.end(), rays.refracted.begin(), rays.refracted.end());
        const double total = double(nearest.size() + rays.shadow.size());
        IntersectCounters counters;
        volatile float sink = 0;
        // Each pass times its nearest-hit queries and its shadow rays apart (part[0], part[1]).
        double part[2];
        const auto luz_pass = [&] {
            part[0] = seconds_of([&] {
                Hit h;
                for (const Ray& r : nearest)
                    sink = sink + (nearest_hit(scene, r, 0, kInf, h, counters) ? h.t : 0);
            });
            part[1] = seconds_of([&] {
                for (const Segment& s : rays.shadow)
                    sink = sink + transmittance(scene, d.materials, s.ray, 0, s.t_max, counters);
            });
        };
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        const auto embree_pass = [&] {
            part[0] = seconds_of([&] {
                for (const Ray& r : nearest) {
                    RTCRayHit rh = embree_ray(r, kInf);
                    rtcIntersect1(es, &ctx, &rh);
                    sink = sink + rh.ray.tfar;
                }
            });
            part[1] = seconds_of([&] {
                for (const Segment& s : rays.shadow) sink = sink + embree_transmittance(es, ctx, s);
            });
        };
        // The two passes alternate, luz first then Embree first, so that the machine's drift
        // falls on both alike: the ratio is the median of each pair's, the rates the best pass.
        std::vector<double> luz_t, embree_t, ratio, ratio_part[2];
        double luz_part[2], embree_part[2];
        const auto run = [&](const auto& pass, std::vector<double>& t, double* parts) {
            t.push_back(seconds_of(pass));
            parts[0] = part[0];
            parts[1] = part[1];
        };
        for (int k = 0; k < reps; ++k) {
            if (k % 2 == 0) {
                run(luz_pass, luz_t, luz_part);
                run(embree_pass, embree_t, embree_part);
            } else {
                run(embree_pass, embree_t, embree_part);
                run(luz_pass, luz_t, luz_part);
            }
            ratio.push_back(embree_t.back() / luz_t.back());
            for (int p = 0; p < 2; ++p) ratio_part[p].push_back(embree_part[p] / luz_part[p]);
        }
        const double luz_s = *std::min_element(luz_t.begin(), luz_t.end());
        const double embree_s = *std::min_element(embree_t.begin(), embree_t.end());
        size_t differ = 0;  // nearest hits whose distance differs (Embree's triangle test is not
        for (const Ray& r : nearest) {  // luz's watertight one: a few edge rays may)
            Hit h;
            const bool found = nearest_hit(scene, r, 0, kInf, h, counters);
            RTCRayHit rh = embree_ray(r, kInf);
            rtcIntersect1(es, &ctx, &rh);
            const bool ef = rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
            if (found != ef || (found && std::fabs(h.t - rh.ray.tfar) > 1e-4f * h.t)) ++differ;
        }
        size_t differ_T = 0;  // shadow rays whose transmittance differs (the same, up to rounding)
        for (const Segment& s : rays.shadow) {
            const float T = transmittance(scene, d.materials, s.ray, 0, s.t_max, counters);
            if (std::fabs(T - embree_transmittance(es, ctx, s)) > 1e-5f) ++differ_T;
        }
        std::printf(
            "| %s | %zu / %zu / %zu / %zu | %.2f | %.2f | %.2f× | %.2f× / %.2f× | %zu | %zu |\n",
            file.c_str(), rays.camera.size(), rays.reflected.size(), rays.refracted.size(),
            rays.shadow.size(), total / luz_s * 1e-6, total / embree_s * 1e-6, median(ratio),
            median(ratio_part[0]), rays.shadow.empty() ? 0.0 : median(ratio_part[1]), differ,
            differ_T);
        std::fflush(stdout);
        rtcReleaseScene(es);
    }
    rtcReleaseDevice(device);
    return 0;
}
