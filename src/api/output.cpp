// The public outputs: checks of output paths before any work, a frame to an image file (atomic),
// its pictures and its refinement mask (include/luz/output.h, options.h, pictures.h).
#include "luz/output.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>

#include "engine/luz_engine.h"  // check_writable_target()
#include "image/atomic_file.h"
#include "image/image_io.h"
#include "luz/options.h"         // check_output_path(), frame_file_paths()
#include "luz/pictures.h"        // aov_picture(), frame_aa_mask(), rgba8()
#include "render/adaptive_aa.h"  // aa_mask_image()

namespace luz {

void check_writable_target(const std::string& path, const char* origin) {
    const auto missing_folder = [&](const std::string& file) {
        const std::filesystem::path dir = std::filesystem::path(file).parent_path();
        std::error_code ec;
        if (!dir.empty() && !std::filesystem::is_directory(dir, ec)) {
            throw SceneError(path + ": " + origin + ": folder " + dir.string() + " does not exist");
        }
    };
    missing_folder(path);
    OutputTarget target;
    try {
        target = resolve_output(path);
    } catch (const FileError& e) {
        std::error_code ec;
        if (std::filesystem::is_directory(path, ec))
            throw SceneError(path + ": " + origin + ": is a folder, not a file");
        const std::string what = e.what(), prefix = path + ": cannot write: ";
        throw SceneError(path + ": " + origin + ": cannot write: " +
                         (what.rfind(prefix, 0) == 0 ? what.substr(prefix.size()) : what));
    }
    // a symlink to nothing yet: its target is created, in a folder that must exist
    if (target.kind == OutputTarget::Kind::file && !target.exists) missing_folder(target.path);
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

namespace {

/// viridis (matplotlib's perceptually uniform colour map, CC0) at 0, 1/8, … 1.
constexpr float kViridis[9][3] = {
    {0.267004f, 0.004874f, 0.329415f}, {0.282327f, 0.140926f, 0.457517f},
    {0.253935f, 0.265254f, 0.529983f}, {0.206756f, 0.371758f, 0.553117f},
    {0.163625f, 0.471133f, 0.558148f}, {0.127568f, 0.566949f, 0.550556f},
    {0.134692f, 0.658636f, 0.517649f}, {0.266941f, 0.748751f, 0.440573f},
    {0.477504f, 0.821444f, 0.318195f}};
constexpr float kViridisEnd[3] = {0.993248f, 0.906157f, 0.143936f};  // at 1

}  // namespace

namespace {

/// viridis at f in [0, 1]: the colour map of the `tests` picture (docs/CLI.md#aov shows its scale).
Rgb viridis(float f) {
    if (!(f > 0)) f = 0;
    if (f > 1) f = 1;
    const float x = f * 8;
    const int i = std::min(7, static_cast<int>(x));
    const float t = x - static_cast<float>(i);
    const float* a = kViridis[i];
    const float* b = i == 7 ? kViridisEnd : kViridis[i + 1];
    // Anchors 0 … 7 are 1/8 apart; the last segment runs from 7/8 to the end colour at 1.
    return Rgb{a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t, a[2] + (b[2] - a[2]) * t};
}

}  // namespace

Image aov_picture(const Aov& aov) {
    const Image& in = aov.image;
    Image out(in.width, in.height);
    switch (aov.kind) {
        case AovKind::depth: {
            // Near bright: the nearest hit white, the farthest grey 0.15, misses black.
            float near = INFINITY, far = -INFINITY;
            for (const Rgb& p : in.pixels) {
                if (std::isfinite(p.x)) {
                    near = std::min(near, p.x);
                    far = std::max(far, p.x);
                }
            }
            const float span = far > near ? far - near : 1.0f;
            for (size_t k = 0; k < in.pixels.size(); ++k) {
                const float t = in.pixels[k].x;
                out.pixels[k] =
                    std::isfinite(t) ? Rgb{1.0f - 0.85f * (t - near) / span} : Rgb{0.0f};
            }
            break;
        }
        case AovKind::normal:
            for (size_t k = 0; k < in.pixels.size(); ++k)
                out.pixels[k] = Rgb{0.5f} + in.pixels[k] * 0.5f;
            break;
        case AovKind::tests: {
            float most = 0;
            for (const Rgb& p : in.pixels) most = std::max(most, p.x);
            for (size_t k = 0; k < in.pixels.size(); ++k)
                out.pixels[k] = viridis(most > 0 ? in.pixels[k].x / most : 0.0f);
            break;
        }
        default:
            out = in;
    }
    return out;
}

namespace {

/// The file of the term `name` beside the image file `path` (not .exr): X.NAME.EXT.
std::string term_path(const std::string& path, const std::string& name) {
    const std::filesystem::path p(path);
    return (p.parent_path() / p.stem()).string() + "." + name + p.extension().string();
}

bool is_exr(const std::string& path) {
    ImageFormat format{};
    return format_from_path(path, format) && format == ImageFormat::exr;
}

}  // namespace

std::vector<std::string> frame_file_paths(const std::string& path,
                                          const std::vector<AovKind>& aovs) {
    std::vector<std::string> paths{path};
    if (!is_exr(path))
        for (AovKind k : aovs) paths.push_back(term_path(path, aov_name(k)));
    return paths;
}

std::vector<std::pair<std::string, std::string>> encode_frame_files(const Frame& frame,
                                                                    const std::string& path,
                                                                    Encoding encoding) {
    ImageFormat format{};
    format_from_path(path, format);
    std::vector<std::pair<std::string, std::string>> files;
    if (format == ImageFormat::exr) {  // one file: the image and every term as layers
        std::vector<ExrLayer> layers;
        for (const Aov& a : frame.aovs) layers.push_back({a.name, &a.image, a.scalar()});
        files.emplace_back(path, encode_image_layers(path, frame.image, layers, encoding));
        return files;
    }
    files.emplace_back(path, encode_frame(frame, path, encoding));
    const bool eight_bit = format == ImageFormat::png || format == ImageFormat::ppm;
    for (const Aov& a : frame.aovs) {
        const std::string name = term_path(path, a.name);
        // The pictures of depth, normal and tests are display values: written as they are.
        const bool picture = eight_bit && (a.scalar() || a.kind == AovKind::normal);
        files.emplace_back(name, picture ? encode_image(name, aov_picture(a), Encoding::linear)
                                         : encode_image(name, a.image, encoding));
    }
    return files;
}

void write_frame_files(const Frame& frame, const std::string& path, Encoding encoding,
                       const std::atomic<bool>* cancel) {
    std::vector<std::unique_ptr<PendingFile>> pending;
    std::vector<PendingFile*> files;
    for (auto& [name, bytes] : encode_frame_files(frame, path, encoding)) {
        pending.push_back(std::make_unique<PendingFile>(name, std::move(bytes)));
        files.push_back(pending.back().get());
    }
    commit_together(files, cancel);
}

Image frame_aa_mask(const Frame& frame) { return aa_mask_image(frame.aa_mask, frame.image); }

std::vector<uint8_t> rgba8(const Image& image, Encoding encoding) {
    std::vector<uint8_t> bytes(image.pixels.size() * 4);
    for (size_t i = 0; i < image.pixels.size(); ++i) {
        const Rgb& c = image.pixels[i];
        bytes[4 * i + 0] = encode_8bit(c.x, encoding);
        bytes[4 * i + 1] = encode_8bit(c.y, encoding);
        bytes[4 * i + 2] = encode_8bit(c.z, encoding);
        bytes[4 * i + 3] = 255;
    }
    return bytes;
}

void write_files_together(std::vector<std::pair<std::string, std::string>> files,
                          const std::atomic<bool>* cancel) {
    std::vector<std::unique_ptr<PendingFile>> pending;
    std::vector<PendingFile*> all;
    for (auto& [name, bytes] : files) {
        pending.push_back(std::make_unique<PendingFile>(name, std::move(bytes)));
        all.push_back(pending.back().get());
    }
    commit_together(all, cancel);
}

}  // namespace luz
