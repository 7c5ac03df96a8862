// rk-analyze: error analysis (SPEC.md §1). Subcommands: apps/analyze_<name>_cmd.cpp
// (compare: estimate vs reference statistics).
#include "subcommand.h"

int main(int argc, char** argv) {
  return rk::app::RunTool(
      "rk-analyze", "Error analysis of rangekit outputs against a reference (truth or another estimate).",
      argc, argv);
}
