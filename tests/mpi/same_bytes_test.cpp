// `mpirun -np N luz render` gives the same bytes as `luz render` in one process
// (docs/DISTRIBUTED.md): every pipeline and antialiasing mode, N from 1 to 4, 1 or 2 threads per
// process, the image, every per-term file and the mask; --region; a scene file naming an OBJ and
// its MTL, which only rank 0 reads (the others render in an empty folder). --stats counts the same
// work and says how it was shared.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "mpi/mpi_run.h"

namespace luz::test {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

/// The folders hold the same files (but `skip`) with the same bytes (subfolders: the same names).
void expect_same_files(const fs::path& one, const fs::path& many, const std::string& skip) {
    std::set<std::string> names = list_dir(one), other = list_dir(many);
    names.erase(skip);
    other.erase(skip);
    ASSERT_EQ(names, other) << one << " vs " << many;
    ASSERT_FALSE(names.empty());
    for (const std::string& n : names) {
        if (fs::is_directory(one / n)) continue;  // the scene's own files (m/x.obj)
        const std::string a = read_file(one / n), b = read_file(many / n);
        EXPECT_FALSE(a.empty()) << n;
        EXPECT_TRUE(a == b) << n << " differs between " << one.filename() << " and "
                            << many.filename();
    }
}

/// The shared render's statistics: N processes whose primary rays add up, and the same work
/// counted as in one process.
void expect_shared_stats(const json& one, const json& many, int np) {
    EXPECT_FALSE(one.contains("processes")) << "one process (not under mpirun)";
    EXPECT_EQ(many["processes"], np);
    ASSERT_TRUE(many["primary_rays_by_process"].is_array());
    ASSERT_EQ(many["primary_rays_by_process"].size(), static_cast<size_t>(np));
    uint64_t sum = 0;
    for (const json& n : many["primary_rays_by_process"]) sum += n.get<uint64_t>();
    EXPECT_EQ(sum, many["rays"]["primary"].get<uint64_t>());
    for (const char* key : {"rays", "intersection_tests", "pixels_refined", "triangles", "width",
                            "height", "pipeline"})
        EXPECT_EQ(one[key], many[key]) << key;
    // The others rendered tiles (every process starts with at least one 16×16 tile of the ray
    // pipelines; the zbuffer's 64×64 raster tiles may be fewer than the processes).
    if (np > 1 && many["pipeline"] != "zbuffer") {
        EXPECT_GT(many["mpi"]["tiles_received"].get<uint64_t>(), 0u);
        for (size_t r = 1; r < static_cast<size_t>(np); ++r)
            EXPECT_GT(many["primary_rays_by_process"][r].get<uint64_t>(), 0u) << "process " << r;
    }
}

struct MpiRun {
    int np;
    int threads;
};

struct Combo {
    std::string scene, pipeline, aa;
    int width, height;
    std::vector<MpiRun> runs;
};

void PrintTo(const Combo& c, std::ostream* os) {
    *os << c.width << "x" << c.height;
    for (const MpiRun& r : c.runs) *os << ", np " << r.np << " threads " << r.threads;
}

std::string combo_name(const testing::TestParamInfo<Combo>& info) {
    std::string scene = info.param.scene.substr(info.param.scene.find(':') + 1);
    return scene + "_" + info.param.pipeline + "_" + info.param.aa;
}

std::vector<Combo> combos() {
    std::vector<Combo> v;
    const char* pipelines[] = {"zbuffer", "raycast", "raytrace"};
    const char* aas[] = {"none", "grid", "adaptive"};
    const int sizes[][2] = {{64, 48}, {133, 97}, {97, 71}, {80, 61}};
    // np 1…4 and threads 1 and 2, spread so that each combination of pipeline and antialiasing
    // meets two process counts, and each process count both thread counts.
    for (int i = 0; i < 9; ++i) {
        const MpiRun a{1 + i % 4, 1 + i % 2}, b{1 + (i + 2) % 4, 2 - i % 2};
        v.push_back(Combo{
            "demo:bunny", pipelines[i / 3], aas[i % 3], sizes[i % 4][0], sizes[i % 4][1], {a, b}});
    }
    v.push_back(Combo{"demo:whitted", "raytrace", "adaptive", 97, 71, {{4, 1}, {2, 2}}});
    v.push_back(Combo{"demo:primitives", "zbuffer", "grid", 80, 61, {{3, 2}, {4, 1}}});
    v.push_back(Combo{"demo:materials", "raytrace", "grid", 64, 48, {{2, 1}, {3, 2}}});
    // 1 200 tiles: replies of many tiles, requests before a process runs out.
    v.push_back(Combo{"demo:whitted", "raytrace", "none", 640, 480, {{3, 1}, {2, 2}}});
    return v;
}

/// `render SCENE …` writing x.pfm, every per-term file, the mask m.png and s.json.
std::vector<std::string> render_args(const Combo& c, int threads,
                                     const std::vector<std::string>& extra = {}) {
    std::vector<std::string> a = {"render",     c.scene,
                                  "--pipeline", c.pipeline,
                                  "--aa",       c.aa,
                                  "--width",    std::to_string(c.width),
                                  "--height",   std::to_string(c.height),
                                  "--threads",  std::to_string(threads),
                                  "-o",         "x.pfm",
                                  "--aov",      "all",
                                  "--aa-mask",  "m.png",
                                  "--stats",    "s.json",
                                  "-q"};
    if (c.aa == "grid")
        a.insert(a.end(), {"--samples", "4", "--set", "render.antialias.filter=\"tent\""});
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
}

class SameBytes : public MpiTest, public testing::WithParamInterface<Combo> {};

TEST_P(SameBytes, AsOneProcess) {
    const Combo& c = GetParam();
    const fs::path one = dir_ / "one";
    fs::create_directory(one);
    const RunResult r1 = run_luz(render_args(c, 2), one);
    ASSERT_EQ(r1.status, 0) << r1.err;
    const json s1 = json::parse(read_file(one / "s.json"));
    for (const MpiRun& run : c.runs) {
        SCOPED_TRACE("np " + std::to_string(run.np) + ", threads " + std::to_string(run.threads));
        const fs::path many =
            dir_ / ("np" + std::to_string(run.np) + "t" + std::to_string(run.threads));
        fs::create_directory(many);
        const RunResult r = run_mpirun(run.np, render_args(c, run.threads), many);
        ASSERT_EQ(r.status, 0) << r.err;
        EXPECT_EQ(r.out, "") << "-q";
        expect_same_files(one, many, "s.json");
        const json s = json::parse(read_file(many / "s.json"));
        expect_shared_stats(s1, s, run.np);
        EXPECT_EQ(s["threads"], run.threads);
    }
}

INSTANTIATE_TEST_SUITE_P(Mpirun, SameBytes, testing::ValuesIn(combos()), combo_name);

// --region under 3 processes: the same bytes as the region rendered in one process.
class RegionMpi : public MpiTest {};

TEST_F(RegionMpi, SameBytesAsOneProcessUnderThreeProcesses) {
    const struct {
        Combo c;
        const char* region;
    } cases[] = {
        {{"demo:whitted", "raytrace", "adaptive", 97, 71, {}}, "13,20,61,33"},
        {{"demo:bunny", "zbuffer", "grid", 64, 48, {}}, "0,40,64,48"},
        {{"demo:bunny", "raycast", "none", 133, 97, {}}, "70,3,133,90"},
    };
    for (const auto& [c, region] : cases) {
        SCOPED_TRACE(c.scene + " " + c.pipeline + " " + c.aa + " --region " + region);
        const fs::path one = dir_ / (c.pipeline + "-one"), many = dir_ / (c.pipeline + "-np3");
        fs::create_directory(one);
        fs::create_directory(many);
        const RunResult r1 = run_luz(render_args(c, 2, {"--region", region}), one);
        ASSERT_EQ(r1.status, 0) << r1.err;
        const RunResult r = run_mpirun(3, render_args(c, 1, {"--region", region}), many);
        ASSERT_EQ(r.status, 0) << r.err;
        expect_same_files(one, many, "s.json");
        const json s1 = json::parse(read_file(one / "s.json"));
        const json s = json::parse(read_file(many / "s.json"));
        expect_shared_stats(s1, s, 3);
        EXPECT_EQ(s["region"], s1["region"]);
    }
}

// A scene file naming an OBJ whose MTL gives its colour: rank 0 reads the three files and sends
// them; the other processes need no shared file system.
class SceneFiles : public MpiTest {
  protected:
    void write_scene(const fs::path& where, bool with_mtl) {
        fs::create_directories(where / "m");
        write_file(where / "m" / "x.obj", std::string(with_mtl ? "mtllib x.mtl\n" : "") +
                                              "v -1 0 0\nv 1 0 0\nv 0 1.5 0\nv 0 0.5 1\n"
                                              "usemtl red\nf 1 2 3\nf 1 4 3\nf 2 3 4\n");
        write_file(where / "m" / "x.mtl",
                   "newmtl red\nKa 0.1 0 0\nKd 0.8 0.1 0.1\nKs 0.3 0.3 0.3\nNs 20\n");
        write_file(where / "s.json", R"({
  "image": {"width": 97, "height": 71},
  "camera": {"position": [0, 1, 4], "look_at": [0, 0.6, 0]},
  "render": {"pipeline": "raytrace"},
  "lights": [{"position": [2, 4, 4], "intensity": 1}],
  "objects": [{"type": "plane", "material": "gesso"}, {"type": "mesh", "file": "m/x.obj"}]
})");
    }
    const std::vector<std::string> args_ = {"render", "s.json",  "-o",      "x.pfm", "--aov",
                                            "all",    "--stats", "st.json", "-q"};
};

