// luz in a web page (docs/WEB.md): the C calls the page's worker (web/worker.js) makes, over luz's
// public API alone. One scene at a time; strings and pixels returned stay valid until the next
// call of the same kind.
#include <emscripten/emscripten.h>

#include <algorithm>
#include <cstdint>
#include <exception>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "luz/demo_scenes.h"
#include "luz/inspect.h"
#include "luz/luz.h"
#include "luz/memory.h"
#include "luz/pictures.h"
#include "luz/scene_text.h"
#include "luz/sliders.h"

namespace {

using namespace luz;

/// What a scene may need here: a 32-bit WebAssembly memory holds at most 2 GB; half of it.
constexpr uint64_t kBrowserMemory = uint64_t{1} << 30;

struct Session {
    SceneDesc desc;  ///< the scene as last loaded, edits applied
    Scene scene;     ///< built from desc (rebuilt only when needs_rebuild says so)
    bool loaded = false;
    std::string text;           ///< the last message or JSON handed out
    std::vector<uint8_t> rgba;  ///< the last band's pixels
    RenderStats stats;          ///< the last band's statistics
    int pass_width = 0, pass_height = 0;
};

Session& session() {
    static Session s;
    return s;
}

const char* hand_out(std::string text) {
    session().text = std::move(text);
    return session().text.c_str();
}

/// The edits, one "PATH=JSON" per line (as --set takes them).
std::vector<Override> parse_sets(const std::string& lines) {
    std::vector<Override> sets;
    std::istringstream in(lines);
    for (std::string line; std::getline(in, line);)
        if (!line.empty()) sets.push_back(parse_set(line));
    return sets;
}

/// The settings of one progressive pass: the image divided by `divisor`, antialiasing only in
/// the last pass (as the native viewer's plan_passes()).
Settings pass_settings(const Settings& s, int divisor, bool antialiased) {
    Settings pass = s;
    pass.image.width = std::max(1, s.image.width / divisor);
    pass.image.height = std::max(1, s.image.height / divisor);
    if (!antialiased) pass.render.antialias.mode = AaMode::none;
    return pass;
}

}  // namespace

extern "C" {

/// Loads `source` (demo:NAME or a file in the worker's file system) with the edits `sets`.
/// Returns 1, or 0 with the message (the CLI's, one line) in luz_text(); the last good scene
/// is kept then.
EMSCRIPTEN_KEEPALIVE int luz_load(const char* source, const char* sets) {
    Session& s = session();
    try {
        SceneDesc desc = load_scene(source, parse_sets(sets));
        check_memory(desc, kBrowserMemory, 1);
        if (!s.loaded || needs_rebuild(s.desc, desc)) s.scene = build(desc);
        s.desc = std::move(desc);
        s.loaded = true;
        hand_out("");
        return 1;
    } catch (const std::exception& e) {
        hand_out(one_line(e.what()));
        return 0;
    }
}

/// The text of the last message, scene or ray tree.
EMSCRIPTEN_KEEPALIVE const char* luz_text() { return session().text.c_str(); }

/// The loaded scene as JSON (every key written): the panel reads it, "save JSON" writes it.
EMSCRIPTEN_KEEPALIVE const char* luz_scene_json() {
    return hand_out(scene_to_json(session().desc, "."));
}

/// The built-in scenes, as JSON [["demo:NAME", "description"], …].
EMSCRIPTEN_KEEPALIVE const char* luz_demos() {
    nlohmann::json list = nlohmann::json::array();
    for (const DemoScene& d : demo_scenes())
        list.push_back({"demo:" + std::string(d.name), std::string(d.description)});
    return hand_out(list.dump());
}

/// Every numeric key's slider range, as JSON {"key": [lo, hi, integer], …}.
EMSCRIPTEN_KEEPALIVE const char* luz_limits() {
    std::ostringstream out;
    out << '{';
    bool first = true;
    for (const SliderKey& k : slider_keys()) {
        const SliderRange r = slider_range(k.key);
        out << (first ? "" : ",") << '"' << k.key << "\":[" << r.lo << ',' << r.hi << ','
            << (k.integer ? 1 : 0) << ']';
        first = false;
    }
    out << '}';
    return hand_out(out.str());
}

/// Renders rows [y0, y1) of one progressive pass (resolution 1/divisor, antialiased or not);
/// term < 0: the image, else that per-term image (docs/SCENES.md#terms) as the viewer shows it.
/// Returns the rows as RGBA bytes, encoded as `luz render` writes PNG, or nullptr with luz_text()
/// set.
EMSCRIPTEN_KEEPALIVE const uint8_t* luz_render(int divisor, int antialiased, int y0, int y1,
                                               int term) {
    Session& s = session();
    try {
        const Settings pass = pass_settings(s.desc, divisor, antialiased != 0);
        s.pass_width = pass.image.width;
        s.pass_height = pass.image.height;
        RenderOptions options;
        options.threads = 1;
        options.region = PixelRect{0, y0, pass.image.width, std::min(y1, pass.image.height)};
        if (term >= 0) options.aovs = {static_cast<AovKind>(term)};
        Frame frame = render(s.scene, pass, options);
        Image picture;
        if (term >= 0) {
            Aov& a = frame.aovs.front();
            picture = a.scalar() || a.kind == AovKind::normal ? aov_picture(a) : std::move(a.image);
        } else {
            picture = std::move(frame.image);
        }
        s.stats = frame.stats;
        s.rgba = rgba8(picture, s.desc.image.encoding);
        return s.rgba.data();
    } catch (const std::exception& e) {
        hand_out(one_line(e.what()));
        return nullptr;
    }
}

/// The size of the last pass rendered, and its last band's rays (every kind) and seconds.
EMSCRIPTEN_KEEPALIVE int luz_pass_width() { return session().pass_width; }
EMSCRIPTEN_KEEPALIVE int luz_pass_height() { return session().pass_height; }
EMSCRIPTEN_KEEPALIVE double luz_band_rays() {
    const RenderStats& st = session().stats;
    const uint64_t rays =
        st.rays_primary + st.rays_shadow + st.rays_reflection + st.rays_refraction;
    return static_cast<double>(rays > 0 ? rays : st.samples);
}
EMSCRIPTEN_KEEPALIVE double luz_band_seconds() { return session().stats.seconds; }

/// The ray tree of pixel (x, y) of the full image as JSON (as `luz view --click` writes it).
EMSCRIPTEN_KEEPALIVE const char* luz_ray_tree(int x, int y) {
    Session& s = session();
    try {
        const RayTree tree = ray_tree(s.scene, s.desc, x + 0.5f, y + 0.5f);
        const Rgb pixel = tree.nodes.empty() ? Rgb{} : tree.nodes[0].colour;
        return hand_out(ray_tree_json(tree, s.desc, x, y, pixel));
    } catch (const std::exception& e) {
        return hand_out(std::string("{\"error\":\"") + one_line(e.what()) + "\"}");
    }
}

}  // extern "C"
