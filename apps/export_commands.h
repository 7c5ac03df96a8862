// rk-export's subcommands (apps/subcommand.h): a trajectory or located target as KML or CZML, and what they share
// (the input options, the document header, the report).
#pragma once

#include <filesystem>
#include <string>

#include "exports/export_common.h"
#include "exports/geo_track.h"
#include "io/cli.h"
#include "io/error.h"
#include "io/utc_time.h"
#include "subcommand.h"

namespace rk::app {

Command AddKmlCommand(CLI::App& app);   // export_kml_cmd.cpp
Command AddCzmlCommand(CLI::App& app);  // export_czml_cmd.cpp

// The options both subcommands take: the input (a trajectory or a located target), the epoch, the name, -o.
struct ExportInputArgs {
  std::string trajectory, located, epoch_utc, name, output;
  io::BadRows bad_rows = io::BadRows::kError;

  void Add(CLI::App* sub) {
    sub->add_option("--trajectory", trajectory,
                    "Trajectory CSV (SPEC.md section 7, rk-intersect): t_s, WGS-84 lat_deg,lon_deg,h_m, 1-sigma, "
                    "status [, id] ('-' = stdin)");
    sub->add_option("--located", located,
                    "Located target CSV (rk-locate with --station: lat_deg,lon_deg,h_m and 1-sigma columns) "
                    "instead of a trajectory ('-' = stdin)");
    sub->add_option("--epoch-utc", epoch_utc,
                    "Trial epoch, ISO-8601 UTC (t_s = 0): absolute times in the document (rk-run gives the manifest's "
                    "epoch_utc)");
    sub->add_option("--name", name, "Document name [default: the input file's name]");
    cli::AddBadRowsOption(sub, &bad_rows);
  }
  void AddOutput(CLI::App* sub, const char* what) { sub->add_option("-o,--output", output, what)->required(); }

  const std::string& input() const { return trajectory.empty() ? located : trajectory; }
  exports::InputKind kind() const {
    return trajectory.empty() ? exports::InputKind::kLocated : exports::InputKind::kTrajectory;
  }

  // Exactly one input; the streams' checks; the epoch parsed. Then the input read (exit 1 when nothing is placed).
  exports::GeoTrack Read(const Context& ctx, exports::ExportHeader* header) const {
    if (trajectory.empty() == located.empty()) throw UsageError("give exactly one of --trajectory and --located");
    cli::CheckStreams(ctx.common, {{kind() == exports::InputKind::kTrajectory ? "--trajectory" : "--located", input()}},
                      {{"-o", output}});
    header->epoch_unix_s = io::ParseEpochOption(epoch_utc);
    header->epoch_text = epoch_utc;
    // The input's file name, not its path: the document is the same wherever the file lies (rk-run's working
    // folder has a random name).
    header->source = input() == "-" ? std::string("stdin") : std::filesystem::path(input()).filename().string();
    header->name = !name.empty() ? name : header->source;
    return exports::ReadGeoTrack(input(), kind(), bad_rows);
  }

  // The report skeleton of a run: inputs, subcommand, output, epoch, name.
  io::Json Report(const Context& ctx, const char* subcommand) const {
    io::Json report = cli::MakeReport(ctx.tool, ctx.argc, ctx.argv);
    cli::AddReportInput(&report, exports::InputKindName(kind()), input());
    report["subcommand"] = subcommand;
    report["output"] = output;
    report["epoch_utc"] = epoch_utc.empty() ? io::Json(nullptr) : io::Json(epoch_utc);
    return report;
  }
};

}  // namespace rk::app
