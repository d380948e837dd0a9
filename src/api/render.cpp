// The public render(), render_png() and ray_tree(): a built Scene with any Settings
// (include/luz/render.h, render_png.h, inspect.h), and their twins with the engine's hooks
// (engine/luz_engine.h).
#include "luz/render.h"

#include <algorithm>
#include <chrono>
#include <string>

#include "api/built_scene.h"
#include "engine/luz_engine.h"
#include "image/image_io.h"
#include "luz/inspect.h"     // ray_tree(), project_point()
#include "luz/options.h"     // check_region(), parse_region()
#include "luz/render_png.h"  // render_png()
#include "render/aov.h"
#include "render/checkpoint.h"
#include "render/parallel.h"
#include "render/ray_tree.h"
#include "render/render.h"
#include "render/tiles.h"
#include "scene/camera.h"

namespace luz {

namespace {

/// The settings must name every material the scene's objects use.
void check_fits(const Scene& scene, const Settings& settings) {
    if (settings.materials.size() < scene.material_count()) {
        throw SceneError("settings: materials: the scene's objects use " +
                         std::to_string(scene.material_count()) + " materials, got " +
                         std::to_string(settings.materials.size()));
    }
}

/// The pixels of `region` of every image of the frame (the whole-size render's).
void crop_frame(Frame& frame, const PixelRect& r, RenderStats& stats) {
    frame.image = crop(frame.image, r.x0, r.y0, r.width(), r.height());
    for (Aov& a : frame.aovs) a.image = crop(a.image, r.x0, r.y0, r.width(), r.height());
    if (!frame.aa_mask.level.empty()) {
        AaMask m{r.width(), r.height(), {}};
        m.level.reserve(static_cast<size_t>(r.width()) * r.height());
        for (int y = r.y0; y < r.y1; ++y) {
            const auto row =
                frame.aa_mask.level.begin() + static_cast<std::ptrdiff_t>(y) * frame.aa_mask.width;
            m.level.insert(m.level.end(), row + r.x0, row + r.x1);
        }
        frame.aa_mask = std::move(m);
    }
    stats.width = r.width();
    stats.height = r.height();
    const int corners[4] = {r.x0, r.y0, r.x1, r.y1};
    std::copy(corners, corners + 4, stats.region);
}

/// The most rows render_png() renders and compresses at a time: each band costs a parallel pass
/// of its own, while a smaller buffer spares the first touch of fresh memory; bands of about
/// 1024 rows keep most of the saving on large images and cost nothing below 1024 rows
/// (docs/BENCHMARKS.md, "PNG bands").
constexpr int kMaxPngRows = 16 * PngBands::kBandRows;

/// Rows per band for an image of h rows: as few bands as kMaxPngRows allows, of equal height
/// rounded up to whole PNG bands (which are whole sampler tiles).
int png_band_rows(int h) {
    static_assert(PngBands::kBandRows % kSamplerTile == 0);
    const int bands = (h + kMaxPngRows - 1) / kMaxPngRows;
    const int rows = (h + bands - 1) / bands;
    constexpr int B = PngBands::kBandRows;
    return std::min(h, (rows + B - 1) / B * B);
}

/// The image as a PNG file, rendered and compressed band by band into one buffer of rows;
/// requires renders_in_rows().
PngFrame render_png_bands(const BuiltScene& scene, const Settings& settings,
                          const RenderControl& control, Encoding encoding) {
    const int w = settings.image.width, h = settings.image.height;
    const int band_rows = png_band_rows(h);
    PngFrame frame;
    PngBands png(w, h, encoding);
    Image rows(w, band_rows, Unwritten{});
    RenderControl band = control;
    const auto cancelled = [&] { return control.cancel && control.cancel->load(); };
    for (int y0 = 0; y0 < h && !cancelled(); y0 += band_rows) {
        const int count = std::min(band_rows, h - y0);
        if (control.progress) {
            band.progress = [&, y0, count](double p) { control.progress((y0 + p * count) / h); };
        }
        render_rows(scene, settings, band, y0, count, rows, frame.stats);
        if (!cancelled()) png.add(rows, count);
    }
    frame.complete = !cancelled();
    if (frame.complete) frame.png = png.finish();
    return frame;
}

/// What the render layer is told: the options and the hooks.
RenderControl control_of(const RenderOptions& options, const EngineHooks& hooks) {
    RenderControl control;
    control.threads = options.threads;
    control.progress = options.progress;
    control.cancel = options.cancel;
    control.warning = options.warning;
    control.region = options.region.value_or(PixelRect{});
    control.checkpoint = hooks.checkpoint ? &hooks.checkpoint->checkpoint() : nullptr;
    control.share = hooks.share;
    return control;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

void check_region(const PixelRect& r, const ImageDesc& image, const std::string& what) {
    if (r.empty()) {
        throw SceneError(what + ": the region is empty (X1 must be greater than X0, Y1 than Y0)");
    }
    if (r.x0 < 0 || r.y0 < 0 || r.x1 > image.width || r.y1 > image.height) {
        throw SceneError(what + ": outside the " + std::to_string(image.width) + "x" +
                         std::to_string(image.height) + " image (X0,Y0 from 0,0; X1,Y1 up to " +
                         std::to_string(image.width) + "," + std::to_string(image.height) + ")");
    }
}

PixelRect parse_region(const std::string& text, const ImageDesc& image) {
    const std::string what = "--region " + text;
    int v[4];
    size_t k = 0, at = 0;
    for (; k < 4 && at <= text.size(); ++k) {
        const size_t comma = std::min(text.find(',', at), text.size());
        const std::string part = text.substr(at, comma - at);
        const size_t digits = part.size() - (!part.empty() && part[0] == '-' ? 1 : 0);
        if (digits == 0 || digits > 9 ||
            !std::all_of(part.end() - static_cast<std::ptrdiff_t>(digits), part.end(),
                         [](char c) { return c >= '0' && c <= '9'; })) {
            break;
        }
        v[k] = std::stoi(part);
        at = comma + 1;
    }
    if (k != 4 || at != text.size() + 1) {
        throw SceneError(what + ": expected four integers X0,Y0,X1,Y1 (X1, Y1 exclusive)");
    }
    const PixelRect r{v[0], v[1], v[2], v[3]};
    check_region(r, image, what);
    return r;
}

Frame render(const Scene& scene, const Settings& settings, const RenderOptions& options) {
    return render(scene, settings, options, EngineHooks{});
}

Frame render(const Scene& scene, const Settings& settings, const RenderOptions& options,
             const EngineHooks& hooks) {
    check_fits(scene, settings);
    scene.prepare(settings.render.pipeline);
    const bool region = options.region.has_value();
    if (region) check_region(*options.region, settings.image, "region");
    Frame frame;
    RenderControl control = control_of(options, hooks);
    control.aa_mask = options.want_aa_mask ? &frame.aa_mask : nullptr;
    // The per-term images asked for, each once, in the order asked; the pipelines fill them.
    TermPlanes planes;
    for (AovKind kind : options.aovs) {
        bool seen = false;
        for (const Aov& a : frame.aovs) seen = seen || a.kind == kind;
        if (!seen) {
            // A region's images are cut from whole-size ones whose other pixels are never read.
            const int w = settings.image.width, h = settings.image.height;
            frame.aovs.push_back(
                Aov{kind, aov_name(kind), region ? Image(w, h, Unwritten{}) : Image(w, h)});
        }
    }
    for (Aov& a : frame.aovs) planes.plane[static_cast<int>(a.kind)] = &a.image;
    control.terms = planes.any() ? &planes : nullptr;
    frame.image = render(built_scene(scene), settings, control, frame.stats);
    frame.complete = !(control.cancel && control.cancel->load());
    if (region) crop_frame(frame, *options.region, frame.stats);
    return frame;
}

PngFrame render_png(const Scene& scene, const Settings& settings, const RenderOptions& options,
                    Encoding encoding) {
    return render_png(scene, settings, options, encoding, EngineHooks{});
}

PngFrame render_png(const Scene& scene, const Settings& settings, const RenderOptions& options,
                    Encoding encoding, const EngineHooks& hooks) {
    const auto start = std::chrono::steady_clock::now();
    check_fits(scene, settings);
    scene.prepare(settings.render.pipeline);
    const RenderControl control = control_of(options, hooks);
    if (options.aovs.empty() && !options.want_aa_mask && !options.region &&
        renders_in_rows(settings, control)) {
        PngFrame frame = render_png_bands(built_scene(scene), settings, control, encoding);
        frame.stats.seconds = seconds_since(start);
        return frame;
    }
    Frame whole = render(scene, settings, options, hooks);
    PngFrame frame;
    frame.stats = whole.stats;
    frame.complete = whole.complete;
    if (frame.complete) frame.png = encode_image("frame.png", whole.image, encoding);
    return frame;
}

int render_threads(int requested) { return resolve_threads(requested); }

bool project_point(const Settings& settings, const Vec3& p, float& px, float& py) {
    const Camera cam = Camera::from(settings.camera, settings.image.width, settings.image.height);
    const Vec3 v = cam.to_view(p);
    float nx, ny;
    if (cam.projection == Projection::orthographic) {
        nx = v.x / cam.half_width;
        ny = v.y / cam.half_height;
    } else {
        if (v.z <= 1e-4f) return false;
        nx = v.x / (v.z * cam.half_width);
        ny = v.y / (v.z * cam.half_height);
    }
    px = (nx + 1) * 0.5f * static_cast<float>(cam.width);
    py = (1 - ny) * 0.5f * static_cast<float>(cam.height);
    return true;
}

RayTree ray_tree(const Scene& scene, const Settings& settings, float px, float py) {
    check_fits(scene, settings);
    scene.prepare(settings.render.pipeline == Pipeline::zbuffer ? Pipeline::raycast
                                                                : settings.render.pipeline);
    return trace_ray_tree(built_scene(scene), settings, px, py);
}

}  // namespace luz
