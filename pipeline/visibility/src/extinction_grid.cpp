#include "walkrad/visibility/extinction_grid.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <mutex>

#include <openvdb/openvdb.h>

#include "walkrad/formats/error.h"

namespace walkrad {

namespace {

constexpr const char* kGridName = "extinction";

void initialize_openvdb() {
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
}

// OpenVDB writes a random UUID into every file's header (after the magic number, the file format
// version, the library's major and minor versions and the grid-offsets flag: byte 21, 36 characters).
// Bakes must be byte-identical run to run: the UUID is replaced by one derived from the file's other
// bytes (FNV-1a), still a well-formed UUID.
void make_uuid_deterministic(const std::string& path) {
  std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
  std::vector<char> bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  constexpr size_t kAt = 8 + 4 + 4 + 4 + 1, kLength = 36;
  if (!f.good() && !f.eof()) throw OutputError(path + ": cannot read back");
  if (bytes.size() < kAt + kLength || bytes[kAt + 8] != '-') throw OutputError(path + ": unexpected OpenVDB header");
  uint64_t h[2] = {0xcbf29ce484222325ull, 0x84222325cbf29ce4ull};
  for (size_t k = 0; k < bytes.size(); ++k) {
    if (k >= kAt && k < kAt + kLength) continue;
    h[k & 1] = (h[k & 1] ^ uint8_t(bytes[k])) * 0x100000001b3ull;
  }
  char uuid[40];
  std::snprintf(uuid, sizeof uuid, "%08llx-%04llx-4%03llx-8%03llx-%012llx", (unsigned long long)(h[0] >> 32),
                (unsigned long long)((h[0] >> 16) & 0xffff), (unsigned long long)(h[0] & 0xfff),
                (unsigned long long)((h[1] >> 48) & 0xfff), (unsigned long long)(h[1] & 0xffffffffffffull));
  f.clear();
  f.seekp(std::streamoff(kAt));
  f.write(uuid, kLength);
  if (!f) throw OutputError(path + ": cannot write");
}

}  // namespace

struct ExtinctionGrid::Impl {
  openvdb::FloatGrid::Ptr grid;
  Vec3 origin;        // world position of voxel (0,0,0)'s lower corner
  double voxel = 1;   // m
  int lo[3] = {0, 0, 0}, hi[3] = {-1, -1, -1};  // active voxels, inclusive (empty: hi < lo)

