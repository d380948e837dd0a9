// The public Scene: a built scene shared by its copies, its BVH built on the first ray-traced
// render, and build counters (include/luz/scene.h).
#include "geometry/scene.h"

#include <mutex>
#include <nlohmann/json.hpp>

#include "api/built_scene.h"
#include "luz/json.h"
#include "luz/scene.h"
#include "luz/scene_text.h"  // share_meshes()
#include "scene/mesh_data.h"

namespace luz {

struct Scene::State {
    BuiltScene built;
    mutable std::mutex mutex;  ///< guards the lazy BVH build and the counters
    mutable BuildCounts counts;
};

const Scene::State& scene_state(const Scene& scene) {
    if (!scene.state_) throw std::logic_error("luz::Scene used before build()");
    return *scene.state_;
}

const BuiltScene& built_scene(const Scene& scene) { return scene_state(scene).built; }

BuildCounts Scene::build_counts() const {
    if (!state_) return {};
    std::lock_guard lock(state_->mutex);
    return state_->counts;
}

size_t Scene::material_count() const { return built_scene(*this).material_count; }

void Scene::prepare(Pipeline pipeline) const {
    const BuiltScene& b = built_scene(*this);
    if (pipeline == Pipeline::zbuffer || b.geometry.accel != Accel::bvh) return;
    std::lock_guard lock(state_->mutex);
    if (b.has_bvh) return;
    // Every ray-traced render of this scene calls prepare() first and waits here until the
    // BVH is built; once built it never changes.
    build_bvh(state_->built);
    ++state_->counts.bvh;
}

Scene build(const SceneDesc& desc) {
    Scene scene;
    scene.state_ = std::make_shared<Scene::State>();
    // The BVH waits for the first ray-traced render (prepare()): a zbuffer render needs none.
    scene.state_->built = build_scene(desc, false);
    scene.state_->counts.geometry = 1;
    return scene;
}

namespace {

/// Two loads of one OBJ file that came out the same (a reload for new overrides).
bool same_mesh(const MeshData& a, const MeshData& b) {
    return a.file == b.file && a.positions == b.positions && a.normals == b.normals &&
           a.position == b.position && a.normal == b.normal && a.material == b.material;
}

// Lets `desc` share `base`'s loaded meshes where they are the same, so that needs_rebuild()
/// (which compares meshes by identity) sees equal objects as equal.
}  // namespace

void share_meshes(const SceneDesc& base, SceneDesc& desc) {
    const size_t n = std::min(base.objects.size(), desc.objects.size());
    for (size_t i = 0; i < n; ++i) {
        const auto& old_mesh = base.objects[i].mesh;
        auto& new_mesh = desc.objects[i].mesh;
        if (old_mesh && new_mesh && old_mesh != new_mesh && same_mesh(*old_mesh, *new_mesh)) {
            new_mesh = old_mesh;
        }
    }
}

bool needs_rebuild(const SceneDesc& a, const SceneDesc& b) {
    if (a.geometry.tessellation != b.geometry.tessellation) return true;
    if (a.geometry.accel != b.geometry.accel) return true;
    return a.objects != b.objects;
}

const Scene& EditableScene::scene() {
    if (!scene_ || needs_rebuild(built_from_, desc_)) {
        const BuildCounts old = scene_.build_counts();
        retired_.geometry += old.geometry;
        retired_.bvh += old.bvh;
        scene_ = build(desc_);
        built_from_ = desc_;
    }
    return scene_;
}

BuildCounts EditableScene::build_counts() const {
    const BuildCounts now = scene_.build_counts();
    return {retired_.geometry + now.geometry, retired_.bvh + now.bvh};
}

SceneDesc load_scene_value(const nlohmann::ordered_json& value, const std::string& label,
                           const std::string& base_dir, const std::vector<Override>& overrides) {
    // A parsed value has no syntax to get wrong: its text goes through the one loader, so that
    // every check and message is the file's (key paths named after `label`).
    return parse_scene(value.dump(), label, base_dir, overrides);
}

std::string one_line(const std::string& message) {
    std::string line = message;
    while (!line.empty() && (line.back() == '\n' || line.back() == '\r')) line.pop_back();
    for (char& c : line) {
        if (c == '\n' || c == '\r') {
            c = ' ';
        } else if (static_cast<unsigned char>(c) < 0x20 && c != '\t') {
            c = '?';  // a NUL or control byte quoted from a bad file
        }
    }
    return line;
}

}  // namespace luz
