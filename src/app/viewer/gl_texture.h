// GlTexture: the rendered float image as an OpenGL texture (8-bit, the scene's encoding).
#pragma once

#include <cstdint>
#include <vector>

#include "luz/luz.h"

namespace luz {

class GlTexture {
  public:
    GlTexture() = default;
    ~GlTexture();
    GlTexture(const GlTexture&) = delete;
    GlTexture& operator=(const GlTexture&) = delete;

    /// Uploads `img` encoded to 8 bits as `luz render` writes PNGs (image_io.h encode_8bit);
    /// sampled nearest, so coarse passes show as blocks and full ones pixel for pixel.
    void upload(const Image& img, Encoding e);

    /// The texture's id for ImGui::Image / AddImage (0 before the first upload).
    void* id() const { return reinterpret_cast<void*>(static_cast<uintptr_t>(id_)); }
    int width() const { return width_; }
    int height() const { return height_; }

  private:
    unsigned id_ = 0;
    int width_ = 0, height_ = 0;
    std::vector<uint8_t> bytes_;
};

}  // namespace luz
