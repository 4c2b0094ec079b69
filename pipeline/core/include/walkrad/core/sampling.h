// Deterministic random numbers: each link (receiver, source) draws from its own stream, seeded by
// its indices, so results never depend on which thread computed what (architecture.md, Principles).
#pragma once

#include <cstdint>

#include "walkrad/formats/scene.h"

namespace walkrad {

// SplitMix64 (Steele, Lea & Flood 2014): tiny, fast, statistically sound for sampling.
class Rng {
 public:
  explicit Rng(uint64_t seed) : state_(seed) {}
  Rng(uint64_t a, uint64_t b) : state_(a * 0x9E3779B97F4A7C15ull ^ (b + 0x632BE59BD9B4E019ull)) { next(); }
  uint64_t next() {
    uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double uniform() { return double(next() >> 11) * 0x1.0p-53; }  // [0, 1)

 private:
  uint64_t state_;
};

// t and b with unit n a right-handed orthonormal frame (t from the x or y axis).
void frame(const Vec3& n, Vec3& t, Vec3& b);

// A point of the polygon from (u, v) in [0,1)²: uniform by area for a triangle (square-root
// warp), bilinear for a quad (uniform by area for a parallelogram).
Vec3 sample_polygon(const Polygon& p, double u, double v);

// A direction about unit n with pdf cos θ / π (Malley's method: a point of the unit disc, lifted), from
// two draws of rng (r² then φ), in a frame made from n and the x or y axis.
Vec3 cosine_direction(const Vec3& n, Rng& rng);

// Uniform over the cap of half-angle `cone` about unit axis (the whole sphere for cone = π), from two
// draws of rng (the height then φ).
Vec3 cone_direction(const Vec3& axis, double cone, Rng& rng);

// The same map from given (u, v) in [0,1)²: u the share of the cap's solid angle within the direction's
// polar angle, v its azimuth's share of the turn (stratified patterns: the sun's rays).
Vec3 cap_direction(const Vec3& axis, double cone, double u, double v);

}  // namespace walkrad
