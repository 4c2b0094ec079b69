// MGF transform arguments → affine maps (mgf_transform.h).
#include "mgf_transform.h"

#include <charconv>
#include <cmath>

namespace walkrad::mgf {

namespace {


// cos and sin of an angle in degrees, exact at multiples of 90° (hand-checked positions stay exact).
void cos_sin(double degrees, double& c, double& s) {
  const double quarter = degrees / 90;
  if (quarter == std::floor(quarter) && std::fabs(quarter) < 1e9) {
    static constexpr double kCos[4] = {1, 0, -1, 0}, kSin[4] = {0, 1, 0, -1};
    const long q = ((long(quarter) % 4) + 4) % 4;
    c = kCos[q];
    s = kSin[q];
    return;
  }
  c = std::cos(degrees * kPi / 180);
  s = std::sin(degrees * kPi / 180);
}

Affine linear(double a, double b, double c, double d, double e, double f, double g, double h, double i) {
  Affine x;
  const double v[3][3] = {{a, b, c}, {d, e, f}, {g, h, i}};
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k) x.m[r][k] = v[r][k];
  return x;
}

}  // namespace

double Affine::det() const {
  return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
         m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

Affine compose(const Affine& a, const Affine& b) {
  Affine r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r.m[i][j] = a.m[i][0] * b.m[0][j] + a.m[i][1] * b.m[1][j] + a.m[i][2] * b.m[2][j];
  r.t = a.point(b.t);
  return r;
}

Affine XfSpec::local(const std::vector<long>& index) const {
  Affine r;
  for (const Group& g : groups) {
    // g applied `times` times, by squaring: large -i counts stay cheap.
    long times = g.array >= 0 ? index[size_t(g.array)] : g.repeat;
    Affine power, base = g.map;
    for (; times > 0; times >>= 1, base = compose(base, base))
      if (times & 1) power = compose(base, power);
    r = compose(power, r);
  }
  return r;
}

double XfSpec::instances() const {
  double n = 1;
  for (long a : arrays) n *= double(a);
  return n;
}

bool parse_number(const std::string& token, double& value) {
  const char* begin = token.data();
  const char* end = begin + token.size();
  if (begin != end && *begin == '+') ++begin;
  if (begin == end || *begin == '+') return false;
  const auto [ptr, ec] = std::from_chars(begin, end, value);
  return ec == std::errc() && ptr == end && std::isfinite(value);
}

bool parse_integer(const std::string& token, long& value) {
  const char* begin = token.data();
  const char* end = begin + token.size();
  if (begin != end && *begin == '+') ++begin;
  if (begin == end || *begin == '+') return false;
  const auto [ptr, ec] = std::from_chars(begin, end, value);
  return ec == std::errc() && ptr == end;
}

bool parse_xf(const std::vector<std::string>& args, size_t first, long max_count, XfSpec& spec, std::string& why) {
  spec = XfSpec{};
  spec.groups.emplace_back();
  auto numbers = [&](size_t i, int n, double* out) {
    if (i + size_t(n) >= args.size()) {
      why = "'" + args[i] + "' needs " + std::to_string(n) + (n == 1 ? " value" : " values");
      return false;
    }
    for (int k = 0; k < n; ++k)
      if (!parse_number(args[i + 1 + size_t(k)], out[k])) {
        why = "'" + args[i] + "': '" + args[i + 1 + size_t(k)] + "' is not a number";
        return false;
      }
    return true;
  };
  for (size_t i = first; i < args.size();) {
    const std::string& a = args[i];
    double v[3];
    Affine op;
    if (a == "-t") {
      if (!numbers(i, 3, v)) return false;
      op.t = {v[0], v[1], v[2]};
      i += 4;
    } else if (a == "-rx" || a == "-ry" || a == "-rz") {
      if (!numbers(i, 1, v)) return false;
      double c, s;
      cos_sin(v[0], c, s);
      if (a == "-rx") op = linear(1, 0, 0, 0, c, -s, 0, s, c);
      else if (a == "-ry") op = linear(c, 0, s, 0, 1, 0, -s, 0, c);
      else op = linear(c, -s, 0, s, c, 0, 0, 0, 1);
      i += 2;
    } else if (a == "-s") {
      if (!numbers(i, 1, v)) return false;
      if (v[0] == 0) {
        why = "'-s 0' collapses the geometry";
        return false;
      }
      op = linear(v[0], 0, 0, 0, v[0], 0, 0, 0, v[0]);
      i += 2;
    } else if (a == "-mx" || a == "-my" || a == "-mz") {
      op = linear(a == "-mx" ? -1 : 1, 0, 0, 0, a == "-my" ? -1 : 1, 0, 0, 0, a == "-mz" ? -1 : 1);
      i += 1;
    } else if (a == "-i" || a == "-a") {
      long n = 0;
      if (i + 1 >= args.size() || !parse_integer(args[i + 1], n)) {
        why = "'" + a + "' needs a whole number";
        return false;
      }
      if (n < (a == "-a" ? 1 : 0) || n > max_count) {
        why = "'" + a + " " + args[i + 1] + "': the count must lie in [" + (a == "-a" ? "1" : "0") + ", " +
              std::to_string(max_count) + "]";
        return false;
      }
      XfSpec::Group g;
      if (a == "-i") g.repeat = n;
      else {
        g.array = int(spec.arrays.size());
        spec.arrays.push_back(n);
      }
      spec.groups.push_back(g);
      i += 2;
      continue;
    } else {
      why = "unknown transform argument '" + a + "'";
      return false;
    }
    spec.groups.back().map = compose(op, spec.groups.back().map);
  }
  return true;
}

}  // namespace walkrad::mgf
