// Sky (sky.h): the CIE skies' formulas, the equirectangular map's layout, and the spec's grammar.
#include "walkrad/formats/sky.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stb_image.h>

#include "input_limits.h"
#include "walkrad/formats/error.h"
#include "walkrad/formats/scene.h"

namespace walkrad {

namespace {

constexpr uint64_t kMaxSkyPixels = uint64_t(1) << 26;  // 8192 × 8192, as the scene's images
constexpr double kMaxSkyRadiance = 1e9;                 // W/(m²·sr): the sun's disc is 2·10⁷

// CIE clear sky: the luminance gradation φ(θ) and the indicatrix f(γ).
double clear_gradation(double cos_theta) { return 1 - std::exp(-0.32 / cos_theta); }
double clear_indicatrix(double gamma) {
  const double c = std::cos(gamma);
  return 0.91 + 10 * std::exp(-3 * gamma) + 0.45 * c * c;
}

// w turned so that `up` becomes +Y (the shortest rotation; about X for up = −Y).
Vec3 to_map_frame(const Vec3& w, const Vec3& up) {
  const Vec3 y(0, 1, 0);
  const double c = dot(up, y);
  if (c > 1 - 1e-12) return w;
  if (c < -1 + 1e-12) return {w.x, -w.y, -w.z};
  const Vec3 k = normalize(cross(up, y));
  const double s = std::sqrt(std::max(0.0, 1 - c * c));
  return w * c + cross(k, w) * s + k * (dot(k, w) * (1 - c));
}

Vec3 pixel(const Sky& sky, int64_t col, int64_t row) {
  col = ((col % sky.width) + sky.width) % sky.width;
  row = std::clamp<int64_t>(row, 0, int64_t(sky.height) - 1);
  const float* p = &sky.rgb[3 * (size_t(row) * sky.width + size_t(col))];
  return {p[0], p[1], p[2]};
}

[[noreturn]] void refuse(const std::string& where, const std::string& place, const std::string& why, ExitCode code) {
  throw InputError(where, place, why, code);
}

// "1.5" or "1,0.5,2": one value for every channel or three. Finite, ≥ 0, ≤ kMaxSkyRadiance, not all 0.
Vec3 parse_radiance(const std::string& text, const std::string& where, const std::string& place, ExitCode code,
                    const std::string& what) {
  std::vector<double> v;
  size_t at = 0;
  while (at <= text.size()) {
    const size_t comma = std::min(text.find(',', at), text.size());
    const std::string item = text.substr(at, comma - at);
    char* end = nullptr;
    const double x = std::strtod(item.c_str(), &end);
    if (item.empty() || end != item.c_str() + item.size() || !std::isfinite(x) || x < 0 || x > kMaxSkyRadiance)
      refuse(where, place, what + " '" + item + "' is not a number from 0 to 1e9", code);
    v.push_back(x);
    at = comma + 1;
  }
  if (v.size() != 1 && v.size() != 3) refuse(where, place, what + " takes one value or three (R,G,B), not " + std::to_string(v.size()), code);
  const Vec3 r = v.size() == 1 ? Vec3(v[0], v[0], v[0]) : Vec3(v[0], v[1], v[2]);
  if (max_component(r) <= 0) refuse(where, place, what + " is 0: the sky would give no light", code);
  return r;
}

// "x,y,z" as a unit direction; false where it is not three finite numbers of some length.
bool parse_direction(const std::string& text, Vec3& out) {
  double d[3];
  char tail = 0;
  if (std::sscanf(text.c_str(), "%lf,%lf,%lf%c", &d[0], &d[1], &d[2], &tail) != 3) return false;
  const Vec3 v(d[0], d[1], d[2]);
  if (!is_finite(v) || !(length(v) > 0)) return false;
  out = normalize(v);
  return true;
}

// The mean luminance over the directions the sky lights, uniform in solid angle (64 × 128 cells).
double mean_luminance(const Sky& sky) {
  double sum = 0;
  int lit = 0;
  for (int i = 0; i < 64; ++i)
    for (int j = 0; j < 128; ++j) {
      const double z = 1 - 2 * (i + 0.5) / 64, r = std::sqrt(1 - z * z), phi = 2 * kPi * (j + 0.5) / 128;
      const double l = luminance(sky.at({r * std::cos(phi), r * std::sin(phi), z}));
      if (l > 0) sum += l, ++lit;
    }
  return lit ? sum / lit : 0.0;
}

void read_image(Sky& sky, const std::string& path) {
  const std::vector<unsigned char> bytes = input_limits::read_file(path, input_limits::kMaxBinaryBytes, "sky image");
  const int size = int(std::min<size_t>(bytes.size(), size_t(INT32_MAX)));
  int w = 0, h = 0, comp = 0;
  if (!stbi_is_hdr_from_memory(bytes.data(), size) || !stbi_info_from_memory(bytes.data(), size, &w, &h, &comp))
    refuse(path, "", "not a Radiance .hdr image (the sky's radiance map)", kExitBadInput);
  if (uint64_t(w) * uint64_t(h) > kMaxSkyPixels)
    refuse(path, "", std::to_string(w) + " × " + std::to_string(h) + " pixels exceed the limit of " + std::to_string(kMaxSkyPixels) +
                         " pixels", kExitLimitReached);
  float* data = stbi_loadf_from_memory(bytes.data(), size, &w, &h, &comp, 3);
  if (!data) refuse(path, "", std::string("cannot be decoded: ") + stbi_failure_reason(), kExitBadInput);
  sky.width = uint32_t(w), sky.height = uint32_t(h);
  sky.rgb.assign(data, data + size_t(w) * size_t(h) * 3);
  stbi_image_free(data);
  for (float& x : sky.rgb)
    if (!std::isfinite(x) || x < 0 || x > kMaxSkyRadiance)
      refuse(path, "", "a pixel's radiance is negative, infinite or beyond 1e9 W/(m²·sr)", kExitBadInput);
}

}  // namespace

Vec3 Sky::at(const Vec3& w) const {
  if (kind == Kind::image) {
    if (width == 0 || height == 0) return {};
    const Vec3 d = to_map_frame(w, up);
    const double u = std::atan2(d.z, d.x) / (2 * kPi) + 0.5, v = 0.5 - std::asin(std::clamp(d.y, -1.0, 1.0)) / kPi;
    const double x = u * width - 0.5, y = v * height - 0.5;
    const double x0 = std::floor(x), y0 = std::floor(y), fx = x - x0, fy = y - y0;
    const auto c = int64_t(x0), r = int64_t(y0);
    const Vec3 l = (pixel(*this, c, r) * (1 - fx) + pixel(*this, c + 1, r) * fx) * (1 - fy) +
                   (pixel(*this, c, r + 1) * (1 - fx) + pixel(*this, c + 1, r + 1) * fx) * fy;
    return mul(l, radiance);
  }
  const double cos_theta = dot(w, up);
  if (cos_theta <= 0) return {};
  switch (kind) {
    case Kind::uniform: return radiance;
    case Kind::cie_overcast: return radiance * ((1 + 2 * cos_theta) / 3);
    case Kind::cie_clear: {
      const double gamma = std::acos(std::clamp(dot(w, sun), -1.0, 1.0));
      const double sun_zenith = std::acos(std::clamp(dot(sun, up), -1.0, 1.0));
      return radiance * (clear_indicatrix(gamma) * clear_gradation(cos_theta) /
                         (clear_indicatrix(sun_zenith) * clear_gradation(1.0)));
    }
    case Kind::image: break;
  }
  return {};
}

Sky parse_sky(const std::string& spec, const std::string& where, const std::string& place, const Vec3& up,
              const std::vector<PunctualLight>& lights, const std::string& base, const std::string& folder) {
  const ExitCode code = where == "--sky" ? kExitBadArguments : kExitBadInput;
  const std::string& at = place.empty() ? spec : place;
  Sky sky;
  sky.spec = spec;
  if (!is_finite(up) || !(length(up) > 0)) refuse(where, at, "the zenith direction is not a direction", code);
  sky.up = normalize(up);
  const size_t colon = spec.find(':');
  const std::string kind = spec.substr(0, colon), args = colon == std::string::npos ? "" : spec.substr(colon + 1);
  std::string lower = spec;
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (lower.size() > 4 && lower.compare(lower.size() - 4, 4, ".hdr") == 0) {
    sky.kind = Sky::Kind::image;
    sky.radiance = {1, 1, 1};
    const std::string path = base.empty() ? spec : (std::filesystem::path(base) / spec).string();
    sky.path = path;
    if (!folder.empty())
      if (const std::string why = input_limits::outside(path, folder); !why.empty()) refuse(where, at, "'" + path + "' " + why, kExitBadInput);
    read_image(sky, path);
  } else if (kind == "uniform" || kind == "cie-overcast") {
    sky.kind = kind == "uniform" ? Sky::Kind::uniform : Sky::Kind::cie_overcast;
    sky.radiance = parse_radiance(args, where, at, code, kind == "uniform" ? "the radiance" : "the zenith's radiance");
  } else if (kind == "cie-clear") {
    sky.kind = Sky::Kind::cie_clear;
    const size_t sun_at = args.find('@');
    sky.radiance = parse_radiance(args.substr(0, sun_at), where, at, code, "the zenith's radiance");
    if (sun_at != std::string::npos) {
      const std::string text = args.substr(sun_at + 1);
      if (!parse_direction(text, sky.sun)) refuse(where, at, "the sun's direction '" + text + "' is not three numbers x,y,z", code);
    } else {
      const auto sun = std::find_if(lights.begin(), lights.end(), [](const PunctualLight& l) { return l.type == PunctualLight::Type::directional; });
      if (sun == lights.end())
        refuse(where, at, "cie-clear needs the sun's position: give it as cie-clear:Lz@x,y,z or give the scene a directional light", code);
      sky.sun = normalize(-sun->direction);
    }
    if (dot(sky.sun, sky.up) <= 0) refuse(where, at, "the sun is below the horizon: a clear sky by day needs it above", code);
  } else {
    refuse(where, at, "unknown sky '" + kind + "' (known: uniform:L, cie-overcast:Lz, cie-clear:Lz[@x,y,z], FILE.hdr)", code);
  }
  sky.mean_luminance = mean_luminance(sky);
  if (!(sky.mean_luminance > 0)) refuse(where, at, "the sky gives no light from any direction", code);
  return sky;
}

std::string sky_description(const Sky& sky) {
  const auto number = [](double x) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", x);
    return std::string(text);
  };
  const auto rgb = [&](const Vec3& v) {
    return v.x == v.y && v.y == v.z ? number(v.x) : number(v.x) + "," + number(v.y) + "," + number(v.z);
  };
  const auto dir = [&](const Vec3& v) { return "(" + number(v.x) + ", " + number(v.y) + ", " + number(v.z) + ")"; };
  const std::string up = ", zenith towards " + dir(sky.up);
  switch (sky.kind) {
    case Sky::Kind::uniform: return "a uniform sky (" + rgb(sky.radiance) + " W/(m²·sr)" + up + ")";
    case Sky::Kind::cie_overcast: return "a CIE overcast sky (zenith " + rgb(sky.radiance) + " W/(m²·sr)" + up + ")";
    case Sky::Kind::cie_clear:
      return "a CIE clear sky (zenith " + rgb(sky.radiance) + " W/(m²·sr), the sun towards " + dir(sky.sun) + up + ")";
    case Sky::Kind::image:
      return "a sky from " + sky.spec + " (" + std::to_string(sky.width) + " × " + std::to_string(sky.height) + ", mean " +
             number(sky.mean_luminance) + " W/(m²·sr)" + up + ")";
  }
  return {};
}

