// IES photometric files (ies.h): ANSI/IES LM-63-2019, "Approved Method: IES Standard File Format
// for the Electronic Transfer of Photometric Data and Related Information", and the earlier
// LM-63-1986, -1991, -1995 and -2002 it supersedes. The reader is strict where a sloppy file would
// light a scene wrongly (counts, angle ranges, signs) and refuses every truncated file: LM-63 ends
// every line with a line end, so a file whose last number touches its end was cut.
#include "walkrad/formats/ies.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>

#include "input_limits.h"
#include "walkrad/formats/error.h"

namespace walkrad {

namespace {

constexpr double kDeg = kPi / 180;

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f'; }

std::string_view trim(std::string_view s) {
  while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
  return s;
}

// A decimal number as LM-63 writes them: [sign] digits [. digits] [e [sign] digits], at least one
// digit before the exponent. Stricter than strtod, which would take "nan", "inf" and hex.
bool decimal_syntax(std::string_view s) {
  size_t i = 0, digits = 0;
  auto run = [&] { size_t n = 0; while (i < s.size() && s[i] >= '0' && s[i] <= '9') ++i, ++n; return n; };
  if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
  digits += run();
  if (i < s.size() && s[i] == '.') ++i, digits += run();
  if (digits == 0) return false;
  if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
    ++i;
    if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
    if (run() == 0) return false;
  }
  return i == s.size();
}

// The text after the TILT= line: numbers separated by white space or commas, wrapping freely.
class Numbers {
 public:
  Numbers(std::string_view text, size_t pos, int line, const std::string& source)
      : text_(text), pos_(pos), line_(line), source_(source) {}

  [[noreturn]] void fail(int line, const std::string& message, ExitCode code = kExitBadInput) const {
    throw InputError(source_, "line " + std::to_string(line), message, code);
  }
  int line() const { return line_; }

  // The next number; `what` and `index` (1-based, 0: none) name it in messages.
  double number(const char* what, long index = 0) {
    while (pos_ < text_.size() && (is_space(text_[pos_]) || text_[pos_] == ',')) {
      if (text_[pos_++] == '\n') ++line_;
    }
    if (pos_ == text_.size()) fail(line_, "truncated: the file ends before " + name(what, index));
    const size_t start = pos_;
    while (pos_ < text_.size() && !is_space(text_[pos_]) && text_[pos_] != ',') ++pos_;
    if (pos_ == text_.size()) fail(line_, "truncated: the file ends inside its last line");
    std::string_view token = text_.substr(start, pos_ - start);
    const std::string shown = "'" + std::string(token.substr(0, 24)) + (token.size() > 24 ? "...'" : "'");
    if (!decimal_syntax(token)) fail(line_, name(what, index) + ": " + shown + " is not a number");
    if (token[0] == '+') token.remove_prefix(1);
    double v = 0;
    const auto r = std::from_chars(token.data(), token.data() + token.size(), v);
    if (r.ec != std::errc() || !std::isfinite(v)) fail(line_, name(what, index) + ": " + shown + " is out of range");
    return v;
  }

  double non_negative(const char* what, long index = 0) {
    const double v = number(what, index);
    if (v < 0) fail(line_, name(what, index) + " is negative (" + format(v) + ")");
    return v;
  }

  // A whole number in [lo, hi]; above hi fails with `above` (kExitLimitReached for a limit).
  int count(const char* what, int lo, int hi, ExitCode above = kExitBadInput) {
    const double v = number(what);
    if (v != std::floor(v)) fail(line_, std::string(what) + " must be a whole number, not " + format(v));
    if (above == kExitBadInput && (v < lo || v > hi))
      fail(line_, std::string(what) + " must be from " + std::to_string(lo) + " to " + std::to_string(hi) + ", not " +
                      format(v));
    if (v < lo) fail(line_, std::string(what) + " must be at least " + std::to_string(lo) + ", not " + format(v));
    if (v > hi) fail(line_, std::string(what) + " (" + format(v) + ") exceeds the limit of " + std::to_string(hi), above);
    return int(v);
  }

  // After the last number: white space up to its line's end, then nothing but white space.
  void expect_end() {
    bool line_ended = false;
    for (; pos_ < text_.size(); ++pos_) {
      if (text_[pos_] == '\n') line_ended = true, ++line_;
      else if (!is_space(text_[pos_])) fail(line_, "unexpected text after the candela values");
    }
    if (!line_ended) fail(line_, "truncated: the file ends inside its last line");
  }

  static std::string format(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.10g", v);
    return buf;
  }

 private:
  static std::string name(const char* what, long index) {
    return index > 0 ? std::string(what) + " " + std::to_string(index) : std::string(what);
  }

