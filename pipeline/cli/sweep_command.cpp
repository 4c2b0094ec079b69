// walkrad sweep: what accuracy costs, bakes against a path-traced reference (see docs/accuracy.md).
#include <cstdio>
#include <string>

#include "commands.h"
#include "walkrad/formats/error.h"

namespace walkrad::command {

void add_sweep(CLI::App& app, SweepCommand& c) {
  c.app = app.add_subcommand("sweep", "bake over a range of requested errors and element sizes; error against a path-traced reference");
  c.app->add_option("scene", c.ss.scene, "scene file (.gltf, .glb, .mgf)")->required();
  c.app->add_option("--views", c.ss.views, "walkthrough JSON (default: the scene's cameras)");
  c.app->add_option("--input-folder", c.ss.input_folder,
                    "the only folder whose files the scene may refer to: buffers, images, MGF includes, IES profiles (default: the scene file's folder)")
      ->check(CLI::ExistingDirectory);
  c.app->add_option("--mgf-sides", c.ss.mgf_sides,
                    "MGF: the sides of a material that does not state them: 1, as RenderPark reads them, or 2, MGF's own default")
      ->check(CLI::IsMember({1, 2}))->capture_default_str();
  c.app->add_option("-o,--output", c.ss.output, "output folder (default: <scene name>.sweep)");
  c.app->add_option("--methods", c.ss.methods,
                        "classic (Gauss-Seidel), southwell (classic, progressive refinement), hemicube (classic, hemicube form "
                        "factors), hierarchical (view-independent), importance; none: only the --measure folders")
      ->delimiter(',')->capture_default_str();
  c.app->add_option("--without", c.ss.without,
                        "also bake each hierarchical run with this effect off (e.g. gather): what the effect buys")->delimiter(',');
  c.app->add_option("--errors", c.ss.errors, "requested errors (--error) for the hierarchical methods")->delimiter(',')
      ->check(CLI::Range(1e-3, 1.0))->capture_default_str();
  c.app->add_option("--element-sizes", c.ss.element_sizes, "classic element sizes in metres (default: diagonal / 10, 15, 21, 30)")
      ->delimiter(',')->check(CLI::PositiveNumber);
  c.app->add_option("--min-area", c.ss.min_area, "hierarchical: smallest element in m² (default: the bake's)")
      ->check(CLI::NonNegativeNumber);
  c.app->add_option("--points", c.ss.points, "reference sample points")->check(CLI::Range(1, 10000000))->capture_default_str();
  c.app->add_option("--point-views", c.ss.max_views, "viewpoints the sample points spread over")->check(CLI::Range(1, 100000))
      ->capture_default_str();
  c.app->add_option("--samples", c.ss.samples, "reference paths per sample point")->check(CLI::Range(2, 10000000))
      ->capture_default_str();
  c.app->add_option("--image-width", c.ss.image_width, "reference image width in pixels (0: no images)")
      ->check(CLI::Range(0, 4096))->capture_default_str();
  c.app->add_option("--image-views", c.ss.image_views, "viewpoints with a reference image")->check(CLI::Range(1, 1000))
      ->capture_default_str();
  c.app->add_option("--image-samples", c.ss.image_samples, "reference paths per pixel")->check(CLI::Range(2, 10000000))
      ->capture_default_str();
  c.app->add_option("--seed", c.ss.seed, "reference random seed")->capture_default_str();
  c.app->add_option("--measure", c.ss.measure, "also measure these bake folders (made elsewhere; not timed)")->delimiter(',');
  c.app->add_option("--reference", c.ss.reference,
                        "reuse the reference of an earlier sweep's folder (its reference.bin; same scene, walkthrough and reference settings)");
  c.app->add_option("--threads", c.ss.threads, "worker threads for the bakes and the reference (default: all cores)")
      ->check(CLI::Range(0, 1024));
  c.app->add_flag("--keep-bakes", c.ss.keep_bakes, "keep every bake folder under OUTPUT/bakes/");
  c.app->add_flag("--no-plots", c.no_plots, "write CSV and JSON only (no matplotlib plots or report.md)");
  c.app->add_flag("-q,--quiet", c.quiet, "no progress lines");

}

int run_sweep(SweepCommand& c, int argc, char** argv) {
  SweepSettings& ss = c.ss;
  ss.plots = !c.no_plots;
  ss.progress = !c.quiet;
  for (int i = 0; i < argc; ++i) ss.command += std::string(i ? " " : "") + (i ? argv[i] : "walkrad");
  if (ss.output.empty()) ss.output = default_output(ss.scene, ".sweep");
  const SweepSummary s = walkrad::run_sweep(ss);
  std::printf("walkrad: swept %s: %zu bakes, reference %.1f s%s\n", s.output.c_str(), s.runs, s.reference_seconds,
              s.plotted ? ", plots and report.md written" : "");
  return kExitOk;
}

}  // namespace walkrad::command
