// OpenEXR codec: writes 32-bit float R, G, B (exact, unclamped); reads R, G, B or Y of any
// scanline or tiled file. Both go through in-memory streams.

#include <Iex.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>

#include <algorithm>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "image/image_codecs.h"
#include "image/image_io.h"

namespace luz {
namespace {

static_assert(sizeof(Rgb) == 3 * sizeof(float), "Rgb must be three packed floats");

/// An OpenEXR output stream that collects the file in a string (it seeks back to patch the
/// line-offset table).
class MemoryOStream : public Imf::OStream {
  public:
    MemoryOStream() : Imf::OStream("memory") {}

    void write(const char c[], int n) override {
        const size_t end = pos_ + static_cast<size_t>(n);
        if (end > data_.size()) data_.resize(end);
        std::memcpy(data_.data() + pos_, c, static_cast<size_t>(n));
        pos_ = end;
    }
    uint64_t tellp() override { return pos_; }
    void seekp(uint64_t pos) override { pos_ = static_cast<size_t>(pos); }

    std::string data_;

  private:
    size_t pos_ = 0;
};

/// An OpenEXR input stream over bytes in memory.
class MemoryIStream : public Imf::IStream {
  public:
    explicit MemoryIStream(std::string_view bytes) : Imf::IStream("memory"), bytes_(bytes) {}

    bool read(char c[], int n) override {
        if (n < 0 || pos_ > bytes_.size() || static_cast<size_t>(n) > bytes_.size() - pos_) {
            throw IEX_NAMESPACE::InputExc("file is truncated");
        }
        std::memcpy(c, bytes_.data() + pos_, static_cast<size_t>(n));
        pos_ += static_cast<size_t>(n);
        return pos_ < bytes_.size();
    }
    uint64_t tellg() override { return pos_; }
    void seekg(uint64_t pos) override { pos_ = static_cast<size_t>(pos); }

  private:
    std::string_view bytes_;
    size_t pos_ = 0;
};

}  // namespace

std::string encode_exr(const Image& img) { return encode_exr_layers(img, {}); }

std::string encode_exr_layers(const Image& img, const std::vector<ExrLayer>& layers) {
    Imf::Header header(img.width, img.height);
    header.compression() = Imf::ZIP_COMPRESSION;
    Imf::FrameBuffer fb;
    const size_t x_stride = sizeof(Rgb), y_stride = sizeof(Rgb) * static_cast<size_t>(img.width);
    // Channel `name` from component `c` of `image` (the writer only reads through the pointer).
    auto add = [&](const std::string& name, const Image& image, int c) {
        char* base = const_cast<char*>(reinterpret_cast<const char*>(image.pixels.data()));
        header.channels().insert(name, Imf::Channel(Imf::FLOAT));
        fb.insert(name, Imf::Slice(Imf::FLOAT, base + c * sizeof(float), x_stride, y_stride));
    };
    add("R", img, 0);
    add("G", img, 1);
    add("B", img, 2);
    for (const ExrLayer& layer : layers) {
        if (layer.image->width != img.width || layer.image->height != img.height) {
            throw ImageError("EXR layer " + layer.name + " is not the image's size");
        }
        if (layer.scalar) {
            add(layer.name + ".Y", *layer.image, 0);
        } else {
            add(layer.name + ".R", *layer.image, 0);
            add(layer.name + ".G", *layer.image, 1);
            add(layer.name + ".B", *layer.image, 2);
        }
    }

    MemoryOStream out;
    try {
        Imf::OutputFile file(out, header);  // its destructor writes the line-offset table
        file.setFrameBuffer(fb);
        file.writePixels(img.height);
    } catch (const std::exception& e) {
        throw ImageError(std::string("EXR encoding failed: ") + e.what());
    }
    return std::move(out.data_);
}

Image decode_exr(std::string_view bytes) { return decode_exr_layer(bytes, ""); }

Image decode_exr_layer(std::string_view bytes, const std::string& layer) {
    if (bytes.size() < 4 || std::memcmp(bytes.data(), "\x76\x2f\x31\x01", 4) != 0) {
        throw ImageError("not an OpenEXR file");
    }
    try {
        MemoryIStream in(bytes);
        Imf::InputFile file(in);
        const IMATH_NAMESPACE::Box2i dw = file.header().dataWindow();
        const int64_t w = int64_t{dw.max.x} - dw.min.x + 1;
        const int64_t h = int64_t{dw.max.y} - dw.min.y + 1;
        if (w <= 0 || h <= 0 || w > std::numeric_limits<int>::max() ||
            h > std::numeric_limits<int>::max()) {
            throw ImageError("bad data window");
        }

        // Channels absent from the file read as 0; a luminance-only file fills all three.
        const Imf::ChannelList& channels = file.header().channels();
        const std::string prefix = layer.empty() ? "" : layer + ".";
        const std::string R = prefix + "R", G = prefix + "G", B = prefix + "B", Y = prefix + "Y";
        const bool has_rgb = channels.findChannel(R) != nullptr ||
                             channels.findChannel(G) != nullptr ||
                             channels.findChannel(B) != nullptr;
        const bool has_y = channels.findChannel(Y) != nullptr;
        if (!has_rgb && !has_y)
            throw ImageError("no " + R + ", " + G + ", " + B + " or " + Y + " channel");

        Image img(static_cast<int>(w), static_cast<int>(h));
        char* base = reinterpret_cast<char*>(img.pixels.data());
        const size_t x_stride = sizeof(Rgb), y_stride = sizeof(Rgb) * static_cast<size_t>(w);
        Imf::FrameBuffer fb;
        const std::string* names[3] = {&R, &G, &B};
        if (!has_rgb) names[0] = &Y;
        const int count = has_rgb ? 3 : 1;
        for (int c = 0; c < count; ++c) {
            fb.insert(*names[c], Imf::Slice::Make(Imf::FLOAT, base + c * sizeof(float), dw,
                                                  x_stride, y_stride));
        }
        file.setFrameBuffer(fb);
        file.readPixels(dw.min.y, dw.max.y);
        if (!has_rgb) {
            for (Rgb& p : img.pixels) p = Rgb{p.x};
        }
        return img;
    } catch (const ImageError&) {
        throw;
    } catch (const std::exception& e) {
        throw ImageError(std::string("invalid OpenEXR: ") + e.what());
    }
}

}  // namespace luz
