// rk-import: real recordings and records into rangekit's files (SPEC.md §1, §1.1): `frames` writes a
// recording's own frame times (CINE/MRAW stamps, container times, rk-capture's frames.csv, else the
// nominal rate) as frames.csv; `asterix` writes radar plots from a radar feed's ASTERIX records. Subcommands: apps/import_<name>_cmd.cpp.
#include "import_commands.h"

int main(int argc, char** argv) {
  // --help lists the subcommands in this order.
  // clang-format off
  static constexpr rk::app::Subcommand kSubcommands[] = {
      {"frames", rk::app::AddFramesCommand},
      {"asterix", rk::app::AddAsterixCommand},
  };
  // clang-format on
  return rk::app::RunTool("rk-import",
                          "rk-import: real recordings and records into rangekit's files: frames (a recording's own frame times), "
                          "asterix (radar plots from EUROCONTROL ASTERIX)",
                          kSubcommands, argc, argv);
}
