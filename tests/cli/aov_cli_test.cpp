// `luz render --aov`: the per-term files beside the image (X.NAME.EXT) or as layers of one EXR,
// float formats with the raw values, 8-bit pictures of depth, normal and tests, and bad names.
#include <gtest/gtest.h>

#include <cmath>

#include "cli/run_luz.h"
#include "image/image_io.h"

namespace luz::test {
namespace {

class Aov : public TempDirTest {};

const std::vector<std::string> kAovSize = {"--width", "48", "--height", "36", "-q"};

std::vector<std::string> args(std::vector<std::string> a) {
    a.insert(a.end(), kAovSize.begin(), kAovSize.end());
    return a;
}

TEST_F(Aov, PngWritesEachTermBesideTheImage) {
    const RunResult r = run_luz(
        args({"render", "demo:whitted", "-o", "w.png", "--aov", "diffuse,depth,tests"}), dir_);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(list_dir(dir_),
              (std::set<std::string>{"w.png", "w.diffuse.png", "w.depth.png", "w.tests.png"}));
    // Depth: near bright, misses black.
    const Image depth = read_image((dir_ / "w.depth.png").string());
    float brightest = 0;
    for (const Rgb& p : depth.pixels) brightest = std::max(brightest, p.x);
    EXPECT_EQ(brightest, 1.0f);
}

TEST_F(Aov, PfmHoldsTheRawValuesThatAddUpToTheImage) {
    const RunResult r = run_luz(
        args({"render", "demo:whitted", "-o", "w.pfm", "--aov", "all", "--aa", "grid"}), dir_);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(list_dir(dir_).size(), 11u);
    const Image image = read_image((dir_ / "w.pfm").string());
    Image sum(image.width, image.height);
    for (const char* t : {"ambient", "diffuse", "specular", "reflected", "refracted", "emitted"}) {
        const Image term = read_image((dir_ / (std::string("w.") + t + ".pfm")).string());
        for (size_t p = 0; p < sum.pixels.size(); ++p) sum.pixels[p] += term.pixels[p];
    }
    for (size_t p = 0; p < sum.pixels.size(); ++p)
        for (int c = 0; c < 3; ++c)
            ASSERT_NEAR(sum.pixels[p][c], image.pixels[p][c], 2e-6 * (1 + image.pixels[p][c]));
    const Image depth = read_image((dir_ / "w.depth.pfm").string());
    int misses = 0;
    for (const Rgb& p : depth.pixels) misses += std::isinf(p.x);
    EXPECT_GT(misses, 0);  // the sky above the floor
}

TEST_F(Aov, ExrHoldsEveryTermAsLayersOfOneFile) {
    const RunResult r =
        run_luz(args({"render", "demo:whitted", "-o", "w.exr", "--aov", "normal,depth"}), dir_);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(list_dir(dir_), (std::set<std::string>{"w.exr"}));
    const std::string path = (dir_ / "w.exr").string();
    const Image normal = read_exr_layer(path, "normal"), depth = read_exr_layer(path, "depth");
    EXPECT_EQ(normal.width, 48);
    float longest = 0;
    for (const Rgb& n : normal.pixels) longest = std::max(longest, length(n));
    EXPECT_NEAR(longest, 1.0f, 1e-4f);
    bool finite = false;
    for (const Rgb& p : depth.pixels) finite = finite || std::isfinite(p.x);
    EXPECT_TRUE(finite);
    EXPECT_THROW(read_exr_layer(path, "diffuse"), ImageError);  // not asked for
}

TEST_F(Aov, UnknownNameIsBadInputListingTheValidOnes) {
    const RunResult r = run_luz(
        args({"render", "demo:whitted", "-o", "w.png", "--aov", "diffuse,specularity"}), dir_);
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.err,
              "--aov diffuse,specularity: unknown term \"specularity\"; valid: ambient, "
              "diffuse, specular, reflected, refracted, emitted, shadow, depth, normal, tests, "
              "all\n");
    EXPECT_TRUE(list_dir(dir_).empty());
}

}  // namespace
}  // namespace luz::test
