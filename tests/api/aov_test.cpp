// Per-term images (docs/SCENES.md#terms): the colour terms add up to the image in every pipeline
// and antialiasing mode; each term holds the hand-computed value; asking for terms changes no bit
// of the image; names are checked.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "luz/luz.h"
#include "same_bits.h"

namespace luz {
namespace {

constexpr AovKind kColourTerms[] = {AovKind::ambient,   AovKind::diffuse,   AovKind::specular,
                                    AovKind::reflected, AovKind::refracted, AovKind::emitted};

Frame render_terms(const SceneDesc& d, int threads = 0) {
    RenderOptions o;
    o.aovs = all_aovs();
    o.threads = threads;
    return render(build(d), d, o);
}

const Image& term(const Frame& f, AovKind k) {
    const Aov* a = f.aov(aov_name(k));
    EXPECT_NE(a, nullptr) << aov_name(k);
    return a->image;
}

/// Largest |Σ colour terms − image| over the frame's pixels and channels, relative to 1 + |I|.
float sum_error(const Frame& f) {
    float worst = 0;
    for (size_t p = 0; p < f.image.pixels.size(); ++p) {
        Rgb sum{0.0f};
        for (AovKind k : kColourTerms) sum += term(f, k).pixels[p];
        for (int c = 0; c < 3; ++c) {
            const float I = f.image.pixels[p][c];
            worst = std::max(worst, std::fabs(sum[c] - I) / (1.0f + std::fabs(I)));
        }
    }
    return worst;
}

/// A scene with everything the sum must hold over: shadows, a mirror, glass (with total internal
/// reflection), a light sphere seen directly and in the mirror, background, two lights.
SceneDesc everything(const char* pipeline, const char* aa) {
    const char* json = R"({
      "image": {"width": 72, "height": 54},
      "camera": {"projection": "perspective", "position": [0, 2.5, 7], "look_at": [0, 0.7, 0]},
      "render": {"max_depth": 4},
      "lights": [{"position": [3, 5, 4], "intensity": 9, "radius": 0.3},
                 {"position": [-4, 3, 2], "intensity": [4, 2, 1]}],
      "materials": {"mirror": {"preset": "metal_polido", "reflection": 0.8},
                    "glass": {"preset": "vidro"}},
      "objects": [
        {"type": "plane", "material": {"checker": {"size": 1, "kd": 0.1}}},
        {"type": "sphere", "center": [-1.2, 1, 0], "material": "mirror"},
        {"type": "sphere", "center": [1.2, 1, 0.5], "radius": 0.8, "material": "glass"},
        {"type": "box", "min": [-0.3, 0, 1.5], "max": [0.3, 0.6, 2.1]}
      ]})";
    std::vector<Override> o{{"render.pipeline", std::string("\"") + pipeline + "\""},
                            {"render.antialias.mode", std::string("\"") + aa + "\""},
                            {"render.antialias.filter", "\"tent\""},
                            {"render.antialias.samples", "4"}};
    return parse_scene(json, "everything.json", ".", o);
}

TEST(Aov, ColourTermsAddUpToTheImageInEveryPipelineAndMode) {
    for (const char* pipeline : {"zbuffer", "raycast", "raytrace"}) {
        for (const char* aa : {"none", "grid", "adaptive"}) {
            const SceneDesc d = everything(pipeline, aa);
            const Frame f = render_terms(d);
            EXPECT_LT(sum_error(f), 2e-6f) << pipeline << " " << aa;
            // Asking for the terms changes no bit of the image.
            EXPECT_TRUE(same_bits(f.image, render(build(d), d).image)) << pipeline << " " << aa;
        }
    }
}

TEST(Aov, RayTracedTermsAreAllPresentWhereTheSceneHasThem) {
    const Frame f = render_terms(everything("raytrace", "none"));
    auto most = [&](AovKind k) {
        float m = 0;
        for (const Rgb& p : term(f, k).pixels) m = std::max(m, max_component(p));
        return m;
    };
    for (AovKind k : {AovKind::ambient, AovKind::diffuse, AovKind::specular, AovKind::reflected,
                      AovKind::refracted, AovKind::emitted, AovKind::shadow})
        EXPECT_GT(most(k), 0.01f) << aov_name(k);
    // Neither zbuffer nor raycast has shadow rays or secondary rays.
    for (const char* pipeline : {"zbuffer", "raycast"}) {
        const Frame g = render_terms(everything(pipeline, "grid"));
        for (AovKind k : {AovKind::reflected, AovKind::refracted, AovKind::shadow})
            for (const Rgb& p : term(g, k).pixels) ASSERT_EQ(p, Rgb{0.0f}) << pipeline;
    }
}

