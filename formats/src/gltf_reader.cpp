// read_gltf (gltf_reader.h): glTF 2.0 scene → plain scene arrays.
#include "walkrad/formats/gltf_reader.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>

#include "gltf_access.h"
#include "gltf_ies.h"
#include "input_limits.h"
#include "walkrad/formats/error.h"

namespace walkrad {

namespace {

using Mat4 = std::array<double, 16>;  // column-major, as glTF stores it

constexpr int kMaxNodeDepth = 256;                 // nodes are visited recursively
constexpr size_t kMaxGltfPolygons = 50'000'000;  // as MgfOptions::max_polygons (kExitLimitReached past it)

Mat4 identity() { return {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}; }

Mat4 multiply(const Mat4& a, const Mat4& b) {
  Mat4 r{};
  for (int c = 0; c < 4; ++c)
    for (int row = 0; row < 4; ++row)
      for (int k = 0; k < 4; ++k) r[c * 4 + row] += a[k * 4 + row] * b[c * 4 + k];
  return r;
}

Vec3 transform_point(const Mat4& m, const Vec3& p) {
  return {m[0] * p.x + m[4] * p.y + m[8] * p.z + m[12], m[1] * p.x + m[5] * p.y + m[9] * p.z + m[13],
          m[2] * p.x + m[6] * p.y + m[10] * p.z + m[14]};
}
Vec3 transform_vector(const Mat4& m, const Vec3& v) {
  return {m[0] * v.x + m[4] * v.y + m[8] * v.z, m[1] * v.x + m[5] * v.y + m[9] * v.z, m[2] * v.x + m[6] * v.y + m[10] * v.z};
}

// The node's local matrix: its matrix, or T·R·S (glTF 2.0 §5.25).
Mat4 local_matrix(const tinygltf::Node& n) {
  if (n.matrix.size() == 16) {
    Mat4 m;
    std::copy(n.matrix.begin(), n.matrix.end(), m.begin());
    return m;
  }
  Mat4 t = identity(), r = identity(), s = identity();
  if (n.translation.size() == 3) { t[12] = n.translation[0]; t[13] = n.translation[1]; t[14] = n.translation[2]; }
  if (n.rotation.size() == 4) {
    const double x = n.rotation[0], y = n.rotation[1], z = n.rotation[2], w = n.rotation[3];
    r = {1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (x * z - y * w), 0,
         2 * (x * y - z * w), 1 - 2 * (x * x + z * z), 2 * (y * z + x * w), 0,
         2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y), 0,
         0, 0, 0, 1};
  }
  if (n.scale.size() == 3) { s[0] = n.scale[0]; s[5] = n.scale[1]; s[10] = n.scale[2]; }
  return multiply(t, multiply(r, s));
}

double srgb_to_linear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

// A glTF texture decoded to linear RGB (base colour and emissive textures are sRGB-encoded) and kept in
// the scene; returns its index there, or −1 when it has no decodable 8-bit image.
int32_t load_texture(const tinygltf::Model& m, int texture, Scene& scene) {
  if (texture < 0 || texture >= int(m.textures.size())) return -1;
  const int source = m.textures[texture].source;
  if (source < 0 || source >= int(m.images.size())) return -1;
  const tinygltf::Image& img = m.images[source];
  if (img.image.empty() || img.component < 3 || img.bits != 8 || img.width <= 0 || img.height <= 0 ||
      size_t(img.width) * size_t(img.height) * size_t(img.component) != img.image.size())
    return -1;
  Texture t;
  t.width = uint32_t(img.width);
  t.height = uint32_t(img.height);
  const size_t pixels = size_t(img.width) * size_t(img.height);
  t.rgb.resize(pixels * 3);
  Vec3 sum;
  for (size_t i = 0; i < pixels; ++i) {
    for (int c = 0; c < 3; ++c) t.rgb[i * 3 + c] = float(srgb_to_linear(img.image[i * img.component + c] / 255.0));
    sum += Vec3(t.rgb[i * 3], t.rgb[i * 3 + 1], t.rgb[i * 3 + 2]);
  }
  t.mean = sum / double(pixels);
  scene.textures.push_back(std::move(t));
  return int32_t(scene.textures.size()) - 1;
}

Material convert_material(const tinygltf::Model& m, int index, Scene& scene, const std::string& file) {
  const tinygltf::Material& gm = m.materials[index];
  const std::string place = "materials[" + std::to_string(index) + "]";
  Material mat;
  mat.name = gm.name.empty() ? "material-" + std::to_string(index) : gm.name;
  const auto& bc = gm.pbrMetallicRoughness.baseColorFactor;
  mat.reflectance = {bc.size() > 0 ? bc[0] : 1.0, bc.size() > 1 ? bc[1] : 1.0, bc.size() > 2 ? bc[2] : 1.0};
  if (gm.pbrMetallicRoughness.baseColorTexture.index >= 0) {
    mat.reflectance_texture = load_texture(m, gm.pbrMetallicRoughness.baseColorTexture.index, scene);
    if (mat.reflectance_texture >= 0) mat.reflectance = mul(mat.reflectance, scene.textures[size_t(mat.reflectance_texture)].mean);
  }
  double strength = 1.0;
  const auto ext = gm.extensions.find("KHR_materials_emissive_strength");
  if (ext != gm.extensions.end() && ext->second.Has("emissiveStrength"))
    strength = ext->second.Get("emissiveStrength").GetNumberAsDouble();
  // Transmission: KHR_materials_diffuse_transmission splits the diffuse lobe, ρ = (1 − f) base colour,
  // τ = f × diffuseTransmissionColorFactor. KHR_materials_transmission (thin glass): with roughness 0,
  // clear glass, its filter t × base colour and its index KHR_materials_ior's (1.5 without), ρ = (1 − t)
  // base colour; rough, diffused, ρ = (1 − t) base colour, τ = t × base colour.
  const auto number = [&](const tinygltf::Value& v, const char* key, double fallback) {
    return v.Has(key) && v.Get(key).IsNumber() ? v.Get(key).GetNumberAsDouble() : fallback;
  };
  const auto dt = gm.extensions.find("KHR_materials_diffuse_transmission");
  const auto st = gm.extensions.find("KHR_materials_transmission");
  if (dt != gm.extensions.end()) {
    const double f = number(dt->second, "diffuseTransmissionFactor", 0.0);
    Vec3 colour(1, 1, 1);
    if (dt->second.Has("diffuseTransmissionColorFactor") && dt->second.Get("diffuseTransmissionColorFactor").IsArray() &&
        dt->second.Get("diffuseTransmissionColorFactor").ArrayLen() == 3)
      for (int k = 0; k < 3; ++k) colour[k] = dt->second.Get("diffuseTransmissionColorFactor").Get(k).GetNumberAsDouble();
    if (!(f >= 0 && f <= 1)) throw InputError(file, place + ".extensions.KHR_materials_diffuse_transmission", "diffuseTransmissionFactor must lie in [0, 1]");
    mat.transmittance = colour * f;
    mat.reflectance = mat.reflectance * (1 - f);
  } else if (st != gm.extensions.end()) {
    const double t = number(st->second, "transmissionFactor", 0.0);
    if (!(t >= 0 && t <= 1)) throw InputError(file, place + ".extensions.KHR_materials_transmission", "transmissionFactor must lie in [0, 1]");
    if (gm.pbrMetallicRoughness.roughnessFactor == 0) {
      mat.clear = mat.reflectance * t;
      const auto ior = gm.extensions.find("KHR_materials_ior");
      if (ior != gm.extensions.end()) mat.ior = number(ior->second, "ior", 1.5);
      if (!(mat.ior >= 1 && mat.ior <= 10))
        throw InputError(file, place + ".extensions.KHR_materials_ior", "ior must lie in [1, 10] for glass");
    } else {
      mat.transmittance = mat.reflectance * t;
    }
    mat.reflectance = mat.reflectance * (1 - t);
  }
  const auto& ef = gm.emissiveFactor;
  const Vec3 radiance = Vec3(ef.size() > 0 ? ef[0] : 0, ef.size() > 1 ? ef[1] : 0, ef.size() > 2 ? ef[2] : 0) * strength;
  mat.emission = radiance * kPi;  // E = π L for a Lambertian emitter
  if (gm.emissiveTexture.index >= 0) {
    mat.emission_texture = load_texture(m, gm.emissiveTexture.index, scene);
    if (mat.emission_texture >= 0) mat.emission = mul(mat.emission, scene.textures[size_t(mat.emission_texture)].mean);
  }
  if (!is_finite(mat.reflectance) || !is_finite(mat.emission) || !is_finite(mat.transmittance))
    throw InputError(file, place, "colour factors must be finite");
  if (std::min({mat.reflectance.x, mat.reflectance.y, mat.reflectance.z}) < 0 || max_component(mat.reflectance) > 1)
    throw InputError(file, place, "baseColorFactor must lie in [0, 1]");
  if (std::min({mat.transmittance.x, mat.transmittance.y, mat.transmittance.z}) < 0 ||
      max_component(mat.transmittance + mat.reflectance) > 1 + 1e-12)
    throw InputError(file, place, "reflectance + transmittance must lie in [0, 1] (energy cannot be created)");
  if (std::min({mat.emission.x, mat.emission.y, mat.emission.z}) < 0)
    throw InputError(file, place, "emission must not be negative");
  // ρ = 1 absorbs nothing. Stated in the file (an explicit baseColorFactor, no texture), a channel of
  // 1 is kept, with a warning: the scene has a solution where light escapes or other surfaces absorb,
  // which the bake checks (bake.cpp refuses a closed scene where nothing absorbs). Values in (0.99, 1)
  // and those from glTF's default white or a texture's mean are capped at 0.99, and said so: they
  // converge slowly for a difference nobody sees.
  const bool stated = gm.values.count("baseColorFactor") > 0 && mat.reflectance_texture < 0;
  constexpr double kMaxReflectance = 0.99;
  const auto cap = [&](double c) { return stated && c == 1.0 ? c : std::min(c, kMaxReflectance); };
  const Vec3 capped(cap(mat.reflectance.x), cap(mat.reflectance.y), cap(mat.reflectance.z));
  if (capped != mat.reflectance) scene.warnings.push_back(place + " \"" + mat.name + "\": reflectance capped at 0.99");
  mat.reflectance = capped;
  if (max_component(mat.reflectance) >= 1)
    scene.warnings.push_back(place + " \"" + mat.name + "\": reflectance 1 absorbs nothing: the scene needs light to "
                             "escape or other surfaces to absorb it (the bake checks)");
  return mat;
}

// The affine texture-coordinate map of a triangle from its corners' (u, v): with the barycentric
// gradients ∇λ1 = (e2 × n) / |n|², ∇λ2 = (n × e1) / |n|² (e1 = v1 − v0, e2 = v2 − v0, n = e1 × e2).
UvMap uv_map(const Polygon& t, const float u[3], const float v[3]) {
  const Vec3 e1 = t.v[1] - t.v[0], e2 = t.v[2] - t.v[0], n = cross(e1, e2);
  const double n2 = dot(n, n);
  UvMap m;
  if (!(n2 > 0)) return m;
  const Vec3 g1 = cross(e2, n) / n2, g2 = cross(n, e1) / n2;
  m.a_u = g1 * double(u[1] - u[0]) + g2 * double(u[2] - u[0]);
  m.a_v = g1 * double(v[1] - v[0]) + g2 * double(v[2] - v[0]);
  m.b_u = u[0] - dot(m.a_u, t.v[0]);
  m.b_v = v[0] - dot(m.a_v, t.v[0]);
  m.valid = is_finite(m.a_u) && is_finite(m.a_v) && std::isfinite(m.b_u) && std::isfinite(m.b_v);
  return m;
}

// Two triangles' texture maps agree on their shared quad (so it can be one polygon): the second's
// corners map to the same (u, v) under the first's map, within 1e-6 texel-space units.
bool same_uv(const Polygon& a, const Polygon& b) {
  if (a.uv.valid != b.uv.valid) return false;
  if (!a.uv.valid) return true;
  for (int k = 0; k < 3; ++k)
    if (std::fabs(a.uv.u(b.v[k]) - b.uv.u(b.v[k])) > 1e-6 || std::fabs(a.uv.v(b.v[k]) - b.uv.v(b.v[k])) > 1e-6) return false;
  return true;
}

// Merges consecutive triangles (a, b) sharing an edge in opposite directions into one planar
// convex quad: fewer, better-shaped elements (a quad splits into 4 quads, not slivers).
bool merge_quad(const Polygon& a, const Polygon& b, Polygon& quad) {
  if (a.material != b.material || !same_uv(a, b)) return false;
  for (int i = 0; i < 3; ++i) {
    const Vec3 u = a.v[i], v = a.v[(i + 1) % 3], p = a.v[(i + 2) % 3];
    for (int j = 0; j < 3; ++j) {
      if (!(b.v[j] == v && b.v[(j + 1) % 3] == u)) continue;
      const Vec3 q = b.v[(j + 2) % 3];
      quad.v = {p, u, q, v};
      quad.count = 4;
      quad.material = a.material;
      quad.source = a.source;
      quad.uv = a.uv;
      const Vec3 n = polygon_normal(a);
      const double size = std::max(length(q - p), length(v - u));
      // Planar to 1e-6 of the quad's size, or to the rounding of float positions (2^-23 of the
      // coordinates' magnitude, twice): a small planar quad far from the origin stays one quad.
      double magnitude = 0;
      for (const Vec3& c : {p, u, q, v}) magnitude = std::max({magnitude, std::fabs(c.x), std::fabs(c.y), std::fabs(c.z)});
      if (std::fabs(dot(q - p, n)) > 1e-6 * size + 2.4e-7 * magnitude) return false;  // not planar
      for (int k = 0; k < 4; ++k)  // convex: every corner turns the same way as the normal
        if (dot(cross(quad.v[(k + 1) % 4] - quad.v[k], quad.v[(k + 2) % 4] - quad.v[(k + 1) % 4]), n) <= 0) return false;
      return true;
    }
  }
  return false;
}

struct Reader {
  const tinygltf::Model& model;
  const std::string& file;
  Scene& scene;
  std::vector<int> material_map;  // glTF material index → scene material (-1: default)
  int default_material = -1;
  std::vector<bool> visited;      // glTF 2.0 §3.5.3: nodes form disjoint strict trees (no cycles, one parent)
  GltfIesLights ies;              // EXT_lights_ies luminaires

