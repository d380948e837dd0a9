// SceneDesc: the validated scene as plain structs, every default filled
// (docs/SCENES.md#scene-files).
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "luz/animation_desc.h"
#include "luz/material.h"
#include "luz/object_desc.h"
#include "luz/vec3.h"

namespace luz {

enum class Encoding { linear, srgb };
enum class Projection { orthographic, perspective };
enum class Pipeline { zbuffer, raycast, raytrace };
enum class Model { lambert, phong };
/// The distance law of phong's light term (`attenuation`): Il, Il/(d+K), Il/d².
enum class Attenuation { none, linear, inverse_square };
enum class Accel { bvh, none };
enum class AaMode { none, grid, adaptive };
enum class AaFilter { box, tent };

struct ImageDesc {
    int width = 800;
    int height = 600;
    Rgb background{0.05f, 0.05f, 0.08f};
    Encoding encoding = Encoding::linear;
};

struct CameraDesc {
    Projection projection = Projection::orthographic;
    Vec3 position{0, 3, 10};
    Vec3 look_at{0, 0.5f, 0};
    Vec3 up{0, 1, 0};
    float view_height = 6.0f;
    float fov_y = 40.0f;  ///< degrees
};

struct AntialiasDesc {
    AaMode mode = AaMode::none;
    int samples = 4;
    AaFilter filter = AaFilter::box;
    bool jitter = false;
    float threshold = 0.1f;
    int max_level = 3;
};

/// The `render` keys a render may change without a rebuild.
struct RenderDesc {
    Pipeline pipeline = Pipeline::zbuffer;
    Model model = Model::phong;
    int max_depth = 5;
    bool tree_attenuation = false;
    /// A secondary ray whose weight (the product of the reflection and transparency
    /// coefficients on its path from the camera) is below this is not traced
    /// (docs/SCENES.md#scene-files).
    float min_weight = 0;
    AntialiasDesc antialias;
};

/// The `render` keys that shape the built scene (a change needs a rebuild): how finely
/// curved shapes are tessellated for the zbuffer, and whether rays use a BVH.
struct GeometryDesc {
    int tessellation = 64;
    Accel accel = Accel::bvh;
};

struct Light {
    Vec3 position;
    Rgb intensity{1.0f};  ///< Il, ≥ 0, may exceed 1
    float radius = 0.0f;  ///< > 0: a visible sphere of the light's clamped colour
};

/// What a render may change without rebuilding the scene: image size, camera, pipeline, model,
/// antialiasing, depth, and the constants of lights and materials (objects refer to materials
/// by index, so a render's settings must have at least the scene's materials).
struct Settings {
    ImageDesc image;
    CameraDesc camera;
    RenderDesc render;
    Rgb ambient{1.0f};           ///< Ia
    float attenuation_k = 1.0f;  ///< K
    Attenuation attenuation = Attenuation::linear;
    std::vector<Light> lights;
    std::vector<Material> materials;  ///< materials[0] is the default material
};

/// A whole scene file: its Settings, and what needs a build (the objects and GeometryDesc).
struct SceneDesc : Settings {
    std::string name;       ///< file stem or demo name; the default output is name + ".png"
    std::string source;     ///< the file (or demo:NAME) it came from, for messages
    GeometryDesc geometry;  ///< the `render` keys tessellation and accel
    std::vector<ObjectDesc> objects;
    std::vector<std::string> warnings;  ///< non-fatal input problems ("FILE:LINE: what")
    AnimationDesc animation;            ///< the `animation` key (frames 0: none)
    int frame = 0;                      ///< which of its frames this description is
};

/// One `--set PATH=JSON` (or a command-line option turned into one). `origin` names where it
/// came from in messages, e.g. "--set" or "--width".
struct Override {
    std::string path;  ///< dotted key path; array elements by index, e.g. "lights.0.intensity"
    std::string json;  ///< the value as JSON text
    std::string origin = "--set";
};

}  // namespace luz