TEST(Aov, SameBitsWhateverTheThreadCount) {
    const SceneDesc d = everything("raytrace", "adaptive");
    const Frame one = render_terms(d, 1), two = render_terms(d, 2);
    for (size_t k = 0; k < one.aovs.size(); ++k)
        EXPECT_TRUE(same_bits(one.aovs[k].image, two.aovs[k].image)) << one.aovs[k].name;
}

/// One sphere straight ahead, orthographic, one light: the centre pixel's terms by hand.
SceneDesc one_sphere(const char* pipeline) {
    const char* json = R"({
      "image": {"width": 33, "height": 33, "background": [0.2, 0.3, 0.4]},
      "camera": {"position": [0, 0, 10], "look_at": [0, 0, 0], "view_height": 3},
      "render": {"tessellation": 256},
      "attenuation_k": 2,
      "lights": [{"position": [0, 4, 9], "intensity": [6, 5, 4]}],
      "objects": [{"type": "sphere", "radius": 1,
                   "material": {"ka": 0.1, "kd": 0.45, "ks": 0.5, "n": 10}}]})";
    return parse_scene(json, "sphere.json", ".",
                       {{"render.pipeline", std::string("\"") + pipeline + "\""}});
}

TEST(Aov, CentrePixelTermsEqualTheHandComputedModel) {
    // P = (0, 0, 1), N = (0, 0, 1), S = (0, 0, 1); light at (0, 4, 9): d = √80, L = (0, 4, 8)/d.
    const double d = std::sqrt(80.0), cos_theta = 8 / d;
    // R = 2(N·L)N − L = (0, −4, 8)/d, cosα = R·S = 8/d.
    const double att = 1 / (d + 2), spec = 0.5 * std::pow(8 / d, 10.0);
    const Rgb Il{6, 5, 4};
    for (const char* pipeline : {"zbuffer", "raycast", "raytrace"}) {
        const Frame f = render_terms(one_sphere(pipeline));
        const float tol = std::string(pipeline) == "zbuffer" ? 2e-3f : 1e-5f;  // tessellation
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(term(f, AovKind::ambient).at(16, 16)[c], 0.1, 1e-6) << pipeline;
            EXPECT_NEAR(term(f, AovKind::diffuse).at(16, 16)[c], Il[c] * att * 0.45 * cos_theta,
                        tol)
                << pipeline;
            EXPECT_NEAR(term(f, AovKind::specular).at(16, 16)[c], Il[c] * att * spec, tol)
                << pipeline;
            EXPECT_NEAR(term(f, AovKind::emitted).at(0, 0)[c], Rgb(0.2f, 0.3f, 0.4f)[c], 0);
            EXPECT_EQ(term(f, AovKind::emitted).at(16, 16)[c], 0.0f);
        }
        // Depth: the camera plane is at z = 10, the sphere's front at z = 1.
        EXPECT_NEAR(term(f, AovKind::depth).at(16, 16).x, 9.0f, tol) << pipeline;
        EXPECT_TRUE(std::isinf(term(f, AovKind::depth).at(0, 0).x)) << pipeline;
        EXPECT_NEAR(term(f, AovKind::normal).at(16, 16).z, 1.0f, tol) << pipeline;
        EXPECT_EQ(term(f, AovKind::normal).at(0, 0), Rgb{0.0f}) << pipeline;
        EXPECT_EQ(term(f, AovKind::shadow).at(16, 16), Rgb{0.0f}) << pipeline;
    }
}