  void finish() {
    const openvdb::CoordBBox box = grid->evalActiveVoxelBoundingBox();
    if (grid->activeVoxelCount() == 0) return;
    for (int k = 0; k < 3; ++k) {
      lo[k] = box.min()[k];
      hi[k] = box.max()[k];
    }
  }
  bool empty() const { return hi[0] < lo[0]; }
};

ExtinctionGrid::ExtinctionGrid() : impl_(std::make_unique<Impl>()) {}
ExtinctionGrid::~ExtinctionGrid() = default;
ExtinctionGrid::ExtinctionGrid(ExtinctionGrid&&) noexcept = default;
ExtinctionGrid& ExtinctionGrid::operator=(ExtinctionGrid&&) noexcept = default;

double ExtinctionGrid::choose_voxel_size(const std::vector<VolumeBox>& boxes) {
  double smallest = INFINITY, volume = 0;
  for (const VolumeBox& b : boxes) {
    const Vec3 d = b.bounds.diagonal();
    smallest = std::min({smallest, d.x, d.y, d.z});
    volume += d.x * d.y * d.z;
  }
  if (boxes.empty() || !(smallest > 0)) return 1.0;
  return std::max(smallest / 2.0, std::cbrt(volume / double(1 << 24)));
}

ExtinctionGrid ExtinctionGrid::build(const std::vector<VolumeBox>& boxes, double voxel_size) {
  initialize_openvdb();
  ExtinctionGrid out;
  Impl& g = *out.impl_;
  g.voxel = voxel_size;
  Bounds all;
  for (const VolumeBox& b : boxes) all.extend(b.bounds);
  g.origin = all.empty() ? Vec3{} : all.lo;
  g.grid = openvdb::FloatGrid::create(0.0f);
  g.grid->setName(kGridName);
  g.grid->setGridClass(openvdb::GRID_FOG_VOLUME);
  // Index (i, j, k) is the voxel whose centre is origin + (i + ½, j + ½, k + ½) h.
  openvdb::math::Transform::Ptr xform = openvdb::math::Transform::createLinearTransform(voxel_size);
  xform->postTranslate(openvdb::Vec3d(g.origin.x + 0.5 * voxel_size, g.origin.y + 0.5 * voxel_size, g.origin.z + 0.5 * voxel_size));
  g.grid->setTransform(xform);
  auto acc = g.grid->getAccessor();
  for (const VolumeBox& b : boxes) {
    if (!(b.kappa > 0)) continue;
    int first[3], last[3];
    for (int k = 0; k < 3; ++k) {
      first[k] = int(std::floor((b.bounds.lo[k] - g.origin[k]) / voxel_size));
      last[k] = int(std::ceil((b.bounds.hi[k] - g.origin[k]) / voxel_size)) - 1;
      last[k] = std::max(last[k], first[k]);
    }
    // Each voxel gets κ × the fraction of it the box covers.
    auto cover = [&](int axis, int i) {
      const double a = g.origin[axis] + i * voxel_size, c = a + voxel_size;
      const double lo = std::max(a, b.bounds.lo[axis]), hi = std::min(c, b.bounds.hi[axis]);
      if (b.bounds.hi[axis] <= b.bounds.lo[axis]) return 0.0;
      return std::max(0.0, hi - lo) / voxel_size;
    };
    for (int i = first[0]; i <= last[0]; ++i)
      for (int j = first[1]; j <= last[1]; ++j)
        for (int k = first[2]; k <= last[2]; ++k) {
          const double f = cover(0, i) * cover(1, j) * cover(2, k);
          if (f <= 0) continue;
          const openvdb::Coord c(i, j, k);
          acc.setValue(c, float(double(acc.getValue(c)) + b.kappa * f));
        }
  }
  g.finish();
  return out;
}

void ExtinctionGrid::write(const std::string& path, const std::map<std::string, std::string>& metadata) const {
  initialize_openvdb();
  openvdb::FloatGrid::Ptr grid = impl_->grid ? impl_->grid->deepCopy() : openvdb::FloatGrid::create(0.0f);
  grid->setName(kGridName);
  grid->insertMeta("walkrad:kappa_units", openvdb::StringMetadata("1/m"));
  grid->insertMeta("walkrad:length_units", openvdb::StringMetadata("m"));
  grid->insertMeta("walkrad:formula", openvdb::StringMetadata("kappa = A / (4 V) per finest volume cluster"));
  for (const auto& [key, value] : metadata) grid->insertMeta("walkrad:" + key, openvdb::StringMetadata(value));
  try {
    openvdb::io::File file(path);
    file.write(openvdb::GridCPtrVec{grid});
    file.close();
  } catch (const std::exception& e) {
    throw OutputError(path + ": cannot write the extinction grid (" + e.what() + ")");
  }
  make_uuid_deterministic(path);
}

ExtinctionGrid ExtinctionGrid::read(const std::string& path) {
  initialize_openvdb();
  ExtinctionGrid out;
  Impl& g = *out.impl_;
  try {
    openvdb::io::File file(path);
    file.open();
    openvdb::GridBase::Ptr base = file.readGrid(kGridName);
    file.close();
    g.grid = openvdb::gridPtrCast<openvdb::FloatGrid>(base);
  } catch (const std::exception& e) {
    throw InputError(path, "", std::string("not a readable OpenVDB file with a grid named 'extinction' (") + e.what() + ")");
  }
  if (!g.grid) throw InputError(path, kGridName, "the grid is not a float grid");
  const openvdb::Vec3d size = g.grid->voxelSize();
  if (!g.grid->transform().isLinear() || size[0] <= 0 || size[0] != size[1] || size[0] != size[2])
    throw InputError(path, kGridName, "expected uniform cubic voxels");
  g.voxel = size[0];
  const openvdb::Vec3d centre = g.grid->indexToWorld(openvdb::Vec3d(0, 0, 0));
  g.origin = Vec3(centre[0], centre[1], centre[2]) - Vec3(1, 1, 1) * (0.5 * g.voxel);
  g.finish();
  return out;
}

std::string ExtinctionGrid::metadata(const std::string& key) const {
  if (!impl_->grid) return "";
  const openvdb::Metadata::ConstPtr m = (*impl_->grid)["walkrad:" + key];
  return m ? m->str() : "";
}

bool ExtinctionGrid::empty() const { return !impl_->grid || impl_->empty(); }

double ExtinctionGrid::optical_depth(const Vec3& from, const Vec3& to) const {
  const Impl& g = *impl_;
  if (empty()) return 0.0;
  // In voxel units: voxel (i, j, k) is the cell [i, i+1) × [j, j+1) × [k, k+1).
  const Vec3 a = (from - g.origin) / g.voxel, d = (to - from) / g.voxel;
  double t0 = 0, t1 = 1;
  for (int k = 0; k < 3; ++k) {  // clip to the active voxels' box (slabs)
    const double lo = g.lo[k], hi = g.hi[k] + 1.0;
    if (d[k] == 0) {
      if (a[k] < lo || a[k] >= hi) return 0.0;
      continue;
    }
    double ta = (lo - a[k]) / d[k], tb = (hi - a[k]) / d[k];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  if (!(t0 < t1)) return 0.0;
  // Amanatides & Woo: step from cell to cell, adding κ × the parameter length spent in each.
  const Vec3 p = a + d * t0;
  int cell[3], step[3];
  double next[3], delta[3];
  for (int k = 0; k < 3; ++k) {
    cell[k] = std::clamp(int(std::floor(p[k])), g.lo[k], g.hi[k]);
    step[k] = d[k] > 0 ? 1 : -1;
    if (d[k] == 0) {
      next[k] = delta[k] = INFINITY;
    } else {
      const double boundary = cell[k] + (d[k] > 0 ? 1.0 : 0.0);
      next[k] = t0 + (boundary - p[k]) / d[k];
      delta[k] = 1.0 / std::fabs(d[k]);
    }
  }
  // An unregistered accessor: the grid does not change while links are evaluated, and registering one
  // per segment with the tree (a concurrent hash map shared by every thread) would serialise them.
  openvdb::tree::ValueAccessor<const openvdb::FloatTree, /*IsSafe=*/false> acc(g.grid->constTree());
  double sum = 0, t = t0;
  const int limit = (g.hi[0] - g.lo[0]) + (g.hi[1] - g.lo[1]) + (g.hi[2] - g.lo[2]) + 4;
  for (int n = 0; n < limit; ++n) {
    const int axis = next[0] <= next[1] ? (next[0] <= next[2] ? 0 : 2) : (next[1] <= next[2] ? 1 : 2);
    const double end = std::min(next[axis], t1);
    if (end > t) sum += double(acc.getValue(openvdb::Coord(cell[0], cell[1], cell[2]))) * (end - t);
    if (next[axis] >= t1) break;
    t = next[axis];
    cell[axis] += step[axis];
    next[axis] += delta[axis];
    if (cell[axis] < g.lo[axis] || cell[axis] > g.hi[axis]) break;
  }
  return sum * length(to - from);
}

double ExtinctionGrid::transmittance(const Vec3& from, const Vec3& to) const { return std::exp(-optical_depth(from, to)); }

double ExtinctionGrid::value_at(const Vec3& p) const {
  if (!impl_->grid) return 0.0;
  const Vec3 u = (p - impl_->origin) / impl_->voxel;
  return double(impl_->grid->tree().getValue(openvdb::Coord(int(std::floor(u.x)), int(std::floor(u.y)), int(std::floor(u.z)))));
}

ExtinctionGrid::Stats ExtinctionGrid::stats() const {
  Stats s;
  s.voxel_size = impl_->voxel;
  if (empty()) return s;
  const Impl& g = *impl_;
  s.active_voxels = g.grid->activeVoxelCount();
  s.memory_bytes = g.grid->memUsage();
  s.kappa_min = INFINITY;
  for (auto it = g.grid->cbeginValueOn(); it; ++it) {
    const double v = double(*it);
    // A tile stands for many voxels of one value: min and max are what matter here.
    s.kappa_min = std::min(s.kappa_min, v);
    s.kappa_max = std::max(s.kappa_max, v);
  }
  s.bounds.extend(g.origin + Vec3(g.lo[0], g.lo[1], g.lo[2]) * g.voxel);
  s.bounds.extend(g.origin + Vec3(g.hi[0] + 1.0, g.hi[1] + 1.0, g.hi[2] + 1.0) * g.voxel);
  return s;
}

}  // namespace walkrad
