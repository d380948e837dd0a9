// The shape functions called once per shape or per hit, dispatched by visit_shape() (shapes.h):
// make_shape, bounds, surface_at, tessellate, analytic_area.
#include "geometry/shapes.h"

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

double analytic_area(const Shape& s) {
    return visit_shape(s.type, [&](auto shape) { return decltype(shape)::area(s); });
}

}  // namespace luz
