#include "bake_inputs.h"

#include <type_traits>

#include "walkrad/core/byte_buffer.h"
#include "walkrad/core/file_hash.h"
#include "walkrad/core/ranks.h"
#include "walkrad/formats/error.h"
#include "walkrad/formats/scene_reader.h"
#include "walkrad/formats/walkthrough.h"
#include "walkrad/scene/scene_cleanup.h"

namespace walkrad::bake_detail {

namespace {

// Every field, one by one: the structs below hold strings and lists. A field added to one of them must
// be added here; the size checks fail until it is.
static_assert(std::is_trivially_copyable_v<Polygon> && std::is_trivially_copyable_v<Vec3>);
static_assert(sizeof(Material) == sizeof(std::string) + 4 * sizeof(Vec3) + 8 + 8, "Material changed: see bake_inputs.cpp");
static_assert(sizeof(Viewpoint) == sizeof(std::string) + 3 * sizeof(Vec3) + 16, "Viewpoint changed: see bake_inputs.cpp");
static_assert(sizeof(PunctualLight) == sizeof(std::string) + 8 + 4 * sizeof(Vec3) + 32 + 2 * sizeof(std::shared_ptr<int>),
              "PunctualLight changed: see bake_inputs.cpp");
static_assert(sizeof(IesProfile) == 3 * sizeof(std::string) + 5 * sizeof(std::vector<double>) + 8 + 8 + 8 + 8 + 8,
              "IesProfile changed: see bake_inputs.cpp");
static_assert(sizeof(Sky) == 8 + 3 * sizeof(Vec3) + 2 * sizeof(std::string) + 8 + sizeof(std::vector<float>) + 8,
              "Sky changed: see bake_inputs.cpp");
static_assert(sizeof(Texture) == 8 + sizeof(std::vector<float>) + sizeof(Vec3), "Texture changed: see bake_inputs.cpp");

template <class Io, class M>
void each(Io&& io, M& m) {  // Material
  io(m.reflectance), io(m.emission), io(m.transmittance), io(m.reflectance_texture), io(m.emission_texture);
  io(m.clear), io(m.ior);
}
template <class Io, class V>  // Viewpoint, const or not
void each_view(Io&& io, V& v) { io(v.position), io(v.forward), io(v.up), io(v.yfov), io(v.aspect); }

void put_views(ByteWriter& out, const std::vector<Viewpoint>& views) {
  out.put(uint64_t(views.size()));
  for (const Viewpoint& v : views) {
    out.put_string(v.name);
    each_view([&](const auto& x) { out.put(x); }, v);
  }
}

void get_views(ByteReader& in, std::vector<Viewpoint>& views) {
  views.resize(size_t(in.get<uint64_t>()));
  for (Viewpoint& v : views) {
    v.name = in.get_string();
    each_view([&](auto& x) { x = in.get<std::remove_reference_t<decltype(x)>>(); }, v);
  }
}

}  // namespace

std::vector<uint8_t> scene_to_bytes(const Scene& scene, const std::vector<Viewpoint>& views) {
  ByteWriter out;
  out.put_string(scene.source);
  out.put(scene.dropped_degenerate);
  out.put(uint64_t(scene.materials.size()));
  for (const Material& m : scene.materials) {
    out.put_string(m.name);
    each([&](const auto& x) { out.put(x); }, m);
  }
  out.put_vector(scene.polygons);
  out.put_vector(scene.glass);
  put_views(out, scene.cameras);
  put_views(out, views);
  out.put(scene.up);
  out.put(uint64_t(scene.lights.size()));
  for (const PunctualLight& l : scene.lights) {
    out.put_string(l.name);
    out.put(l.type), out.put(l.position), out.put(l.direction), out.put(l.up), out.put(l.intensity);
    out.put(l.range), out.put(l.inner_cone), out.put(l.outer_cone), out.put(l.angular_diameter);
    out.put(bool(l.sky));
    if (l.sky) {
      const Sky& k = *l.sky;
      out.put(k.kind), out.put(k.radiance), out.put(k.up), out.put(k.sun), out.put(k.width), out.put(k.height);
      out.put(k.mean_luminance), out.put_string(k.path), out.put_string(k.spec), out.put_vector(k.rgb);
    }
    out.put(bool(l.profile));
    if (!l.profile) continue;
    const IesProfile& p = *l.profile;
    out.put_string(p.source), out.put_string(p.version), out.put_string(p.text);
    out.put(p.photometry), out.put(p.lamp_geometry), out.put(p.lamps), out.put(p.lumens_per_lamp), out.put(p.input_watts);
    out.put_vector(p.vertical), out.put_vector(p.horizontal), out.put_vector(p.candela);
    out.put_vector(p.tilt_angles), out.put_vector(p.tilt_factors);
  }
  out.put(uint64_t(scene.textures.size()));
  for (const Texture& t : scene.textures) {
    out.put(t.width), out.put(t.height), out.put(t.mean);
    out.put_vector(t.rgb);
  }
  out.put(uint64_t(scene.warnings.size()));
  for (const std::string& w : scene.warnings) out.put_string(w);
  return std::move(out.bytes());
}

void scene_from_bytes(const std::vector<uint8_t>& bytes, Scene& scene, std::vector<Viewpoint>& views) {
  ByteReader in(bytes);
  auto get = [&](auto& x) { x = in.get<std::remove_reference_t<decltype(x)>>(); };
  scene = {};
  scene.source = in.get_string();
  get(scene.dropped_degenerate);
  scene.materials.resize(size_t(in.get<uint64_t>()));
  for (Material& m : scene.materials) {
    m.name = in.get_string();
    each(get, m);
  }
  in.get_vector(scene.polygons);
  in.get_vector(scene.glass);
  get_views(in, scene.cameras);
  get_views(in, views);
  get(scene.up);
  scene.lights.resize(size_t(in.get<uint64_t>()));
  for (PunctualLight& l : scene.lights) {
    l.name = in.get_string();
    get(l.type), get(l.position), get(l.direction), get(l.up), get(l.intensity);
    get(l.range), get(l.inner_cone), get(l.outer_cone), get(l.angular_diameter);
    if (in.get<bool>()) {
      auto k = std::make_shared<Sky>();
      get(k->kind), get(k->radiance), get(k->up), get(k->sun), get(k->width), get(k->height);
      get(k->mean_luminance), k->path = in.get_string(), k->spec = in.get_string(), in.get_vector(k->rgb);
      l.sky = std::move(k);
    }
    if (!in.get<bool>()) continue;
    auto p = std::make_shared<IesProfile>();
    p->source = in.get_string(), p->version = in.get_string(), p->text = in.get_string();
    get(p->photometry), get(p->lamp_geometry), get(p->lamps), get(p->lumens_per_lamp), get(p->input_watts);
    in.get_vector(p->vertical), in.get_vector(p->horizontal), in.get_vector(p->candela);
    in.get_vector(p->tilt_angles), in.get_vector(p->tilt_factors);
    l.profile = std::move(p);
  }
  scene.textures.resize(size_t(in.get<uint64_t>()));
  for (Texture& t : scene.textures) {
    get(t.width), get(t.height), get(t.mean);
    in.get_vector(t.rgb);
  }
  scene.warnings.resize(size_t(in.get<uint64_t>()));
  for (std::string& w : scene.warnings) w = in.get_string();
  if (!in.done()) throw std::runtime_error("the scene sent by rank 0 has bytes past its end");
}


BakeInputs read_bake_inputs(const BakeSettings& s) {
  BakeInputs in;
  std::vector<uint8_t> bytes;
  if (ranks().rank == 0) {
    in.scene = read_scene(s.scene, s.input_folder, s.mgf_sides);
    apply_sky_options(in.scene, s.sky, s.up, s.sun);
    if (const uint64_t copies = remove_duplicate_polygons(in.scene))
      in.scene.warnings.push_back(std::to_string(copies) + " duplicate polygons (same corners, same facing) dropped");
    separate_clear_glass(in.scene);
    in.views = s.views.empty() ? in.scene.cameras : read_walkthrough(s.views);
    in.scene_hash = hash_file(s.scene);
    in.views_hash = s.views.empty() ? "" : hash_file(s.views);
    if (ranks().size == 1) return in;
    ByteWriter out;
    out.put_string(in.scene_hash), out.put_string(in.views_hash);
    const std::vector<uint8_t> scene = scene_to_bytes(in.scene, in.views);
    out.put_vector(scene);
    bytes = std::move(out.bytes());
  }
  broadcast(bytes);
  if (ranks().rank != 0) {
    ByteReader r(bytes);
    in.scene_hash = r.get_string(), in.views_hash = r.get_string();
    std::vector<uint8_t> scene;
    r.get_vector(scene);
    scene_from_bytes(scene, in.scene, in.views);
  }
  return in;
}

}  // namespace walkrad::bake_detail
