// The built-in scenes (demo:NAME), kept as JSON text so they read like scene files.
// To add one, write its JSON as a raw string below and add a row to kDemos.
#include "scene/demo_scenes.h"

namespace luz {
namespace {

// The practical assignment: sphere, cube, cylinder, cone and torus on a floor, orthographic,
// zbuffer, phong. Exposure by hand (docs/SCENES.md#models model 2, K = 1): the key light is ~10–11
// units from the shapes, so Il/(d+K) ≈ 10/11 ≈ 0.9; the fill gives ≈ 4/12 ≈ 0.33. A surface facing
// the key gets about 0.9·Kd + Ka (0.75 → 0.79), the tops of the shapes ≈ 0.65·Kd + Ka, so the
// shapes average ≈ 0.3 and only specular highlights reach 1.
constexpr std::string_view kPrimitives = R"json({
  "image":  { "width": 800, "height": 600, "background": [0.05, 0.05, 0.08] },
  "camera": { "projection": "orthographic", "position": [0, 4, 10], "look_at": [0, 0.6, 0],
              "up": [0, 1, 0], "view_height": 5.5 },
  "render": { "pipeline": "zbuffer", "model": "phong", "tessellation": 64 },
  "ambient": 1.0,
  "attenuation_k": 1.0,
  "lights": [
    { "position": [-5, 8, 7], "intensity": 10 },
    { "position": [6, 4, 8],  "intensity": 4 }
  ],
  "materials": {
    "floor":  { "ka": [0.08, 0.08, 0.08], "kd": [0.55, 0.55, 0.55], "ks": 0.05, "n": 4,
                "checker": { "size": 1, "ka": [0.05, 0.05, 0.055], "kd": [0.36, 0.36, 0.4] } },
    "blue":   { "ka": [0.02, 0.045, 0.11], "kd": [0.15, 0.3, 0.75], "ks": 0.5, "n": 30 },
    "yellow": { "ka": [0.11, 0.09, 0.02], "kd": [0.75, 0.6, 0.15], "ks": 0.4, "n": 25 },
    "jade":   { "ka": [0.02, 0.09, 0.045], "kd": [0.15, 0.6, 0.3], "ks": 0.5, "n": 50 }
  },
  "objects": [
    { "type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": "floor" },
    { "type": "sphere", "center": [-2.9, 0.55, 0], "radius": 0.55, "material": "plastico" },
    { "type": "box", "min": [-0.45, 0, -0.45], "max": [0.45, 0.9, 0.45], "material": "madeira",
      "transform": { "rotate": [0, 30, 0], "translate": [-1.45, 0, 0] } },
    { "type": "cylinder", "base": [0, 0, 0], "axis": [0, 1, 0], "radius": 0.45, "height": 1.1,
      "caps": true, "material": "blue" },
    { "type": "cone", "base": [1.45, 0, 0], "axis": [0, 1, 0], "radius": 0.5, "height": 1.2,
      "cap": true, "material": "yellow" },
    { "type": "torus", "center": [2.9, 0.47, 0], "axis": [0, 1, 1], "major_radius": 0.45,
      "minor_radius": 0.15, "material": "jade" }
  ]
})json";

// Whitted's classic picture: a mirror sphere and a glass sphere over a red and yellow
// checkered floor, two lights, perspective, ray traced to depth 5. The key light is ~8 units
// from the spheres (Il/(d+K) ≈ 7/9 ≈ 0.8 on Kd ≈ 0.8); the sky-blue background is what
// the mirror and the glass mostly show.
constexpr std::string_view kWhitted = R"json({
  "image":  { "width": 800, "height": 600, "background": [0.35, 0.55, 0.85] },
  "camera": { "projection": "perspective", "position": [0, 1.7, 7], "look_at": [0, 0.9, 0],
              "up": [0, 1, 0], "fov_y": 40 },
  "render": { "pipeline": "raytrace", "model": "phong", "max_depth": 5 },
  "ambient": 1.0,
  "attenuation_k": 1.0,
  "lights": [
    { "position": [-4, 6, 5], "intensity": 7 },
    { "position": [5, 4, 2],  "intensity": 2.5 }
  ],
  "materials": {
    "floor":  { "ka": [0.1, 0.09, 0.02], "kd": [0.85, 0.75, 0.15], "ks": 0, "n": 1,
                "checker": { "size": 1, "ka": [0.1, 0.02, 0.015], "kd": [0.8, 0.12, 0.08] } },
    "mirror": { "preset": "metal_polido", "reflection": 0.8 },
    "glass":  { "preset": "vidro" }
  },
  "objects": [
    { "type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": "floor" },
    { "type": "sphere", "center": [-0.9, 1.0, -1.0], "radius": 1.0, "material": "mirror" },
    { "type": "sphere", "center": [0.9, 0.75, 1.0], "radius": 0.75, "material": "glass" }
  ]
})json";

