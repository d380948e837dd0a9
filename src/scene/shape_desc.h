// Each shape's JSON keys (kShapeKeys, read by the loader and written by the writer) and checks.
#pragma once

#include <array>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "luz/object_desc.h"
#include "math/transform.h"
#include "scene/limits.h"
#include "scene/mesh_data.h"
#include "scene/number_text.h"

namespace luz {

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

/// The checks across one shape's keys, made once its keys are read (docs/SCENES.md#scene-files).
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
