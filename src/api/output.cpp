// The public outputs: checks of output paths before any work, a frame to an image file (atomic),
// its statistics and its refinement mask (include/luz/output.h).
#include "luz/output.h"

#include <filesystem>

namespace luz {

void check_writable_target(const std::string& path, const char* origin) {
    const std::filesystem::path dir = std::filesystem::path(path).parent_path();
    std::error_code ec;
    if (!dir.empty() && !std::filesystem::is_directory(dir, ec)) {
        throw SceneError(path + ": " + origin + ": folder " + dir.string() + " does not exist");
    }
    if (std::filesystem::is_directory(path, ec)) {
        throw SceneError(path + ": " + origin + ": is a folder, not a file");
    }
}

void check_output_path(const std::string& path, const char* origin) {
    ImageFormat format;
    if (!format_from_path(path, format)) {
        const std::string ext = std::filesystem::path(path).extension().string();
        throw SceneError(path + ": " + origin + ": unknown image format " +
                         (ext.empty() ? std::string("(no extension)") : "\"" + ext + "\"") +
                         ", expected .png, .ppm, .pfm or .exr");
    }
    check_writable_target(path, origin);
}

std::string encode_frame(const Frame& frame, const std::string& path, Encoding encoding) {
    return encode_image(path, frame.image, encoding);
}

void write_frame(const Frame& frame, const std::string& path, Encoding encoding) {
    write_file_atomically(path, encode_frame(frame, path, encoding));
}

std::string frame_stats_json(const Frame& frame, const SceneDesc& desc) {
    return stats_json_text(frame.stats, desc);
}

Image frame_aa_mask(const Frame& frame) { return aa_mask_image(frame.aa_mask, frame.image); }

}  // namespace luz
