// HeadlessContext (headless_context.h): EGL_PLATFORM_SURFACELESS_MESA through
// eglGetPlatformDisplayEXT, desktop OpenGL bound with eglBindAPI, a 3.3 core context made current
// without a surface (EGL_KHR_surfaceless_context). Verified on Mesa 22.3 (docs: deps.md).
#include "walkrad/runtime/headless_context.h"

#include <cstdio>
#include <cstring>

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include "walkrad/runtime/graphics_error.h"

namespace walkrad {

namespace {

[[noreturn]] void fail(const std::string& step) {
  char code[16];
  std::snprintf(code, sizeof code, "0x%04X", unsigned(eglGetError()));
  throw GraphicsError("EGL: " + step + " (EGL error " + code + ")");
}

// Extension lists are space separated: a plain strstr would take a prefix for a match.
bool has_extension(const char* list, const char* name) {
  if (!list) return false;
  const size_t n = std::strlen(name);
  for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += n)
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  return false;
}

}  // namespace

HeadlessContext::HeadlessContext() {
  // Checked before calling through epoxy, which aborts the process on a function nobody provides.
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (!has_extension(client, "EGL_EXT_platform_base") || !has_extension(client, "EGL_MESA_platform_surfaceless"))
    throw GraphicsError("EGL: the surfaceless platform (EGL_MESA_platform_surfaceless) is not available; "
                        "headless rendering needs Mesa's libEGL (Debian: libegl-mesa0)");

  EGLDisplay display = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  if (display == EGL_NO_DISPLAY) fail("no surfaceless display");
  EGLint major = 0, minor = 0;
  if (!eglInitialize(display, &major, &minor)) fail("cannot initialise the surfaceless display");
  display_ = display;
  if (!has_extension(eglQueryString(display, EGL_EXTENSIONS), "EGL_KHR_surfaceless_context"))
    throw GraphicsError("EGL: EGL_KHR_surfaceless_context is not supported");
  if (!eglBindAPI(EGL_OPENGL_API)) fail("desktop OpenGL is not available");

  // The surfaceless platform offers pbuffer configs only; the bit is asked for, no pbuffer is made.
  const EGLint config_attribs[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
  EGLConfig config = nullptr;
  EGLint configs = 0;
  if (!eglChooseConfig(display, config_attribs, &config, 1, &configs) || configs < 1)
    fail("no config for desktop OpenGL");

  const EGLint context_attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                                    EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
  EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, context_attribs);
  if (context == EGL_NO_CONTEXT) fail("cannot create an OpenGL 3.3 core context");
  context_ = context;
  if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
    eglDestroyContext(display, context);
    fail("cannot make the context current without a surface");
  }
}

HeadlessContext::~HeadlessContext() {
  if (!context_) return;
  eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(display_, context_);
  // No eglTerminate: the platform display is one per process, shared by every HeadlessContext, and
  // terminating it would pull it from under the others.
}

std::string HeadlessContext::description() const {
  const auto text = [](GLenum name) {
    const GLubyte* s = glGetString(name);
    return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
  };
  return text(GL_RENDERER) + ", " + text(GL_VERSION);
}

}  // namespace walkrad
