#include "walkrad/accuracy/sweep.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <stdexcept>

#include <nlohmann/json.hpp>
#include <tbb/global_control.h>

#include "walkrad/formats/error.h"
#include "walkrad/formats/scene_reader.h"
#include "walkrad/formats/walkthrough.h"
#include "walkrad/accuracy/error_measures.h"
#include "walkrad/accuracy/bake_process.h"
#include "walkrad/accuracy/reference_cache.h"
#include "walkrad/accuracy/reference_set.h"
#include "walkrad/scene/scene_cleanup.h"
#include "walkrad/core/staged_output.h"
#include "walkrad/accuracy/sweep_plot_script.h"

namespace walkrad {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

// The phases a bake's report.json may list, in pipeline order (a column each in sweep.csv).
const char* const kPhases[] = {"read", "prepare", "importance", "subdivide", "form factors", "solve", "exposure", "mesh", "write"};

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

struct Run {
  std::string name, method;
  double error = NAN, element_size = NAN;
  std::vector<std::string> args;
};

std::vector<Run> plan_runs(const SweepSettings& s, double diagonal) {
  std::vector<Run> runs;
  for (const std::string& method : s.methods) {
    if (method == "none") continue;  // only the --measure folders
    if (method == "classic" || method == "southwell" || method == "hemicube") {
      std::vector<double> sizes = s.element_sizes;
      if (sizes.empty())
        for (double d : {10.0, 15.0, 21.0, 30.0}) sizes.push_back(diagonal / d);
      for (double h : sizes)
        runs.push_back({method + "-" + number(h), method, NAN, h,
                        {"--method", "classic", "--element-size", number(h), "--solver", method == "southwell" ? "southwell" : "gauss-seidel",
                         "--form-factors", method == "hemicube" ? "hemicube" : "contour"}});
    } else if (method == "hierarchical" || method == "importance") {
      for (double e : s.errors) {
        Run r{method + "-" + number(e), method, e, NAN, {"--method", "hierarchical", "--error", number(e)}};
        if (method == "hierarchical") r.args.push_back("--view-independent");
        if (s.min_area > 0) r.args.insert(r.args.end(), {"--min-area", number(s.min_area)});
        runs.push_back(r);
        // The same bake without an effect, to show what it buys (method "importance-no-gather", ...).
        for (const std::string& effect : s.without) {
          Run w = r;
          w.method = method + "-no-" + effect;
          w.name = w.method + "-" + number(e);
          w.args.insert(w.args.end(), {"--effect", effect + "=off"});
          runs.push_back(w);
        }
      }
    } else {
      throw InputError("--methods", "", "unknown method '" + method + "' (available: classic, southwell, hemicube, hierarchical, importance, none)",
                       kExitBadArguments);
    }
  }
  return runs;
}

double sum3(const json& v) { return v.at(0).get<double>() + v.at(1).get<double>() + v.at(2).get<double>(); }

uint64_t folder_bytes(const std::string& dir) {
  uint64_t bytes = 0;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_regular_file() && e.path().filename() != "report.json") bytes += e.file_size();
  return bytes;
}

// Where the bake is furthest from the reference (for the reader who wants to look): the sample point
// with the largest |a − r|, its position, both values and the reference's standard error.
json worst_point(const ReferenceSet& ref, const std::vector<double>& bake) {
  size_t worst = ref.rays.size();
  double largest = -1;
  for (size_t k = 0; k < bake.size(); ++k)
    if (!std::isnan(bake[k]) && !std::isnan(ref.luminance[k]) && std::fabs(bake[k] - ref.luminance[k]) > largest) {
      largest = std::fabs(bake[k] - ref.luminance[k]);
      worst = k;
    }
  if (worst == ref.rays.size()) return nullptr;
  const Vec3 p = ref.rays[worst].origin + ref.rays[worst].direction * ref.distance[worst];
  return {{"view", ref.rays[worst].view}, {"position", {p.x, p.y, p.z}}, {"reference", ref.luminance[worst]},
          {"standard_error", ref.standard_error[worst]}, {"bake", bake[worst]}};
}

