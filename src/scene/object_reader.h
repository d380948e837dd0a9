// The scene loader's reader of `objects` entries: each shape's keys from kShapeKeys
// (shape_desc.h), its checks, `material`, `transform`, and the OBJ files of meshes.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "scene/json_text.h"
#include "scene/material_table.h"
#include "scene/scene_desc.h"

namespace luz::loader {

/// The OBJ files of the scene's meshes, each loaded once (docs/SCENES.md#scene-files `mesh`).
class MeshFiles {
  public:
    /// `cache`: meshes read by earlier loads, reused and added to; nullptr: none.
    MeshFiles(SceneDesc& scene, MeshCache* cache) : scene_(scene), cache_(cache) {}

    /// Loads o.file into o.mesh. Without a `material` key, the MTL materials its faces use join
    /// the scene's materials (named "file.obj:name") and o.mesh_materials maps them. A built-in
    /// scene reads its meshes from the binary (embedded_files.h), other files from disk.
    void load(ObjectDesc& o, bool names_material, MaterialTable& materials);

  private:
    /// Reads and parses `file` (named at key path `path` in messages).
    std::shared_ptr<const MeshData> read_mesh(const std::string& file, bool with_materials,
                                              const std::string& path);

    struct Loaded {
        std::shared_ptr<const MeshData> mesh;
        std::vector<int> scene_index;
    };
    SceneDesc& scene_;
    MeshCache* cache_;
    std::map<std::pair<std::string, bool>, Loaded> loaded_;
};

/// One entry of `objects` at key path `path`; relative mesh paths resolve against `base_dir`.
/// Throws KeyError (InputError when a mesh file cannot be read or parsed).
ObjectDesc read_object(const Json& j, const std::string& path, MaterialTable& materials,
                       const std::string& base_dir, MeshFiles& meshes);

}  // namespace luz::loader