void apply_sky_options(Scene& scene, const std::string& sky, const std::string& up, const std::string& sun) {
  if (!up.empty() && !parse_direction(up, scene.up))  // a glTF file's own sky keeps its zenith
    throw InputError("--up", up, "expected a direction x,y,z", kExitBadArguments);
  if (!sun.empty()) {
    const size_t at = sun.find('@');
    if (at == std::string::npos) throw InputError("--sun", sun, "expected E@x,y,z: the irradiance, then the direction towards the sun", kExitBadArguments);
    PunctualLight l;
    l.name = "sun";
    l.type = PunctualLight::Type::directional;
    l.intensity = parse_radiance(sun.substr(0, at), "--sun", sun, kExitBadArguments, "the irradiance");
    Vec3 towards;
    if (!parse_direction(sun.substr(at + 1), towards))
      throw InputError("--sun", sun, "the direction towards the sun is not three numbers x,y,z", kExitBadArguments);
    l.direction = -towards;
    scene.lights.push_back(std::move(l));
  }
  if (!sky.empty()) set_sky(scene, parse_sky(sky, "--sky", sky, scene.up, scene.lights));
}

void set_sky(Scene& scene, Sky sky) {
  scene.lights.erase(std::remove_if(scene.lights.begin(), scene.lights.end(),
                                    [](const PunctualLight& l) { return l.type == PunctualLight::Type::sky; }),
                     scene.lights.end());
  PunctualLight l;
  l.name = "sky";
  l.type = PunctualLight::Type::sky;
  l.intensity = {1, 1, 1};
  l.sky = std::make_shared<const Sky>(std::move(sky));
  scene.lights.push_back(std::move(l));
}

}  // namespace walkrad
