// Small generated scenes with exact answers, shared by the pipeline's tests.
#pragma once

#include <algorithm>
#include <cmath>
#include <utility>

#include "walkrad/formats/scene.h"

namespace walkrad::test {

inline Polygon quad(Vec3 a, Vec3 b, Vec3 c, Vec3 d, uint32_t material = 0) {
  Polygon p;
  p.v = {a, b, c, d};
  p.count = 4;
  p.material = material;
  return p;
}

// The axis-aligned rectangle coordinate[axis] = c, spanning [a0, a1] × [b0, b1] on the next two axes
// in cyclic order (x: y, z; y: z, x; z: x, y), facing +axis (facing > 0) or −axis. Rooms and corridors
// with walls of no thickness are made of these, one quad a side of each wall.
inline Polygon rect(int axis, double c, double a0, double a1, double b0, double b1, int facing, uint32_t material = 0) {
  const int i = (axis + 1) % 3, j = (axis + 2) % 3;
  auto at = [&](double a, double b) {
    Vec3 p;
    p[axis] = c;
    p[i] = a;
    p[j] = b;
    return p;
  };
  Polygon q = quad(at(a0, b0), at(a1, b0), at(a1, b1), at(a0, b1), material);
  if (facing < 0) std::swap(q.v[1], q.v[3]);
  return q;
}

// A closed box [0,s]³ whose six faces face inwards, all of one material (reflectance rho,
// emission e): the furnace, where B = E / (1 − ρ) exactly.
inline Scene closed_box(double s, Vec3 rho, Vec3 e) {
  Scene scene;
  scene.source = "closed box";
  scene.materials.push_back({"furnace", rho, e});
  const Vec3 o(0, 0, 0), x(s, 0, 0), y(0, s, 0), z(0, 0, s);
  scene.polygons = {quad(o, x, x + z, z), quad(y, y + z, y + x + z, y + x), quad(o, y, y + x, x),
                    quad(z, z + x, z + x + y, z + y), quad(o, z, z + y, y), quad(x, x + y, x + y + z, x + z)};
  const Vec3 centre = (x + y + z) * 0.5;
  for (Polygon& p : scene.polygons)  // face inwards
    if (dot(polygon_normal(p), centre - polygon_centroid(p)) < 0) std::swap(p.v[1], p.v[3]);
  return scene;
}

// A closed box of reflectance rho, 1 m square and `length` long in z, lit by its end at z = 0
// (emission 1, reflectance 0.5): light crosses many elements from one end to the other.
inline Scene corridor_lit_at_one_end(double length, Vec3 rho) {
  Scene box = closed_box(1.0, rho, {0, 0, 0});
  for (Polygon& p : box.polygons)
    for (Vec3& v : p.v) v.z *= length;
  box.materials.push_back({"lamp", {0.5, 0.5, 0.5}, {1, 1, 1}});
  for (Polygon& p : box.polygons)
    if (std::fabs(polygon_normal(p).z) > 0.5 && polygon_centroid(p).z < 0.5) p.material = 1;
  return box;
}

}  // namespace walkrad::test

namespace walkrad::test {

// A closed cube of side `side` centred at c, rotated by the orthonormal frame (u, v, w), faces
// outwards, sharing its 8 corners between faces (one connected object).
inline void add_cube(Scene& scene, Vec3 c, double side, Vec3 u, Vec3 v, Vec3 w, uint32_t material = 0) {
  const double h = side / 2;
  auto corner = [&](int i) { return c + u * ((i & 1) ? h : -h) + v * ((i & 2) ? h : -h) + w * ((i & 4) ? h : -h); };
  const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces) {
    Polygon p = quad(corner(f[0]), corner(f[1]), corner(f[2]), corner(f[3]), material);
    if (dot(polygon_normal(p), polygon_centroid(p) - c) < 0) std::swap(p.v[1], p.v[3]);  // outwards
    scene.polygons.push_back(p);
  }
}

inline void add_cube(Scene& scene, Vec3 c, double side, uint32_t material = 0) {
  add_cube(scene, c, side, Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), material);
}

// A 6 × 6 × 3 m room, z up, walls and ceiling of material 1 facing in, its floor of material 0 facing
// up, and one opening: a 2 × 1.2 m window in the wall x = 6, y ∈ [2, 4], z ∈ [1, 2.2] (window_opening()).
inline Scene window_room(Vec3 floor_rho = {0.5, 0.5, 0.5}, Vec3 wall_rho = {0, 0, 0}) {
  Scene s;
  s.up = {0, 0, 1};
  s.materials.push_back({"floor", floor_rho, {}});
  s.materials.push_back({"wall", wall_rho, {}});
  s.polygons.push_back(rect(2, 0, 0, 6, 0, 6, +1, 0));  // floor
  s.polygons.push_back(rect(2, 3, 0, 6, 0, 6, -1, 1));  // ceiling
  s.polygons.push_back(rect(0, 0, 0, 6, 0, 3, +1, 1));  // x = 0
  s.polygons.push_back(rect(1, 0, 0, 3, 0, 6, +1, 1));  // y = 0 (spans z, x)
  s.polygons.push_back(rect(1, 6, 0, 3, 0, 6, -1, 1));  // y = 6
  s.polygons.push_back(rect(0, 6, 0, 6, 0, 1, -1, 1));  // x = 6 around the window
  s.polygons.push_back(rect(0, 6, 0, 6, 2.2, 3, -1, 1));
  s.polygons.push_back(rect(0, 6, 0, 2, 1, 2.2, -1, 1));
  s.polygons.push_back(rect(0, 6, 4, 6, 1, 2.2, -1, 1));
  return s;
}
inline Polygon window_opening() { return rect(0, 6, 2, 4, 1, 2.2, -1); }

// What a bake's floor vertex at x may show of the exact value f: a vertex shows the solution read a
// little way into each face around it (surface_mesher.cpp, kInward: 5% of the way to the face's centre),
// so the range of f over x and 8 points around it, 2% of x's distance to the room's centre away.
template <class F>
std::pair<double, double> floor_range_near(const Vec3& x, F f) {
  const double radius = 0.02 * length(Vec3(3, 3, 0) - x);
  double lo = f(x), hi = lo;
  for (int k = 0; k < 8; ++k) {
    const Vec3 y = x + Vec3(std::cos(k * 3.141592653589793 / 4), std::sin(k * 3.141592653589793 / 4), 0) * radius;
    if (y.x < 0 || y.x > 6 || y.y < 0 || y.y > 6) continue;
    const double v = f(y);
    lo = std::min(lo, v), hi = std::max(hi, v);
  }
  return {lo, hi};
}

}  // namespace walkrad::test
