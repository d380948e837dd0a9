// `luz scenes` and `luz materials`: listings of demo_scenes() and presets().
#include "app/list_commands.h"

#include <algorithm>
#include <string>
#include <vector>

#include "luz/demo_scenes.h"
#include "luz/presets.h"

namespace luz {

void print_scenes(std::FILE* out) {
    size_t width = 0;
    for (const DemoScene& d : demo_scenes()) width = std::max(width, d.name.size() + 5);
    for (const DemoScene& d : demo_scenes()) {
        const std::string name = "demo:" + std::string(d.name);
        std::fprintf(out, "%-*s  %.*s\n", static_cast<int>(width), name.c_str(),
                     static_cast<int>(d.description.size()), d.description.data());
    }
}

/// A colour as one number when its channels agree, else "r,g,b".
static std::string rgb_text(const Rgb& c) {
    char buf[64];
    if (c.x == c.y && c.y == c.z) {
        std::snprintf(buf, sizeof buf, "%g", c.x);
    } else {
        std::snprintf(buf, sizeof buf, "%g,%g,%g", c.x, c.y, c.z);
    }
    return buf;
}

void print_materials(std::FILE* out) {
    // rows of text first, so that every column is as wide as its widest cell
    std::vector<std::vector<std::string>> rows = {{"name", "alias", "ka", "kd", "ks", "n",
                                                   "reflection", "transparency", "ior",
                                                   "reflectance"}};
    auto num = [](float v) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%g", v);
        return std::string(buf);
    };
    for (const Preset& p : presets()) {
        const Material& m = p.material;
        rows.push_back({std::string(p.name), std::string(p.alias), rgb_text(m.ka), rgb_text(m.kd),
                        rgb_text(m.ks), num(m.n), num(m.reflection), num(m.transparency),
                        num(m.ior),
                        m.reflectance == Reflectance::schlick ? "schlick" : "constant"});
    }
    std::vector<size_t> width(rows[0].size(), 0);
    for (const auto& row : rows) {
        for (size_t i = 0; i < row.size(); ++i) width[i] = std::max(width[i], row[i].size());
    }
    for (const auto& row : rows) {
        std::string line;
        for (size_t i = 0; i < row.size(); ++i) {
            line += row[i];
            if (i + 1 < row.size()) line.append(width[i] - row[i].size() + 2, ' ');
        }
        std::fprintf(out, "%s\n", line.c_str());
    }
}

}  // namespace luz
