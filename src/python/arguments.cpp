// Keyword checks and conversions for luz.render() and luz.ray_tree().
#include "python/arguments.h"

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>

namespace luz::python {

namespace py = pybind11;

namespace {

std::string type_name(py::handle v) { return Py_TYPE(v.ptr())->tp_name; }

bool is_integer(py::handle v) {
    return !PyBool_Check(v.ptr()) && (PyLong_Check(v.ptr()) || PyIndex_Check(v.ptr()));
}

/// An integer's decimal text, whatever its size (the loader reports what is out of range).
std::string integer_text(py::handle v) {
    return py::str(py::reinterpret_steal<py::object>(PyNumber_Index(v.ptr()))).cast<std::string>();
}

std::optional<std::string> word(py::handle v, const char* name) {
    if (v.is_none()) return std::nullopt;
    if (!PyUnicode_Check(v.ptr())) {
        throw py::type_error(std::string(name) + ": expected a str, got " + type_name(v));
    }
    return v.cast<std::string>();
}

std::optional<std::string> integer(py::handle v, const char* name) {
    if (v.is_none()) return std::nullopt;
    if (!is_integer(v)) {
        throw py::type_error(std::string(name) + ": expected an int, got " + type_name(v));
    }
    return integer_text(v);
}

std::optional<std::string> number(py::handle v, const char* name) {
    if (v.is_none()) return std::nullopt;
    if (is_integer(v)) return integer_text(v);
    const bool real =
        PyFloat_Check(v.ptr()) || (!PyBool_Check(v.ptr()) && !PyUnicode_Check(v.ptr()) &&
                                   !PyBytes_Check(v.ptr()) && py::hasattr(v, "__float__"));
    if (!real) {
        throw py::type_error(std::string(name) + ": expected a number, got " + type_name(v));
    }
    const double d = PyFloat_AsDouble(v.ptr());
    if (d == -1.0 && PyErr_Occurred()) throw py::error_already_set();
    if (!std::isfinite(d)) {
        throw py::value_error(std::string(name) + ": expected a finite number, got " +
                              std::string(py::repr(v)));
    }
    return nlohmann::json(d).dump();  // the shortest text that reads back as the same double
}

}  // namespace

SceneOptions scene_options(py::handle pipeline, py::handle model, py::handle width,
                           py::handle height, py::handle max_depth, py::handle aa,
                           py::handle samples, py::handle threshold) {
    SceneOptions o;
    o.pipeline = word(pipeline, "pipeline");
    o.model = word(model, "model");
    o.width = integer(width, "width");
    o.height = integer(height, "height");
    o.max_depth = integer(max_depth, "max_depth");
    o.aa = word(aa, "aa");
    o.samples = integer(samples, "samples");
    o.threshold = number(threshold, "threshold");
    return o;
}

long long int_argument(py::handle v, const char* name, long long lo, long long hi) {
    if (!is_integer(v)) {
        throw py::type_error(std::string(name) + ": expected an int, got " + type_name(v));
    }
    const py::object i = py::reinterpret_steal<py::object>(PyNumber_Index(v.ptr()));
    if (!i) throw py::error_already_set();
    int overflow = 0;
    const long long n = PyLong_AsLongLongAndOverflow(i.ptr(), &overflow);
    if (overflow != 0 || n < lo || n > hi) {
        throw py::value_error(std::string(name) + ": must be in [" + std::to_string(lo) + ", " +
                              std::to_string(hi) + "], got " + std::string(py::str(i)));
    }
    return n;
}

std::optional<PixelRect> region_argument(py::handle region) {
    if (region.is_none()) return {};
    const std::string expected = "region: expected a sequence of four ints (x0, y0, x1, y1), got ";
    if (!PySequence_Check(region.ptr()) || PyUnicode_Check(region.ptr()) ||
        PyBytes_Check(region.ptr())) {
        throw py::type_error(expected + type_name(region));
    }
    const py::sequence seq = py::reinterpret_borrow<py::sequence>(region);
    if (seq.size() != 4) {
        throw py::type_error(expected + std::to_string(seq.size()) + " items");
    }
    int v[4];
    for (size_t k = 0; k < 4; ++k) {
        const py::object item = seq[k];
        if (!is_integer(item))
            throw py::type_error(expected + "an item of type " + type_name(item));
        v[k] = static_cast<int>(int_argument(item, "region", -(1ll << 30), 1ll << 30));
    }
    return PixelRect{v[0], v[1], v[2], v[3]};
}

void check_region_argument(const std::optional<PixelRect>& r, const ImageDesc& image) {
    if (!r) return;
    try {
        check_region(*r, image,
                     "region (" + std::to_string(r->x0) + ", " + std::to_string(r->y0) + ", " +
                         std::to_string(r->x1) + ", " + std::to_string(r->y1) + ")");
    } catch (const SceneError& e) {
        throw py::value_error(e.what());
    }
}

std::vector<AovKind> aov_argument(py::handle aov) {
    std::string text;
    if (aov.is_none()) return {};
    if (PyUnicode_Check(aov.ptr())) {
        text = aov.cast<std::string>();
    } else {
        if (!py::isinstance<py::iterable>(aov) || PyBytes_Check(aov.ptr())) {
            throw py::type_error("aov: expected a list of names or a str, got " + type_name(aov));
        }
        size_t names = 0;
        for (py::handle name : py::reinterpret_borrow<py::iterable>(aov)) {
            if (!PyUnicode_Check(name.ptr())) {
                throw py::type_error("aov: expected names (str), got " + type_name(name));
            }
            if (names++ > 0) text += ',';
            text += name.cast<std::string>();
        }
        if (names == 0) return {};
    }
    try {
        return parse_aov_list(text, "aov");
    } catch (const SceneError& e) {
        throw py::value_error(e.what());
    }
}

std::string path_argument(py::handle path, const char* name) {
    if (!PyUnicode_Check(path.ptr()) && !PyBytes_Check(path.ptr()) &&
        !py::hasattr(path, "__fspath__")) {
        throw py::type_error(std::string(name) + ": expected a path (str or os.PathLike), got " +
                             type_name(path));
    }
    std::string text = py::module_::import("os").attr("fsdecode")(path).cast<std::string>();
    // the operating system would read the path only up to it: "d/a\0b.png" as "d/a"
    if (text.find('\0') != std::string::npos) {
        throw py::value_error(std::string(name) + ": the path contains a NUL character");
    }
    return text;
}

}  // namespace luz::python
