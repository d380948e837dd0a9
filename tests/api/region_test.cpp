// Render regions (--region, docs/CLI.md): a rectangle's pixels are bit for bit those of the same
// rectangle of the whole render, in every pipeline and antialiasing mode and filter (the tent
// reads samples of neighbours outside the rectangle, adaptive the corners of its last row and
// column), with the per-term images and the refinement mask cut the same way; bad rectangles
// are refused with the argument's name.
#include <gtest/gtest.h>

#include <cctype>
#include <cstring>
#include <ostream>
#include <string>
#include <vector>

#include "luz/luz.h"
#include "luz/options.h"

namespace luz {
namespace {

/// Whether `part` is bit for bit the rectangle `r` of `whole`.
bool same_bits_as_crop(const Image& part, const Image& whole, const PixelRect& r) {
    if (part.width != r.width() || part.height != r.height()) return false;
    for (int y = r.y0; y < r.y1; ++y) {
        if (std::memcmp(&part.at(0, y - r.y0), &whole.at(r.x0, y), sizeof(Rgb) * r.width()) != 0)
            return false;
    }
    return true;
}

struct RegionCase {
    std::string scene;
    std::vector<std::string> sets;  // PATH=JSON
};

void PrintTo(const RegionCase& c, std::ostream* os) {
    *os << c.scene;
    for (const std::string& s : c.sets) *os << " --set " << s;
}

/// A test name: the scene and the values set, letters and digits only.
std::string case_name(const testing::TestParamInfo<RegionCase>& info) {
    std::string name = info.param.scene.substr(5) + "_" + std::to_string(info.index);
    for (const std::string& s : info.param.sets) {
        name += "_";
        for (char c : s.substr(s.find('=') + 1))
            if (std::isalnum(static_cast<unsigned char>(c))) name += c;
    }
    return name;
}

SceneDesc load(const RegionCase& c) {
    std::vector<Override> o;
    for (const std::string& s : c.sets) o.push_back(parse_set(s));
    o.push_back(parse_set("image.width=83"));  // not a multiple of the tile size
    o.push_back(parse_set("image.height=61"));
    return load_scene(c.scene, o);
}

// Rectangles: inside one tile, across tile borders, at every edge and corner of the image, one
// pixel, one row, the whole image.
const PixelRect kRects[] = {{3, 4, 9, 10},   {10, 12, 50, 40}, {0, 0, 83, 61},   {70, 50, 83, 61},
                            {0, 30, 83, 31}, {47, 0, 48, 61},  {16, 16, 32, 32}, {82, 60, 83, 61}};

class RegionTest : public testing::TestWithParam<RegionCase> {};

TEST_P(RegionTest, PixelsAreThoseOfTheWholeRender) {
    const SceneDesc d = load(GetParam());
    const Scene scene = build(d);
    RenderOptions whole_options;
    whole_options.aovs = all_aovs();
    whole_options.want_aa_mask = true;
    const Frame whole = render(scene, d, whole_options);
    for (const PixelRect& r : kRects) {
        RenderOptions o = whole_options;
        o.region = r;
        o.threads = 1 + (r.x0 % 3);  // and whatever the thread count
        const Frame part = render(scene, d, o);
        const std::string where = std::to_string(r.x0) + "," + std::to_string(r.y0) + "," +
                                  std::to_string(r.x1) + "," + std::to_string(r.y1);
        ASSERT_TRUE(part.complete);
        EXPECT_TRUE(same_bits_as_crop(part.image, whole.image, r)) << where;
        ASSERT_EQ(part.aovs.size(), whole.aovs.size());
        for (size_t k = 0; k < part.aovs.size(); ++k) {
            EXPECT_TRUE(same_bits_as_crop(part.aovs[k].image, whole.aovs[k].image, r))
                << where << " " << part.aovs[k].name;
        }
        ASSERT_EQ(part.aa_mask.width, r.width());
        ASSERT_EQ(part.aa_mask.height, r.height());
        for (int y = r.y0; y < r.y1; ++y)
            for (int x = r.x0; x < r.x1; ++x)
                ASSERT_EQ(part.aa_mask.level[size_t(y - r.y0) * r.width() + (x - r.x0)],
                          whole.aa_mask.level[size_t(y) * whole.aa_mask.width + x])
                    << where;
        EXPECT_EQ(part.stats.width, r.width());
        EXPECT_EQ(part.stats.height, r.height());
        EXPECT_EQ(part.stats.region[2], r.x1);
        // Only the region's tiles are rendered: a small rectangle traces fewer rays.
        if (r.width() * r.height() * 4 < 83 * 61 && d.render.pipeline != Pipeline::zbuffer) {
            EXPECT_LT(part.stats.rays_primary, whole.stats.rays_primary) << where;
        }
    }
}

INSTANTIATE_TEST_SUITE_P(
    EveryPipelineAndAntialiasing, RegionTest,
    testing::Values(
        RegionCase{"demo:whitted", {"render.antialias.mode=\"none\""}},
        RegionCase{"demo:whitted",
                   {"render.antialias.mode=\"grid\"", "render.antialias.samples=4"}},
        RegionCase{"demo:whitted",
                   {"render.antialias.mode=\"grid\"", "render.antialias.samples=9",
                    "render.antialias.filter=\"tent\""}},
        RegionCase{"demo:whitted",
                   {"render.antialias.mode=\"grid\"", "render.antialias.samples=4",
                    "render.antialias.filter=\"tent\"", "render.antialias.jitter=true"}},
        RegionCase{"demo:whitted", {"render.antialias.mode=\"adaptive\""}},
        RegionCase{"demo:whitted",
                   {"render.pipeline=\"raycast\"", "render.antialias.mode=\"adaptive\""}},
        RegionCase{"demo:primitives", {"render.antialias.mode=\"none\""}},
        RegionCase{"demo:primitives",
                   {"render.antialias.mode=\"grid\"", "render.antialias.filter=\"tent\""}},
        RegionCase{"demo:primitives", {"render.antialias.mode=\"adaptive\""}}),
    case_name);

TEST(Region, BadRectanglesAreRefusedNamingTheArgument) {
    const SceneDesc d = load({"demo:whitted", {}});
    const Scene scene = build(d);
    for (const PixelRect& r :
         {PixelRect{5, 5, 5, 9}, PixelRect{0, 0, 0, 0}, PixelRect{0, 0, 84, 10},
          PixelRect{-1, 0, 3, 3}, PixelRect{4, 4, 2, 8}}) {
        RenderOptions o;
        o.region = r;
        try {
            render(scene, d, o);
            ADD_FAILURE() << "no error for " << r.x0 << "," << r.y0 << "," << r.x1 << "," << r.y1;
        } catch (const SceneError& e) {
            EXPECT_EQ(std::string(e.what()).rfind("region: ", 0), 0u) << e.what();
        }
    }
}

TEST(Region, ParseRegionNamesTheOptionAndWhatIsWrong) {
    ImageDesc img;
    img.width = 80;
    img.height = 60;
    const PixelRect r = parse_region("1,2,30,40", img);
    EXPECT_EQ(r.x0, 1);
    EXPECT_EQ(r.y0, 2);
    EXPECT_EQ(r.x1, 30);
    EXPECT_EQ(r.y1, 40);
    auto message = [&](const std::string& text) {
        try {
            parse_region(text, img);
        } catch (const SceneError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    for (const char* bad : {"1,2,3", "1,2,3,4,5", "a,b,c,d", "1,2,3,4x", "", "1,,3,4", "1.5,2,3,4",
                            "99999999999,0,1,1", "1,2,3,4,"}) {
        EXPECT_EQ(message(bad), "--region " + std::string(bad) +
                                    ": expected four integers X0,Y0,X1,Y1 (X1, Y1 exclusive)");
    }
    EXPECT_EQ(message("0,0,81,60"),
              "--region 0,0,81,60: outside the 80x60 image (X0,Y0 from 0,0; X1,Y1 up to 80,60)");
    EXPECT_EQ(message("-1,0,5,5").rfind("--region -1,0,5,5: outside", 0), 0u);
    EXPECT_EQ(message("5,5,5,9"),
              "--region 5,5,5,9: the region is empty (X1 must be greater "
              "than X0, Y1 than Y0)");
}

}  // namespace
}  // namespace luz
