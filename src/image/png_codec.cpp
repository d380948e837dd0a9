// PNG codec with libpng: writes 8-bit RGB (image data deflated in parallel bands with zlib, whole
// or band by band as a render gives them: PngBands),
// reads any PNG (8/16-bit, grey, palette, alpha).
// libpng reports errors by longjmp: every setjmp lives in a small function without C++ objects.

#include <png.h>
#include <tbb/parallel_for.h>
#include <zlib.h>

#include <algorithm>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <new>
#include <vector>

#include "image/image_codecs.h"
#include "image/image_io.h"
#include "scene/cancel.h"

namespace luz {
namespace {

/// What libpng's callbacks share with us: the output or input bytes and the last error.
struct PngContext {
    std::string* out = nullptr;
    std::string_view in;
    size_t pos = 0;
    char message[200] = "libpng error";
};

PngContext& context_of(png_structp png) {
    return *static_cast<PngContext*>(png_get_error_ptr(png));
}

void on_error(png_structp png, png_const_charp msg) {
    std::snprintf(context_of(png).message, sizeof(PngContext::message), "%s", msg);
    png_longjmp(png, 1);
}

void on_warning(png_structp, png_const_charp) {}

void write_bytes(png_structp png, png_bytep data, size_t n) {
    PngContext& ctx = context_of(png);
    bool ok = true;
    try {
        ctx.out->append(reinterpret_cast<const char*>(data), n);
    } catch (...) {  // no C++ exception may cross libpng's C frames
        ok = false;
    }
    if (!ok) png_error(png, "out of memory");
}

void flush_bytes(png_structp) {}

void read_bytes(png_structp png, png_bytep data, size_t n) {
    PngContext& ctx = context_of(png);
    if (n > ctx.in.size() - ctx.pos) png_error(png, "file is truncated");
    std::memcpy(data, ctx.in.data() + ctx.pos, n);
    ctx.pos += n;
}

/// Rows per band of the PNG image data (PngBands::kBandRows).
constexpr int kBandRows = PngBands::kBandRows;

}  // namespace

/// One band of the PNG image data (PngBands): its rows quantized by encode_8bit, each
/// prefixed by filter type 1 (Sub: every byte minus the one 3 to its left), deflated at level 3
/// on its own; every band but the image's last ends with a sync flush (on a byte boundary), so
/// the bands joined make one deflate stream (as pigz does). The Adler-32 of the whole is
/// combined from the bands'. Quantized and filtered in a per-thread buffer: only the
/// compressed bytes are kept. `ok` false on failure (zlib out of memory).
struct PngBand {
    std::unique_ptr<Bytef[]> bytes;  // compressed; uninitialised beyond `size`
    size_t size = 0;
    uLong adler = 1;
    size_t length = 0;  // filtered bytes
    bool ok = false;
};  // outside the anonymous namespace: PngBands::Bands, which is not in one, holds a list of them

namespace {

/// Band `band` from `rows` rows of `img` starting at its row `first`; `last`: the image's last.
void deflate_band(const Image& img, int first, int rows, bool last, Encoding e, PngBand& band) {
    constexpr int kLevel = 3;
    const size_t row_size = static_cast<size_t>(img.width) * 3;
    // Reused by the thread's bands and kept until it ends (~(64 + 1)·3·width bytes).
    thread_local std::vector<Bytef> filtered, line;
    filtered.resize(static_cast<size_t>(rows) * (row_size + 1));
    line.resize(row_size);
    Bytef* f = filtered.data();
    Bytef* const l = line.data();  // (bytes may alias anything: not line[k], which reloads)
    for (int y = first; y < first + rows; ++y) {
        const Rgb* px = &img.at(0, y);
        for (int x = 0; x < img.width; ++x) {
            l[3 * x + 0] = encode_8bit(px[x].x, e);
            l[3 * x + 1] = encode_8bit(px[x].y, e);
            l[3 * x + 2] = encode_8bit(px[x].z, e);
        }
        *f++ = 1;  // Sub
        for (size_t k = 0; k < row_size; ++k) {
            *f++ = static_cast<Bytef>(l[k] - (k >= 3 ? l[k - 3] : 0));
        }
    }
    band.length = filtered.size();
    band.adler = adler32(1, filtered.data(), static_cast<uInt>(filtered.size()));
    z_stream z{};
    if (deflateInit2(&z, kLevel, Z_DEFLATED, -15, 8, Z_DEFAULT_STRATEGY) != Z_OK) return;
    const size_t bound = deflateBound(&z, static_cast<uLong>(filtered.size())) + 16;
    band.bytes.reset(new (std::nothrow) Bytef[bound]);
    if (!band.bytes) {
        deflateEnd(&z);
        return;
    }
    z.next_in = filtered.data();
    z.avail_in = static_cast<uInt>(filtered.size());
    z.next_out = band.bytes.get();
    z.avail_out = static_cast<uInt>(bound);
    const int flush = last ? Z_FINISH : Z_SYNC_FLUSH;
    const int status = deflate(&z, flush);
    band.ok = flush == Z_FINISH ? status == Z_STREAM_END : status == Z_OK && z.avail_in == 0;
    band.size = bound - z.avail_out;
    deflateEnd(&z);
}

/// Runs libpng's writer: signature, IHDR (and the sRGB chunks), then `idat` (PngBands) in
/// IDAT chunks of at most 8 MiB, then IEND; false on error (message in ctx).
bool run_png_writer(PngContext& ctx, png_uint_32 w, png_uint_32 h, const std::string& idat,
                    bool srgb) {
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &ctx, on_error, on_warning);
    if (png == nullptr) return false;
    png_infop info = png_create_info_struct(png);
    if (info == nullptr) {
        png_destroy_write_struct(&png, nullptr);
        return false;
    }
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        return false;
    }
    png_set_write_fn(png, &ctx, write_bytes, flush_bytes);
    png_set_IHDR(png, info, w, h, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    // Linear files carry no colour chunk: viewers show the values as they are (the lecture's
    // model); sRGB-encoded files say so.
    if (srgb) png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
    png_write_info(png, info);
    constexpr size_t kChunk = size_t{8} << 20;
    for (size_t at = 0; at < idat.size(); at += kChunk) {
        png_write_chunk(png, reinterpret_cast<png_const_bytep>("IDAT"),
                        reinterpret_cast<png_const_bytep>(idat.data()) + at,
                        std::min(kChunk, idat.size() - at));
    }
    png_write_chunk(png, reinterpret_cast<png_const_bytep>("IEND"), nullptr, 0);
    png_destroy_write_struct(&png, &info);
    return true;
}

/// A libpng reader, destroyed with its owner.
struct PngReader {
    PngContext ctx;
    png_structp png = nullptr;
    png_infop info = nullptr;
    ~PngReader() {
        if (png != nullptr)
            png_destroy_read_struct(&png, info != nullptr ? &info : nullptr, nullptr);
    }
};

/// Reads the header and sets the transforms to 3-channel RGB; false on error.
bool read_png_header(PngReader& r, png_uint_32& w, png_uint_32& h, int& bits, size_t& rowbytes) {
    if (setjmp(png_jmpbuf(r.png))) return false;
    png_set_read_fn(r.png, &r.ctx, read_bytes);
    png_read_info(r.png, r.info);
    png_set_expand(r.png);  // palette → RGB, grey below 8 bits → 8, tRNS → alpha
    png_set_gray_to_rgb(r.png);
    png_set_strip_alpha(r.png);
    png_set_interlace_handling(r.png);
    png_read_update_info(r.png, r.info);
    w = png_get_image_width(r.png, r.info);
    h = png_get_image_height(r.png, r.info);
    bits = png_get_bit_depth(r.png, r.info);
    rowbytes = png_get_rowbytes(r.png, r.info);
    return true;
}

/// Reads every row (rows[] prepared by the caller); false on error.
bool read_png_rows(PngReader& r, png_bytepp rows) {
    if (setjmp(png_jmpbuf(r.png))) return false;
    png_read_image(r.png, rows);
    png_read_end(r.png, nullptr);
    return true;
}

}  // namespace

