// What this stage's accuracy tests compare: a scene baked with the defaults a user gets, in a fresh
// folder under the test temp dir, read back as a viewer sees it (BakeSampler), beside the scene and
// the independent reference tracer over it (reference_tracer.h). The folder goes with the object
// unless WALKRAD_KEEP_TEST_BAKE is set.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <string>
#include <utility>

#include <unistd.h>

#include <gtest/gtest.h>

#include "walkrad/accuracy/bake_sampler.h"
#include "walkrad/accuracy/reference_tracer.h"
#include "walkrad/bake/bake.h"
#include "walkrad/formats/scene_reader.h"
#include "walkrad/formats/scene_writer.h"

namespace walkrad::test {

class DefaultBake {
 public:
  // A scene file, baked as it is. name: the folder's, unique among the tests.
  DefaultBake(const std::string& name, const std::string& scene_file)
      : dir_(fresh(name)), scene(read_scene(scene_file)), sampler(bake_into(dir_, scene_file)), rays(scene),
        tracer(scene, rays) {}
  // A scene made in code, written as glTF into the folder and baked from there.
  DefaultBake(const std::string& name, Scene made)
      : dir_(fresh(name)), scene(std::move(made)), sampler(bake_into(dir_, written(dir_, scene))), rays(scene),
        tracer(scene, rays) {}
  DefaultBake(const DefaultBake&) = delete;  // the tracer refers to the scene and the rays
  DefaultBake& operator=(const DefaultBake&) = delete;
  ~DefaultBake() {
    if (!std::getenv("WALKRAD_KEEP_TEST_BAKE")) std::filesystem::remove_all(dir_);
  }
  // The folder: scene.gltf (a scene made in code) and the bake, scene.bake.
  const std::filesystem::path& folder() const { return dir_; }

 private:
  std::filesystem::path dir_;  // first: the members below are made in declaration order, the bake into it

 public:
  const Scene scene;
  const BakeSampler sampler;
  const RayScene rays;
  const ReferenceTracer tracer;

 private:
  static std::filesystem::path fresh(const std::string& name) {
    const std::filesystem::path dir =
        std::filesystem::path(::testing::TempDir()) / ("walkrad-" + name + "-" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
  }
  static std::string written(const std::filesystem::path& dir, const Scene& scene) {
    const std::string file = (dir / "scene.gltf").string();
    write_scene_gltf(scene, file);
    return file;
  }
  static BakeSampler bake_into(const std::filesystem::path& dir, const std::string& scene_file) {
    BakeSettings s;  // the defaults a user gets
    s.scene = scene_file;
    s.output = (dir / "scene.bake").string();
    s.progress = false;
    bake(s);
    return BakeSampler::open(s.output);
  }
};

}  // namespace walkrad::test
