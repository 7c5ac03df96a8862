// rk-attitude: target attitude from one station (SPEC.md §1): cylinder (single-station axis attitude
// from three silhouette points, seed 004) and oi (orthogonal-iteration pose from feature points,
// seed 001). Subcommands: apps/attitude_<name>_cmd.cpp.
#include "attitude_commands.h"

int main(int argc, char** argv) {
  // --help lists the subcommands in this order.
  // clang-format off
  static constexpr rk::app::Subcommand kSubcommands[] = {
      {"cylinder", rk::app::AddCylinderCommand},
      {"oi", rk::app::AddOiCommand},
  };
  // clang-format on
  return rk::app::RunTool(
      "rk-attitude",
      "rk-attitude: target attitude from one station (cylinder axis, orthogonal-iteration pose)",
      kSubcommands, argc, argv);
}
