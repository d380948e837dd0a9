// The malformed-input corpus (tests/corpus/): every scene in scenes/ and every OBJ in obj/ (the
// latter through a one-mesh scene) is rendered; tests/corpus/expected.tsv gives its exit status
// and a fragment of its message. Errors: one line naming the file, and no output file.
// Warnings (exit 0): a "luz: warning:" line naming the file, and the image is written.
#include <gtest/gtest.h>

#include <fstream>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include "cli/run_luz.h"

namespace luz::test {
namespace {

namespace fs = std::filesystem;

const fs::path kCorpus = fs::path(LUZ_SOURCE_DIR) / "tests" / "corpus";

struct CorpusCase {
    std::string file;      ///< relative to tests/corpus, e.g. "scenes/syntax_truncated.json"
    int status = 0;        ///< expected exit status
    std::string fragment;  ///< must appear in the message line
};

void PrintTo(const CorpusCase& c, std::ostream* os) { *os << c.file; }

/// expected.tsv: FILE <tab> STATUS <tab> FRAGMENT; '#' starts a comment line.
std::vector<CorpusCase> corpus_cases() {
    std::vector<CorpusCase> v;
    std::ifstream in(kCorpus / "expected.tsv");
    std::string line;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#') continue;
        std::istringstream fields(line);
        CorpusCase c;
        std::string status;
        std::getline(fields, c.file, '\t');
        std::getline(fields, status, '\t');
        std::getline(fields, c.fragment);
        c.status = std::stoi(status);
        v.push_back(c);
    }
    return v;
}

std::string case_name(const testing::TestParamInfo<CorpusCase>& info) {
    std::string name = fs::path(info.param.file).parent_path().string() + "_" +
                       fs::path(info.param.file).stem().string();
    for (char& ch : name) {
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
    }
    return name;
}

class Corpus : public TempDirTest, public testing::WithParamInterface<CorpusCase> {};

TEST_P(Corpus, ExitStatusAndOneLineNamingTheFile) {
    const CorpusCase& c = GetParam();
    const fs::path source = kCorpus / c.file;
    ASSERT_TRUE(fs::exists(source)) << source;
    const std::string name = source.filename().string();
    fs::copy_file(source, dir_ / name);
    std::string scene = name;
    if (source.extension() == ".obj") {
        // the OBJ's MTL files next to it, and a scene with just that mesh
        for (const auto& e : fs::directory_iterator(source.parent_path())) {
            if (e.path().extension() == ".mtl") fs::copy_file(e.path(), dir_ / e.path().filename());
        }
        scene = "s.json";
        write_file(dir_ / scene, R"({"image": {"width": 64, "height": 48},
            "objects": [{"type": "mesh", "file": ")" +
                                     name + R"("}]})");
    }
    const RunResult r = run_luz({"render", scene, "-o", "out.png", "--quiet"}, dir_);
    EXPECT_EQ(r.status, c.status) << r.err;
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    // the file at fault: the OBJ, or the MTL file the fragment names
    const bool names_mtl = c.fragment.find(".mtl:") != std::string::npos;
    EXPECT_TRUE(names_mtl || r.err.find(name) != std::string::npos) << r.err;
    EXPECT_NE(r.err.find(c.fragment), std::string::npos)
        << "expected \"" << c.fragment << "\" in: " << r.err;
    EXPECT_EQ(r.err.find("std::"), std::string::npos) << r.err;
    if (c.status == 0) {
        EXPECT_EQ(r.err.rfind("luz: warning: ", 0), 0u) << r.err;
        EXPECT_TRUE(fs::exists(dir_ / "out.png"));
    } else {
        EXPECT_FALSE(fs::exists(dir_ / "out.png"));
    }
}

INSTANTIATE_TEST_SUITE_P(Files, Corpus, testing::ValuesIn(corpus_cases()), case_name);

TEST(CorpusManifest, ListsEveryFileAndEnoughOfThem) {
    std::set<std::string> listed;
    int scenes = 0, objs = 0;
    for (const CorpusCase& c : corpus_cases()) {
        listed.insert(c.file);
        if (c.file.rfind("scenes/", 0) == 0) ++scenes;
        if (c.file.rfind("obj/", 0) == 0 && c.status != 0) ++objs;
    }
    EXPECT_GE(scenes, 40);
    EXPECT_GE(objs, 20);
    for (const char* folder : {"scenes", "obj"}) {
        for (const auto& e : fs::directory_iterator(kCorpus / folder)) {
            if (e.path().extension() == ".mtl") continue;
            const std::string file = std::string(folder) + "/" + e.path().filename().string();
            EXPECT_TRUE(listed.count(file)) << file << " is not in expected.tsv";
        }
    }
}

}  // namespace
}  // namespace luz::test
