// Mesh: an OBJ file's triangles (geometry/mesh.h), built in world space once (identity
// transform); two-sided. A hit's part is the triangle, u and v its barycentrics. The scene
// queries put its triangles in the BVH; intersect() here tests them all.
#pragma once

#include <cstdint>
#include <memory>
#include <stdexcept>

#include "geometry/mesh.h"
#include "geometry/ray_triangle.h"
#include "geometry/shapes/object_space.h"
#include "geometry/shapes/placement.h"

namespace luz::shapes {

struct mesh {
    static constexpr bool bounded = true;

    /// The triangles in world space already (build_mesh applies the object's transform).
    static void place(const ObjectDesc& o, Shape& s) {
        s.mesh = std::make_shared<const Mesh>(build_mesh(o));
    }

    /// The mesh's bounds, padded; empty for a mesh without triangles.
    static Bounds3 bounds(const Shape& s) {
        if (!s.mesh || s.mesh->bounds.empty()) return Bounds3{};
        return pad(s.mesh->bounds);
    }

    /// Out of line (object_space.h: intersect_in_object_space).
    [[gnu::noinline]] static bool intersect(const Shape& s, const Ray& r, float t_min, float t_max,
                                            Hit& hit) {
        return s.mesh && intersect_mesh(*s.mesh, prepare_watertight(r), t_min, t_max, hit);
    }

    static uint32_t count_crossings(const Shape& s, const Ray& r, float t_min, float t_max,
                                    bool first_only, uint64_t& tests) {
        return count_by_repeated_hits(
            t_min, t_max, first_only, tests,
            [&](float t0, float t1, Hit& h) { return intersect(s, r, t0, t1, h); });
    }

    /// World space; N interpolated (smooth) on the face normal's side, Ng the face normal.
    static SurfacePoint surface_at(const Shape& s, const Ray& r, const Hit& hit) {
        const size_t t = static_cast<size_t>(hit.part);
        const Vec3 Ng = s.mesh->face_normal(t);
        return {r.at(hit.t), s.mesh->shading_normal(t, hit.u, hit.v, Ng), Ng};
    }

    /// The mesh's own triangles, in order, whatever the level. Smooth: its shared vertices and
    /// normals; flat: three vertices per triangle carrying the face normal, so interpolation
    /// keeps it constant.
    static void tessellate(const Shape& s, int, TriangleMesh& out) {
        if (!s.mesh) return;
        const Mesh& m = *s.mesh;
        const uint32_t base = static_cast<uint32_t>(out.positions.size());
        if (m.smooth()) {
            out.positions.insert(out.positions.end(), m.positions.begin(), m.positions.end());
            for (const Vec3& n : m.normals)
                out.normals.push_back(n == Vec3{0.0f} ? Vec3{0, 0, 1} : n);
            for (uint32_t i : m.indices) out.indices.push_back(base + i);
            return;
        }
        out.reserve_more(m.indices.size(), m.indices.size());
        for (size_t t = 0; t < m.triangle_count(); ++t) {
            Vec3 p[3];
            m.vertices(t, p[0], p[1], p[2]);
            const Vec3 n = m.face_normal(t);
            for (int k = 0; k < 3; ++k) {
                out.indices.push_back(static_cast<uint32_t>(out.positions.size()));
                out.positions.push_back(p[k]);
                out.normals.push_back(n);
            }
        }
    }

    static double area(const Shape&) {
        throw std::logic_error("analytic_area: mesh shapes are not supported yet");
    }
};

}  // namespace luz::shapes
