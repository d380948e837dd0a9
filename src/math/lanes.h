// luz's one SIMD vocabulary: lane types and the free functions over them — scalar lanes
// (float, double) here, four lanes in lane4.h, eight in lane8.h, lane masks counted in
// lane_count.h. The ISA branches (SSE2, AVX, AVX2, FMA, POPCNT) live in these headers only.
#pragma once

#include <cmath>

#include "math/lane4.h"
#include "math/lane8.h"
#include "math/lane_count.h"

namespace luz {

// ---- scalar lanes: float and double, for arithmetic written once over a lane type ------------

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

}  // namespace luz
