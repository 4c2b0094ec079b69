// play_in_window (viewer.h): a GLFW loop over Playback. Keys only change the Playback state; the
// loop draws whatever frame it names, once per display refresh.
#include <string>

#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "walkrad/runtime/playback.h"
#include "walkrad/runtime/player.h"
#include "walkrad/runtime/viewer.h"
#include "walkrad/runtime/window_context.h"

namespace walkrad {

namespace {

// Walkthrough files hold frames, not times: play them at video rate.
constexpr double kFramesPerSecond = 30.0;

void on_key(GLFWwindow* window, int key, int /*scancode*/, int action, int /*mods*/) {
  if (action != GLFW_PRESS && action != GLFW_REPEAT) return;
  auto* playback = static_cast<Playback*>(glfwGetWindowUserPointer(window));
  switch (key) {
    case GLFW_KEY_ESCAPE: glfwSetWindowShouldClose(window, GLFW_TRUE); break;
    case GLFW_KEY_SPACE: if (action == GLFW_PRESS) playback->toggle_pause(); break;
    case GLFW_KEY_RIGHT: playback->step(+1); break;
    case GLFW_KEY_LEFT: playback->step(-1); break;
    default: break;
  }
}

std::string title(const ViewerOptions& options, const Playback& playback, size_t frames) {
  return "walkrad-view " + options.bake_dir + " — frame " + std::to_string(playback.frame() + 1) + "/" +
         std::to_string(frames) + (playback.paused() ? " (paused)" : "");
}

}  // namespace

void play_in_window(const ViewerOptions& options, const std::vector<Viewpoint>& views) {
  const FrameSize size = frame_size(options, views.front());
  WindowContext context(size.width, size.height, "walkrad-view " + options.bake_dir);
  Player player = Player::open(options.bake_dir);
  Playback playback(views.size(), kFramesPerSecond);
  GLFWwindow* window = context.window();
  glfwSetWindowUserPointer(window, &playback);
  glfwSetKeyCallback(window, on_key);

  std::string shown_title;
  double last = glfwGetTime();
  while (!glfwWindowShouldClose(window)) {
    const double now = glfwGetTime();
    playback.advance(now - last);
    last = now;
    int width = 0, height = 0;
    glfwGetFramebufferSize(window, &width, &height);
    if (width > 0 && height > 0) player.draw(views[playback.frame()], width, height);  // 0 while minimised
    const std::string wanted_title = title(options, playback, views.size());
    if (wanted_title != shown_title) glfwSetWindowTitle(window, (shown_title = wanted_title).c_str());
    glfwSwapBuffers(window);
    glfwPollEvents();
  }
}

}  // namespace walkrad
