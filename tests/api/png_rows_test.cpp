// render_png() (the CLI's `-o X.png`): a ray-traced image rendered band by band into one buffer
// of rows and compressed as it goes makes the very PNG bytes, and the very counts, of the whole
// image rendered and then encoded; renders it cannot band are rendered whole, then encoded.
#include <gtest/gtest.h>

#include <atomic>
#include <string>
#include <vector>

#include "image/image_io.h"
#include "luz/luz.h"
#include "luz/render_png.h"

namespace luz {
namespace {

SceneDesc scene(const std::string& name, int width, int height,
                std::vector<std::string> sets = {}) {
    std::vector<Override> o;
    for (const std::string& s : sets) o.push_back(parse_set(s));
    o.push_back(parse_set("image.width=" + std::to_string(width)));
    o.push_back(parse_set("image.height=" + std::to_string(height)));
    return load_scene(name, o);
}

void expect_same_counts(const RenderStats& a, const RenderStats& b) {
    EXPECT_EQ(a.width, b.width);
    EXPECT_EQ(a.height, b.height);
    EXPECT_EQ(a.samples, b.samples);
    EXPECT_EQ(a.rays_primary, b.rays_primary);
    EXPECT_EQ(a.rays_shadow, b.rays_shadow);
    EXPECT_EQ(a.rays_reflection, b.rays_reflection);
    EXPECT_EQ(a.rays_refraction, b.rays_refraction);
    EXPECT_EQ(a.tests_primitive, b.tests_primitive);
    EXPECT_EQ(a.tests_bounds, b.tests_bounds);
    EXPECT_EQ(a.triangles, b.triangles);
    EXPECT_EQ(a.bvh_nodes, b.bvh_nodes);
}

struct Case {
    std::string scene;
    std::vector<std::string> sets;
};

// Bands of at most 1024 rows, equal and whole PNG bands: 1500 rows are 768 + 732; 83 columns
// are not whole tiles.
TEST(RenderPng, BandsMakeTheBytesAndCountsOfTheWholeImage) {
    const Case cases[] = {
        {"demo:whitted", {}},
        {"demo:whitted", {"render.antialias.mode=\"grid\"", "render.antialias.samples=4"}},
        {"demo:whitted",
         {"render.antialias.mode=\"grid\"", "render.antialias.jitter=true",
          "image.encoding=\"srgb\""}},
        {"demo:materials", {"render.pipeline=\"raycast\""}},
        {"demo:bunny", {}},  // a mesh: the BVH
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.scene + (c.sets.empty() ? "" : " " + c.sets[0]));
        const SceneDesc d = scene(c.scene, 83, 1500, c.sets);
        const Scene s = build(d);
        RenderOptions options;
        options.threads = 2;
        const Frame whole = render(s, d, options);
        const PngFrame banded = render_png(s, d, options, d.image.encoding);
        ASSERT_TRUE(banded.complete);
        EXPECT_EQ(banded.png, encode_image("x.png", whole.image, d.image.encoding));
        expect_same_counts(banded.stats, whole.stats);
    }
}

// Renders that cannot be banded are rendered whole, then encoded: adaptive antialiasing and the
// tent filter (samples shared across rows), the zbuffer, terms, regions.
TEST(RenderPng, OtherRendersAreEncodedWhole) {
    const Case cases[] = {
        {"demo:whitted", {"render.antialias.mode=\"adaptive\""}},
        {"demo:whitted", {"render.antialias.mode=\"grid\"", "render.antialias.filter=\"tent\""}},
        {"demo:primitives", {}},  // zbuffer
    };
    for (const Case& c : cases) {
        const SceneDesc d = scene(c.scene, 40, 30, c.sets);
        const Scene s = build(d);
        const PngFrame f = render_png(s, d, {}, Encoding::linear);
        EXPECT_EQ(f.png, encode_image("x.png", render(s, d).image, Encoding::linear)) << c.scene;
    }
    const SceneDesc d = scene("demo:whitted", 40, 30);
    const Scene s = build(d);
    RenderOptions region;
    region.region = PixelRect{0, 0, 10, 10};
    EXPECT_EQ(render_png(s, d, region, Encoding::linear).png,
              encode_image("x.png", render(s, d, region).image, Encoding::linear));
}

// A Frame owns its image whatever the output will be: a ray-traced render that render_png()
// would band keeps its float image of the whole size in render().
TEST(RenderPng, FrameAlwaysHoldsItsImage) {
    const SceneDesc d = scene("demo:whitted", 40, 30);
    const Frame f = render(build(d), d);
    EXPECT_EQ(f.image.width, 40);
    EXPECT_EQ(f.image.height, 30);
    EXPECT_EQ(encode_frame(f, "x.png", Encoding::linear),
              render_png(build(d), d, {}, Encoding::linear).png);
}

// Cancelled before it starts: incomplete, and no file.
TEST(RenderPng, CancelledRenderHasNoFile) {
    const SceneDesc d = scene("demo:whitted", 40, 300);
    std::atomic<bool> cancel{true};
    RenderOptions o;
    o.cancel = &cancel;
    const PngFrame f = render_png(build(d), d, o, Encoding::linear);
    EXPECT_FALSE(f.complete);
    EXPECT_TRUE(f.png.empty());
}

}  // namespace
}  // namespace luz
