// Camera: the basis and ray generation of docs/SCENES.md#geometry, shared by every pipeline.
#pragma once

#include <cmath>
#include <numbers>

#include "math/ray.h"
#include "scene/scene_desc.h"

namespace luz {

struct Camera {
    Projection projection = Projection::orthographic;
    Vec3 position;
    Vec3 u, v, w;  ///< w = normalize(position − look_at), u = normalize(up × w), v = w × u
    int width = 1, height = 1;
    /// Half extents of the image plane: orthographic in world units
    /// (view_height·W/H/2, view_height/2); perspective per unit depth (tan(fov_y/2)·W/H,
    /// tan(fov_y/2)).
    float half_width = 1, half_height = 1;

    static Camera from(const CameraDesc& d, int width, int height) {
        Camera c;
        c.projection = d.projection;
        c.position = d.position;
        c.w = normalize(d.position - d.look_at);
        c.u = normalize(cross(d.up, c.w));
        c.v = cross(c.w, c.u);
        c.width = width;
        c.height = height;
        const float aspect = static_cast<float>(width) / static_cast<float>(height);
        if (d.projection == Projection::orthographic) {
            c.half_height = d.view_height / 2;
        } else {
            c.half_height =
                static_cast<float>(std::tan(d.fov_y * std::numbers::pi / 360.0));  // fov_y/2
        }
        c.half_width = c.half_height * aspect;
        return c;
    }

    /// Image-plane coordinates of pixel-space point (px, py): x = 2px/W − 1, y = 1 − 2py/H.
    float ndc_x(float px) const { return 2.0f * px / static_cast<float>(width) - 1.0f; }
    float ndc_y(float py) const { return 1.0f - 2.0f * py / static_cast<float>(height); }

    /// The primary ray through pixel-space point (px, py) (docs/SCENES.md#geometry).
    Ray ray(float px, float py) const {
        const float x = ndc_x(px), y = ndc_y(py);
        if (projection == Projection::orthographic) {
            return {position + u * (x * half_width) + v * (y * half_height), -w};
        }
        return {position, normalize(-w + u * (x * half_width) + v * (y * half_height))};
    }

    /// World point to view space: (along u, along v, depth in front of the camera plane).
    Vec3 to_view(const Vec3& p) const {
        const Vec3 d = p - position;
        return {dot(d, u), dot(d, v), -dot(d, w)};
    }
};

}  // namespace luz
