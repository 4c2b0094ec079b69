// The walkrad command's subcommands, a file each: each adds its options to the app (add_*) and, once
// parsed, runs (run_*), returning an exit code of walkrad/formats/error.h. walkrad_main.cpp parses and
// maps failures to exit codes.
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "walkrad/accuracy/sweep.h"
#include "walkrad/bake/bake.h"
#include "walkrad/core/ranks.h"
#include "walkrad/output/bake_diff.h"

namespace walkrad::command {

// A subcommand's output folder by default: the scene file's name less its extension, with `suffix`, in
// the working folder (office.gltf → office.bake).
inline std::string default_output(const std::string& scene, const char* suffix) {
  const std::string name = scene.substr(scene.find_last_of('/') + 1);
  return name.substr(0, name.find_last_of('.')) + suffix;
}

struct BakeCommand {
  CLI::App* app = nullptr;
  BakeSettings bs;
  // As typed (each parsed into bs's enum by run_bake).
  std::string method = method_name(Method::hierarchical), solver = iteration_name(Iteration::gauss_seidel),
              form_factors = form_factors_name(FormFactors::contour), quality;
  std::vector<std::string> effect_overrides;
  bool quiet = false, no_compression = false, with_web = false;
  std::string depfile;  // --depfile: written by rank 0 once the bake folder is in place
};
void add_bake(CLI::App& app, BakeCommand& c);
// Over several ranks (mpirun), rank 0 reports and writes the bake; the others bake into a scratch folder
// of their own, removed afterwards. `stopped`: the ranks were stopped here (another build on some rank),
// and the code is to be returned as it is.
int run_bake(BakeCommand& c, const Ranks& rk, bool& stopped);

struct ConvertCommand {
  CLI::App* app = nullptr;
  std::string scene, output, input_folder, sky, up, sun;
  int mgf_sides = 1;
};
void add_convert(CLI::App& app, ConvertCommand& c);
int run_convert(const ConvertCommand& c);

struct DiffCommand {
  CLI::App* app = nullptr;
  std::string a, b;
  DiffSettings ds;
};
void add_diff(CLI::App& app, DiffCommand& c);
int run_diff(const DiffCommand& c);

struct WebCommand {
  CLI::App* app = nullptr;
  std::string dir, viewer;
};
void add_web(CLI::App& app, WebCommand& c);
int run_web(const WebCommand& c);

struct InspectCommand {
  CLI::App* app = nullptr;
  std::string dir, mesh_json;
};
void add_inspect(CLI::App& app, InspectCommand& c);
int run_inspect(const InspectCommand& c);

struct SweepCommand {
  CLI::App* app = nullptr;
  SweepSettings ss;
  bool no_plots = false, quiet = false;
};
void add_sweep(CLI::App& app, SweepCommand& c);
// argv: the command line, recorded in the sweep's files.
int run_sweep(SweepCommand& c, int argc, char** argv);

}  // namespace walkrad::command
