// Orbit, pan and zoom of a CameraDesc (docs/SCENES.md#geometry basis).
#include "app/viewer/camera_controls.h"

#include <cmath>
#include <numbers>

namespace luz {

namespace {

/// v rotated by `degrees` about unit axis k (Rodrigues).
Vec3 rotate_about(const Vec3& v, const Vec3& k, float degrees) {
    const float a = degrees * std::numbers::pi_v<float> / 180.0f;
    const float c = std::cos(a), s = std::sin(a);
    return v * c + cross(k, v) * s + k * (dot(k, v) * (1 - c));
}

}  // namespace

void orbit_camera(CameraDesc& c, float yaw, float pitch) {
    const Vec3 up = normalize(c.up);
    Vec3 offset = c.position - c.look_at;
    offset = rotate_about(offset, up, yaw);
    const Vec3 w = normalize(offset);
    const Vec3 u = normalize(cross(up, w));
    const Vec3 turned = rotate_about(offset, u, -pitch);
    // Stay short of the poles, where u = up × w is undefined.
    if (std::fabs(dot(normalize(turned), up)) < 0.995f) offset = turned;
    c.position = c.look_at + offset;
}

void pan_camera(CameraDesc& c, float dx, float dy) {
    const Vec3 w = normalize(c.position - c.look_at);
    const Vec3 u = normalize(cross(c.up, w));
    const Vec3 v = cross(w, u);
    const float height = c.projection == Projection::orthographic
                             ? c.view_height
                             : 2 * length(c.position - c.look_at) *
                                   std::tan(c.fov_y * std::numbers::pi_v<float> / 360.0f);
    const Vec3 move = u * (dx * height) + v * (dy * height);
    c.position += move;
    c.look_at += move;
}

void zoom_camera(CameraDesc& c, float factor) {
    if (c.projection == Projection::orthographic) {
        c.view_height = std::max(1e-3f, c.view_height * factor);
    } else {
        const Vec3 offset = (c.position - c.look_at) * factor;
        if (length(offset) > 1e-3f) c.position = c.look_at + offset;
    }
}

}  // namespace luz
