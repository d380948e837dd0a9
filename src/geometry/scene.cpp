// build_scene: the runtime scene, one Shape per object of a validated SceneDesc, and the BVH
// over its bounded shapes and mesh triangles.
#include "geometry/scene.h"

#include <chrono>
#include <utility>

#include "geometry/query_parts.h"

namespace luz {

BuiltScene build_scene(const SceneDesc& desc) {
    BuiltScene scene;
    scene.geometry = desc.geometry;
    scene.material_count = desc.materials.size();
    scene.shapes.reserve(desc.objects.size());
    for (size_t i = 0; i < desc.objects.size(); ++i) {
        scene.shapes.push_back(make_shape(desc.objects[i], static_cast<int>(i)));
        scene.bounds.push_back(bounds(scene.shapes.back()));
        if (const auto& m = scene.shapes.back().mesh) scene.mesh_triangles += m->triangle_count();
    }
    if (desc.geometry.accel == Accel::bvh && desc.render.pipeline != Pipeline::zbuffer) {
        build_bvh(scene);
    }
    return scene;
}

void build_bvh(BuiltScene& scene) {
    const auto start = std::chrono::steady_clock::now();
    // The primitives: every bounded shape, except that a mesh gives its triangles instead.
    std::vector<BvhPrim> prims;
    std::vector<Bounds3> boxes;
    prims.reserve(scene.shapes.size() + scene.mesh_triangles);
    boxes.reserve(prims.capacity());
    scene.unbounded.clear();
    for (size_t i = 0; i < scene.shapes.size(); ++i) {
        const Shape& s = scene.shapes[i];
        const uint32_t shape = static_cast<uint32_t>(i);
        if (!is_bounded(s)) {
            scene.unbounded.push_back(shape);
        } else if (s.mesh) {
            for (size_t t = 0; t < s.mesh->triangle_count(); ++t) {
                BvhPrim p{{}, {}, {}, shape, static_cast<uint32_t>(t)};
                s.mesh->vertices(t, p.p0, p.p1, p.p2);
                Bounds3 b;
                b.expand(p.p0);
                b.expand(p.p1);
                b.expand(p.p2);
                prims.push_back(p);
                boxes.push_back(b);
            }
        } else {
            prims.push_back({{}, {}, {}, shape, BvhPrim::kNotTriangle});
            boxes.push_back(scene.bounds[i]);
        }
    }
    scene.bvh = Bvh8::build(boxes);
    // Primitives in leaf order (those with empty bounds, never hit, are left out); the order
    // itself is not kept: slot i is bvh_prims[i].
    const std::vector<uint32_t> order = scene.bvh.take_order();
    std::vector<BvhPrim> in_order;
    in_order.reserve(order.size());
    for (uint32_t id : order) in_order.push_back(prims[id]);
    scene.bvh_prims = std::move(in_order);
    scene.has_bvh = true;
    query::prepare_direct(scene);
    scene.bvh_build_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace luz
