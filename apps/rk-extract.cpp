// rk-extract: recorded video → per-frame image measurements (SPEC.md §1).
// Subcommands: apps/extract_<name>_cmd.cpp (beacon: cooperative IR lamp cluster track).
#include "extract_commands.h"

int main(int argc, char** argv) {
  // --help lists the subcommands in this order.
  // clang-format off
  static constexpr rk::app::Subcommand kSubcommands[] = {
      {"beacon", rk::app::AddBeaconCommand},
      {"features", rk::app::AddFeaturesCommand},
      {"silhouette", rk::app::AddSilhouetteCommand},
      {"points", rk::app::AddPointsCommand},
  };
  // clang-format on
  return rk::app::RunTool("rk-extract", "rk-extract: recorded video -> per-frame image measurements",
                          kSubcommands, argc, argv);
}
