// walkrad: the offline pipeline's command line. Thin: the subcommands add their options and run
// (commands.h, a file each); here the arguments are parsed, the ranks of an mpirun bake started and
// stopped, and failures mapped to the exit codes of walkrad/formats/error.h (documented in README.md).
#include <cstdio>
#include <exception>
#include <string>

#include <CLI/CLI.hpp>

#include "commands.h"
#include "walkrad/core/ranks.h"
#include "walkrad/formats/error.h"

int main(int argc, char** argv) {
  using namespace walkrad;
  using namespace walkrad::command;
  CLI::App app{"walkrad: precomputed diffuse global illumination for walkthroughs"};
  app.require_subcommand(1);
  BakeCommand bake;
  ConvertCommand convert;
  DiffCommand diff;
  WebCommand web;
  InspectCommand inspect;
  SweepCommand sweep;
  add_bake(app, bake);
  add_convert(app, convert);
  add_diff(app, diff);
  add_web(app, web);
  add_inspect(app, inspect);
  add_sweep(app, sweep);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? kExitOk : kExitBadArguments;
  }

  // Under mpirun (a bake over several ranks, walkrad/core/ranks.h) a failure on any rank ends them all
  // with its exit code.
  const Ranks rk = bake.app->parsed() ? start_ranks(&argc, &argv) : Ranks{};
  auto finish = [&](int code) {
    if (code != kExitOk && rk.size > 1) abort_ranks(code);
    stop_ranks();
    return code;
  };
  try {
    if (bake.app->parsed()) {
      bool stopped = false;
      const int code = run_bake(bake, rk, stopped);
      return stopped ? code : finish(code);
    }
    if (sweep.app->parsed()) return finish(run_sweep(sweep, argc, argv));
    if (convert.app->parsed()) return finish(run_convert(convert));
    if (diff.app->parsed()) return run_diff(diff);
    if (inspect.app->parsed()) return finish(run_inspect(inspect));
    if (web.app->parsed()) return finish(run_web(web));
    return finish(kExitOk);
  } catch (const InputError& e) {
    // Inputs are read by rank 0 (the others get what it read, and agree on what is wrong with it); a
    // limit is each rank's own (--max-memory-mb bounds each).
    if (rk.rank == 0) std::fprintf(stderr, "walkrad: error: %s\n", e.what());
    else if (e.code() == kExitLimitReached) std::fprintf(stderr, "walkrad: error: rank %d: %s\n", rk.rank, e.what());
    return finish(e.code());
  } catch (const OutputError& e) {
    std::fprintf(stderr, "walkrad: error: %s%s\n", rk.rank ? ("rank " + std::to_string(rk.rank) + ": ").c_str() : "", e.what());
    return finish(kExitOutputFailure);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "walkrad: internal error: %s%s\n", rk.rank ? ("rank " + std::to_string(rk.rank) + ": ").c_str() : "",
                 e.what());
    return finish(kExitInternal);
  }
}
