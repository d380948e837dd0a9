// intersect() on grazing rays: rays tangent to every shape (sides, edges, rims, generators),
// moved a little off or into the surface, never give NaN, and hit or miss where they should.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "geometry/shapes.h"
#include "intersect_fixtures.h"

namespace luz::test {
namespace {

struct Tangent {
    std::string name;
    Vec3 o, d;    ///< object space, touching the surface at o + t_touch·d
    Vec3 offset;  ///< unit direction in which the ray is moved away from the surface
    float t_touch;
};

std::vector<Tangent> tangent_rays(const Shape& s) {
    const float m = s.minor;
    switch (s.type) {
        case ShapeType::sphere:
            return {{"sphere", {1, 0, -3}, {0, 0, 1}, {1, 0, 0}, 3},
                    {"sphere_oblique", Vec3{0.6f, 0.8f, 0} - normalize(Vec3{-0.8f, 0.6f, 0.5f}) * 2,
                     normalize(Vec3{-0.8f, 0.6f, 0.5f}), Vec3{0.6f, 0.8f, 0}, 2}};
        case ShapeType::box: {
            const Vec3 mid = (s.lo + s.hi) * 0.5f;
            return {
                {"box_face", {s.hi.x, mid.y, s.lo.z - 2}, {0, 0, 1}, {1, 0, 0}, 2},
                {"box_edge", {s.hi.x, s.hi.y, s.lo.z - 2}, {0, 0, 1}, normalize(Vec3{1, 1, 0}), 2}};
        }
        case ShapeType::cylinder:
            return {{"cyl_side", {1, -3, 0.5f}, {0, 1, 0}, {1, 0, 0}, 3},
                    {"cyl_along_side", {1, 0, -2}, {0, 0, 1}, {1, 0, 0}, 2},
                    {"cyl_rim", {-3, 0, 1}, {1, 0, 0}, {0, 0, 1}, 2}};
        case ShapeType::cone: {
            // along a generator x = 1 − k·z (the quadratic's a = 0) and across the side;
            // k = 1 − apex is the slope
            const float k = 1 - s.apex;
            return {{"cone_generator", {1 + 2 * k, 0, -2}, {-k, 0, 1}, normalize(Vec3{1, 0, k}), 2},
                    {"cone_side", {-3, 1 - 0.5f * k, 0.5f}, {1, 0, 0}, {0, 1, 0}, 3}};
        }
        case ShapeType::torus:
            return {{"torus_top", {-3, 0, m}, {1, 0, 0}, {0, 0, 1}, 2},
                    {"torus_outer", {1 + m, -3, 0}, {0, 1, 0}, {1, 0, 0}, 3},
                    {"torus_inner", {1 - m, 0, -3}, {0, 0, 1}, {-1, 0, 0}, 3},
                    {"torus_oblique",
                     Vec3{0, -1 - m, 0} - Vec3{1, 0, 1} * 3,
                     normalize(Vec3{1, 0, 1}),
                     {0, -1, 0},
                     3 * std::sqrt(2.0f)}};
        case ShapeType::plane:
            return {{"plane", {-3, 0, 0}, {1, 0, 0}, {0, 0, 1}, 3}};
        case ShapeType::triangle: {
            const Vec3* v = s.vertices;
            const Vec3 n = normalize(cross(v[1] - v[0], v[2] - v[0]));
            const Vec3 c = (v[0] + v[1] + v[2]) / 3.0f, e = v[1] - v[0];
            return {{"triangle_edge_on", c - e, e, n, 1}};
        }
        case ShapeType::mesh:
            break;
    }
    return {};
}

TEST(Intersect, GrazingRaysNeverGiveNaN) {
    for (const NamedObject& obj : shapes_under_test()) {
        for (const NamedTransform& tr : user_transforms()) {
            const Shape s = make_shape(with_transform(obj.desc, tr.affine), 0);
            for (const Tangent& tg : tangent_rays(s)) {
                SCOPED_TRACE(obj.name + " / " + tr.name + " / " + tg.name);
                for (const float delta :
                     {-1e-3f, -1e-4f, -1e-6f, -1e-7f, 0.0f, 1e-7f, 1e-6f, 1e-4f, 1e-3f}) {
                    const Ray r = world_ray(s, tg.o + tg.offset * delta, tg.d);
                    Hit h;
                    const bool hit = intersect(s, r, 0, inf, h);
                    const bool near_touch = hit && std::fabs(h.t - tg.t_touch) < 0.1f;
                    if (hit) {
                        EXPECT_TRUE(std::isfinite(h.t) && h.t > 0) << delta;
                        EXPECT_TRUE(std::isfinite(h.u) && std::isfinite(h.v)) << delta;
                        const SurfacePoint sp = surface_at(s, r, h);
                        EXPECT_TRUE(is_finite(sp.P)) << delta;
                        EXPECT_TRUE(unit(sp.N) && unit(sp.Ng)) << delta;
                        // (a nearly parallel ray may meet the plane far away: float tolerance)
                        EXPECT_NEAR(world_sdf(s, sp.P), 0.0, 1e-4 + 1e-6 * length(sp.P))
                            << delta << " t " << h.t;
                    }
                    // clearly off the surface: no hit there; clearly into it: a hit there
                    // (open shapes and the plane can only be missed or hit elsewhere)
                    if (delta >= 1e-4f) {
                        EXPECT_FALSE(near_touch) << delta;
                    }
                    if (delta <= -1e-4f && obj.closed) {
                        EXPECT_TRUE(near_touch) << delta;
                    }
                }
            }
        }
    }
}

}  // namespace
}  // namespace luz::test
