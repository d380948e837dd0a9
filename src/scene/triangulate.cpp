// Polygon triangulation for OBJ faces: ear clipping with a grid of reflex corners (see
// triangulate.h).
#include "scene/triangulate.h"

#include <algorithm>
#include <cmath>

namespace luz {
namespace {

struct Point {
    double u, v;
};

/// Twice the signed area of triangle (a, b, c): > 0 counter-clockwise.
double area2(const Point& a, const Point& b, const Point& c) {
    return (b.u - a.u) * (c.v - a.v) - (b.v - a.v) * (c.u - a.u);
}

/// The polygon as a ring of corners being cut, and a grid of its reflex corners.
class EarClipper {
  public:
    explicit EarClipper(std::vector<Point> p) : p_(std::move(p)), n_(p_.size()) {
        prev_.resize(n_);
        next_.resize(n_);
        for (std::size_t i = 0; i < n_; ++i) {
            prev_[i] = static_cast<uint32_t>(i == 0 ? n_ - 1 : i - 1);
            next_[i] = static_cast<uint32_t>(i + 1 == n_ ? 0 : i + 1);
        }
        make_grid();
    }

    /// Cuts ears in the order they are found. A corner is tested again only when a neighbour
    /// goes (in a simple polygon nothing else changes whether it is an ear), so the tests are
    /// linear in the corners; each looks at the reflex corners of the grid cells its triangle
    /// spans.
    void run(std::vector<std::array<uint32_t, 3>>& out) {
        std::size_t remaining = n_;
        queue_.clear();
        queued_at_.assign(n_, 0);
        removed_.assign(n_, false);
        for (uint32_t i = 0; i < n_; ++i) push(i);
        std::size_t head = 0;
        uint32_t live = 0;  // a corner still in the ring
        int rescans = 0;
        bool cut_since_rescan = true;
        bool relaxed = false;  // any corner that turns the right way: a polygon crossing itself
        while (remaining > 3) {
            if (head == queue_.size()) {
                // No candidate left: around the ring again, after two turns without the ear
                // test; a turn that cuts nothing ends it.
                if (!cut_since_rescan) {
                    if (relaxed) return;  // no corner turns the right way: nothing left to cut
                    relaxed = true;
                }
                if (++rescans > 2) relaxed = true;
                cut_since_rescan = false;
                uint32_t i = live;
                do {
                    push(i);
                    i = next_[i];
                } while (i != live);
                continue;
            }
            const uint32_t b = queue_[head];
            if (removed_[b] || queued_at_[b] != head++) continue;  // gone, or queued again later
            const uint32_t a = prev_[b], c = next_[b];
            const double cross = area2(p_[a], p_[b], p_[c]);
            if (cross > 0 && !relaxed && !is_ear(a, b, c)) continue;
            if (cross < 0) continue;
            if (cross > 0) out.push_back({a, b, c});  // else no area: dropped without a triangle
            remove(b, a, c);
            --remaining;
            cut_since_rescan = true;
            live = a;
            push(a);
            push(c);
        }
        const uint32_t b = live, a = prev_[b], c = next_[b];
        if (remaining == 3 && area2(p_[a], p_[b], p_[c]) > 0) out.push_back({a, b, c});
    }

  private:
    static constexpr uint32_t kNone = UINT32_MAX;

    bool is_reflex(uint32_t i) const { return area2(p_[prev_[i]], p_[i], p_[next_[i]]) < 0; }

    /// Cell of a point, column and row clamped to the grid.
    std::size_t column(double u) const {
        const double c = (u - min_.u) * scale_u_;
        return c <= 0 ? 0 : std::min(cols_ - 1, static_cast<std::size_t>(c));
    }
    std::size_t row(double v) const {
        const double r = (v - min_.v) * scale_v_;
        return r <= 0 ? 0 : std::min(rows_ - 1, static_cast<std::size_t>(r));
    }

