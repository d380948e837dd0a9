// The ray tracer against docs/SCENES.md#ray-tracing: Snell's law, total internal reflection,
// shadows through opaque and glass objects, two-sided planes, light spheres, tree attenuation,
// determinism, and raycast ≡ zbuffer.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <numbers>
#include <numeric>
#include <vector>

#include "image/compare.h"
#include "render/batch_tracer.h"
#include "render/render.h"
#include "scene/scene_loader.h"

namespace luz {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

void expect_near_vec(const Vec3& a, const Vec3& b, float tol = 1e-5f) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

TEST(Refract, FollowsSnellsLawAtSeveralAngles) {
    const Vec3 N{0, 1, 0};
    for (float n2 : {1.33f, 1.5f, 2.4f}) {
        for (float deg : {0.0f, 10.0f, 30.0f, 45.0f, 60.0f, 85.0f}) {
            const float i = deg * kPi / 180;
            const Vec3 D{std::sin(i), -std::cos(i), 0};
            Vec3 T;
            ASSERT_TRUE(refract(D, N, 1.0f, n2, T));
            EXPECT_NEAR(length(T), 1.0f, 1e-6f);
            // n1·sin i = n2·sin r, in the plane of incidence, on the other side.
            const float sin_r = T.x;
            EXPECT_NEAR(1.0f * std::sin(i), n2 * sin_r, 1e-5f) << n2 << " " << deg;
            EXPECT_LT(T.y, 0);
            EXPECT_NEAR(T.z, 0, 1e-7f);
        }
    }
}

TEST(Refract, TotalInternalReflectionPastTheCriticalAngle) {
    const Vec3 N{0, 1, 0};
    const float critical = std::asin(1.0f / 1.5f);
    Vec3 T;
    const float below = critical - 0.01f, above = critical + 0.01f;
    EXPECT_TRUE(refract({std::sin(below), -std::cos(below), 0}, N, 1.5f, 1.0f, T));
    EXPECT_FALSE(refract({std::sin(above), -std::cos(above), 0}, N, 1.5f, 1.0f, T));
}

SceneDesc empty_scene() {
    SceneDesc d;
    d.image.width = 8;
    d.image.height = 8;
    d.image.background = Rgb{0.0f};
    d.render.pipeline = Pipeline::raytrace;
    d.render.model = Model::lambert;
    d.camera.position = {0, 5, 0.001f};
    d.camera.look_at = {0, 0, 0};
    Material m;  // materials[0]: Ka = 0.1, Kd = 0.45
    d.materials.push_back(m);
    return d;
}

ObjectDesc floor_plane(int material = 0) {
    ObjectDesc o;
    o.type = ShapeType::plane;
    o.material = material;
    return o;
}

ObjectDesc sphere(Vec3 c, float r, int material) {
    ObjectDesc o;
    o.type = ShapeType::sphere;
    o.center = c;
    o.radius = r;
    o.material = material;
    return o;
}

Rgb trace_down(const BuiltScene& scene, const Settings& settings, Vec3 from,
               TraceCounters* counters_out = nullptr) {
    const Whitted tracer(scene, settings, true);
    TraceCounters counters;
    float d;
    const Rgb c = tracer.trace(Ray{from, {0, -1, 0}}, 0, counters, d);
    if (counters_out) *counters_out = counters;
    return c;
}

TEST(Shadows, OpaqueSphereLeavesAmbientOnly) {
    SceneDesc d = empty_scene();
    d.lights.push_back({Vec3{0, 10, 0}, Rgb{1.0f}, 0});
    d.objects = {floor_plane(), sphere({0, 3, 0}, 1, 0)};
    const BuiltScene scene = build_scene(d);
    // Right under the sphere: in shadow.
    const Rgb shadowed = trace_down(scene, d, {0, 0.5f, 0});
    expect_near_vec(shadowed, Rgb{0.1f});
    // Far to the side: lit, I = Ka + Kd·cosθ.
    const Vec3 P{5, 0, 0};
    const float cos_theta = normalize(Vec3{0, 10, 0} - P).y;
    expect_near_vec(trace_down(scene, d, {5, 0.5f, 0}), Rgb{0.1f + 0.45f * cos_theta});
}

TEST(Shadows, GlassSphereTransmitsTransparencySquared) {
    SceneDesc d = empty_scene();
    d.render.max_depth = 0;  // only the local model at the floor
    Material glass;
    glass.transparency = 0.6f;
    glass.ior = 1.5f;
    d.materials.push_back(glass);
    d.lights.push_back({Vec3{0, 10, 0}, Rgb{1.0f}, 0});
    d.objects = {floor_plane(), sphere({0, 3, 0}, 1, 1)};
    const BuiltScene scene = build_scene(d);
    TraceCounters c;
    const Rgb I = trace_down(scene, d, {0, 0.5f, 0}, &c);
    // vis = 0.6 · 0.6 (the shadow ray enters and leaves the sphere).
    expect_near_vec(I, Rgb{0.1f + 0.36f * 0.45f});
    EXPECT_EQ(c.shadow, 1u);
}

TEST(Planes, LitFromBelowAndSeenFromBelow) {
    SceneDesc d = empty_scene();
    d.lights.push_back({Vec3{0, -4, 0}, Rgb{1.0f}, 0});
    d.objects = {floor_plane()};
    const BuiltScene scene = build_scene(d);
    const Whitted tracer(scene, d, true);
    TraceCounters c;
    float dist;
    // Seen from below, lit from below: the normal flips towards the viewer.
    const Rgb below = tracer.trace(Ray{{0, -1, 0}, {0, 1, 0}}, 0, c, dist);
    expect_near_vec(below, Rgb{0.1f + 0.45f});
    EXPECT_NEAR(dist, 1.0f, 1e-6f);
    // Seen from above, the light below does not reach the viewer's side.
    expect_near_vec(trace_down(scene, d, {0, 1, 0}), Rgb{0.1f});
}

TEST(LightSpheres, SeenDirectlyAndInAMirrorNeverCastingShadows) {
    SceneDesc d = empty_scene();
    Material mirror;
    mirror.ka = Rgb{0.0f};
    mirror.kd = Rgb{0.0f};
    mirror.ks = Rgb{0.0f};
    mirror.reflection = 0.5f;
    d.materials.push_back(mirror);
    d.lights.push_back({Vec3{0, 3, 0}, Rgb{2.0f, 0.5f, 0.25f}, 0.5f});
    d.objects = {floor_plane(1)};
    const BuiltScene scene = build_scene(d);
    const Whitted tracer(scene, d, true);
    TraceCounters c;
    float dist;
    // Directly: the light's intensity clamped to [0, 1].
    expect_near_vec(tracer.trace(Ray{{0, 10, 0}, {0, -1, 0}}, 0, c, dist), Rgb{1.0f, 0.5f, 0.25f});
    EXPECT_NEAR(dist, 6.5f, 1e-5f);
    // In the mirror floor, from beside the light: reflection · clamped colour; the local
    // term is 0 (Ka = Kd = 0) and the light sphere does not shadow the floor point.
    const Vec3 from{0, 1, 2};
    const Vec3 dir = normalize(Vec3{0, -1, -0.5f});  // meets the floor at (0, 0, 1.5)
    const Rgb seen = tracer.trace(Ray{from, dir}, 0, c, dist);
    // The reflected ray from (0, 0, 1.5) goes up and back: (0, 1, −0.5), towards (0, 3, 0).
    expect_near_vec(seen, Rgb{0.5f, 0.25f, 0.125f});
    // A floor point right under the light is lit by it (the sphere does not block).
    d.materials[1] = Material{};
    const BuiltScene lit = build_scene(d);
    const Rgb under = trace_down(lit, d, {0, 1, 0.2f});
    EXPECT_GT(under.x, 0.1f + 0.4f);
}

TEST(RayTree, ReflectionAddsTheMirroredColourAndMaxDepthCutsIt) {
    SceneDesc d = empty_scene();
    d.image.background = Rgb{0.2f, 0.4f, 0.6f};
    Material mirror;
    mirror.reflection = 0.5f;
    d.materials.push_back(mirror);
    d.lights.push_back({Vec3{0, 10, 0}, Rgb{1.0f}, 0});
    d.objects = {floor_plane(1)};
    const Rgb local{0.1f + 0.45f};
    {
        const BuiltScene scene = build_scene(d);
        expect_near_vec(trace_down(scene, d, {0, 1, 0}), local + Rgb{0.2f, 0.4f, 0.6f} * 0.5f);
    }
    d.render.max_depth = 0;
    {
        const BuiltScene scene = build_scene(d);
        TraceCounters c;
        expect_near_vec(trace_down(scene, d, {0, 1, 0}, &c), local);
        EXPECT_EQ(c.reflection, 0u);
    }
    d.render.max_depth = 5;
    d.render.tree_attenuation = true;  // a reflected ray into the void contributes nothing
    {
        const BuiltScene scene = build_scene(d);
        expect_near_vec(trace_down(scene, d, {0, 1, 0}), local);
    }
}

TEST(RayTree, SchlickLeavesTheMirrorCoefficientAlone) {
    // docs/SCENES.md#reflectance: `reflectance` changes the specular term only; `reflection` still
    // scales the reflected ray by itself, at any angle of view (here 45°, where w(45°) would
    // differ).
    SceneDesc d = empty_scene();
    d.render.model = Model::phong;
    d.image.background = Rgb{0.2f, 0.4f, 0.6f};
    Material mirror;  // Ka = 0.1, Kd = 0.45
    mirror.ks = Rgb{0.04f};
    mirror.n = 2000;  // no highlight 45° away from the mirror direction
    mirror.reflection = 0.5f;
    mirror.reflectance = Reflectance::schlick;
    d.materials.push_back(mirror);
    d.lights.push_back({Vec3{0, 10, 0}, Rgb{1.0f}, 0});
    d.objects = {floor_plane(1)};
    const BuiltScene scene = build_scene(d);
    const Whitted tracer(scene, d, true);
    TraceCounters c;
    float dist;
    const Rgb seen = tracer.trace(Ray{{0, 1, 1}, normalize(Vec3{0, -1, -1})}, 0, c, dist);
    // Ia·Ka + Il/(d+K)·Kd·cos 0 + reflection·background
    expect_near_vec(seen, Rgb{0.1f + 0.45f / 11} + Rgb{0.2f, 0.4f, 0.6f} * 0.5f);
}

TEST(RayTree, TreeAttenuationDividesBySegmentLengthPlusK) {
    SceneDesc d = empty_scene();
    Material mirror;
    mirror.ka = Rgb{0.0f};
    mirror.kd = Rgb{0.0f};
    mirror.reflection = 1.0f;
    d.materials.push_back(mirror);
    d.attenuation_k = 2.0f;
    d.render.tree_attenuation = true;
    d.lights.push_back({Vec3{0.25f, 0.5f, 0}, Rgb{0.8f}, 0.1f});  // a light sphere to look at
    d.objects = {floor_plane(1)};
    const BuiltScene scene = build_scene(d);
    const Whitted tracer(scene, d, true);
    TraceCounters c;
    float dist;
    // From (1, 1, 0) to the mirror at (0.5, 0, 0); the reflected ray (−0.5, 1, 0) passes
    // through the light's centre and meets its sphere after d = |(−0.25, 0.5)| − 0.1,
    // so A = 1/(d + 2) scales the light's colour.
    const Rgb seen = tracer.trace(Ray{{1, 1, 0}, normalize(Vec3{-0.5f, -1, 0})}, 0, c, dist);
    const float seg = std::sqrt(0.25f * 0.25f + 0.5f * 0.5f) - 0.1f;
    expect_near_vec(seen, Rgb{0.8f / (seg + 2.0f)}, 1e-4f);  // the origin moved by ε
}

TEST(Refraction, ARayThroughAGlassSphereComesOutAndGoesOn) {
    SceneDesc d = empty_scene();
    d.image.background = Rgb{0.0f};
    Material glass;
    glass.ka = Rgb{0.0f};
    glass.kd = Rgb{0.0f};
    glass.ks = Rgb{0.0f};
    glass.transparency = 1.0f;
    glass.ior = 1.5f;
    d.materials.push_back(glass);
    d.lights.push_back({Vec3{0, -3, 0}, Rgb{0.7f, 0.6f, 0.5f}, 0.5f});
    d.objects = {sphere({0, 0, 0}, 1, 1)};
    const BuiltScene scene = build_scene(d);
    TraceCounters c;
    // Straight through the centre: no bending; enters, leaves and meets the light sphere.
    const Rgb I = trace_down(scene, d, {0, 5, 0}, &c);
    expect_near_vec(I, Rgb{0.7f, 0.6f, 0.5f});
    EXPECT_EQ(c.refraction, 2u);
    // Off-centre rays bend towards the axis inside and away outside: a ray at x = 0.3 comes
    // out on the far side (its exit point is at x < 0.3); check by tracing it step by step.
    const Vec3 D{0, -1, 0};
    const float x = 0.3f;
    const Vec3 P1{x, std::sqrt(1 - x * x), 0};
    Vec3 T1;
    ASSERT_TRUE(refract(D, P1, 1.0f, 1.5f, T1));
    EXPECT_GT(std::abs(T1.y), 0);
    EXPECT_LT(T1.x, 0);  // bent towards the centre
    // The exit point: second intersection of P1 + s·T1 with the unit sphere.
    const float s = -2 * dot(P1, T1);
    const Vec3 P2 = P1 + T1 * s;
    EXPECT_NEAR(length(P2), 1.0f, 1e-5f);
    Vec3 T2;
    ASSERT_TRUE(refract(T1, -P2, 1.5f, 1.0f, T2));
    // Symmetry: the ray leaves at the same angle to the normal as it entered.
    EXPECT_NEAR(dot(T2, P2), dot(-D, P1), 1e-5f);
}

TEST(Pipelines, RaycastEqualsZbufferUpToTessellation) {
    // docs/SCENES.md: demo:primitives through both pipelines with a fine tessellation agree on at
    // least 99 % of pixels within 2/255.
    SceneDesc d = load_scene("demo:primitives", {{"render.tessellation", "512"}});
    const SceneDesc dz = d;
    const BuiltScene zb = build_scene(d);
    d.render.pipeline = Pipeline::raycast;
    const BuiltScene rc = build_scene(d);
    RenderStats s1, s2;
    RenderControl control;
    const Image a = render(zb, dz, control, s1), b = render(rc, d, control, s2);
    const double share = fraction_within(a, b, 2.0f / 255);
    EXPECT_GE(share, 0.99);
    RecordProperty("share_within_2_255", std::to_string(share));
}

TEST(Pipelines, RaytraceGivesTheSameBitsForAnyThreadCount) {
    SceneDesc d = load_scene("demo:whitted", {{"image.width", "203"}, {"image.height", "151"}});
    const BuiltScene scene = build_scene(d);
    RenderStats s1, s2;
    RenderControl one, two;
    one.threads = 1;
    two.threads = 2;
    const Image a = render(scene, d, one, s1), b = render(scene, d, two, s2);
    ASSERT_EQ(a.pixels.size(), b.pixels.size());
    EXPECT_EQ(0, std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(Rgb)));
    EXPECT_EQ(s1.rays_shadow, s2.rays_shadow);
    EXPECT_EQ(s1.rays_reflection, s2.rays_reflection);
    EXPECT_GT(s1.rays_refraction, 0u);
}