// The eleven presets side by side, as spheres over a grey floor, ray traced so the metals
// reflect and the water and glass refract: the picture behind `luz materials`. The lecture's
// eight in two rows; behind them, between their spheres, the three metals whose w(i, λ) is
// Schlick's curve (docs/SCENES.md#reflectance).
constexpr std::string_view kMaterials = R"json({
  "image":  { "width": 800, "height": 400, "background": [0.3, 0.4, 0.55] },
  "camera": { "projection": "perspective", "position": [0, 5, 8.5], "look_at": [0, 0.4, -0.6],
              "up": [0, 1, 0], "fov_y": 32 },
  "render": { "pipeline": "raytrace", "model": "phong", "max_depth": 5 },
  "lights": [
    { "position": [-5, 7, 6], "intensity": 8 },
    { "position": [6, 5, 4],  "intensity": 3 }
  ],
  "materials": {
    "floor": { "ka": 0.06, "kd": 0.5, "ks": 0, "n": 1,
               "checker": { "size": 1, "ka": 0.04, "kd": 0.35 } }
  },
  "objects": [
    { "type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": "floor" },
    { "type": "sphere", "center": [-3.3, 0.7, -1.5], "radius": 0.7, "material": "gesso" },
    { "type": "sphere", "center": [-1.1, 0.7, -1.5], "radius": 0.7, "material": "madeira" },
    { "type": "sphere", "center": [1.1, 0.7, -1.5], "radius": 0.7, "material": "concreto" },
    { "type": "sphere", "center": [3.3, 0.7, -1.5], "radius": 0.7, "material": "cortica" },
    { "type": "sphere", "center": [-3.3, 0.7, 1.3], "radius": 0.7, "material": "plastico" },
    { "type": "sphere", "center": [-1.1, 0.7, 1.3], "radius": 0.7, "material": "metal_polido" },
    { "type": "sphere", "center": [1.1, 0.7, 1.3], "radius": 0.7, "material": "agua" },
    { "type": "sphere", "center": [3.3, 0.7, 1.3], "radius": 0.7, "material": "vidro" },
    { "type": "sphere", "center": [-2.2, 0.7, -4.3], "radius": 0.7, "material": "ouro" },
    { "type": "sphere", "center": [0, 0.7, -4.3], "radius": 0.7, "material": "prata" },
    { "type": "sphere", "center": [2.2, 0.7, -4.3], "radius": 0.7, "material": "cobre" }
  ]
})json";

// The Stanford bunny (scenes/bunny.obj, 3674 triangles, compiled into luz) in glass, between
// the primitives of the practical assignment and a polished metal sphere, ray traced: the
// mesh refracts the checkered floor and shows in the metal. Exposure as demo:primitives.
constexpr std::string_view kBunny = R"json({
  "image":  { "width": 800, "height": 600, "background": [0.3, 0.4, 0.55] },
  "camera": { "projection": "perspective", "position": [0, 3.2, 7.5], "look_at": [0, 0.7, 0],
              "up": [0, 1, 0], "fov_y": 38 },
  "render": { "pipeline": "raytrace", "model": "phong", "max_depth": 6 },
  "lights": [
    { "position": [-5, 8, 7], "intensity": 10 },
    { "position": [6, 4, 8],  "intensity": 4 }
  ],
  "materials": {
    "floor":  { "ka": [0.08, 0.08, 0.08], "kd": [0.55, 0.55, 0.55], "ks": 0.05, "n": 4,
                "checker": { "size": 1, "ka": [0.05, 0.05, 0.055], "kd": [0.3, 0.3, 0.34] } },
    "blue":   { "ka": [0.02, 0.045, 0.11], "kd": [0.15, 0.3, 0.75], "ks": 0.5, "n": 30 },
    "yellow": { "ka": [0.11, 0.09, 0.02], "kd": [0.75, 0.6, 0.15], "ks": 0.4, "n": 25 },
    "jade":   { "ka": [0.02, 0.09, 0.045], "kd": [0.15, 0.6, 0.3], "ks": 0.5, "n": 50 },
    "mirror": { "preset": "metal_polido", "reflection": 0.8 }
  },
  "objects": [
    { "type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": "floor" },
    { "type": "mesh", "file": "bunny.obj", "smooth": true, "material": "vidro",
      "transform": { "scale": 0.17, "rotate": [0, 20, 0], "translate": [0, 0, 0.6] } },
    { "type": "sphere", "center": [-1.6, 0.9, -1.6], "radius": 0.9, "material": "mirror" },
    { "type": "sphere", "center": [-2.9, 0.45, 0.6], "radius": 0.45, "material": "plastico" },
    { "type": "box", "min": [-0.4, 0, -0.4], "max": [0.4, 0.8, 0.4], "material": "madeira",
      "transform": { "rotate": [0, 30, 0], "translate": [1.3, 0, -1.8] } },
    { "type": "cylinder", "base": [2.9, 0, -0.4], "axis": [0, 1, 0], "radius": 0.4, "height": 1.0,
      "caps": true, "material": "blue" },
    { "type": "cone", "base": [2.2, 0, 1.3], "axis": [0, 1, 0], "radius": 0.45, "height": 1.1,
      "cap": true, "material": "yellow" },
    { "type": "torus", "center": [-1.9, 0.4, 1.9], "axis": [0, 1, 1], "major_radius": 0.4,
      "minor_radius": 0.13, "material": "jade" }
  ]
})json";