  std::string_view text_;
  size_t pos_;
  int line_;
  const std::string& source_;
};

// Reads `n` angles, strictly ascending within [lo, hi]; returns them, with the lines of the first
// and last for the start and end rules.
std::vector<double> angles(Numbers& in, int n, const char* what, double lo, double hi, int& first_line) {
  std::vector<double> a(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    a[size_t(i)] = in.number(what, i + 1);
    if (i == 0) first_line = in.line();
    if (a[size_t(i)] < lo || a[size_t(i)] > hi)
      in.fail(in.line(), std::string(what) + " " + std::to_string(i + 1) + " (" + Numbers::format(a[size_t(i)]) +
                             ") is outside " + Numbers::format(lo) + ".." + Numbers::format(hi));
    if (i > 0 && !(a[size_t(i)] > a[size_t(i) - 1]))
      in.fail(in.line(), std::string(what) + " " + std::to_string(i + 1) + " (" + Numbers::format(a[size_t(i)]) +
                             ") does not ascend");
  }
  return a;
}

// Index i and weight t with x = (1 − t)·a[i] + t·a[i+1] (t = 0 for a single angle); false outside.
bool locate(const std::vector<double>& a, double x, size_t& i, double& t) {
  if (!(x >= a.front() && x <= a.back())) return false;
  if (a.size() == 1) return i = 0, t = 0, true;
  i = size_t(std::upper_bound(a.begin(), a.end() - 1, x) - a.begin()) - 1;
  t = (x - a[i]) / (a[i + 1] - a[i]);
  return true;
}

// ∫ w(x) φ_k(x) dx for the hat function φ_k of each tabulated angle (x in radians), by 5-point
// Gauss-Legendre on each interval: the product of a linear piece and sin or cos, so exact to about
// 1e-7 relative on an interval of 180° and far better on real tables.
std::vector<double> node_weights(const std::vector<double>& deg, double (*w)(double)) {
  static const double x[5] = {0, -0.5384693101056831, 0.5384693101056831, -0.9061798459386640, 0.9061798459386640};
  static const double g[5] = {0.5688888888888889, 0.4786286704993665, 0.4786286704993665, 0.2369268850561891,
                              0.2369268850561891};
  std::vector<double> out(deg.size(), 0.0);
  for (size_t i = 0; i + 1 < deg.size(); ++i) {
    const double a = deg[i] * kDeg, len = (deg[i + 1] - deg[i]) * kDeg;
    for (int k = 0; k < 5; ++k) {
      const double t = (1 + x[k]) / 2, f = w(a + len * t) * g[k] * len / 2;
      out[i] += f * (1 - t);
      out[i + 1] += f * t;
    }
  }
  return out;
}

}  // namespace

