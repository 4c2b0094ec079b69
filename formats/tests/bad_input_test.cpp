// Bad input is refused cleanly: every prefix of a .glb, lying GLB lengths, JSON
// nested too deep, node hierarchies that are not trees, NaN and out-of-range values, devices in
// place of files. Each refusal is an InputError naming the file, the place and the rule, with the
// documented exit code (README.md, "Exit codes"); limits give kExitLimitReached.
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "walkrad/formats/chunk.h"
#include "walkrad/formats/error.h"
#include "walkrad/formats/gltf_reader.h"
#include "walkrad/formats/manifest.h"
#include "walkrad/formats/mgf_reader.h"
#include "walkrad/formats/sky.h"
#include "walkrad/formats/walkthrough.h"

namespace walkrad {
namespace {

namespace fs = std::filesystem;
using Bytes = std::vector<char>;

const std::string kSeeds = std::string(WALKRAD_SOURCE_DIR) + "/tests/fuzz/corpus/";

Bytes read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return Bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

class BadInput : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("walkrad-bad-input-" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& name, const Bytes& bytes) {
    const std::string path = (dir_ / name).string();
    std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
    return path;
  }
  std::string write(const std::string& name, const std::string& text) { return write(name, Bytes(text.begin(), text.end())); }
  std::string write(const std::string& name, const nlohmann::json& j) { return write(name, j.dump()); }

  // Runs read, expects an InputError for `path` with `code` whose message holds every part.
  template <typename Read>
  void expect_refused(Read&& read, const std::string& path, ExitCode code, std::initializer_list<std::string> parts) {
    try {
      read();
      ADD_FAILURE() << "accepted " << path;
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), path) << e.what();
      EXPECT_EQ(e.code(), code) << e.what();
      for (const std::string& p : parts) EXPECT_NE(std::string(e.what()).find(p), std::string::npos) << e.what();
    }
  }

  fs::path dir_;
};

uint32_t u32_at(const Bytes& b, size_t at) {
  uint32_t v;
  std::memcpy(&v, b.data() + at, 4);
  return v;
}
void put_u32(Bytes& b, size_t at, uint32_t v) { std::memcpy(b.data() + at, &v, 4); }
// Offset of the BIN chunk's data in a .glb (after the JSON chunk).
size_t bin_data(const Bytes& glb) { return 20 + u32_at(glb, 12) + 8; }

TEST_F(BadInput, EveryPrefixOfAGlbIsRefused) {
  const Bytes glb = read_bytes(kSeeds + "gltf/quad.glb");
  ASSERT_GT(glb.size(), 1000u);
  EXPECT_NO_THROW(read_gltf(write("whole.glb", glb)));
  for (size_t n = 0; n < glb.size(); ++n) {
    const std::string path = write("prefix.glb", Bytes(glb.begin(), glb.begin() + long(n)));
    expect_refused([&] { read_gltf(path); }, path, kExitBadInput, {});
  }
}

TEST_F(BadInput, LyingGlbLengthsAreRefusedBeforeAllocation) {
  const Bytes glb = read_bytes(kSeeds + "gltf/quad.glb");
  // 20 bytes that claim a 4 GB file and a 4 GB JSON chunk.
  Bytes tiny(glb.begin(), glb.begin() + 20);
  put_u32(tiny, 8, 0xFFFFFFF0u);
  put_u32(tiny, 12, 0xFFFFFFD0u);
  const std::string t = write("tiny.glb", tiny);
  expect_refused([&] { read_gltf(t); }, t, kExitBadInput, {"GLB header", "differs from the file size 20"});

  Bytes json_long = glb;
  put_u32(json_long, 12, uint32_t(glb.size()));
  const std::string j = write("json-long.glb", json_long);
  expect_refused([&] { read_gltf(j); }, j, kExitBadInput, {"GLB chunk 0", "does not fit"});

  Bytes bin_long = glb;
  put_u32(bin_long, bin_data(glb) - 8, 0x7FFFFFF0u);
  const std::string b = write("bin-long.glb", bin_long);
  expect_refused([&] { read_gltf(b); }, b, kExitBadInput, {"GLB chunk 1", "exceeds"});

  // The JSON's buffer byteLength larger than the BIN chunk (same length of digits keeps the layout).
  Bytes buffer_long = glb;
  std::string text(buffer_long.begin() + 20, buffer_long.begin() + 20 + u32_at(glb, 12));
  const size_t at = text.find("\"buffers\":[{\"byteLength\":60}]");
  ASSERT_NE(at, std::string::npos) << text;
  text.replace(at, 29, "\"buffers\":[{\"byteLength\":99}]");
  std::copy(text.begin(), text.end(), buffer_long.begin() + 20);
  const std::string l = write("buffer-long.glb", buffer_long);
  expect_refused([&] { read_gltf(l); }, l, kExitBadInput, {"byteLength"});
}

