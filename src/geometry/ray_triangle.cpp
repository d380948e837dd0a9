// The watertight ray–triangle test's rare double path (Woop, Benthin and Wald,
// JCGT 2013), and the nearest hit of a whole mesh by it.
#include "geometry/ray_triangle.h"

#include <cmath>
#include <utility>

namespace luz {

namespace watertight_detail {

void edges_in_double(float Ax, float Ay, float Bx, float By, float Cx, float Cy, float& U, float& V,
                     float& W) {
    U = static_cast<float>(double(Cx) * By - double(Cy) * Bx);
    V = static_cast<float>(double(Ax) * Cy - double(Ay) * Cx);
    W = static_cast<float>(double(Bx) * Ay - double(By) * Ax);
}

}  // namespace watertight_detail

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
