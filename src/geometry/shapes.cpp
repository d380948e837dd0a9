// The shape functions called once per shape or per hit, dispatched by visit_shape() (shapes.h):
// make_shape, bounds, surface_at, tessellate, analytic_area; and the triangle count of a
// tessellation.
#include "geometry/shapes.h"

#include <algorithm>

#include "geometry/tessellate.h"

namespace luz {

Shape make_shape(const ObjectDesc& o, int object_index) {
    Shape s;
    s.type = o.type;
    s.material = o.material;
    s.object = object_index;
    visit_shape(o.type, [&](auto shape) {
        s.bounded = decltype(shape)::bounded;
        decltype(shape)::place(o, s);
    });
    return s;
}

Bounds3 bounds(const Shape& s) {
    return visit_shape(s.type, [&](auto shape) { return decltype(shape)::bounds(s); });
}

SurfacePoint surface_at(const Shape& s, const Ray& r, const Hit& hit) {
    return visit_shape(s.type, [&](auto shape) { return decltype(shape)::surface_at(s, r, hit); });
}

void tessellate(const Shape& s, int level, TriangleMesh& out) {
    level = std::max(3, level);
    visit_shape(s.type, [&](auto shape) { decltype(shape)::tessellate(s, level, out); });
}

uint64_t tessellated_triangle_count(const ObjectDesc& o, int level) {
    const uint64_t n = static_cast<uint64_t>(std::max(3, level));
    const uint64_t caps = o.caps ? 1 : 0;
    switch (o.type) {
        case ShapeType::sphere:
            return 2 * n * (std::max<uint64_t>(2, n / 2) - 1);
        case ShapeType::torus:
            return 2 * n * std::max<uint64_t>(3, n / 2);
        case ShapeType::cylinder:
            return 2 * n + 2 * caps * n;
        case ShapeType::cone:
            return o.apex_radius > 0 ? 2 * n + 2 * caps * n : n + caps * n;
        case ShapeType::box:
            return 12;
        case ShapeType::triangle:
            return 1;
        case ShapeType::mesh:
            return o.mesh ? o.mesh->triangle_count() : 0;
        case ShapeType::plane:
            break;
    }
    return 0;
}

double analytic_area(const Shape& s) {
    return visit_shape(s.type, [&](auto shape) { return decltype(shape)::area(s); });
}

}  // namespace luz
