#include "walkrad/accuracy/reference_cache.h"

#include <cstdint>
#include <fstream>
#include <type_traits>

#include "walkrad/core/file_hash.h"
#include "walkrad/formats/error.h"

namespace walkrad {

namespace {

constexpr char kMagic[8] = {'W', 'R', 'R', 'E', 'F', '0', '0', '1'};

std::string file_digest(const std::string& path) { return path.empty() ? "none" : hash_file(path); }

template <class T>
void put(std::ofstream& out, const T& v) {
  static_assert(std::is_trivially_copyable_v<T>);
  out.write(reinterpret_cast<const char*>(&v), sizeof v);
}

template <class T>
void put_vector(std::ofstream& out, const std::vector<T>& v) {
  put(out, uint64_t(v.size()));
  out.write(reinterpret_cast<const char*>(v.data()), std::streamsize(v.size() * sizeof(T)));
}

struct Reader {
  std::ifstream in;
  std::string path;
  template <class T>
  T get() {
    T v{};
    if (!in.read(reinterpret_cast<char*>(&v), sizeof v)) throw InputError(path, "", "truncated reference file");
    return v;
  }
  template <class T>
  std::vector<T> get_vector() {
    const uint64_t n = get<uint64_t>();
    if (n > (uint64_t(1) << 32)) throw InputError(path, "", "corrupt reference file (a count of " + std::to_string(n) + ")");
    std::vector<T> v(n);
    if (!in.read(reinterpret_cast<char*>(v.data()), std::streamsize(n * sizeof(T)))) throw InputError(path, "", "truncated reference file");
    return v;
  }
};

void put_set(std::ofstream& out, const ReferenceSet& r) {
  put_vector(out, r.rays);
  put_vector(out, r.distance);
  put_vector(out, r.luminance);
  put_vector(out, r.standard_error);
  put_vector(out, r.weight);
  put_vector(out, r.B);
  put(out, r.rays_cast);
  put(out, r.seconds);
}

ReferenceSet get_set(Reader& in) {
  ReferenceSet r;
  r.rays = in.get_vector<ViewRay>();
  r.distance = in.get_vector<double>();
  r.luminance = in.get_vector<double>();
  r.standard_error = in.get_vector<double>();
  r.weight = in.get_vector<double>();
  r.B = in.get_vector<Vec3>();
  r.rays_cast = in.get<uint64_t>();
  r.seconds = in.get<double>();
  const size_t n = r.rays.size();
  if (r.distance.size() != n || r.luminance.size() != n || r.standard_error.size() != n || r.weight.size() != n || r.B.size() != n)
    throw InputError(in.path, "", "corrupt reference file (its arrays differ in length)");
  return r;
}

}  // namespace

std::string reference_key(const std::string& scene_path, const std::string& views_path, const std::string& settings) {
  return "scene " + file_digest(scene_path) + ", walkthrough " + file_digest(views_path) + ", " + settings;
}

void save_reference(const std::string& path, const std::string& key, const ReferenceSet& points, const ReferenceSet& image) {
  std::ofstream out(path, std::ios::binary);
  out.write(kMagic, sizeof kMagic);
  put(out, uint64_t(key.size()));
  out.write(key.data(), std::streamsize(key.size()));
  put_set(out, points);
  put_set(out, image);
  if (!out) throw OutputError(path + ": cannot write");
}

void load_reference(const std::string& path, const std::string& key, ReferenceSet& points, ReferenceSet& image) {
  Reader r{std::ifstream(path, std::ios::binary), path};
  if (!r.in) throw InputError(path, "", "cannot open the reference (give a folder an earlier walkrad sweep wrote)");
  char magic[sizeof kMagic];
  if (!r.in.read(magic, sizeof magic) || !std::equal(magic, magic + sizeof magic, kMagic))
    throw InputError(path, "", "not a walkrad sweep reference");
  const uint64_t length = r.get<uint64_t>();
  if (length > 4096) throw InputError(path, "", "corrupt reference file");
  std::string stored(length, '\0');
  if (!r.in.read(stored.data(), std::streamsize(length))) throw InputError(path, "", "truncated reference file");
  if (stored != key)
    throw InputError(path, "", "this reference was traced for another scene or settings (" + stored + "); this sweep asks for " + key,
                     kExitBadArguments);
  points = get_set(r);
  image = get_set(r);
}

}  // namespace walkrad
