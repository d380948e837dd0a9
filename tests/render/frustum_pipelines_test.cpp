// Truncated cones (docs/SCENES.md#scene-files: a cone's apex_radius) through every pipeline:
// raycast and zbuffer agree on a frustum scene as they do on demo:primitives, and apex_radius 0 is
// the full cone.
#include <gtest/gtest.h>

#include <string>

#include "image/compare.h"
#include "render/render.h"
#include "scene/scene_loader.h"

namespace luz {
namespace {

// Closed and open frustums, upright, tilted and squashed by a non-uniform transform; the open
// ones are seen from above so that their inside wall shows through the top hole.
constexpr const char* kFrustums = R"json({
  "image": { "width": 160, "height": 120, "background": [0.1, 0.1, 0.15] },
  "camera": { "projection": "perspective", "position": [0, 4, 6], "look_at": [0, 0.5, 0],
              "up": [0, 1, 0], "fov_y": 45 },
  "render": { "pipeline": "zbuffer", "model": "phong", "tessellation": 512 },
  "lights": [ { "position": [3, 6, 4], "intensity": 6 } ],
  "objects": [
    { "type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0] },
    { "type": "cone", "base": [-1.6, 0, 0], "axis": [0, 1, 0], "radius": 0.7, "height": 1.2,
      "apex_radius": 0.3, "cap": true },
    { "type": "cone", "base": [0, 0, 0.3], "axis": [0, 1, 0], "radius": 0.6, "height": 1.0,
      "apex_radius": 0.45, "cap": false },
    { "type": "cone", "base": [1.6, 0.6, 0], "axis": [1, 1, 0.5], "radius": 0.5, "height": 1.0,
      "apex_radius": 0.2, "cap": true,
      "transform": { "scale": [1, 0.7, 1.3], "rotate": [0, 20, 0] } }
  ]
})json";

Image render_with(const std::string& text, Pipeline p) {
    SceneDesc d = parse_scene(text, "frustums.json", "");
    d.render.pipeline = p;
    RenderStats stats;
    return render(build_scene(d), d, RenderControl{}, stats);
}

TEST(Frustum, RaycastEqualsZbufferUpToTessellation) {
    // As Pipelines.RaycastEqualsZbufferUpToTessellation: at least 99 % of pixels within 2/255.
    const Image zb = render_with(kFrustums, Pipeline::zbuffer);
    const Image rc = render_with(kFrustums, Pipeline::raycast);
    const double share = fraction_within(zb, rc, 2.0f / 255);
    EXPECT_GE(share, 0.99);
    RecordProperty("share_within_2_255", std::to_string(share));
    // and the frustums are in the picture: it differs from the floor alone
    const SceneDesc d = parse_scene(kFrustums, "frustums.json", "");
    SceneDesc bare = d;
    bare.objects.resize(1);
    RenderStats stats;
    const Image floor = render(build_scene(bare), bare, RenderControl{}, stats);
    EXPECT_LT(fraction_within(floor, rc, 2.0f / 255), 0.95);
}

TEST(Frustum, ApexRadiusZeroIsTheFullCone) {
    // The same cone with and without "apex_radius": 0 gives the same bits in every pipeline.
    const std::string with = R"json({
      "image": { "width": 64, "height": 48 },
      "objects": [ { "type": "cone", "radius": 0.8, "height": 1.5, "apex_radius": 0 } ] })json";
    std::string without = with;
    without.erase(without.find(", \"apex_radius\": 0"), std::string(", \"apex_radius\": 0").size());
    for (Pipeline p : {Pipeline::zbuffer, Pipeline::raycast, Pipeline::raytrace}) {
        const Image a = render_with(with, p), b = render_with(without, p);
        EXPECT_TRUE(a.pixels == b.pixels) << static_cast<int>(p);
    }
}

}  // namespace
}  // namespace luz
