// The first root of a quartic in an interval, by root isolation through its derivatives (the
// torus, torus.h).
#pragma once

#include <cmath>
#include <utility>

#include "geometry/shapes/object_space.h"

namespace luz::shapes {

/// The quartic f(x) = c4·x⁴ + c3·x³ + c2·x² + c1·x + c0 and its derivatives.
struct Quartic {
    double c4, c3, c2, c1, c0;
    double f(double x) const { return (((c4 * x + c3) * x + c2) * x + c1) * x + c0; }
    double df(double x) const { return ((4 * c4 * x + 3 * c3) * x + 2 * c2) * x + c1; }
    double d2f(double x) const { return (12 * c4 * x + 6 * c3) * x + 2 * c2; }
};

/// The root of a function that is monotonic on [lo, hi] and changes sign there (f_lo = value at
/// lo): Newton steps, falling back to bisection whenever a step leaves the bracket or does not
/// shrink fast enough (rtsafe, Numerical Recipes §9.4). eval(x, f, df).
template <class Eval>
inline double bracketed_root(const Eval& eval, double lo, double hi, double f_lo) {
    constexpr double tol = 1e-13;
    const bool positive_lo = f_lo > 0;
    double step_old = hi - lo, step = step_old;
    double x = 0.5 * (lo + hi), fx, dfx;
    eval(x, fx, dfx);
    for (int i = 0; i < 100; ++i) {
        if (fx == 0) return x;
        if ((fx > 0) == positive_lo) {
            lo = x;
        } else {
            hi = x;
        }
        const double newton = x - fx / dfx;
        if (!(newton > lo && newton < hi) || std::fabs(2 * fx) > std::fabs(step_old * dfx)) {
            step_old = step;
            step = 0.5 * (hi - lo);
            x = lo + step;
        } else {
            step_old = step;
            step = x - newton;
            x = newton;
        }
        if (std::fabs(step) <= tol * (1 + std::fabs(x)) || hi - lo <= tol) return x;
        eval(x, fx, dfx);
    }
    return x;
}

/// The first root of q in (0, L], or a negative value if none. Root isolation by derivatives:
/// the roots of q'' (a quadratic, exact) split [0, L] into pieces where q' is monotonic; the
/// roots of q' found there split it into pieces where q is monotonic, each holding at most one
/// root, which a sign change reveals. No root is missed, tangent (double) roots included.
inline double first_root(const Quartic& q, double L) {
    // roots of q''/2 = 6·c4·x² + 3·c3·x + c2
    double g[4] = {0, 0, 0, L};
    int ng = 1;
    {
        const double a = 6 * q.c4, b = 1.5 * q.c3, c = q.c2, disc = b * b - a * c;
        if (disc > 0) {
            double r0, r1;
            quadratic_roots(a, b, c, disc, r0, r1);
            if (r0 > r1) std::swap(r0, r1);
            if (r0 > 0 && r0 < L) g[ng++] = r0;
            if (r1 > 0 && r1 < L) g[ng++] = r1;
        }
    }
    g[ng++] = L;

    const auto eval_f = [&](double x, double& f, double& df) {
        f = q.f(x);
        df = q.df(x);
    };
    const auto eval_df = [&](double x, double& f, double& df) {
        f = q.df(x);
        df = q.d2f(x);
    };
    double prev = 0, f_prev = q.f(0);
    double d_prev = q.df(0);
    for (int i = 1; i < ng; ++i) {
        const double d_next = q.df(g[i]);
        if ((d_prev > 0) != (d_next > 0)) {
            // a critical point of q: the end of a monotonic piece
            const double c = bracketed_root(eval_df, g[i - 1], g[i], d_prev);
            const double f_c = q.f(c);
            if ((f_prev > 0) != (f_c > 0)) return bracketed_root(eval_f, prev, c, f_prev);
            prev = c;
            f_prev = f_c;
        }
        d_prev = d_next;
    }
    const double f_L = q.f(L);
    if ((f_prev > 0) != (f_L > 0)) return bracketed_root(eval_f, prev, L, f_prev);
    return -1;
}

}  // namespace luz::shapes
