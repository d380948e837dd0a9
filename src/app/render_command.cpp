// `luz render`: options → overrides → scene (and its frames) → checks → render with progress →
// images and stats. A thin front end: everything it does goes through the public API.
#include "app/render_command.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>

#include "app/progress_bar.h"
#include "app/signals.h"
#include "app/standard_output.h"
#include "luz/animation.h"
#include "luz/luz.h"
#include "luz/memory.h"
#include "luz/options.h"
#include "luz/pictures.h"
#include "luz/scene_text.h"
#include "luz/stats_json.h"
#include "luz_engine.h"

namespace luz {
namespace {

/// The files of one rendered frame: the refinement mask, the image, its per-term images and,
/// with the last frame, the statistics, each written to a temporary file as it is encoded.
/// commit() writes the streams among them, then renames the others into place: a failure
/// leaves none of them.
struct FrameFiles {
    PendingOutputs files;

    /// A frame rendered whole (terms, mask, a format other than PNG).
    FrameFiles(const Frame& frame, const std::string& out, const std::string& mask_path,
               Encoding encoding) {
        if (!mask_path.empty())
            add(mask_path, encode_image(mask_path, frame_aa_mask(frame), Encoding::linear));
        for (auto& [path, bytes] : encode_frame_files(frame, out, encoding))
            add(path, std::move(bytes));
    }
    /// A frame rendered straight into a PNG file (render_png()).
    FrameFiles(PngFrame& frame, const std::string& out) { add(out, std::move(frame.png)); }
    void add(const std::string& path, std::string&& bytes) { files.add(path, std::move(bytes)); }
    /// Throws Interrupted when a signal stops a stream's writing, FileError on failure.
    void commit() {
        try {
            files.commit(&interrupt_flag());
        } catch (const WriteCancelled&) {
            throw_if_interrupted();
            throw;
        }
    }
};

/// Every file `luz render` writes (each frame's image, terms and mask, the statistics, the
/// checkpoint) and reads (the scene and `inputs`, the files it named), each with its option.
/// Before the scene is loaded (`range` null), the frames' files are not known yet: only those
/// of a render without --frames and with -o are listed.
std::vector<NamedFile> render_files(const RenderArgs& o, const std::string& out,
                                    const std::vector<AovKind>& aovs, const FrameRange* range,
                                    const std::vector<std::string>& inputs) {
    std::vector<NamedFile> files;
    const auto add_frame = [&](const std::string& image, const std::string& mask) {
        const std::vector<std::string> paths = frame_file_paths(image, aovs);
        files.push_back({paths[0], o.output.empty() ? "the default output" : "-o"});
        for (size_t k = 1; k < paths.size(); ++k)
            files.push_back({paths[k], std::string("--aov ") + aov_name(aovs[k - 1])});
        if (!mask.empty()) files.push_back({mask, "--aa-mask"});
    };
    if (range && o.frames) {
        for (int f = range->first; f < range->end; ++f)
            add_frame(frame_path(out, f),
                      o.aa_mask_file.empty() ? "" : frame_path(o.aa_mask_file, f));
    } else if (!o.frames && !out.empty()) {
        add_frame(out, o.aa_mask_file);
    }
    if (!o.stats_file.empty()) files.push_back({o.stats_file, "--stats"});
    if (!o.checkpoint.empty()) files.push_back({o.checkpoint, "--checkpoint"});
    if (o.scene.rfind("demo:", 0) != 0) files.push_back({o.scene, "the scene file", false});
    for (const std::string& in : inputs)
        files.push_back({in, "the scene's mesh or MTL file", false});
    return files;
}

}  // namespace

int run_render(const RenderArgs& o, const FrameRenderer& render_frame) {
    // 0. Ctrl-C / SIGTERM: until the render starts nothing is written, so a signal ends luz at
    //    once; from then on it cancels the render and nothing is written (app/signals.h).
    install_interrupt_handlers();
    set_interrupt_exits_now(true);

    // 1. Everything the command line alone can get wrong, before reading the scene.
    if (!o.output.empty()) check_output_path(o.output, "-o");
    if (!o.stats_file.empty()) check_writable_target(o.stats_file, "--stats");
    if (!o.aa_mask_file.empty()) check_output_path(o.aa_mask_file, "--aa-mask");
    if (!o.checkpoint.empty()) check_writable_target(o.checkpoint, "--checkpoint");
    if (o.frames && !o.checkpoint.empty()) {
        throw InputError(
            "--checkpoint: cannot be used with --frames (each frame is written "
            "when done: run again with --frames from the first one missing)");
    }
    const std::vector<AovKind> aovs =
        o.aovs.empty() ? std::vector<AovKind>{} : parse_aov_list(o.aovs, "--aov " + o.aovs);
    const std::vector<Override> overrides = overrides_of(o);
    // Two names for one file (an output and another output or the scene): before reading it.
    check_distinct_files(render_files(o, o.output, aovs, nullptr, {}));

    // 2. The scene, with --set and then the options applied; one validation names the key, for
    //    every frame of an animation. A mesh file may take a quarter of the memory limit.
    set_memory_limit(o.max_memory ? *o.max_memory : default_memory_limit());
    InputFileRecorder inputs;
    const Animation animation = Animation::load(o.scene, overrides);
    const SceneDesc& first = animation.first();
    for (const std::string& w : first.warnings)
        std::fprintf(stderr, "luz: warning: %s\n", w.c_str());
    const FrameRange range = o.frames ? parse_frames(*o.frames, animation) : FrameRange{};
    const std::string out = o.output.empty() ? first.name + ".png" : o.output;
    if (o.output.empty()) check_output_path(out, "default output");
    // Memory and --region for every frame to render, before any work: a key may make a frame
    // larger or smaller than the first.
    std::optional<PixelRect> region;
    for (int f = range.first; f < range.end; ++f) {
        try {
            std::optional<SceneDesc> other;  // frame 0 is `first`: not copied
            const SceneDesc& d = f == 0 ? first : other.emplace(animation.frame(f));
            check_memory(d, o.max_memory, static_cast<int>(aovs.size()));
            if (o.region) region = parse_region(*o.region, d.image);
        } catch (const InputError& e) {
            if (f == 0) throw;
            throw InputError("--frames " + *o.frames + ": frame " + std::to_string(f) + ": " +
                             e.what());
        }
    }
    // Each frame's files: X.EXT, or X.0007.EXT with --frames. Every one of them can be
    // written (none is a folder) and none is another output or an input.
    const auto file_of = [&](const std::string& path, int f) {
        return o.frames && !path.empty() ? frame_path(path, f) : path;
    };
    const std::vector<NamedFile> files = render_files(o, out, aovs, &range, inputs.files());
    for (const NamedFile& file : files)
        if (file.output) check_writable_target(file.path, file.origin.c_str());
    check_distinct_files(files);

    // 3. Build, then render with a progress bar on a terminal.
    const auto start = std::chrono::steady_clock::now();
    // --checkpoint: the file is read (and refused when it belongs to another render) before
    // any work; its key is the whole scene as the loader understood it, with the options.
    std::optional<CheckpointFile> checkpoint;
    if (!o.checkpoint.empty()) {
        std::string key = scene_to_json(first, "/") + "\naovs";
        for (AovKind k : aovs) key += std::string(" ") + aov_name(k);
        key += o.aa_mask_file.empty() ? "\nno mask" : "\nmask";
        if (o.region) key += "\nregion " + *o.region;
        checkpoint.emplace(o.checkpoint, key);
    }
    ProgressBar bar(!o.quiet && stderr_is_terminal());
    luz::RenderOptions options;
    options.threads = o.threads;
    options.want_aa_mask = !o.aa_mask_file.empty();
    options.aovs = aovs;
    options.region = region;
    options.cancel = &interrupt_flag();
    options.warning = [&bar](const std::string& w) { bar.interject("luz: warning: " + w); };
    EngineHooks hooks;
    if (checkpoint) hooks.checkpoint = &*checkpoint;

    Scene scene;
    SceneDesc built_from;
    std::vector<RenderStats> frame_stats;
    std::vector<int> numbers;
    Frame frame;
    for (int f = range.first; f < range.end; ++f) {
        std::optional<SceneDesc> other;  // frame 0 is `first`: not copied
        const SceneDesc& desc = f == 0 ? first : other.emplace(animation.frame(f));
        if (!scene || needs_rebuild(built_from, desc)) {
            scene = build(desc);
            if (f + 1 < range.end) built_from = desc;  // only a later frame compares with it
        }
        // A PNG file with nothing else asked of the frame: render_png() (band by band where it
        // can, without a float image of the whole size).
        const bool png = is_png_path(file_of(out, f)) && aovs.empty() && o.aa_mask_file.empty();
        const int done = f - range.first;
        if (bar.enabled()) {
            options.progress = [&bar, done, n = range.count()](double p) {
                bar.update((done + p) / n);
            };
        }
        set_interrupt_exits_now(false);
        const auto frame_start = std::chrono::steady_clock::now();
        // On a throw, ~ProgressBar ends the line.
        PngFrame png_frame;
        if (png) {
            png_frame = render_frame.png(scene, desc, options, desc.image.encoding, hooks);
            frame = Frame{};
            frame.stats = png_frame.stats;
            frame.complete = png_frame.complete;
        } else {
            frame = render_frame.whole(scene, desc, options, hooks);
        }
        if (checkpoint && !frame.complete) checkpoint->save();  // interrupted: keep what is done
        throw_if_interrupted();  // the image is incomplete: write nothing
        RenderStats& stats = frame.stats;
        // From scene build (or, for later frames, the frame's own start) to image in memory.
        stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                                      (f == range.first ? start : frame_start))
                            .count();
        stats.threads = render_threads(o.threads);
        stats.peak_memory_bytes = std::max(stats.peak_memory_bytes, peak_resident_bytes());

        // 4. The files: all to temporary files, then renamed into place together (the
        //    statistics with the last frame), so that a failure leaves none of this frame
        //    behind. Finished frames stay.
        png_frame.stats = stats;
        FrameFiles files = png ? FrameFiles(png_frame, file_of(out, f))
                               : FrameFiles(frame, file_of(out, f), file_of(o.aa_mask_file, f),
                                            desc.image.encoding);
        frame_stats.push_back(stats);
        numbers.push_back(f);
        if (f + 1 == range.end && !o.stats_file.empty()) {  // the last frame: all stats known
            files.add(o.stats_file, o.frames ? animation_stats_json(frame_stats, numbers, first)
                                             : stats_json(frame.stats, first));
        }
        throw_if_interrupted();  // the temporary files go with their destructors
        files.commit();
        if (o.frames && !o.quiet && !bar.enabled()) {
            std::printf("wrote %s\n", file_of(out, f).c_str());
            flush_standard_output();  // a reader gone away stops the lines, not the frames
        }
    }
    bar.finish();
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (checkpoint) checkpoint->remove();  // the outputs are written: nothing left to continue

    if (!o.quiet) {
        if (o.frames) {
            std::printf("wrote %d frames %s … %s (%d\u00d7%d, %s, %.2f s)\n", range.count(),
                        file_of(out, range.first).c_str(), file_of(out, range.end - 1).c_str(),
                        frame.stats.width, frame.stats.height, pipeline_name(first.render.pipeline),
                        seconds);
        } else {
            std::printf("wrote %s (%d\u00d7%d, %s, %.2f s)\n", out.c_str(), frame.stats.width,
                        frame.stats.height, pipeline_name(first.render.pipeline), seconds);
        }
    }
    return 0;
}

int run_render(const RenderArgs& o) {
    FrameRenderer renderer;
    renderer.whole = [](const Scene& scene, const SceneDesc& desc, const RenderOptions& options,
                        const EngineHooks& hooks) { return render(scene, desc, options, hooks); };
    renderer.png = [](const Scene& scene, const SceneDesc& desc, const RenderOptions& options,
                      Encoding encoding, const EngineHooks& hooks) {
        return render_png(scene, desc, options, encoding, hooks);
    };
    return run_render(o, renderer);
}

}  // namespace luz
