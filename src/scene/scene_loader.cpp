// BuiltScene loading (docs/SCENES.md#scene-files): JSON text (json_text.h) or an NFF file
// (nff_reader.h, docs/SCENES.md#nff) → --set overrides applied to the document (overrides.h) → the
// sections read and validated (settings_readers.h, material_table.h, object_reader.h) into a
// SceneDesc with every default filled. Every error names the file (or the override) and the
// line:column, line or key path.
#include "scene/scene_loader.h"

#include <malloc.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <utility>

#include "scene/animation.h"
#include "scene/animation_reader.h"
#include "scene/cancel.h"
#include "scene/demo_scenes.h"
#include "scene/json_readers.h"
#include "scene/material_table.h"
#include "scene/message_text.h"
#include "scene/nff_reader.h"
#include "scene/obj_loader.h"
#include "scene/object_reader.h"
#include "scene/overrides.h"
#include "scene/settings_readers.h"
#include "scene/text_files.h"

namespace luz {
namespace {

using namespace loader;

/// Returns the pages the parsed document held to the system: its many small blocks, once
/// freed, would otherwise stay resident beside the built scene (--max-memory counts them once).
void give_back_free_memory() {
#ifdef __GLIBC__
    malloc_trim(0);
#endif
}

/// The document (overrides already applied) → SceneDesc, its camera turned by the orbit of
/// `animation` at `frame`. Throws KeyError.
void read_scene(const Json& doc, const std::string& base_dir, MeshCache* meshes_read,
                const AnimationDesc& animation, int frame, SceneDesc& scene,
                const NffScene::Direct* direct = nullptr) {
    const Section top(doc, "",
                      {"image", "camera", "render", "ambient", "attenuation_k", "attenuation",
                       "lights", "materials", "objects", "animation"},
                      "");
    if (const Json* j = top.get("image")) read_image(*j, scene.image);
    read_camera(top.get("camera"), scene.camera);
    // The orbit before anything placed by the camera (the implicit light, lights without a
    // position): frame f is the scene with the camera where the orbit puts it.
    apply_orbit(animation, frame, scene.camera);
    if (const Json* j = top.get("render")) read_render(*j, scene.render, scene.geometry);
    top.rgb("ambient", scene.ambient);
    top.number("attenuation_k", scene.attenuation_k);
    top.enumeration("attenuation", scene.attenuation,
                    {{"none", Attenuation::none},
                     {"linear", Attenuation::linear},
                     {"inverse_square", Attenuation::inverse_square}});

    MaterialTable materials(scene.materials);
    MeshFiles meshes(scene, meshes_read);
    if (const Json* j = top.get("materials")) materials.read_section(*j);
    if (direct) {
        // An NFF file read directly (nff_reader.h): its objects in the file's order, those of
        // the document (its meshes) read as below, the others given their path and material.
        const Json* j = top.get("objects");
        std::map<std::string, int> material_of;  // by name, resolved as the document's would be
        scene.objects.reserve(scene.objects.size() + direct->order.size());
        for (std::size_t i = 0; i < direct->order.size(); ++i) {
            check_cancel();
            const std::int64_t k = direct->order[i];
            if (k < 0) {
                const auto m = static_cast<std::size_t>(-1 - k);
                scene.objects.push_back(
                    read_object(j->at(m), join("objects", i), materials, base_dir, meshes));
                continue;
            }
            ObjectDesc& o = scene.objects.emplace_back(
                shape_object(direct->objects[static_cast<std::size_t>(k)]));
            o.path = join("objects", i);
            if (const std::string& name = direct->materials[static_cast<std::size_t>(k)];
                !name.empty()) {
                auto [it, added] = material_of.try_emplace(name, 0);
                if (added) it->second = materials.resolve(Json(name), KeyPath(o.path, "material"));
                o.material = it->second;
            }
        }
    } else if (const Json* j = top.get("objects")) {
        if (!j->is_array()) fail("objects", "expected an array of objects, got " + describe(*j));
        scene.objects.reserve(scene.objects.size() + j->size());
        for (std::size_t i = 0; i < j->size(); ++i) {
            check_cancel();
            scene.objects.push_back(
                read_object((*j)[i], join("objects", i), materials, base_dir, meshes));
        }
    }
    read_lights(top.get("lights"), scene);
}

/// Runs `read` (which reads part of `doc`, where `overrides` were applied, creating or
/// replacing `roots`) and turns its KeyError into an InputError blaming the latest override
/// that put the bad value there (or, for a check across keys, changed one of the keys
/// involved); otherwise the file.
template <typename Read>
void blaming(const std::string& file, const NffScene* nff, const std::vector<Override>& overrides,
             const std::vector<std::string>& roots, Read read) {
    try {
        read();
    } catch (const KeyError& e) {
        for (std::size_t i = overrides.size(); i-- > 0;) {
            const Override& o = overrides[i];
            if (!e.path.empty() &&
                (is_under(e.path, roots[i]) || (!e.scope.empty() && is_under(roots[i], e.scope)))) {
                const bool same = e.path == o.path && o.origin == "--set";
                throw InputError(override_label(o) + ": " + (same ? "" : printable(e.path) + ": ") +
                                 e.what);
            }
        }
        // An NFF file's key paths came from its lines: the message names the line too.
        const std::size_t line = nff ? nff->line_of(e.path) : 0;
        throw InputError(printable(file) + (line ? ":" + std::to_string(line) : "") + ": " +
                         (e.path.empty() ? "" : printable(e.path) + ": ") + e.what);
    }
}

/// The document with the user's overrides applied, and its animation.
struct Document {
    Json text;  ///< the file as parsed: kept for an animation only (its frames start from it)
    Json doc;   ///< with the user's overrides applied
    std::vector<Override> overrides;
    std::vector<std::string> roots;  ///< per override: what it created or replaced
    AnimationDesc animation;
    std::optional<NffScene> nff;  ///< an NFF file: its lines and meshes (its doc moved to doc)
};

/// The file's document: its JSON text parsed, or an NFF file read (docs/SCENES.md#nff),
/// `direct` if asked and it can be (NffScene::direct).
Json read_text(std::string_view text, const std::string& file, const std::string& base_dir,
               std::optional<NffScene>* nff, bool direct = false) {
    if (!is_nff_file(file)) return parse_text(text, file);
    NffScene scene;
    try {
        scene = read_nff(text, file, base_dir, direct);
    } catch (const NffNotDirect&) {  // an object out of range: the document's message
        scene = read_nff(text, file, base_dir);
    }
    Json doc = std::move(scene.doc);
    if (nff) *nff = std::move(scene);
    return doc;
}

/// Whether an NFF file may be read directly (NffScene::direct) under these overrides: none
/// reaches into its objects or gives it an animation.
bool direct_under(const std::vector<Override>& overrides) {
    for (const Override& o : overrides) {
        const std::string_view root = std::string_view(o.path).substr(0, o.path.find('.'));
        if (root.empty() || root == "objects" || root == "animation") return false;
    }
    return true;
}

Document read_document(std::string_view text, const std::string& file, const std::string& base_dir,
                       const std::vector<Override>& overrides) {
    Document d{{}, {}, overrides, {}, {}, {}};
    d.doc = read_text(text, file, base_dir, &d.nff, direct_under(overrides));
    d.roots.reserve(overrides.size());
    for (const Override& o : overrides) d.roots.push_back(apply_override(d.doc, o));
    blaming(file, d.nff ? &*d.nff : nullptr, d.overrides, d.roots, [&] {
        if (d.doc.is_object() && d.doc.contains("animation")) {
            d.animation = read_animation(d.doc["animation"]);
        }
    });
    // Parsed twice only when animated: a large scene is held once.
    if (!d.animation.keys.empty()) {
        d.text = overrides.empty() ? d.doc : read_text(text, file, base_dir, nullptr);
    }
    return d;
}

/// Frame `frame` of the document: its keyframed values, then the user's overrides, then the
/// scene read with the camera's orbit.
SceneDesc read_frame(const Document& d, const std::string& file, const std::string& base_dir,
                     int frame, MeshCache* meshes) {
    SceneDesc scene;
    scene.source = file;
    if (file.rfind("demo:", 0) == 0) {
        scene.name = file.substr(5);
    } else {
        scene.name = std::filesystem::path(file).stem().string();
    }
    if (scene.name.empty()) scene.name = "scene";

    std::vector<Override> overrides = d.overrides;
    std::vector<std::string> roots = d.roots;
    Json doc_copy;
    const Json* doc = &d.doc;
    if (!d.animation.keys.empty()) {
        // The file, then the frame's keyed values, then the user's overrides: the command line
        // overrides the scene, its animation included (a --set on an animated path holds it).
        doc_copy = d.text;
        doc = &doc_copy;
        overrides = frame_overrides(d.animation, frame, file);
        overrides.insert(overrides.end(), d.overrides.begin(), d.overrides.end());
        roots.clear();
        for (const Override& o : overrides) roots.push_back(apply_override(doc_copy, o));
    }
    MeshCache own;
    if (d.nff) {
        // The NFF file's polygons: the meshes its `mesh` objects name, found as if read.
        if (!meshes) meshes = &own;
        meshes->insert(d.nff->meshes.begin(), d.nff->meshes.end());
    }
    const NffScene::Direct* direct = d.nff && d.nff->direct ? &*d.nff->direct : nullptr;
    blaming(file, d.nff ? &*d.nff : nullptr, overrides, roots,
            [&] { read_scene(*doc, base_dir, meshes, d.animation, frame, scene, direct); });
    scene.animation = d.animation;
    scene.frame = frame;
    return scene;
}

}  // namespace

SceneDesc parse_scene(std::string_view json_text, const std::string& file,
                      const std::string& base_dir, const std::vector<Override>& overrides,
                      MeshCache* meshes) {
    SceneDesc first;
    {
        const Document d = read_document(json_text, file, base_dir, overrides);
        MeshCache own;
        if (!meshes) meshes = &own;
        first = read_frame(d, file, base_dir, 0, meshes);
        // Every frame is checked now, before any rendering (orbit alone changes nothing
        // checked).
        if (!d.animation.keys.empty()) {
            for (int f = 1; f < d.animation.frames; ++f) read_frame(d, file, base_dir, f, meshes);
        }
    }
    give_back_free_memory();
    return first;
}

SceneDesc parse_scene(std::string_view json_text, const std::string& file,
                      const std::string& base_dir, const std::vector<Override>& overrides) {
    return parse_scene(json_text, file, base_dir, overrides, nullptr);
}

SceneDesc parse_scene_frame(std::string_view json_text, const std::string& file,
                            const std::string& base_dir, const std::vector<Override>& overrides,
                            int frame, MeshCache* meshes) {
    const Document d = read_document(json_text, file, base_dir, overrides);
    const int frames = std::max(d.animation.frames, 1);
    if (frame < 0 || frame >= frames) {
        throw InputError(file + ": no frame " + std::to_string(frame) + " (frames 0 to " +
                         std::to_string(frames - 1) + ")");
    }
    return read_frame(d, file, base_dir, frame, meshes);
}

SceneText read_scene_text(const std::string& source) {
    if (source.rfind("demo:", 0) == 0) {
        const std::string name = source.substr(5);
        const DemoScene* demo = find_demo(name);
        if (!demo) {
            std::string known;
            for (const DemoScene& d : demo_scenes()) {
                known += (known.empty() ? "" : ", ") + std::string("demo:") + std::string(d.name);
            }
            throw InputError(printable(source) + ": no such built-in scene (known: " + known + ")");
        }
        return {std::string(demo->json), source, ""};
    }

    // From disk (a regular file, with a size bound), or under mpirun what rank 0 read.
    std::string reason;
    std::optional<std::string> text = read_text_file(source, reason);
    if (!text) throw InputError(printable(source) + ": cannot read: " + reason);
    return {std::move(*text), source, std::filesystem::path(source).parent_path().string()};
}

SceneDesc load_scene(const std::string& source, const std::vector<Override>& overrides) {
    const SceneText t = read_scene_text(source);
    return parse_scene(t.text, t.label, t.base_dir, overrides);
}

}  // namespace luz
