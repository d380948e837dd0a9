// The scene key `attenuation` (docs/SCENES.md#models): phong's light term Il, Il/(d+K) or Il/d² in
// every pipeline, per-term images that still add up, the ray tree's A per law, and the implicit
// light.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "luz/inspect.h"
#include "luz/luz.h"

namespace luz {
namespace {

constexpr float kOneLevel = 1.0f / 255;

/// One sphere straight ahead, orthographic, one light: the centre pixel by hand (as the test
/// Aov.CentrePixelTermsEqualTheHandComputedModel).
SceneDesc one_sphere(const std::string& pipeline, const std::string& law) {
    const char* json = R"({
      "image": {"width": 33, "height": 33},
      "camera": {"position": [0, 0, 10], "look_at": [0, 0, 0], "view_height": 3},
      "render": {"tessellation": 256},
      "attenuation_k": 2,
      "lights": [{"position": [0, 4, 9], "intensity": [6, 5, 4]}],
      "objects": [{"type": "sphere", "radius": 1,
                   "material": {"ka": 0.1, "kd": 0.45, "ks": 0.5, "n": 10}}]})";
    return parse_scene(json, "sphere.json", ".",
                       {{"render.pipeline", pipeline}, {"attenuation", law}});
}

Frame render_with_terms(const SceneDesc& d) {
    RenderOptions o;
    o.aovs = all_aovs();
    return render(build(d), d, o);
}

TEST(Attenuation, CentrePixelFollowsTheLawInEveryPipeline) {
    // P = (0, 0, 1), N = S = (0, 0, 1); the light at d = √80, cosθ = cosα = 8/d (K = 2).
    const double d = std::sqrt(80.0), cos_theta = 8 / d;
    const double local = 0.45 * cos_theta + 0.5 * std::pow(8 / d, 10.0);  // Kd·cosθ + Ks·cosα^n
    const Rgb Il{6, 5, 4};
    const struct {
        const char* law;
        double factor;  // what multiplies Il
    } laws[] = {{"none", 1.0}, {"linear", 1 / (d + 2)}, {"inverse_square", 1 / 80.0}};
    for (const char* pipeline : {"zbuffer", "raycast", "raytrace"}) {
        for (const auto& law : laws) {
            SCOPED_TRACE(std::string(pipeline) + " " + law.law);
            const SceneDesc desc = one_sphere(pipeline, law.law);
            EXPECT_EQ(desc.attenuation, std::string(law.law) == "none" ? Attenuation::none
                                        : std::string(law.law) == "linear"
                                            ? Attenuation::linear
                                            : Attenuation::inverse_square);
            const Frame plain = render(build(desc), desc);
            const Frame f = render_with_terms(desc);
            for (int c = 0; c < 3; ++c) {
                // I = Ia·Ka + Il·factor·(Kd·cosθ + Ks·cosα^n), to 1/255
                const double want = 0.1 + Il[c] * law.factor * local;
                EXPECT_NEAR(plain.image.at(16, 16)[c], want, kOneLevel);
                EXPECT_NEAR(f.image.at(16, 16)[c], want, kOneLevel);
                EXPECT_NEAR(f.aov("diffuse")->image.at(16, 16)[c],
                            Il[c] * law.factor * 0.45 * cos_theta, kOneLevel);
                // the terms add up to the image
                const Rgb sum = f.aov("ambient")->image.at(16, 16) +
                                f.aov("diffuse")->image.at(16, 16) +
                                f.aov("specular")->image.at(16, 16);
                EXPECT_NEAR(sum[c], f.image.at(16, 16)[c], 1e-6f);
            }
        }
    }
}

TEST(Attenuation, LambertIsTheSameUnderEveryLaw) {
    for (const char* pipeline : {"zbuffer", "raytrace"}) {
        SceneDesc a = one_sphere(pipeline, "none"), b = one_sphere(pipeline, "inverse_square");
        a.render.model = b.render.model = Model::lambert;
        const Frame fa = render(build(a), a), fb = render(build(b), b);
        EXPECT_TRUE(fa.image.pixels == fb.image.pixels) << pipeline;
    }
}

