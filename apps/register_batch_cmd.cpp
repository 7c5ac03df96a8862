// rk-register batch: offline maximum-likelihood bias registration over the whole trial (Ceres,
// robust loss), starting from a Bernoulli pass. Thin CLI over lib/registration/batch.h.
#include <memory>

#include "register_commands.h"
#include "register_options.h"
#include "registration/batch.h"

namespace rk::app {
namespace {

struct BatchArgs {
  reg::InputArgs in;
  registration::BatchOptions opt;
  std::string associate = "gate", loss = "huber";
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
  reg::AddBernoulliOptions(sub, &args->opt.initial, false);
  sub->add_option("--associate", args->associate, "gate, bernoulli or track")
      ->check(CLI::IsMember({"gate", "bernoulli", "track"}))
      ->capture_default_str();
  sub->add_option("--loss", args->loss, "Robust loss: huber, cauchy or none")
      ->check(CLI::IsMember({"huber", "cauchy", "none"}))
      ->capture_default_str();
  sub->add_option("--loss-scale", args->opt.loss_scale,
                  "Whitened residual norm beyond which the loss is no longer quadratic")
      ->capture_default_str();
  sub->add_option("--gate", args->opt.gate_d2, "Association gate on the pair's Mahalanobis distance squared")
      ->capture_default_str();
  sub->add_option("--rounds", args->opt.max_rounds, "Association rounds at most (gate)")->capture_default_str();
  sub->add_option("--iterations", args->opt.max_iterations, "Ceres iterations per solve at most")
      ->capture_default_str();
  Command cmd;
  cmd.app = sub;
  cmd.run = [args](const Context& ctx) -> int {
    BatchArgs& a = *args;
    registration::BatchOptions opt = a.opt;
    opt.initial.filter = reg::MakeFilterOptions(a.in);
    registration::ParseBatchAssociation(a.associate, &opt.association);
    registration::ParseRobustLoss(a.loss, &opt.loss);
    std::string why;
    if (!opt.Check(&why)) throw UsageError(why);
    reg::CheckPaths(a.in, ctx);
    const registration::RegistrationInput in =
        reg::ReadInput(a.in, opt.association == registration::BatchAssociation::kTrack);
    const registration::BatchResult res = registration::RunBatch(in, opt);
    io::Json extra;
    extra["initial_bernoulli"] = registration::EstimateJson(in, res.initial.result.x, res.initial.result.P);
    extra["initial_bernoulli"].erase("correlation");
    reg::WriteOutputs(a.in, ctx, "batch", in, res.result, extra);
    if (!res.stats.covariance_ok) {
      cli::Warn(ctx.tool, ctx.common, "the covariance could not be computed (biases not all observable): sigmas empty");
    }
    return 0;
  };
  return cmd;
}

}  // namespace rk::app
