// write_scene_gltf (scene_writer.h), through tinygltf's writer (as chunk_writer.cpp).
#include "walkrad/formats/scene_writer.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <tiny_gltf.h>

#include "gltf_build.h"
#include "walkrad/formats/error.h"

namespace walkrad {

namespace {



// True when read_gltf would merge triangle b into triangle a (b holds an edge of a reversed).
bool shares_reversed_edge(const Polygon& a, const Polygon& b) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (a.v[i] == b.v[(j + 1) % 3] && a.v[(i + 1) % 3] == b.v[j]) return true;
  return false;
}

tinygltf::Material material(const Material& m) {
  tinygltf::Material g;
  g.name = m.name;
  g.pbrMetallicRoughness.baseColorFactor = {m.reflectance.x, m.reflectance.y, m.reflectance.z, 1.0};
  g.pbrMetallicRoughness.metallicFactor = 0.0;
  g.pbrMetallicRoughness.roughnessFactor = 1.0;
  const Vec3 radiance = m.emission / kPi;  // E = π L for a Lambertian emitter
  const double strength = max_component(radiance);
  if (strength > 1) {
    g.emissiveFactor = {radiance.x / strength, radiance.y / strength, radiance.z / strength};
    tinygltf::Value::Object ext;
    ext["emissiveStrength"] = tinygltf::Value(strength);
    g.extensions["KHR_materials_emissive_strength"] = tinygltf::Value(ext);
  } else {
    g.emissiveFactor = {radiance.x, radiance.y, radiance.z};
  }
  if (m.transmits()) {  // KHR_materials_diffuse_transmission: ρ = (1 − f) base colour, τ = f × colour
    const double f = max_component(m.transmittance);
    const Vec3 base = f < 1 ? m.reflectance / (1 - f) : Vec3{};
    g.pbrMetallicRoughness.baseColorFactor = {std::min(base.x, 1.0), std::min(base.y, 1.0), std::min(base.z, 1.0), 1.0};
    tinygltf::Value::Object ext;
    ext["diffuseTransmissionFactor"] = tinygltf::Value(f);
    ext["diffuseTransmissionColorFactor"] = tinygltf::Value(tinygltf::Value::Array{
        tinygltf::Value(m.transmittance.x / f), tinygltf::Value(m.transmittance.y / f), tinygltf::Value(m.transmittance.z / f)});
    g.extensions["KHR_materials_diffuse_transmission"] = tinygltf::Value(ext);
  }
  if (m.is_clear_glass()) {  // KHR_materials_transmission, roughness 0: filter t × base, ρ = (1 − t) × base
    const Vec3 base = m.reflectance + m.clear;
    const double t = max_component(base) > 0 ? max_component(m.clear) / max_component(base) : 0.0;
    g.pbrMetallicRoughness.baseColorFactor = {std::min(base.x, 1.0), std::min(base.y, 1.0), std::min(base.z, 1.0), 1.0};
    g.pbrMetallicRoughness.roughnessFactor = 0.0;
    tinygltf::Value::Object transmission, ior;
    transmission["transmissionFactor"] = tinygltf::Value(t);
    g.extensions["KHR_materials_transmission"] = tinygltf::Value(transmission);
    ior["ior"] = tinygltf::Value(m.ior);
    g.extensions["KHR_materials_ior"] = tinygltf::Value(ior);
  }
  return g;
}

// The rotation taking glTF's camera frame (-Z forward, +Y up) to the viewpoint's, as a unit quaternion.
std::vector<double> camera_rotation(const Viewpoint& v) {
  const Vec3 back = -normalize(v.forward);
  const Vec3 right = normalize(cross(v.up, back));
  const Vec3 up = cross(back, right);
  const double m[3][3] = {{right.x, up.x, back.x}, {right.y, up.y, back.y}, {right.z, up.z, back.z}};
  double x, y, z, w;
  const double trace = m[0][0] + m[1][1] + m[2][2];
  if (trace > 0) {
    const double s = 2 * std::sqrt(1 + trace);
    w = s / 4; x = (m[2][1] - m[1][2]) / s; y = (m[0][2] - m[2][0]) / s; z = (m[1][0] - m[0][1]) / s;
  } else if (m[0][0] > m[1][1] && m[0][0] > m[2][2]) {
    const double s = 2 * std::sqrt(1 + m[0][0] - m[1][1] - m[2][2]);
    w = (m[2][1] - m[1][2]) / s; x = s / 4; y = (m[0][1] + m[1][0]) / s; z = (m[0][2] + m[2][0]) / s;
  } else if (m[1][1] > m[2][2]) {
    const double s = 2 * std::sqrt(1 + m[1][1] - m[0][0] - m[2][2]);
    w = (m[0][2] - m[2][0]) / s; x = (m[0][1] + m[1][0]) / s; y = s / 4; z = (m[1][2] + m[2][1]) / s;
  } else {
    const double s = 2 * std::sqrt(1 + m[2][2] - m[0][0] - m[1][1]);
    w = (m[1][0] - m[0][1]) / s; x = (m[0][2] + m[2][0]) / s; y = (m[1][2] + m[2][1]) / s; z = s / 4;
  }
  const double n = std::sqrt(x * x + y * y + z * z + w * w);
  return {x / n, y / n, z / n, w / n};
}

// Raw bytes in buffer 0 as a view of their own (no accessor), 4-byte aligned like the others.
int append_bytes(tinygltf::Model& model, const std::string& bytes) {
  auto& buf = model.buffers[0].data;
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = buf.size();
  view.byteLength = bytes.size();
  buf.insert(buf.end(), bytes.begin(), bytes.end());
  while (buf.size() % 4) buf.push_back(0);
  model.bufferViews.push_back(view);
  return int(model.bufferViews.size()) - 1;
}

// A mesh a material, a node each, about the material's centre.
void add_meshes(const Scene& scene, tinygltf::Model& model, tinygltf::Scene& gscene) {
  for (size_t mi = 0; mi < scene.materials.size(); ++mi) {
    // Quads in one primitive; triangles in as few primitives as keep read_gltf from merging neighbours.
    std::vector<const Polygon*> quads;
    std::vector<std::vector<const Polygon*>> chains;
    Bounds bounds;
    std::vector<const Polygon*> all;  // the panes of clear glass a bake took out too (Scene::glass)
    for (const Polygon& p : scene.polygons) all.push_back(&p);
    for (const Polygon& p : scene.glass) all.push_back(&p);
    for (const Polygon* polygon : all) {
      const Polygon& p = *polygon;
      if (p.material != mi) continue;
      for (int k = 0; k < p.count; ++k) bounds.extend(p.v[k]);
      if (p.count == 4) {
        quads.push_back(&p);
        continue;
      }
      size_t chain = 0;
      while (chain < chains.size() && shares_reversed_edge(*chains[chain].back(), p)) ++chain;
      if (chain == chains.size()) chains.emplace_back();
      chains[chain].push_back(&p);
    }
    if (bounds.empty()) continue;
    const Vec3 centre = bounds.center();
    if (!quads.empty()) chains.insert(chains.begin(), quads);

    tinygltf::Mesh mesh;
    mesh.name = scene.materials[mi].name;
    for (const auto& chain : chains) {
      std::vector<float> positions;
      std::vector<uint32_t> indices;
      for (const Polygon* p : chain) {
        const uint32_t base = uint32_t(positions.size() / 3);
        for (int k = 0; k < p->count; ++k) {
          const Vec3 q = p->v[k] - centre;
          positions.insert(positions.end(), {float(q.x), float(q.y), float(q.z)});
        }
        indices.insert(indices.end(), {base, base + 1, base + 2});
        if (p->count == 4) indices.insert(indices.end(), {base, base + 2, base + 3});
      }
      tinygltf::Primitive prim;
      prim.mode = TINYGLTF_MODE_TRIANGLES;
      prim.material = int(mi);
      prim.attributes["POSITION"] = gltf_build::append_vec3(model, positions, true);
      prim.indices = gltf_build::append_indices(model, indices);
      mesh.primitives.push_back(prim);
    }
    model.meshes.push_back(mesh);
    tinygltf::Node node;
    node.name = mesh.name;
    node.mesh = int(model.meshes.size()) - 1;
    node.translation = {centre.x, centre.y, centre.z};
    model.nodes.push_back(node);
    gscene.nodes.push_back(int(model.nodes.size()) - 1);
  }

}

// A perspective camera node per viewpoint.
void add_cameras(const Scene& scene, tinygltf::Model& model, tinygltf::Scene& gscene) {
  const Bounds all = scene.bounds();
  for (const Viewpoint& v : scene.cameras) {
    tinygltf::Camera cam;
    cam.type = "perspective";
    cam.name = v.name;
    cam.perspective.yfov = v.yfov;
    cam.perspective.aspectRatio = v.aspect;
    // 1 cm to twice the distance that takes in the whole scene (tinygltf always writes zfar).
    cam.perspective.znear = 0.01;
    const double reach = all.empty() ? 0 : length(v.position - all.center()) + length(all.diagonal());
    cam.perspective.zfar = std::max(1.0, 2 * reach);
    model.cameras.push_back(cam);
    tinygltf::Node node;
    node.name = v.name;
    node.camera = int(model.cameras.size()) - 1;
    node.translation = {v.position.x, v.position.y, v.position.z};
    node.rotation = camera_rotation(v);
    model.nodes.push_back(node);
    gscene.nodes.push_back(int(model.nodes.size()) - 1);
  }
}

void add_ies_lights(const Scene& scene, tinygltf::Model& model, tinygltf::Scene& gscene) {
  // EXT_lights_ies: each profile once, its file's bytes in a bufferView; a node per luminaire.
  tinygltf::Value::Array profiles;
  std::vector<const IesProfile*> written;
  for (const PunctualLight& l : scene.lights) {
    if (l.type != PunctualLight::Type::ies || !l.profile) continue;
    size_t index = std::find(written.begin(), written.end(), l.profile.get()) - written.begin();
    if (index == written.size()) {
      written.push_back(l.profile.get());
      tinygltf::Value::Object profile;
      profile["bufferView"] = tinygltf::Value(append_bytes(model, l.profile->text));
      profile["mimeType"] = tinygltf::Value(std::string("application/x-ies-lm-63"));
      profile["name"] = tinygltf::Value(std::filesystem::path(l.profile->source).filename().string());
      profiles.push_back(tinygltf::Value(profile));
    }
    // The reader multiplies by the tilt factor at the node's tilt: divided out here.
    const double tilt = l.profile->tilt_factor(l.direction, {0, -1, 0});
    const double peak = max_component(l.intensity);
    tinygltf::Value::Object instance;
    instance["light"] = tinygltf::Value(int(index));
    instance["multiplier"] = tinygltf::Value(tilt > 0 ? peak / tilt : 0.0);
    instance["color"] = tinygltf::Value(tinygltf::Value::Array{
        tinygltf::Value(peak > 0 ? l.intensity.x / peak : 1.0), tinygltf::Value(peak > 0 ? l.intensity.y / peak : 1.0),
        tinygltf::Value(peak > 0 ? l.intensity.z / peak : 1.0)});
    Viewpoint frame;
    frame.forward = l.direction;
    frame.up = l.up;
    tinygltf::Node node;
    node.name = l.name;
    node.translation = {l.position.x, l.position.y, l.position.z};
    node.rotation = camera_rotation(frame);
    node.extensions["EXT_lights_ies"] = tinygltf::Value(instance);
    model.nodes.push_back(node);
    gscene.nodes.push_back(int(model.nodes.size()) - 1);
  }
  if (!profiles.empty()) {
    tinygltf::Value::Object top;
    top["lights"] = tinygltf::Value(profiles);
    model.extensions["EXT_lights_ies"] = tinygltf::Value(top);
    model.extensionsUsed.push_back("EXT_lights_ies");
  }
}

void add_punctual_lights(const Scene& scene, tinygltf::Model& model, tinygltf::Scene& gscene) {
  for (const PunctualLight& l : scene.lights) {  // KHR_lights_punctual: a node shining along its −Z
    if (l.type == PunctualLight::Type::ies || l.type == PunctualLight::Type::sky) continue;
    tinygltf::Light light;
    light.name = l.name;
    light.type = l.type == PunctualLight::Type::spot          ? "spot"
                 : l.type == PunctualLight::Type::directional ? "directional"
                                                              : "point";
    if (l.type == PunctualLight::Type::directional && l.angular_diameter != kSunDiameter) {
      tinygltf::Value::Object extras;
      extras["walkrad:angular_diameter"] = tinygltf::Value(l.angular_diameter);
      light.extras = tinygltf::Value(extras);
    }
    const double peak = max_component(l.intensity);
    light.intensity = peak;
    light.color = peak > 0 ? std::vector<double>{l.intensity.x / peak, l.intensity.y / peak, l.intensity.z / peak}
                           : std::vector<double>{1, 1, 1};
    light.range = l.range;
    light.spot.innerConeAngle = l.inner_cone;
    light.spot.outerConeAngle = l.outer_cone;
    model.lights.push_back(light);
    Viewpoint frame;
    frame.forward = l.direction;
    frame.up = std::fabs(l.direction.y) < 0.9 ? Vec3(0, 1, 0) : Vec3(1, 0, 0);
    frame.up = normalize(frame.up - l.direction * dot(frame.up, l.direction));
    tinygltf::Node node;
    node.name = l.name;
    node.translation = {l.position.x, l.position.y, l.position.z};
    node.rotation = camera_rotation(frame);
    tinygltf::Value::Object light_ref;
    light_ref["light"] = tinygltf::Value(int(model.lights.size()) - 1);
    node.extensions["KHR_lights_punctual"] = tinygltf::Value(light_ref);
    model.nodes.push_back(node);
    gscene.nodes.push_back(int(model.nodes.size()) - 1);
  }
}

// The sky: the scene's extras "walkrad:sky" (its spec; an image's path relative to the file written) and,
// where its zenith is not glTF's +Y, "walkrad:up".
void add_sky(const Scene& scene, const std::string& path, tinygltf::Scene& gscene) {
  for (const PunctualLight& l : scene.lights) {
    if (l.type != PunctualLight::Type::sky || !l.sky) continue;
    const Sky& sky = *l.sky;
    tinygltf::Value::Object extras;
    std::string spec = sky.spec;
    if (sky.kind == Sky::Kind::image) {
      namespace fs = std::filesystem;
      spec = fs::absolute(sky.path).lexically_normal().lexically_relative(fs::absolute(path).parent_path()).generic_string();
    }
    extras["walkrad:sky"] = tinygltf::Value(spec);
    if (length(sky.up - Vec3(0, 1, 0)) > 1e-12)
      extras["walkrad:up"] = tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(sky.up.x), tinygltf::Value(sky.up.y),
                                                                    tinygltf::Value(sky.up.z)});
    gscene.extras = tinygltf::Value(extras);
  }
}

}  // namespace