    void make_grid() {
        std::size_t reflex = 0;
        min_ = max_ = p_[0];
        for (std::size_t i = 0; i < n_; ++i) {
            reflex += is_reflex(static_cast<uint32_t>(i));
            min_ = {std::min(min_.u, p_[i].u), std::min(min_.v, p_[i].v)};
            max_ = {std::max(max_.u, p_[i].u), std::max(max_.v, p_[i].v)};
        }
        // about one reflex corner per cell, the cells about square
        const double w = max_.u - min_.u, h = max_.v - min_.v;
        const double cells = std::max<double>(1, reflex);
        const double aspect = w > 0 && h > 0 ? w / h : 1;
        cols_ = std::clamp<std::size_t>(std::llround(std::sqrt(cells * aspect)), 1, 4096);
        rows_ = std::clamp<std::size_t>(std::llround(std::sqrt(cells / aspect)), 1, 4096);
        if (!(w > 0)) cols_ = 1;
        if (!(h > 0)) rows_ = 1;
        scale_u_ = w > 0 ? cols_ / w : 0;
        scale_v_ = h > 0 ? rows_ / h : 0;
        cells_.assign(cols_ * rows_, {});
        slot_.assign(n_, kNone);
        cell_of_.assign(n_, 0);
        for (uint32_t i = 0; i < n_; ++i) {
            if (is_reflex(i)) add(i);
        }
    }

    void add(uint32_t i) {
        const std::size_t cell = row(p_[i].v) * cols_ + column(p_[i].u);
        cell_of_[i] = static_cast<uint32_t>(cell);
        slot_[i] = static_cast<uint32_t>(cells_[cell].size());
        cells_[cell].push_back(i);
    }

    void drop(uint32_t i) {
        std::vector<uint32_t>& cell = cells_[cell_of_[i]];
        const uint32_t moved = cell.back();
        cell[slot_[i]] = moved;
        slot_[moved] = slot_[i];
        cell.pop_back();
        slot_[i] = kNone;
    }

    /// In the grid exactly when reflex.
    void update(uint32_t i) {
        const bool reflex = is_reflex(i);
        if (reflex && slot_[i] == kNone) add(i);
        if (!reflex && slot_[i] != kNone) drop(i);
    }

    /// Queues corner `i` to be tested (an earlier place in the queue no longer counts).
    void push(uint32_t i) {
        queued_at_[i] = queue_.size();
        queue_.push_back(i);
    }

    /// Takes corner `b` out of the ring (a and c its neighbours).
    void remove(uint32_t b, uint32_t a, uint32_t c) {
        removed_[b] = true;
        if (slot_[b] != kNone) drop(b);
        next_[a] = c;
        prev_[c] = a;
        update(a);
        update(c);
    }

    /// No reflex corner in triangle (a, b, c) or on its edges, besides corners at its own
    /// corners' places (a polygon may touch itself there). Row by row, only the cells the
    /// triangle crosses are looked at (a long thin triangle's box would hold many more).
    bool is_ear(uint32_t a, uint32_t b, uint32_t c) const {
        const Point &pa = p_[a], &pb = p_[b], &pc = p_[c];
        const std::size_t r0 = row(std::min({pa.v, pb.v, pc.v}));
        const std::size_t r1 = row(std::max({pa.v, pb.v, pc.v}));
        const auto same = [](const Point& x, const Point& y) { return x.u == y.u && x.v == y.v; };
        for (std::size_t r = r0; r <= r1; ++r) {
            // the triangle's extent in u within the row (a little wider, against rounding)
            double lo, hi;
            if (rows_ == 1) {
                lo = std::min({pa.u, pb.u, pc.u});
                hi = std::max({pa.u, pb.u, pc.u});
            } else {
                const double margin = 0.1 / scale_v_;
                const double v0 = min_.v + double(r) / scale_v_ - margin;
                const double v1 = min_.v + double(r + 1) / scale_v_ + margin;
                lo = INFINITY;
                hi = -INFINITY;
                extent_in_band(pa, pb, v0, v1, lo, hi);
                extent_in_band(pb, pc, v0, v1, lo, hi);
                extent_in_band(pc, pa, v0, v1, lo, hi);
                if (lo > hi) continue;
            }
            const double margin = cols_ == 1 ? 0 : 0.1 / scale_u_;
            const std::size_t c0 = column(lo - margin), c1 = column(hi + margin);
            for (std::size_t col = c0; col <= c1; ++col) {
                for (const uint32_t i : cells_[r * cols_ + col]) {
                    const Point& q = p_[i];
                    if (same(q, pa) || same(q, pb) || same(q, pc)) continue;
                    if (area2(pa, pb, q) >= 0 && area2(pb, pc, q) >= 0 && area2(pc, pa, q) >= 0) {
                        return false;
                    }
                }
            }
        }
        return true;
    }

