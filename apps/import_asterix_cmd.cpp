// rk-import asterix: a radar feed's EUROCONTROL ASTERIX records (CAT048, CAT034, CAT001; pcap, pcapng or a raw
// .ast stream) as radar plots (SPEC.md §1.1, §2.1 radar plots with the ASTERIX columns). Method:
// lib/asterix/feed.h; page docs/rk-import.md.
#include <memory>
#include <string>
#include <vector>

#include "asterix/feed.h"
#include "formats/radar_plots.h"
#include "import_commands.h"
#include "io/cli.h"
#include "io/error.h"
#include "io/utc_time.h"

namespace rk::app {
namespace {

struct AsterixArgs {
  std::vector<std::string> inputs;
  std::string epoch_utc, radars, output, bad_records = "skip";
};

int RunAsterix(const AsterixArgs& a, const Context& ctx) {
  std::vector<cli::NamedPath> in;
  for (const std::string& i : a.inputs) in.push_back({"--input", i});
  if (!a.radars.empty()) in.push_back({"--radars", a.radars});
  cli::CheckStreams(ctx.common, in, {{"-o", a.output}});
  asterix::FeedOptions o;
  o.epoch_unix_s = *io::ParseEpochOption(a.epoch_utc);
  o.bad_records_error = a.bad_records == "error";
  if (!a.radars.empty()) o.radars = formats::LoadRadars(a.radars);
  const asterix::FeedResult feed = asterix::ImportFeed(a.inputs, o);
  std::vector<std::string> comments = {"radar plots from EUROCONTROL ASTERIX (CAT048, CAT001; CAT034 in the report)",
                                       "t_s: seconds since " + a.epoch_utc};
  formats::WriteAsterixPlots(a.output, feed.radar_names, feed.rows, comments);
  if (!ctx.common.report_path.empty()) {
    io::Json report = cli::MakeReport(ctx.tool, ctx.argc, ctx.argv);
    for (std::size_t i = 0; i < a.inputs.size(); ++i) cli::AddReportInput(&report, "input_" + std::to_string(i), a.inputs[i]);
    if (!a.radars.empty()) cli::AddReportInput(&report, "radars", a.radars);
    report["subcommand"] = "asterix";
    report["output"] = a.output;
    report["epoch_utc"] = a.epoch_utc;
    cli::WriteReport(ctx.common.report_path, report, feed.summary);
  }
  cli::WarnAll(ctx.tool, ctx.common, feed.summary);
  return 0;
}

}  // namespace

Command AddAsterixCommand(CLI::App& app) {
  auto a = std::make_shared<AsterixArgs>();
  CLI::App* sub = app.add_subcommand(
      "asterix",
      "Write radar plots from a radar feed's EUROCONTROL ASTERIX records: CAT048 target reports and CAT001 plots "
      "(range, azimuth, elevation from a 3-D height or Mode C), CAT034 north markers and sectors in the report; "
      "duplicates of a redundant feed written once (docs/rk-import.md)");
  sub->add_option("--input", a->inputs,
                  "Feed: a pcap or pcapng capture (UDP payloads), or a raw .ast record stream; repeat for several, "
                  "read in the order given")
      ->required();
  sub->add_option("--epoch-utc", a->epoch_utc,
                  "Trial epoch, ISO-8601 UTC: t_s counts from it (a raw stream's records also take their date "
                  "from it)")
      ->required();
  sub->add_option("--radars", a->radars,
                  "radars.json: each radar's name and WGS-84 position by SAC/SIC (elevation from heights needs the "
                  "position) [default: radars named SAC-SIC, no elevation]");
  sub->add_option("--bad-records", a->bad_records,
                  "A record that cannot be decoded: skip = warn (the first 20 with file and byte offset, then a "
                  "count) and go on; error = stop with exit code 3 and no output")
      ->check(CLI::IsMember({"skip", "error"}))
      ->capture_default_str();
  sub->add_option("-o,--output", a->output, "Output radar plots CSV ('-' = stdout)")->required();
  return {sub, [a](const Context& ctx) { return RunAsterix(*a, ctx); }};
}

}  // namespace rk::app
