// The profile-guided build never trains on a scene a benchmark times (cmake/pgo_train.cmake
// against bench/): every speed figure comes from a build that did not see its scene.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace luz::test {
namespace {

namespace fs = std::filesystem;

const fs::path kSourceRoot = LUZ_SOURCE_DIR;

std::string read_text(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

/// The training renders: the quoted lines of `set(runs …)`, each a scene and its options.
std::vector<std::string> training_runs() {
    const std::string text = read_text(kSourceRoot / "cmake/pgo_train.cmake");
    const size_t begin = text.find("set(runs");
    const size_t end = text.find(')', begin);
    std::vector<std::string> runs;
    if (begin == std::string::npos || end == std::string::npos) return runs;
    const std::string list = text.substr(begin, end - begin);
    const std::regex quoted("\"([^\"]+)\"");
    for (std::sregex_iterator it(list.begin(), list.end(), quoted), e; it != e; ++it) {
        runs.push_back((*it)[1]);
    }
    return runs;
}

/// The built-in scenes (demo:NAME) and scene files (NAME.json/.obj/.nff) that bench/ names.
std::set<std::string> benchmarked_scenes() {
    std::set<std::string> names;
    const std::regex name(R"((demo:[a-z_]+)|([A-Za-z0-9_]+\.(json|obj|nff)))");
    for (const auto& e : fs::recursive_directory_iterator(kSourceRoot / "bench")) {
        if (!e.is_regular_file()) continue;
        const std::string text = read_text(e.path());
        for (std::sregex_iterator it(text.begin(), text.end(), name), end; it != end; ++it) {
            names.insert((*it)[0]);
        }
    }
    return names;
}

TEST(PgoTraining, NoSceneABenchmarkTimes) {
    const std::vector<std::string> runs = training_runs();
    ASSERT_GE(runs.size(), 5u) << "no training renders found in cmake/pgo_train.cmake";
    const std::set<std::string> timed = benchmarked_scenes();
    ASSERT_TRUE(timed.count("demo:whitted")) << "bench/ no longer names demo:whitted?";
    ASSERT_TRUE(timed.count("bunny.obj"));
    for (const std::string& run : runs) {
        const std::string scene = run.substr(0, run.find(' '));
        const fs::path file = fs::path(scene).filename();
        EXPECT_FALSE(timed.count(scene) || timed.count(file.string()))
            << run << ": a benchmark (bench/) times this scene";
        // The SPD's files are all timed (bench/spd.sh): an NFF scene here is one of
        // bench/spd_gen.py's at a size no benchmark renders (spd_NAME_SIZE.nff: balls 2, rings
        // 3, tree 8; bench/spd_sizes.py renders balls 3–5, rings 5–10, tree 11–14). The bunny
        // (demo:bunny too) and the big mesh are timed by bench/bvh_vs_embree; demo:primitives
        // through the zbuffer by `luz view --benchmark` (docs/BENCHMARKS.md).
        if (file.extension() == ".nff") {
            static const std::set<std::string> untimed = {"spd_balls_2.nff", "spd_rings_3.nff",
                                                          "spd_tree_8.nff"};
            EXPECT_TRUE(untimed.count(file.string())) << run;
        }
        EXPECT_EQ(scene.find("bunny"), std::string::npos) << run;
        EXPECT_EQ(scene.find("bigmesh"), std::string::npos) << run;
        if (scene == "demo:primitives") {
            EXPECT_TRUE(run.find("--pipeline raycast") != std::string::npos ||
                        run.find("--pipeline raytrace") != std::string::npos)
                << run;
        }
    }
}

}  // namespace
}  // namespace luz::test
