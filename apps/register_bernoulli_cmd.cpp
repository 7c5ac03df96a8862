// rk-register bernoulli: Gaussian-mixture Bernoulli filter with the modified greedy measurement
// partition (seed 002, unknown association, clutter). Thin CLI over lib/registration/bernoulli.h.
#include <cstdint>
#include <iostream>
#include <memory>

#include "register_commands.h"
#include "register_options.h"
#include "registration/bernoulli.h"

namespace rk::app {
namespace {

struct BernoulliArgs {
  reg::InputArgs in;
  registration::BernoulliOptions opt;
};

}  // namespace

Command AddBernoulliCommand(CLI::App& app) {
  auto args = std::make_shared<BernoulliArgs>();
  CLI::App* sub = app.add_subcommand(
      "bernoulli",
      "Gaussian-mixture Bernoulli filter (existence 1) over all pairwise differences of the two radars' plots, "
      "with the modified greedy measurement partition (K subsets of L pairs per component and step), pruning "
      "and merging. Association unknown; clutter allowed. -L 1 = no partition (the paper's 'before').");
  reg::AddInputOptions(sub, &args->in);
  cli::AddOptions(sub, &args->opt, registration::BernoulliOptions::Table());
  Command cmd;
  cmd.app = sub;
  cmd.run = [args](const Context& ctx) -> int {
    BernoulliArgs& a = *args;
    registration::BernoulliOptions opt = a.opt;
    opt.filter = reg::MakeFilterOptions(a.in);
    std::string why;
    if (!opt.Check(&why)) throw UsageError(why);
    reg::CheckPaths(a.in, ctx);
    const registration::RegistrationInput in = reg::ReadInput(a.in, false);
    const bool progress = cli::ShowProgress(ctx.common);
    cli::ProgressMeter meter(ctx.tool, "steps", static_cast<std::int64_t>(in.steps.size()), progress);
    const registration::BernoulliResult res =
        registration::RunBernoulli(in, opt, [&](std::int64_t k) { meter.Update(k); });
    meter.Finish();
    std::vector<io::Warning> warnings;
    if (res.stats.counters.steps_updated == 0) {
      warnings.push_back({"prior_only", "no step could be updated (no pair passed the gate): the biases are the prior"});
    }
    reg::WriteOutputs(a.in, ctx, "bernoulli", in, res.result, io::Json::object(), warnings);
    if (progress) {
      std::cerr << ctx.tool << ": " << in.steps.size() << " steps: " << res.stats.counters.steps_updated
                << " updated, " << res.stats.counters.steps_predicted << " predicted\n";
    }
    return 0;
  };
  return cmd;
}

}  // namespace rk::app
