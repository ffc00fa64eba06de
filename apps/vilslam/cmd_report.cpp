// `vilslam report RUN_DIR [--gt GT] [--map MAP [--model MODEL]] --out report.html`: one self-contained HTML page
// of a run (docs/report.md): paths against the ground truth, errors over time and distance, degenerate
// sweeps and loops on the path, timing histograms, and a 3D view of the map.
#include <cstdio>
#include <memory>
#include <string>

#include "common/json_writer.h"
#include "report/report_data.h"
#include "report/report_html.h"
#include "report/report_json.h"
#include "vilslam/command.h"

namespace {

using namespace vilslam;

struct Options {
  report::ReportOptions report;
  std::string out_path;
};

vilslam::cli::Command reg("report", "One self-contained HTML page of a run: paths, errors, events, timings, map",
                          [](CLI::App& app) {
  auto o = std::make_shared<Options>();
  app.add_option("run_dir", o->report.run_dir, "Output folder of `vilslam run`")->required();
  app.add_option("--gt", o->report.gt_path, "Ground truth: a dataset folder or a TUM file");
  auto* map = app.add_option("--map", o->report.map_path, "Map cloud of `vilslam map` (.ply, .pcd): the 3D view");
  app.add_option("--model", o->report.model_path, "Reference model cloud: colour the map by its MRE distance to it")
      ->needs(map);
  app.add_option("--out", o->out_path, "HTML file to write")->required();
  app.add_option("--max-map-points", o->report.max_map_points, "At most this many map points (every k-th) in the page")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--max-path-points", o->report.max_path_points, "At most this many poses per drawn path")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  return [o]() {
    const report::ReportData data = report::build_report_data(o->report);
    const std::string html = report::report_html(report::report_json(data, o->report));
    write_file_atomic(o->out_path, html);
    std::printf("report: %s (%.1f MB)\n", o->out_path.c_str(), static_cast<double>(html.size()) / 1e6);
    for (const std::string& note : data.notes) std::printf("  note: %s\n", note.c_str());
    return 0;
  };
});

}  // namespace
