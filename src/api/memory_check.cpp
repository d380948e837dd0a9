// The memory check made before rendering: estimate, limit, and the refusal message.
#include "api/memory_check.h"

#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "render/aov.h"
#include "scene/input_error.h"

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

/// "12.5 GiB", or MiB / bytes for small amounts (a --max-memory given in bytes).
static std::string bytes_text(uint64_t bytes) {
    char buf[48];
    if (bytes >= (uint64_t{1} << 30)) {
        std::snprintf(buf, sizeof buf, "%.1f GiB", bytes / double(uint64_t{1} << 30));
    } else if (bytes >= (uint64_t{1} << 20)) {
        std::snprintf(buf, sizeof buf, "%.1f MiB", bytes / double(uint64_t{1} << 20));
    } else {
        std::snprintf(buf, sizeof buf, "%llu bytes", static_cast<unsigned long long>(bytes));
    }
    return buf;
}

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
    // Per triangle: tessellated (3 vertices with normals, projected copies, bins) ~ 160 bytes;
    // a mesh triangle (shared vertices, indices, material, BVH node share and leaf copy) ~ 192.
    const uint64_t t = uint64_t(desc.geometry.tessellation < 0 ? 0 : desc.geometry.tessellation);
    for (const ObjectDesc& o : desc.objects) {
        if (o.type == ShapeType::mesh) {
            if (o.mesh) e.geometry += uint64_t(o.mesh->triangle_count()) * 192;
        } else if (desc.render.pipeline == Pipeline::zbuffer && o.type != ShapeType::triangle &&
                   o.type != ShapeType::plane) {
            e.geometry += 2 * t * t * 160;
        }
    }
    return e;
}

void check_memory(const SceneDesc& desc, std::optional<uint64_t> limit, int aov_count) {
    const uint64_t max_bytes = limit ? *limit : default_memory_limit();
    const MemoryEstimate e = estimate_memory(desc, aov_count);
    const uint64_t need = e.total();
    if (need <= max_bytes) return;
    // the key of the largest part, so that the message says what to change
    std::string key = "image.width";
    char what[96];
    std::snprintf(what, sizeof what, "%dx%d", desc.image.width, desc.image.height);
    std::string subject = what;
    if (e.geometry > e.image) {
        // the mesh with most triangles, or the tessellation
        size_t most = 0;
        int index = -1;
        for (size_t i = 0; i < desc.objects.size(); ++i) {
            const ObjectDesc& o = desc.objects[i];
            if (o.type == ShapeType::mesh && o.mesh && o.mesh->triangle_count() > most) {
                most = o.mesh->triangle_count();
                index = static_cast<int>(i);
            }
        }
        if (index >= 0 && uint64_t(most) * 192 * 2 >= e.geometry) {
            key = "objects." + std::to_string(index) + ".file";
            subject =
                desc.objects[size_t(index)].file + " (" + std::to_string(most) + " triangles)";
        } else {
            key = "render.tessellation";
            subject = "tessellation " + std::to_string(desc.geometry.tessellation);
        }
    }
    throw InputError(desc.source + ": " + key + ": " + subject + " needs " + bytes_text(need) +
                     ", more than the " + bytes_text(max_bytes) +
                     " limit (--max-memory to change it)");
}

}  // namespace luz
