// The per-term images of docs/SCENES.md#terms (AOVs): their names, which of them a render fills,
// and the terms of one sample that the samplers filter like the colour.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <type_traits>
#include <vector>

#include "image/image.h"
#include "luz/terms.h"
#include "math/vec3.h"

namespace luz {

/// One sample's terms (docs/SCENES.md#terms), computed at its primary hit by the pipeline that made
/// its colour: colour = ambient + diffuse + specular + reflected + refracted + emitted. The
/// samplers combine samples of this type with the same weights as the colour.
struct TermSample {
    Rgb colour;
    Rgb ambient, diffuse, specular, reflected, refracted, emitted, shadow;
    Rgb normal;
    float depth = 0;
    float tests = 0;

    TermSample& operator+=(const TermSample& o);
    friend TermSample operator+(TermSample a, const TermSample& b) { return a += b; }
    friend TermSample operator*(TermSample a, float w);
};

/// The colour the adaptive sampler compares (its threshold is on the colour alone).
inline const Rgb& colour_of(const Rgb& c) { return c; }
inline const Rgb& colour_of(const TermSample& s) { return s.colour; }

/// The images a render fills with the terms asked for (null: not asked for), each the image's
/// size; scalar terms are written to all three channels.
struct TermPlanes {
    std::array<Image*, kAovCount> plane{};

    bool any() const {
        for (const Image* p : plane)
            if (p) return true;
        return false;
    }
};

/// Where the samplers put a pixel's filtered value: the image alone (Rgb samples), or the image
/// and the term planes (TermSample samples).
inline void put(Image& out, int x, int y, const Rgb& colour) { out.at(x, y) = colour; }

/// Rows of an image kept apart (render_rows()): pixel (x, y) of the image is rows.at(x, y − y0).
struct ImageRows {
    Image& rows;
    int y0;
};
inline void put(ImageRows& out, int x, int y, const Rgb& colour) {
    out.rows.at(x, y - out.y0) = colour;
}

struct TermOut {
    Image& image;
    const TermPlanes& planes;
};
void put(TermOut& out, int x, int y, const TermSample& s);

/// The sample type an output takes: Rgb for an Image, TermSample for a TermOut.
template <class Out>
using SampleFor = std::conditional_t<std::is_same_v<Out, TermOut>, TermSample, Rgb>;

}  // namespace luz
