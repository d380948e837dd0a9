// build_mesh: OBJ data (object space) → world-space Mesh: transform, winding, shared vertices,
// angle-weighted vertex normals, per-triangle materials.
#include "geometry/mesh.h"

#include <cmath>
#include <string>
#include <unordered_map>

#include "math/transform.h"
#include "scene/cancel.h"
#include "scene/input_error.h"

namespace luz {

namespace {

/// Normalised, or zero for a zero or non-finite vector.
Vec3 unit_or_zero(const Vec3& v) {
    const float l = length(v);
    if (!(l > 0) || !std::isfinite(l)) return Vec3{0.0f};
    const Vec3 u = v / l;
    return is_finite(u) ? u : Vec3{0.0f};
}

/// Angle-weighted vertex normals (Thürmer and Wüthrich 1998): each face adds its unit normal
/// times its corner angle at the vertex. Zero-area faces add nothing; a vertex with nothing
/// gets zero.
std::vector<Vec3> angle_weighted_normals(const std::vector<Vec3>& p,
                                         const std::vector<uint32_t>& index) {
    std::vector<Vec3> n(p.size(), Vec3{0.0f});
    for (size_t t = 0; t + 2 < index.size(); t += 3) {
        const uint32_t i[3] = {index[t], index[t + 1], index[t + 2]};
        const Vec3 face = unit_or_zero(cross(p[i[1]] - p[i[0]], p[i[2]] - p[i[0]]));
        if (face == Vec3{0.0f}) continue;
        for (int k = 0; k < 3; ++k) {
            const Vec3 a = p[i[(k + 1) % 3]] - p[i[k]], b = p[i[(k + 2) % 3]] - p[i[k]];
            const float angle = std::atan2(length(cross(a, b)), dot(a, b));  // robust for all
            n[i[k]] += face * angle;
        }
    }
    for (Vec3& v : n) v = unit_or_zero(v);
    return n;
}

/// The unit winding normal of triangle t of `mesh` (Mesh::face_normal()).
Vec3 winding_normal(const Mesh& mesh, size_t t) {
    Vec3 p0, p1, p2;
    mesh.vertices(t, p0, p1, p2);
    const Vec3 n = unit_or_zero(cross(p1 - p0, p2 - p0));
    return n == Vec3{0.0f} ? Vec3{0, 0, 1} : n;
}

/// The face normals of `mesh`, once its positions and indices are final.
Mesh with_face_normals(Mesh mesh) {
    mesh.face_normals.resize(mesh.triangle_count());
    for (size_t t = 0; t < mesh.face_normals.size(); ++t)
        mesh.face_normals[t] = winding_normal(mesh, t);
    return mesh;
}

}  // namespace

Vec3 Mesh::shading_normal(size_t t, float b1, float b2, const Vec3& Ng) const {
    if (normals.empty()) return Ng;
    const Vec3& n0 = normals[indices[3 * t]];
    const Vec3& n1 = normals[indices[3 * t + 1]];
    const Vec3& n2 = normals[indices[3 * t + 2]];
    const Vec3 N = unit_or_zero(n0 * (1 - b1 - b2) + n1 * b1 + n2 * b2);
    if (N == Vec3{0.0f}) return Ng;
    return dot(N, Ng) < 0 ? -N : N;
}

Mesh build_mesh(const ObjectDesc& o) {
    Mesh mesh;
    if (!o.mesh) return mesh;
    const MeshData& d = *o.mesh;
    const Transform xf = Transform::from(o.transform);
    const bool mirror = o.transform.determinant() < 0;
    const size_t triangles = d.triangle_count();

    // Positions in world space; triangles counter-clockwise from outside.
    std::vector<Vec3> world(d.positions.size());
    for (size_t i = 0; i < world.size(); ++i) {
        world[i] = xf.point(d.positions[i]);
        if (!is_finite(world[i])) {
            throw InputError(d.file + ": vertex " + std::to_string(i + 1) +
                             " is out of float range after the object's transform (" + o.path +
                             ".transform)");
        }
    }
    check_cancel();
    std::vector<uint32_t> position(d.position);
    std::vector<int32_t> normal(d.normal);
    if (mirror) {
        for (size_t t = 0; t < triangles; ++t) {
            std::swap(position[3 * t + 1], position[3 * t + 2]);
            std::swap(normal[3 * t + 1], normal[3 * t + 2]);
        }
    }

    mesh.materials.resize(triangles);
    for (size_t t = 0; t < triangles; ++t) {
        const int32_t m = d.material[t];
        mesh.materials[t] = (m >= 0 && static_cast<size_t>(m) < o.mesh_materials.size())
                                ? o.mesh_materials[m]
                                : o.material;
    }
    for (uint32_t i : position) mesh.bounds.expand(world[i]);
    check_cancel();

    if (!o.smooth) {
        mesh.positions = std::move(world);
        mesh.indices = std::move(position);
        return with_face_normals(std::move(mesh));
    }

    // Smooth: one vertex per distinct (position, file normal) pair; a corner without a usable
    // file normal takes the angle-weighted normal of its position.
    const std::vector<Vec3> computed = angle_weighted_normals(world, position);
    check_cancel();
    std::vector<Vec3> file_normals(d.normals.size());
    for (size_t i = 0; i < file_normals.size(); ++i) {
        file_normals[i] = unit_or_zero(xf.normal(d.normals[i]));
    }
    bool any_file_normal = false;
    for (int32_t n : normal) any_file_normal = any_file_normal || n >= 0;
    if (!any_file_normal) {
        mesh.positions = std::move(world);
        mesh.normals = computed;
        mesh.indices = std::move(position);
        return with_face_normals(std::move(mesh));
    }
    std::unordered_map<uint64_t, uint32_t> vertex_of;
    vertex_of.reserve(position.size());
    mesh.indices.resize(position.size());
    for (size_t c = 0; c < position.size(); ++c) {
        const uint32_t p = position[c];
        int32_t n = normal[c];
        if (n >= 0 && file_normals[n] == Vec3{0.0f}) n = -1;  // zero or unusable: computed
        const uint64_t key = (uint64_t{p} << 32) | static_cast<uint32_t>(n + 1);
        const auto [it, added] = vertex_of.try_emplace(key, uint32_t(mesh.positions.size()));
        if (added) {
            mesh.positions.push_back(world[p]);
            mesh.normals.push_back(n >= 0 ? file_normals[n] : computed[p]);
        }
        mesh.indices[c] = it->second;
    }
    return with_face_normals(std::move(mesh));
}

}  // namespace luz
