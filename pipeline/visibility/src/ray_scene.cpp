#include "walkrad/visibility/ray_scene.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "walkrad/core/fresnel.h"
#include "walkrad/scene/openings.h"

namespace walkrad {

namespace {

void check(RTCDevice device, const char* what) {
  const RTCError e = rtcGetDeviceError(device);
  if (e != RTC_ERROR_NONE) throw std::runtime_error(std::string("Embree: ") + what + " failed (error " + std::to_string(int(e)) + ")");
}

// An intersect context that passes only front faces (rtcInitIntersectContext's filter slot; the scene
// allows context filters): Embree hands the context back to the filter, which reads the normals.
struct FrontFacesOnly {
  RTCIntersectContext context;
  const std::vector<Vec3>* normals;
};

void keep_front_faces(const RTCFilterFunctionNArguments* args) {
  const auto* self = reinterpret_cast<const FrontFacesOnly*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    const Vec3& n = (*self->normals)[RTCHitN_primID(args->hit, args->N, i)];
    const Vec3 d(RTCRayN_dir_x(args->ray, args->N, i), RTCRayN_dir_y(args->ray, args->N, i),
                 RTCRayN_dir_z(args->ray, args->N, i));
    if (dot(n, d) >= 0) args->valid[i] = 0;
  }
}

}  // namespace

RayScene::RayScene(const Scene& scene) {
  build(scene, nullptr);
  if (!scene.glass.empty()) {
    Scene panes;
    panes.materials.push_back({"glass", {}, {}});
    panes.polygons = scene.glass;
    for (Polygon& p : panes.polygons) p.material = 0;
    glass_ = std::make_unique<Glass>();
    glass_->rays = std::make_unique<RayScene>(panes);
    for (const Polygon& p : scene.glass) {
      const Material& m = scene.materials[p.material];
      glass_->filter.push_back(m.clear);
      glass_->normal.push_back(polygon_normal(p));
      glass_->ior.push_back(m.ior);
    }
  }
  const bool sky = std::any_of(scene.lights.begin(), scene.lights.end(), [](const PunctualLight& l) { return l.type == PunctualLight::Type::sky; });
  if (!sky) return;
  Scene holes;
  holes.materials.push_back({"opening", {}, {}});
  for (const Opening& o : find_openings(scene)) holes.polygons.insert(holes.polygons.end(), o.triangles.begin(), o.triangles.end());
  openings_ = std::make_unique<Openings>();
  if (!holes.polygons.empty()) openings_->rays = std::make_unique<RayScene>(holes);
  openings_->triangles = std::move(holes.polygons);
}

RayScene::RayScene(const Scene& scene, const std::vector<uint8_t>& exclude) { build(scene, &exclude); }

void RayScene::build(const Scene& scene, const std::vector<uint8_t>* exclude) {
  const Bounds b = scene.bounds();
  origin_ = b.center();
  const double diag = std::max(length(b.diagonal()), 1e-30);
  // Relative 1e-6 of the scene (1 µm in a 1 m room) is far above float's 6e-8 relative rounding of
  // re-centred coordinates, and far below any feature an element resolves.
  offset_ = 1e-6 * diag;
  // A power of two (exact in floating point) that brings the diagonal into [1, 2): float rounding of
  // the geometry and of rays is then the same at any scale, so the same scene in millimetres or
  // kilometres casts rays with the same answers (stability suite, docs/numerics.md).
  scale_ = std::ldexp(1.0, -std::ilogb(diag));

  device_ = rtcNewDevice("verbose=0");
  if (!device_) throw std::runtime_error("Embree: cannot create a device");
  scene_ = rtcNewScene(device_);
  rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);
  rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);

  // Origin, scale and offset come from the whole scene: a solid scene answers like the full one.
  std::vector<uint32_t> kept;
  for (uint32_t i = 0; i < scene.polygons.size(); ++i)
    if (!exclude || !(*exclude)[i]) kept.push_back(i);
  if (exclude) prim_polygon_ = kept;
  const size_t n = kept.size();
  if (n > 0) add_quads(scene, kept);
  rtcCommitScene(scene_);
  check(device_, "building the scene");
}

void RayScene::add_quads(const Scene& scene, const std::vector<uint32_t>& kept) {
  RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_QUAD);
  const size_t n = kept.size();
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                               3 * sizeof(float), 4 * n));
  auto* quads = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT4,
                                                               4 * sizeof(unsigned), n));
  check(device_, "allocating geometry");
  prim_normal_.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const Polygon& p = scene.polygons[kept[i]];
    prim_normal_[i] = cross(p.v[1] - p.v[0], p.v[2] - p.v[0]);
    for (int k = 0; k < 4; ++k) {
      const Vec3 v = (p.v[std::min(k, p.count - 1)] - origin_) * scale_;
      vertices[(4 * i + k) * 3 + 0] = float(v.x);
      vertices[(4 * i + k) * 3 + 1] = float(v.y);
      vertices[(4 * i + k) * 3 + 2] = float(v.z);
      quads[4 * i + k] = unsigned(4 * i + k);
    }
  }
  rtcCommitGeometry(geom);
  rtcAttachGeometry(scene_, geom);
  rtcReleaseGeometry(geom);
}

