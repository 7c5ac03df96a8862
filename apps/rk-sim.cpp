// rk-sim: synthesize trials with ground truth (SPEC.md §1). Subcommands: apps/sim_<name>_cmd.cpp
// (beacon: beacon-camera tracking trial of seed 001; posetrack: 6-DOF pose measurements of seed 000).
#include "subcommand.h"

int main(int argc, char** argv) {
  return rk::app::RunTool(
      "rk-sim", "rk-sim: synthesize trials with ground truth (video, turret and range logs, truth files)",
      argc, argv);
}
