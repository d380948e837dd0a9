// `luz view` under Xvfb: the headless screenshot shows the image `luz render` makes and the
// panel; --set edits show; --click writes a ray tree whose terms add up to the pixel; the
// render thread cancels promptly. Skipped when luz was built without the viewer.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>

#include "cli/run_luz.h"
#include "image/image_io.h"

namespace luz::test {
namespace {

namespace fs = std::filesystem;

class ViewTest : public TempDirTest {
  protected:
    void SetUp() override {
#ifndef LUZ_HAVE_VIEWER
        GTEST_SKIP() << "luz was built without the viewer";
#endif
        TempDirTest::SetUp();
    }

    /// luz view ARGS under a fresh Xvfb (24-bit screen large enough for the window).
    RunResult view(std::vector<std::string> args) {
        std::vector<std::string> all = {"view"};
        all.insert(all.end(), args.begin(), args.end());
        std::string cmd = "cd '" + dir_.string() + "' && xvfb-run -a -n " +
                          std::to_string(100 + ::getpid() % 400) +
                          " -s '-screen 0 1600x1200x24' '" LUZ_BINARY "'";
        for (const std::string& a : all) cmd += " '" + a + "'";
        cmd += " > out.txt 2> err.txt";
        RunResult r;
        const int s = std::system(cmd.c_str());
        r.status = WIFEXITED(s) ? WEXITSTATUS(s) : 128;
        r.out = read_file(dir_ / "out.txt");
        r.err = read_file(dir_ / "err.txt");
        return r;
    }
};

/// Channels of pixel (x, y) of a differ from b's by more than `tol` (8-bit units).
bool differs(const Image& a, int ax, int ay, const Image& b, int bx, int by, float tol = 0.5f) {
    const Rgb p = a.at(ax, ay), q = b.at(bx, by);
    return std::fabs(p.x - q.x) * 255 > tol || std::fabs(p.y - q.y) * 255 > tol ||
           std::fabs(p.z - q.z) * 255 > tol;
}

TEST_F(ViewTest, ScreenshotShowsTheRenderedImageAndThePanel) {
    const RunResult v =
        view({"demo:primitives", "--width", "320", "--height", "240", "--screenshot", "shot.png"});
    ASSERT_EQ(v.status, 0) << v.err;
    const RunResult r = run_luz(
        {"render", "demo:primitives", "--width", "320", "--height", "240", "-o", "ref.png", "-q"},
        dir_);
    ASSERT_EQ(r.status, 0) << r.err;
    const Image shot = read_image((dir_ / "shot.png").string());
    const Image ref = read_image((dir_ / "ref.png").string());
    ASSERT_GE(shot.width, ref.width + 300);
    ASSERT_GE(shot.height, ref.height);
    int different = 0;
    for (int y = 0; y < ref.height; ++y)
        for (int x = 0; x < ref.width; ++x) different += differs(shot, x, y, ref, x, y);
    EXPECT_EQ(different, 0) << "the image region must be luz render's picture, pixel for pixel";
    // The panel, right of the image: many colours (text, widgets), not a blank area.
    int changes = 0;
    for (int y = 0; y < shot.height - 1; ++y)
        for (int x = ref.width + 10; x < shot.width - 1; ++x)
            changes += differs(shot, x, y, shot, x + 1, y, 20);
    EXPECT_GT(changes, 1000);
}

TEST_F(ViewTest, ShowsATermInsteadOfTheImage) {
    // --aov depth: the window shows luz render's 8-bit picture of the depth term.
    const RunResult v = view({"demo:primitives", "--width", "320", "--height", "240", "--aov",
                              "depth", "--screenshot", "shot.png"});
    ASSERT_EQ(v.status, 0) << v.err;
    const RunResult r = run_luz({"render", "demo:primitives", "--width", "320", "--height", "240",
                                 "-o", "ref.png", "--aov", "depth", "-q"},
                                dir_);
    ASSERT_EQ(r.status, 0) << r.err;
    const Image shot = read_image((dir_ / "shot.png").string());
    const Image ref = read_image((dir_ / "ref.depth.png").string());
    int different = 0;
    for (int y = 0; y < ref.height; ++y)
        for (int x = 0; x < ref.width; ++x) different += differs(shot, x, y, ref, x, y);
    EXPECT_EQ(different, 0) << "the image region must be the depth picture, pixel for pixel";
    const RunResult bad = view({"demo:primitives", "--aov", "depht", "--screenshot", "s.png"});
    EXPECT_EQ(bad.status, 2);
    EXPECT_NE(bad.err.find("unknown term \"depht\""), std::string::npos) << bad.err;
}

TEST_F(ViewTest, SetChangesTheHighlight) {
    const std::vector<std::string> size = {"--width", "320", "--height", "240"};
    auto args = [&](std::vector<std::string> a) {
        a.insert(a.begin() + 1, size.begin(), size.end());
        return a;
    };
    ASSERT_EQ(view(args({"demo:primitives", "--screenshot", "a.png"})).status, 0);
    const RunResult v =
        view(args({"demo:primitives", "--set", "materials.blue.n=2", "--screenshot", "b.png"}));
    ASSERT_EQ(v.status, 0) << v.err;
    const Image a = read_image((dir_ / "a.png").string());
    const Image b = read_image((dir_ / "b.png").string());
    int different = 0;
    for (int y = 0; y < 240; ++y)
        for (int x = 0; x < 320; ++x) different += differs(a, x, y, b, x, y);
    EXPECT_GT(different, 20) << "n of the blue cylinder changes its highlight";
    EXPECT_LT(different, 320 * 240 / 10) << "and only on the cylinder";
}

/// Checks that the node's terms add up (within `eps`) and recurses into its children.
void check_node(const nlohmann::json& nodes, int i, double eps) {
    const auto& n = nodes[i];
    auto c = [](const nlohmann::json& v, int k) { return v[k].get<double>(); };
    if (n["hit"] == "object") {
        for (int k = 0; k < 3; ++k) {
            double local = c(n["ambient"], k);
            for (const auto& l : n["lights"]) local += c(l["diffuse"], k) + c(l["specular"], k);
            EXPECT_NEAR(local, c(n["local"], k), eps) << "node " << i;
            double total = c(n["local"], k);
            for (const char* child : {"reflection_child", "refraction_child"}) {
                const int j = n[child].get<int>();
                if (j < 0) continue;
                const auto& m = nodes[j];
                EXPECT_EQ(m["parent"].get<int>(), i);
                EXPECT_NEAR(
                    c(m["returned"], k) * m["A"].get<double>() * m["coefficient"].get<double>(),
                    c(m["contribution"], k), eps);
                EXPECT_NEAR(c(m["returned"], k), c(m["colour"], k), eps);
                total += c(m["contribution"], k);
                check_node(nodes, j, eps);
            }
            EXPECT_NEAR(total, c(n["colour"], k), eps) << "node " << i;
        }
    }
}

TEST_F(ViewTest, ClickWritesARayTreeThatAddsUpToThePixel) {
    // A pixel on the glass sphere of demo:whitted: reflected and refracted rays below it.
    const RunResult v = view({"demo:whitted", "--width", "160", "--height", "120", "--click",
                              "98,70", "--screenshot", "shot.png"});
    ASSERT_EQ(v.status, 0) << v.err;
    std::ifstream f(dir_ / "shot.json");
    ASSERT_TRUE(f) << "the tree is written next to the screenshot";
    const nlohmann::json tree = nlohmann::json::parse(f);
    const auto& nodes = tree["nodes"];
    ASSERT_GE(nodes.size(), 3u) << tree.dump(1);
    EXPECT_EQ(nodes[0]["kind"], "primary");
    check_node(nodes, 0, 1e-5);
    for (int k = 0; k < 3; ++k) {
        const double pixel = tree["pixel_value"][k].get<double>();
        EXPECT_NEAR(nodes[0]["colour"][k].get<double>(), pixel, 1.0 / 255);
    }
    // The value luz render writes for that pixel.
    ASSERT_EQ(run_luz({"render", "demo:whitted", "--width", "160", "--height", "120", "-o",
                       "ref.pfm", "-q"},
                      dir_)
                  .status,
              0);
    const Image ref = read_image((dir_ / "ref.pfm").string());
    for (int k = 0; k < 3; ++k) {
        const float v = k == 0 ? ref.at(98, 70).x : k == 1 ? ref.at(98, 70).y : ref.at(98, 70).z;
        EXPECT_NEAR(tree["colour"][k].get<double>(), v, 1.0 / 255);
    }
}

TEST_F(ViewTest, BadClickIsBadInput) {
    const RunResult v = view({"demo:primitives", "--click", "5000,1", "--screenshot", "s.png"});
    EXPECT_EQ(v.status, 2);
    EXPECT_NE(v.err.find("--click 5000,1"), std::string::npos) << v.err;
    EXPECT_FALSE(fs::exists(dir_ / "s.png"));
}

TEST_F(ViewTest, RenderThreadCancelsPromptly) {
    // No window needed: the benchmark mode measures the render worker itself.
    const RunResult r = run_luz({"view", "demo:whitted", "--benchmark", "--width", "640",
                                 "--height", "480", "--threads", "2"},
                                dir_);
    ASSERT_EQ(r.status, 0) << r.err;
    std::smatch m;
    ASSERT_TRUE(std::regex_search(
        r.out, m, std::regex("cancel latency +median ([0-9.]+) ms +max ([0-9.]+) ms")))
        << r.out;
    EXPECT_LT(std::stod(m[1]), 50.0) << r.out;   // the target
    EXPECT_LT(std::stod(m[2]), 250.0) << r.out;  // generous: the machine is shared
}

TEST_F(ViewTest, BenchmarkSaysWhenNoEditFoundARenderToCancel) {
    // 16×12 renders end within the 20 ms before each edit: a line says so, not nothing.
    const RunResult r = run_luz({"view", "demo:primitives", "--benchmark", "--width", "16",
                                 "--height", "12", "--threads", "1"},
                                dir_);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("cancel latency  "), std::string::npos) << r.out;
}

TEST_F(ViewTest, WithoutItsModuleViewSaysWhereItLookedAndRenderStillWorks) {
    // A copy of the binary in a folder of its own: luz_viewer.so is not beside it.
    fs::create_directories(dir_ / "bin");
    fs::copy_file(LUZ_BINARY, dir_ / "bin" / "luz");
    const std::string luz = (dir_ / "bin" / "luz").string();
    const RunResult v = run_program(luz, {"view", "demo:primitives", "--benchmark"}, dir_);
    EXPECT_EQ(v.status, 1);
    EXPECT_NE(v.err.find("cannot load the viewer module luz_viewer.so"), std::string::npos)
        << v.err;
    EXPECT_NE(v.err.find((dir_ / "bin" / "luz_viewer.so").string()), std::string::npos) << v.err;
    const RunResult r = run_program(
        luz, {"render", "demo:primitives", "--width", "16", "--height", "12", "-o", "p.png"}, dir_);
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(fs::exists(dir_ / "p.png"));
}

TEST_F(ViewTest, NffSceneShowsWhatRenderMakes) {
    // docs/SCENES.md#nff: `luz view x.nff` reads NFF as `luz render` does (its resolution, --set
    // f1).
    const std::string nff = std::string(LUZ_SOURCE_DIR) + "/tests/scenes/nff/small.nff";
    const std::vector<std::string> set = {"--set", "materials.f1.kd=[0,0,1]"};
    std::vector<std::string> v_args = {nff, "--screenshot", "shot.png"};
    std::vector<std::string> r_args = {"render", nff, "-o", "ref.png", "-q"};
    v_args.insert(v_args.end(), set.begin(), set.end());
    r_args.insert(r_args.end(), set.begin(), set.end());
    const RunResult v = view(v_args);
    ASSERT_EQ(v.status, 0) << v.err;
    ASSERT_EQ(run_luz(r_args, dir_).status, 0);
    const Image shot = read_image((dir_ / "shot.png").string());
    const Image ref = read_image((dir_ / "ref.png").string());
    ASSERT_EQ(ref.width, 48);
    int different = 0;
    for (int y = 0; y < ref.height; ++y)
        for (int x = 0; x < ref.width; ++x) different += differs(shot, x, y, ref, x, y);
    EXPECT_EQ(different, 0);
}

}  // namespace
}  // namespace luz::test
