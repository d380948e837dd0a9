// `luz render`: options → overrides → scene → checks → render with progress → image and stats.
// A thin front end: everything it does goes through the public API (include/luz/).
#include "app/render_command.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>

#include "app/signals.h"
#include "luz/luz.h"

namespace luz {

int run_render(const RenderArgs& o) {
    // 0. Ctrl-C / SIGTERM: until the render starts nothing is written, so a signal ends luz at
    //    once; from then on it cancels the render and nothing is written (app/signals.h).
    install_interrupt_handlers();
    set_interrupt_exits_now(true);

    // 1. Everything the command line alone can get wrong, before reading the scene.
    if (!o.output.empty()) check_output_path(o.output, "-o");
    if (!o.stats_file.empty()) check_writable_target(o.stats_file, "--stats");
    if (!o.aa_mask_file.empty()) check_output_path(o.aa_mask_file, "--aa-mask");
    if (!o.checkpoint.empty()) check_writable_target(o.checkpoint, "--checkpoint");
    const std::vector<AovKind> aovs =
        o.aovs.empty() ? std::vector<AovKind>{} : parse_aov_list(o.aovs, "--aov " + o.aovs);
    const std::vector<Override> overrides = overrides_of(o);

    // 2. The scene, with --set and then the options applied; one validation names the key.
    //    A mesh file may take a quarter of the memory limit (its text, parse and mesh).
    set_max_text_file_bytes((o.max_memory ? *o.max_memory : default_memory_limit()) / 4);
    const SceneDesc desc = load_scene(o.scene, overrides);
    for (const std::string& w : desc.warnings)
        std::fprintf(stderr, "luz: warning: %s\n", w.c_str());
    const std::string out = o.output.empty() ? desc.name + ".png" : o.output;
    if (o.output.empty()) check_output_path(out, "default output");
    check_memory(desc, o.max_memory, static_cast<int>(aovs.size()));
    std::optional<PixelRect> region;
    if (o.region) region = parse_region(*o.region, desc.image);

    // 3. Build, then render with a progress bar on a terminal.
    const auto start = std::chrono::steady_clock::now();
    // --checkpoint: the file is read (and refused when it belongs to another render) before
    // any work; its key is the whole scene as the loader understood it, with the options.
    std::optional<Checkpoint> checkpoint;
    if (!o.checkpoint.empty()) {
        std::string key = scene_to_json(desc, "/") + "\naovs";
        for (AovKind k : aovs) key += std::string(" ") + aov_name(k);
        key += o.aa_mask_file.empty() ? "\nno mask" : "\nmask";
        if (o.region) key += "\nregion " + *o.region;
        checkpoint.emplace(o.checkpoint, fingerprint(key));
    }
    const Scene scene = build(desc);
    ProgressBar bar(!o.quiet && stderr_is_terminal());
    luz::RenderOptions options;
    options.control.threads = o.threads;
    options.want_aa_mask = !o.aa_mask_file.empty();
    options.aovs = aovs;
    options.region = region;
    if (bar.enabled()) options.control.progress = [&bar](double f) { bar.update(f); };
    options.control.cancel = &interrupt_flag();
    if (checkpoint) options.control.checkpoint = &*checkpoint;
    options.control.warning = [&bar](const std::string& w) { bar.interject("luz: warning: " + w); };
    set_interrupt_exits_now(false);
    Frame frame = render(scene, desc, options);  // on a throw, ~ProgressBar ends the line
    if (checkpoint && !frame.complete) checkpoint->save();  // interrupted: keep what is done
    throw_if_interrupted();  // the image is incomplete: write nothing
    bar.finish();
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    RenderStats& stats = frame.stats;
    stats.seconds = seconds;  // from scene build to image in memory (stats.h)
    stats.threads = resolve_threads(o.threads);
    stats.peak_memory_bytes = std::max(stats.peak_memory_bytes, peak_resident_bytes());

    // 4. The files: statistics and the refinement mask to temporary files, the image
    //    atomically, then the others renamed into place, so that a failure leaves none behind.
    std::optional<PendingFile> stats_file;
    if (!o.stats_file.empty()) stats_file.emplace(o.stats_file, frame_stats_json(frame, desc));
    std::optional<PendingFile> mask_file;
    if (!o.aa_mask_file.empty()) {
        mask_file.emplace(o.aa_mask_file, encode_image(o.aa_mask_file, frame_aa_mask(frame)));
    }
    // The image, then each per-term image (X.NAME.EXT, or layers of X.exr).
    std::vector<std::unique_ptr<PendingFile>> image_files;
    for (auto& [path, bytes] : encode_frame_files(frame, out, desc.image.encoding))
        image_files.push_back(std::make_unique<PendingFile>(path, bytes));
    throw_if_interrupted();  // the temporary files go with their destructors
    for (auto& f : image_files) f->commit();
    if (stats_file) stats_file->commit();
    if (mask_file) mask_file->commit();
    if (checkpoint) checkpoint->remove();  // the outputs are written: nothing left to continue

    if (!o.quiet) {
        std::printf("wrote %s (%d\u00d7%d, %s, %.2f s)\n", out.c_str(), frame.image.width,
                    frame.image.height, pipeline_name(desc.render.pipeline), seconds);
    }
    return 0;
}

}  // namespace luz
