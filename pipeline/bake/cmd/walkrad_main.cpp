// walkrad: the offline pipeline's command line. Thin: parses arguments, calls the stage, maps
// failures to the exit codes of walkrad/formats/error.h (documented in README.md).
#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <unistd.h>

#include "walkrad/core/build_identity.h"
#include "walkrad/core/ranks.h"
#include "walkrad/formats/error.h"
#include "walkrad/formats/scene_reader.h"
#include "walkrad/formats/scene_writer.h"
#include "walkrad/bake/bake.h"
#include "walkrad/bake/web_viewer.h"
#include "walkrad/output/bake_diff.h"
#include "walkrad/output/bake_inspect.h"
#include "walkrad/accuracy/sweep.h"

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
  auto* error_opt = bake_cmd->add_option("--error", bs.error,
                       "hierarchical: refinement tolerance, relative to what each surface shows where the walkthrough looks "
                       "(docs/accuracy.md: the error it delivers)")
      ->check(CLI::Range(1e-3, 1.0))->capture_default_str();
  std::string quality;
  bake_cmd->add_option("--quality", quality, "hierarchical: draft, medium (the default), high or final: a preset --error")
      ->check(CLI::IsMember({"draft", "medium", "high", "final"}))->excludes(error_opt);
  bake_cmd->add_option("--solver", bs.solver,
                       "gauss-seidel (both methods), jacobi (hierarchical; under mpirun it divides the links among the "
                       "ranks) or southwell (classic: progressive refinement, shooting the most unshot power first)")
      ->check(CLI::IsMember({"gauss-seidel", "jacobi", "southwell"}))->capture_default_str();
  bake_cmd->add_option("--form-factors", bs.form_factors,
                       "classic: contour (contour formula × Embree rays) or hemicube (Cohen & Greenberg 1985, z-buffered)")
      ->check(CLI::IsMember({"contour", "hemicube"}))->capture_default_str();
  bake_cmd->add_option("--hemicube-resolution", bs.hemicube_resolution, "classic, hemicube: pixels on the top face's side")
      ->check(CLI::Range(2, 4096))->capture_default_str();
  bake_cmd->add_flag("--view-independent", bs.view_independent,
                     "hierarchical: hold every surface to the error alike, not only what the viewpoints see");
  bake_cmd->add_option("--min-area", bs.min_area, "hierarchical: smallest element in m² (default: the median polygon's side / 128, squared)")
      ->check(CLI::NonNegativeNumber);
  bake_cmd->add_option("--element-size", bs.element_size, "classic: element edge length in metres (default: scene diagonal / 30)")
      ->check(CLI::NonNegativeNumber);
  bake_cmd->add_option("--rays", bs.rays_per_point, "visibility rays per receiver quadrature point")
      ->check(CLI::Range(1, 1024))->capture_default_str();
  bake_cmd->add_option("--exposure", bs.exposure, "display colour = radiance × exposure (default: automatic)")
      ->check(CLI::NonNegativeNumber);
  bake_cmd->add_option("--chunk-triangles", bs.chunk_triangles, "largest streaming chunk, in triangles")
      ->check(CLI::Range(uint64_t(1), uint64_t(1) << 31))->capture_default_str();
  std::vector<std::string> effect_overrides;
  bake_cmd->add_option("--effect", effect_overrides,
                       "force an effect on or off: indirect|visibility|importance|clusters|closure|punctual|transmission|textures|volumes|gather|discontinuities=on|off (repeatable)");
  bake_cmd->add_option("--penumbra-ratio", bs.volume_penumbra_ratio,
                       "hierarchical: a link sees through a volume cluster where its objects are smaller than this × the "
                       "link's penumbra width there")
      ->check(CLI::PositiveNumber)->capture_default_str();
  bake_cmd->add_option("--volume-min-polygons", bs.volume_min_polygons,
                       "hierarchical: polygons a cluster of small objects needs to be a volume")
      ->check(CLI::Range(uint32_t(2), uint32_t(1) << 30))->capture_default_str();
  bake_cmd->add_flag("--explain", bs.explain, "print the effect plan (what is simulated, and why) before solving");
  bool no_compression = false, with_web = false;
  bake_cmd->add_flag("--no-compression", no_compression, "write plain glTF chunks (default: Draco)");
  bake_cmd->add_flag("--web", with_web, "copy the web viewer into the bake folder (as `walkrad web`)");
  bake_cmd->add_option("--position-tolerance", bs.position_tolerance,
                       "Draco: largest position error, as a fraction of the scene's diagonal")
      ->check(CLI::Range(1e-9, 1e-2))->capture_default_str();
  bake_cmd->add_option("--radiosity-tolerance", bs.radiosity_tolerance,
                       "Draco: largest _RADIOSITY error, as a fraction of the radiosity shown as white")
      ->check(CLI::Range(1e-9, 1.0))->capture_default_str();
  bake_cmd->add_option("--threads", bs.threads, "worker threads (default: all cores)")->check(CLI::Range(0, 1024));
  bake_cmd->add_option("--tolerance", bs.tolerance, "solver stop: largest relative update (hierarchical: at least 1e-6 and --error / 200, each leaf's weighed by what the walkthrough sees of it)")->capture_default_str();
  bake_cmd->add_option("--max-seconds", bs.caps.max_seconds,
                       "stop with exit code 6, writing nothing, when the bake runs longer (checked between phases and solve rounds)")
      ->check(CLI::NonNegativeNumber);
  bake_cmd->add_option("--max-memory-mb", bs.caps.max_memory_mb,
                       "stop with exit code 6, writing nothing, when memory passes this many MiB or the next solve round is "
                       "predicted to (default: 60% of the machine's memory; 0: no cap)");
  auto* checkpoint_opt = bake_cmd->add_option(
      "--checkpoint", bs.checkpoint,
      "hierarchical: save the solve's state in this folder after each refinement round (removed when the bake is written)");
  bake_cmd->add_flag("--resume", bs.resume,
                     "hierarchical: start from the --checkpoint folder's last complete round (from the start when it has none)")
      ->needs(checkpoint_opt);
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

  // diff: two bake folders compared within a tolerance (golden-file tests).
  std::string diff_a, diff_b;
  DiffSettings ds;
  CLI::App* diff_cmd = app.add_subcommand("diff", "compare two bake folders: manifests, geometry, _RADIOSITY (exit 7 if they differ)");
  diff_cmd->add_option("a", diff_a, "bake folder A (the reference)")->required();
  diff_cmd->add_option("b", diff_b, "bake folder B")->required();
  diff_cmd->add_option("--tolerance", ds.tolerance,
                       "radiosity: largest relative RMS difference (and 10× this for the largest single difference)")
      ->check(CLI::NonNegativeNumber)->capture_default_str();
  diff_cmd->add_option("--position-tolerance", ds.position_tolerance, "vertex matching, fraction of the bake's diagonal")
      ->check(CLI::PositiveNumber)->capture_default_str();

  // web: the web viewer copied into a bake folder (web/).
  std::string web_dir, web_viewer = default_web_viewer_dir();
  CLI::App* web_cmd = app.add_subcommand("web", "copy the web viewer into a bake folder (then serve it: python3 -m http.server)");
  web_cmd->add_option("bake", web_dir, "bake folder")->required();
  web_cmd->add_option("--viewer", web_viewer, "the built viewer's folder")->capture_default_str();

  // inspect: what a bake folder holds; optionally its whole surface as JSON for scripts.
  std::string inspect_dir, inspect_mesh_json;
  CLI::App* inspect_cmd = app.add_subcommand("inspect", "print what a bake folder holds");
  inspect_cmd->add_option("bake", inspect_dir, "bake folder")->required();
  inspect_cmd->add_option("--mesh-json", inspect_mesh_json,
                          "write the whole surface (positions, normals, colours, radiosity, indices) as JSON to this file");
  // sweep: what accuracy costs (docs/accuracy.md).
  SweepSettings ss;
  CLI::App* sweep_cmd = app.add_subcommand("sweep", "bake over a range of requested errors and element sizes; error against a path-traced reference");
  sweep_cmd->add_option("scene", ss.scene, "scene file (.gltf, .glb, .mgf)")->required();
  sweep_cmd->add_option("--views", ss.views, "walkthrough JSON (default: the scene's cameras)");
  sweep_cmd->add_option("-o,--output", ss.output, "output folder (default: <scene name>.sweep)");
  sweep_cmd->add_option("--methods", ss.methods,
                        "classic (Gauss-Seidel), southwell (classic, progressive refinement), hemicube (classic, hemicube form "
                        "factors), hierarchical (view-independent), importance; none: only the --measure folders")
      ->delimiter(',')->capture_default_str();
  sweep_cmd->add_option("--without", ss.without,
                        "also bake each hierarchical run with this effect off (e.g. gather): what the effect buys")->delimiter(',');
  sweep_cmd->add_option("--errors", ss.errors, "requested errors (--error) for the hierarchical methods")->delimiter(',')
      ->check(CLI::Range(1e-3, 1.0))->capture_default_str();
  sweep_cmd->add_option("--element-sizes", ss.element_sizes, "classic element sizes in metres (default: diagonal / 10, 15, 21, 30)")
      ->delimiter(',')->check(CLI::PositiveNumber);
  sweep_cmd->add_option("--min-area", ss.min_area, "hierarchical: smallest element in m² (default: the bake's)")
      ->check(CLI::NonNegativeNumber);
  sweep_cmd->add_option("--points", ss.points, "reference sample points")->check(CLI::Range(1, 10000000))->capture_default_str();
  sweep_cmd->add_option("--point-views", ss.max_views, "viewpoints the sample points spread over")->check(CLI::Range(1, 100000))
      ->capture_default_str();
  sweep_cmd->add_option("--samples", ss.samples, "reference paths per sample point")->check(CLI::Range(2, 10000000))
      ->capture_default_str();
  sweep_cmd->add_option("--image-width", ss.image_width, "reference image width in pixels (0: no images)")
      ->check(CLI::Range(0, 4096))->capture_default_str();
  sweep_cmd->add_option("--image-views", ss.image_views, "viewpoints with a reference image")->check(CLI::Range(1, 1000))
      ->capture_default_str();
  sweep_cmd->add_option("--image-samples", ss.image_samples, "reference paths per pixel")->check(CLI::Range(2, 10000000))
      ->capture_default_str();
  sweep_cmd->add_option("--seed", ss.seed, "reference random seed")->capture_default_str();
  sweep_cmd->add_option("--measure", ss.measure, "also measure these bake folders (made elsewhere; not timed)")->delimiter(',');
  sweep_cmd->add_option("--reference", ss.reference,
                        "reuse the reference of an earlier sweep's folder (its reference.bin; same scene, walkthrough and reference settings)");
  sweep_cmd->add_option("--threads", ss.threads, "worker threads for the bakes and the reference (default: all cores)")
      ->check(CLI::Range(0, 1024));
  sweep_cmd->add_flag("--keep-bakes", ss.keep_bakes, "keep every bake folder under OUTPUT/bakes/");
  bool no_plots = false, sweep_quiet = false;
  sweep_cmd->add_flag("--no-plots", no_plots, "write CSV and JSON only (no matplotlib plots or report.md)");
  sweep_cmd->add_flag("-q,--quiet", sweep_quiet, "no progress lines");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? kExitOk : kExitBadArguments;
  }

  // Under mpirun (a bake over several ranks, walkrad/core/ranks.h) rank 0 reports and writes the bake;
  // the others bake into a scratch folder of their own, removed afterwards. A failure on any rank ends
  // them all with its exit code.
  const Ranks rk = bake_cmd->parsed() ? start_ranks(&argc, &argv) : Ranks{};
  auto finish = [&](int code) {
    if (code != kExitOk && rk.size > 1) abort_ranks(code);
    stop_ranks();
    return code;
  };
  try {
    if (bake_cmd->parsed()) {
      // Every rank knows of a mismatch: rank 0 says it, and they all end alike (no abort needed).
      std::string other;
      if (const int r = rk.size > 1 ? first_different_rank(build_identity(), &other) : -1; r > 0) {
        if (rk.rank == 0)
          std::fprintf(stderr, "walkrad: error: mpirun: rank %d runs another build (%s) than rank 0 (%s): every host needs the "
                       "same walkrad executable\n", r, other.c_str(), build_identity().c_str());
        stop_ranks();
        return kExitBadArguments;
      }
      bs.progress = !quiet && rk.rank == 0;
      bs.compress = !no_compression;
      if (!quality.empty()) bs.error = quality_error(quality);
      for (const std::string& e : effect_overrides) {
        const size_t eq = e.find('=');
        if (eq == std::string::npos) throw InputError("--effect", e, "expected NAME=on or NAME=off", kExitBadArguments);
        bs.effects[e.substr(0, eq)] = e.substr(eq + 1);
      }
      if (bs.output.empty()) {
        std::string name = bs.scene.substr(bs.scene.find_last_of('/') + 1);
        bs.output = name.substr(0, name.find_last_of('.')) + ".bake";
      }
      if (rk.rank != 0) {
        bs.output = (std::filesystem::temp_directory_path() /
                     ("walkrad-rank-" + std::to_string(rk.rank) + "-" + std::to_string(::getpid())))
                        .string();
        with_web = false;
      }
      if (with_web) check_web_viewer(default_web_viewer_dir());  // before the long work, not after it
      const BakeSummary s = bake(bs);
      if (rk.rank != 0) {
        std::filesystem::remove_all(bs.output);
        return finish(kExitOk);
      }
      if (with_web) install_web_viewer(s.output, default_web_viewer_dir());
      std::printf("walkrad: baked %s: %zu elements, %zu triangles, %zu viewpoints, exposure %.4g, %.2f s%s\n",
                  s.output.c_str(), s.elements, s.triangles, s.viewpoints, s.exposure, s.seconds,
                  rk.size > 1 ? (", " + std::to_string(rk.size) + " ranks").c_str() : "");
    }
    if (sweep_cmd->parsed()) {
      ss.plots = !no_plots;
      ss.progress = !sweep_quiet;
      for (int i = 0; i < argc; ++i) ss.command += std::string(i ? " " : "") + (i ? argv[i] : "walkrad");
      if (ss.output.empty()) {
        std::string name = ss.scene.substr(ss.scene.find_last_of('/') + 1);
        ss.output = name.substr(0, name.find_last_of('.')) + ".sweep";
      }
      const SweepSummary s = run_sweep(ss);
      std::printf("walkrad: swept %s: %zu bakes, reference %.1f s%s\n", s.output.c_str(), s.runs, s.reference_seconds,
                  s.plotted ? ", plots and report.md written" : "");
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
    if (diff_cmd->parsed()) {
      const BakeDiff d = diff_bakes(diff_a, diff_b, ds);
      for (const std::string& n : d.notes) std::printf("note: %s\n", n.c_str());
      for (const std::string& x : d.differences) std::printf("differs: %s\n", x.c_str());
      std::printf("walkrad: %s: %zu / %zu vertices, %zu unmatched, radiosity relative RMS %.3g, largest %.3g\n",
                  d.same() ? "same within tolerance" : "the bakes differ", d.vertices_a, d.vertices_b, d.unmatched,
                  d.radiosity_rms, d.radiosity_max);
      return d.same() ? kExitOk : kExitDiffers;
    }
    if (inspect_cmd->parsed()) inspect_bake(inspect_dir, inspect_mesh_json);
    if (web_cmd->parsed()) {
      install_web_viewer(web_dir, web_viewer);
      std::printf("walkrad: web viewer in %s: serve the folder (cd %s && python3 -m http.server) and open http://localhost:8000/\n",
                  web_dir.c_str(), web_dir.c_str());
    }
    return finish(kExitOk);
  } catch (const InputError& e) {
    // Inputs are read by rank 0 (the others get what it read, and agree on what is wrong with it); a
    // limit is each rank's own (--max-memory-mb bounds each).
    if (rk.rank == 0) std::fprintf(stderr, "walkrad: error: %s\n", e.what());
    else if (e.code() == kExitLimitReached) std::fprintf(stderr, "walkrad: error: rank %d: %s\n", rk.rank, e.what());
    return finish(e.code());
  } catch (const OutputError& e) {
    std::fprintf(stderr, "walkrad: error: %s%s\n", rk.rank ? ("rank " + std::to_string(rk.rank) + ": ").c_str() : "", e.what());
    return finish(kExitOutputFailure);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "walkrad: internal error: %s%s\n", rk.rank ? ("rank " + std::to_string(rk.rank) + ": ").c_str() : "",
                 e.what());
    return finish(kExitInternal);
  }
}