/// A mirror (no local light: Ka = Kd = Ks = 0) seen at 45°; its reflected ray meets a light
/// sphere of colour 0.5 after a segment of length 3. tree_attenuation on, K = 1.
SceneDesc mirror(const std::string& law) {
    const char* json = R"({
      "image": {"width": 33, "height": 33, "background": 0},
      "camera": {"position": [0, 5, 5], "look_at": [0, 0, 0], "view_height": 0.5},
      "render": {"pipeline": "raytrace", "max_depth": 1, "tree_attenuation": true},
      "lights": [{"position": [0, 2.8284271, -2.8284271], "intensity": 0.5, "radius": 1}],
      "objects": [{"type": "triangle", "vertices": [[-9, 0, -9], [9, 0, -9], [0, 0, 9]],
                   "material": {"ka": 0, "kd": 0, "ks": 0, "reflection": 1}}]})";
    return parse_scene(json, "mirror.json", ".", {{"attenuation", law}});
}

TEST(Attenuation, TreeAttenuationAFollowsTheLaw) {
    // centre pixel = reflection · A · 0.5 with A = 1/(3 + K), 1, 1/3²
    const struct {
        const char* law;
        float A;
    } laws[] = {{"linear", 0.25f}, {"none", 1.0f}, {"inverse_square", 1.0f / 9}};
    for (const auto& law : laws) {
        SCOPED_TRACE(law.law);
        const SceneDesc d = mirror(law.law);
        const Frame batch = render(build(d), d);  // the batch engine
        const Frame f = render_with_terms(d);     // the reference, observed
        EXPECT_NEAR(batch.image.at(16, 16).x, 0.5f * law.A, 1e-4f);
        EXPECT_NEAR(f.image.at(16, 16).x, 0.5f * law.A, 1e-4f);
        EXPECT_NEAR(f.aov("reflected")->image.at(16, 16).y, 0.5f * law.A, 1e-4f);
        // the ray tree the viewer shows records the same A
        const RayTree tree = ray_tree(build(d), d, 16.5f, 16.5f);
        ASSERT_GE(tree.nodes.size(), 2u);
        EXPECT_NEAR(tree.nodes[1].A, law.A, 1e-5f);
    }
}

TEST(Attenuation, ImplicitLightGivesOneAtTheLookAtPointUnderEveryLaw) {
    // No lights: Il/divisor = 1 at look_at, d the light's distance to it (K = 1.5).
    const char* json = R"({"attenuation_k": 1.5, "objects": [{"type": "sphere"}]})";
    const float Il_linear =
        parse_scene(json, "s.json", ".", {{"attenuation", "linear"}}).lights.at(0).intensity.x;
    const float d = Il_linear - 1.5f;
    EXPECT_GT(d, 1.0f);
    EXPECT_EQ(parse_scene(json, "s.json", ".", {{"attenuation", "none"}}).lights.at(0).intensity,
              Rgb{1.0f});
    EXPECT_NEAR(parse_scene(json, "s.json", ".", {{"attenuation", "inverse_square"}})
                    .lights.at(0)
                    .intensity.x,
                d * d, 1e-4f * d * d);
}

TEST(Attenuation, DefaultIsLinearAndBadValuesNameTheKey) {
    EXPECT_EQ(parse_scene(R"({"objects": []})", "s.json", ".", {}).attenuation,
              Attenuation::linear);
    try {
        parse_scene(R"({"attenuation": "cubic"})", "s.json", ".", {});
        ADD_FAILURE() << "no error";
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("attenuation: unknown value \"cubic\""),
                  std::string::npos)
            << e.what();
    }
}

}  // namespace
}  // namespace luz