// The bake's own estimate of the error the sweep measures as rms_weighted (report.json), or null.
json estimated_error(const json& report) {
  if (!report.contains("solver") || !report["solver"].contains("estimated_error")) return nullptr;
  return report["solver"]["estimated_error"].value("overall", json(nullptr));
}

// Surfaces, for the per-surface errors: a reference point belongs to the plane of the polygon its
// ray meets (material, the normal's main axis, the plane's offset to 1% of the diagonal), so that a
// box's walls, floor and ceiling are told apart. Empty where the ray meets nothing.
std::vector<std::string> surface_names(const Scene& scene, const RayScene& rays, const ReferenceSet& ref, double diagonal) {
  std::vector<std::string> out(ref.rays.size());
  for (size_t k = 0; k < ref.rays.size(); ++k) {
    if (std::isnan(ref.luminance[k])) continue;
    const RayScene::Hit hit = rays.intersect(ref.rays[k].origin, ref.rays[k].direction);
    if (!hit.hit) continue;
    const Polygon& p = scene.polygons[hit.polygon];
    const Vec3 n = polygon_normal(p);
    int axis = 0;
    for (int a = 1; a < 3; ++a)
      if (std::fabs(n[a]) > std::fabs(n[axis])) axis = a;
    char text[160];
    std::snprintf(text, sizeof text, "%s, facing %c%c, at %.2f", scene.materials[p.material].name.c_str(), n[axis] > 0 ? '+' : '-',
                  "xyz"[axis], std::round(100 * dot(n, p.v[0]) / diagonal) / 100 * diagonal);
    out[k] = text;
  }
  return out;
}

// The error on each surface that holds at least 1% of the weight, heaviest first.
json surface_errors(const std::vector<std::string>& surface, const std::vector<double>& bake, const ReferenceSet& ref) {
  std::map<std::string, std::vector<size_t>> groups;
  double total = 0;
  for (size_t k = 0; k < surface.size(); ++k)
    if (!surface[k].empty() && !std::isnan(bake[k])) {
      groups[surface[k]].push_back(k);
      total += ref.weight[k];
    }
  std::vector<std::pair<double, json>> rows;
  for (const auto& [name, index] : groups) {
    std::vector<double> a, r, w;
    for (size_t k : index) {
      a.push_back(bake[k]);
      r.push_back(ref.luminance[k]);
      w.push_back(ref.weight[k]);
    }
    double share = 0;
    for (double x : w) share += x / total;
    if (share < 0.01) continue;
    const ErrorMeasures e = relative_errors(a, r, w);
    rows.push_back({share, {{"surface", name}, {"weight_share", share}, {"points", e.points}, {"rms_weighted", e.rms_weighted},
                            {"bias", e.bias}}});
  }
  std::stable_sort(rows.begin(), rows.end(), [](const auto& x, const auto& y) { return x.first > y.first; });
  json out = json::array();
  for (auto& row : rows) out.push_back(std::move(row.second));
  return out;
}

json or_null(size_t points, double value) { return points ? json(value) : json(nullptr); }

json error_json(const ErrorMeasures& e) {
  return {{"rms", or_null(e.points, e.rms)}, {"rms_weighted", or_null(e.points, e.rms_weighted)},
          {"max", or_null(e.points, e.max)}, {"max_weighted", or_null(e.points, e.max_weighted)}, {"points", e.points}};
}

// One row of sweep.csv per run, from the run's JSON record.
const char* const kColumns[] = {"method", "error", "element_size", "seconds", "cpu_seconds", "elements", "links", "rays",
                                "triangles", "peak_rss_mib", "output_bytes", "points", "rms", "rms_weighted", "estimated_error", "max",
                                "max_weighted", "bias", "image_pixels", "image_rms", "image_rms_weighted", "reference_ci_rms",
                                "reference_ci_rms_weighted", "reference_image_ci_rms", "absorbed_over_emitted"};

