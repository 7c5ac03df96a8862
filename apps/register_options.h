// Options and output shared by the rk-register subcommands (register_<name>_cmd.cpp): inputs,
// measurement noise, filter prior and process noise, output and report. Thin: everything is
// parsed into lib/registration's Options structs; see docs/rk-register.md.
#pragma once

#include <CLI/CLI.hpp>
#include <cmath>
#include <string>
#include <vector>

#include "io/cli.h"
#include "io/csv.h"
#include "io/error.h"
#include "io/file_util.h"
#include "registration/bernoulli.h"
#include "registration/filter_common.h"
#include "registration/input.h"
#include "subcommand.h"

namespace rk::app::reg {

struct InputArgs {
  std::string plots, nav, output;
  bool sigmas = false;
  registration::InputOptions input;     // --pair-tol
  registration::FilterOptions filter;   // noise, --linearize; --p0 and --q below
  std::string p0, q;  // six values each, file units (m, deg)
  io::BadRows bad_rows = io::BadRows::kError;
};

// The options every subcommand takes: files, --sigmas, then the input and filter tables and the prior lists.
inline void AddInputOptions(CLI::App* sub, InputArgs* a) {
  sub->add_option("--plots", a->plots, "Radar plots CSV: t_s,radar,range_m,az_deg,el_deg[,track_id] ('-' = stdin)")
      ->required();
  sub->add_option("--nav", a->nav, "Platform nav CSV: t_s,radar,lat_deg,lon_deg,h_m,yaw_deg,pitch_deg,roll_deg")
      ->required();
  cli::AddBadRowsOption(sub, &a->bad_rows);
  sub->add_option("-o,--output", a->output, "Biases CSV, one row per step ('-' = stdout)")->required();
  sub->add_flag("--sigmas", a->sigmas, "Add the 1-sigma columns <radar>_range_sigma_m ... <radar>_roll_sigma_deg");
  cli::AddOptions(sub, &a->input, registration::InputOptions::Table());
  cli::AddOptions(sub, &a->filter, registration::FilterOptions::Table());
  sub->add_option("--p0", a->p0,
                  "Prior 1-sigma of each radar's biases: range_m,az_deg,el_deg,yaw_deg,pitch_deg,roll_deg "
                  "(default 2000,1.719,1.719,1.719,1.719,1.719; prior mean 0)");
  sub->add_option("--q", a->q,
                  "Random-walk 1-sigma per step of each radar's biases, same order and units "
                  "(default 0.05,1.146e-5,...: 0.05 m and 2e-7 rad)");
}

inline registration::RadarBias ParseSix(const std::string& list, const std::string& option) {
  const std::vector<std::string> items = io::SplitList(list);
  if (items.size() != 6) throw UsageError(option + ": give six values (range_m,az_deg,el_deg,yaw_deg,pitch_deg,roll_deg)");
  registration::RadarBias v;
  for (int i = 0; i < 6; ++i) {
    try {
      std::size_t used = 0;
      const double x = std::stod(items[i], &used);
      if (used != items[i].size() || !std::isfinite(x)) throw std::invalid_argument(items[i]);
      v[i] = x / registration::BiasToFileUnit(i);
    } catch (const std::exception&) {
      throw UsageError(option + ": '" + items[i] + "' is not a number");
    }
  }
  return v;
}

// The filter options of the flags with --p0 and --q parsed (file units → m, rad). Throws UsageError.
inline registration::FilterOptions MakeFilterOptions(const InputArgs& a) {
  registration::FilterOptions f = a.filter;
  if (!a.p0.empty()) f.initial_sigma = ParseSix(a.p0, "--p0");
  if (!a.q.empty()) f.process_sigma = ParseSix(a.q, "--q");
  std::string why;
  if (!f.Check(&why)) throw UsageError(why);
  return f;
}

inline void CheckPaths(const InputArgs& a, const Context& ctx) {
  cli::CheckStreams(ctx.common, {{"--plots", a.plots}, {"--nav", a.nav}}, {{"-o", a.output}});
}

inline registration::RegistrationInput ReadInput(const InputArgs& a, bool require_track_id) {
  registration::InputOptions io_opt = a.input;
  io_opt.require_track_id = require_track_id;
  std::string why;
  if (!io_opt.Check(&why)) throw UsageError(why);
  const io::CsvTable plots = io::CsvTable::Read(a.plots, {a.bad_rows, registration::PlotsRowRule()});
  const io::CsvTable nav = io::CsvTable::Read(a.nav, {a.bad_rows, registration::NavRowRule()});
  registration::RegistrationInput in = registration::ReadRegistrationInput(plots, nav, io_opt);
  registration::RequirePairedSteps(in, io_opt.pair_tol_s);
  return in;
}

// Writes the biases CSV and, with --report, the JSON report: {tool, version, command_line,
// inputs, subcommand, radars, input, options, estimate, sigma, correlation, stats, summary, rows_written}
// plus `extra`, with the run's summary (RegistrationResult::Summary, then the method's own `warnings`), which
// it prints.
inline void WriteOutputs(const InputArgs& a, const Context& ctx, const std::string& subcommand,
                         const registration::RegistrationInput& in, const registration::RegistrationResult& r,
                         const io::Json& extra = io::Json::object(), const std::vector<io::Warning>& warnings = {}) {
  const io::CsvWriter csv = registration::BiasesCsv(in, r, a.sigmas);
  io::RunSummary summary = r.Summary(in);
  summary.warnings.insert(summary.warnings.end(), warnings.begin(), warnings.end());
  csv.Write(a.output);
  if (!ctx.common.report_path.empty()) {
    io::Json report = cli::MakeReport(ctx.tool, ctx.argc, ctx.argv);
    cli::AddReportInput(&report, "plots", a.plots);
    cli::AddReportInput(&report, "nav", a.nav);
    report["subcommand"] = subcommand;
    for (auto it = extra.begin(); it != extra.end(); ++it) summary.details[it.key()] = it.value();
    summary.details["rows_written"] = csv.rows();
    cli::WriteReport(ctx.common.report_path, report, summary);
  }
  cli::WarnAll(ctx.tool, ctx.common, summary);
}

}  // namespace rk::app::reg
