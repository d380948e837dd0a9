// The double-precision path of world_sphere_roots() (ray_sphere.h).
#include "geometry/ray_sphere.h"

namespace luz {

bool world_sphere_roots_double(const Vec3& centre, float radius, const Ray& r, float& t0,
                               float& t1) {
    const Lane3<double> o{double(r.origin.x) - centre.x, double(r.origin.y) - centre.y,
                          double(r.origin.z) - centre.z};
    const Lane3<double> d{r.direction.x, r.direction.y, r.direction.z};
    const double rho = radius;
    double r0, r1;
    if (!ray_sphere::solve(o, d, rho * rho, r0, r1)) return false;
    t0 = static_cast<float>(r0);
    t1 = static_cast<float>(r1);
    return true;
}

}  // namespace luz
