// Ray queries on a whole scene: the nearest hit (camera, reflected and refracted rays) and the
// transmittance of a segment (shadow rays). With render.accel = bvh they traverse the scene's
// BVH (planes apart), except in a scene of at most 8 shapes and no mesh (BuiltScene::direct), whose
// shapes are tested in order, spheres four at a time; with none every shape, and every mesh
// triangle, is tested.
//
// Shooting rays at one mesh directly (e.g. a benchmark):
//     std::vector<std::string> warnings;
//     SceneDesc d;
//     d.render.pipeline = Pipeline::raytrace;  // build_scene() builds the BVH for ray pipelines
//     d.materials.resize(1);
//     ObjectDesc o;
//     o.type = ShapeType::mesh;
//     o.mesh = std::make_shared<const MeshData>(load_obj("big.obj", false, warnings));
//     d.objects = {o};
//     const BuiltScene scene = build_scene(d);      // scene.bvh_build_seconds, scene.bvh_bytes()
//     IntersectCounters counters;
//     Hit hit;
//     if (nearest_hit(scene, ray, 0.0f, inf, hit, counters)) { /* hit.t, hit.part = triangle */ }
// or use Bvh (bvh.h) alone over any primitives' boxes.
#pragma once

#include <cstdint>
#include <vector>

#include "geometry/intersect.h"
#include "geometry/scene.h"

namespace luz {

/// Intersection tests counted by the queries (per thread; summed at the end), and the time
/// spent in the queries while `timing` is set (the ray tracer sets it for a sample of rays).
/// The materials a render uses, indexed by Shape::material (Settings::materials).
using Materials = std::vector<Material>;

struct IntersectCounters {
    uint64_t primitive = 0;  ///< ray–shape and ray–triangle tests
    uint64_t bounds = 0;     ///< ray–box tests (object bounds, BVH nodes)
    bool timing = false;     ///< measure the time spent in nearest_hit and transmittance
    uint64_t query_ns = 0;   ///< nanoseconds spent in them while timing
};

/// Whether ray r meets box b in (t_min, t_max) (slab test; inv_dir = 1/direction).
bool hit_bounds(const Bounds3& b, const Ray& r, const Vec3& inv_dir, float t_min, float t_max);

/// The nearest hit of r among the scene's shapes in (t_min, t_max); hit.shape is its index
/// (hit.part the triangle for a mesh). Ties in t go to the lowest shape, then triangle, so
/// that the BVH and testing everything give the very same hit.
bool nearest_hit(const BuiltScene& scene, const Ray& r, float t_min, float t_max, Hit& hit,
                 IntersectCounters& counters);

/// The product of `transparency` over every surface r crosses in (t_min, t_max): 1 if none,
/// 0 as soon as an opaque one is met (SPEC §1: vis_j; a closed glass shape counts twice). The
/// crossings are counted per material and multiplied in material order, so the result does
/// not depend on the order they are found in (up to 32 transparent materials per segment).
/// `materials` are the render's (Settings::materials): their `transparency` decides.
float transmittance(const BuiltScene& scene, const Materials& materials, const Ray& r, float t_min,
                    float t_max, IntersectCounters& counters);

}  // namespace luz
