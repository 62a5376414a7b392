#include "raster/GlContext.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <cstdio>
#include <cstring>
#include <utility>

#include "core/Errors.h"

namespace raycache {

namespace {

bool hasExtension(const char* list, const char* name) {
    if (list == nullptr) return false;
    const std::size_t n = std::strlen(name);
    for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += n) {
        const bool startsWord = p == list || p[-1] == ' ';
        const bool endsWord = p[n] == ' ' || p[n] == '\0';
        if (startsWord && endsWord) return true;
    }
    return false;
}

std::string eglErrorText() {
    char buf[32];
    std::snprintf(buf, sizeof buf, "EGL error 0x%04x", static_cast<unsigned>(eglGetError()));
    return buf;
}

struct Attempt {
    EGLDisplay display;
    const char* name;
};

}  // namespace

std::unique_ptr<GlContext> GlContext::create(std::string& whyNot, int minMajor, int minMinor) {
    const int minVersion = minMajor * 10 + minMinor;
    whyNot.clear();
    // Client extensions (EGL_NO_DISPLAY) say whether platform displays exist.
    const char* clientExtensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);

    Attempt attempts[2] = {{EGL_NO_DISPLAY, "surfaceless"}, {EGL_NO_DISPLAY, "default display"}};
    if (hasExtension(clientExtensions, "EGL_EXT_platform_base") &&
        hasExtension(clientExtensions, "EGL_MESA_platform_surfaceless")) {
        attempts[0].display = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        if (attempts[0].display == EGL_NO_DISPLAY) whyNot += "surfaceless: no display (" + eglErrorText() + "); ";
    } else {
        whyNot += "surfaceless: EGL_MESA_platform_surfaceless unavailable; ";
    }
    attempts[1].display = eglGetDisplay(EGL_DEFAULT_DISPLAY);

    for (const Attempt& attempt : attempts) {
        if (attempt.display == EGL_NO_DISPLAY) {
            if (&attempt == &attempts[1]) whyNot += "default display: eglGetDisplay failed (" + eglErrorText() + "); ";
            continue;
        }
        const std::string where = std::string(attempt.name) + ": ";
        EGLint major = 0, minor = 0;
        if (!eglInitialize(attempt.display, &major, &minor)) {
            whyNot += where + "eglInitialize failed (" + eglErrorText() + "); ";
            continue;
        }
        std::unique_ptr<GlContext> gl(new GlContext);
        gl->display_ = attempt.display;  // from here on the destructor cleans up
        if (!eglBindAPI(EGL_OPENGL_API)) {
            whyNot += where + "no desktop OpenGL API (" + eglErrorText() + "); ";
            continue;
        }
        const EGLint configAttribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, EGL_PBUFFER_BIT,
                                        EGL_NONE};
        EGLConfig config = nullptr;
        EGLint configCount = 0;
        if (!eglChooseConfig(attempt.display, configAttribs, &config, 1, &configCount) || configCount == 0) {
            whyNot += where + "no OpenGL pbuffer config (" + eglErrorText() + "); ";
            continue;
        }
        // Newest first: 4.5 core is preferred; callers say what they need at least.
        constexpr std::pair<EGLint, EGLint> kVersions[] = {{4, 5}, {4, 3}, {3, 3}};
        for (const auto& [wantMajor, wantMinor] : kVersions) {
            if (wantMajor * 10 + wantMinor < minVersion) continue;
            const EGLint contextAttribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                             wantMajor,
                                             EGL_CONTEXT_MINOR_VERSION,
                                             wantMinor,
                                             EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                             EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                             EGL_NONE};
            gl->context_ = eglCreateContext(attempt.display, config, EGL_NO_CONTEXT, contextAttribs);
            if (gl->context_ != EGL_NO_CONTEXT) break;
        }
        if (gl->context_ == EGL_NO_CONTEXT) {
            whyNot += where + "no OpenGL " + std::to_string(minMajor) + "." + std::to_string(minMinor) +
                      "+ core context (" + eglErrorText() + "); ";
            continue;
        }
        // Users render into their own framebuffer objects, so no surface is
        // needed where EGL allows that; otherwise a 1x1 pbuffer.
        const bool surfaceless =
            hasExtension(eglQueryString(attempt.display, EGL_EXTENSIONS), "EGL_KHR_surfaceless_context");
        if (!surfaceless) {
            const EGLint pbufferAttribs[] = {EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE};
            gl->surface_ = eglCreatePbufferSurface(attempt.display, config, pbufferAttribs);
            if (gl->surface_ == EGL_NO_SURFACE) {
                whyNot += where + "no pbuffer surface (" + eglErrorText() + "); ";
                continue;
            }
        }
        if (!eglMakeCurrent(attempt.display, gl->surface_, gl->surface_, gl->context_)) {
            whyNot += where + "eglMakeCurrent failed (" + eglErrorText() + "); ";
            continue;
        }
        const int glVersion = epoxy_gl_version();
        if (glVersion < minVersion) {
            whyNot += where + "context is OpenGL " + std::to_string(glVersion / 10) + "." +
                      std::to_string(glVersion % 10) + ", need " + std::to_string(minMajor) + "." +
                      std::to_string(minMinor) + "; ";
            continue;
        }
        gl->version_ = glVersion;
        gl->description_ = std::string("EGL ") + std::to_string(major) + "." + std::to_string(minor) + " " +
                           attempt.name + (surfaceless ? " (no surface)" : " (pbuffer)") + ", OpenGL " +
                           reinterpret_cast<const char*>(glGetString(GL_VERSION)) + ", " + gl->renderer();
        whyNot.clear();
        return gl;
    }
    return nullptr;
}

GlContext::~GlContext() {
    if (display_ == EGL_NO_DISPLAY) return;
    if (eglGetCurrentContext() == context_) eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (surface_ != EGL_NO_SURFACE) eglDestroySurface(display_, surface_);
    if (context_ != EGL_NO_CONTEXT) eglDestroyContext(display_, context_);
    // No eglTerminate: an EGL display lives as long as the process anyway, and
    // terminating it unloads Mesa's driver, whose one-time allocations are then
    // referenced only from unmapped memory. LeakSanitizer reports those as
    // leaks in "<unknown module>", which no suppression can name.
    eglReleaseThread();
}

void GlContext::makeCurrent() const {
    if (eglGetCurrentContext() == context_) return;
    if (!eglMakeCurrent(display_, surface_, surface_, context_))
        throw RuntimeError("OpenGL: cannot make the context current (" + eglErrorText() + ")");
}

std::string GlContext::renderer() const {
    const auto* text = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    return text != nullptr ? text : "";
}

}  // namespace raycache
