// Golden images: every built-in scene through every pipeline, and a few antialiasing variants,
// rendered by the real `luz` binary at 160×120 and compared with the PNGs kept in tests/golden/.
// The cases (name and `luz` arguments, one a line) are tests/golden/cases.txt, which
// scripts/update_golden.sh reads too to regenerate the PNGs: run it only when a change of
// picture is intended, and look at the new images before committing them. A failing case leaves
// its render in <build dir>/golden_actual/NAME.png for inspection.
#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cli/run_luz.h"
#include "image/compare.h"
#include "image/image_io.h"
#include "scene/demo_scenes.h"

namespace luz::test {
namespace {

namespace fs = std::filesystem;

const fs::path kGoldenDir = fs::path(LUZ_SOURCE_DIR) / "tests" / "golden";
const fs::path kCasesFile = kGoldenDir / "cases.txt";
// Next to the binary under test, in the build folder.
const fs::path kActualDir = fs::path(LUZ_BINARY).parent_path() / "golden_actual";

struct Threshold {
    int max_diff = 0;           ///< largest channel difference allowed, in 8-bit units
    double max_fraction = 0.0;  ///< fraction of pixels allowed to differ at all
};

// The one table of tolerances, per scene (the name's part before the first '.'). Default and
// rule: 0, bit-identical — the same code on the same machine gives the same bits, whatever
// --threads is, and a refactor must not change a picture. Loosen one only with a reason here.
const std::map<std::string, Threshold> kThresholds = {
    {"primitives", {0, 0.0}},
    {"whitted", {0, 0.0}},
    {"materials", {0, 0.0}},
    {"bunny", {0, 0.0}},
};

std::string scene_of(const std::string& name) { return name.substr(0, name.find('.')); }

Threshold threshold_for(const std::string& name) {
    const auto it = kThresholds.find(scene_of(name));
    return it == kThresholds.end() ? Threshold{} : it->second;
}

struct GoldenCase {
    std::string name;               ///< SCENE.PIPELINE[.VARIANT]; the file is NAME.png
    std::vector<std::string> args;  ///< the arguments of `luz`, without -o
};

// tests/golden/cases.txt: blank lines and lines starting with '#' are skipped; the others are
// NAME then the arguments, split at blanks (no quoting, as in scripts/update_golden.sh).
std::vector<GoldenCase> load_cases() {
    std::vector<GoldenCase> cases;
    std::ifstream in(kCasesFile);
    std::string line;
    while (std::getline(in, line)) {
        std::istringstream words(line);
        GoldenCase c;
        if (!(words >> c.name) || c.name[0] == '#') continue;
        for (std::string w; words >> w;) c.args.push_back(w);
        cases.push_back(std::move(c));
    }
    return cases;
}

void PrintTo(const GoldenCase& c, std::ostream* os) { *os << c.name; }

const std::vector<GoldenCase>& cases() {
    static const std::vector<GoldenCase> all = load_cases();
    return all;
}

std::string join(const std::vector<std::string>& words) {
    std::string s;
    for (const std::string& w : words) s += (s.empty() ? "" : " ") + w;
    return s;
}

TEST(GoldenSet, CoversEveryBuiltInSceneThroughEveryPipeline) {
    ASSERT_FALSE(cases().empty()) << "no cases in " << kCasesFile;
    std::set<std::string> names;
    for (const GoldenCase& c : cases()) {
        EXPECT_TRUE(names.insert(c.name).second) << "case named twice: " << c.name;
    }
    for (const DemoScene& d : demo_scenes()) {
        for (const char* pipeline : {"zbuffer", "raycast", "raytrace"}) {
            const std::string name = std::string(d.name) + "." + pipeline;
            EXPECT_TRUE(names.count(name)) << "no golden case " << name << " in " << kCasesFile;
        }
    }
}

TEST(GoldenSet, ThresholdsNameBuiltInScenes) {
    std::set<std::string> scenes;
    for (const DemoScene& d : demo_scenes()) scenes.emplace(d.name);
    for (const auto& [scene, t] : kThresholds) {
        EXPECT_TRUE(scenes.count(scene)) << "threshold for an unknown scene: " << scene;
        EXPECT_GE(t.max_diff, 0) << scene;
        EXPECT_GE(t.max_fraction, 0.0) << scene;
    }
}

TEST(GoldenSet, FolderHoldsExactlyTheCasesImagesUnderOneMegabyte) {
    std::set<std::string> expected = {"cases.txt"};
    for (const GoldenCase& c : cases()) expected.insert(c.name + ".png");
    EXPECT_EQ(list_dir(kGoldenDir), expected)
        << kGoldenDir << " must hold cases.txt and one NAME.png per case: run "
        << "scripts/update_golden.sh";
    uintmax_t bytes = 0;
    for (const auto& e : fs::directory_iterator(kGoldenDir)) bytes += e.file_size();
    EXPECT_LT(bytes, 1u << 20) << kGoldenDir << " holds " << bytes << " bytes";
}

class GoldenImage : public testing::TestWithParam<GoldenCase> {
  protected:
    void SetUp() override {
        std::string tmpl = (fs::temp_directory_path() / "luz-golden-XXXXXX").string();
        ASSERT_NE(mkdtemp(tmpl.data()), nullptr);
        dir_ = tmpl;
    }
    void TearDown() override {
        std::error_code ec;
        if (!dir_.empty()) fs::remove_all(dir_, ec);
    }
    fs::path dir_;
};

TEST_P(GoldenImage, MatchesStoredPng) {
    const GoldenCase& c = GetParam();
    const std::string file = c.name + ".png";
    const fs::path golden = kGoldenDir / file;
    ASSERT_TRUE(fs::exists(golden)) << golden << " is missing: run scripts/update_golden.sh";

    std::vector<std::string> args = c.args;
    args.insert(args.end(), {"-o", "actual.png"});
    const RunResult r = run_luz(args, dir_);
    ASSERT_EQ(r.status, 0) << "luz " << join(args) << "\n" << r.err;

    const Image actual = read_image((dir_ / "actual.png").string());
    const Image expected = read_image(golden.string());
    const ImageDiff d = compare_images(actual, expected, 0.0f);  // pixels_above: any difference
    const Threshold t = threshold_for(c.name);
    const int max_diff = d.same_size ? static_cast<int>(std::lround(d.max_abs * 255.0)) : -1;
    const double fraction = 1.0 - d.fraction_within();
    const bool ok = d.same_size && max_diff <= t.max_diff && fraction <= t.max_fraction;

    std::error_code ec;
    const fs::path kept = kActualDir / file;
    if (ok) {
        fs::remove(kept, ec);  // an earlier failure's render, now stale
        return;
    }
    fs::create_directories(kActualDir, ec);
    fs::copy_file(dir_ / "actual.png", kept, fs::copy_options::overwrite_existing, ec);
    const std::string where = ec ? "(could not keep it: " + ec.message() + ")" : kept.string();
    if (!d.same_size) {
        FAIL() << file << ": the render is " << actual.width << "×" << actual.height
               << ", the golden image " << expected.width << "×" << expected.height
               << "\n  actual render: " << where << "\n  luz " << join(args);
    }
    const char* channel = "RGB";
    std::ostringstream shares;  // percentages to 3 significant digits
    shares << std::setprecision(3) << 100.0 * fraction << " %, allowed " << 100.0 * t.max_fraction
           << " %";
    FAIL() << file << ": " << d.pixels_above << " of " << d.pixels << " pixels differ ("
           << shares.str() << "), max difference " << max_diff << "/255 (allowed " << t.max_diff
           << ") at (" << d.max_x << ", " << d.max_y << ") channel " << channel[d.max_channel]
           << "\n  actual render: " << where << "\n  golden image:  " << golden.string()
           << "\n  luz " << join(args)
           << "\n  if the change of picture is intended: scripts/update_golden.sh";
}

INSTANTIATE_TEST_SUITE_P(Golden, GoldenImage, testing::ValuesIn(cases()),
                         [](const testing::TestParamInfo<GoldenCase>& info) {
                             std::string id = info.param.name;
                             for (char& ch : id) {
                                 if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                             }
                             return id;
                         });

}  // namespace
}  // namespace luz::test
