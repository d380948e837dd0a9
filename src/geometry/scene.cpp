// build_scene: the runtime scene, one Shape per object of a validated SceneDesc.
#include "geometry/scene.h"

#include <utility>

namespace luz {

Scene build_scene(SceneDesc desc) {
    Scene scene;
    scene.shapes.reserve(desc.objects.size());
    for (size_t i = 0; i < desc.objects.size(); ++i) {
        scene.shapes.push_back(make_shape(desc.objects[i], static_cast<int>(i)));
        scene.bounds.push_back(bounds(scene.shapes.back()));
    }
    scene.desc = std::move(desc);
    return scene;
}

}  // namespace luz
