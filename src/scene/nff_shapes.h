// NFF's spheres, cylinders and cones (its `s` and `c` statements): the document's object of
// each, or the ObjectDesc the loader would read from that object (NffScene::direct), and the
// JSON builders the NFF reader writes its document with.
#pragma once

#include <utility>

#include "luz/object_desc.h"
#include "scene/json_text.h"

namespace luz::loader {

/// A sphere, or an open cylinder or cone, as an NFF statement gives it.
struct NffShape {
    ShapeType type = ShapeType::sphere;
    Vec3 point;             ///< sphere: centre; cylinder, cone: base (the wider end)
    double axis[3] = {};    ///< cylinder, cone: the unit axis, as the document writes it
    float radius = 0;       ///< sphere, cylinder, cone (the base)
    float apex_radius = 0;  ///< cone
    double height = 0;      ///< cylinder, cone
};

/// The shape's object in the document ("type", its keys; no "material").
Json shape_json(const NffShape& s);

/// Thrown by shape_object() when the document's object would be refused: the file is then to be
/// read through the document, for its message.
struct NffNotDirect {};

/// The object the loader reads from shape_json(s), its material and path not set; NffNotDirect
/// where that reading would fail (a number out of its range, a direction that cannot be
/// normalised, check_shape()).
ObjectDesc shape_object(const NffShape& s);

/// [x, y, z], and an object's keys in order: built element by element, as an initializer list
/// would copy each value (and each key–value pair) through temporaries, thousands of times.
template <class T>
Json json_array3(T x, T y, T z) {
    Json a(Json::value_t::array);
    auto& elements = a.get_ref<Json::array_t&>();
    elements.reserve(3);
    elements.emplace_back(x);
    elements.emplace_back(y);
    elements.emplace_back(z);
    return a;
}
inline Json json_vec(const Vec3& v) { return json_array3(v.x, v.y, v.z); }
template <class... Value>
Json json_object(std::pair<const char*, Value>... kv) {
    Json o(Json::value_t::object);
    auto& members = o.get_ref<Json::object_t&>();
    members.reserve(sizeof...(kv) + 1);  // and the material the reader may append
    (members.emplace_back(kv.first, std::move(kv.second)), ...);
    return o;
}

}  // namespace luz::loader
