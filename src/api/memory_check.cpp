// The memory check made before rendering: estimate, limit, and the refusal message.
#include "api/memory_check.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <string>

#include "geometry/tessellate.h"
#include "render/aov.h"
#include "scene/input_error.h"
#include "scene/message_text.h"

namespace luz {

uint64_t estimate_render_bytes(int width, int height) {
    const uint64_t pixels = static_cast<uint64_t>(width < 0 ? 0 : width) *
                            static_cast<uint64_t>(height < 0 ? 0 : height);
    // float RGB image + 4-byte depth + 16-byte g-buffer, then the 8-bit RGB copy for the file
    const uint64_t per_pixel = sizeof(Rgb) + 4 + 16 + 3;
    return pixels * per_pixel;
}

uint64_t default_memory_limit() {
    const long pages = sysconf(_SC_PHYS_PAGES);
    const long page_size = sysconf(_SC_PAGE_SIZE);
    uint64_t physical = pages > 0 && page_size > 0
                            ? static_cast<uint64_t>(pages) * static_cast<uint64_t>(page_size)
                            : (uint64_t{8} << 30);
    // A container may have less than the machine: cgroup v2 "memory.max" ("max" = no limit).
    std::ifstream cgroup("/sys/fs/cgroup/memory.max");
    std::string text;
    if (cgroup >> text && text != "max") {
        try {
            const uint64_t limit = std::stoull(text);
            if (limit > 0 && limit < physical) physical = limit;
        } catch (const std::exception&) {
        }
    }
    return physical / 2;
}

namespace {

// Bytes per part, measured as resident sizes:
// - a tessellated triangle: 3 vertices with normals, projected copies, bins;
// - a mesh triangle: shared vertices, indices, material, face normal, BVH node share and leaf
//   copy;
// - an object: its ObjectDesc (which `luz render` holds three times during the first frame),
//   its built Shape, its primitive and BVH share; 400 000 spheres peak at 645 MB.
constexpr uint64_t kTessellatedTriangleBytes = 160;
constexpr uint64_t kMeshTriangleBytes = 204;
constexpr uint64_t kObjectBytes = 1600;

bool is_tessellated(const SceneDesc& desc, const ObjectDesc& o) {
    return desc.render.pipeline == Pipeline::zbuffer && o.type != ShapeType::mesh &&
           o.type != ShapeType::triangle && o.type != ShapeType::plane;
}

}  // namespace

MemoryEstimate estimate_memory(const SceneDesc& desc, int aov_count) {
    MemoryEstimate e;
    const int W = desc.image.width, H = desc.image.height;
    const uint64_t pixels = uint64_t(W < 0 ? 0 : W) * uint64_t(H < 0 ? 0 : H);
    // Each per-term image: its float pixels and its encoded file.
    e.image = estimate_render_bytes(W, H) + pixels * (sizeof(Rgb) + 4) * uint64_t(aov_count);
    if (desc.render.antialias.mode == AaMode::adaptive) {
        // (W+1)×(H+1) corner samples (colours, or colours with their terms), plus one byte a
        // pixel for the refinement mask
        const uint64_t sample = aov_count > 0 ? sizeof(TermSample) : sizeof(Rgb);
        e.antialias = uint64_t(W < 0 ? 0 : W + 1) * uint64_t(H < 0 ? 0 : H + 1) * sample + pixels;
    }
    const uint64_t t = uint64_t(desc.geometry.tessellation < 0 ? 0 : desc.geometry.tessellation);
    for (const ObjectDesc& o : desc.objects) {
        e.objects += kObjectBytes;
        if (o.type == ShapeType::mesh) {
            if (o.mesh) e.meshes += uint64_t(o.mesh->triangle_count()) * kMeshTriangleBytes;
        } else if (is_tessellated(desc, o)) {
            e.tessellation +=
                tessellated_triangle_count(o, static_cast<int>(t)) * kTessellatedTriangleBytes;
        }
    }
    return e;
}

void check_memory(const SceneDesc& desc, std::optional<uint64_t> limit, int aov_count) {
    const uint64_t max_bytes = limit ? *limit : default_memory_limit();
    const MemoryEstimate e = estimate_memory(desc, aov_count);
    const uint64_t need = e.total();
    if (need <= max_bytes) return;
    // The key of the largest part, so that the message says what to change.
    std::string key = "image.width", subject;
    bool plural = false;
    char size[96];
    std::snprintf(size, sizeof size, "%dx%d", desc.image.width, desc.image.height);
    subject = size;
    const uint64_t largest = std::max({e.image + e.antialias, e.tessellation, e.meshes, e.objects});
    if (largest == e.image + e.antialias) {
        // the image
    } else if (largest == e.tessellation) {
        std::size_t curved = 0;
        for (const ObjectDesc& o : desc.objects) curved += is_tessellated(desc, o);
        key = "render.tessellation";
        subject = "tessellation " + std::to_string(desc.geometry.tessellation) + " of " +
                  std::to_string(curved) + " curved shape" + (curved == 1 ? "" : "s");
    } else if (largest == e.meshes) {
        // one mesh with most of the triangles, or many meshes
        std::size_t most = 0, meshes = 0;
        uint64_t triangles = 0;
        int index = -1;
        for (std::size_t i = 0; i < desc.objects.size(); ++i) {
            const ObjectDesc& o = desc.objects[i];
            if (o.type != ShapeType::mesh || !o.mesh) continue;
            ++meshes;
            triangles += o.mesh->triangle_count();
            if (o.mesh->triangle_count() > most) {
                most = o.mesh->triangle_count();
                index = static_cast<int>(i);
            }
        }
        if (index >= 0 && uint64_t(most) * 2 >= triangles) {
            key = "objects." + std::to_string(index) + ".file";
            subject = printable(desc.objects[std::size_t(index)].file) + " (" +
                      std::to_string(most) + " triangles)";
        } else {
            key = "objects";
            subject = std::to_string(meshes) + " meshes (" + std::to_string(triangles) +
                      " triangles in all)";
            plural = true;
        }
    } else {
        key = "objects";
        subject = std::to_string(desc.objects.size()) + " objects";
        plural = true;
    }
    throw InputError(printable(desc.source) + ": " + key + ": " + subject +
                     (plural ? " need " : " needs ") + bytes_text(need) + ", more than the " +
                     bytes_text(max_bytes) + " limit (--max-memory to change it)");
}

}  // namespace luz