// BatchTracer::samples() traces neighbouring camera rays as one packet and shades their hits
// side by side (shade_lanes()); in raytrace their ray trees go level by level, the rays of one
// depth side by side (trace_trees()). Whitted::sample() goes one ray at a time with shade() and
// trace()'s recursion. Both give every pixel the same bits and count the same rays (in
// all and sample by sample) and primitive tests, on scenes with checkers, Schlick's metals,
// glass, a mesh, light spheres and a packet's worth of misses; with the tree's attenuation and
// min_weight; and with trees larger than a batch keeps (kHall: a closed box of half-mirror,
// half-clear panes, some 230 secondary rays a pixel at max_depth 11, more than kMaxTreeRays in a
// run of 61 samples: the rest go depth-first); in runs of 61 samples and in one call for them all.
constexpr std::string_view kHall = R"json({
  "image": { "width": 16, "height": 12, "background": [0.2, 0.3, 0.4] },
  "camera": { "projection": "perspective", "position": [0.1, 0.2, 0.3],
              "look_at": [-0.4, 0.1, -1], "up": [0, 1, 0], "fov_y": 60 },
  "render": { "pipeline": "raytrace", "model": "phong", "max_depth": 11, "min_weight": 0 },
  "lights": [ { "position": [0.3, 0.6, 0.2], "intensity": 2 } ],
  "materials": {
    "pane": { "ka": 0.1, "kd": 0.3, "ks": 0.2, "n": 10, "reflection": 0.5,
              "transparency": 0.4, "ior": 1.0 },
    "tile": { "ka": 0.1, "kd": 0.6, "ks": 0, "n": 1, "reflection": 0.3, "transparency": 0.3,
              "ior": 1.0, "checker": { "size": 0.5, "ka": 0.05, "kd": 0.2 } }
  },
  "objects": [
    { "type": "plane", "point": [1, 0, 0], "normal": [-1, 0, 0], "material": "pane" },
    { "type": "plane", "point": [-1, 0, 0], "normal": [1, 0, 0], "material": "pane" },
    { "type": "plane", "point": [0, 0, 1], "normal": [0, 0, -1], "material": "pane" },
    { "type": "plane", "point": [0, 0, -1], "normal": [0, 0, 1], "material": "pane" },
    { "type": "plane", "point": [0, -1, 0], "normal": [0, 1, 0], "material": "pane" },
    { "type": "plane", "point": [0, 1.5, 0], "normal": [0, -1, 0], "material": "tile" }
  ]
})json";

