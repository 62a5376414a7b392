#pragma once
// An RGBA8 OpenGL texture that a frame (or the cache inspector's picture) is
// uploaded into, and that can be drawn into the window by a framebuffer
// blit or shown by ImGui. UI thread only, with the context current.
#include <cstdint>
#include <span>

namespace raycache {

struct ViewportRect {
    int x = 0, y = 0, width = 0, height = 0;  // GL window coordinates, origin bottom-left
};

// The largest rectangle of `contentWidth:contentHeight` aspect centred in a
// `width` x `height` framebuffer (letterboxing).
ViewportRect fitRect(int contentWidth, int contentHeight, int width, int height);

class GlTexture {
public:
    GlTexture();
    ~GlTexture();
    GlTexture(const GlTexture&) = delete;
    GlTexture& operator=(const GlTexture&) = delete;

    // Replaces the contents with `rgba` (width x height, row 0 at the top),
    // reallocating only when the size changes.
    void upload(std::span<const std::uint8_t> rgba, int width, int height);
    int width() const { return width_; }
    int height() const { return height_; }
    // For ImGui::Image.
    unsigned int id() const { return texture_; }

    // Copies the texture into `target` of the default framebuffer, flipped so
    // row 0 is at the top; linear filtering when scaled.
    void blitTo(const ViewportRect& target) const;

private:
    unsigned int texture_ = 0;
    unsigned int framebuffer_ = 0;
    int width_ = 0;
    int height_ = 0;
};

// Reads the default framebuffer's back buffer (width x height) as RGBA8,
// row 0 at the top: what the next swap shows.
void readBackBuffer(int width, int height, std::span<std::uint8_t> rgba);

}  // namespace raycache