TEST_F(BadInput, ChunkLengthsAreCheckedToo) {
  Bytes chunk = read_bytes(kSeeds + "chunk/quad-chunk.glb");
  put_u32(chunk, 8, uint32_t(chunk.size() + 4));
  const std::string c = write("chunk.glb", chunk);
  expect_refused([&] { read_chunk(c); }, c, kExitBadInput, {"GLB header"});
}

// Found by the fuzzer: tinygltf indexes a Draco primitive's bufferView unchecked; refused before.
TEST_F(BadInput, DracoReferencesAreCheckedBeforeTinygltf) {
  const std::string crasher = std::string(WALKRAD_SOURCE_DIR) + "/tests/fuzz/crashers/chunk/draco-missing-bufferview.glb";
  expect_refused([&] { read_chunk(crasher); }, crasher, kExitBadInput,
                 {"meshes[0].primitives[0].KHR_draco_mesh_compression", "bufferView does not exist"});
  // A Draco attribute id that the compressed mesh does not have (tinygltf would dereference null).
  const Bytes draco = read_bytes(kSeeds + "chunk/quad-draco.glb");
  std::string text(draco.begin() + 20, draco.begin() + 20 + u32_at(draco, 12));
  const std::string key = "KHR_draco_mesh_compression\":{\"attributes\":{\"COLOR_0\":";
  const size_t at = text.find(key);
  ASSERT_NE(at, std::string::npos) << text;
  text[at + key.size()] = '7';
  Bytes bad = draco;
  std::copy(text.begin(), text.end(), bad.begin() + 20);
  const std::string p = write("draco-id.glb", bad);
  expect_refused([&] { read_chunk(p); }, p, kExitBadInput, {"attributes/COLOR_0", "no Draco attribute with id 7"});
  // A Draco attribute of more components than a glTF vector has (tinygltf's 4-value stack array overflowed).
  const std::string wide = std::string(WALKRAD_SOURCE_DIR) + "/tests/fuzz/crashers/chunk/draco-attribute-nine-components.glb";
  expect_refused([&] { read_chunk(wide); }, wide, kExitBadInput, {"attributes/NORMAL", "has 9 components"});
}

TEST_F(BadInput, DeepJsonIsALimit) {
  const std::string deep = "{\"asset\":{\"version\":\"2.0\"},\"extras\":" + std::string(100000, '[') + std::string(100000, ']') + "}";
  const std::string g = write("deep.gltf", deep);
  expect_refused([&] { read_gltf(g); }, g, kExitLimitReached, {"byte ", "nests deeper than 64"});
  const std::string w = write("deep.json", std::string(100000, '[') + std::string(100000, ']'));
  expect_refused([&] { read_walkthrough(w); }, w, kExitLimitReached, {"nests deeper"});
}

nlohmann::json quad_gltf() {
  std::ifstream in(kSeeds + "gltf/quad-embedded.gltf");
  return nlohmann::json::parse(in);
}

TEST_F(BadInput, NodeHierarchiesMustBeShallowStrictTrees) {
  nlohmann::json chain = quad_gltf();
  chain["scenes"][0]["nodes"] = {4};
  for (int i = 0; i < 300; ++i) chain["nodes"].push_back({{"children", {5 + i}}});
  chain["nodes"].push_back({{"mesh", 0}});
  const std::string c = write("chain.gltf", chain);
  expect_refused([&] { read_gltf(c); }, c, kExitLimitReached, {"nodes[", "deeper than 256"});

  // 2^40 paths through 40 nodes: refused as a node with two parents, not walked.
  nlohmann::json dag = quad_gltf();
  dag["scenes"][0]["nodes"] = {4};
  for (int i = 0; i < 40; ++i) dag["nodes"].push_back({{"children", {5 + i, 5 + i}}, {"mesh", 0}});
  dag["nodes"].push_back({{"mesh", 0}});
  const std::string d = write("dag.gltf", dag);
  expect_refused([&] { read_gltf(d); }, d, kExitBadInput, {"nodes[44]", "reached twice"});
}

