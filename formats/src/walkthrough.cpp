// Walkthrough files (walkthrough.h): strict parsing, and camera paths sampled with Catmull-Rom
// splines so that a path through few keyframes gives smooth motion.
#include "walkrad/formats/walkthrough.h"

#include <algorithm>
#include <cmath>

#include "json_util.h"
#include "walkrad/formats/error.h"

namespace walkrad {

using namespace json_util;

namespace {


// Completes a viewpoint from position, direction and up; refuses degenerate frames.
Viewpoint make_viewpoint(std::string name, Vec3 position, Vec3 direction, Vec3 up, double yfov, double aspect,
                         const std::string& file, const std::string& pointer) {
  Viewpoint v;
  v.name = std::move(name);
  v.position = position;
  v.forward = normalize(direction);
  if (!is_finite(position) || !is_finite(direction) || !is_finite(up))
    throw InputError(file, pointer, "position, direction and up must be finite (after interpolation)");
  if (length(direction) <= 0) throw InputError(file, pointer, "view direction has zero length (target equals position)");
  const Vec3 right = cross(v.forward, up);
  if (length(right) < 1e-9 * std::max(1.0, length(up)))
    throw InputError(file, pointer, "up vector is parallel to the view direction");
  v.up = normalize(cross(normalize(right), v.forward));
  if (!(yfov > 0 && yfov < kPi)) throw InputError(file, pointer, "field of view must be in (0, 180) degrees");
  if (!(aspect > 0 && aspect < 100)) throw InputError(file, pointer, "aspect must be in (0, 100)");
  v.yfov = yfov;
  v.aspect = aspect;
  return v;
}

Vec3 catmull_rom(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3, double t) {
  const double t2 = t * t, t3 = t2 * t;
  return 0.5 * ((2.0 * p1) + (p2 - p0) * t + (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3) * t2 +
                (3.0 * p1 - p0 - 3.0 * p2 + p3) * t3);
}

struct Keyframe {
  double time;
  Vec3 position, target;
};

std::vector<Viewpoint> sample_path(const json& path, const std::string& file) {
  const std::string pp = "/path";
  check_keys(path, {"frames", "yfov_deg", "aspect", "up", "keyframes"}, file, pp);
  const uint64_t frames = count(member(path, "frames", file, pp), kMaxWalkthroughFrames, file, pp + "/frames");
  if (frames == 0) throw InputError(file, pp + "/frames", "a path needs at least one frame");
  const double yfov = number(member(path, "yfov_deg", file, pp), file, pp + "/yfov_deg") * kPi / 180.0;
  const double aspect = optional_member(path, "aspect") ? number(path["aspect"], file, pp + "/aspect") : 1.0;
  const Vec3 up = optional_member(path, "up") ? vec3(path["up"], file, pp + "/up") : Vec3{0, 1, 0};
  const json& keys = member(path, "keyframes", file, pp);
  if (!keys.is_array() || keys.empty()) throw InputError(file, pp + "/keyframes", "expected a non-empty array");
  if (keys.size() > kMaxWalkthroughFrames) throw InputError(file, pp + "/keyframes", "too many keyframes", kExitLimitReached);

  std::vector<Keyframe> kf;
  for (size_t i = 0; i < keys.size(); ++i) {
    const std::string kp = pp + "/keyframes/" + std::to_string(i);
    check_keys(keys[i], {"time", "position", "target"}, file, kp);
    Keyframe k{number(member(keys[i], "time", file, kp), file, kp + "/time"),
               vec3(member(keys[i], "position", file, kp), file, kp + "/position"),
               vec3(member(keys[i], "target", file, kp), file, kp + "/target")};
    if (!kf.empty() && !(k.time > kf.back().time)) throw InputError(file, kp + "/time", "keyframe times must increase");
    kf.push_back(k);
  }

  std::vector<Viewpoint> out;
  const double t0 = kf.front().time, t1 = kf.back().time;
  size_t s = 0;  // the segment: times grow with f, so it only moves forward (linear, not frames × keys)
  for (uint64_t f = 0; f < frames; ++f) {
    const double t = frames == 1 ? t0 : t0 + (t1 - t0) * double(f) / double(frames - 1);
    while (s + 2 < kf.size() && kf[s + 1].time <= t) ++s;
    Vec3 pos = kf[s].position, tgt = kf[s].target;
    if (kf.size() > 1) {
      const size_t a = s == 0 ? 0 : s - 1, b = s, c = s + 1, d = std::min(s + 2, kf.size() - 1);
      const double u = std::clamp((t - kf[b].time) / (kf[c].time - kf[b].time), 0.0, 1.0);
      pos = catmull_rom(kf[a].position, kf[b].position, kf[c].position, kf[d].position, u);
      tgt = catmull_rom(kf[a].target, kf[b].target, kf[c].target, kf[d].target, u);
    }
    char name[32];
    std::snprintf(name, sizeof name, "frame-%05llu", static_cast<unsigned long long>(f));
    out.push_back(make_viewpoint(name, pos, tgt - pos, up, yfov, aspect, file, pp + "/keyframes"));
  }
  return out;
}

}  // namespace

std::vector<Viewpoint> walkthrough_from_json(const json& j, const std::string& file) {
  check_keys(j, {"format", "version", "viewpoints", "path"}, file, "");
  if (string(member(j, "format", file, ""), file, "/format") != kWalkthroughFormat)
    throw InputError(file, "/format", std::string("expected \"") + kWalkthroughFormat + "\"");
  const double version = number(member(j, "version", file, ""), file, "/version");
  if (version != kWalkthroughVersion)
    throw InputError(file, "/version", "unsupported version (this walkrad reads version " + std::to_string(kWalkthroughVersion) + ")", kExitMissingFeature);
  const json* views = optional_member(j, "viewpoints");
  const json* path = optional_member(j, "path");
  if (!views == !path) throw InputError(file, "", "needs exactly one of \"viewpoints\" or \"path\"");
  if (path) return sample_path(*path, file);

  if (!views->is_array() || views->empty()) throw InputError(file, "/viewpoints", "expected a non-empty array");
  if (views->size() > kMaxWalkthroughFrames) throw InputError(file, "/viewpoints", "too many viewpoints", kExitLimitReached);
  std::vector<Viewpoint> out;
  for (size_t i = 0; i < views->size(); ++i) {
    const std::string vp = "/viewpoints/" + std::to_string(i);
    const json& v = (*views)[i];
    check_keys(v, {"name", "position", "target", "direction", "up", "yfov_deg", "aspect"}, file, vp);
    const Vec3 pos = vec3(member(v, "position", file, vp), file, vp + "/position");
    const json* target = optional_member(v, "target");
    const json* dir = optional_member(v, "direction");
    if (!target == !dir) throw InputError(file, vp, "needs exactly one of \"target\" or \"direction\"");
    const Vec3 d = target ? vec3(*target, file, vp + "/target") - pos : vec3(*dir, file, vp + "/direction");
    const Vec3 up = optional_member(v, "up") ? vec3(v["up"], file, vp + "/up") : Vec3{0, 1, 0};
    const double yfov = number(member(v, "yfov_deg", file, vp), file, vp + "/yfov_deg") * kPi / 180.0;
    const double aspect = optional_member(v, "aspect") ? number(v["aspect"], file, vp + "/aspect") : 1.0;
    const std::string name = optional_member(v, "name") ? string(v["name"], file, vp + "/name") : "view-" + std::to_string(i);
    out.push_back(make_viewpoint(name, pos, d, up, yfov, aspect, file, vp));
  }
  return out;
}

std::vector<Viewpoint> read_walkthrough(const std::string& path) {
  return walkthrough_from_json(parse_file(path), path);
}

nlohmann::json viewpoint_to_json(const Viewpoint& v) {
  return {{"name", v.name}, {"position", to_json(v.position)}, {"forward", to_json(v.forward)},
          {"up", to_json(v.up)}, {"yfov", v.yfov}, {"aspect", v.aspect}};
}

Viewpoint viewpoint_from_json(const json& j, const std::string& file, const std::string& pointer) {
  check_keys(j, {"name", "position", "forward", "up", "yfov", "aspect"}, file, pointer);
  const Vec3 pos = vec3(member(j, "position", file, pointer), file, pointer + "/position");
  const Vec3 fwd = vec3(member(j, "forward", file, pointer), file, pointer + "/forward");
  const Vec3 up = vec3(member(j, "up", file, pointer), file, pointer + "/up");
  return make_viewpoint(string(member(j, "name", file, pointer), file, pointer + "/name"), pos, fwd, up,
                        number(member(j, "yfov", file, pointer), file, pointer + "/yfov"),
                        number(member(j, "aspect", file, pointer), file, pointer + "/aspect"), file, pointer);
}

}  // namespace walkrad
