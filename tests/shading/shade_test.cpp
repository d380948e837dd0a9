// shade() against values computed by hand from the formulas of SPEC §1.
#include "shading/shade.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace luz {
namespace {

constexpr float kTol = 1e-5f;

void expect_rgb(const Rgb& got, const Rgb& want, float tol = kTol) {
    EXPECT_NEAR(got.x, want.x, tol);
    EXPECT_NEAR(got.y, want.y, tol);
    EXPECT_NEAR(got.z, want.z, tol);
}

Material slide_material() {
    Material m;  // the slide's tested values: Ka = 0.1, Kd = 0.45
    m.ks = Rgb{0.5f};
    m.n = 10;
    return m;
}

ShadingPoint point_at_origin(const Material& m, Vec3 S = {0, 0, 1}) {
    return {Vec3{0, 0, 0}, Vec3{0, 0, 1}, Vec3{0, 0, 1}, normalize(S), &m};
}

TEST(Shade, LambertIsAmbientPlusCosineLaw) {
    const Material m = slide_material();
    // Light at 60° from the normal: cosθ = 0.5, at distance 2 (no effect under lambert).
    const std::vector<Light> lights{{Vec3{0, std::sqrt(3.0f), 1.0f}, Rgb{1.0f}, 0}};
    const Lighting lighting{Model::lambert, Rgb{1.0f}, 1.0f, lights};
    const Rgb I = shade(point_at_origin(m), lighting, AllVisible{});
    // I = Ia·Ka + Il·Kd·cosθ = 0.1 + 0.45·0.5
    expect_rgb(I, Rgb{0.325f});
}

TEST(Shade, PhongSpecularPeaksWhereRequalsS) {
    const Material m = slide_material();
    const float d = 3.0f;
    // L at 45° in the y-z plane; the viewer at the mirror direction S = R.
    const Vec3 L = normalize(Vec3{0, 1, 1});
    const std::vector<Light> lights{{L * d, Rgb{2.0f}, 0}};
    const Lighting lighting{Model::phong, Rgb{1.0f}, 1.0f, lights};
    LightTerm t[1];
    ShadeTerms terms{Rgb{}, t};
    const Rgb I = shade(point_at_origin(m, {0, -1, 1}), lighting, AllVisible{}, &terms);
    const float cos_theta = std::sqrt(0.5f);
    // I = Ia·Ka + Il/(d+K)·(Kd·cosθ + Ks·1^n)
    const float want = 0.1f + 2.0f / (d + 1.0f) * (0.45f * cos_theta + 0.5f);
    expect_rgb(I, Rgb{want});
    EXPECT_NEAR(t[0].cos_alpha, 1.0f, kTol);
    // Moving the viewer off the mirror direction lowers the highlight as cosα^n.
    const Vec3 S = normalize(Vec3{0, -1, 2});
    const Rgb off = shade(point_at_origin(m, S), lighting, AllVisible{});
    const float cos_alpha = dot(normalize(Vec3{0, -1, 1}), S);
    const float want_off =
        0.1f + 2.0f / (d + 1.0f) * (0.45f * cos_theta + 0.5f * std::pow(cos_alpha, 10.0f));
    expect_rgb(off, Rgb{want_off});
}

TEST(Shade, LinearFalloffOneOverDPlusK) {
    Material m = slide_material();
    m.ka = Rgb{0.0f};
    m.ks = Rgb{0.0f};
    for (float K : {0.5f, 1.0f, 4.0f}) {
        for (float d : {1.0f, 2.0f, 10.0f}) {
            const std::vector<Light> lights{{Vec3{0, 0, d}, Rgb{3.0f}, 0}};
            const Lighting lighting{Model::phong, Rgb{1.0f}, K, lights};
            const Rgb I = shade(point_at_origin(m), lighting, AllVisible{});
            expect_rgb(I, Rgb{3.0f / (d + K) * 0.45f});  // Il/(d+K)·Kd·cos 0
        }
    }
}

TEST(Shade, ColouredLightsAddPerChannel) {
    Material m = slide_material();
    m.ka = Rgb{0.1f, 0.2f, 0.3f};
    m.kd = Rgb{0.4f, 0.5f, 0.6f};
    m.ks = Rgb{0.0f};
    const std::vector<Light> lights{{Vec3{0, 0, 1}, Rgb{1.0f, 0.0f, 0.0f}, 0},
                                    {Vec3{0, 0, 3}, Rgb{0.0f, 2.0f, 4.0f}, 0}};
    const Lighting lighting{Model::phong, Rgb{0.5f, 1.0f, 2.0f}, 1.0f, lights};
    const Rgb I = shade(point_at_origin(m), lighting, AllVisible{});
    // Ia·Ka + Il_1/(1+1)·Kd + Il_2/(3+1)·Kd, channel by channel.
    const Rgb want{0.5f * 0.1f + 0.5f * 0.4f, 1.0f * 0.2f + 0.5f * 0.5f, 2.0f * 0.3f + 1.0f * 0.6f};
    expect_rgb(I, want);
}

TEST(Shade, LightBehindTheSurfaceGivesNoDiffuseNorSpecular) {
    const Material m = slide_material();
    // N·L < 0 while R·S > 0 would hold for the formula's R: the specular must still be 0.
    const std::vector<Light> lights{{Vec3{0, 1, -1}, Rgb{5.0f}, 0}};
    const Lighting lighting{Model::phong, Rgb{1.0f}, 1.0f, lights};
    LightTerm t[1];
    ShadeTerms terms{Rgb{}, t};
    const Rgb I = shade(point_at_origin(m, {0, 1, 0.01f}), lighting, AllVisible{}, &terms);
    expect_rgb(I, Rgb{0.1f});
    expect_rgb(t[0].specular, Rgb{0.0f});
    expect_rgb(t[0].diffuse, Rgb{0.0f});
}

TEST(Shade, NormalFlipsTowardsTheViewer) {
    const Material m = slide_material();
    // The viewer and the light are below a surface whose normal points up.
    const std::vector<Light> lights{{Vec3{0, 0, -2}, Rgb{1.0f}, 0}};
    const Lighting lighting{Model::lambert, Rgb{1.0f}, 1.0f, lights};
    LightTerm t[1];
    ShadeTerms terms{Rgb{}, t};
    const Rgb I = shade(point_at_origin(m, {0, 0, -1}), lighting, AllVisible{}, &terms);
    EXPECT_TRUE(terms.flipped);
    expect_rgb(I, Rgb{0.1f + 0.45f});
    // Seen from above, the same light lights nothing.
    const Rgb above = shade(point_at_origin(m, {0, 0, 1}), lighting, AllVisible{});
    expect_rgb(above, Rgb{0.1f});
}

TEST(Shade, TermsAddUpToTheColourAndVisibilityScales) {
    const Material m = slide_material();
    const std::vector<Light> lights{{Vec3{1, 1, 2}, Rgb{3.0f, 2.0f, 1.0f}, 0},
                                    {Vec3{-2, 0, 1}, Rgb{1.0f}, 0},
                                    {Vec3{0, 0, -1}, Rgb{1.0f}, 0}};
    const Lighting lighting{Model::phong, Rgb{1.0f}, 1.0f, lights};
    std::vector<size_t> asked;
    auto vis = [&](size_t j, const Vec3&, const Vec3&, float) {
        asked.push_back(j);
        return j == 0 ? 0.25f : 1.0f;
    };
    LightTerm t[3];
    ShadeTerms terms{Rgb{}, t};
    const Rgb I = shade(point_at_origin(m, {0.3f, 0.2f, 1}), lighting, vis, &terms);
    Rgb sum = terms.ambient;
    for (const LightTerm& lt : t) sum += lt.diffuse + lt.specular;
    expect_rgb(I, sum);
    // Light 2 is behind the surface: its visibility is never asked (no shadow ray needed).
    EXPECT_EQ(asked, (std::vector<size_t>{0, 1}));
    EXPECT_FLOAT_EQ(t[0].visibility, 0.25f);
    const Rgb unshadowed = shade(point_at_origin(m, {0.3f, 0.2f, 1}), lighting, AllVisible{});
    expect_rgb(unshadowed - I, (t[0].diffuse + t[0].specular) * 3.0f);
}

TEST(Shade, CheckerReplacesKaKdInOddCells) {
    Material m = slide_material();
    m.ks = Rgb{0.0f};
    m.checker = Checker{1.0f, Rgb{0.0f}, Rgb{0.9f}};
    const std::vector<Light> lights{{Vec3{0.5f, 10, 0.5f}, Rgb{1.0f}, 0}};
    const Lighting lighting{Model::lambert, Rgb{1.0f}, 1.0f, lights};
    auto at = [&](Vec3 P) {
        // A floor at y = 0 seen from above: the cell is chosen just below the surface.
        return shade(ShadingPoint{P, {0, 1, 0}, {0, 1, 0}, {0, 1, 0}, &m}, lighting, AllVisible{});
    };
    const Vec3 L0 = normalize(Vec3{0.5f, 10, 0.5f} - Vec3{0.5f, 0, 0.5f});
    // (0.5, 0, 0.5): cell (0, −1, 0), odd → checker constants.
    expect_rgb(at({0.5f, 0, 0.5f}), Rgb{0.0f + 0.9f * L0.y});
    // (1.5, 0, 0.5): cell (1, −1, 0), even → the material's own.
    const Vec3 L1 = normalize(Vec3{0.5f, 10, 0.5f} - Vec3{1.5f, 0, 0.5f});
    expect_rgb(at({1.5f, 0, 0.5f}), Rgb{0.1f + 0.45f * L1.y});
}

}  // namespace
}  // namespace luz

// phong_power() is std::pow(cosα, n) bit for bit, including where the power underflows to 0
// (taken without pow) and 0^n = 0; exponents as the presets and users set them.
TEST(Shade, PhongPowerIsPowIncludingUnderflow) {
    int underflows = 0;
    for (float n : {1.0f, 2.5f, 10.0f, 50.0f, 200.0f, 500.0f, 1000.0f, 10000.0f}) {
        for (float c = 1.0f; c > 1e-30f; c *= 0.937f) {
            const float p = std::pow(c, n);
            EXPECT_EQ(luz::phong_power(c, n), p) << "cos " << c << " n " << n;
            underflows += p == 0.0f;
        }
        EXPECT_EQ(luz::phong_power(0.0f, n), 0.0f);
        const float tiny = std::nextafter(0.0f, 1.0f);
        EXPECT_EQ(luz::phong_power(tiny, n), std::pow(tiny, n));
    }
    EXPECT_GT(underflows, 100);  // the sweep does reach the underflow region
}
