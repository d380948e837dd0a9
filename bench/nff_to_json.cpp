// An NFF scene written as a JSON scene with OBJ meshes that a luz without the NFF reader (the
// old tree of issue 37, 5b7f603) renders: bench/old_vs_new.sh's SPD rows. The scene is read by
// this tree's NFF reader (docs/SCENES.md#nff), so the objects, materials, camera and the
// triangulated polygons are exactly what `luz render NAME.nff` renders; two things differ
// because the old scene format cannot say them:
//   - `attenuation: none` becomes Il/(d+K) with K = 1000 and every light 1000 times as bright,
//     so Il/(d+K) = I·(1 − d/1000 …): within 1–2 % of NFF's light over the SPD's distances;
//   - a truncated cone (`apex_radius` > 0; the tree's branches) has no old form: exit 3.
// The same rays are traced either way (lighting does not steer any ray).
//
// usage: nff_to_json SCENE.nff OUT_DIR   (writes OUT_DIR/scene.json and OUT_DIR/NAME_fK.obj)
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "scene/json_text.h"
#include "scene/nff_reader.h"

namespace {

using luz::loader::Json;

constexpr double kK = 1000;  // the old tree's largest attenuation_k

void write_obj(const luz::MeshData& m, const std::filesystem::path& path) {
    std::ofstream out(path);
    char line[128];
    for (const luz::Vec3& p : m.positions) {
        std::snprintf(line, sizeof line, "v %.9g %.9g %.9g\n", p.x, p.y, p.z);
        out << line;
    }
    for (const luz::Vec3& n : m.normals) {
        std::snprintf(line, sizeof line, "vn %.9g %.9g %.9g\n", n.x, n.y, n.z);
        out << line;
    }
    for (size_t t = 0; t < m.triangle_count(); ++t) {
        out << 'f';
        for (size_t k = 3 * t; k < 3 * t + 3; ++k) {
            out << ' ' << m.position[k] + 1;
            if (!m.normal.empty() && m.normal[k] >= 0) out << "//" << m.normal[k] + 1;
        }
        out << '\n';
    }
    if (!out) throw std::runtime_error(path.string() + ": cannot write");
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: nff_to_json SCENE.nff OUT_DIR\n");
        return 2;
    }
    try {
        const std::filesystem::path nff = argv[1], out_dir = argv[2];
        std::ifstream in(nff);
        if (!in) throw std::runtime_error(nff.string() + ": cannot read");
        std::stringstream text;
        text << in.rdbuf();
        luz::loader::NffScene scene =
            luz::loader::read_nff(text.str(), nff.filename().string(), "");
        Json& doc = scene.doc;

        if (doc.value("attenuation", "") == "none") {
            doc.erase("attenuation");
            doc["attenuation_k"] = kK;
            for (Json& light : doc["lights"]) {
                for (Json& c : light["intensity"]) c = c.get<double>() * kK;
            }
        }
        std::filesystem::create_directories(out_dir);
        const std::string stem = nff.stem().string();
        for (Json& object : doc["objects"]) {
            if (object.contains("apex_radius") && object["apex_radius"].get<double>() > 0) {
                std::fprintf(stderr,
                             "nff_to_json: %s has a truncated cone (apex_radius), which the old "
                             "scene format cannot express\n",
                             nff.string().c_str());
                return 3;
            }
            object.erase("apex_radius");
            if (object.value("type", "") != "mesh") continue;
            const std::string file = object["file"].get<std::string>();
            const auto it = scene.meshes.find({file, false});
            const auto it_mtl = scene.meshes.find({file, true});
            if (it == scene.meshes.end() && it_mtl == scene.meshes.end())
                throw std::runtime_error("no mesh data for " + file);
            const auto& mesh = it != scene.meshes.end() ? it->second : it_mtl->second;
            // "balls.nff#f3" -> "balls_f3.obj"
            std::string name = stem + "_" + file.substr(file.find('#') + 1) + ".obj";
            write_obj(*mesh, out_dir / name);
            object["file"] = name;
        }
        std::ofstream json(out_dir / "scene.json");
        json << doc.dump(1) << '\n';
        if (!json) throw std::runtime_error((out_dir / "scene.json").string() + ": cannot write");
    } catch (const std::exception& e) {
        std::fprintf(stderr, "nff_to_json: %s\n", e.what());
        return 1;
    }
    return 0;
}
