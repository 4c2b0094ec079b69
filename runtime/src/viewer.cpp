// The viewer's choices shared by both modes (viewer.h): what to play and at what size.
#include "walkrad/runtime/viewer.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "walkrad/formats/error.h"
#include "walkrad/formats/manifest.h"
#include "walkrad/formats/walkthrough.h"

namespace walkrad {

std::vector<Viewpoint> viewer_viewpoints(const ViewerOptions& options) {
  if (!options.path_file.empty()) return read_walkthrough(options.path_file);
  const std::string manifest_file = (std::filesystem::path(options.bake_dir) / "manifest.json").string();
  std::vector<Viewpoint> views = read_manifest(manifest_file).viewpoints;
  if (views.empty())
    throw InputError(manifest_file, "/viewpoints", "the bake has no viewpoints to play; give a walkthrough with --path");
  return views;
}

FrameSize frame_size(const ViewerOptions& options, const Viewpoint& view) {
  const int width = options.width > 0 ? options.width : int(std::lround(options.height * view.aspect));
  return {std::max(width, 1), options.height};
}

}  // namespace walkrad
