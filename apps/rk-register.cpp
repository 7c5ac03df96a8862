// rk-register: radar bias registration (SPEC.md §1, seed 002). Subcommands: apps/register_<name>_cmd.cpp
// (bernoulli: GM Bernoulli filter with greedy partition; kf: known-association Kalman filter; batch:
// offline maximum likelihood with Ceres). Method: lib/registration; docs/rk-register.md.
#include "register_commands.h"

int main(int argc, char** argv) {
  // --help lists the subcommands in this order.
  // clang-format off
  static constexpr rk::app::Subcommand kSubcommands[] = {
      {"bernoulli", rk::app::AddBernoulliCommand},
      {"kf", rk::app::AddKfCommand},
      {"batch", rk::app::AddBatchCommand},
  };
  // clang-format on
  return rk::app::RunTool(
      "rk-register",
      "rk-register: radar range/azimuth/elevation and platform attitude bias registration "
      "of two mobile radars (seed 002)",
      kSubcommands, argc, argv);
}
