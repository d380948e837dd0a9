// shade_lanes() against shade(), lane for lane and bit for bit: random points, normals, viewers,
// materials (Ks zero or not, many exponents, Schlick's reflectance, checkers whose Ka and Kd the
// caller picks per lane) and lights (in front, behind, several; seen, blocked or through glass
// lane by lane), both models, every attenuation law; and only the active lanes are shaded.
#include "shading/shade_lanes.h"

#include <gtest/gtest.h>

#include <bit>
#include <random>
#include <vector>

namespace luz {
namespace {

Vec3 random_unit(std::mt19937& rng) {
    std::normal_distribution<float> g(0.0f, 1.0f);
    return normalize(Vec3{g(rng), g(rng), g(rng)});
}

Material random_material(std::mt19937& rng, int i) {
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const float exponents[] = {0.5f, 1.0f, 5.0f, 20.0f, 30.0f, 100.0f, 1000.0f, 50000.0f};
    Material m;
    m.ka = Rgb{u(rng), u(rng), u(rng)};
    m.kd = Rgb{u(rng), u(rng), u(rng)};
    m.ks = i % 4 == 0 ? Rgb{0.0f} : (i % 4 == 1 ? Rgb{0.0f, u(rng), 0.0f} : Rgb{u(rng)});
    m.n = exponents[i % 8];
    if (i % 3 == 2) m.reflectance = Reflectance::schlick;  // w(θ) from Ks, up to 1 at grazing
    if (i % 5 == 4) m.checker = Checker{0.5f + u(rng), Rgb{u(rng), 0.0f, u(rng)}, Rgb{u(rng)}};
    return m;
}

/// vis_j at lane k of group g when `shadows` (else 1): lit, blocked, or through glass.
float visibility_of(bool shadows, int group, size_t j, int k) {
    const float vis[] = {1.0f, 0.0f, 0.35f, 0.7f * 0.7f, 1e-3f};
    return shadows ? vis[(group * 7 + static_cast<int>(j) * 3 + k) % 5] : 1.0f;
}

/// Shades `count` random points both ways under `model` and compares every active lane; with
/// `shadows`, each light's visibility varies by lane (as shadow rays give it).
void expect_lanes_match(Model model, int light_count, unsigned seed, bool shadows = false,
                        Attenuation law = Attenuation::linear) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> pos(-5.0f, 5.0f), u(0.0f, 1.0f);
    std::vector<Material> materials;
    for (int i = 0; i < 16; ++i) materials.push_back(random_material(rng, i));
    std::vector<Light> lights;
    for (int j = 0; j < light_count; ++j)
        lights.push_back(
            Light{{pos(rng), pos(rng), pos(rng)}, Rgb{20 * u(rng), 9 * u(rng), 3.0f}, 0});
    const Lighting lighting{model, Rgb{u(rng), u(rng), u(rng)}, 2 * u(rng), lights, law};

    int compared = 0, lit = 0, schlick = 0, checker = 0;
    for (int group = 0; group < 400; ++group) {
        ShadingPoint points[kPacketLanes];
        ShadingLanes p;
        for (int k = 0; k < kPacketLanes; ++k) {
            ShadingPoint& s = points[k];
            s.P = {pos(rng), pos(rng), pos(rng)};
            s.N = random_unit(rng);
            s.Ng = s.N;
            s.S = random_unit(rng);
            s.material = &materials[(group * 3 + k) % materials.size()];
            const Material& m = *s.material;
            const SurfaceConstants c = surface_constants(m, s.P, s.Ng);  // the caller's part
            for (int a = 0; a < 3; ++a) {
                p.P[a][k] = s.P[a];
                p.N[a][k] = s.N[a];
                p.S[a][k] = s.S[a];
                p.ka[a][k] = c.ka[a];
                p.kd[a][k] = c.kd[a];
                p.ks[a][k] = m.ks[a];
            }
            p.n[k] = m.n;
            p.schlick[k] = m.reflectance == Reflectance::schlick ? -1 : 0;
            schlick += m.reflectance == Reflectance::schlick;
            checker += m.checker.has_value();
        }
        const unsigned active = group % 5 == 0 ? 0x5Bu : 0xFFu;
        Lane8f I[3];
        if (shadows) {
            shade_lanes(p, lighting, active, I,
                        [&](size_t j, const Lane8f*, const Lane8f&, unsigned lit) {
                            EXPECT_EQ(lit & ~active, 0u);
                            Lane8f v = lanes(-1.0f);  // never read outside `lit`
                            for (int k = 0; k < kPacketLanes; ++k)
                                if (lit >> k & 1u) v[k] = visibility_of(true, group, j, k);
                            return v;
                        });
        } else {
            shade_lanes(p, lighting, active, I);
        }
        for (int k = 0; k < kPacketLanes; ++k) {
            if (!(active >> k & 1u)) continue;
            const Rgb expected =
                shade(points[k], lighting, [&](size_t j, const Vec3&, const Vec3&, float) {
                    return visibility_of(shadows, group, j, k);
                });
            const Rgb ambient =
                lighting.Ia * surface_constants(*points[k].material, points[k].P, points[k].Ng).ka;
            lit += expected != ambient;
            for (int a = 0; a < 3; ++a) {
                ASSERT_EQ(std::bit_cast<uint32_t>(I[a][k]), std::bit_cast<uint32_t>(expected[a]))
                    << "group " << group << " lane " << k << " component " << a << ": " << I[a][k]
                    << " vs " << expected[a];
            }
            ++compared;
        }
    }
    EXPECT_GT(compared, 2900);
    EXPECT_GT(schlick, 800);  // both kinds of w(θ), with and without checkers, were compared
    EXPECT_GT(checker, 400);
    if (light_count > 0) {
        EXPECT_GT(lit, compared / 4);  // the lights' terms were compared, not only ambient
    } else {
        EXPECT_EQ(lit, 0);
    }
}

TEST(ShadeLanes, PhongMatchesShadeBitForBit) {
    expect_lanes_match(Model::phong, 1, 1);
    expect_lanes_match(Model::phong, 3, 2);
}

TEST(ShadeLanes, LambertMatchesShadeBitForBit) {
    expect_lanes_match(Model::lambert, 1, 3);
    expect_lanes_match(Model::lambert, 2, 4);
}

TEST(ShadeLanes, EveryAttenuationLawMatchesShadeBitForBit) {
    expect_lanes_match(Model::phong, 2, 8, true, Attenuation::none);
    expect_lanes_match(Model::phong, 2, 9, true, Attenuation::inverse_square);
}

TEST(ShadeLanes, NoLightsGiveTheAmbientTerm) { expect_lanes_match(Model::phong, 0, 5); }

TEST(ShadeLanes, VisibilityByLaneMatchesShadeBitForBit) {
    expect_lanes_match(Model::phong, 2, 6, true);
    expect_lanes_match(Model::lambert, 3, 7, true);
}

}  // namespace
}  // namespace luz
