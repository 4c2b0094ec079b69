// The files a scene refers to are read only from its input folder (input_limits.h): a glTF buffer, an
// image and an IES profile by uri, an MGF include and an MGF luminaire's profile. Each loads inside the
// folder; outside it (by "..", an absolute path or a symbolic link) it is refused, naming the file,
// before anything opens it (an inotify watch on the outside file sees no open); a folder given by the
// caller admits it.
#include <sys/inotify.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "walkrad/formats/error.h"
#include "walkrad/formats/gltf_reader.h"
#include "walkrad/formats/mgf_reader.h"

namespace walkrad {
namespace {

namespace fs = std::filesystem;

const std::string kCorpus = std::string(WALKRAD_SOURCE_DIR) + "/tests/fuzz/corpus/";
const std::string kOutside = "lies outside the input folder";

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// Whether a file is opened while the watch lasts (inotify IN_OPEN): stat and realpath do not open it.
class OpenWatch {
 public:
  explicit OpenWatch(const std::string& path) : fd_(inotify_init1(IN_NONBLOCK)) {
    EXPECT_GE(fd_, 0);
    EXPECT_GE(inotify_add_watch(fd_, path.c_str(), IN_OPEN), 0) << path;
  }
  ~OpenWatch() { close(fd_); }
  bool opened() const {
    char events[4096];
    return read(fd_, events, sizeof events) > 0;
  }

 private:
  int fd_;
};

// A scene folder and a folder beside it that the scene must not read from.
class InputFolder : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("walkrad-input-folder-" + std::to_string(::getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_ / "scene");
    fs::create_directories(root_ / "outside");
  }
  void TearDown() override { fs::remove_all(root_); }

  std::string write(const std::string& at, const std::string& bytes) {
    const std::string path = (root_ / at).string();
    std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
    return path;
  }
  std::string dir(const std::string& at) const { return (root_ / at).string(); }

  // quad.glb's JSON, its BIN chunk written as `bin` and referred to by `uri` (.gltf in scene/).
  std::string gltf_with_buffer(const std::string& bin, const std::string& uri) {
    const std::string glb = read_text(kCorpus + "gltf/quad.glb");
    uint32_t json_length = 0, bin_length = 0;
    std::memcpy(&json_length, glb.data() + 12, 4);
    std::memcpy(&bin_length, glb.data() + 20 + json_length, 4);
    write(bin, glb.substr(20 + json_length + 8, bin_length));
    nlohmann::json g = nlohmann::json::parse(glb.substr(20, json_length));
    g["buffers"][0]["uri"] = uri;
    return write("scene/scene.gltf", g.dump());
  }

