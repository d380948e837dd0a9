// NFF scenes (docs/SCENES.md#nff): Eric Haines' Neutral File Format read into the JSON document of
// the same scene, its polygons as in-memory meshes, and the line each key path came from.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "luz/object_desc.h"
#include "scene/json_text.h"
#include "scene/mesh_data.h"
#include "scene/nff_shapes.h"  // NffShape, NffNotDirect

namespace luz::loader {

/// True when a scene named `label` is read as NFF: its name ends in ".nff" (any case).
bool is_nff_file(std::string_view label);

/// An NFF file as the loader reads a JSON scene.
struct NffScene {
    Json doc;          ///< the scene's document: image, camera, render, lights, materials…
    MeshCache meshes;  ///< the meshes its `mesh` objects name, keyed as MeshFiles finds them
    std::unordered_map<std::string, std::size_t> lines;  ///< key path → its line in the file
    std::vector<std::size_t> object_lines;  ///< the line of key path "objects.N", for each N

    /// Read `direct` (read_nff()): its spheres, cylinders and cones as statements, already
    /// checked as the JSON reader checks their objects (shape_object() gives each one's
    /// ObjectDesc); `doc`'s objects are then its meshes alone.
    struct Direct {
        std::vector<NffShape> objects;       ///< 56 bytes each, the ObjectDesc 352
        std::vector<std::string> materials;  ///< each one's material name ("": none)
        /// Per object of the file, in order: k ≥ 0 is objects[k], −1 − m the doc's objects[m].
        std::vector<std::int64_t> order;
    };
    std::optional<Direct> direct;

    /// The line of `path` or of the nearest key path above it that came from a line; 0: none.
    std::size_t line_of(std::string_view path) const;
};

/// Reads NFF text. `file` names it in messages; `base_dir` is its folder (mesh objects name
/// their polygons as `FILE-NAME#fK`, resolved against it as a mesh file is). Throws InputError
/// "FILE:LINE: …" for a malformed line, a wrong count of numbers, a non-finite number, an
/// unknown keyword, a polygon of fewer than 3 vertices, `v` after another statement (only `b`
/// and comments may come before it) or missing, or a file ending inside a statement.
/// With `direct`, spheres, cylinders and cones skip the document (NffScene::direct): the same
/// objects, read in a fraction of the time; throws NffNotDirect where one is out of range.
NffScene read_nff(std::string_view text, const std::string& file, const std::string& base_dir,
                  bool direct = false);

}  // namespace luz::loader
