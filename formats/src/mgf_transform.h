// MGF transforms for the MGF reader (mgf_reader.h): the arguments of `xf` and `i` (the MGF spec,
// "Hierarchical Contexts and Transformations") as affine maps.
//
// Arguments act on the geometry in the order given, each in the world frame after the ones before:
// "-t -15 0 35 -ry -20 -t 15 0 -35" rotates about the point (15, 0, -35). Nested contexts compose
// outwards: a vertex inside `xf A` inside `xf B` is mapped by B∘A. "-i N" repeats the arguments
// after it (up to the next -i or -a) N times; "-a N" makes N instances, the arguments after it
// repeated 0, 1, ..., N-1 times, the last array changing fastest (MGF's parser turns -a into -i).
#pragma once

#include <string>
#include <vector>

#include "walkrad/formats/vec3.h"

namespace walkrad::mgf {

// x ↦ m·x + t. MGF allows rotations, uniform scales and mirrors only; det < 0 is a mirror.
struct Affine {
  double m[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  Vec3 t;

  Vec3 point(const Vec3& p) const {
    return Vec3{m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z, m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z,
                m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z} + t;
  }
  double det() const;
};

// a∘b: b first, then a.
Affine compose(const Affine& a, const Affine& b);

// A parsed argument list: groups applied in order, each `repeat` times or, for an array group,
// as many times as its array's current index.
struct XfSpec {
  struct Group {
    Affine map;       // the group's arguments composed in order
    long repeat = 1;  // for -i groups (and the leading group)
    int array = -1;   // index into arrays for -a groups
  };
  std::vector<Group> groups;
  std::vector<long> arrays;  // instance count of each -a

  Affine local(const std::vector<long>& index) const;  // index: one entry per array
  double instances() const;                            // product of the array counts (no overflow)
};

// Parses args[first..]; on a malformed argument returns false with the reason. Counts (-i, -a)
// above max_count are refused.
bool parse_xf(const std::vector<std::string>& args, size_t first, long max_count, XfSpec& spec, std::string& why);

// A number as MGF writes it ("1", "-.5", "2e-3", "+1"): the whole token, finite.
bool parse_number(const std::string& token, double& value);
bool parse_integer(const std::string& token, long& value);

}  // namespace walkrad::mgf
