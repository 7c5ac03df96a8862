// rk-attitude: target attitude from one station (SPEC.md §1): cylinder (single-station axis attitude
// from three silhouette points, seed 004) and oi (orthogonal-iteration pose from feature points,
// seed 001). Subcommands: apps/attitude_<name>_cmd.cpp.
#include "subcommand.h"

int main(int argc, char** argv) {
  return rk::app::RunTool("rk-attitude", "rk-attitude: target attitude from one station (cylinder axis, orthogonal-iteration pose)",
                          argc, argv);
}