TEST(Pipelines, PacketsGiveTheBitsAndCountsOfOneRayAtATime) {
    using Overrides = std::vector<Override>;
    struct Case {
        const char* demo;  // nullptr: kHall
        Overrides overrides;
    };
    const std::vector<Case> cases = {
        {"demo:whitted", {}},
        {"demo:materials", {}},
        {"demo:bunny", {}},
        {"demo:whitted", {{"render.tree_attenuation", "true"}, {"render.min_weight", "0.05"}}},
        {"demo:materials", {{"render.tree_attenuation", "true"}, {"render.min_weight", "0.2"}}},
        {nullptr, {}},
        {nullptr, {{"lights.0.radius", "0.1"}}},  // a light sphere seen in the mirrors
        {"demo:whitted", {{"lights.0.radius", "0.5"}}},
    };
    for (const Case& test : cases) {
        for (const Pipeline pipeline : {Pipeline::raycast, Pipeline::raytrace}) {
            Overrides overrides = {{"image.width", test.demo ? "67" : "64"},
                                   {"image.height", test.demo ? "45" : "8"}};
            overrides.insert(overrides.end(), test.overrides.begin(), test.overrides.end());
            SceneDesc d = test.demo ? load_scene(test.demo, overrides)
                                    : parse_scene(kHall, "hall.json", ".", overrides);
            d.render.pipeline = pipeline;
            const BuiltScene scene = build_scene(d);
            const Whitted tracer(scene, d, pipeline == Pipeline::raytrace);
            const BatchTracer batch(tracer);
            TraceCounters one, packets;
            std::vector<float> xs, ys;
            for (int y = 0; y < d.image.height; ++y) {
                for (int x = 0; x < d.image.width; ++x) {
                    xs.push_back(x + 0.5f);
                    ys.push_back(y + 0.5f);
                }
            }
            const int n = static_cast<int>(xs.size());
            std::vector<Rgb> a(xs.size()), b(xs.size());
            std::vector<uint64_t> rays_one(xs.size()), rays_packets(xs.size());
            std::vector<uint64_t> secondary_one(xs.size());  // reflected and refracted rays
            for (int k = 0; k < n; ++k) {
                const uint64_t before = work_of(one), secondary = one.reflection + one.refraction;
                a[k] = tracer.sample(xs[k], ys[k], one);
                rays_one[k] = work_of(one) - before;
                secondary_one[k] = one.reflection + one.refraction - secondary;
            }
            for (int first = 0; first < n; first += 61)  // uneven runs: partial packets too
                batch.samples(&xs[first], &ys[first], std::min(61, n - first), packets, &b[first],
                              &rays_packets[first]);
            if (!test.demo && pipeline == Pipeline::raytrace) {
                uint64_t most = 0;  // the most secondary rays of a run of 61 samples
                for (int first = 0; first < n; first += 61) {
                    const auto run = secondary_one.begin() + first;
                    most = std::max(
                        most, std::accumulate(run, run + std::min(61, n - first), uint64_t{0}));
                }
                EXPECT_GT(most, kMaxTreeRays) << "the hall's trees overflow a batch";
            }
            // All the samples in one call: several batches of 64.
            std::vector<Rgb> whole(xs.size());
            TraceCounters once;
            batch.samples(xs.data(), ys.data(), n, once, whole.data());
            EXPECT_EQ(std::memcmp(whole.data(), b.data(), whole.size() * sizeof(Rgb)), 0);
            EXPECT_EQ(work_of(once), work_of(one));
            const std::string what = std::string(test.demo ? test.demo : "hall") + " pipeline " +
                                     std::to_string(static_cast<int>(pipeline)) + " overrides " +
                                     std::to_string(test.overrides.size());
            int lit = 0;
            for (int k = 0; k < n; ++k) {
                for (int c = 0; c < 3; ++c) {
                    ASSERT_EQ(std::bit_cast<uint32_t>(a[k][c]), std::bit_cast<uint32_t>(b[k][c]))
                        << what << " sample " << k;
                }
                ASSERT_EQ(rays_one[k], rays_packets[k]) << what << " sample " << k;
                lit += a[k] != d.image.background;
            }
            EXPECT_GT(lit, n / 3) << what;
            EXPECT_EQ(one.primary, packets.primary) << what;
            EXPECT_EQ(one.shadow, packets.shadow) << what;
            EXPECT_EQ(one.reflection, packets.reflection) << what;
            EXPECT_EQ(one.refraction, packets.refraction) << what;
            // Down a deeper BVH a packet's shadow rays test the last occluder first
            // (ShadowCache): other primitive tests, the same transmittances.
            if (scene.root_leaf != 0) {
                EXPECT_EQ(one.tests.primitive, packets.tests.primitive) << what;
            } else {
                EXPECT_GT(packets.tests.primitive, 0u) << what;
            }
            if (pipeline == Pipeline::raytrace) {
                EXPECT_GT(one.reflection + one.refraction, static_cast<uint64_t>(n / 8)) << what;
            }
            // A packet goes down the BVH nearest child first for the packet, not for each ray:
            // a ray may enter a box it alone would have skipped (more box tests, same hits).
            if (scene.root_leaf != 0) {
                EXPECT_EQ(one.tests.bounds, packets.tests.bounds) << what;
            }
        }
    }
}

}  // namespace
}  // namespace luz