  uint32_t material_for(int gltf_material) {
    if (gltf_material >= 0 && gltf_material < int(model.materials.size())) return uint32_t(material_map[gltf_material]);
    if (default_material < 0) {
      // glTF's default material is white (baseColor 1); capped like any other at 0.99.
      scene.materials.push_back({"default", {0.99, 0.99, 0.99}, {0, 0, 0}});
      default_material = int(scene.materials.size()) - 1;
    }
    return uint32_t(default_material);
  }

  void add_mesh(int mesh_index, const Mat4& world) {
    const tinygltf::Mesh& mesh = model.meshes[mesh_index];
    for (size_t pi = 0; pi < mesh.primitives.size(); ++pi) {
      const tinygltf::Primitive& prim = mesh.primitives[pi];
      const std::string place = "meshes[" + std::to_string(mesh_index) + "].primitives[" + std::to_string(pi) + "]";
      if (prim.mode == TINYGLTF_MODE_POINTS || prim.mode == TINYGLTF_MODE_LINE || prim.mode == TINYGLTF_MODE_LINE_LOOP ||
          prim.mode == TINYGLTF_MODE_LINE_STRIP)
        continue;  // points and lines carry no area: nothing to light
      if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != -1)
        throw InputError(file, place, "triangle strips and fans are not supported", kExitMissingFeature);
      const auto pos = prim.attributes.find("POSITION");
      if (pos == prim.attributes.end()) throw InputError(file, place, "primitive has no POSITION");
      std::vector<float> p;
      gltf_access::append_floats(model, pos->second, 3, p, file, "POSITION");
      std::vector<uint32_t> idx;
      if (prim.indices >= 0) gltf_access::append_indices(model, prim.indices, 0, idx, file);
      else for (uint32_t i = 0; i < p.size() / 3; ++i) idx.push_back(i);
      if (idx.size() % 3) throw InputError(file, place, "index count is not a multiple of 3");
      if (scene.polygons.size() + idx.size() / 3 > kMaxGltfPolygons)
        throw InputError(file, place, "the scene has more than " + std::to_string(kMaxGltfPolygons) + " triangles", kExitLimitReached);
      const uint32_t material = material_for(prim.material);
      // Texture coordinates where the material has a texture (float VEC2; else its average is used).
      std::vector<float> uv;
      const Material& mat = scene.materials[material];
      if (mat.reflectance_texture >= 0 || mat.emission_texture >= 0) {
        const tinygltf::Material& gm = model.materials[size_t(prim.material)];
        const int set = gm.pbrMetallicRoughness.baseColorTexture.index >= 0 ? gm.pbrMetallicRoughness.baseColorTexture.texCoord
                                                                           : gm.emissiveTexture.texCoord;
        const auto tc = prim.attributes.find("TEXCOORD_" + std::to_string(set));
        if (tc == prim.attributes.end() || !gltf_access::append_uvs(model, tc->second, uv, file))
          scene.warnings.push_back(place + ": no float TEXCOORD_" + std::to_string(set) + " for its material's texture: the texture's average is used");
        if (uv.size() / 2 != p.size() / 3) uv.clear();
      }

      Polygon pending;
      bool has_pending = false;
      auto flush = [&] { if (has_pending) scene.polygons.push_back(pending); has_pending = false; };
      for (size_t t = 0; t < idx.size(); t += 3) {
        Polygon tri;
        tri.count = 3;
        tri.material = material;
        tri.source = uint32_t(mesh_index);
        for (int k = 0; k < 3; ++k) {
          const uint32_t i = idx[t + k];
          if (size_t(i) * 3 + 2 >= p.size()) throw InputError(file, place, "index " + std::to_string(i) + " out of range");
          tri.v[k] = transform_point(world, {p[i * 3], p[i * 3 + 1], p[i * 3 + 2]});
          if (!is_valid_vertex(tri.v[k]))
            throw InputError(file, place + ": accessors[" + std::to_string(pos->second) + "] (POSITION)",
                             "vertex " + std::to_string(i) + (is_finite(tri.v[k]) ? " lies beyond ±1e9 m" : " is not finite") +
                                 " (after the node transforms)");
        }
        if (polygon_area(tri) <= 0) { ++scene.dropped_degenerate; continue; }
        if (!uv.empty()) {
          float tu[3], tv[3];
          for (int k = 0; k < 3; ++k) {
            tu[k] = uv[idx[t + k] * 2];
            tv[k] = uv[idx[t + k] * 2 + 1];
          }
          tri.uv = uv_map(tri, tu, tv);
        }
        Polygon quad;
        if (has_pending && pending.count == 3 && merge_quad(pending, tri, quad)) { pending = quad; continue; }
        flush();
        pending = tri;
        has_pending = true;
      }
      flush();
    }
  }

