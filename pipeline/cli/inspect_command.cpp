// walkrad inspect: what a bake folder holds; optionally its whole surface as JSON for scripts.
#include "commands.h"
#include "walkrad/formats/error.h"
#include "walkrad/output/bake_inspect.h"

namespace walkrad::command {

void add_inspect(CLI::App& app, InspectCommand& c) {
  c.app = app.add_subcommand("inspect", "print what a bake folder holds");
  c.app->add_option("bake", c.dir, "bake folder")->required();
  c.app->add_option("--mesh-json", c.mesh_json,
                          "write the whole surface (positions, normals, colours, radiosity, indices) as JSON to this file");
}

int run_inspect(const InspectCommand& c) {
  inspect_bake(c.dir, c.mesh_json);
  return kExitOk;
}

}  // namespace walkrad::command
