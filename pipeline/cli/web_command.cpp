// walkrad web: the web viewer (web/) copied into a bake folder.
#include <cstdio>

#include "commands.h"
#include "walkrad/bake/web_viewer.h"
#include "walkrad/formats/error.h"

namespace walkrad::command {

void add_web(CLI::App& app, WebCommand& c) {
  c.viewer = default_web_viewer_dir();
  c.app = app.add_subcommand("web", "copy the web viewer into a bake folder (then serve it: python3 -m http.server)");
  c.app->add_option("bake", c.dir, "bake folder")->required();
  c.app->add_option("--viewer", c.viewer, "the built viewer's folder")->capture_default_str();

}

int run_web(const WebCommand& c) {
  install_web_viewer(c.dir, c.viewer);
  std::printf("walkrad: web viewer in %s: serve the folder (cd %s && python3 -m http.server) and open http://localhost:8000/\n",
              c.dir.c_str(), c.dir.c_str());
  return kExitOk;
}

}  // namespace walkrad::command