TEST_F(SceneFiles, ObjAndMtlRenderTheSameUnderThreeProcesses) {
    const fs::path one = dir_ / "one", many = dir_ / "many", plain = dir_ / "plain";
    write_scene(one, true);
    write_scene(many, true);
    write_scene(plain, false);
    const RunResult r1 = run_luz(args_, one);
    ASSERT_EQ(r1.status, 0) << r1.err;
    EXPECT_EQ(r1.err, "");
    const RunResult r = run_mpirun(3, args_, many);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err, "");
    expect_same_files(one, many, "st.json");
    // The MTL counts: without it the mesh has the default material.
    ASSERT_EQ(run_luz(args_, plain).status, 0);
    EXPECT_NE(read_file(one / "x.pfm"), read_file(plain / "x.pfm"));
}

TEST_F(SceneFiles, OtherProcessesNeedNoSharedFileSystem) {
    // mpirun's multiple-program form: rank 0 in the folder with the scene, ranks 1 and 2 in an
    // empty one (as on another machine).
    const fs::path one = dir_ / "one", many = dir_ / "many", empty = dir_ / "empty";
    write_scene(one, true);
    write_scene(many, true);
    fs::create_directory(empty);
    ASSERT_EQ(run_luz(args_, one).status, 0);
    std::vector<std::string> a = {"--allow-run-as-root", "--oversubscribe", "-np", "1", LUZ_BINARY};
    a.insert(a.end(), args_.begin(), args_.end());
    a.insert(a.end(), {":", "-np", "2", "-wdir", empty.string(), LUZ_BINARY});
    a.insert(a.end(), args_.begin(), args_.end());
    const RunResult r = run_program("mpirun", a, many);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err, "");
    expect_same_files(one, many, "st.json");
    EXPECT_TRUE(list_dir(empty).empty()) << "only rank 0 writes";
    const json s = json::parse(read_file(many / "st.json"));
    ASSERT_EQ(s["primary_rays_by_process"].size(), 3u);
    for (int rank = 1; rank < 3; ++rank)
        EXPECT_GT(s["primary_rays_by_process"][rank].get<uint64_t>(), 0u)
            << "rank " << rank << " rendered tiles";
}

}  // namespace
}  // namespace luz::test
