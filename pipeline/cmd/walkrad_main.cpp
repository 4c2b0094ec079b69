// walkrad: the offline pipeline's command line. Thin: parses arguments, calls the stage, maps
// failures to the exit codes of walkrad/formats/error.h (documented in README.md).
#include <chrono>
#include <cstdio>
#include <exception>
#include <string>

#include <CLI/CLI.hpp>

#include "walkrad/formats/error.h"
#include "walkrad/formats/scene_reader.h"
#include "walkrad/formats/scene_writer.h"
#include "walkrad/pipeline/bake.h"

int main(int argc, char** argv) {
  using namespace walkrad;
  CLI::App app{"walkrad: precomputed diffuse global illumination for walkthroughs"};
  app.require_subcommand(1);

  BakeSettings bs;
  CLI::App* bake_cmd = app.add_subcommand("bake", "bake a scene's radiosity into a folder of vertex-coloured glTF");
  bake_cmd->add_option("scene", bs.scene, "scene file (.gltf, .glb)")->required();
  bake_cmd->add_option("--views", bs.views, "walkthrough JSON (default: the scene's cameras)");
  bake_cmd->add_option("-o,--output", bs.output, "output folder (default: <scene name>.bake)");
  bake_cmd->add_option("--method", bs.method, "solver: hierarchical (with importance when there are viewpoints) or classic")
      ->capture_default_str();
  bake_cmd->add_option("--epsilon", bs.epsilon, "hierarchical: refinement threshold, relative to the emitted power")
      ->check(CLI::PositiveNumber)->capture_default_str();
  bake_cmd->add_option("--solver", bs.solver, "hierarchical: gauss-seidel or jacobi")
      ->check(CLI::IsMember({"gauss-seidel", "jacobi"}))->capture_default_str();
  bake_cmd->add_flag("--view-independent", bs.view_independent,
                     "hierarchical: refine for every surface alike (BF oracle), not for what the viewpoints see");
  bake_cmd->add_option("--min-area", bs.min_area, "hierarchical: smallest element in m² (default: (diagonal/256)²)")
      ->check(CLI::NonNegativeNumber);
  bake_cmd->add_option("--element-size", bs.element_size, "classic: element edge length in metres (default: scene diagonal / 30)")
      ->check(CLI::NonNegativeNumber);
  bake_cmd->add_option("--rays", bs.rays_per_point, "visibility rays per receiver quadrature point")
      ->check(CLI::Range(1, 1024))->capture_default_str();
  bake_cmd->add_option("--exposure", bs.exposure, "display colour = radiance × exposure (default: automatic)")
      ->check(CLI::NonNegativeNumber);
  bake_cmd->add_option("--threads", bs.threads, "worker threads (default: all cores)")->check(CLI::Range(0, 1024));
  bake_cmd->add_option("--tolerance", bs.tolerance, "solver stop: largest relative update")->capture_default_str();
  bake_cmd->add_option("--max-seconds", bs.caps.max_seconds,
                       "stop with exit code 6, writing nothing, when the bake runs longer (checked between phases and solve rounds)")
      ->check(CLI::NonNegativeNumber);
  bake_cmd->add_option("--max-memory-mb", bs.caps.max_memory_mb,
                       "stop with exit code 6, writing nothing, when peak memory passes this many MiB (checked as --max-seconds)");
  bool quiet = false;
  bake_cmd->add_flag("-q,--quiet", quiet, "no progress lines");

  // convert: a scene (.mgf, .gltf, .glb) written as glTF, for users who move on from MGF.
  std::string convert_scene, convert_output;
  CLI::App* convert_cmd = app.add_subcommand("convert", "write a scene (.mgf, .gltf, .glb) as glTF (.glb or .gltf)");
  convert_cmd->add_option("scene", convert_scene, "scene file (.mgf, .gltf, .glb)")->required();
  convert_cmd->add_option("output", convert_output, "glTF file to write (.glb or .gltf)")->required()->check(
      [](const std::string& out) {
        const size_t dot = out.find_last_of('.');
        const std::string ext = dot == std::string::npos ? "" : out.substr(dot);
        return ext == ".glb" || ext == ".gltf" ? std::string() : std::string("the output must end in .glb or .gltf");
      });

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? kExitOk : kExitBadArguments;
  }

  try {
    if (bake_cmd->parsed()) {
      bs.progress = !quiet;
      if (bs.output.empty()) {
        std::string name = bs.scene.substr(bs.scene.find_last_of('/') + 1);
        bs.output = name.substr(0, name.find_last_of('.')) + ".bake";
      }
      const BakeSummary s = bake(bs);
      std::printf("walkrad: baked %s: %zu elements, %zu triangles, %zu viewpoints, exposure %.4g, %.2f s\n",
                  s.output.c_str(), s.elements, s.triangles, s.viewpoints, s.exposure, s.seconds);
    }
    if (convert_cmd->parsed()) {
      const auto start = std::chrono::steady_clock::now();
      const Scene scene = read_scene(convert_scene);
      for (const std::string& w : scene.warnings)
        std::fprintf(stderr, "walkrad: warning: %s: %s\n", convert_scene.c_str(), w.c_str());
      write_scene_gltf(scene, convert_output);
      size_t emitting = 0;
      for (const Material& m : scene.materials) emitting += m.emits();
      std::printf("walkrad: converted %s to %s: %zu polygons, %zu materials (%zu emitting), %zu viewpoints, %.2f s\n",
                  convert_scene.c_str(), convert_output.c_str(), scene.polygons.size(), scene.materials.size(), emitting,
                  scene.cameras.size(), std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
    return kExitOk;
  } catch (const InputError& e) {
    std::fprintf(stderr, "walkrad: error: %s\n", e.what());
    return e.code();
  } catch (const OutputError& e) {
    std::fprintf(stderr, "walkrad: error: %s\n", e.what());
    return kExitOutputFailure;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "walkrad: internal error: %s\n", e.what());
    return kExitInternal;
  }
}
