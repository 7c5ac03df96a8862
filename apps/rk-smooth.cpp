// rk-smooth: time-series filtering (SPEC.md §1): aukf (adaptive UKF fixed-lead prediction, seed 000),
// singer (Singer-model filter/smoother with derivatives), resample (one series to the times of another).
// Subcommands: apps/smooth_<name>_cmd.cpp.
#include "smooth_commands.h"

int main(int argc, char** argv) {
  // --help lists the subcommands in this order.
  // clang-format off
  static constexpr rk::app::Subcommand kSubcommands[] = {
      {"aukf", rk::app::AddAukfCommand},
      {"singer", rk::app::AddSingerCommand},
      {"resample", rk::app::AddResampleCommand},
  };
  // clang-format on
  return rk::app::RunTool(
      "rk-smooth", "rk-smooth: adaptive UKF fixed-lead prediction, Singer tracking/smoothing, resampling",
      kSubcommands, argc, argv);
}
