// Ray–shape intersection (SPEC §1.1): every shape is hit in its canonical object space
// (shape.h); quadrics and the torus quartic are solved in double, the box by slabs, triangles by
// the watertight test of Woop, Benthin and Wald.
#include "geometry/intersect.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

namespace luz {

namespace {

/// A double-precision point or vector for the solvers (object space).
struct D3 {
    double x, y, z;
};
inline D3 to_d3(const Vec3& v) { return {v.x, v.y, v.z}; }
inline double dot3(const D3& a, const D3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline D3 along(const D3& o, const D3& d, double t) {
    return {o.x + t * d.x, o.y + t * d.y, o.z + t * d.z};
}

/// The nearest accepted candidate so far. A candidate root t (double) is accepted if, rounded
/// to float, it lies in (t_min, best): the returned t always satisfies t_min < t < t_max.
struct Nearest {
    float t_min;
    float best;  // t_max until something is found
    double t = 0;
    int part = part_side;
    bool found = false;

    bool offer(double candidate, int p) {
        const float tf = static_cast<float>(candidate);  // NaN and ±inf fail below
        if (tf > t_min && tf < best) {
            best = tf;
            t = candidate;
            part = p;
            found = true;
            return true;
        }
        return false;
    }
};

/// Real roots of a·t² + 2·b·t + c = 0 (note the half coefficient b) in the cancellation-free
/// form q = −(b + sign(b)·√disc), roots c/q and q/a; disc = b² − a·c is passed in so callers can
/// compute it in their best-conditioned way. A root that does not exist comes out ±inf or NaN,
/// which Nearest::offer rejects (a = 0: the linear case keeps its root c/q).
inline void quadratic_roots(double a, double b, double c, double disc, double& r0, double& r1) {
    const double q = -(b + std::copysign(std::sqrt(disc), b));
    r0 = c / q;
    r1 = q / a;
}

// ---- sphere: |p|² = 1 -----------------------------------------------------------------------

/// The roots r0 ≤ r1 of |o + t·d|² = rr (a sphere of radius² rr about the origin); false if
/// the line misses it.
bool sphere_roots(const D3& o, const D3& d, double rr, double& r0, double& r1) {
    const double a = dot3(d, d), b = dot3(o, d), c = dot3(o, o) - rr;
    if (!(a > 0)) return false;
    // disc = b² − a·c computed as a·(rr − |o − (b/a)·d|²): no cancellation for distant origins
    // (Haines et al., "Precision improvements for ray/sphere intersection", Ray Tracing Gems).
    const D3 l = along(o, d, -b / a);
    const double disc = a * (rr - dot3(l, l));
    if (disc < 0) return false;
    quadratic_roots(a, b, c, disc, r0, r1);
    if (r0 > r1) std::swap(r0, r1);
    return true;
}

bool hit_sphere(const Ray& ro, Nearest& n) {
    double r0, r1;
    if (!sphere_roots(to_d3(ro.origin), to_d3(ro.direction), 1.0, r0, r1)) return false;
    n.offer(r0, part_side) || n.offer(r1, part_side);
    return n.found;
}

// ---- box: slabs -----------------------------------------------------------------------------

bool hit_box(const Shape& s, const Ray& ro, Nearest& n) {
    const float inf = std::numeric_limits<float>::infinity();
    float t_near = -inf, t_far = inf;
    int f_near = -1, f_far = -1;
    for (int k = 0; k < 3; ++k) {
        const float o = ro.origin[k], d = ro.direction[k];
        if (d == 0.0f) {
            // parallel to the slab: inside it or a miss (no 0·inf NaN)
            if (o < s.lo[k] || o > s.hi[k]) return false;
            continue;
        }
        const float inv = 1.0f / d;
        float ta = (s.lo[k] - o) * inv, tb = (s.hi[k] - o) * inv;
        int fa = 2 * k, fb = 2 * k + 1;
        if (ta > tb) {
            std::swap(ta, tb);
            std::swap(fa, fb);
        }
        if (ta > t_near) t_near = ta, f_near = fa;
        if (tb < t_far) t_far = tb, f_far = fb;
    }
    if (t_near > t_far) return false;
    if (f_near >= 0 && n.offer(t_near, f_near)) return true;
    return f_far >= 0 && n.offer(t_far, f_far);
}

// ---- cylinder: x² + y² = 1, z ∈ [0, 1]; caps at z = 0 and z = 1 -----------------------------

/// Cap discs are accepted up to this much beyond r² = 1, so that a ray through the rim never
/// slips between side (z test) and cap (r test) by rounding.
constexpr double cap_slack = 1e-9;

void hit_caps(const D3& o, const D3& d, bool both, Nearest& n) {
    if (d.z == 0) return;
    for (int k = 0; k < (both ? 2 : 1); ++k) {
        const double t = (k - o.z) / d.z;
        const double x = o.x + t * d.x, y = o.y + t * d.y;
        if (x * x + y * y <= 1.0 + cap_slack) n.offer(t, k == 0 ? part_cap0 : part_cap1);
    }
}

bool hit_cylinder(const Shape& s, const Ray& ro, Nearest& n) {
    const D3 o = to_d3(ro.origin), d = to_d3(ro.direction);
    const double a = d.x * d.x + d.y * d.y;
    if (a > 0) {
        const double b = o.x * d.x + o.y * d.y, c = o.x * o.x + o.y * o.y - 1.0;
        // as for the sphere, in the xy projection: disc = a·(1 − |o⊥ − (b/a)·d⊥|²)
        const double lx = o.x - b / a * d.x, ly = o.y - b / a * d.y;
        const double disc = a * (1.0 - (lx * lx + ly * ly));
        if (disc >= 0) {
            double r[2];
            quadratic_roots(a, b, c, disc, r[0], r[1]);
            for (double t : r) {
                const double z = o.z + t * d.z;
                if (z >= 0 && z <= 1) n.offer(t, part_side);
            }
        }
    }
    if (s.caps) hit_caps(o, d, true, n);
    return n.found;
}

// ---- cone: x² + y² = (1 − z)², z ∈ [0, 1]; cap at z = 0 --------------------------------------

bool hit_cone(const Shape& s, const Ray& ro, Nearest& n) {
    const D3 o = to_d3(ro.origin), d = to_d3(ro.direction);
    // with w = 1 − z: x² + y² − w² = 0, w(t) = (1 − oz) − t·dz
    const double w0 = 1.0 - o.z;
    const double a = d.x * d.x + d.y * d.y - d.z * d.z;
    const double b = o.x * d.x + o.y * d.y + w0 * d.z;
    const double c = o.x * o.x + o.y * o.y - w0 * w0;
    const double disc = b * b - a * c;
    if (disc >= 0) {
        double r[2];
        quadratic_roots(a, b, c, disc, r[0], r[1]);  // a = 0 (parallel to a generator): c/q
        for (double t : r) {
            const double z = o.z + t * d.z;  // z ≤ 1 drops the mirrored nappe above the apex
            if (z >= 0 && z <= 1) n.offer(t, part_side);
        }
    }
    if (s.caps) hit_caps(o, d, false, n);
    return n.found;
}

// ---- torus: (|p|² + 1 − m²)² − 4(x² + y²) = 0 ------------------------------------------------

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
double bracketed_root(const Eval& eval, double lo, double hi, double f_lo) {
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
double first_root(const Quartic& q, double L) {
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

bool hit_torus(const Shape& s, const Ray& ro, Nearest& n, D3& p_hit) {
    const D3 o = to_d3(ro.origin), d = to_d3(ro.direction);
    const double dl2 = dot3(d, d);
    if (!(dl2 > 0)) return false;
    const double dl = std::sqrt(dl2);
    const D3 dn{d.x / dl, d.y / dl, d.z / dl};
    const double m = s.minor, k = 1.0 - m * m;

    // Bounding sphere (radius 1 + m, a little margin): the search runs over the part of the
    // ray inside it, with distances x along the unit direction from its first point p0.
    const double Rb = (1.0 + m) * 1.001;
    const double b = dot3(o, dn);
    const D3 l = along(o, dn, -b);
    const double h2 = Rb * Rb - dot3(l, l);
    if (!(h2 > 0)) return false;
    const double h = std::sqrt(h2);
    const double s_lo = std::fmax(-b - h, double(n.t_min) * dl);
    const double s_hi = std::fmin(-b + h, double(n.best) * dl);
    if (!(s_lo < s_hi)) return false;

    // Moving the origin to p0 (inside or on the bounding sphere) keeps the quartic's
    // coefficients of order 1 however far the ray starts: the conditioning that matters.
    const D3 p0 = along(o, dn, s_lo);
    const double A = dot3(dn, dn), B = dot3(p0, dn), E = dot3(p0, p0) + k;
    const double alpha = dn.x * dn.x + dn.y * dn.y, beta = p0.x * dn.x + p0.y * dn.y,
                 gamma = p0.x * p0.x + p0.y * p0.y;
    // (A·x² + 2B·x + E)² − 4(α·x² + 2β·x + γ)
    const Quartic q{A * A, 4 * A * B, 4 * B * B + 2 * A * E - 4 * alpha, 4 * B * E - 8 * beta,
                    E * E - 4 * gamma};
    const double x = first_root(q, s_hi - s_lo);
    if (!(x >= 0)) return false;
    if (!n.offer((s_lo + x) / dl, part_side)) return false;
    p_hit = along(p0, dn, x);
    return true;
}

// ---- plane z = 0 -----------------------------------------------------------------------------

bool hit_plane(const Ray& ro, Nearest& n) {
    if (ro.direction.z == 0.0f) return false;
    return n.offer(-double(ro.origin.z) / ro.direction.z, part_side);
}

/// Normalised, or `fallback` for a zero (or non-finite) vector.
inline Vec3 unit_or(const Vec3& v, const Vec3& fallback) {
    const float l = length(v);
    return (l > 0 && std::isfinite(l)) ? v / l : fallback;
}

}  // namespace

WatertightRay prepare_watertight(const Ray& r) {
    WatertightRay w;
    w.origin = r.origin;
    const Vec3 a{std::fabs(r.direction.x), std::fabs(r.direction.y), std::fabs(r.direction.z)};
    w.kz = a.x > a.y ? (a.x > a.z ? 0 : 2) : (a.y > a.z ? 1 : 2);
    w.kx = (w.kz + 1) % 3;
    w.ky = (w.kx + 1) % 3;
    if (r.direction[w.kz] < 0) std::swap(w.kx, w.ky);  // keeps the winding's sign
    w.Sx = r.direction[w.kx] / r.direction[w.kz];
    w.Sy = r.direction[w.ky] / r.direction[w.kz];
    w.Sz = 1.0f / r.direction[w.kz];
    return w;
}

bool intersect_triangle(const WatertightRay& r, const Vec3& p0, const Vec3& p1, const Vec3& p2,
                        float t_min, float t_max, float& t, float& b1, float& b2) {
    // vertices relative to the origin, sheared so that the ray runs along +z
    const Vec3 A = p0 - r.origin, B = p1 - r.origin, C = p2 - r.origin;
    const float Ax = A[r.kx] - r.Sx * A[r.kz], Ay = A[r.ky] - r.Sy * A[r.kz];
    const float Bx = B[r.kx] - r.Sx * B[r.kz], By = B[r.ky] - r.Sy * B[r.kz];
    const float Cx = C[r.kx] - r.Sx * C[r.kz], Cy = C[r.ky] - r.Sy * C[r.kz];
    // scaled barycentrics: 2D edge functions; exact in double when one is zero in float
    float U = Cx * By - Cy * Bx, V = Ax * Cy - Ay * Cx, W = Bx * Ay - By * Ax;
    if (U == 0.0f || V == 0.0f || W == 0.0f) {
        U = static_cast<float>(double(Cx) * By - double(Cy) * Bx);
        V = static_cast<float>(double(Ax) * Cy - double(Ay) * Cx);
        W = static_cast<float>(double(Bx) * Ay - double(By) * Ax);
    }
    if ((U < 0 || V < 0 || W < 0) && (U > 0 || V > 0 || W > 0)) return false;
    const float det = U + V + W;
    if (det == 0.0f) return false;
    const float T = U * (r.Sz * A[r.kz]) + V * (r.Sz * B[r.kz]) + W * (r.Sz * C[r.kz]);
    const float inv_det = 1.0f / det;
    const float tt = T * inv_det;
    if (!(tt > t_min && tt < t_max)) return false;
    t = tt;
    b1 = V * inv_det;
    b2 = W * inv_det;
    return true;
}

bool intersect_mesh(const Mesh& mesh, const WatertightRay& w, float t_min, float t_max, Hit& hit) {
    bool found = false;
    Vec3 p0, p1, p2;
    for (size_t k = 0; k < mesh.triangle_count(); ++k) {
        mesh.vertices(k, p0, p1, p2);
        float t, b1, b2;
        if (intersect_triangle(w, p0, p1, p2, t_min, t_max, t, b1, b2)) {
            t_max = t;
            hit.t = t;
            hit.u = b1;
            hit.v = b2;
            hit.part = static_cast<int>(k);
            found = true;
        }
    }
    return found;
}

namespace detail {

bool world_sphere_roots_double(const Vec3& centre, float radius, const Ray& r, float& t0,
                               float& t1) {
    const D3 o{double(r.origin.x) - centre.x, double(r.origin.y) - centre.y,
               double(r.origin.z) - centre.z};
    const double rho = radius;
    double r0, r1;
    if (!sphere_roots(o, to_d3(r.direction), rho * rho, r0, r1)) return false;
    t0 = static_cast<float>(r0);
    t1 = static_cast<float>(r1);
    return true;
}

bool intersect_object_space(const Shape& s, const Ray& r, float t_min, float t_max, Hit& hit) {
    if (s.type == ShapeType::mesh) {
        return s.mesh && intersect_mesh(*s.mesh, prepare_watertight(r), t_min, t_max, hit);
    }
    Nearest n{t_min, t_max};
    hit.u = hit.v = 0;
    const Ray ro = s.transform.to_object(r);
    switch (s.type) {
        case ShapeType::sphere:
            if (!hit_sphere(ro, n)) return false;
            break;
        case ShapeType::box:
            if (!hit_box(s, ro, n)) return false;
            break;
        case ShapeType::cylinder:
            if (!hit_cylinder(s, ro, n)) return false;
            break;
        case ShapeType::cone:
            if (!hit_cone(s, ro, n)) return false;
            break;
        case ShapeType::torus: {
            D3 p;
            if (!hit_torus(s, ro, n, p)) return false;
            break;
        }
        case ShapeType::plane:
            if (!hit_plane(ro, n)) return false;
            break;
        case ShapeType::triangle: {
            const WatertightRay w = prepare_watertight(ro);
            float t, b1, b2;
            if (!intersect_triangle(w, s.vertices[0], s.vertices[1], s.vertices[2], t_min, t_max, t,
                                    b1, b2))
                return false;
            n.best = t;
            n.part = part_side;
            hit.u = b1;
            hit.v = b2;
            break;
        }
        case ShapeType::mesh:
            return false;  // handled above
    }
    hit.t = n.best;
    hit.part = n.part;
    return true;
}

uint32_t count_crossings_object_space(const Shape& s, const Ray& r, float t_min, float t_max,
                                      bool first_only, uint64_t& tests) {
    Hit hit;
    float t = t_min;
    uint32_t n = 0;
    for (int k = 0; k < 64; ++k) {
        ++tests;
        if (!intersect_object_space(s, r, t, t_max, hit)) break;
        ++n;
        if (first_only) break;
        // Step past this crossing (relative step: the same root is not found twice).
        t = hit.t + 1e-4f * std::max(1.0f, hit.t);
    }
    return n;
}

}  // namespace detail

SurfacePoint surface_at(const Shape& s, const Ray& r, const Hit& hit) {
    if (s.type == ShapeType::mesh) {
        // world space; N interpolated (smooth) on the face normal's side, Ng the face normal
        const size_t t = static_cast<size_t>(hit.part);
        return {r.at(hit.t), s.mesh->shading_normal(t, hit.u, hit.v), s.mesh->face_normal(t)};
    }
    if (s.world_form) {
        SurfacePoint sp;
        sp.P = r.at(hit.t);
        sp.N = s.type == ShapeType::plane ? s.normal : unit_or(sp.P - s.centre, {0, 0, 1});
        sp.Ng = sp.N;
        return sp;
    }
    const Ray ro = s.transform.to_object(r);
    const Vec3 p = ro.at(hit.t);
    // the outward normal in object space (any length)
    Vec3 n{0, 0, 1};
    switch (s.type) {
        case ShapeType::sphere:
            n = p;
            break;
        case ShapeType::box:
            n = Vec3{0.0f};
            n[hit.part / 2] = (hit.part & 1) ? 1.0f : -1.0f;
            break;
        case ShapeType::cylinder:
            if (hit.part == part_side) {
                n = unit_or({p.x, p.y, 0}, {1, 0, 0});
            } else {
                n = {0, 0, hit.part == part_cap0 ? -1.0f : 1.0f};
            }
            break;
        case ShapeType::cone:
            if (hit.part == part_side) {
                // ∇(x² + y² − (1 − z)²) ∝ (x, y, 1 − z) = (x, y, r) on the surface; using
                // r = √(x² + y²) keeps it exact near the apex, where (0, 0, 1) is the choice
                const float rr = std::sqrt(p.x * p.x + p.y * p.y);
                n = rr > 0 ? Vec3{p.x, p.y, rr} : Vec3{0, 0, 1};
            } else {
                n = {0, 0, -1};
            }
            break;
        case ShapeType::torus: {
            // ∇f ∝ p − (nearest point of the major circle)
            const float rr = std::sqrt(p.x * p.x + p.y * p.y);
            n = rr > 0 ? p - Vec3{p.x / rr, p.y / rr, 0} : Vec3{0, 0, 1};
            break;
        }
        case ShapeType::plane:
            break;
        case ShapeType::triangle:
            n = cross(s.vertices[1] - s.vertices[0], s.vertices[2] - s.vertices[0]);
            break;
        case ShapeType::mesh:
            break;
    }
    SurfacePoint sp;
    sp.P = r.at(hit.t);
    sp.N = unit_or(s.transform.normal(n), {0, 0, 1});
    sp.Ng = sp.N;
    return sp;
}

}  // namespace luz