IesProfile parse_ies(std::string_view text, const std::string& source) {
  IesProfile p;
  p.source = source;
  p.text = std::string(text);
  p.version = "LM-63-1986";  // no version line: LM-63-1986, whose first lines are free labels
  size_t pos = text.substr(0, 3) == "\xEF\xBB\xBF" ? 3 : 0;  // a UTF-8 byte order mark
  int line = 1;
  std::string_view tilt;
  // The version line, then keyword lines ([TEST] ..., any content) up to TILT=.
  for (;; ++line) {
    const size_t eol = text.find('\n', pos);
    if (eol == std::string_view::npos)
      throw InputError(source, "line " + std::to_string(line),
                       trim(text.substr(pos)).empty() ? "truncated: the file ends before its TILT= line"
                                                      : "truncated: the file ends inside its last line");
    const std::string_view l = trim(text.substr(pos, eol - pos));
    pos = eol + 1;
    if (line == 1) {
      static const std::pair<const char*, const char*> kVersions[] = {
          {"IESNA:LM-63-1995", "LM-63-1995"}, {"IESNA:LM-63-2002", "LM-63-2002"},
          {"IES:LM-63-2019", "LM-63-2019"}, {"IESNA91", "LM-63-1991"}};
      const auto v = std::find_if(std::begin(kVersions), std::end(kVersions), [&](auto& k) { return l == k.first; });
      if (v != std::end(kVersions)) {
        p.version = v->second;
        continue;
      }
    }
    if (l.substr(0, 5) == "TILT=") {
      tilt = trim(l.substr(5));
      break;
    }
  }
  Numbers in(text, pos, line + 1, source);
  if (tilt == "INCLUDE") {
    p.lamp_geometry = in.count("the lamp-to-luminaire geometry", 1, 3);
    const int n = in.count("the number of tilt angles", 1, kMaxIesAngles, kExitLimitReached);
    int first = 0;
    p.tilt_angles = angles(in, n, "tilt angle", -360, 360, first);
    p.tilt_factors.resize(size_t(n));
    for (int i = 0; i < n; ++i) p.tilt_factors[size_t(i)] = in.non_negative("tilt factor", i + 1);
  } else if (tilt != "NONE") {
    in.fail(line, tilt.empty() ? "TILT= names nothing (NONE, INCLUDE or a file)"
                               : "TILT=<file> is not supported: include the data (TILT=INCLUDE) or use TILT=NONE",
            tilt.empty() ? kExitBadInput : kExitMissingFeature);
  }

  p.lamps = in.count("the number of lamps", 1, 1'000'000);
  p.lumens_per_lamp = in.number("the lumens per lamp");
  if (p.lumens_per_lamp < 0 && p.lumens_per_lamp != -1)
    in.fail(in.line(), "the lumens per lamp must be -1 (absolute photometry) or at least 0");
  const double multiplier = in.non_negative("the candela multiplier");
  const int nv = in.count("the number of vertical angles", 1, kMaxIesAngles, kExitLimitReached);
  const int nh = in.count("the number of horizontal angles", 1, kMaxIesAngles, kExitLimitReached);
  if (long(nv) * nh > kMaxIesCandela)
    in.fail(in.line(), std::to_string(long(nv) * nh) + " candela values exceed the limit of " +
                           std::to_string(kMaxIesCandela), kExitLimitReached);
  p.photometry = IesProfile::Photometry(in.count("the photometric type", 1, 3));
  in.count("the units type", 1, 2);
  for (const char* what : {"the width", "the length", "the height"}) in.number(what);
  const double ballast = in.non_negative("the ballast factor");
  // LM-63-1995 and earlier: the ballast-lamp photometric factor; 2002 and 2019: "future use" (1).
  const double ballast_lamp = in.non_negative("the ballast-lamp photometric factor");
  p.input_watts = in.non_negative("the input watts");

  // Angle rules (LM-63-2002 section 5): type C vertical 0..90, 0..180 or 90..180; horizontal 0 (a
  // rotationally symmetric luminaire), 0..90, 0..180 or 0..360, or 90..270 (LM-63-1995, accepted
  // from any version as readers do); types A and B: −90..90, or 0..90 for a symmetric half.
  const bool c = p.photometry == IesProfile::Photometry::C;
  int v_line = 0, h_line = 0;
  p.vertical = angles(in, nv, "vertical angle", c ? 0 : -90, c ? 180 : 90, v_line);
  const int v_end_line = in.line();
  p.horizontal = angles(in, nh, "horizontal angle", c ? 0 : -90, c ? 360 : 90, h_line);
  const int h_end_line = in.line();
  const double v0 = p.vertical.front(), v1 = p.vertical.back(), h0 = p.horizontal.front(), h1 = p.horizontal.back();
  if (c ? v0 != 0 && v0 != 90 : v0 != 0 && v0 != -90)
    in.fail(v_line, "the first vertical angle must be " + std::string(c ? "0 or 90" : "-90 or 0"));
  if (c ? v1 != 90 && v1 != 180 : v1 != 90)
    in.fail(v_end_line, "the last vertical angle must be " + std::string(c ? "90 or 180" : "90"));
  if (c ? h0 != 0 && h0 != 90 : h0 != 0 && h0 != -90)
    in.fail(h_line, "the first horizontal angle must be " + std::string(c ? "0 (or 90 for 90..270)" : "-90 or 0"));
  if (c ? (h0 == 90 ? h1 != 270 : h1 != 0 && h1 != 90 && h1 != 180 && h1 != 360) : h1 != 90)
    in.fail(h_end_line, "the last horizontal angle must be " +
                            std::string(!c ? "90" : h0 == 90 ? "270 (starting at 90)" : "0, 90, 180 or 360"));

  const double scale = multiplier * ballast * (p.version < "LM-63-2002" ? ballast_lamp : 1.0);
  p.candela.resize(size_t(nv) * size_t(nh));
  for (size_t i = 0; i < p.candela.size(); ++i) {
    p.candela[i] = in.non_negative("candela value", long(i) + 1) * scale;
    if (!std::isfinite(p.candela[i]))
      in.fail(in.line(), "candela value " + std::to_string(i + 1) + " times the multipliers is out of range");
  }
  in.expect_end();
  return p;
}

IesProfile read_ies(const std::string& path) {
  const std::vector<unsigned char> bytes = input_limits::read_file(path, kMaxIesBytes, "IES file");
  return parse_ies(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), path);
}

