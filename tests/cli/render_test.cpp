// `luz render` that succeeds: the file, its format and size, the options that change it,
// --stats, --quiet, the progress bar on a terminal, and the same bits whatever --threads is.
#include <gtest/gtest.h>

#include <cstdint>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "cli/run_luz.h"
#include "image/image_io.h"

namespace luz::test {
namespace {

class Render : public TempDirTest {};

/// Width and height from a PNG's IHDR chunk (0, 0 if the file is not a PNG).
std::pair<uint32_t, uint32_t> png_size(const std::string& bytes) {
    static const std::string signature = "\x89PNG\r\n\x1a\n";
    if (bytes.size() < 24 || bytes.compare(0, 8, signature) != 0) return {0, 0};
    if (bytes.compare(12, 4, "IHDR") != 0) return {0, 0};
    auto be32 = [&](size_t i) {
        return (uint32_t(uint8_t(bytes[i])) << 24) | (uint32_t(uint8_t(bytes[i + 1])) << 16) |
               (uint32_t(uint8_t(bytes[i + 2])) << 8) | uint32_t(uint8_t(bytes[i + 3]));
    };
    return {be32(16), be32(20)};
}

TEST_F(Render, PrimitivesWritesAn800x600Png) {
    const RunResult r = run_luz({"render", "demo:primitives", "-o", "x.png"}, dir_);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(png_size(read_file(dir_ / "x.png")), (std::pair<uint32_t, uint32_t>{800, 600}));
    const Image img = read_image((dir_ / "x.png").string());
    EXPECT_EQ(img.width, 800);
    EXPECT_EQ(img.height, 600);
    EXPECT_EQ(r.out.rfind("wrote x.png (800\u00d7600, zbuffer, ", 0), 0u) << r.out;
    EXPECT_EQ(count_lines(r.out), 1);
    EXPECT_EQ(r.err, "") << "no progress bar when stderr is not a terminal";
    EXPECT_EQ(list_dir(dir_), (std::set<std::string>{"x.png"})) << "no temporary file left";
}

TEST_F(Render, DefaultOutputIsTheScenesNameAsPng) {
    const RunResult r =
        run_luz({"render", "demo:primitives", "--width", "16", "--height", "12"}, dir_);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(png_size(read_file(dir_ / "primitives.png")),
              (std::pair<uint32_t, uint32_t>{16, 12}));
}

TEST_F(Render, WidthAndHeightChangeTheSize) {
    const RunResult r = run_luz(
        {"render", "demo:primitives", "-o", "x.png", "--width", "64", "--height", "48"}, dir_);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(png_size(read_file(dir_ / "x.png")), (std::pair<uint32_t, uint32_t>{64, 48}));
    EXPECT_NE(r.out.find("64\u00d748"), std::string::npos) << r.out;
}

TEST_F(Render, SetChangesAnyKeyAndOptionsComeAfterIt) {
    RunResult r = run_luz({"render", "demo:primitives", "-o", "a.png", "--set", "image.width=32",
                           "--set", "image.height=24"},
                          dir_);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(png_size(read_file(dir_ / "a.png")), (std::pair<uint32_t, uint32_t>{32, 24}));

    r = run_luz({"render", "demo:primitives", "-o", "b.png", "--width", "40", "--set",
                 "image.width=32", "--height", "30"},
                dir_);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(png_size(read_file(dir_ / "b.png")), (std::pair<uint32_t, uint32_t>{40, 30}));

    // options may come before the scene, and each --set takes one value
    r = run_luz({"render", "--set", "image.width=12", "--set", "image.height=10", "demo:primitives",
                 "-o", "c.png"},
                dir_);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(png_size(read_file(dir_ / "c.png")), (std::pair<uint32_t, uint32_t>{12, 10}));
}

TEST_F(Render, PpmIsBinaryP6) {
    const RunResult r = run_luz(
        {"render", "demo:primitives", "-o", "x.ppm", "--width", "64", "--height", "48"}, dir_);
    ASSERT_EQ(r.status, 0) << r.err;
    const std::string bytes = read_file(dir_ / "x.ppm");
    std::istringstream in(bytes);
    std::string magic;
    int w = 0, h = 0, maxval = 0;
    in >> magic >> w >> h >> maxval;
    EXPECT_EQ(magic, "P6");
    EXPECT_EQ(w, 64);
    EXPECT_EQ(h, 48);
    EXPECT_EQ(maxval, 255);
    in.get();  // the single whitespace after the header
    EXPECT_EQ(bytes.size() - static_cast<size_t>(in.tellg()), 64u * 48u * 3u);
}

TEST_F(Render, PfmIsFloatLittleEndian) {
    const RunResult r = run_luz(
        {"render", "demo:primitives", "-o", "x.pfm", "--width", "64", "--height", "48"}, dir_);
    ASSERT_EQ(r.status, 0) << r.err;
    const std::string bytes = read_file(dir_ / "x.pfm");
    std::istringstream in(bytes);
    std::string magic;
    int w = 0, h = 0;
    double scale = 0;
    in >> magic >> w >> h >> scale;
    EXPECT_EQ(magic, "PF");
    EXPECT_EQ(w, 64);
    EXPECT_EQ(h, 48);
    EXPECT_EQ(scale, -1.0);
    in.get();
    EXPECT_EQ(bytes.size() - static_cast<size_t>(in.tellg()), 64u * 48u * 12u);
}

TEST_F(Render, ExrIsReadableAtItsSize) {
    const RunResult r = run_luz(
        {"render", "demo:primitives", "-o", "x.exr", "--width", "64", "--height", "48"}, dir_);
    ASSERT_EQ(r.status, 0) << r.err;
    const std::string bytes = read_file(dir_ / "x.exr");
    ASSERT_GE(bytes.size(), 4u);
    EXPECT_EQ(bytes.substr(0, 4), std::string("\x76\x2f\x31\x01", 4)) << "OpenEXR magic number";
    const Image img = read_image((dir_ / "x.exr").string());
    EXPECT_EQ(img.width, 64);
    EXPECT_EQ(img.height, 48);
}

TEST_F(Render, ReplacesAnExistingOutput) {
    write_file(dir_ / "x.png", "old");
    const RunResult r = run_luz(
        {"render", "demo:primitives", "-o", "x.png", "--width", "20", "--height", "10"}, dir_);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(png_size(read_file(dir_ / "x.png")), (std::pair<uint32_t, uint32_t>{20, 10}));
}

TEST_F(Render, StatsJsonHasEveryKey) {
    const RunResult r = run_luz({"render", "demo:primitives", "-o", "x.png", "--width", "64",
                                 "--height", "48", "--threads", "2", "--stats", "s.json"},
                                dir_);
    ASSERT_EQ(r.status, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(read_file(dir_ / "s.json"));
    for (const char* key :
         {"seconds", "width", "height", "threads", "pipeline", "rays", "intersection_tests",
          "pixels_refined", "samples", "triangles", "bvh_nodes", "peak_memory_bytes"}) {
        EXPECT_TRUE(j.contains(key)) << key;
    }
    for (const char* key : {"primary", "shadow", "reflection", "refraction"}) {
        EXPECT_TRUE(j["rays"].contains(key) && j["rays"][key].is_number_unsigned()) << key;
    }
    for (const char* key : {"primitive", "bounds"}) {
        EXPECT_TRUE(j["intersection_tests"].contains(key) &&
                    j["intersection_tests"][key].is_number_unsigned())
            << key;
    }
    EXPECT_EQ(j["width"], 64);
    EXPECT_EQ(j["height"], 48);
    EXPECT_EQ(j["threads"], 2);
    EXPECT_EQ(j["pipeline"], "zbuffer");
    EXPECT_TRUE(j["seconds"].is_number());
    EXPECT_GE(j["seconds"].get<double>(), 0.0);
    EXPECT_GT(j["peak_memory_bytes"].get<uint64_t>(), 1000000u) << "getrusage, in bytes";
    EXPECT_GT(j["triangles"].get<uint64_t>(), 0u) << "zbuffer counts rasterized triangles";
    EXPECT_EQ(list_dir(dir_), (std::set<std::string>{"x.png", "s.json"}));
}

// -o X.png renders a ray-traced image band by band into one buffer of rows, compressing each
// band as it is done: no float image of the whole size is made (36 MB here, 92 MB at
// 3200×2400; here 3 bands of 1024 rows, 12 MB), so the process's peak memory stays far below
// that of -o X.pfm (which holds the float image); the PNG is the one the float image makes.
TEST_F(Render, RayTracedPngNeedsNoFloatImageOfItsSize) {
    auto run = [&](const std::string& out) {
        const RunResult r =
            run_luz({"render", "demo:whitted", "-o", out, "--width", "1000", "--height", "3000",
                     "--set", "render.pipeline=\"raycast\"", "--stats", out + ".json"},
                    dir_);
        EXPECT_EQ(r.status, 0) << r.err;
        EXPECT_EQ(r.out.rfind("wrote " + out + " (1000\u00d73000, raycast, ", 0), 0u) << r.out;
        return nlohmann::json::parse(read_file(dir_ / (out + ".json")));
    };
    const nlohmann::json png = run("x.png"), pfm = run("x.pfm");
    const uint64_t float_image = uint64_t{1000} * 3000 * 12;  // 36 MB; the PNG's rows: 12 MB
#if defined(__SANITIZE_ADDRESS__)
    // Not under ASan: its quarantine keeps freed blocks resident (the bands' zlib states and
    // compressed bytes), 91 MB against 100 MB for the PFM.
    (void)float_image;
#else
    EXPECT_LT(png["peak_memory_bytes"].get<uint64_t>() + float_image / 3,
              pfm["peak_memory_bytes"].get<uint64_t>());
#endif
    for (const char* key : {"rays", "intersection_tests", "samples"}) EXPECT_EQ(png[key], pfm[key]);
    const Image from_png = read_image((dir_ / "x.png").string());
    const Image from_pfm = read_image((dir_ / "x.pfm").string());
    ASSERT_EQ(from_png.width, 1000);
    int off = 0;
    for (size_t i = 0; i < from_png.pixels.size(); ++i) {
        const Rgb& f = from_pfm.pixels[i];
        const Rgb q{encode_8bit(f.x, Encoding::linear) / 255.0f,
                    encode_8bit(f.y, Encoding::linear) / 255.0f,
                    encode_8bit(f.z, Encoding::linear) / 255.0f};
        off += !(q == from_png.pixels[i]);
    }
    EXPECT_EQ(off, 0) << "the PNG is the float image's";
}

TEST_F(Render, DefaultThreadsAreTheCoresTheProcessMayUse) {
    // --threads 0 (the default) is the CPU affinity, which taskset (or mpirun's binding, or a
    // container's cpuset) narrows: one core allowed, one thread.
    if (find_on_path("taskset").empty()) GTEST_SKIP() << "no taskset (util-linux)";
    const RunResult r =
        run_program("taskset",
                    {"-c", "0", LUZ_BINARY, "render", "demo:whitted", "--width", "32", "--height",
                     "24", "-q", "-o", "x.png", "--stats", "s.json"},
                    dir_);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(nlohmann::json::parse(read_file(dir_ / "s.json"))["threads"], 1);
}

TEST_F(Render, QuietPrintsNothing) {
    const RunResult r = run_luz(
        {"render", "demo:primitives", "-o", "x.png", "--width", "32", "--height", "24", "--quiet"},
        dir_);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(r.err, "");
    EXPECT_TRUE(std::filesystem::exists(dir_ / "x.png"));
}

TEST_F(Render, ProgressBarOnATerminal) {
    const RunResult r = run_luz_on_terminal({"render", "demo:primitives", "-o", "x.png"}, dir_);
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_NE(r.out.find("100%"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("[###"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("wrote x.png"), std::string::npos) << r.out;
}

TEST_F(Render, NoProgressBarOnATerminalWhenQuiet) {
    const RunResult r =
        run_luz_on_terminal({"render", "demo:primitives", "-o", "x.png", "--quiet"}, dir_);
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_EQ(r.out, "");
}

/// Renders `extra` with --threads 1 and --threads 2 and expects the same file bits.
void expect_same_bits_whatever_threads(const std::filesystem::path& dir,
                                       const std::vector<std::string>& extra,
                                       const std::string& scene = "demo:primitives") {
    std::vector<std::string> one = {"render", scene, "-o", "t1.png", "--threads", "1"};
    std::vector<std::string> two = {"render", scene, "-o", "t2.png", "--threads", "2"};
    one.insert(one.end(), extra.begin(), extra.end());
    two.insert(two.end(), extra.begin(), extra.end());
    const RunResult r1 = run_luz(one, dir);
    const RunResult r2 = run_luz(two, dir);
    ASSERT_EQ(r1.status, 0) << r1.err;
    ASSERT_EQ(r2.status, 0) << r2.err;
    const std::string a = read_file(dir / "t1.png"), b = read_file(dir / "t2.png");
    EXPECT_FALSE(a.empty());
    EXPECT_TRUE(a == b) << "--threads 1 and --threads 2 differ";
}

TEST_F(Render, SameBitsWhateverThreads) { expect_same_bits_whatever_threads(dir_, {}); }

TEST_F(Render, SameBitsWhateverThreadsLambert) {
    expect_same_bits_whatever_threads(dir_, {"--model", "lambert"});
}

TEST_F(Render, SameBitsWhateverThreadsPerspective) {
    expect_same_bits_whatever_threads(dir_, {"--set", "camera.projection=perspective"});
}

TEST_F(Render, SameBitsWhateverThreadsWhittedAdaptive) {
    expect_same_bits_whatever_threads(
        dir_, {"--aa", "adaptive", "--width", "320", "--height", "240"}, "demo:whitted");
}

TEST_F(Render, ModelChangesThePicture) {
    ASSERT_EQ(
        run_luz({"render", "demo:primitives", "-o", "p.png", "--width", "80", "--height", "60"},
                dir_)
            .status,
        0);
    ASSERT_EQ(run_luz({"render", "demo:primitives", "-o", "l.png", "--width", "80", "--height",
                       "60", "--model", "lambert"},
                      dir_)
                  .status,
              0);
    EXPECT_NE(read_file(dir_ / "p.png"), read_file(dir_ / "l.png"));
}

}  // namespace
}  // namespace luz::test