  // Expects read() refused with kExitBadInput, for `file`, saying why, without `watched` ever being
  // opened.
  template <typename Read>
  void expect_confined(Read&& read, const std::string& file, const std::string& watched,
                       const std::string& why = kOutside) {
    const OpenWatch watch(watched);
    try {
      read();
      ADD_FAILURE() << "read a file outside the input folder: " << watched;
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), file) << e.what();
      EXPECT_EQ(e.code(), kExitBadInput) << e.what();
      EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
      if (why == kOutside)  // the refusal names the way out
        EXPECT_NE(std::string(e.what()).find("--input-folder"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(watch.opened()) << watched << " was opened before it was refused";
  }

  fs::path root_;
};

TEST_F(InputFolder, ABufferIsReadOnlyFromTheScenesFolder) {
  const std::string inside = gltf_with_buffer("scene/quad.bin", "quad.bin");
  EXPECT_EQ(read_gltf(inside).polygons.size(), 3u);

  const std::string outside = dir("outside/quad.bin");
  const std::string up = gltf_with_buffer("outside/quad.bin", "../outside/quad.bin");
  expect_confined([&] { read_gltf(up); }, up, outside);
  // tinygltf joins an absolute uri to the glTF's folder, then to the working directory: neither reaches it.
  const std::string absolute = gltf_with_buffer("outside/quad.bin", outside);
  expect_confined([&] { read_gltf(absolute); }, absolute, outside, "File not found");
  // A symbolic link in the folder is followed to where it points.
  fs::create_symlink(outside, dir("scene/link.bin"));
  const std::string linked = gltf_with_buffer("outside/quad.bin", "link.bin");
  expect_confined([&] { read_gltf(linked); }, linked, outside);

  // A folder the caller names admits it, and the watch sees that read.
  const std::string g = gltf_with_buffer("outside/quad.bin", "../outside/quad.bin");
  const OpenWatch watch(outside);
  EXPECT_EQ(read_gltf(g, root_.string()).polygons.size(), 3u);
  EXPECT_TRUE(watch.opened());
}

TEST_F(InputFolder, AnImageIsReadOnlyFromTheScenesFolder) {
  // A 1 × 1 PNG of pure red: the texture's average times baseColorFactor (0.8, 0.5, 0.2).
  static const unsigned char kRed[] = {
      0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44, 0x52, 0x00, 0x00,
      0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x08, 0x02, 0x00, 0x00, 0x00, 0x90, 0x77, 0x53, 0xde, 0x00, 0x00, 0x00,
      0x0c, 0x49, 0x44, 0x41, 0x54, 0x78, 0x9c, 0x63, 0xf8, 0xcf, 0xc0, 0x00, 0x00, 0x03, 0x01, 0x01, 0x00, 0xc9,
      0xfe, 0x92, 0xef, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};
  const std::string png(reinterpret_cast<const char*>(kRed), sizeof kRed);
  write("scene/red.png", png);
  const std::string outside = write("outside/red.png", png);
  auto textured = [&](const std::string& uri) {
    nlohmann::json g = nlohmann::json::parse(read_text(kCorpus + "gltf/quad-embedded.gltf"));
    g["images"] = {{{"uri", uri}}};
    g["textures"] = {{{"source", 0}}};
    g["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 0}};
    return write("scene/textured.gltf", g.dump());
  };
  const Scene s = read_gltf(textured("red.png"));
  EXPECT_NEAR(s.materials[0].reflectance.x, 0.8, 1e-6);
  EXPECT_EQ(s.materials[0].reflectance.y, 0.0);
  const std::string g = textured("../outside/red.png");
  expect_confined([&] { read_gltf(g); }, g, outside);
}

TEST_F(InputFolder, AnIesProfileByUriIsReadOnlyFromTheScenesFolder) {
  const std::string ies = read_text(kCorpus + "ies/c-rotational-downlight.ies");
  write("scene/lamp.ies", ies);
  const std::string outside = write("outside/lamp.ies", ies);
  auto lit = [&](const std::string& uri) {
    nlohmann::json g = nlohmann::json::parse(read_text(kCorpus + "gltf/quad-ies-light.gltf"));
    g["extensions"]["EXT_lights_ies"]["lights"][0] = {{"uri", uri}};
    return write("scene/lit.gltf", g.dump());
  };
  EXPECT_EQ(read_gltf(lit("lamp.ies")).lights.size(), 1u);
  const std::string g = lit("../outside/lamp.ies");
  expect_confined([&] { read_gltf(g); }, g, outside);
}

TEST_F(InputFolder, MgfIncludesAndLuminairesAreReadOnlyFromTheScenesFolder) {
  const std::string face = "v a =\n\tp 0 0 0\nv b =\n\tp 1 0 0\nv c =\n\tp 0 1 0\nf a b c\n";
  write("scene/part.mgf", face);
  const std::string outside_part = write("outside/part.mgf", face);
  const std::string ies = read_text(kCorpus + "ies/c-rotational-downlight.ies");
  write("scene/lamp.ies", ies);
  const std::string outside_ies = write("outside/lamp.ies", ies);

  // Included by a file in a sub-folder: paths are relative to the including file, confined to the
  // scene file's folder.
  fs::create_directories(root_ / "scene/sub");
  write("scene/sub/inner.mgf", "i ../part.mgf\nies ../lamp.ies\n");
  const std::string inside = write("scene/inside.mgf", "i sub/inner.mgf\n");
  const Scene s = read_mgf(inside);
  EXPECT_EQ(s.polygons.size(), 1u);
  EXPECT_EQ(s.lights.size(), 1u);

  const std::string include = write("scene/include.mgf", "i ../outside/part.mgf\n");
  expect_confined([&] { read_mgf(include); }, include, outside_part);
  const std::string luminaire = write("scene/luminaire.mgf", face + "ies ../outside/lamp.ies\n");
  expect_confined([&] { read_mgf(luminaire); }, luminaire, outside_ies);

  MgfOptions wider;
  wider.input_folder = root_.string();
  EXPECT_EQ(read_mgf(include, wider).polygons.size(), 1u);
  EXPECT_EQ(read_mgf(luminaire, wider).lights.size(), 1u);
}

}  // namespace
}  // namespace walkrad