TEST(Aov, ShadowTermIsTheLightTheShadowRayTookAway) {
    // A sphere hangs over a floor between it and the light straight above: the floor under it
    // gets no direct light, and the shadow term is what that light would have given.
    const char* json = R"({
      "image": {"width": 21, "height": 21},
      "camera": {"position": [0, 10, 0.001], "look_at": [0, 0, 0], "up": [0, 0, -1],
                 "view_height": 4},
      "render": {"pipeline": "raytrace"},
      "lights": [{"position": [0, 5, 0], "intensity": 3}],
      "objects": [{"type": "plane"}, {"type": "sphere", "center": [0, 2, 0], "radius": 0.5}]})";
    const SceneDesc d = parse_scene(json, "shadow.json", ".", {});
    const Frame f = render_terms(d);
    const Image& shadow = term(f, AovKind::shadow);
    const Image& diffuse = term(f, AovKind::diffuse);
    // The camera looks straight down, image up = −z: pixel (i, j) sees the floor at
    // x = (i + 0.5 − 10.5)·4/21, z = (j + 0.5 − 10.5)·4/21 unless the sphere (|(x, z)| < 0.5) is
    // in the way. The sphere's shadow on the floor is a disc of radius 5·tan(asin(0.5/3)) ≈ 0.85.
    EXPECT_EQ(shadow.at(0, 0), Rgb{0.0f});  // (−1.9, −1.9): lit, nothing taken away
    const float pixel = 4.0f / 21;
    const int j = 7;
    const float z = (static_cast<float>(j) + 0.5f - 10.5f) * pixel;  // −0.57: floor, shadowed
    ASSERT_GT(std::fabs(z), 0.5f);
    ASSERT_LT(std::fabs(z), 0.8f);
    EXPECT_EQ(diffuse.at(10, j), Rgb{0.0f});  // the sphere blocks the light
    // Unshadowed at P = (0, 0, z), N = (0, 1, 0), S ≈ (0, 1, 0), the default material (Kd 0.45,
    // Ks 0.3, n 20), K = 1: d = |(0, 5, −z)|, cosθ = 5/d, R = (0, 5, z)/d, cosα = R·S = 5/d.
    const double x = 0;
    const double dist = std::sqrt(x * x + 25 + double(z) * z), cos_theta = 5 / dist;
    const double expected = 3 / (dist + 1) * (0.45 * cos_theta + 0.3 * std::pow(cos_theta, 20));
    EXPECT_NEAR(shadow.at(10, j).x, expected, 2e-3);  // S is 1e-4 off vertical
}

TEST(Aov, ZbufferAndRaycastAgreeOnDepthAndNormalUpToTessellation) {
    const Frame z = render_terms(one_sphere("zbuffer")), r = render_terms(one_sphere("raycast"));
    int both = 0;
    for (int j = 0; j < 33; ++j) {
        for (int i = 0; i < 33; ++i) {
            const float dz = term(z, AovKind::depth).at(i, j).x,
                        dr = term(r, AovKind::depth).at(i, j).x;
            if (std::isinf(dz) || std::isinf(dr)) continue;
            ++both;
            EXPECT_NEAR(dz, dr, 0.02f) << i << "," << j;
            const Rgb nz = term(z, AovKind::normal).at(i, j),
                      nr = term(r, AovKind::normal).at(i, j);
            EXPECT_LT(length(nz - nr), 0.02f) << i << "," << j;
        }
    }
    EXPECT_GT(both, 300);  // the sphere covers π·11² ≈ 380 pixels
}

TEST(Aov, TestsCountsIntersectionTestsAndDepthTests) {
    // raycast with accel none: every primary ray tests the one sphere, and nothing else.
    SceneDesc d = one_sphere("raycast");
    d.geometry.accel = Accel::none;
    Frame f = render_terms(d);
    double total = 0;
    for (const Rgb& p : term(f, AovKind::tests).pixels) total += p.x;
    EXPECT_EQ(total, static_cast<double>(f.stats.tests_primitive));
    // zbuffer: behind the sphere's centre pixel lie its front and back triangles.
    f = render_terms(one_sphere("zbuffer"));
    EXPECT_EQ(term(f, AovKind::tests).at(16, 16).x, 2.0f);
    EXPECT_EQ(term(f, AovKind::tests).at(0, 0).x, 0.0f);
}

TEST(Aov, NamesAreCheckedAndAllListsEveryTermOnce) {
    EXPECT_EQ(parse_aov_list("all", "--aov").size(), 10u);
    EXPECT_EQ(parse_aov_list("depth,all,depth", "--aov").front(), AovKind::depth);
    EXPECT_EQ(parse_aov_list("depth,all,depth", "--aov").size(), 10u);
    try {
        parse_aov_list("diffuse,bogus", "--aov diffuse,bogus");
        FAIL() << "no error";
    } catch (const SceneError& e) {
        EXPECT_STREQ(e.what(),
                     "--aov diffuse,bogus: unknown term \"bogus\"; valid: ambient, diffuse, "
                     "specular, reflected, refracted, emitted, shadow, depth, normal, tests, all");
    }
    EXPECT_THROW(parse_aov_list("", "--aov"), SceneError);
}

}  // namespace
}  // namespace luz
