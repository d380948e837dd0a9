// shade() against values computed by hand from the formulas of docs/SCENES.md#models.
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

// --- the reflectance curve w(i, λ) (docs/SCENES.md#reflectance) ---

Material schlick_material(Rgb Ks) {
    Material m = slide_material();
    m.ks = Ks;
    m.reflectance = Reflectance::schlick;
    return m;
}

// A light at angle θ from the normal (in the y-z plane, at distance d) and the viewer at its
// mirror direction (cosα = 1): the specular term is Il/(d+K)·w(θ)·1^n.
struct MirrorSetup {
    std::vector<Light> lights;
    Vec3 S;
    MirrorSetup(float cos_theta, float d, float Il) {
        const float sin_theta = std::sqrt(1 - cos_theta * cos_theta);
        lights = {{Vec3{0, sin_theta, cos_theta} * d, Rgb{Il}, 0}};
        S = Vec3{0, -sin_theta, cos_theta};
    }
};

TEST(Reflectance, SchlickIsKsAtNormalIncidence) {
    // w(0°) = Ks + (1 − Ks)·0^5 = Ks, exactly.
    for (const Rgb Ks : {Rgb{0.04f}, Rgb{1.00f, 0.71f, 0.29f}, Rgb{0.0f}, Rgb{1.0f}}) {
        EXPECT_EQ(schlick_reflectance(Ks, 1.0f), Ks);
        EXPECT_EQ(specular_reflectance(schlick_material(Ks), 1.0f), Ks);
    }
}

TEST(Reflectance, SchlickRisesToOneAtGrazing) {
    // w(90°) = Ks + (1 − Ks)·1 = 1, and w grows as cosθ falls.
    for (const Rgb Ks : {Rgb{0.04f}, Rgb{1.00f, 0.71f, 0.29f}, Rgb{0.0f}}) {
        expect_rgb(schlick_reflectance(Ks, 0.0f), Rgb{1.0f}, 1e-6f);
        expect_rgb(specular_reflectance(schlick_material(Ks), 1e-4f), Rgb{1.0f}, 1e-3f);
        Rgb previous = Ks;
        for (float c = 0.95f; c > 0; c -= 0.05f) {
            const Rgb w = schlick_reflectance(Ks, c);
            for (int k = 0; k < 3; ++k) {
                if (Ks[k] < 1) {
                    EXPECT_GT(w[k], previous[k]) << "cos " << c;
                }
            }
            previous = w;
        }
    }
}

TEST(Reflectance, SchlickMidValueByHand) {
    // cosθ = 0.5: (1 − 0.5)^5 = 1/32 = 0.03125.
    // Ks = 0.04: 0.04 + 0.96/32 = 0.07.
    expect_rgb(schlick_reflectance(Rgb{0.04f}, 0.5f), Rgb{0.07f}, 1.0f / 255);
    // Gold's F0 (1.00, 0.71, 0.29): (1, 0.71 + 0.29/32, 0.29 + 0.71/32) = (1, 0.7190625,
    // 0.3121875).
    expect_rgb(schlick_reflectance(Rgb{1.00f, 0.71f, 0.29f}, 0.5f),
               Rgb{1.0f, 0.7190625f, 0.3121875f}, 1.0f / 255);
    // cosθ = 0.1: 0.9^5 = 0.59049; Ks = 0.04: 0.04 + 0.96·0.59049 = 0.6068704.
    expect_rgb(schlick_reflectance(Rgb{0.04f}, 0.1f), Rgb{0.6068704f}, 1.0f / 255);
}

TEST(Reflectance, ConstantIsKsAtEveryAngle) {
    Material m = slide_material();
    m.ks = Rgb{0.04f, 0.5f, 0.9f};
    ASSERT_EQ(m.reflectance, Reflectance::constant);  // the default
    for (float c : {1.0f, 0.5f, 0.1f, 0.0f}) EXPECT_EQ(specular_reflectance(m, c), m.ks);
}

TEST(Shade, SchlickScalesThePhongSpecularByW) {
    // θ = 60° (cosθ = 0.5), viewer at the mirror direction: specular = Il/(d+K)·w(60°).
    const MirrorSetup setup(0.5f, 3.0f, 2.0f);
    const Lighting lighting{Model::phong, Rgb{1.0f}, 1.0f, setup.lights};
    const Material m = schlick_material(Rgb{0.04f, 0.5f, 0.29f});
    LightTerm t[1];
    ShadeTerms terms{Rgb{}, t};
    const Rgb I = shade(point_at_origin(m, setup.S), lighting, AllVisible{}, &terms);
    EXPECT_NEAR(t[0].cos_theta, 0.5f, kTol);
    EXPECT_NEAR(t[0].cos_alpha, 1.0f, kTol);
    // w = Ks + (1 − Ks)/32: (0.07, 0.515625, 0.3121875); Il/(d+K) = 2/4.
    const Rgb w{0.07f, 0.515625f, 0.3121875f};
    expect_rgb(t[0].specular, w * 0.5f);
    // the diffuse term is the model's own: Il/(d+K)·Kd·cosθ
    expect_rgb(t[0].diffuse, Rgb{0.5f * 0.45f * 0.5f});
    expect_rgb(I, Rgb{0.1f} + Rgb{0.5f * 0.45f * 0.5f} + w * 0.5f);
    // The same material with the constant curve: Ks alone.
    Material c = m;
    c.reflectance = Reflectance::constant;
    shade(point_at_origin(c, setup.S), lighting, AllVisible{}, &terms);
    expect_rgb(t[0].specular, Rgb{0.04f, 0.5f, 0.29f} * 0.5f);
}

