// play_in_window (viewer.h): a GLFW loop over Playback or a FlyCamera. Keys and the mouse only
// change that state; the loop asks the player for whatever camera it names, once per display
// refresh, and never waits for a chunk (a missing one appears a frame or two later).
#include <cstdio>
#include <string>

#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "walkrad/runtime/fly_camera.h"
#include "walkrad/runtime/playback.h"
#include "walkrad/runtime/player.h"
#include "walkrad/runtime/viewer.h"
#include "walkrad/runtime/window_context.h"

namespace walkrad {

namespace {

// Walkthrough files hold frames, not times: play them at video rate.
constexpr double kFramesPerSecond = 30.0;
constexpr double kWalkSpeed = 2.0;           // metres per second, a brisk walk
constexpr double kLookRadiansPerPixel = 0.003;

struct WindowState {
  Playback playback;
  FlyCamera fly;
  bool flying = false;
  bool show_stats = false;
  double last_x = 0, last_y = 0;
  bool dragging = false;
};

void on_key(GLFWwindow* window, int key, int /*scancode*/, int action, int /*mods*/) {
  if (action != GLFW_PRESS && action != GLFW_REPEAT) return;
  auto* state = static_cast<WindowState*>(glfwGetWindowUserPointer(window));
  switch (key) {
    case GLFW_KEY_ESCAPE: glfwSetWindowShouldClose(window, GLFW_TRUE); break;
    case GLFW_KEY_SPACE: if (action == GLFW_PRESS) state->playback.toggle_pause(); break;
    case GLFW_KEY_RIGHT: state->playback.step(+1); break;
    case GLFW_KEY_LEFT: state->playback.step(-1); break;
    case GLFW_KEY_R: state->flying = false; break;
    case GLFW_KEY_TAB: if (action == GLFW_PRESS) state->show_stats = !state->show_stats; break;
    default: break;
  }
}

// Leaving the path starts from where the path is now, and pauses it there.
void start_flying(WindowState& state, const Viewpoint& path_view) {
  if (state.flying) return;
  state.fly = FlyCamera::from(path_view);
  state.flying = true;
  if (!state.playback.paused()) state.playback.toggle_pause();
}

void fly(GLFWwindow* window, WindowState& state, const Viewpoint& path_view, double seconds) {
  const auto down = [&](int key) { return glfwGetKey(window, key) == GLFW_PRESS ? 1.0 : 0.0; };
  const double forward = down(GLFW_KEY_W) - down(GLFW_KEY_S), right = down(GLFW_KEY_D) - down(GLFW_KEY_A),
               up = down(GLFW_KEY_E) - down(GLFW_KEY_Q);
  double x = 0, y = 0;
  glfwGetCursorPos(window, &x, &y);
  const bool dragging = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
  const bool looking = dragging && state.dragging && (x != state.last_x || y != state.last_y);
  if (forward != 0 || right != 0 || up != 0 || looking) start_flying(state, path_view);
  if (state.flying) {
    if (looking) state.fly.turn((x - state.last_x) * kLookRadiansPerPixel, -(y - state.last_y) * kLookRadiansPerPixel);
    const double step = kWalkSpeed * seconds;
    state.fly.move(forward * step, right * step, up * step);
  }
  state.last_x = x;
  state.last_y = y;
  state.dragging = dragging;
}

std::string title(const ViewerOptions& options, const WindowState& state, size_t frames, Player& player) {
  std::string t = "walkrad-view " + options.bake_dir + " — ";
  t += state.flying ? std::string("free flight (R: back to the path)")
                    : "frame " + std::to_string(state.playback.frame() + 1) + "/" + std::to_string(frames) +
                          (state.playback.paused() ? " (paused)" : "");
  if (state.show_stats) {
    const RenderStats& s = player.stats();
    char line[200];
    std::snprintf(line, sizeof line, " — %zu/%zu chunks, %.1f MB resident (budget %s), %llu misses, %.1f ms",
                  s.chunks_resident, s.chunks_total, double(s.resident_bytes) / 1e6,
                  s.budget_bytes ? (std::to_string(s.budget_bytes / 1000000) + " MB").c_str() : "none",
                  static_cast<unsigned long long>(s.chunk_misses), s.frame_cpu_ms.empty() ? 0.0 : s.frame_cpu_ms.back());
    t += line;
  }
  return t;
}

}  // namespace

void play_in_window(const ViewerOptions& options, const std::vector<Viewpoint>& views) {
  const FrameSize size = frame_size(options, views.front());
  WindowContext context(size.width, size.height, "walkrad-view " + options.bake_dir);
  Player player = Player::open(options.bake_dir, options.stream);
  const bool on_path = options.path_file.empty();  // the manifest's viewpoints: importance applies
  WindowState state{Playback(views.size(), kFramesPerSecond), FlyCamera{}, false, false, 0, 0, false};
  GLFWwindow* window = context.window();
  glfwSetWindowUserPointer(window, &state);
  glfwSetKeyCallback(window, on_key);

  std::string shown_title;
  double last = glfwGetTime();
  while (!glfwWindowShouldClose(window)) {
    const double now = glfwGetTime();
    state.playback.advance(now - last);
    const Viewpoint& path_view = views[state.playback.frame()];
    fly(window, state, path_view, now - last);
    last = now;
    int width = 0, height = 0;
    glfwGetFramebufferSize(window, &width, &height);
    if (width > 0 && height > 0) {  // 0 while minimised
      CameraPlace camera{path_view, on_path ? std::optional<size_t>(state.playback.frame()) : std::nullopt, true};
      if (state.flying) camera = CameraPlace{state.fly.viewpoint(), std::nullopt, true};
      camera.view.aspect = double(width) / double(height);
      player.update(camera);
      player.draw(width, height, MissPolicy::kDrawWithout);
    }
    const std::string wanted_title = title(options, state, views.size(), player);
    if (wanted_title != shown_title) glfwSetWindowTitle(window, (shown_title = wanted_title).c_str());
    glfwSwapBuffers(window);
    glfwPollEvents();
  }
}

}  // namespace walkrad
