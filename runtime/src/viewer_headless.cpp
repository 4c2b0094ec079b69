// render_frames_headless (viewer.h): EGL context → offscreen framebuffer → PNG per viewpoint. The
// framebuffer is remade only when a viewpoint asks for another size.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <system_error>

#include "walkrad/formats/error.h"
#include "walkrad/runtime/framebuffer.h"
#include "walkrad/runtime/headless_context.h"
#include "walkrad/runtime/player.h"
#include "walkrad/runtime/viewer.h"

namespace walkrad {

namespace {

std::string frame_file(const std::filesystem::path& dir, size_t index) {
  char name[32];
  std::snprintf(name, sizeof name, "frame-%05zu.png", index);
  return (dir / name).string();
}

void write_stats(const std::filesystem::path& file, const nlohmann::json& stats) {
  std::ofstream out(file);
  out << stats.dump(2) << '\n';
  if (!out.flush()) throw OutputError(file.string() + ": cannot write");
}

}  // namespace

size_t render_frames_headless(const ViewerOptions& options, const std::vector<Viewpoint>& views, std::ostream& log) {
  // Context and bake first: a missing EGL or a bad bake leaves no empty frames folder behind.
  HeadlessContext context;
  Player player = Player::open(options.bake_dir);
  const std::filesystem::path dir(options.frames_dir);
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  if (error) throw OutputError(dir.string() + ": cannot create the frames folder: " + error.message());

  std::unique_ptr<Framebuffer> target;
  for (size_t i = 0; i < views.size(); ++i) {
    const FrameSize size = frame_size(options, views[i]);
    if (!target || target->width() != size.width || target->height() != size.height)
      target = std::make_unique<Framebuffer>(size.width, size.height);
    target->bind();
    player.draw(views[i], size.width, size.height);
    const std::string file = frame_file(dir, i);
    write_png(file, target->read_pixels());
    log << "walkrad-view: wrote " << file << '\n';
  }

  nlohmann::json stats = stats_to_json(player.stats());
  stats["renderer"] = context.description();
  write_stats(dir / "stats.json", stats);
  log << "walkrad-view: " << views.size() << " frames in " << dir.string() << '\n';
  return views.size();
}

}  // namespace walkrad
