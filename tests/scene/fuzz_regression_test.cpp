// Inputs with which scripts/fuzz.sh found bugs (tests/corpus/fuzz/<target>/), fed to the loaders
// exactly as the fuzz targets do (fuzz/*.cpp): each must load or throw InputError, nothing else.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "scene/obj_loader.h"
#include "scene/scene_loader.h"

namespace luz {
namespace {

namespace fs = std::filesystem;

const fs::path kFuzzCorpus = fs::path(LUZ_SOURCE_DIR) / "tests" / "corpus" / "fuzz";

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

std::vector<fs::path> inputs(const char* target) {
    std::vector<fs::path> v;
    if (fs::is_directory(kFuzzCorpus / target)) {
        for (const auto& e : fs::directory_iterator(kFuzzCorpus / target)) v.push_back(e.path());
    }
    return v;
}

/// fuzz/fuzz_obj_loader.cpp: OBJ text, then optionally "\n#MTL\n" and what every mtllib reads.
void load_obj_input(std::string_view obj) {
    std::string_view mtl;
    bool has_mtl = false;
    if (const size_t at = obj.find("\n#MTL\n"); at != std::string_view::npos) {
        mtl = obj.substr(at + 6);
        obj = obj.substr(0, at + 1);
        has_mtl = true;
    }
    const TextReader read = [&](const std::string&,
                                std::string& reason) -> std::optional<std::string> {
        if (!has_mtl) {
            reason = "No such file or directory";
            return std::nullopt;
        }
        return std::string(mtl);
    };
    std::vector<std::string> warnings;
    parse_obj(obj, "fuzz.obj", true, read, warnings);
}

TEST(FuzzRegression, ObjInputsLoadOrThrowInputError) {
    const std::vector<fs::path> files = inputs("obj");
    EXPECT_GE(files.size(), 1u);
    for (const fs::path& f : files) {
        const std::string text = slurp(f);
        try {
            load_obj_input(text);
        } catch (const InputError& e) {
            // "FILE:LINE: what" (the file: fuzz.obj, or an MTL file it names)
            EXPECT_NE(std::string(e.what()).find(": "), std::string::npos) << f << e.what();
        } catch (const std::exception& e) {
            ADD_FAILURE() << f << ": not an InputError: " << e.what();
        }
    }
}

TEST(FuzzRegression, SceneInputsLoadOrThrowInputError) {
    for (const fs::path& f : inputs("scene")) {
        try {
            parse_scene(slurp(f), "fuzz.json", kFuzzCorpus.string());
        } catch (const InputError&) {
        } catch (const std::exception& e) {
            ADD_FAILURE() << f << ": not an InputError: " << e.what();
        }
    }
}

}  // namespace
}  // namespace luz
