// `luz render`: options → overrides → scene → checks → render with progress → image and stats.
#include "app/render_command.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <thread>

#include "app/memory_check.h"
#include "app/signals.h"
#include "app/stats_json.h"
#include "geometry/scene.h"
#include "image/atomic_file.h"
#include "image/image_io.h"
#include "render/progress.h"
#include "render/render.h"
#include "render/sampler.h"
#include "scene/input_error.h"
#include "scene/obj_loader.h"
#include "scene/scene_loader.h"

namespace luz {

namespace {

/// Checks a file to be written before any work: its folder exists and it is not a folder.
void check_writable_target(const std::string& path, const char* origin) {
    const std::filesystem::path dir = std::filesystem::path(path).parent_path();
    std::error_code ec;
    if (!dir.empty() && !std::filesystem::is_directory(dir, ec)) {
        throw InputError(path + ": " + origin + ": folder " + dir.string() + " does not exist");
    }
    if (std::filesystem::is_directory(path, ec)) {
        throw InputError(path + ": " + origin + ": is a folder, not a file");
    }
}

/// Checks the output image's path before any work: a known extension, a writable place.
void check_output_path(const std::string& out, const char* origin) {
    ImageFormat format;
    if (!format_from_path(out, format)) {
        const std::string ext = std::filesystem::path(out).extension().string();
        throw InputError(out + ": " + origin + ": unknown image format " +
                         (ext.empty() ? std::string("(no extension)") : "\"" + ext + "\"") +
                         ", expected .png, .ppm, .pfm or .exr");
    }
    check_writable_target(out, origin);
}

int resolved_threads(int requested) {
    if (requested > 0) return requested;
    const unsigned n = std::thread::hardware_concurrency();
    return n > 0 ? static_cast<int>(n) : 1;
}

}  // namespace

int run_render(const RenderOptions& o) {
    // 0. Ctrl-C / SIGTERM: until the render starts nothing is written, so a signal ends luz at
    //    once; from then on it cancels the render and nothing is written (app/signals.h).
    install_interrupt_handlers();
    set_interrupt_exits_now(true);

    // 1. Everything the command line alone can get wrong, before reading the scene.
    if (!o.output.empty()) check_output_path(o.output, "-o");
    if (!o.stats_file.empty()) check_writable_target(o.stats_file, "--stats");
    if (!o.aa_mask_file.empty()) check_output_path(o.aa_mask_file, "--aa-mask");
    const std::vector<Override> overrides = overrides_of(o);

    // 2. The scene, with --set and then the options applied; one validation names the key.
    //    A mesh file may take a quarter of the memory limit (its text, parse and mesh).
    set_max_text_file_bytes((o.max_memory ? *o.max_memory : default_memory_limit()) / 4);
    SceneDesc desc = load_scene(o.scene, overrides);
    for (const std::string& w : desc.warnings)
        std::fprintf(stderr, "luz: warning: %s\n", w.c_str());
    const std::string out = o.output.empty() ? desc.name + ".png" : o.output;
    if (o.output.empty()) check_output_path(out, "default output");
    check_memory(desc, o.max_memory);

    // 3. Render, with a progress bar on a terminal.
    const auto start = std::chrono::steady_clock::now();
    const Scene scene = build_scene(desc);
    ProgressBar bar(!o.quiet && stderr_is_terminal());
    RenderControl control;
    control.threads = o.threads;
    AaMask mask;
    if (!o.aa_mask_file.empty()) control.aa_mask = &mask;
    if (bar.enabled()) control.progress = [&bar](double f) { bar.update(f); };
    control.cancel = &interrupt_flag();
    RenderStats stats;
    set_interrupt_exits_now(false);
    const Image image = render(scene, control, stats);  // on a throw, ~ProgressBar ends the line
    throw_if_interrupted();                             // the image is incomplete: write nothing
    bar.finish();
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    stats.seconds = seconds;  // from scene build to image in memory (stats.h)
    if (stats.width == 0) stats.width = image.width;
    if (stats.height == 0) stats.height = image.height;
    if (stats.threads == 0) stats.threads = resolved_threads(o.threads);
    stats.peak_memory_bytes = std::max(stats.peak_memory_bytes, peak_resident_bytes());

    // 4. The files: statistics and the refinement mask to temporary files, the image
    //    atomically, then the others renamed into place, so that a failure leaves none behind.
    std::optional<PendingFile> stats_file;
    if (!o.stats_file.empty()) stats_file.emplace(o.stats_file, stats_json_text(stats, desc));
    std::optional<PendingFile> mask_file;
    if (!o.aa_mask_file.empty()) {
        mask_file.emplace(o.aa_mask_file, encode_image(o.aa_mask_file, aa_mask_image(mask, image)));
    }
    PendingFile image_file(out, encode_image(out, image, desc.image.encoding));
    throw_if_interrupted();  // the temporary files go with their destructors
    image_file.commit();
    if (stats_file) stats_file->commit();
    if (mask_file) mask_file->commit();

    if (!o.quiet) {
        std::printf("wrote %s (%d\u00d7%d, %s, %.2f s)\n", out.c_str(), image.width, image.height,
                    pipeline_name(desc.render.pipeline), seconds);
    }
    return 0;
}

}  // namespace luz
