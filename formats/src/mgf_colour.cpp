// MGF colours → linear sRGB (mgf_colour.h). CIE 1931 2° colour matching functions from CIE 015:2018
// (ISO/CIE 11664-1), tabulated every 5 nm; sRGB from IEC 61966-2-1 (Rec. 709 primaries, D65).
#include "mgf_colour.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace walkrad::mgf {

namespace {

constexpr double kFirstNm = 380, kStepNm = 5;
constexpr int kSamples = 81;  // 380..780 nm

// x̄(λ), ȳ(λ), z̄(λ) of the CIE 1931 standard observer.
constexpr double kCmf[kSamples][3] = {
    {0.001368, 0.000039, 0.006450}, {0.002236, 0.000064, 0.010550}, {0.004243, 0.000120, 0.020050},  // 380 nm
    {0.007650, 0.000217, 0.036210}, {0.014310, 0.000396, 0.067850}, {0.023190, 0.000640, 0.110200},  // 395 nm
    {0.043510, 0.001210, 0.207400}, {0.077630, 0.002180, 0.371300}, {0.134380, 0.004000, 0.645600},  // 410 nm
    {0.214770, 0.007300, 1.039050}, {0.283900, 0.011600, 1.385600}, {0.328500, 0.016840, 1.622960},  // 425 nm
    {0.348280, 0.023000, 1.747060}, {0.348060, 0.029800, 1.782600}, {0.336200, 0.038000, 1.772110},  // 440 nm
    {0.318700, 0.048000, 1.744100}, {0.290800, 0.060000, 1.669200}, {0.251100, 0.073900, 1.528100},  // 455 nm
    {0.195360, 0.090980, 1.287640}, {0.142100, 0.112600, 1.041900}, {0.095640, 0.139020, 0.812950},  // 470 nm
    {0.057950, 0.169300, 0.616200}, {0.032010, 0.208020, 0.465180}, {0.014700, 0.258600, 0.353300},  // 485 nm
    {0.004900, 0.323000, 0.272000}, {0.002400, 0.407300, 0.212300}, {0.009300, 0.503000, 0.158200},  // 500 nm
    {0.029100, 0.608200, 0.111700}, {0.063270, 0.710000, 0.078250}, {0.109600, 0.793200, 0.057250},  // 515 nm
    {0.165500, 0.862000, 0.042160}, {0.225750, 0.914850, 0.029840}, {0.290400, 0.954000, 0.020300},  // 530 nm
    {0.359700, 0.980300, 0.013400}, {0.433450, 0.994950, 0.008750}, {0.512050, 1.000000, 0.005750},  // 545 nm
    {0.594500, 0.995000, 0.003900}, {0.678400, 0.978600, 0.002750}, {0.762100, 0.952000, 0.002100},  // 560 nm
    {0.842500, 0.915400, 0.001800}, {0.916300, 0.870000, 0.001650}, {0.978600, 0.816300, 0.001400},  // 575 nm
    {1.026300, 0.757000, 0.001100}, {1.056700, 0.694900, 0.001000}, {1.062200, 0.631000, 0.000800},  // 590 nm
    {1.045600, 0.566800, 0.000600}, {1.002600, 0.503000, 0.000340}, {0.938400, 0.441200, 0.000240},  // 605 nm
    {0.854450, 0.381000, 0.000190}, {0.751400, 0.321000, 0.000100}, {0.642400, 0.265000, 0.000050},  // 620 nm
    {0.541900, 0.217000, 0.000030}, {0.447900, 0.175000, 0.000020}, {0.360800, 0.138200, 0.000010},  // 635 nm
    {0.283500, 0.107000, 0.000000}, {0.218700, 0.081600, 0.000000}, {0.164900, 0.061000, 0.000000},  // 650 nm
    {0.121200, 0.044580, 0.000000}, {0.087400, 0.032000, 0.000000}, {0.063600, 0.023200, 0.000000},  // 665 nm
    {0.046770, 0.017000, 0.000000}, {0.032900, 0.011920, 0.000000}, {0.022700, 0.008210, 0.000000},  // 680 nm
    {0.015840, 0.005723, 0.000000}, {0.011359, 0.004102, 0.000000}, {0.008111, 0.002929, 0.000000},  // 695 nm
    {0.005790, 0.002091, 0.000000}, {0.004109, 0.001484, 0.000000}, {0.002899, 0.001047, 0.000000},  // 710 nm
    {0.002049, 0.000740, 0.000000}, {0.001440, 0.000520, 0.000000}, {0.001000, 0.000361, 0.000000},  // 725 nm
    {0.000690, 0.000249, 0.000000}, {0.000476, 0.000172, 0.000000}, {0.000332, 0.000120, 0.000000},  // 740 nm
    {0.000235, 0.000085, 0.000000}, {0.000166, 0.000060, 0.000000}, {0.000117, 0.000042, 0.000000},  // 755 nm
    {0.000083, 0.000030, 0.000000}, {0.000059, 0.000021, 0.000000}, {0.000042, 0.000015, 0.000000},  // 770 nm
};

using Mat3 = std::array<std::array<double, 3>, 3>;

Vec3 apply(const Mat3& m, const Vec3& v) {
  return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z, m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
          m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
}

Mat3 inverse(const Mat3& m) {
  const Vec3 a{m[0][0], m[1][0], m[2][0]}, b{m[0][1], m[1][1], m[2][1]}, c{m[0][2], m[1][2], m[2][2]};
  const Vec3 r0 = cross(b, c), r1 = cross(c, a), r2 = cross(a, b);
  const double det = dot(a, r0);
  return {{{r0.x / det, r0.y / det, r0.z / det}, {r1.x / det, r1.y / det, r1.z / det}, {r2.x / det, r2.y / det, r2.z / det}}};
}

// The Rec. 709 primaries and D65 white point (IEC 61966-2-1).
constexpr double kPrimaries[3][2] = {{0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}};
constexpr double kWhiteX = 0.3127, kWhiteY = 0.3290;

// XYZ → linear sRGB: the inverse of the matrix whose columns are the primaries' XYZ, scaled so
// that R = G = B = 1 gives the white point at Y = 1.
Mat3 xyz_to_srgb() {
  Mat3 p{};
  for (int i = 0; i < 3; ++i) {
    const double x = kPrimaries[i][0], y = kPrimaries[i][1];
    p[0][i] = x / y;
    p[1][i] = 1;
    p[2][i] = (1 - x - y) / y;
  }
  const Vec3 s = apply(inverse(p), {kWhiteX / kWhiteY, 1, (1 - kWhiteX - kWhiteY) / kWhiteY});
  for (int row = 0; row < 3; ++row)
    for (int i = 0; i < 3; ++i) p[row][i] *= s[i];
  return inverse(p);
}

// Linear interpolation of evenly spaced samples over [lmin, lmax]; 0 outside.
double sample_at(double nm, double lmin, double lmax, const std::vector<double>& v) {
  if (nm < lmin || nm > lmax) return 0;
  const double t = (nm - lmin) / (lmax - lmin) * double(v.size() - 1);
  const size_t i = std::min(size_t(t), v.size() - 2);
  const double f = t - double(i);
  return v[i] * (1 - f) + v[i + 1] * f;
}

}  // namespace

