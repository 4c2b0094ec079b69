// Mat4 (mat4.h): the two matrices of a pinhole camera, following the gluLookAt / gluPerspective
// definitions so that the results can be checked against any OpenGL text.
#include "walkrad/runtime/mat4.h"

#include <cmath>

#include "walkrad/formats/vec3.h"

namespace walkrad {

Mat4 Mat4::identity() {
  Mat4 r;
  for (int i = 0; i < 4; ++i) r.at(i, i) = 1.0f;
  return r;
}

Mat4 Mat4::operator*(const Mat4& o) const {
  Mat4 r;
  for (int row = 0; row < 4; ++row)
    for (int col = 0; col < 4; ++col) {
      float s = 0.0f;
      for (int k = 0; k < 4; ++k) s += at(row, k) * o.at(k, col);
      r.at(row, col) = s;
    }
  return r;
}

std::array<float, 4> Mat4::transform(float x, float y, float z, float w) const {
  const float v[4] = {x, y, z, w};
  std::array<float, 4> r{};
  for (int row = 0; row < 4; ++row)
    for (int k = 0; k < 4; ++k) r[row] += at(row, k) * v[k];
  return r;
}

Mat4 view_matrix(const Vec3& eye, const Vec3& forward, const Vec3& up) {
  // The rows are the camera's axes in world space: right (+x), up (+y), backward (+z).
  const Vec3 right = normalize(cross(forward, up));
  const Vec3 true_up = cross(right, forward);
  const Vec3 axes[3] = {right, true_up, -forward};
  Mat4 r = Mat4::identity();
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) r.at(row, col) = float(axes[row][col]);
    // The translation is computed in double: eye positions far from the origin lose digits in float.
    r.at(row, 3) = float(-dot(axes[row], eye));
  }
  return r;
}

Mat4 perspective(double yfov, double aspect, double near, double far) {
  const double f = 1.0 / std::tan(yfov / 2.0);
  Mat4 r;
  r.at(0, 0) = float(f / aspect);
  r.at(1, 1) = float(f);
  r.at(2, 2) = float((far + near) / (near - far));
  r.at(2, 3) = float(2.0 * far * near / (near - far));
  r.at(3, 2) = -1.0f;
  return r;
}

}  // namespace walkrad
