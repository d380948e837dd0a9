// Shared helpers of the intersect() tests: world rays from object-space ones, signed distances
// to every shape, surface samples with their normals, the shapes under test and checks on normals.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "geometry/shapes.h"
#include "geometry_fixtures.h"

namespace luz::test {

inline constexpr float inf = std::numeric_limits<float>::infinity();
inline constexpr double pi = std::numbers::pi;

/// The world ray whose object-space image is (o, d): t is the same along both.
inline Ray world_ray(const Shape& s, const Vec3& o, const Vec3& d) {
    return {s.transform.point(o), s.transform.vector(d)};
}

/// Signed distance-like function of the shape in object space (double): > 0 outside, < 0
/// inside, 0 on the surface, |value| ≈ the distance near the surface (exact for most shapes).
inline double object_sdf(const Shape& s, const Vec3& pf) {
    const double x = pf.x, y = pf.y, z = pf.z;
    const double r = std::sqrt(x * x + y * y);
    switch (s.type) {
        case ShapeType::sphere:
            return std::sqrt(x * x + y * y + z * z) - 1.0;
        case ShapeType::box: {
            double q[3], out = 0, in = -1e30;
            for (int k = 0; k < 3; ++k) {
                const double c = 0.5 * (double(s.lo[k]) + s.hi[k]);
                const double h = 0.5 * (double(s.hi[k]) - s.lo[k]);
                q[k] = std::fabs(pf[k] - c) - h;
                out += std::max(q[k], 0.0) * std::max(q[k], 0.0);
                in = std::max(in, q[k]);
            }
            return std::sqrt(out) + std::min(in, 0.0);
        }
        case ShapeType::cylinder: {
            const double dr = r - 1.0;
            if (!s.caps) return dr;
            const double dz = std::max(-z, z - 1.0);
            return std::hypot(std::max(dr, 0.0), std::max(dz, 0.0)) +
                   std::min(std::max(dr, dz), 0.0);
        }
        case ShapeType::cone: {
            const double m = 1.0 - s.apex;  // the slope: radius 1 − m·z
            const double side = (r - (1.0 - m * z)) / std::sqrt(1.0 + m * m);
            if (!s.caps) return side;
            return s.apex > 0 ? std::max({side, -z, z - 1.0}) : std::max(side, -z);
        }
        case ShapeType::torus:
            return std::hypot(r - 1.0, z) - s.minor;
        case ShapeType::plane:
            return z;
        case ShapeType::triangle: {
            const Vec3 n =
                normalize(cross(s.vertices[1] - s.vertices[0], s.vertices[2] - s.vertices[0]));
            return dot(pf - s.vertices[0], n);
        }
        case ShapeType::mesh:
            break;
    }
    return 0;
}

inline double world_sdf(const Shape& s, const Vec3& P) {
    return object_sdf(s, s.transform.object_from_world.point(P));
}

/// A point of the surface (object space) away from edges, with its outward object normal.
struct SurfaceSample {
    Vec3 p, n;
};

inline SurfaceSample sample_surface(const Shape& s, std::mt19937& rng) {
    std::uniform_real_distribution<float> U(0, 1);
    const float phi = 2 * float(pi) * U(rng);
    const float c = std::cos(phi), sn = std::sin(phi);
    switch (s.type) {
        case ShapeType::sphere: {
            const float z = 2 * U(rng) - 1, rr = std::sqrt(1 - z * z);
            const Vec3 p{rr * c, rr * sn, z};
            return {p, p};
        }
        case ShapeType::box: {
            const int face = int(U(rng) * 6) % 6, k = face / 2;
            Vec3 p, n{0.0f};
            for (int i = 0; i < 3; ++i)
                p[i] = s.lo[i] + (0.1f + 0.8f * U(rng)) * (s.hi[i] - s.lo[i]);
            p[k] = (face & 1) ? s.hi[k] : s.lo[k];
            n[k] = (face & 1) ? 1.0f : -1.0f;
            return {p, n};
        }
        case ShapeType::cylinder:
        case ShapeType::cone: {
            const bool cone = s.type == ShapeType::cone;
            const int caps = s.caps ? (cone && s.apex == 0 ? 1 : 2) : 0;
            const int pick = int(U(rng) * (2 + caps));  // the side twice as often
            if (pick >= 2) {
                const float z = (pick == 2) ? 0.0f : 1.0f;
                const float rr = 0.9f * std::sqrt(U(rng)) * (cone && z == 1 ? s.apex : 1.0f);
                return {{rr * c, rr * sn, z}, {0, 0, z == 0 ? -1.0f : 1.0f}};
            }
            const float z = 0.1f + 0.8f * U(rng);
            if (!cone) return {{c, sn, z}, {c, sn, 0}};
            const float m = 1 - s.apex, rr = 1 - m * z;
            return {{rr * c, rr * sn, z}, {c, sn, m}};
        }
        case ShapeType::torus: {
            const float psi = 2 * float(pi) * U(rng);
            const Vec3 n{std::cos(psi) * c, std::cos(psi) * sn, std::sin(psi)};
            return {Vec3{c, sn, 0} + n * s.minor, n};
        }
        case ShapeType::plane:
            return {{10 * U(rng) - 5, 10 * U(rng) - 5, 0}, {0, 0, 1}};
        case ShapeType::triangle: {
            float b1 = 0.05f + 0.9f * U(rng), b2 = 0.05f + 0.9f * U(rng);
            if (b1 + b2 > 0.95f) b1 = 0.95f - b1, b2 = 0.95f - b2;
            b1 = std::max(b1, 0.02f), b2 = std::max(b2, 0.02f);
            const Vec3* v = s.vertices;
            return {v[0] * (1 - b1 - b2) + v[1] * b1 + v[2] * b2, cross(v[1] - v[0], v[2] - v[0])};
        }
        case ShapeType::mesh:
            break;
    }
    return {};
}

/// Every shape: the fixtures' objects and a plane.
inline std::vector<NamedObject> shapes_under_test() {
    std::vector<NamedObject> all = all_objects();
    all.push_back({"plane", plane_desc(), false});
    return all;
}

inline bool unit(const Vec3& v) { return is_finite(v) && std::fabs(length(v) - 1.0f) < 1e-5f; }

inline void expect_near(const Vec3& a, const Vec3& b, float tol) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

/// The world normal of an object-space normal.
inline Vec3 world_normal(const Shape& s, const Vec3& n) { return normalize(s.transform.normal(n)); }

}  // namespace luz::test
