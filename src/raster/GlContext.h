#pragma once
// A headless desktop OpenGL context through EGL (Mesa's surfaceless platform,
// else the default display with a pbuffer), with GL functions loaded by
// libepoxy. Works without a window system or a GPU (Mesa llvmpipe), and with
// a vendor driver where there is one.
//
// The header names no EGL or GL type, so only the code that issues GL calls
// (src/raster/, GL tests) needs epoxy's headers.
#include <memory>
#include <string>

namespace raycache {

class GlContext {
public:
    // A context of at least OpenGL `minMajor`.`minMinor` core, current on the
    // calling thread, or null with `whyNot` saying what failed at each attempt.
    static std::unique_ptr<GlContext> create(std::string& whyNot, int minMajor = 3, int minMinor = 3);

    ~GlContext();
    GlContext(const GlContext&) = delete;
    GlContext& operator=(const GlContext&) = delete;

    // Makes the context current on the calling thread (a no-op when it already is).
    void makeCurrent() const;

    // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)".
    std::string renderer() const;
    // How the context was made and what it is, e.g. for a log line.
    const std::string& description() const { return description_; }
    // The context's OpenGL version as major * 10 + minor (45 for 4.5).
    int version() const { return version_; }

private:
    GlContext() = default;

    void* display_ = nullptr;  // EGLDisplay
    void* context_ = nullptr;  // EGLContext
    void* surface_ = nullptr;  // EGLSurface, null when surfaceless
    std::string description_;
    int version_ = 0;
};

}  // namespace raycache
