// The per-term images' names and the arithmetic the samplers use to filter a sample's terms.
#include "render/aov.h"

#include <algorithm>

#include "scene/input_error.h"

namespace luz {

namespace {

constexpr const char* kNames[kAovCount] = {"ambient",   "diffuse", "specular", "reflected",
                                           "refracted", "emitted", "shadow",   "depth",
                                           "normal",    "tests"};

}  // namespace

const char* aov_name(AovKind kind) { return kNames[static_cast<int>(kind)]; }

std::vector<AovKind> all_aovs() {
    std::vector<AovKind> kinds;
    for (int k = 0; k < kAovCount; ++k) kinds.push_back(static_cast<AovKind>(k));
    return kinds;
}

std::vector<AovKind> parse_aov_list(const std::string& text, const std::string& origin) {
    std::vector<AovKind> kinds;
    auto add_once = [&](AovKind k) {
        if (std::find(kinds.begin(), kinds.end(), k) == kinds.end()) kinds.push_back(k);
    };
    auto valid = [] {
        std::string list;
        for (const char* n : kNames) list += std::string(n) + ", ";
        return list + "all";
    };
    size_t start = 0;
    while (true) {
        const size_t comma = text.find(',', start);
        const std::string name =
            text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
        if (name == "all") {
            for (AovKind k : all_aovs()) add_once(k);
        } else {
            int found = -1;
            for (int k = 0; k < kAovCount; ++k)
                if (name == kNames[k]) found = k;
            if (found < 0) {
                throw InputError(origin + ": unknown term \"" + name + "\"; valid: " + valid());
            }
            add_once(static_cast<AovKind>(found));
        }
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    return kinds;
}

TermSample& TermSample::operator+=(const TermSample& o) {
    colour += o.colour;
    ambient += o.ambient;
    diffuse += o.diffuse;
    specular += o.specular;
    reflected += o.reflected;
    refracted += o.refracted;
    emitted += o.emitted;
    shadow += o.shadow;
    normal += o.normal;
    depth += o.depth;
    tests += o.tests;
    return *this;
}

TermSample operator*(TermSample a, float w) {
    // A weight of 0 contributes nothing, even from a miss's infinite depth (0·∞ is NaN).
    if (w == 0.0f) return TermSample{};
    a.colour = a.colour * w;
    a.ambient = a.ambient * w;
    a.diffuse = a.diffuse * w;
    a.specular = a.specular * w;
    a.reflected = a.reflected * w;
    a.refracted = a.refracted * w;
    a.emitted = a.emitted * w;
    a.shadow = a.shadow * w;
    a.normal = a.normal * w;
    a.depth *= w;
    a.tests *= w;
    return a;
}

void put(TermOut& out, int x, int y, const TermSample& s) {
    out.image.at(x, y) = s.colour;
    const Rgb values[kAovCount] = {s.ambient, s.diffuse, s.specular,   s.reflected, s.refracted,
                                   s.emitted, s.shadow,  Rgb{s.depth}, s.normal,    Rgb{s.tests}};
    for (int k = 0; k < kAovCount; ++k)
        if (Image* plane = out.planes.plane[k]) plane->at(x, y) = values[k];
}

}  // namespace luz
