// The public render() and ray_tree(): a built Scene with any Settings (include/luz/render.h).
#include "luz/render.h"

#include <string>

#include "geometry/scene.h"

namespace luz {

namespace {

/// The settings must name every material the scene's objects use.
void check_fits(const Scene& scene, const Settings& settings) {
    if (settings.materials.size() < scene.material_count()) {
        throw SceneError("settings: materials: the scene's objects use " +
                         std::to_string(scene.material_count()) + " materials, got " +
                         std::to_string(settings.materials.size()));
    }
}

}  // namespace

Frame render(const Scene& scene, const Settings& settings, const RenderOptions& options) {
    check_fits(scene, settings);
    scene.prepare(settings.render.pipeline);
    Frame frame;
    RenderControl control = options.control;
    control.aa_mask = options.want_aa_mask ? &frame.aa_mask : nullptr;
    // The per-term images asked for, each once, in the order asked; the pipelines fill them.
    TermPlanes planes;
    for (AovKind kind : options.aovs) {
        bool seen = false;
        for (const Aov& a : frame.aovs) seen = seen || a.kind == kind;
        if (!seen) {
            frame.aovs.push_back(
                Aov{kind, aov_name(kind), Image(settings.image.width, settings.image.height)});
        }
    }
    for (Aov& a : frame.aovs) planes.plane[static_cast<int>(a.kind)] = &a.image;
    control.terms = planes.any() ? &planes : nullptr;
    frame.image = render(scene.built(), settings, control, frame.stats);
    frame.complete = !(control.cancel && control.cancel->load());
    return frame;
}

RayTree ray_tree(const Scene& scene, const Settings& settings, float px, float py) {
    check_fits(scene, settings);
    scene.prepare(settings.render.pipeline == Pipeline::zbuffer ? Pipeline::raycast
                                                                : settings.render.pipeline);
    return trace_ray_tree(scene.built(), settings, px, py);
}

}  // namespace luz
