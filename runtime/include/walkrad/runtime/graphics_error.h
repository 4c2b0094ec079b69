// GraphicsError: OpenGL, EGL or the window system could not give what the runtime needs (no EGL
// surfaceless platform, no 3.3 core context, no display, a shader that does not compile). Kept
// apart from InputError so that walkrad-view can exit with kExitMissingFeature for it.
#pragma once

#include <stdexcept>

namespace walkrad {

class GraphicsError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace walkrad
