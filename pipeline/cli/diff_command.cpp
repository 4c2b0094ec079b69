// walkrad diff: two bake folders compared within a tolerance (golden-file tests); exit 7 where they differ.
#include <cstdio>

#include "commands.h"
#include "walkrad/formats/error.h"

namespace walkrad::command {

void add_diff(CLI::App& app, DiffCommand& c) {
  c.app = app.add_subcommand("diff", "compare two bake folders: manifests, geometry, _RADIOSITY (exit 7 if they differ)");
  c.app->add_option("a", c.a, "bake folder A (the reference)")->required();
  c.app->add_option("b", c.b, "bake folder B")->required();
  c.app->add_option("--tolerance", c.ds.tolerance,
                       "radiosity: largest relative RMS difference (and 10× this for the largest single difference)")
      ->check(CLI::NonNegativeNumber)->capture_default_str();
  c.app->add_option("--position-tolerance", c.ds.position_tolerance, "vertex matching, fraction of the bake's diagonal")
      ->check(CLI::PositiveNumber)->capture_default_str();

}

int run_diff(const DiffCommand& c) {
  const BakeDiff d = diff_bakes(c.a, c.b, c.ds);
  for (const std::string& n : d.notes) std::printf("note: %s\n", n.c_str());
  for (const std::string& x : d.differences) std::printf("differs: %s\n", x.c_str());
  std::printf("walkrad: %s: %zu / %zu vertices, %zu unmatched, radiosity relative RMS %.3g, largest %.3g\n",
              d.same() ? "same within tolerance" : "the bakes differ", d.vertices_a, d.vertices_b, d.unmatched,
              d.radiosity_rms, d.radiosity_max);
  return d.same() ? kExitOk : kExitDiffers;
}

}  // namespace walkrad::command
