// render_frames_headless (viewer.h): EGL context → offscreen framebuffer → PNG per viewpoint. The
// framebuffer is remade only when a viewpoint asks for another size. Frames are paced like a
// window's, so that streaming gets the time it would have on screen.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <system_error>
#include <thread>

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
  Player player = Player::open(options.bake_dir, options.stream);
  // The manifest's viewpoints are the path the bake (and its chunk importance) was made for.
  const bool on_path = options.path_file.empty();
  const std::filesystem::path dir(options.frames_dir);
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  if (error) throw OutputError(dir.string() + ": cannot create the frames folder: " + error.message());

  std::unique_ptr<Framebuffer> target;
  using Clock = std::chrono::steady_clock;
  Clock::time_point due;
  for (size_t i = 0; i < views.size(); ++i) {
    if (i > 0 && options.frames_per_second > 0) {
      due += std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / options.frames_per_second));
      std::this_thread::sleep_until(due);
    }
    const FrameSize size = frame_size(options, views[i]);
    if (!target || target->width() != size.width || target->height() != size.height)
      target = std::make_unique<Framebuffer>(size.width, size.height);
    target->bind();
    player.update(CameraPlace{views[i], on_path ? std::optional<size_t>(i) : std::nullopt, false});
    player.draw(size.width, size.height, MissPolicy::kWait);
    if (i == 0) due = Clock::now();  // the clock starts with the first frame on screen
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
