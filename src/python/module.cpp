// The extension module luz._luz (re-exported by the package luz, luz/__init__.py): docs/PYTHON.md
// over the public API (include/luz/), with no loader, limit or formula of its own.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <chrono>
#include <nlohmann/json.hpp>

#include "luz/demo_scenes.h"
#include "luz/inspect.h"
#include "luz/luz.h"
#include "luz/memory.h"
#include "luz/options.h"
#include "luz/presets.h"
#include "luz/progress_text.h"
#include "luz/scene_text.h"
#include "luz/stats_json.h"
#include "python/arguments.h"
#include "python/frame_object.h"
#include "python/interruptible.h"
#include "python/json_convert.h"
#include "python/render_call.h"
#include "python/scene_handle.h"

namespace py = pybind11;
using namespace pybind11::literals;

namespace luz::python {
namespace {

/// The scene a render or a ray tree uses: `scene` (a Scene or a source) with `set` and the
/// options applied after its own overrides, `set` first (as `luz render` applies --set first).
SceneRef resolve(py::handle scene, py::handle set, const SceneOptions& options) {
    std::vector<Override> overrides = set_overrides(set);
    for (Override& o : option_overrides(options)) overrides.push_back(std::move(o));
    return load_source(scene, overrides);
}

std::shared_ptr<FrameObject> render_py(py::handle scene, py::handle pipeline, py::handle model,
                                       py::handle width, py::handle height, py::handle max_depth,
                                       py::handle aa, py::handle samples, py::handle threshold,
                                       py::handle threads, py::handle aov, py::handle set,
                                       py::handle region, py::handle progress) {
    // Every argument is checked before any work.
    const SceneOptions options =
        scene_options(pipeline, model, width, height, max_depth, aa, samples, threshold);
    RenderOptions render_options;
    render_options.threads = static_cast<int>(int_argument(threads, "threads", 0, 4096));
    render_options.aovs = aov_argument(aov);
    render_options.region = region_argument(region);
    const bool callable = !PyBool_Check(progress.ptr()) && PyCallable_Check(progress.ptr());
    if (!PyBool_Check(progress.ptr()) && !callable && !progress.is_none()) {
        throw py::type_error(std::string("progress: expected a bool or a callable, got ") +
                             Py_TYPE(progress.ptr())->tp_name);
    }

    const auto start = std::chrono::steady_clock::now();
    const SceneRef resolved = resolve(scene, set, options);
    check_region_argument(render_options.region, resolved->desc.image);
    py::object bar;  // progress: None, a luz._progress.Bar, or the caller's callable
    if (callable) {
        bar = py::reinterpret_borrow<py::object>(progress);
    } else if (progress.ptr() == Py_True) {
        bar = py::module_::import("luz._progress").attr("Bar")();
    }
    auto out = std::make_shared<FrameObject>();
    try {
        out->frame = render_interruptibly(resolved, render_options, bar);
    } catch (...) {
        if (bar && py::hasattr(bar, "close")) bar.attr("close")();
        throw;
    }
    if (bar) {
        bar(1.0);
        if (py::hasattr(bar, "close")) bar.attr("close")();
    }
    // As `luz render` reports them (app/render_command.cpp).
    RenderStats& stats = out->frame.stats;
    stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    stats.threads = render_threads(render_options.threads);
    stats.peak_memory_bytes = std::max(stats.peak_memory_bytes, peak_resident_bytes());
    out->scene = resolved;
    return out;
}

py::object ray_tree_py(py::handle scene, py::handle px, py::handle py_, py::handle pipeline,
                       py::handle model, py::handle width, py::handle height, py::handle max_depth,
                       py::handle set) {
    const SceneOptions options = scene_options(pipeline, model, width, height, max_depth,
                                               py::none(), py::none(), py::none());
    const SceneRef s = resolve(scene, set, options);
    const int x = static_cast<int>(int_argument(px, "px", 0, s->desc.image.width - 1));
    const int y = static_cast<int>(int_argument(py_, "py", 0, s->desc.image.height - 1));
    std::string text;
    run_interruptibly([&](const std::atomic<bool>&) {
        const RayTree tree = ray_tree(s->scene, s->desc, x + 0.5f, y + 0.5f);
        // The pixel's value: its centre sample's colour (the tree's total).
        const Rgb pixel = tree.nodes.empty() ? Rgb{} : tree.nodes[0].colour;
        text = ray_tree_json(tree, s->desc, x, y, pixel);
    });
    return to_python(nlohmann::ordered_json::parse(text));
}

py::dict scenes_py() {
    py::dict d;
    for (const DemoScene& s : demo_scenes())
        d[py::str("demo:" + std::string(s.name))] = py::str(std::string(s.description));
    return d;
}

py::dict materials_py() {
    py::dict d;
    auto rgb = [](const Rgb& c) {
        py::list l;
        l.append(c.x);
        l.append(c.y);
        l.append(c.z);
        return l;
    };
    for (const Preset& p : presets()) {
        const Material& m = p.material;
        d[py::str(std::string(p.name))] = py::dict(
            "alias"_a = std::string(p.alias), "description"_a = std::string(p.description),
            "ka"_a = rgb(m.ka), "kd"_a = rgb(m.kd), "ks"_a = rgb(m.ks), "n"_a = m.n,
            "reflection"_a = m.reflection, "transparency"_a = m.transparency, "ior"_a = m.ior);
    }
    return d;
}

}  // namespace
}  // namespace luz::python

