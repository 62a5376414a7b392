#pragma once
// Test-only: a headless desktop OpenGL context through EGL (Mesa's
// surfaceless platform, else the default display with a pbuffer), with GL
// functions loaded by libepoxy. Lets tests ask real OpenGL for answers
// without a window system or a GPU.
#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <memory>
#include <string>

namespace raycache {

class HeadlessGl {
public:
    // A context current on the calling thread, or null with `whyNot` saying
    // what failed at each attempt (for a skip message).
    static std::unique_ptr<HeadlessGl> create(std::string& whyNot);

    ~HeadlessGl();
    HeadlessGl(const HeadlessGl&) = delete;
    HeadlessGl& operator=(const HeadlessGl&) = delete;

    // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)".
    std::string renderer() const;
    // How the context was made and what it is, for test logs.
    const std::string& description() const { return description_; }

private:
    HeadlessGl() = default;

    EGLDisplay display_ = EGL_NO_DISPLAY;
    EGLContext context_ = EGL_NO_CONTEXT;
    EGLSurface surface_ = EGL_NO_SURFACE;
    std::string description_;
};

}  // namespace raycache