// EXT_lights_ies: a profile by data URI, placed by a node with a multiplier and a colour
// (clamped to [0, 1] as the extension says); broken references and profiles refused naming the place.
TEST_F(BadInput, IesLightsInGltf) {
  const std::string ies = "IESNA:LM-63-2002\r\nTILT=NONE\r\n1 -1 1 2 1 1 2 0 0 0\r\n1 1 10\r\n0 90\r\n0\r\n40 20\r\n";
  const auto base64 = [](const std::string& in) {
    static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < in.size(); i += 3) {
      const uint32_t n = (uint32_t(uint8_t(in[i])) << 16) | (i + 1 < in.size() ? uint32_t(uint8_t(in[i + 1])) << 8 : 0) |
                         (i + 2 < in.size() ? uint32_t(uint8_t(in[i + 2])) : 0);
      const size_t bytes = std::min<size_t>(3, in.size() - i);  // 1–3 bytes: 2–4 characters, then '='
      for (size_t k = 0; k < 4; ++k) out += k <= bytes ? kAlphabet[(n >> (18 - 6 * k)) & 63] : '=';
    }
    return out;
  };
  nlohmann::json g = quad_gltf();
  g["extensionsUsed"] = {"EXT_lights_ies"};
  g["extensions"]["EXT_lights_ies"]["lights"] = {{{"uri", "data:application/x-ies-lm-63;base64," + base64(ies)}}};
  g["nodes"].push_back({{"name", "lamp"}, {"translation", {0.5, 0.5, 2}},
                        {"extensions", {{"EXT_lights_ies", {{"light", 0}, {"multiplier", 3}, {"color", {1.5, 0.5, 0}}}}}}});
  g["scenes"][0]["nodes"].push_back(g["nodes"].size() - 1);
  const Scene s = read_gltf(write("ies.gltf", g));
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.lights[0].name, "lamp");
  EXPECT_EQ(s.lights[0].intensity, Vec3(3, 1.5, 0));
  EXPECT_EQ(s.lights[0].profile->text, ies);
  EXPECT_DOUBLE_EQ(s.lights[0].profile->intensity({0, 0, -1}), 40);
  EXPECT_DOUBLE_EQ(s.lights[0].profile->intensity({1, 0, 0}), 20);

  // By a relative uri, percent-encoded as glTF says.
  write("my lamp.ies", ies);
  nlohmann::json by_file = g;
  by_file["extensions"]["EXT_lights_ies"]["lights"][0] = {{"uri", "my%20lamp.ies"}};
  const Scene from_file = read_gltf(write("ies-file.gltf", by_file));
  ASSERT_EQ(from_file.lights.size(), 1u);
  EXPECT_EQ(from_file.lights[0].profile->text, ies);

  nlohmann::json wrong = g;
  wrong["nodes"].back()["extensions"]["EXT_lights_ies"]["light"] = 4;
  const std::string w = write("ies-index.gltf", wrong);
  expect_refused([&] { read_gltf(w); }, w, kExitBadInput, {"EXT_lights_ies", "light profile 4 does not exist"});
  nlohmann::json view = g;
  view["extensions"]["EXT_lights_ies"]["lights"][0] = {{"bufferView", 0}};
  const std::string v = write("ies-mime.gltf", view);
  expect_refused([&] { read_gltf(v); }, v, kExitBadInput, {"lights[0]", "mimeType"});
  nlohmann::json bad = g;
  bad["extensions"]["EXT_lights_ies"]["lights"][0]["uri"] = "data:application/x-ies-lm-63;base64," + base64(ies.substr(0, ies.size() - 3));
  const std::string b = write("ies-truncated.gltf", bad);
  try {
    read_gltf(b);
    ADD_FAILURE() << "a truncated profile was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(e.file().find("EXT_lights_ies.lights[0]"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("truncated"), std::string::npos) << e.what();
  }
}

