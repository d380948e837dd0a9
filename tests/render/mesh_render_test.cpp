// Meshes through the pipelines: accel none and bvh give the same image bits, a mesh sphere
// looks the same through zbuffer and raycast, MTL materials reach the pixels, and the BVH's
// statistics are reported.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <numbers>

#include "geometry/scene.h"
#include "image/compare.h"
#include "render/render.h"
#include "same_bits.h"
#include "scene/scene_loader.h"

namespace luz {
namespace {

/// A UV sphere of radius r around c: `n` segments around, n/2 rings; counter-clockwise from
/// outside, with its exact normals in the file when `with_normals`.
std::shared_ptr<MeshData> uv_sphere(Vec3 c, float r, int n, bool with_normals) {
    auto d = std::make_shared<MeshData>();
    const int rings = n / 2;
    for (int j = 0; j <= rings; ++j) {
        const double th = std::numbers::pi * j / rings;
        for (int i = 0; i < n; ++i) {
            const double ph = 2 * std::numbers::pi * i / n;
            const Vec3 u{float(std::sin(th) * std::cos(ph)), float(std::cos(th)),
                         float(std::sin(th) * std::sin(ph))};
            d->positions.push_back(c + u * r);
            d->normals.push_back(u);
        }
    }
    const auto at = [n](int i, int j) { return static_cast<uint32_t>(j * n + (i % n)); };
    for (int j = 0; j < rings; ++j) {
        for (int i = 0; i < n; ++i) {
            const uint32_t a = at(i, j), b = at(i + 1, j), cc = at(i + 1, j + 1), dd = at(i, j + 1);
            // (θ down, φ around): counter-clockwise from outside is a, b, c reversed
            if (j > 0) d->position.insert(d->position.end(), {a, b, cc});
            if (j < rings - 1) d->position.insert(d->position.end(), {a, cc, dd});
        }
    }
    for (uint32_t p : d->position) d->normal.push_back(with_normals ? int32_t(p) : -1);
    d->material.assign(d->triangle_count(), -1);
    return d;
}

ObjectDesc mesh(std::shared_ptr<MeshData> d, int material, bool smooth = true) {
    ObjectDesc o;
    o.type = ShapeType::mesh;
    o.material = material;
    o.smooth = smooth;
    o.mesh = std::move(d);
    return o;
}

/// A small scene: a glass mesh sphere, a mirror mesh sphere, an analytic sphere and a floor,
/// two lights, perspective.
SceneDesc glass_and_mirror(Pipeline pipeline) {
    SceneDesc d = load_scene("demo:whitted", {{"image.width", "96"}, {"image.height", "72"}});
    d.render.pipeline = pipeline;
    ObjectDesc glass =
        mesh(uv_sphere({0.9f, 0.75f, 1.0f}, 0.75f, 48, false), d.objects[2].material);
    ObjectDesc mirror =
        mesh(uv_sphere({-0.9f, 1.0f, -1.0f}, 1.0f, 32, true), d.objects[1].material, false);
    d.objects = {d.objects[0], glass, mirror, d.objects[2]};
    d.objects[3].center = {2.2f, 0.5f, -0.5f};
    d.objects[3].radius = 0.5f;
    return d;
}

TEST(MeshRender, AccelNoneAndBvhGiveTheSameImage) {
    for (Pipeline p : {Pipeline::raytrace, Pipeline::raycast}) {
        SceneDesc d = glass_and_mirror(p);
        const BuiltScene bvh = build_scene(d);
        d.geometry.accel = Accel::none;
        const BuiltScene none = build_scene(d);
        RenderStats sb, sn;
        const Image a = render(bvh, d, {}, sb), b = render(none, d, {}, sn);
        EXPECT_TRUE(same_bits(a, b)) << to_string(compare_images(a, b));
        // the same rays, far fewer tests with the BVH
        EXPECT_EQ(sb.rays_shadow, sn.rays_shadow);
        EXPECT_EQ(sb.rays_refraction, sn.rays_refraction);
        EXPECT_LT(sb.tests_primitive * 10, sn.tests_primitive);
        EXPECT_GT(sb.bvh_nodes, 100u);
        EXPECT_EQ(sn.bvh_nodes, 0u);
        EXPECT_EQ(sb.triangles, sn.triangles);
        EXPECT_EQ(sb.triangles, bvh.mesh_triangles);
        if (p == Pipeline::raytrace) {
            EXPECT_GT(sb.rays_refraction, 0u);
        }
    }
}

TEST(MeshRender, StatisticsOfTheBvhAndOfIntersectionTime) {
    const SceneDesc d = glass_and_mirror(Pipeline::raytrace);
    const BuiltScene scene = build_scene(d);
    RenderStats s;
    render(scene, d, {}, s);
    EXPECT_EQ(s.bvh_nodes, scene.bvh.nodes().size());
    EXPECT_GE(s.bvh_bytes, s.bvh_nodes * 32 + scene.mesh_triangles * sizeof(BvhPrim));
    EXPECT_GT(s.bvh_build_seconds, 0.0);
    EXPECT_GT(s.sampled_seconds, 0.0);
    EXPECT_GT(s.intersect_sampled_seconds, 0.0);
    EXPECT_LE(s.intersect_sampled_seconds, s.sampled_seconds);
    // the zbuffer builds no BVH
    SceneDesc z = glass_and_mirror(Pipeline::zbuffer);
    const BuiltScene zb = build_scene(z);
    EXPECT_FALSE(zb.has_bvh);
}

TEST(MeshRender, MeshSphereLooksTheSameThroughZbufferAndRaycast) {
    for (bool smooth : {true, false}) {
        SceneDesc d;
        d.image.width = 160;
        d.image.height = 120;
        d.materials.resize(2);
        d.materials[1].kd = {0.7f, 0.3f, 0.2f};
        d.materials[1].ks = Rgb{0.5f};
        d.lights.push_back({{-3, 4, 5}, Rgb{6.0f}, 0});
        ObjectDesc floor;
        floor.type = ShapeType::plane;
        floor.point = {0, -1, 0};
        d.objects = {floor, mesh(uv_sphere({0, 0.2f, 0}, 1.2f, 64, false), 1, smooth)};
        d.render.pipeline = Pipeline::zbuffer;
        const SceneDesc dz = d;
        const BuiltScene zb = build_scene(d);
        d.render.pipeline = Pipeline::raycast;
        const BuiltScene rc = build_scene(d);
        RenderStats s1, s2;
        const Image a = render(zb, dz, {}, s1), b = render(rc, d, {}, s2);
        const ImageDiff diff = compare_images(a, b, 2.0f / 255);
        EXPECT_GE(diff.fraction_within(), 0.99) << smooth << ": " << to_string(diff);
        EXPECT_EQ(s2.triangles, rc.mesh_triangles);      // raycast: triangles in meshes
        EXPECT_GT(s1.triangles, rc.mesh_triangles / 3);  // zbuffer: rasterized (the front)
    }
}

TEST(MeshRender, MtlMaterialsColourTheirFaces) {
    // two triangles side by side, red and green by their MTL, seen from the front
    const auto dir = std::filesystem::temp_directory_path() / "luz_mesh_render_test";
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "two.obj") << "mtllib two.mtl\nv -2 -1 0\nv 0 -1 0\nv -1 1 0\n"
                                      "v 0 -1 0\nv 2 -1 0\nv 1 1 0\n"
                                      "usemtl red\nf 1 2 3\nusemtl green\nf 4 5 6\n";
    std::ofstream(dir / "two.mtl") << "newmtl red\nKa 0\nKd 1 0 0\nKs 0\n"
                                      "newmtl green\nKa 0\nKd 0 1 0\nKs 0\n";
    std::ofstream(dir / "s.json") << R"({"image": {"width": 40, "height": 20, "background": 0},
        "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0], "view_height": 2.5},
        "render": {"model": "lambert"}, "lights": [{"position": [0, 0, 5]}],
        "objects": [{"type": "mesh", "file": "two.obj"}]})";
    for (const char* pipeline : {"zbuffer", "raycast"}) {
        const SceneDesc d = load_scene((dir / "s.json").string(), {{"render.pipeline", pipeline}});
        const BuiltScene scene = build_scene(d);
        RenderStats s;
        const Image img = render(scene, d, {}, s);
        const Rgb left = img.at(10, 13), right = img.at(30, 13);
        EXPECT_GT(left.x, 0.5f) << pipeline;
        EXPECT_EQ(left.y, 0.0f) << pipeline;
        EXPECT_GT(right.y, 0.5f) << pipeline;
        EXPECT_EQ(right.x, 0.0f) << pipeline;
    }
    std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace luz
