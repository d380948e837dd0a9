// ObjectDesc: one object of the scene as its JSON keys define it, the list of shape types, and
// each shape's JSON keys (kShapeKeys, read by the loader and written by the writer) and checks.
#pragma once

#include <array>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "math/transform.h"
#include "math/vec3.h"
#include "scene/limits.h"
#include "scene/mesh_data.h"
#include "scene/number_text.h"

namespace luz {

/// Every shape of SPEC §2, in one list: X(name) for each `type` value. The enum, the loader's and
/// writer's key table and the geometry's dispatch are all generated from it.
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

/// How a shape key is written in JSON.
enum class ShapeKeyKind {
    point,      ///< [x, y, z]
    direction,  ///< [x, y, z], not zero-length (normalised where used)
    number,     ///< a number within the key's limit
    flag,       ///< true or false
    vertices,   ///< [[x, y, z], [x, y, z], [x, y, z]]
    obj_file,   ///< required: an OBJ file's path, relative to the scene file
};

/// The ObjectDesc member a key fills (the alternative matches the kind).
using ShapeMember = std::variant<Vec3 ObjectDesc::*, float ObjectDesc::*, bool ObjectDesc::*,
                                 std::array<Vec3, 3> ObjectDesc::*, std::string ObjectDesc::*>;

/// One JSON key of one shape type. `type`, `material` and `transform` are every shape's.
struct ShapeKey {
    ShapeType type;
    std::string_view name;
    ShapeKeyKind kind;
    ShapeMember member;
    Limit limit = kAnyNumber;  ///< numbers only (scene/limits.h)
};

/// Every shape's keys, in the order they are read, written and listed in messages.
inline constexpr ShapeKey kShapeKeys[] = {
    {ShapeType::sphere, "center", ShapeKeyKind::point, &ObjectDesc::center},
    {ShapeType::sphere, "radius", ShapeKeyKind::number, &ObjectDesc::radius, kShapeSize},
    {ShapeType::box, "min", ShapeKeyKind::point, &ObjectDesc::min},
    {ShapeType::box, "max", ShapeKeyKind::point, &ObjectDesc::max},
    {ShapeType::cylinder, "base", ShapeKeyKind::point, &ObjectDesc::base},
    {ShapeType::cylinder, "axis", ShapeKeyKind::direction, &ObjectDesc::axis},
    {ShapeType::cylinder, "radius", ShapeKeyKind::number, &ObjectDesc::radius, kShapeSize},
    {ShapeType::cylinder, "height", ShapeKeyKind::number, &ObjectDesc::height, kShapeSize},
    {ShapeType::cylinder, "caps", ShapeKeyKind::flag, &ObjectDesc::caps},
    {ShapeType::cone, "base", ShapeKeyKind::point, &ObjectDesc::base},
    {ShapeType::cone, "axis", ShapeKeyKind::direction, &ObjectDesc::axis},
    {ShapeType::cone, "radius", ShapeKeyKind::number, &ObjectDesc::radius, kShapeSize},
    {ShapeType::cone, "height", ShapeKeyKind::number, &ObjectDesc::height, kShapeSize},
    {ShapeType::cone, "apex_radius", ShapeKeyKind::number, &ObjectDesc::apex_radius, kApexRadius},
    {ShapeType::cone, "cap", ShapeKeyKind::flag, &ObjectDesc::caps},
    {ShapeType::torus, "center", ShapeKeyKind::point, &ObjectDesc::center},
    {ShapeType::torus, "axis", ShapeKeyKind::direction, &ObjectDesc::axis},
    {ShapeType::torus, "major_radius", ShapeKeyKind::number, &ObjectDesc::major_radius, kShapeSize},
    {ShapeType::torus, "minor_radius", ShapeKeyKind::number, &ObjectDesc::minor_radius, kShapeSize},
    {ShapeType::plane, "point", ShapeKeyKind::point, &ObjectDesc::point},
    {ShapeType::plane, "normal", ShapeKeyKind::direction, &ObjectDesc::normal},
    {ShapeType::triangle, "vertices", ShapeKeyKind::vertices, &ObjectDesc::vertices},
    {ShapeType::mesh, "file", ShapeKeyKind::obj_file, &ObjectDesc::file},
    {ShapeType::mesh, "smooth", ShapeKeyKind::flag, &ObjectDesc::smooth},
};

/// A problem across a shape's keys: the key blamed and what is wrong. `whole_object`: an
/// override of any key of the object is blamed for it (else only one of the key itself).
struct ShapeProblem {
    std::string key;
    std::string what;
    bool whole_object = true;
};

/// True when the triangle has (nearly) zero area: |e1 × e2| ≈ 0 relative to |e1||e2|.
inline bool is_degenerate_triangle(const std::array<Vec3, 3>& p) {
    const double e1[3] = {double(p[1].x) - p[0].x, double(p[1].y) - p[0].y,
                          double(p[1].z) - p[0].z};
    const double e2[3] = {double(p[2].x) - p[0].x, double(p[2].y) - p[0].y,
                          double(p[2].z) - p[0].z};
    const double c[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                         e1[0] * e2[1] - e1[1] * e2[0]};
    const double cross_len = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    const double l1 = std::sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
    const double l2 = std::sqrt(e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2]);
    return !(cross_len > 1e-7 * l1 * l2) || !(cross_len > 0);
}

/// The checks across one shape's keys, made once its keys are read (SPEC §2).
inline std::optional<ShapeProblem> check_shape(const ObjectDesc& o) {
    switch (o.type) {
        case ShapeType::box:
            if (!(o.min.x < o.max.x && o.min.y < o.max.y && o.min.z < o.max.z)) {
                return ShapeProblem{"max", "must be greater than min on every axis, got min " +
                                               format_vec(o.min) + " and max " + format_vec(o.max)};
            }
            break;
        case ShapeType::torus:
            if (!(o.minor_radius < o.major_radius)) {
                return ShapeProblem{"minor_radius", "must be < major_radius (" +
                                                        format_number(o.major_radius) + "), got " +
                                                        format_number(o.minor_radius)};
            }
            break;
        case ShapeType::cone:
            if (!(o.apex_radius < o.radius)) {
                return ShapeProblem{"apex_radius", "must be < radius (" + format_number(o.radius) +
                                                       "), got " + format_number(o.apex_radius)};
            }
            break;
        case ShapeType::triangle:
            if (is_degenerate_triangle(o.vertices)) {
                const auto& p = o.vertices;
                return ShapeProblem{"vertices",
                                    "degenerate triangle (zero area): " + format_vec(p[0]) + ", " +
                                        format_vec(p[1]) + ", " + format_vec(p[2]),
                                    false};
            }
            break;
        default:
            break;
    }
    return std::nullopt;
}

}  // namespace luz
