// rk-export czml: a trajectory (or a located target with WGS-84 columns) as CZML for Cesium. Method:
// lib/exports/czml.h; page docs/rk-export.md.
#include <memory>
#include <string>

#include "export_commands.h"
#include "exports/czml.h"
#include "io/file_util.h"

namespace rk::app {
namespace {

struct CzmlArgs {
  ExportInputArgs in;
  exports::CzmlOptions opt;
};

int RunCzml(const CzmlArgs& a, const Context& ctx) {
  std::string why;
  if (!a.opt.Check(&why)) throw UsageError(why);
  exports::ExportHeader header;
  const exports::GeoTrack track = a.in.Read(ctx, &header);
  const std::string text = exports::CzmlText(track, header, a.opt);
  io::RunSummary summary = track.Summary();
  if (!header.epoch_unix_s) {
    summary.Warn("no_epoch", std::string("no --epoch-utc: t_s = 0 is shown at ") + exports::kStandInEpoch +
                                 ", a stand-in date");
  }
  io::WriteFileAtomic(a.in.output, text);
  if (!ctx.common.report_path.empty()) {
    io::Json report = a.in.Report(ctx, "czml");
    report["options"] = a.opt.ToJson();
    cli::WriteReport(ctx.common.report_path, report, summary);
  }
  cli::WarnAll(ctx.tool, ctx.common, summary);
  return 0;
}

}  // namespace

Command AddCzmlCommand(CLI::App& app) {
  auto a = std::make_shared<CzmlArgs>();
  CLI::App* sub = app.add_subcommand(
      "czml",
      "Write CZML 1.0 (Cesium): a document packet, then per id a packet with time-tagged positions "
      "(cartographicDegrees, ellipsoidal heights), availability per run, path, and the sigma and status as "
      "time-tagged properties (docs/rk-export.md)");
  a->in.Add(sub);
  cli::AddOptions(sub, &a->opt, exports::CzmlOptions::Table());
  a->in.AddOutput(sub, "Output CZML ('-' = stdout)");
  return {sub, [a](const Context& ctx) { return RunCzml(*a, ctx); }};
}

}  // namespace rk::app
