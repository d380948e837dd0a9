// Small inputs that asked for quadratic work (minutes each before): an OBJ of 200 000 MTL
// materials, one face of a million corners (or of 200 000 equal ones), and 3000 spheres through
// the zbuffer. Each now takes the time its size predicts.
#include <chrono>
#include <cmath>
#include <fstream>

#include "cli/run_luz.h"

namespace luz::test {
namespace {

using Clock = std::chrono::steady_clock;

class LargeInput : public TempDirTest {
  protected:
    /// Renders s.json at 32×24; checks exit 0; returns the seconds taken.
    double render(const std::vector<std::string>& extra = {}) {
        std::vector<std::string> args = {"render", "s.json", "--width", "32", "--height",
                                         "24",     "-o",     "out.png", "-q"};
        args.insert(args.end(), extra.begin(), extra.end());
        const auto start = Clock::now();
        const RunResult r = run_luz(args, dir_);
        const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
        EXPECT_EQ(r.status, 0) << r.err;
        EXPECT_TRUE(std::filesystem::exists(dir_ / "out.png"));
        err_ = r.err;
        return seconds;
    }
    std::string err_;
};

TEST_F(LargeInput, TwoHundredThousandMtlMaterialsLoadInSeconds) {
    LUZ_SPEED_TEST();
    // each face uses its own material: a look-up per usemtl among all of them was quadratic
    {
        std::ofstream mtl(dir_ / "m.mtl");
        for (int i = 0; i < 200000; ++i) mtl << "newmtl m" << i << "\nKd 0.5 0.5 0.5\n";
        std::ofstream obj(dir_ / "m.obj");
        obj << "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n";
        for (int i = 0; i < 200000; ++i) obj << "usemtl m" << i << "\nf 1 2 3\n";
    }
    write_file(dir_ / "s.json", R"({"objects": [{"type": "mesh", "file": "m.obj"}]})");
    const double seconds = render();
    EXPECT_LT(seconds, 10);
    RecordProperty("seconds", std::to_string(seconds));
}

TEST_F(LargeInput, AFaceOfAMillionCornersLoadsInSeconds) {
    LUZ_SPEED_TEST();
    // a circle of 1 000 000 corners as one face (30 MB): ear clipping without an index is
    // quadratic
    {
        std::ofstream obj(dir_ / "m.obj");
        char line[64];
        for (int i = 0; i < 1000000; ++i) {
            const double a = 2 * M_PI * i / 1e6;
            std::snprintf(line, sizeof line, "v %.7f %.7f 0\n", std::cos(a), std::sin(a));
            obj << line;
        }
        obj << "f";
        for (int i = 1; i <= 1000000; ++i) obj << ' ' << i;
        obj << '\n';
    }
    write_file(dir_ / "s.json", R"({"objects": [{"type": "mesh", "file": "m.obj"}]})");
    const double seconds = render();
    EXPECT_LT(seconds, 10);
    RecordProperty("seconds", std::to_string(seconds));
}

TEST_F(LargeInput, AFaceOfTwoHundredThousandEqualCornersIsEmpty) {
    {
        std::ofstream obj(dir_ / "m.obj");
        for (int i = 0; i < 200000; ++i) obj << "v 1 2 3\n";
        obj << "f";
        for (int i = 1; i <= 200000; ++i) obj << ' ' << i;
        obj << '\n';
    }
    write_file(dir_ / "s.json", R"({"objects": [{"type": "mesh", "file": "m.obj"}]})");
    EXPECT_LT(render(), 5 * kSlowdown);
    EXPECT_NE(err_.find("m.obj: no faces; the mesh is empty"), std::string::npos) << err_;
}

TEST_F(LargeInput, ThreeThousandSpheresThroughTheZbufferInSeconds) {
    LUZ_SPEED_TEST();
    // each sphere's vertices reserved to the exact size copied all the spheres before it (about
    // two minutes at tessellation 48; 25 s at 32)
    {
        std::ofstream s(dir_ / "s.json");
        s << R"({"render": {"pipeline": "zbuffer", "tessellation": 48}, "objects": [)";
        for (int i = 0; i < 3000; ++i) {
            s << (i ? ",\n" : "") << R"({"type": "sphere", "radius": 0.4, "center": [)"
              << i % 60 - 30 << ", " << i / 60 - 25 << ", -40]}";
        }
        s << "]}";
    }
    const double seconds = render();
    EXPECT_LT(seconds, 10);
    RecordProperty("seconds", std::to_string(seconds));
}

}  // namespace
}  // namespace luz::test