// The lecture's Phong highlight Ks·cos(α)^n as an animation (48 frames, 2 s at 24 fps): the
// exponent n grows from 1 (a broad sheen over the whole lit side) to 200 (a small sharp spot),
// keyed nearly geometrically since the look changes most at small n, while the light sweeps
// from the left to the right, so the highlight narrows and follows it. Exposure: the light is
// ≈ 8 units from the sphere, Il/(d+K) ≈ 10/9 ≈ 1.1, so the lit side is ≈ Kd·cos θ + Ks·cos(α)^n +
// Ka, up to ≈ 1 in red.
constexpr std::string_view kHighlight = R"json({
  "image":  { "width": 640, "height": 480, "background": [0.05, 0.05, 0.08] },
  "camera": { "projection": "perspective", "position": [0, 1.6, 6], "look_at": [0, 0.9, 0],
              "up": [0, 1, 0], "fov_y": 32 },
  "render": { "pipeline": "raycast", "model": "phong" },
  "lights": [ { "position": [-6, 5, 5], "intensity": 10 } ],
  "materials": {
    "floor":  { "ka": [0.06, 0.06, 0.06], "kd": [0.5, 0.5, 0.5], "ks": 0.05, "n": 4,
                "checker": { "size": 1, "ka": [0.04, 0.04, 0.045], "kd": [0.25, 0.25, 0.28] } },
    "red":    { "ka": [0.08, 0.015, 0.015], "kd": [0.5, 0.07, 0.07], "ks": 0.35, "n": 1 }
  },
  "objects": [
    { "type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": "floor" },
    { "type": "sphere", "center": [0, 1, 0], "radius": 1, "material": "red" }
  ],
  "animation": {
    "frames": 48, "fps": 24,
    "keys": {
      "materials.red.n": [[0, 1], [12, 5], [24, 20], [36, 60], [47, 200]],
      "lights.0.position": [[0, [-6, 5, 5]], [47, [6, 5, 5]]]
    }
  }
})json";

constexpr DemoScene kDemos[] = {
    {"primitives",
     "the practical assignment: sphere, cube, cylinder, cone and torus on a floor (zbuffer)",
     kPrimitives},
    {"whitted", "Whitted's mirror and glass spheres over a checkered floor (raytrace)", kWhitted},
    {"materials",
     "the eleven presets as spheres: ouro, prata, cobre (back, Schlick's reflectance); gesso, "
     "madeira, concreto, cortica (middle); plastico, metal_polido, agua, vidro (front) "
     "(raytrace)",
     kMaterials},
    {"bunny",
     "the Stanford bunny in glass among the primitives and a metal sphere (raytrace, a mesh)",
     kBunny},
    {"highlight",
     "an animation (48 frames): Phong's exponent n from 1 to 200 on a red sphere while the "
     "light sweeps from left to right (raycast; luz render demo:highlight --frames all)",
     kHighlight},
};

}  // namespace

std::span<const DemoScene> demo_scenes() { return kDemos; }

const DemoScene* find_demo(std::string_view name) {
    for (const DemoScene& d : kDemos) {
        if (d.name == name) return &d;
    }
    return nullptr;
}

}  // namespace luz