struct PngBands::Bands {
    std::vector<PngBand> list;
};

PngBands::PngBands(int width, int height, Encoding e)
    : width_(width), height_(height), encoding_(e), bands_(std::make_unique<Bands>()) {
    bands_->list.resize(static_cast<size_t>((height + kBandRows - 1) / kBandRows));
}

PngBands::~PngBands() = default;

void PngBands::add(const Image& rows, int count) {
    if (rows.width != width_ || count < 0 || count > rows.height || count > height_ - done_ ||
        (done_ + count < height_ && count % kBandRows != 0)) {
        throw ImageError("PNG encoding failed: rows given out of order");
    }
    const int first_band = done_ / kBandRows, bands = (count + kBandRows - 1) / kBandRows;
    const std::atomic<bool>* cancel = cancel_flag();  // checked band by band (~1.5 MB each)
    tbb::parallel_for(0, bands, [&](int b) {
        if (cancel_requested(cancel)) return;
        const int first = b * kBandRows, n = std::min(kBandRows, count - first);
        const bool last = done_ + first + n == height_;
        deflate_band(rows, first, n, last, encoding_, bands_->list[first_band + b]);
    });
    check_cancel();
    done_ += count;
}

std::string PngBands::finish() {
    if (done_ != height_) throw ImageError("PNG encoding failed: rows missing");
    // zlib header: deflate, 32 KiB window, FLEVEL 1 (levels 2–5), FCHECK making it a multiple
    // of 31; then the bands; then the Adler-32 of all filtered bytes, big-endian. Quantized
    // and compressed first: no C++ allocation happens while libpng runs, except in
    // write_bytes.
    size_t total = 2 + 4;
    for (const PngBand& band : bands_->list) total += band.size;
    std::string idat = {'\x78', '\x5E'};
    idat.reserve(total);
    uLong adler = 1;
    for (const PngBand& band : bands_->list) {
        if (!band.ok) throw ImageError("PNG encoding failed: zlib could not compress the image");
        idat.append(reinterpret_cast<const char*>(band.bytes.get()), band.size);
        adler = adler32_combine(adler, band.adler, static_cast<z_off_t>(band.length));
    }
    for (int shift = 24; shift >= 0; shift -= 8) idat += static_cast<char>((adler >> shift) & 0xFF);
    bands_->list.clear();
    std::string out;
    out.reserve(idat.size() + 1024);
    PngContext ctx;
    ctx.out = &out;
    if (!run_png_writer(ctx, static_cast<png_uint_32>(width_), static_cast<png_uint_32>(height_),
                        idat, encoding_ == Encoding::srgb)) {
        throw ImageError(std::string("PNG encoding failed: ") + ctx.message);
    }
    return out;
}

