// The subcommands of rk-extract, one translation unit each (apps/extract_<name>_cmd.cpp); rk-extract.cpp
// lists them in --help order. Each adds its subcommand to the tool's CLI::App (subcommand.h).
#pragma once

#include "subcommand.h"

namespace rk::app {

Command AddBeaconCommand(CLI::App& app);      // extract_beacon_cmd.cpp
Command AddFeaturesCommand(CLI::App& app);    // extract_features_cmd.cpp
Command AddSilhouetteCommand(CLI::App& app);  // extract_silhouette_cmd.cpp

}  // namespace rk::app
