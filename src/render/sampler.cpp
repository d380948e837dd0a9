// Antialiasing (docs/SCENES.md#antialiasing): grid filters (box, tent), the adaptive sub-corner
// cache, and the image that shows which pixels adaptive sampling refined.
#include "render/sampler.h"

#include <limits>

namespace luz {

namespace {

float centre(int i) { return static_cast<float>(i) + 0.5f; }

/// Per-thread working memory of the separable tent filter.
template <class S>
struct TentScratch {
    std::vector<float> xs, ys;  ///< sample positions of the region's columns and rows
    std::vector<S> rows;        ///< horizontally filtered sample rows, one per tile column
};

template <class S>
TentScratch<S>& tent_scratch() {
    thread_local TentScratch<S> s;
    return s;
}

template <class S, class Out>
void box_filter(const GridSpec& g, const PixelRect& tile, const PixelRect& region, const S* samples,
                Out& out) {
    const int s = g.s;
    const size_t stride = static_cast<size_t>(region.width()) * s;
    const float inv = 1.0f / static_cast<float>(s * s);
    for (int j = tile.y0; j < tile.y1; ++j) {
        for (int i = tile.x0; i < tile.x1; ++i) {
            S sum{};
            for (int b = 0; b < s; ++b) {
                const S* row = samples + static_cast<size_t>((j - region.y0) * s + b) * stride +
                               static_cast<size_t>(i - region.x0) * s;
                for (int a = 0; a < s; ++a) sum += row[a];
            }
            put(out, i, j, sum * inv);
        }
    }
}

/// Tent filter with jittered samples: every sample of the 3×3 pixels, weighted directly.
template <class S, class Out>
void tent_filter_direct(const GridSpec& g, const PixelRect& tile, const PixelRect& region,
                        const S* samples, Out& out) {
    const int s = g.s;
    const size_t stride = static_cast<size_t>(region.width()) * s;
    for (int j = tile.y0; j < tile.y1; ++j) {
        for (int i = tile.x0; i < tile.x1; ++i) {
            const float cx = centre(i), cy = centre(j);
            S sum{};
            float weights = 0;
            for (int nj = std::max(j - 1, region.y0); nj <= std::min(j + 1, region.y1 - 1); ++nj) {
                for (int ni = std::max(i - 1, region.x0); ni <= std::min(i + 1, region.x1 - 1);
                     ++ni) {
                    for (int b = 0; b < s; ++b) {
                        const S* row = samples +
                                       static_cast<size_t>((nj - region.y0) * s + b) * stride +
                                       static_cast<size_t>(ni - region.x0) * s;
                        for (int a = 0; a < s; ++a) {
                            float x, y;
                            g.position(ni, nj, a, b, x, y);
                            const float w = tent_weight(x - cx, y - cy);
                            if (w > 0) {
                                sum += row[a] * w;
                                weights += w;
                            }
                        }
                    }
                }
            }
            put(out, i, j, sum * (1.0f / weights));
        }
    }
}

/// Tent filter on the regular grid: the weight is a product of an x and a y factor and every
/// sample of a column shares its x, so rows are filtered horizontally, then vertically.
template <class S, class Out>
void tent_filter_separable(const GridSpec& g, const PixelRect& tile, const PixelRect& region,
                           const S* samples, Out& out) {
    const int s = g.s;
    const int cols = region.width() * s, rows = region.height() * s, tw = tile.width();
    TentScratch<S>& t = tent_scratch<S>();
    t.xs.resize(cols);
    t.ys.resize(rows);
    float unused;
    for (int c = 0; c < cols; ++c)
        g.position(region.x0 + c / s, region.y0, c % s, 0, t.xs[c], unused);
    for (int r = 0; r < rows; ++r)
        g.position(region.x0, region.y0 + r / s, 0, r % s, unused, t.ys[r]);
    // Rows of samples that some tile pixel uses, filtered horizontally per tile column.
    const int r0 = (std::max(tile.y0 - 1, region.y0) - region.y0) * s;
    const int r1 = (std::min(tile.y1 + 1, region.y1) - region.y0) * s;
    t.rows.resize(static_cast<size_t>(r1 - r0) * tw);
    for (int r = r0; r < r1; ++r) {
        const S* row = samples + static_cast<size_t>(r) * cols;
        for (int i = tile.x0; i < tile.x1; ++i) {
            const float cx = centre(i);
            const int c0 = (std::max(i - 1, region.x0) - region.x0) * s;
            const int c1 = (std::min(i + 2, region.x1) - region.x0) * s;
            S sum{};
            for (int c = c0; c < c1; ++c) {
                const float w = tent1(t.xs[c] - cx);
                if (w > 0) sum += row[c] * w;
            }
            t.rows[static_cast<size_t>(r - r0) * tw + (i - tile.x0)] = sum;
        }
    }
    for (int j = tile.y0; j < tile.y1; ++j) {
        const float cy = centre(j);
        const int ra = (std::max(j - 1, region.y0) - region.y0) * s;
        const int rb = (std::min(j + 2, region.y1) - region.y0) * s;
        for (int i = tile.x0; i < tile.x1; ++i) {
            const float cx = centre(i);
            const int c0 = (std::max(i - 1, region.x0) - region.x0) * s;
            const int c1 = (std::min(i + 2, region.x1) - region.x0) * s;
            float wx_sum = 0, wy_sum = 0;
            for (int c = c0; c < c1; ++c) wx_sum += tent1(t.xs[c] - cx);
            S sum{};
            for (int r = ra; r < rb; ++r) {
                const float w = tent1(t.ys[r] - cy);
                if (w > 0) {
                    sum += t.rows[static_cast<size_t>(r - r0) * tw + (i - tile.x0)] * w;
                    wy_sum += w;
                }
            }
            put(out, i, j, sum * (1.0f / (wx_sum * wy_sum)));
        }
    }
}

}  // namespace

void append_rect(std::string& out, const Image& img, const PixelRect& r) {
    for (int y = r.y0; y < r.y1; ++y)
        out.append(reinterpret_cast<const char*>(&img.at(r.x0, y)), sizeof(Rgb) * r.width());
}

void read_rect(std::string_view& in, Image& img, const PixelRect& r) {
    for (int y = r.y0; y < r.y1; ++y)
        for (int x = r.x0; x < r.x1; ++x) read_raw(in, img.at(x, y));
}

void append_rect(std::string& out, const TermOut& o, const PixelRect& r) {
    append_rect(out, o.image, r);
    for (const Image* plane : o.planes.plane)
        if (plane) append_rect(out, *plane, r);
}

void read_rect(std::string_view& in, TermOut& o, const PixelRect& r) {
    read_rect(in, o.image, r);
    for (Image* plane : o.planes.plane)
        if (plane) read_rect(in, *plane, r);
}

void append_rect(std::string& out, const ImageRows& o, const PixelRect& r) {
    append_rect(out, o.rows, {r.x0, r.y0 - o.y0, r.x1, r.y1 - o.y0});
}

void read_rect(std::string_view& in, ImageRows& o, const PixelRect& r) {
    read_rect(in, o.rows, {r.x0, r.y0 - o.y0, r.x1, r.y1 - o.y0});
}

std::vector<size_t> tile_order(size_t count) {
    std::vector<size_t> order(count);
    for (size_t i = 0; i < count; ++i) order[i] = i;
    // Fisher–Yates with a fixed hash for the random numbers: the same order in every run.
    for (size_t i = count; i > 1; --i) {
        const size_t k = static_cast<size_t>(mix64(kJitterSeed + i) % i);
        std::swap(order[i - 1], order[k]);
    }
    return order;
}

GridSpec GridSpec::from(const AntialiasDesc& aa, int width, int height) {
    GridSpec g;
    g.s = std::max(1, static_cast<int>(std::lround(std::sqrt(static_cast<double>(aa.samples)))));
    g.filter = aa.filter;
    g.jitter = aa.jitter;
    g.width = width;
    g.height = height;
    return g;
}

PixelRect GridSpec::region(const PixelRect& tile) const {
    if (filter == AaFilter::box) return tile;
    return {std::max(0, tile.x0 - 1), std::max(0, tile.y0 - 1), std::min(width, tile.x1 + 1),
            std::min(height, tile.y1 + 1)};
}

bool GridSpec::needed(const PixelRect& tile, float x, float y) const {
    if (filter == AaFilter::box) return true;
    // The tile pixel whose centre is nearest along each axis has the largest weight.
    const int i = std::clamp(static_cast<int>(std::floor(x)), tile.x0, tile.x1 - 1);
    const int j = std::clamp(static_cast<int>(std::floor(y)), tile.y0, tile.y1 - 1);
    return tent1(x - centre(i)) > 0 && tent1(y - centre(j)) > 0;
}

template <class S, class Out>
void filter_tile(const GridSpec& g, const PixelRect& tile, const PixelRect& region,
                 const S* samples, Out& out) {
    if (g.filter == AaFilter::box) {
        box_filter(g, tile, region, samples, out);
    } else if (g.jitter) {
        tent_filter_direct(g, tile, region, samples, out);
    } else {
        tent_filter_separable(g, tile, region, samples, out);
    }
}

AdaptiveSpec AdaptiveSpec::from(const AntialiasDesc& aa, int width, int height) {
    AdaptiveSpec a;
    a.threshold = aa.threshold;
    a.max_level = std::clamp(aa.max_level, 0, 6);
    a.width = width;
    a.height = height;
    return a;
}

template void filter_tile<Rgb, Image>(const GridSpec&, const PixelRect&, const PixelRect&,
                                      const Rgb*, Image&);
template void filter_tile<TermSample, TermOut>(const GridSpec&, const PixelRect&, const PixelRect&,
                                               const TermSample*, TermOut&);
template void filter_tile<Rgb, ImageRows>(const GridSpec&, const PixelRect&, const PixelRect&,
                                          const Rgb*, ImageRows&);

template <class Sample>
uint32_t AdaptiveCache<Sample>::next_generation() {
    if (generation_ == std::numeric_limits<uint32_t>::max()) {  // wrapped: forget everything
        for (auto* v : {&rows_, &cols_, &inner_})
            for (Slot& s : *v) s.stamp = 0;
        generation_ = 0;
    }
    return ++generation_;
}

template <class Sample>
void AdaptiveCache<Sample>::begin_tile(const PixelRect& tile, int S) {
    tile_ = tile;
    S_ = S;
    // Horizontal pixel edges: tile height + 1 lines of width·S + 1 points; vertical alike.
    const size_t row_points = static_cast<size_t>(tile.width()) * S + 1;
    const size_t col_points = static_cast<size_t>(tile.height()) * S + 1;
    const size_t rows = (tile.height() + 1) * row_points, cols = (tile.width() + 1) * col_points;
    if (rows_.size() < rows) rows_.resize(rows);
    if (cols_.size() < cols) cols_.resize(cols);
    const size_t inner = static_cast<size_t>(S + 1) * (S + 1);
    if (inner_.size() < inner) inner_.resize(inner);
    tile_gen_ = next_generation();
}

template <class Sample>
void AdaptiveCache<Sample>::begin_pixel(int i, int j) {
    li_ = i - tile_.x0;
    lj_ = j - tile_.y0;
    pixel_gen_ = next_generation();
}

template <class Sample>
typename AdaptiveCache<Sample>::Slot& AdaptiveCache<Sample>::slot(int k, int l) {
    if (l == 0 || l == S_) {  // on a horizontal edge: line lj (top) or lj + 1 (bottom)
        const size_t row_points = static_cast<size_t>(tile_.width()) * S_ + 1;
        return rows_[(lj_ + (l == S_)) * row_points + static_cast<size_t>(li_) * S_ + k];
    }
    if (k == 0 || k == S_) {  // on a vertical edge
        const size_t col_points = static_cast<size_t>(tile_.height()) * S_ + 1;
        return cols_[(li_ + (k == S_)) * col_points + static_cast<size_t>(lj_) * S_ + l];
    }
    return inner_[static_cast<size_t>(l) * (S_ + 1) + k];
}

template <class Sample>
AdaptiveCache<Sample>& AdaptiveCache<Sample>::for_this_thread() {
    thread_local AdaptiveCache cache;
    return cache;
}

template class AdaptiveCache<Rgb>;
template class AdaptiveCache<TermSample>;

Image aa_mask_image(const AaMask& mask, const Image& render) {
    static const Rgb kLevel[6] = {{0.15f, 0.35f, 1.0f}, {0.0f, 0.85f, 0.95f}, {0.2f, 0.9f, 0.2f},
                                  {1.0f, 0.9f, 0.1f},   {1.0f, 0.5f, 0.0f},   {0.95f, 0.1f, 0.1f}};
    Image img(mask.width, mask.height);
    for (int y = 0; y < mask.height; ++y) {
        for (int x = 0; x < mask.width; ++x) {
            const uint8_t level = mask.level[static_cast<size_t>(y) * mask.width + x];
            if (level > 0) {
                img.at(x, y) = kLevel[std::min<int>(level, 6) - 1];
            } else {
                Rgb c{0.0f};
                if (render.width == mask.width && render.height == mask.height)
                    c = clamp01(render.at(x, y));
                const float luminance = 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z;
                img.at(x, y) = Rgb{0.25f * luminance};
            }
        }
    }
    return img;
}

}  // namespace luz
