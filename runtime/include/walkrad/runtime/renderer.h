// Renderer: draws baked meshes as they are, unlit: the colour is in the vertices, so the shader
// only projects positions and encodes the linear display colour to sRGB for the screen or file.
// Needs a current OpenGL 3.3 core context for its whole life.
#pragma once

#include "walkrad/runtime/gpu_mesh.h"
#include "walkrad/runtime/mat4.h"

namespace walkrad {

class Renderer {
 public:
  // Compiles and links the shader program. Throws GraphicsError with the driver's log on failure.
  Renderer();
  ~Renderer();
  Renderer(Renderer&& other) noexcept;
  Renderer& operator=(Renderer&& other) noexcept;
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Sets the viewport of the bound framebuffer and clears it to black. Depth test on; back faces
  // kept, since some bakes hold single-sided surfaces that the walkthrough sees from both sides.
  void begin_frame(int width, int height) const;
  // Draws into the frame begun last.
  void draw(const GpuMesh& mesh, const Mat4& view_projection) const;

 private:
  unsigned program_ = 0;
  int view_projection_location_ = -1;
};

}  // namespace walkrad
