// Renderer (renderer.h): one GLSL 3.30 program. sRGB encoding happens in the fragment shader rather
// than through GL_FRAMEBUFFER_SRGB so that the offscreen RGBA8 target and a window's default
// framebuffer (sRGB-capable or not) give the same bytes.
#include "walkrad/runtime/renderer.h"

#include <string>
#include <utility>

#include <epoxy/gl.h>

#include "walkrad/runtime/graphics_error.h"

namespace walkrad {

namespace {

const char* const kVertexShader = R"(#version 330 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 color;
uniform mat4 view_projection;
out vec3 linear_color;
void main() {
  linear_color = color;
  gl_Position = view_projection * vec4(position, 1.0);
}
)";

// The colour is interpolated in linear space, then clamped (a bake's display colour may exceed 1)
// and encoded with the piecewise sRGB curve of IEC 61966-2-1.
const char* const kFragmentShader = R"(#version 330 core
in vec3 linear_color;
out vec4 frag_color;
vec3 srgb_encode(vec3 c) {
  c = clamp(c, 0.0, 1.0);
  return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}
void main() {
  frag_color = vec4(srgb_encode(linear_color), 1.0);
}
)";

GLuint compile(GLenum stage, const char* source, const char* name) {
  const GLuint shader = glCreateShader(stage);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    glDeleteShader(shader);
    throw GraphicsError(std::string("OpenGL: the ") + name + " shader does not compile: " + log);
  }
  return shader;
}

}  // namespace

Renderer::Renderer() {
  const GLuint vertex = compile(GL_VERTEX_SHADER, kVertexShader, "vertex");
  GLuint fragment = 0;
  try {
    fragment = compile(GL_FRAGMENT_SHADER, kFragmentShader, "fragment");
  } catch (...) {
    glDeleteShader(vertex);
    throw;
  }
  program_ = glCreateProgram();
  glAttachShader(program_, vertex);
  glAttachShader(program_, fragment);
  glLinkProgram(program_);
  glDeleteShader(vertex);  // flagged only: they live on while attached to the program
  glDeleteShader(fragment);
  GLint ok = GL_FALSE;
  glGetProgramiv(program_, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    glGetProgramInfoLog(program_, sizeof log, nullptr, log);
    glDeleteProgram(program_);
    throw GraphicsError(std::string("OpenGL: the shader program does not link: ") + log);
  }
  view_projection_location_ = glGetUniformLocation(program_, "view_projection");
}

Renderer::~Renderer() {
  if (program_) glDeleteProgram(program_);
}

Renderer::Renderer(Renderer&& other) noexcept { *this = std::move(other); }

Renderer& Renderer::operator=(Renderer&& other) noexcept {
  if (this != &other) {
    if (program_) glDeleteProgram(program_);
    program_ = std::exchange(other.program_, 0);
    view_projection_location_ = std::exchange(other.view_projection_location_, -1);
  }
  return *this;
}

void Renderer::begin_frame(int width, int height) const {
  glViewport(0, 0, width, height);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  // The chunks' materials are single-sided (glTF's doubleSided false), their triangles counter-clockwise
  // seen from the front: back faces are culled, as the format asks. Drawn, the two faces of a wall of no
  // thickness fought in the depth buffer (and the room side showed the corridor side's light).
  glEnable(GL_CULL_FACE);
  glCullFace(GL_BACK);
  glFrontFace(GL_CCW);
  glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glUseProgram(program_);
}

void Renderer::draw(const GpuMesh& mesh, const Mat4& view_projection) const {
  if (mesh.index_count() == 0) return;
  glUniformMatrix4fv(view_projection_location_, 1, GL_FALSE, view_projection.data());
  glBindVertexArray(mesh.vertex_array());
  glDrawElements(GL_TRIANGLES, mesh.index_count(), GL_UNSIGNED_INT, nullptr);
  glBindVertexArray(0);
}

}  // namespace walkrad
