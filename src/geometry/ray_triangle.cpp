// The watertight ray–triangle test (Woop, Benthin and Wald, JCGT 2013) and the nearest hit of
// a whole mesh by it.
#include "geometry/ray_triangle.h"

#include <cmath>
#include <utility>

namespace luz {

WatertightRay prepare_watertight(const Ray& r) {
    WatertightRay w;
    w.origin = r.origin;
    const Vec3 a{std::fabs(r.direction.x), std::fabs(r.direction.y), std::fabs(r.direction.z)};
    w.kz = a.x > a.y ? (a.x > a.z ? 0 : 2) : (a.y > a.z ? 1 : 2);
    w.kx = (w.kz + 1) % 3;
    w.ky = (w.kx + 1) % 3;
    if (r.direction[w.kz] < 0) std::swap(w.kx, w.ky);  // keeps the winding's sign
    w.Sx = r.direction[w.kx] / r.direction[w.kz];
    w.Sy = r.direction[w.ky] / r.direction[w.kz];
    w.Sz = 1.0f / r.direction[w.kz];
    return w;
}

bool intersect_triangle(const WatertightRay& r, const Vec3& p0, const Vec3& p1, const Vec3& p2,
                        float t_min, float t_max, float& t, float& b1, float& b2) {
    // vertices relative to the origin, sheared so that the ray runs along +z
    const Vec3 A = p0 - r.origin, B = p1 - r.origin, C = p2 - r.origin;
    const float Ax = A[r.kx] - r.Sx * A[r.kz], Ay = A[r.ky] - r.Sy * A[r.kz];
    const float Bx = B[r.kx] - r.Sx * B[r.kz], By = B[r.ky] - r.Sy * B[r.kz];
    const float Cx = C[r.kx] - r.Sx * C[r.kz], Cy = C[r.ky] - r.Sy * C[r.kz];
    // scaled barycentrics: 2D edge functions; exact in double when one is zero in float
    float U = Cx * By - Cy * Bx, V = Ax * Cy - Ay * Cx, W = Bx * Ay - By * Ax;
    if (U == 0.0f || V == 0.0f || W == 0.0f) {
        U = static_cast<float>(double(Cx) * By - double(Cy) * Bx);
        V = static_cast<float>(double(Ax) * Cy - double(Ay) * Cx);
        W = static_cast<float>(double(Bx) * Ay - double(By) * Ax);
    }
    if ((U < 0 || V < 0 || W < 0) && (U > 0 || V > 0 || W > 0)) return false;
    const float det = U + V + W;
    if (det == 0.0f) return false;
    const float T = U * (r.Sz * A[r.kz]) + V * (r.Sz * B[r.kz]) + W * (r.Sz * C[r.kz]);
    const float inv_det = 1.0f / det;
    const float tt = T * inv_det;
    if (!(tt > t_min && tt < t_max)) return false;
    t = tt;
    b1 = V * inv_det;
    b2 = W * inv_det;
    return true;
}

bool intersect_mesh(const Mesh& mesh, const WatertightRay& w, float t_min, float t_max, Hit& hit) {
    bool found = false;
    Vec3 p0, p1, p2;
    for (size_t k = 0; k < mesh.triangle_count(); ++k) {
        mesh.vertices(k, p0, p1, p2);
        float t, b1, b2;
        if (intersect_triangle(w, p0, p1, p2, t_min, t_max, t, b1, b2)) {
            t_max = t;
            hit.t = t;
            hit.u = b1;
            hit.v = b2;
            hit.part = static_cast<int>(k);
            found = true;
        }
    }
    return found;
}

}  // namespace luz
