// rk-register kf: known-association Kalman filter baseline (seed 002's comparison method; needs
// track_id in the plots). Thin CLI over lib/registration/kalman.h.
#include <cstdint>
#include <iostream>
#include <memory>

#include "register_commands.h"
#include "register_options.h"
#include "registration/kalman.h"

namespace rk::app {
namespace {

struct KfArgs {
  reg::InputArgs in;
  registration::KfOptions opt;
};

}  // namespace

Command AddKfCommand(CLI::App& app) {
  auto args = std::make_shared<KfArgs>();
  CLI::App* sub = app.add_subcommand(
      "kf",
      "Known-association Kalman filter: each step, the pairs of plots with the same track_id in both radars update "
      "the 12 biases (same model as bernoulli). Needs the plots' track_id column.");
  reg::AddInputOptions(sub, &args->in);
  sub->add_option("--track", args->opt.track,
                  "'all' (every common target, centralised) or one track_id (the paper's per-target baseline)")
      ->capture_default_str();
  Command cmd;
  cmd.app = sub;
  cmd.run = [args](const Context& ctx) -> int {
    KfArgs& a = *args;
    registration::KfOptions opt = a.opt;
    opt.filter = reg::MakeFilterOptions(a.in);
    std::string why;
    if (!opt.Check(&why)) throw UsageError(why);
    reg::CheckPaths(a.in, ctx);
    const registration::RegistrationInput in = reg::ReadInput(a.in, true);
    const bool progress = cli::ShowProgress(ctx.common);
    cli::ProgressMeter meter(ctx.tool, "steps", static_cast<std::int64_t>(in.steps.size()), progress);
    const registration::KfResult res = registration::RunKalman(in, opt, [&](std::int64_t k) { meter.Update(k); });
    meter.Finish();
    std::vector<io::Warning> warnings;
    if (res.counters.steps_updated == 0) {
      warnings.push_back({"prior_only", "no step had a pair with a common track_id: the biases are the prior"});
    }
    reg::WriteOutputs(a.in, ctx, "kf", in, res.result, io::Json::object(), warnings);
    if (progress) {
      std::cerr << ctx.tool << ": " << in.steps.size() << " steps: " << res.counters.steps_updated << " updated, "
                << res.counters.steps_predicted << " predicted; " << res.counters.updates << " pair updates\n";
    }
    return 0;
  };
  return cmd;
}

}  // namespace rk::app
