// install_web_viewer (web_viewer.h).
#include "walkrad/bake/web_viewer.h"

#include <filesystem>
#include <system_error>
#include <vector>

#include "walkrad/formats/error.h"

namespace walkrad {

namespace fs = std::filesystem;

namespace {
// What web/build.mjs writes.
const std::vector<std::string> kFiles = {"index.html", "walkrad-viewer.js", "draco/draco_decoder.wasm",
                                         "draco/draco_wasm_wrapper.js"};
}  // namespace

std::string default_web_viewer_dir() { return WALKRAD_WEB_VIEWER_DIR; }

void check_web_viewer(const std::string& viewer_dir) {
  for (const std::string& f : kFiles)
    if (!fs::is_regular_file(fs::path(viewer_dir) / f))
      throw InputError(viewer_dir, f, "no built web viewer here: build it (cmake --build BUILD --target walkrad_web, "
                                      "after scripts/install-deps.sh) or name one with --viewer");
}

int install_web_viewer(const std::string& bake_dir, const std::string& viewer_dir) {
  check_web_viewer(viewer_dir);
  if (!fs::is_regular_file(fs::path(bake_dir) / "manifest.json"))
    throw InputError(bake_dir, "", "not a bake folder (no manifest.json)");
  for (const std::string& f : kFiles) {
    const fs::path to = fs::path(bake_dir) / f, partial = fs::path(to.string() + ".partial");
    std::error_code ec;
    fs::create_directories(to.parent_path(), ec);
    if (!ec) fs::copy_file(fs::path(viewer_dir) / f, partial, fs::copy_options::overwrite_existing, ec);
    if (!ec) fs::rename(partial, to, ec);
    if (ec) {
      const std::string why = ec.message();
      fs::remove(partial, ec);
      throw OutputError(to.string() + ": cannot write the web viewer's file (" + why + ")");
    }
  }
  return int(kFiles.size());
}

}  // namespace walkrad