    /// Widens [lo, hi] to the u of segment p–q where v is in [v0, v1].
    static void extent_in_band(const Point& p, const Point& q, double v0, double v1, double& lo,
                               double& hi) {
        const double pv = std::clamp(p.v, v0, v1), qv = std::clamp(q.v, v0, v1);
        if (p.v == q.v) {
            if (p.v < v0 || p.v > v1) return;
            lo = std::min({lo, p.u, q.u});
            hi = std::max({hi, p.u, q.u});
            return;
        }
        if (std::max(p.v, q.v) < v0 || std::min(p.v, q.v) > v1) return;
        const auto u_at = [&](double v) { return p.u + (q.u - p.u) * ((v - p.v) / (q.v - p.v)); };
        const double u0 = u_at(pv), u1 = u_at(qv);
        lo = std::min({lo, u0, u1});
        hi = std::max({hi, u0, u1});
    }

    std::vector<Point> p_;
    std::size_t n_;
    std::vector<uint32_t> prev_, next_;
    Point min_{}, max_{};
    std::size_t cols_ = 1, rows_ = 1;
    double scale_u_ = 0, scale_v_ = 0;
    std::vector<std::vector<uint32_t>> cells_;
    std::vector<uint32_t> slot_;          ///< a reflex corner's place in its cell, or kNone
    std::vector<uint32_t> cell_of_;       ///< the cell of a corner in the grid
    std::vector<uint32_t> queue_;         ///< corners to test, in order
    std::vector<std::size_t> queued_at_;  ///< a corner's latest place in queue_
    std::vector<bool> removed_;
};

/// The corners in the plane the polygon's Newell normal is most along, turned so that the
/// polygon goes counter-clockwise; empty when it has no area.
std::vector<Point> project(const std::vector<Vec3>& corners) {
    double n[3] = {0, 0, 0};
    for (std::size_t i = 0; i < corners.size(); ++i) {
        const Vec3& p = corners[i];
        const Vec3& q = corners[i + 1 == corners.size() ? 0 : i + 1];
        n[0] += (double(p.y) - q.y) * (double(p.z) + q.z);
        n[1] += (double(p.z) - q.z) * (double(p.x) + q.x);
        n[2] += (double(p.x) - q.x) * (double(p.y) + q.y);
    }
    int axis = 0;
    for (int k = 1; k < 3; ++k) {
        if (std::fabs(n[k]) > std::fabs(n[axis])) axis = k;
    }
    if (!(std::fabs(n[axis]) > 0) || !std::isfinite(n[axis])) return {};
    // (u, v) in cyclic order after the dropped axis: n[axis] > 0 means counter-clockwise
    const int ku = (axis + 1) % 3, kv = (axis + 2) % 3;
    const double flip = n[axis] > 0 ? 1 : -1;
    std::vector<Point> out(corners.size());
    for (std::size_t i = 0; i < corners.size(); ++i) {
        out[i] = {flip * corners[i][ku], double(corners[i][kv])};
    }
    return out;
}

}  // namespace

void triangulate_polygon(const std::vector<Vec3>& corners,
                         std::vector<std::array<uint32_t, 3>>& out) {
    const std::size_t n = corners.size();
    if (n < 3) return;
    if (n == 3) {
        out.push_back({0, 1, 2});
        return;
    }
    if (n == 4) {
        // tinyobjloader's rule, in its float arithmetic: the shorter diagonal
        const Vec3 e02 = corners[2] - corners[0], e13 = corners[3] - corners[1];
        const float d02 = e02.x * e02.x + e02.y * e02.y + e02.z * e02.z;
        const float d13 = e13.x * e13.x + e13.y * e13.y + e13.z * e13.z;
        if (d02 < d13) {
            out.push_back({0, 1, 2});
            out.push_back({0, 2, 3});
        } else {
            out.push_back({0, 1, 3});
            out.push_back({1, 2, 3});
        }
        return;
    }
    std::vector<Point> points = project(corners);
    if (points.empty()) return;
    EarClipper(std::move(points)).run(out);
}

}  // namespace luz
