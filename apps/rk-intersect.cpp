// rk-intersect: two or more stations' located-target files → one trajectory with covariance (SPEC.md §7).
// Thin CLI: the method lives in lib/intersect (intersect/intersect.h).
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "formats/located.h"
#include "formats/stations.h"
#include "intersect/intersect.h"
#include "intersect/station_track.h"
#include "io/cli.h"
#include "io/csv.h"
#include "io/error.h"
#include "io/file_util.h"

namespace {

const char* const kTool = "rk-intersect";

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Intersect the lines of sight (and ranges) of two or more stations into one trajectory with its "
      "covariance, in the origin's ENU frame and WGS-84 (SPEC.md section 7).",
      kTool};
  rk::cli::CommonOptions common;
  rk::cli::AddCommonOptions(app, kTool, &common);
  std::string stations_path, out_path, at_path;
  rk::intersect::IntersectOptions opt;
  app.add_option("--stations", stations_path,
                 "stations.json: origin and, per station, lat_deg/lon_deg/h_m and its located.csv")
      ->required();
  app.add_option("-o,--output", out_path, "Trajectory CSV ('-' = stdout)")->required();
  rk::cli::AddOptions(&app, &opt, rk::intersect::IntersectOptions::Table(),
                      {{"--rate", [&] {
                          app.add_option("--at", at_path, "Output times: CSV with a t_s column (exclusive with --rate)");
                        }}});
  rk::io::BadRows bad_rows = rk::io::BadRows::kError;
  rk::cli::AddBadRowsOption(&app, &bad_rows);

  return rk::cli::Run(app, kTool, argc, argv, [&]() -> int {
    std::string why;
    if (!opt.Check(&why)) throw rk::UsageError(why);
    if (!at_path.empty() && opt.rate_hz > 0.0) throw rk::UsageError("--at and --rate exclude each other");
    // Checked twice: the stations file before it is read, then with the located files it names.
    std::vector<rk::cli::NamedPath> inputs = {{"--stations", stations_path}, {"--at", at_path}};
    rk::cli::CheckStreams(common, inputs, {{"-o", out_path}});

    const rk::formats::StationsFile stations = rk::formats::LoadStations(stations_path);
    for (const auto& s : stations.stations) inputs.push_back({s.name, s.located});
    rk::cli::CheckStreams(common, inputs, {{"-o", out_path}});
    std::vector<rk::formats::LocatedFile> files;
    bool by_id = false;
    for (const auto& s : stations.stations) {
      files.push_back(rk::formats::ReadLocated(rk::io::CsvTable::Read(s.located, {bad_rows, rk::formats::LocatedRowRule()})));
      by_id = by_id || files.back().has_id;
    }
    std::vector<double> at;
    if (!at_path.empty()) at = rk::intersect::ReadTimes(rk::io::CsvTable::Read(at_path, {bad_rows, {}}));
    rk::io::RunSummary summary;
    if (by_id) {
      // Located from points tracks: one trajectory per id.
      std::vector<std::string> warnings;
      const std::vector<rk::intersect::IntersectResult> results =
          rk::intersect::IntersectById(stations, files, opt, at, &warnings);
      summary = rk::intersect::SummaryById(results, warnings);
      rk::cli::WarnAll(kTool, common, summary);
      rk::intersect::TrajectoryCsv(results).Write(out_path);
    } else {
      std::vector<rk::intersect::StationTrack> tracks;
      for (const auto& f : files) tracks.emplace_back(f, opt.Defaults());
      const std::vector<double> times = rk::intersect::OutputTimes(tracks, opt, at);
      const rk::intersect::IntersectResult result = rk::intersect::Intersect(stations, tracks, times, opt);
      summary = result.Summary();
      rk::cli::WarnAll(kTool, common, summary);
      rk::intersect::TrajectoryCsv(result).Write(out_path);
    }

    if (!common.report_path.empty()) {
      rk::io::Json report = rk::cli::MakeReport(kTool, argc, argv);
      rk::cli::AddReportInput(&report, "stations", stations_path);
      for (const auto& s : stations.stations) rk::cli::AddReportInput(&report, "located_" + s.name, s.located);
      if (!at_path.empty()) rk::cli::AddReportInput(&report, "at", at_path);
      report["output"] = out_path;
      report["options"] = opt.ToJson();
      rk::cli::WriteReport(common.report_path, report, summary);
    }
    return 0;
  });
}
