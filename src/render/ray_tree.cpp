// The ray tree of one pixel: RayTracer::trace with recording, for the viewer's inspector.
#include "render/ray_tree.h"

#include "render/ray_tracer.h"

namespace luz {

RayTree trace_ray_tree(const BuiltScene& scene, const Settings& settings, float px, float py) {
    const bool full = settings.render.pipeline == Pipeline::raytrace;
    const RayTracer tracer(scene, settings, full);
    RayTree tree;
    tree.raycast_for_zbuffer = settings.render.pipeline == Pipeline::zbuffer;
    TraceCounters counters;
    float distance;
    tracer.trace(tracer.camera().ray(px, py), 0, counters, distance, &tree);
    return tree;
}

}  // namespace luz
