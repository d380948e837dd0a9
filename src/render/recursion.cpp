// Snell's law and the directions of a hit's secondary rays (render/recursion.h).
#include "render/recursion.h"

#include <cmath>

namespace luz {

bool refract(const Vec3& D, const Vec3& N, float n1, float n2, Vec3& T) {
    const float eta = n1 / n2;
    const float cos_i = -dot(D, N);
    const float k = 1 - eta * eta * (1 - cos_i * cos_i);  // cos² r
    if (k < 0) return false;                              // total internal reflection
    T = normalize(D * eta + N * (eta * cos_i - std::sqrt(k)));
    return true;
}

Bounce bounce(const Vec3& D, const SurfacePoint& sp, const Material& m) {
    const bool entering = dot(D, sp.Ng) < 0;
    const Vec3 N = dot(D, sp.N) < 0 ? sp.N : -sp.N;  // facing the incoming ray
    Bounce b;
    b.reflected = reflect(D, N);
    if (m.transparency > 0) {
        const float n1 = entering ? 1.0f : m.ior, n2 = entering ? m.ior : 1.0f;
        Vec3 T;
        b.tir = !refract(D, N, n1, n2, T);
        b.refracted = b.tir ? b.reflected : T;
    }
    return b;
}

}  // namespace luz