void write_scene_gltf(const Scene& scene, const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (ext != ".glb" && ext != ".gltf") throw std::invalid_argument(path + ": the output must end in .glb or .gltf");

  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "walkrad";
  model.buffers.resize(1);
  tinygltf::Scene gscene;
  for (const Material& m : scene.materials) {
    model.materials.push_back(material(m));
    for (const auto& [name, value] : model.materials.back().extensions)
      if (std::find(model.extensionsUsed.begin(), model.extensionsUsed.end(), name) == model.extensionsUsed.end())
        model.extensionsUsed.push_back(name);
  }

  add_meshes(scene, model, gscene);
  add_cameras(scene, model, gscene);
  add_ies_lights(scene, model, gscene);
  add_punctual_lights(scene, model, gscene);
  add_sky(scene, path, gscene);
  model.scenes.push_back(gscene);
  model.defaultScene = 0;

  // Serialised in memory (a .gltf gets its buffer as a data URI), then written with checks:
  // tinygltf's file writer does not report a file it could not open.
  const bool binary = ext == ".glb";
  std::ostringstream bytes;
  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToStream(&model, bytes, /*prettyPrint=*/!binary, /*writeBinary=*/binary))
    throw OutputError(path + ": cannot serialise the glTF");
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  const std::string data = bytes.str();
  out.write(data.data(), std::streamsize(data.size()));
  out.close();
  if (!out) throw OutputError(path + ": cannot write the file");
}

}  // namespace walkrad
