// What the shapes share to tessellate themselves: the Emitter that places object-space vertices
// in world space and keeps the winding, and the cos/sin table of a circle.
#pragma once

#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "geometry/triangle_mesh.h"
#include "math/transform.h"

namespace luz::shapes {

constexpr double pi = std::numbers::pi;

/// Appends vertices and triangles of one shape: object-space positions and normals go in,
/// world-space ones come out. A mirroring transform (negative determinant) turns
/// counter-clockwise into clockwise, so the winding is reversed to stay counter-clockwise
/// seen from outside.
class Emitter {
  public:
    Emitter(const Transform& t, TriangleMesh& out)
        : t_(t), out_(out), flip_(t.world_from_object.determinant() < 0) {}

    /// Adds a vertex at object point p with object normal n (any length); returns its index.
    uint32_t vertex(const Vec3& p, const Vec3& n) {
        out_.positions.push_back(t_.point(p));
        out_.normals.push_back(normalize(t_.normal(n)));
        return static_cast<uint32_t>(out_.positions.size() - 1);
    }
    /// Adds triangle (a, b, c), counter-clockwise from outside in object space.
    void triangle(uint32_t a, uint32_t b, uint32_t c) {
        out_.indices.push_back(a);
        out_.indices.push_back(flip_ ? c : b);
        out_.indices.push_back(flip_ ? b : c);
    }
    /// Adds quad (a, b, c, d), counter-clockwise from outside, as triangles (a,b,c), (a,c,d).
    void quad(uint32_t a, uint32_t b, uint32_t c, uint32_t d) {
        triangle(a, b, c);
        triangle(a, c, d);
    }
    void reserve(size_t vertices, size_t triangles) { out_.reserve_more(vertices, 3 * triangles); }

  private:
    const Transform& t_;
    TriangleMesh& out_;
    bool flip_;
};

/// cos and sin of 2π·j/n for j = 0 … n−1, computed once so that every vertex on the same
/// circle (side rims and cap rims, seams) uses the very same float values.
struct Circle {
    std::vector<float> c, s;
    explicit Circle(int n) : c(n), s(n) {
        for (int j = 0; j < n; ++j) {
            const double phi = 2.0 * pi * j / n;
            c[j] = static_cast<float>(std::cos(phi));
            s[j] = static_cast<float>(std::sin(phi));
        }
    }
};

}  // namespace luz::shapes
