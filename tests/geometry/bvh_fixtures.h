// Shared helpers of the BVH tests: mesh objects (random soups, planar grids, degenerate
// triangles), spheres, boxes and planes in a scene of three materials, a crowded scene of every
// bounded shape kind, random and camera rays.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "geometry_fixtures.h"

namespace luz::test {

/// A mesh object from triangle vertex triples (vertices shared where the triples share them).
inline ObjectDesc mesh_object(const std::vector<Vec3>& positions,
                              const std::vector<uint32_t>& index, int material,
                              bool smooth = false) {
    auto data = std::make_shared<MeshData>();
    data->file = "test.obj";
    data->positions = positions;
    data->position = index;
    data->normal.assign(index.size(), -1);
    data->material.assign(index.size() / 3, -1);
    ObjectDesc o;
    o.type = ShapeType::mesh;
    o.material = material;
    o.smooth = smooth;
    o.mesh = data;
    return o;
}

/// A triangle soup: n random triangles of random sizes in [−4, 4]³.
inline ObjectDesc random_soup(Rng& rng, int n, int material) {
    std::vector<Vec3> p;
    std::vector<uint32_t> idx;
    for (int t = 0; t < n; ++t) {
        const Vec3 c = random_point(rng, -4, 4);
        const float size = uniform(rng, 0.05f, 1.2f);
        for (int k = 0; k < 3; ++k) {
            idx.push_back(static_cast<uint32_t>(p.size()));
            p.push_back(c + random_point(rng, -size, size));
        }
    }
    return mesh_object(p, idx, material);
}

/// A grid of n×n quads in the plane z = z0 (shared vertices), as two triangles each.
inline ObjectDesc planar_grid(int n, float z0, int material) {
    std::vector<Vec3> p;
    std::vector<uint32_t> idx;
    const float s = 8.0f / n;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) p.push_back({-4 + i * s, -4 + j * s, z0});
    const auto at = [n](int i, int j) { return static_cast<uint32_t>(j * (n + 1) + i); };
    for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
            idx.insert(idx.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            idx.insert(idx.end(), {at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    }
    return mesh_object(p, idx, material);
}

/// Degenerate triangles: zero-area ones (a repeated vertex, collinear vertices, a point),
/// and every triangle of `base` twice (the copy later in the index list, reversed).
inline ObjectDesc degenerate_mesh(Rng& rng, const ObjectDesc& base, int zero_area, int material) {
    std::vector<Vec3> p = base.mesh->positions;
    std::vector<uint32_t> idx = base.mesh->position;
    const size_t n = idx.size();
    for (size_t c = 0; c < n; c += 3) idx.insert(idx.end(), {idx[c], idx[c + 2], idx[c + 1]});
    for (int t = 0; t < zero_area; ++t) {
        const Vec3 a = random_point(rng, -4, 4), b = random_point(rng, -4, 4);
        const uint32_t i = static_cast<uint32_t>(p.size());
        switch (t % 3) {
            case 0:  // a repeated vertex
                p.insert(p.end(), {a, b});
                idx.insert(idx.end(), {i, i + 1, i});
                break;
            case 1:  // collinear
                p.insert(p.end(), {a, b, (a + b) * 0.5f});
                idx.insert(idx.end(), {i, i + 1, i + 2});
                break;
            default:  // one point
                p.push_back(a);
                idx.insert(idx.end(), {i, i, i});
                break;
        }
    }
    return mesh_object(p, idx, material);
}

/// Materials: 0 default (opaque), 1 glass (transparency 0.7), 2 water (0.35); not powers of
/// two, so that the order of multiplication would show in the products.
inline SceneDesc scene_with(std::vector<ObjectDesc> objects) {
    SceneDesc d;
    d.render.pipeline = Pipeline::raytrace;
    d.geometry.accel = Accel::bvh;
    d.materials.resize(3);
    d.materials[1].transparency = 0.7f;
    d.materials[2].transparency = 0.35f;
    for (size_t i = 0; i < objects.size(); ++i) objects[i].path = "objects." + std::to_string(i);
    d.objects = std::move(objects);
    return d;
}

inline ObjectDesc sphere(Vec3 c, float r, int material) {
    ObjectDesc o;
    o.type = ShapeType::sphere;
    o.center = c;
    o.radius = r;
    o.material = material;
    return o;
}

inline ObjectDesc box(Vec3 lo, Vec3 hi, int material) {
    ObjectDesc o;
    o.type = ShapeType::box;
    o.min = lo;
    o.max = hi;
    o.material = material;
    return o;
}

inline ObjectDesc plane(Vec3 point, int material) {
    ObjectDesc o;
    o.type = ShapeType::plane;
    o.point = point;
    o.material = material;
    return o;
}

/// Random rays: from points in [−6, 6]³ in random directions; every fourth aimed exactly at a
/// mesh vertex (where triangles meet and ties happen) and every eighth a segment (for shadows).
struct RandomRays {
    std::vector<Vec3> targets;
    Rng rng{12345};
    Ray next(int k, float& t_max) {
        Ray r{random_point(rng, -6, 6), random_direction(rng)};
        t_max = std::numeric_limits<float>::infinity();
        if (k % 4 == 0 && !targets.empty()) {
            const Vec3 to = targets[rng() % targets.size()] - r.origin;
            if (length(to) > 0) r.direction = normalize(to);
        }
        if (k % 8 == 1) t_max = uniform(rng, 0.5f, 12.0f);
        return r;
    }
};

/// Thin and thick cylinders and cones (capped or open, opaque or glass), sheared, mirrored and
/// scaled by the user transforms, among spheres: the open round cylinders are cylinder lanes
/// (prim_block.h) tested four at a time, the others axis lanes pre-tested four at a time.
inline std::vector<ObjectDesc> cylinder_field(Rng& rng) {
    std::vector<ObjectDesc> objects;
    const auto transforms = test::user_transforms();
    for (int i = 0; i < 300; ++i) {
        ObjectDesc o;
        o.type = i % 6 == 1 ? ShapeType::cone : ShapeType::cylinder;
        o.base = random_point(rng, -4, 4);
        o.axis = random_direction(rng);
        o.radius = i % 3 == 0 ? uniform(rng, 0.3f, 1.0f) : uniform(rng, 0.01f, 0.1f);
        o.height = i % 5 == 0 ? uniform(rng, 2.0f, 8.0f) : uniform(rng, 0.2f, 1.5f);
        o.caps = i % 2 == 0;
        o.material = i % 7 == 0 ? 1 : 0;
        if (i % 4 == 0) o.transform = transforms[i / 4 % transforms.size()].affine;
        objects.push_back(o);
    }
    for (int i = 0; i < 40; ++i)
        objects.push_back(sphere(random_point(rng, -4, 4), uniform(rng, 0.1f, 0.6f), i % 3));
    return objects;
}

/// `n` shapes in a cube of side 12, in three materials (opaque, glass 0.7, water 0.35) by turns:
/// spheres, cylinders and frusta along random axes, boxes, tori; with `soup` > 0 two triangle
/// soups of that many triangles beside them (glass, opaque); a plane under them.
inline SceneDesc crowded_scene(Rng& rng, int n, int soup) {
    std::vector<ObjectDesc> objects;
    for (int i = 0; i < n; ++i) {
        const int material = i % 3;
        ObjectDesc o = sphere(random_point(rng, -6, 6), uniform(rng, 0.1f, 0.6f), material);
        if (i % 5 == 1) {
            o = cylinder_desc(i % 2 == 0);
            o.base = random_point(rng, -6, 6);
            o.axis = random_direction(rng);
            o.radius = uniform(rng, 0.05f, 0.3f);
            o.height = uniform(rng, 0.3f, 1.5f);
        } else if (i % 5 == 3) {
            o = frustum_desc(i % 2 == 0);
            o.base = random_point(rng, -6, 6);
            o.axis = random_direction(rng);
        } else if (i % 7 == 4) {
            const Vec3 lo = random_point(rng, -6, 6);
            o = box(lo, lo + random_point(rng, 0.1f, 0.8f), material);
        } else if (i % 11 == 6) {
            o = torus_desc();
            o.center = random_point(rng, -6, 6);
        }
        o.material = material;
        objects.push_back(o);
    }
    if (soup > 0) {
        objects.push_back(random_soup(rng, soup, 1));
        objects.push_back(random_soup(rng, soup, 0));
    }
    objects.push_back(plane({0, -7, 0}, 2));
    return scene_with(objects);
}

/// Camera-like packets: rays from one eye through neighbouring points of a small square of
/// the view (8 in a row, as the renderer's tiles give them), over a w×h grid aimed at `at`.
inline std::vector<Ray> camera_rays(Vec3 eye, Vec3 at, int w, int h, float half) {
    const Vec3 f = normalize(at - eye);
    const Vec3 r = normalize(cross(f, Vec3{0, 1, 0})), u = cross(r, f);
    std::vector<Ray> rays;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            rays.push_back({eye, normalize(f + r * ((2.0f * (x + 0.5f) / w - 1) * half) +
                                           u * ((1 - 2.0f * (y + 0.5f) / h) * half))});
    return rays;
}

}  // namespace luz::test