namespace luz::python {
namespace {

constexpr const char* kModuleDoc = R"(luz's renderer (the extension module; use the package luz).)";

constexpr const char* kLoadDoc = R"(load(source, set=None) -> Scene

Loads and builds a scene.

source: a scene file path (str or os.PathLike), "demo:NAME" (see scenes()), a dict holding
    the scene as its JSON file would, or a Scene (then `set` is applied on top of its own).
set: a dict {PATH: value} applied like `luz render --set PATH=JSON`, in order: dotted key
    paths ("materials.red.n", "lights.0.intensity"), values as JSON (numbers, str, lists,
    dicts, bool, None).

Raises SceneError (a ValueError) with the command line's one-line message for bad input,
TypeError for a wrong argument type. Warnings (a missing MTL file …) are SceneWarning.
Ctrl-C (KeyboardInterrupt) stops a long load or build within a second.)";

constexpr const char* kRenderDoc =
    R"(render(scene, *, pipeline=None, model=None, width=None, height=None, max_depth=None, aa=None, samples=None, threshold=None, threads=0, aov=(), set=None, region=None, progress=False) -> Frame

Renders a scene: the same pixels, bit for bit, as `luz render` with the same options.

scene: a Scene, or anything load() takes (a path, "demo:NAME", a dict).
pipeline: "zbuffer", "raycast" or "raytrace" (render.pipeline).
model: "lambert" or "phong" (render.model).
width, height: the image size in pixels (image.width, image.height).
max_depth: the ray tree's depth in raytrace (render.max_depth).
aa: "none", "grid" or "adaptive" (render.antialias.mode).
samples: samples per pixel for grid antialiasing, a perfect square (render.antialias.samples).
threshold: the colour difference that splits a pixel in adaptive antialiasing
    (render.antialias.threshold).
    Each of these means what the `luz render` option of that name means; None keeps the
    scene's value.
threads: worker threads; 0 (default) uses every core. The image does not depend on it.
aov: per-term images to make too (docs/SCENES.md#terms): names among ambient, diffuse, specular,
    reflected, refracted, emitted, shadow, depth, normal, tests, or "all"; a list or a
    comma-separated str. They are in Frame.aov.
set: a dict {PATH: value} applied like --set, before the options above.
region: (x0, y0, x1, y1), x1 and y1 exclusive: renders only that rectangle, as --region; the
    Frame is x1-x0 by y1-y0 and its pixels are those of the same rectangle of the whole render.
progress: True draws a progress bar (tqdm when installed, else a line on sys.stderr); a
    callable is called with the fraction done (0..1) instead, from the calling thread.

The GIL is released while rendering (other Python threads run; several threads may render
at once). Ctrl-C (KeyboardInterrupt) stops the render within a second.
Raises SceneError (a ValueError) for a bad scene or option value, TypeError for a wrong
argument type, ValueError for a bad threads or aov.)";

constexpr const char* kRayTreeDoc =
    R"(ray_tree(scene, px, py, *, pipeline=None, model=None, width=None, height=None, max_depth=None, set=None) -> dict

The ray tree of pixel (px, py) — column px, row py, row 0 on top — traced through the pixel's
centre, as the viewer (`luz view`) shows it: every ray traced for it with the numbers shade()
and trace() used. Keys: pixel, pixel_value (the centre sample's colour), pipeline,
traced_as_raycast (a zbuffer scene is traced as raycast), colour, nodes (parents before
children: kind, depth, parent, origin, direction, hit, t, object, object_label, material,
point, normal, flipped, ambient, lights [visibility, distance, cos_theta, cos_alpha, diffuse,
specular], local, total_internal_reflection, reflection_child, refraction_child, returned, A,
coefficient, contribution, colour).

scene, set and the options: as for render().)";

constexpr const char* kScenesDoc = R"(scenes() -> dict

The built-in scenes, as `luz scenes` lists them: {"demo:NAME": description}. Each name can be
given wherever a scene is (load("demo:whitted"), render("demo:primitives")).)";

