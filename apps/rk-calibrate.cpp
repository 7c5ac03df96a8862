// rk-calibrate: station calibration (SPEC.md §1). Subcommands: apps/calibrate_<name>_cmd.cpp
// (lens: intrinsics and distortion from board images).
#include "calibrate_commands.h"

int main(int argc, char** argv) {
  // --help lists the subcommands in this order.
  // clang-format off
  static constexpr rk::app::Subcommand kSubcommands[] = {
      {"lens", rk::app::AddLensCommand},
  };
  // clang-format on
  return rk::app::RunTool("rk-calibrate", "rk-calibrate: station calibration (lens)", kSubcommands, argc, argv);
}
