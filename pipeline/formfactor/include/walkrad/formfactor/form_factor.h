// Unoccluded form factors (../shared/design/algorithms.md §3; Cohen & Wallace 1993, ch. 4).
//
// point_to_polygon: Lambert's contour formula, exact for a differential area and a polygon
//   F_dA→P = (1/2π) Σ_k β_k n·(R_k × R_{k+1}) / |R_k × R_{k+1}|,
//   after clipping the polygon to the receiver's upper hemisphere (the formula assumes the polygon
//   lies entirely above the receiver's tangent plane). Independent of the polygon's winding.
// element_to_element: (1/A_i) ∫_{A_i} F_dA→A_j dA by Gauss-Legendre quadrature over the receiver,
//   its order chosen from the distance/size ratio (the kernel varies fastest where elements touch).
#pragma once

#include <array>
#include <vector>

#include "walkrad/formats/scene.h"

namespace walkrad {

// Form factor from a differential area at p with unit normal n to the polygon. A point on the
// polygon's plane, or a polygon entirely below the point's horizon, gets 0 (never NaN).
double point_to_polygon(const Vec3& p, const Vec3& n, const Polygon& poly);

// A polygon prepared for the contour formula at many points (a receiver's quadrature points): its
// area normal and length, computed once instead of at every point. The same result to the bit.
struct ContourSource {
  explicit ContourSource(const Polygon& p);
  const Polygon& poly;
  Vec3 area_normal;
  double norm, root_norm;  // |area_normal| and its square root
};
double point_to_polygon(const Vec3& p, const Vec3& n, const ContourSource& source);

// The angle between two vectors a and b from s = |a × b| >= 0 and c = a·b: atan2(s, c) in [0, π], by the
// rational approximation of Cephes' atan (S. L. Moshier, "Methods and Programs for Mathematical
// Functions", 1989) after reduction to |t| <= 0.66, within 2.2e-16 relative of atan2, one division.
// libm's atan2 rounds correctly and saves and restores the rounding mode on every call: it would be a
// sixth of a bake's time (the contour formula runs millions of times at the gathered vertices).
double vector_angle(double s, double c);

// Clips a polygon of at most 4 corners to the half-space dot(x - p, n) >= 0: its corners (possibly
// none), on the stack (the contour formula runs millions of times in a bake). Each edge keeps at most
// its start and one crossing: 8 corners at most, 5 for a convex polygon.
struct ClippedPolygon {
  std::array<Vec3, 8> v;
  int count = 0;
};
ClippedPolygon clip_to_hemisphere(const Vec3& p, const Vec3& n, const Vec3* v, int count);

// A quadrature point on a receiver: position and weight (weights sum to the receiver's area).
struct QuadraturePoint {
  Vec3 position;
  double weight;
};

// order×order Gauss-Legendre points over a triangle or quad (a triangle as a collapsed quad:
// the Duffy transform, so every point lies strictly inside). order in [1, 8]. On the stack: a bake
// asks for them at every link's receiver quadrant and every exactly integrated polygon pair (a
// 32-room level: tens of millions of calls), where a heap list per call cost more than the points.
// Plain doubles, not QuadraturePoints, so that the 64 slots are not zeroed on every call.
struct QuadraturePoints {
  struct Raw {
    double x, y, z, weight;
  };
  struct Iterator {
    const Raw* at;
    QuadraturePoint operator*() const { return {{at->x, at->y, at->z}, at->weight}; }
    Iterator& operator++() { ++at; return *this; }
    bool operator!=(const Iterator& o) const { return at != o.at; }
  };
  Raw point[64];
  int count = 0;
  Iterator begin() const { return {point}; }
  Iterator end() const { return {point + count}; }
};
QuadraturePoints quadrature_points(const Polygon& receiver, int order);

// The quadrature order for a receiver of size `size` seeing a source at distance `distance`
// (centroid to centroid): 2 when far, up to 8 when touching.
int quadrature_order(double distance, double receiver_size, double source_size);

// Unoccluded element-to-element form factor F_ij (receiver i, source j): the fraction of the
// energy leaving i that arrives at j. Only j's front side is seen.
double element_to_element(const Polygon& receiver, const Polygon& source);

// The same, to the bit, for one polygon met against many (a cluster's exact unoccluded form factor,
// pair by pair): each end's normal, area, centroid and contour computed once, and the receiver's
// quadrature points once per order (ReceiverPoints) instead of once per pair.
struct ElementEnd {
  explicit ElementEnd(const Polygon& p);
  const Polygon& poly;
  Vec3 normal, centroid;
  double area, size;      // size: √area, as quadrature_order takes it
  ContourSource contour;  // read where this end is the source
};
class ReceiverPoints {
 public:
  explicit ReceiverPoints(const Polygon& receiver) : receiver_(receiver) {}
  const QuadraturePoints& of_order(int order);

 private:
  const Polygon& receiver_;
  QuadraturePoints points_[8];
  bool have_[8] = {};
};
double element_to_element(const ElementEnd& receiver, const ElementEnd& source, ReceiverPoints& points);

}  // namespace walkrad