double IesProfile::candela_at(double v, double h) const {
  if (candela.empty() || !std::isfinite(v) || !std::isfinite(h)) return 0;
  const double h0 = horizontal.front(), h1 = horizontal.back();
  if (photometry == Photometry::C) {
    // LM-63's symmetries: map C into the tabulated set.
    h = std::fmod(h, 360.0);
    if (h < 0) h += 360;
    if (horizontal.size() == 1) h = h0;                          // rotationally symmetric
    else if (h0 == 90) h = h < 90 || h > 270 ? std::fmod(540 - h, 360.0) : h;  // about the 90–270 plane
    else if (h1 == 90) h = h <= 90 ? h : h <= 180 ? 180 - h : h <= 270 ? h - 180 : 360 - h;  // quadrants
    else if (h1 == 180 && h > 180) h = 360 - h;                 // about the 0–180 plane
  } else {
    if (h0 == 0) h = std::fabs(h);  // a symmetric half
    if (vertical.front() == 0) v = std::fabs(v);
  }
  size_t iv, ih;
  double tv, th;
  if (!locate(vertical, v, iv, tv) || !locate(horizontal, h, ih, th)) return 0;
  const size_t n = vertical.size(), iv1 = std::min(iv + 1, n - 1), ih1 = std::min(ih + 1, horizontal.size() - 1);
  const double lo = (1 - tv) * candela[ih * n + iv] + tv * candela[ih * n + iv1];
  const double hi = (1 - tv) * candela[ih1 * n + iv] + tv * candela[ih1 * n + iv1];
  return (1 - th) * lo + th * hi;
}

double IesProfile::intensity(const Vec3& d) const {
  // The inverses of ies.h's formulas; at a pole the other angle is arbitrary and taken as 0.
  switch (photometry) {
    case Photometry::C: {
      const double rho = std::hypot(d.x, d.y);
      double c = rho > 0 ? std::atan2(d.y, d.x) / kDeg : 0;
      if (c < 0) c += 360;
      return candela_at(std::atan2(rho, -d.z) / kDeg, c >= 360 ? c - 360 : c);
    }
    case Photometry::B: {
      const double r = std::hypot(d.x, d.z);
      return candela_at(r > 0 ? std::atan2(d.x, -d.z) / kDeg : 0, std::atan2(-d.y, r) / kDeg);
    }
    case Photometry::A: {
      const double r = std::hypot(d.y, d.z);
      return candela_at(std::atan2(d.x, r) / kDeg, r > 0 ? std::atan2(-d.y, -d.z) / kDeg : 0);
    }
  }
  return 0;
}

double IesProfile::tilt_factor(double tilt_deg) const {
  if (tilt_angles.empty()) return 1;
  if (!(tilt_deg > tilt_angles.front())) return tilt_factors.front();
  if (tilt_deg >= tilt_angles.back()) return tilt_factors.back();
  size_t i;
  double t;
  locate(tilt_angles, tilt_deg, i, t);
  return (1 - t) * tilt_factors[i] + t * tilt_factors[i + 1];
}

double IesProfile::tilt_factor(const Vec3& aim, const Vec3& down) const {
  return tilt_factor(std::acos(std::clamp(dot(normalize(aim), normalize(down)), -1.0, 1.0)) / kDeg);
}

double IesProfile::flux() const {
  // Exact for the bilinear interpolation: in each cell the integrand is bilinear in the angles times
  // the solid angle's density, which depends on one angle only (sin γ for type C; cos of the
  // latitude, B's H or A's V, for types A and B). So flux = Σ candela · Wv · Wh over the nodes, with
  // Wv, Wh the hat functions' weighted integrals, times the copies the symmetry implies.
  if (candela.empty()) return 0;
  double (*const one)(double) = [](double) { return 1.0; };
  double (*const sine)(double) = [](double x) { return std::sin(x); };
  double (*const cosine)(double) = [](double x) { return std::cos(x); };
  const bool c = photometry == Photometry::C, b = photometry == Photometry::B;
  const std::vector<double> wv = node_weights(vertical, c ? sine : b ? one : cosine);
  std::vector<double> wh = node_weights(horizontal, b ? cosine : one);
  double copies = 1;
  if (c) {
    const double h1 = horizontal.back();
    if (horizontal.size() == 1) wh[0] = 2 * kPi;
    else copies = horizontal.front() == 90 ? 2 : h1 == 90 ? 4 : h1 == 180 ? 2 : 1;
  } else {
    copies = (horizontal.front() == 0 ? 2 : 1) * (vertical.front() == 0 ? 2 : 1);
  }
  double sum = 0;
  for (size_t h = 0; h < horizontal.size(); ++h)
    for (size_t v = 0; v < vertical.size(); ++v) sum += candela[h * vertical.size() + v] * (wv[v] * wh[h]);
  return copies * sum;
}

double IesProfile::max_candela() const {
  return candela.empty() ? 0 : *std::max_element(candela.begin(), candela.end());
}

}  // namespace walkrad
