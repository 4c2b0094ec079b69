// bake: the offline pipeline end to end, as one function over plain settings (main() stays thin).
// read scene + walkthrough → split polygons at contacts → solve (hierarchical: importance from the
// viewpoints, refine/gather/push-pull over links; classic: uniform elements, full form factor matrix,
// Gauss-Seidel) → exposure → vertex mesh → bake folder (manifest.json, chunk-NNNN.glb, report.json,
// extinction.vdb when volume clusters are used), staged and swapped into place only when complete.
#pragma once

#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "walkrad/bake/bake_caps.h"
#include "walkrad/hierarchical/error_presets.h"
#include "walkrad/plan/method.h"

namespace walkrad {

struct RaySample;  // walkrad/hierarchical/hierarchical_solver.h

// The iteration that solves a method's system (walkrad bake --solver).
enum class Iteration : uint8_t {
  gauss_seidel,  // both methods (hierarchical: by input polygon)
  jacobi,        // hierarchical; under mpirun it divides the links among the ranks
  southwell,     // classic: progressive refinement (southwell.h)
};
// The classic method's form factors (walkrad bake --form-factors).
enum class FormFactors : uint8_t {
  contour,   // contour formula × Embree rays
  hemicube,  // Cohen & Greenberg 1985, z-buffered
};
// The named presets of --error (walkrad bake --quality).
enum class Quality : uint8_t { draft, medium, high, final };

// Each as the command line and the manifest spell it, and parsed once from that word: InputError (exit 2,
// naming the option and the choices) for another.
const char* iteration_name(Iteration iteration);
const char* form_factors_name(FormFactors form_factors);
Iteration parse_iteration(const std::string& word);
FormFactors parse_form_factors(const std::string& word);
Quality parse_quality(const std::string& word);

struct BakeSettings {
  std::string scene;        // .gltf / .glb
  std::string views;        // walkthrough JSON; empty: the scene's cameras
  std::string input_folder; // where the files the scene refers to may lie; empty: the scene file's folder
  int mgf_sides = 1;        // MGF: the sides of a material that does not state them (1 as RenderPark reads, or 2)
  std::string sky;          // a sky (sky.h parse_sky's spec) in place of the scene file's; empty: the file's, if any
  std::string up;           // "x,y,z": the zenith, for a sky; empty: the format's (glTF +Y, MGF +Z)
  std::string sun;          // "E@x,y,z": a directional light added (sky.h apply_sky_options); empty: none
  bool view_independent = false;  // every surface held to the error alike, not weighed by importance; exposure still uses the views
  std::string output;       // the bake folder
  Method method = Method::hierarchical;
  FormFactors form_factors = FormFactors::contour;  // classic
  int hemicube_resolution = 256;                    // classic, hemicube: pixels on the top face's side
  Iteration solver = Iteration::gauss_seidel;
  // hierarchical: the relative error each surface may show (where the walkthrough looks, with
  // importance), e.g. 0.02 for 2%; quality_error() maps the named presets to it.
  double error = kDefaultError;
  double min_area = 0;      // hierarchical: smallest element, m² (0: default_min_area, from the median polygon's side)
  double element_size = 0;  // classic: metres; 0: the scene's diagonal / 30
  int rays_per_point = 1;   // visibility rays: per quadrature point (classic), × 16 per link (hierarchical)
  double exposure = 0;      // 0: automatic from the viewpoints
  int threads = 0;          // 0: all cores
  uint64_t chunk_triangles = 16384;  // largest chunk, triangles (a lone leaf cluster may exceed it)
  bool compress = true;              // Draco (KHR_draco_mesh_compression); false: plain glTF
  double position_tolerance = 1e-5;  // Draco: position error, fraction of the scene's diagonal
  double radiosity_tolerance = 1e-3; // Draco: _RADIOSITY error, fraction of the radiosity shown as white
  double tolerance = 1e-7;  // solver stop: every element's last update below tolerance × its radiosity
  int max_iterations = 10000;
  bool progress = true;     // progress lines on stderr
  bool explain = false;     // print the effect plan (effect_plan.h) before solving
  std::map<std::string, std::string> effects;  // effect plan overrides: name → "on" / "off"
  // Volumetric visibility (volume_clusters.h, volume_visibility.h): a cluster of at least
  // volume_min_polygons small objects is a volume; a link sees through it where its objects are
  // smaller than volume_penumbra_ratio × the link's penumbra width there.
  uint32_t volume_min_polygons = 64;
  double volume_penumbra_ratio = 1.0;
  BakeCaps caps;            // time and memory caps (not recorded: they do not change the result)
  // hierarchical: a folder for the solve's state after each round (checkpoint_file.h), and whether
  // to start from it. Not recorded: a resumed bake is byte-identical to one that ran through.
  std::string checkpoint;
  bool resume = false;
  // Benchmarks only (bench/level_rays_bench.cpp): a sample of the hierarchical solve's rays goes here.
  // Not recorded, not owned.
  RaySample* ray_sample = nullptr;

  nlohmann::json to_json() const;  // what the manifest records (no paths that vary by machine)
};

struct BakeSummary {
  std::string output;
  size_t elements = 0;
  size_t triangles = 0;
  size_t viewpoints = 0;
  double exposure = 1;
  double seconds = 0;
};

// The requested relative error of a named quality: draft, medium (the default), high, final.
double quality_error(Quality quality);

// Throws InputError (bad scene or walkthrough), OutputError (cannot write), std::runtime_error.
BakeSummary bake(const BakeSettings& settings);

}  // namespace walkrad
