// Readers of the scene's settings sections: image, camera, render (with antialias), lights.
#include "scene/settings_readers.h"

#include <cmath>

#include "scene/json_readers.h"
#include "scene/number_text.h"

namespace luz::loader {

void read_image(const Json& j, ImageDesc& image) {
    const Section s(j, "image", {"width", "height", "background", "encoding"}, "image");
    s.integer("width", image.width);
    s.integer("height", image.height);
    if (static_cast<long long>(image.width) * image.height > kMaxPixels) {
        fail("image",
             "width*height must be at most " + std::to_string(kMaxPixels) + " (2^28) pixels, got " +
                 std::to_string(image.width) + "x" + std::to_string(image.height),
             "image");
    }
    s.rgb("background", image.background);
    s.enumeration("encoding", image.encoding,
                  {{"linear", Encoding::linear}, {"srgb", Encoding::srgb}});
}

void read_camera(const Json* j, CameraDesc& camera) {
    if (j) {
        const Section s(*j, "camera",
                        {"projection", "position", "look_at", "up", "view_height", "fov_y"},
                        "camera");
        s.enumeration(
            "projection", camera.projection,
            {{"orthographic", Projection::orthographic}, {"perspective", Projection::perspective}});
        s.vec3("position", camera.position);
        s.vec3("look_at", camera.look_at);
        s.direction("up", camera.up);
        s.number("view_height", camera.view_height);
        s.number("fov_y", camera.fov_y);
    }
    // The basis of docs/SCENES.md#geometry must exist: w = normalize(position − look_at), u = up ×
    // w ≠ 0.
    const Vec3 d = camera.position - camera.look_at;
    const float len = length(d);
    if (d == Vec3(0.0f)) {
        fail("camera.look_at",
             "must differ from camera.position, got " + format_vec(camera.look_at) + " for both",
             "camera");
    }
    if (!(len > 0) || !std::isfinite(len)) {
        fail("camera.look_at",
             "is too far from camera.position (their distance overflows a float), got " +
                 format_vec(camera.look_at) + " and " + format_vec(camera.position),
             "camera");
    }
    const Vec3 w = d / len;
    const Vec3 up = normalize(camera.up);
    if (!(length(cross(up, w)) > 1e-6f)) {
        fail("camera.up",
             "must not be parallel to the view direction, got up " + format_vec(camera.up) +
                 " and look_at - position = " + format_vec(-d),
             "camera");
    }
}

namespace {

/// `antialias.samples`: an integer within its limit that is a perfect square (s² samples).
void read_samples(const Section& a, int& samples) {
    const Json* v = a.get("samples");
    if (!v) return;
    const std::string key = a.key("samples");
    const Limit& l = a.limit("samples", NumberKind::integer);
    const std::string what = "must be a perfect square in [" + format_number(l.lo) + ", " +
                             format_number(l.hi) + "] (1, 4, 9, 16, ...), got ";
    if (!v->is_number()) fail(key, "expected an integer, got " + describe(*v));
    const double d = v->get<double>();
    if (!l.contains(d) || std::floor(d) != d) fail(key, what + v->dump());
    samples = static_cast<int>(d);
    const int s_root = static_cast<int>(std::lround(std::sqrt(d)));
    if (s_root * s_root != samples) fail(key, what + v->dump());
}

}  // namespace

void read_render(const Json& j, RenderDesc& render, GeometryDesc& geometry) {
    const Section s(j, "render",
                    {"pipeline", "model", "max_depth", "min_weight", "tree_attenuation",
                     "tessellation", "accel", "antialias"},
                    "render");
    s.enumeration("pipeline", render.pipeline,
                  {{"zbuffer", Pipeline::zbuffer},
                   {"raycast", Pipeline::raycast},
                   {"raytrace", Pipeline::raytrace}});
    s.enumeration("model", render.model, {{"lambert", Model::lambert}, {"phong", Model::phong}});
    s.integer("max_depth", render.max_depth);
    s.number("min_weight", render.min_weight);
    s.boolean("tree_attenuation", render.tree_attenuation);
    s.integer("tessellation", geometry.tessellation);
    s.enumeration("accel", geometry.accel, {{"bvh", Accel::bvh}, {"none", Accel::none}});
    if (const Json* aj = s.get("antialias")) {
        AntialiasDesc& aa = render.antialias;
        const Section a(*aj, s.key("antialias"),
                        {"mode", "samples", "filter", "jitter", "threshold", "max_level"},
                        "render.antialias");
        a.enumeration(
            "mode", aa.mode,
            {{"none", AaMode::none}, {"grid", AaMode::grid}, {"adaptive", AaMode::adaptive}});
        read_samples(a, aa.samples);
        a.enumeration("filter", aa.filter, {{"box", AaFilter::box}, {"tent", AaFilter::tent}});
        a.boolean("jitter", aa.jitter);
        a.number("threshold", aa.threshold);
        a.integer("max_level", aa.max_level);
    }
}

namespace {

/// Where the implicit light sits: at the camera's upper left, half the viewing distance away:
/// position + (−u + v)·(0.5·|position − look_at|), with u, v as in docs/SCENES.md#geometry.
Vec3 upper_left_of_camera(const CameraDesc& c) {
    const Vec3 w = normalize(c.position - c.look_at);
    const Vec3 u = normalize(cross(c.up, w));
    const Vec3 v = cross(w, u);
    return c.position + (v - u) * (0.5f * length(c.position - c.look_at));
}

}  // namespace

void read_lights(const Json* j, SceneDesc& scene) {
    const Vec3 default_position = upper_left_of_camera(scene.camera);
    if (j) {
        if (!j->is_array()) fail("lights", "expected an array of lights, got " + describe(*j));
        for (std::size_t i = 0; i < j->size(); ++i) {
            const Section s((*j)[i], join("lights", i), {"position", "intensity", "radius"},
                            "lights.*");
            Light light;
            light.position =
                default_position;  // a light without position: where the implicit one sits
            s.vec3("position", light.position);
            s.rgb("intensity", light.intensity);
            s.number("radius", light.radius);
            scene.lights.push_back(light);
        }
    }
    if (scene.lights.empty()) {
        // No lights: one white light at the camera's upper left. Under `lambert` Il = 1 (the
        // slide's value). Under `phong` Il/(d+K) would make Il = 1 very dim, so Il = d + K with
        // d the light's distance to look_at: Il/(d+K) = 1 at the look-at point
        // (docs/SCENES.md#models model 2); likewise Il = d² under `attenuation: inverse_square` and
        // Il = 1 under `none`.
        Light light;
        light.position = default_position;
        const float d = length(light.position - scene.camera.look_at);
        float Il = 1.0f;
        if (scene.render.model == Model::phong) {
            if (scene.attenuation == Attenuation::linear) Il = d + scene.attenuation_k;
            if (scene.attenuation == Attenuation::inverse_square) Il = d * d;
        }
        light.intensity = Rgb(Il);
        scene.lights.push_back(light);
    }
}

}  // namespace luz::loader
