// rk-smooth: time-series filtering (SPEC.md §1): aukf (adaptive UKF fixed-lead prediction, seed 000),
// singer (Singer-model filter/smoother with derivatives), resample (one series to the times of another).
// Subcommands: apps/smooth_<name>_cmd.cpp.
#include "subcommand.h"

int main(int argc, char** argv) {
  return rk::app::RunTool(
      "rk-smooth", "rk-smooth: adaptive UKF fixed-lead prediction, Singer tracking/smoothing, resampling",
      argc, argv);
}
