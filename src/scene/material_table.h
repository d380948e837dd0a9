// The scene loader's materials: the `materials` section, objects' `material` keys (names,
// presets, inline objects) and MTL materials, as one list.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "scene/json_readers.h"
#include "scene/json_text.h"
#include "scene/material.h"
#include "scene/presets.h"

namespace luz::loader {

/// The scene's materials: materials[0] is the default, then those of `materials` in file
/// order, then the presets and inline materials objects refer to, one entry per name.
class MaterialTable {
  public:
    explicit MaterialTable(std::vector<Material>& list);

    /// Reads the `materials` section. A material named "default" replaces the default one
    /// (the material of every object that names none). Throws KeyError.
    void read_section(const Json& j);

    /// The `material` key of an object: a name from `materials`, a preset, or an inline object.
    int resolve(const Json& j, const KeyPath& path);

    /// Adds a material no key names (an MTL material); returns its index.
    int add(const Material& m);

  private:
    std::vector<Material>& list_;
    std::map<std::string, int> by_name_;
    std::map<const Preset*, int> by_preset_;
};

}  // namespace luz::loader
