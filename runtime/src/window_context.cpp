// WindowContext (window_context.h). GLFW_INCLUDE_NONE keeps GLFW from including the system GL
// header, which would clash with epoxy's wherever both are used.
#include "walkrad/runtime/window_context.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "walkrad/runtime/graphics_error.h"

namespace walkrad {

namespace {

// GLFW's description of its last error ("DISPLAY environment variable is missing"), read before
// glfwTerminate clears it.
std::string glfw_error(const std::string& step) {
  const char* reason = nullptr;
  glfwGetError(&reason);
  return "GLFW: " + step + (reason ? std::string(": ") + reason : std::string());
}

}  // namespace

WindowContext::WindowContext(int width, int height, const std::string& title) {
  if (!glfwInit()) throw GraphicsError(glfw_error("cannot initialise"));
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (!window_) {
    const std::string message = glfw_error("cannot open a window with an OpenGL 3.3 core context");
    glfwTerminate();
    throw GraphicsError(message);
  }
  glfwMakeContextCurrent(window_);
  glfwSwapInterval(1);  // paced by the display, not spinning the CPU
}

WindowContext::~WindowContext() {
  glfwDestroyWindow(window_);
  glfwTerminate();
}

}  // namespace walkrad
