// Lane types for arithmetic written once: a plain float (or double), or four floats side by side
// (SSE2), with the same operators and the same IEEE results lane for lane (ray_sphere.h).
#pragma once

#include <cmath>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace luz {

// ---- scalar lanes: float and double ----------------------------------------------------------

inline float lane_sqrt(float x) { return std::sqrt(x); }
inline double lane_sqrt(double x) { return std::sqrt(x); }
inline float lane_abs(float x) { return std::fabs(x); }
inline double lane_abs(double x) { return std::fabs(x); }
/// |x| with the sign of s.
inline float lane_copysign(float x, float s) { return std::copysign(x, s); }
inline double lane_copysign(double x, double s) { return std::copysign(x, s); }
/// std::min(a, b): b < a ? b : a (a when either is NaN).
inline float lane_min(float a, float b) { return b < a ? b : a; }
inline double lane_min(double a, double b) { return b < a ? b : a; }
/// std::max(a, b): a < b ? b : a (a when either is NaN).
inline float lane_max(float a, float b) { return a < b ? b : a; }
inline double lane_max(double a, double b) { return a < b ? b : a; }

#if defined(__SSE2__)

// ---- four float lanes (SSE2) -----------------------------------------------------------------

/// Four floats; arithmetic is lane by lane, comparisons give a mask (all bits set where true).
struct Float4 {
    __m128 v;
    Float4() = default;
    explicit Float4(__m128 x) : v(x) {}
    /// x in every lane.
    explicit Float4(float x) : v(_mm_set1_ps(x)) {}
    static Float4 load(const float* p) { return Float4(_mm_loadu_ps(p)); }
    void store(float* p) const { _mm_storeu_ps(p, v); }
    /// Bit k set where lane k of a mask is true.
    unsigned bits() const { return static_cast<unsigned>(_mm_movemask_ps(v)); }
};

inline Float4 operator+(Float4 a, Float4 b) { return Float4(_mm_add_ps(a.v, b.v)); }
inline Float4 operator-(Float4 a, Float4 b) { return Float4(_mm_sub_ps(a.v, b.v)); }
inline Float4 operator*(Float4 a, Float4 b) { return Float4(_mm_mul_ps(a.v, b.v)); }
inline Float4 operator/(Float4 a, Float4 b) { return Float4(_mm_div_ps(a.v, b.v)); }
/// −a: the sign bit flipped, as float negation does.
inline Float4 operator-(Float4 a) { return Float4(_mm_xor_ps(_mm_set1_ps(-0.0f), a.v)); }
inline Float4 operator<(Float4 a, Float4 b) { return Float4(_mm_cmplt_ps(a.v, b.v)); }
inline Float4 lane_sqrt(Float4 x) { return Float4(_mm_sqrt_ps(x.v)); }
inline Float4 lane_abs(Float4 x) { return Float4(_mm_andnot_ps(_mm_set1_ps(-0.0f), x.v)); }
inline Float4 lane_copysign(Float4 x, Float4 s) {
    const __m128 sign = _mm_set1_ps(-0.0f);
    return Float4(_mm_or_ps(_mm_andnot_ps(sign, x.v), _mm_and_ps(sign, s.v)));
}
/// std::min(a, b) lane by lane: _mm_min_ps(b, a) is b < a ? b : a.
inline Float4 lane_min(Float4 a, Float4 b) { return Float4(_mm_min_ps(b.v, a.v)); }
/// std::max(a, b) lane by lane: _mm_max_ps(b, a) is b > a ? b : a, i.e. a < b ? b : a.
inline Float4 lane_max(Float4 a, Float4 b) { return Float4(_mm_max_ps(b.v, a.v)); }

#endif

}  // namespace luz
