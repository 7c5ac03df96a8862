// rk-register batch: offline maximum-likelihood bias registration over the whole trial (Ceres,
// robust loss), starting from a Bernoulli pass. Thin CLI over lib/registration/batch.h.
#include <cstdint>
#include <iostream>
#include <memory>

#include "register_commands.h"
#include "register_options.h"
#include "registration/batch.h"

namespace rk::app {
namespace {

struct BatchArgs {
  reg::InputArgs in;
  registration::BatchOptions opt;
};

}  // namespace

Command AddBatchCommand(CLI::App& app) {
  auto args = std::make_shared<BatchArgs>();
  CLI::App* sub = app.add_subcommand(
      "batch",
      "Offline maximum likelihood over the whole trial: the exact bias-corrected points of associated pairs must "
      "coincide; robust loss; Ceres; biases with their covariance. Starts from a Bernoulli pass; association by "
      "re-gating with the whole-trial estimate (default), the Bernoulli pass's selection, or track_id.");
  reg::AddInputOptions(sub, &args->in);
  cli::AddOptions(sub, &args->opt.initial, registration::BernoulliOptions::PassTable());
  cli::AddOptions(sub, &args->opt, registration::BatchOptions::Table());
  Command cmd;
  cmd.app = sub;
  cmd.run = [args](const Context& ctx) -> int {
    BatchArgs& a = *args;
    registration::BatchOptions opt = a.opt;
    opt.initial.filter = reg::MakeFilterOptions(a.in);
    std::string why;
    if (!opt.Check(&why)) throw UsageError(why);
    reg::CheckPaths(a.in, ctx);
    const registration::RegistrationInput in =
        reg::ReadInput(a.in, opt.association == registration::BatchAssociation::kTrack);
    // Two stages, one meter each: the Bernoulli pass over the steps, then the association rounds' solves.
    const bool progress = cli::ShowProgress(ctx.common);
    cli::ProgressMeter pass_meter(ctx.tool, "Bernoulli-pass steps", static_cast<std::int64_t>(in.steps.size()),
                                  progress);
    const int rounds = opt.association == registration::BatchAssociation::kGate ? opt.max_rounds : 1;
    cli::ProgressMeter solve_meter(ctx.tool, "association rounds", rounds, progress);
    const registration::BatchResult res = registration::RunBatch(
        in, opt, [&](std::int64_t k) { pass_meter.Update(k); },
        [&](std::int64_t r) {
          pass_meter.Finish();
          solve_meter.Update(r);
        });
    pass_meter.Finish();
    solve_meter.Finish();
    if (progress) {
      const auto& s = res.stats;
      std::cerr << ctx.tool << ": " << in.steps.size() << " steps, " << s.pairs << " pairs; " << s.rounds
                << " rounds, " << s.iterations << " solver iterations (" << s.termination << "); variance factor "
                << s.variance_factor << "\n";
    }
    io::Json extra;
    extra["initial_bernoulli"] = registration::EstimateJson(in, res.initial.result.x, res.initial.result.P);
    extra["initial_bernoulli"].erase("correlation");
    std::vector<io::Warning> warnings;
    if (!res.stats.covariance_ok) {
      warnings.push_back(
          {"covariance_unavailable", "the covariance could not be computed (biases not all observable): sigmas empty"});
    }
    reg::WriteOutputs(a.in, ctx, "batch", in, res.result, extra, warnings);
    return 0;
  };
  return cmd;
}

}  // namespace rk::app
