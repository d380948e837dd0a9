// Tests of the material presets: the lecture's eight and the three metals, in order, found by
// both names, constants in range, the metals' measured Ks and Schlick's curve.
#include "scene/presets.h"

#include <gtest/gtest.h>

#include <string>

namespace luz {
namespace {

TEST(Presets, TheLecturesEightInOrderThenTheThreeMetals) {
    const char* names[][2] = {
        {"gesso", "plaster"},    {"madeira", "wood"},     {"concreto", "concrete"},
        {"cortica", "cork"},     {"plastico", "plastic"}, {"metal_polido", "polished_metal"},
        {"agua", "still_water"}, {"vidro", "glass"},      {"ouro", "gold"},
        {"prata", "silver"},     {"cobre", "copper"}};
    ASSERT_EQ(presets().size(), 11u);
    for (std::size_t i = 0; i < 11; ++i) {
        const Preset& p = presets()[i];
        EXPECT_EQ(p.name, names[i][0]);
        EXPECT_EQ(p.alias, names[i][1]);
        EXPECT_EQ(p.material.name, names[i][0]);
        EXPECT_FALSE(p.description.empty());
        EXPECT_EQ(p.description.find('\n'), std::string_view::npos);
        EXPECT_EQ(find_preset(names[i][0]), &p);
        EXPECT_EQ(find_preset(names[i][1]), &p);
    }
    EXPECT_EQ(find_preset("marble"), nullptr);
    EXPECT_EQ(find_preset(""), nullptr);
}

TEST(Presets, MetalsUseSchlicksCurveFromMeasuredReflectance) {
    // docs/SCENES.md#reflectance, #scene-files: Ks = F(0°), linear RGB, from Hoffman's table
    // (Real-Time Rendering 3rd ed.; see presets.cpp), with `reflectance: schlick` and a mirror.
    const struct {
        const char* name;
        Rgb F0;
    } metals[] = {{"ouro", {1.00f, 0.71f, 0.29f}},
                  {"prata", {0.95f, 0.93f, 0.88f}},
                  {"cobre", {0.95f, 0.64f, 0.54f}}};
    for (const auto& metal : metals) {
        const Material& m = find_preset(metal.name)->material;
        SCOPED_TRACE(metal.name);
        EXPECT_EQ(m.reflectance, Reflectance::schlick);
        EXPECT_EQ(m.ks, metal.F0);
        EXPECT_GE(m.reflection, 0.5f);  // polished: a mirror
        EXPECT_EQ(m.transparency, 0.0f);
        EXPECT_GE(m.n, 100.0f);  // a tight highlight
        // the body colour follows the metal's own (gold: red > green > blue)
        EXPECT_GE(m.kd.x, m.kd.y);
        EXPECT_GE(m.kd.y, m.kd.z);
    }
    // The lecture's eight keep the constant Ks of its practical model.
    for (std::size_t i = 0; i < 8; ++i) {
        EXPECT_EQ(presets()[i].material.reflectance, Reflectance::constant) << presets()[i].name;
    }
}

TEST(Presets, ConstantsInRangeAndAmbientIsADimDiffuse) {
    for (const Preset& p : presets()) {
        const Material& m = p.material;
        SCOPED_TRACE(std::string(p.name));
        for (int c = 0; c < 3; ++c) {
            EXPECT_GE(m.ka[c], 0.0f);
            EXPECT_LE(m.ka[c], 1.0f);
            EXPECT_GE(m.kd[c], 0.0f);
            EXPECT_LE(m.kd[c], 1.0f);
            EXPECT_GE(m.ks[c], 0.0f);
            EXPECT_LE(m.ks[c], 1.0f);
            // Ka ≈ 0.1–0.2 × Kd
            EXPECT_GE(m.ka[c], 0.1f * m.kd[c] - 1e-6f);
            EXPECT_LE(m.ka[c], 0.2f * m.kd[c] + 1e-6f);
        }
        EXPECT_GT(m.n, 0.0f);
        EXPECT_GE(m.reflection, 0.0f);
        EXPECT_LE(m.reflection, 1.0f);
        EXPECT_GE(m.transparency, 0.0f);
        EXPECT_LE(m.transparency, 1.0f);
        EXPECT_GE(m.ior, 1.0f);
        EXPECT_FALSE(m.checker.has_value());
    }
}

TEST(Presets, MatteVersusShiny) {
    for (const char* matte : {"gesso", "madeira", "concreto", "cortica"}) {
        const Material& m = find_preset(matte)->material;
        EXPECT_LE(m.ks.x, 0.15f) << matte;
        EXPECT_LE(m.n, 10.0f) << matte;
        EXPECT_GE(m.kd.x, 0.45f) << matte;
        EXPECT_EQ(m.reflection, 0.0f) << matte;
        EXPECT_EQ(m.transparency, 0.0f) << matte;
    }
    for (const char* shiny : {"plastico", "metal_polido", "agua", "vidro"}) {
        const Material& m = find_preset(shiny)->material;
        EXPECT_GE(m.ks.x, 0.6f) << shiny;
        EXPECT_GE(m.n, 40.0f) << shiny;
    }
    EXPECT_GT(find_preset("gesso")->material.kd.x, 0.75f);  // near-white
    EXPECT_GT(find_preset("metal_polido")->material.reflection, 0.5f);
    EXPECT_FLOAT_EQ(find_preset("agua")->material.ior, 1.33f);
    EXPECT_GT(find_preset("agua")->material.transparency, 0.5f);
    EXPECT_FLOAT_EQ(find_preset("vidro")->material.ior, 1.5f);
    EXPECT_GT(find_preset("vidro")->material.transparency, 0.8f);
    const Material& water = find_preset("agua")->material;
    EXPECT_GT(water.kd.z, water.kd.x);  // blue tint
}

}  // namespace
}  // namespace luz
