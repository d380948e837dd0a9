// The commands other than render: scenes, materials, view, --version, --help.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "cli/run_luz.h"
#include "scene/demo_scenes.h"
#include "scene/presets.h"

namespace luz::test {
namespace {

class Commands : public TempDirTest {};

TEST_F(Commands, ScenesListsEveryDemoOnItsOwnLine) {
    const RunResult r = run_luz({"scenes"}, dir_);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(count_lines(r.out), static_cast<int>(demo_scenes().size()));
    for (const DemoScene& d : demo_scenes()) {
        const std::string name = "demo:" + std::string(d.name);
        const size_t at = r.out.find(name + " ");
        ASSERT_NE(at, std::string::npos) << name;
        const size_t eol = r.out.find('\n', at);
        EXPECT_NE(r.out.substr(at, eol - at).find(d.description), std::string::npos) << name;
    }
    EXPECT_NE(r.out.find("demo:primitives"), std::string::npos);
}

TEST_F(Commands, MaterialsListsEveryPresetWithItsConstants) {
    const RunResult r = run_luz({"materials"}, dir_);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(count_lines(r.out), 1 + static_cast<int>(presets().size()));
    for (const char* column : {"name", "alias", "ka", "kd", "ks", "n", "reflection", "transparency",
                               "ior", "reflectance"}) {
        EXPECT_NE(r.out.find(column), std::string::npos) << column;
    }
    for (const Preset& p : presets()) {
        const size_t at = r.out.find(std::string(p.name) + " ");
        ASSERT_NE(at, std::string::npos) << p.name;
        const std::string line = r.out.substr(at, r.out.find('\n', at) - at);
        EXPECT_NE(line.find(std::string(p.alias)), std::string::npos) << line;
        char ior[32];
        std::snprintf(ior, sizeof ior, "%g", p.material.ior);
        EXPECT_NE(line.find(ior), std::string::npos) << line;
        // the reflectance curve, last (docs/SCENES.md#reflectance)
        const bool schlick = p.material.reflectance == Reflectance::schlick;
        EXPECT_TRUE(line.ends_with(schlick ? " schlick" : " constant")) << line;
    }
    for (const char* name : {"gesso", "madeira", "concreto", "cortica", "plastico", "metal_polido",
                             "agua", "vidro", "ouro", "prata", "cobre"}) {
        EXPECT_NE(r.out.find(name), std::string::npos) << name;
    }
}

TEST_F(Commands, MaterialsListsTheMetalsWithTheirMeasuredKsAndSchlick) {
    const RunResult r = run_luz({"materials"}, dir_);
    ASSERT_EQ(r.status, 0) << r.err;
    const auto line_of = [&](const std::string& name) {
        const size_t at = r.out.find("\n" + name + " ");
        if (at == std::string::npos) return std::string();
        return r.out.substr(at + 1, r.out.find('\n', at + 1) - at - 1);
    };
    EXPECT_NE(line_of("ouro").find(" gold "), std::string::npos) << r.out;
    EXPECT_NE(line_of("prata").find(" silver "), std::string::npos) << r.out;
    EXPECT_NE(line_of("cobre").find(" copper "), std::string::npos) << r.out;
    EXPECT_NE(line_of("ouro").find(" 1,0.71,0.29 "), std::string::npos) << line_of("ouro");
    EXPECT_NE(line_of("prata").find(" 0.95,0.93,0.88 "), std::string::npos) << line_of("prata");
    EXPECT_NE(line_of("cobre").find(" 0.95,0.64,0.54 "), std::string::npos) << line_of("cobre");
    for (const char* metal : {"ouro", "prata", "cobre"}) {
        EXPECT_TRUE(line_of(metal).ends_with(" schlick")) << line_of(metal);
    }
    EXPECT_TRUE(line_of("metal_polido").ends_with(" constant")) << line_of("metal_polido");
}

TEST_F(Commands, VersionPrintsNameAndVersion) {
    const RunResult r = run_luz({"--version"}, dir_);
    EXPECT_EQ(r.status, 0);
    EXPECT_EQ(r.out, "luz 0.1.0\n");  // project(luz VERSION 0.1.0)
}

TEST_F(Commands, HelpListsTheCommands) {
    const RunResult r = run_luz({"--help"}, dir_);
    EXPECT_EQ(r.status, 0);
    for (const char* word : {"render", "scenes", "materials", "view", "--version"}) {
        EXPECT_NE(r.out.find(word), std::string::npos) << word;
    }
}

TEST_F(Commands, RenderHelpListsEveryOption) {
    const RunResult r = run_luz({"render", "--help"}, dir_);
    EXPECT_EQ(r.status, 0);
    for (const char* word :
         {"--output", "--pipeline", "--model", "--width", "--height", "--max-depth", "--aa",
          "--samples", "--threshold", "--threads", "--stats", "--quiet", "--set", "SCENE"}) {
        EXPECT_NE(r.out.find(word), std::string::npos) << word;
    }
}

TEST_F(Commands, ViewWithoutADisplayFailsWithOneLine) {
    // No X server: `luz view` says it cannot open a window (or, built without the viewer, that
    // it has none) and exits 1 — never a window nobody sees.
    ::unsetenv("DISPLAY");
    ::unsetenv("WAYLAND_DISPLAY");
    const RunResult r = run_luz({"view", "demo:primitives"}, dir_);
    EXPECT_EQ(r.status, 1);
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_TRUE(r.err.find("cannot open a window") != std::string::npos ||
                r.err.find("built without the viewer") != std::string::npos)
        << r.err;
}

}  // namespace
}  // namespace luz::test
