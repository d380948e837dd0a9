// NFF's spheres, cylinders and cones as the document's objects, or read directly into the
// objects the loader would make of them (nff_shapes.h).
#include "scene/nff_shapes.h"

#include <cmath>

#include "scene/limits.h"
#include "scene/shape_desc.h"

namespace luz::loader {

namespace {

/// x as the loader reads a number within `limit` (read_float()), or NffNotDirect.
float number(double x, const Limit& limit) {
    const float f = static_cast<float>(x);
    if (!std::isfinite(x) || !std::isfinite(f) || !limit.contains(x) || !limit.contains(f))
        throw NffNotDirect{};
    return f;
}

/// An axis as the loader reads a direction (read_direction()), or NffNotDirect.
Vec3 direction(const double a[3]) {
    const Vec3 v(number(a[0], kAnyNumber), number(a[1], kAnyNumber), number(a[2], kAnyNumber));
    const float len = length(v);
    if (v == Vec3(0.0f) || !(len > 0) || !std::isfinite(len) || !is_finite(v / len))
        throw NffNotDirect{};
    return v;
}

}  // namespace

Json shape_json(const NffShape& s) {
    const Json axis = json_array3(s.axis[0], s.axis[1], s.axis[2]);
    switch (s.type) {
        case ShapeType::cylinder:
            return json_object(std::pair{"type", Json("cylinder")},
                               std::pair{"base", json_vec(s.point)}, std::pair{"axis", axis},
                               std::pair{"radius", Json(s.radius)},
                               std::pair{"height", Json(s.height)}, std::pair{"caps", Json(false)});
        case ShapeType::cone:
            return json_object(std::pair{"type", Json("cone")},
                               std::pair{"base", json_vec(s.point)}, std::pair{"axis", axis},
                               std::pair{"radius", Json(s.radius)},
                               std::pair{"apex_radius", Json(s.apex_radius)},
                               std::pair{"height", Json(s.height)}, std::pair{"cap", Json(false)});
        default:
            return json_object(std::pair{"type", Json("sphere")},
                               std::pair{"center", json_vec(s.point)},
                               std::pair{"radius", Json(s.radius)});
    }
}

ObjectDesc shape_object(const NffShape& s) {
    ObjectDesc o;
    o.type = s.type;
    o.radius = number(s.radius, kShapeSize);
    if (s.type == ShapeType::sphere) {
        o.center = s.point;
        return o;
    }
    o.base = s.point;
    o.axis = direction(s.axis);
    o.height = number(s.height, kShapeSize);
    o.caps = false;
    if (s.type == ShapeType::cone) o.apex_radius = number(s.apex_radius, kApexRadius);
    if (check_shape(o)) throw NffNotDirect{};
    return o;
}

}  // namespace luz::loader