  void add_camera(int camera_index, const Mat4& world, int node) {
    const tinygltf::Camera& cam = model.cameras[camera_index];
    if (cam.type != "perspective") {
      scene.warnings.push_back("cameras[" + std::to_string(camera_index) + "]: only perspective cameras become viewpoints");
      return;
    }
    Viewpoint v;
    v.name = model.nodes[node].name.empty() ? "camera-" + std::to_string(camera_index) : model.nodes[node].name;
    v.position = transform_point(world, {0, 0, 0});
    v.forward = normalize(transform_vector(world, {0, 0, -1}));
    v.up = normalize(transform_vector(world, {0, 1, 0}));
    v.yfov = cam.perspective.yfov;
    v.aspect = cam.perspective.aspectRatio > 0 ? cam.perspective.aspectRatio : 1.0;
    if (!is_finite(v.position) || length(v.forward) == 0 || !(v.yfov > 0 && v.yfov < kPi))
      throw InputError(file, "cameras[" + std::to_string(camera_index) + "]", "degenerate camera");
    scene.cameras.push_back(v);
  }

  // KHR_lights_punctual: a node's light, placed at the node's origin, shining along its −Z (a
  // directional light: from infinitely far, its angular size in extras "walkrad:angular_diameter").
  void add_light(int node, const Mat4& world) {
    const tinygltf::Node& n = model.nodes[node];
    const auto ext = n.extensions.find("KHR_lights_punctual");
    if (ext == n.extensions.end() || !ext->second.IsObject() || !ext->second.Has("light")) return;
    const std::string place = "nodes[" + std::to_string(node) + "].extensions.KHR_lights_punctual";
    const tinygltf::Value& index = ext->second.Get("light");
    if (!index.IsInt() || index.GetNumberAsInt() < 0 || index.GetNumberAsInt() >= int(model.lights.size()))
      throw InputError(file, place, "light index out of range");
    const int li = index.GetNumberAsInt();
    const tinygltf::Light& gl = model.lights[size_t(li)];
    const std::string lplace = "extensions.KHR_lights_punctual.lights[" + std::to_string(li) + "]";
    PunctualLight l;
    l.name = !gl.name.empty() ? gl.name : !n.name.empty() ? n.name : "light-" + std::to_string(li);
    if (gl.type == "point") {
      l.type = PunctualLight::Type::point;
    } else if (gl.type == "spot") {
      l.type = PunctualLight::Type::spot;
      l.inner_cone = gl.spot.innerConeAngle;
      l.outer_cone = gl.spot.outerConeAngle;
      if (!(l.inner_cone >= 0 && l.inner_cone < l.outer_cone && l.outer_cone <= kPi / 2))
        throw InputError(file, lplace, "spot cones must satisfy 0 <= innerConeAngle < outerConeAngle <= pi/2");
    } else if (gl.type == "directional") {
      l.type = PunctualLight::Type::directional;
      if (gl.extras.IsObject() && gl.extras.Has("walkrad:angular_diameter")) {
        const tinygltf::Value& a = gl.extras.Get("walkrad:angular_diameter");
        l.angular_diameter = a.IsNumber() ? a.GetNumberAsDouble() : -1.0;
        if (!(l.angular_diameter >= 0 && l.angular_diameter <= kMaxAngularDiameter))
          throw InputError(file, lplace + ".extras", "walkrad:angular_diameter must be a number of radians from 0 to " +
                                                         std::to_string(kMaxAngularDiameter));
      }
    } else {
      throw InputError(file, lplace, "light type '" + gl.type + "' is not supported (point, spot and directional are)",
                       kExitMissingFeature);
    }
    const auto& c = gl.color;
    const Vec3 colour(c.size() > 0 ? c[0] : 1.0, c.size() > 1 ? c[1] : 1.0, c.size() > 2 ? c[2] : 1.0);
    l.intensity = colour * gl.intensity;
    l.range = gl.range;
    if (!is_finite(l.intensity) || std::min({l.intensity.x, l.intensity.y, l.intensity.z}) < 0 || !(l.range >= 0) ||
        !std::isfinite(l.range))
      throw InputError(file, lplace, "color, intensity and range must be finite and not negative");
    l.position = transform_point(world, {0, 0, 0});
    l.direction = transform_vector(world, {0, 0, -1});
    if (!is_valid_vertex(l.position) || !(length(l.direction) > 0))
      throw InputError(file, place, "the light's node transform is degenerate");
    l.direction = normalize(l.direction);
    scene.lights.push_back(l);
  }

