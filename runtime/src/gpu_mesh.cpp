// GpuMesh (gpu_mesh.h): one buffer per attribute, as the ChunkMesh stores them, so upload is a
// plain copy. Attribute locations match the renderer's shader (renderer.cpp).
#include "walkrad/runtime/gpu_mesh.h"

#include <climits>
#include <stdexcept>
#include <utility>

#include <epoxy/gl.h>

namespace walkrad {

namespace {

constexpr GLuint kPositionLocation = 0;
constexpr GLuint kColorLocation = 1;

GLuint upload_vec3(GLuint location, const std::vector<float>& values) {
  GLuint buffer = 0;
  glGenBuffers(1, &buffer);
  glBindBuffer(GL_ARRAY_BUFFER, buffer);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(values.size() * sizeof(float)), values.data(), GL_STATIC_DRAW);
  glEnableVertexAttribArray(location);
  glVertexAttribPointer(location, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
  return buffer;
}

}  // namespace

GpuMesh::GpuMesh(const ChunkMesh& mesh) {
  if (mesh.colors.size() != mesh.positions.size())
    throw std::invalid_argument("GpuMesh: a chunk needs one RGB colour per vertex");
  if (mesh.indices.size() > size_t(INT_MAX)) throw std::invalid_argument("GpuMesh: too many indices for one draw");
  glGenVertexArrays(1, &vertex_array_);
  glBindVertexArray(vertex_array_);
  positions_ = upload_vec3(kPositionLocation, mesh.positions);
  colors_ = upload_vec3(kColorLocation, mesh.colors);
  glGenBuffers(1, &indices_);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, indices_);  // recorded in the vertex array
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(mesh.indices.size() * sizeof(uint32_t)), mesh.indices.data(),
               GL_STATIC_DRAW);
  glBindVertexArray(0);
  index_count_ = int(mesh.indices.size());
}

GpuMesh::~GpuMesh() { release(); }

GpuMesh::GpuMesh(GpuMesh&& other) noexcept { *this = std::move(other); }

GpuMesh& GpuMesh::operator=(GpuMesh&& other) noexcept {
  if (this != &other) {
    release();
    vertex_array_ = std::exchange(other.vertex_array_, 0);
    positions_ = std::exchange(other.positions_, 0);
    colors_ = std::exchange(other.colors_, 0);
    indices_ = std::exchange(other.indices_, 0);
    index_count_ = std::exchange(other.index_count_, 0);
  }
  return *this;
}

void GpuMesh::release() {
  // A moved-from mesh owns nothing: it makes no GL call, so it may die without a current context.
  if (!vertex_array_) return;
  glDeleteVertexArrays(1, &vertex_array_);
  const GLuint buffers[] = {positions_, colors_, indices_};
  glDeleteBuffers(3, buffers);
  vertex_array_ = positions_ = colors_ = indices_ = 0;
}

}  // namespace walkrad
