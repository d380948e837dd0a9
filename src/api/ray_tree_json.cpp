// Ray tree → JSON.
#include <cmath>
#include <nlohmann/json.hpp>

#include "luz/inspect.h"

namespace luz {

namespace {

using Json = nlohmann::ordered_json;

Json rgb(const Rgb& c) { return Json::array({c.x, c.y, c.z}); }

const char* kind_name(RayKind k) {
    switch (k) {
        case RayKind::primary:
            return "primary";
        case RayKind::reflection:
            return "reflection";
        case RayKind::refraction:
            return "refraction";
    }
    return "?";
}

}  // namespace

std::string object_label(const SceneDesc& desc, int object) {
    if (object < 0 || object >= static_cast<int>(desc.objects.size())) return "none";
    return "objects." + std::to_string(object) + " (" +
           std::string(shape_name(desc.objects[object].type)) + ")";
}

std::string material_label(const SceneDesc& desc, int material) {
    if (material < 0 || material >= static_cast<int>(desc.materials.size())) return "none";
    return desc.materials[material].name;
}

std::string ray_tree_json(const RayTree& tree, const SceneDesc& desc, int x, int y,
                          const Rgb& pixel) {
    Json j;
    j["pixel"] = {x, y};
    j["pixel_value"] = rgb(pixel);
    j["pipeline"] = desc.render.pipeline == Pipeline::zbuffer   ? "zbuffer"
                    : desc.render.pipeline == Pipeline::raycast ? "raycast"
                                                                : "raytrace";
    j["traced_as_raycast"] = tree.raycast_for_zbuffer;
    // An exploding tree is recorded up to kRayTreeMaxNodes nodes; its colours are still exact.
    j["truncated"] = tree.truncated;
    j["max_nodes"] = kRayTreeMaxNodes;
    j["colour"] = tree.nodes.empty() ? rgb(pixel) : rgb(tree.nodes[0].colour);
    Json nodes = Json::array();
    for (const RayTreeNode& n : tree.nodes) {
        Json o;
        o["kind"] = kind_name(n.kind);
        o["depth"] = n.depth;
        o["parent"] = n.parent;
        o["origin"] = rgb(n.origin);
        o["direction"] = rgb(n.direction);
        o["hit"] = n.hit == RayHit::object  ? "object"
                   : n.hit == RayHit::light ? "light"
                                            : "background";
        if (std::isinf(n.t)) {
            o["t"] = nullptr;
        } else {
            o["t"] = n.t;
        }
        if (n.hit == RayHit::light) o["light"] = n.light;
        if (n.hit == RayHit::object) {
            o["object"] = n.object;
            o["object_label"] = object_label(desc, n.object);
            o["material"] = material_label(desc, n.material);
            o["point"] = rgb(n.P);
            o["normal"] = rgb(n.N);
            o["flipped"] = n.flipped;
            o["ambient"] = rgb(n.ambient);
            Json lights = Json::array();
            for (const LightTerm& l : n.lights) {
                lights.push_back({{"visibility", l.visibility},
                                  {"distance", l.distance},
                                  {"cos_theta", l.cos_theta},
                                  {"cos_alpha", l.cos_alpha},
                                  {"diffuse", rgb(l.diffuse)},
                                  {"specular", rgb(l.specular)}});
            }
            o["lights"] = lights;
            o["local"] = rgb(n.local);
            o["total_internal_reflection"] = n.total_internal_reflection;
        }
        o["reflection_child"] = n.reflection_child;
        o["refraction_child"] = n.refraction_child;
        if (n.parent >= 0) {
            o["returned"] = rgb(n.returned);
            o["A"] = n.A;
            o["coefficient"] = n.coefficient;
            o["contribution"] = rgb(n.contribution);
        }
        o["colour"] = rgb(n.colour);
        nodes.push_back(o);
    }
    j["nodes"] = nodes;
    return j.dump(2) + "\n";
}

}  // namespace luz