constexpr const char* kMaterialsDoc = R"(materials() -> dict

The material presets, as `luz materials` lists them: {name: {"alias", "description", "ka",
"kd", "ks", "n", "reflection", "transparency", "ior"}}. A scene names one (or its alias) as an
object's "material", or as a material's "preset".)";

constexpr const char* kSceneDoc = R"(A loaded and built scene (see load()). Immutable: render it
any number of times, from any number of threads, with any options; options that change only
settings (image, camera, pipeline, model, antialiasing, lights, materials) reuse its geometry.)";

constexpr const char* kFrameDoc = R"(What a render made (see render()).

image: numpy float32 array (height, width, 3), linear, unclamped, row 0 on top.
aov: dict name → numpy float32 array: colour terms and normal (height, width, 3), depth and
    tests (height, width).
stats: dict, the `luz render --stats` JSON.
save(path): writes the image files as `luz render -o path` does.

image and aov are views over the frame's own memory (no copy): editing them edits the frame,
and the frame lives as long as any of them does. In Jupyter a Frame shows as its picture.)";

const char* pipeline_text(Pipeline p) { return pipeline_name(p); }

/// luz.SceneError (held for the life of the process).
py::handle scene_error_type;

/// Raises `type` with `message` as `luz` prints it (app/main.cpp): one line, control bytes
/// quoted from a bad file shown as '?', bytes that are not UTF-8 replaced.
void set_error(PyObject* type, const std::string& message) {
    const std::string line = one_line(message);
    PyObject* text =
        PyUnicode_DecodeUTF8(line.data(), static_cast<Py_ssize_t>(line.size()), "replace");
    if (!text) return;  // the decoding error stays set
    PyErr_SetObject(type, text);
    Py_DECREF(text);
}

}  // namespace
}  // namespace luz::python

