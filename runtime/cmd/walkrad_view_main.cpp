// walkrad-view: plays a bake (see docs/architecture.md). Parses the command line, picks
// headless or window mode, and turns every failure into a message and an exit code (error.h).
//
//   walkrad-view BAKE_DIR [--headless] [--frames DIR] [--width W] [--height H] [--path FILE]
//                [--budget-mb MB] [--workers N] [--lookahead FRAMES] [--fps F]
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>

#include <CLI/CLI.hpp>

#include "walkrad/formats/error.h"
#include "walkrad/runtime/graphics_error.h"
#include "walkrad/runtime/viewer.h"

namespace {

int run(int argc, char** argv) {
  using namespace walkrad;
  ViewerOptions options;
  bool headless = false;
  CLI::App app{"walkrad-view: plays a walkrad bake in a window, or renders it to PNG frames"};
  app.add_option("BAKE_DIR", options.bake_dir, "bake folder (manifest.json + chunks)")->required();
  app.add_flag("--headless", headless, "render to PNG files without a window (also when DISPLAY is unset)");
  app.add_option("--frames", options.frames_dir, "folder for headless frames and stats.json; implies --headless "
                                                 "(default: BAKE_DIR/frames)");
  app.add_option("--width", options.width, "image width in pixels (default: height × the viewpoint's aspect)")
      ->check(CLI::Range(1, 16384));
  app.add_option("--height", options.height, "image height in pixels")->check(CLI::Range(1, 16384))
      ->capture_default_str();
  app.add_option("--path", options.path_file, "walkthrough file to play instead of the bake's viewpoints");
  double budget_mb = 0;
  app.add_option("--budget-mb", budget_mb, "memory for resident chunks, in MB of 10^6 bytes (GPU buffers and decoded "
                                           "meshes, docs/architecture.md); 0: no limit")
      ->check(CLI::NonNegativeNumber)->capture_default_str();
  app.add_option("--workers", options.stream.worker_threads, "threads that read and decode chunks")
      ->check(CLI::Range(1, 64))->capture_default_str();
  app.add_option("--lookahead", options.stream.lookahead_frames, "frames of the path that streaming looks ahead")
      ->check(CLI::Range(0, 100000))->capture_default_str();
  app.add_option("--fps", options.frames_per_second, "headless: frame rate to pace the frames at (0: as fast as "
                                                     "possible)")
      ->check(CLI::NonNegativeNumber)->capture_default_str();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? kExitOk : kExitBadArguments;
  }

  options.stream.budget_bytes = uint64_t(std::llround(budget_mb * 1e6));
  const char* display = std::getenv("DISPLAY");
  headless = headless || !options.frames_dir.empty() || !display || !*display;
  if (options.frames_dir.empty()) options.frames_dir = (std::filesystem::path(options.bake_dir) / "frames").string();

  const std::vector<Viewpoint> views = viewer_viewpoints(options);
  if (headless) render_frames_headless(options, views, std::cout);
  else play_in_window(options, views);
  return kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const walkrad::InputError& e) {
    std::cerr << "walkrad-view: " << e.what() << '\n';
    return e.code();
  } catch (const walkrad::GraphicsError& e) {
    std::cerr << "walkrad-view: " << e.what() << '\n';
    return walkrad::kExitMissingFeature;
  } catch (const walkrad::OutputError& e) {
    std::cerr << "walkrad-view: " << e.what() << '\n';
    return walkrad::kExitOutputFailure;
  } catch (const std::exception& e) {
    std::cerr << "walkrad-view: internal error: " << e.what() << '\n';
    return walkrad::kExitInternal;
  } catch (...) {
    std::cerr << "walkrad-view: internal error\n";
    return walkrad::kExitInternal;
  }
}
