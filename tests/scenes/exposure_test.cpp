// Defaults are tested (docs/SCENES.md#models): every built-in scene, rendered at its own size with
// its own settings, is well exposed — neither too dark nor washed out.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <string>
#include <vector>

#include "geometry/scene.h"
#include "render/render.h"
#include "scene/demo_scenes.h"
#include "scene/scene_loader.h"

namespace luz {
namespace {

std::vector<std::string> demo_names() {
    std::vector<std::string> names;
    for (const DemoScene& d : demo_scenes()) names.emplace_back(d.name);
    return names;
}

struct Exposure {
    size_t object_pixels = 0;  ///< pixels whose colour differs from the background
    double mean = 0;           ///< mean linear value (average of the channels) over them
    double clipped_share = 0;  ///< share of them with a channel ≥ 1.0
};

Exposure measure(const Image& img, const Rgb& background) {
    Exposure e;
    double sum = 0;
    size_t clipped = 0;
    for (const Rgb& c : img.pixels) {
        if (c == background) continue;
        ++e.object_pixels;
        sum += (double(c.x) + c.y + c.z) / 3.0;
        if (c.x >= 1.0f || c.y >= 1.0f || c.z >= 1.0f) ++clipped;
    }
    if (e.object_pixels > 0) {
        e.mean = sum / e.object_pixels;
        e.clipped_share = double(clipped) / e.object_pixels;
    }
    return e;
}

TEST(Measure, CountsOnlyPixelsUnlikeTheBackground) {
    Image img(4, 1, Rgb{0.1f});
    img.at(1, 0) = Rgb{0.5f};
    img.at(2, 0) = Rgb{1.0f, 0.2f, 0.3f};
    const Exposure e = measure(img, Rgb{0.1f});
    EXPECT_EQ(e.object_pixels, 2u);
    EXPECT_NEAR(e.mean, (0.5 + 0.5) / 2, 1e-6);
    EXPECT_DOUBLE_EQ(e.clipped_share, 0.5);
}

TEST(DemoScenes, ThereArePrimitivesAndWhitted) {
    const std::vector<std::string> names = demo_names();
    EXPECT_NE(std::find(names.begin(), names.end(), "primitives"), names.end());
    EXPECT_NE(std::find(names.begin(), names.end(), "whitted"), names.end());
}

class DefaultExposure : public testing::TestWithParam<std::string> {};

TEST_P(DefaultExposure, IsWellExposed) {
    const SceneDesc desc = load_scene("demo:" + GetParam());
    const BuiltScene scene = build_scene(desc);
    RenderStats stats;
    const Image img = render(scene, desc, RenderControl{}, stats);
    ASSERT_EQ(img.width, desc.image.width);
    ASSERT_EQ(img.height, desc.image.height);

    const Exposure e = measure(img, desc.image.background);
    const size_t total = img.pixels.size();
    EXPECT_GT(e.object_pixels, total / 20) << "the objects cover under 5 % of the picture";
    EXPECT_GE(e.mean, 0.2) << "too dark";
    EXPECT_LE(e.mean, 0.8) << "washed out";
    EXPECT_LT(e.clipped_share, 0.01) << "too many pixels with a channel at or above 1.0";
}

INSTANTIATE_TEST_SUITE_P(BuiltIn, DefaultExposure, testing::ValuesIn(demo_names()),
                         [](const testing::TestParamInfo<std::string>& info) {
                             std::string s = info.param;
                             for (char& c : s) {
                                 if (!isalnum(static_cast<unsigned char>(c))) c = '_';
                             }
                             return s;
                         });

}  // namespace
}  // namespace luz
