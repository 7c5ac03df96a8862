// rk-export: a trajectory (SPEC.md §7, rk-intersect) or a located target with its WGS-84 columns (rk-locate
// --station) for viewers of the earth: `kml` (OGC KML 2.2: Google Earth, GIS tools), `czml` (Cesium).
// Subcommands: apps/export_<name>_cmd.cpp; the writers: lib/exports.
#include "export_commands.h"

int main(int argc, char** argv) {
  // --help lists the subcommands in this order.
  // clang-format off
  static constexpr rk::app::Subcommand kSubcommands[] = {
      {"kml", rk::app::AddKmlCommand},
      {"czml", rk::app::AddCzmlCommand},
  };
  // clang-format on
  return rk::app::RunTool("rk-export",
                          "rk-export: a trajectory (or a located target with WGS-84 columns) as KML (Google Earth, "
                          "GIS tools) or CZML (Cesium), with its 1-sigma and status",
                          kSubcommands, argc, argv);
}
