// rk-intersect: two or more stations' located-target files → one trajectory with covariance (SPEC.md §7).
// Thin CLI: the method lives in lib/intersect (intersect/intersect.h).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "formats/located.h"
#include "formats/stations.h"
#include "intersect/intersect.h"
#include "intersect/station_track.h"
#include "intersect/time_offsets.h"
#include "io/cli.h"
#include "io/csv.h"
#include "io/error.h"
#include "io/file_util.h"

namespace {

const char* const kTool = "rk-intersect";

// Why the offsets matter, in metres: the same intersection with the offsets as given, and how far the
// trajectory moves between the two (RMS and largest over the rows ok in both).
void AddTrajectoryShift(const rk::formats::StationsFile& stations, const std::vector<rk::intersect::StationTrack>& given,
                        const rk::intersect::IntersectOptions& opt, const std::vector<double>& times,
                        const rk::intersect::IntersectResult& estimated, rk::io::RunSummary* summary) {
  rk::intersect::IntersectOptions plain = opt;
  plain.smooth = false;
  rk::intersect::IntersectResult as_given;
  try {
    as_given = rk::intersect::Intersect(stations, given, times, plain);
  } catch (const rk::Error&) {
    return;  // as given, no time has two stations: nothing to compare
  }
  double s2 = 0.0, worst = 0.0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < times.size(); ++i) {
    if (estimated.rows[i].status != rk::RowStatus::kOk || as_given.rows[i].status != rk::RowStatus::kOk) continue;
    const double d = (estimated.rows[i].result.solution.p - as_given.rows[i].result.solution.p).norm();
    s2 += d * d;
    worst = std::max(worst, d);
    ++n;
  }
  if (n == 0) return;
  const double rms = std::sqrt(s2 / static_cast<double>(n));
  summary->details["time_offset_fit"]["trajectory_shift_m"] = {{"rms", rms}, {"max", worst}, {"rows", n}};
  char note[160];
  std::snprintf(note, sizeof note, "largest %.3f m; RMS 3-D distance between the trajectories with the offsets as "
                "given and estimated", worst);
  summary->AddFigure("trajectory moved by the offsets", rms, "m", note);
}

// The estimated clock offsets into the run's summary: the report's time_offsets and time_offset_fit, a figure per
// station and the warnings for poorly determined ones.
void AddTimeOffsets(const std::optional<rk::intersect::TimeOffsetFit>& fit, rk::io::RunSummary* summary) {
  if (!fit) return;
  summary->details["time_offsets"] = fit->OffsetsJson();
  summary->details["time_offset_fit"] = fit->FitJson();
  for (std::size_t s = 0; s < fit->names.size(); ++s) {
    if (s == fit->reference) continue;
    char note[160];
    std::snprintf(note, sizeof note, "± %.4f ms (1σ) against '%s'", 1e3 * fit->sigma_s[s],
                  fit->names[fit->reference].c_str());
    summary->AddFigure("clock offset " + fit->names[s], 1e3 * fit->offset_s[s], "ms", note);
  }
  char note[160];
  std::snprintf(note, sizeof note, "%.3f arcsec with the offsets as given", fit->rms_arcsec_as_given);
  summary->AddFigure("residual RMS with the estimated offsets", fit->rms_arcsec_estimated, "arcsec", note);
  for (const std::string& w : fit->warnings) summary->Warn("time_offset_poorly_determined", w);
}

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
    // Clocks (SPEC §7): each station's t_s + time_offset_s is the common clock; --estimate-time-offsets
    // estimates the offsets (the given ones are the start) and the trajectory is made with them.
    std::optional<rk::intersect::TimeOffsetFit> fit;
    rk::formats::StationsFile clocked = stations;
    // One target's tracks on the clocks as given: the estimation's start, and the trajectory it is compared with.
    std::vector<rk::intersect::StationTrack> start;
    if (opt.estimate_time_offsets) {
      const rk::intersect::TimeOffsetOptions to;
      if (by_id) {
        fit = rk::intersect::EstimateTimeOffsetsById(stations, files, opt, to);
      } else {
        rk::intersect::OffsetTarget target;
        for (std::size_t s = 0; s < files.size(); ++s) {
          start.emplace_back(files[s], opt.Defaults(), stations.stations[s].time_offset_s);
        }
        for (std::size_t s = 0; s < start.size(); ++s) {
          target.station.push_back(static_cast<int>(s));
          target.track.push_back(&start[s]);
        }
        fit = rk::intersect::EstimateTimeOffsets(stations, {target}, to);
      }
      for (std::size_t s = 0; s < clocked.stations.size(); ++s) clocked.stations[s].time_offset_s = fit->offset_s[s];
    }
    rk::io::RunSummary summary;
    if (by_id) {
      // Located from points tracks: one trajectory per id.
      std::vector<std::string> warnings;
      const std::vector<rk::intersect::IntersectResult> results =
          rk::intersect::IntersectById(clocked, files, opt, at, &warnings, fit ? &fit->sigma_s : nullptr);
      summary = rk::intersect::SummaryById(results, warnings);
      AddTimeOffsets(fit, &summary);
      rk::cli::WarnAll(kTool, common, summary);
      rk::intersect::TrajectoryCsv(results).Write(out_path);
    } else {
      std::vector<rk::intersect::StationTrack> tracks;
      for (std::size_t s = 0; s < files.size(); ++s) {
        tracks.emplace_back(files[s], opt.Defaults(), clocked.stations[s].time_offset_s);
        if (fit) tracks.back().SetTimeSigma(fit->sigma_s[s]);
      }
      const std::vector<double> times = rk::intersect::OutputTimes(tracks, opt, at);
      const rk::intersect::IntersectResult result = rk::intersect::Intersect(clocked, tracks, times, opt);
      summary = result.Summary();
      AddTimeOffsets(fit, &summary);
      if (fit) AddTrajectoryShift(stations, start, opt, times, result, &summary);
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
