#include "viewer/GlTexture.h"

#include <algorithm>
#include <cstring>
#include <vector>

#include <epoxy/gl.h>

namespace raycache {

ViewportRect fitRect(int contentWidth, int contentHeight, int width, int height) {
    if (contentWidth <= 0 || contentHeight <= 0 || width <= 0 || height <= 0) return {};
    // Integer arithmetic: a framebuffer of the content's own size maps 1:1.
    ViewportRect r;
    if (static_cast<long>(width) * contentHeight <= static_cast<long>(height) * contentWidth) {
        r.width = width;
        r.height = static_cast<int>(static_cast<long>(width) * contentHeight / contentWidth);
    } else {
        r.height = height;
        r.width = static_cast<int>(static_cast<long>(height) * contentWidth / contentHeight);
    }
    r.x = (width - r.width) / 2;
    r.y = (height - r.height) / 2;
    return r;
}

GlTexture::GlTexture() {
    glGenTextures(1, &texture_);
    glBindTexture(GL_TEXTURE_2D, texture_);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);  // the cube inspector shows texels
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glGenFramebuffers(1, &framebuffer_);
}

GlTexture::~GlTexture() {
    glDeleteFramebuffers(1, &framebuffer_);
    glDeleteTextures(1, &texture_);
}

void GlTexture::upload(std::span<const std::uint8_t> rgba, int width, int height) {
    glBindTexture(GL_TEXTURE_2D, texture_);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    if (width != width_ || height != height_) {
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
        width_ = width;
        height_ = height;
        glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_);
        glFramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture_, 0);
        glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    } else {
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    }
}

void GlTexture::blitTo(const ViewportRect& target) const {
    if (width_ == 0 || target.width <= 0) return;
    glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    // Texture row 0 is the image's top row; GL's y axis points up: flip.
    const bool sameSize = target.width == width_ && target.height == height_;
    glBlitFramebuffer(0, 0, width_, height_, target.x, target.y + target.height, target.x + target.width, target.y,
                      GL_COLOR_BUFFER_BIT, sameSize ? GL_NEAREST : GL_LINEAR);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
}

void readBackBuffer(int width, int height, std::span<std::uint8_t> rgba) {
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glReadBuffer(GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    // GL's row 0 is the bottom one.
    const auto rowBytes = static_cast<std::size_t>(width) * 4;
    std::vector<std::uint8_t> row(rowBytes);
    for (int y = 0; y < height / 2; ++y) {
        std::uint8_t* a = rgba.data() + static_cast<std::size_t>(y) * rowBytes;
        std::uint8_t* b = rgba.data() + static_cast<std::size_t>(height - 1 - y) * rowBytes;
        std::memcpy(row.data(), a, rowBytes);
        std::memcpy(a, b, rowBytes);
        std::memcpy(b, row.data(), rowBytes);
    }
}

}  // namespace raycache
