// Tests of the material presets: all eight, in order, found by both names, constants in range.
#include "scene/presets.h"

#include <gtest/gtest.h>

#include <string>

namespace luz {
namespace {

TEST(Presets, AllEightInTheLecturesOrder) {
    const char* names[][2] = {{"gesso", "plaster"},     {"madeira", "wood"},
                              {"concreto", "concrete"}, {"cortica", "cork"},
                              {"plastico", "plastic"},  {"metal_polido", "polished_metal"},
                              {"agua", "still_water"},  {"vidro", "glass"}};
    ASSERT_EQ(presets().size(), 8u);
    for (std::size_t i = 0; i < 8; ++i) {
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