void write_csv(const std::string& path, const json& runs) {
  std::ofstream out(path);
  std::string header;
  for (const char* c : kColumns) header += std::string(header.empty() ? "" : ",") + c;
  for (const char* p : kPhases) {
    std::string name = std::string("t_") + p;
    std::replace(name.begin(), name.end(), ' ', '_');
    header += "," + name;
  }
  out << header << '\n';
  for (const json& r : runs) {
    std::string line;
    for (const char* c : kColumns) {
      const json& v = r.at(c);
      line += line.empty() ? "" : ",";
      line += v.is_string() ? v.get<std::string>() : v.is_null() ? "" : v.is_number_float() ? number(v.get<double>()) : v.dump();
    }
    for (const char* p : kPhases) line += "," + (r.at("phases").contains(p) ? number(r.at("phases").at(p).get<double>()) : "");
    out << line << '\n';
  }
  if (!out) throw OutputError(path + ": cannot write");
}

void write_text(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out) throw OutputError(path + ": cannot write");
}

// The reference: sample points over the walkthrough, and images from a few of its viewpoints, traced or
// (--reference) read back; written to the sweep's folder with the images and reference-points.csv.
struct SweepReference {
  ReferenceSet points, image;
  ErrorMeasures ci, image_ci;  // the reference's own error bars (reference_error_bar)
  json images = json::array();
  size_t view_count = 0;
};

void write_reference_files(StagedOutput& out, const SweepReference& ref) {
  const ReferenceSet& points = ref.points;
  const ReferenceSet& image = ref.image;
  size_t first = 0;
  for (const json& im : ref.images) {
    const size_t count = size_t(im["width"].get<int>()) * im["height"].get<size_t>();
    write_image_png(out.path(im["file"].get<std::string>()),
                    std::vector<Vec3>(image.B.begin() + long(first), image.B.begin() + long(first + count)),
                    std::vector<double>(image.luminance.begin() + long(first), image.luminance.begin() + long(first + count)),
                    im["width"].get<int>(), im["height"].get<int>());
    first += count;
  }
  std::ofstream csv(out.path("reference-points.csv"));
  csv << "view,origin_x,origin_y,origin_z,dir_x,dir_y,dir_z,weight,distance,B_r,B_g,B_b,luminance,standard_error\n";
  for (size_t k = 0; k < points.rays.size(); ++k) {
    const ViewRay& r = points.rays[k];
    csv << r.view << ',' << number(r.origin.x) << ',' << number(r.origin.y) << ',' << number(r.origin.z) << ','
        << number(r.direction.x) << ',' << number(r.direction.y) << ',' << number(r.direction.z) << ',' << number(r.weight)
        << ',' << number(points.distance[k]) << ',' << number(points.B[k].x) << ',' << number(points.B[k].y) << ','
        << number(points.B[k].z) << ',' << number(points.luminance[k]) << ',' << number(points.standard_error[k]) << '\n';
  }
  if (!csv) throw OutputError(out.path("reference-points.csv") + ": cannot write");
}

