// Truncated cones (docs/SCENES.md#scene-files: a cone's apex_radius) hit by hand-computed rays: the
// slanted side and its normal, the top disc, the inside wall, and rays through the holes of an open
// frustum.
#include <gtest/gtest.h>

#include <limits>

#include "geometry/shapes.h"

namespace luz {
namespace {

constexpr float inf = std::numeric_limits<float>::infinity();

void expect_near(const Vec3& a, const Vec3& b, float tol) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

TEST(Frustum, SideTopDiscAndHole) {
    // radius 1 at y = 0, 0.5 at y = 2: radius 1 − y/4 (the full cone's apex would be at y = 4)
    ObjectDesc o;
    o.type = ShapeType::cone;
    o.base = {0, 0, 0};
    o.axis = {0, 1, 0};
    o.radius = 1.0f;
    o.apex_radius = 0.5f;
    o.height = 2.0f;
    o.caps = true;
    const Shape s = make_shape(o, 0);
    Hit h;
    // the slanted side at height 1 (radius 0.75); outward normal ∝ (height, r − r′) = (2, 0.5)
    const Ray side{{5, 1, 0}, {-1, 0, 0}};
    ASSERT_TRUE(intersect(s, side, 0, inf, h));
    EXPECT_NEAR(h.t, 4.25f, 1e-5f);
    EXPECT_EQ(h.part, part_side);
    expect_near(surface_at(s, side, h).Ng, normalize(Vec3{4, 1, 0}), 1e-6f);
    // the top disc (radius 0.5 at y = 2) from above
    const Ray top{{0.3f, 5, 0.2f}, {0, -1, 0}};
    ASSERT_TRUE(intersect(s, top, 0, inf, h));
    EXPECT_NEAR(h.t, 3.0f, 1e-5f);
    EXPECT_EQ(h.part, part_cap1);
    expect_near(surface_at(s, top, h).Ng, {0, 1, 0}, 1e-6f);
    // beside the top disc (0.6 > 0.5): onto the side where the radius is 0.6, y = 1.6
    const Ray beside{{0.6f, 5, 0}, {0, -1, 0}};
    ASSERT_TRUE(intersect(s, beside, 0, inf, h));
    EXPECT_NEAR(h.t, 3.4f, 1e-5f);
    EXPECT_EQ(h.part, part_side);
    // the base disc from below
    const Ray up{{0.2f, -5, 0}, {0, 1, 0}};
    ASSERT_TRUE(intersect(s, up, 0, inf, h));
    EXPECT_NEAR(h.t, 5.0f, 1e-5f);
    EXPECT_EQ(h.part, part_cap0);
    expect_near(surface_at(s, up, h).Ng, {0, -1, 0}, 1e-6f);
    // nothing between the top disc and where the apex would be, nor beyond it
    EXPECT_FALSE(intersect(s, Ray{{5, 3, 0}, {-1, 0, 0}}, 0, inf, h));
    EXPECT_FALSE(intersect(s, Ray{{5, 5, 0}, {-1, 0, 0}}, 0, inf, h));
    // open: down the axis through both holes, and up through them
    o.caps = false;
    const Shape open = make_shape(o, 0);
    EXPECT_FALSE(intersect(open, top, 0, inf, h));
    EXPECT_FALSE(intersect(open, up, 0, inf, h));
    // the inside wall seen through the top hole: the outward normal, facing away from the ray
    ASSERT_TRUE(intersect(open, beside, 0, inf, h));
    EXPECT_NEAR(h.t, 3.4f, 1e-5f);
    const SurfacePoint sp = surface_at(open, beside, h);
    expect_near(sp.Ng, normalize(Vec3{4, 1, 0}), 1e-6f);
}

}  // namespace
}  // namespace luz
