// Upload of a float image to an OpenGL texture.
#include "app/viewer/gl_texture.h"

#include <SDL_opengl.h>

#include "luz/luz.h"
#include "luz/pictures.h"

namespace luz {

GlTexture::~GlTexture() {
    if (id_) glDeleteTextures(1, &id_);
}

void GlTexture::upload(const Image& img, Encoding e) {
    bytes_ = rgba8(img, e);
    if (!id_) glGenTextures(1, &id_);
    glBindTexture(GL_TEXTURE_2D, id_);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, img.width, img.height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                 bytes_.data());
    width_ = img.width;
    height_ = img.height;
}

}  // namespace luz