SweepReference make_reference(const SweepSettings& s, const Scene& scene, const RayScene& rays, const std::vector<Viewpoint>& views,
                              StagedOutput& out, const std::function<void(const std::string&)>& log) {
  const ReferenceTracer tracer(scene, rays);
  SweepReference ref;
  ref.view_count = std::min(views.size(), std::max<size_t>(1, s.max_views));
  std::vector<ViewRay> pixels;
  for (uint32_t v : s.image_width > 0 ? spread_views(views.size(), s.image_views) : std::vector<uint32_t>{}) {
    int height = 0;
    const std::vector<ViewRay> px = image_rays(views, v, s.image_width, height);
    pixels.insert(pixels.end(), px.begin(), px.end());
    ref.images.push_back({{"view", v}, {"name", views[v].name}, {"width", s.image_width}, {"height", height},
                          {"file", "reference-view-" + std::to_string(v) + ".png"}});
  }
  const std::string key =
      reference_key(s.scene, s.views, "points " + std::to_string(s.points) + " over " + std::to_string(ref.view_count) + " views, " +
                                          std::to_string(s.samples) + " paths, images " + std::to_string(s.image_width) + " px × " +
                                          std::to_string(s.image_views) + " views × " + std::to_string(s.image_samples) +
                                          " paths, seed " + std::to_string(s.seed));
  if (!s.reference.empty()) {
    log("reference: reused from " + s.reference);
    load_reference(s.reference + "/reference.bin", key, ref.points, ref.image);
  } else {
    log("reference: " + std::to_string(s.points) + " points × " + std::to_string(s.samples) + " paths");
    ref.points = trace_reference(scene, rays, tracer, stratified_view_rays(views, ref.view_count, s.points / ref.view_count, s.seed),
                                 s.samples, s.seed);
    if (!pixels.empty()) {
      log("reference images: " + std::to_string(pixels.size()) + " pixels × " + std::to_string(s.image_samples) + " paths");
      ref.image = trace_reference(scene, rays, tracer, std::move(pixels), s.image_samples, s.seed + 1);
    }
  }
  save_reference(out.path("reference.bin"), key, ref.points, ref.image);
  write_reference_files(out, ref);
  ref.ci = reference_error_bar(ref.points.luminance, ref.points.standard_error, ref.points.weight);
  ref.image_ci = reference_error_bar(ref.image.luminance, ref.image.standard_error, ref.image.weight);
  return ref;
}

