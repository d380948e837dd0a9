// SceneDesc: the validated scene as plain structs, every default filled (SPEC §2).
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "math/transform.h"
#include "math/vec3.h"
#include "scene/material.h"
#include "scene/mesh_data.h"

namespace luz {

enum class Encoding { linear, srgb };
enum class Projection { orthographic, perspective };
enum class Pipeline { zbuffer, raycast, raytrace };
enum class Model { lambert, phong };
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

struct RenderDesc {
    Pipeline pipeline = Pipeline::zbuffer;
    Model model = Model::phong;
    int max_depth = 5;
    bool tree_attenuation = false;
    int tessellation = 64;
    Accel accel = Accel::bvh;
    AntialiasDesc antialias;
};

struct Light {
    Vec3 position;
    Rgb intensity{1.0f};  ///< Il, ≥ 0, may exceed 1
    float radius = 0.0f;  ///< > 0: a visible sphere of the light's clamped colour
};

enum class ShapeType { sphere, box, cylinder, cone, torus, plane, triangle, mesh };

/// One object as its keys define it (only the fields of its type are meaningful).
struct ObjectDesc {
    ShapeType type = ShapeType::sphere;
    int material = 0;  ///< index into SceneDesc::materials
    std::string path;  ///< key path, e.g. "objects.3", for messages
    Affine transform;  ///< the `transform` key: T·Rz·Ry·Rx·S
    /// The `transform` keys as given (scale, rotate in degrees, translate), for the scene writer.
    Vec3 scale{1.0f}, rotate{0.0f}, translate{0.0f};
    // sphere, torus
    Vec3 center{0, 0, 0};
    float radius = 1.0f;  // sphere, cylinder, cone
    // box
    Vec3 min{-0.5f, -0.5f, -0.5f}, max{0.5f, 0.5f, 0.5f};
    // cylinder, cone
    Vec3 base{0, 0, 0};
    Vec3 axis{0, 1, 0};
    float height = 1.0f;
    bool caps = true;  ///< cylinder `caps`, cone `cap`
    // torus
    float major_radius = 1.0f, minor_radius = 0.25f;
    // plane
    Vec3 point{0, 0, 0};
    Vec3 normal{0, 1, 0};
    // triangle
    std::array<Vec3, 3> vertices{Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{0, 1, 0}};
    // mesh
    std::string file;
    bool smooth = true;
    /// The loaded OBJ file (shared: objects naming the same file share it).
    std::shared_ptr<const MeshData> mesh;
    /// MeshData::materials index → index into SceneDesc::materials; empty when the object
    /// names a material (then every triangle has `material`). Faces without an MTL material
    /// have `material` (the default material unless the object names one).
    std::vector<int> mesh_materials;
};

struct SceneDesc {
    std::string name;    ///< file stem or demo name; the default output is name + ".png"
    std::string source;  ///< the file (or demo:NAME) it came from, for messages
    ImageDesc image;
    CameraDesc camera;
    RenderDesc render;
    Rgb ambient{1.0f};           ///< Ia
    float attenuation_k = 1.0f;  ///< K
    std::vector<Light> lights;
    std::vector<Material> materials;  ///< materials[0] is the default material
    std::vector<ObjectDesc> objects;
    std::vector<std::string> warnings;  ///< non-fatal input problems ("FILE:LINE: what")
};

}  // namespace luz
