// read_mgf (mgf_reader.h): MGF entities → plain scene arrays. The parser keeps MGF's contexts
// (named vertices, colours and materials, the transform stack, the object depth) and hands faces
// to mgf_geometry.h; colours go through mgf_colour.h, transforms through mgf_transform.h.
// Semantics follow the MGF 1.1 specification (G. Ward, LBNL, 1996).
#include "walkrad/formats/mgf_reader.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <set>
#include <stdexcept>
#include <unordered_map>

#include "mgf_colour.h"
#include "mgf_geometry.h"
#include "input_limits.h"
#include "mgf_transform.h"
#include "walkrad/formats/error.h"

namespace walkrad {

namespace {

namespace fs = std::filesystem;
using mgf::Affine;
using mgf::Colour;
using mgf::Loop;

constexpr size_t kMaxIncludeDepth = 32;
constexpr long kMaxInstances = 1'000'000;  // array instances (and -i repeats) alive at once
// Entities handled in all, arrays' repeats included: nested arrays multiply, and a 1 KiB file could
// make 10^9 (fuzzing findings: 12 M in a 1.3 KiB file, 4 s; a 2.5 KiB file of nested arrays at the
// 2,000,000 this limit was, 0.47 s in Release and 7.4 s under ASan). The largest classic scenes here
// (the hospital, ../shared/scenes/mgf, and RenderPark's office1) handle about 67,000 and 59,000: the
// limit is 15 times that.
constexpr uint64_t kMaxHandled = 1'000'000;
constexpr size_t kMaxFaceVertices = 4096;  // ear clipping is quadratic; MGF lines hold 4096 characters

// One entity: its keyword and arguments, and the line it starts on.
struct Entity {
  uint32_t line = 0;
  std::vector<std::string> args;
};
struct ParsedFile {
  std::string path;
  std::vector<Entity> entities;
};

// Lines joined at a trailing backslash, split at white space; comments (#) dropped.
std::unique_ptr<ParsedFile> load(const std::string& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return nullptr;  // a device or FIFO could block or never end
  input_limits::check_regular_file(path, input_limits::kMaxBinaryBytes, "MGF file");
  std::ifstream in(path, std::ios::binary);
  if (!in) return nullptr;
  auto file = std::make_unique<ParsedFile>();
  file->path = path;
  std::string line, text;
  uint32_t number = 0, start = 0;
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (text.empty()) start = number;
    if (!line.empty() && line.back() == '\\') {
      line.back() = ' ';
      text += line;
      continue;
    }
    text += line;
    Entity e;
    e.line = start;
    size_t i = 0;
    while (i < text.size()) {
      while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
      size_t j = i;
      while (j < text.size() && !std::isspace(static_cast<unsigned char>(text[j]))) ++j;
      if (j > i) e.args.push_back(text.substr(i, j - i));
      i = j;
    }
    text.clear();
    if (!e.args.empty() && e.args[0][0] != '#') file->entities.push_back(std::move(e));
  }
  return file;
}

bool is_name(const std::string& s) {
  if (s.empty() || !(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_')) return false;
  return std::all_of(s.begin(), s.end(), [](char c) { return std::isgraph(static_cast<unsigned char>(c)); });
}

struct VertexContext {
  Vec3 p, n;  // n: unit, or zero when not given
};

struct MaterialContext {
  double rd = 0, td = 0, ed = 0, rs = 0, rs_a = 0, ts = 0, ts_a = 0, nr = 1, ni = 0;
  Colour rd_c, td_c, ed_c, rs_c, ts_c;
  int sides = 0;         // 0: not stated
  uint64_t version = 0;  // unique per state (see Reader::touch)
};

// A material as the scene holds it, for the faces made while its context is in one state.
struct Resolved {
  uint32_t index = 0;
  bool two_sided = false;
  bool emits = false;
};

// A transform context: an xf, or the transform of an include.
struct Frame {
  mgf::XfSpec spec;
  std::vector<long> index;  // the current instance of each array
  Affine world;             // parent's world ∘ spec.local(index)
  size_t resume = 0;        // the entity after the opening xf, where an array repeats from
};

class Reader {
 public:
  Reader(const MgfOptions& options, MgfStats& stats, Scene& scene, std::string folder)
      : options_(options), stats_(stats), scene_(scene), divisions_(mgf::quarter_divisions(options.tolerance)),
        folder_(std::move(folder)) {}

  void read(const std::string& path) {
    const ParsedFile* file = open(path);
    if (!file) throw InputError(path, "", "cannot open MGF file");
    stack_.push_back(canonical(path));
    run(*file);
    finish();
  }

 private:
  [[noreturn]] void fail(const std::string& message, ExitCode code = kExitBadInput) const {
    throw InputError(file_->path, "line " + std::to_string(entity_->line), message, code);
  }
  const std::string& keyword() const { return entity_->args[0]; }
  std::string where() const { return file_->path + ":" + std::to_string(entity_->line); }

  static std::string canonical(const std::string& path) {
    std::error_code ec;
    const fs::path c = fs::weakly_canonical(path, ec);
    return ec ? fs::path(path).lexically_normal().string() : c.string();
  }

  const ParsedFile* open(const std::string& path) {
    const std::string key = canonical(path);
    auto it = files_.find(key);
    if (it == files_.end()) {
      std::unique_ptr<ParsedFile> f = load(path);
      if (!f) return nullptr;
      it = files_.emplace(key, std::move(f)).first;
    }
    ++stats_.files;
    return it->second.get();
  }

  // ---- argument checks ------------------------------------------------------------------------
  void count(size_t lo, size_t hi) const {  // arguments after the keyword
    const size_t n = entity_->args.size() - 1;
    if (n < lo || n > hi) {
      const std::string want = lo == hi ? std::to_string(lo) : hi == SIZE_MAX ? "at least " + std::to_string(lo)
                                                                              : std::to_string(lo) + " to " + std::to_string(hi);
      const bool one = lo == 1 && (hi == 1 || hi == SIZE_MAX);
      fail(keyword() + ": expected " + want + " argument" + (one ? "" : "s") + ", got " + std::to_string(n));
    }
  }
  double number(size_t i) const {
    double v = 0;
    if (!mgf::parse_number(entity_->args[i], v)) fail(keyword() + ": '" + entity_->args[i] + "' is not a number");
    return v;
  }
  const VertexContext& vertex(const std::string& name) const {
    const auto it = vertices_.find(name);
    if (it == vertices_.end()) fail(keyword() + ": undefined vertex '" + name + "'");
    return it->second;
  }
  void touch(MaterialContext& m) { m.version = ++versions_; }

  // ---- the entity loop ------------------------------------------------------------------------
  void run(const ParsedFile& file) {
    const ParsedFile* outer_file = file_;
    const Entity* outer_entity = entity_;
    file_ = &file;
    const size_t frames_at_entry = frames_.size();
    bool warned_open = false;
    size_t k = 0;
    while (true) {
      for (; k < file.entities.size(); ++k) {
        entity_ = &file.entities[k];
        if (++handled_ > kMaxHandled)
          fail("arrays repeat the file's entities more than " + std::to_string(kMaxHandled) + " times", kExitLimitReached);
        const std::string& kw = keyword();
        if (kw == "xf") {
          ++stats_.entities[kw];
          if (entity_->args.size() > 1) push_frame(1, k + 1);
          else if (frames_.size() == frames_at_entry) fail("xf: end of a transform that was not begun in this file");
          else if (advance(frames_.back())) k = frames_.back().resume - 1;
          else frames_.pop_back();
        } else {
          handle();
        }
      }
      if (frames_.size() == frames_at_entry) break;
      // Transforms left open at the end of the file end there (arrays still repeat).
      if (!warned_open) warnings_.push_back(file.path + ": transform (xf) left open at the end of the file, closed there");
      warned_open = true;
      if (advance(frames_.back())) k = frames_.back().resume;
      else frames_.pop_back();
    }
    file_ = outer_file;
    entity_ = outer_entity;
  }

  // Pushes the transform given by the current entity's arguments from `first` on.
  void push_frame(size_t first, size_t resume) {
    Frame f;
    std::string why;
    if (!mgf::parse_xf(entity_->args, first, kMaxInstances, f.spec, why)) fail(keyword() + ": " + why);
    double alive = f.spec.instances();
    for (const Frame& g : frames_) alive *= g.spec.instances();
    if (alive > double(kMaxInstances))
      fail(keyword() + ": arrays make more than " + std::to_string(kMaxInstances) + " instances", kExitLimitReached);
    f.index.assign(f.spec.arrays.size(), 0);
    f.resume = resume;
    f.world = compose(world(), f.spec.local(f.index));
    frames_.push_back(std::move(f));
  }
  const Affine& world() const { return frames_.empty() ? identity_ : frames_.back().world; }

  // Next array instance (the last array fastest); false when there is none.
  bool advance(Frame& f) {
    for (size_t d = f.index.size(); d-- > 0;) {
      if (++f.index[d] < f.spec.arrays[d]) {
        const Affine& parent = frames_.size() > 1 ? frames_[frames_.size() - 2].world : identity_;
        f.world = compose(parent, f.spec.local(f.index));
        return true;
      }
      f.index[d] = 0;
    }
    return false;
  }

  void handle() {
    const std::string& kw = keyword();
    static const std::set<std::string> known = {"c", "cxy", "cspec", "cct", "cmix", "m", "sides", "rd", "td", "ed",
                                                "rs", "ts", "ir", "v", "p", "n", "f", "fh", "sph", "cyl", "cone",
                                                "ring", "torus", "prism", "i", "o", "ies"};
    if (!known.count(kw)) {
      auto& u = unknown_[kw];
      if (u.first++ == 0) u.second = where();
      return;
    }
    ++stats_.entities[kw];
    if (kw == "c") colour_context();
    else if (kw == "cxy" || kw == "cspec" || kw == "cct" || kw == "cmix") colour_value();
    else if (kw == "m") material_context();
    else if (kw == "sides" || kw == "rd" || kw == "td" || kw == "ed" || kw == "rs" || kw == "ts" || kw == "ir")
      material_value();
    else if (kw == "v") vertex_context();
    else if (kw == "p" || kw == "n") vertex_value();
    else if (kw == "f") face();
    else if (kw == "fh") face_with_holes();
    else if (kw == "i") include();
    else if (kw == "o") object();
    else if (kw == "ies") luminaire();
    else primitive();
  }

  // ---- contexts: c, m, v share one grammar: "X", "X name", "X name =", "X name = template" -----
  template <typename T>
  T* context(std::unordered_map<std::string, T>& table, T& unnamed, const char* what) {
    count(0, 3);
    const auto& a = entity_->args;
    if (a.size() == 1) {
      unnamed = T{};
      return &unnamed;
    }
    if (!is_name(a[1])) fail(keyword() + ": '" + a[1] + "' is not a name (a letter, then printing characters)");
    if (a.size() == 2) {
      const auto it = table.find(a[1]);
      if (it == table.end()) fail(keyword() + ": undefined " + what + " '" + a[1] + "'");
      return &it->second;
    }
    if (a[2] != "=") fail(keyword() + ": expected '=' after the name, got '" + a[2] + "'");
    T value{};
    if (a.size() == 4) {
      const auto it = table.find(a[3]);
      if (it == table.end()) fail(keyword() + ": undefined " + what + " '" + a[3] + "' as template");
      value = it->second;
    }
    T& slot = table[a[1]];
    slot = value;
    return &slot;
  }

  void colour_context() { colour_ = context(colours_, unnamed_colour_, "colour"); }

  void colour_value() {
    const std::string& kw = keyword();
    const auto& a = entity_->args;
    if (kw == "cxy") {
      count(2, 2);
      const double x = number(1), y = number(2);
      if (x < 0 || y < 0 || x + y > 1) fail("cxy: chromaticity (" + a[1] + ", " + a[2] + ") needs x >= 0, y >= 0, x + y <= 1");
      *colour_ = mgf::colour_from_xy(x, y);
    } else if (kw == "cspec") {
      count(4, SIZE_MAX);
      const double lmin = number(1), lmax = number(2);
      if (!(lmin < lmax)) fail("cspec: the wavelength range must increase");
      std::vector<double> samples;
      // Negative samples are allowed (CIE daylight basis functions have them), as in MGF's parser.
      for (size_t i = 3; i < a.size(); ++i) samples.push_back(number(i));
      if (!mgf::colour_from_spectrum(lmin, lmax, samples, *colour_))
        fail("cspec: the spectrum has no positive sum or no luminance in 380-780 nm");
    } else if (kw == "cct") {
      count(1, 1);
      if (!mgf::colour_from_temperature(number(1), *colour_)) fail("cct: temperature must lie in [1000, 100000] K");
    } else {  // cmix w1 c1 w2 c2 ...
      count(4, SIZE_MAX);
      if ((a.size() - 1) % 2) fail("cmix: expected weight and colour pairs");
      std::vector<std::pair<double, Colour>> parts;
      double sum = 0;
      for (size_t i = 1; i < a.size(); i += 2) {
        const double w = number(i);
        if (w < 0) fail("cmix: negative weight '" + a[i] + "'");
        const auto it = colours_.find(a[i + 1]);
        if (it == colours_.end()) fail("cmix: undefined colour '" + a[i + 1] + "'");
        parts.emplace_back(w, it->second);
        sum += w;
      }
      if (!(sum > 0)) fail("cmix: the weights sum to zero");
      *colour_ = mgf::colour_mix(parts);
    }
  }

  void material_context() {
    material_ = context(materials_, unnamed_material_, "material");
    material_name_ = entity_->args.size() > 1 ? entity_->args[1] : "";
    touch(*material_);
  }

  void material_value() {
    const std::string& kw = keyword();
    MaterialContext& m = *material_;
    auto fraction = [&](size_t i) {
      const double v = number(i);
      if (v < 0 || v > 1) fail(kw + ": '" + entity_->args[i] + "' must lie in [0, 1]");
      return v;
    };
    if (kw == "sides") {
      count(1, 1);
      long s = 0;
      if (!mgf::parse_integer(entity_->args[1], s) || (s != 1 && s != 2)) fail("sides: expected 1 or 2, got '" + entity_->args[1] + "'");
      m.sides = int(s);
    } else if (kw == "rd" || kw == "td") {
      count(1, 1);
      (kw == "rd" ? m.rd : m.td) = fraction(1);
      (kw == "rd" ? m.rd_c : m.td_c) = *colour_;
    } else if (kw == "ed") {
      count(1, 1);
      m.ed = number(1);
      if (m.ed < 0) fail("ed: emittance must not be negative");
      m.ed_c = *colour_;
    } else if (kw == "rs" || kw == "ts") {
      count(2, 2);
      const double v = fraction(1), roughness = number(2);
      if (roughness < 0) fail(kw + ": roughness must not be negative");
      if (kw == "rs") { m.rs = v; m.rs_a = roughness; m.rs_c = *colour_; }
      else { m.ts = v; m.ts_a = roughness; m.ts_c = *colour_; }
    } else {  // ir
      count(2, 2);
      m.nr = number(1);
      m.ni = number(2);
      if (m.nr <= 0) fail("ir: the index of refraction must be positive");
    }
    touch(m);
  }

  void vertex_context() { vertex_ = context(vertices_, unnamed_vertex_, "vertex"); }

  void vertex_value() {
    count(3, 3);
    const Vec3 v{number(1), number(2), number(3)};
    if (keyword() == "p") vertex_->p = v;
    else vertex_->n = normalize(v);
  }

  void object() {
    count(0, 1);
    if (entity_->args.size() == 2) ++objects_;
    else if (objects_ == 0) fail("o: end of an object that was not begun");
    else --objects_;
  }

  // ies pathname [-m multiplier] [transform]: an IES luminaire at the origin of its transform, its
  // web's zero point along −Z and type C's horizontal angle 0 along +X (the MGF spec; ies.h). The
  // candela become W/sr as ed's lm/m² become W/m² (÷ kWhiteEfficacy), in the current colour.
  // The file an entity names (relative to the file that holds it), refused outside the input folder.
  std::string referenced_file(const char* keyword) {
    fs::path target(entity_->args[1]);
    if (target.is_relative()) target = fs::path(file_->path).parent_path() / target;
    const std::string path = target.lexically_normal().string();
    if (const std::string why = input_limits::outside(path, folder_); !why.empty()) fail(std::string(keyword) + ": '" + path + "' " + why);
    return path;
  }

  void luminaire() {
    count(1, SIZE_MAX);
    const std::string path = referenced_file("ies");
    size_t first = 2;
    double multiplier = 1;
    if (entity_->args.size() > 2 && entity_->args[2] == "-m") {
      if (entity_->args.size() < 4) fail("ies: -m needs a multiplier");
      multiplier = number(3);
      if (!(multiplier >= 0) || !std::isfinite(multiplier)) fail("ies: the multiplier must be finite and not negative");
      first = 4;
    }
    std::shared_ptr<const IesProfile>& profile = profiles_[canonical(path)];
    if (!profile) profile = std::make_shared<const IesProfile>(read_ies(path));
    const size_t frames_before = frames_.size();
    if (entity_->args.size() > first) push_frame(first, 0);
    do {
      const Affine& xf = world();
      PunctualLight l;
      l.type = PunctualLight::Type::ies;
      l.profile = profile;
      l.name = fs::path(path).stem().string() + "-" + std::to_string(scene_.lights.size());
      l.position = xf.point({0, 0, 0});
      const Vec3 direction = xf.point({0, 0, -1}) - l.position, up = xf.point({0, 1, 0}) - l.position;
      if (!(length(direction) > 0)) fail("ies: the luminaire's transform is degenerate");
      l.direction = normalize(direction);
      l.up = orthogonal_up(l.direction, up);
      if (l.up == Vec3{}) fail("ies: the luminaire's transform is degenerate");
      l.intensity = mgf::linear_srgb(*colour_, multiplier * profile->tilt_factor(l.direction, {0, 0, -1}) / mgf::kWhiteEfficacy);
      scene_.lights.push_back(l);
    } while (frames_.size() > frames_before && advance(frames_.back()));
    if (frames_.size() > frames_before) frames_.pop_back();
  }

  void include() {
    count(1, SIZE_MAX);
    const std::string path = referenced_file("i");
    const std::string key = canonical(path);
    if (std::find(stack_.begin(), stack_.end(), key) != stack_.end()) {
      std::string chain;
      for (const std::string& s : stack_) chain += fs::path(s).filename().string() + " → ";
      fail("i: include cycle: " + chain + fs::path(key).filename().string());
    }
    if (stack_.size() > kMaxIncludeDepth) fail("i: includes nested deeper than " + std::to_string(kMaxIncludeDepth), kExitLimitReached);
    const ParsedFile* file = open(path);
    if (!file) fail("i: cannot open included file '" + path + "'");
    const size_t frames_before = frames_.size();
    if (entity_->args.size() > 2) push_frame(2, 0);
    stack_.push_back(key);
    const Entity* at = entity_;
    do {
      run(*file);
      entity_ = at;
    } while (frames_.size() > frames_before && advance(frames_.back()) && (++stats_.files, true));
    if (frames_.size() > frames_before) frames_.pop_back();
    stack_.pop_back();
  }

  // ---- geometry -------------------------------------------------------------------------------
  Resolved resolve() {
    MaterialContext& m = *material_;
    const auto cached = resolved_.find(m.version);
    if (cached != resolved_.end()) return cached->second;
    Material mat;
    mat.name = material_name_.empty() ? "unnamed" : material_name_;
    bool desaturated_r = false, desaturated_e = false;
    mat.reflectance = mgf::linear_srgb(m.rd_c, m.rd, &desaturated_r);
    mat.emission = mgf::linear_srgb(m.ed_c, m.ed / mgf::kWhiteEfficacy, &desaturated_e);
    if (desaturated_r || desaturated_e) out_of_gamut_.insert(mat.name);
    if ((m.rd > 0 && mgf::is_black(m.rd_c)) || (m.ed > 0 && mgf::is_black(m.ed_c))) black_.insert(mat.name);
    // As read_gltf: rd 1 is kept (1 per channel at most), with a warning: the bake refuses a closed
    // scene where nothing absorbs. Channels in (0.99, 1) are capped at 0.99 (slow for nothing visible).
    const double most = m.rd >= 1 ? 1.0 : 0.99;
    if (max_component(mat.reflectance) > most) {
      mat.reflectance = {std::min(mat.reflectance.x, most), std::min(mat.reflectance.y, most), std::min(mat.reflectance.z, most)};
      if (m.rd < 1) capped_.insert(mat.name);
    }
    if (m.rd >= 1) absorbs_nothing_.insert(mat.name);
    if (m.rs > 0) ignored_["specular reflectance (rs)"].insert(mat.name);
    // ts with roughness 0: clear glass of the material's index (ir; 1.5 where not given), the rest of
    // specular transmission is not simulated.
    if (m.ts > 0 && m.ts_a == 0) {
      mat.clear = mgf::linear_srgb(m.ts_c, m.ts, &desaturated_r);
      mat.ior = m.nr > 1 ? m.nr : 1.5;
    } else if (m.ts > 0) {
      ignored_["rough specular transmittance (ts with roughness > 0)"].insert(mat.name);
    }
    mat.transmittance = mgf::linear_srgb(m.td_c, m.td, &desaturated_r);
    if (max_component(mat.reflectance + mat.transmittance) > 1 + 1e-9)
      fail("material '" + mat.name + "': rd + td exceed 1 (a surface cannot send on more light than it receives)");
    if (m.sides == 0) unstated_sides_.insert(mat.name);
    Resolved r;
    // A transmitting material's back side is its transmission twin (added by the pipeline).
    r.two_sided = (m.sides ? m.sides : options_.default_sides) == 2 && !mat.transmits();
    r.emits = mat.emits();
    // The same name and values: the same scene material. The same name with other values (a
    // redefined material) gets a suffix.
    int variant = 1;
    for (size_t i = 0; i < scene_.materials.size(); ++i) {
      const Material& s = scene_.materials[i];
      if (base_names_[i] != mat.name) continue;
      if (s.reflectance == mat.reflectance && s.emission == mat.emission) {
        r.index = uint32_t(i);
        return resolved_[m.version] = r;
      }
      ++variant;
    }
    base_names_.push_back(mat.name);
    if (variant > 1) mat.name += "#" + std::to_string(variant);
    scene_.materials.push_back(mat);
    r.index = uint32_t(scene_.materials.size() - 1);
    return resolved_[m.version] = r;
  }

  // Transforms faces given in the current vertex frame and adds their polygons.
  void emit(const std::vector<Loop>& faces, bool primitive) {
    const Resolved r = resolve();
    const Affine& xf = world();
    const bool mirrored = xf.det() < 0;
    if (primitive) {
      ++stats_.primitives;
      stats_.emitting_primitives += r.emits;
    } else {
      ++stats_.faces;
      stats_.emitting_faces += r.emits;
    }
    for (const Loop& local : faces) {
      Loop w;
      w.reserve(local.size());
      for (const Vec3& p : local) {
        w.push_back(xf.point(p));
        if (!is_valid_vertex(w.back())) fail(keyword() + ": a vertex is not finite or lies beyond ±1e9 m after the transform");
      }
      if (mirrored) std::reverse(w.begin(), w.end());  // a mirror turns the right-hand rule around
      const mgf::SplitResult s = mgf::split_face(w);
      if (s.degenerate) ++scene_.dropped_degenerate;
      nonplanar_ += s.nonplanar;
      untriangulated_ += s.untriangulated;
      for (const Loop& piece : s.pieces) {
        Polygon poly;
        poly.count = uint8_t(piece.size());
        std::copy(piece.begin(), piece.end(), poly.v.begin());
        poly.material = r.index;
        poly.source = entity_->line;
        scene_.polygons.push_back(poly);
        if (r.two_sided) {
          std::reverse(poly.v.begin(), poly.v.begin() + poly.count);
          scene_.polygons.push_back(poly);
          ++stats_.back_polygons;
        }
      }
    }
    if (scene_.polygons.size() > options_.max_polygons)
      fail("the scene has more than " + std::to_string(options_.max_polygons) + " polygons", kExitLimitReached);
  }

  Loop positions(size_t first, size_t last) const {
    Loop l;
    for (size_t i = first; i < last; ++i) l.push_back(vertex(entity_->args[i]).p);
    return l;
  }

  void vertex_limit() const {
    if (entity_->args.size() - 1 > kMaxFaceVertices)
      fail(keyword() + ": more than " + std::to_string(kMaxFaceVertices) + " vertices", kExitLimitReached);
  }

  void face() {
    count(3, SIZE_MAX);
    vertex_limit();
    emit({positions(1, entity_->args.size())}, false);
  }

  void face_with_holes() {
    count(3, SIZE_MAX);
    vertex_limit();
    const auto& a = entity_->args;
    std::vector<Loop> contours(1);
    for (size_t i = 1; i < a.size(); ++i) {
      if (a[i][0] == '-') contours.emplace_back();
      else contours.back().push_back(vertex(a[i]).p);
    }
    for (const Loop& c : contours)
      if (c.size() < 3) fail("fh: the outline and each hole need at least 3 vertices");
    if (contours.size() == 1) return emit(contours, false);
    Loop joined;
    std::string why;
    if (!mgf::join_holes(contours[0], {contours.begin() + 1, contours.end()}, joined, why)) fail("fh: " + why);
    emit({joined}, false);
  }

  void primitive() {
    const std::string& kw = keyword();
    const auto& a = entity_->args;
    std::vector<Loop> faces;
    if (kw == "sph") {
      count(2, 2);
      const double r = number(2);
      if (r == 0) fail("sph: the radius must not be 0");
      mgf::tessellate_sphere(vertex(a[1]).p, r, divisions_, faces);
    } else if (kw == "cyl" || kw == "cone") {
      const bool cyl = kw == "cyl";
      count(cyl ? 3 : 4, cyl ? 3 : 4);
      const Vec3 p1 = vertex(a[1]).p, p2 = vertex(a[3]).p;
      const double r1 = number(2), r2 = cyl ? r1 : number(4);
      if (r1 == 0 && r2 == 0) fail(kw + ": the radii must not both be 0");
      if ((r1 < 0 && r2 > 0) || (r1 > 0 && r2 < 0)) fail(kw + ": the radii must not have opposite signs");
      if (p1 == p2) fail(kw + ": the two end vertices coincide");
      mgf::tessellate_cone(p1, r1, p2, r2, divisions_, faces);
    } else if (kw == "ring" || kw == "torus") {
      count(3, 3);
      const VertexContext& c = vertex(a[1]);
      if (c.n == Vec3{}) fail(kw + ": the centre vertex '" + a[1] + "' needs a normal (n)");
      const double rmin = number(2), rmax = number(3);
      if (kw == "ring") {
        if (rmin < 0 || rmax <= rmin) fail("ring: the radii must satisfy 0 <= rmin < rmax");
        mgf::tessellate_ring(c.p, c.n, rmin, rmax, divisions_, faces);
      } else {
        const double sign = rmin != 0 ? (rmin > 0 ? 1 : -1) : (rmax > 0 ? 1 : -1);
        if ((rmin == 0 && rmax == 0) || sign * (rmax - rmin) <= 0 || (rmin != 0 && (rmin > 0) != (rmax > 0)))
          fail("torus: the radii must satisfy 0 <= rmin < rmax (both negated for an inward torus)");
        mgf::tessellate_torus(c.p, c.n, rmin, rmax, divisions_, faces);
      }
    } else {  // prism v1 v2 v3 ... length
      count(4, SIZE_MAX);
      vertex_limit();
      const double length = number(a.size() - 1);
      if (length == 0) fail("prism: the length must not be 0");
      const Loop base = positions(1, a.size() - 1);
      Vec3 an;
      for (size_t i = 0; i < base.size(); ++i) an += cross(base[i], base[(i + 1) % base.size()]);
      if (an == Vec3{}) fail("prism: the base has no area");
      mgf::tessellate_prism(base, length, faces);
    }
    emit(faces, true);
  }

  // ---- the end: warnings --------------------------------------------------------------------
  static std::string some(const std::set<std::string>& names) {
    std::string s;
    size_t i = 0;
    for (const std::string& n : names) {
      if (i == 3) return s + ", ...";
      s += (i++ ? ", " : "") + n;
    }
    return s;
  }

  void finish() {
    std::vector<std::string>& w = scene_.warnings;
    for (const auto& [kw, u] : unknown_)
      w.push_back(std::to_string(u.first) + " unknown '" + kw + "' entit" + (u.first == 1 ? "y" : "ies") +
                  " skipped (first at " + u.second + ")");
    if (objects_) w.push_back(std::to_string(objects_) + " objects (o) left open at the end");
    w.insert(w.end(), warnings_.begin(), warnings_.end());
    if (!unstated_sides_.empty() && options_.default_sides == 1)
      w.push_back(std::to_string(unstated_sides_.size()) +
                  " materials do not state 'sides': read as one-sided, as RenderPark does (MGF's default is two-sided: --mgf-sides 2)");
    for (const auto& [what, names] : ignored_)
      w.push_back(what + " ignored in " + std::to_string(names.size()) + " materials (" + some(names) +
                  "): walkrad's materials are diffuse");
    if (!capped_.empty())
      w.push_back("reflectance capped at 0.99 in " + std::to_string(capped_.size()) + " materials (" + some(capped_) + ")");
    if (!absorbs_nothing_.empty())
      w.push_back("rd 1 in " + std::to_string(absorbs_nothing_.size()) + " materials (" + some(absorbs_nothing_) +
                  "): they absorb nothing, so the scene needs light to escape or other surfaces to absorb it (the bake checks)");
    if (!black_.empty())
      w.push_back(std::to_string(black_.size()) + " materials take a colour with chromaticity y = 0, which has no luminance: " +
                  "black, as in RenderPark (" + some(black_) + ")");
    if (!out_of_gamut_.empty())
      w.push_back(std::to_string(out_of_gamut_.size()) + " materials have colours outside the sRGB gamut, desaturated (" +
                  some(out_of_gamut_) + ")");
    if (scene_.dropped_degenerate) w.push_back(std::to_string(scene_.dropped_degenerate) + " faces without area dropped");
    if (nonplanar_) w.push_back(std::to_string(nonplanar_) + " non-planar faces split into triangles");
    if (untriangulated_)
      w.push_back(std::to_string(untriangulated_) + " self-intersecting faces only partly triangulated");
    if (scene_.polygons.empty()) throw InputError(scene_.source, "", "the scene has no faces");
  }

  const MgfOptions& options_;
  const std::string folder_;  // where includes and IES profiles may lie (MgfOptions::input_folder)
  MgfStats& stats_;
  uint64_t handled_ = 0;  // entities handled, repeats included (kMaxHandled)
  Scene& scene_;
  const int divisions_;
  const Affine identity_{};

  std::unordered_map<std::string, std::unique_ptr<ParsedFile>> files_;  // by canonical path
  std::vector<std::string> stack_;                                       // the include chain
  const ParsedFile* file_ = nullptr;
  const Entity* entity_ = nullptr;
  std::vector<Frame> frames_;
  int objects_ = 0;

  std::unordered_map<std::string, VertexContext> vertices_;
  std::unordered_map<std::string, Colour> colours_;
  std::unordered_map<std::string, MaterialContext> materials_;
  VertexContext unnamed_vertex_;
  Colour unnamed_colour_;
  MaterialContext unnamed_material_;
  VertexContext* vertex_ = &unnamed_vertex_;
  Colour* colour_ = &unnamed_colour_;
  MaterialContext* material_ = &unnamed_material_;
  std::string material_name_;
  uint64_t versions_ = 0;
  std::unordered_map<uint64_t, Resolved> resolved_;  // by material version
  std::vector<std::string> base_names_;              // scene material → its MGF name

  std::map<std::string, std::pair<uint64_t, std::string>> unknown_;  // keyword → count, first place
  uint64_t nonplanar_ = 0, untriangulated_ = 0;
  std::unordered_map<std::string, std::shared_ptr<const IesProfile>> profiles_;  // IES files by canonical path
  std::vector<std::string> warnings_;
  std::set<std::string> unstated_sides_, capped_, out_of_gamut_, black_, absorbs_nothing_;
  std::map<std::string, std::set<std::string>> ignored_;
};

}  // namespace

Scene read_mgf(const std::string& path, const MgfOptions& options, MgfStats* stats) {
  if (!(options.tolerance >= 1e-4 && options.tolerance <= 0.5))
    throw std::invalid_argument("MGF tessellation tolerance must lie in [1e-4, 0.5]");
  if (options.default_sides != 1 && options.default_sides != 2) throw std::invalid_argument("MGF default sides must be 1 or 2");
  Scene scene;
  scene.source = path;
  scene.up = {0, 0, 1};  // MGF states no zenith; RenderPark's scenes but one have z up (--up for the others)
  MgfStats local;
  Reader(options, stats ? *stats : local, scene, input_limits::input_folder(path, options.input_folder)).read(path);
  return scene;
}

}  // namespace walkrad
