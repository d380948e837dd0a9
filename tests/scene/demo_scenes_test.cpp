// Tests of the built-in scenes: they parse, demo:primitives has its five shapes on a floor,
// in view and apart, and its exposure computed by hand (docs/SCENES.md#models model 2) is
// reasonable.
#include "scene/demo_scenes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "scene/presets.h"
#include "scene/scene_loader.h"

namespace luz {
namespace {

TEST(DemoScenes, AllParse) {
    ASSERT_FALSE(demo_scenes().empty());
    for (const DemoScene& d : demo_scenes()) {
        SCOPED_TRACE(std::string(d.name));
        EXPECT_EQ(find_demo(d.name), &d);
        EXPECT_FALSE(d.description.empty());
        const SceneDesc s = load_scene("demo:" + std::string(d.name));
        EXPECT_EQ(s.name, d.name);
        EXPECT_FALSE(s.objects.empty());
    }
    EXPECT_EQ(find_demo("nothing"), nullptr);
}

TEST(DemoScenes, PrimitivesIsThePracticalAssignment) {
    const SceneDesc s = load_scene("demo:primitives");
    EXPECT_EQ(s.render.pipeline, Pipeline::zbuffer);
    EXPECT_EQ(s.render.model, Model::phong);
    EXPECT_EQ(s.camera.projection, Projection::orthographic);
    EXPECT_EQ(s.image.width, 800);
    EXPECT_EQ(s.image.height, 600);
    EXPECT_EQ(s.lights.size(), 2u);
    std::multiset<ShapeType> types;
    std::set<int> materials;
    for (const ObjectDesc& o : s.objects) {
        types.insert(o.type);
        materials.insert(o.material);
    }
    for (ShapeType t : {ShapeType::sphere, ShapeType::box, ShapeType::cylinder, ShapeType::cone,
                        ShapeType::torus, ShapeType::plane}) {
        EXPECT_EQ(types.count(t), 1u);
    }
    EXPECT_EQ(materials.size(), s.objects.size());  // each with its own material
    EXPECT_EQ(materials.count(0), 0u);              // and none left at the default
}

/// Lowest and highest x of an object (the camera's u is +x in demo:primitives).
std::pair<float, float> x_extent(const ObjectDesc& o) {
    switch (o.type) {
        case ShapeType::sphere:
            return {o.center.x - o.radius, o.center.x + o.radius};
        case ShapeType::cylinder:
        case ShapeType::cone:
            return {o.base.x - o.radius, o.base.x + o.radius};
        case ShapeType::torus: {
            const float r = o.major_radius + o.minor_radius;
            return {o.center.x - r, o.center.x + r};
        }
        case ShapeType::box: {
            float lo = 1e30f, hi = -1e30f;
            for (int i = 0; i < 8; ++i) {
                const Vec3 c{(i & 1) ? o.max.x : o.min.x, (i & 2) ? o.max.y : o.min.y,
                             (i & 4) ? o.max.z : o.min.z};
                const float x = o.transform.point(c).x;
                lo = std::min(lo, x);
                hi = std::max(hi, x);
            }
            return {lo, hi};
        }
        default:
            return {0, 0};
    }
}

/// The top of an object (its highest point on the axis above its base or centre).
Vec3 top_of(const ObjectDesc& o) {
    switch (o.type) {
        case ShapeType::sphere:
            return o.center + Vec3{0, o.radius, 0};
        case ShapeType::cylinder:
        case ShapeType::cone:
            return o.base + normalize(o.axis) * o.height;
        case ShapeType::torus:
            return o.center + Vec3{0, o.minor_radius, 0};
        case ShapeType::box:
            return o.transform.point({0, o.max.y, 0});
        default:
            return {};
    }
}

TEST(DemoScenes, PrimitivesShapesAreInViewAndApart) {
    const SceneDesc s = load_scene("demo:primitives");
    ASSERT_EQ(s.camera.look_at.x, s.camera.position.x);  // u = +x
    const float half_w = s.camera.view_height * s.image.width / s.image.height / 2;
    const float half_h = s.camera.view_height / 2;
    const Vec3 w = normalize(s.camera.position - s.camera.look_at);
    const Vec3 v = cross(w, normalize(cross(s.camera.up, w)));
    std::vector<std::pair<float, float>> spans;
    for (const ObjectDesc& o : s.objects) {
        if (o.type == ShapeType::plane) continue;
        const auto [lo, hi] = x_extent(o);
        EXPECT_GT(lo, -half_w + 0.1f) << o.path;
        EXPECT_LT(hi, half_w - 0.1f) << o.path;
        const float y = dot(top_of(o) - s.camera.look_at, v);
        EXPECT_LT(y, half_h - 0.1f) << o.path;
        spans.push_back({lo, hi});
    }
    std::sort(spans.begin(), spans.end());
    for (std::size_t i = 1; i < spans.size(); ++i) {
        EXPECT_GT(spans[i].first, spans[i - 1].second + 0.1f) << "overlap in the picture";
    }
}

TEST(DemoScenes, PrimitivesExposureByHand) {
    // At the top of each shape (N = +y) and on its side facing the camera (N = w):
    // I = Ia·Ka + Σ Il/(d+K)·Kd·cosθ (docs/SCENES.md#models model 2 without the specular term).
    const SceneDesc s = load_scene("demo:primitives");
    const Vec3 w = normalize(s.camera.position - s.camera.look_at);
    for (const ObjectDesc& o : s.objects) {
        if (o.type == ShapeType::plane) continue;
        const Material& m = s.materials[o.material];
        for (const Vec3 N : {Vec3{0, 1, 0}, w}) {
            const Vec3 P = top_of(o);
            Rgb I = s.ambient * m.ka;
            for (const Light& l : s.lights) {
                const float d = length(l.position - P);
                const float cos_theta = std::max(0.0f, dot(N, (l.position - P) / d));
                I += l.intensity * (1.0f / (d + s.attenuation_k)) * m.kd * cos_theta;
            }
            SCOPED_TRACE(o.path);
            EXPECT_LT(max_component(I), 0.97f);       // not clipped
            EXPECT_GT((I.x + I.y + I.z) / 3, 0.15f);  // not dark
            EXPECT_GT(max_component(I), 0.35f);       // its colour reads clearly
        }
    }
}

TEST(DemoScenes, MaterialsShowsEveryPresetInView) {
    // demo:materials is the presets sheet: one sphere per preset (the lecture's eight and the
    // three metals), each wholly inside the picture (docs/SCENES.md#geometry's perspective camera).
    const SceneDesc s = load_scene("demo:materials");
    const CameraDesc& c = s.camera;
    ASSERT_EQ(c.projection, Projection::perspective);
    const Vec3 w = normalize(c.position - c.look_at);
    const Vec3 u = normalize(cross(c.up, w));
    const Vec3 v = cross(w, u);
    const float tan_half = std::tan(c.fov_y * 3.14159265f / 360);
    const float aspect = float(s.image.width) / float(s.image.height);
    std::set<std::string> shown;
    for (const ObjectDesc& o : s.objects) {
        if (o.type != ShapeType::sphere) continue;
        shown.insert(s.materials[o.material].name);
        SCOPED_TRACE(o.path);
        for (const Vec3 edge : {u, -u, v, -v}) {
            const Vec3 d = o.center + edge * o.radius - c.position;
            const float depth = -dot(d, w);
            ASSERT_GT(depth, 0);
            EXPECT_LT(std::abs(dot(d, u) / (depth * tan_half * aspect)), 0.98f);
            EXPECT_LT(std::abs(dot(d, v) / (depth * tan_half)), 0.98f);
        }
    }
    for (const Preset& p : presets()) EXPECT_EQ(shown.count(std::string(p.name)), 1u) << p.name;
    EXPECT_EQ(shown.size(), presets().size());
}

}  // namespace
}  // namespace luz
