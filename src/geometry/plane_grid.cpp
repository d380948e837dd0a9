// The zbuffer's stand-in for a plane: a grid of quads whose cells double in size away from the
// camera's foot on the plane, far larger than the scene.
#include "geometry/plane_grid.h"

#include <algorithm>
#include <vector>

#include "math/transform.h"

namespace luz {

namespace {

/// The scene's size: the diagonal of everything bounded, the camera and what it looks at.
float scene_size(const BuiltScene& scene, const CameraDesc& c) {
    Bounds3 b;
    for (const Shape& s : scene.shapes)
        if (is_bounded(s)) b.expand(bounds(s));
    b.expand(c.position);
    b.expand(c.look_at);
    return std::max(length(b.extent()) + c.view_height, 1.0f);
}

}  // namespace

void append_plane_grid(const BuiltScene& scene, const CameraDesc& camera, const Shape& plane,
                       TriangleMesh& mesh) {
    const float size = scene_size(scene, camera);
    const Vec3 o = plane.transform.point({0, 0, 0});
    const Vec3 n = normalize(plane.transform.normal({0, 0, 1}));
    const Vec3 eye = camera.position;
    const Vec3 foot = eye - n * dot(eye - o, n);
    Vec3 u, v;
    orthonormal_basis(n, u, v);
    std::vector<float> coords{0.0f};
    for (float c = size / 16; c < 1000 * size; c *= 2) {
        coords.push_back(c);
        coords.insert(coords.begin(), -c);
    }
    const auto k = static_cast<uint32_t>(coords.size());
    const auto base = static_cast<uint32_t>(mesh.positions.size());
    for (float cv : coords) {
        for (float cu : coords) {
            mesh.positions.push_back(foot + u * cu + v * cv);
            mesh.normals.push_back(n);
        }
    }
    for (uint32_t j = 0; j + 1 < k; ++j) {
        for (uint32_t i = 0; i + 1 < k; ++i) {
            const uint32_t a = base + j * k + i, b = a + 1, c = a + k + 1, d = a + k;
            for (uint32_t index : {a, b, c, a, c, d}) mesh.indices.push_back(index);
        }
    }
}

}  // namespace luz