  void visit(int node, const Mat4& parent, int depth) {
    if (node < 0 || node >= int(model.nodes.size())) throw InputError(file, "nodes", "node index " + std::to_string(node) + " out of range");
    if (visited[node])
      throw InputError(file, "nodes[" + std::to_string(node) + "]", "node is reached twice: the hierarchy has a cycle or a node with two parents (glTF 2.0 §3.5.3)");
    if (depth > kMaxNodeDepth)
      throw InputError(file, "nodes[" + std::to_string(node) + "]", "node hierarchy deeper than " + std::to_string(kMaxNodeDepth), kExitLimitReached);
    visited[node] = true;
    const tinygltf::Node& n = model.nodes[node];
    const Mat4 world = multiply(parent, local_matrix(n));
    if (n.mesh >= 0) {
      if (n.mesh >= int(model.meshes.size())) throw InputError(file, "nodes[" + std::to_string(node) + "]", "mesh index out of range");
      add_mesh(n.mesh, world);
    }
    if (n.camera >= 0 && n.camera < int(model.cameras.size())) add_camera(n.camera, world, node);
    add_light(node, world);
    ies.add(node, transform_point(world, {0, 0, 0}), transform_vector(world, {0, 0, -1}), transform_vector(world, {0, 1, 0}), scene);
    for (int child : n.children) visit(child, world, depth + 1);
  }
};

}  // namespace

