// Python values ↔ JSON: a dict scene and `set=` values become JSON for the one loader; the
// statistics and the ray tree (JSON in the library) become dicts.
#pragma once

#include <pybind11/pybind11.h>

#include <nlohmann/json.hpp>
#include <string>

namespace luz::python {

/// `value` as JSON: dict (str keys) → object, list or tuple → array, str, bool, int, float,
/// None → null, numpy scalars and arrays through item()/tolist(). `where` names it in messages
/// ("<dict>", "--set PATH"), followed by the key path inside it. Throws pybind11::type_error for
/// what JSON cannot hold, SceneError for a non-finite or out-of-range number and for nesting
/// deeper than the loader accepts (so that a self-containing dict ends too).
nlohmann::ordered_json to_json(pybind11::handle value, const std::string& where);

/// A JSON value as Python: object → dict (in the value's key order), array → list, string,
/// number, boolean, null → None.
template <class Json>
pybind11::object to_python(const Json& value) {
    namespace py = pybind11;
    switch (value.type()) {
        case Json::value_t::object: {
            py::dict d;
            for (auto it = value.begin(); it != value.end(); ++it)
                d[py::str(it.key())] = to_python(it.value());
            return d;
        }
        case Json::value_t::array: {
            py::list l(value.size());
            for (size_t i = 0; i < value.size(); ++i) l[i] = to_python(value[i]);
            return l;
        }
        case Json::value_t::string:
            return py::str(value.template get_ref<const std::string&>());
        case Json::value_t::boolean:
            return py::bool_(value.template get<bool>());
        case Json::value_t::number_integer:
            return py::int_(value.template get<int64_t>());
        case Json::value_t::number_unsigned:
            return py::int_(value.template get<uint64_t>());
        case Json::value_t::number_float:
            return py::float_(value.template get<double>());
        default:
            return py::none();
    }
}

}  // namespace luz::python
