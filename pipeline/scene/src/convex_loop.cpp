#include "walkrad/scene/convex_loop.h"

#include <algorithm>
#include <cmath>

namespace walkrad {

double loop_area(const Loop& l) {
  Vec3 n;
  for (size_t k = 0; k < l.size(); ++k) n += cross(l[k], l[(k + 1) % l.size()]);
  return 0.5 * length(n);
}

void split_loop(const Loop& l, const Vec3& n, double d, Loop& below, Loop& above, double tol) {
  below.clear();
  above.clear();
  auto side = [&](const Vec3& x) {
    const double s = dot(x, n) - d;
    return std::fabs(s) <= tol ? 0.0 : s;
  };
  for (size_t k = 0; k < l.size(); ++k) {
    const Vec3& a = l[k];
    const Vec3& b = l[(k + 1) % l.size()];
    const double da = side(a), db = side(b);
    if (da <= 0) below.push_back(a);
    if (da >= 0) above.push_back(a);
    if ((da < 0 && db > 0) || (da > 0 && db < 0)) {
      const Vec3 x = a + (b - a) * (da / (da - db));
      below.push_back(x);
      above.push_back(x);
    }
  }
}

bool clip_segment(const Vec3* corners, size_t n, const Vec3& normal, const Vec3& a, const Vec3& b, double& t0, double& t1) {
  t0 = 0;
  t1 = 1;
  for (size_t e = 0; e < n; ++e) {
    const Vec3 inward = cross(normal, corners[(e + 1) % n] - corners[e]);
    const double s0 = dot(a - corners[e], inward), s1 = dot(b - corners[e], inward);
    if (s0 < 0 && s1 < 0) return false;
    if (s0 < 0) t0 = std::max(t0, s0 / (s0 - s1));
    if (s1 < 0) t1 = std::min(t1, s0 / (s0 - s1));
    if (t0 >= t1) return false;
  }
  return true;
}

void emit_loop(const Loop& l, const Polygon& like, std::vector<Polygon>& out) {
  for (size_t k = 1; k + 1 < l.size(); k += 2) {
    Polygon p = like;
    if (k + 2 < l.size()) {
      p.count = 4;
      p.v = {l[0], l[k], l[k + 1], l[k + 2]};
    } else {
      p.count = 3;
      p.v = {l[0], l[k], l[k + 1], Vec3{}};
    }
    if (polygon_area(p) > 0) out.push_back(p);
  }
}

}  // namespace walkrad
