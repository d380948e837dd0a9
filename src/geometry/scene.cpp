// build_scene: the runtime scene, one Shape per object of a validated SceneDesc, and the BVH
// over its bounded shapes and mesh triangles.
#include "geometry/scene.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include "geometry/query_parts.h"
#include "geometry/shapes/cone.h"
#include "geometry/shapes/cylinder.h"
#include "scene/cancel.h"

namespace luz {

namespace {

// The SAH's costs for the scene's BVH: a node visit against a block test of four primitives
// (measured: 0.5–1 alike, 1.5 and up slower on bvh_vs_embree's incoherent rays), and the
// largest leaf (in primitives: two blocks; 16 is slower on primary rays).
const float kBlockTraversalCost = 0.7f;
const uint32_t kBlockMaxLeaf = 8;

/// A block of four unused lanes: no shape, NaN vertices.
PrimBlock padding_block() {
    PrimBlock b;
    for (auto& corner : b.v)
        for (auto& axis : corner)
            for (float& x : axis) x = std::numeric_limits<float>::quiet_NaN();
    for (int k = 0; k < PrimBlock::kLanes; ++k) {
        b.shape[k] = PrimBlock::kPadding;
        b.triangle[k] = PrimBlock::kNotTriangle;
    }
    return b;
}

/// Lane k of b as a shape around the axis origin(M) + s·column(M, 2) whose points are
/// c·U + s·V + z·W with c² + s² ≤ 1 (a cylinder or a cone: every point of theirs lies within
/// unit distance of the z axis in object space; U, V, W the columns of M), for
/// axis_lanes_missed() (prim_block.h): R² = max(|U|², |V|²) + |U·V| in double, inflated by
/// 2⁻⁸ and rounded up; the slack factor κ = 2⁻¹⁶·|W|₁·max(1, cond/16), cond the ratio of the
/// longest to the shortest column (the exact test's rounding grows with it).
void set_axis_lane(PrimBlock& b, int k, const Affine& M) {
    const Vec3 U = shapes::column(M, 0), V = shapes::column(M, 1), W = shapes::column(M, 2),
               B = shapes::origin(M);
    const auto dot_d = [](const Vec3& a, const Vec3& c) {
        return double(a.x) * c.x + double(a.y) * c.y + double(a.z) * c.z;
    };
    const double uu = dot_d(U, U), vv = dot_d(V, V), ww = dot_d(W, W);
    const double R2 = (std::max(uu, vv) + std::fabs(dot_d(U, V))) * (1.0 + 0x1p-8);
    const float Rt2 = std::nextafter(static_cast<float>(R2), std::numeric_limits<float>::max());
    const float Rt = std::nextafter(std::sqrt(Rt2), std::numeric_limits<float>::max());
    const double longest = std::sqrt(std::max({uu, vv, ww})),
                 shortest = std::sqrt(std::min({uu, vv, ww}));
    const double cond = shortest > 0 ? longest / shortest : 1e30;
    const double w1 = std::fabs(W.x) + std::fabs(W.y) + std::fabs(W.z);
    for (int a = 0; a < 3; ++a) {
        b.v[0][a][k] = B[a];
        b.v[1][a][k] = W[a];
    }
    b.v[2][0][k] = Rt2;
    b.v[2][1][k] = static_cast<float>(0x1p-16 * w1 * std::max(1.0, cond / 16));
    b.v[2][2][k] = std::fabs(B.x) + std::fabs(B.y) + std::fabs(B.z) + Rt;
    b.triangle[k] = PrimBlock::kAroundAxis;
}

bool is_axial(const Shape& s) {
    return !s.mesh && (s.type == ShapeType::cylinder || s.type == ShapeType::cone);
}

/// Piece k of n of an axial shape (the part k/n ≤ z ≤ (k+1)/n in object space): its bounds.
Bounds3 piece_bounds(const Shape& s, int k, int n) {
    const float z0 = static_cast<float>(k) / static_cast<float>(n);
    const float z1 = k + 1 == n ? 1.0f : static_cast<float>(k + 1) / static_cast<float>(n);
    return s.type == ShapeType::cone ? shapes::cone::bounds(s, z0, z1)
                                     : shapes::cylinder::bounds(s, z0, z1);
}

/// How many pieces an axial shape enters the BVH as: of 1 … kMaxPieces, the count whose boxes
/// have the least surface area, each piece past the first counted as kPieceCost more (a
/// reference costs a lane and a test). A shape along a world axis stays whole; rings' slanted
/// cylinders (length 7 diameters) become two.
int axis_pieces(const Shape& s) {
    constexpr int kMaxPieces = 3;
    constexpr double kPieceCost = 0.1;
    // No longer than its diameter: each piece's box would keep the whole cross-section.
    const Affine& M = s.transform.world_from_object;
    const Vec3 U = shapes::column(M, 0), V = shapes::column(M, 1), W = shapes::column(M, 2);
    if (dot(W, W) <= 4.0f * std::max(dot(U, U), dot(V, V))) return 1;
    int best = 1;
    double best_cost = std::numeric_limits<double>::infinity();
    for (int n = 1; n <= kMaxPieces; ++n) {
        double area = 0;
        for (int k = 0; k < n; ++k) {
            const Vec3 d = piece_bounds(s, k, n).extent();
            area += double(d.x) * d.y + double(d.y) * d.z + double(d.z) * d.x;  // halved
        }
        const double cost = area * (1.0 + kPieceCost * (n - 1));
        if (cost < best_cost) {
            best = n;
            best_cost = cost;
        }
    }
    return best;
}

/// Whether the leaf being laid out from slot `at` (its first `kept` slots filled) holds shape i.
bool in_leaf(const HugeVector<PrimBlock>& blocks, uint32_t at, uint32_t kept, uint32_t i) {
    constexpr uint32_t L = PrimBlock::kLanes;
    for (uint32_t slot = at; slot < at + kept; ++slot)
        if (blocks[slot / L].shape[slot % L] == i) return true;
    return false;
}

}  // namespace

BuiltScene build_scene(const SceneDesc& desc) {
    return build_scene(desc, desc.render.pipeline != Pipeline::zbuffer);
}

BuiltScene build_scene(const SceneDesc& desc, bool with_bvh) {
    BuiltScene scene;
    scene.geometry = desc.geometry;
    scene.material_count = desc.materials.size();
    scene.shapes.reserve(desc.objects.size());
    scene.bounds.reserve(desc.objects.size());
    for (size_t i = 0; i < desc.objects.size(); ++i) {
        check_cancel();
        scene.shapes.push_back(make_shape(desc.objects[i], static_cast<int>(i)));
        scene.bounds.push_back(bounds(scene.shapes.back()));
        if (const auto& m = scene.shapes.back().mesh) scene.mesh_triangles += m->triangle_count();
    }
    if (desc.geometry.accel == Accel::bvh && with_bvh) build_bvh(scene);
    return scene;
}

void build_bvh(BuiltScene& scene) {
    const auto start = std::chrono::steady_clock::now();
    // The primitives: every bounded shape, except that a mesh gives its triangles instead.
    HugeVector<BvhPrim> prims;  // on huge pages when large: fewer page faults
    HugeVector<Bounds3> boxes;
    prims.reserve(scene.shapes.size() + scene.mesh_triangles);
    boxes.reserve(prims.capacity());
    scene.unbounded.clear();
    for (size_t i = 0; i < scene.shapes.size(); ++i) {
        const Shape& s = scene.shapes[i];
        const uint32_t shape = static_cast<uint32_t>(i);
        if (!is_bounded(s)) {
            scene.unbounded.push_back(shape);
        } else if (s.mesh) {
            if (s.mesh->triangle_count() > 0x7FFFFFF0u)  // PrimBlock's markers: top bit set
                throw std::length_error("a mesh of more than 2^31 - 16 triangles");
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
    // Long slanted cylinders and cones enter as pieces along their axis, whose boxes hug them
    // better (each piece tests the whole shape); not when everything fits one leaf anyway.
    if (prims.size() > kBlockMaxLeaf) {
        for (size_t p = 0, n = prims.size(); p < n; ++p) {
            Shape& s = scene.shapes[prims[p].shape];
            if (prims[p].triangle != BvhPrim::kNotTriangle || !is_axial(s)) continue;
            const int pieces = axis_pieces(s);
            s.split = pieces > 1;
            for (int k = 0; k < pieces; ++k) {
                const Bounds3 b = piece_bounds(s, k, pieces);
                if (k == 0) {
                    boxes[p] = b;
                } else {
                    prims.push_back(prims[p]);
                    boxes.push_back(b);
                }
            }
        }
    }
    check_cancel();
    // The SAH counts a leaf's primitives in blocks of four, tested at once.
    BvhOptions options;
    options.leaf_block = PrimBlock::kLanes;
    options.traversal_cost = kBlockTraversalCost;
    options.max_leaf_size = kBlockMaxLeaf;
    // Primitives that fit one leaf stay in one: the queries test it without any node
    // (BuiltScene::root_leaf), a saving the SAH, which prices the visits below the root, misses.
    // Otherwise mesh triangles and other shapes get leaves of their own: a ground polygon's
    // leaf then has a flat box, which the shadow rays leaving the ground (their origins lifted
    // off it) miss, instead of a box raised by a shape beside it that every such ray enters.
    std::vector<uint8_t> kinds;
    if (prims.size() <= kBlockMaxLeaf) {
        options.traversal_cost = std::numeric_limits<float>::infinity();
    } else {
        kinds.resize(prims.size());  // 0: a mesh triangle, 1: any other shape
        for (size_t p = 0; p < prims.size(); ++p)
            kinds[p] = prims[p].triangle == BvhPrim::kNotTriangle ? 1 : 0;
        const size_t shapes = std::count(kinds.begin(), kinds.end(), uint8_t{1});
        if (shapes > 0 && shapes < prims.size()) options.kinds = kinds;  // both kinds
    }
    scene.bvh = Bvh8::build(boxes, options);
    // Primitives in blocks, leaf by leaf in node order (those with empty bounds, never hit,
    // are left out); the order itself is not kept.
    const HugeVector<uint32_t> order = scene.bvh.take_order();
    constexpr uint32_t L = PrimBlock::kLanes;
    auto& blocks = scene.bvh_blocks;
    blocks.clear();
    size_t block_count = 0;
    for (const Bvh8::Node& n : scene.bvh.nodes())
        for (uint32_t count : n.count) block_count += (count + L - 1) / L;
    blocks.reserve(block_count);
    scene.bvh.renumber_leaves([&](uint32_t first, uint32_t& count) {
        const uint32_t at = static_cast<uint32_t>(blocks.size()) * L;
        uint32_t kept = 0;
        for (uint32_t i = 0; i < count; ++i) {
            const BvhPrim& p = prims[order[first + i]];
            if (scene.shapes[p.shape].split && in_leaf(blocks, at, kept, p.shape)) continue;
            if (kept % L == 0) blocks.push_back(padding_block());
            PrimBlock& b = blocks.back();
            const uint32_t k = kept++ % L;
            const Vec3 corners[3] = {p.p0, p.p1, p.p2};
            for (int c = 0; c < 3; ++c)
                for (int a = 0; a < 3; ++a) b.v[c][a][k] = corners[c][a];
            b.shape[k] = p.shape;
            b.triangle[k] = p.triangle;
            const Shape& s = scene.shapes[p.shape];
            if (p.triangle == BvhPrim::kNotTriangle && s.world_form &&
                s.type == ShapeType::sphere) {  // tested four at a time (query_parts.h)
                for (int a = 0; a < 3; ++a) b.v[0][a][k] = s.centre[a];
                b.v[1][0][k] = s.radius * s.radius;  // as world_sphere_roots() rounds it
                b.v[1][1][k] = s.radius;
                b.triangle[k] = PrimBlock::kSphere;
            } else if (p.triangle == BvhPrim::kNotTriangle && s.world_form &&
                       s.type == ShapeType::cylinder) {  // as world_cylinder_roots() takes it
                for (int a = 0; a < 3; ++a) {
                    b.v[0][a][k] = s.centre[a];
                    b.v[1][a][k] = s.normal[a];
                }
                b.v[2][0][k] = s.radius * s.radius;
                b.v[2][1][k] = s.offset;
                b.triangle[k] = PrimBlock::kCylinder;
            } else if (p.triangle == BvhPrim::kNotTriangle &&
                       (s.type == ShapeType::cylinder || s.type == ShapeType::cone)) {
                set_axis_lane(b, static_cast<int>(k), s.transform.world_from_object);
            }
        }
        count = kept;  // two pieces of one shape in a leaf: it is tested once
        return at;
    });
    scene.has_bvh = true;
    scene.root_leaf = 0;
    if (const auto& nodes = scene.bvh.nodes(); nodes.size() == 1) {
        const Bvh8::Node& root = nodes[0];
        int used = 0;
        for (int k = 0; k < 8; ++k)
            used += root.count[k] > 0 || root.child[k] != Bvh8::Node::kUnused;
        if (used == 1 && root.count[0] > 0 && root.child[0] == 0) scene.root_leaf = root.count[0];
    }
    scene.bvh_build_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace luz