// One run: its bake made in a child process (or, measured, read from its folder) and measured against
// the reference. Returns its record for sweep.json; at_points: its luminance at every sample point.
json measure_run(const SweepSettings& s, const Run& run, const SweepReference& ref, const std::vector<std::string>& surfaces,
                 double tolerance, StagedOutput& out, std::vector<double>& at_points) {
  const ReferenceSet& points = ref.points;
  const bool measured = run.method == "measured";
  const std::string dir = measured ? run.args[0] : out.path("bakes/" + run.name);
  ProcessRun p;
  if (!measured) {
    const std::string exe = s.executable.empty() ? "/proc/self/exe" : s.executable;
    std::vector<std::string> args{"bake", s.scene, "-o", dir, "-q", "--exposure", "1"};
    if (!s.views.empty()) args.insert(args.end(), {"--views", s.views});
    if (!s.input_folder.empty()) args.insert(args.end(), {"--input-folder", s.input_folder});
    if (s.mgf_sides != 1) args.insert(args.end(), {"--mgf-sides", std::to_string(s.mgf_sides)});
    if (s.threads > 0) args.insert(args.end(), {"--threads", std::to_string(s.threads)});
    args.insert(args.end(), run.args.begin(), run.args.end());
    const std::string log_path = out.path("bakes/" + run.name + ".log");
    p = run_process(exe, args, log_path);
    if (p.exit_code >= kExitBadArguments && p.exit_code <= kExitLimitReached)  // the bake's own refusal: keep its code
      throw InputError(s.scene, "run " + run.name, "the bake failed: " + last_line(log_path), ExitCode(p.exit_code));
    if (p.exit_code != 0)
      throw std::runtime_error("the bake of run " + run.name + " failed (exit code " + std::to_string(p.exit_code) +
                               "): " + last_line(log_path));
  }
  std::ifstream report_file(dir + "/report.json");
  if (!report_file) throw InputError(dir, "", "no report.json: not a bake folder");
  const json report = json::parse(report_file);
  if (measured) p.wall_seconds = report.value("total_seconds", 0.0);
  const json& counts = report.at("counts");
  const BakeSampler bake = BakeSampler::open(dir);
  at_points = sample_bake(bake, points, tolerance);
  const ErrorMeasures e = relative_errors(at_points, points.luminance, points.weight);
  const ErrorMeasures ie = relative_errors(sample_bake(bake, ref.image, tolerance), ref.image.luminance, ref.image.weight);
  const ErrorMeasures& ci = ref.ci;
  const ErrorMeasures& image_ci = ref.image_ci;
  json phases = json::object();
  for (const json& ph : report.at("phases")) phases[ph.at("name").get<std::string>()] = ph.at("seconds");
  json rec = {{"name", run.name}, {"method", run.method},
              {"error", std::isnan(run.error) ? json(nullptr) : json(run.error)},
              {"element_size", std::isnan(run.element_size) ? json(nullptr) : json(run.element_size)},
              {"args", run.args}, {"seconds", p.wall_seconds}, {"cpu_seconds", p.cpu_seconds}, {"phases", phases},
              {"elements", counts.value("elements", uint64_t(0))},
              {"links", counts.contains("links") ? counts.at("links") : counts.value("form_factor_pairs", json(0))},
              {"rays", counts.value("visibility_rays", uint64_t(0))}, {"triangles", counts.value("triangles", uint64_t(0))},
              {"peak_rss_mib", p.peak_rss_mib}, {"output_bytes", folder_bytes(dir)},
              {"points", e.points}, {"rms", e.rms}, {"rms_weighted", e.rms_weighted},
              {"estimated_error", estimated_error(report)}, {"max", e.max},
              {"max_weighted", e.max_weighted}, {"bias", e.bias}, {"image_pixels", ie.points}, {"image_rms", or_null(ie.points, ie.rms)},
              {"image_rms_weighted", or_null(ie.points, ie.rms_weighted)}, {"reference_ci_rms", ci.rms},
              {"reference_ci_rms_weighted", ci.rms_weighted}, {"reference_image_ci_rms", or_null(image_ci.points, image_ci.rms)},
              {"absorbed_over_emitted", sum3(report.at("energy").at("absorbed_w")) / sum3(report.at("energy").at("emitted_w"))},
              {"worst_point", worst_point(points, at_points)}, {"surfaces", surface_errors(surfaces, at_points, points)},
              {"counts", counts}};
  if (!s.keep_bakes && !measured) fs::remove_all(dir);
  return rec;
}

// Every run at every sample point, beside the reference, for a reader who wants to look closer.
void write_bake_points(const std::string& path, const std::vector<Run>& all, const ReferenceSet& points,
                       const std::vector<std::string>& surfaces, const std::vector<std::vector<double>>& per_point) {
  std::ofstream csv(path);
  csv << "point,surface,reference";
  for (const Run& run : all) csv << ',' << run.name;
  csv << '\n';
  for (size_t k = 0; k < points.rays.size(); ++k) {
    csv << k << ",\"" << surfaces[k] << "\"," << number(points.luminance[k]);
    for (const std::vector<double>& v : per_point) csv << ',' << number(v[k]);
    csv << '\n';
  }
  if (!csv) throw OutputError(path + ": cannot write");
}

// plot_sweep.py run on the sweep's folder: whether its plots and report.md were written.
bool plot(StagedOutput& out) {
  // Debian's python3-matplotlib is installed for the system interpreter, which a PATH may shadow.
  const std::string python = fs::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
  const ProcessRun p = run_process(python, {out.path("plot_sweep.py"), out.path("")}, out.path("plot.log"));
  if (p.exit_code == 0) {
    fs::remove(out.path("plot.log"));
    return true;
  }
  std::fprintf(stderr, "walkrad: warning: plots and report.md not written (python3 with matplotlib is needed: %s)\n",
               last_line(out.path("plot.log")).c_str());
  return false;
}

}  // namespace

