// rk-extract: recorded video → per-frame image measurements (SPEC.md §1).
// Subcommands: apps/extract_<name>_cmd.cpp (beacon: cooperative IR lamp cluster track).
#include "subcommand.h"

int main(int argc, char** argv) {
  return rk::app::RunTool("rk-extract", "rk-extract: recorded video -> per-frame image measurements", argc,
                          argv);
}
