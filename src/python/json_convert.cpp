// Python values → JSON (the other direction is the template in json_convert.h).
#include "python/json_convert.h"

#include <cmath>
#include <vector>

#include "luz/json.h"  // kMaxJsonNesting, load_scene_value()
#include "luz/scene.h"

namespace luz::python {

namespace py = pybind11;
using Json = nlohmann::ordered_json;

namespace {

/// Walks a Python value, keeping the key path for messages.
struct Converter {
    const std::string& where;
    std::vector<std::string> path;

    std::string place() const {
        std::string s = where;
        std::string dotted;
        for (const std::string& p : path) dotted += (dotted.empty() ? "" : ".") + p;
        if (!dotted.empty()) s += ": " + dotted;
        return s;
    }

    [[noreturn]] void type_error(py::handle v) const {
        throw py::type_error(place() + ": cannot be given as " +
                             std::string(Py_TYPE(v.ptr())->tp_name) +
                             " (JSON holds dicts with str keys, lists, str, int, float, bool "
                             "and None)");
    }

    Json number(double d) const {
        if (!std::isfinite(d)) {
            throw SceneError(place() + ": not a JSON number: " +
                             std::string(std::isnan(d) ? "nan"
                                         : d > 0       ? "inf"
                                                       : "-inf"));
        }
        return Json(d);
    }

    Json integer(py::handle v) const {
        int overflow = 0;
        const long long n = PyLong_AsLongLongAndOverflow(v.ptr(), &overflow);
        if (overflow == 0) {
            if (n == -1 && PyErr_Occurred()) throw py::error_already_set();
            return Json(static_cast<int64_t>(n));
        }
        if (overflow > 0) {
            const unsigned long long u = PyLong_AsUnsignedLongLong(v.ptr());
            if (!PyErr_Occurred()) return Json(static_cast<uint64_t>(u));
            PyErr_Clear();
        }
        // Beyond 64 bits: a JSON text would hold it as a double, as here.
        const double d = PyLong_AsDouble(v.ptr());
        if (d == -1.0 && PyErr_Occurred()) {
            PyErr_Clear();
            throw SceneError(place() + ": number out of range: " + std::string(py::str(v)));
        }
        return number(d);
    }

    Json convert(py::handle v, int depth) {
        if (v.is_none()) return Json(nullptr);
        if (PyBool_Check(v.ptr())) return Json(v.ptr() == Py_True);
        if (PyLong_Check(v.ptr())) return integer(v);
        if (PyFloat_Check(v.ptr())) return number(PyFloat_AsDouble(v.ptr()));
        if (PyUnicode_Check(v.ptr())) return Json(v.cast<std::string>());
        const bool dict = PyDict_Check(v.ptr());
        const bool list = PyList_Check(v.ptr()) || PyTuple_Check(v.ptr());
        if (dict || list) {
            if (depth + 1 > kMaxJsonNesting) {
                throw SceneError(place() + ": JSON nested deeper than " +
                                 std::to_string(kMaxJsonNesting) + " levels");
            }
        }
        if (dict) {
            Json out = Json::object();
            for (auto [key, item] : py::reinterpret_borrow<py::dict>(v)) {
                if (!PyUnicode_Check(key.ptr())) {
                    throw py::type_error(place() + ": keys must be str, got " +
                                         std::string(py::repr(key)));
                }
                path.push_back(key.cast<std::string>());
                out[path.back()] = convert(item, depth + 1);
                path.pop_back();
            }
            return out;
        }
        if (list) {
            Json out = Json::array();
            const py::sequence seq = py::reinterpret_borrow<py::sequence>(v);
            for (size_t i = 0; i < seq.size(); ++i) {
                path.push_back(std::to_string(i));
                const py::object item = seq[i];
                out.push_back(convert(item, depth + 1));
                path.pop_back();
            }
            return out;
        }
        // numpy arrays and scalars (np.float32(0.5), np.array([1, 0, 0])): as Python values.
        if (py::hasattr(v, "dtype")) {
            if (py::hasattr(v, "tolist") && py::hasattr(v, "ndim") &&
                v.attr("ndim").cast<int>() > 0) {
                return convert(v.attr("tolist")(), depth);
            }
            if (py::hasattr(v, "item")) {
                const py::object item = v.attr("item")();
                if (!py::hasattr(item, "dtype")) return convert(item, depth);
            }
        }
        type_error(v);
    }
};

}  // namespace

Json to_json(py::handle value, const std::string& where) {
    Converter c{where, {}};
    return c.convert(value, 0);
}

}  // namespace luz::python
