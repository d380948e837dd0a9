// Shared helpers of the geometry tests: random points and directions, object descriptions of
// every shape, user transforms, and checks on tessellated meshes (edges by position, areas,
// reference points for normals).
#pragma once

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "geometry/shape.h"
#include "geometry/tessellate.h"
#include "geometry/triangle_mesh.h"
#include "math/transform.h"
#include "scene/scene_desc.h"

namespace luz::test {

using Rng = std::mt19937;

inline float uniform(Rng& rng, float lo, float hi) {
    return std::uniform_real_distribution<float>(lo, hi)(rng);
}
inline Vec3 random_point(Rng& rng, float lo, float hi) {
    return {uniform(rng, lo, hi), uniform(rng, lo, hi), uniform(rng, lo, hi)};
}
/// A unit vector, uniform over directions (rejection from the unit ball).
inline Vec3 random_direction(Rng& rng) {
    for (;;) {
        const Vec3 d = random_point(rng, -1, 1);
        const float l = length(d);
        if (l > 0.05f && l <= 1) return d / l;
    }
}

/// The `transform` key: p_world = T·Rz·Ry·Rx·S·p (docs/SCENES.md#scene-files).
inline Affine user_transform(Vec3 scale, Vec3 rotate_deg, Vec3 translate) {
    return translation(translate) * rotation(2, rotate_deg.z) * rotation(1, rotate_deg.y) *
           rotation(0, rotate_deg.x) * scaling(scale);
}

struct NamedTransform {
    std::string name;
    Affine affine;
    bool similarity;  ///< rotation, uniform scale and translation only
};

inline std::vector<NamedTransform> user_transforms() {
    return {
        {"identity", Affine{}, true},
        {"similarity", user_transform(Vec3{1.7f}, {20, -35, 70}, {0.5f, -2, 3}), true},
        {"nonuniform", user_transform({2.0f, 0.5f, 1.3f}, {10, 40, -25}, {-1, 0, 2}), false},
        {"mirror", user_transform({-1.5f, 1.0f, 0.7f}, {-30, 15, 5}, {0, 1, -1}), false},
        {"mirror_uniform", user_transform(Vec3{-1.2f}, {0, 90, 0}, {3, 0, 0}), true},
    };
}

inline ObjectDesc sphere_desc() {
    ObjectDesc o;
    o.type = ShapeType::sphere;
    o.center = {1, 2, 3};
    o.radius = 1.5f;
    return o;
}
inline ObjectDesc box_desc() {
    ObjectDesc o;
    o.type = ShapeType::box;
    o.min = {-1, 0, -2};
    o.max = {2, 1, 0.5f};
    return o;
}
inline ObjectDesc cylinder_desc(bool caps = true) {
    ObjectDesc o;
    o.type = ShapeType::cylinder;
    o.base = {1, 0, -1};
    o.axis = {1, 2, 3};
    o.radius = 0.5f;
    o.height = 2.0f;
    o.caps = caps;
    return o;
}
inline ObjectDesc cone_desc(bool cap = true) {
    ObjectDesc o;
    o.type = ShapeType::cone;
    o.base = {-1, 0.5f, 0};
    o.axis = {0, 1, 1};
    o.radius = 0.6f;
    o.height = 1.5f;
    o.caps = cap;
    return o;
}
/// A truncated cone: radius 0.6 at the base, 0.25 at the top.
inline ObjectDesc frustum_desc(bool cap = true) {
    ObjectDesc o = cone_desc(cap);
    o.apex_radius = 0.25f;
    return o;
}
inline ObjectDesc torus_desc() {
    ObjectDesc o;
    o.type = ShapeType::torus;
    o.center = {0, 0.3f, 3};
    o.axis = {0.3f, 1, -0.2f};
    o.major_radius = 1.2f;
    o.minor_radius = 0.35f;
    return o;
}
inline ObjectDesc triangle_desc() {
    ObjectDesc o;
    o.type = ShapeType::triangle;
    o.vertices = {Vec3{0, 0, 0}, Vec3{2, 0, 1}, Vec3{0, 1.5f, 0.5f}};
    return o;
}
inline ObjectDesc plane_desc() {
    ObjectDesc o;
    o.type = ShapeType::plane;
    o.point = {0, -1, 0};
    o.normal = {0, 2, 0.5f};
    return o;
}

struct NamedObject {
    std::string name;
    ObjectDesc desc;
    bool closed;
};

/// Every tessellated shape, closed or open.
inline std::vector<NamedObject> all_objects() {
    return {
        {"sphere", sphere_desc(), true},         {"box", box_desc(), true},
        {"cylinder", cylinder_desc(true), true}, {"open_cylinder", cylinder_desc(false), false},
        {"cone", cone_desc(true), true},         {"open_cone", cone_desc(false), false},
        {"frustum", frustum_desc(true), true},   {"open_frustum", frustum_desc(false), false},
        {"torus", torus_desc(), true},           {"triangle", triangle_desc(), false},
    };
}

inline ObjectDesc with_transform(ObjectDesc o, const Affine& a) {
    o.transform = a;
    return o;
}

inline TriangleMesh tessellated(const Shape& s, int level) {
    TriangleMesh m;
    tessellate(s, level, m);
    return m;
}

using Key = std::tuple<float, float, float>;
inline Key key(const Vec3& p) { return {p.x, p.y, p.z}; }

/// Each vertex's position as a number: equal for vertices at exactly the same place (a mesh
/// may repeat a position under several indices, as at a seam).
inline std::vector<uint32_t> position_ids(const TriangleMesh& m) {
    std::vector<uint32_t> order(m.positions.size());
    for (uint32_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(),
              [&](uint32_t a, uint32_t b) { return key(m.positions[a]) < key(m.positions[b]); });
    std::vector<uint32_t> id(order.size());
    uint32_t next = 0;
    for (size_t i = 0; i < order.size(); ++i) {
        if (i > 0 && key(m.positions[order[i]]) != key(m.positions[order[i - 1]])) ++next;
        id[order[i]] = next;
    }
    return id;
}

/// An edge between two positions (position_ids()).
using Edge = std::pair<uint32_t, uint32_t>;

/// Edges with the number of times each occurs, sorted by edge: a flat map, quick at the
/// hundreds of thousands of edges of a finely tessellated torus.
struct EdgeCounts {
    std::vector<std::pair<Edge, int>> items;
    auto begin() const { return items.begin(); }
    auto end() const { return items.end(); }
    /// How often `e` occurs (0 when never).
    int count(const Edge& e) const {
        const auto it =
            std::lower_bound(items.begin(), items.end(), e,
                             [](const auto& item, const Edge& x) { return item.first < x; });
        return it != items.end() && it->first == e ? it->second : 0;
    }
};

inline EdgeCounts counted(std::vector<Edge> edges) {
    std::sort(edges.begin(), edges.end());
    EdgeCounts out;
    for (const Edge& e : edges) {
        if (out.items.empty() || out.items.back().first != e) out.items.push_back({e, 0});
        ++out.items.back().second;
    }
    return out;
}

/// Directed edges (a → b of each triangle) by exact vertex position, with their counts.
inline EdgeCounts directed_edges(const TriangleMesh& m) {
    const std::vector<uint32_t> id = position_ids(m);
    std::vector<Edge> edges;
    edges.reserve(3 * m.triangle_count());
    for (size_t t = 0; t < m.triangle_count(); ++t) {
        for (int k = 0; k < 3; ++k) {
            edges.push_back({id[m.indices[3 * t + k]], id[m.indices[3 * t + (k + 1) % 3]]});
        }
    }
    return counted(std::move(edges));
}

/// Undirected edges by exact vertex position, with the number of triangles using each, from
/// the directed ones.
inline EdgeCounts undirected_edges(const EdgeCounts& directed) {
    std::vector<Edge> edges;
    for (const auto& [e, n] : directed) {
        const auto& [a, b] = e;
        for (int i = 0; i < n; ++i) edges.push_back(a < b ? Edge{a, b} : Edge{b, a});
    }
    return counted(std::move(edges));
}

/// The same from the mesh.
inline EdgeCounts undirected_edges(const TriangleMesh& m) {
    return undirected_edges(directed_edges(m));
}

/// (b − a) × (c − a) of triangle t, in double: twice its area, along its winding's normal.
inline void face(const TriangleMesh& m, size_t t, double out[3]) {
    const Vec3& a = m.positions[m.indices[3 * t]];
    const Vec3& b = m.positions[m.indices[3 * t + 1]];
    const Vec3& c = m.positions[m.indices[3 * t + 2]];
    const double u[3] = {double(b.x) - a.x, double(b.y) - a.y, double(b.z) - a.z};
    const double v[3] = {double(c.x) - a.x, double(c.y) - a.y, double(c.z) - a.z};
    out[0] = u[1] * v[2] - u[2] * v[1];
    out[1] = u[2] * v[0] - u[0] * v[2];
    out[2] = u[0] * v[1] - u[1] * v[0];
}

inline double face_area(const TriangleMesh& m, size_t t) {
    double f[3];
    face(m, t, f);
    return 0.5 * std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
}

inline double total_area(const TriangleMesh& m) {
    double sum = 0;
    for (size_t t = 0; t < m.triangle_count(); ++t) sum += face_area(m, t);
    return sum;
}

/// The point inside the shape that a world vertex p must face away from: the centre of convex
/// shapes, the nearest point of the major circle for the torus (computed in object space).
inline Vec3 reference_point(const Shape& s, const Vec3& p) {
    const Vec3 q = s.transform.object_from_world.point(p);
    switch (s.type) {
        case ShapeType::box:
            return s.transform.point((s.lo + s.hi) * 0.5f);
        case ShapeType::cylinder:
            return s.transform.point({0, 0, 0.5f});
        case ShapeType::cone:
            return s.transform.point({0, 0, 0.25f});
        case ShapeType::torus:
            return s.transform.point(normalize(Vec3{q.x, q.y, 0}));
        default:
            return s.transform.point({0, 0, 0});
    }
}

}  // namespace luz::test