RayScene::~RayScene() {
  if (scene_) rtcReleaseScene(scene_);
  if (device_) rtcReleaseDevice(device_);
}

bool RayScene::occluded(const Vec3& from, const Vec3& to) const {
  const Vec3 o = (from - origin_) * scale_, d = (to - from) * scale_;
  RTCRay ray{};
  ray.org_x = float(o.x); ray.org_y = float(o.y); ray.org_z = float(o.z);
  ray.dir_x = float(d.x); ray.dir_y = float(d.y); ray.dir_z = float(d.z);
  ray.tnear = 0.0f;
  ray.tfar = 1.0f;  // the direction spans the whole segment
  ray.mask = 0xFFFFFFFFu;
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  rtcOccluded1(scene_, &ctx, &ray);
  return ray.tfar < 0.0f;  // Embree marks an occluded ray with tfar = -inf
}

void RayScene::occluded(const Segment* segments, size_t count, uint8_t* blocked) const {
  constexpr size_t kBatch = 64;
  RTCRay rays[kBatch];
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;  // a link's rays run between two small patches
  for (size_t base = 0; base < count; base += kBatch) {
    const size_t n = std::min(kBatch, count - base);
    for (size_t k = 0; k < n; ++k) {
      const Vec3 o = (segments[base + k].from - origin_) * scale_, d = (segments[base + k].to - segments[base + k].from) * scale_;
      RTCRay& r = rays[k];
      r.org_x = float(o.x); r.org_y = float(o.y); r.org_z = float(o.z);
      r.dir_x = float(d.x); r.dir_y = float(d.y); r.dir_z = float(d.z);
      r.tnear = 0.0f;
      r.tfar = 1.0f;
      r.time = 0.0f;
      r.mask = 0xFFFFFFFFu;
      r.id = unsigned(k);
      r.flags = 0;
    }
    rtcOccluded1M(scene_, &ctx, rays, unsigned(n), sizeof(RTCRay));
    for (size_t k = 0; k < n; ++k) blocked[base + k] = rays[k].tfar < 0.0f ? 1 : 0;
  }
}

RayScene::Hit RayScene::intersect(const Vec3& origin, const Vec3& direction) const {
  const Vec3 o = (origin - origin_) * scale_, dir = direction * scale_;
  RTCRayHit rh{};
  rh.ray.org_x = float(o.x); rh.ray.org_y = float(o.y); rh.ray.org_z = float(o.z);
  rh.ray.dir_x = float(dir.x); rh.ray.dir_y = float(dir.y); rh.ray.dir_z = float(dir.z);
  rh.ray.tnear = 0.0f;
  rh.ray.tfar = std::numeric_limits<float>::infinity();
  rh.ray.mask = 0xFFFFFFFFu;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  rtcIntersect1(scene_, &ctx, &rh);
  Hit h;
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return h;
  if (dot(prim_normal_[rh.hit.primID], direction) >= 0) {
    // A back face: look again for a front face within the offset of it, on either side.
    const float t = rh.ray.tfar, dt = float(offset_ / std::max(length(direction), 1e-300));
    RTCRayHit front = rh;
    front.ray.tnear = std::max(0.0f, t - dt);
    front.ray.tfar = t + dt;
    front.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    FrontFacesOnly only{{}, &prim_normal_};
    rtcInitIntersectContext(&only.context);
    only.context.filter = keep_front_faces;
    rtcIntersect1(scene_, &only.context, &front);
    if (front.hit.geomID != RTC_INVALID_GEOMETRY_ID) rh = front;
  }
  h.hit = true;
  h.polygon = prim_polygon_.empty() ? rh.hit.primID : prim_polygon_[rh.hit.primID];
  h.position = origin + direction * double(rh.ray.tfar);
  return h;
}

Vec3 RayScene::transmittance(const Vec3& from, const Vec3& to) const {
  Vec3 t(1, 1, 1);
  if (!glass_) return t;
  const Vec3 d = to - from;
  const double length2 = dot(d, d);
  if (!(length2 > 0)) return t;
  const Vec3 unit = d / std::sqrt(length2);
  const double step = glass_->rays->offset();
  Vec3 at = from;
  for (int crossed = 0; crossed < 64; ++crossed) {  // a stack of 64 panes lets nothing through anyway
    const Hit h = glass_->rays->intersect(at, d);
    if (!h.hit || dot(h.position - from, d) >= length2) break;
    const uint32_t k = h.polygon;
    t = mul(t, glass_->filter[k] * pane_transmittance(dot(unit, glass_->normal[k]), glass_->ior[k]));
    at = h.position + unit * step;
  }
  return t;
}

}  // namespace walkrad
