// The walkthrough viewer behind walkrad-view: plays a bake's viewpoints (or a walkthrough file's)
// either into PNG files without a display, or in a window. main() only parses the command line.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "walkrad/formats/scene.h"
#include "walkrad/runtime/chunk_cache.h"

namespace walkrad {

struct ViewerOptions {
  std::string bake_dir;
  std::string path_file;   // a walkthrough (walkthrough.h); empty: the manifest's viewpoints
  std::string frames_dir;  // where headless frames and stats.json go
  int width = 0;           // 0: height × the viewpoint's aspect, rounded
  int height = 512;
  StreamSettings stream;   // budget, workers, lookahead
  // Headless: frames are due at this rate, as in the window, and the streamer gets the time between
  // them (a frame finished early waits for its time); 0 renders as fast as possible.
  double frames_per_second = 30.0;
};

struct FrameSize {
  int width = 0;
  int height = 0;
};

// The viewpoints to play: the walkthrough file's, else the manifest's. Throws InputError naming the
// file, also when there is none to play.
std::vector<Viewpoint> viewer_viewpoints(const ViewerOptions& options);

// The image size for a viewpoint: the options' width, or height × its aspect (at least 1 pixel).
FrameSize frame_size(const ViewerOptions& options, const Viewpoint& view);

// Renders each viewpoint to frames_dir/frame-00000.png, frame-00001.png, … with a headless
// context, writes frames_dir/stats.json, and logs a line per file. Returns the frame count. The
// manifest's own viewpoints are played as its path (importance ahead); a --path file's as free
// flight. Every frame waits for the chunks it needs (a miss when prefetching did not bring them).
// Throws GraphicsError (no EGL), InputError (bake), OutputError (frames or stats not written).
size_t render_frames_headless(const ViewerOptions& options, const std::vector<Viewpoint>& views, std::ostream& log);

// Plays the viewpoints in a window until it is closed: space pauses, left/right step, W/A/S/D (and
// Q/E down/up) and the mouse with its left button held fly freely, R returns to the path, Tab shows
// the streaming stats in the title, Esc quits. Throws GraphicsError (no display) or InputError (bake).
void play_in_window(const ViewerOptions& options, const std::vector<Viewpoint>& views);

}  // namespace walkrad
