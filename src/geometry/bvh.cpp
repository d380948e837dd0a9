// Bvh::build: top-down binned SAH (Wald 2007) over primitive boxes and centroids, exact SAH for
// small nodes, depth-first nodes; large nodes binned, partitioned and split in parallel (oneTBB)
// by decisions that never depend on the thread count, so the tree is the same for any.
// The tree's assembly is here; the builder's parts are in bvh_builder.h.
#include "geometry/bvh.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <memory>
#include <stdexcept>

#include "geometry/bvh_builder.h"

namespace luz::bvh_build {

std::unique_ptr<Subtree> Builder::build_task(size_t begin, size_t end, const Box& box,
                                             const Box& cbox, int depth) {
    auto sub = std::make_unique<Subtree>();
    const auto scratch = std::make_unique<Bins>();
    const auto leaf = [&] {  // a flat subtree of one node
        sub->root = make_node(box);
        sub->root.offset = static_cast<uint32_t>(begin);
        sub->root.count = static_cast<uint32_t>(end - begin);
        flat_[2 * begin] = sub->root;
        sub->nodes = flat_.get() + 2 * begin;
        sub->size = 1;
        return std::move(sub);
    };
    if (cancel_requested(cancel_)) return leaf();  // cancelled: thrown away by build()
    if (end - begin < serial_below_) {
        FlatNodes flat{flat_.get() + 2 * begin};
        build_serial(flat, begin, end, box, cbox, depth, *scratch);
        sub->nodes = flat.at;
        sub->size = flat.size;
        return sub;
    }
    Box child[4];
    size_t mid = split(begin, end, depth, box, cbox, child, *scratch);
    if (mid == begin) mid = split_kinds(begin, end, child);
    sub->root = make_node(box);
    if (mid == begin) return leaf();
    tbb::parallel_invoke([&] { sub->left = build_task(begin, mid, child[0], child[1], depth + 1); },
                         [&] { sub->right = build_task(mid, end, child[2], child[3], depth + 1); });
    sub->size = 1 + sub->left->size + sub->right->size;
    return sub;
}

void Builder::flatten(const Subtree& s, BvhNode* out, uint32_t base) {
    if (!s.left) {
        for (size_t i = 0; i < s.size; ++i) {
            BvhNode n = s.nodes[i];
            if (!n.leaf()) n.offset += base;
            out[base + i] = n;
        }
        return;
    }
    BvhNode root = s.root;
    const uint32_t second = base + 1 + static_cast<uint32_t>(s.left->size);
    root.offset = second;
    root.count = 0;
    out[base] = root;
    tbb::parallel_invoke([&] { flatten(*s.left, out, base + 1); },
                         [&] { flatten(*s.right, out, second); });
}

uint32_t Builder::build_serial(FlatNodes& nodes, size_t begin, size_t end, const Box& box,
                               const Box& cbox, int depth, Bins& scratch) {
    const uint32_t index = nodes.push(make_node(box));
    Box child[4];  // box and cbox of the first and the second child
    size_t mid = end - begin > 1 ? split(begin, end, depth, box, cbox, child, scratch) : begin;
    if (mid == begin) mid = split_kinds(begin, end, child);
    if (mid == begin) {
        nodes.at[index].offset = static_cast<uint32_t>(begin);
        nodes.at[index].count = static_cast<uint32_t>(end - begin);
        return index;
    }
    build_serial(nodes, begin, mid, child[0], child[1], depth + 1, scratch);  // the next node
    const uint32_t second = build_serial(nodes, mid, end, child[2], child[3], depth + 1, scratch);
    nodes.at[index].offset = second;
    nodes.at[index].count = 0;
    return index;
}

}  // namespace luz::bvh_build

namespace luz {

using namespace bvh_build;

Bvh Bvh::build(std::span<const Bounds3> bounds, const BvhOptions& options) {
    if (!options.kinds.empty() && options.kinds.size() != bounds.size())
        throw std::invalid_argument("Bvh::build: one kind per primitive");
    Bvh bvh;
    Refs refs;
    refs.reserve(bounds.size());
    for (size_t i = 0; i < bounds.size(); ++i) {
        const Bounds3& b = bounds[i];
        if (b.empty()) continue;
        Ref r;
        const uint32_t id = static_cast<uint32_t>(i);
        float id_bits;
        std::memcpy(&id_bits, &id, 4);
        r.lo = Lane4f{b.lo.x, b.lo.y, b.lo.z, id_bits};
        r.hi = Lane4f{b.hi.x, b.hi.y, b.hi.z, 0.0f};
        refs.push_back(r);
    }
    if (refs.empty()) return bvh;
    Builder builder(refs, options);
    Box box, cbox;
    builder.bounds_of(0, refs.size(), box, cbox);
    const std::unique_ptr<Subtree> tree = builder.build_task(0, refs.size(), box, cbox, 0);
    check_cancel();
    bvh.nodes_.resize(tree->size);
    Builder::flatten(*tree, bvh.nodes_.data(), 0);
    bvh.order_.resize(refs.size());
    const auto take_ids = [&](size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i) bvh.order_[i] = refs[i].id();
    };
    if (refs.size() < 4 * kChunk) {
        take_ids(0, refs.size());
    } else {
        tbb::parallel_for(
            tbb::blocked_range<size_t>(0, refs.size(), kChunk),
            [&](const tbb::blocked_range<size_t>& r) { take_ids(r.begin(), r.end()); });
    }
    return bvh;
}

}  // namespace luz