SweepSummary run_sweep(const SweepSettings& s) {
  std::unique_ptr<tbb::global_control> limit;
  if (s.threads > 0) limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, size_t(s.threads));
  Scene scene = read_scene(s.scene, s.input_folder, s.mgf_sides);
  remove_duplicate_polygons(scene);
  separate_clear_glass(scene);
  const std::vector<Viewpoint> views = s.views.empty() ? scene.cameras : read_walkthrough(s.views);
  if (views.empty())
    throw InputError(s.views.empty() ? s.scene : s.views, "", "no viewpoints: the sweep measures error where a walkthrough looks (give --views)");
  const double diagonal = length(scene.bounds().diagonal());
  const std::vector<Run> runs = plan_runs(s, diagonal);
  StagedOutput out(s.output);
  auto log = [&](const std::string& line) {
    if (s.progress) std::fprintf(stderr, "walkrad: sweep: %s\n", line.c_str());
  };

  const RayScene rays(scene);
  const SweepReference ref = make_reference(s, scene, rays, views, out, log);
  const ReferenceSet& points = ref.points;
  const ErrorMeasures& ci = ref.ci;
  const ErrorMeasures& image_ci = ref.image_ci;
  const std::vector<std::string> surfaces = surface_names(scene, rays, points, diagonal);

  // The bakes, one child process each.
  const double tolerance = 1e-4 * diagonal;
  fs::create_directories(out.path("bakes"));
  json records = json::array();
  std::vector<Run> all = runs;
  for (const std::string& dir : s.measure) {  // bakes made elsewhere: measured, not timed
    const std::string name = fs::path(dir).filename().string();
    all.push_back({"measured-" + name, "measured", NAN, NAN, {dir}});
  }
  std::vector<std::vector<double>> per_point;  // each run's luminance at every sample point, for bake-points.csv
  for (const Run& run : all) {
    per_point.emplace_back();
    const json rec = measure_run(s, run, ref, surfaces, tolerance, out, per_point.back());
    records.push_back(rec);
    char line[256];
    std::snprintf(line, sizeof line, "%s: %.2f s, %.0f MiB, %s links, error %.2f%% (weighted %.2f%%, image %.2f%%)",
                  run.name.c_str(), rec["seconds"].get<double>(), rec["peak_rss_mib"].get<double>(), rec["links"].dump().c_str(),
                  100 * rec["rms"].get<double>(), 100 * rec["rms_weighted"].get<double>(),
                  100 * (rec["image_rms_weighted"].is_null() ? 0.0 : rec["image_rms_weighted"].get<double>()));
    log(line);
  }

  json doc = {{"format", "walkrad-sweep"}, {"version", 1}, {"command", s.command}, {"scene", s.scene}, {"views", s.views},
              {"viewpoints", views.size()}, {"input_polygons", scene.polygons.size()}, {"threads", s.threads},
              {"unavailable", json::array({"hemicube: walkrad bake has no hemicube form factor option"})},
              {"reference", {{"points", points.rays.size()}, {"measured_points", ci.points}, {"views", ref.view_count},
                             {"samples", s.samples}, {"rays", points.rays_cast}, {"seconds", points.seconds},
                             {"ci", error_json(ci)}, {"image_ci", error_json(image_ci)}, {"image_samples", s.image_samples},
                             {"image_rays", ref.image.rays_cast}, {"image_seconds", ref.image.seconds}, {"images", ref.images},
                             {"seed", s.seed}}},
              {"runs", records}};
  write_text(out.path("sweep.json"), doc.dump(2) + "\n");
  write_bake_points(out.path("bake-points.csv"), all, points, surfaces, per_point);
  write_csv(out.path("sweep.csv"), records);
  if (!s.keep_bakes) fs::remove_all(out.path("bakes"));

  SweepSummary summary;
  summary.output = s.output;
  summary.runs = runs.size();
  summary.reference_seconds = points.seconds + ref.image.seconds;
  write_text(out.path("plot_sweep.py"), kSweepPlotScript);
  if (s.plots) summary.plotted = plot(out);
  out.commit();
  return summary;
}

}  // namespace walkrad
