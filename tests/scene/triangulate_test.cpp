// Tests of OBJ face triangulation (scene/triangulate.h): convex and concave polygons covered
// exactly in their own winding, in any plane; corners without area dropped; a million corners
// in about a second.
#include "scene/triangulate.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>

#include "sanitizer.h"

namespace luz {
namespace {

using Triangles = std::vector<std::array<uint32_t, 3>>;

Triangles cut(const std::vector<Vec3>& corners) {
    Triangles t;
    triangulate_polygon(corners, t);
    return t;
}

/// Newell's normal of a polygon: its direction the winding's, its length twice the area.
std::array<double, 3> newell(const std::vector<Vec3>& p) {
    std::array<double, 3> n{0, 0, 0};
    for (size_t i = 0; i < p.size(); ++i) {
        const Vec3& a = p[i];
        const Vec3& b = p[(i + 1) % p.size()];
        n[0] += (double(a.y) - b.y) * (double(a.z) + b.z);
        n[1] += (double(a.z) - b.z) * (double(a.x) + b.x);
        n[2] += (double(a.x) - b.x) * (double(a.y) + b.y);
    }
    return n;
}

/// Checks that the triangles cover the polygon once: each turns the polygon's way (its normal
/// along the polygon's), and their areas add up to the polygon's.
void expect_exact_cover(const std::vector<Vec3>& p, const Triangles& t, double tolerance = 1e-6) {
    const std::array<double, 3> n = newell(p);
    const double area = 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    double sum = 0;
    for (const auto& tri : t) {
        for (uint32_t k : tri) ASSERT_LT(k, p.size());
        const std::array<double, 3> m = newell({p[tri[0]], p[tri[1]], p[tri[2]]});
        const double along = (m[0] * n[0] + m[1] * n[1] + m[2] * n[2]) / (2 * area);
        EXPECT_GE(along, -1e-9) << "a triangle turns against the polygon";
        sum += 0.5 * along;
    }
    EXPECT_NEAR(sum, area, tolerance * area);
}

/// A regular polygon of `n` corners, or a star when `inner` < 1 (every other corner at radius
/// `inner`), counter-clockwise in the xy plane.
std::vector<Vec3> star(size_t n, double inner = 1) {
    std::vector<Vec3> p(n);
    for (size_t i = 0; i < n; ++i) {
        const double a = 2 * M_PI * double(i) / double(n), r = i % 2 ? inner : 1;
        p[i] = Vec3(float(r * std::cos(a)), float(r * std::sin(a)), 0);
    }
    return p;
}

TEST(Triangulate, TrianglesAndQuadsAsTinyobjloaderCutsThem) {
    EXPECT_EQ(cut({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}), (Triangles{{0, 1, 2}}));
    // the shorter diagonal: 1–3 here
    EXPECT_EQ(cut({{0, 0, 0}, {3, 0, 0}, {3, 1, 0}, {2, 1, 0}}), (Triangles{{0, 1, 3}, {1, 2, 3}}));
    EXPECT_EQ(cut({{0, 0, 0}, {3, 0, 0}, {1, 1, 0}, {0, 1, 0}}), (Triangles{{0, 1, 2}, {0, 2, 3}}));
}

TEST(Triangulate, ConvexPolygonsGiveNMinusTwoTriangles) {
    for (size_t n : {5, 6, 7, 64, 1000}) {
        const std::vector<Vec3> p = star(n);
        const Triangles t = cut(p);
        EXPECT_EQ(t.size(), n - 2);
        expect_exact_cover(p, t);
    }
}

TEST(Triangulate, ConcavePolygonsAreCoveredExactly) {
    // an L, a comb, stars, and a gear of 144 corners (the Standard Procedural Databases' gears)
    const std::vector<Vec3> l = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}};
    expect_exact_cover(l, cut(l));
    EXPECT_EQ(cut(l).size(), 4u);
    std::vector<Vec3> comb = {{0, 0, 0}, {20, 0, 0}};
    for (int k = 9; k >= 0; --k) {
        comb.push_back(Vec3(2.0f * k + 2, 5, 0));
        comb.push_back(Vec3(2.0f * k + 1, 1, 0));
        comb.push_back(Vec3(2.0f * k, 5, 0));
    }
    expect_exact_cover(comb, cut(comb));
    expect_exact_cover(star(10, 0.4), cut(star(10, 0.4)));
    expect_exact_cover(star(1000, 0.9), cut(star(1000, 0.9)));
    std::vector<Vec3> gear;
    for (int tooth = 0; tooth < 36; ++tooth) {
        for (int k = 0; k < 4; ++k) {
            const double a = 2 * M_PI * (tooth * 4 + k) / 144.0, r = k < 2 ? 1.0 : 0.8;
            gear.push_back(Vec3(float(r * std::cos(a)), float(r * std::sin(a)), 0));
        }
    }
    const Triangles t = cut(gear);
    EXPECT_EQ(t.size(), 142u);
    expect_exact_cover(gear, t);
}