PYBIND11_MODULE(_luz, m) {
    using namespace luz;
    using namespace luz::python;
    m.doc() = kModuleDoc;
    // The docstrings start with their own signature (pybind11's would show every keyword's
    // type as `object`: they are checked here, to name the argument in errors).
    py::options options;
    options.disable_function_signatures();
    m.attr("__version__") = LUZ_VERSION;

    // Work still running in other threads when the interpreter exits is cancelled and joined
    // first (python/interruptible.h).
    py::module_::import("atexit").attr("register")(
        py::cpp_function(&cancel_all_at_exit, py::name("_cancel_all_at_exit")));

    // The memory limit `luz render` has by default (a scene or mesh file may take a quarter).
    set_memory_limit(default_memory_limit());

    // Both exception classes are held for the life of the process.
    scene_error_type = PyErr_NewExceptionWithDoc(
        "luz._luz.SceneError",
        "Bad input (a scene file or dict, an override, an option value): the message is the "
        "command line's one line naming the file (or <dict>, --set …), the place and what is "
        "wrong. A ValueError.",
        PyExc_ValueError, nullptr);
    scene_warning_type = PyErr_NewExceptionWithDoc(
        "luz._luz.SceneWarning",
        "A problem in the input that does not stop the render (a missing MTL file, an unknown "
        "usemtl …): what `luz render` prints as `luz: warning: …`.",
        PyExc_UserWarning, nullptr);
    if (!scene_error_type || !scene_warning_type) throw py::error_already_set();
    m.add_object("SceneError", scene_error_type);
    m.add_object("SceneWarning", scene_warning_type);
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const InputError& e) {
            set_error(scene_error_type.ptr(), e.what());
        } catch (const FileError& e) {
            set_error(PyExc_OSError, e.what());
        }
    });

    py::class_<SceneHandle, std::shared_ptr<SceneHandle>>(m, "Scene", kSceneDoc)
        .def_property_readonly(
            "source", [](const SceneHandle& s) { return s.source.label; },
            "Where the scene came from: its file, \"demo:NAME\" or \"<dict>\".")
        .def_property_readonly(
            "name", [](const SceneHandle& s) { return s.desc.name; },
            "The file's stem or the demo's name (`luz render`'s default output is NAME.png).")
        .def_property_readonly(
            "width", [](const SceneHandle& s) { return s.desc.image.width; }, "image.width")
        .def_property_readonly(
            "height", [](const SceneHandle& s) { return s.desc.image.height; }, "image.height")
        .def_property_readonly(
            "pipeline", [](const SceneHandle& s) { return pipeline_text(s.desc.render.pipeline); },
            "render.pipeline")
        .def_property_readonly(
            "warnings", [](const SceneHandle& s) { return s.desc.warnings; },
            "The input's warnings (also issued as SceneWarning when loaded).")
        .def(
            "to_dict",
            [](const SceneHandle& s) {
                return to_python(nlohmann::ordered_json::parse(scene_to_json(s.desc, "")));
            },
            "The scene as a dict with every key and default filled in (what `luz view` "
            "saves): load(scene.to_dict()) gives the same scene.")
        .def("__repr__", [](const SceneHandle& s) {
            return "<luz.Scene " + s.source.label + ": " + std::to_string(s.desc.image.width) +
                   "\u00d7" + std::to_string(s.desc.image.height) + ", " +
                   pipeline_text(s.desc.render.pipeline) + ", " +
                   std::to_string(s.desc.objects.size()) + " objects, " +
                   std::to_string(s.desc.lights.size()) + " lights>";
        });

    py::class_<FrameObject, std::shared_ptr<FrameObject>>(m, "Frame", kFrameDoc)
        .def_property_readonly(
            "image",
            [](py::object self) {
                return image_view(self.cast<FrameObject&>().frame.image, false, self);
            },
            "numpy float32 (height, width, 3): linear, unclamped, row 0 on top; a view over the "
            "frame's memory.")
        .def_property_readonly(
            "aov",
            [](py::object self) {
                py::dict d;
                for (const Aov& a : self.cast<FrameObject&>().frame.aovs)
                    d[py::str(a.name)] = image_view(a.image, a.scalar(), self);
                return d;
            },
            "dict name → numpy float32 view: the per-term images asked for with aov= (colour "
            "terms and normal (height, width, 3); depth and tests (height, width)).")
        .def_property_readonly(
            "stats", [](const FrameObject& f) { return frame_stats(f); },
            "dict: the statistics `luz render --stats FILE` writes.")
        .def_property_readonly(
            "width", [](const FrameObject& f) { return f.frame.image.width; }, "pixels")
        .def_property_readonly(
            "height", [](const FrameObject& f) { return f.frame.image.height; }, "pixels")
        .def(
            "save",
            [](const FrameObject& f, py::handle path) {
                save_frame(f, path_argument(path, "path"));
            },
            "path"_a,
            "save(path): writes the image (and each per-term image) as `luz render -o path` "
            "does: the extension picks the format (.png .ppm .pfm .exr), written atomically; "
            "per-term images go to PATH-STEM.NAME.EXT, or into the .exr as layers. Raises "
            "SceneError for an unknown extension or a missing folder, OSError when it cannot "
            "write.")
        .def("_repr_png_", &frame_png,
             "The PNG bytes `luz render -o X.png` writes (Jupyter shows the frame with it).")
        .def("__repr__", [](const FrameObject& f) {
            char buf[160];
            std::snprintf(buf, sizeof buf, "<luz.Frame %d\u00d7%d, %s, %.3f s>",
                          f.frame.image.width, f.frame.image.height,
                          pipeline_text(f.scene->desc.render.pipeline), f.frame.stats.seconds);
            return std::string(buf);
        });

    m.def(
        "load",
        [](py::handle source, py::handle set) { return load_source(source, set_overrides(set)); },
        kLoadDoc, "source"_a, "set"_a = py::none());
    m.def("render", &render_py, kRenderDoc, "scene"_a, py::kw_only(), "pipeline"_a = py::none(),
          "model"_a = py::none(), "width"_a = py::none(), "height"_a = py::none(),
          "max_depth"_a = py::none(), "aa"_a = py::none(), "samples"_a = py::none(),
          "threshold"_a = py::none(), "threads"_a = 0, "aov"_a = py::tuple(), "set"_a = py::none(),
          "region"_a = py::none(), "progress"_a = false);
    m.def("ray_tree", &ray_tree_py, kRayTreeDoc, "scene"_a, "px"_a, "py"_a, py::kw_only(),
          "pipeline"_a = py::none(), "model"_a = py::none(), "width"_a = py::none(),
          "height"_a = py::none(), "max_depth"_a = py::none(), "set"_a = py::none());
    m.def("scenes", &scenes_py, kScenesDoc);
    m.def("materials", &materials_py, kMaterialsDoc);
    m.def("_progress_status", &luz::format_status, "fraction"_a, "elapsed"_a,
          "The words of `luz render`'s progress line after its bar: \"0.04%  ETA 3h05m\" "
          "(luz._progress.Bar shows them too).");
}
