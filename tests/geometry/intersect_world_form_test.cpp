// The world-space fast path of intersect() (spheres under a similarity, planes) against the
// same equations solved in double.
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

/// The roots in (0, inf) of r with the world form of s, solved in double from the same float
/// parameters (centre, radius; normal, offset), nearest first.
std::vector<double> world_form_reference(const Shape& s, const Ray& r) {
    const double ox = r.origin.x, oy = r.origin.y, oz = r.origin.z;
    const double dx = r.direction.x, dy = r.direction.y, dz = r.direction.z;
    std::vector<double> roots;
    if (s.type == ShapeType::plane) {
        const double nd = s.normal.x * dx + s.normal.y * dy + s.normal.z * dz;
        roots = {(s.offset - (s.normal.x * ox + s.normal.y * oy + s.normal.z * oz)) / nd};
    } else {
        const double px = ox - s.centre.x, py = oy - s.centre.y, pz = oz - s.centre.z;
        const double a = dx * dx + dy * dy + dz * dz, b = px * dx + py * dy + pz * dz;
        const double c = px * px + py * py + pz * pz - double(s.radius) * s.radius;
        const double disc = b * b - a * c;
        if (disc >= 0) roots = {(-b - std::sqrt(disc)) / a, (-b + std::sqrt(disc)) / a};
    }
    std::erase_if(roots, [](double t) { return !(t > 0 && std::isfinite(t)); });
    return roots;
}

// The world-space fast path (Shape::world_form: spheres under a similarity — solved in float
// unless an origin on the surface needs double — and planes) against the same equations in
// double: the same hit or miss, and t within float rounding of the ray (relative to the
// origin's distance from the centre, the radius and t; planes divided by the cosine of the
// incidence), for origins far away, near and on the surface (spawned rays, 1e-4 off either
// side, as the ray tracer spawns them), spheres of radius 0.01 to 1000; the same crossing
// counts.
TEST(Intersect, WorldFormSpheresAndPlanesAgreeWithDoubleSolutions) {
    Rng rng(7);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    auto unit = [&] { return random_direction(rng); };
    int compared = 0, disagreements = 0, counted = 0, count_differs = 0;
    int spawned_disagreements = 0;  // rays from (1e-4 off) the surface: never a wrong answer
    for (float radius : {0.01f, 1.0f, 37.5f, 1000.0f}) {
        for (int object = 0; object < 2; ++object) {
            ObjectDesc o = sphere_desc();
            if (object == 0) {
                o.radius = radius;
                o.transform = rotation(1, 30.0f) * scaling(Vec3{-1.0f});  // a similarity
            } else {
                o.type = ShapeType::plane;
                o.point = Vec3{0.3f, -0.2f, 0.1f} * radius;
                o.normal = {0.2f, 1.0f, -0.4f};
                o.transform = rotation(0, 20.0f) * scaling({1.0f, 2.0f, 0.5f});  // any affine
            }
            const Shape fast = make_shape(o, 0);
            ASSERT_TRUE(fast.world_form);
            Shape slow = fast;
            slow.world_form = false;
            const Vec3 centre = fast.transform.point({0, 0, 0});
            for (int k = 0; k < 6000; ++k) {
                // an origin: far, on the surface (1e-4 off either side) or near
                Vec3 origin = centre + unit() * (radius * (k % 3 == 0 ? 40.0f : 1.5f * u(rng)));
                if (k % 3 == 1) {
                    Hit h;
                    const Ray probe{centre + unit() * (3.0f * radius), unit()};
                    if (!intersect(slow, probe, 0, inf, h)) continue;
                    const SurfacePoint sp = surface_at(slow, probe, h);
                    origin = sp.P + sp.Ng * ((k & 4) ? 1e-4f : -1e-4f);  // kRayEpsilon
                }
                const Ray r{origin, unit()};
                Hit h;
                const bool hit = intersect(fast, r, 0, inf, h);
                const std::vector<double> roots = world_form_reference(fast, r);
                const double ref = roots.empty() ? 0.0 : roots[0];
                ++compared;
                if (hit != !roots.empty()) {
                    spawned_disagreements += k % 3 == 1;
                    ++disagreements;  // tangent rays, at the rounding of the discriminant
                    continue;
                }
                if (hit) {
                    const double scale =
                        object == 0
                            ? std::max({double(length(origin - centre)), double(radius), ref})
                            : std::max(double(length(origin)), ref) /
                                  std::fabs(dot(fast.normal, r.direction));
                    EXPECT_NEAR(h.t, ref, 2e-6 * scale)
                        << "radius " << radius << " object " << object << " ray " << k;
                    const SurfacePoint a = surface_at(fast, r, h), b = surface_at(slow, r, h);
                    EXPECT_GT(dot(a.N, b.N), 0.9999f);
                }
                uint64_t tests = 0;
                ++counted;
                count_differs += count_crossings(fast, r, 0, inf, false, tests) != roots.size();
            }
        }
    }
    EXPECT_GT(compared, 20000);
    EXPECT_LE(disagreements, compared / 10000) << disagreements << " of " << compared;
    EXPECT_EQ(spawned_disagreements, 0);
    EXPECT_LE(count_differs, counted / 1000) << count_differs << " of " << counted;
    // not a similarity: an ellipsoid stays in object space
    ObjectDesc e = sphere_desc();
    e.transform = scaling({1.0f, 2.0f, 1.0f});
    EXPECT_FALSE(make_shape(e, 0).world_form);
}

}  // namespace
}  // namespace luz::test
