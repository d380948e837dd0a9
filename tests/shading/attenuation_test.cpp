// The distance law of phong's light term (docs/SCENES.md#models `attenuation`): shade() against
// values computed by hand for none (Il), linear (Il/(d+K)) and inverse_square (Il/d²); lambert has
// none.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "shading/shade.h"

namespace luz {
namespace {

constexpr float kAttenuationTol = 1e-5f;

Material slides_material() {
    Material m;  // the slide's tested values: Ka = 0.1, Kd = 0.45
    m.ks = Rgb{0.5f};
    m.n = 10;
    return m;
}

/// shade() at the origin (N = +z) of a light of intensity 2 at distance d, 45° from the normal,
/// seen from the mirror direction (cosα = 1), with K = 1.
Rgb shade_at(Attenuation law, Model model, float d, LightTerm* term = nullptr) {
    static const Material m = slides_material();
    const std::vector<Light> lights{{normalize(Vec3{0, 1, 1}) * d, Rgb{2.0f}, 0}};
    const Lighting lighting{model, Rgb{1.0f}, 1.0f, lights, law};
    LightTerm t[1];
    ShadeTerms terms{Rgb{}, t};
    const ShadingPoint p{Vec3{0, 0, 0}, Vec3{0, 0, 1}, Vec3{0, 0, 1}, normalize(Vec3{0, -1, 1}),
                         &m};
    const Rgb I = shade(p, lighting, AllVisible{}, &terms);
    if (term) *term = t[0];
    return I;
}

TEST(Attenuation, PhongLightTermFollowsTheLaw) {
    const float d = 3.0f, local = 0.45f * std::sqrt(0.5f) + 0.5f;  // Kd·cosθ + Ks·cosα^n
    struct Case {
        Attenuation law;
        float factor;  // Il's divisor
    } cases[] = {{Attenuation::none, 1.0f},
                 {Attenuation::linear, d + 1.0f},
                 {Attenuation::inverse_square, d * d}};
    for (const Case& c : cases) {
        SCOPED_TRACE(static_cast<int>(c.law));
        LightTerm t;
        const Rgb I = shade_at(c.law, Model::phong, d, &t);
        // I = Ia·Ka + Il/divisor·(Kd·cosθ + Ks·cosα^n)
        EXPECT_NEAR(I.x, 0.1f + 2.0f / c.factor * local, kAttenuationTol);
        EXPECT_NEAR(t.diffuse.y, 2.0f / c.factor * 0.45f * std::sqrt(0.5f), kAttenuationTol);
        EXPECT_NEAR(t.specular.z, 2.0f / c.factor * 0.5f, kAttenuationTol);
        EXPECT_NEAR(t.unshadowed.x, t.diffuse.x + t.specular.x, kAttenuationTol);
    }
    // the three differ: 0.1 + 2·local, 0.1 + 0.5·local, 0.1 + (2/9)·local
    EXPECT_GT(shade_at(Attenuation::none, Model::phong, d).x,
              shade_at(Attenuation::linear, Model::phong, d).x + 0.5f);
    EXPECT_GT(shade_at(Attenuation::linear, Model::phong, d).x,
              shade_at(Attenuation::inverse_square, Model::phong, d).x + 0.1f);
}

TEST(Attenuation, InverseSquareQuartersWithTwiceTheDistance) {
    const float near = shade_at(Attenuation::inverse_square, Model::phong, 2.0f).x - 0.1f;
    const float far = shade_at(Attenuation::inverse_square, Model::phong, 4.0f).x - 0.1f;
    EXPECT_NEAR(far, near / 4, kAttenuationTol);
    // and `none` does not change with distance at all
    EXPECT_NEAR(shade_at(Attenuation::none, Model::phong, 2.0f).x,
                shade_at(Attenuation::none, Model::phong, 40.0f).x, kAttenuationTol);
}

TEST(Attenuation, LambertHasNoDistanceTermUnderAnyLaw) {
    // I = Ia·Ka + Il·Kd·cosθ = 0.1 + 2·0.45·cos45°, whatever the law and the distance
    const float want = 0.1f + 2.0f * 0.45f * std::sqrt(0.5f);
    for (Attenuation law : {Attenuation::none, Attenuation::linear, Attenuation::inverse_square}) {
        EXPECT_NEAR(shade_at(law, Model::lambert, 3.0f).x, want, kAttenuationTol);
        EXPECT_NEAR(shade_at(law, Model::lambert, 7.0f).x, want, kAttenuationTol);
    }
}

TEST(Attenuation, DistanceDivisorOfEachLaw) {
    EXPECT_EQ(distance_divisor(Attenuation::linear, 3.0f, 0.5f), 3.5f);
    EXPECT_EQ(distance_divisor(Attenuation::none, 3.0f, 0.5f), 1.0f);
    EXPECT_EQ(distance_divisor(Attenuation::inverse_square, 3.0f, 0.5f), 9.0f);
}

}  // namespace
}  // namespace luz
