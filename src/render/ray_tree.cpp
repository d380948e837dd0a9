// The ray tree of one pixel: trace() observed by a RayTreeRecorder, for the viewer's inspector.
#include "render/ray_tree.h"

#include "render/whitted.h"

namespace luz {

void RayTreeRecorder::ray(const Ray& ray, int depth) {
    int self = -1;
    if (tree_.nodes.size() < kRayTreeMaxNodes) {
        self = static_cast<int>(tree_.nodes.size());
        RayTreeNode& n = tree_.nodes.emplace_back();
        n.depth = depth;
        n.origin = ray.origin;
        n.direction = ray.direction;
    } else {
        tree_.truncated = true;  // traced in full, not recorded
    }
    open_.push_back(self);
}

void RayTreeRecorder::found(float t, RayHit hit, int light) {
    if (open_.back() < 0) return;
    RayTreeNode& n = tree_.nodes[open_.back()];
    n.t = t;
    n.hit = hit;
    n.light = light;
}

ShadeTerms* RayTreeRecorder::terms() {
    if (open_.back() < 0) return nullptr;
    RayTreeNode& n = tree_.nodes[open_.back()];
    n.lights.resize(lights_);
    terms_.light = n.lights;
    return &terms_;
}

void RayTreeRecorder::shaded(const Hit& hit, int material, const SurfacePoint& sp,
                             const ShadeTerms* terms, const Rgb& local) {
    if (open_.back() < 0) return;
    RayTreeNode& n = tree_.nodes[open_.back()];
    n.object = static_cast<int>(hit.shape);
    n.material = material;
    n.P = sp.P;
    n.N = sp.N;
    n.ambient = terms->ambient;
    n.flipped = terms->flipped;
    n.local = local;
}

void RayTreeRecorder::bounced(const Bounce& b) {
    if (open_.back() >= 0) tree_.nodes[open_.back()].total_internal_reflection = b.tir;
}

void RayTreeRecorder::secondary(RayKind kind, float coefficient, const Rgb& returned, float A,
                                const Rgb& contribution) {
    const int self = open_.back(), child = last_;
    if (self < 0 || child < 0) return;  // beyond the recording cap
    RayTreeNode& n = tree_.nodes[child];
    n.kind = kind;
    n.parent = self;
    n.returned = returned;
    n.A = A;
    n.coefficient = coefficient;
    n.contribution = contribution;
    (kind == RayKind::reflection ? tree_.nodes[self].reflection_child
                                 : tree_.nodes[self].refraction_child) = child;
}

Rgb RayTreeRecorder::done(const Rgb& c) {
    last_ = open_.back();
    open_.pop_back();
    if (last_ >= 0) tree_.nodes[last_].colour = c;
    return c;
}

RayTree trace_ray_tree(const BuiltScene& scene, const Settings& settings, float px, float py) {
    const Whitted tracer(scene, settings, settings.render.pipeline == Pipeline::raytrace);
    RayTree tree;
    tree.raycast_for_zbuffer = settings.render.pipeline == Pipeline::zbuffer;
    RayTreeRecorder recorder(tree, settings.lights.size());
    TraceCounters counters;
    float distance;
    tracer.trace(tracer.camera().ray(px, py), 0, 1.0f, counters, distance, recorder);
    return tree;
}

}  // namespace luz
