// rk-export kml: a trajectory (or a located target with WGS-84 columns) as OGC KML 2.2 for Google Earth and GIS
// tools. Method: lib/exports/kml.h; page docs/rk-export.md.
#include <memory>
#include <string>

#include "export_commands.h"
#include "exports/kml.h"
#include "io/file_util.h"

namespace rk::app {
namespace {

struct KmlArgs {
  ExportInputArgs in;
  exports::KmlOptions opt;
};

int RunKml(const KmlArgs& a, const Context& ctx) {
  std::string why;
  if (!a.opt.Check(&why)) throw UsageError(why);
  exports::ExportHeader header;
  const exports::GeoTrack track = a.in.Read(ctx, &header);
  exports::KmlCounts counts;
  const std::string text = exports::KmlText(track, header, a.opt, &counts);
  io::RunSummary summary = track.Summary();
  summary.details["export"]["lines"] = counts.lines;
  summary.details["export"]["sample_placemarks"] = counts.placemarks;
  io::WriteFileAtomic(a.in.output, text);
  if (!ctx.common.report_path.empty()) {
    io::Json report = a.in.Report(ctx, "kml");
    report["options"] = a.opt.ToJson();
    cli::WriteReport(ctx.common.report_path, report, summary);
  }
  cli::WarnAll(ctx.tool, ctx.common, summary);
  return 0;
}

}  // namespace

Command AddKmlCommand(CLI::App& app) {
  auto a = std::make_shared<KmlArgs>();
  CLI::App* sub = app.add_subcommand(
      "kml",
      "Write OGC KML 2.2 (Google Earth, GIS tools): per id a line per run of placed rows and sample points with "
      "time stamp, sigma and status; altitudes above sea level = h_m - --geoid-undulation (docs/rk-export.md)");
  a->in.Add(sub);
  cli::AddOptions(sub, &a->opt, exports::KmlOptions::Table());
  a->in.AddOutput(sub, "Output KML ('-' = stdout)");
  return {sub, [a](const Context& ctx) { return RunKml(*a, ctx); }};
}

}  // namespace rk::app
