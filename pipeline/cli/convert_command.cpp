// walkrad convert: a scene (.mgf, .gltf, .glb) written as glTF, for users who move on from MGF.
#include <chrono>
#include <cstdio>

#include "commands.h"
#include "walkrad/formats/error.h"
#include "walkrad/formats/scene_reader.h"
#include "walkrad/formats/scene_writer.h"
#include "walkrad/formats/sky.h"

namespace walkrad::command {

void add_convert(CLI::App& app, ConvertCommand& c) {
  c.app = app.add_subcommand("convert", "write a scene (.mgf, .gltf, .glb) as glTF (.glb or .gltf)");
  c.app->add_option("scene", c.scene, "scene file (.mgf, .gltf, .glb)")->required();
  c.app->add_option("--input-folder", c.input_folder,
                    "the only folder whose files the scene may refer to: buffers, images, MGF includes, IES profiles (default: the scene file's folder)")
      ->check(CLI::ExistingDirectory);
  c.app->add_option("--mgf-sides", c.mgf_sides,
                    "MGF: the sides of a material that does not state them: 1, as RenderPark reads them, or 2, MGF's own default")
      ->check(CLI::IsMember({1, 2}))->capture_default_str();
  c.app->add_option("--sky", c.sky, "a sky to write with the scene (walkrad bake --sky), in place of the file's");
  c.app->add_option("--up", c.up, "x,y,z: the sky's zenith (default: +Y for glTF, +Z for MGF)");
  c.app->add_option("--sun", c.sun, "E@x,y,z: add the sun (walkrad bake --sun)");
  c.app->add_option("output", c.output, "glTF file to write (.glb or .gltf)")->required()->check(
      [](const std::string& out) {
        const size_t dot = out.find_last_of('.');
        const std::string ext = dot == std::string::npos ? "" : out.substr(dot);
        return ext == ".glb" || ext == ".gltf" ? std::string() : std::string("the output must end in .glb or .gltf");
      });

}

int run_convert(const ConvertCommand& c) {
  const auto start = std::chrono::steady_clock::now();
  Scene scene = read_scene(c.scene, c.input_folder, c.mgf_sides);
  apply_sky_options(scene, c.sky, c.up, c.sun);
  for (const std::string& w : scene.warnings) std::fprintf(stderr, "walkrad: warning: %s: %s\n", c.scene.c_str(), w.c_str());
  write_scene_gltf(scene, c.output);
  size_t emitting = 0;
  for (const Material& m : scene.materials) emitting += m.emits();
  std::printf("walkrad: converted %s to %s: %zu polygons, %zu materials (%zu emitting), %zu viewpoints, %.2f s\n",
              c.scene.c_str(), c.output.c_str(), scene.polygons.size(), scene.materials.size(), emitting,
              scene.cameras.size(), std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  return kExitOk;
}

}  // namespace walkrad::command
