// Limits before allocation (docs/SCENES.md#limits): sizes and counts beyond the documented caps,
// and renders needing more than --max-memory, are refused at once with exit 2 and no file.
#include <chrono>
#include <fstream>

#include "cli/run_luz.h"

namespace luz::test {
namespace {

using Clock = std::chrono::steady_clock;

class Limits : public TempDirTest {
  protected:
    /// Runs luz; checks exit 2, one line holding every fragment, no out.png; returns seconds.
    double refused(const std::vector<std::string>& args,
                   const std::vector<std::string>& fragments) {
        const auto start = Clock::now();
        const RunResult r = run_luz(args, dir_);
        const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
        EXPECT_EQ(r.status, 2) << r.err;
        EXPECT_EQ(count_lines(r.err), 1) << r.err;
        for (const std::string& f : fragments) EXPECT_NE(r.err.find(f), std::string::npos) << r.err;
        EXPECT_FALSE(std::filesystem::exists(dir_ / "out.png"));
        return seconds;
    }
};

TEST_F(Limits, AHundredThousandSquaredImageIsRefusedQuickly) {
    EXPECT_LT(refused({"render", "demo:whitted", "--width", "100000", "--height", "100000", "-o",
                       "out.png"},
                      {"--width 100000", "image.width", "65536"}),
              1.0);
    write_file(
        dir_ / "s.json",
        R"({"image": {"width": 100000, "height": 100000}, "objects": [{"type": "sphere"}]})");
    EXPECT_LT(refused({"render", "s.json", "-o", "out.png"}, {"s.json", "image.width"}), 1.0);
}

TEST_F(Limits, CapsOnDepthTessellationSamplesAndLevels) {
    refused({"render", "demo:whitted", "--max-depth", "65", "-o", "out.png"},
            {"render.max_depth", "[0, 64]"});
    refused({"render", "demo:primitives", "--set", "render.tessellation=4097", "-o", "out.png"},
            {"render.tessellation", "[3, 4096]"});
    refused({"render", "demo:primitives", "--aa", "grid", "--samples", "289", "-o", "out.png"},
            {"render.antialias.samples", "[1, 256]"});
    refused({"render", "demo:primitives", "--set", "render.antialias.max_level=7", "-o", "out.png"},
            {"render.antialias.max_level", "[0, 6]"});
}

TEST_F(Limits, TessellationBeyondMemoryIsRefusedNamingTheKey) {
    EXPECT_LT(refused({"render", "demo:primitives", "--set", "render.tessellation=4096",
                       "--max-memory", "4G", "-o", "out.png"},
                      {"demo:primitives", "render.tessellation", "4.0 GiB limit"}),
              1.0);
}

TEST_F(Limits, AdaptiveAntialiasingCountsItsCorners) {
    // 4000×4000: the image alone needs 534 MiB (under 600 MiB), its corners another 200 MiB
    refused({"render", "demo:primitives", "--width", "4000", "--height", "4000", "--aa", "adaptive",
             "--max-memory", "600M", "-o", "out.png"},
            {"image.width", "4000x4000 needs 7"});
}

TEST_F(Limits, MeshLargerThanTheLimitIsRefusedBeforeLoading) {
    {
        std::ofstream obj(dir_ / "big.obj");
        for (int i = 0; i < 20000; ++i) obj << "v " << i << " 0 0\nv 0 " << i << " 0\nv 0 0 1\n";
        for (int i = 0; i < 20000; ++i)
            obj << "f " << 3 * i + 1 << ' ' << 3 * i + 2 << ' ' << 3 * i + 3 << '\n';
    }
    write_file(dir_ / "s.json", R"({"objects": [{"type": "mesh", "file": "big.obj"}]})");
    refused({"render", "s.json", "--max-memory", "1M", "-o", "out.png"},
            {"s.json", "objects.0.file", "big.obj", "a quarter of --max-memory"});
}

TEST_F(Limits, EndlessMeshFileIsRefused) {
    write_file(dir_ / "s.json", R"({"objects": [{"type": "mesh", "file": "/dev/zero"}]})");
    EXPECT_LT(refused({"render", "s.json", "-o", "out.png"}, {"/dev/zero", "not a regular file"}),
              1.0);
}

/// A scene file of `n` spheres in a row (about 60 bytes of JSON each).
void write_spheres(const std::filesystem::path& file, int n) {
    std::ofstream s(file);
    s << R"({"render": {"pipeline": "raytrace"}, "objects": [)";
    for (int i = 0; i < n; ++i) {
        s << (i ? ",\n" : "") << R"({"type": "sphere", "center": [)" << i << ", 0, -40]}";
    }
    s << "]}";
}

TEST_F(Limits, ManyObjectsCountAgainstMaxMemory) {
    // 50 000 spheres: their JSON fits in 70 MB once parsed, the objects built do not
    write_spheres(dir_ / "s.json", 50000);
    refused({"render", "s.json", "--width", "16", "--height", "16", "--max-memory", "70M", "-o",
             "out.png"},
            {"s.json: objects: 50000 objects need", "70.0 MiB limit"});
}

TEST_F(Limits, AParsedSceneLargerThanMaxMemoryIsRefusedWhileParsing) {
    write_spheres(dir_ / "s.json", 50000);
    refused({"render", "s.json", "--width", "16", "--height", "16", "--max-memory", "20M", "-o",
             "out.png"},
            {"s.json:", "the scene needs more memory than the 20.0 MiB limit"});
}

TEST_F(Limits, ManyMeshesAreNamedAsTheCause) {
    // 300 objects sharing one OBJ of 1000 triangles: no one mesh is the cause, nor tessellation
    {
        std::ofstream obj(dir_ / "m.obj");
        for (int i = 0; i < 1000; ++i) obj << "v " << i << " 0 0\nv 0 " << i << " 0\nv 0 0 1\n";
        for (int i = 0; i < 1000; ++i)
            obj << "f " << 3 * i + 1 << ' ' << 3 * i + 2 << ' ' << 3 * i + 3 << '\n';
    }
    std::ofstream s(dir_ / "s.json");
    s << R"({"objects": [)";
    for (int i = 0; i < 300; ++i) s << (i ? "," : "") << R"({"type": "mesh", "file": "m.obj"})";
    s << "]}";
    s.close();
    refused({"render", "s.json", "--width", "16", "--height", "16", "--max-memory", "40M", "-o",
             "out.png"},
            {"s.json: objects: 300 meshes (300000 triangles in all) need", "40.0 MiB limit"});
}

}  // namespace
}  // namespace luz::test