TEST(Triangulate, AnyPlaneAndEitherWinding) {
    std::vector<Vec3> p = star(12, 0.5);
    for (Vec3& v : p) v = Vec3(v.z + 3, v.x, v.y);  // in the plane x = 3
    expect_exact_cover(p, cut(p));
    std::reverse(p.begin(), p.end());  // clockwise
    expect_exact_cover(p, cut(p));
    for (Vec3& v : p) v = Vec3(v.x + 0.3f * v.y, v.y, v.z - 0.5f * v.y);  // a tilted plane
    expect_exact_cover(p, cut(p), 1e-5);
}

TEST(Triangulate, CornersWithoutAreaAreDropped) {
    // a square with corners repeated and in line on its edges: still two triangles' worth
    const std::vector<Vec3> p = {{0, 0, 0}, {0.5f, 0, 0}, {1, 0, 0}, {1, 0, 0},
                                 {1, 1, 0}, {0.5f, 1, 0}, {0, 1, 0}};
    const Triangles t = cut(p);
    expect_exact_cover(p, t);
    for (const auto& tri : t) {
        const std::array<double, 3> m = newell({p[tri[0]], p[tri[1]], p[tri[2]]});
        EXPECT_GT(m[2], 0) << "a triangle without area";
    }
    // no area at all: nothing
    EXPECT_TRUE(cut(std::vector<Vec3>(7, Vec3(1, 2, 3))).empty());
    EXPECT_TRUE(cut({{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {3, 3, 3}, {1, 1, 1}}).empty());
}

TEST(Triangulate, APolygonCrossingItselfStillEnds) {
    // a bow tie of 6 corners and a random scribble: some triangles, no hang
    const std::vector<Vec3> bow = {{0, 0, 0}, {1, 1, 0}, {2, 0, 0},
                                   {2, 2, 0}, {1, 1, 0}, {0, 2, 0}};
    EXPECT_FALSE(cut(bow).empty());
    std::vector<Vec3> scribble;
    uint32_t seed = 12345;
    for (int i = 0; i < 2000; ++i) {
        seed = seed * 1664525u + 1013904223u;
        scribble.push_back(Vec3(float(seed % 1000), float((seed >> 10) % 1000), 0));
    }
    for (const auto& t : cut(scribble)) {
        for (uint32_t k : t) ASSERT_LT(k, scribble.size());
    }
}

TEST(Triangulate, AMillionCornersInAboutASecond) {
    LUZ_SPEED_TEST();
    // ear clipping without the grid is quadratic: minutes for each of these. Only cut() is
    // timed (the test's own polygons and checks are compiled without optimisation).
    using Clock = std::chrono::steady_clock;
    double seconds = 0;
    const auto timed_cut = [&](const std::vector<Vec3>& polygon) {
        const auto start = Clock::now();
        auto triangles = cut(polygon);
        seconds += std::chrono::duration<double>(Clock::now() - start).count();
        return triangles;
    };
    // (in float, many neighbouring corners of the circle are in line: dropped)
    const std::vector<Vec3> circle = star(1000000);
    expect_exact_cover(circle, timed_cut(circle), 1e-4);
    const std::vector<Vec3> spiky = star(1000000, 0.999);  // half the corners reflex
    expect_exact_cover(spiky, timed_cut(spiky), 1e-4);
    EXPECT_TRUE(timed_cut(std::vector<Vec3>(200000, Vec3(1, 1, 1))).empty());
    // Linear: about a second; quadratic would take minutes.
    EXPECT_LT(seconds, 5.0);
    RecordProperty("seconds", std::to_string(seconds));
}

}  // namespace
}  // namespace luz