Scene read_gltf(const std::string& path, const std::string& input_folder) {
  const std::string folder = input_limits::input_folder(path, input_folder);
  const tinygltf::Model model = gltf_access::load(path, /*load_images=*/true, folder);
  Scene scene;
  scene.source = path;
  Reader r{model, path, scene, {}, -1, std::vector<bool>(model.nodes.size(), false), GltfIesLights(model, path, folder)};
  for (size_t i = 0; i < model.materials.size(); ++i) {
    scene.materials.push_back(convert_material(model, int(i), scene, path));
    r.material_map.push_back(int(i));
  }
  std::vector<int> roots;
  int shown = -1;  // the scene shown
  if (!model.scenes.empty()) {
    const int s = model.defaultScene >= 0 && model.defaultScene < int(model.scenes.size()) ? model.defaultScene : 0;
    roots = model.scenes[s].nodes;
    shown = s;
  } else {
    // No scene: every node that is nobody's child is a root.
    std::vector<bool> child(model.nodes.size(), false);
    for (const auto& n : model.nodes)
      for (int c : n.children) if (c >= 0 && c < int(child.size())) child[c] = true;
    for (size_t i = 0; i < model.nodes.size(); ++i) if (!child[i]) roots.push_back(int(i));
  }
  for (int root : roots) r.visit(root, identity(), 0);
  // The sky: the scene's extras "walkrad:sky", a spec as `walkrad bake --sky` takes (sky.h), glTF's +Y up;
  // after the lights, whose sun a clear sky may follow.
  if (shown >= 0 && model.scenes[size_t(shown)].extras.IsObject() && model.scenes[size_t(shown)].extras.Has("walkrad:sky")) {
    const std::string place = "scenes[" + std::to_string(shown) + "].extras.walkrad:sky";
    const tinygltf::Value& v = model.scenes[size_t(shown)].extras.Get("walkrad:sky");
    if (!v.IsString()) throw InputError(path, place, "must be a string such as \"cie-overcast:1000\" (see walkrad bake --sky)");
    const tinygltf::Value& extras = model.scenes[size_t(shown)].extras;
    if (extras.Has("walkrad:up")) {  // the zenith, where not glTF's +Y
      const tinygltf::Value& u = extras.Get("walkrad:up");
      const std::string uplace = "scenes[" + std::to_string(shown) + "].extras.walkrad:up";
      if (!u.IsArray() || u.ArrayLen() != 3 || !u.Get(0).IsNumber() || !u.Get(1).IsNumber() || !u.Get(2).IsNumber())
        throw InputError(path, uplace, "must be three numbers [x, y, z]");
      scene.up = {u.Get(0).GetNumberAsDouble(), u.Get(1).GetNumberAsDouble(), u.Get(2).GetNumberAsDouble()};
    }
    set_sky(scene, parse_sky(v.Get<std::string>(), path, place, scene.up, scene.lights,
                             std::filesystem::path(path).parent_path().string(), folder));
  }
  if (scene.dropped_degenerate)
    scene.warnings.push_back(std::to_string(scene.dropped_degenerate) + " zero-area triangles dropped");
  if (scene.polygons.empty()) throw InputError(path, "", "the scene has no triangles");
  return scene;
}

}  // namespace walkrad
