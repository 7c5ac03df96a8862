// rk-sim: synthesize trials with ground truth (SPEC.md §1). Subcommands: apps/sim_<name>_cmd.cpp
// (beacon: beacon-camera tracking trial of seed 001; posetrack: 6-DOF pose measurements of seed 000).
#include "sim_commands.h"

int main(int argc, char** argv) {
  // --help lists the subcommands in this order.
  // clang-format off
  static constexpr rk::app::Subcommand kSubcommands[] = {
      {"beacon", rk::app::AddBeaconCommand},
      {"posetrack", rk::app::AddPosetrackCommand},
      {"theodolite", rk::app::AddTheodoliteCommand},
      {"attitude", rk::app::AddAttitudeCommand},
      {"radar", rk::app::AddRadarCommand},
      {"device", rk::app::AddDeviceCommand},
      {"multistation", rk::app::AddMultistationCommand},
      {"pointing", rk::app::AddPointingCommand},
      {"points", rk::app::AddPointsCommand},
  };
  // clang-format on
  return rk::app::RunTool(
      "rk-sim", "rk-sim: synthesize trials with ground truth (video, turret and range logs, truth files)",
      kSubcommands, argc, argv);
}
