// The web viewer (web/) put beside a bake: `walkrad web BAKE` and `walkrad bake --web` copy
// the built viewer (index.html, walkrad-viewer.js with three.js bundled, draco/) into the bake folder,
// so that any static HTTP server shows it (`python3 -m http.server` in the folder, then
// http://localhost:8000/). The viewer reads ./manifest.json and streams the chunks beside it.
#pragma once

#include <string>

namespace walkrad {

// Where the build put the viewer (web/build.mjs → <build>/web); --viewer overrides it.
std::string default_web_viewer_dir();

// Throws InputError naming the folder when `viewer_dir` holds no built viewer (exit 3), and when
// `bake_dir` holds no manifest.json; OutputError when a file cannot be written. Each file is written
// under a temporary name and renamed into place. Returns the number of files copied.
int install_web_viewer(const std::string& bake_dir, const std::string& viewer_dir);

// Only the check of the viewer folder (before a bake that will install it).
void check_web_viewer(const std::string& viewer_dir);

}  // namespace walkrad