// A directional light (the sun): read with its angular size from the light's extras; a size that is not
// a number from 0 to kMaxAngularDiameter, or a light type walkrad does not know, is refused naming the light.
TEST_F(BadInput, DirectionalLightsInGltf) {
  nlohmann::json g = quad_gltf();
  g["extensionsUsed"] = {"KHR_lights_punctual"};
  g["extensions"]["KHR_lights_punctual"]["lights"] = {
      {{"type", "directional"}, {"intensity", 80}, {"color", {1, 0.5, 0.25}}, {"extras", {{"walkrad:angular_diameter", 0.02}}}}};
  g["nodes"].push_back({{"name", "sun"}, {"rotation", {-0.5, 0, 0, 0.8660254037844386}},  // −Z turned 60° about x
                        {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  g["scenes"][0]["nodes"].push_back(g["nodes"].size() - 1);
  const Scene s = read_gltf(write("sun.gltf", g));
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.lights[0].type, PunctualLight::Type::directional);
  EXPECT_EQ(s.lights[0].intensity, Vec3(80, 40, 20));
  EXPECT_EQ(s.lights[0].angular_diameter, 0.02);
  EXPECT_NEAR(s.lights[0].direction.y, -std::sin(kPi / 3), 1e-9);
  EXPECT_NEAR(s.lights[0].direction.z, -std::cos(kPi / 3), 1e-9);
  for (const nlohmann::json& size : {nlohmann::json(-0.1), nlohmann::json(0.6), nlohmann::json("wide")}) {
    nlohmann::json bad = g;
    bad["extensions"]["KHR_lights_punctual"]["lights"][0]["extras"]["walkrad:angular_diameter"] = size;
    const std::string b = write("sun-size.gltf", bad);
    expect_refused([&] { read_gltf(b); }, b, kExitBadInput, {"lights[0].extras", "walkrad:angular_diameter"});
  }
  nlohmann::json area = g;
  area["extensions"]["KHR_lights_punctual"]["lights"][0]["type"] = "area";
  const std::string a = write("area.gltf", area);
  expect_refused([&] { read_gltf(a); }, a, kExitMissingFeature, {"lights[0]", "light type 'area' is not supported"});
}

// The sky: read from the scene's extras (a spec, as --sky takes), kept with glTF's +Y up or the extras'
// walkrad:up; every malformed spec refused naming the file, the place and the fault, or --sky and the spec.
TEST_F(BadInput, SkiesInGltfAndOnTheCommandLine) {
  nlohmann::json g = quad_gltf();
  g["scenes"][0]["extras"] = {{"walkrad:sky", "cie-overcast:800"}};
  const Scene s = read_gltf(write("sky.gltf", g));
  ASSERT_EQ(s.lights.size(), 1u);
  ASSERT_EQ(s.lights[0].type, PunctualLight::Type::sky);
  EXPECT_EQ(s.lights[0].sky->kind, Sky::Kind::cie_overcast);
  EXPECT_EQ(s.lights[0].sky->radiance, Vec3(800, 800, 800));
  EXPECT_EQ(s.lights[0].sky->up, Vec3(0, 1, 0));
  nlohmann::json zup = g;
  zup["scenes"][0]["extras"]["walkrad:up"] = {0, 0, 2};
  EXPECT_EQ(read_gltf(write("zup.gltf", zup)).lights[0].sky->up, Vec3(0, 0, 1));
  const std::pair<nlohmann::json, std::string> bad[] = {
      {"overcast:800", "unknown sky 'overcast'"},
      {"uniform:", "is not a number"},
      {"uniform:-1", "is not a number from 0 to 1e9"},
      {"uniform:1,2", "one value or three"},
      {"uniform:0", "is 0: the sky would give no light"},
      {"uniform:nan", "is not a number"},
      {"cie-clear:1000", "cie-clear needs the sun's position"},
      {"cie-clear:1000@0,-1,0", "the sun is below the horizon"},
      {"cie-clear:1000@1,2", "is not three numbers"},
      {"missing.hdr", "missing.hdr"},
      {"../outside.hdr", "lies outside the input folder"},
      {42, "must be a string"}};
  for (const auto& [spec, why] : bad) {
    nlohmann::json b = g;
    b["scenes"][0]["extras"]["walkrad:sky"] = spec;
    const std::string f = write("bad-sky.gltf", b);
    try {
      read_gltf(f);
      ADD_FAILURE() << "read " << spec.dump();
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << spec.dump() << ": " << e.what();
      EXPECT_EQ(e.code(), kExitBadInput) << e.what();
      if (!spec.is_string() || spec.get<std::string>().find(".hdr") == std::string::npos)
        EXPECT_EQ(e.file(), f) << e.what();
    }
  }
  nlohmann::json up = g;
  up["scenes"][0]["extras"]["walkrad:up"] = {0, 1};
  const std::string u = write("bad-up.gltf", up);
  expect_refused([&] { read_gltf(u); }, u, kExitBadInput, {"walkrad:up", "three numbers"});
  // From the command line: --sky and the spec named, the command line's exit code.
  Scene q = read_gltf(write("plain.gltf", quad_gltf()));
  try {
    apply_sky_options(q, "cie-clear:5", "");
    ADD_FAILURE() << "a clear sky without a sun";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "--sky");
    EXPECT_EQ(e.code(), kExitBadArguments);
  }
  expect_refused([&] { apply_sky_options(q, "uniform:1", "0,0,0"); }, "--up", kExitBadArguments, {"expected a direction"});
  apply_sky_options(q, "uniform:1,2,3", "0,0,1");
  ASSERT_EQ(q.lights.size(), 1u);
  EXPECT_EQ(q.lights[0].sky->up, Vec3(0, 0, 1));
  apply_sky_options(q, "uniform:4", "");  // replaces it
  ASSERT_EQ(q.lights.size(), 1u);
  EXPECT_EQ(q.lights[0].sky->radiance, Vec3(4, 4, 4));
  // An MGF scene (its zenith +Z) takes the sun and the sky from the command line; the clear sky follows the sun.
  const std::string m = write("floor.mgf", std::string("m grey =\n rd 0.5\nv a =\n p 0 0 0\nv b =\n p 1 0 0\nv c =\n p 1 1 0\nf a b c\n"));
  Scene day = read_mgf(m);
  apply_sky_options(day, "cie-clear:3000", "", "50000,48000,45000@0.5,0.5,0.7");
  ASSERT_EQ(day.lights.size(), 2u);
  EXPECT_EQ(day.lights[0].type, PunctualLight::Type::directional);
  EXPECT_EQ(day.lights[0].intensity, Vec3(50000, 48000, 45000));
  EXPECT_LT(length(day.lights[0].direction + normalize(Vec3(0.5, 0.5, 0.7))), 1e-12);
  EXPECT_EQ(day.lights[1].sky->up, Vec3(0, 0, 1));
  EXPECT_LT(length(day.lights[1].sky->sun - normalize(Vec3(0.5, 0.5, 0.7))), 1e-12);
  for (const std::string sun : {"50000", "50000@1,2", "-5@0,0,1", "5@0,0,0"})
    expect_refused([&] { apply_sky_options(day, "", "", sun); }, "--sun", kExitBadArguments, {});
}

// Clear glass: KHR_materials_transmission with roughness 0 reads as a pane of KHR_materials_ior's index;
// an index glass cannot have is refused.
TEST_F(BadInput, ClearGlassInGltf) {
  nlohmann::json g = quad_gltf();
  g["extensionsUsed"] = {"KHR_materials_transmission", "KHR_materials_ior"};
  g["materials"] = {{{"pbrMetallicRoughness", {{"baseColorFactor", {1, 1, 1, 1}}, {"roughnessFactor", 0}}},
                     {"extensions", {{"KHR_materials_transmission", {{"transmissionFactor", 0.9}}}, {"KHR_materials_ior", {{"ior", 1.33}}}}}}};
  for (auto& m : g["meshes"]) for (auto& p : m["primitives"]) p["material"] = 0;
  const Scene s = read_gltf(write("glass.gltf", g));
  ASSERT_FALSE(s.materials.empty());
  EXPECT_TRUE(s.materials[0].is_clear_glass());
  EXPECT_NEAR(s.materials[0].clear.x, 0.9, 1e-12);
  EXPECT_NEAR(s.materials[0].reflectance.x, 0.1, 1e-12);
  EXPECT_EQ(s.materials[0].ior, 1.33);
  for (const double ior : {0.5, 20.0}) {
    nlohmann::json bad = g;
    bad["materials"][0]["extensions"]["KHR_materials_ior"]["ior"] = ior;
    const std::string b = write("bad-glass.gltf", bad);
    expect_refused([&] { read_gltf(b); }, b, kExitBadInput, {"KHR_materials_ior", "ior must lie in [1, 10]"});
  }
}

// Devices are refused outside the input folder (input_folder_test.cpp) and, where the folder holds them
// ("/" here), as not regular files: a read from one could block or never end.
TEST_F(BadInput, DevicesAreNotFiles) {
  nlohmann::json g = quad_gltf();
  g["buffers"][0]["uri"] = "../../../../../../../../dev/zero";
  const std::string p = write("dev.gltf", g);
  expect_refused([&] { read_gltf(p); }, p, kExitBadInput, {"/dev/zero", "lies outside the input folder"});
  expect_refused([&] { read_gltf(p, "/"); }, p, kExitBadInput, {"/dev/zero", "not a regular file"});
  expect_refused([&] { read_walkthrough("/dev/zero"); }, "/dev/zero", kExitBadInput, {"not a regular file"});
  const std::string m = write("include.mgf", std::string("i /dev/zero\n"));
  expect_refused([&] { read_mgf(m); }, m, kExitBadInput, {"line 1", "lies outside the input folder"});
  MgfOptions root;
  root.input_folder = "/";
  expect_refused([&] { read_mgf(m, root); }, m, kExitBadInput, {"line 1", "cannot open included file"});
}

// Non-finite coordinates, reflectance ≥ 1 or < 0, negative emission: exit 3 with the place.
TEST_F(BadInput, NonFiniteCoordinatesNameTheAccessor) {
  Bytes glb = read_bytes(kSeeds + "gltf/quad.glb");
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(glb.data() + bin_data(glb) + 12, &nan, 4);  // vertex 1's x
  const std::string p = write("nan.glb", glb);
  expect_refused([&] { read_gltf(p); }, p, kExitBadInput, {"meshes[0].primitives[0]", "accessors[0]", "vertex 1 is not finite"});
}

TEST_F(BadInput, MaterialsOutOfRangeNameTheMaterial) {
  for (const double bad : {1.5, -0.1}) {
    nlohmann::json g = quad_gltf();
    g["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"][1] = bad;
    const std::string p = write("rho.gltf", g);
    expect_refused([&] { read_gltf(p); }, p, kExitBadInput, {"materials[0]", "baseColorFactor must lie in [0, 1]"});
  }
  // Reflectance 1 stated in the file (an untextured baseColorFactor) is kept with a warning (the bake
  // refuses a closed scene where nothing absorbs: tests/stability); glTF's default white, which the
  // file does not state, is capped at 0.99 with a warning.
  nlohmann::json white = quad_gltf();
  white["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"] = {0.5, 1.0, 0.995, 1.0};
  const Scene stated = read_gltf(write("white.gltf", white));
  EXPECT_EQ(stated.materials[0].reflectance, Vec3(0.5, 1.0, 0.99));
  const auto warned = [&](const std::string& what) {
    for (const std::string& w : stated.warnings)
      if (w.find("materials[0]") != std::string::npos && w.find(what) != std::string::npos) return true;
    return false;
  };
  EXPECT_TRUE(warned("reflectance capped at 0.99"));
  EXPECT_TRUE(warned("reflectance 1 absorbs nothing"));
  white["materials"][0]["pbrMetallicRoughness"].erase("baseColorFactor");
  const Scene defaulted = read_gltf(write("default-white.gltf", white));
  EXPECT_EQ(defaulted.materials[0].reflectance.x, 0.99);
  ASSERT_FALSE(defaulted.warnings.empty());
  EXPECT_NE(defaulted.warnings.front().find("reflectance capped at 0.99"), std::string::npos) << defaulted.warnings.front();

  nlohmann::json g = quad_gltf();
  g["materials"][1]["emissiveFactor"] = {1, -1, 1};
  const std::string p = write("emission.gltf", g);
  expect_refused([&] { read_gltf(p); }, p, kExitBadInput, {"materials[1]", "emission must not be negative"});

  const std::string nan = write("nan.mgf", std::string("v a =\n\tp 0 0 nan\n"));
  expect_refused([&] { read_mgf(nan); }, nan, kExitBadInput, {"line 2", "'nan' is not a number"});
  const std::string rd = write("rd.mgf", std::string("m x =\n\trd 1.2\n"));
  expect_refused([&] { read_mgf(rd); }, rd, kExitBadInput, {"line 2", "must lie in [0, 1]"});
  // rd 1 is read (with a warning: mgf_reader_test.cpp), so a file of only it fails for having no faces.
  const std::string one = write("rd1.mgf", std::string("m x =\n\trd 1\n"));
  expect_refused([&] { read_mgf(one); }, one, kExitBadInput, {"no faces"});
  const std::string ed = write("ed.mgf", std::string("m x =\n\ted -5\n"));
  expect_refused([&] { read_mgf(ed); }, ed, kExitBadInput, {"line 2", "emittance must not be negative"});
  const std::string huge = write("huge.mgf", std::string("v a =\n\tp 1e300 0 0\nv b =\n\tp 0 1 0\nv c =\n\tp 0 0 1\n"
                                                        "xf -s 1e300\nf a b c\nxf\n"));
  expect_refused([&] { read_mgf(huge); }, huge, kExitBadInput, {"line 8", "beyond ±1e9 m after the transform"});
}

// Zero-area triangles and repeated vertices are dropped and counted, the rest is read.
TEST_F(BadInput, DegenerateTrianglesAreDroppedAndCounted) {
  Bytes glb = read_bytes(kSeeds + "gltf/quad.glb");
  const uint16_t repeated[6] = {0, 1, 2, 0, 2, 2};  // the second triangle repeats a vertex
  std::memcpy(glb.data() + bin_data(glb) + 48, repeated, sizeof repeated);
  const Scene s = read_gltf(write("degenerate.glb", glb));
  // Mesh 0 appears under two nodes, one triangle each now; mesh 1 is one triangle.
  EXPECT_EQ(s.dropped_degenerate, 2u);
  EXPECT_EQ(s.polygons.size(), 3u);
  ASSERT_FALSE(s.warnings.empty());
  EXPECT_EQ(s.warnings.back(), "2 zero-area triangles dropped");
}

TEST_F(BadInput, WalkthroughLimitsAndNonNumbers) {
  nlohmann::json path = nlohmann::json::parse(read_bytes(kSeeds + "walkthrough/path.json"));
  path["path"]["frames"] = 1000000000;
  const std::string p = write("long.json", path);
  expect_refused([&] { read_walkthrough(p); }, p, kExitLimitReached, {"/path/frames", "exceeds the limit of 100000"});
  const std::string n = write("nan.json", std::string(R"({"format": "walkrad-walkthrough", "version": 1, "path": {"frames": NaN}})"));
  expect_refused([&] { read_walkthrough(n); }, n, kExitBadInput, {"not valid JSON"});
  // Found by the fuzzer: a number past double's range is nlohmann's out_of_range, not a parse error.
  const std::string big = write("big.json", std::string(R"({"format": "walkrad-walkthrough", "version": 1e99999})"));
  expect_refused([&] { read_walkthrough(big); }, big, kExitBadInput, {"a number is out of range"});
  path["path"]["frames"] = 10;
  path["path"]["keyframes"][0]["position"][0] = 1e308;
  path["path"]["keyframes"][1]["position"][0] = -1e308;
  const std::string o = write("overflow.json", path);
  expect_refused([&] { read_walkthrough(o); }, o, kExitBadInput, {"/path/keyframes", "must be finite"});
}

TEST_F(BadInput, ManifestChunksStayInTheFolder) {
  for (const char* name : {"../../etc/passwd", "/etc/passwd", "..", "sub/chunk.glb"}) {
    nlohmann::json m = nlohmann::json::parse(read_bytes(kSeeds + "manifest/manifest.json"));
    m["chunks"][0]["file"] = name;
    const std::string p = write("manifest.json", m);
    expect_refused([&] { read_manifest(p); }, p, kExitBadInput, {"/chunks/0/file", "plain file name"});
  }
}

}  // namespace
}  // namespace walkrad
