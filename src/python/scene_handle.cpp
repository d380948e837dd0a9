// luz.load(): sources (path, demo, dict, Scene) to a SceneHandle, and handles derived with more
// overrides, re-using the built geometry when nothing that needs a build changed.
#include "python/scene_handle.h"

#include <algorithm>
#include <optional>

#include "luz/memory.h"
#include "python/interruptible.h"
#include "python/json_convert.h"

namespace luz::python {

namespace py = pybind11;

py::handle scene_warning_type;

std::vector<Override> set_overrides(py::handle set) {
    std::vector<Override> out;
    if (set.is_none()) return out;
    if (!PyDict_Check(set.ptr())) {
        throw py::type_error(std::string("set: expected a dict PATH → value, got ") +
                             Py_TYPE(set.ptr())->tp_name);
    }
    for (auto [key, value] : py::reinterpret_borrow<py::dict>(set)) {
        if (!PyUnicode_Check(key.ptr())) {
            throw py::type_error("set: keys are dotted key paths (str), got " +
                                 std::string(py::repr(key)));
        }
        const std::string path = key.cast<std::string>();
        out.push_back(Override{path, to_json(value, "--set " + path).dump(), "--set"});
    }
    return out;
}

namespace {

SceneRef make_handle(SceneText source, std::vector<Override> overrides) {
    auto h = std::make_shared<SceneHandle>();
    h->desc = parse_scene(source.text, source.label, source.base_dir, overrides);
    check_memory(h->desc);  // as `luz render`: before anything is built
    h->scene = build(h->desc);
    h->source = std::move(source);
    h->overrides = std::move(overrides);
    return h;
}

}  // namespace

SceneRef derive(const SceneRef& base, const std::vector<Override>& extra) {
    if (extra.empty()) return base;
    auto h = std::make_shared<SceneHandle>();
    h->source = base->source;
    h->overrides = base->overrides;
    h->overrides.insert(h->overrides.end(), extra.begin(), extra.end());
    h->desc = parse_scene(h->source.text, h->source.label, h->source.base_dir, h->overrides);
    share_meshes(base->desc, h->desc);
    check_memory(h->desc);
    h->scene = needs_rebuild(base->desc, h->desc) ? build(h->desc) : base->scene;
    return h;
}

SceneRef load_source(py::handle source, const std::vector<Override>& overrides) {
    // Reading, parsing and building run interruptibly: Ctrl-C stops a long load.
    if (py::isinstance<SceneHandle>(source)) {
        const SceneRef base = source.cast<SceneRef>();
        SceneRef h;
        run_interruptibly([&](const std::atomic<bool>&) { h = derive(base, overrides); });
        warn(h->desc, &base->desc);
        return h;
    }
    SceneText text;
    std::optional<std::string> path;  // a file or demo to read, or the dict's text
    if (PyDict_Check(source.ptr())) {
        text = {to_json(source, "<dict>").dump(), "<dict>", ""};
    } else if (PyUnicode_Check(source.ptr()) || PyBytes_Check(source.ptr()) ||
               py::hasattr(source, "__fspath__")) {
        // os.fsdecode: str as it is, bytes and path-like objects as the OS names them
        path = py::module_::import("os").attr("fsdecode")(source).cast<std::string>();
    } else {
        throw py::type_error(
            std::string("scene: expected a scene file path, \"demo:NAME\", a dict or a "
                        "luz.Scene, got ") +
            Py_TYPE(source.ptr())->tp_name);
    }
    SceneRef h;
    run_interruptibly([&](const std::atomic<bool>&) {
        if (path) text = read_scene_text(*path);
        h = make_handle(std::move(text), overrides);
    });
    warn(h->desc);
    return h;
}

void warn(const SceneDesc& desc, const SceneDesc* already) {
    for (const std::string& w : desc.warnings) {
        if (already && std::find(already->warnings.begin(), already->warnings.end(), w) !=
                           already->warnings.end()) {
            continue;
        }
        if (PyErr_WarnEx(scene_warning_type.ptr(), w.c_str(), 1) != 0) {
            throw py::error_already_set();
        }
    }
}

}  // namespace luz::python
