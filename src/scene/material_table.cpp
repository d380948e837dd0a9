// Reading materials (docs/SCENES.md#scene-files): named, preset, inline, with checker; see
// material_table.h.
#include "scene/material_table.h"

#include "scene/json_readers.h"
#include "scene/message_text.h"

namespace luz::loader {
namespace {

/// How many material names an "unknown material" message lists.
constexpr std::size_t kNamesListed = 10;

std::string preset_names() {
    std::string s;
    for (const Preset& p : presets()) {
        s += (s.empty() ? "" : ", ") + std::string(p.name) + "/" + std::string(p.alias);
    }
    return s;
}

/// A material object: optionally `preset` first, then the constants it overrides.
Material read_material(const Json& j, const std::string& path) {
    const Section s(j, path,
                    {"preset", "ka", "kd", "ks", "n", "reflection", "transparency", "ior",
                     "reflectance", "checker"},
                    "materials.*");
    Material m;
    if (const Json* p = s.get("preset")) {
        const std::string name = read_string(*p, s.key("preset"));
        const Preset* preset = find_preset(name);
        if (!preset) {
            fail(s.key("preset"),
                 "unknown preset " + quote(name) + " (known: " + preset_names() + ")");
        }
        m = preset->material;
    }
    s.rgb("ka", m.ka);
    s.rgb("kd", m.kd);
    s.rgb("ks", m.ks);
    s.number("n", m.n);
    s.number("reflection", m.reflection);
    s.number("transparency", m.transparency);
    s.number("ior", m.ior);
    s.enumeration("reflectance", m.reflectance,
                  {{"constant", Reflectance::constant}, {"schlick", Reflectance::schlick}});
    if (const Json* cj = s.get("checker")) {
        Checker c;
        const Section cs(*cj, s.key("checker"), {"size", "ka", "kd"}, "materials.*.checker");
        cs.number("size", c.size);
        cs.rgb("ka", c.ka);
        cs.rgb("kd", c.kd);
        m.checker = c;
    }
    return m;
}

}  // namespace

MaterialTable::MaterialTable(std::vector<Material>& list) : list_(list) {
    list_.clear();
    Material def;  // docs/SCENES.md#models: the slide's Ka = 0.1, Kd = 0.45
    def.name = "default";
    list_.push_back(def);
    by_name_["default"] = 0;
}

void MaterialTable::read_section(const Json& j) {
    if (!j.is_object()) {
        fail("materials", "expected an object of named materials, got " + describe(j));
    }
    for (const auto& item : j.items()) {
        const std::string path = join("materials", item.key());
        Material m = read_material(item.value(), path);
        m.name = item.key();
        if (item.key() == "default") {
            list_[0] = m;
            by_name_[item.key()] = 0;
        } else {
            by_name_[item.key()] = static_cast<int>(list_.size());
            list_.push_back(m);
        }
    }
}

int MaterialTable::resolve(const Json& j, const KeyPath& path) {
    if (j.is_string()) {
        const std::string& name = j.get_ref<const std::string&>();
        if (const auto it = by_name_.find(name); it != by_name_.end()) return it->second;
        if (const Preset* p = find_preset(name)) {
            const auto it = by_preset_.find(p);
            if (it != by_preset_.end()) return it->second;
            Material m = p->material;
            m.name = std::string(p->name);
            by_preset_[p] = static_cast<int>(list_.size());
            list_.push_back(m);
            return by_preset_[p];
        }
        // the first few names defined (a scene may define thousands)
        std::string defined;
        std::size_t listed = 0;
        for (const auto& [n, i] : by_name_) {
            if (listed == kNamesListed) {
                defined += " and " + std::to_string(by_name_.size() - listed) + " more";
                break;
            }
            defined += (listed++ ? ", " : "") + printable(n, kMaxQuotedChars);
        }
        fail(path.str(), "unknown material " + quote(name) +
                             " (defined in materials: " + (defined.empty() ? "none" : defined) +
                             "; presets: " + preset_names() + ")");
    }
    if (j.is_object()) {
        const std::string name = path.str();
        Material m = read_material(j, name);
        m.name = name;
        list_.push_back(m);
        return static_cast<int>(list_.size()) - 1;
    }
    fail(path.str(), "expected a material name or a material object, got " + describe(j));
}

int MaterialTable::add(const Material& m) {
    list_.push_back(m);
    return static_cast<int>(list_.size()) - 1;
}

}  // namespace luz::loader
