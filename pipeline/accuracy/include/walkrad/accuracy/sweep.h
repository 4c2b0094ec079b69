// walkrad sweep: what accuracy costs. Bakes a scene over a range of requested errors (hierarchical, view-independent
// and importance-driven) and of element sizes (classic), each bake a child process (bake_process.h)
// for its own time and peak memory; measures each against the independent reference (reference_tracer.h)
// at sample points seen from the walkthrough (view_samples.h) and in images from its viewpoints
// (error_measures.h); writes sweep.csv, sweep.json, reference images, and — through python3-matplotlib —
// plots and report.md (docs/accuracy.md explains every column).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace walkrad {

struct SweepSettings {
  std::string scene;
  std::string views;    // walkthrough JSON; empty: the scene's cameras
  std::string input_folder;  // where the files the scene refers to may lie; empty: the scene file's folder
  int mgf_sides = 1;         // MGF: the sides of a material that does not state them (BakeSettings::mgf_sides)
  std::string output;   // the sweep folder (staged, swapped into place when complete)
  std::string command;  // the command line, recorded in sweep.json and the report
  std::vector<std::string> methods = {"classic", "hierarchical", "importance"};
  std::vector<double> errors = {0.4, 0.2, 0.1, 0.05};  // hierarchical --error values (the quality presets)
  std::vector<double> element_sizes;  // classic, metres; empty: the scene's diagonal / {10, 15, 21, 30}
  double min_area = 0;                // hierarchical --min-area (0: the bake's default)
  std::vector<std::string> without;   // effects (e.g. gather): each hierarchical run again with NAME=off
  size_t points = 2048;               // reference sample points, over up to max_views viewpoints
  size_t max_views = 16;
  int samples = 8192;                 // paths per point (Cornell box 95% bar: 2.55% at 4096, 0.92% at 32768)
  int image_width = 64;               // reference images: width in pixels (0: none)
  size_t image_views = 4;             // viewpoints with an image
  int image_samples = 1024;           // paths per pixel
  uint64_t seed = 1;
  std::vector<std::string> measure;   // bake folders made elsewhere, measured too (not timed; method "measured")
  std::string reference;              // an earlier sweep's folder whose reference.bin to reuse (same key)
  int threads = 0;                    // for the bakes and the reference (0: all cores)
  bool plots = true;                  // run the plotting script (python3-matplotlib)
  bool keep_bakes = false;
  bool progress = true;
  std::string executable;             // the walkrad binary that bakes (default: this one, /proc/self/exe)
};

struct SweepSummary {
  std::string output;
  size_t runs = 0;
  double reference_seconds = 0;
  bool plotted = false;
};

// Throws InputError (bad scene or walkthrough, no viewpoints; or a bake refused its input or settings:
// the message names the run, quotes the bake's error and keeps its exit code), OutputError,
// std::runtime_error (a bake crashed).
SweepSummary run_sweep(const SweepSettings& settings);

}  // namespace walkrad