Colour colour_from_xy(double x, double y) {
  if (!(y > 0)) return {{0, 0, 0}};
  return {{x / y, 1, (1 - x - y) / y}};
}

bool colour_from_spectrum(double lmin, double lmax, const std::vector<double>& samples, Colour& out) {
  double sum = 0;
  for (double s : samples) sum += s;
  if (!(sum > 0) || samples.size() < 2 || !(lmax > lmin)) return false;
  const double mean = sum / double(samples.size());
  Vec3 xyz;
  for (int k = 0; k < kSamples; ++k) {
    const double s = sample_at(kFirstNm + kStepNm * k, lmin, lmax, samples) / mean;
    xyz += Vec3(kCmf[k][0], kCmf[k][1], kCmf[k][2]) * s;
  }
  if (!(xyz.y > 1e-9)) return false;
  out.xyz = xyz;
  return true;
}

bool colour_from_temperature(double kelvin, Colour& out) {
  if (!(kelvin >= 1000 && kelvin <= 100000)) return false;
  constexpr double c2 = 1.4387769e-2;  // second radiation constant, m·K
  std::vector<double> samples(kSamples);
  for (int k = 0; k < kSamples; ++k) {
    const double m = (kFirstNm + kStepNm * k) * 1e-9;
    samples[k] = 1 / (std::pow(m * 1e6, 5) * std::expm1(c2 / (m * kelvin)));  // λ in µm keeps it in range
  }
  return colour_from_spectrum(kFirstNm, kFirstNm + kStepNm * (kSamples - 1), samples, out);
}

Colour colour_mix(const std::vector<std::pair<double, Colour>>& parts) {
  Vec3 xyz;
  double weights = 0;
  for (const auto& [w, c] : parts) {
    xyz += c.xyz * w;
    weights += w;
  }
  return {xyz / weights};
}

std::pair<double, double> chromaticity(const Colour& c) {
  const double s = c.xyz.x + c.xyz.y + c.xyz.z;
  if (!(s != 0)) return {0, 0};
  return {c.xyz.x / s, c.xyz.y / s};
}

bool is_neutral(const Colour& c) {
  const auto [x, y] = chromaticity(c);
  return std::fabs(x - 1.0 / 3) <= 1e-3 && std::fabs(y - 1.0 / 3) <= 1e-3;
}

Vec3 linear_srgb(const Colour& c, double luminance, bool* desaturated) {
  if (desaturated) *desaturated = false;
  if (luminance == 0 || is_black(c)) return {};
  if (is_neutral(c)) return {luminance, luminance, luminance};
  static const Mat3 kToSrgb = xyz_to_srgb();
  const Vec3 xyz = c.xyz * (luminance / c.xyz.y);
  // E → D65 by scaling X and Z: E's XYZ is (1, 1, 1), D65's (x/y, 1, z/y).
  const Vec3 adapted{xyz.x * (kWhiteX / kWhiteY), xyz.y, xyz.z * ((1 - kWhiteX - kWhiteY) / kWhiteY)};
  Vec3 rgb = apply(kToSrgb, adapted);
  const double lo = std::min({rgb.x, rgb.y, rgb.z});
  if (lo < 0) {
    // Towards the grey of equal luminance: rgb - (Y, Y, Y) has zero luminance, so any mix keeps Y.
    const double t = luminance / (luminance - lo);
    const Vec3 grey{luminance, luminance, luminance};
    rgb = grey + (rgb - grey) * t;
    rgb = {std::max(rgb.x, 0.0), std::max(rgb.y, 0.0), std::max(rgb.z, 0.0)};
    if (desaturated) *desaturated = true;
  }
  return rgb;
}

}  // namespace walkrad::mgf
