// WindowContext: an on-screen window with an OpenGL 3.3 core context (GLFW), for watching a bake
// interactively. Needs a display (X11 here: GLFW is built for it); headless runs use
// HeadlessContext instead. One per process, since it owns GLFW's initialisation.
#pragma once

#include <string>

struct GLFWwindow;

namespace walkrad {

class WindowContext {
 public:
  // Opens the window and makes its context current. Throws GraphicsError with GLFW's reason
  // (no display, no 3.3 core context).
  WindowContext(int width, int height, const std::string& title);
  ~WindowContext();
  WindowContext(const WindowContext&) = delete;
  WindowContext& operator=(const WindowContext&) = delete;

  GLFWwindow* window() const { return window_; }

 private:
  GLFWwindow* window_ = nullptr;
};

}  // namespace walkrad