TEST(Shade, SchlickWithoutKsStillShinesAtGrazing) {
    // Ks = 0: the constant curve has no highlight at all, Schlick's w = (1 − cosθ)^5 still
    // does away from normal incidence (cosθ = 0.1: 0.9^5 = 0.59049), so the fast path that
    // skips the power must look at w, not at Ks.
    const MirrorSetup setup(0.1f, 1.0f, 1.0f);
    const Lighting lighting{Model::phong, Rgb{1.0f}, 1.0f, setup.lights};
    LightTerm t[1];
    ShadeTerms terms{Rgb{}, t};
    Material m = schlick_material(Rgb{0.0f});
    shade(point_at_origin(m, setup.S), lighting, AllVisible{}, &terms);
    expect_rgb(t[0].specular, Rgb{0.59049f * 0.5f}, 1e-4f);  // Il/(d+K) = 1/2, cosα = 1
    // At normal incidence w = Ks = 0: no highlight.
    const MirrorSetup normal(1.0f, 1.0f, 1.0f);
    const Lighting head_on{Model::phong, Rgb{1.0f}, 1.0f, normal.lights};
    shade(point_at_origin(m, normal.S), head_on, AllVisible{}, &terms);
    EXPECT_EQ(t[0].specular, Rgb{0.0f});
    m.reflectance = Reflectance::constant;
    shade(point_at_origin(m, setup.S), lighting, AllVisible{}, &terms);
    EXPECT_EQ(t[0].specular, Rgb{0.0f});
}

TEST(Shade, LambertIgnoresReflectance) {
    // Lambert has no specular term (docs/SCENES.md#reflectance): the curve changes no bit.
    const std::vector<Light> lights{{Vec3{0, 2, 1}, Rgb{1.0f, 0.5f, 2.0f}, 0},
                                    {Vec3{1, 0.1f, 0.2f}, Rgb{3.0f}, 0}};
    const Lighting lighting{Model::lambert, Rgb{0.7f}, 1.0f, lights};
    Material constant = slide_material();
    constant.ks = Rgb{0.04f, 0.5f, 0.9f};
    const Material schlick = schlick_material(constant.ks);
    for (const Vec3 S : {Vec3{0, 0, 1}, Vec3{0, -2, 1}, Vec3{-1, 0.2f, 0.1f}}) {
        LightTerm t[2];
        ShadeTerms terms{Rgb{}, t};
        const Rgb a = shade(point_at_origin(constant, S), lighting, AllVisible{});
        const Rgb b = shade(point_at_origin(schlick, S), lighting, AllVisible{}, &terms);
        EXPECT_EQ(a, b);
        EXPECT_EQ(t[0].specular, Rgb{0.0f});
        EXPECT_EQ(t[1].specular, Rgb{0.0f});
    }
}

/// shade()'s phong before `reflectance` existed (docs/SCENES.md#models, model 2), operation for
/// operation: Ia·Ka + Σ_j vis_j·Il_j/(d_j+K)·(Kd·cosθ_j + Ks·cosα_j^n).
Rgb previous_phong(const ShadingPoint& p, const Lighting& lighting) {
    const Material& m = *p.material;
    const Vec3 N = dot(p.N, p.S) < 0 ? -p.N : p.N;
    Rgb I = lighting.Ia * m.ka;
    for (const Light& light : lighting.lights) {
        const Vec3 to_light = light.position - p.P;
        const float d = length(to_light);
        const Vec3 L = to_light / d;
        const float N_dot_L = dot(N, L);
        if (!(N_dot_L > 0)) continue;
        const Vec3 R = N * (2 * N_dot_L) - L;
        const float R_dot_S = dot(R, p.S);
        const float cos_alpha = R_dot_S > 0 ? R_dot_S : 0.0f;
        const Rgb Il_att = light.intensity * (1.0f / (d + lighting.K));
        const Rgb diffuse = Il_att * m.kd * N_dot_L;
        Rgb specular{0.0f};
        if (max_component(m.ks) > 0) specular = Il_att * m.ks * phong_power(cos_alpha, m.n);
        I += diffuse + specular;
    }
    return I;
}

TEST(Shade, ConstantReflectanceIsThePreviousPhongBitForBit) {
    // The default curve changes no bit of any image (the golden images check whole scenes).
    const std::vector<Light> lights{{Vec3{1, 3, 2}, Rgb{3.0f, 2.0f, 1.0f}, 0},
                                    {Vec3{-2, 0.3f, 1}, Rgb{0.7f}, 0},
                                    {Vec3{0.2f, -1, 4}, Rgb{5.0f}, 0}};
    int lit = 0;
    for (float K : {0.5f, 1.0f, 3.0f}) {
        const Lighting lighting{Model::phong, Rgb{1.0f, 0.8f, 0.6f}, K, lights};
        for (const Rgb Ks : {Rgb{0.0f}, Rgb{0.3f}, Rgb{0.04f, 0.5f, 0.9f}, Rgb{1.0f}}) {
            for (float n : {1.0f, 20.0f, 500.0f}) {
                Material m = slide_material();
                m.ks = Ks;
                m.n = n;
                for (float sx = -1.0f; sx <= 1.0f; sx += 0.25f) {
                    for (float sy = -1.0f; sy <= 1.0f; sy += 0.25f) {
                        const ShadingPoint p = point_at_origin(m, {sx, sy, 0.6f});
                        const Rgb got = shade(p, lighting, AllVisible{});
                        const Rgb want = previous_phong(p, lighting);
                        EXPECT_EQ(got, want) << sx << " " << sy << " n " << n;
                        lit += got != lighting.Ia * m.ka;
                    }
                }
            }
        }
    }
    EXPECT_GT(lit, 1000);  // the sweep does light the point
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
