// walkrad bake: a scene's radiosity baked into a folder of vertex-coloured glTF chunks.
#include <cstdio>
#include <filesystem>
#include <string>

#include <unistd.h>

#include "commands.h"
#include "walkrad/bake/web_viewer.h"
#include "walkrad/core/build_identity.h"
#include "walkrad/formats/dependencies.h"
#include "walkrad/formats/error.h"

namespace walkrad::command {

void add_bake(CLI::App& app, BakeCommand& c) {
  c.app = app.add_subcommand("bake", "bake a scene's radiosity into a folder of vertex-coloured glTF");
  c.app->add_option("scene", c.bs.scene, "scene file (.gltf, .glb, .mgf)")->required();
  c.app->add_option("--views", c.bs.views, "walkthrough JSON (default: the scene's cameras)");
  c.app->add_option("--input-folder", c.bs.input_folder,
                    "the only folder whose files the scene may refer to: buffers, images, MGF includes, IES profiles (default: the scene file's folder)")
      ->check(CLI::ExistingDirectory);
  c.app->add_option("--mgf-sides", c.bs.mgf_sides,
                    "MGF: the sides of a material that does not state them: 1, as RenderPark reads them, or 2, MGF's own default")
      ->check(CLI::IsMember({1, 2}))->capture_default_str();
  c.app->add_option("--sky", c.bs.sky,
                    "light from a sky, in place of the scene file's: uniform:L, cie-overcast:Lz, cie-clear:Lz[@x,y,z] (radiance in "
                    "W/(m²·sr), one value or R,G,B; the sun's direction, else the scene's directional light) or FILE.hdr "
                    "(an equirectangular radiance map)");
  c.app->add_option("--up", c.bs.up, "x,y,z: the sky's zenith (default: +Y for glTF, +Z for MGF)");
  c.app->add_option("--sun", c.bs.sun,
                    "E@x,y,z: add the sun, a directional light of irradiance E (W/m², one value or R,G,B) from towards x,y,z "
                    "(for scenes whose format has none: MGF)");
  c.app->add_option("-o,--output", c.bs.output, "output folder (default: <scene name>.bake)");
  c.app->add_option("--method", c.method, "solver: hierarchical (with importance when there are viewpoints) or classic")
      ->capture_default_str();
  auto* error_opt = c.app->add_option("--error", c.bs.error,
                       "hierarchical: refinement tolerance, relative to what each surface shows where the walkthrough looks "
                       "(docs/accuracy.md: the error it delivers)")
      ->check(CLI::Range(1e-3, 1.0))->capture_default_str();
  c.app->add_option("--quality", c.quality, "hierarchical: draft, medium (the default), high or final: a preset --error")
      ->check(CLI::IsMember({"draft", "medium", "high", "final"}))->excludes(error_opt);
  c.app->add_option("--solver", c.solver,
                       "gauss-seidel (both methods), jacobi (hierarchical; under mpirun it divides the links among the "
                       "ranks) or southwell (classic: progressive refinement, shooting the most unshot power first)")
      ->check(CLI::IsMember({"gauss-seidel", "jacobi", "southwell"}))->capture_default_str();
  c.app->add_option("--form-factors", c.form_factors,
                       "classic: contour (contour formula × Embree rays) or hemicube (Cohen & Greenberg 1985, z-buffered)")
      ->check(CLI::IsMember({"contour", "hemicube"}))->capture_default_str();
  c.app->add_option("--hemicube-resolution", c.bs.hemicube_resolution, "classic, hemicube: pixels on the top face's side")
      ->check(CLI::Range(2, 4096))->capture_default_str();
  c.app->add_flag("--view-independent", c.bs.view_independent,
                     "hierarchical: hold every surface to the error alike, not only what the viewpoints see");
  c.app->add_option("--min-area", c.bs.min_area, "hierarchical: smallest element in m² (default: the median polygon's side / 128, squared, the median by area or by what the walkthrough sees, the smaller)")
      ->check(CLI::NonNegativeNumber);
  c.app->add_option("--element-size", c.bs.element_size, "classic: element edge length in metres (default: scene diagonal / 30)")
      ->check(CLI::NonNegativeNumber);
  c.app->add_option("--rays", c.bs.rays_per_point, "visibility rays per receiver quadrature point")
      ->check(CLI::Range(1, 1024))->capture_default_str();
  c.app->add_option("--exposure", c.bs.exposure, "display colour = radiance × exposure (default: automatic)")
      ->check(CLI::NonNegativeNumber);
  c.app->add_option("--chunk-triangles", c.bs.chunk_triangles, "largest streaming chunk, in triangles")
      ->check(CLI::Range(uint64_t(1), uint64_t(1) << 31))->capture_default_str();
  c.app->add_option("--effect", c.effect_overrides,
                       "force an effect on or off: indirect|visibility|importance|clusters|closure|punctual|transmission|textures|volumes|gather|discontinuities=on|off (repeatable)");
  c.app->add_option("--penumbra-ratio", c.bs.volume_penumbra_ratio,
                       "hierarchical: a link sees through a volume cluster where its objects are smaller than this × the "
                       "link's penumbra width there")
      ->check(CLI::PositiveNumber)->capture_default_str();
  c.app->add_option("--volume-min-polygons", c.bs.volume_min_polygons,
                       "hierarchical: polygons a cluster of small objects needs to be a volume")
      ->check(CLI::Range(uint32_t(2), uint32_t(1) << 30))->capture_default_str();
  c.app->add_flag("--explain", c.bs.explain, "print the effect plan (what is simulated, and why) before solving");
  c.app->add_flag("--no-compression", c.no_compression, "write plain glTF chunks (default: Draco)");
  c.app->add_flag("--web", c.with_web, "copy the web viewer into the bake folder (as `walkrad web`)");
  c.app->add_option("--position-tolerance", c.bs.position_tolerance,
                       "Draco: largest position error, as a fraction of the scene's diagonal")
      ->check(CLI::Range(1e-9, 1e-2))->capture_default_str();
  c.app->add_option("--radiosity-tolerance", c.bs.radiosity_tolerance,
                       "Draco: largest _RADIOSITY error, as a fraction of the radiosity shown as white")
      ->check(CLI::Range(1e-9, 1.0))->capture_default_str();
  c.app->add_option("--threads", c.bs.threads, "worker threads (default: all cores)")->check(CLI::Range(0, 1024));
  c.app->add_option("--tolerance", c.bs.tolerance, "solver stop: largest relative update (hierarchical: at least 1e-6 and --error / 200, each leaf's weighed by what the walkthrough sees of it)")->capture_default_str();
  c.app->add_option("--max-seconds", c.bs.caps.max_seconds,
                       "stop with exit code 6, writing nothing, when the bake runs longer (checked between phases and solve rounds)")
      ->check(CLI::NonNegativeNumber);
  c.app->add_option("--max-memory-mb", c.bs.caps.max_memory_mb,
                       "stop with exit code 6, writing nothing, when memory passes this many MiB or the next solve round is "
                       "predicted to (default: 60% of the machine's memory; 0: no cap)");
  auto* checkpoint_opt = c.app->add_option(
      "--checkpoint", c.bs.checkpoint,
      "hierarchical: save the solve's state in this folder after each refinement round (removed when the bake is written)");
  c.app->add_flag("--resume", c.bs.resume,
                     "hierarchical: start from the --checkpoint folder's last complete round (from the start when it has none)")
      ->needs(checkpoint_opt);
  c.app->add_flag("-q,--quiet", c.quiet, "no progress lines");
  c.app->add_option("--depfile", c.depfile,
                    "write a Make-syntax dependency file: the bake's manifest.json depends on every file the bake read "
                    "(the scene, its buffers, images, MGF includes and IES profiles, the walkthrough), for a build "
                    "system's DEPFILE (cmake/WalkradBake.cmake)");

}

int run_bake(BakeCommand& c, const Ranks& rk, bool& stopped) {
  BakeSettings& bs = c.bs;
  // Every rank knows of a mismatch: rank 0 says it, and they all end alike (no abort needed).
  std::string other;
  if (const int r = rk.size > 1 ? first_different_rank(build_identity(), &other) : -1; r > 0) {
    if (rk.rank == 0)
      std::fprintf(stderr, "walkrad: error: mpirun: rank %d runs another build (%s) than rank 0 (%s): every host needs the "
                   "same walkrad executable\n", r, other.c_str(), build_identity().c_str());
    stop_ranks();
    stopped = true;
    return kExitBadArguments;
  }
  bs.progress = !c.quiet && rk.rank == 0;
  bs.compress = !c.no_compression;
  // The words parsed once: the bake reads enums.
  bs.method = parse_method(c.method);
  bs.solver = parse_iteration(c.solver);
  bs.form_factors = parse_form_factors(c.form_factors);
  if (!c.quality.empty()) bs.error = quality_error(parse_quality(c.quality));
  for (const std::string& e : c.effect_overrides) {
    const size_t eq = e.find('=');
    if (eq == std::string::npos) throw InputError("--effect", e, "expected NAME=on or NAME=off", kExitBadArguments);
    bs.effects[e.substr(0, eq)] = e.substr(eq + 1);
  }
  if (bs.output.empty()) bs.output = default_output(bs.scene, ".bake");
  bool with_web = c.with_web;
  if (rk.rank != 0) {
    bs.output = (std::filesystem::temp_directory_path() /
                 ("walkrad-rank-" + std::to_string(rk.rank) + "-" + std::to_string(::getpid())))
                    .string();
    with_web = false;
  }
  if (with_web) check_web_viewer(default_web_viewer_dir());  // before the long work, not after it
  ReadLog read;  // rank 0 reads every input (bake_inputs.h)
  const BakeSummary s = bake(bs);
  if (rk.rank != 0) {
    std::filesystem::remove_all(bs.output);
    return kExitOk;
  }
  if (with_web) install_web_viewer(s.output, default_web_viewer_dir());
  // After the bake folder is in place: a build that stops before has no depfile saying it is up to date.
  if (!c.depfile.empty())
    write_depfile(c.depfile, (std::filesystem::absolute(s.output) / "manifest.json").lexically_normal().string(), read.files());
  std::printf("walkrad: baked %s: %zu elements, %zu triangles, %zu viewpoints, exposure %.4g, %.2f s%s\n",
              s.output.c_str(), s.elements, s.triangles, s.viewpoints, s.exposure, s.seconds,
              rk.size > 1 ? (", " + std::to_string(rk.size) + " ranks").c_str() : "");
  return kExitOk;
}

}  // namespace walkrad::command
