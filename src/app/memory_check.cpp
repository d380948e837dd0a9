// The memory check made before rendering: estimate, limit, and the refusal message.
#include "app/memory_check.h"

#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <string>

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

void check_memory(const SceneDesc& desc, std::optional<uint64_t> limit) {
    const uint64_t max_bytes = limit ? *limit : default_memory_limit();
    const uint64_t need = estimate_render_bytes(desc.image.width, desc.image.height);
    if (need <= max_bytes) return;
    char buf[160];
    std::snprintf(buf, sizeof buf, "image.width: %dx%d needs %s, more than the %s limit",
                  desc.image.width, desc.image.height, bytes_text(need).c_str(),
                  bytes_text(max_bytes).c_str());
    throw InputError(desc.source + ": " + buf);
}

}  // namespace luz
