// The zbuffer pipeline against closed forms: per-pixel shading of an analytic sphere and a
// perspective floor, watertight rasterization, near clipping, light spheres, determinism.
#include "render/zbuffer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "render/render.h"
#include "scene/camera.h"
#include "shading/shade.h"

namespace luz {
namespace {

constexpr float kOne255 = 1.0f / 255.0f;

SceneDesc base_scene(int w, int h) {
    SceneDesc d;
    d.image.width = w;
    d.image.height = h;
    d.image.background = Rgb{0.0f, 0.0f, 1.0f};  // pure blue: never a shaded colour here
    d.camera.position = {0, 0, 10};
    d.camera.look_at = {0, 0, 0};
    d.camera.view_height = 2.5f;
    Material m;
    m.ks = Rgb{0.5f};
    m.n = 10;
    d.materials.push_back(m);
    return d;
}

ObjectDesc sphere(Vec3 centre, float radius) {
    ObjectDesc o;
    o.type = ShapeType::sphere;
    o.center = centre;
    o.radius = radius;
    return o;
}

Image zbuffer_render(const SceneDesc& d, int threads = 1, RenderStats* stats_out = nullptr) {
    const BuiltScene scene = build_scene(d);
    RenderStats stats;
    RenderControl control;
    control.threads = threads;
    Image img = render(scene, d, control, stats);
    if (stats_out) *stats_out = stats;
    return img;
}

bool is_background(const Rgb& c) { return c == Rgb{0.0f, 0.0f, 1.0f}; }

// docs/SCENES.md: "an orthographic sphere lit along the view axis — every covered pixel within
// 1/255 of the closed form at a fine tessellation".
TEST(Zbuffer, OrthographicSphereMatchesTheClosedFormAtEveryCoveredPixel) {
    SceneDesc d = base_scene(160, 160);
    d.geometry.tessellation = 720;
    d.lights.push_back({Vec3{0, 0, 10}, Rgb{10.0f}, 0});
    d.objects.push_back(sphere({0, 0, 0}, 1));
    const Image img = zbuffer_render(d, 2);
    const Camera cam = Camera::from(d.camera, 160, 160);
    const Material& m = d.materials[0];
    int covered = 0;
    for (int j = 0; j < 160; ++j) {
        for (int i = 0; i < 160; ++i) {
            const Ray r = cam.ray(i + 0.5f, j + 0.5f);
            const float x = r.origin.x, y = r.origin.y, rr = x * x + y * y;
            if (is_background(img.at(i, j))) {
                // Only pixels at the silhouette may be missed by the inscribed tessellation.
                EXPECT_GT(rr, 0.99f) << i << "," << j;
                continue;
            }
            ++covered;
            ASSERT_LT(rr, 1.0f) << i << "," << j;
            // Closed form: P on the unit sphere, N = P, S = (0, 0, 1), one light at (0, 0, 10).
            const Vec3 P{x, y, std::sqrt(1 - rr)};
            const Vec3 N = P, S{0, 0, 1};
            const Vec3 Lp{0, 0, 10};
            const float dist = length(Lp - P);
            const Vec3 L = (Lp - P) / dist;
            const float cos_theta = std::max(0.0f, dot(N, L));
            const Vec3 R = N * (2 * dot(N, L)) - L;
            const float cos_alpha = std::max(0.0f, dot(R, S));
            const float want = 0.1f + 10.0f / (dist + 1.0f) *
                                          (0.45f * cos_theta + 0.5f * std::pow(cos_alpha, m.n));
            ASSERT_NEAR(img.at(i, j).x, want, kOne255) << i << "," << j;
        }
    }
    // π·r² in pixels: (160/2.5)² · π ≈ 12868.
    EXPECT_NEAR(covered, 64.0 * 64.0 * std::numbers::pi, 150);
}

// A perspective floor: the plane is drawn as a quad clipped to the view and the near plane;
// perspective-correct interpolation puts every pixel's point where the camera ray meets it.
TEST(Zbuffer, PerspectiveFloorIsPerspectiveCorrectAndClipped) {
    SceneDesc d = base_scene(120, 90);
    d.camera.projection = Projection::perspective;
    d.camera.position = {0, 1, 0};
    d.camera.look_at = {0, 0.5f, -3};
    d.camera.fov_y = 60;
    d.render.model = Model::lambert;
    d.materials[0].checker = Checker{0.5f, Rgb{0.0f}, Rgb{0.9f}};
    d.lights.push_back({Vec3{1, 3, -2}, Rgb{1.0f}, 0});
    ObjectDesc floor;
    floor.type = ShapeType::plane;
    floor.point = {0, 0, 0};
    floor.normal = {0, 1, 0};
    d.objects.push_back(floor);
    const Image img = zbuffer_render(d, 2);
    const Camera cam = Camera::from(d.camera, 120, 90);
    const Lighting lighting{d.render.model, d.ambient, d.attenuation_k, d.lights};
    int floor_pixels = 0, checked = 0;
    for (int j = 0; j < 90; ++j) {
        for (int i = 0; i < 120; ++i) {
            const Ray r = cam.ray(i + 0.5f, j + 0.5f);
            const float t = r.direction.y < 0 ? -r.origin.y / r.direction.y : -1;
            if (t <= 0 || t > 1000) {
                EXPECT_TRUE(is_background(img.at(i, j))) << i << "," << j;
                continue;
            }
            ++floor_pixels;
            const Vec3 P = r.at(t);
            // Skip pixels whose point lies within 1 % of a cell of a checker edge.
            const float fx = P.x / 0.5f - std::floor(P.x / 0.5f);
            const float fz = P.z / 0.5f - std::floor(P.z / 0.5f);
            if (fx < 0.01f || fx > 0.99f || fz < 0.01f || fz > 0.99f || t > 50) continue;
            const ShadingPoint p{P, {0, 1, 0}, {0, 1, 0}, -r.direction, &d.materials[0]};
            const Rgb want = shade(p, lighting, AllVisible{});
            ++checked;
            ASSERT_NEAR(img.at(i, j).y, want.y, kOne255) << i << "," << j << " t=" << t;
        }
    }
    EXPECT_GT(floor_pixels, 120 * 40);
    EXPECT_GT(checked, 120 * 30);
}

// A checkered floor seen obliquely in orthographic projection: every pixel's checker cell is
// the one the camera ray meets, up to 0.1 % of a cell from its edges (positions are precise
// even though the plane is drawn as a huge quad).
TEST(Zbuffer, OrthographicFloorCellsArePrecise) {
    SceneDesc d = base_scene(400, 300);
    d.camera.position = {0.3f, 4, 10};
    d.camera.look_at = {0.3f, 0.6f, 0};
    d.camera.view_height = 6;
    d.render.model = Model::lambert;
    d.materials[0].checker = Checker{1.0f, Rgb{0.0f}, Rgb{0.0f}};
    d.materials[0].ka = Rgb{1.0f};
    d.materials[0].kd = Rgb{0.0f};
    ObjectDesc floor;
    floor.type = ShapeType::plane;
    d.objects.push_back(floor);
    const Image img = zbuffer_render(d, 2);
    const Camera cam = Camera::from(d.camera, 400, 300);
    int checked = 0;
    for (int j = 0; j < 300; ++j) {
        for (int i = 0; i < 400; ++i) {
            const Ray r = cam.ray(i + 0.5f, j + 0.5f);
            const Vec3 P = r.at(-r.origin.y / r.direction.y);
            const float fx = P.x - std::floor(P.x), fz = P.z - std::floor(P.z);
            if (fx < 0.001f || fx > 0.999f || fz < 0.001f || fz > 0.999f) continue;
            const bool odd =
                (static_cast<long>(std::floor(P.x)) + static_cast<long>(std::floor(P.z)) + (-1)) &
                1;
            ++checked;
            ASSERT_EQ(img.at(i, j).x, odd ? 0.0f : 1.0f) << i << "," << j;
        }
    }
    EXPECT_GT(checked, 400 * 290);
}

TEST(Zbuffer, CoarseSphereHasNoCracks) {
    SceneDesc d = base_scene(200, 200);
    d.geometry.tessellation = 12;
    d.objects.push_back(sphere({0, 0, 0}, 1));
    const Image img = zbuffer_render(d);
    const Camera cam = Camera::from(d.camera, 200, 200);
    // Everything well inside the inscribed polygon's silhouette is covered.
    const float inner = std::cos(std::numbers::pi_v<float> / 6) - 0.05f;
    for (int j = 0; j < 200; ++j) {
        for (int i = 0; i < 200; ++i) {
            const Vec3 o = cam.ray(i + 0.5f, j + 0.5f).origin;
            if (o.x * o.x + o.y * o.y < inner * inner) {
                ASSERT_FALSE(is_background(img.at(i, j))) << i << "," << j;
            }
        }
    }
}

TEST(Zbuffer, SharedEdgesCoverEachPixelOnce) {
    // A fan of 64 thin triangles around the image centre covers a disc exactly once: with
    // additive counting by rendering each alone, every pixel's count would be 1. Here we use
    // the depth test instead: two triangles of a quad, and the nearer one decides.
    SceneDesc d = base_scene(64, 64);
    ObjectDesc a;
    a.type = ShapeType::triangle;
    a.vertices = {Vec3{-1, -1, 0}, Vec3{1, -1, 0}, Vec3{1, 1, 0}};
    ObjectDesc b = a;
    b.vertices = {Vec3{-1, -1, 0}, Vec3{1, 1, 0}, Vec3{-1, 1, 0}};
    d.objects = {a, b};
    d.camera.view_height = 2;  // the quad fills the image exactly
    const Image img = zbuffer_render(d);
    for (const Rgb& c : img.pixels) ASSERT_FALSE(is_background(c));
}

TEST(Zbuffer, OnlyWhatLiesInFrontOfTheCameraPlaneIsDrawn) {
    SceneDesc d = base_scene(40, 40);
    d.objects.push_back(sphere({0, 0, 12}, 1));  // behind the camera at z = 10
    const Image img = zbuffer_render(d);
    for (const Rgb& c : img.pixels) ASSERT_TRUE(is_background(c));
    // A sphere cut by the camera plane shows its far half only (no crash, no NaN).
    d.objects = {sphere({0, 0, 10}, 1)};
    const Image cut = zbuffer_render(d);
    int covered = 0;
    for (const Rgb& c : cut.pixels) {
        ASSERT_TRUE(is_finite(c));
        covered += !is_background(c);
    }
    EXPECT_GT(covered, 0);
}

TEST(Zbuffer, LightSpheresAreDrawnInTheLightsClampedColour) {
    SceneDesc d = base_scene(50, 50);
    d.lights.push_back({Vec3{0, 0, 0}, Rgb{3.0f, 0.5f, 0.0f}, 0.5f});
    const Image img = zbuffer_render(d);
    EXPECT_EQ(img.at(25, 25), (Rgb{1.0f, 0.5f, 0.0f}));
    EXPECT_TRUE(is_background(img.at(2, 2)));
}

TEST(Zbuffer, SameBitsForAnyThreadCount) {
    SceneDesc d = base_scene(333, 211);
    d.camera.projection = Projection::perspective;
    d.lights.push_back({Vec3{3, 4, 5}, Rgb{8.0f}, 0});
    for (int k = 0; k < 12; ++k)
        d.objects.push_back(sphere({-3.0f + 0.5f * k, 0.2f * (k % 3), -0.3f * k}, 0.6f));
    ObjectDesc floor;
    floor.type = ShapeType::plane;
    floor.point = {0, -1, 0};
    d.objects.push_back(floor);
    const Image one = zbuffer_render(d, 1);
    const Image two = zbuffer_render(d, 2);
    const Image four = zbuffer_render(d, 4);
    ASSERT_EQ(one.pixels.size(), two.pixels.size());
    EXPECT_EQ(0,
              std::memcmp(one.pixels.data(), two.pixels.data(), one.pixels.size() * sizeof(Rgb)));
    EXPECT_EQ(0,
              std::memcmp(one.pixels.data(), four.pixels.data(), one.pixels.size() * sizeof(Rgb)));
}

}  // namespace
}  // namespace luz
