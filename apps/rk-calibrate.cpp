// rk-calibrate: station calibration (SPEC.md §1). Subcommands: apps/calibrate_<name>_cmd.cpp
// (lens: intrinsics and distortion from board images; pointing: turret pointing model, camera mount, focal
// length and time offset from landmarks and stars).
#include "calibrate_commands.h"

int main(int argc, char** argv) {
  // --help lists the subcommands in this order.
  // clang-format off
  static constexpr rk::app::Subcommand kSubcommands[] = {
      {"lens", rk::app::AddLensCommand},
      {"pointing", rk::app::AddPointingCommand},
  };
  // clang-format on
  return rk::app::RunTool("rk-calibrate", "rk-calibrate: station calibration (lens intrinsics, turret pointing model)",
                          kSubcommands, argc, argv);
}