std::string encode_png(const Image& img, Encoding e) {
    PngBands png(img.width, img.height, e);
    png.add(img, img.height);
    return png.finish();
}

Image decode_png(std::string_view bytes) {
    if (bytes.size() < 8 || png_sig_cmp(reinterpret_cast<png_const_bytep>(bytes.data()), 0, 8)) {
        throw ImageError("not a PNG file");
    }
    PngReader r;
    r.ctx.in = bytes;
    r.png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &r.ctx, on_error, on_warning);
    if (r.png == nullptr) throw ImageError("cannot initialise libpng");
    r.info = png_create_info_struct(r.png);
    if (r.info == nullptr) throw ImageError("cannot initialise libpng");

    png_uint_32 w = 0, h = 0;
    int bits = 0;
    size_t rowbytes = 0;
    if (!read_png_header(r, w, h, bits, rowbytes)) {
        throw ImageError(std::string("invalid PNG: ") + r.ctx.message);
    }
    const size_t bytes_per_sample = bits == 16 ? 2 : 1;
    if ((bits != 8 && bits != 16) || rowbytes != static_cast<size_t>(w) * 3 * bytes_per_sample ||
        w > static_cast<png_uint_32>(std::numeric_limits<int>::max()) ||
        h > static_cast<png_uint_32>(std::numeric_limits<int>::max())) {
        throw ImageError("unsupported PNG layout");
    }

    std::vector<png_byte> data(rowbytes * h);
    std::vector<png_bytep> rows(h);
    for (png_uint_32 y = 0; y < h; ++y) rows[y] = data.data() + rowbytes * y;
    if (!read_png_rows(r, rows.data())) {
        throw ImageError(std::string("invalid PNG: ") + r.ctx.message);
    }

    // Samples become v / (2^bits − 1); 16-bit samples are big-endian.
    Image img(static_cast<int>(w), static_cast<int>(h));
    const size_t count = img.pixels.size();
    if (bits == 8) {
        for (size_t i = 0; i < count; ++i) {
            const png_byte* s = data.data() + 3 * i;
            img.pixels[i] = Rgb{s[0] / 255.0f, s[1] / 255.0f, s[2] / 255.0f};
        }
    } else {
        const auto sample = [](const png_byte* s) {
            return static_cast<float>((static_cast<unsigned>(s[0]) << 8) | s[1]) / 65535.0f;
        };
        for (size_t i = 0; i < count; ++i) {
            const png_byte* s = data.data() + 6 * i;
            img.pixels[i] = Rgb{sample(s), sample(s + 2), sample(s + 4)};
        }
    }
    return img;
}

}  // namespace luz
