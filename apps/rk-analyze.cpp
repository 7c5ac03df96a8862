// rk-analyze: error analysis (SPEC.md §1). Subcommands: apps/analyze_<name>_cmd.cpp
// (compare: estimate vs reference statistics).
#include "analyze_commands.h"

int main(int argc, char** argv) {
  // --help lists the subcommands in this order.
  // clang-format off
  static constexpr rk::app::Subcommand kSubcommands[] = {
      {"compare", rk::app::AddCompareCommand},
      {"budget", rk::app::AddBudgetCommand},
  };
  // clang-format on
  return rk::app::RunTool(
      "rk-analyze", "Error analysis of rangekit outputs against a reference (truth or another estimate).",
      kSubcommands, argc, argv);
}
