// Mat4: the small float 4×4 matrix the renderer hands to its shader. Column-major, like OpenGL
// expects, so data() uploads as is (glUniformMatrix4fv with transpose = GL_FALSE). Only what the
// camera needs: product, a view matrix from a viewpoint's frame, and a perspective projection.
#pragma once

#include <array>

namespace walkrad {

struct Vec3;

struct Mat4 {
  std::array<float, 16> m{};  // m[column * 4 + row]

  static Mat4 identity();
  float& at(int row, int column) { return m[column * 4 + row]; }
  float at(int row, int column) const { return m[column * 4 + row]; }
  const float* data() const { return m.data(); }

  Mat4 operator*(const Mat4& o) const;
  // The homogeneous product M·(x, y, z, w).
  std::array<float, 4> transform(float x, float y, float z, float w) const;
};

// World → eye space, right-handed: the camera at `eye` looks along unit `forward` (eye −z) with
// unit `up` (eye +y) orthogonal to it.
Mat4 view_matrix(const Vec3& eye, const Vec3& forward, const Vec3& up);

// Eye → clip space, OpenGL convention: eye −z in [near, far] maps to NDC z in [−1, 1].
Mat4 perspective(double yfov, double aspect, double near, double far);

}  // namespace walkrad
