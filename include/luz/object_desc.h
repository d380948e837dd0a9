// ObjectDesc: one object of the scene as its JSON keys define it, and the list of shape types
// (docs/SCENES.md#scene-files). The keys' table and checks are the loader's (scene/shape_desc.h).
#pragma once

#include <array>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "luz/affine.h"
#include "luz/vec3.h"

namespace luz {

struct MeshData;  // an OBJ file's triangles as read (scene/mesh_data.h)

/// Every shape of docs/SCENES.md#scene-files, in one list: X(name) for each `type` value. The enum,
/// the loader's and writer's key table and the geometry's dispatch are all generated from it.
#define LUZ_SHAPES(X) X(sphere) X(box) X(cylinder) X(cone) X(torus) X(plane) X(triangle) X(mesh)

enum class ShapeType {
#define LUZ_SHAPE_ENUM(name) name,
    LUZ_SHAPES(LUZ_SHAPE_ENUM)
#undef LUZ_SHAPE_ENUM
};

/// The `type` value of each ShapeType, in LUZ_SHAPES order.
inline constexpr std::string_view kShapeNames[] = {
#define LUZ_SHAPE_NAME(name) #name,
    LUZ_SHAPES(LUZ_SHAPE_NAME)
#undef LUZ_SHAPE_NAME
};

/// The `type` value of `t` ("sphere", …).
constexpr std::string_view shape_name(ShapeType t) { return kShapeNames[static_cast<int>(t)]; }

/// One object as its keys define it (only the fields of its type are meaningful).
struct ObjectDesc {
    ShapeType type = ShapeType::sphere;
    int material = 0;  ///< index into SceneDesc::materials
    std::string path;  ///< key path, e.g. "objects.3", for messages
    Affine transform;  ///< the `transform` key: T·Rz·Ry·Rx·S
    /// The `transform` keys as given (scale, rotate in degrees, translate), for the scene writer.
    Vec3 scale{1.0f}, rotate{0.0f}, translate{0.0f};
    // sphere, torus
    Vec3 center{0, 0, 0};
    float radius = 1.0f;  // sphere, cylinder, cone
    // box
    Vec3 min{-0.5f, -0.5f, -0.5f}, max{0.5f, 0.5f, 0.5f};
    // cylinder, cone
    Vec3 base{0, 0, 0};
    Vec3 axis{0, 1, 0};
    float height = 1.0f;
    float apex_radius = 0.0f;  ///< cone: the radius at base + axis·height (0: a full cone)
    bool caps = true;          ///< cylinder `caps`, cone `cap`
    // torus
    float major_radius = 1.0f, minor_radius = 0.25f;
    // plane
    Vec3 point{0, 0, 0};
    Vec3 normal{0, 1, 0};
    // triangle
    std::array<Vec3, 3> vertices{Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{0, 1, 0}};
    // mesh
    std::string file;
    bool smooth = true;
    /// The loaded OBJ file (shared: objects naming the same file share it).
    std::shared_ptr<const MeshData> mesh;
    /// MeshData::materials index → index into SceneDesc::materials; empty when the object
    /// names a material (then every triangle has `material`). Faces without an MTL material
    /// have `material` (the default material unless the object names one).
    std::vector<int> mesh_materials;

    /// Same keys, same values (meshes: the same loaded file): no rebuild needed.
    bool operator==(const ObjectDesc&) const = default;
};

}  // namespace luz
