// A frame of an animation: keyframes interpolated into overrides, then the orbit
// (docs/SCENES.md#scene-files).
#include "scene/animation.h"

#include <cmath>

#include "scene/number_text.h"

namespace luz {

std::vector<double> key_value(const AnimationKey& key, int f) {
    const std::vector<int>& k = key.frames;
    if (f <= k.front()) return key.values.front();
    if (f >= k.back()) return key.values.back();
    std::size_t i = 1;
    while (k[i] < f) ++i;  // k[i-1] < f <= k[i]
    if (k[i] == f) return key.values[i];
    const double t = double(f - k[i - 1]) / double(k[i] - k[i - 1]);
    const std::vector<double>&a = key.values[i - 1], &b = key.values[i];
    std::vector<double> v(a.size());
    for (std::size_t c = 0; c < a.size(); ++c) v[c] = a[c] + (b[c] - a[c]) * t;
    return v;
}

std::vector<Override> frame_overrides(const AnimationDesc& a, int f, const std::string& label) {
    std::vector<Override> out;
    for (const AnimationKey& key : a.keys) {
        const std::vector<double> v = key_value(key, f);
        std::string json;
        if (key.array) {
            json = "[";
            for (std::size_t c = 0; c < v.size(); ++c) {
                if (c) json += ", ";
                json += json_number(v[c]);
            }
            json += "]";
        } else {
            json = json_number(v[0]);
        }
        out.push_back(
            {key.path, json,
             label + ": animation.keys." + key.path + " at frame " + std::to_string(f) + " ="});
    }
    return out;
}

void apply_orbit(const AnimationDesc& a, int f, CameraDesc& camera) {
    if (a.orbit == 0 || a.frames <= 0 || f == 0) return;
    // Rodrigues' rotation of p = position − look_at about the unit axis k = up by θ.
    const double theta = a.orbit * double(f) / double(a.frames) * (M_PI / 180.0);
    const double c = std::cos(theta), s = std::sin(theta);
    double k[3] = {camera.up.x, camera.up.y, camera.up.z};
    const double len = std::sqrt(k[0] * k[0] + k[1] * k[1] + k[2] * k[2]);
    for (double& x : k) x /= len;
    const double p[3] = {double(camera.position.x) - camera.look_at.x,
                         double(camera.position.y) - camera.look_at.y,
                         double(camera.position.z) - camera.look_at.z};
    const double kxp[3] = {k[1] * p[2] - k[2] * p[1], k[2] * p[0] - k[0] * p[2],
                           k[0] * p[1] - k[1] * p[0]};
    const double kdp = k[0] * p[0] + k[1] * p[1] + k[2] * p[2];
    double r[3];
    for (int i = 0; i < 3; ++i) r[i] = p[i] * c + kxp[i] * s + k[i] * kdp * (1 - c);
    camera.position = Vec3(float(camera.look_at.x + r[0]), float(camera.look_at.y + r[1]),
                           float(camera.look_at.z + r[2]));
}

}  // namespace luz
