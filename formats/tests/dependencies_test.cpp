// What a read depended on (dependencies.h): every file a reader opens is in the ReadLog, each once, and
// nothing else; the depfile says so in Make's syntax, escaped, and is written whole.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "walkrad/formats/dependencies.h"
#include "walkrad/formats/mgf_reader.h"
#include "walkrad/formats/scene_reader.h"
#include "walkrad/formats/walkthrough.h"

namespace walkrad {
namespace {

namespace fs = std::filesystem;

const std::string kExamples = std::string(WALKRAD_SOURCE_DIR) + "/examples/";

std::string normal(const std::string& path) { return fs::absolute(path).lexically_normal().string(); }

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// The IES room's glTF refers to two profiles by uri: the scene and both are what it depends on.
TEST(ReadLog, ListsTheSceneAndEveryFileItRefersTo) {
  ReadLog log;
  const Scene s = read_scene(kExamples + "ies-room/ies-room.gltf");
  ASSERT_FALSE(s.lights.empty());
  EXPECT_EQ(log.files(), (std::vector<std::string>{normal(kExamples + "ies-room/ies-room.gltf"),
                                                    normal(kExamples + "ies-room/downlight.ies"),
                                                    normal(kExamples + "ies-room/wall-washer.ies")}));
}

// MGF includes, a luminaire's profile, a file included twice (listed once), a walkthrough; a log made
// inside another sees only what was read while it lived, and a finished log nothing more.
TEST(ReadLog, ListsMgfIncludesOnceAndNestsByLifetime) {
  const fs::path root = fs::temp_directory_path() / ("walkrad-read-log-" + std::to_string(::getpid()));
  fs::remove_all(root);
  fs::create_directories(root / "sub");
  auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream(root / name, std::ios::binary) << text;
    return (root / name).string();
  };
  write("part.mgf", "v a =\n\tp 0 0 0\nv b =\n\tp 1 0 0\nv c =\n\tp 0 1 0\nf a b c\n");
  write("lamp.ies", read_text(std::string(WALKRAD_SOURCE_DIR) + "/tests/fuzz/corpus/ies/c-rotational-downlight.ies"));
  write("sub/inner.mgf", "i ../part.mgf\nies ../lamp.ies\n");
  const std::string scene = write("scene.mgf", "i sub/inner.mgf\ni part.mgf\n");
  const std::string views = write("views.json", R"({"format": "walkrad-walkthrough", "version": 1, "path": {"frames": 2, "yfov_deg": 60, "aspect": 1.5,
    "keyframes": [{"time": 0, "position": [0, 0, 1], "target": [0, 0, 0]}, {"time": 1, "position": [0, 0, 2], "target": [0, 0, 0]}]}})");

  ReadLog outer;
  read_mgf(scene);
  std::vector<std::string> inner_files;
  {
    ReadLog inner;
    read_walkthrough(views);
    inner_files = inner.files();
  }
  EXPECT_EQ(inner_files, std::vector<std::string>{normal(views)});
  EXPECT_EQ(outer.files(), (std::vector<std::string>{normal(scene), normal((root / "sub/inner.mgf").string()),
                                                      normal((root / "part.mgf").string()),
                                                      normal((root / "lamp.ies").string()), normal(views)}));
  fs::remove_all(root);
}

TEST(Depfile, EscapesWhatMakeAndNinjaReadSpecially) {
  EXPECT_EQ(depfile_text("/b/level.bake/manifest.json", {"/s/a b.gltf", "/s/#1.bin", "/s/$x.ies"}),
            "/b/level.bake/manifest.json: \\\n  /s/a\\ b.gltf \\\n  /s/\\#1.bin \\\n  /s/$$x.ies\n");
  EXPECT_EQ(depfile_text("out", {}), "out:\n");
  EXPECT_THROW(depfile_text("out", {"/s/a\nb.gltf"}), std::invalid_argument);
}

TEST(Depfile, IsWrittenWholeThroughARename) {
  const fs::path path = fs::temp_directory_path() / ("walkrad-depfile-" + std::to_string(::getpid()) + ".d");
  write_depfile(path.string(), "out", {"/s/a.gltf"});
  EXPECT_EQ(read_text(path.string()), depfile_text("out", {"/s/a.gltf"}));
  EXPECT_FALSE(fs::exists(path.string() + ".tmp"));
  fs::remove(path);
}

}  // namespace
}  // namespace walkrad
