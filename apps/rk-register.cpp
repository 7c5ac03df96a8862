// rk-register: radar bias registration (SPEC.md §1, seed 002). Subcommands: apps/register_<name>_cmd.cpp
// (bernoulli: GM Bernoulli filter with greedy partition; kf: known-association Kalman filter; batch:
// offline maximum likelihood with Ceres). Method: lib/registration; docs/rk-register.md.
#include "subcommand.h"

int main(int argc, char** argv) {
  return rk::app::RunTool("rk-register",
                          "rk-register: radar range/azimuth/elevation and platform attitude bias registration "
                          "of two mobile radars (seed 002)",
                          argc, argv);
}
